--- `lsys repl`: the interactive REPL (lsys.repl), as `lsys` with no arguments starts it.
-- @module lsys.cli.commands.repl
local A = require "lsys.cli.args"
local HELP = require("lsys.cli.help").help

local require = require
local parse, out = A.parse, A.out
local _ENV = nil

local function run (args)
  local opts = parse("repl", { help = "flag", short = { h = "help" } }, args, 2)
  if opts.help then out(HELP.repl) return 0 end
  return require("lsys.repl").run()
end

return run
