--- Organs from 3-view strokes (Anastacio et al. 2009, §6): a leaf, petal or scale drawn as
-- its left and right boundaries in a top view, its midrib in a side view and its
-- cross-section in a front view, made into a cross-sectional blending surface with an
-- orthogonal deformation (Cherlin, Samavati, Sousa and Jorge 2005), fitted with bicubic
-- Bézier patches and usable as a `~` surface of any model.
--
--   organ.build{ top = { left = pts, right = pts }, side = pts, front = pts,
--                resolution = {across, along}, precision = {s, t}, name = "leaf",
--                width_scale = 1 }                 -> Organ (also organ{...})
--   organ.load(path_or_table)                      -> Organ (JSON: {"organ": {...}})
--   organ.leaf{ length =, width =, shape = "ovate" | "lanceolate" | "cordate" | ... }
--   org:surface()  org:text()  org:save(path)  org:save_mesh(path [, view])
--   org:to_table()  org:blend(s, t)  org:point(s, t)
--
-- Strokes are lists of points {x, y} (a third number, the pen pressure, is allowed and not
-- used) in pixels, y down as drawn on a screen. The organ's frame is the one of the cpfg
-- surface files (docs/surfaces.md): x across (the turtle's L), y along the organ (its
-- heading H), z its upper side (its up U); the contact point is the base at the origin and
-- the length from the base to the tip is 1, so `~X(h)` draws the organ h long.
--   top view    screen right = +x, screen up = along the organ. Each boundary runs from the
--               base to the tip; the end lower on the screen (larger y) is its base. The
--               base is the middle of the two boundaries' bases, the tip the middle of
--               their tips; the strokes are turned so that base -> tip is +y and scaled so
--               that it is 1 long. A single boundary is mirrored about its own chord.
--   side view   screen up = along the organ, screen right = +z (the organ seen from its
--               left, -x). The end lower on the screen is the base; the stroke is scaled to
--               arc length 1 and bends the flat organ along it (its start at the base).
--   front view  screen right = +x, screen up = +z (seen from the base towards the tip).
--               The end further left meets the left boundary, the other the right one.
-- @module lsys.sketch.organ
local core = require "lsys.core"
local model = require "lsys.model"

local type, pairs, ipairs, error, setmetatable, tostring, pcall, math, string,
      table, require =
      type, pairs, ipairs, error, setmetatable, tostring, pcall, math, string,
      table, require
local format, sqrt, abs, floor, max, min = string.format, math.sqrt, math.abs, math.floor,
      math.max, math.min
local _ENV = nil

local M = {}

local MAXPOINTS = 100000       -- points of one stroke
local MAXCOORD = 1e6           -- |pixel coordinate|
local MAXFILE = 16 * 2 ^ 20    -- bytes of an organ file
local MAXPATCH = 64            -- patches across or along
local TOL = 0.004              -- the fit's target: distance / size of the organ
local FIT_START, FIT_CAP = { 2, 4 }, { 16, 32 }   -- patches {across, along}
local LINES = { 12, 24 }       -- lines across and along the organ drawn by default

local Organ = { __name = "lsys.Organ" }
Organ.__index = Organ
M.Organ = Organ

local function isnum (x)
  return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge
end

local function isint (x) return isnum(x) and x == floor(x) end

-- --------------------------------------------------------------------------
-- Strokes

-- The points of stroke `role` checked and copied into xs, ys (pixels, duplicates of the
-- previous point dropped). `who` begins every message.
local function stroke (who, role, pts)
  local function bad (fmt, ...) error(format("%s: %s stroke: " .. fmt, who, role, ...), 0) end
  if type(pts) ~= "table" then bad("must be a list of points {x, y}, got %s", type(pts)) end
  local n = #pts
  if n > MAXPOINTS then bad("more than %d points", MAXPOINTS) end
  if n < 2 then bad("fewer than two points") end
  local xs, ys = {}, {}
  for i = 1, n do
    local p = pts[i]
    if type(p) ~= "table" or #p < 2 or #p > 3 then
      bad("point %d must be {x, y} or {x, y, pressure}", i)
    end
    for k = 1, #p do
      local c = ({ "x", "y", "pressure" })[k]
      if not isnum(p[k]) then bad("point %d: %s is not a finite number", i, c) end
      if abs(p[k]) > MAXCOORD then bad("point %d: %s is out of range (limit 1e6)", i, c) end
    end
    local m = #xs
    if m == 0 or p[1] ~= xs[m] or p[2] ~= ys[m] then xs[m + 1], ys[m + 1] = p[1], p[2] end
  end
  if #xs < 2 then bad("has no length (all its points are the same)") end
  return { xs = xs, ys = ys }
