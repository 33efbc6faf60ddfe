-- Twist of generalized cylinders (cpfg guide §3.3, fig. 19).
-- `a`: `@Gs f -(30) f /(180) @Ge(10)` with the twist minimisation switched off
-- (`minimize_twist = false`, cpfg's "twist of cylinders: off"): the contour follows the
-- turtle's up vector, which the roll /(180) turns half around before the last point, so the
-- segment is twisted by 180°. (The guide prints `f(180)` for the roll: a misprint.)
-- `b`: the same string with the twist minimised (the default): the contour is carried along
-- the axis by the rotation-minimising frame and the roll has no effect.
-- The contour is a four-pointed star given inline in the view (`points`), so the twist
-- shows; radius 0.3.
-- `c`: an ornamental twisted column, designed here: 32 control points with a roll of 12°
-- before each, a five-armed star contour and no twist minimisation, so the arms wind
-- around the axis as on a barley-sugar column; a bend in the middle shows that the
-- winding follows the axis.
local lsys = require "lsys"

local function star (arms, r0, r1)      -- control points of a star-shaped closed contour
  local pts = {}
  for i = 0, 2 * arms - 1 do
    local a = math.pi * i / arms
    local r = i % 2 == 0 and r1 or r0
    pts[#pts + 1] = { r * math.cos(a), r * math.sin(a) }
  end
  return { points = pts, closed = true }
end

local palette = { { diffuse = { 0.78, 0.60, 0.36 }, specular = { 0.3, 0.3, 0.3 },
                    shininess = 30 } }

local function view (minimize, contour)
  return { contours = { [2] = contour }, contour_sides = 48, minimize_twist = minimize,
           palette = palette, direction = { -0.3, -0.4, -1 } }
end

local column = { "#(1.2) @#(2) @Gs" }
for i = 1, 32 do
  column[#column + 1] = (i == 16 and "-(40) " or "") .. "f(0.25) /(12) @Gc(3)"
end
column[#column] = column[#column]:gsub("@Gc", "@Ge")

return {
  a = lsys.lsystem { axiom = "#(0.6) @#(2) @Gs f -(30) f /(180) @Ge(10)",
                     view = view(false, star(4, 0.45, 1.1)) },
  b = lsys.lsystem { axiom = "#(0.6) @#(2) @Gs f -(30) f /(180) @Ge(10)",
                     view = view(true, star(4, 0.45, 1.1)) },
  c = lsys.lsystem { axiom = table.concat(column, " "),
                     view = view(false, star(5, 0.55, 1.1)) },
}
