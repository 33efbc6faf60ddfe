--- A component graph as an ordinary lsys model (issue 16): the p-graph is expanded
-- (lsys.components.expand), its i-tree emitted as turtle modules (lsys.components.emit),
-- and the model's derivation gives that Lstring, so `lsys view`, `lsys render`, export,
-- picking and the arrangement take the plant like any L-system. After the turtle has drawn
-- it, the scene is finished in place: primitives whose size is not uniform are scaled, and
-- the FFD and Hyperpatch components deform what their subtrees drew (Lintermann and Deussen
-- 1999, section "Free-form deformations").
-- @module lsys.components.model
local C = require "lsys.components.proto"
local X = require "lsys.components.expand"
local E = require "lsys.components.emit"
local lmodel = require "lsys.model"
local core = require "lsys.core"

local type, pairs, ipairs, error, tostring, pcall, math, string, table =
      type, pairs, ipairs, error, tostring, pcall, math, string, table
local format, concat = string.format, table.concat
local huge = math.huge
local right, front, dot = X.right, X.front, X.dot
local _ENV = nil

local M = {}

-- The view of a component plant: cylinders for `F`, rounder tubes, the Area contour.
local function baseview (user)
  local v = { line_style = "cylinder", contour_sides = 12 }
  for k, x in pairs(user or {}) do v[k] = x end
  v.contours = {}
  for k, x in pairs(user and user.contours or {}) do v.contours[k] = x end
  if v.contours[E.AREA] == nil then
    v.contours[E.AREA] = { points = { { -1, 0 }, { -1, 0 }, { -0.33, 0 }, { 0.33, 0 },
                                      { 1, 0 }, { 1, 0 } }, closed = false }
  end
  return v
end

-- The 3 x 4 matrix of a scale by (sx, sy, sz) along a frame's right, heading and front
-- axes, about its position.
local function scaling (f, sx, sy, sz)
  local B = { right(f), f.H, front(f) }
  local s = { sx, sy, sz }
  local m = {}
  for i = 1, 3 do
    m[i] = {}
    for j = 1, 3 do
      local x = 0
      for k = 1, 3 do x = x + B[k][i] * s[k] * B[k][j] end
      m[i][j] = x
    end
    m[i][4] = f.p[i] - (m[i][1] * f.p[1] + m[i][2] * f.p[2] + m[i][3] * f.p[3])
  end
  return m
end

