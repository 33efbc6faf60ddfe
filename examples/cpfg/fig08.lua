-- Tangent coefficients of the axis curve (cpfg guide §3.2.1, fig. 8):
-- `@Gs -(45) f -(45) @Gt(s,e) @Ge(20)` for (s,e) = a) the default 1.2,1.2; b) 2,2;
-- c) 0.5,0.5; d) 4,1; e) 3,-2, left to right. The two control points are 1 apart; the
-- tangents have length s and e times that distance. As in the guide, the tangent vectors
-- are drawn scaled by 1/4 (grey lines: up at the first point, to the right at the second;
-- e = -2 points back). Long tangents pull the curve outward; a negative one makes a loop.
local lsys = require "lsys"

local CASES = { { 1.2, 1.2 }, { 2, 2 }, { 0.5, 0.5 }, { 4, 1 }, { 3, -2 } }

local function tangent (len)    -- a grey line of |len|/4 along (or against) the heading
  if len < 0 then return string.format("[ ;(2) #(2) | F(%g) ]", -len / 4) end
  return string.format("[ ;(2) #(2) F(%g) ]", len / 4)
end

local parts = {}
for i, c in ipairs(CASES) do
  local s, e = c[1], c[2]
  parts[i] = string.format(
    "[ @M(%g, 0, 0) %s @O(0.06) @Gs -(45) f -(45) @Gt(%g, %g) @O(0.06) %s @Ge(20) ]",
    (i - 1) * 1.8, tangent(s), s, e, tangent(e))
end

return lsys.lsystem {
  axiom = "!(0.04) " .. table.concat(parts, " "),
  view = { palette = { "#1f1f1f", "#8c8c8c" }, contour_sides = 12 },
}
