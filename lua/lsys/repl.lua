--- The interactive REPL of the `lsys` program (`lsys` with no arguments).
-- Lua 5.4 like the `lua` REPL, with `lsys` loaded as a global and `help` (lsys.repl.help):
-- a line is first tried as an expression list (`=expr` works too) and its values are
-- printed (lsys.repl.show: Lstrings abbreviated, tables one level deep); otherwise it is run
-- as a statement, continued on `>> ` lines while Lua reports it incomplete; `_` is the
-- first value of the last line whose values were printed. A `local` at the top of a line
-- stays visible to the lines after it. Errors print their message and
-- the session goes on. With readline (lsys.readline): line editing, Tab completion
-- (lsys.repl.complete) and a history kept in ~/.lsys_history; Ctrl-C at the prompt
-- abandons the line being typed.
-- @module lsys.repl
local host = require("lsys.program").host
local S = require "lsys.repl.show"
local C = require "lsys.repl.complete"
local Help = require "lsys.repl.help"

local G = _G
local type, tostring, pcall, xpcall, load, require, getmetatable, pairs, ipairs, error,
      setmetatable, rawset =
      type, tostring, pcall, xpcall, load, require, getmetatable, pairs, ipairs, error,
      setmetatable, rawset
local io, os, string, table, package, debug, math = io, os, string, table, package, debug, math
local format = string.format
local _ENV = nil

local M = {}

local WIDTH = 60       -- characters of a picked module shown
local HISTORY = 1000   -- lines kept in ~/.lsys_history

M.show = S.show        -- how the REPL shows a value
M.digits = S.digits    -- lsys.repl.digits(n): digits of the floats in Lstrings and tables

local function is_lstring (v)
  if type(v) ~= "userdata" then return false end
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__name == "lsys.Lstring"
end

local function num (x) return format("%.4g", x) end

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
The environment of the lines typed at the prompt: the `local`s kept from earlier lines and
`_`, the first value the last printed line gave (as in IPython), then the globals. An
assignment to a name that is not a kept local sets the global; one to `_` stays in the
environment, as `_` does.
]]
local function new_env ()
  return setmetatable({}, { __index = G, __newindex = function (env, k, v)
    if k == "_" then rawset(env, k, v) else G[k] = v end
  end })
end

--[[
The function a statement calls last (it gets it as its first vararg): keeps the locals of
the chunk still in scope at its end, the `local`s at its top level, in 'env'. So
`local x = 1` on one line and `x` on the next work as in one chunk; a global of the same
name is shadowed for the lines typed at the prompt only.
]]
local function keeper (env)
  return function ()
    for i = 1, 255 do
      local name, v = debug.getlocal(2, i)
      if name == nil then break end
      if name:sub(1, 1) ~= "(" then rawset(env, name, v) end
    end
  end
end

--[[
Compiles 'src' as an expression list, or returns nil. The values go through select() so
that the last call is not a tail call: an error(msg, 2) raised by a function called from the
REPL then names "stdin:1" instead of "[C]:-1". The ")" goes on its own line so that a
trailing comment cannot swallow it.
]]
local function asexpr (src, env)
  local e = src:gsub("[%s;]+$", "")
  if e == "" then return nil end
  return (load("return select(1, " .. e .. "\n)", "=stdin", "t", env))
end

--[[
Reads one chunk: lines tried as an expression list (whose values are printed), else as a
statement, continued on ">> " lines while Lua reports it incomplete. A statement ends with
a call of the keeper it is given (unless it ends with `return`). Returns the compiled
function; nil, message for a syntax error; false when Ctrl-C abandoned the input; nil at
the end of the input.
]]
local function loadchunk (read, env)
  local line = read(tostring(G._PROMPT or "> "))
  if not line then return line end
  if line:sub(1, 1) == "=" then line = line:sub(2) end  -- `=expr`, as in Lua 5.1
  local buf = line
  while true do
    local f = asexpr(buf, env)
    if f ~= nil then return f end
    local err
    f, err = load(buf, "=stdin", "t", env)
    if f ~= nil then
      return load(buf .. "\n;(...)()", "=stdin", "t", env) or f
    end
    if not incomplete(err) then return nil, err end
    local more = read(tostring(G._PROMPT2 or ">> "))
    if more == false then return false end
    if more == nil then return nil, err end  -- end of input inside a statement
    buf = buf .. "\n" .. more
  end
