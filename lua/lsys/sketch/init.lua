--- Sketch-based parameterization of L-systems (Anastacio, Prusinkiewicz and Sousa 2009):
-- a sketch of construction lines becomes positional functions, which parameterize a
-- phyllotaxis template, which is an ordinary lsys Model. docs/sketch.md is the reference.
--
--   local sketch = require "lsys.sketch"
--   local sk = sketch.load("plant.json")          -- or a table; options below
--   local f = sk:functions()                       -- Funcs by name
--   local m = sk:model { phyllotaxis = "fibonacci" }
--   sk:save_model("plant.lua")
--
-- The steps (lsys.sketch.geometry, .functions, .templates) are exported for the tests and
-- the sketch window: sketch.geometry, sketch.functions, sketch.templates.
-- @module lsys.sketch
local geometry = require "lsys.sketch.geometry"
local functions = require "lsys.sketch.functions"
local templates = require "lsys.sketch.templates"
local compose = require "lsys.sketch.compose"
local write = require "lsys.sketch.write"
local cpfg = require "lsys.sketch.cpfg"
local model = require "lsys.model"

local type, pairs, ipairs, error, pcall, setmetatable, getmetatable, rawget, tostring,
      require, string, table, math =
      type, pairs, ipairs, error, pcall, setmetatable, getmetatable, rawget, tostring,
      require, string, table, math
local format, concat = string.format, table.concat
local _ENV = nil

local M = {}
M.geometry, M.functions, M.templates = geometry, functions, templates

local Sketch = {}
Sketch.__index = Sketch
M.Sketch = Sketch

local PHYLLOTAXIS = { distichous = true, decussate = true, fibonacci = true }
local LOAD_OPTIONS = { nodes_per_layer = "number", phyllotaxis = "string", depth = "boolean",
                       near = "number", far = "number", resolution = "number",
                       name = "string" }

local function checkn (n, what)
  if type(n) ~= "number" or n ~= math.floor(n) or n < 1 or n > 100000 then
    error(format("%s: nodes_per_layer must be a whole number from 1 to 100000, got %s", what,
                 tostring(n)), 3)
  end
end

local function checkp (p, what)
  if not PHYLLOTAXIS[p] then
    error(format("%s: unknown phyllotaxis '%s' (distichous, decussate or fibonacci)", what,
                 tostring(p)), 3)
  end
end

-- The Debian packages of the Lua libraries the sketch modules load (lsys.sketch.read:
-- cjson for JSON, lxp for SVG; lsys.sketch.organ: cjson for its JSON files).
local PACKAGES = { cjson = "lua-cjson", ["cjson.safe"] = "lua-cjson", lxp = "lua-expat" }

-- `require(name)` for `who`, raising a message that names the missing Debian package.
local function need (name, who, level)
  local ok, mod = pcall(require, name)
  if ok then return mod end
  local msg = tostring(mod)
  local missing = msg:match("module '([^']+)' not found")
  if missing and PACKAGES[missing] then
    msg = format("the Lua library '%s' is missing (install the Debian package %s)", missing,
                 PACKAGES[missing])
  end
  error(format("%s: %s: %s", who, name, msg), level + 1)
end

-- lsys.sketch.read, .organ and .plot as fields, loaded at first use: `require "lsys"` and
-- `require "lsys.sketch"` work without cjson and lxp, and the error comes with the first
-- sketch read.
local LAZY = { read = "lsys.sketch.read", organ = "lsys.sketch.organ",
               plot = "lsys.sketch.plot" }
setmetatable(M, { __index = function (_, k)
  if LAZY[k] then return need(LAZY[k], "lsys.sketch." .. k, 2) end
end })

-- The normalized sketch of a path or a table (lsys.sketch.read).
local function read (src, name)
  local rd = need("lsys.sketch.read", "lsys.sketch.load", 3)
  local ok2, sk
  if type(src) == "string" then ok2, sk = pcall(rd.file, src)
  else ok2, sk = pcall(rd.table, src, name) end
  if not ok2 then error(sk, 3) end
  return sk
end

