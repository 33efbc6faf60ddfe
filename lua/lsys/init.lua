--- lsys: L-systems for plant modelling (docs/manual.md).
-- `local lsys = require "lsys"`
--
-- This file only gathers: the library's functions live in lsys.model (models, Lstrings,
-- the memory budget), lsys.kinds (lsys.type), lsys.view (view options), lsys.render
-- (pictures), lsys.frames (picture series, animations), lsys.population, lsys.func, and
-- the modules loaded at first use below. None of those requires this file, so the requires
-- form no cycle (tests/layout_spec.lua checks it).
-- @module lsys
local core = require "lsys.core"
local model = require "lsys.model"
local kinds = require "lsys.kinds"
local func = require "lsys.func"
local view = require "lsys.view"
local warning = require "lsys.warning"
local population = require "lsys.population"
local environment = require "lsys.environment"
local stand = require "lsys.stand"
local render = require "lsys.render"
local frames = require "lsys.frames"

local setmetatable, require = setmetatable, require
local _ENV = nil

local M = {}

M.version = "0.1.0"
M.lstring = model.lstring      -- cpfg text notation to an Lstring; `names`: "Apex Leaf"
M.produce = core.produce
M.nproduce = core.nproduce
M.ran = core.ran       -- ran(x), nran(m, sd) for rule functions: the deriving model's generator
M.nran = core.nran
M.srand = model.srand          -- cpfg's srand: the deriving model's generator, or the hook's
M.view = view

M.parse_size = model.parse_size        -- the memory budget (max_memory)
M.max_memory = model.max_memory
M.func = func                          -- positional functions (cpfg .func files)
M.environment = environment            -- open L-systems: what ?E modules ask (docs/open.md)
M.stand = stand.stand                  -- open L-systems growing together in one environment

M.type = kinds.type                    -- "lstring", "scene", "model", ... or nil

-- the type predicates before lsys.type: one release more, with a warning
M.islstring = warning.alias("lsys.islstring", 'lsys.type(x) == "lstring"', model.islstring)
M.isscene = warning.alias("lsys.isscene", 'lsys.type(x) == "scene"', model.isscene)
M.ismodel = warning.alias("lsys.ismodel", 'lsys.type(x) == "model"', model.ismodel)
M.BUILTIN = model.BUILTIN              -- the names rule expressions see besides env
M.Model = model.Model
M.lsystem = model.lsystem

M.here = model.here      -- the calling file's directory: `view = { dir = lsys.here() }`

--- Many plants in one scene, plants alike sharing their geometry (lsys.population,
-- docs/population.md): `plants` is a list of { model =, at =, rotate =, scale =, seed =,
-- steps =, env = } or { count = N, place = function (i) ... end }. Returns a Scene.
M.population = population.population

--- Renders `x` (a Scene, a Model or a component graph's root) to a PNG file (lsys.render).
M.render = render.render

--- Writes one PNG picture per derivation step of `m` into `opts.dir`, all through one
-- camera fitted to the last step, so the plant grows in place (lsys.frames.frames).
M.frames = frames.frames

--- Writes an animation of `m` growing, step by step through one camera, to `opts.out`
-- (.mp4 or .gif) through ffmpeg (lsys.frames.animate).
M.animate = frames.animate

--- Writes a turntable of `x` (a Model, a Scene or a component graph's root): a camera going
-- once around the final plant, to `opts.out` (.mp4 or .gif) or `opts.dir` (lsys.frames.orbit).
M.orbit = frames.orbit

--- Shows `x` (a Model, an Lstring or a Scene) in the viewer window; see lsys.viewer.
function M.show (x, opts) return require("lsys.viewer").show(x, opts) end

--- Handles the window's events until it is closed (lsys.viewer.wait): the end of a script
-- that shows a model.
function M.wait () return require("lsys.viewer").wait() end

--- Starts arranging a plant by inverse kinematics (lsys.arrange, docs/arrange.md).
function M.arrange (m, s, opts) return require("lsys.arrange")(m, s, opts) end

-- Modules loaded at first use, as the fields lsys.viewer, lsys.sketch, ...: a script that
-- never opens a window does not load lsys.viewer; lsys.sketch's readers need cjson and lxp
-- only when a sketch is read, so `require "lsys"` works without them; lsys.components (the
-- component graphs), lsys.grow (incremental growth), lsys.batch (batch runs) and lsys.cpfg
-- (cpfg's model files) are loaded by the scripts that use them.
local LAZY = { viewer = "lsys.viewer", sketch = "lsys.sketch", components = "lsys.components",
               grow = "lsys.grow", batch = "lsys.batch", cpfg = "lsys.cpfg" }
setmetatable(M, { __index = function (_, k) return LAZY[k] and require(LAZY[k]) end })

return M
