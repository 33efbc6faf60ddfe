-- Shells made by sweeping an open contour along a helico-spiral (cpfg guide §3.2.3,
-- fig. 17). The L-system of fig. 11a with a roll around the heading that orients
-- the contour (Ang3), as printed in the guide:
--   ω: #(5) @Gt(1.0) @#(2) \(Ang3) @Gs /(Ang3) A(1)
--   p1: A(s) -> +(Ang1) /(Ang2) F(s) A(s*R)
--   h1: F(s) -> f(s) #(s*Wid) +(Ang1/2) \(Ang3) @Gc(4) /(Ang3) -(Ang1/2)
-- `a`: a conical contour, R = 1.04, Ang1 = -20, Ang2 = -3.9, Ang3 = 78, 60 steps;
-- `b`: a triangular contour, R = 1.02, Ang1 = -20, Ang2 = -3, Ang3 = 80, 100 steps;
-- `c`: two contours, the triangle on even segments and the triangle with a bump on its
--      outer side on odd segments, interpolated along each segment, so every whorl carries
--      a row of knobs: R = 1.02, Ang1 = -20, Ang2 = -3, Ang3 = 86; A and F count the steps in a
--      second parameter n, and the homomorphism picks the contour by n % 2.
-- Reconstructed here: the contours (contours/shell_*.con; a contour is normalised so its
-- first point lies on the x axis, so what matters is the shape seen from the origin, which
-- is on the spiral); the step counts; the sign of the half turn around the control point
-- (the guide prints -(Ang1/2) before @Gc and +(Ang1/2) after it here, the opposite of
-- fig. 11, which folds the surface into a saw-tooth; +(Ang1/2) first keeps the heading
-- along the spiral); and `minimize_twist = false`: the contour must follow the turtle's
-- roll, or the twist-minimising frame slowly turns it away from the shell's axis and the
-- whorls come apart.
local lsys = require "lsys"

local palette = { { diffuse = { 0.93, 0.84, 0.70 }, specular = { 0.35, 0.35, 0.35 },
                    shininess = 40 } }

local function view (contours)
  return { dir = lsys.here(), contours = contours, contour_sides = 32, minimize_twist = false,
           palette = palette, direction = { 1, 0, -0.2 }, up = { 0, 0, 1 },
           light = { -0.5, 0.4, 0.8 } }
end

local function shell (R, Ang1, Ang2, Ang3, steps, contour)
  return lsys.lsystem {
    axiom = "#(Wid) @Gt(1.0) @#(2) \\(Ang3) @Gs /(Ang3) A(1)",
    steps = steps,
    env = { R = R, Ang1 = Ang1, Ang2 = Ang2, Ang3 = Ang3, Wid = 5 },
    productions = "A(s) --> +(Ang1) /(Ang2) F(s) A(s*R)",
    homomorphism = "F(s) --> f(s) #(s*Wid) +(Ang1/2) \\(Ang3) @Gc(4) /(Ang3) -(Ang1/2)",
    view = view { [2] = contour },
  }
end

return {
  a = shell(1.04, -20, -3.9, 78, 60, "contours/shell_cone.con"),
  b = shell(1.02, -20, -3, 80, 100, "contours/shell_triangle.con"),
  c = lsys.lsystem {
    axiom = "#(Wid) @Gt(1.0) @#(2) \\(Ang3) @Gs /(Ang3) A(1,0)",
    steps = 100,
    env = { R = 1.02, Ang1 = -20, Ang2 = -3, Ang3 = 86, Wid = 5 },
    productions = "A(s,n) --> +(Ang1) /(Ang2) F(s,n) A(s*R, n+1)",
    homomorphism = [[
      F(s,n) : n % 2 == 0 --> f(s) #(s*Wid) +(Ang1/2) \(Ang3) @#(2) @Gc(4) /(Ang3) -(Ang1/2)
      F(s,n) : n % 2 == 1 --> f(s) #(s*Wid) +(Ang1/2) \(Ang3) @#(3) @Gc(4) /(Ang3) -(Ang1/2)
    ]],
    view = view { [2] = "contours/shell_triangle.con", [3] = "contours/shell_knob.con" },
  },
}
