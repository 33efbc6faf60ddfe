-- Helpers for the construction pictures of the cpfg examples (not a figure): they turn
-- points computed in Lua into turtle strings, so a contour file or a curve can be drawn
-- with lines next to the geometry made from it. Load with
-- `local plot = dofile(lsys.here() .. "/plot.lua")`.
local M = {}

local fmt = string.format

-- A polyline through the points {x, y[, z]}: @M to the first one, then @R (point the
-- turtle at the next point) and F (draw to it) for each following point.
function M.polyline (pts)
  local p = pts[1]
  local out = { fmt("@M(%.6f,%.6f,%.6f)", p[1], p[2], p[3] or 0) }
  for i = 2, #pts do
    local a, b = pts[i - 1], pts[i]
    local dx, dy, dz = b[1] - a[1], b[2] - a[2], (b[3] or 0) - (a[3] or 0)
    local len = math.sqrt(dx * dx + dy * dy + dz * dz)
    if len > 1e-9 then
      out[#out + 1] = fmt("@R(%.6f,%.6f,%.6f) F(%.6f)", dx / len, dy / len, dz / len, len)
    end
  end
  return table.concat(out, " ")
end

-- The control points of a contour file (cpfg guide, Appendix B.1) and whether it is closed.
function M.read_contour (path)
  local f = assert(io.open(path, "r"))
  local n, dim, kind = f:read("n", "n", "l")
  local pts = {}
  for i = 1, n do
    local p = {}
    for k = 1, dim do p[k] = f:read("n") end
    pts[i] = p
  end
  f:close()
  return pts, kind:match("closed") ~= nil
end

-- Points along the uniform cubic B-spline of the control points: n segments for a closed
-- contour, n - 3 for an open one (§3.2.3), 'per' points per segment.
function M.bspline (pts, closed, per)
  local n, out = #pts, {}
  local segs = closed and n or n - 3
  local function P (i) return pts[(i % n) + 1] end
  for s = 0, segs - 1 do
    for k = 0, per - 1 do
      local t = k / per
      local b0, b1 = (1 - t) ^ 3 / 6, (3 * t ^ 3 - 6 * t ^ 2 + 4) / 6
      local b2, b3 = (-3 * t ^ 3 + 3 * t ^ 2 + 3 * t + 1) / 6, t ^ 3 / 6
      local q = {}
      for c = 1, 3 do
        q[c] = b0 * (P(s)[c] or 0) + b1 * (P(s + 1)[c] or 0) + b2 * (P(s + 2)[c] or 0)
               + b3 * (P(s + 3)[c] or 0)
      end
      out[#out + 1] = q
    end
  end
  if closed then out[#out + 1] = out[1] else
    local q = {}
    for c = 1, 3 do
      q[c] = ((P(n - 3)[c] or 0) + 4 * (P(n - 2)[c] or 0) + (P(n - 1)[c] or 0)) / 6
    end
    out[#out + 1] = q
  end
  return out
end

-- A picture of a contour file like fig. 12a of the guide: the unit circle (colour 2), the
-- spline (colour 1, 'w' pixels wide), the control points as small spheres with the first
-- one bigger (colour 3).
function M.contour (path, w)
  local pts, closed = M.read_contour(path)
  local circle = {}
  for i = 0, 64 do
    local a = 2 * math.pi * i / 64
    circle[#circle + 1] = { math.cos(a), math.sin(a), 0 }
  end
  local out = { "[ ;(2) #(1) " .. M.polyline(circle) .. " ]",
                fmt("[ ;(1) #(%g) ", w or 3) .. M.polyline(M.bspline(pts, closed, 12)) .. " ]" }
  for i, p in ipairs(pts) do
    out[#out + 1] = fmt("[ ;(3) @M(%g,%g,%g) @O(%g) ]", p[1], p[2], p[3] or 0,
                        i == 1 and 0.1 or 0.06)
  end
  return table.concat(out, " ")
end

return M
