-- Ternary branching trees bent by tropism (ABOP fig. 2.8 a–d).
-- Returns a table of named models, one per panel. Constants: d1, d2 divergence angles, a
-- branching angle, lr elongation rate, vr width increase rate; the tropism vector T and the
-- susceptibility e of each panel go into the view, which the turtle applies to every F.
local lsys = require "lsys"

local function tree (n, d1, d2, a, lr, T, e)
  return lsys.lsystem {
    axiom = "!(1) F(200) /(45) A",
    steps = n,
    env = { d1 = d1, d2 = d2, a = a, lr = lr, vr = 1.732 },
    productions = [[
      A --> !(vr) F(50) [ &(a) F(50) A ] /(d1) [ &(a) F(50) A ] /(d2) [ &(a) F(50) A ]
      F(l) --> F(l*lr)
      !(w) --> !(w*vr)
    ]],
    view = { angle = a, tropisms = { { vector = T, elasticity = e } },
             line_style = "cylinder", contour_sides = 10, projection = "perspective" },
  }
end

return {
  a = tree(6, 94.74, 132.63, 18.95, 1.109, { 0, -1, 0 }, 0.22),
  b = tree(8, 137.5, 137.5, 18.95, 1.109, { 0, -1, 0 }, 0.14),
  c = tree(8, 112.5, 157.5, 22.5, 1.790, { -0.02, -1, 0 }, 0.27),
  d = tree(6, 180, 252, 36, 1.070, { -0.61, 0.77, -0.19 }, 0.40),
}
