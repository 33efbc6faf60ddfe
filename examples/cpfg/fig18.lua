-- The pelican's foot shell, Aporrhais pespelecani (cpfg guide §3.2.3, fig. 18):
-- the two alternating contours of fig. 17c and a third contour (4) for the opening, a flat
-- lip with three long fingers. The guide adds one homomorphism production that draws the
-- last segment (n = Steps - 1) twice as long and ends it with contour 4, so the whorl
-- flares into the lip over that segment:
--   F(s,n) : n == Steps-1 -> f(2*s) #(s*Wid) +(Ang1/2) \(Ang3) @#(4) @Gc(6) /(Ang3) -(Ang1/2)
-- R = 1.025, Ang1 = -20 and Ang3 = 84 as in the guide. Ang2 is -3.6 here: the guide prints
-- 3.6, but a positive roll coils the shell the other way along its axis and turns the
-- contours of fig. 17 (designed for a negative one) inside out. Steps = 90, the lip contour
-- (contours/pelican_lip.con), the half-turn sign and `minimize_twist = false` (see
-- fig17.lua) are choices made here too.
local lsys = require "lsys"

local STEPS = 90

return lsys.lsystem {
  axiom = "#(Wid) @Gt(1.0) @#(2) \\(Ang3) @Gs /(Ang3) A(1,0)",
  steps = STEPS,
  env = { R = 1.025, Ang1 = -20, Ang2 = -3.6, Ang3 = 84, Wid = 5, Steps = STEPS },
  productions = "A(s,n) --> +(Ang1) /(Ang2) F(s,n) A(s*R, n+1)",
  homomorphism = [[
    F(s,n) : n == Steps-1 --> f(2*s) #(s*Wid) +(Ang1/2) \(Ang3) @#(4) @Gc(6) /(Ang3) -(Ang1/2)
    F(s,n) : n % 2 == 0 --> f(s) #(s*Wid) +(Ang1/2) \(Ang3) @#(2) @Gc(4) /(Ang3) -(Ang1/2)
    F(s,n) : n % 2 == 1 --> f(s) #(s*Wid) +(Ang1/2) \(Ang3) @#(3) @Gc(4) /(Ang3) -(Ang1/2)
  ]],
  view = {
    dir = lsys.here(), contour_sides = 48, minimize_twist = false,
    contours = { [2] = "contours/shell_triangle.con", [3] = "contours/shell_knob.con",
                 [4] = "contours/pelican_lip.con" },
    palette = { { diffuse = { 0.90, 0.80, 0.66 }, specular = { 0.35, 0.35, 0.35 },
                  shininess = 40 } },
    direction = { 1, 0, -0.2 }, up = { 0, 0, 1 }, light = { -0.5, 0.4, 0.8 },
  },
}
