--- A component graph as an ordinary lsys model: the p-graph is expanded
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
local W = require "lsys.components.world"
local lmodel = require "lsys.model"

local type, pairs, ipairs, error, tostring, pcall, math, string, table =
      type, pairs, ipairs, error, tostring, pcall, math, string, table
local format, concat = string.format, table.concat
local huge, sqrt = math.huge, math.sqrt
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

-- The 3 x 4 matrix (rows for scene:transform) of the affine map that takes the point
-- p + x B[1] + y B[2] + z B[3] to q + s1 x B2[1] + s2 y B2[2] + s3 z B2[3] (B, B2 orthonormal
-- bases: a frame's right, heading and front).
local function framemap (B, p, B2, q, s)
  local m = {}
  for i = 1, 3 do
    m[i] = {}
    for j = 1, 3 do
      m[i][j] = B2[1][i] * s[1] * B[1][j] + B2[2][i] * s[2] * B[2][j] +
                B2[3][i] * s[3] * B[3][j]
    end
    m[i][4] = q[i] - (m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] * p[3])
  end
  return m
end

--- The 3 x 4 matrix of a scale by (sx, sy, sz) along frame f's right, heading and front
-- axes, about its position (primitives of non-uniform size; lsys.components.mix too).
function M.scaling (f, sx, sy, sz)
  local B = { right(f), f.H, front(f) }
  return framemap(B, f.p, B, f.p, { sx, sy, sz })
end
local scaling = M.scaling

