-- Anastacio et al. 2009, fig. 9 (§7.2): `single`, a single compound (pinnate) leaf from the
-- sketch fig9_leaf.json: a long rachis, distichous leaflets (organ_leaflet.json), two pairs
-- per layer, shorter towards the tip. `double`, a double compound leaf: that leaf used as
-- the organ of a second sketch (fig9_axis.json, one pair of pinnae per layer along a
-- straight axis), so the whole single leaf is repeated at every node of the axis, scaled to
-- the organ size there (composition, §7.2).
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

-- the leaflets lie in the plane of the rachis (their upper side towards the viewer), so
-- that the fronds of the double leaf are flat as in the paper's figure
local leaflet = common.organ("leaflet", true)
local single = common.sketch("fig9_leaf"):model {
  organ = leaflet, organ_color = common.LEAF, width = 0.008,
  view = common.view({ 0, -0.9, -1 }),
}

local double = common.sketch("fig9_axis"):model {
  organ = single, organ_color = common.LEAF, width = 0.006,
  view = common.view({ 0, -0.9, -1 }),
}

return { single = single, double = double }
