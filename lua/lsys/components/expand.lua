--- The expansion of a p-graph into the i-tree (issue 16; Lintermann and Deussen 1999,
-- sections "Modeling with components" and "A geometry generation example"): every link
-- followed from the root makes an instance of its target; multipliers (Hydra, Wreath,
-- Phiball, and Tree on its branch links) make one instance per iteration; a prototype on a
-- cycle is expanded until it is on the path `recursion` times; a leaf link makes its target
-- once, where the recursion of its source ends. Each instance gets its world frame and its
-- parameters evaluated for its iteration number (ranges, functions, the seeded generator).
-- @module lsys.components.expand
local C = require "lsys.components.proto"

local type, pairs, ipairs, error, setmetatable, tostring, pcall, require, math, string, table =
      type, pairs, ipairs, error, setmetatable, tostring, pcall, require, math, string, table
local format, concat = string.format, table.concat
local sqrt, sin, cos, rad, floor = math.sqrt, math.sin, math.cos, math.rad, math.floor
local isnum, who = C.isnum, C.who
local _ENV = nil

local M = {}
M.MAX_INSTANCES = 2000000

-- {=========================================================================================
-- Vectors and frames. A frame is { p = position, H = heading (the direction the component
-- grows), U = up, s = uniform scale }; left L = H x U as the turtle's. A point (x, y, z) of
-- the component's own coordinates is at p + s (x R + y H + z F) with R = -L (right) and
-- F = -U (front): at the turtle's first frame (H = +y, U = -z) they are the world's axes.

local function cross (a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function add (a, b, k)
  k = k or 1
  return { a[1] + k * b[1], a[2] + k * b[2], a[3] + k * b[3] }
end
local function scale (a, k) return { a[1] * k, a[2] * k, a[3] * k } end
local function norm (a)
  local l = sqrt(dot(a, a))
  if l < 1e-300 then return nil end
  return { a[1] / l, a[2] / l, a[3] / l }
end
M.cross, M.dot, M.norm = cross, dot, norm

-- v rotated by `deg` degrees about the unit axis k (Rodrigues).
local function rotate (v, k, deg)
  local a = rad(deg)
  local c, s = cos(a), sin(a)
  local kv = cross(k, v)
  local kd = dot(k, v) * (1 - c)
  return { v[1] * c + kv[1] * s + k[1] * kd, v[2] * c + kv[2] * s + k[2] * kd,
           v[3] * c + kv[3] * s + k[3] * kd }
end
M.rotate = rotate

local function right (f) return scale(cross(f.H, f.U), -1) end     -- R = -L
local function front (f) return scale(f.U, -1) end                 -- F = -U
M.right, M.front = right, front

local function copyframe (f)
  return { p = { f.p[1], f.p[2], f.p[3] }, H = { f.H[1], f.H[2], f.H[3] },
           U = { f.U[1], f.U[2], f.U[3] }, s = f.s }
end

--- The world position of the local point (x, y, z) of frame f.
function M.topoint (f, x, y, z)
  local R, F = right(f), front(f)
  return { f.p[1] + f.s * (x * R[1] + y * f.H[1] + z * F[1]),
           f.p[2] + f.s * (x * R[2] + y * f.H[2] + z * F[2]),
           f.p[3] + f.s * (x * R[3] + y * f.H[3] + z * F[3]) }
end

-- The frame turned by the basic parameters: translate (local), rotate (degrees about the
-- local x, then y, then z axes), scale.
local function transform (f, t, r, s)
  local g = copyframe(f)
  g.p = M.topoint(f, t[1], t[2], t[3])
  if r[1] ~= 0 then local ax = right(g) g.H, g.U = rotate(g.H, ax, r[1]), rotate(g.U, ax, r[1]) end
  if r[2] ~= 0 then g.U = rotate(g.U, g.H, r[2]) end
  if r[3] ~= 0 then local az = front(g) g.H = rotate(g.H, az, r[3]) end
  g.s = g.s * s
  return g
end
M.transform = transform

-- }=========================================================================================

-- {=========================================================================================
-- The seeded generator: splitmix64 on Lua's 64-bit integers, the same on every machine.

local function generator (seed)
  local state = floor(seed or 1)
  return function ()
    state = state + 0x9E3779B97F4A7C15
    local z = state
    z = (z ~ (z >> 30)) * 0xBF58476D1CE4E5B9
    z = (z ~ (z >> 27)) * 0x94D049BB133111EB
    z = z ~ (z >> 31)
    return (z >> 11) * (1.0 / 9007199254740992.0)
  end
end
M.generator = generator

-- }=========================================================================================

-- {=========================================================================================
-- Parameters of an instance: ranges over the iteration number, then the user's function

local function efail (inst, key, fmt, ...)
  error(format("lsys.components: %s (at %s): '%s': " .. fmt, who(inst.proto), inst.path, key,
               ...), 0)
end

-- The value of parameter `key` of prototype p for iteration ctx.i of ctx.n.
local function value (inst, p, key, ctx)
  local v = p:param(key)
  local sch = C.schema(p.kind, key)
  local t = sch[1]
  if t ~= "number" and t ~= "vec3" then return v end
  local out
  if type(v) == "function" then
    local ok, r = pcall(v, ctx)
    if not ok then efail(inst, key, "its function failed: %s", tostring(r)) end
    out = r
  elseif type(v) == "table" and (t == "number" and #v == 2 or t == "vec3" and #v == 2) then
    local n, i = ctx.n or 1, ctx.i or 1
    local u = n > 1 and (i - 1) / (n - 1) or 0
    if t == "number" then out = v[1] + u * (v[2] - v[1])
    else
      out = { v[1][1] + u * (v[2][1] - v[1][1]), v[1][2] + u * (v[2][2] - v[1][2]),
              v[1][3] + u * (v[2][3] - v[1][3]) }
    end
    if v.f ~= nil then
      ctx.v = out
      local ok, r = pcall(v.f, out, ctx)
      ctx.v = nil
      if not ok then efail(inst, key, "its function failed: %s", tostring(r)) end
      out = r
    end
  else
    return v
  end
  if t == "number" and not isnum(out) then
    efail(inst, key, "gave %s, not a finite number", tostring(out))
  elseif t == "vec3" and (type(out) ~= "table" or not (isnum(out[1]) and isnum(out[2]) and
                                                      isnum(out[3]))) then
    efail(inst, key, "gave %s, not a vector of three finite numbers", tostring(out))
  end
  return out
end
M.value = value

-- }=========================================================================================

-- {=========================================================================================
-- The i-tree

local Tree = {}
Tree.__index = Tree
M.Tree = Tree

--- The instances in depth-first order (each { index, proto, kind, name, path, parent
-- (index or nil), children (indices), i, n, depth, link, frame, params, ... }).
function Tree:instances () return self.list end

--- How many instances have the name or kind `what` (nil: all).
function Tree:count (what)
  if what == nil then return #self.list end
  local n = 0
  for _, inst in ipairs(self.list) do
    if inst.name == what or inst.kind == what then n = n + 1 end
  end
  return n
end

--- The instance at `path` ("tree#1/leaf#3"), or nil.
function Tree:find (path)
  return self.bypath[path]
end

function Tree:__tostring ()
  return format("lsys.components.Tree(%d instances)", #self.list)
end

-- The flags of a link allow iteration i (of n)?
local function allowed (inst, l, i, n)
  local f = l.flags
  if f == nil then return true end
  for _, x in ipairs(f.list) do
    if x > n then
      error(format("lsys.components: %s (at %s): the flags of its %s link to %s name " ..
                   "iteration %d, but it makes %d", who(inst.proto), inst.path, l.type,
                   who(l.to), x, n), 0)
    end
  end
  if f.mode == "only" then return f.set[i] == true end
  return f.set[i] ~= true
end

-- The stem of a Horn or Tree: frames at the ends of `segments` equal pieces, bent by the
-- curvature, the gnarl (random), the tropisms of the world and, for a Tree, deviated at its
-- branches. Returns the list of frames (1 = the base) with radius r and the arc length u.
local function stem (ex, inst, f, len, segs, branches)
  local p = inst.proto
  local ctx = inst.ctx
  local curv = value(inst, p, "curvature", ctx)
  local gnarl = p.kind == "tree" and value(inst, p, "gnarl", ctx) or 0
  local grav = p.kind == "tree" and value(inst, p, "gravitropism", ctx) or 0
  local photo = p.kind == "tree" and value(inst, p, "phototropism", ctx) or 0
  local dev = p.kind == "tree" and value(inst, p, "deviation", ctx) or 0
  local twist = p.kind == "horn" and value(inst, p, "twist", ctx) or 0
  local w = inst.world
  local tropisms = { { w.gravity, grav }, { w.light, photo } }
  local out = { copyframe(f) }
  out[1].u = 0
  local g = copyframe(f)
  local step = len / segs
  local nextb = 1
  for k = 1, segs do
    if curv ~= 0 then
      local ax = right(g)
      g.H, g.U = rotate(g.H, ax, curv / segs), rotate(g.U, ax, curv / segs)
    end
    if twist ~= 0 then g.U = rotate(g.U, g.H, twist / segs) end
    if gnarl ~= 0 then
      local a = (ex.random() * 2 - 1) * gnarl
      local ax = rotate(right(g), g.H, ex.random() * 360)
      g.H, g.U = rotate(g.H, ax, a), rotate(g.U, ax, a)
    end
    for _, tr in ipairs(tropisms) do
      local T, e = tr[1], tr[2]
      if e ~= 0 then
        if type(T) == "function" then T = { T(g.p[1], g.p[2], g.p[3]) } end
        -- cpfg's tropism (ABOP §2.3): H turns towards T by e |H x T|
        local ax = cross(g.H, T)
        local m = sqrt(dot(ax, ax))
        if m > 1e-12 then
          ax = scale(ax, 1 / m)
          local a = math.deg(e * m)
          g.H, g.U = rotate(g.H, ax, a), rotate(g.U, ax, a)
        end
      end
    end
    -- deviation: the stem turns away from each branch it passes
    while branches and branches[nextb] and branches[nextb].u <= k / segs do
      if dev ~= 0 then
        local b = branches[nextb]
        local ax = norm(cross(g.H, b.dir))
        if ax then g.H, g.U = rotate(g.H, ax, -dev), rotate(g.U, ax, -dev) end
      end
      nextb = nextb + 1
    end
    g.p = add(g.p, g.H, step * g.s)
    local h = copyframe(g)
    h.u = k / segs
    out[#out + 1] = h
  end
  return out
end

-- The frame of the stem at arc-length fraction u (between its frames).
local function stemframe (st, u)
  local n = #st - 1
  local x = u * n
  local k = floor(x)
  if k >= n then k = n - 1 end
  if k < 0 then k = 0 end
  local a, b, t = st[k + 1], st[k + 2], x - k
  local f = copyframe(a)
  f.p = add(a.p, add(b.p, a.p, -1), t)
  return f
end

-- The branches of a Tree: where along the stem, their frames before the stem bends.
local function branchplan (inst, nb)
  local p, ctx = inst.proto, inst.ctx
  local first, last = value(inst, p, "first", ctx), value(inst, p, "last", ctx)
  local dens = value(inst, p, "density", ctx)
  local div = value(inst, p, "divergence", ctx)
  local out = {}
  for b = 1, nb do
    local t = nb > 1 and (b - 1) / (nb - 1) or 0
    if dens ~= 1 then t = t ^ dens end
    local bctx = { i = b, n = nb, depth = ctx.depth, random = ctx.random, u = nil }
    local u = first + (last - first) * t
    bctx.u = u
    out[b] = { u = u, roll = div * (b - 1), ctx = bctx,
               angle = value(inst, p, "angle", bctx),
               scale = value(inst, p, "branch_scale", bctx) }
  end
  return out
end

local Expander = {}
Expander.__index = Expander

function Expander:add (proto, frame, ctx, parent, ltype)
  local list = self.list
  if #list >= self.max then
    error(format("lsys.components: the graph makes more than %d instances (at %s/%s); " ..
                 "raise max_instances or lower a count", self.max,
                 parent and parent.path or "", proto.name or proto.kind), 0)
  end
  local on = self.onpath
  local depth = (on[proto] or 0) + 1
  local label = proto.name or proto.kind
  self.seq[label] = (self.seq[label] or 0) + 1
  local inst = { index = #list + 1, proto = proto, kind = proto.kind, name = proto.name,
                 parent = parent and parent.index, children = {}, link = ltype,
                 i = ctx.i or 1, n = ctx.n or 1, depth = depth,
                 path = (parent and parent.path .. "/" or "") .. label .. "#" ..
                        self.seq[label] }
  inst.ctx = { i = inst.i, n = inst.n, depth = depth, random = self.random }
  inst.u = ctx.u                     -- a tree's branch: where along the parent's stem
  inst.world = parent and parent.world or self.world
  list[#list + 1] = inst
  self.bypath[inst.path] = inst
  if parent then parent.children[#parent.children + 1] = inst.index end
  on[proto] = depth
  self:build(inst, frame)
  on[proto] = depth > 1 and depth - 1 or nil
  return inst
end

-- Whether prototype p has branch links (a Tree without them makes no branch plan).
local function hasbranches (p)
  for _, l in ipairs(p.links) do if l.type == "branch" then return true end end
  return false
end

-- The instance's own frame, its geometry's skeleton, and its children.
function Expander:build (inst, frame)
  local p, ctx = inst.proto, inst.ctx
  local params = {}
  for _, k in ipairs { "translate", "rotate", "scale", "size" } do
    params[k] = value(inst, p, k, ctx)
  end
  inst.params = params
  local f = transform(frame, params.translate, params.rotate, params.scale)
  inst.frame = f
  local kind = p.kind
  if kind == "world" then
    local w = {}
    for k, v in pairs(inst.world) do w[k] = v end
    for _, k in ipairs { "gravity", "light", "cylinder", "wind" } do
      if p.params[k] ~= nil then w[k] = p.params[k] end
    end
    inst.world = w
  end
  local tip = f
  local branches
  if kind == "horn" or kind == "tree" then
    local len = value(inst, p, "length", ctx)
    local segs = p:param("segments")
    if segs < 1 or segs > 100000 then
      efail(inst, "segments", "must be from 1 to 100000, got %s", tostring(segs))
    end
    local nb = kind == "tree" and p:param("n") or 0
    local plan
    if nb > 0 and hasbranches(p) then
      plan = branchplan(inst, nb)
      for _, b in ipairs(plan) do
        b.dir = rotate(right(f), f.H, b.roll)     -- roughly where it will point
      end
    end
    inst.stem = stem(self, inst, f, len, segs, plan)
    inst.length = len
    tip = inst.stem[#inst.stem]
    branches = plan
  elseif kind == "leaf" then
    local len = value(inst, p, "length", ctx)
    tip = copyframe(f)
    tip.p = add(f.p, f.H, len * f.s)
  elseif kind == "revo" then
    local prof = p:param("profile")
    tip = copyframe(f)
    tip.p = add(f.p, f.H, (prof[#prof][2] - prof[1][2]) * params.size[2] * f.s)
  elseif p.params.primitive ~= nil or kind == "simple" then
    local prim = p:param("primitive")
    if prim ~= "none" then
      tip = copyframe(f)
      tip.p = add(f.p, f.H, params.size[2] * f.s)
    end
  end
  inst.tip = tip
  local ends = not self:recurses(inst)
  for _, l in ipairs(p.links) do
    self:follow(inst, l, tip, branches, ends)
  end
end

-- Whether the recursion of inst's prototype goes on below it: one of its links leads back
-- to a prototype on the path that may still appear again.
function Expander:recurses (inst)
  local p = inst.proto
  if not p.recursive then return false end
  return (self.onpath[p] or 0) < p.recursion
end

function Expander:follow (inst, l, tip, branches, ends)
  local target = l.to
  local on = self.onpath[target]
  if on ~= nil and on >= target.recursion then return end    -- the recursion ends here
  if l.type == "leaf" and not ends then return end             -- only where it ends
  local kind = inst.kind
  if C.MULTIPLIERS[kind] and l.type ~= "leaf" then
    self:multiply(inst, l)
  elseif kind == "tree" and l.type == "branch" then
    local nb = #(branches or {})
    for b, br in ipairs(branches or {}) do
      if allowed(inst, l, b, nb) then
        local f = stemframe(inst.stem, br.u)
        f.U = rotate(f.U, f.H, br.roll)
        local ax = right(f)
        f.H, f.U = rotate(f.H, ax, -br.angle), rotate(f.U, ax, -br.angle)
        f.s = f.s * br.scale
        self:add(target, f, br.ctx, inst, "branch")
      end
    end
  else
    self:add(target, tip, { i = inst.i, n = inst.n }, inst, l.type)
  end
end

-- The children of a Hydra, Wreath or Phiball on link l.
function Expander:multiply (inst, l)
  local place = require "lsys.components.place"
  local p, ctx = inst.proto, inst.ctx
  local n = p:param("n")
  local f = inst.frame
  local spec = { n = n }
  for _, k in ipairs { "radius", "open", "close" } do
    if p:param(k) ~= nil then spec[k] = value(inst, p, k, ctx) end
  end
  local sizes
  if inst.kind == "hydra" then spec.angle = value(inst, p, "angle", ctx)
  elseif inst.kind == "phiball" then
    sizes = {}
    for i = 1, n do
      sizes[i] = value(inst, p, "child_size", { i = i, n = n, depth = ctx.depth,
                                               random = ctx.random })
    end
    -- the children's areas size the sphere; `influence` blends their spacing from equal
    -- (0) to by area (1)
    spec.sizes, spec.influence = {}, value(inst, p, "influence", ctx)
    for i = 1, n do spec.sizes[i] = sizes[i] * sizes[i] end
  end
  if n == 0 then return end
  local ok, kids = pcall(place[inst.kind], spec)
  if not ok then
    error(format("lsys.components: %s (at %s): %s", who(p), inst.path,
                 tostring(kids):gsub("^[^:]*: ", "")), 0)
  end
  -- local axes: X = the multiplier's up, Y = its left, Z = its heading (place.lua)
  local X, Y, Z = f.U, cross(f.H, f.U), f.H
  local function world (v) return add(add(scale(X, v[1]), Y, v[2]), Z, v[3]) end
  for i, k in ipairs(kids) do
    if allowed(inst, l, i, n) then
      local g = { p = add(f.p, world(k.pos), f.s), H = world(k.H), U = world(k.U),
                  s = f.s * (sizes and sizes[i] or 1) }
      self:add(l.to, g, { i = i, n = n }, inst, l.type)
    end
  end
end

-- Cycles: every prototype a link leads back to (a back edge of the depth-first search from
-- the root) must have a recursion depth.
local function checkcycles (root)
  local state = {}
  local function visit (p, trail)
    state[p] = "open"
    trail[#trail + 1] = p.name or p.kind
    for _, l in ipairs(p.links) do
      local q = l.to
      if state[q] == "open" and not q.recursive then
        error(format("lsys.components: %s: a cycle (%s -> %s) but %s has no recursion " ..
                     "depth (give it recursion = n)", who(q), concat(trail, " -> "),
                     q.name or q.kind, who(q)), 0)
      elseif state[q] == nil then
        visit(q, trail)
      end
    end
    trail[#trail] = nil
    state[p] = "done"
  end
  visit(root, {})
end

--- Expands the p-graph at `root` (a prototype) into an i-tree. opts: `seed` (1),
-- `max_instances` (M.MAX_INSTANCES), `frame` (the root's frame: { p, H, U, s }; default the
-- turtle's first frame at the origin).
function M.expand (root, opts)
  if not C.isproto(root) then
    error(format("lsys.components.expand: a component prototype expected, got %s",
                 type(root)), 2)
  end
  opts = opts or {}
  for k in pairs(opts) do
    if k ~= "seed" and k ~= "max_instances" and k ~= "frame" then
      error(format("lsys.components.expand: unknown option '%s' (known: seed, " ..
                   "max_instances, frame)", tostring(k)), 2)
    end
  end
  local max = opts.max_instances or M.MAX_INSTANCES
  if not isnum(max) or max < 1 then
    error("lsys.components.expand: max_instances must be a positive number", 2)
  end
  checkcycles(root)
  local ex = setmetatable({
    list = {}, bypath = {}, onpath = {}, seq = {}, max = max,
    random = generator(opts.seed or 1),
    world = { gravity = { 0, -1, 0 }, light = { 0, 1, 0 } },
  }, Expander)
  local f = opts.frame or { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, -1 }, s = 1 }
  ex:add(root, copyframe(f), { i = 1, n = 1 }, nil, "root")
  return setmetatable({ list = ex.list, bypath = ex.bypath, root = root }, Tree)
end

return M