end

--[[
Whether the values of an evaluation are left unprinted: none; or several, all nil but a
leading `true`, a status that says nothing (lsys.render(m, { out = ... }) returns true,
nil, nil). A single value prints whatever it is, nil and true included, as in `lua`, and
so do several nils.
]]
local function quiet (r)
  if r.n <= 2 then return r.n == 1 end   -- r[1] is xpcall's status
  for i = 3, r.n do
    if r[i] ~= nil then return false end
  end
  return r[2] == true
end

-- Prints the values of an evaluation (r: xpcall's status and results, packed); whether
-- it printed them.
local function print_results (r)
  if quiet(r) then return false end
  local shown = {}
  for i = 2, r.n do
    local ok, s = pcall(S.show, r[i])
    shown[i - 1] = ok and s or format("(%s)", tostring(s))
  end
  local pok, perr = pcall(G.print, table.unpack(shown, 1, r.n - 1))
  if not pok then io.stderr:write("error calling 'print' (", tostring(perr), ")\n") end
  return true
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

-- The line reader: readline's, or io.read with a prompt when stdin is a terminal. Returns
-- the reader and lsys.readline's table (nil without it).
local function reader (h, interactive)
  local rl
  if interactive then
    local ok, mod = pcall(require, "lsys.readline")
    if ok and type(mod) == "table" then rl = mod end
  end
  local interrupted = h.interrupted or function () return false end
  return function (prompt)
    if rl ~= nil then return rl.readline(prompt) end   -- false on Ctrl-C
    interrupted()   -- forget a Ctrl-C typed before the prompt
    if interactive then
      io.stdout:write(prompt)
      io.stdout:flush()
    end
    -- a Ctrl-C ends the read (no SA_RESTART); one just before it is seen here
    local line = false
    if not interrupted() then line = io.stdin:read("l") end
    if line == nil and interrupted() then line = false end
    if line == false then io.stdout:write("\n") end
    return line
  end, rl
end

-- Sets up history and completion of lsys.readline 'rl' for the environment 'env'.
local function setup_readline (rl, env)
  local home = os.getenv("HOME")
  if home ~= nil and home ~= "" then
    pcall(rl.history, home .. "/.lsys_history", HISTORY)
  end
  rl.set_complete(function (line, start, stop)
    return C.complete(env, line, start, stop)
  end)
end

--- Runs the REPL on stdin until its end (Ctrl-D) or os.exit.
-- @return the exit status, 0
function M.run ()
  local h = host()
  local interactive = h.isatty == nil or h.isatty(0)
  local env = new_env()
  local read, rl = reader(h, interactive)
  if rl ~= nil then setup_readline(rl, env) end
  local interrupt = h.interrupt or function () end
  local idle_mode = interactive and "prompt" or false   -- Ctrl-C at the prompt

  local ok, lsys = pcall(require, "lsys")
  if ok then
    G.lsys = lsys
    if type(lsys) == "table" then lsys.repl = M end
    local vok, V = pcall(require, "lsys.viewer")
    if vok and V.on_pick == nil then V.on_pick = M.print_pick end
    if h.set_idle then h.set_idle(function () return idle(h) end) end
  else
    io.stderr:write("lsys: warning: cannot load lsys: ", tostring(lsys), "\n")
  end
  G.help = Help.new()
  if interactive then
    io.stdout:write(format("lsys %s (%s); `lsys` is loaded; help() for help; Ctrl-D quits\n",
      h.version or "scm", G._VERSION))
  end

  interrupt(idle_mode)
  while true do
    local f, err = loadchunk(read, env)
    if f == nil and err == nil then break end  -- end of input
    if f then
      interrupt(true)
      local r = table.pack(xpcall(f, msghandler, keeper(env)))
      interrupt(idle_mode)
      if not r[1] then err = r[2]
      elseif print_results(r) then rawset(env, "_", r[2]) end   -- the last result
    end
    if err ~= nil then
      io.stderr:write(tostring(err), "\n")
      io.stderr:flush()
    end
    if rl == nil then idle(h) end   -- no line editor to call it while waiting
    io.stdout:flush()
  end
  interrupt(false)
  if h.set_idle then h.set_idle(nil) end
  if interactive then io.stdout:write("\n") end
  return 0
end

return M
