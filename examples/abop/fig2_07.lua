-- Sympodial tree architectures after Aono and Kunii, n = 10 (ABOP fig. 2.7 a–d).
-- Returns a table of named models, one per panel. Constants: r1, r2 contraction ratios,
-- a1, a2 branching angles, wr width decrease rate. ABOP's `$` (roll to horizontal) is cpfg's `@v`.
-- Drawn in the default line style, so the widths !(w) are pixels (10 at the base of the trunk).
local lsys = require "lsys"

local function tree (r1, r2, a1, a2)
  return lsys.lsystem {
    axiom = "A(1,10)",
    steps = 10,
    env = { r1 = r1, r2 = r2, a1 = a1, a2 = a2, wr = 0.707 },
    productions = [[
      A(l,w) --> !(w) F(l) [ &(a1) B(l*r1, w*wr) ] /(180) [ &(a2) B(l*r2, w*wr) ]
      B(l,w) --> !(w) F(l) [ +(a1) @v B(l*r1, w*wr) ] [ -(a2) @v B(l*r2, w*wr) ]
    ]],
    view = { angle = a1, direction = { 0, -0.3, -1 } },   -- from a little above: the flat crowns
  }
end

return {
  a = tree(0.9, 0.7, 5, 65),
  b = tree(0.9, 0.7, 10, 60),
  c = tree(0.9, 0.8, 20, 50),
  d = tree(0.9, 0.8, 35, 35),
}
