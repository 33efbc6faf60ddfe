-- Anastacio et al. 2009, fig. 8 (§7.1): one sketch (fig8_herb.json), three phyllotactic
-- patterns with three nodes per layer: `decussate` (pairs of leaves, each pair turned 90°
-- from the last), `distichous` (pairs in one plane) and `fibonacci` (one leaf per node,
-- 137.5° apart). The ovate leaf is organ_leaf.json.
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

local sk = common.sketch("fig8_herb")
local leaf = common.organ("leaf")
local out = {}
for _, p in ipairs { "decussate", "distichous", "fibonacci" } do
  out[p] = sk:model { phyllotaxis = p, nodes_per_layer = 3, organ = leaf,
                      organ_color = common.LEAF, width = 0.012,
                      view = common.view({ 0.4, -0.7, -1 }) }
end
return out
