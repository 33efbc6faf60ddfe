-- A fern frond with polygonal leaflets (cpfg guide §4.2, fig. 23).
-- A leaflet is the closed polygon traced by the turtle, as printed in the guide:
--   p1: L -> { - F X + X - F X - | - F X + X + F X }
--   p2: X -> F X
-- so every step each edge made of F's grows by one F: the leaflet grows linearly with age.
-- Inside braces F adds a vertex and draws nothing. With δ = 22.5° the outline is a
-- slightly sickle-shaped (asymmetric) leaflet; the leaflets on the right side of the
-- frond use the mirror image of p1 (R, + and - exchanged), so the pairs are symmetric.
-- The frond is designed here: the apex A makes an internode and a pair of opposite
-- leaflets each step and turns by 2°, so the frond curls a little; the leaflets appear in
-- order of age, the youngest at the top, so the frond tapers to its tip. n = 16; the
-- rachis is a thin cylinder; the leaflets are scaled by @D(0.055).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = ";(1) #(0.1) F(2) A",
  steps = 16,
  productions = [[
    A --> F(1) [ +(65) ;(2) @D(0.055) L ] [ -(65) ;(2) @D(0.055) R ] +(2) A
    L --> { - F X + X - F X - | - F X + X + F X }
    R --> { + F X - X + F X + | + F X - X - F X }
    X --> F X
  ]],
  view = {
    angle = 22.5, line_style = "cylinder", contour_sides = 8,
    palette = { "#6b5a2e", "#3f7a2c" },
  },
}
