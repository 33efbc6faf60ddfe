--- lsys.arrange_ui, the documented name (docs/arrange.md) of the window session lsys.ui.arrange:
-- this module is that one.
-- @module lsys.arrange_ui
local require = require
local _ENV = nil

return require "lsys.ui.arrange"
