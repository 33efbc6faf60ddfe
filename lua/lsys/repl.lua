--- The interactive REPL of the `lsys` program (`lsys` with no arguments).
-- Lua 5.4 like the `lua` REPL, with `lsys` loaded as a global: a line is first tried as an
-- expression list (`=expr` works too) and its values are printed, Lstrings abbreviated;
-- otherwise it is run as a statement, continued on `>> ` lines while Lua reports it
-- incomplete (a multi-line expression prints its values too). Errors print their message
-- and the session goes on. Line editing and history come from lsys.readline when the
-- program was built with readline.
-- @module lsys.repl
local host = require("lsys.program").host

local G = _G
local type, tostring, pcall, xpcall, load, require, getmetatable, pairs, ipairs, error =
      type, tostring, pcall, xpcall, load, require, getmetatable, pairs, ipairs, error
local io, os, string, table, package, debug, math = io, os, string, table, package, debug, math
local format = string.format
local _ENV = nil

local M = {}

local WIDTH = 60  -- characters of an Lstring shown

local function is_lstring (v)
  if type(v) ~= "userdata" then return false end
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__name == "lsys.Lstring"
end

local function is_scene (v)
  if type(v) ~= "userdata" then return false end
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__name == "lsys.Scene"
end

local function num (x) return format("%.4g", x) end

-- A scene: its counts and extent.
local function scene_summary (v)
  local ok, s = pcall(function ()
    local lo, hi = v:bounds()
    local ext = lo and format("; x %s..%s, y %s..%s, z %s..%s", num(lo[1]), num(hi[1]),
      num(lo[2]), num(hi[2]), num(lo[3]), num(hi[3])) or "; empty"
    return format("Scene(%d triangles, %d lines, %d turtle records%s)", v.ntriangles,
      v.nlines, v.nrecords, ext)
  end)
  return ok and s or tostring(v)
end

--- How the REPL shows a value: tostring, except Lstrings, which are abbreviated as
-- `Lstring(1234 modules): F[+F]F...` (the first 60 characters of their text), and
-- scenes, summarised as `Scene(120 triangles, 40 lines, 55 turtle records; x -1..1, ...)`.
function M.show (v)
  if is_scene(v) then return scene_summary(v) end
  if not is_lstring(v) then return tostring(v) end
  local n = #v
  local ok, text = pcall(function ()
    -- convert only a prefix: a million-module string need not become text
    return tostring(n > WIDTH and v:sub(1, WIDTH) or v)
  end)
  if not ok then text = "?" end
  local more = n > WIDTH or #text > WIDTH
  return format("Lstring(%d module%s): %s%s", n, n == 1 and "" or "s",
    text:sub(1, WIDTH), more and "..." or "")
end

local function msghandler (e)
  local msg = e
  if type(msg) ~= "string" then
    local mt = getmetatable(e)
    msg = (type(mt) == "table" and mt.__tostring ~= nil) and tostring(e)
      or format("(error object is a %s value)", type(e))
  end
  if os.getenv("LSYS_DEBUG") ~= nil then msg = debug.traceback(msg, 2) end
  return msg
end

