--- The prototypes of a component graph (Lintermann and Deussen 1999): the nodes
-- of the p-graph, their kinds, their parameters with defaults and checks, and the links
-- between them. lsys.components gathers this module with the expansion
-- (lsys.components.expand) and the placements (lsys.components.place).
-- @module lsys.components.proto
local type, pairs, ipairs, error, setmetatable, getmetatable, tostring, select, pcall =
      type, pairs, ipairs, error, setmetatable, getmetatable, tostring, select, pcall
local math, string, table = math, string, table
local format, concat, sort = string.format, table.concat, table.sort
local floor, huge = math.floor, math.huge
local place = require "lsys.components.place"
local _ENV = nil

local M = {}

-- {=========================================================================================
-- Parameters

-- The kinds of parameter values (a schema entry's first field):
--   number   a finite number, or a range {v0, v1} over the instance's iteration (see
--            docs/components.md, "Ranges, functions and flag lists"), or a function
--   vec3     {x, y, z}, or a range of two such, or a function
-- A number or vec3 entry may have bounds as its third field ({lo, hi, what}: every value,
-- each component of a vector, in [lo, hi]; `what` says so in messages): a constant and the
-- ends of a range are checked here, a function's value for each instance
-- (lsys.components.expand).
--   integer  a whole number (not varied per instance)
--   enum     one of the listed strings
--   points   a list of {x, y} or {x, y, z} points (outlines, profiles)
--   boolean
--   any      a number, vector or function the component reads itself (fields)
-- Bounds of the values that lsys.components hands to code with limits of its own: the
-- curvatures of lsys.sketch.organ.leaf, sizes the drawing divides by, stem lengths the
-- turtle draws forwards, and tropism strengths
-- (radians of turn per segment and unit of |H x T|: past 100 a stem only spins, and the
-- angle in degrees must stay finite).
local NONNEG = { 0, huge, "three numbers >= 0" }
local LENGTH = { 0, huge, "a number >= 0" }        -- a stem's: the turtle draws it forwards
local CURL = { -10, 10, "a number from -10 to 10" }
local TROPISM = { -100, 100, "a number from -100 to 100" }
M.TROPISM = TROPISM
-- A guide's strength (a World's cylinder and wall): the most it turns a stem a segment.
local GUIDE = { 0, 100, "a number from 0 to 100 (radians a segment at most)" }
local INDEX = { 0, huge, "a whole number >= 0" }   -- a view's texture (its count: the model's)

