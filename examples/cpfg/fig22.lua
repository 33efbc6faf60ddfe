-- An apple blossom with predefined surfaces (cpfg guide §4.1, fig. 22), 2 steps,
-- angle increment 18°:
--   ω: F F F F F B
--   p1: B -> [ S //// S //// S //// S //// S ]      five segments 72° apart
--   p2: S -> [ ~C ] [ ~P ] [ ^^ F [ -F ] [ +F ] ]    calyx leaf, petal, stamen
-- The surfaces are cpfg surface files written by surfaces/make.lua (designed here; the
-- guide's were made in its interactive editor): surfaces/calyx.s, a narrow sepal bent
-- below the horizontal, and surfaces/petal.s, a cupped, rounded petal 25° above it, both
-- leaving the stalk along the turtle's up vector, so the five rolls place them around the
-- flower. lsys colours a surface with the turtle's colour, so colours (;) and stamen
-- widths (#) are added to p2; the stalk is drawn as a cylinder.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = ";(1) #(0.22) F F F F F B",
  steps = 2,
  productions = [[
    B --> [ S //// S //// S //// S //// S ]
    S --> [ ;(2) ~C ] [ ;(3) ~P ] [ ;(4) #(0.05) ^^ F [ -F ] [ +F ] ]
  ]],
  view = {
    angle = 18, line_style = "cylinder", contour_sides = 12,
    dir = lsys.here(),
    surfaces = { C = { file = "surfaces/calyx.s", scale = 2.2 },
                 P = { file = "surfaces/petal.s", scale = 2.8 } },
    palette = { "#5f7d3a", "#4f7f2a",
                { diffuse = { 0.98, 0.88, 0.90 }, specular = { 0.2, 0.2, 0.2 }, shininess = 20 },
                "#e8c640" },
    direction = { 0, -1, -0.6 }, projection = "perspective",
  },
}
