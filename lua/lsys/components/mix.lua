--- L-systems that place component plants ("an L-system can place a component
-- graph's plant with a module"). The other direction, a component drawing an L-system,
-- is the basic parameter `geometry` (lsys.components.emit).
--
--   local mix = require "lsys.components.mix"
--   local m = lsys.lsystem { axiom = "P(1) f(4) P(0.5) f(4) P(2, 7)", ... }
--   mix.place(m, { P = plant })          -- plant: a component graph's root prototype
--
-- After each derivation (the model's `finish`), every module P(s) or P(s, seed) of the
-- string is followed by the plant, expanded with that seed (default opts.seed) and
-- emitted as relative turtle modules with the model's own rules (lsys.components.emit), in
-- a branch `[@Di(s) ...]` that scales it by s and leaves the turtle as it was. A plant
-- is expanded and emitted once per seed, however often it is placed. Its leaf surfaces
-- join the model's view; its non-uniform primitives are scaled after the interpretation
-- (`after_interpret`) in the frame of the turtle at P; picking reports the instance as
-- `P#2/plant#1/leaf#17` (the second P of the string). Lintermann and Deussen 1999 build
-- plants from components only; placing them by a grammar is ours.
-- @module lsys.components.mix
local C = require "lsys.components.proto"
local X = require "lsys.components.expand"
local E = require "lsys.components.emit"
local lmodel = require "lsys.model"
local scaling = require("lsys.components.model").scaling

local type, pairs, ipairs, error, tostring, pcall, setmetatable, next, math, string, table,
      utf8 = type, pairs, ipairs, error, tostring, pcall, setmetatable, next, math, string,
      table, utf8
local format, sort = string.format, table.sort
local _ENV = nil

local M = {}

local OPTS = { seed = true, max_instances = true }

local function fail (fmt, ...)
  error("lsys.components.mix: " .. format(fmt, ...), 0)
end

-- {=========================================================================================
-- Emitting a plant with the host's rules

-- The first character from U+0600 that neither the host's view surfaces nor an earlier
-- plant use: the plant's leaf surfaces get fresh ones (each emission numbers its own
-- from U+0101, so two plants would otherwise share characters).
local function freshchar (st, surfaces)
  local k = st.nextchar
  while surfaces[utf8.char(k)] ~= nil do k = k + 1 end
  st.nextchar = k + 1
  return utf8.char(k)
end

-- The emitter's renaming of module names: `~c` surface modules get fresh characters.
local function renaming (rename)
  return function (name)
    local c = name:match("^~(.+)$")
    if c ~= nil and rename[c] ~= nil then return "~" .. rename[c] end
    return name
  end
end

-- The open line contour of the Area primitive (as lsys.components.model gives its plants).
local AREA = { points = { { -1, 0 }, { -1, 0 }, { -0.33, 0 }, { 0.33, 0 }, { 1, 0 },
                          { 1, 0 } }, closed = false }

-- The placed form of plant 'name' for 'seed': { piece = `[@Di(1) plant ]`, tree, owner, n,
-- post }, made once and kept.
local function emitted (st, m, name, seed)
  local key = name .. "\0" .. tostring(seed)
  local e = st.cache[key]
  if e ~= nil then return e end
  local proto = st.plants[name]
  local ok, tree = pcall(X.expand, proto, { seed = seed, max_instances = st.max_instances })
  if not ok then fail("the plant of module '%s': %s", name, tostring(tree)) end
  local view = m.view
  view.surfaces = view.surfaces or {}
  -- surfaces are numbered by the emitter from U+0101 in the order it meets them: rename
  -- each to a fresh character as it appears
  local rename = setmetatable({}, { __index = function (t, c)
    if utf8.len(c) ~= 1 then return nil end
    local cp = utf8.codepoint(c)
    if cp < 0x101 or cp >= 0x600 then return nil end
    local nc = freshchar(st, view.surfaces)
    t[c] = nc
    return nc
  end })
  local out = E.emit(tree, m._rules, nil, renaming(rename), #(view.textures or {}))
  for c, entry in pairs(out.surfaces) do view.surfaces[rename[c] or c] = entry end
  if out.area then
    view.contours = view.contours or {}
    if view.contours[E.AREA] == nil then view.contours[E.AREA] = AREA end
  end
  for _, d in ipairs(out.deformers) do
    if d.proto:param("mode") == "all" then
      fail("the plant of module '%s' has a deformation (%s at %s), which a placed plant " ..
           "does not apply yet; use lsys.components.model for it", name, C.who(d.proto), d.path)
    end
  end
  local piece = m:lstring("[@Di(1)") .. out.lstring .. m:lstring("]")
  e = { piece = piece, tree = tree, owner = out.owner, n = #out.lstring, post = out.post }
  st.cache[key] = e
  return e
end

-- }=========================================================================================

-- {=========================================================================================
-- Placing the plants in a derived string

-- The modules that place plants in s: { i, name, k (its count among its name), scale,
-- seed }, in order.
local function occurrences (st, s)
  local any = false
  for name in pairs(st.plants) do
    if s:count(name) > 0 then any = true end
  end
  if not any then return {} end
  local occ, count = {}, {}
  for i, name, a, b, extra in s:modules() do
    if st.plants[name] ~= nil then
      local scale, seed = a or 1, b or st.seed
      if extra ~= nil then
        fail("module %d %s: %s(scale) or %s(scale, seed) expected, got more parameters", i,
             name, name, name)
      end
      if not (scale > 0 and scale < math.huge) then
        fail("module %d %s: the scale must be a number > 0, got %s", i, name, tostring(scale))
      end
      if math.tointeger(seed) == nil then
        fail("module %d %s: the seed must be a whole number, got %s", i, name, tostring(seed))
      end
      count[name] = (count[name] or 0) + 1
      occ[#occ + 1] = { i = i, name = name, k = count[name], scale = scale,
                        seed = math.tointeger(seed) }
    end
  end
  return occ
end

-- The string s with each plant inserted after the module that places it; fills each
-- occurrence's `start` (the index of its `[` in the result) and `e` (its emitted plant).
local function insert (st, m, s, occ)
  local groups, order = {}, {}
  for _, o in ipairs(occ) do
    o.e = emitted(st, m, o.name, o.seed)
    if groups[o.e] == nil then groups[o.e] = true order[#order + 1] = o.e end
  end
  local done = {}
  for _, g in ipairs(order) do          -- one pass of Lstring:insert per distinct plant
    local pos, shift = {}, 0
    for j, o in ipairs(occ) do
      if o.e == g then pos[#pos + 1] = o.i + 1 + shift end
      if done[j] then shift = shift + #o.e.piece end
    end
    s = s:insert(pos, g.piece)
    for j, o in ipairs(occ) do if o.e == g then done[j] = true end end
  end
  local shift = 0
  for _, o in ipairs(occ) do
    o.start = o.i + 1 + shift
    shift = shift + #o.e.piece
    s:set(o.start + 1, o.scale)        -- @Di(scale)
  end
  return s
end

-- }=========================================================================================

-- {=========================================================================================
-- After the interpretation: non-uniform primitives, in the frame of the turtle at P

-- The world frame of a plant's frame f when the plant starts at the turtle (P, H, L, U)
-- with scale s. A plant is emitted from the turtle's first frame, H0 = +y, U0 = -z,
-- L0 = H0 x U0 = -x: a vector v there is (v.y) H0 + (-v.z) U0 + (-v.x) L0.
local function placed (f, P, H, L, U, s)
  local function w (v)
    return { v[2] * H[1] - v[3] * U[1] - v[1] * L[1], v[2] * H[2] - v[3] * U[2] - v[1] * L[2],
             v[2] * H[3] - v[3] * U[3] - v[1] * L[3] }
  end
  local p = w(f.p)
  return { p = { P[1] + s * p[1], P[2] + s * p[2], P[3] + s * p[3] }, H = w(f.H), U = w(f.U),
           s = 1 }
end

local function finishscene (info, scene)
  for _, o in ipairs(info) do
    if #o.e.post > 0 then
      local P, H, L, U = scene:turtle(o.start + 1)     -- after @Di: where the plant begins
      local off = o.start + 1
      for _, t in ipairs(o.e.post) do
        local mt = scaling(placed(t.frame, P, H, L, U, o.scale), t.sx, t.sy, t.sz)
        scene:transform(mt, { modules = { t.m0 + off, t.m1 + off } })
      end
    end
  end
end

-- }=========================================================================================

--- Makes the L-system model `m` place component plants: `plants` maps module names to
-- component graphs' root prototypes (`{ P = plant }`); opts: `seed` (the expansions' seed
-- when a module gives none, default 1), `max_instances` (as lsys.components.expand). Each
-- module P(s) or P(s, seed) of a derived string is followed by the plant scaled by s
-- (default 1). Chains the model's own `finish` and `after_interpret` hooks (they run
-- first) and sets `m.components.instance(i, s)` for picking. Returns `m`.
function M.place (m, plants, opts)
  if not lmodel.ismodel(m) then
    error(format("lsys.components.mix.place: a model expected, got %s", type(m)), 2)
  end
  if type(plants) ~= "table" or next(plants) == nil then
    error("lsys.components.mix.place: a table of plants expected ({ P = plant })", 2)
  end
  opts = opts or {}
  if type(opts) ~= "table" then
    error("lsys.components.mix.place: an options table expected", 2)
  end
  for k in pairs(opts) do
    if not OPTS[k] then
      error(format("lsys.components.mix.place: unknown option '%s' (known: max_instances, " ..
                   "seed)", tostring(k)), 2)
    end
  end
  if m.components ~= nil then
    error("lsys.components.mix.place: the model already has components; place all its " ..
          "plants in one call", 2)
  end
  local names = {}
  for name, p in pairs(plants) do
    if type(name) ~= "string" then
      error(format("lsys.components.mix.place: plant keys must be module names, got %s",
                   tostring(name)), 2)
    end
    local ok, t = pcall(m.lstring, m, name)
    if not ok or #t ~= 1 or t:module(1) ~= name then
      error(format("lsys.components.mix.place: '%s' is not a module name of %s (declare a " ..
                   "name of several characters with the model's `modules` option)", name,
                   tostring(m)), 2)
    end
    if not C.isproto(p) then
      error(format("lsys.components.mix.place: plant '%s' must be a component prototype " ..
                   "(lsys.components), got %s", name, type(p)), 2)
    end
    names[#names + 1] = name
  end
  sort(names)
  local st = { plants = plants, seed = opts.seed or 1, max_instances = opts.max_instances,
               cache = {}, nextchar = 0x600 }
  local strings = setmetatable({}, { __mode = "k" })    -- placed string -> occurrences
  local finish0, after0 = m.finish, m.after_interpret
  m.finish = function (self, s)
    if finish0 ~= nil then s = finish0(self, s) or s end
    local occ = occurrences(st, s)
    if #occ == 0 then return s end
    local r = insert(st, self, s, occ)
    strings[r] = occ
    return r
  end
  m.after_interpret = function (self, scene, s)
    if after0 ~= nil then after0(self, scene, s) end
    local info = strings[s]
    if info ~= nil then finishscene(info, scene) end
  end
  m.components = {
    plants = names,
    --- The instance that drew module i of the placed string s, and the placing module's
    -- path ("P#2"); nil outside the plants.
    instance = function (i, s)
      local occ = strings[s]
      if occ == nil then return nil end
      local lo, hi = 1, #occ              -- the last occurrence starting before i
      while lo < hi do
        local mid = (lo + hi + 1) // 2
        if occ[mid].start < i then lo = mid else hi = mid - 1 end
      end
      local o = occ[lo]
      if o == nil or i <= o.start + 1 or i > o.start + 1 + o.e.n then return nil end
      return o.e.tree.list[o.e.owner[i - o.start - 1]], format("%s#%d", o.name, o.k)
    end,
  }
  return m
end

return M
