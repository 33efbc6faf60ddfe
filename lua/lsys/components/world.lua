--- The World component's fields and the deformations of the skeleton (Lintermann
-- and Deussen 1999, section "Tropisms" and section "Free-form deformations"): the checked
-- settings of a World (gravity, light, a cylinder to climb, a wall, wind), the guides that
-- steer stems onto the cylinder's helix and the wall's plane, the phototropism of a leaf's
-- frame, the maps of FFD and
-- Hyperpatch components, and their "skeleton" mode, which moves the frames of a subtree
-- (stems and instances) instead of the vertices of the scene.
-- @module lsys.components.world
local C = require "lsys.components.proto"
local core = require "lsys.core"

local type, pairs, ipairs, error, tostring, pcall, rawget, math, string =
      type, pairs, ipairs, error, tostring, pcall, rawget, math, string
local format = string.format
local sqrt, sin, cos, rad, acos, asin, atan, abs, huge = math.sqrt, math.sin, math.cos,
  math.rad, math.acos, math.asin, math.atan, math.abs, math.huge
local isnum, who = C.isnum, C.who
local _ENV = nil

local M = {}

local function cross (a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function unit (a)
  local l = sqrt(dot(a, a))
  if l < 1e-300 then return nil end
  return { a[1] / l, a[2] / l, a[3] / l }
end
-- v rotated by the angle a (radians) about the unit axis k (Rodrigues).
local function rotate (v, k, a)
  local c, s = cos(a), sin(a)
  local kv, kd = cross(k, v), dot(k, v) * (1 - c)
  return { v[1] * c + kv[1] * s + k[1] * kd, v[2] * c + kv[2] * s + k[2] * kd,
           v[3] * c + kv[3] * s + k[3] * kd }
end

-- {=========================================================================================
-- The settings of a World

local function wfail (inst, key, fmt, ...)
  error(format("lsys.components: %s (at %s): '%s' " .. fmt, who(inst.proto), inst.path, key,
               ...), 0)
end

local function isvec (v)
  return type(v) == "table" and isnum(v[1]) and isnum(v[2]) and isnum(v[3])
end

-- The fields of a table setting (cylinder, wall, wind) with their defaults, checked.
local FIELDS = {
  cylinder = { { "axis", "vec", { 0, 1, 0 } }, { "point", "vec", { 0, 0, 0 } },
               { "radius", "num", 0.3 }, { "pitch", "num", 30 }, { "strength", "num", 0.3 } },
  wall = { { "point", "vec", { 0, 0, 0 } }, { "normal", "vec", { 0, 0, 1 } },
           { "distance", "num", 0 }, { "strength", "num", 0.3 } },
  wind = { { "direction", "vec", { 1, 0, 0 } }, { "strength", "num", 0.1 } },
}
M.SETTINGS = { "gravity", "light", "cylinder", "wall", "wind" }

--- The World setting `key` of instance inst checked: gravity and light a vector or a
-- function of position; cylinder, wall and wind a table of fields (a copy with defaults
-- filled in, and what the tropisms use precomputed), or false (none, over a parent
-- World's).
function M.check (inst, key, v)
  if key == "gravity" or key == "light" then
    if type(v) == "function" then return v end
    if not isvec(v) or dot(v, v) == 0 then
      wfail(inst, key, "must be a non-zero vector {x, y, z} or a function (x, y, z) -> x, y, z")
    end
    return unit(v)
  end
  if v == false then return false end
  if type(v) ~= "table" then wfail(inst, key, "must be a table or false, got %s", type(v)) end
  local out = {}
  local known = {}
  for _, fd in ipairs(FIELDS[key]) do
    local name, t, def = fd[1], fd[2], fd[3]
    known[name] = true
    local x = v[name]
    if x == nil then x = def end
    if t == "vec" and not isvec(x) or t == "num" and not isnum(x) then
      wfail(inst, key .. "." .. name, "must be %s, got %s",
            t == "vec" and "a vector {x, y, z}" or "a finite number", tostring(x))
    end
    out[name] = x
  end
  for k in pairs(v) do
    if not known[k] then wfail(inst, key, "has no field '%s'", tostring(k)) end
  end
  if key == "cylinder" then
    out.a = unit(out.axis)
    if out.a == nil then wfail(inst, "cylinder.axis", "must not be zero") end
    if out.radius < 0 then wfail(inst, "cylinder.radius", "must be >= 0") end
  elseif key == "wall" then
    out.n = unit(out.normal)
    if out.n == nil then wfail(inst, "wall.normal", "must not be zero") end
  else
    local d = out.direction
    out.dir = unit { d[1], 0, d[3] }          -- horizontal: lsys is y-up
    if out.dir == nil then wfail(inst, "wind.direction", "has no horizontal part") end
  end
  if key ~= "wind" and out.strength < 0 then wfail(inst, key .. ".strength", "must be >= 0") end
  return out
end

-- The guides (a World's cylinder and wall) steer a stem's next frame onto a target: the
-- helix, the plane. Each segment the stem's heading H turns by cpfg's tropism, towards T
-- by the angle e |H x T| (radians; ABOP section 2.3); a guide picks the T that makes that
-- turn take H onto the direction D towards the target: by the whole angle b between H and
-- D when b <= e (T at asin(b / e) from H towards D, so e |H x T| = b), else by e (T normal
-- to H, towards D). So e is the most a guide turns a stem in a segment, and a stem that
-- can follow its target lands every frame on it.
local function steer (hx, hy, hz, dx, dy, dz, e)
  local c = hx * dx + hy * dy + hz * dz
  local wx, wy, wz = dx - c * hx, dy - c * hy, dz - c * hz
  local w = sqrt(wx * wx + wy * wy + wz * wz)
  if w < 1e-15 then return dx, dy, dz end     -- on course (or straight back: no turn)
  wx, wy, wz = wx / w, wy / w, wz / w
  local b = atan(w, c)
  if b >= e then return wx, wy, wz end
  local g = asin(b / e)
  local cg, sg = cos(g), sin(g)
  return cg * hx + sg * wx, cg * hy + sg * wy, cg * hz + sg * wz
end

--- The guide of a World's cylinder for a stem of segments `step` long (in the world):
-- a function (x, y, z, hx, hy, hz) -> T for the stem's tropism (see steer). Its target is
-- the helix of angle `pitch` (degrees against the plane normal to the axis) at `radius`
-- from the axis line through `point`: D climbs at the pitch (D = cos(pitch) u + sin(pitch)
-- a, a the axis) with u the horizontal direction (normal to the axis) that takes the frame
-- from its distance d to `radius` in one step of s cos(pitch): u = sqrt(1 - c^2) t + c r,
-- c = (radius^2 - d^2 - h^2) / (2 d h) clamped to [-1, 1], r the unit direction away from
-- the axis and t = a x r round it. On the helix (d = radius) u is the chord of the circle
-- to the next frame, so the stem's frames keep to the radius exactly, and its axis between
-- them sags inwards by at most radius (1 - cos(phi / 2)), phi the angle round the axis a
-- segment makes. Seen from the axis's tip the helix turns clockwise. Lintermann and Deussen
-- 1999, fig. 9b (a philodendron climbing a stick) and section "Tropisms"; the article gives
-- no formula, this is ours.
function M.cylinderguide (cyl, step, e)
  local a, o, R = cyl.a, cyl.point, cyl.radius
  local cp, sp = cos(rad(cyl.pitch)), sin(rad(cyl.pitch))
  local h = step * cp
  return function (x, y, z, hx, hy, hz)
    local d1, d2, d3 = x - o[1], y - o[2], z - o[3]
    local al = d1 * a[1] + d2 * a[2] + d3 * a[3]
    local r1, r2, r3 = d1 - al * a[1], d2 - al * a[2], d3 - al * a[3]
    local rho = sqrt(r1 * r1 + r2 * r2 + r3 * r3)
    local D1, D2, D3
    if rho < 1e-12 then
      D1, D2, D3 = a[1], a[2], a[3]           -- on the axis: up it, until off it
    else
      r1, r2, r3 = r1 / rho, r2 / rho, r3 / rho
      local t1, t2, t3 = a[2] * r3 - a[3] * r2, a[3] * r1 - a[1] * r3, a[1] * r2 - a[2] * r1
      local c = 0
      if h > 1e-12 then c = (R * R - rho * rho - h * h) / (2 * rho * h) end
      if c > 1 then c = 1 elseif c < -1 then c = -1 end
      local k = sqrt(1 - c * c)
      D1 = cp * (k * t1 + c * r1) + sp * a[1]
      D2 = cp * (k * t2 + c * r2) + sp * a[2]
      D3 = cp * (k * t3 + c * r3) + sp * a[3]
    end
    return steer(hx, hy, hz, D1, D2, D3, e)
  end
end

--- The guide of a World's wall for a stem of segments `step` long: its target is the plane
-- `distance` in front of the wall (the plane through `point` normal to `normal`, on the
-- normal's side). D keeps the heading's direction along the plane and takes the frame from
-- its offset q to the plane in one step: D = sqrt(1 - m^2) p + m n, m = -q / step clamped
-- to [-1, 1], p the unit part of H along the plane (the plane's direction nearest to +y
-- when H is normal to it). On the plane with a heading along it D is H: a stem the wall
-- guides bends only by its own curvature and tropisms, and the wall takes it back to the
-- plane. Lintermann and Deussen 1999, section "Tropisms" ("a plant can be forced to grow
-- along a wall"); the article gives no formula, this is ours.
function M.wallguide (wall, step, e)
  local n, o, dist = wall.n, wall.point, wall.distance
  return function (x, y, z, hx, hy, hz)
    local q = (x - o[1]) * n[1] + (y - o[2]) * n[2] + (z - o[3]) * n[3] - dist
    local hn = hx * n[1] + hy * n[2] + hz * n[3]
    local p1, p2, p3 = hx - hn * n[1], hy - hn * n[2], hz - hn * n[3]
    local pl = sqrt(p1 * p1 + p2 * p2 + p3 * p3)
    if pl < 1e-9 then
      local ref = abs(n[2]) < 0.999 and { 0, 1, 0 } or { 1, 0, 0 }
      local rn = dot(ref, n)
      p1, p2, p3 = ref[1] - rn * n[1], ref[2] - rn * n[2], ref[3] - rn * n[3]
      pl = sqrt(p1 * p1 + p2 * p2 + p3 * p3)
    end
    local m = -q / step
    if m > 1 then m = 1 elseif m < -1 then m = -1 end
    local k = sqrt(1 - m * m) / pl
    return steer(hx, hy, hz, k * p1 + m * n[1], k * p2 + m * n[2], k * p3 + m * n[3], e)
  end
end

--- A leaf's phototropism: the frame f turned, in place, by the fraction e of the rotation
-- that makes its up vector U face the light (Lintermann and Deussen 1999, section
-- "Tropisms": the leaf's frame is rotated towards lying perpendicular to the light).
function M.leafturn (f, light, e)
  local L = light
  if type(L) == "function" then L = { L(f.p[1], f.p[2], f.p[3]) } end
  L = isvec(L) and unit(L)
  if not L then return end
  local U = f.U
  local c = dot(U, L)
  if c > 1 then c = 1 elseif c < -1 then c = -1 end
  local ax = unit(cross(U, L))
  if ax == nil then
    if c > 0 then return end
    ax = f.H                                  -- facing away: turn over about the heading
  end
  local a = e * acos(c)
  f.H, f.U = rotate(f.H, ax, a), rotate(U, ax, a)
end

-- }=========================================================================================

-- {=========================================================================================
-- The maps of FFD and Hyperpatch components

local function right (f)
  local H, U = f.H, f.U
  return { -(H[2] * U[3] - H[3] * U[2]), -(H[3] * U[1] - H[1] * U[3]),
           -(H[1] * U[2] - H[2] * U[1]) }
end
local function front (f) return { -f.U[1], -f.U[2], -f.U[3] } end

--- World -> the local coordinates of frame f (x right, y along, z front, in units of s).
function M.tolocal (f, x, y, z)
  local R, F = right(f), front(f)
  local d = { x - f.p[1], y - f.p[2], z - f.p[3] }
  return dot(d, R) / f.s, dot(d, f.H) / f.s, dot(d, F) / f.s
end
local tolocal = M.tolocal

local function topoint (f, x, y, z)
  local R, F, s = right(f), front(f), f.s
  return { f.p[1] + s * (x * R[1] + y * f.H[1] + z * F[1]),
           f.p[2] + s * (x * R[2] + y * f.H[2] + z * F[2]),
           f.p[3] + s * (x * R[3] + y * f.H[3] + z * F[3]) }
end

local function dfail (inst, fmt, ...)
  error(format("lsys.components: %s (at %s): " .. fmt, who(inst.proto), inst.path, ...), 0)
end
M.dfail = dfail

-- The Hyperpatch of a deformer instance in world coordinates: its `box` ({origin =, size =}
-- in its local coordinates) or the box `bounds()` gives (lo, hi local corners, or nil).
local function hyperpatch (inst, bounds)
  local p, f = inst.proto, inst.frame
  local box = p:param("box")
  local o, sz
  if box ~= nil then
    if type(box) ~= "table" or type(box.origin) ~= "table" or type(box.size) ~= "table" then
      dfail(inst, "'box' must be { origin = {x, y, z}, size = {x, y, z} }")
    end
    o, sz = box.origin, box.size
  else
    local lo, hi = bounds()
    if lo == nil then return nil end
    o, sz = lo, {}
    for k = 1, 3 do
      sz[k] = hi[k] - lo[k]
      if sz[k] < 1e-9 then sz[k] = 1e-3 o[k] = o[k] - 5e-4 end
    end
  end
  local R, F = right(f), front(f)
  local s = f.s
  local function w (v, k) return { v[1] * k * s, v[2] * k * s, v[3] * k * s } end
  local origin = topoint(f, o[1], o[2], o[3])
  local deg = p:param("degree")
  if type(deg) == "number" then deg = { deg, deg, deg } end
  local ok, hp = pcall(core.hyperpatch, { degree = deg, origin = origin,
                                          axes = { w(R, sz[1]), w(f.H, sz[2]),
                                                   w(F, sz[3]) } })
  if not ok then dfail(inst, "%s", tostring(hp):gsub("^[^:]*: ", "")) end
  for k, mv in ipairs(p:param("moves")) do
    if type(mv) ~= "table" or #mv ~= 6 then
      dfail(inst, "'moves[%d]' must be {i, j, k, dx, dy, dz}", k)
    end
    local ok2, x, y, z = pcall(hp.point, hp, mv[1], mv[2], mv[3])
    if not ok2 then dfail(inst, "'moves[%d]': %s", k, tostring(x)) end
    local d = topoint({ p = { 0, 0, 0 }, H = f.H, U = f.U, s = s }, mv[4], mv[5], mv[6])
    hp:set(mv[1], mv[2], mv[3], x + d[1], y + d[2], z + d[3])
  end
  return hp
end

-- The FFD of a deformer instance by its functions fx, fy, fz of the local coordinates.
local function ffdfunction (inst)
  local p, f = inst.proto, inst.frame
  local fx, fy, fz = p:param("fx"), p:param("fy"), p:param("fz")
  for k, fn in pairs { fx = fx, fy = fy, fz = fz } do
    if fn ~= nil and type(fn) ~= "function" then
      dfail(inst, "'%s' must be a function (x, y, z) -> number", k)
    end
  end
  return function (x, y, z)
    local a, b, c = tolocal(f, x, y, z)
    local a2 = fx and fx(a, b, c) or a
    local b2 = fy and fy(a, b, c) or b
    local c2 = fz and fz(a, b, c) or c
    local q = topoint(f, a2, b2, c2)
    return q[1], q[2], q[3]
  end
end

--- The map of a deformer instance (FFD or Hyperpatch): a Hyperpatch, a function (x, y, z)
-- -> x', y', z', or nil (nothing to deform); bounds() as for the hyperpatch's box.
function M.map (inst, bounds)
  if inst.kind == "hyperpatch" then return hyperpatch(inst, bounds) end
  return ffdfunction(inst)
end

-- }=========================================================================================

-- {=========================================================================================
-- Skeleton mode: the frames of a deformer's subtree move, the geometry follows rigidly

-- The instances under deformer d (indices, preorder) less the subtrees of isolated
-- deformers below it.
local function subtree (list, d)
  local out = {}
  local function visit (i)
    local inst = list[i]
    if i ~= d.index and (inst.kind == "ffd" or inst.kind == "hyperpatch") and
       inst.proto:param("isolate") then
      return
    end
    if i ~= d.index then out[#out + 1] = inst end
    for _, c in ipairs(inst.children) do visit(c) end
  end
  visit(d.index)
  return out
end

-- The arena indices of the frames of these instances: their own and their stems' (each
-- once; a tip is made from the frame it is ahead of when it is read).
local function frames (insts)
  local out, seen = {}, {}
  local function put (i)
    if not seen[i] then seen[i] = true out[#out + 1] = i end
  end
  for _, inst in ipairs(insts) do
    put(inst.fi)
    local st = rawget(inst, "st")
    if st then for j = 0, inst.ns - 1 do put(st + j) end end
  end
  return out
end

-- Frame f moved by the map g: p -> g(p); H and U by the Jacobian (central differences of
-- step h), U made normal to H again; the scale kept, so what hangs on it moves rigidly.
local function moveframe (g, f, h)
  local x, y, z = f.p[1], f.p[2], f.p[3]
  local function J (v)
    local ax, ay, az = g(x + h * v[1], y + h * v[2], z + h * v[3])
    local bx, by, bz = g(x - h * v[1], y - h * v[2], z - h * v[3])
    return { ax - bx, ay - by, az - bz }
  end
  local H, U = unit(J(f.H)), J(f.U)
  local px, py, pz = g(x, y, z)
  f.p = { px, py, pz }
  if H == nil then return end
  local k = dot(U, H)
  U = unit { U[1] - k * H[1], U[2] - k * H[2], U[3] - k * H[3] }
  if U == nil then return end
  f.H, f.U = H, U
end

-- A stem after its frames moved: each frame's heading made the direction of the segment
-- that ends at it (the turtle moves along H), U turned with it by the least rotation.
local function restem (st)
  for k = 2, #st do
    local a, b = st[k - 1], st[k]
    local d = unit { b.p[1] - a.p[1], b.p[2] - a.p[2], b.p[3] - a.p[3] }
    if d then
      local ax = unit(cross(b.H, d))
      if ax then
        local c = dot(b.H, d)
        if c > 1 then c = 1 elseif c < -1 then c = -1 end
        b.U = rotate(b.U, ax, acos(c))
        local kk = dot(b.U, d)
        b.U = unit { b.U[1] - kk * d[1], b.U[2] - kk * d[2], b.U[3] - kk * d[3] } or b.U
      end
      b.H = d
    end
  end
end

--- Applies the FFD and Hyperpatch components of mode "skeleton" of the i-tree to the frames
-- of their subtrees, the deepest first (the outer ones then move the already deformed).
function M.skeleton (tree)
  local list = tree.list
  local ds = {}
  for _, inst in ipairs(list) do
    if (inst.kind == "ffd" or inst.kind == "hyperpatch") and
       inst.proto:param("mode") == "skeleton" then
      ds[#ds + 1] = inst
    end
  end
  for k = #ds, 1, -1 do
    local d = ds[k]
    local insts = subtree(list, d)
    local arena = tree.frames
    local fs = {}
    for k2, i in ipairs(frames(insts)) do fs[k2] = arena:get(i, true) end
    local df = d.frame
    local lo, hi = { huge, huge, huge }, { -huge, -huge, -huge }
    for _, f in ipairs(fs) do
      local q = { tolocal(df, f.p[1], f.p[2], f.p[3]) }
      for j = 1, 3 do
        if q[j] < lo[j] then lo[j] = q[j] end
        if q[j] > hi[j] then hi[j] = q[j] end
      end
    end
    local map = M.map(d, function () if lo[1] == huge then return nil end return lo, hi end)
    if map ~= nil and #fs > 0 then
      local g = map
      if type(map) ~= "function" then g = function (x, y, z) return map:map(x, y, z) end end
      local diag = 0
      for j = 1, 3 do diag = diag + (hi[j] - lo[j]) ^ 2 end
      local h = 1e-4 * (sqrt(diag) * df.s + 1e-3)
      for _, f in ipairs(fs) do
        local ok, msg = pcall(moveframe, g, f, h)
        if not ok then dfail(d, "its map failed: %s", tostring(msg)) end
        if not (isnum(f.p[1]) and isnum(f.p[2]) and isnum(f.p[3])) then
          dfail(d, "its map gave a point that is not three finite numbers")
        end
      end
      for k2, i in ipairs(frames(insts)) do arena:set(i, fs[k2]) end
      for _, inst in ipairs(insts) do
        local st = rawget(inst, "st")
        if st then
          local sf = inst.stem
          restem(sf)
          for j, f in ipairs(sf) do arena:set(st + j - 1, f) end
        end
      end
    end
  end
end

-- }=========================================================================================

return M
