-- The default plant with its sliders beside it (docs/viewer.md, "Editing a plant"): move one
-- and this script hears it (m:on_param), then prints what was built once the plant is made
-- again. Values set here (m.params.a = 30) reach the window the same way. Run with
-- `build/bin/lsys examples/interactive/tune.lua`; close the window to end.
local lsys = require "lsys"
local V = require "lsys.viewer"

local m = dofile(lsys.here() .. "/../default.lua")
m.steps = 7                                  -- a little lighter than `lsys render`'s

m:on_param(function (name, value)
  io.write(string.format("%s = %s\n", name, tostring(value)))
end)

local session = lsys.show(m, { width = 1200, height = 800, title = "tune.lua" })
local built = session.builds
while V.poll(0.1) do
  if session.builds ~= built then           -- a new plant
    built = session.builds
    local st = session.stats
    io.write(string.format("  %d modules, %d triangles, built in %.0f ms\n", st.modules,
                           st.triangles, st.ms))
  end
end
