--- The expansion of a p-graph into the i-tree (Lintermann and Deussen 1999,
-- sections "Modeling with components" and "A geometry generation example"): every link
-- followed from the root makes an instance of its target; multipliers (Hydra, Wreath,
-- Phiball, and Tree on its branch links) make one instance per iteration; a prototype on a
-- cycle is expanded until it is on the path `recursion` times; a leaf link makes its target
-- once, where the recursion of its source ends. Each instance gets its world frame and its
-- parameters evaluated for its iteration number (ranges, functions, the seeded generator).
-- @module lsys.components.expand
local C = require "lsys.components.proto"
local W = require "lsys.components.world"
local core = require "lsys.core"

local type, pairs, ipairs, error, setmetatable, rawget, rawset, tostring, pcall, require =
      type, pairs, ipairs, error, setmetatable, rawget, rawset, tostring, pcall, require
local math, string, table = math, string, table
local format, concat = string.format, table.concat
local floor = math.floor
local isnum, who, show = C.isnum, C.who, C.show
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
local function scale (a, k) return { a[1] * k, a[2] * k, a[3] * k } end
M.cross, M.dot = cross, dot

local function right (f) return scale(cross(f.H, f.U), -1) end     -- R = -L
local function front (f) return scale(f.U, -1) end                 -- F = -U
M.right, M.front = right, front

-- }=========================================================================================

-- {=========================================================================================
-- The seeded generator: splitmix64, the same on every machine. The expansion draws from the
-- frame arena's (compgeo.c): parameter functions (ctx.random) and the stems' gnarl in turn.

-- A generator function of the seed, for a caller that wants the sequence alone.
local function generator (seed)
  local a = core.frames(floor(seed or 1))
  return function () return a:random() end
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
  elseif t == "number" and C.isfunc(v) then
    local n, i = ctx.n or 1, ctx.i or 1
    out = v(n > 1 and (i - 1) / (n - 1) or 0)
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
  local b = sch[3]
  if b ~= nil and not C.within(b, out) then
    efail(inst, key, "gave %s, not %s", show(out), b[3])
  end
  return out
end
M.value = value
M.fail = efail

-- Per prototype, what each parameter is: most are plain constants, read once; a range
-- without a function depends only on (i, n); the rest (functions) go through `value` with
-- the instance's ctx. cache[p][key] = CONST, RANGE, CALL or FUNC in .how, the constant in .v.
-- FUNC: a Lua function of ctx giving a number, called straight from `get` (.v the
-- function, .b the bounds).
local CONST, RANGE, CALL, FUNC = 1, 2, 3, 4
local NIL = {}

local function howof (p, key)
  local v = p:param(key)
  local t = C.schema(p.kind, key)[1]
  if t ~= "number" and t ~= "vec3" then return CONST, v end
  if type(v) == "function" then return t == "number" and FUNC or CALL, v end
  if C.isfunc(v) then return CALL end
  if type(v) == "table" and #v == 2 then
    if v.f ~= nil or t == "vec3" then return CALL end
    return RANGE, v
  end
  return CONST, v
end

-- The per-prototype cache of parameter kinds (weak: prototypes can be collected), made
-- again when the prototype's `version` changed (proto:set).
local cachemeta = { __mode = "k" }
local protocache = setmetatable({}, cachemeta)

local function pcache (p)
  local pc = protocache[p]
  if pc == nil or pc.version ~= p.version then
    pc = { how = {}, v = {}, b = {}, version = p.version }
    protocache[p] = pc
  end
  return pc
end

--- The value of parameter `key` for instance inst at iteration i of n (ctx made only for a
-- function); the fast path of `value`.
local function get (inst, p, key, i, n)
  local pc = protocache[p]                    -- pcache(p), inline: this runs most often
  if pc == nil or pc.version ~= p.version then pc = pcache(p) end
  local how = pc.how[key]
  if how == nil then
    local h, v = howof(p, key)
    pc.how[key] = h
    if v == nil then v = NIL end
    pc.v[key] = v
    if h == FUNC then pc.b[key] = C.schema(p.kind, key)[3] or false end
    how = h
  end
  if how == CONST then
    local v = pc.v[key]
    if v == NIL then return nil end
    return v
  elseif how == RANGE then
    local v = pc.v[key]
    local u = n > 1 and (i - 1) / (n - 1) or 0
    return v[1] + u * (v[2] - v[1])
  elseif how == FUNC then
    local ok, r = pcall(pc.v[key], inst.ctx)
    if not ok then efail(inst, key, "its function failed: %s", tostring(r)) end
    if not isnum(r) then efail(inst, key, "gave %s, not a finite number", tostring(r)) end
    local b = pc.b[key]
    if b and not (r >= b[1] and r <= b[2]) then
      efail(inst, key, "gave %s, not %s", show(r), b[3])
    end
    return r
  end
  return value(inst, p, key, inst.ctx)
end
M.get = function (inst, key) return get(inst, inst.proto, key, inst.i, inst.n) end

--- Whether parameter `key` of prototype p is a function (its value may differ for
-- instances of the same iteration).
function M.calls (p, key)
  local pc = pcache(p)
  local how = pc.how[key]
  if how == nil then how = howof(p, key) end
  return how == CALL or how == FUNC
end

-- }=========================================================================================

