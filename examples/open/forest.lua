-- Nine of examples/open/selforg.lua's trees, 20 steps, grown together in one shadow grid
-- (lsys.stand; Palubicki et al. 2009, §6): every bud senses its neighbours' shade as well
-- as its own tree's, each tree shares out its own vigour, and each crown keeps to the space
-- it won (crown shyness): the trees at the edge spread into the open, those inside stay
-- narrow, and a tree overtopped early stays small.
--
--   lsys render examples/open/forest.lua -o forest.png
local lsys = require "lsys"

local here = lsys.here()
local plants = {}
-- a 3 x 3 grid, 6 apart, each tree nudged off it (the same nudges every run), each with
-- leaves of its own autumn colour so that each crown shows where it ends
local NUDGE = { { 0.3, -0.2 }, { -0.4, 0.1 }, { 0.2, 0.4 }, { -0.1, -0.3 }, { 0, 0 },
                { 0.4, 0.2 }, { -0.3, 0.3 }, { 0.1, -0.4 }, { -0.2, 0.1 } }
local GREENS = { { 0.3, 0.6, 0.2 }, { 0.85, 0.65, 0.1 }, { 0.2, 0.45, 0.3 },
                 { 0.8, 0.35, 0.1 }, { 0.45, 0.7, 0.2 }, { 0.65, 0.2, 0.15 },
                 { 0.6, 0.7, 0.15 }, { 0.15, 0.5, 0.15 }, { 0.9, 0.5, 0.15 } }
for i = 1, 9 do
  local m = dofile(here .. "/selforg.lua")
  m.steps = 20
  m.view.palette[2] = GREENS[i]
  local x, z = ((i - 1) % 3 - 1) * 6, ((i - 1) // 3 - 1) * 6
  plants[i] = { model = m, at = { x + NUDGE[i][1], 0, z + NUDGE[i][2] } }
end
return lsys.stand(plants, {
  environment = plants[1].model.environment,           -- one environment for the stand
  -- from above and to the side: the crowns and the gaps between them
  view = { background = { 1, 1, 1 }, direction = { 0.35, -1, -0.6 }, up = { 0, 0, -1 } },
})
