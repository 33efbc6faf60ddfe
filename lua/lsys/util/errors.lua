--- Error messages as a user reads them: without the positions in lsys's own Lua files, so
-- that a message names the user's file or the public function, not where inside lsys it
-- was raised.
-- @module lsys.util.errors
local tostring, debug = tostring, debug
local _ENV = nil

local M = {}

-- The folder holding lsys's own Lua modules (the one above this file's lsys/util/), as it
-- appears in error positions ("/usr/share/lua/5.4/").
local SRCDIR = (debug.getinfo(1, "S").source:match("^@(.*)lsys[/\\]util[/\\]errors%.lua$"))

--- `msg` (made text by tostring) without the positions in lsys's own sources that Lua put
-- in it ("/usr/share/lua/5.4/lsys/model.lua:123: ").
function M.strip_internal (msg)
  msg = tostring(msg)
  if SRCDIR == nil or SRCDIR == "" then return msg end
  return (msg:gsub(SRCDIR:gsub("%p", "%%%0") .. "lsys[/\\][%w_/\\]*%.lua:%d+: ", ""))
end

return M
