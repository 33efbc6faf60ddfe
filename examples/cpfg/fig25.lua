-- Stacked polygons (cpfg guide §4.2, fig. 25): one curved blade made of three
-- planar polygons whose vertices are listed in the order 1..11 by two branches of one
-- string: {1,2,11} at the base, {3,4,9,10} in the middle and {5,6,7,8} at the tip. `{`
-- pushes a new polygon onto the polygon stack and `}` pops and fills the top one,
-- independently of the branch stack, so all three polygons are started in the left branch
-- and completed in the right one. The string is reconstructed from the caption: the left
-- branch walks up the midrib (G draws the framework, adds no vertex) and marks the left
-- edge, opening a polygon at each of its points; the right branch nests the rest of the
-- midrib in a branch before each right point, so it marks the right edge from the tip
-- down and closes the polygons in reverse order:
--   { .1 [ G [+g .2 { .3 ] G [+g .4 { .5 ] G [+g .6 ] ]
--        [ G [ G [ G [-g .7 ] ] [-g .8 } .9 ] ] [-g .10 } .11 ] ] }
-- The midrib bends 15° toward the viewer at each node (&), so the blade is not planar and
-- could not be one polygon; each of the three pieces is planar. Small spheres mark the
-- vertices (one sphere where two vertices coincide: 2 and 3, 4 and 5, 8 and 9, 10 and 11).
local lsys = require "lsys"

local W = { 1.0, 1.2, 0.5 }           -- half widths at the three nodes
local H, BEND = 1.3, 15

local function left (i, open)         -- a left vertex, and a polygon opened there
  return string.format("[ +(90) g(%g) . @O(0.1) %s ]", W[i], open and "{ ." or "")
end
local function right (i, close)       -- a right vertex, and a polygon closed there
  return string.format("[ -(90) g(%g) . @O(0.1) %s ]", W[i], close and ";(1) } ." or "")
end
local G = string.format("&(%g) G(%g)", BEND, H)

local axiom = table.concat({
  ";(1) { . @O(0.1) ;(2)",
  "[", G, left(1, true), G, left(2, true), G, left(3), "]",
  "[", G, "[", G, "[", G, right(3), "]", right(2, true), "]", right(1, true), "]",
  ";(1) }",
}, " ")

return lsys.lsystem {
  axiom = axiom,
  view = { line_width = 3, palette = { "#6aa84f", "#274e13" }, contour_sides = 12,
           direction = { -0.7, -0.3, -1 } },
}
