-- Textures on cylinders and generalized cylinders (cpfg guide §5.2, fig. 33).
-- @Tx(1) selects the first texture of the view, textures/bark.png (written by
-- textures/make.lua; it tiles in both directions). Around a segment u runs once around the
-- circumference; v runs along it so that the texture's pixels stay square, and continues
-- from one segment to the next, so the pattern runs on without a seam.
-- `a`: a stem of four cylinders (line style "cylinder") bending to the left and tapering
-- (F segments, each narrower at the top: `!` after F).
-- `b`: a branching generalized cylinder, designed here: a forked stem of three orders
-- (A(k, w) makes a segment and two thinner branches, 35° and 30° from it, rolled by 90°)
-- drawn with the homomorphism of fig. 21 (B -> @Gs, F -> f(0.5) @Gc(4) f(0.5), E -> @Ge);
-- the apices A left at the tips narrow the last control point.
-- As in cpfg the two daughter branches are two generalized cylinders that overlap at the
-- fork, so the texture is discontinuous there.
local lsys = require "lsys"

local textures = { { file = "textures/bark.png", mag = "linear", min = "linear" } }
local palette = { { 1, 1, 1 } }

return {
  a = lsys.lsystem {
    axiom = "@Tx(1) !(1) F(1.2) !(0.9) +(8) F(1.2) !(0.8) +(10) F(1.2) !(0.7) +(12) F(1.2) !(0.6)",
    view = { dir = lsys.here(), textures = textures, palette = palette,
             line_style = "cylinder", contour_sides = 24, direction = { -0.3, -0.2, -1 } },
  },
  b = lsys.lsystem {
    axiom = "@Tx(1) !(0.5) B F A(3, 0.5) E",
    steps = 3,
    productions = {
      "A(k,w) : k > 0 --> [ +(35) /(90) !(w*0.7) F A(k-1, w*0.7) E ]"
        .. " [ -(30) /(90) !(w*0.75) F A(k-1, w*0.75) E ]",
    },
    homomorphism = [[
      B --> @Gs
      E --> @Ge(3)
      F --> f(0.5) @Gc(4) f(0.5)
      A(k,w) --> !(w*0.8)
    ]],
    view = { dir = lsys.here(), textures = textures, palette = palette, contour_sides = 24,
             direction = { -0.3, -0.2, -1 } },
  },
}
