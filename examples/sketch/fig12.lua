-- Anastacio et al. 2009, figs. 11 and 12 (§7.2): a bromeliad, its stem drawn with pen
-- pressure (fig. 12): the stalk leans away from the viewer. Two sketches, one grammar:
-- the rosette of long arching, channelled leaves (fig12_leaves.json, Fibonacci, 8 nodes
-- per layer, organ_strap.json) and the flower stalk from its centre with red bracts
-- in its upper third (fig12_spike.json, organ_bract.json), drawn on one stem; the
-- stalk's rules are renamed, its stem moves without drawing and its apex starts with the
-- rosette's (lsys.sketch.compose).
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

local leaves = common.sketch("fig12_leaves"):model {
  organ = common.organ("strap"), organ_color = common.LEAF, width = 0.012 }
local spike = common.sketch("fig12_spike"):model {
  organ = common.organ("bract"), organ_color = common.RED }
return lsys.sketch.compose({ leaves, spike }, { name = "bromeliad",
  view = common.view({ 0.3, -0.4, -1 }) })
