--- lsys: L-systems for plant modelling (docs/manual.md).
-- `local lsys = require "lsys"`
--
-- This file gathers the library's functions; they live in lsys.model (models, the memory
-- budget), lsys.view (view options), lsys.viewer (the window, loaded at first use) and
-- lsys.arrange. None of those requires this file, so the requires form no cycle.
-- @module lsys
local core = require "lsys.core"
local model = require "lsys.model"
local func = require "lsys.func"
local view = require "lsys.view"
local warning = require "lsys.warning"
local population = require "lsys.population"

local type, pairs, ipairs, error, setmetatable, getmetatable, rawget, tostring, pcall, string,
      debug, next, package, _G =
      type, pairs, ipairs, error, setmetatable, getmetatable, rawget, tostring, pcall, string,
      debug, next, package, _G
local format = string.format
local _ENV = nil

local M = {}
--- Parses cpfg text notation into an Lstring; `names` declares
-- multi-character module names ("Apex Leaf").
function M.lstring (text, names)
  if (names == nil or names == "") and type(text) ~= "string" then
    error(format("lsys.lstring: the text must be a string, got %s", type(text)), 2)
  end
  if names == nil or names == "" then
    local ok, s = pcall(core.lstring, text)
    if not ok then error((tostring(s):gsub("^lstring: ", "lsys.lstring: ")), 2) end
    return s
  end
  if type(text) ~= "string" then
    error(format("lsys.lstring: the text must be a string, got %s", type(text)), 2)
  end
  if type(names) ~= "string" then
    error(format("lsys.lstring: the names must be a string (\"Apex Leaf\"), got %s",
                 type(names)), 2)
  end
  local s, msg, pos = core.rules(names):lstring(text)
  if not s then error(format("lsys.lstring: %s at character %d", msg, pos), 2) end
  return s
end
M.produce = core.produce
M.nproduce = core.nproduce
M.ran = core.ran       -- ran(x), nran(m, sd) for rule functions: the deriving model's generator
M.nran = core.nran
--- srand(seed), cpfg's: in a rule function, reseeds the generator of the model deriving;
-- in a model's hook (start, start_each, end_each, finish), that model's (m:srand).
function M.srand (seed)
  local m = not core.producing() and model.hooked()
  if m then return m:srand(seed) end
  local ok, err = pcall(core.srand, seed)
  if not ok then error("lsys." .. tostring(err):gsub("^[^:]*:%d+: ", ""), 2) end
end
M.version = "0.1.0"
M.view = view

M.parse_size = model.parse_size        -- the memory budget (max_memory)
M.max_memory = model.max_memory
M.func = func                          -- positional functions (cpfg .func files)

-- What lsys.type calls the userdata of lsys.core, by metatable name; the arrangement and
-- the model are Lua tables, told apart by their metatables.
local KINDS = {
  ["lsys.Lstring"] = "lstring", ["lsys.Scene"] = "scene", ["lsys.Contour"] = "contour",
  ["lsys.Surface"] = "surface", ["lsys.Texture"] = "texture", ["lsys.IK"] = "ik",
  ["lsys.Viewer"] = "viewer", ["lsys.Rules"] = "rules", ["lsys.Func"] = "func",
  ["lsys.Canvas"] = "canvas", ["lsys.BSpline"] = "bspline",
}
-- Lua objects of modules loaded on demand: { module, its metatable's field, kind }
local TABLE_KINDS = { { "lsys.arrange", "Arrangement", "arrangement" },
                      { "lsys.sketch", "Sketch", "sketch" },
                      { "lsys.sketch.organ", "Organ", "organ" } }
local REGISTRY = debug.getregistry()

--- The kind of lsys object `x` is: "lstring", "scene", "model", "arrangement", "contour",
-- "surface", "texture", "ik", "viewer", "rules", "func", "canvas", "bspline", "sketch" or
-- "organ"; nil for any other value (as io.type, math.type and lpeg.type). Closed objects
-- keep their kind.
function M.type (x)
  local mt = getmetatable(x)
  if mt == nil then return nil end
  if mt == model.Model then return "model" end
  if type(x) == "userdata" then
    local name = type(mt) == "table" and rawget(mt, "__name")
    -- the registry check: another library's userdata may call itself "lsys.Scene" too
    return name and REGISTRY[name] == mt and KINDS[name] or nil
  end
  for _, k in ipairs(TABLE_KINDS) do                 -- none before its module is loaded
    local mod = package.loaded[k[1]]
    if type(mod) == "table" and mt == rawget(mod, k[2]) then return k[3] end
  end
  return nil
end

-- the type predicates before lsys.type: one release more, with a warning
M.islstring = warning.alias("lsys.islstring", 'lsys.type(x) == "lstring"', model.islstring)
M.isscene = warning.alias("lsys.isscene", 'lsys.type(x) == "scene"', model.isscene)
M.ismodel = warning.alias("lsys.ismodel", 'lsys.type(x) == "model"', model.ismodel)
M.BUILTIN = model.BUILTIN              -- the names rule expressions see besides env
M.Model = model.Model
M.lsystem = model.lsystem

--- The directory of the Lua file that calls this ("." when it is not a file): for a
-- model's contour, surface and texture files next to it, as `view = { dir = lsys.here() }`.
function M.here ()
  local src = debug.getinfo(2, "S").source
  return src:match("^@(.*)/[^/]*$") or "."
end

--- Many plants in one scene, plants alike sharing their geometry (lsys.population,
-- docs/population.md): `plants` is a list of { model =, at =, rotate =, scale =, seed =,
-- steps =, env = } or { count = N, place = function (i) ... end }. Returns a Scene.
M.population = population.population

--- Shows `x` (a Model, an Lstring or a Scene) in the viewer window; see lsys.viewer.
function M.show (x, opts) return _G.require("lsys.viewer").show(x, opts) end

--- Starts arranging a plant by inverse kinematics (lsys.arrange, docs/arrange.md).
function M.arrange (m, s, opts) return _G.require("lsys.arrange")(m, s, opts) end

--- Writes one PNG picture per derivation step of `m` into `opts.dir`, all through one
-- camera fitted to the last step, so the plant grows in place (lsys.frames.frames).
function M.frames (m, opts) return _G.require("lsys.frames").frames(m, opts) end

--- Writes an animation of `m` growing, step by step through one camera, to `opts.out`
-- (.mp4 or .gif) through ffmpeg (lsys.frames.animate).
function M.animate (m, opts) return _G.require("lsys.frames").animate(m, opts) end

--- Handles the window's events until it is closed (lsys.viewer.wait): the end of a script
-- that shows a model.
function M.wait () return _G.require("lsys.viewer").wait() end

-- lsys.viewer: the window's module, loaded at first use (a script that never opens a
-- window does not load it).
-- lsys.sketch likewise (docs/sketch.md): its readers need cjson and lxp only when a sketch
-- is read, so `require "lsys"` works without them. lsys.components (docs/components.md),
-- the component graphs, lsys.grow (incremental growth) and lsys.batch
-- (batch runs) likewise.
setmetatable(M, { __index = function (_, k)
  if k == "viewer" then return _G.require("lsys.viewer") end
  if k == "sketch" then return _G.require("lsys.sketch") end
  if k == "components" then return _G.require("lsys.components") end
  if k == "grow" then return _G.require("lsys.grow") end
  if k == "batch" then return _G.require("lsys.batch") end
  if k == "cpfg" then return _G.require("lsys.cpfg") end
end })