-- The module ranges of a deformer's subtree, less those of deformers below it that
-- switch off the deformations above them (`isolate`).
local function pieces (inst, deformers)
  local out = { { inst.modules[1], inst.modules[2] } }
  for _, d in ipairs(deformers) do
    if d ~= inst and d.proto:param("isolate") and d.modules[1] > inst.modules[1] and
       d.modules[2] <= inst.modules[2] then
      local nxt = {}
      for _, r in ipairs(out) do
        if d.modules[2] < r[1] or d.modules[1] > r[2] then nxt[#nxt + 1] = r
        else
          if d.modules[1] > r[1] then nxt[#nxt + 1] = { r[1], d.modules[1] - 1 } end
          if d.modules[2] < r[2] then nxt[#nxt + 1] = { d.modules[2] + 1, r[2] } end
        end
      end
      out = nxt
    end
  end
  return out
end

-- World <-> the local coordinates of frame f (x right, y along, z front, in units of s).
local function tolocal (f, x, y, z)
  local R, F = right(f), front(f)
  local d = { x - f.p[1], y - f.p[2], z - f.p[3] }
  return dot(d, R) / f.s, dot(d, f.H) / f.s, dot(d, F) / f.s
end

local function dfail (inst, fmt, ...)
  error(format("lsys.components: %s (at %s): " .. fmt, C.who(inst.proto), inst.path, ...), 0)
end

-- The Hyperpatch of a deformer instance, in world coordinates: its `box` ({origin =,
-- size =} in its local coordinates) or the box around what its subtree drew.
local function hyperpatch (inst, scene, ranges)
  local p, f = inst.proto, inst.frame
  local box = p:param("box")
  local o, sz
  if box ~= nil then
    if type(box) ~= "table" or type(box.origin) ~= "table" or type(box.size) ~= "table" then
      dfail(inst, "'box' must be { origin = {x, y, z}, size = {x, y, z} }")
    end
    o, sz = box.origin, box.size
  else
    local lo, hi = { huge, huge, huge }, { -huge, -huge, -huge }
    for _, r in ipairs(ranges) do
      local v0, v1 = scene:module_range(r[1], r[2])
      for i = v0 or 1, v0 and v1 or 0 do
        local q = { tolocal(f, scene:vertex(i)) }
        for k = 1, 3 do
          if q[k] < lo[k] then lo[k] = q[k] end
          if q[k] > hi[k] then hi[k] = q[k] end
        end
      end
    end
    if lo[1] == huge then return nil end
    o, sz = lo, {}
    for k = 1, 3 do
      sz[k] = hi[k] - lo[k]
      if sz[k] < 1e-9 then sz[k] = 1e-3 o[k] = o[k] - 5e-4 end
    end
  end
  local R, F = right(f), front(f)
  local s = f.s
  local function w (v, k) return { v[1] * k * s, v[2] * k * s, v[3] * k * s } end
  local origin = X.topoint(f, o[1], o[2], o[3])
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
    local d = X.topoint({ p = { 0, 0, 0 }, H = f.H, U = f.U, s = s }, mv[4], mv[5], mv[6])
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
    local q = X.topoint(f, a2, b2, c2)
    return q[1], q[2], q[3]
  end
end

-- Finishes the scene the turtle drew from the emitted string.
local function finish (out, scene)
  for _, t in ipairs(out.post) do
    local m = scaling(t.frame, t.sx, t.sy, t.sz)
    scene:transform(m, { modules = { t.m0, t.m1 } })
  end
  local ds = out.deformers
  for k = #ds, 1, -1 do                        -- the deepest first
    local inst = ds[k]
    if inst.proto:param("mode") == "all" then
      local ranges = pieces(inst, ds)
      local map = inst.kind == "hyperpatch" and hyperpatch(inst, scene, ranges) or
                  ffdfunction(inst)
      if map ~= nil then
        for _, r in ipairs(ranges) do
          local ok, msg = pcall(scene.deform, scene, map, { modules = r })
          if not ok then dfail(inst, "%s", tostring(msg)) end
        end
      end
    end
  end
end

local OPTS = { seed = true, max_instances = true, view = true, name = true, detail = true }

--- The component graph at `root` as an lsys model. opts: `seed`, `max_instances` (as
-- expand), `view` (fields over the component view: a cylinder line style, 12-sided
-- tubes), `name`, `detail` (how finely leaves are drawn: 1, the default, 16 triangles a
-- leaf; n: 2 x 2 patches of n x (n + 1) quads). The model derives the plant's Lstring in
-- 0 steps; `m.components` holds
-- { tree = the i-tree, owner = module index -> instance index, instance(i) = the
-- instance that drew module i }.
function M.model (root, opts)
  if not C.isproto(root) then
    error(format("lsys.components.model: a component prototype expected, got %s",
                 type(root)), 2)
  end
  opts = opts or {}
  for k in pairs(opts) do
    if not OPTS[k] then
      local known = {}
      for n in pairs(OPTS) do known[#known + 1] = n end
      table.sort(known)
      error(format("lsys.components.model: unknown option '%s' (known: %s)", tostring(k),
                   concat(known, ", ")), 2)
    end
  end
  local detail = opts.detail
  if detail ~= nil and (not C.isnum(detail) or detail ~= math.floor(detail) or detail < 1 or
                        detail > 16) then
    error(format("lsys.components.model: 'detail' must be a whole number from 1 to 16, got %s",
                 tostring(detail)), 2)
  end
  local tree = X.expand(root, { seed = opts.seed, max_instances = opts.max_instances })
  local out
  local m = lmodel.lsystem {
    axiom = "", steps = 0, name = opts.name or root.name or "components",
    view = baseview(opts.view),
    finish = function () return out.lstring:copy() end,
    after_interpret = function (_, scene, s)
      if #s == #out.lstring then finish(out, scene) end
    end,
  }
  out = E.emit(tree, m._rules, detail)
  local v = m.view
  v.surfaces = v.surfaces or {}
  for c, entry in pairs(out.surfaces) do v.surfaces[c] = entry end
  m.components = {
    tree = tree, owner = out.owner, lstring = out.lstring,
    instance = function (i) return tree.list[out.owner[i]] end,
  }
  return m
end

return M
