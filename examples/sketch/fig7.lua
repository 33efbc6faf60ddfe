-- Anastacio et al. 2009, fig. 7 (§7.1): one kind of sketch, two plants. `cone`: a pine
-- cone, Fibonacci phyllotaxis with 55 nodes per layer, its woody scales (organ_scale.json)
-- in an ovoid of many thin layers, the lower scales pointing down and the upper ones up.
-- `flower`: a flower head on a stalk, 13 nodes per layer in five layers close together,
-- long pink petals (organ_petal.json) spreading at the rim and shorter upright ones inside.
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

local cone = common.sketch("fig7_cone"):model {
  organ = common.organ("scale"), organ_color = common.SCALE, color = common.SCALE,
  width = 0.012,
  view = common.view({ 0, -0.25, -1 }),
}

local flower = common.sketch("fig7_flower"):model {
  organ = common.organ("petal"), organ_color = common.PETAL, width = 0.025,
  view = common.view({ 0, -0.6, -1 }),
}

return { cone = cone, flower = flower }
