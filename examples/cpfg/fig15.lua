-- Aloe variegata (cpfg guide §3.2.3, fig. 15). The guide describes this model in
-- prose only; this L-system is a reconstruction. The axiom lays out the plant: a whorl of
-- thick leaves at the bottom (A), a tapered flower stalk (S F ... E) and a phyllotactic
-- raceme of flowers at its top (P).
--   p1: A(n) makes one leaf L and a short step up the rosette per step; the leaf's
--       initial angle from the vertical decreases from the outer (first) leaf to the inner
--       ones; divergence 121°, so the leaves stand in three slowly twisting ranks, as in
--       the real plant.
--   p2: P(n) makes an internode I of the raceme, a flower G and a roll of 137.5°.
--   p3, p4: leaves and flowers grow for a few steps.
-- Homomorphism h1 draws a leaf L as a generalized cylinder with two control points and the
-- keeled leaf contour 2 (contours/aloe_leaf.con, designed here), bent a little outward;
-- @Gr shapes its longitudinal section: full width at the base, a slight bulge, a point at
-- the tip. h2 draws a flower G as a thin pedicel and a pendulous tube with the six-lobed
-- contour 3, again with two control points. The stalk is one generalized cylinder that
-- tapers from S to E, with a control point at each internode. Contours are in fig15.v.
-- The leaves carry the texture textures/aloe.png (@Tx(1); written by textures/make.lua):
-- the broken pale bands across the leaves of the real plant. The /(40) of the axiom only
-- turns the plant so that all three ranks of leaves show. `a` is a single leaf (fig. 15b).
local lsys = require "lsys"

local function view (over)
  local v = lsys.view.load(lsys.here() .. "/fig15.v")
  v.textures = { { file = "textures/aloe.png", mag = "linear", min = "linear" } }
  v.palette = {
    { diffuse = { 1, 1, 1 }, specular = { 0.25, 0.25, 0.25 }, shininess = 30 },  -- 1 leaves
    { 0.46, 0.52, 0.30 },                                       -- 2 stalk
    { diffuse = { 0.90, 0.42, 0.36 }, specular = { 0.2, 0.2, 0.2 }, shininess = 20 },
  }
  for k, x in pairs(over or {}) do v[k] = x end
  return v
end

local homomorphism = {
  "L(s) --> ;(1) @Tx(1) @#(2) #(0.45*s) @Gs f(0.6*s) &(12) @Gr(12,1,-20,1) f(0.4*s) !(0.01)"
    .. " @Ge(12)",
  "G(s) --> ;(2) !(0.05) @Gs &(30) f(0.25) &(110) @Ge(3)"            -- the pedicel
    .. " ;(3) @#(3) !(0.22*s) @Gs f(s) !(0.3*s) @Ge(6)",               -- the flower
  "S --> ;(2) !(0.32) @Gs",
  "F(l) --> f(l) !(0.22) @Gc(4)",
  "I(l,w) --> f(l) !(w) @Gc(1)",
  "E --> !(0.06) f(0.3) @Ge(2)",
}

return {
  c = lsys.lsystem {
    axiom = "/(40) A(NL) S F(3.5) P(NF) E",
    steps = 16,
    env = { NL = 16, NF = 16, DIV = 121 },
    productions = {
      "A(n) : n > 0 --> [ &(20 + 45*n/NL) L(1) ] f(0.06) /(DIV) A(n-1)",
      "P(n) : n > 0 --> I(0.28, 0.07 + 0.14*n/NF) [ G(0.3) ] /(137.5) P(n-1)",
      "L(s) : s < 4.2 --> L(s*1.3)",
      "G(s) : s < 0.9 --> G(s*1.25)",
    },
    homomorphism = homomorphism,
    view = view { direction = { 0, -0.5, -1 } },
  },
  a = lsys.lsystem {
    axiom = "L(4)",
    homomorphism = homomorphism,
    view = view { direction = { -0.6, -0.3, -1 } },
  },
}
