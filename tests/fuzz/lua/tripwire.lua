--- The sandbox check of the Lua fuzz targets whose inputs become code (targets/ruleexpr.lua,
-- targets/cpfg.lua): while an input runs, _G is emptied behind a metatable, and os.execute,
-- os.remove, os.rename, os.exit, os.getenv, os.tmpname, io.open, io.popen, io.lines,
-- io.output, io.input, load, loadfile, dofile and require fail when code compiled from a
-- string (not from a file) is on the stack. What trips is kept in `w.hits` and raised as
-- "fuzz tripwire: ...". Options say which code is watched (targets/import.lua: the file the
-- importer wrote, too), which globals it may read, and whether only direct calls count.
local G = _G
local next, error, tostring, setmetatable, getmetatable, rawset, ipairs =
      next, error, tostring, setmetatable, getmetatable, rawset, ipairs
local getinfo, sub = debug.getinfo, string.sub
local os_lib, io_lib = os, io

local M = {}

--- True when the function of `info` (debug.getinfo) was compiled from a string.
function M.rulecode (info)
  return info and info.what ~= "C" and sub(info.source, 1, 1) ~= "@"
end
local rulecode = M.rulecode

local GWIRED = { "load", "loadfile", "dofile", "require" }

--- A new tripwire set: `what` names the code in messages ("rule expression"); `top()`
-- returns the function where the stack walk stops (the target's run). opts: `iscode(info)`
-- (debug.getinfo "S" of a function: true for the code watched; default M.rulecode),
-- `allow(info, name)` (true when that code may read global `name`: it is then not a
-- tripwire either), `direct` (a tripwire counts only when the watched code calls it
-- itself, not through lsys's functions further down).
function M.new (what, top, opts)
  opts = opts or {}
  local watched = opts.iscode or rulecode
  local allow = opts.allow or function () return false end
  local direct = opts.direct
  local w = { hits = {} }
  local function hit (msg)
    w.hits[#w.hits + 1] = msg
    error("fuzz tripwire: " .. msg, 0)
  end
  local shadow, oldmeta, sealed, greal = {}, nil, false, {}
  local TRAP = {
    __index = function (_, k)
      local info = getinfo(2, "S")
      if watched(info) and not allow(info, k) then
        hit(what .. " reached global '" .. tostring(k) .. "'")
      end
      return shadow[k]
    end,
    __newindex = function (_, k, v)
      if watched(getinfo(2, "S")) then hit(what .. " wrote global '" .. tostring(k) .. "'") end
      shadow[k] = v
    end,
  }

  --- A function that fails when such code is on the stack (below top()), else calls `real`.
  function w.tripwire (name, real)
    return function (...)
      local stop = top()
      for level = 2, direct and 2 or 200 do
        local info = getinfo(level, "Sf")
        if info == nil or info.func == stop then break end
        if watched(info) and not allow(info, name) then hit(what .. " called " .. name) end
      end
      return real(...)
    end
  end

  local WIRES = {}     -- { table, key, wrapper, real }
  local function wire (tbl, tname, key)
    local real = tbl[key]
    WIRES[#WIRES + 1] = { tbl, key, w.tripwire(tname .. key, real), real }
  end
  for _, k in ipairs { "execute", "remove", "rename", "exit", "getenv", "tmpname" } do
    wire(os_lib, "os.", k)
  end
  for _, k in ipairs { "open", "popen", "lines", "output", "input" } do wire(io_lib, "io.", k) end

  --- Before an input: no hits, the wires in place, _G sealed.
  function w.arm ()
    w.hits = {}
    for _, x in ipairs(WIRES) do x[1][x[2]] = x[3] end
    for k, v in next, G do shadow[k] = v end
    for k in next, shadow do rawset(G, k, nil) end
    oldmeta = getmetatable(G)
    setmetatable(G, TRAP)
    sealed = true
    for _, name in ipairs(GWIRED) do
      greal[name] = shadow[name]
      shadow[name] = w.tripwire(name, greal[name])
    end
  end

  --- After it: _G and the libraries as they were.
  function w.disarm ()
    if sealed then
      for _, name in ipairs(GWIRED) do shadow[name] = greal[name] end
      setmetatable(G, oldmeta)
      for k, v in next, shadow do rawset(G, k, v); shadow[k] = nil end
      sealed = false
    end
    for _, x in ipairs(WIRES) do x[1][x[2]] = x[4] end
  end
  return w
end

return M
