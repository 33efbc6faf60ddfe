-- examples/open/selforg.lua's tree as a sapling 3 from an older tree (Palubicki et al. 2009,
-- §6: trees that compete for light): the sapling's seed waits 7 steps (W(7)) while its
-- neighbour grows, then both grow together in one shadow grid (lsys.stand), each sharing
-- out its own vigour. Under the older crown the sapling gets little light: it stays small
-- and leans out to the open side, and the older tree's crown keeps away from it.
--
--   lsys render examples/open/neighbour.lua -o neighbour.png
local lsys = require "lsys"

local here = lsys.here()
local old, young = dofile(here .. "/selforg.lua"), dofile(here .. "/selforg.lua")
young.axiom = "W(7)"
return lsys.stand({ { model = old }, { model = young, at = { 3, 0, 0 } } }, {
  environment = old.environment,           -- one environment for the stand
  view = { direction = { 0, -0.15, -1 } },   -- a little from above: the ground shows
})
