--- lsys.growview, the documented name (docs/grow.md) of the window session lsys.ui.grow:
-- this module is that one.
-- @module lsys.growview
local require = require
local _ENV = nil

return require "lsys.ui.grow"
