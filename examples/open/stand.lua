-- Three of examples/open/shade.lua's plants grown together in one light environment
-- (lsys.stand): every bud sees the sky through its own leaves and its neighbours', so the
-- crowns grow away from each other and the stand makes one canopy (crown shyness, after
-- Palubicki et al. 2009, fig. 12). The file returns the stand as a population Scene:
--
--   lsys render examples/open/stand.lua -o stand.png
local lsys = require "lsys"

local here = lsys.here()
local plants = {}
for i, x in ipairs { -3, 0, 3 } do
  plants[i] = { model = dofile(here .. "/shade.lua"), at = { x, 0, 0 } }
end
local scene = lsys.stand(plants, {
  environment = lsys.environment.light { samples = 48, radiance = "cosine" },
  view = { background = { 1, 1, 1 } },
})
return scene
