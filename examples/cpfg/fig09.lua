-- Radius interpolation along a straight generalized cylinder (cpfg guide §3.2.2,
-- fig. 9). `a`: the longitudinal section R(t), the Hermite curve from (0, 0.2) to (1, 0.1)
-- with tangents of 30°, length 4.5 and 0°, length 3.5, drawn with lines over the u axis
-- (computed here in Lua, only for the picture). `bcd`, left to right:
--   b) `!(0.4) @Gs f(1) !(0.2) @Gr(30,4.5,0,3.5) @Ge(20)`: length 1, the section as drawn;
--   c) the same with f(1.5): the section is stretched along the axis, so the bulge is lower;
--   d) f(1.5) with @Gr(1) first: the tangents keep their 30° and 0° after the stretching.
local lsys = require "lsys"

-- the Hermite curve R(t) of the section, as a polyline: @R points the turtle, F draws
local function section ()
  local P0, P1 = { 0, 0.2 }, { 1, 0.1 }
  local a = math.rad(30)
  local T0, T1 = { 4.5 * math.cos(a), 4.5 * math.sin(a) }, { 3.5, 0 }
  local pts, n = {}, 48
  for i = 0, n do
    local t = i / n
    local h00, h10 = 2 * t ^ 3 - 3 * t ^ 2 + 1, t ^ 3 - 2 * t ^ 2 + t
    local h01, h11 = -2 * t ^ 3 + 3 * t ^ 2, t ^ 3 - t ^ 2
    pts[i + 1] = { h00 * P0[1] + h10 * T0[1] + h01 * P1[1] + h11 * T1[1],
                   h00 * P0[2] + h10 * T0[2] + h01 * P1[2] + h11 * T1[2] }
  end
  local out = { ";(2) #(1) @R(1,0,0) F(1) ;(1) #(2) @M(0, 0.2, 0)" }  -- the u axis, then R(t)
  for i = 2, #pts do
    local dx, dy = pts[i][1] - pts[i - 1][1], pts[i][2] - pts[i - 1][2]
    local len = math.sqrt(dx * dx + dy * dy)
    out[#out + 1] = string.format("@R(%.6f,%.6f,0) F(%.6f)", dx / len, dy / len, len)
  end
  return table.concat(out, " ")
end

local function gc (x, len, adjust)
  return string.format("[ @M(%g,0,0) !(0.4) @Gs f(%g) !(0.2) %s @Gr(30,4.5,0,3.5) @Ge(20) ]",
    x, len, adjust and "@Gr(1)" or "")
end

return {
  a = lsys.lsystem {
    axiom = section(),
    view = { palette = { "#1f1f1f", "#8c8c8c" } },
  },
  bcd = lsys.lsystem {
    axiom = gc(0, 1) .. gc(1.4, 1.5) .. gc(2.8, 1.5, true),
    view = { palette = { "#c99a5b" }, contour_sides = 24, direction = { 0, -0.3, -1 } },
  },
}
