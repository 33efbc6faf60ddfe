-- Monopodial tree architectures after Honda, n = 10 (ABOP fig. 2.6 a–d).
-- Returns a table of named models, one per panel. Constants: r1, r2 contraction ratios of the
-- trunk and the branches, a0 branching angle from the trunk, a2 for lateral axes, d divergence
-- angle, wr width decrease rate. ABOP's `$` (roll the turtle to horizontal) is cpfg's `@v`.
-- Drawn in the default line style, so the widths !(w) are pixels (10 at the base of the trunk).
local lsys = require "lsys"

local function tree (r1, r2, a0, a2)
  return lsys.lsystem {
    axiom = "A(1,10)",
    steps = 10,
    env = { r1 = r1, r2 = r2, a0 = a0, a2 = a2, d = 137.5, wr = 0.707 },
    productions = [[
      A(l,w) --> !(w) F(l) [ &(a0) B(l*r2, w*wr) ] /(d) A(l*r1, w*wr)
      B(l,w) --> !(w) F(l) [ -(a2) @v C(l*r2, w*wr) ] C(l*r1, w*wr)
      C(l,w) --> !(w) F(l) [ +(a2) @v B(l*r2, w*wr) ] B(l*r1, w*wr)
    ]],
    view = { angle = 45, direction = { 0, -0.25, -1 } },   -- seen from a little above
  }
end

return {
  a = tree(0.9, 0.6, 45, 45),
  b = tree(0.9, 0.9, 45, 45),
  c = tree(0.9, 0.8, 45, 45),
  d = tree(0.9, 0.7, 30, -30),
}
