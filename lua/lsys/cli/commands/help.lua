--- `lsys help [COMMAND]`: the list of commands, or a command's help.
-- @module lsys.cli.commands.help
local A = require "lsys.cli.args"
local H = require "lsys.cli.help"

local out, usage = A.out, A.usage
local USAGE, HELP = H.usage, H.help
local _ENV = nil

local function run (args)
  local cmd = args[2]
  if cmd == nil then out(USAGE) return 0 end
  if HELP[cmd] == nil then usage(nil, "no help for '%s': not a command", cmd) end
  out(HELP[cmd])
  return 0
end

return run
