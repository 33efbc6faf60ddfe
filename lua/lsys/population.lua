--- Many plants in one scene (docs/population.md): `lsys.population(plants [, opts])`.
--
-- Each plant is a model (or a Scene, or an Lstring) placed by a translation, a rotation and
-- a scale. Plants of the same model with the same seed, steps, env, Lstring and view are
-- one prototype: derived and interpreted once, their geometry held once in the scene, and
-- each plant an instance of it (a transform: csrc/core/population.h). The result is an
-- lsys.Scene that lsys.render, scene:save and lsys.show take as they take any scene.
-- @module lsys.population
local core = require "lsys.core"
local model = require "lsys.model"
local view = require "lsys.view"

local type, pairs, ipairs, error, pcall, tostring, setmetatable, getmetatable, rawequal =
      type, pairs, ipairs, error, pcall, tostring, setmetatable, getmetatable, rawequal
local math, string, table = math, string, table
local format = string.format
local _ENV = nil

local M = {}

-- The fields of a plant, and the options of a population.
local ENTRY = { model = true, lstring = true, at = true, rotate = true, scale = true,
                seed = true, steps = true, env = true, view = true }
local ENTRY_LIST = "model, lstring, at, rotate, scale, seed, steps, env, view"
local OPTS = { view = true, records = true, progress = true, count = true, place = true }

--- The most plants one population may have.
M.MAX_PLANTS = 100000000

