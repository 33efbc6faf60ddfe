--- Positional functions of a sketch (Anastacio et al. 2009, §4): internode length, stem shape
-- (2D) or yaw and pitch (3D), inclination angles and organ sizes, as functions of the
-- relative position x in [0, 1] along the stem. Each is built as a polyline through exact
-- values and handed to cpfg's function form (a clamped cubic B-spline, core.func) with every
-- interior vertex tripled: where four consecutive control points are collinear the cubic
-- B-spline is that straight segment, and with each interior vertex repeated three times any
-- four consecutive control points hold at most two distinct points. So the function IS the
-- polyline, passes through every vertex, and its values at the nodes are exact (a jump is a
-- vertical segment: two vertices with the same x). The templates (lsys.sketch.templates)
-- evaluate the functions only at those vertices, so the derived plant puts its organs at the
-- node positions of §3.3.
-- @module lsys.sketch.functions
local core = require "lsys.core"

local ipairs, error, pcall, math, string, table =
      ipairs, error, pcall, math, string, table
local format = string.format
local sqrt, atan, deg = math.sqrt, math.atan, math.deg
local _ENV = nil

local M = {}

M.RESOLUTION = 1 / 32     -- the longest piece of stem one F draws (stem lengths)

--- Control points of the clamped cubic B-spline that is exactly the polyline `pts`
-- ({{x, y}...}, x nondecreasing from 0 to 1): interior vertices tripled; a single segment
-- gets two points on it at 1/3 and 2/3.
function M.controls (pts)
  local n = #pts
  if n == 2 then
    local a, b = pts[1], pts[2]
    return { { a[1], a[2] }, { a[1] + (b[1] - a[1]) / 3, a[2] + (b[2] - a[2]) / 3 },
             { a[1] + 2 * (b[1] - a[1]) / 3, a[2] + 2 * (b[2] - a[2]) / 3 }, { b[1], b[2] } }
  end
  local out = { { pts[1][1], pts[1][2] } }
  for i = 2, n - 1 do
    local p = pts[i]
    for _ = 1, 3 do out[#out + 1] = { p[1], p[2] } end
  end
  out[#out + 1] = { pts[n][1], pts[n][2] }
  return out
end

--- A Func named `name` that is exactly the polyline `pts`.
function M.polyline (name, pts)
  local ok, f = pcall(core.func, M.controls(pts), { name = name })
  if not ok then error(format("lsys.sketch: function %s: %s", name, f), 0) end
  return f
end

-- Values at points x[1..n] (increasing), extended as constants to 0 and 1 (§4.3, §4.4).
local function nodal (xs, vs)
  local pts = {}
  if xs[1] > 0 then pts[1] = { 0, vs[1] } end
  for i, x in ipairs(xs) do pts[#pts + 1] = { x, vs[i] } end
  if xs[#xs] < 1 then pts[#pts + 1] = { 1, vs[#vs] } end
  if #pts == 1 then pts = { { 0, vs[1] }, { 1, vs[1] } } end
  return pts
end
M.nodal = nodal

--- The pieces the template draws the stem with: every interval between consecutive stops
-- (0, the nodes, 1) halved while it is longer than `res`, as the rule
-- `S(x, d) : d > D --> S(x, d/2) S(x + d/2, d/2)` halves it. Returns the start and length
-- of each piece.
function M.pieces (stops, res)
  local xs, ds = {}, {}
  local function split (x, d)
    if d > res then
      split(x, d / 2)
      split(x + d / 2, d / 2)
    else
      xs[#xs + 1], ds[#ds + 1] = x, d
    end
  end
  for i = 1, #stops - 1 do
    local d = stops[i + 1] - stops[i]
    if d > 0 then split(stops[i], d) end
  end
  return xs, ds
end

--- The stops of the stem: 0, the nodes' x (the first omitted when it is 0) and 1 (omitted
-- when the top node is at 1), and the internode length at each stop but the last.
function M.stops (an)
  local stops = { 0 }
  for _, nd in ipairs(an.nodes) do
    if nd.x > stops[#stops] then stops[#stops + 1] = nd.x end
  end
  if stops[#stops] < 1 then stops[#stops + 1] = 1 end
  return stops
end

--- Internode length (§4.1): at 0 the distance d1 from the base to the first node, at each
-- node the distance to the next node (the layer's length over the nodes per layer), at the
-- top node P_n the distance d2 left to the tip. A piecewise constant function: where the
-- value changes, the jump is a vertical segment half-way between the two stops (not on a
-- stop, where the template evaluates it; the paper draws it at the inclination line).
function M.internode (stops)
  local xs, vs = {}, {}
  for i = 1, #stops - 1 do xs[i], vs[i] = stops[i], stops[i + 1] - stops[i] end
  local pts = { { xs[1], vs[1] } }
  for i = 2, #xs do
    if vs[i] ~= vs[i - 1] then
      local m = (xs[i - 1] + xs[i]) / 2
      pts[#pts + 1] = { m, vs[i - 1] }
      pts[#pts + 1] = { m, vs[i] }
    end
  end
  local last = pts[#pts]
  if last[1] < 1 then pts[#pts + 1] = { 1, last[2] } end
  return M.polyline("internode", pts), pts
end

-- The chord of the 3D stem from relative arc length a to b.
local function chord (geometry, st, a, b)
  local x0, y0, z0 = geometry.at(st, a)
  local x1, y1, z1 = geometry.at(st, b)
  return x1 - x0, y1 - y0, z1 - z0
end

-- Heading angle (degrees, anticlockwise from +y, i.e. towards the turtle's L = -x) of a
-- chord in the drawing plane.
local function heading (sx, sy) return deg(atan(-sx, sy)) end

local function wrap (a)
  while a > 180 do a = a - 360 end
  while a <= -180 do a = a + 360 end
  return a
end

--- Stem shape, 2D (§4.2.1): at the start of each piece the template draws, the angle by which
-- the turtle turns (+, to the left) from the previous piece's chord to this one's (the first
-- from the initial heading, up). The paper's turn "between consecutive tangent vectors" at
-- the resolution of the stem; positive is anticlockwise on the screen.
function M.stem_shape (geometry, an, xs, ds)
  local st, pts, prev = an.stem, {}, 0
  for i, x in ipairs(xs) do
    local sx, sy = chord(geometry, st, x, x + ds[i])
    local h = heading(sx, sy)
    pts[i] = { x, wrap(h - prev) }
    prev = h
  end
  local p = pts
  if p[#p][1] < 1 then p[#p + 1] = { 1, p[#p][2] } end
  return M.polyline("stem_shape", p), p
end

--- Yaw and pitch, 3D (§4.2.2), at the middle of each piece: the Euler angles, in the global
-- frame, of the piece's chord s (x to the viewer's right, y up, z towards the viewer).
-- After the template's @R(0,1,0,0,0,-1) (H = +y, L = -x, U = -z), + turns towards L, to
-- the viewer's left, and ^ pitches towards -U, towards the viewer, so the paper's
-- yaw = atan(sx/sy) and pitch = atan(sz/|sxy|) become yaw = atan2(-sx, sy) (sx counted
-- along L) and pitch = atan2(sz, |sxy|): +(yaw) ^(pitch) then heads the turtle along s.
-- Yaw is unwrapped (continuous) along the stem.
function M.yaw_pitch (geometry, an, xs, ds)
  local st, py, pp = an.stem, {}, {}
  local prev
  for i, x in ipairs(xs) do
    local sx, sy, sz = chord(geometry, st, x, x + ds[i])
    local y = heading(sx, sy)
    if prev then y = prev + wrap(y - prev) end
    prev = y
    local m = x + ds[i] / 2
    py[i] = { m, y }
    pp[i] = { m, deg(atan(sz, sqrt(sx * sx + sy * sy))) }
  end
  local function ends (p)
    if p[1][1] > 0 then table.insert(p, 1, { 0, p[1][2] }) end
    if p[#p][1] < 1 then p[#p + 1] = { 1, p[#p][2] } end
    return p
  end
  py, pp = ends(py), ends(pp)
  return M.polyline("yaw", py), M.polyline("pitch", pp), py, pp
end

--- All the functions of an analysis (lsys.sketch.geometry.analyze): a table by name, the
-- polylines they are made of (`points`), and the pieces of the stem (`pieces`: xs, ds).
function M.build (geometry, an, res)
  res = res or M.RESOLUTION
  local stops = M.stops(an)
  local xs, ds = M.pieces(stops, res)
  local F, P = {}, {}
  F.internode, P.internode = M.internode(stops)
  if an.threed then
    F.yaw, F.pitch, P.yaw, P.pitch = M.yaw_pitch(geometry, an, xs, ds)
  else
    F.stem_shape, P.stem_shape = M.stem_shape(geometry, an, xs, ds)
  end
  local nx, al, be, hl, hr = {}, {}, {}, {}, {}
  for i, nd in ipairs(an.nodes) do
    nx[i], al[i], be[i], hl[i], hr[i] = nd.x, nd.alpha, nd.beta, nd.size_left, nd.size_right
  end
  P.angle_left, P.angle_right = nodal(nx, al), nodal(nx, be)
  P.size_left, P.size_right = nodal(nx, hl), nodal(nx, hr)
  for _, k in ipairs { "angle_left", "angle_right", "size_left", "size_right" } do
    F[k] = M.polyline(k, P[k])
  end
  return F, P, { xs = xs, ds = ds, stops = stops, resolution = res }
end

return M