local BASIC = {
  translate = { "vec3", { 0, 0, 0 } },    -- in the parent's frame: x right, y along, z front
  rotate = { "vec3", { 0, 0, 0 } },       -- degrees about the local x, then y, then z axes
  scale = { "number", 1 },                 -- uniform, for the component and all below it
  primitive = { "enum", "none", { "none", "cube", "sphere", "cylinder", "cone", "disc",
                                  "area", "tube" } },
  size = { "vec3", { 1, 1, 1 }, NONNEG },  -- of the primitive: width, height, depth
  color = { "integer", nil },              -- a palette index (the view's colours)
  texture = { "integer", 0, INDEX },       -- a view texture index (0: none)
  geometry = { "any", nil },               -- an L-system model or Lstring drawn on the frame
}

-- Each kind's own parameters (and a different default for a basic one).
local KINDS = {
  simple = { primitive = { "enum", "sphere", BASIC.primitive[3] } },
  revo = {
    profile = { "points", { { 0.3, 0 }, { 0.5, 0.3 }, { 0.35, 0.7 }, { 0.15, 1 } } },
  },
  horn = {
    length = { "number", 1, LENGTH }, radius = { "number", 0.05 }, tip = { "number", 0.5 },
    segments = { "integer", 8 }, curvature = { "number", 0 }, twist = { "number", 0 },
    thickness = { "points", nil },
    primitive = { "enum", "tube", BASIC.primitive[3] },
  },
  leaf = {
    length = { "number", 1 }, width = { "number", 0.5 },
    shape = { "enum", "ovate", { "ovate", "lanceolate", "elliptic", "obovate", "linear",
                                 "cordate" } },
    outline = { "points", nil }, lateral = { "number", 0, CURL },
    longitudinal = { "number", 0, CURL },
    phototropism = { "number", 0, { 0, 1, "a number from 0 to 1 (the fraction of the turn " ..
                                          "to the light)" } },
  },
  tree = {
    length = { "number", 1, LENGTH }, radius = { "number", 0.05 }, tip = { "number", 0.3 },
    segments = { "integer", 16 }, n = { "integer", 10 }, thickness = { "points", nil },
    first = { "number", 0.25 }, last = { "number", 1 }, density = { "number", 1 },
    angle = { "number", 60 }, divergence = { "number", 137.50776405003785 },
    deviation = { "number", 0 }, gnarl = { "number", 0 }, curvature = { "number", 0 },
    phototropism = { "number", 0, TROPISM }, gravitropism = { "number", 0, TROPISM },
    branch_scale = { "number", 1 },
    primitive = { "enum", "tube", BASIC.primitive[3] },
  },
  hydra = {
    n = { "integer", 5 }, radius = { "number", 0 }, open = { "number", 0 },
    close = { "number", 360 }, angle = { "number", 90 },
  },
  wreath = {
    n = { "integer", 8 }, radius = { "number", 1 }, open = { "number", 0 },
    close = { "number", 360 },
  },
  phiball = {
    n = { "integer", 21 }, radius = { "number", nil }, open = { "number", 0 },
    close = { "number", 90 }, child_size = { "number", 1 }, influence = { "number", 0 },
  },
  ffd = {
    fx = { "any", nil }, fy = { "any", nil }, fz = { "any", nil },
    mode = { "enum", "all", { "all", "skeleton" } }, isolate = { "boolean", false },
  },
  hyperpatch = {
    degree = { "any", { 2, 2, 2 } }, moves = { "any", {} }, box = { "any", nil },
    mode = { "enum", "all", { "all", "skeleton" } }, isolate = { "boolean", false },
  },
  world = {
    gravity = { "any", { 0, -1, 0 } }, light = { "any", { 0, 1, 0 } },
    cylinder = { "any", nil }, wall = { "any", nil }, wind = { "any", nil },
  },
}
M.KINDS = KINDS
M.BASIC = BASIC

-- The kinds in the order the article lists them (sidebar "Component Types of the Modeler").
M.ORDER = { "simple", "revo", "horn", "leaf", "tree", "hydra", "wreath", "phiball", "ffd",
            "hyperpatch", "world" }
M.MULTIPLIERS = { hydra = true, wreath = true, phiball = true }

local function schema (kind, key)
  local k = KINDS[kind][key]
  if k ~= nil then return k end
  return BASIC[key]
end
M.schema = schema

-- Each kind's defaults and known parameters, for Proto:param, which runs for every
-- instance: default[kind][key] (nil for none) and isknown[kind][key].
local default, isknown = {}, {}
for kind, own in pairs(KINDS) do
  local d, k = {}, {}
  for key, sch in pairs(BASIC) do d[key], k[key] = sch[2], true end
  for key, sch in pairs(own) do d[key], k[key] = sch[2], true end
  default[kind], isknown[kind] = d, k
end

local function known (kind)
  local out = {}
  for k in pairs(BASIC) do out[#out + 1] = k end
  for k in pairs(KINDS[kind]) do if BASIC[k] == nil then out[#out + 1] = k end end
  out[#out + 1] = "name"
  out[#out + 1] = "recursion"
  sort(out)
  return out
end
M.known = known

local function isnum (x) return type(x) == "number" and x == x and x > -huge and x < huge end
M.isnum = isnum

-- Whether x is an lsys.Func (a positional function, lsys.func): a number parameter may be
-- one, read at the instance's place u = (i - 1)/(n - 1) in its iteration as a range is.
local function isfunc (x)
  local mt = type(x) == "userdata" and getmetatable(x)
  return type(mt) == "table" and mt.__name == "lsys.Func"
end
M.isfunc = isfunc

local function who (p)
  return p.name and format("%s '%s'", p.kind, p.name) or p.kind
end
M.who = who

-- A number or a vector of them as messages show it.
local function show (v)
  if type(v) == "table" then
    local out = {}
    for i, x in ipairs(v) do out[i] = show(x) end
    return "{" .. concat(out, ", ") .. "}"
  elseif type(v) == "number" then
    return format("%.14g", v)
  end
  return tostring(v)
end
M.show = show

local function fail (p, fmt, ...)
  error(format("lsys.components: %s: " .. fmt, who(p), ...), 0)
end

local function isvec (v)
  return type(v) == "table" and #v == 3 and isnum(v[1]) and isnum(v[2]) and isnum(v[3])
end

-- The parameters of type "any": each checked by its own function (raises via fail).
local function isdegree (d) return isnum(d) and d == floor(d) and d >= 1 and d <= 4 end
local function fields (p, key, v, spec)
  if type(v) ~= "table" then fail(p, "'%s' must be a table", key) end
  local names = {}
  for k in pairs(spec) do names[#names + 1] = k end
  table.sort(names)
  for k, x in pairs(v) do
    local t = spec[k]
    if t == nil then
      fail(p, "'%s': unknown field '%s' (known: %s)", key, tostring(k), concat(names, ", "))
    end
    if t == "vec3" and not isvec(x) or t ~= "vec3" and not isnum(x) then
      fail(p, "'%s.%s' must be %s", key, k,
           t == "vec3" and "a vector {x, y, z} of finite numbers" or "a finite number")
    end
    local b = t == "tropism" and TROPISM or t == "guide" and GUIDE
    if b and not (x >= b[1] and x <= b[2]) then
      fail(p, "'%s.%s' must be %s, got %s", key, k, b[3], show(x))
    end
  end
end
local ANY = {
  ["hyperpatch.degree"] = function (p, key, v)
    if isdegree(v) then return end
    if type(v) == "table" and #v == 3 and isdegree(v[1]) and isdegree(v[2]) and
       isdegree(v[3]) then return end
    fail(p, "'%s' must be a whole number from 1 to 4, or three of them, got %s", key,
         type(v) == "table" and "{" .. concat({ tostring(v[1]), tostring(v[2]),
                                                tostring(v[3]) }, ", ") .. "}" or tostring(v))
  end,
  ["hyperpatch.moves"] = function (p, key, v)
    if type(v) ~= "table" then fail(p, "'%s' must be a list of {i, j, k, dx, dy, dz}", key) end
    for i, m in ipairs(v) do
      local ok = type(m) == "table" and #m == 6
      for k = 1, 6 do ok = ok and isnum(m[k]) and (k > 3 or m[k] == floor(m[k])) end
      if not ok then
        fail(p, "'%s[%d]' must be {i, j, k, dx, dy, dz}: three whole lattice indices and " ..
                "a move of finite numbers", key, i)
      end
    end
  end,
  ["hyperpatch.box"] = function (p, key, v)
    fields(p, key, v, { origin = "vec3", size = "vec3" })
    if not v.origin or not v.size then fail(p, "'%s' needs an origin and a size", key) end
  end,
  ["world.cylinder"] = function (p, key, v)
    if v == false then return end
    if type(v) ~= "table" then fail(p, "'%s' must be a table or false", key) end
    fields(p, key, v, { axis = "vec3", point = "vec3", radius = "number", pitch = "number",
                        strength = "guide" })
  end,
  ["world.wall"] = function (p, key, v)
    if v == false then return end
    if type(v) ~= "table" then fail(p, "'%s' must be a table or false", key) end
    fields(p, key, v, { point = "vec3", normal = "vec3", distance = "number",
                        strength = "guide" })
  end,
  ["world.wind"] = function (p, key, v)
    if v == false then return end
    if type(v) ~= "table" then fail(p, "'%s' must be a table or false", key) end
    fields(p, key, v, { direction = "vec3", strength = "tropism" })
  end,
}
for _, k in ipairs { "ffd.fx", "ffd.fy", "ffd.fz" } do
  ANY[k] = function (p, key, v)
    if type(v) ~= "function" then
      fail(p, "'%s' must be a function (x, y, z) -> number, got %s", key, type(v))
    end
  end
end
for _, k in ipairs { "world.gravity", "world.light" } do
  ANY[k] = function (p, key, v)
    if type(v) == "function" then return end
    if not isvec(v) or v[1] == 0 and v[2] == 0 and v[3] == 0 then
      fail(p, "'%s' must be a non-zero vector {x, y, z} or a function (x, y, z) -> x, y, z",
           key)
    end
  end
end
ANY["*.geometry"] = function (p, key, v)
  local mt = getmetatable(v)
  local ok = type(v) == "userdata" and mt ~= nil and mt.__name == "lsys.Lstring" or
             type(v) == "table" and type(v.derive) == "function"
  if not ok then fail(p, "'%s' must be an L-system model or an Lstring, got %s", key, type(v)) end
end

-- Whether the number or vector x is within the bounds b ({lo, hi, what}; nil: none).
local function within (b, x)
  if b == nil then return true end
  if type(x) == "number" then return x >= b[1] and x <= b[2] end
  for k = 1, 3 do
    if not (x[k] >= b[1] and x[k] <= b[2]) then return false end
  end
  return true
end
M.within = within

-- A constant, or each end of a range without a function, within the schema's bounds.
local function bounded (p, key, sch, v, ...)
  local b = sch[3]
  if b == nil or type(v) == "table" and v.f ~= nil then return v end
  for k = 1, select("#", ...) do
    if not within(b, (select(k, ...))) then
      fail(p, "'%s' must be %s, got %s", key, b[3], show(v))
    end
  end
  return v
end

-- Checks the value of parameter `key` of prototype `p` against its schema.
local function check (p, key, v)
  local sch = schema(p.kind, key)
  local t = sch[1]
  if t == "any" then
    local f = ANY[p.kind .. "." .. key] or ANY["*." .. key]
    if f then f(p, key, v) end
    return v
  end
  if type(v) == "function" and (t == "number" or t == "vec3") then return v end
  if t == "number" and isfunc(v) then return v end
  if t == "number" then
    if isnum(v) then return bounded(p, key, sch, v, v) end
    if type(v) == "table" and isnum(v[1]) and isnum(v[2]) and #v == 2 then
      if v.f ~= nil and type(v.f) ~= "function" then
        fail(p, "'%s': the range's f must be a function, got %s", key, type(v.f))
      end
      return bounded(p, key, sch, v, v[1], v[2])
    end
    fail(p, "'%s' must be a number, a range {v0, v1} or a function, got %s", key,
         v ~= v and "NaN" or type(v) == "number" and tostring(v) or type(v))
  elseif t == "vec3" then
    if isvec(v) then return bounded(p, key, sch, v, v) end
    if type(v) == "table" and #v == 2 and isvec(v[1]) and isvec(v[2]) then
      return bounded(p, key, sch, v, v[1], v[2])
    end
    fail(p, "'%s' must be a vector {x, y, z}, a range of two vectors or a function", key)
  elseif t == "integer" then
    if isnum(v) and v == floor(v) then return bounded(p, key, sch, v, v) end
    fail(p, "'%s' must be a whole number, got %s", key, tostring(v))
  elseif t == "enum" then
    for _, e in ipairs(sch[3]) do if v == e then return v end end
    fail(p, "'%s' must be one of %s, got %s", key, concat(sch[3], ", "), tostring(v))
  elseif t == "points" then
    if type(v) ~= "table" or #v < 2 then
      fail(p, "'%s' must be a list of two points or more", key)
    end
    for i, q in ipairs(v) do
      if type(q) ~= "table" or not isnum(q[1]) or not isnum(q[2]) or
         (q[3] ~= nil and not isnum(q[3])) then
        fail(p, "'%s': point %d must be {x, y} or {x, y, z} of finite numbers", key, i)
      end
    end
    return v
  elseif t == "boolean" then
    if type(v) == "boolean" then return v end
    fail(p, "'%s' must be true or false, got %s", key, tostring(v))
  end
  return v
end

-- }=========================================================================================

-- {=========================================================================================
-- Prototypes

local Proto = {}
Proto.__index = Proto
M.Proto = Proto

--- True when `x` is a component prototype.
function M.isproto (x) return getmetatable(x) == Proto end

-- One limit for every `n` (a Tree's branches, a multiplier's children), the placements':
-- checked here, before anything is computed for n children.
local MAX_N = place.MAX_N

-- The most a leaf's width may be, in lengths (lsys.sketch.organ.leaf's limit).
M.MAX_LEAF_RATIO = 10

-- The width and length of a leaf whose values are known (constants, ranges without a
-- function; at each end of a range), checked against M.MAX_LEAF_RATIO. A leaf with an
-- outline has no width of its own.
local function leafratio (p)
  local w, l = p.params.width, p.params.length
  if p.params.outline ~= nil or type(w) == "function" or type(l) == "function" or
     isfunc(w) or isfunc(l) or
     type(w) == "table" and w.f ~= nil or type(l) == "table" and l.f ~= nil then
    return
  end
  w, l = w or KINDS.leaf.width[2], l or KINDS.leaf.length[2]
  for k = 1, 2 do
    local a = type(w) == "table" and w[k] or w
    local b = type(l) == "table" and l[k] or l
    if not (a / b <= M.MAX_LEAF_RATIO) then
      fail(p, "'width' must be at most %d times 'length', got %s and %s", M.MAX_LEAF_RATIO,
           show(w), show(l))
    end
  end
end

-- A new prototype of `kind` from the table of parameters `t`.
local function new (kind, t)
  if t ~= nil and type(t) ~= "table" then
    error(format("lsys.components.%s: a table of parameters expected, got %s", kind, type(t)),
          3)
  end
  t = t or {}
  local p = setmetatable({ kind = kind, links = {}, params = {}, recursion = 1, version = 0,
                           xversion = 0 }, Proto)
  if t.name ~= nil then
    if type(t.name) ~= "string" or t.name == "" then
      error(format("lsys.components.%s: 'name' must be a non-empty string", kind), 3)
    end
    p.name = t.name
  end
  for k, v in pairs(t) do
    if k ~= "name" then
      if type(k) ~= "string" or (schema(kind, k) == nil and k ~= "recursion") then
        fail(p, "unknown parameter '%s' (known: %s)", tostring(k), concat(known(kind), ", "))
      end
      if k == "recursion" then
        if not isnum(v) or v ~= floor(v) or v < 1 or v > 1000 then
          fail(p, "'recursion' must be a whole number from 1 to 1000, got %s", tostring(v))
        end
        p.recursion = v
        p.recursive = true
      else
        p.params[k] = check(p, k, v)
      end
    end
  end
  local n = p.params.n
  if n ~= nil and (n < 0 or n > MAX_N) then
    fail(p, "'n' must be from 0 to %d, got %s", MAX_N, tostring(n))
  end
  if kind == "leaf" then leafratio(p) end
  return p
end

--- The value of parameter `key` as given (a number, range, function...) or its default.
function Proto:param (key)
  local v = self.params[key]
  if v ~= nil then return v end
  local kind = self.kind
  v = default[kind][key]
  if v == nil and not isknown[kind][key] then
    fail(self, "unknown parameter '%s'", tostring(key))
  end
  return v
end

-- The parameters that only the geometry's emitter reads (lsys.components.emit), never the
-- expansion: a change of one leaves the i-tree as it was, so lsys.ui.graph draws the plant
-- again from the i-tree it has.
M.DRAWN = {
  ["*"] = { color = true, texture = true },
  leaf = { width = true, shape = true, outline = true, lateral = true, longitudinal = true },
  horn = { radius = true, tip = true, thickness = true, primitive = true },
  tree = { radius = true, tip = true, thickness = true, primitive = true },
}
local function drawn (kind, key)
  local k = M.DRAWN[kind]
  return M.DRAWN["*"][key] == true or k ~= nil and k[key] == true
end
M.drawn = drawn

--- Sets parameter `key` (a name in M.known(kind), "recursion" or "name") to `v`, checked as
-- the constructor checks it (nil: back to the default); a failure raises and leaves the
-- prototype as it was. Bumps `version`, which tells the expansion's per-prototype caches
-- that the parameters changed, and `xversion` unless the parameter is one of M.DRAWN (an
-- i-tree made before is then no longer the graph's). Returns self.
function Proto:set (key, v)
  if getmetatable(self) ~= Proto then
    error("lsys.components: set: call it as proto:set(key, value)", 2)
  end
  if key == "name" then
    if v ~= nil and (type(v) ~= "string" or v == "") then
      fail(self, "'name' must be a non-empty string")
    end
    self.name = v
  elseif key == "recursion" then
    if v == nil then v = 1 end
    if not isnum(v) or v ~= floor(v) or v < 1 or v > 1000 then
      fail(self, "'recursion' must be a whole number from 1 to 1000, got %s", tostring(v))
    end
    self.recursion, self.recursive = v, true
  else
    if type(key) ~= "string" or schema(self.kind, key) == nil then
      fail(self, "unknown parameter '%s' (known: %s)", tostring(key),
           concat(known(self.kind), ", "))
    end
    local old = self.params[key]
    if v ~= nil then check(self, key, v) end
    if key == "n" and v ~= nil and (v < 0 or v > MAX_N) then
      fail(self, "'n' must be from 0 to %d, got %s", MAX_N, tostring(v))
    end
    self.params[key] = v
    if self.kind == "leaf" and (key == "width" or key == "length" or key == "outline") then
      local ok, err = pcall(leafratio, self)
      if not ok then
        self.params[key] = old
        error(err, 0)
      end
    end
  end
  self.version = (self.version or 0) + 1
  if not drawn(self.kind, key) then self.xversion = (self.xversion or 0) + 1 end
  return self
end

-- Checks the flags of a link: { only = {i...} } or { except = {i...} }.
local function checkflags (p, flags)
  if flags == nil then return nil end
  if type(flags) ~= "table" then fail(p, "a link's flags must be a table, got %s", type(flags)) end
  local list, mode
  for k, v in pairs(flags) do
    if k ~= "only" and k ~= "except" then
      fail(p, "a link's flags: unknown field '%s' (known: only, except)", tostring(k))
    end
    if list ~= nil then fail(p, "a link's flags take 'only' or 'except', not both") end
    list, mode = v, k
  end
  if type(list) ~= "table" then fail(p, "a link's flags: '%s' must be a list of iteration numbers",
                                     tostring(mode)) end
  local set = {}
  for i, x in ipairs(list) do
    if not isnum(x) or x ~= floor(x) or x < 1 then
      fail(p, "a link's flags: entry %d must be an iteration number (1, 2, ...), got %s", i,
           tostring(x))
    end
    set[x] = true
  end
  return { mode = mode, list = list, set = set }
end

local function link (self, kind, target, flags)
  if getmetatable(self) ~= Proto then
    error(format("lsys.components: %s: call it as proto:%s(other)", kind, kind), 3)
  end
  if getmetatable(target) ~= Proto then
    fail(self, "%s link: a component prototype expected, got %s", kind,
         type(target) == "table" and "a table" or type(target))
  end
  self.links[#self.links + 1] = { type = kind, to = target, flags = checkflags(self, flags) }
  return self
end

--- Links `b` as a child (placed relative to this component's geometry); returns self.
-- flags: { only = {i...} } or { except = {i...} } (iteration numbers of a multiplier).
function Proto:child (b, flags) return link(self, "child", b, flags) end
--- Links `b` as a branch: multiplied along the stem when this is a Tree, else a child.
function Proto:branch (b, flags) return link(self, "branch", b, flags) end
--- Links `b` as a leaf: made once, where this component's recursion ends.
function Proto:leaf (b, flags) return link(self, "leaf", b, flags) end

function Proto:__tostring ()
  return format("lsys.components.%s(%s%d links)", self.kind,
                self.name and "'" .. self.name .. "', " or "", #self.links)
end

for _, kind in ipairs(M.ORDER) do
  M[kind] = function (t) return new(kind, t) end
end

-- }=========================================================================================

return M
