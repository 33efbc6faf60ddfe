-- Shells on a helico-spiral (cpfg guide §3.2.2, fig. 11).
-- `a`: 117 steps of A(s) -> +(Ang1) /(Ang2) F(s) A(s*R) with R = 1.03, Ang1 = 20°,
-- Ang2 = 2.1°, Wid = 5. The homomorphism turns each F(s) into an invisible f(s) ending in a
-- control point of width s*Wid, turned by half a step so the heading there follows the
-- spiral; @Gt(1.1) in the axiom sets the tangent coefficient of the whole axis. The radius
-- is interpolated linearly between the points, so the tube widens smoothly.
-- `b`: the precious wentletrap. The guide describes but does not print this L-system; this
-- is a reconstruction from its prose. Odd segments F(s,1) end in a control point P half way
-- between two ribs, with the diameter reduced by a quarter; even segments F(s,2) end in
-- two points R and S close together on the rib. The radius tangents (@Gr) are
-- P→R (0°,3)/(60°,2.5): the rising slope; R→S (60°,1)/(−100°,1): the tip of the rib;
-- S→P (−100°,2.5)/(0°,4): the concave falling slope. @Gr(1) in the axiom keeps those
-- angles on the long segments near the opening. Chosen here: 126 steps, R = 1.02,
-- Ang1 = 20° (9 ribs a whorl), Ang2 = 7° (a tall, open spire whose whorls are joined by the
-- ribs, as in Epitonium scalare) and k = 0.25, the part of an even segment between R and S;
-- Wid is that of `a`.
local lsys = require "lsys"

local palette = { { diffuse = { 0.93, 0.86, 0.74 }, specular = { 0.35, 0.35, 0.35 },
                    shininess = 40 } }

return {
  a = lsys.lsystem {
    axiom = "#(Wid) @Gt(1.1) @Gs A(1)",
    steps = 117,
    env = { R = 1.03, Ang1 = 20, Ang2 = 2.1, Wid = 5 },
    productions = "A(s) --> +(Ang1) /(Ang2) F(s) A(s*R)",
    homomorphism = "F(s) --> f(s) #(s*Wid) +(Ang1/2) @Gc(4) -(Ang1/2)",
    view = { palette = palette, contour_sides = 24, direction = { 0, 1, -0.4 },
             up = { 0, 0, 1 }, light = { -0.4, -0.7, 0.7 } },
  },
  b = lsys.lsystem {
    axiom = "#(Wid) @Gt(1.1) @Gr(1) @Gs A(1,1)",
    steps = 126,
    env = { R = 1.02, Ang1 = 20, Ang2 = 7, Wid = 5, k = 0.25 },
    productions = "A(s,n) --> +(Ang1) /(Ang2) F(s,n) A(s*R, 3-n)",
    homomorphism = {
      "F(s,n) : n == 1 --> f(s) #(0.75*s*Wid) +(Ang1/2) @Gr(-100,2.5,0,4) @Gc(4) -(Ang1/2)",
      "F(s,n) : n == 2 --> f(s*(1-k)) #(s*Wid) +(Ang1/2) @Gr(0,3,60,2.5) @Gc(4) -(Ang1/2)"
        .. " f(s*k) +(Ang1/2) @Gr(60,1,-100,1) @Gc(2) -(Ang1/2)",
    },
    view = { palette = palette, contour_sides = 24, direction = { 0, 1, -0.4 },
             up = { 0, 0, 1 }, light = { -0.4, -0.7, 0.7 } },
  },
}