--- Loads a sketch from a file (JSON or SVG) or a table in the sketch file's form.
-- opts: nodes_per_layer, phyllotaxis (override the file's), depth (true: 3D stem from the
-- pressure, false: 2D, nil: 3D when the stem's pressure is not 0.5 everywhere), near, far
-- (the depths of pressure 1 and 0, in stem lengths; default +0.3 and -0.3), resolution
-- (the longest straight piece of the drawn stem, in stem lengths; 1/32), name.
function M.load (src, opts)
  opts = opts or {}
  if type(src) ~= "string" and type(src) ~= "table" then
    error("lsys.sketch.load: a file name or a sketch table expected", 2)
  end
  if type(opts) ~= "table" then error("lsys.sketch.load: an options table expected", 2) end
  for k, v in pairs(opts) do
    local t = LOAD_OPTIONS[k]
    if not t then error(format("lsys.sketch.load: unknown option '%s'", tostring(k)), 2) end
    if type(v) ~= t then
      error(format("lsys.sketch.load: option '%s' must be a %s", k, t), 2)
    end
  end
  local sk = read(src, opts.name)
  local self = setmetatable({ data = sk, file = sk.file, depth = opts.depth,
    near = opts.near, far = opts.far, resolution = opts.resolution or functions.RESOLUTION,
  }, Sketch)
  local n = opts.nodes_per_layer or sk.nodes_per_layer or 3
  checkn(n, "lsys.sketch.load")
  local p = opts.phyllotaxis or sk.phyllotaxis or "distichous"
  checkp(p, "lsys.sketch.load")
  self.nodes_per_layer, self.phyllotaxis = n, p
  return self
end

function Sketch:__tostring ()
  return format("lsys.Sketch: %s, %d strokes, %d nodes per layer, %s", self.file or "table",
                #self.data.strokes, self.nodes_per_layer, self.phyllotaxis)
end

--- Sets the number of nodes per layer (§3.3); the functions are computed again.
function Sketch:set_nodes_per_layer (n)
  checkn(n, "set_nodes_per_layer")
  self.nodes_per_layer, self._an, self._fn = n, nil, nil
end

--- Sets the phyllotaxis of the models made from now on (§5).
function Sketch:set_phyllotaxis (p)
  checkp(p, "set_phyllotaxis")
  self.phyllotaxis = p
end

-- The analysis for a depth choice (nil: from the pressure), cached.
function Sketch:_analysis (depth, n)
  n = n or self.nodes_per_layer
  if depth == nil then depth = self.depth end
  local key = format("%s:%d", tostring(depth), n)
  if self._an and self._an.key == key then return self._an.value end
  local an = geometry.analyze(self.data, { nodes_per_layer = n, depth = depth,
                                           near = self.near, far = self.far })
  self._an, self._fn = { key = key, value = an }, nil
  return an
end

-- The functions, their polylines and the stem's pieces, cached with the analysis.
function Sketch:_functions (depth, n)
  local an = self:_analysis(depth, n)
  if self._fn and self._fn.an == an then return self._fn end
  local F, P, pieces = functions.build(geometry, an, self.resolution)
  self._fn = { an = an, F = F, P = P, pieces = pieces }
  return self._fn
end

--- The intermediate geometry (docs/sketch.md, "The pipeline").
function Sketch:analysis (opts)
  opts = opts or {}
  return self:_analysis(opts.depth, opts.nodes_per_layer)
end

--- The positional functions (§4): { internode, stem_shape | yaw, pitch, angle_left,
-- angle_right, size_left, size_right }, Funcs of the relative position x in [0, 1].
function Sketch:functions (opts)
  opts = opts or {}
  local fn = self:_functions(opts.depth, opts.nodes_per_layer)
  local out = {}
  for k, f in pairs(fn.F) do out[k] = f end
  return out
end

--- The control points of the functions: { name = {{x, y}, ...} } (the polylines, before
-- their interior vertices are tripled).
function Sketch:function_points (opts)
  opts = opts or {}
  local fn = self:_functions(opts.depth, opts.nodes_per_layer)
  return fn.P
end

local MODEL_OPTIONS = { phyllotaxis = "string", nodes_per_layer = "number", organ = true,
  steps = "number", depth = "boolean", width = "number", color = "number",
  organ_color = "number", name = "string", view = "table" }

local function isSketch (x) return getmetatable(x) == Sketch end
M.issketch = isSketch

-- The generated description of a model: { axiom, productions (lines), homomorphism (lines),
-- sub, env (name -> Func or number), funcs (name -> polyline), steps, view, modules, origin }.
function Sketch:_spec (o, prefix)
  local ph = o.phyllotaxis or self.phyllotaxis
  checkp(ph, "model")
  local n = o.nodes_per_layer or self.nodes_per_layer
  checkn(n, "model")
  local fn = self:_functions(o.depth, n)
  local an = fn.an
  local first = an.nodes[1].x <= 0
  local t = templates.rules { phyllotaxis = ph, threed = an.threed, prefix = prefix,
                              first = first }
  local env, funcs = {}, {}
  for k, f in pairs(fn.F) do env[prefix .. k], funcs[prefix .. k] = f, fn.P[k] end
  -- XT: half the shortest internode below P_n; XE: as far below the tip
  local dmin = math.huge
  for i = 1, #fn.pieces.stops - 1 do
    local d = fn.pieces.stops[i + 1] - fn.pieces.stops[i]
    if d > 0 and d < dmin then dmin = d end
  end
  local top = an.nodes[#an.nodes].x
  env[prefix .. "XT"] = top - dmin / 2
  env[prefix .. "XE"] = 1 - dmin / 2
  env[prefix .. "D"] = fn.pieces.resolution
  -- steps: one per stop, the halvings of the longest piece, two for the organs
  local halvings = 0
  for i = 1, #fn.pieces.stops - 1 do
    local d, k = fn.pieces.stops[i + 1] - fn.pieces.stops[i], 0
    while d > fn.pieces.resolution do d, k = d / 2, k + 1 end
    if k > halvings then halvings = k end
  end
  return { axiom = t.axiom, productions = t.productions, env = env, funcs = funcs,
           steps = #fn.pieces.stops + halvings + 2, threed = an.threed, phyllotaxis = ph,
           nodes_per_layer = n, analysis = an }
end

--- An lsys Model of the sketch (§5): the template of the phyllotaxis with the sketch's
-- functions. opts: phyllotaxis, nodes_per_layer (for this model), organ (nil: a flat leaf;
-- "~X": the view's surface X, scaled by the organ size; a Sketch, or a Model made by
-- sk:model: that plant as the organ, §7.2), steps (default: enough to finish the plant),
-- depth (true/false: force a 3D/2D stem), width (stem diameter in stem lengths, 0.01),
-- color (stem colour index, 1), organ_color (2), name, view (more view options).
function Sketch:model (opts)
  opts = opts or {}
  if type(opts) ~= "table" then error("model: an options table expected", 2) end
  for k, v in pairs(opts) do
    local t = MODEL_OPTIONS[k]
    if not t then error(format("model: unknown option '%s'", tostring(k)), 2) end
    if t ~= true and type(v) ~= t then
      error(format("model: option '%s' must be a %s", k, t), 2)
    end
  end
  local ok, d = pcall(self._describe, self, opts)
  if not ok then error(d, 2) end
  local ok2, m = pcall(model.lsystem, d.options)
  if not ok2 then error(m, 2) end
  m.sketch = { sketch = self, description = d }
  return m
end

-- "organ" for an Organ of lsys.sketch.organ, "surface" for an lsys.Surface, else nil.
local function surfacekind (o)
  local mt = getmetatable(o)
  local name = type(mt) == "table" and rawget(mt, "__name")
  if name == "lsys.Organ" and type(o) == "table" then return "organ" end
  if name == "lsys.Surface" and type(o) == "userdata" then return "surface" end
  return nil
end

-- The organ's homomorphism line, and for a composed organ its sub-L-system spec.
local function organ (opts)
  local o, color = opts.organ, opts.organ_color or 2
  if o == nil then return templates.leaf(color) end
  if type(o) == "string" then
    local name = o:match("^~(%a)$")
    if not name then error(format("model: organ '%s': expected '~X', a surface name", o), 0) end
    return format("Organ(h) --> ;(%d) ~%s(h)", color, name)
  end
  local inner = isSketch(o) and o or
                (type(o) == "table" and type(o.sketch) == "table" and o.sketch.sketch)
  if isSketch(inner) then return nil, inner end
  if surfacekind(o) then return nil, nil, o end
  error("model: organ must be nil, '~X', an organ (lsys.sketch.organ), an lsys.Surface, " ..
        "a Sketch or a Model made from a sketch", 0)
end

-- Everything lsys.lsystem needs, and the parts save_model writes.
function Sketch:_describe (opts)
  local d = self:_spec(opts, "")
  local color, width = opts.color or 1, opts.width or 0.01
  local homo, inner, surface = organ(opts)
  local sub, productions = nil, d.productions
  local steps = d.steps
  if inner then
    -- §7.2: the inner plant is a sub-L-system (cpfg's ?(id, scale) ... $) started at each
    -- organ, scaled by the organ size; its functions and constants are renamed (o1_...)
    -- and its stem is 2D (its yaw and pitch would be in the global frame, not the organ's)
    local io_ = inner:_spec({ depth = false, phyllotaxis = opts.organ.sketch and
                              opts.organ.sketch.description.phyllotaxis or nil }, "o1_")
    productions = {}
    for _, l in ipairs(d.productions) do productions[#productions + 1] = l end
    productions[#productions + 1] = format("Organ(h) --> ?(1, h) %s $", io_.axiom)
    for k, v in pairs(io_.env) do d.env[k] = v end
    for k, v in pairs(io_.funcs) do d.funcs[k] = v end
    sub = { [1] = { productions = io_.productions } }
    steps = steps + io_.steps
    -- the inner plant's organs as that Model draws them (its leaf, its "~X" -- the view
    -- must then have X -- or its organ surface); a Sketch's: the default leaf
    local idesc = type(opts.organ) == "table" and type(opts.organ.sketch) == "table"
                  and opts.organ.sketch.description
    homo = idesc and idesc.homomorphism[1] or templates.leaf(opts.organ_color or 2)
    if idesc and idesc.surfaces then surface = idesc.surfaces.P end
    d.inner = io_
  elseif surface then
    homo = "Organ(h) --> ;(" .. (opts.organ_color or 2) .. ") ~P(h)"
  end
  d.surfaces = surface and { P = surface } or nil
  d.homomorphism = { homo }
  local view = { line_style = "cylinder", line_width = width, color = color }
  if surface then view.surfaces = { P = surface } end
  for k, v in pairs(opts.view or {}) do view[k] = v end
  d.view = view
  d.steps = opts.steps or steps
  d.modules = "Organ"
  d.plants = { { phyllotaxis = d.phyllotaxis, nodes_per_layer = d.nodes_per_layer,
                 suffix = "", file = self.file } }
  d.options = { axiom = d.axiom, productions = productions, homomorphism = d.homomorphism,
                sub = sub, modules = d.modules, env = d.env, steps = d.steps, view = view,
                name = opts.name or (self.file and self.file:match("([^/]*)$")) }
  d.productions = productions
  d.sub = sub
  return d
end

--- The rules text of a template (2D unless threed), to read.
function M.template (name, threed)
  checkp(name, "lsys.sketch.template")
  return templates.text(name, threed)
end

--- Writes a Lua model file that builds the same Model (docs/sketch.md, "Models from
-- sketches"): the functions inline as control points, the rules as text. opts as
-- sk:model; an organ of lsys.sketch.organ is written beside it as a cpfg surface file
-- (plant.lua: plant.organ.s), which the model file reads from its own folder.
function Sketch:save_model (path, opts)
  opts = opts or {}
  if type(path) ~= "string" then error("save_model: a file name expected", 2) end
  local ok, d = pcall(self._describe, self, opts)
  if not ok then error(d, 2) end
  local okw, err = pcall(write.lua, d, path, "save_model")
  if not okw then error(err, 2) end
  return path
end

-- The description of a Model made by sk:model or lsys.sketch.compose, or raises for `who`.
local function description (m, who)
  local d = type(m) == "table" and type(m.sketch) == "table" and m.sketch.description
  if type(d) ~= "table" then
    error(format("%s: a Model made by sk:model or lsys.sketch.compose expected, got %s", who,
                 type(m) == "table" and (m.name and "the model '" .. tostring(m.name) .. "'"
                 or "a table") or type(m)), 3)
  end
  return d
end

--- Composes Models made by sk:model into one that draws them on one stem (§7.2;
-- lsys.sketch.compose): `models` is a list of two or more; the first draws its stem,
-- the others' names take the suffixes 2, 3, ... and their stems move without drawing.
-- opts: name, view (more view options).
function M.compose (models, opts)
  opts = opts or {}
  if type(models) ~= "table" or #models < 2 then
    error("lsys.sketch.compose: a list of two or more sketch Models expected", 2)
  end
  if type(opts) ~= "table" then error("lsys.sketch.compose: an options table expected", 2) end
  for k, v in pairs(opts) do
    if k ~= "name" and k ~= "view" then
      error(format("lsys.sketch.compose: unknown option '%s' (name, view)", tostring(k)), 2)
    end
    if k == "view" and type(v) ~= "table" or k == "name" and type(v) ~= "string" then
      error(format("lsys.sketch.compose: option '%s' must be a %s", k,
                   k == "view" and "table" or "string"), 2)
    end
  end
  local descs, files = {}, {}
  for i, m in ipairs(models) do
    local d = description(m, format("lsys.sketch.compose: models[%d]", i))
    if #d.plants > 1 then
      error(format("lsys.sketch.compose: models[%d] is a composition already; compose " ..
                   "the plants it was made of", i), 2)
    end
    descs[i], files[i] = d, d.plants[1].file
  end
  local names = {}
  for i, m in ipairs(models) do names[i] = m.name or ("plant " .. i) end
  local ok, d = pcall(compose.describe, descs, { name = opts.name or concat(names, " + "),
                                                  view = opts.view }, files)
  if not ok then error("lsys.sketch." .. tostring(d), 2) end
  local ok2, m = pcall(model.lsystem, d.options)
  if not ok2 then error(m, 2) end
  m.sketch = { composed = models, description = d }
  return m
end

--- Writes the Lua model file of a Model made by sk:model or lsys.sketch.compose (as
-- sk:save_model writes a sketch's).
function M.save_model (m, path)
  local d = description(m, "lsys.sketch.save_model")
  if type(path) ~= "string" then error("lsys.sketch.save_model: a file name expected", 2) end
  local ok, err = pcall(write.lua, d, path, "lsys.sketch.save_model")
  if not ok then error(err, 2) end
  return path
end

--- Writes the sketch's plant as a cpfg model (docs/sketch.md, "cpfg and L-studio"):
-- `path` (a .l file), the view file, the function files, a colour map and the organ
-- surfaces beside it. opts as sk:model. Returns the list of files written and the number
-- of function readings cpfg cannot tell apart from their neighbours (0 but for very dense
-- nodes).
function Sketch:save_cpfg (path, opts)
  opts = opts or {}
  if type(path) ~= "string" then error("save_cpfg: a file name expected", 2) end
  local ok, d = pcall(self._describe, self, opts)
  if not ok then error(d, 2) end
  local okw, files, inexact = pcall(cpfg.write, d, path, "save_cpfg")
  if not okw then error(files, 2) end
  return files, inexact
end

--- Writes a Model made by sk:model or lsys.sketch.compose as a cpfg model (as
-- sk:save_cpfg writes a sketch's).
function M.save_cpfg (m, path)
  local d = description(m, "lsys.sketch.save_cpfg")
  if type(path) ~= "string" then error("lsys.sketch.save_cpfg: a file name expected", 2) end
  local ok, files, inexact = pcall(cpfg.write, d, path, "lsys.sketch.save_cpfg")
  if not ok then error(files, 2) end
  return files, inexact
end

--- Writes the sketch to a file (lsys.sketch.read's save: JSON).
function Sketch:save (path)
  local rd = need("lsys.sketch.read", "save", 2)
  local ok, err = pcall(rd.save, self.data, path)
  if not ok then error(err, 2) end
  return path
end

return M
