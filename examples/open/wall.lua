-- examples/open/selforg.lua's tree grown 2.5 from a wall (Palubicki et al. 2009, §6: a
-- tree's crown takes the shape of the space it has). The wall, 30 high, 30 wide and 0.5
-- thick (seen edge on), stands in the shadow grid as an obstacle: its voxels are as dark as
-- deep shade, and each casts its shadow below it as a bud does, so the buds near it sense
-- less light and turn away; the crown grows to the open side.
--
--   lsys render examples/open/wall.lua -o wall.png
local lsys = require "lsys"

local here = lsys.here()
local m = dofile(here .. "/selforg.lua")
local WALL = { lo = { -3, 0, -15 }, hi = { -2.5, 30, 15 } }
local GROUND = { lo = { -1e4, -1e4, -1e4 }, hi = { 1e4, 0, 1e4 }, cast = false }
m.name = "wall"
-- the same vigour, sensing through a grid with the wall in it
m.environment.sense = lsys.environment.shadow { voxel = 0.5, depth = 6, a = 0.2, b = 2,
                                                C = 1, radius = 1.8,
                                                obstacles = { GROUND, WALL } }
-- the wall drawn as a grey rectangle in its middle plane, before the tree in the string
local x = (WALL.lo[1] + WALL.hi[1]) / 2
local h, d = WALL.hi[2] - WALL.lo[2], WALL.hi[3] - WALL.lo[3]
m.axiom = string.format("[ ;(3) @M(%g, %g, %g) @R(0, 1, 0, 1, 0, 0) { . G(%g) . -(90) G(%g) . "
  .. "-(90) G(%g) . } ] ", x, WALL.lo[2], WALL.lo[3], h, d, h) .. m.axiom
m.view.palette[3] = { 0.7, 0.7, 0.68 }
return m