-- What the population holds besides its scene, for the memory budget: the
-- bytes of a Lua array of k slots (16 a value, the slots a power of 2), a plant's instance
-- in the scene (lsys_instance: 16 floats and a part), and the tables and key string of a
-- prototype with its entry (measured with collectgarbage("count"): about 800 bytes and the
-- key's length).
local function arraybytes (k)
  local c = 1
  while c < k do c = c * 2 end
  return k > 0 and 16 * c or 0
end
local INSTANCE, PROTOTYPE = 68, 800

-- Sizes as the core writes them (lsys_common_fmtsize).
local function fmtsize (b)
  if b >= 2 ^ 63 then return "no limit" end
  if b >= 2 ^ 30 then return format("%.1f GiB", b / 2 ^ 30) end
  if b >= 2 ^ 20 then return format("%.0f MiB", b / 2 ^ 20) end
  if b >= 2 ^ 10 then return format("%.0f KiB", b / 2 ^ 10) end
  return format("%d bytes", b)
end

-- Errors found here are raised as FAIL objects and turned into the message of
-- lsys.population at its level; errors of the models themselves pass through with the
-- plant named.
local FAIL = {}
local function fail (fmt, ...) error(setmetatable({ msg = format(fmt, ...) }, FAIL), 0) end

local function isnum (x) return type(x) == "number" and x == x and x > -math.huge and
                                x < math.huge end

local function show (x)
  if type(x) == "number" then return format("%.14g", x) end
  if type(x) == "string" then return format("%q", x) end
  return type(x)
end

-- ---------------------------------------------------------------------------
-- transforms: M = T R S, as 12 numbers (the images of the axes, then the translation)

local function vec3 (v, where, field)
  if type(v) ~= "table" or #v ~= 3 or not (isnum(v[1]) and isnum(v[2]) and isnum(v[3])) then
    fail("%s: '%s' must be a list of 3 finite numbers {x, y, z}, got %s", where, field,
         type(v) ~= "table" and show(v) or #v ~= 3 and format("%d numbers", #v) or
         format("{%s, %s, %s}", show(v[1]), show(v[2]), show(v[3])))
  end
  return v[1], v[2], v[3]
end

-- The rotation by `deg` degrees about the unit axis (x, y, z) (right-handed), by rows.
local function axisangle (x, y, z, deg)
  local a = deg * math.pi / 180
  local c, s = math.cos(a), math.sin(a)
  local t = 1 - c
  return { { t * x * x + c, t * x * y - s * z, t * x * z + s * y },
           { t * x * y + s * z, t * y * y + c, t * y * z - s * x },
           { t * x * z - s * y, t * y * z + s * x, t * z * z + c } }
end

-- A rotation given by rows: orthonormal with determinant 1, within 1e-4.
local function checkrows (r, where)
  local bad = #r ~= 3
  for i = 1, 3 do
    local row = r[i]
    if bad or type(row) ~= "table" or #row ~= 3 then bad = true; break end
    for j = 1, 3 do if not isnum(row[j]) then bad = true end end
  end
  if bad then
    fail("%s: 'rotate' must be a number of degrees, { axis = {x, y, z}, angle = degrees } or "
         .. "a 3 x 3 rotation matrix (a list of 3 rows)", where)
  end
  for i = 1, 3 do
    for j = i, 3 do
      local d = 0
      for k = 1, 3 do d = d + r[i][k] * r[j][k] end
      if math.abs(d - (i == j and 1 or 0)) > 1e-4 then
        fail("%s: 'rotate' is not a rotation: its rows must be orthonormal", where)
      end
    end
  end
  local det = r[1][1] * (r[2][2] * r[3][3] - r[2][3] * r[3][2])
            - r[1][2] * (r[2][1] * r[3][3] - r[2][3] * r[3][1])
            + r[1][3] * (r[2][1] * r[3][2] - r[2][2] * r[3][1])
  if det < 0 then fail("%s: 'rotate' is a mirror (determinant -1), not a rotation", where) end
  return r
end

-- The rotation of a plant by rows: about +y (the turtle's first heading, up) by a number
-- of degrees, about an axis, or a matrix.
local function rotation (rot, where)
  if rot == nil then return nil end
  if type(rot) == "number" then
    if not isnum(rot) then fail("%s: 'rotate' must be a finite number of degrees", where) end
    return axisangle(0, 1, 0, rot)
  end
  if type(rot) ~= "table" then
    fail("%s: 'rotate' must be a number of degrees, { axis = {x, y, z}, angle = degrees } or "
         .. "a 3 x 3 rotation matrix, got %s", where, show(rot))
  end
  if rot.axis ~= nil or rot.angle ~= nil then
    for k in pairs(rot) do
      if k ~= "axis" and k ~= "angle" then
        fail("%s: 'rotate' has an unknown field '%s' (axis, angle)", where, tostring(k))
      end
    end
    local x, y, z = vec3(rot.axis, where, "rotate.axis")
    local len = math.sqrt(x * x + y * y + z * z)
    if len == 0 then fail("%s: 'rotate.axis' must not be the zero vector", where) end
    if not isnum(rot.angle) then
      fail("%s: 'rotate.angle' must be a finite number of degrees, got %s", where,
           show(rot.angle))
    end
    return axisangle(x / len, y / len, z / len, rot.angle)
  end
  return checkrows(rot, where)
end

local function scales (sc, where)
  if sc == nil then return 1, 1, 1 end
  if isnum(sc) and sc > 0 then return sc, sc, sc end
  if type(sc) == "table" and #sc == 3 then
    local ok = true
    for i = 1, 3 do ok = ok and isnum(sc[i]) and sc[i] > 0 end
    if ok then return sc[1], sc[2], sc[3] end
  end
  fail("%s: 'scale' must be a positive number or a list of 3 positive numbers, got %s", where,
       type(sc) == "table" and "a table" or show(sc))
end

-- The transform of entry e as 12 numbers appended to `out` at `at`.
local function transform (e, where, out, at)
  local tx, ty, tz = 0, 0, 0
  if e.at ~= nil then tx, ty, tz = vec3(e.at, where, "at") end
  local r = rotation(e.rotate, where)
  local sx, sy, sz = scales(e.scale, where)
  local s = { sx, sy, sz }
  for j = 1, 3 do                          -- column j: R's column j times s_j
    for i = 1, 3 do
      out[at + 3 * (j - 1) + i] = (r and r[i][j] or (i == j and 1 or 0)) * s[j]
    end
  end
  out[at + 10], out[at + 11], out[at + 12] = tx, ty, tz
end

--- The transform of plant `e` (its at, rotate and scale, as the population places it): 12
-- numbers, the 3 x 3 matrix by columns then the translation; raises naming `where`.
function M.transform (e, where)
  local out = {}
  local ok, err = pcall(transform, e, where, out, 0)
  if not ok then error(getmetatable(err) == FAIL and err.msg or err, 0) end
  return out
end

-- ---------------------------------------------------------------------------
-- prototypes: what makes two plants the same

-- A canonical text of a value for the prototype key: numbers exactly, tables by sorted
-- keys, functions and userdata (and tables at `depth` 16) by identity (ids: the objects
-- of this call).
local function canon (x, ids, depth)
  local t = type(x)
  if t == "number" then return format("%.17g", x)
  elseif t == "string" then return format("%q", x)
  elseif t == "boolean" or t == "nil" then return tostring(x)
  elseif t == "table" and depth < 16 then
    local keys = {}
    for k in pairs(x) do keys[#keys + 1] = k end
    table.sort(keys, function (a, b)
      local ta, tb = type(a), type(b)
      if ta ~= tb then return ta < tb end
      if ta == "number" or ta == "string" then return a < b end
      return canon(a, ids, depth + 1) < canon(b, ids, depth + 1)
    end)
    local parts = {}
    for i, k in ipairs(keys) do
      parts[i] = canon(k, ids, depth + 1) .. "=" .. canon(x[k], ids, depth + 1)
    end
    return "{" .. table.concat(parts, ",") .. "}"
  end
  local id = ids[x]
  if id == nil then
    ids.n = ids.n + 1
    id = ids.n
    ids[x] = id
  end
  return "@" .. id
end

local function checkentry (e, where)
  if type(e) ~= "table" then fail("%s: a table expected, got %s", where, show(e)) end
  for k in pairs(e) do
    if not ENTRY[k] then
      fail("%s: unknown field '%s' (%s)", where, tostring(k), ENTRY_LIST)
    end
  end
  local m = e.model
  if m == nil then fail("%s: 'model' is missing (a Model, a Scene or an Lstring)", where) end
  local ismodel = model.ismodel(m)
  if not (ismodel or model.isscene(m) or model.islstring(m)) then
    fail("%s: 'model' must be a Model, a Scene or an Lstring, got %s", where, show(m))
  end
  if model.isscene(m) and m.ninstances > 0 then
    fail("%s: 'model' is a population; a plant must be one plant", where)
  end
  if not ismodel then
    for _, k in ipairs { "lstring", "seed", "steps", "env" } do
      if e[k] ~= nil then
        fail("%s: '%s' needs a Model ('model' is %s, drawn as it is)", where, k,
             model.isscene(m) and "a Scene" or "an Lstring")
      end
    end
    if model.isscene(m) and e.view ~= nil then
      fail("%s: 'view' needs a Model or an Lstring ('model' is a Scene, drawn as it is)", where)
    end
  end
  if e.seed ~= nil and not (isnum(e.seed) and e.seed == math.floor(e.seed)) then
    fail("%s: 'seed' must be an integer, got %s", where, show(e.seed))
  end
  if e.steps ~= nil and not (isnum(e.steps) and e.steps >= 0 and e.steps == math.floor(e.steps))
  then
    fail("%s: 'steps' must be a whole number >= 0, got %s", where, show(e.steps))
  end
  if e.env ~= nil and type(e.env) ~= "table" then
    fail("%s: 'env' must be a table of names, got %s", where, show(e.env))
  end
  if e.view ~= nil and type(e.view) ~= "table" then
    fail("%s: 'view' must be a view table, got %s", where, show(e.view))
  end
  if e.lstring ~= nil and not model.islstring(e.lstring) and type(e.lstring) ~= "string" then
    fail("%s: 'lstring' must be an Lstring or its text, got %s", where, show(e.lstring))
  end
end

-- The prototype of a plant: its model and Lstring by identity, the rest by value.
local function key (e, ids)
  return table.concat({ canon(e.model, ids, 16), canon(e.lstring, ids, 16),
                        canon(e.seed, ids, 0), canon(e.steps, ids, 0), canon(e.env, ids, 0),
                        canon(e.view, ids, 0) }, "|")
end

-- The plain turtle for Lstrings no model owns.
local plain

-- The scene of prototype entry e (and the Lstring it drew), interpreted with `records`.
local function interpret (e, records)
  local m, over = e.model, e.view
  if not records then
    over = view.merge(over, nil)
    over.records = false
  end
  if model.isscene(m) then return m, m.lstring end
  if model.islstring(m) then
    local owner = model.owner(m)
    if owner == nil then
      plain = plain or model.lsystem { axiom = "", name = "plain turtle" }
      owner = plain
    end
    return owner:interpret(m, over), m
  end
  local seed, env = m.seed, m.env
  if e.seed ~= nil then m.seed = e.seed end
  if e.env ~= nil then
    local merged = {}
    for k, x in pairs(env or {}) do merged[k] = x end
    for k, x in pairs(e.env) do merged[k] = x end
    m.env = merged
  end
  local ok, sc, s = pcall(function ()
    local s = e.lstring or m:derive(e.steps)
    if type(s) == "string" then s = m:lstring(s) end
    return m:interpret(s, over), s
  end)
  m.seed, m.env = seed, env
  if not ok then error(sc, 0) end
  return sc, s
end

-- ---------------------------------------------------------------------------
-- the population

-- The options from opts and the hash part of spec (either may give them).
local function options (spec, opts)
  if opts ~= nil and type(opts) ~= "table" then
    fail("the options must be a table, got %s", show(opts))
  end
  local o = {}
  for _, t in ipairs { spec, opts or {} } do
    for k, x in pairs(t) do
      if type(k) ~= "number" or k ~= math.floor(k) or k < 1 then
        if not OPTS[k] then
          fail("unknown option '%s' (view, records, progress, count, place)", tostring(k))
        end
        if o[k] ~= nil then fail("option '%s' is given twice", k) end
        o[k] = x
      end
    end
  end
  if o.progress ~= nil and type(o.progress) ~= "function" then
    fail("option 'progress' must be a function (phase, k, n)")
  end
  if o.records ~= nil and type(o.records) ~= "boolean" then
    fail("option 'records' must be a boolean")
  end
  if o.view ~= nil and type(o.view) ~= "table" then fail("option 'view' must be a table") end
  for k in pairs(o.view or {}) do
    if view.TURTLE[k] then
      fail("view.%s changes how the plants are drawn: give it in a plant's view", k)
    end
  end
  return o
end

-- The plants: a list, or count and place. Returns n and a function giving plant i.
local function plants (spec, o)
  local n = #spec
  if o.count ~= nil or o.place ~= nil then
    if n > 0 then fail("give a list of plants or count and place, not both") end
    if not (isnum(o.count) and o.count >= 0 and o.count == math.floor(o.count)) then
      fail("'count' must be a whole number >= 0, got %s", show(o.count))
    end
    if type(o.place) ~= "function" then
      fail("'place' must be a function (i) returning a plant, got %s", show(o.place))
    end
    n = o.count
    local place = o.place
    return n, function (i)
      local ok, e = pcall(place, i)
      if not ok then
        if getmetatable(e) == FAIL then error(e, 0) end
        fail("place(%d): %s", i, tostring(e))
      end
      return e, format("place(%d)", i)
    end
  end
  return n, function (i) return spec[i], format("plant %d", i) end
end

-- Builds the population; raises FAIL objects or the models' own errors.
local function build (spec, opts)
  if type(spec) ~= "table" then
    fail("a list of plants or { count = N, place = function (i) ... end } expected, got %s",
         show(spec))
  end
  local o = options(spec, opts)
  local n, get = plants(spec, o)
  if n > M.MAX_PLANTS then fail("%d plants: more than the limit of %d", n, M.MAX_PLANTS) end
  -- the plants' tables (which, xf) and instances, and the prototypes' tables as they come,
  -- within the memory budget before they are built
  local budget = core.max_memory()
  local held = arraybytes(n) + arraybytes(12 * n)
  if held + INSTANCE * n > budget then
    fail("%d plants need %s, more than max_memory (%s)", n, fmtsize(held + INSTANCE * n),
         fmtsize(budget))
  end
  local records = o.records ~= false
  local progress = o.progress
  -- 1: every plant checked, its prototype found, its transform computed
  local ids, byid, protos = { n = 0 }, {}, {}
  local which, xf = {}, {}
  for i = 1, n do
    local e, where = get(i)
    checkentry(e, where)
    local k = key(e, ids)
    local p = byid[k]
    if p == nil then
      held = held + PROTOTYPE + #k
      if held + INSTANCE * n > budget then
        fail("%s makes prototype %d: the plants and their prototypes need more than "
             .. "max_memory (%s)", where, #protos + 1, fmtsize(budget))
      end
      protos[#protos + 1] = { entry = e, where = where, first = i }
      p = #protos
      byid[k] = p
    end
    which[i] = p
    transform(e, where, xf, 12 * (i - 1))
  end
  -- 2: each prototype derived, interpreted and added
  local vok, v = pcall(view.normalize, o.view or {}, "lsys.population")
  if not vok then fail("%s", (tostring(v):gsub("^lsys%.population: ", ""))) end
  local state = view.render_options(v)     -- the look, and what the scene keeps
  state.view, state.textures, state.prototypes = v, {}, {}
  local pop = core.population(state)
  for p, proto in ipairs(protos) do
    local ok, sc, s = pcall(interpret, proto.entry, records)
    if not ok then error(format("%s (prototype %d): %s", proto.where, p, tostring(sc)), 0) end
    local aok, aerr = pcall(core.population_add, pop, sc, records, n, held)
    if not aok then fail("%s", (tostring(aerr):gsub("^.-lsys%.population: ", ""))) end
    local e = proto.entry
    state.prototypes[p] = {
      model = model.ismodel(e.model) and e.model or nil, seed = e.seed, steps = e.steps,
      env = e.env, view = e.view, lstring = records and s or nil, plant = proto.first,
    }
    state.contour_sides = state.contour_sides or (model.sceneview(sc) or {}).contour_sides
    if not rawequal(sc, e.model) then getmetatable(sc).__close(sc) end
    if progress then progress("prototype", p, #protos) end
  end
  -- 3: the plants placed
  for i = 1, n do
    local a = 12 * (i - 1)
    core.population_place(pop, which[i], xf[a + 1], xf[a + 2], xf[a + 3], xf[a + 4],
                          xf[a + 5], xf[a + 6], xf[a + 7], xf[a + 8], xf[a + 9], xf[a + 10],
                          xf[a + 11], xf[a + 12])
    if progress and (i % 1000 == 0 or i == n) then progress("place", i, n) end
  end
  v.textures = state.textures
  return pop
end

--- A scene of many plants (docs/population.md). `plants` is a list of plants, or
-- { count = N, place = function (i) return plant end }; a plant is { model = (a Model, a
-- Scene or an Lstring), at = {x, y, z}, rotate = (degrees about +y, { axis = {x, y, z},
-- angle = degrees } or a 3 x 3 rotation matrix by rows), scale = (a positive number or
-- {sx, sy, sz} along the plant's own axes), seed =, steps =, env = (over the model's),
-- lstring = (drawn instead of deriving), view = (view fields for drawing it) }. Plants
-- alike (same model, lstring, seed, steps, env and view) share one prototype. opts (or
-- the same keys in `plants`): `view` (how the scene is looked at: camera, light,
-- background, supersample), `records` (false: no turtle records nor Lstrings kept: less
-- memory, nothing to pick), `progress(phase, k, n)` ("prototype": k of n made; "place":
-- k of n plants placed). Returns an lsys.Scene; raises naming the plant and field.
function M.population (spec, opts)
  local ok, r = pcall(build, spec, opts)
  if ok then return r end
  if getmetatable(r) == FAIL then r = r.msg end
  error("lsys.population: " .. tostring(r), 2)
end

return M