-- {=========================================================================================
-- The i-tree

local Tree = {}
Tree.__index = Tree
M.Tree = Tree

--- The instances in depth-first order (each { index, proto, kind, name, path, parent
-- (index or nil), children (indices), i, n, depth, link, frame, params, ... }).
function Tree:instances () return self.list end

--- How many instances there are (nil: all) by the label their paths show (`what` a string:
-- the prototype's name, its kind when it has none) or by kind (`{ kind = "leaf" }`). A
-- named prototype is counted by its name only: in the rhododendron `count("leaf")` is the
-- 920 leaves named "leaf", `count{ kind = "leaf" }` 3,320 with the 2,400 petals.
function Tree:count (what)
  if what == nil then return #self.list end
  local key = "label"
  if type(what) == "table" then
    for k in pairs(what) do
      if k ~= "kind" then
        error(format("lsys.components: count: unknown field '%s' (known: kind)", tostring(k)),
              2)
      end
    end
    key, what = "kind", what.kind
  end
  if type(what) ~= "string" then
    error(format("lsys.components: count: expected a name or { kind = KIND }, got %s",
                 type(what)), 2)
  end
  local n = 0
  for _, inst in ipairs(self.list) do
    if inst[key] == what then n = n + 1 end
  end
  return n
end

--- The instance at `path` ("tree#1/leaf#3"), or nil.
function Tree:find (path)
  local by = self.bypath
  if by == nil then
    by = {}
    for _, inst in ipairs(self.list) do by[inst.path] = inst end
    self.bypath = by
  end
  return by[path]
end

function Tree:__tostring ()
  return format("lsys.components.Tree(%d instances)", #self.list)
end

-- The arena index of the tip frame of an instance (where its children start): the stem's
-- end, a leaf's or a primitive's far end along the heading, else its own frame.
local function tipindex (tree, inst)
  local p, kind = inst.proto, inst.kind
  local d
  if kind == "horn" or kind == "tree" then return inst.st + inst.ns - 1
  elseif kind == "leaf" then d = inst.length
  elseif kind == "revo" then
    local prof = p:param("profile")
    d = (prof[#prof][2] - prof[1][2]) * inst.params.size[2]
  elseif (p.params.primitive ~= nil or kind == "simple") and p:param("primitive") ~= "none" then
    d = inst.params.size[2]
  else
    return inst.fi
  end
  return tree.frames:ahead(inst.fi, d)
end

-- Instances keep what is rarely read lazily: the name and label (from the prototype), the
-- path (from the parent chain), the ctx of parameter functions, an empty list of children;
-- the frames are in the tree's arena (`fi`, a stem's `st` and `ns`), and `frame`, `stem`
-- and `tip` are new tables made from it at each read; the module range of the last
-- emission (`modules`, `m0`, `m1`, `at`) is the writer's.
local function instmeta (tree)
  local frames = tree.frames
  return {
    __index = function (inst, k)
      local v
      if k == "name" then return inst.proto.name
      elseif k == "label" then local p = inst.proto return p.name or p.kind
      elseif k == "frame" then return frames:get(inst.fi)
      elseif k == "stem" then
        local st = rawget(inst, "st")
        if st == nil then return nil end
        v = {}
        for j = 1, inst.ns do v[j] = frames:get(st + j - 1, true) end
        return v
      elseif k == "tip" then return frames:get(tipindex(tree, inst))
      elseif k == "m0" or k == "m1" or k == "at" or k == "modules" then
        local wr = tree.writer
        if wr == nil then return nil end
        local m0, m1, at = wr:range(inst.index)
        if m0 == nil then return nil end
        if k == "modules" then return { m0, m1 } end
        return k == "m0" and m0 or k == "m1" and m1 or at
      elseif k == "path" then
        local par = inst.parent
        v = (par and tree.list[par].path .. "/" or "") .. inst.label .. "#" .. inst.seq
      elseif k == "children" then v = {}
      elseif k == "ctx" then
        v = { i = inst.i, n = inst.n, depth = inst.depth, random = tree.random }
      else return nil end
      rawset(inst, k, v)
      return v
    end,
  }
end

-- The flags of link l name only iterations of the n that inst makes.
local function checkflags (inst, l, n)
  for _, x in ipairs(l.flags.list) do
    if x > n then
      error(format("lsys.components: %s (at %s): the flags of its %s link to %s name " ..
                   "iteration %s, but it makes %d", who(inst.proto), inst.path, l.type,
                   who(l.to), show(x), n), 0)
    end
  end
end

-- The flags of a link allow iteration i (of n)?
local function allowed (inst, l, i, n)
  local f = l.flags
  if f == nil then return true end
  checkflags(inst, l, n)
  if f.mode == "only" then return f.set[i] == true end
  return f.set[i] ~= true
end

-- How many of the n iterations the flags of link l allow.
local function nallowed (inst, l, n)
  local f = l.flags
  if f == nil then return n end
  checkflags(inst, l, n)
  local k = 0
  for _ in pairs(f.set) do k = k + 1 end
  return f.mode == "only" and k or n - k
end

-- The tropisms acting on a stem of segments `step` long (in the world): { direction (a
-- vector or a function of position and heading), its strength } for the Tree's gravi- and
-- phototropism, the World's wind, then its guides (cylinder, wall), which turn the heading
-- left by the others onto their target (world.lua, steer).
local function tropisms (inst, grav, photo, step)
  local w = inst.world
  local out = {}
  if grav ~= 0 then out[#out + 1] = { w.gravity, grav } end
  if photo ~= 0 then out[#out + 1] = { w.light, photo } end
  if w.wind and w.wind.strength ~= 0 then
    out[#out + 1] = { w.wind.dir, w.wind.strength }
  end
  if w.cylinder and w.cylinder.strength ~= 0 then
    out[#out + 1] = { W.cylinderguide(w.cylinder, step, w.cylinder.strength),
                      w.cylinder.strength }
  end
  if w.wall and w.wall.strength ~= 0 then
    out[#out + 1] = { W.wallguide(w.wall, step, w.wall.strength), w.wall.strength }
  end
  return out
end

local NOTROPISM = {}

-- The stem of a Horn or Tree (compgeo.c, lsys_compgeo_frames_stem): frames at the ends of
-- `segments` equal pieces from frame fi, bent by the curvature, the gnarl (random), the
-- tropisms of the world (each turning H towards its direction by the angle e |H x T|, as
-- cpfg's tropism, ABOP section 2.3) and, for a Tree, deviated at its branches (plan). Returns
-- the arena index of the first of segs + 1 frames (the base, u = 0, to the tip, u = 1).
local function stem (ex, inst, fi, len, segs, plan)
  local p = inst.proto
  local i, n = inst.i, inst.n
  local istree = p.kind == "tree"
  local curv = get(inst, p, "curvature", i, n)
  local gnarl = istree and get(inst, p, "gnarl", i, n) or 0
  local grav = istree and get(inst, p, "gravitropism", i, n) or 0
  local photo = istree and get(inst, p, "phototropism", i, n) or 0
  local dev = istree and get(inst, p, "deviation", i, n) or 0
  local twist = p.kind == "horn" and get(inst, p, "twist", i, n) or 0
  local w = inst.world
  local trop = NOTROPISM
  if grav ~= 0 or photo ~= 0 or w.cylinder or w.wall or w.wind then
    trop = tropisms(inst, grav, photo, len / segs * ex.frames:scale(fi))
  end
  local bu, broll
  if plan and dev ~= 0 then bu, broll = plan.u, plan.roll end
  return ex.frames:stem(fi, len, segs, curv, twist, gnarl, trop, dev, bu, broll)
end

-- The branches of a Tree: where along the stem, their roll, branching angle and scale, as
-- lists by branch number.
local function branchplan (inst, nb)
  local p, i, n = inst.proto, inst.i, inst.n
  local first, last = get(inst, p, "first", i, n), get(inst, p, "last", i, n)
  local dens = get(inst, p, "density", i, n)
  local div = get(inst, p, "divergence", i, n)
  local pc = pcache(p)
  get(inst, p, "angle", 1, nb)
  get(inst, p, "branch_scale", 1, nb)
  local ha, hs = pc.how.angle, pc.how.branch_scale
  local callang, callsc = ha == CALL or ha == FUNC, hs == CALL or hs == FUNC
  local us, rolls, angles, scales = {}, {}, {}, {}
  for b = 1, nb do
    local t = nb > 1 and (b - 1) / (nb - 1) or 0
    if dens ~= 1 then t = t ^ dens end
    local u = first + (last - first) * t
    us[b], rolls[b] = u, div * (b - 1)
    local ctx
    if callang or callsc then
      ctx = { i = b, n = nb, depth = inst.depth, random = inst.ctx.random, u = u }
    end
    angles[b] = callang and value(inst, p, "angle", ctx) or get(inst, p, "angle", b, nb)
    scales[b] = callsc and value(inst, p, "branch_scale", ctx) or
                get(inst, p, "branch_scale", b, nb)
  end
  return { u = us, roll = rolls, angle = angles, scale = scales, n = nb }
end

local Expander = {}
Expander.__index = Expander

-- A new instance of proto at arena frame fi (its parent's; `fresh`: a frame made for it
-- alone, which the instance may keep), iteration i of n, u along a Tree's stem.
-- The error of a graph that makes more than max_instances, at proto below parent.
function Expander:toomany (parent, proto)
  error(format("lsys.components: the graph makes more than %d instances (at %s/%s); " ..
               "raise max_instances or lower a count", self.max,
               parent and parent.path or "", proto.name or proto.kind), 0)
end

-- Stops before the k instances that link l of inst makes (of a multiplier or a Tree's
-- branches) are worked out, when they would make more than max_instances.
function Expander:room (inst, l, k)
  if #self.list + k > self.max then self:toomany(inst, l.to) end
end

function Expander:add (proto, fi, fresh, i, n, u, parent, ltype)
  local list = self.list
  local index = #list + 1
  if index > self.max then self:toomany(parent, proto) end
  local on = self.onpath
  local depth = (on[proto] or 0) + 1
  local label = proto.name or proto.kind
  local seq = (self.seq[label] or 0) + 1
  self.seq[label] = seq
  -- every field the expansion sets is in the constructor, so the table is made at its size
  local inst = setmetatable({ index = index, proto = proto, kind = proto.kind,
                              parent = parent and parent.index, link = ltype, i = i, n = n,
                              depth = depth, seq = seq, u = u,
                              world = parent and parent.world or self.world,
                              fi = false, params = false, length = nil, st = nil,
                              ns = nil }, self.meta)
  list[index] = inst
  if parent then
    local ch = rawget(parent, "children")
    if ch == nil then ch = {} parent.children = ch end
    ch[#ch + 1] = index
  end
  on[proto] = depth
  self:build(inst, fi, fresh)
  on[proto] = depth > 1 and depth - 1 or nil
  return inst
end

-- Whether prototype p has branch links (a Tree without them makes no branch plan).
local function hasbranches (p)
  for _, l in ipairs(p.links) do if l.type == "branch" then return true end end
  return false
end

local BASICS = { "translate", "rotate", "scale", "size" }

-- The basic parameters of an instance; one shared table when all four are constants.
local function basics (inst, p)
  local pc = pcache(p)
  local shared = pc.params
  if shared ~= nil then return shared end
  local params, const = {}, true
  for _, k in ipairs(BASICS) do
    params[k] = get(inst, p, k, inst.i, inst.n)
    if pc.how[k] ~= CONST then const = false end
  end
  if const then
    local t, r = params.translate, params.rotate
    pc.identity = t[1] == 0 and t[2] == 0 and t[3] == 0 and r[1] == 0 and r[2] == 0 and
                  r[3] == 0 and params.scale == 1
    pc.params = params
  end
  return params
end

-- The World's settings over its parent's.
local function worldof (inst, p)
  local w = {}
  for k, v in pairs(inst.world) do w[k] = v end
  for _, k in ipairs(W.SETTINGS) do
    if p.params[k] ~= nil then w[k] = W.check(inst, k, p.params[k]) end
  end
  return w
end

-- The instance's own frame, its geometry's skeleton, and its children.
function Expander:build (inst, fi, fresh)
  local p = inst.proto
  local params = basics(inst, p)
  inst.params = params
  local frames = self.frames
  if pcache(p).identity then
    if not fresh then fi = frames:copy(fi) end
  else
    local t, r = params.translate, params.rotate
    fi = frames:transform(fi, t[1], t[2], t[3], r[1], r[2], r[3], params.scale)
  end
  inst.fi = fi
  local kind = p.kind
  if kind == "world" then inst.world = worldof(inst, p)
  elseif kind == "leaf" then
    inst.length = get(inst, p, "length", inst.i, inst.n)        -- sets the tip
    local e = get(inst, p, "phototropism", inst.i, inst.n)
    if e ~= 0 then
      local f = frames:get(fi)
      W.leafturn(f, inst.world.light, e)
      frames:set(fi, f)
    end
  end
  local plan
  if kind == "horn" or kind == "tree" then
    local len = get(inst, p, "length", inst.i, inst.n)
    local segs = p:param("segments")
    if segs < 1 or segs > 100000 then
      efail(inst, "segments", "must be from 1 to 100000, got %s", tostring(segs))
    end
    local nb = kind == "tree" and p:param("n") or 0
    if nb > 0 and hasbranches(p) then
      for _, l in ipairs(p.links) do
        if l.type == "branch" and self:follows(l) then
          self:room(inst, l, nallowed(inst, l, nb))
        end
      end
      plan = branchplan(inst, nb)
    end
    inst.st = stem(self, inst, fi, len, segs, plan)
    inst.ns = segs + 1
    inst.length = len
  end
  local links = p.links
  if #links == 0 then return end
  local tip = tipindex(self.tree, inst)
  local ends = not self:recurses(inst)
  for _, l in ipairs(links) do
    self:follow(inst, l, tip, plan, ends)
  end
end

-- Whether the recursion of inst's prototype goes on below it: one of its links leads back
-- to a prototype on the path that may still appear again.
function Expander:recurses (inst)
  local p = inst.proto
  if not p.recursive then return false end
  return (self.onpath[p] or 0) < p.recursion
end

-- A Tree's branches on link l: the stem frame at u (position between the stem frames,
-- orientation of the one below), rolled by the divergence about H and pitched down by the
-- branching angle about the right axis (compgeo.c, lsys_compgeo_frame_branch).
function Expander:branches (inst, l, plan)
  local frames, st, ns = self.frames, inst.st, inst.ns
  local nb = plan.n
  local us, rolls, angles, scales = plan.u, plan.roll, plan.angle, plan.scale
  local target = l.to
  for b = 1, nb do
    if allowed(inst, l, b, nb) then
      local u = us[b]
      local fi = frames:branch(st, ns, u, rolls[b], angles[b], scales[b])
      self:add(target, fi, true, b, nb, u, inst, "branch")
    end
  end
end

-- Whether link l's target may appear again on the path (its recursion has not ended).
function Expander:follows (l)
  local on = self.onpath[l.to]
  return on == nil or on < l.to.recursion
end

function Expander:follow (inst, l, tip, plan, ends)
  if not self:follows(l) then return end                      -- the recursion ends here
  if l.type == "leaf" and not ends then return end             -- only where it ends
  local kind = inst.kind
  if C.MULTIPLIERS[kind] and l.type ~= "leaf" then
    self:multiply(inst, l)
  elseif kind == "tree" and l.type == "branch" then
    if plan then self:branches(inst, l, plan) end
  else
    self:add(l.to, tip, false, inst.i, inst.n, nil, inst, l.type)
  end
end

local MULTKEYS = { hydra = { "radius", "open", "close", "angle" },
                   wreath = { "radius", "open", "close" },
                   phiball = { "radius", "open", "close", "child_size", "influence" } }

-- The children of a multiplier as place.lua gives them (local frames, sizes); the same for
-- every instance of a prototype whose parameters are all constants (kept per prototype).
local function placekids (inst, p)
  local pc = pcache(p)
  if pc.kids ~= nil then return pc.kids, pc.sizes end
  local place = require "lsys.components.place"
  local ctx = inst.ctx
  local n = p:param("n")
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
  if n == 0 then return {}, sizes end
  local ok, kids = pcall(place[inst.kind], spec)
  if not ok then
    error(format("lsys.components: %s (at %s): %s", who(p), inst.path,
                 tostring(kids):gsub("^[^:]*: ", "")), 0)
  end
  local const = true
  for _, k in ipairs(MULTKEYS[inst.kind]) do
    if howof(p, k) ~= CONST then const = false end
  end
  if const then pc.kids, pc.sizes = kids, sizes end
  return kids, sizes
end

-- The children of a Hydra, Wreath or Phiball on link l: place.lua's local frames (X = the
-- multiplier's up, Y = its left, Z = its heading) in the multiplier's frame.
function Expander:multiply (inst, l)
  local p = inst.proto
  local n = p:param("n")
  self:room(inst, l, nallowed(inst, l, n))
  local kids, sizes = placekids(inst, p)
  local frames, fi = self.frames, inst.fi
  for i, k in ipairs(kids) do
    if allowed(inst, l, i, n) then
      local q, H, U = k.pos, k.H, k.U
      local g = frames:place(fi, q[1], q[2], q[3], H[1], H[2], H[3], U[1], U[2], U[3],
                             sizes and sizes[i] or 1)
      self:add(l.to, g, true, i, n, nil, inst, l.type)
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
  local seed = opts.seed or 1
  if not isnum(seed) then error("lsys.components.expand: seed must be a number", 2) end
  local frames = core.frames(floor(seed))
  local random = function () return frames:random() end
  local tree = setmetatable({ list = {}, root = root, frames = frames, random = random }, Tree)
  local ex = setmetatable({
    list = tree.list, onpath = {}, seq = {}, max = max, tree = tree, frames = frames,
    random = random, meta = instmeta(tree),
    world = { gravity = { 0, -1, 0 }, light = { 0, 1, 0 } },
  }, Expander)
  local fi = frames:add(opts.frame or { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, -1 },
                                        s = 1 })
  ex:add(root, fi, true, 1, 1, nil, nil, "root")
  W.skeleton(tree)
  return tree
end

return M
