--- lsys.sketch.window, the documented name (docs/sketch.md) of the window session lsys.ui.sketch:
-- this module is that one.
-- @module lsys.sketch.window
local require = require
local _ENV = nil

return require "lsys.ui.sketch"
