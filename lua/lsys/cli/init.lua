--- The `lsys` command line (lsys.cli): main, the dispatch to the command modules
-- lsys/cli/commands/NAME.lua, the error handler and the script runner.
--
-- The program (csrc/prog/lsys.c) calls `main(...)` with its arguments and exits with what it
-- returns: 0 on success, 1 when something failed, 2 for a usage error. `main` prints its
-- own messages (`lsys: ...` on stderr) and does not raise, so it can be called from Lua too:
-- `require("lsys.cli").main("derive", "examples/default.lua", "--stats")`.
--
--   lsys                      the REPL (lsys.repl)
--   lsys FILE.lua [ARGS]      run a Lua script, like `lua FILE.lua ARGS`
--   lsys derive [MODEL] ...   derive a model; print the L-string or its statistics
--   lsys render [MODEL] ...   derive, interpret and render a model to PNG (headless, OSMesa)
--   lsys render MODEL --frames DIR   one PNG per derivation step, through one camera
--   lsys animate MODEL -o OUT  the model growing, as .mp4 or .gif (ffmpeg)
--   lsys export MODEL -o OUT  derive, interpret and write the geometry (.obj .ply .glb)
--   lsys view [MODEL] ...     the viewer window on a model, reloaded when its file changes
--   lsys arrange [MODEL] ...  bend, twist and prune a derived model in the window (IK)
--   lsys sketch [FILE] ...    the sketch window; sketch plot|model|render FILE -o OUT
--   lsys components graph MODEL -o OUT   a component graph's p-graph (.png .svg .pdf .dot)
--   lsys grow FILE ...        a growing world (lsys.grow) live in the window, or --frames DIR
--   lsys import MODEL.l -o OUT.lua   a cpfg model as a readable lsys model file
--   lsys batch SPEC ...       the jobs of a CSV or Lua spec (sweeps), sharded: lsys.batch
--   lsys test [PATH...]       busted on a user's specs, with lsys and lsys.testing
--   lsys help [COMMAND]       help
--
-- The rest of the package: lsys.cli.help (the help texts), lsys.cli.args (usage errors,
-- output, the option parser, what several commands share), lsys.cli.source (finding and
-- loading models).
-- @module lsys.cli
local host = require("lsys.program").host
local A = require "lsys.cli.args"
local H = require "lsys.cli.help"
local strip_internal = require("lsys.util.errors").strip_internal
local runfile = require("lsys.model").runfile
local warning = require "lsys.warning"
local suggest = require "lsys.util.suggest"

local G = _G
local type, tostring, error, xpcall, require, loadfile, getmetatable, warn =
      type, tostring, error, xpcall, require, loadfile, getmetatable, warn
local io, os, string, table, math, debug = io, os, string, table, math, debug
local format = string.format
local out, usage, isfile, USAGE_ERROR = A.out, A.usage, A.isfile, A.USAGE_ERROR
local USAGE = H.usage
local _ENV = nil

local M = {}

-- The commands, each a module lsys.cli.commands.NAME that returns the function of the
-- arguments; only the one that runs is loaded (`lsys derive` loads no window nor busted).
local COMMANDS, NAMES = {}, {}
for name in ("derive render animate export view arrange sketch components grow import batch "
             .. "test repl help"):gmatch("%S+") do
  COMMANDS[name] = true
  NAMES[#NAMES + 1] = name
end

-- Runs the script 'path' ("-": stdin) with args[first+1..] as `arg` and `...`, like lua.c.
local function run_script (path, args, first)
  local chunk, err = loadfile(path ~= "-" and path or nil)
  if chunk == nil then error(err, 0) end
  local sarg = { [-1] = G.arg ~= nil and G.arg[0] or "lsys", [0] = path }
  for i = first + 1, args.n do sarg[#sarg + 1] = args[i] end
  G.arg = sarg
  chunk(table.unpack(sarg, 1, #sarg))
  return 0
end

local function dispatch (args)
  local a = args[1]
  if a == nil then return require("lsys.repl").run() end
  if a == "-h" or a == "--help" then out(USAGE) return 0 end
  -- -V and --version print the version; -v is --verbose where a command has a verbose
  -- mode (lsys test), and prints the version here for one more release, with a warning
  if a == "-V" or a == "--version" or a == "-v" then
    if a == "-v" then warning.deprecated("'lsys -v'", "'lsys -V' (--version)") end
    out(format("lsys %s (%s)\n", host().version or "scm", G._VERSION))
    return 0
  end
  if COMMANDS[a] then return require("lsys.cli.commands." .. a)(args) end
  if a == "-" then return run_script(a, args, 1) end
  if a:sub(1, 1) == "-" then usage(nil, "unknown option '%s'", a) end
  if isfile(a) then return run_script(a, args, 1) end
  if a:find("%.lua$") or a:find("/") then error(format("cannot open '%s'", a), 0) end
  usage(nil, "unknown command '%s'%s", a, suggest.hint(a, NAMES))
end

--- 'msg' without the positions in lsys's own sources that Lua put in it ("/usr/share/lsys/
-- lua/lsys/model.lua:123: "): a user's error names the user's file or the public function,
-- not where inside lsys it was raised (LSYS_DEBUG=1 keeps them, with a traceback).
M.strip_internal = strip_internal

local function handler (e)
  if getmetatable(e) == USAGE_ERROR then return e end
  local msg = e
  if type(msg) ~= "string" then
    local mt = getmetatable(e)
    msg = (mt ~= nil and mt.__tostring ~= nil) and tostring(e)
      or format("(error object is a %s value)", type(e))
  end
  if os.getenv("LSYS_DEBUG") ~= nil then return debug.traceback(msg, 2) end
  return M.strip_internal(msg)
end

-- The program's dofile (the REPL's and its scripts'): Lua's, run through lsys.model.runfile,
-- so that a model the file makes without a name is named after it, as the commands name
-- theirs: `dofile("examples/abop/fig1_24a.lua")` shows as
-- lsys.Model(examples/abop/fig1_24a.lua), not lsys.Model(model), in the REPL and the
-- window's title. Errors as dofile's.
local lua_dofile = G.dofile
local function dofile (path)
  if path == nil then return lua_dofile() end    -- stdin
  local chunk, err = loadfile(path)
  if chunk == nil then error(err, 0) end
  local r = table.pack(runfile(path, chunk))
  if not r[1] then error(r[2], 0) end
  return table.unpack(r, 2, r.n)
end

--- Runs the command line `lsys ...` given its arguments (strings).
-- @return the exit status: 0 success, 1 error, 2 usage error
function M.main (...)
  -- The library's warnings (a view file's unsupported commands, a deprecated name) go
  -- through warn(), which Lua starts with off; the program shows them, as `lua -W` does.
  -- Called from another Lua, main leaves that, and dofile, to its host.
  if host().exe ~= nil then
    warn("@on")
    G.dofile = dofile
  end
  local args = table.pack(...)
  local ok, r = xpcall(dispatch, handler, args)
  io.stdout:flush()
  if ok then return math.tointeger(r) or 0 end
  if getmetatable(r) == USAGE_ERROR then
    local prefix = r.cmd and ("lsys: " .. r.cmd .. ": ") or "lsys: "
    local more = r.cmd and format("Run 'lsys %s --help' for its options.", r.cmd)
      or "Run 'lsys --help' for the commands."
    io.stderr:write(prefix, r.msg, "\n", more, "\n")
    return 2
  end
  io.stderr:write("lsys: ", r, "\n")
  return 1
end

M.usage = USAGE
M.help = H.help

return M
