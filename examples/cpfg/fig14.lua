-- The cactus Lemaireocereus chende (cpfg guide §3.2.3, fig. 14): stems drawn as
-- generalized cylinders with an 8-ribbed star-shaped contour (contours/cactus.con, designed
-- here: 16 control points alternating radius 1.1 and 0.62; the guide's contour is not
-- printed). The L-system is the one printed in the guide:
--   an apex A(ord) makes a segment F, a branch marker B and rolls (/, 60° here);
--   B(ord) makes two opposite branches, or one on the left, or one on the right, each with
--   probability 0.2 - 0.1 ord (so first-order branches rarely and no third order), or none;
--   each new branch starts horizontally, rolled by a normally distributed angle;
--   an apex whose heading ?H points down (y < 0) is cut off with %.
-- The view file fig14.v holds the contour, the angle increment and an upward tropism whose
-- elasticity @Ts(1,0.07) sets, which bends the branches up. The homomorphism makes each
-- stem a generalized cylinder: S starts it, F puts a control point in its middle, E ends it
-- in a point (radius tangent -45° at the tip). Steps (16) and seed (2) are chosen here.
-- `b` is a single stem with the contour (fig. 14b).
local lsys = require "lsys"

local function view ()
  local v = lsys.view.load(lsys.here() .. "/fig14.v")
  v.palette = { { diffuse = { 0.33, 0.52, 0.30 }, specular = { 0.15, 0.15, 0.15 },
                  shininess = 20 } }
  v.direction = { 0, -0.3, -1 }
  return v
end

local homomorphism = [[
  S --> @Gs
  E --> @Gr(0,1,-45,1) !(0.01) @Ge(4)
  F --> f(0.5) @Gc(2) f(0.5)
]]

return {
  c = lsys.lsystem {
    axiom = "@#(2) @Ts(1,0.07) !(0.9) S F A(0) ?H(0,0,0) E",
    steps = 16,
    seed = 2,
    productions = {
      "A(ord) > ?H(x,y,z) : y < 0 --> %",
      "A(ord) --> F B(ord) / A(ord)",
      "B(ord) : ran(1) < 0.2 - ord*0.1 --> "
        .. "[ -(90) /(nran(90,30)) S A(ord+1) ?H(0,0,0) E ] "
        .. "[ +(90) /(nran(90,30)) S A(ord+1) ?H(0,0,0) E ]",
      "B(ord) : ran(1) < 0.2 - ord*0.1 --> [ -(90) /(nran(90,30)) S A(ord+1) ?H(0,0,0) E ]",
      "B(ord) : ran(1) < 0.2 - ord*0.1 --> [ +(90) /(nran(90,30)) S A(ord+1) ?H(0,0,0) E ]",
      "B(ord) --> *",
    },
    homomorphism = homomorphism,
    view = view(),
  },
  b = lsys.lsystem {
    axiom = "@#(2) !(0.9) S F F F E",
    homomorphism = homomorphism,
    view = view(),
  },
}
