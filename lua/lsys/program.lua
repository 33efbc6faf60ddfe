--- What the lsys program (csrc/prog/lsys.c) gives its Lua side: lsys.cli and lsys.repl
-- read it here. Before it loads lsys.cli, the program puts a table in
-- package.loaded["lsys.host"]: its executable's path and directory, the directories of
-- its Lua files and examples, its version, whether it has readline, and POSIX helpers
-- (isatty, clock, interrupt for Ctrl-C, set_idle and clear_line for the REPL's prompt).
-- A plain `lua` has no such table: both modules then go without the helpers.
-- @module lsys.program
local type, package, os = type, package, os
local _ENV = nil

local M = {}

--- The program's table, or an empty one under another Lua. It is looked up at each call,
-- not once: nothing requires "lsys.host", which would make a plain Lua look for a file.
function M.host ()
  local h = package.loaded["lsys.host"]
  return type(h) == "table" and h or {}
end

--- Seconds on the program's clock (monotonic, for timings), or os.clock's under another Lua.
function M.clock ()
  local f = M.host().clock
  return f ~= nil and f() or os.clock()
end

return M
