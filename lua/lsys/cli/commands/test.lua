--- `lsys test`: busted run in this program on a user's specs, with lsys and lsys.testing.
-- @module lsys.cli.commands.test
local A = require "lsys.cli.args"
local HELP = require("lsys.cli.help").help

local G = _G
local tostring, error, pcall, require = tostring, error, pcall, require
local out, isfile, isdir = A.out, A.isfile, A.isdir
local _ENV = nil

-- busted's options that take a value, so that `lsys test -t fast` does not read "fast" as a
-- path; and those that choose the specs themselves (a folder, a .busted file, a run in it).
local BUSTED_VALUE, BUSTED_ROOT = {}, {}
for o in ("o output C directory f config-file coverage-config-file t tags exclude-tags "
          .. "filter filter-out m lpath cpath r run repeat seed lang loaders helper lua p "
          .. "pattern exclude-pattern e Xoutput Xhelper"):gmatch("%S+") do
  BUSTED_VALUE[o] = true
end
for o in ("C directory f config-file r run"):gmatch("%S+") do BUSTED_ROOT[o] = true end

local function run (args)
  local bargs = { [0] = G.arg ~= nil and G.arg[0] or "lsys", "--ignore-lua" }
  local paths, chosen = 0, false
  local i = 2
  while i <= args.n do
    local a = args[i]
    bargs[#bargs + 1] = a
    local name, val = a:match("^%-%-?([^=]+)(=?)")
    if a == "-h" or a == "--help" then out(HELP.test) return 0 end
    if a == "--" then
      for j = i + 1, args.n do bargs[#bargs + 1] = args[j] end
      paths = paths + args.n - i
      break
    elseif name == nil or a == "-" then
      paths = paths + 1
    else
      chosen = chosen or BUSTED_ROOT[name] ~= nil
      if val == "" and BUSTED_VALUE[name] and i < args.n then      -- `-t fast`
        i = i + 1
        bargs[#bargs + 1] = args[i]
      end
    end
    i = i + 1
  end
  if paths == 0 and not chosen and not isfile(".busted") and not isdir("spec") then
    bargs[#bargs + 1] = "."
  end
  local ok, runner = pcall(require, "busted.runner")
  if not ok then
    if tostring(runner):find("module 'busted.runner' not found", 1, true) then
      error("busted is not installed for Lua 5.4: apt-get install lua-busted (Debian, "
            .. "Ubuntu), or luarocks --lua-version 5.4 install busted", 0)
    end
    error("cannot load busted: " .. tostring(runner), 0)
  end
  -- busted reads the global `arg`, and names itself after the file of the function that
  -- calls its runner: a chunk called "lsys test". It exits the program itself (os.exit)
  -- when a test fails, and returns when all passed.
  G.arg = bargs
  G.load("(...)({ standalone = false })", "@lsys test")(runner)
  return 0
end

return run
