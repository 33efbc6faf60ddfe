-- Anastacio et al. 2009, figs. 13 and 14 (§7.2): a foxglove (Digitalis purpurea), its
-- stem drawn with pen pressure (fig. 14): it leans back and its raceme nods forward.
-- Composed from two sketches drawn on one stem: the flowers (fig14_flowers.json, a raceme
-- of hanging bells, organ_bell.json, Fibonacci, 6 per layer, smaller towards the tip) and
-- the leaves (fig14_leaves.json, a rosette at the base, organ_foxleaf.json, shorter and more
-- upright up the stem). The distribution of the organs is edited in the rules as the
-- paper's was: the flowers' stem moves without drawing (the leaves' stem is drawn once).
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

local leaves = common.sketch("fig14_leaves"):model {
  organ = common.organ("foxleaf"), organ_color = common.DARK, width = 0.012 }
local flowers = common.sketch("fig14_flowers"):model {
  organ = common.organ("bell"), organ_color = common.BELL }
return lsys.sketch.compose({ leaves, flowers }, { name = "foxglove",
  view = common.view({ 0.3, -0.3, -1 }) })
