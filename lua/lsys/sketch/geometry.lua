--- The geometry of a sketch (Anastacio et al. 2009, §3): stroke capture, construction lines,
-- layers, nodes and branching intersections. `analyze(sk, opts)` turns a normalized sketch
-- (lsys.sketch.read) into the analysis table documented in docs/sketch.md ("The pipeline").
--
-- Coordinates. Strokes are in pixels, y down. World coordinates put the stem's base a (the
-- lower end of the stem stroke) at the origin, x to the right, y up, z towards the viewer,
-- and take the stem's arc length as the unit (§4.1, §4.4 give every length relative to it):
-- x = (px - ax) / L, y = (ay - py) / L. Depth (§3.5): pressure 0.5 is the drawing plane
-- z = 0, pressure 1 the nearest depth (depth.near, default +0.3), pressure 0 the farthest
-- (depth.far, default -0.3), linear in between; depths are in units of the drawn (projected)
-- stem length, and L is the arc length of the 3D stem, so the 3D stem has length 1.
-- @module lsys.sketch.geometry
local core = require "lsys.core"

local type, ipairs, error, pcall, math, string, table, tostring =
      type, ipairs, error, pcall, math, string, table, tostring
local format = string.format
local sqrt, acos, deg, rad, cos, sin, max, min, huge =
      math.sqrt, math.acos, math.deg, math.rad, math.cos, math.sin, math.max, math.min,
      math.huge
local _ENV = nil

local M = {}

M.DEPTH = { near = 0.3, far = -0.3 }
-- The stem is captured as a 3D polyline whose third coordinate is the pressure times this
-- scale, so that resampling and reverse subdivision (linear in each coordinate) carry the
-- pressure along while the spacing stays one point per pixel of the drawing plane.
local PZ = 1e-3

-- "FILE: stroke 4 (boundary_left): what"
local function fail (sk, stroke, what)
  local where = sk.file or "sketch"
  if stroke and stroke.id ~= nil then
    error(format("%s: stroke %d (%s '%s'): %s", where, stroke.index, stroke.role,
                 tostring(stroke.id), what), 0)
  elseif stroke then
    error(format("%s: stroke %d (%s): %s", where, stroke.index, stroke.role, what), 0)
  end
  error(format("%s: %s", where, what), 0)
end
M.fail = fail

-- The core's message without the "name: " its functions put first.
local function bare (msg)
  return (tostring(msg):gsub("^[%w%._]+: ", ""))
end

-- Points returned by a curve method: a list of {x, y[, z]} or a flat list of numbers.
local function pointlist (r, dim)
  if type(r[1]) == "table" then return r end
  local out = {}
  for i = 1, #r // dim do
    local b = (i - 1) * dim
    out[i] = dim == 3 and { r[b + 1], r[b + 2], r[b + 3] } or { r[b + 1], r[b + 2] }
  end
  return out
end

--- Stroke capture (§3.1): one point per pixel, three steps of Chaikin reverse subdivision,
-- the result as control points of a clamped quadratic B-spline. The curve's anchor points
-- are the stroke's two end points (the clamped curve starts and ends there); nothing else
-- is anchored. `dim` 3 carries the pressure along (the stem in 3D); `reverse` takes the
-- points from last to first. Returns the control points and the curve.
function M.capture (sk, stroke, dim, reverse)
  local pts, n = {}, #stroke.points
  for i = 1, n do
    local p = stroke.points[reverse and n + 1 - i or i]
    pts[i] = dim == 3 and { p[1], p[2], (p[3] or 0.5) * PZ } or { p[1], p[2] }
  end
  local ok, ctrl = pcall(core.stroke_curve, pts, { spacing = 1, steps = 3, degree = 2 })
  if not ok then fail(sk, stroke, bare(ctrl)) end
  ctrl = pointlist(ctrl, dim)
  local ok2, curve = pcall(core.bspline, ctrl, { degree = 2, clamped = true })
  if not ok2 then fail(sk, stroke, bare(curve)) end
  return ctrl, curve
end

-- The 2D curve of the first two coordinates of 3D control points.
local function flat (sk, stroke, ctrl)
  local c2 = {}
  for i, p in ipairs(ctrl) do c2[i] = { p[1], p[2] } end
  local ok, curve = pcall(core.bspline, c2, { degree = 2, clamped = true })
  if not ok then fail(sk, stroke, bare(curve)) end
  return curve
end