end

local function reverse (s)
  local xs, ys, n = {}, {}, #s.xs
  for i = 1, n do xs[i], ys[i] = s.xs[n + 1 - i], s.ys[n + 1 - i] end
  return { xs = xs, ys = ys }
end

-- Stroke capture (Anastacio et al. 2009, §3.1), when this build's core has it: the points
-- resampled one per pixel, three steps of Chaikin reverse subdivision, the result the
-- control points of a clamped quadratic B-spline, sampled again at equal arc length. A
-- stroke too short for that is taken as drawn.
local function smooth (s)
  local capture, bspline = core.stroke_curve, core.bspline
  if capture == nil or bspline == nil then return s end
  local pts = {}
  for i = 1, #s.xs do pts[i] = { s.xs[i], s.ys[i] } end
  local ok, ctrl = pcall(capture, pts, { spacing = 1, steps = 3, degree = 2 })
  if not ok or type(ctrl) ~= "table" then return s end
  if type(ctrl[1]) ~= "table" then                    -- a flat list x1, y1, x2, y2, ...
    local q = {}
    for i = 1, #ctrl // 2 do q[i] = { ctrl[2 * i - 1], ctrl[2 * i] } end
    ctrl = q
  end
  local ok2, c = pcall(bspline, ctrl, { degree = 2, clamped = true })
  if not ok2 or c == nil then return s end
  local ok3, q = pcall(c.sample_length, c, max(64, min(2048, 4 * #ctrl)))
  if not ok3 or type(q) ~= "table" then return s end
  local xs, ys = {}, {}
  if type(q[1]) == "table" then
    for i = 1, #q do xs[i], ys[i] = q[i][1], q[i][2] end
  else
    for i = 1, #q // 2 do xs[i], ys[i] = q[2 * i - 1], q[2 * i] end
  end
  if #xs < 2 then return s end
  return { xs = xs, ys = ys }
end

-- A polyline as a curve of its normalised arc length: cum[i] is the length up to point i.
local function curve (xs, ys)
  local cum, n = { 0 }, #xs
  for i = 2, n do
    local dx, dy = xs[i] - xs[i - 1], ys[i] - ys[i - 1]
    cum[i] = cum[i - 1] + sqrt(dx * dx + dy * dy)
  end
  return { xs = xs, ys = ys, cum = cum, len = cum[n], n = n }
end

-- The point of curve c at arc-length fraction a (clamped to [0, 1]).
local function at (c, a)
  if a <= 0 then return c.xs[1], c.ys[1] end
  if a >= 1 then return c.xs[c.n], c.ys[c.n] end
  local d, cum = a * c.len, c.cum
  local lo, hi = 1, c.n
  while hi - lo > 1 do
    local mid = (lo + hi) // 2
    if cum[mid] <= d then lo = mid else hi = mid end
  end
  local seg = cum[hi] - cum[lo]
  local f = seg > 0 and (d - cum[lo]) / seg or 0
  return c.xs[lo] + f * (c.xs[hi] - c.xs[lo]), c.ys[lo] + f * (c.ys[hi] - c.ys[lo])
end

-- --------------------------------------------------------------------------
-- The three views in the organ's frame

-- The boundaries in the organ's frame: curves of (x, y), base at the origin, tip at (0, 1).
local function topview (who, left, right, wscale)
  -- each boundary runs from its lower end on the screen (the base) to the tip
  if left and left.ys[1] < left.ys[#left.ys] then left = reverse(left) end
  if right and right.ys[1] < right.ys[#right.ys] then right = reverse(right) end
  local a, b = left or right, right or left
  local bx, by = (a.xs[1] + b.xs[1]) / 2, -(a.ys[1] + b.ys[1]) / 2   -- y up from here
  local tx, ty = (a.xs[#a.xs] + b.xs[#b.xs]) / 2, -(a.ys[#a.ys] + b.ys[#b.ys]) / 2
  local len = sqrt((tx - bx) ^ 2 + (ty - by) ^ 2)
  if len < 1e-9 then
    error(format("%s: top view: the boundaries end where they begin (the organ has no " ..
                 "length)", who), 0)
  end
  local ey = { (tx - bx) / len, (ty - by) / len }
  local ex = { ey[2], -ey[1] }
  local function place (s, role, sign)
    local xs, ys, mean = {}, {}, 0
    for i = 1, #s.xs do
      local qx, qy = s.xs[i] - bx, -s.ys[i] - by
      xs[i] = sign * (qx * ex[1] + qy * ex[2]) / len * wscale
      ys[i] = (qx * ey[1] + qy * ey[2]) / len
      mean = mean + xs[i]
    end
    mean = mean / #xs
    if sign == 1 and role == "left" and mean > 0 then
      error(format("%s: top left stroke: lies right of the midline (base to tip); draw the " ..
                   "left boundary on the left", who), 0)
    elseif sign == 1 and role == "right" and mean < 0 then
      error(format("%s: top right stroke: lies left of the midline (base to tip); draw the " ..
                   "right boundary on the right", who), 0)
    end
    return curve(xs, ys), mean
  end
  local L, R
  if left and right then
    L, R = place(left, "left", 1), place(right, "right", 1)
  else
    local role = left and "left" or "right"
    local c, mean = place(a, role, 1)
    local m = place(a, role, -1)
    if abs(mean) < 1e-9 then
      local wide = 0
      for i = 1, c.n do wide = max(wide, abs(c.xs[i])) end
      if wide < 1e-9 then
        error(format("%s: top %s stroke: a single straight boundary, mirrored, encloses " ..
                     "nothing", who, role), 0)
      end
    end
    if left then L, R = c, m else L, R = m, c end
  end
  return L, R
end

-- The midrib: a curve of (along, height) from the side stroke, arc length 1, base at 0.
local function sideview (s)
  if s.ys[1] < s.ys[#s.ys] then s = reverse(s) end
  local x0, y0 = s.xs[1], s.ys[1]
  local as, hs = {}, {}
  for i = 1, #s.xs do as[i], hs[i] = y0 - s.ys[i], s.xs[i] - x0 end
  local c = curve(as, hs)
  for i = 1, c.n do
    as[i], hs[i], c.cum[i] = as[i] / c.len, hs[i] / c.len, c.cum[i] / c.len
  end
  c.len = 1
  return c
end

-- The cross-section: a curve of (across, height) with its ends at (0, 0) and (1, 0).
local function frontview (who, s)
  if s.xs[1] > s.xs[#s.xs] then s = reverse(s) end
  local n = #s.xs
  local x0, y0 = s.xs[1], -s.ys[1]
  local cx, cy = s.xs[n] - x0, -s.ys[n] - y0
  local c2 = cx * cx + cy * cy
  local len = curve(s.xs, s.ys).len
  if c2 < (1e-6 * len) ^ 2 then
    error(format("%s: front stroke: its ends meet (the cross-section spans no width " ..
                 "between the boundaries)", who), 0)
  end
  local us, ws = {}, {}
  for i = 1, n do
    local dx, dy = s.xs[i] - x0, -s.ys[i] - y0
    us[i], ws[i] = (dx * cx + dy * cy) / c2, (cx * dy - cy * dx) / c2
  end
  return curve(us, ws)
end

-- --------------------------------------------------------------------------
-- The blended surface

-- The midrib's point and unit normal (in the y-z plane) at along-position y: the curve
-- itself on [0, 1], its end tangents beyond. Without a side stroke, a straight midrib.
local function midrib (c, y)
  if c == nil then return y, 0, 0, 1 end
  local d = 1 / 512
  local a, b = max(0, min(y, 1) - d), min(1, max(y, 0) + d)
  local ay, az = at(c, a)
  local by, bz = at(c, b)
  local ty, tz = by - ay, bz - az
  local tl = sqrt(ty * ty + tz * tz)
  if tl > 0 then ty, tz = ty / tl, tz / tl else ty, tz = 1, 0 end
  local my, mz
  if y < 0 then
    my, mz = at(c, 0); my, mz = my + y * ty, mz + y * tz
  elseif y > 1 then
    my, mz = at(c, 1); my, mz = my + (y - 1) * ty, mz + (y - 1) * tz
  else
    my, mz = at(c, y)
  end
  return my, mz, -tz, ty
end

--- The blended surface (before the patch fit) at s (across, 0 = left boundary) and t
-- (along the boundaries, 0 = base), both in [0, 1]: the cross-section placed between the
-- two boundary points at t, scaled to their distance (Cherlin et al. 2005, cross-sectional
-- blending), then bent along the midrib (their orthogonal deformation).
-- @return x, y, z in the organ's frame
function Organ:blend (s, t)
  local g = self._geom
  local lx, ly = at(g.left, t)
  local rx, ry = at(g.right, t)
  local cu, cw = s, 0
  if g.front then cu, cw = at(g.front, s) end
  local dx, dy = rx - lx, ry - ly
  local x, y = lx + cu * dx, ly + cu * dy
  local z0 = cw * sqrt(dx * dx + dy * dy)
  local ym = (ly + ry) / 2
  if ym < 0 then
    -- a row whose middle lies below the base (the boundaries go down round basal lobes, a
    -- cordate or sagittate outline) is bent up through the base on the midline, so the
    -- lobes fan out from the attachment point and the notch between them stays open
    local nx = (lx + rx) / 2
    if cu <= 0.5 then
      x, y = lx + 2 * cu * (nx - lx), ly + 2 * cu * (0 - ly)
    else
      x, y = nx + (2 * cu - 1) * (rx - nx), (2 * cu - 1) * ry
    end
  end
  local my, mz, ny, nz = midrib(g.side, y)
  return x, my + z0 * ny, mz + z0 * nz
end

-- --------------------------------------------------------------------------
-- The patch fit: each patch is the bicubic Bézier patch through 4 x 4 samples of the
-- blended surface at the thirds of its parameter square. Neighbours share their edge
-- samples, so they share the edge curve exactly; a crease of the strokes (a V section)
-- that falls on a patch edge stays sharp.

-- The 3n + 1 Bézier control values of the n cubic pieces through p[0 .. 3n], piece k
-- passing through p[3k], ..., p[3k + 3] at 0, 1/3, 2/3 and 1 (the inverse of the
-- Bernstein matrix at those parameters).
local function interp (p, n)
  local b = { [0] = p[0] }
  for k = 0, n - 1 do
    local p0, p1, p2, p3 = p[3 * k], p[3 * k + 1], p[3 * k + 2], p[3 * k + 3]
    b[3 * k + 1] = (-5 * p0 + 18 * p1 - 9 * p2 + 2 * p3) / 6
    b[3 * k + 2] = (2 * p0 - 9 * p1 + 18 * p2 - 5 * p3) / 6
    b[3 * k + 3] = p3
  end
  return b
end

-- The control net: net[r][c] = {x, y, z}, r = 0 .. 3 nt (along), c = 0 .. 3 ns (across).
local function fit (org, ns, nt)
  local rows = {}
  for i = 0, 3 * nt do
    local px, py, pz = {}, {}, {}
    for j = 0, 3 * ns do px[j], py[j], pz[j] = org:blend(j / (3 * ns), i / (3 * nt)) end
    rows[i] = { interp(px, ns), interp(py, ns), interp(pz, ns) }
  end
  local net = {}
  for r = 0, 3 * nt do net[r] = {} end
  for c = 0, 3 * ns do
    local cols = {}
    for k = 1, 3 do
      local p = {}
      for i = 0, 3 * nt do p[i] = rows[i][k][c] end
      cols[k] = interp(p, nt)
    end
    for r = 0, 3 * nt do net[r][c] = { cols[1][r], cols[2][r], cols[3][r] } end
  end
  return net
end

local function bernstein (u)
  local v = 1 - u
  return v * v * v, 3 * u * v * v, 3 * u * u * v, u * u * u
end

--- The fitted patch surface at (s, t) in [0, 1]², the parameters of `blend`.
-- @return x, y, z
function Organ:point (s, t)
  local ns, nt, net = self.resolution[1], self.resolution[2], self._net
  local ps, pt = min(floor(s * ns), ns - 1), min(floor(t * nt), nt - 1)
  local ws, wt = { bernstein(s * ns - ps) }, { bernstein(t * nt - pt) }
  local x, y, z = 0, 0, 0
  for r = 0, 3 do
    for c = 0, 3 do
      local p, w = net[3 * pt + r][3 * ps + c], wt[r + 1] * ws[c + 1]
      x, y, z = x + w * p[1], y + w * p[2], z + w * p[3]
    end
  end
  return x, y, z
end

-- The largest distance between the fit and the blended surface at 9 points inside each
-- patch, divided by the organ's size (the largest extent of its control net).
local function fiterror (org)
  local ns, nt = org.resolution[1], org.resolution[2]
  local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
  for _, row in pairs(org._net) do
    for _, p in pairs(row) do
      for k = 1, 3 do lo[k], hi[k] = min(lo[k], p[k]), max(hi[k], p[k]) end
    end
  end
  local size = max(hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3])
  local worst = 0
  for i = 0, nt - 1 do
    for j = 0, ns - 1 do
      for _, a in ipairs { 0.25, 0.5, 0.75 } do
        for _, b in ipairs { 0.25, 0.5, 0.75 } do
          local s, t = (j + a) / ns, (i + b) / nt
          local x, y, z = org:blend(s, t)
          local u, v, w = org:point(s, t)
          worst = max(worst, sqrt((x - u) ^ 2 + (y - v) ^ 2 + (z - w) ^ 2))
        end
      end
    end
  end
  return worst / size, size
end

-- --------------------------------------------------------------------------
-- Building

local KNOWN = { top = true, side = true, front = true, resolution = true, precision = true,
                name = true, width_scale = true, capture = true }
local KNOWNLIST = "top, side, front, resolution, precision, name, width_scale, capture"

-- A pair of whole numbers from 1 to `hi`, or nil when not given.
local function pair (who, what, p, hi)
  if p == nil then return nil end
  if type(p) ~= "table" or #p ~= 2 or not isint(p[1]) or not isint(p[2])
     or p[1] < 1 or p[2] < 1 or p[1] > hi or p[2] > hi then
    error(format("%s: '%s' must be {across, along}, whole numbers from 1 to %d", who, what, hi),
          0)
  end
  return { math.tointeger(p[1]), math.tointeger(p[2]) }
end

local function build (t, who)
  if type(t) ~= "table" then
    error(format("%s: a table { top = ..., side = ..., front = ... } expected, got %s", who,
                 type(t)), 0)
  end
  if t.organ ~= nil then t = t.organ end
  if type(t) ~= "table" then error(format("%s: 'organ' must be an object", who), 0) end
  for k in pairs(t) do
    if not KNOWN[k] then
      error(format("%s: unknown field '%s' (known: %s)", who, tostring(k), KNOWNLIST), 0)
    end
  end
  local top = t.top
  if type(top) ~= "table" then
    error(format("%s: 'top' must be { left = points, right = points }", who), 0)
  end
  for k in pairs(top) do
    if k ~= "left" and k ~= "right" then
      error(format("%s: top: unknown field '%s' (known: left, right)", who, tostring(k)), 0)
    end
  end
  if top.left == nil and top.right == nil then
    error(format("%s: top view: a left or a right boundary stroke is needed", who), 0)
  end
  local name = t.name
  if name == nil then name = "organ"
  elseif type(name) ~= "string" or not name:match("^[%w_%-%.]+$") or #name > 63 then
    error(format("%s: 'name' must be a word of at most 63 letters, digits, '_', '-' or '.'",
                 who), 0)
  end
  local ws = t.width_scale
  if ws == nil then ws = 1
  elseif not isnum(ws) or ws <= 0 or ws > 1000 then
    error(format("%s: 'width_scale' must be a number > 0 and at most 1000", who), 0)
  end
  local res = pair(who, "resolution", t.resolution, MAXPATCH)
  local prec = pair(who, "precision", t.precision, 256)
  if t.capture ~= nil and type(t.capture) ~= "boolean" then
    error(format("%s: 'capture' must be true or false", who), 0)
  end
  local cap = t.capture ~= false and smooth or function (x) return x end
  local left = top.left ~= nil and cap(stroke(who, "top left", top.left)) or nil
  local right = top.right ~= nil and cap(stroke(who, "top right", top.right)) or nil
  local side = t.side ~= nil and cap(stroke(who, "side", t.side)) or nil
  local front = t.front ~= nil and cap(stroke(who, "front", t.front)) or nil
  local L, R = topview(who, left, right, ws)
  local org = setmetatable({
    name = name, width_scale = ws,
    _geom = { left = L, right = R, side = side and sideview(side),
              front = front and frontview(who, front) },
    _src = { top = { left = top.left, right = top.right }, side = t.side, front = t.front },
  }, Organ)
  local ns, nt = res and res[1] or FIT_START[1], res and res[2] or FIT_START[2]
  while true do
    org.resolution = { ns, nt }
    org._net = fit(org, ns, nt)
    org.fit_error, org.size = fiterror(org)
    if res or org.fit_error <= TOL or (ns >= FIT_CAP[1] and nt >= FIT_CAP[2]) then break end
    ns, nt = min(2 * ns, FIT_CAP[1]), min(2 * nt, FIT_CAP[2])
  end
  org.precision = prec or { max(1, -(-LINES[1] // ns)), max(1, -(-LINES[2] // nt)) }
  org._given = { resolution = res, precision = prec, capture = t.capture }
  return org
end

--- An Organ from strokes (see the top of this file). Raises naming the stroke and what is
-- wrong with it ("lsys.sketch.organ: side stroke: fewer than two points").
function M.build (t)
  return build(t, "lsys.sketch.organ")
end

-- --------------------------------------------------------------------------
-- Files

local function num (x) return (format("%.6f", x):gsub("^%-(0%.0+)$", "%1")) end

--- The organ as the text of a cpfg surface file (.s; docs/surfaces.md).
function Organ:text ()
  if self._text then return self._text end
  local ns, nt, net = self.resolution[1], self.resolution[2], self._net
  local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
  for r = 0, 3 * nt do
    for c = 0, 3 * ns do
      for k = 1, 3 do lo[k], hi[k] = min(lo[k], net[r][c][k]), max(hi[k], net[r][c][k]) end
    end
  end
  local out = {
    table.concat({ num(lo[1]), num(hi[1]), num(lo[2]), num(hi[2]), num(lo[3]), num(hi[3]) },
                 " "),
    format("PRECISION S: %d T: %d", self.precision[1], self.precision[2]),
    "CONTACT POINT  X: 0.000000 Y: 0.000000 Z: 0.000000",
    "END POINT  X: 0.000000 Y: 0.000000 Z: 0.000000",
    "HEADING  X: 0.000000 Y: 1.000000 Z: 0.000000",
    "UP  X: 0.000000 Y: 0.000000 Z: 1.000000",
    "SIZE: 1.000000",
  }
  -- patch (i along, j across); "above" is the base side (row 0), "left" is -x (column 0)
  local function pname (i, j)
    if i < 0 or j < 0 or i >= nt or j >= ns then return "~" end
    return format("p%d_%d", i, j)
  end
  for i = 0, nt - 1 do
    for j = 0, ns - 1 do
      out[#out + 1] = pname(i, j)
      out[#out + 1] = "TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00"
      out[#out + 1] = format("AL: %s A: %s AR: %s", pname(i - 1, j - 1), pname(i - 1, j),
                             pname(i - 1, j + 1))
      out[#out + 1] = format("L: %s R: %s", pname(i, j - 1), pname(i, j + 1))
      out[#out + 1] = format("BL: %s B: %s BR: %s", pname(i + 1, j - 1), pname(i + 1, j),
                             pname(i + 1, j + 1))
      for r = 0, 3 do
        local row = {}
        for c = 0, 3 do
          local p = net[3 * i + r][3 * j + c]
          row[#row + 1] = format("%s %s %s", num(p[1]), num(p[2]), num(p[3]))
        end
        out[#out + 1] = table.concat(row, "  ")
      end
    end
  end
  self._text = table.concat(out, "\n") .. "\n"
  return self._text
end

--- The organ as an lsys.Surface (core.surface_parse of `text`), made once.
function Organ:surface ()
  if self._surface == nil then
    self._surface = core.surface_parse(self:text(), self.name .. ".s")
  end
  return self._surface
end

--- Writes the organ as a cpfg surface file, atomically. Raises naming the file.
function Organ:save (path)
  if type(path) ~= "string" or path == "" then
    error("save: a file name expected, got " .. type(path), 2)
  end
  local ok, err = pcall(core.write_file, path, self:text())
  if not ok then error("save: " .. tostring(err), 2) end
  return self
end

--- Writes the organ alone as a mesh (.obj with .mtl, .ply or .glb by the extension): a
-- model that draws it once with `~O`, in colour 2 (leaf green) unless `view` (view
-- options merged over those) says otherwise.
function Organ:save_mesh (path, view)
  if type(path) ~= "string" or path == "" then
    error("save_mesh: a file name expected, got " .. type(path), 2)
  end
  if view ~= nil and type(view) ~= "table" then
    error("save_mesh: 'view' must be a table of view options", 2)
  end
  local v = { color = 2 }
  for k, x in pairs(view or {}) do v[k] = x end
  v.surfaces = { O = self }
  local ok, err = pcall(function ()
    local m = model.lsystem { axiom = "~O", view = v }
    m:interpret(m:derive(0)):save(path)
  end)
  if not ok then error("save_mesh: " .. tostring(err), 2) end
  return self
end

-- A copy of a stroke's points as plain lists (for JSON).
local function copypts (pts)
  if pts == nil then return nil end
  local out = {}
  for i, p in ipairs(pts) do out[i] = { table.unpack(p) } end
  return out
end

--- The organ as a table for JSON: { organ = { top = { left =, right = }, side =, front =,
-- name =, width_scale = [, resolution =, precision =] } }, strokes as given.
function Organ:to_table ()
  local o = {
    top = { left = copypts(self._src.top.left), right = copypts(self._src.top.right) },
    side = copypts(self._src.side), front = copypts(self._src.front),
    name = self.name, width_scale = self.width_scale,
  }
  if self._given.resolution then o.resolution = { table.unpack(self._given.resolution) } end
  if self._given.precision then o.precision = { table.unpack(self._given.precision) } end
  o.capture = self._given.capture
  return { organ = o }
end

function Organ:__tostring ()
  local n = self.resolution[1] * self.resolution[2]
  return format("lsys.Organ(%s, %d patch%s)", self.name, n, n == 1 and "" or "es")
end

--- An Organ from a JSON file ({"organ": {...}}) or from such a table. Raises naming the
-- file: "organ leaf.json: side stroke: fewer than two points".
function M.load (x)
  if type(x) == "table" then return build(x, "lsys.sketch.organ.load") end
  if type(x) ~= "string" then
    error("lsys.sketch.organ.load: a file name or a table expected, got " .. type(x), 2)
  end
  local who = "organ " .. x
  local ok, text, why = pcall(core.read_file, x, MAXFILE)
  if not ok or type(text) ~= "string" then
    -- read_file raises on misuse and returns nil and why for a file it cannot read
    error(format("%s: %s", who, tostring(ok and why or text):gsub("^lsys%.[%w_.]+: ", "")), 2)
  end
  local cjson = require("cjson").new()
  cjson.decode_invalid_numbers(false)
  cjson.decode_max_depth(16)
  local ok2, t = pcall(cjson.decode, text)
  if not ok2 then error(format("%s: malformed JSON: %s", who, tostring(t)), 2) end
  if type(t) ~= "table" or t.organ == nil then
    error(format("%s: expected an object {\"organ\": {...}}", who), 2)
  end
  -- JSON null is cjson.null: report it as a missing stroke's wrong type
  local ok3, org = pcall(build, t, who)
  if not ok3 then error(org, 2) end
  return org
end

--- Writes org:to_table() as JSON, atomically.
function Organ:save_json (path)
  local cjson = require "cjson"
  local ok, err = pcall(core.write_file, path, cjson.encode(self:to_table()) .. "\n")
  if not ok then error("save_json: " .. tostring(err), 2) end
  return self
end

-- --------------------------------------------------------------------------
-- Leaf shapes

-- Leaf outlines as half-widths w(y), y from 0 at the base to 1 at the tip: y^a (1 - y)^b
-- scaled to 1/2 at its widest (y = a / (a + b)), and each shape's usual width (of the
-- length). The cordate outline is drawn apart: its basal lobes reach below the base.
local SHAPES = {
  ovate = { 0.5, 0.9, 0.6 }, obovate = { 0.9, 0.5, 0.6 }, elliptic = { 0.7, 0.7, 0.5 },
  lanceolate = { 0.45, 1.3, 0.25 }, linear = { 0.15, 0.25, 0.1 }, cordate = { 0, 0, 0.8 },
}
local function halfwidth (shape, y)
  local a, b = SHAPES[shape][1], SHAPES[shape][2]
  local m = a / (a + b)
  return 0.5 * (y ^ a * (1 - y) ^ b) / (m ^ a * (1 - m) ^ b)
end
local SECTIONS = { flat = true, v = true, cup = true }

--- Strokes for a common leaf shape, built into an Organ: { length = 100 (pixels),
-- width = (of the length: ovate and obovate 0.6, elliptic 0.5, lanceolate 0.25, linear 0.1,
-- cordate 0.8), shape = "ovate" | "lanceolate" | "elliptic" | "obovate" |
-- "linear" | "cordate", curl = 0 (how far the tip droops, of the length; < 0 lifts),
-- section = "flat" | "v" | "cup", depth = 0.15 (of the width, for "v" and "cup"),
-- outline = (instead of a shape: points {x, y} of one half from the base, y = 0, to the tip,
-- y = 1, x the half-width as a fraction of the length; mirrored), name =, resolution =,
-- precision = }.
function M.leaf (o)
  o = o or {}
  local who = "lsys.sketch.organ.leaf"
  local known = { length = true, width = true, shape = true, curl = true, section = true,
                  depth = true, name = true, resolution = true, precision = true,
                  outline = true }
  for k in pairs(o) do
    if not known[k] then error(format("%s: unknown option '%s'", who, tostring(k)), 2) end
  end
  local shape, sect = o.shape or "ovate", o.section or "flat"
  local len, wid = o.length or 100, o.width or (SHAPES[shape] or SHAPES.ovate)[3]
  local curl, depth = o.curl or 0, o.depth or 0.15
  if not isnum(len) or len <= 0 or len > 1e5 then
    error(who .. ": 'length' must be a number of pixels > 0 (at most 1e5)", 2)
  end
  for _, kx in ipairs { { "width", wid }, { "curl", curl }, { "depth", depth } } do
    local k, x = kx[1], kx[2]
    if not isnum(x) or abs(x) > 10 or (k == "width" and x <= 0) then
      error(format("%s: '%s' must be a number %s", who, k,
                   k == "width" and "> 0 and at most 10" or "from -10 to 10"), 2)
    end
  end
  if SHAPES[shape] == nil then
    error(format("%s: unknown shape '%s' (known: ovate, lanceolate, elliptic, obovate, " ..
                 "linear, cordate)", who, tostring(shape)), 2)
  end
  if not SECTIONS[sect] then
    error(format("%s: unknown section '%s' (known: flat, v, cup)", who, tostring(sect)), 2)
  end
  local left, N = {}, 48
  local x0, y0 = 200, 200 + len              -- the base, on the screen
  if o.outline ~= nil then
    local ol = o.outline
    if type(ol) ~= "table" or #ol < 2 or #ol > 10000 then
      error(who .. ": 'outline' must be a list of 2 to 10000 points {x, y}", 2)
    end
    for i, q in ipairs(ol) do
      if type(q) ~= "table" or not isnum(q[1]) or not isnum(q[2]) or abs(q[1]) > 10 or
         abs(q[2]) > 10 then
        error(format("%s: 'outline[%d]' must be a point {x, y} of finite numbers (at most " ..
                     "10 in size)", who, i), 2)
      end
      left[i] = { x0 - len * abs(q[1]), y0 - len * q[2] }
    end
  elseif shape == "cordate" then
    -- from the notch down round a basal lobe, out to the widest part and up to the tip:
    -- the classic heart curve (x = sin^3, y from four cosines), its lobes made half as deep
    for i = 0, N do
      local th = math.pi * i / N
      local y = (5 - 13 * math.cos(th) + 5 * math.cos(2 * th) + 2 * math.cos(3 * th)
                 + math.cos(4 * th)) / 22
      if y < 0 then y = y / 2 end
      left[i + 1] = { x0 - len * wid * 0.6 * math.sin(th) ^ 3, y0 - len * y }
    end
  else
    for i = 0, N do
      local y = 0.5 - 0.5 * math.cos(math.pi * i / N)   -- denser at the base and the tip
      left[i + 1] = { x0 - len * wid * halfwidth(shape, y), y0 - len * y }
    end
  end
  local side = {}
  for i = 0, N do
    local y = i / N
    side[i + 1] = { 100 - len * curl * y * y, y0 - len * y }
  end
  local front
  if sect == "v" then
    front = { { 0, 0 }, { 50, 100 * depth }, { 100, 0 } }
  elseif sect == "cup" then
    front = {}
    for i = 0, N do
      local a = math.pi * i / N
      front[i + 1] = { 50 - 50 * math.cos(a), 200 * depth * math.sin(a) }
    end
  end
  return build({ top = { left = left }, side = curl ~= 0 and side or nil, front = front,
                 name = o.name or shape, resolution = o.resolution, precision = o.precision,
                 capture = false }, who)
end

setmetatable(M, { __call = function (_, t) return build(t, "lsys.sketch.organ") end })
return M
