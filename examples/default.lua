-- The default plant of `lsys render`: a 3D broadleaf tree with leaf whorls, bent by gravitropism.
-- Ternary branching after ABOP fig. 2.8a with random branching and divergence angles and
-- occasional forks; trunk and branches elongate (F) and thicken (!) every step; leaves L(t)
-- live for three steps and the homomorphism draws each as a whorl of three polygons.
-- About 43 000 modules after 8 steps. Colour index 1 is bark, 2 is foliage.
local lsys = require "lsys"

-- a lateral shoot: pitched down from the parent axis, one internode, a leaf whorl, an apex
local shoot = "[ &(a + ran(12) - 6) F(50) L(0) A ]"

-- one leaf: a petiole G, then a rhombic blade whose four vertices are recorded with `.`
-- (g moves without drawing or adding a vertex); the blade grows with the leaf's age t
local leaf = "[ ;(2) !(1) &(50) G(8) { . -(25) g(10+3*t) . +(50) g(10+3*t) . +(130) g(10+3*t) . } ]"

return lsys.lsystem {
  axiom = ";(1) !(1) F(200) /(300) A",
  steps = 8,
  seed = 4,
  -- tunable in `lsys view` (sliders beside the plant) and from scripts (m.params.a = 30)
  params = {
    a = { 24, min = 0, max = 90, step = 1, label = "branching angle" },
    d1 = { 94.74, min = 0, max = 180, step = 0.01, label = "divergence 1" },
    d2 = { 132.63, min = 0, max = 180, step = 0.01, label = "divergence 2" },
    lr = { 1.109, min = 1, max = 1.3, step = 0.001, label = "elongation rate" },
    vr = { 1.732, min = 1, max = 2.5, step = 0.001, label = "width rate" },
  },
  productions = {
    "A --> !(vr) F(50) " .. shoot .. " /(d1 + ran(20) - 10) " .. shoot
      .. " /(d2 + ran(20) - 10) " .. shoot .. " : 0.75",
    "A --> !(vr) F(50) " .. shoot .. " /(137.5 + ran(40) - 20) " .. shoot .. " : 0.25",
    "F(l) --> F(l*lr)",
    "!(w) --> !(w*vr)",
    "L(t) : t < 2 --> L(t+1)",
    "L(t) --> *",                 -- the leaves of three steps ago fall
  },
  homomorphism = "L(t) --> " .. leaf .. " /(120) " .. leaf .. " /(120) " .. leaf,
  view = {
    angle = 24,
    tropisms = { { vector = { 0, -1, 0 }, elasticity = 0.1 } },
    line_style = "cylinder", contour_sides = 10,
    projection = "perspective", fov = 30,
  },
}