-- Index k of the polyline segment [k, k+1] whose relative arc length range holds s.
local function segment (S, s)
  local lo, hi = 1, #S - 1
  while lo < hi do
    local mid = (lo + hi + 1) // 2
    if S[mid] <= s then lo = mid else hi = mid - 1 end
  end
  return lo
end

--- The stem (§3.2, §3.5): its curve and a polyline of `m` points at equal arc length,
-- in pixels (px, py, pressure p) and world coordinates (wx, wy, wz) with the relative arc
-- length s of each point (s = 0 at the base, 1 at the tip). The base is the lower end of
-- the stroke: a stroke drawn from the top is reversed.
function M.stem (sk, stroke, threed, depth)
  local pts = stroke.points
  local reverse = pts[1][2] < pts[#pts][2]
  local ctrl, curve3 = M.capture(sk, stroke, 3, reverse)
  local curve = flat(sk, stroke, ctrl)
  local m = max(64, min(4096, 4 * #ctrl))
  local P = pointlist(curve3:sample_length(m), 3)
  local near, far = depth.near, depth.far
  local PX, PY, PR = {}, {}, {}
  local len2 = 0
  for i = 1, m do
    local p = P[i]
    PX[i], PY[i] = p[1], p[2]
    local pr = p[3] / PZ
    PR[i] = pr < 0 and 0 or pr > 1 and 1 or pr
    if i > 1 then len2 = len2 + sqrt((PX[i] - PX[i - 1]) ^ 2 + (PY[i] - PY[i - 1]) ^ 2) end
  end
  if not (len2 > 0) then fail(sk, stroke, "the stem has no length") end
  -- depth in pixels: pressure 0.5 -> 0, 1 -> near, 0 -> far (§3.5)
  local PZd = {}
  for i = 1, m do
    local pr = PR[i]
    local d = threed and (pr >= 0.5 and (pr - 0.5) * 2 * near or (0.5 - pr) * 2 * far) or 0
    PZd[i] = d * len2
  end
  local cum, L = { 0 }, 0
  for i = 2, m do
    L = L + sqrt((PX[i] - PX[i - 1]) ^ 2 + (PY[i] - PY[i - 1]) ^ 2 + (PZd[i] - PZd[i - 1]) ^ 2)
    cum[i] = L
  end
  local ax, ay = PX[1], PY[1]
  local st = { curve = curve, curve3 = curve3, ctrl = ctrl, m = m, length = L,
               length2d = len2, base = { ax, ay }, px = PX, py = PY, pressure = PR,
               x = {}, y = {}, z = {}, s = {} }
  for i = 1, m do
    st.x[i], st.y[i], st.z[i] = (PX[i] - ax) / L, (ay - PY[i]) / L, PZd[i] / L
    st.s[i] = cum[i] / L
  end
  st.s[m] = 1
  return st
end

--- The point of the stem at relative arc length s: world x, y, z, pixel x, y, and the unit
-- 2D tangent (world, pointing up the stem).
function M.at (st, s)
  local k = segment(st.s, s)
  local s0, s1 = st.s[k], st.s[k + 1]
  local f = s1 > s0 and (s - s0) / (s1 - s0) or 0
  local X, Y, Z = st.x, st.y, st.z
  local tx, ty = X[k + 1] - X[k], Y[k + 1] - Y[k]
  local tl = sqrt(tx * tx + ty * ty)
  if tl > 0 then tx, ty = tx / tl, ty / tl else tx, ty = 0, 1 end
  return X[k] + f * (X[k + 1] - X[k]), Y[k] + f * (Y[k + 1] - Y[k]), Z[k] + f * (Z[k + 1] - Z[k]),
         st.px[k] + f * (st.px[k + 1] - st.px[k]), st.py[k] + f * (st.py[k + 1] - st.py[k]),
         tx, ty
end

-- The relative arc length of the stem point nearest to the pixel point (x, y), and the
-- side of it the point lies on (+1 left of the stem, -1 right, in the drawing plane).
local function project (st, x, y)
  local PX, PY = st.px, st.py
  local best, bs, side = huge, 0, 0
  for k = 1, st.m - 1 do
    local ux, uy = PX[k + 1] - PX[k], PY[k + 1] - PY[k]
    local uu = ux * ux + uy * uy
    local f = uu > 0 and ((x - PX[k]) * ux + (y - PY[k]) * uy) / uu or 0
    f = f < 0 and 0 or f > 1 and 1 or f
    local qx, qy = PX[k] + f * ux, PY[k] + f * uy
    local d = (x - qx) ^ 2 + (y - qy) ^ 2
    if d < best then
      best, bs = d, st.s[k] + f * (st.s[k + 1] - st.s[k])
      -- pixel y is down: left of the direction u on screen is cross(u, p - q) < 0
      local c = ux * (y - qy) - uy * (x - qx)
      side = c < 0 and 1 or c > 0 and -1 or 0
    end
  end
  return bs, side
end
M.project = project

--- A boundary (§3.2): its curve, after checking that most of it lies on its side of the
-- stem ("lies right of the stem" for a left boundary that does not).
function M.boundary (sk, stroke, st, want)
  local ctrl, curve = M.capture(sk, stroke, 2)
  local P = pointlist(curve:sample(17), 2)
  local left, right = 0, 0
  for _, p in ipairs(P) do
    local _, side = project(st, p[1], p[2])
    if side > 0 then left = left + 1 elseif side < 0 then right = right + 1 end
  end
  if want > 0 and right > left then fail(sk, stroke, "lies right of the stem") end
  if want < 0 and left > right then fail(sk, stroke, "lies left of the stem") end
  return { curve = curve, ctrl = ctrl, stroke = stroke }
end

-- The crossing of curves a and b nearest to the pixel point (x, y) (the first one when
-- x is nil), or nil.
local function crossing (a, b, x, y)
  local hits = a:intersect(b)
  local best, bd
  for _, h in ipairs(hits) do
    local hx, hy = h.x or h[3], h.y or h[4]
    local d = x and (hx - x) ^ 2 + (hy - y) ^ 2 or 0
    if not bd or d < bd then best, bd = { hx, hy }, d end
  end
  return best
end

-- The angle in degrees (0..180) between the unit vector (tx, ty) and (vx, vy).
local function angle (tx, ty, vx, vy)
  local l = sqrt(vx * vx + vy * vy)
  if l == 0 then return 0 end
  local c = (tx * vx + ty * vy) / l
  return deg(acos(c > 1 and 1 or c < -1 and -1 or c))
end

--- An inclination line (§3.2, §3.4): where it crosses the stem (relative arc length c and
-- the pixel point) and the two boundaries, and the angles alpha (left) and beta (right)
-- between the stem's tangent (up the stem) and the chords from the stem crossing to the
-- boundary crossings.
function M.inclination (sk, stroke, st, bl, br)
  local ctrl, curve = M.capture(sk, stroke, 2)
  local cs = crossing(st.curve, curve)
  if not cs then fail(sk, stroke, "does not cross the stem") end
  local cl = crossing(bl.curve, curve, cs[1], cs[2])
  if not cl then fail(sk, stroke, "does not cross the left boundary") end
  local cr = crossing(br.curve, curve, cs[1], cs[2])
  if not cr then fail(sk, stroke, "does not cross the right boundary") end
  local c = project(st, cs[1], cs[2])
  local _, _, _, _, _, tx, ty = M.at(st, c)
  local L = st.length
  local alpha = angle(tx, ty, (cl[1] - cs[1]) / L, (cs[2] - cl[2]) / L)
  local beta = angle(tx, ty, (cr[1] - cs[1]) / L, (cs[2] - cr[2]) / L)
  return { stroke = stroke, index = stroke.index, curve = curve, ctrl = ctrl, c = c,
           stem_px = cs, left_px = cl, right_px = cr, alpha = alpha, beta = beta }
end

-- The organ size on one side (§3.4): a ray in the drawing plane from the node (pixel point
-- ox, oy) at `ang` degrees from the stem's tangent (tx, ty: world, unit), turned left
-- (side 1) or right (side -1), to the boundary curve; the distance to the nearest hit in
-- stem lengths. A ray that misses the boundary takes the boundary's point nearest to the
-- node instead (miss = true).
local function ray (b, L, ox, oy, tx, ty, ang, side)
  local a = rad(ang) * side
  local dx, dy = tx * cos(a) - ty * sin(a), tx * sin(a) + ty * cos(a)
  local hits = b.curve:ray(ox, oy, dx, -dy)         -- pixel y is down
  local h = hits[1]
  if h then
    local s, hx, hy = h.s or h[2], h.x or h[3], h.y or h[4]
    return s / L, hx, hy, false
  end
  local t, dist = b.curve:closest(ox, oy)
  local px, py = b.curve:eval(t)
  if type(px) == "table" then px, py = px[1], px[2] end
  return dist / L, px, py, true
end

--- The whole analysis of §3: see docs/sketch.md, "The pipeline", for the table it returns.
-- opts: nodes_per_layer, depth (true/false/nil: from the pressure), near, far.
function M.analyze (sk, opts)
  local strokes = { stem = {}, boundary_left = {}, boundary_right = {}, inclination = {} }
  for _, s in ipairs(sk.strokes) do
    local list = strokes[s.role]
    if not list then fail(sk, s, "unknown role") end
    list[#list + 1] = s
  end
  if #strokes.stem ~= 1 then
    fail(sk, nil, format("a sketch needs exactly one stem stroke, it has %d", #strokes.stem))
  end
  for _, role in ipairs { "boundary_left", "boundary_right" } do
    if #strokes[role] ~= 1 then
      fail(sk, nil, format("a sketch needs exactly one %s stroke, it has %d", role,
                           #strokes[role]))
    end
  end
  if #strokes.inclination < 2 then
    fail(sk, nil, format("a sketch needs at least two inclination lines, it has %d",
                         #strokes.inclination))
  end
  local stem = strokes.stem[1]
  local threed = opts.depth
  if threed == nil then
    threed = false
    for _, p in ipairs(stem.points) do
      if (p[3] or 0.5) ~= 0.5 then threed = true; break end
    end
  end
  local depth = { near = opts.near or (sk.depth and sk.depth.near) or M.DEPTH.near,
                  far = opts.far or (sk.depth and sk.depth.far) or M.DEPTH.far }
  local st = M.stem(sk, stem, threed, depth)
  local bl = M.boundary(sk, strokes.boundary_left[1], st, 1)
  local br = M.boundary(sk, strokes.boundary_right[1], st, -1)
  local lines = {}
  for i, s in ipairs(strokes.inclination) do lines[i] = M.inclination(sk, s, st, bl, br) end
  table.sort(lines, function (a, b) return a.c < b.c end)
  for i = 2, #lines do
    if not (lines[i].c - lines[i - 1].c > 1e-9) then
      fail(sk, nil, format("strokes %d and %d (inclination) cross the stem at the same point",
                           lines[i - 1].index, lines[i].index))
    end
  end
  local N = opts.nodes_per_layer or sk.nodes_per_layer or 3
  local nodes = M.nodes(st, lines, N, bl, br)
  local layers = {}
  for i = 1, #lines - 1 do
    layers[i] = { from = lines[i].c, to = lines[i + 1].c, length = lines[i + 1].c - lines[i].c,
                  internode = (lines[i + 1].c - lines[i].c) / N }
  end
  return { threed = threed, depth = depth, stem = st, left = bl, right = br, lines = lines,
           layers = layers, nodes = nodes, nodes_per_layer = N, length = st.length,
           base = st.base }
end

--- Nodes (§3.3) and their branching intersections (§3.4): N nodes per layer, evenly spaced
-- by arc length, the first on the layer's lower inclination line, plus P_n on the topmost
-- line (§4.1). The angles are interpolated linearly between the layer's lower and upper
-- values; the sizes come from rays to the boundaries.
function M.nodes (st, lines, N, bl, br)
  local nodes, L = {}, st.length
  local function add (x, alpha, beta)
    local wx, wy, wz, px, py, tx, ty = M.at(st, x)
    local hl, lx, ly, lmiss = ray(bl, L, px, py, tx, ty, alpha, 1)
    local hr, rx, ry, rmiss = ray(br, L, px, py, tx, ty, beta, -1)
    nodes[#nodes + 1] = { x = x, pos = { wx, wy, wz }, px = { px, py }, tangent = { tx, ty },
                          alpha = alpha, beta = beta, size_left = hl, size_right = hr,
                          hit_left = { lx, ly }, hit_right = { rx, ry },
                          miss_left = lmiss, miss_right = rmiss }
  end
  for i = 1, #lines - 1 do
    local a, b = lines[i], lines[i + 1]
    for k = 0, N - 1 do
      local f = k / N
      add(a.c + f * (b.c - a.c), a.alpha + f * (b.alpha - a.alpha), a.beta + f * (b.beta - a.beta))
    end
  end
  local top = lines[#lines]
  add(top.c, top.alpha, top.beta)
  return nodes
end

M.segment = segment

return M
