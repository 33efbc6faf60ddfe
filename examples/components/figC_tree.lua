-- The parameters of a Tree component, after Lintermann and Deussen 1999, fig. C (sidebar
-- "Component Types of the Modeler", Tree: "(1) default outline; (2) gnarled branches; (3)
-- branching density; (4) branching angle; (5) phototropism; and (6) stem curvature"). Six
-- copies of one small tree stand in a row, each with one parameter changed from the first:
--
--   1 the tree: a stem (a Tree of 12 branches, 60 degrees out, 137.5 degrees apart) whose
--     branches are Trees without branches of their own;
--   2 gnarl = 14 on the stem and the branches (random bends, degrees a segment);
--   3 density = 2.5 (the branches crowd towards the stem's base);
--   4 angle = { 110, 25 } (the branching angle as a range: the lower branches point down);
--   5 phototropism = 0.25 on the branches ("applied to the twigs": they turn up to the
--     light);
--   6 curvature = 70 (the stem bends 70 degrees over its length).
--
-- A row of six Trees on a Simple without geometry.
--
--   build/bin/lsys render examples/components/figC_tree.lua -o figC.png --size 720x240
local lsys = require "lsys"
local C = lsys.components

local GAP = 3.2

-- The tree of column k with the parameters `stem` and `branch` over the defaults.
local function tree (k, name, stem, branch)
  local b = { name = name .. "-branch", length = { 1.7, 0.5 }, radius = 0.035, tip = 0.4,
              n = 0, segments = 8, color = 2 }
  for key, v in pairs(branch or {}) do b[key] = v end
  local s = { name = name, length = 4, radius = 0.1, tip = 0.3, n = 12, first = 0.25,
              last = 0.95, angle = 60, segments = 16, color = 1,
              translate = { (k - 3.5) * GAP, 0, 0 } }
  for key, v in pairs(stem or {}) do s[key] = v end
  local t = C.tree(s)
  t:branch(C.tree(b))
  return t
end

local function figC ()
  local row = C.simple { name = "row", primitive = "none" }
  row:child(tree(1, "default"))
  row:child(tree(2, "gnarl", { gnarl = 14 }, { gnarl = 14 }))
  row:child(tree(3, "density", { density = 2.5 }))
  row:child(tree(4, "angle", { angle = { 110, 25 } }))
  row:child(tree(5, "phototropism", nil, { phototropism = 0.25 }))
  row:child(tree(6, "curvature", { curvature = 70 }))
  return row
end

local VIEW = {
  palette = { { 0.45, 0.32, 0.20 }, { 0.50, 0.40, 0.24 } },
  background = { 0.92, 0.94, 0.96 },
  viewpoint = { 0, 3.2, 19 }, target = { 0, 2.1, 0 }, projection = "perspective", fov = 22,
}

local M = C.model(figC(), { seed = 1, view = VIEW, name = "figC" })
M.graph = figC
M.VIEW = VIEW
return M