-- options of lsys.render that are not view options
local RENDER_ONLY = { out = true, width = true, height = true, view = true, zoom = true,
                      transparent = true, wireframe = true, fit = true }

--- Renders `x` (a Scene, or a Model: derived and interpreted) to a PNG file.
-- opts: out (the PNG path; without it the RGBA pixels are returned as a string, plus
-- width and height), width, height (800), zoom (1: magnifies about the centre),
-- transparent (a transparent background, RGBA PNG), wireframe, fit (a box {x0, y0, z0, x1,
-- y1, z1} the camera frames instead of the scene: one camera for a series of pictures of a
-- growing plant), and view fields (camera,
-- background, light, supersample) that replace the scene's view for this picture;
-- `opts.view` may hold them.
function M.render (x, opts)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.render: an options table expected", 2) end
  local ext = type(opts.out) == "string" and opts.out:match("%.([%w]+)$")
  if ext and ext:lower() ~= "png" then      -- not PNG data under another format's name
    error(format("lsys.render: '%s': lsys writes PNG images; name the file .png", opts.out), 2)
  end
  if type(x) == "table" and x.links ~= nil and M.components.isproto(x) then
    x = M.components.model(x)                     -- a component graph's root
  end
  local over, drawn = {}, {}
  for k, val in pairs(opts.view or {}) do over[k] = val end
  for k, val in pairs(opts) do
    if view.KINDS[k] then over[k] = val
    elseif not RENDER_ONLY[k] then
      error(format("lsys.render: unknown option '%s'", tostring(k)), 2)
    end
  end
  for k, val in pairs(over) do        -- what changes the drawing goes to the turtle
    if view.TURTLE[k] then drawn[k] = val; over[k] = nil end
  end
  if model.ismodel(x) then
    local ok, sc = pcall(x.interpret, x, nil, next(drawn) and drawn or nil)
    if not ok then error(sc, 2) end
    x = sc
  elseif next(drawn) and model.isscene(x) then
    error(format("lsys.render: '%s' changes how the turtle draws: render the model, or "
                 .. "interpret it with the option (m:interpret(s, { %s = ... }))",
                 next(drawn), next(drawn)), 2)
  end
  if not model.isscene(x) then
    error("lsys.render: a Scene, a Model or a component prototype expected", 2)
  end
  -- the scene keeps its camera, light, background and textures; a render that changes
  -- them passes the whole view they make with the scene's own
  local v = model.sceneview(x)
  local ro = { supersample = v and v.supersample }
  if next(over) then
    local ok, r = pcall(view.normalize, view.merge(v or view.normalize({}, "lsys.render"), over),
                        "lsys.render")
    if not ok then error(r, 2) end
    ro = view.render_options(r)
  end
  ro.out, ro.width, ro.height = opts.out, opts.width or 800, opts.height or 800
  ro.zoom, ro.transparent, ro.wireframe = opts.zoom, opts.transparent, opts.wireframe
  ro.fit = opts.fit
  local ok, a, b, c = pcall(core.render, x, ro)
  if not ok then error(a, 2) end
  return a, b, c
end

return M
