-- A surface specified with a branching structure as a framework (cpfg guide §4.2,
-- fig. 24). The guide shows only the picture; this L-system is a reconstruction.
-- A leaf blade is one polygon whose vertices are turtle positions marked with `.`; the
-- framework is walked with G, which draws a line but adds no vertex. To list the vertices
-- in order around the outline, each node keeps the rest of the midrib in a branch between
-- its left and its right vein:
--   ω: { . A(1) }          (plus colours: the framework in dark green)
--   p1: A(k) : k < N -> G [ +(60) G(w(k)) . ] [ A(k+1) ] [ -(60) G(w(k)) . ]
--   p2: A(k) : k == N -> G .
-- so the vertices come as base, left veins from bottom to top, tip, right veins from top
-- to bottom (the numbers of the guide's figure; small spheres mark them here). The vein
-- lengths w(k) = 1.6 sin(πk/N) give an elliptic blade; N = 6.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = ";(1) { . @O(0.12) ;(2) A(1) ;(1) }",
  steps = 6,
  env = { N = 6 },
  productions = {
    "A(k) : k < N --> G [ +(60) G(1.6*sin(pi*k/N)) . @O(0.12) ] [ A(k+1) ]"
      .. " [ -(60) G(1.6*sin(pi*k/N)) . @O(0.12) ]",
    "A(k) : k == N --> G . @O(0.12)",
  },
  view = { line_width = 3, palette = { "#6aa84f", "#274e13" }, contour_sides = 12 },
}
