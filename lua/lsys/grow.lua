--- Incremental growth (Davison, "Incremental rules for growing plants", section
-- "Incremental rules"; docs/manual.md §12): a plant is a set of persistent limbs
-- whose state changes a little at each tick, and new limbs are attached to existing ones;
-- nothing is derived or drawn anew. The limbs' state lives in a C table (csrc/core/grow.c,
-- `core.limbs`) that rewrites each limb's cylinder in its scene in place; Lua holds one light
-- handle per limb.
--
--   local grow = require "lsys.grow"
--   local Shoot = grow.kind("shoot")
--   Shoot:rule("length", function (limb)               -- the paper's 'length' rule
--     if limb:length() < 1.0 and not limb:has_leaves() then limb:scale_length(1.1) end
--   end)
--   local w = grow.world { seed = 1 }
--   w:plant { kind = Shoot, position = { 0, 0, 0 } }
--   w:tick(40)
--   lsys.render(w:scene(), { out = "tree.png" })
--
-- Ticks are parallel steps as in an L-system: every rule of a tick reads the state of the
-- start of the tick (its writes go to the next state; two scales in one tick compound),
-- but for the limb counts, which count a child as soon as it is made (as the paper's
-- spawning rule reads its scene's list of limbs); limbs spawned in a tick first run at the
-- next one, and removals and leaves take effect at its end. Within a tick, limbs run in
-- the order they were made and each limb's rules in the order they were declared (a kind's
-- base kind's first). Randomness comes from each plant's seeded generator (`limb:random`),
-- so a run is reproducible.
-- @module lsys.grow
local core = require "lsys.core"
local view = require "lsys.view"
local compile = require "lsys.compile"
local lmodel = require "lsys.model"

local type, pairs, ipairs, error, setmetatable, getmetatable, rawget, rawset, tostring, pcall =
      type, pairs, ipairs, error, setmetatable, getmetatable, rawget, rawset, tostring, pcall
local math, string, debug = math, string, debug
local format, table = string.format, table
local floor = math.floor

-- A generator seed as the integer core.frames takes: a whole number as itself, any other
-- (1e303, 0.5) by its bits, as a model's seed is taken (lua_rules.c, seedof): the same
-- seed gives the same plant everywhere.
local function seedint (x)
  local i = math.tointeger(x)
  if i then return i end
  return (string.unpack("<i8", string.pack("<d", x)))
end
local _ENV = nil

local M = {}

-- Raises "lsys.grow: ..." at the first Lua function outside this file that called into it
-- (its checks sit at different depths: a rule table's fields, a world's options).
local SELF = debug.getinfo(1, "S").source
local function outside ()
  local k = 3                       -- 1: outside, 2: fail, 3: what called fail
  while true do
    local info = debug.getinfo(k, "S")
    if info == nil then return 1 end
    if info.source ~= SELF and info.what ~= "C" then return k - 1 end
    k = k + 1
  end
end
local function fail (fmt, ...) error("lsys.grow: " .. format(fmt, ...), outside()) end

local function isnum (x)
  return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge
end

-- {=========================================================================================
-- Kinds: classes of limbs with their own data, methods and rules

local Limb = {}            -- the methods every limb has
Limb.__index = Limb
Limb._name = "limb"
Limb._rules = {}

local function iskind (k) return type(k) == "table" and rawget(k, "_rules") ~= nil end
M.iskind = iskind

--- A new kind of limb named `name`, extending `base` (a kind; default the plain limb):
-- it inherits its base's data and methods, and the rules its base has when it is made
-- (replacing one by name here leaves the base's alone). Fields set on the kind are defaults for
-- its limbs (`Shoot.max_length = 1`; a limb's own `limb.max_length = 2` overrides), and
-- functions set on it are methods (`function Shoot:bloom() ... end`).
function M.kind (name, base)
  if type(name) ~= "string" or name == "" then
    fail("kind: a name expected, got %s", tostring(name))
  end
  base = base or Limb
  if not iskind(base) then
    fail("kind '%s': the base must be a kind, got %s", name, tostring(base))
  end
  local rules = {}
  for k, r in ipairs(base._rules) do       -- each entry whole: a table rule's condition and
    local c = {}                           -- declared changes with its name and fn
    for f, v in pairs(r) do c[f] = v end
    rules[k] = c
  end
  local K = setmetatable({ _name = name, _rules = rules, _base = base }, { __index = base })
  K.__index = K
  K.__tostring = Limb.__tostring
  K.__newindex = Limb.__newindex
  return K
end
M.Limb = Limb

-- A colour ({r, g, b} or "#rrggbb") as three numbers; `what` names it in errors.
local parsed = setmetatable({}, { __mode = "k" })    -- "#rrggbb" -> {r, g, b}, parsed once

local function rgb (c, what, where)
  local v = type(c) == "string" and parsed[c]
  if not v then
    local ok
    ok, v = pcall(view.color, c, "lsys.grow", what)
    if not ok then
      v = tostring(v):gsub("^lsys%.grow: ", "")
      if where then fail("%s: %s", where, v) end
      fail("%s", v)
    end
    if type(c) == "string" then parsed[c] = v end
  end
  return v[1], v[2], v[3]
end

-- What a condition (`when`) may read: the limb's state at the start of the tick, and the
-- living limbs of its plant (`count`) and of the world (`total`) as they are when the rule
-- runs, with the limbs made so far in the tick (csrc/lua/lua_grow.c, V_COUNT).
local VARS = { "length", "radius", "age", "level", "leaves", "count", "root", "total" }
local FORMALS = {}
for k, v in ipairs(VARS) do FORMALS[v] = k - 1 end
local CONDENV = { math = math }

local RULE = { when = true, scale_length = true, scale_radius = true, blend = true,
               color = true, fn = true }

-- The rule entry { name, fn, code =, scale_length =, ... } of a rule given as a table.
local function tablerule (K, name, spec)
  local where = format("rule '%s' of kind '%s'", name, K._name)
  for k in pairs(spec) do
    if not RULE[k] then fail("%s: unknown field '%s'", where, tostring(k)) end
  end
  local r = { name, spec.fn }
  if spec.fn ~= nil and type(spec.fn) ~= "function" then
    fail("%s: 'fn' must be a function (limb, world)", where)
  end
  if spec.when ~= nil then
    if type(spec.when) ~= "string" then fail("%s: 'when' must be an expression string", where) end
    local tree = compile.parseexpr(spec.when)
    local code = tree and compile.machine({ cond = tree, exprs = {}, formals = FORMALS }, CONDENV)
    if code == nil then
      fail("%s: the condition '%s' must be arithmetic, comparisons, and/or/not and math " ..
           "functions of %s", where, spec.when, table.concat(VARS, ", "))
    end
    r.code, r.when = code, spec.when
  end
  for _, k in ipairs { "scale_length", "scale_radius" } do
    if spec[k] ~= nil then
      if not isnum(spec[k]) or spec[k] < 0 then fail("%s: '%s' must be a factor >= 0", where, k) end
      r[k] = spec[k]
    end
  end
  if spec.color ~= nil then r.color = { rgb(spec.color, "color", where) } end
  if spec.blend ~= nil then
    local b = spec.blend
    if type(b) ~= "table" or not isnum(b[2]) or b[2] < 0 or b[2] > 1 then
      fail("%s: 'blend' must be {colour, fraction 0..1}", where)
    end
    local cr, cg, cb = rgb(b[1], "blend", where)
    r.blend = { cr, cg, cb, b[2] }
  end
  if r[2] == nil and r.scale_length == nil and r.scale_radius == nil and r.color == nil and
     r.blend == nil then
    fail("%s: nothing to do (give fn, scale_length, scale_radius, color or blend)", where)
  end
  return r
end

--- Adds rule `name` to the kind, after its others; a rule of the same name (from the base
-- kind) is replaced where it was. The rule is a function (limb, world) run for every limb
-- of the kind at every tick, or a table run in C: { when = "length < 1 and leaves == 0"
-- (a condition over length, radius, age, level, leaves, count, root, total; none: always),
-- scale_length =, scale_radius =, color =, blend = {colour, fraction}, fn = function (limb,
-- world) called only where the condition holds }.
function Limb.rule (K, name, spec)
  if not iskind(K) then fail("rule: call it on a kind (Kind:rule(name, fn))") end
  if type(name) ~= "string" then fail("rule: a name expected, got %s", tostring(name)) end
  if K == Limb then fail("rule '%s': rules belong to a kind made by lsys.grow.kind", name) end
  local r
  if type(spec) == "function" then r = { name, spec }
  elseif type(spec) == "table" then r = tablerule(K, name, spec)
  else
    fail("rule '%s' of kind '%s': a function (limb, world) expected, got %s", name, K._name,
         tostring(spec))
  end
  K._version = (K._version or 0) + 1
  for k, old in ipairs(K._rules) do
    if old[1] == name then K._rules[k] = r return K end
  end
  K._rules[#K._rules + 1] = r
  return K
end

--- The rules of a kind in the order a tick runs them: { {name, fn}, ... }.
function Limb.rules (K) return K._rules end

-- }=========================================================================================

-- {=========================================================================================
-- Limbs: handles { _id, _w (the world), _p (the plant number), _T (its C table) }

function Limb:__tostring ()
  return format("lsys.grow.Limb(%s #%d)", self._name, self._id)
end

-- A field set on a limb: its own data, except the tree and the kind's methods. A limb's parent
-- is fixed when it is spawned: assigning one (which could make a cycle) is an error.
function Limb.__newindex (h, k, v)
  if k == "parent" or k == "children" or k == "siblings" then
    fail("limb %d: '%s' cannot be assigned: a limb's parent is fixed when it is spawned "
      .. "(a new parent could make a cycle); remove the limb and spawn it anew", h._id, k)
  end
  local K = getmetatable(h)
  if type(k) == "string" and (k:sub(1, 1) == "_" or type(K[k]) == "function") then
    fail("limb %d: '%s' is %s of kind '%s' and cannot be set on a limb", h._id, k,
      k:sub(1, 1) == "_" and "internal" or "a method", K._name)
  end
  rawset(h, k, v)
end

function Limb:id () return self._id end
function Limb:kind () return self._name end
function Limb:length () return self._T:length(self._id) end
function Limb:radius () return self._T:radius(self._id) end
function Limb:color () return { self._T:color(self._id) } end
function Limb:age () return self._T:age(self._id) end
function Limb:level () return self._T:level(self._id) end
function Limb:leaves () return self._T:leaves(self._id) end
function Limb:has_leaves () return self._T:leaves(self._id) > 0 end
function Limb:is_root () return self._T:parent(self._id) == nil end
function Limb:alive () return self._T:alive(self._id) end
--- The number of living limbs of its plant, counted as they are made: within a tick, with
-- the limbs spawned so far in it (Davison's spawning rule tests `treeLimbs.size()`, which
-- `makeChild` has just appended to); the limbs removed in it go at its end.
function Limb:count () return self._T:living(self._p) end
function Limb:base () return self._T:base(self._id) end
function Limb:tip () return self._T:tip(self._id) end

function Limb:parent ()
  local p = self._T:parent(self._id)
  return p and self._w._limbs[p] or nil
end

function Limb:children ()
  local out, limbs = self._T:children(self._id), self._w._limbs
  for k, c in ipairs(out) do out[k] = limbs[c] end
  return out
end

--- The other children of its parent (none for a root).
function Limb:siblings ()
  local p = self:parent()
  if p == nil then return {} end
  local out = {}
  for _, c in ipairs(p:children()) do if c ~= self then out[#out + 1] = c end end
  return out
end

local function factor (f, what)
  if not isnum(f) or f < 0 then fail("%s: a factor >= 0 expected, got %s", what, tostring(f)) end
  return f
end

function Limb:scale_length (f) self._T:scale_length(self._id, factor(f, "scale_length")) end
function Limb:scale_radius (f) self._T:scale_radius(self._id, factor(f, "scale_radius")) end
function Limb:set_length (x) self._T:set_length(self._id, factor(x, "set_length")) end
function Limb:set_radius (x) self._T:set_radius(self._id, factor(x, "set_radius")) end

--- Sets the colour ({r, g, b} in 0..1 or "#rrggbb").
function Limb:set_color (c)
  local r, g, b = rgb(c, "set_color")
  self._T:set_color(self._id, r, g, b)
end

--- Moves the colour from the start of the tick towards c by the fraction t (0..1).
function Limb:blend_color (c, t)
  local r, g, b = rgb(c, "blend_color")
  if not isnum(t) or t < 0 or t > 1 then
    fail("blend_color: a fraction 0..1 expected, got %s", tostring(t))
  end
  self._T:blend_color(self._id, r, g, b, t)
end

--- n leaves at its tip (at the end of the tick): opts { size = 0.3, color = leaf green }.
function Limb:add_leaves (n, opts)
  if type(n) ~= "number" or n ~= floor(n) or n < 0 or n > 1000 then
    fail("add_leaves: a count 0..1000 expected, got %s", tostring(n))
  end
  opts = opts or {}
  local size = opts.size or 0.3
  if not isnum(size) or size < 0 then
    fail("add_leaves: 'size' must be >= 0, got %s", tostring(size))
  end
  local r, g, b = rgb(opts.color or self._w.leaf_color, "add_leaves")
  self._T:add_leaves(self._id, n, size, r, g, b)
end

function Limb:drop_leaves () self._T:drop_leaves(self._id) end

--- Removes the limb and everything that grows on it (at the end of the tick).
function Limb:remove ()
  self._T:remove(self._id)
  self._w._removed = true
end

--- A number from its plant's generator: [0, 1), or [a, b) with two arguments.
function Limb:random (a, b)
  local x = self._w._gen[self._p]:random()
  if a == nil then return x end
  return a + (b - a) * x
end

local AXES = { x = { 1, 0, 0 }, y = { 0, 1, 0 }, z = { 0, 0, 1 } }

local function axisof (a, what)
  if a == nil then return 0, 0, 1 end
  if type(a) == "string" then
    local v = AXES[a]
    if v == nil then fail("%s: axis '%s' is not \"x\", \"y\", \"z\" or {x, y, z}", what, a) end
    return v[1], v[2], v[3]
  end
  if type(a) ~= "table" or not (isnum(a[1]) and isnum(a[2]) and isnum(a[3])) or
     a[1] == 0 and a[2] == 0 and a[3] == 0 then
    fail("%s: 'axis' must be \"x\", \"y\", \"z\" or a non-zero {x, y, z}", what)
  end
  return a[1], a[2], a[3]
end

local function num (t, k, default, what, lo)
  local v = t[k]
  if v == nil then return default end
  if not isnum(v) or (lo ~= nil and v < lo) then
    fail("%s: '%s' must be a finite number%s, got %s", what, k,
         lo ~= nil and format(" >= %g", lo) or "", tostring(v))
  end
  return v
end

local SPAWN = { angle = true, axis = true, roll = true, at = true, length = true, radius = true,
                color = true, kind = true }

--- A child at the limb's tip (or at the fraction `at` along it), without transforms: opts
-- { angle (degrees, 0), axis ("x", "y", "z" or {x, y, z} in the limb's own axes: x right,
-- y along it, z front; "z"), roll (degrees about the limb first, 0), length (0.5), radius
-- (0.05), color (the kind's `shoot_color`, else the world's), kind (this limb's) }.
-- Returns the child, or nil when the world's limb cap is reached.
function Limb:spawn (opts)
  opts = opts or {}
  if type(opts) ~= "table" then fail("spawn: an options table expected") end
  for k in pairs(opts) do
    if not SPAWN[k] then fail("spawn: unknown option '%s'", tostring(k)) end
  end
  local w = self._w
  local K = opts.kind or getmetatable(self)
  if not iskind(K) then fail("spawn: 'kind' must be a kind, got %s", tostring(K)) end
  if w.capped and w._T:living() >= w._max then return nil end   -- full: nothing to make
  local ax, ay, az = axisof(opts.axis, "spawn")
  local r, g, b = rgb(opts.color or K.shoot_color or w.shoot_color, "spawn")
  local at = num(opts, "at", 1, "spawn", 0)
  if at > 1 then fail("spawn: 'at' must be from 0 to 1, got %s", tostring(at)) end
  local id = w._T:add(self._id, 0, at, ax, ay, az, num(opts, "angle", 0, "spawn"),
                      num(opts, "roll", 0, "spawn"), num(opts, "length", 0.5, "spawn", 0),
                      num(opts, "radius", 0.05, "spawn", 0), r, g, b, w:_kind(K))
  if id == nil then w.capped = true return nil end
  local h = setmetatable({ _id = id, _w = w, _p = self._p, _T = w._T }, K)
  w._limbs[id] = h
  return h
end

--- Turns the limb from its parent: opts as spawn's angle, axis and roll.
function Limb:turn (opts)
  opts = opts or {}
  local ax, ay, az = axisof(opts.axis, "turn")
  self._T:set_turn(self._id, ax, ay, az, num(opts, "angle", 0, "turn"),
                      num(opts, "roll", 0, "turn"))
end

-- }=========================================================================================

-- {=========================================================================================
-- Worlds

local World = {}
World.__index = World

local WORLD = { seed = true, max_limbs = true, sides = true, shoot_color = true,
                leaf_color = true, ticks = true, view = true, leaf = true, dir = true }

local function typename (x)
  local mt = getmetatable(x)
  return type(mt) == "table" and rawget(mt, "__name") or type(x)
end

-- The world's leaf shape from its `leaf` option (see M.world); a surface file's name is
-- looked up in `dir` (nil: the current folder), which `whence` describes.
local function leafshape (T, leaf, dir, whence)
  if leaf == nil or leaf == "quad" then return end
  local spec = leaf
  if type(leaf) ~= "table" or typename(leaf) ~= "table" then spec = { surface = leaf } end
  for k in pairs(spec) do
    if k ~= "surface" and k ~= "file" and k ~= "precision" then
      fail("world: leaf: unknown option '%s'", tostring(k))
    end
  end
  local shape = spec.surface
  if type(shape) == "string" then spec.file, shape = shape, nil end
  if shape == nil then
    if type(spec.file) ~= "string" then
      fail("world: leaf: \"quad\", a surface file name, an lsys.Surface, an organ or an "
           .. "lsys.Scene expected")
    end
    local path = view.resolve(dir, spec.file)
    local ok, s = pcall(core.surface_load, path)
    if not ok then
      fail("world: leaf: %s (looked up in %s)", (tostring(s):gsub("^lsys%.[%w_]+: ", "")),
           whence)
    end
    shape = s
  elseif typename(shape) == "lsys.Organ" then
    shape = shape:surface()
  elseif typename(shape) ~= "lsys.Surface" and typename(shape) ~= "lsys.Scene" then
    fail("world: leaf: an lsys.Surface, an organ, an lsys.Scene or a file name expected, "
         .. "got %s", typename(shape))
  end
  local ns, nt
  if spec.precision ~= nil then
    local p = spec.precision
    if type(p) ~= "table" or not (isnum(p[1]) and isnum(p[2])) then
      fail("world: leaf: 'precision' must be {s, t} (lines a patch)")
    end
    ns, nt = p[1], p[2]
    if ns ~= floor(ns) or nt ~= floor(nt) or ns < 1 or nt < 1 or ns > 256 or nt > 256 then
      fail("world: leaf: 'precision' must be whole numbers 1..256")
    end
  end
  local ok, err = pcall(T.set_leaf, T, shape, ns, nt)
  if not ok then fail("world: %s", (tostring(err):gsub("^leaf shape", "leaf"))) end
end

-- What a world's Lua side keeps per limb (its handle, a table of 4 fields, and its slot in
-- _limbs) and per plant (its generator, a Frames, and its slot in _gen), in bytes: the C
-- table counts them in max_memory with its own arrays and its scene (so that a
-- world stays within its budget; tests/grow_spec.lua checks them against collectgarbage("count")).
local LIMB_BYTES, PLANT_BYTES = 176, 100
M._LIMB_BYTES, M._PLANT_BYTES = LIMB_BYTES, PLANT_BYTES

--- A world of plants. opts: `seed` (1: plant k's generator is seeded seed + k - 1 unless
-- its plant call gives one), `max_limbs` (100,000 living limbs in all: spawn returns nil
-- past it), `sides` (8: the limbs' cylinders), `shoot_color` (new limbs; "#5a9e32"),
-- `leaf_color` ("#3f8f2a"), `ticks` (how long it grows: `world:grow()`, `lsys grow`; the
-- field `length`), `view` (how to look at it: background, light, projection, direction,
-- up, viewpoint, target, fov, twist, as in a model's view, and zoom: scene:look's fields),
-- `leaf` (every leaf's shape: "quad" (the default rhombus), a cpfg surface file's name
-- (looked up from the folder of the file that makes the world), an lsys.Surface, a
-- sketched organ, an lsys.Scene (its triangles, y along the leaf, z its normal), or
-- { surface | file, precision = {s, t} }),
-- `dir` (where file names are looked up: default the folder of the Lua file calling
-- grow.world, or the current folder when that cannot be seen, as through `return
-- grow.world{...}`).
function M.world (opts)
  opts = opts or {}
  if type(opts) ~= "table" then fail("world: an options table expected") end
  for k in pairs(opts) do
    if not WORLD[k] then fail("world: unknown option '%s'", tostring(k)) end
  end
  local seed = num(opts, "seed", 1, "world")
  local max = num(opts, "max_limbs", 100000, "world", 1)
  local sides = num(opts, "sides", 8, "world", 3)
  if sides > 64 or sides ~= floor(sides) then
    fail("world: 'sides' must be a whole number 3..64")
  end
  local w = setmetatable({
    _T = core.limbs { sides = sides, max_limbs = floor(max), limb_bytes = LIMB_BYTES,
                      plant_bytes = PLANT_BYTES }, _limbs = {}, _gen = {},
    _kinds = {}, _kindlist = {}, _kver = {}, _names = {}, _fns = {}, _fnidx = {},
    _seed = seed, _max = floor(max), ticks = 0, capped = false,
    shoot_color = opts.shoot_color or "#5a9e32", leaf_color = opts.leaf_color or "#3f8f2a",
  }, World)
  rgb(w.shoot_color, "shoot_color")
  rgb(w.leaf_color, "leaf_color")
  if opts.ticks ~= nil then
    w.length = num(opts, "ticks", nil, "world", 0)
    if w.length ~= floor(w.length) then fail("world: 'ticks' must be a whole number") end
  end
  if opts.view ~= nil then
    if type(opts.view) ~= "table" then fail("world: 'view' must be a table") end
    local ok, err = pcall(w._T:scene().look, w._T:scene(), opts.view)
    if not ok then fail("world: %s", (tostring(err):gsub("^scene:look: opts%.", "view."))) end
  end
  local dir, whence = opts.dir
  if dir ~= nil then
    if type(dir) ~= "string" then fail("world: 'dir' must be a folder's name") end
    whence = format("'%s', the world's dir", dir)
  else
    -- the folder of the Lua file calling grow.world (unknown through a tail call)
    local src = not debug.getinfo(1, "t").istailcall and debug.getinfo(2, "S").source or ""
    dir = src:match("^@(.*)/[^/]*$") or (src:match("^@") and ".")
    whence = dir and format("'%s', the folder of the file making the world", dir)
      or "the current folder (give the world dir = lsys.here() to look next to your file)"
  end
  leafshape(w._T, opts.leaf, dir, whence)
  return w
end

local PLANT = { kind = true, position = true, seed = true, length = true, radius = true,
                color = true }

--- A new plant: its root limb growing up (+y) from `position` ({0, 0, 0}). opts: `kind`
-- (a kind; the plain limb), `seed`, `length` (0.5), `radius` (0.05), `color`.
function World:plant (opts)
  opts = opts or {}
  for k in pairs(opts) do
    if not PLANT[k] then fail("plant: unknown option '%s'", tostring(k)) end
  end
  local K = opts.kind or Limb
  if not iskind(K) then fail("plant: 'kind' must be a kind, got %s", tostring(K)) end
  local pos = opts.position or { 0, 0, 0 }
  if type(pos) ~= "table" or not (isnum(pos[1]) and isnum(pos[2]) and isnum(pos[3])) then
    fail("plant: 'position' must be {x, y, z}")
  end
  local T = self._T
  local p = self:_newplant(pos[1], pos[2], pos[3], num(opts, "seed", nil, "plant"))
  local r, g, b = rgb(opts.color or K.shoot_color or self.shoot_color, "plant")
  local id = T:add(0, p, 1, 0, 0, 1, 0, 0, num(opts, "length", 0.5, "plant", 0),
                   num(opts, "radius", 0.05, "plant", 0), r, g, b, self:_kind(K))
  if id == nil then self.capped = true return nil end
  local h = setmetatable({ _id = id, _w = self, _p = p, _T = T }, K)
  self._limbs[id] = h
  return h
end

--- Advances time by n ticks (1).
function World:tick (n)
  n = n or 1
  if not isnum(n) or n < 0 or n ~= floor(n) then fail("tick: a whole number of ticks expected") end
  for _ = 1, n do self:_step() end
  return self
end

--- Grows the world to its length (the `ticks` it was made with, else `n`): the ticks it
-- has not had yet.
function World:grow (n)
  local length = self.length or n
  if length == nil then fail("grow: the world has no length (world{ticks = N}): give one") end
  return self:tick(math.max(0, length - self.ticks))
end

-- A new plant at (x, y, z) with its generator (seeded `seed`, default the world's seed +
-- its number - 1); its number.
function World:_newplant (x, y, z, seed)
  local p = self._T:plant(x, y, z)
  self._gen[p] = core.frames(seedint(floor(seed or self._seed + p - 1)))
  return p
end

-- The number the C table knows kind K by (given at first use).
function World:_kind (K)
  local id = self._kinds[K]
  if id == nil then
    id = #self._kindlist
    if id > 65535 then fail("a world takes at most 65,536 kinds") end
    self._kindlist[id + 1] = K
    self._kinds[K] = id
  end
  return id
end

-- Gives the C table the rules of every kind whose rules changed since the last tick: a
-- function rule is {fn = its index in self._fns}; a table rule its condition's code and
-- declared changes.
function World:_sync ()
  local fns, fnidx = self._fns, self._fnidx
  for id0, K in ipairs(self._kindlist) do
    local v = K._version or 0
    if self._kver[K] ~= v then
      local list, names = {}, {}
      for k, r in ipairs(K._rules) do
        local fi
        if r[2] ~= nil then
          fi = fnidx[r[2]]
          if fi == nil then fi = #fns + 1 fns[fi] = r[2] fnidx[r[2]] = fi end
        end
        list[k] = { code = r.code, scale_length = r.scale_length,
                    scale_radius = r.scale_radius, blend = r.blend, color = r.color, fn = fi }
        names[k] = r[1]
      end
      self._T:set_rules(id0 - 1, list)
      self._names[id0 - 1] = names
      self._kver[K] = v
    end
  end
end

-- One tick: the C table runs every limb's rules (conditions and declared changes in C,
-- functions where their conditions hold).
function World:_step ()
  local T, limbs = self._T, self._limbs
  self:_sync()
  T:begin()
  local ok, msg = pcall(T.run, T, limbs, self, self._fns)
  local ri, li = T:where()
  local fok, ferr = pcall(T.finish, T)    -- the tick is over even when its geometry fails
  self.ticks = self.ticks + 1
  if self._removed then
    self._removed = false
    for i, h in pairs(limbs) do if h and not T:alive(i) then limbs[i] = false end end
  end
  if not ok then
    local limb = limbs[li]
    local kind = limb and limb._name or "?"
    local names = limb and self._names[self._kinds[getmetatable(limb)]]
    error(format("lsys.grow: rule '%s' of kind '%s' failed on limb %d (tick %d): %s",
                 names and names[ri] or tostring(ri), kind, li or 0, self.ticks,
                 (tostring(msg):gsub("^lsys%.grow: ", ""))), 0)
  end
  if not fok then
    error(format("lsys.grow: tick %d: %s", self.ticks,
                 (tostring(ferr):gsub("^lsys%.grow: ", ""))), 0)
  end
end

--- The living limbs, in the order they were made.
function World:limbs ()
  local out = {}
  for i = 1, self._T:count() do
    local h = self._limbs[i]
    if h then out[#out + 1] = h end
  end
  return out
end

--- The limb with id i (nil once removed).
function World:limb (i) return self._limbs[i] or nil end

--- The number of living limbs (of plant p).
function World:count (p) return self._T:living(p) end

--- The scene the limbs are drawn in, up to date (render it, save it, show it).
function World:scene ()
  self._T:update()
  return self._T:scene()
end

--- The plants as one bracketed Lstring of turtle modules for `model` (an lsys model whose
-- rules intern the names; default a plain one): each limb is a branch `[` that moves the
-- turtle from where its parent left it to the limb's base and orientation (relative rolls,
-- pitches and `f`, as lsys.components writes), `#(2 radius) F(length)`, then its children;
-- so export, the arrangement, tests and the L-system tools take a grown plant. Returns the
-- Lstring and owner(k): the limb that wrote module k.
function World:lstring (model)
  model = model or lmodel.lsystem { axiom = "", steps = 0, name = "grown" }
  if not lmodel.ismodel(model) then fail("lstring: a model expected, got %s", tostring(model)) end
  local T = self._T
  T:update()
  local F = core.frames(1)
  local W = core.cwriter(model._rules, F)
  local width = W:symbol("#")
  local function open (id)
    local p = { T:base(id) }
    local _, H, Fr = T:frame(id)
    W:open(id, F:add { p = p, H = H, U = { -Fr[1], -Fr[2], -Fr[3] } })
    W:op(width, 2 * T:radius(id))
    W:forward(T:length(id), true)     -- F, and the writer's turtle moves with it
  end
  for id = 1, T:count() do
    if T:alive(id) and T:parent(id) == nil then
      open(id)
      local stack = { { T:children(id), 0 } }      -- without recursion: any depth
      while #stack > 0 do
        local top = stack[#stack]
        top[2] = top[2] + 1
        local c = top[1][top[2]]
        if c then
          open(c)
          stack[#stack + 1] = { T:children(c), 0 }
        else
          W:close()
          stack[#stack] = nil
        end
      end
    end
  end
  local limbs = self._limbs
  return W:lstring(), function (k) local id = W:owner(k) return id and limbs[id] or nil end
end

--- A number from the world's own generator (seeded by `seed`): [0, 1) or [a, b).
function World:random (a, b)
  self._wgen = self._wgen or core.frames(seedint(floor(self._seed)))
  local x = self._wgen:random()
  if a == nil then return x end
  return a + (b - a) * x
end

function World:__tostring ()
  return format("lsys.grow.World(%d limbs, %d ticks)", self._T:living(), self.ticks)
end

M.World = World

-- {=========================================================================================
-- From an L-system's plant

local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end

-- The axis and angle (degrees) of the rotation whose matrix has columns X, Y, Z (right-hand
-- Rodrigues, as the C table turns limbs). Below a quarter turn the axis comes from the
-- skew-symmetric part; above it from the diagonal (m_ii = c + k_i^2 (1 - c)), which stays
-- accurate up to a half turn where sin a vanishes.
local function axisangle (X, Y, Z)
  local m = { { X[1], Y[1], Z[1] }, { X[2], Y[2], Z[2] }, { X[3], Y[3], Z[3] } }
  local c = (m[1][1] + m[2][2] + m[3][3] - 1) / 2
  if c > 1 then c = 1 elseif c < -1 then c = -1 end
  local skew = { m[3][2] - m[2][3], m[1][3] - m[3][1], m[2][1] - m[1][2] }
  -- the angle from its sine and cosine both: acos alone loses it near a half turn
  local a = math.atan(math.sqrt(skew[1] ^ 2 + skew[2] ^ 2 + skew[3] ^ 2) / 2, c)
  if a < 1e-9 then return 0, 0, 1, 0 end
  if a < math.pi / 2 then
    local s2 = 2 * math.sin(a)
    return skew[1] / s2, skew[2] / s2, skew[3] / s2, math.deg(a)
  end
  local k, big = {}, 1
  for i = 1, 3 do
    k[i] = math.sqrt(math.max(0, (m[i][i] - c) / (1 - c)))
    if k[i] > k[big] then big = i end
  end
  if skew[big] < 0 then k[big] = -k[big] end
  for j = 1, 3 do
    if j ~= big then k[j] = (m[big][j] + m[j][big]) / (2 * (1 - c) * k[big]) end
  end
  return k[1], k[2], k[3], math.deg(a)
end

local FROM = { model = true, view = true, kind = true, seed = true, max_limbs = true,
               sides = true, color = true }

--- Starts incremental growth from a derived L-system plant: every segment the turtle draws
-- for Lstring `s` becomes a limb (its parent the segment it starts from, its length, radius
-- and orientation the segment's; a segment that does not start at the end of its parent
-- becomes a plant of its own). opts: `model` (the model that derived s: it interprets it;
-- default a plain model of s's text with `view`), `kind` (the limbs' kind), `color` (their
-- colour: default the view palette's), `seed`, `max_limbs`, `sides` (as grow.world).
-- Returns the world and the list of limbs by segment record.
function M.from_lstring (s, opts)
  if type(s) ~= "string" and not lmodel.islstring(s) then
    fail("from_lstring: an Lstring or its text expected, got %s", type(s))
  end
  if opts ~= nil and type(opts) ~= "table" then
    fail("from_lstring: the options must be a table, got %s", type(opts))
  end
  opts = opts or {}
  for k in pairs(opts) do
    if not FROM[k] then fail("from_lstring: unknown option '%s'", tostring(k)) end
  end
  local m = opts.model
  local scene
  if m ~= nil then
    if not lmodel.ismodel(m) then fail("from_lstring: 'model' must be a model") end
    scene = m:interpret(s)
  else
    m = lmodel.lsystem { axiom = tostring(s), steps = 0, view = opts.view }
    scene = m:interpret()
  end
  local w = M.world { seed = opts.seed, max_limbs = opts.max_limbs, sides = opts.sides }
  local K = opts.kind or Limb
  if not iskind(K) then fail("from_lstring: 'kind' must be a kind") end
  local palette = m.view and m.view.palette or {}
  local T = w._T
  local bylimb, byrec = {}, {}
  for k, r in scene:records() do
    if r.kind == "segment" then
      if not (isnum(r.p0[1]) and isnum(r.p0[2]) and isnum(r.p0[3]) and isnum(r.length)) then
        fail("from_lstring: segment %d (module %d) is beyond what the scene's floats hold",
             k, r.module or 0)
      end
      local H, U = r.H, r.U
      local L = { H[2] * U[3] - H[3] * U[2], H[3] * U[1] - H[1] * U[3], H[1] * U[2] - H[2] * U[1] }
      local X, Z = { -L[1], -L[2], -L[3] }, { -U[1], -U[2], -U[3] }
      local col = opts.color or palette[r.color]
      if type(col) == "table" and col.diffuse then col = col.diffuse end
      local cr, cg, cb = rgb(col or w.shoot_color, "from_lstring")
      local p = r.parent and byrec[r.parent]
      local id
      if p then
        local px, py, pz = T:tip(p)
        local d = (px - r.p0[1]) ^ 2 + (py - r.p0[2]) ^ 2 + (pz - r.p0[3]) ^ 2
        if d > 1e-10 * (1 + r.length * r.length) then p = nil end
      end
      if p then                              -- its rotation in the parent's axes
        local PX, PY, PZ = T:frame(p)
        local ax, ay, az, ang = axisangle({ dot(PX, X), dot(PY, X), dot(PZ, X) },
                                          { dot(PX, H), dot(PY, H), dot(PZ, H) },
                                          { dot(PX, Z), dot(PY, Z), dot(PZ, Z) })
        id = T:add(p, 0, 1, ax, ay, az, ang, 0, r.length, r.w0 / 2, cr, cg, cb, w:_kind(K))
      else
        local pl = w:_newplant(r.p0[1], r.p0[2], r.p0[3])
        local ax, ay, az, ang = axisangle(X, H, Z)
        id = T:add(0, pl, 1, ax, ay, az, ang, 0, r.length, r.w0 / 2, cr, cg, cb, w:_kind(K))
      end
      if id == nil then w.capped = true break end
      local h = setmetatable({ _id = id, _w = w, _p = T:plant_of(id), _T = T }, K)
      w._limbs[id] = h
      byrec[k] = id
      bylimb[#bylimb + 1] = h
    end
  end
  return w, bylimb
end

-- }=========================================================================================

-- }=========================================================================================

return M