-- The isolated deformers (`isolate = true`) outermost in the subtree of `inst`: the
-- subtrees its deformation leaves out; `iso` is every isolated deformer sorted by m0.
local function isolated (inst, iso)
  local out, last = {}, -1
  for _, d in ipairs(iso) do
    if d.m0 > inst.m0 and d.m1 <= inst.m1 and d.m0 > last then
      out[#out + 1] = d
      last = d.m1
    end
  end
  return out
end

-- The module ranges of inst's subtree less the isolated subtrees (sorted, disjoint).
local function pieces (inst, holes)
  local out, at = {}, inst.m0
  for _, d in ipairs(holes) do
    if d.m0 > at then out[#out + 1] = { at, d.m0 - 1 } end
    at = d.m1 + 1
  end
  if at <= inst.m1 then out[#out + 1] = { at, inst.m1 } end
  return out
end

local function unit (a)
  local l = sqrt(dot(a, a))
  return { a[1] / l, a[2] / l, a[3] / l }
end

-- The rigid motion that carries frame f along the map (its position mapped, its axes turned
-- as the map turns the heading and up there): 3 x 4 rows for scene:transform. The article's
-- isolated subtree (the pine's needles) follows the deformed skeleton undeformed.
local function follow (map, f)
  local e = 1e-4 * (f.s > 0 and f.s or 1)
  local function mp (v, k)
    local x, y, z = map(f.p[1] + k * v[1], f.p[2] + k * v[2], f.p[3] + k * v[3])
    return { x, y, z }
  end
  local o = mp(f.H, 0)
  local h1, h0, u1, u0 = mp(f.H, e), mp(f.H, -e), mp(f.U, e), mp(f.U, -e)
  local H = unit { h1[1] - h0[1], h1[2] - h0[2], h1[3] - h0[3] }
  local U = { u1[1] - u0[1], u1[2] - u0[2], u1[3] - u0[3] }
  local k = dot(U, H)
  U = unit { U[1] - k * H[1], U[2] - k * H[2], U[3] - k * H[3] }
  local g = { p = o, H = H, U = U, s = 1 }
  return framemap({ right(f), f.H, front(f) }, f.p, { right(g), H, front(g) }, o, { 1, 1, 1 })
end

-- Does the deformer change anything? (An FFD without functions only isolates, and so does
-- a Hyperpatch without moves: its control points on the lattice map every point to itself.)
local function active (inst)
  local p = inst.proto
  if p:param("mode") ~= "all" then return false end
  if inst.kind == "hyperpatch" then return #p:param("moves") > 0 end
  return p:param("fx") ~= nil or p:param("fy") ~= nil or p:param("fz") ~= nil
end

-- Finishes the scene the turtle drew from the emitted string.
local function finish (out, scene)
  for _, t in ipairs(out.post) do
    local m = scaling(t.frame, t.sx, t.sy, t.sz)
    scene:transform(m, { modules = { t.m0, t.m1 } })
  end
  local ds, iso = out.deformers, {}
  for _, d in ipairs(ds) do if d.proto:param("isolate") then iso[#iso + 1] = d end end
  table.sort(iso, function (a, b) return a.m0 < b.m0 end)
  for _, inst in ipairs(ds) do                 -- the emitter lists them deepest first
    if active(inst) then
      local holes = isolated(inst, iso)
      local ranges = pieces(inst, holes)
      local map = W.map(inst, function ()
        -- the frame and its axes once: this runs for every vertex of the subtree
        local f = inst.frame
        local R, F, H, P, s = right(f), front(f), f.H, f.p, f.s
        local x0, x1, y0, y1, z0, z1 = huge, -huge, huge, -huge, huge, -huge
        for _, r in ipairs(ranges) do
          local v0, v1 = scene:module_range(r[1], r[2])
          for i = v0 or 1, v0 and v1 or 0 do
            local x, y, z = scene:vertex(i)
            x, y, z = x - P[1], y - P[2], z - P[3]
            local a = (x * R[1] + y * R[2] + z * R[3]) / s
            local b = (x * H[1] + y * H[2] + z * H[3]) / s
            local c = (x * F[1] + y * F[2] + z * F[3]) / s
            if a < x0 then x0 = a end
            if a > x1 then x1 = a end
            if b < y0 then y0 = b end
            if b > y1 then y1 = b end
            if c < z0 then z0 = c end
            if c > z1 then z1 = c end
          end
        end
        if x0 == huge then return nil end
        return { x0, y0, z0 }, { x1, y1, z1 }
      end)
      if map ~= nil then
        local fn = map
        if type(map) ~= "function" then fn = function (x, y, z) return map:map(x, y, z) end end
        for _, r in ipairs(ranges) do
          local ok, msg = pcall(scene.deform, scene, map, { modules = r })
          if not ok then W.dfail(inst, "%s", tostring(msg)) end
        end
        for _, d in ipairs(holes) do
          local ok, m = pcall(follow, fn, d.frame)
          if not ok then W.dfail(inst, "%s", tostring(m)) end
          scene:transform(m, { modules = { d.m0, d.m1 } })
        end
      end
    end
  end
end

local OPTS = { seed = true, max_instances = true, view = true, name = true, detail = true,
               tree = true }

--- The component graph at `root` as an lsys model. opts: `seed`, `max_instances` (as
-- expand), `view` (fields over the component view: a cylinder line style, 12-sided
-- tubes), `name`, `detail` (how finely leaves are drawn: n, 2 x 2 patches of n x (n + 1)
-- quads, 16 triangles a leaf at 1; nil, the default: each leaf's by its size in the
-- plant and its bend, lsys.components.emit), `tree` (the i-tree of `root` made before,
-- by lsys.components.expand with the same seed and max_instances: used instead of
-- expanding again, when only parameters of proto.DRAWN changed since; it must be
-- root's). The model derives the plant's Lstring in
-- 0 steps; `m.components` holds
-- { tree = the i-tree, owner = module index -> instance index, instance(i) = the
-- instance that drew module i, and the options it was made with: view, detail, seed,
-- max_instances }.
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
  local tree = opts.tree
  if tree ~= nil then
    if type(tree) ~= "table" or tree.root ~= root or type(tree.list) ~= "table" then
      error("lsys.components.model: 'tree' must be an i-tree of this root " ..
            "(lsys.components.expand)", 2)
    end
  else
    tree = X.expand(root, { seed = opts.seed, max_instances = opts.max_instances })
  end
  local out
  local m = lmodel.lsystem {
    axiom = "", steps = 0, name = opts.name or root.name or "components",
    view = baseview(opts.view),
    finish = function () return out.lstring:copy() end,
    after_interpret = function (_, scene, s)
      if #s == #out.lstring then finish(out, scene) end
    end,
  }
  out = E.emit(tree, m._rules, detail, nil, #(m.view.textures or {}))
  local v = m.view
  v.surfaces = v.surfaces or {}
  for c, entry in pairs(out.surfaces) do v.surfaces[c] = entry end
  m.components = {
    tree = tree, owner = out.owner, lstring = out.lstring, view = opts.view,
    detail = detail, seed = opts.seed, max_instances = opts.max_instances,
    instance = function (i) return tree.list[out.owner[i]] end,
  }
  return m
end

return M
