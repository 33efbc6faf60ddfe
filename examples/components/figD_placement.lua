-- How the multipliers place and turn their children, after Lintermann and Deussen 1999,
-- fig. D (sidebar "Component Types of the Modeler": "Placement and orientation of
-- multiplied components: (1) multiplication by a Hydra component; (2) by a Wreath
-- component; and (3) by a Phiball component"). The same child under each: a cone (a Horn
-- narrowing to a point) along the child's heading with a small leaf at its base facing the
-- child's up side, so both axes of each placement show.
--
--   1 a Hydra of 9: a star round its axis, each child tilted 70 degrees out from it;
--   2 a Wreath of 9 on a ring of radius 1.2: every child along the axis (candles on a
--     wreath), up side outwards;
--   3 a Phiball of 40 on the sphere from its pole to 80 degrees by the golden section
--     (sidebar "Golden Section Placement on a Sphere"), each child along the sphere's
--     normal.
--
-- On a disc each, the three stand in a row on a Simple without geometry.
--
--   build/bin/lsys render examples/components/figD_placement.lua -o figD.png --size 720x280
local lsys = require "lsys"
local C = lsys.components

local function child (k)
  local cone = C.horn { name = "cone" .. k, length = 1, radius = 0.08, tip = 0, segments = 2,
                        color = 2 }
  local flag = C.leaf { name = "flag" .. k, shape = "ovate", length = 0.35, width = 0.5,
                        color = 3 }
  local base = C.simple { name = "child" .. k, primitive = "none" }
  base:child(cone)
  base:child(flag)
  return base
end

local function figD ()
  local row = C.simple { name = "row", primitive = "none" }
  local mults = {
    C.hydra { name = "hydra", n = 9, radius = 0.25, angle = 70 },
    C.wreath { name = "wreath", n = 9, radius = 1.2 },
    C.phiball { name = "phiball", n = 40, radius = 0.9, open = 0, close = 80,
                child_size = 0.7, translate = { 0, 0.2, 0 } },
  }
  for k, m in ipairs(mults) do
    local x = (k - 2) * 3.6
    local disc = C.simple { name = "disc" .. k, primitive = "disc", size = { 2.8, 0, 2.8 },
                            color = 1, translate = { x, 0, 0 } }
    local at = C.simple { name = "at" .. k, primitive = "none", translate = { x, 0.02, 0 } }
    at:child(m)
    m:child(child(k))
    row:child(disc)
    row:child(at)
  end
  return row
end

local VIEW = {
  palette = { { 0.62, 0.58, 0.50 }, { 0.80, 0.42, 0.18 }, { 0.28, 0.55, 0.22 } },
  background = { 0.92, 0.94, 0.96 },
  viewpoint = { 0, 3.6, 11 }, target = { 0, 0.5, 0 }, projection = "perspective", fov = 25,
}

local M = C.model(figD(), { seed = 1, view = VIEW, name = "figD" })
M.graph = figD
M.VIEW = VIEW
return M