-- Lua reports an incomplete chunk as a syntax error at <eof> (lua.c's 'incomplete').
local function incomplete (msg)
  return msg:sub(-5) == "<eof>"
end

--[[
Compiles 'src' as an expression list, or returns nil. The values go through select() so
that the last call is not a tail call: an error(msg, 2) raised by a function called from the
REPL then names "stdin:1" instead of "[C]:-1". The ")" goes on its own line so that a
trailing comment cannot swallow it.
]]
local function asexpr (src)
  local e = src:gsub("[%s;]+$", "")
  if e == "" then return nil end
  return (load("return select(1, " .. e .. "\n)", "=stdin", "t", G))
end

--[[
Reads one chunk: lines tried as an expression list (whose values are printed), else as a
statement, continued on ">> " lines while Lua reports it incomplete. Returns the compiled
function; nil, message for a syntax error; nil at the end of the input.
]]
local function loadchunk (read)
  local line = read(tostring(G._PROMPT or "> "))
  if line == nil then return nil end
  if line:sub(1, 1) == "=" then line = line:sub(2) end  -- `=expr`, as in Lua 5.1
  local buf = line
  while true do
    local f = asexpr(buf)
    if f ~= nil then return f end
    local err
    f, err = load(buf, "=stdin", "t", G)
    if f ~= nil then return f end
    if not incomplete(err) then return nil, err end
    local more = read(tostring(G._PROMPT2 or ">> "))
    if more == nil then return nil, err end  -- end of input inside a statement
    buf = buf .. "\n" .. more
  end
end

-- A parameter value in a line: numbers with 4 digits, vectors in braces, point lists
-- and other tables by their size.
local function brief (v)
  if math.type(v) == "integer" then return tostring(v) end
  if type(v) == "number" then return num(v) end
  if type(v) == "string" then return format("%q", v) end
  if type(v) ~= "table" then return is_lstring(v) and M.show(v) or tostring(v) end
  local allnum = #v > 0 and #v <= 4
  for k = 1, #v do allnum = allnum and type(v[k]) == "number" end
  if allnum then
    local t = {}
    for k = 1, #v do t[k] = brief(v[k]) end
    return "{" .. table.concat(t, ", ") .. "}"
  end
  if #v == 2 and type(v[1]) == "table" and type(v[2]) == "table" then
    return "{" .. brief(v[1]) .. ", " .. brief(v[2]) .. "}" .. (v.f and " and a function" or "")
  end
  if #v > 0 then return format("{%d %s}", #v, type(v[1]) == "table" and "points" or "values") end
  return "a table"
end

-- The value of parameter 'key' for the instance: a range or a function evaluated for it
-- (lsys.components.expand.value), or nil when it cannot be computed again (a function
-- that draws random numbers would draw other ones now).
local function evaluated (inst, key)
  local X = require "lsys.components.expand"
  local ctx = {}
  for k, v in pairs(inst.ctx or {}) do ctx[k] = v end
  ctx.random = function () error("random", 0) end
  local ok, v = pcall(X.value, inst, inst.proto, key, ctx)
  return ok and v or nil
end

-- Parameters whose ranges run over the children a component makes, not over its own
-- iteration (lsys.components.expand evaluates them per branch or per child).
local OVER_CHILDREN = { tree = { angle = "branches", branch_scale = "branches" },
                        phiball = { child_size = "children" } }

--- The lines that describe a component instance (lsys.components) picked in the viewer:
-- its path (`where`, else inst.path), kind, name, iteration i of n and recursion depth,
-- then each parameter its prototype gives, with the value for this instance where a
-- range or a function makes it vary (`length = {0.3, 0.5} -> 0.4`; a Tree's angle and
-- branch_scale and a Phiball's child_size vary over its branches or children instead).
function M.instance_lines (inst, where)
  local lines = { format("  instance %s: %s%s, iteration %d of %d, depth %d",
    where or inst.path, inst.kind, inst.name and inst.name ~= inst.kind and
    format(" '%s'", inst.name) or "", inst.i or 1, inst.n or 1, inst.depth or 0) }
  local params = inst.proto and inst.proto.params or {}
  local keys = {}
  for k in pairs(params) do keys[#keys + 1] = k end
  table.sort(keys)
  for _, k in ipairs(keys) do
    local v = params[k]
    local text = type(v) == "function" and "a function" or brief(v)
    local over = OVER_CHILDREN[inst.kind] and OVER_CHILDREN[inst.kind][k]
    if over and (type(v) == "function" or type(v) == "table") then
      text = text .. " over its " .. over
    elseif type(v) == "function" or (type(v) == "table" and #v == 2) then
      local e = evaluated(inst, k)
      if e ~= nil and e ~= v then text = text .. " -> " .. brief(e)
      elseif type(v) == "function" then text = text .. " (of the random generator)" end
    end
    lines[#lines + 1] = format("    %s = %s", k, text)
  end
  return lines
end

--- What the REPL prints for a click on a module in the viewer window (lsys.show): the
-- module, and for a component plant the instance that drew it with its parameters.
function M.print_pick (info)
  local what = info.text or "?"
  if #what > WIDTH then what = what:sub(1, WIDTH) .. "..." end
  io.stdout:write(format("picked module %d: %s (%s%s)\n", info.module, what,
    info.kind or "?", info.step and format(", step %d", info.step) or ""))
  if info.instance ~= nil then
    io.stdout:write(table.concat(M.instance_lines(info.instance, info.path), "\n"), "\n")
  end
  io.stdout:flush()
end

-- Handles the viewer window's events at the prompt; true when there were some (the
-- prompt line was cleared for what the callbacks print, and must be drawn again).
local function idle (h)
  local V = package.loaded["lsys.viewer"]
  if type(V) ~= "table" or V.pending() == 0 then return false end
  if h.clear_line then h.clear_line() end
  local ok, err = pcall(V.poll, 0)
  if not ok then io.stderr:write(tostring(err), "\n") end
  return true
end

--- Runs the REPL on stdin until its end (Ctrl-D) or os.exit.
-- @return the exit status, 0
function M.run ()
  local h = host()
  local interactive = h.isatty == nil or h.isatty(0)
  local readline
  if interactive then
    local ok, rl = pcall(require, "lsys.readline")
    if ok and type(rl) == "function" then readline = rl end
  end
  local function read (prompt)
    if readline ~= nil then return readline(prompt) end
    if interactive then
      io.stdout:write(prompt)
      io.stdout:flush()
    end
    return io.stdin:read("l")
  end
  local interrupt = h.interrupt or function () end

  local ok, lsys = pcall(require, "lsys")
  if ok then
    G.lsys = lsys
    local vok, V = pcall(require, "lsys.viewer")
    if vok and V.on_pick == nil then V.on_pick = M.print_pick end
    if h.set_idle then h.set_idle(function () return idle(h) end) end
  else
    io.stderr:write("lsys: warning: cannot load lsys: ", tostring(lsys), "\n")
  end
  if interactive then
    io.stdout:write(format("lsys %s (%s); `lsys` is loaded; =expr prints; Ctrl-D quits\n",
      h.version or "scm", G._VERSION))
  end

  while true do
    local f, err = loadchunk(read)
    if f == nil and err == nil then break end  -- end of input
    if f ~= nil then
      interrupt(true)
      local r = table.pack(xpcall(f, msghandler))
      interrupt(false)
      if r[1] then
        if r.n > 1 then
          local shown = {}
          for i = 2, r.n do shown[i - 1] = M.show(r[i]) end
          local pok, perr = pcall(G.print, table.unpack(shown, 1, r.n - 1))
          if not pok then io.stderr:write("error calling 'print' (", tostring(perr), ")\n") end
        end
      else
        err = r[2]
      end
    end
    if err ~= nil then
      io.stderr:write(tostring(err), "\n")
      io.stderr:flush()
    end
    if readline == nil then idle(h) end   -- no line editor to call it while waiting
    io.stdout:flush()
  end
  if h.set_idle then h.set_idle(nil) end
  if interactive then io.stdout:write("\n") end
  return 0
end

return M
