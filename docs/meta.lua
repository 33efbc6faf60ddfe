---@meta
-- LuaLS definitions for lsys: the Lua API of `require "lsys"` (models, Lstrings, scenes,
-- views, rendering, the viewer window, the arrangement) and the C-implemented functions of
-- `require "lsys.core"` that it is built on. Nothing here runs. Point `workspace.library`
-- at this docs/ directory; where the language server does not infer the module type, write
-- `local lsys = require "lsys" ---@type lsys`.
--
-- Conventions: indices are 1-based unless a name ends in "idx" (0-based rule indices of the
-- core); angles in module parameters are degrees (for the turtle), angles in expression
-- functions radians (Lua's math); vectors are `{x, y, z}` lists; "raises" means a Lua error
-- with the message shown. The manuals are docs/manual.md (derivation), docs/drawing.md
-- (turtle, views, scenes, rendering), docs/viewer.md (the window) and docs/arrange.md (the
-- arrangement).


-- ===========================================================================================
-- Types shared by the two modules

--- A rule string: `lc < pred > rc : condition --> successor : weight` (manual §4.2).
---@alias lsys.RuleText string

--- A rule whose successor a Lua function builds with `lsys.produce`/`lsys.nproduce`
--- (manual §7). The pattern is `lc < pred > rc` only (no condition, successor or weight);
--- the function receives the formal parameters of left context, predecessor and right
--- context in that order (Lua floats). The rule applies only if the function called
--- `lsys.produce`; its return values are ignored.
---@alias lsys.FnRule { [1]: string, [2]: fun(...: number): any }

--- Rules: a string with one rule per line (blank lines skipped, no comments), or a list whose
--- entries are rule strings (each may span lines) or `{ pattern, function }` pairs.
---@alias lsys.RuleList string | (lsys.RuleText | lsys.FnRule)[]


-- ===========================================================================================
-- lsys: the Lua API

---@class lsys
---@field version string The library version, `"0.1.0"`.
---@field BUILTIN table<string, any> Names visible in every rule expression after the formal parameters, `ran`/`nran` and `env`: `math string table pi huge abs floor ceil sqrt exp log sin cos tan asin acos atan min max fmod deg rad type tostring tonumber print select error assert pairs ipairs`. Changing this table changes what all models see.
---@field Model lsys.Model The model metatable (its methods).
---@field view lsys.view View options and cpfg view files.
---@field viewer lsys.viewer The window's module, loaded at first use.
---@field func lsys.func Positional functions (cpfg .func files).
---@field sketch lsys.sketch Sketch-based models (docs/sketch.md), loaded at first use.
---@field components lsys.components Component graphs (docs/components.md), loaded at first use.
---@field grow lsys.grow Incremental growth (docs/grow.md), loaded at first use.
---@field batch lsys.batch Batch runs of many jobs, sharded (docs/batch.md), loaded at first use.
---@field cpfg table cpfg model files: `load`, `load_object`, `options`, `object_files` (docs/cpfg.md), loaded at first use.
local lsys = {}

--- Makes a model: checks the options, parses and compiles every rule, parses the axiom.
--- Nothing is derived yet.
---
--- Raises, with the file and line of this call in front when Lua knows it (not when the call
--- is a tail call such as `return lsys.lsystem{...}`):
--- `lsys.lsystem: a table of options expected`; `unknown option 'NAME'`;
--- `option 'NAME' must be a TYPE (got TYPE)`; `give either 'ignore' or 'consider', not both`;
--- `option 'steps' must be a whole number >= 0`; `groups: keys must be group numbers >= 1`;
--- `sub: keys must be sub-L-system numbers >= 1`; `sub[N]: unknown option 'NAME'`;
--- `max_modules must be between 1 and 1e12`;
--- `max_depth.KEY must be a whole number from 0 to 1024`;
--- `rule N 'TEXT' (line L of productions): MESSAGE at character C` for a malformed rule
--- (`entry E` for list entries; `decomposition`, `homomorphism`, `group G`,
--- `sub-L-system S` instead of `productions`);
--- `axiom 'TEXT': MESSAGE at character C` for a malformed axiom (brackets must balance).
--- Names that are neither formal parameters nor in `env` are reported later, when a
--- derivation binds the rules.
---@param options lsys.Options
---@return lsys.Model
function lsys.lsystem(options) end

--- Parses cpfg text notation (`"F(1,0.5)[+A]"`) into a new Lstring. White space between
--- modules and inside parameter lists is ignored; parameters are finite numbers, at most 31
--- per module; brackets need not balance.
--- Raises `lsys.lstring: MESSAGE at character C` for malformed text (`unexpected ':'`,
--- `unbalanced parentheses after 'F'`, `bad number 'x' in parameters of 'F'`, ...).
---@param text string
---@param names? string Multi-character module names, as in the `modules` option: `"Apex Leaf"`.
---@return lsys.Lstring
function lsys.lstring(text, names) end

--- The kind of lsys object `x` is, as `io.type` and `math.type` name theirs; nil for any
--- other value. Closed objects keep their kind.
---@param x any
---@return "lstring"|"scene"|"model"|"arrangement"|"contour"|"surface"|"texture"|"ik"|"viewer"|"rules"|"func"|"canvas"|"bspline"|"sketch"|"organ"|nil
function lsys.type(x) end

--- True when `x` is an Lstring. Deprecated: `lsys.type(x) == "lstring"`; the first call
--- warns once (manual §9).
---@deprecated
---@param x any
---@return boolean
function lsys.islstring(x) end

--- True when `x` is a model made by `lsys.lsystem`. Deprecated: `lsys.type(x) == "model"`;
--- the first call warns once.
---@deprecated
---@param x any
---@return boolean
function lsys.ismodel(x) end

--- A memory size in bytes from a number of bytes or a string: `"512M"`, `"2G"`, `"1.5GiB"`,
--- `"800MB"` (binary units: K = 1024), `"unlimited"` or `"none"` (math.huge). Raises
--- `WHAT must be at least 1 byte, got X`, `WHAT must be a number of bytes or a string such
--- as "2G", got TYPE`, `WHAT: 'X' is not a size (...)`.
---@param x number|string
---@param what? string Names the value in messages. Default `"lsys.parse_size"`.
---@return number bytes A whole number, or math.huge.
function lsys.parse_size(x, what) end

--- The process-wide memory budget: the most one derivation step or one interpretation may
--- take for its strings, tables, mesh and records (manual §9). With an argument, sets it
--- first (`nil` leaves it). The default is half the physical memory, or `LSYS_MAX_MEMORY`
--- from the environment; a model's own `max_memory` option takes precedence. Raises as
--- `lsys.parse_size`, naming `lsys.max_memory`.
---@param size? number|string Bytes, or a size string such as `"2G"` or `"unlimited"`.
---@return number limit Bytes (math.huge: none).
---@return integer physical The physical memory in bytes.
function lsys.max_memory(size) end

--- Inside a rule function: appends the modules of `template` to the successor and marks the
--- rule as applied. `template` is module text whose parameters are numbers or `?`; the `?`
--- marks are filled in order with the extra arguments. Templates are parsed once per model
--- and cached. Does not end the function: a second call appends more.
---
--- Raises `produce called outside a rule function`;
--- `produce: the template 'T' has N '?' but M values were given`;
--- `produce: value K is TYPE, not a number`; `produce: value K is not a finite number`;
--- `produce: MESSAGE at character C in 'T'` for malformed text;
--- `produce: parameters in a template are numbers or '?' (got 'X' in 'T')`;
--- `produce: the successor would exceed max_modules`. When the function returns, a
--- successor with unbalanced brackets raises `unbalanced brackets in the produced successor`.
---@param template string
---@param ... number One finite number per `?` mark.
---@return true
function lsys.produce(template, ...) end

--- Inside a rule function: uniform in [0, x) from the generator of the model deriving now
--- (the same sequence as `ran` in rule expressions). Raises `ran called outside a
--- derivation (use it in a rule function)` elsewhere.
---@param x? number Default 1.
---@return number
function lsys.ran(x) end

--- Inside a rule function: normal with mean `mean` and standard deviation `sd`, from the
--- generator of the model deriving now. Raises outside a derivation, like `lsys.ran`.
---@param mean number
---@param sd number
---@return number
function lsys.nran(mean, sd) end

--- cpfg's `srand`: in a rule function, reseeds the generator of the model deriving now (the
--- modules rewritten after it in the step, and the steps after, draw from `seed`); in a
--- hook, the hooked model's (as `Model:srand`).
---@param seed number
function lsys.srand(seed) end

--- Inside a rule function: appends the modules of `template` to the successor without marking
--- the rule as applied; the pieces are dropped if the function never calls `lsys.produce`.
--- Pieces may leave brackets open for later pieces to close. Raises as `lsys.produce`
--- (`nproduce called outside a rule function`).
---@param template string
---@param ... number One finite number per `?` mark.
---@return true
function lsys.nproduce(template, ...) end


-- ===========================================================================================
-- lsys.lsystem options

--- The options of `lsys.lsystem`. Unknown keys are errors. Each option becomes a field of
--- the model; see lsys.Model for which fields are read again after the model is made.
---@class lsys.Options
---@field axiom? string The starting string, in successor notation: parameters may be Lua expressions, evaluated in `env` at the start of every `derive`. Brackets must balance. Default `""` (empty; `"*"` is empty too).
---@field steps? integer Steps done by `m:derive()` without a count; whole number >= 0. Default 1.
---@field seed? number Seed of the derivation generator (stochastic choice, `ran`, `nran`); `derive` and making the model reseed from it. Whole numbers seed with their value, others with the bits of their double. Default 0.
---@field env? table<string, any> Names visible in rule expressions besides the formal parameters. Values are read when a derivation starts, after every `start_each`, and at every `step`/`expand`. Default `{}`.
---@field modules? string Multi-character module names separated by spaces, tabs, newlines or commas: `"Apex Leaf"`. They take precedence over every other name when text is split into modules. Default: none.
---@field ignore? string Module names that context matching skips; brackets are never skipped. Not together with `consider`. Default: none.
---@field consider? string The only module names context matching sees (brackets are always seen). Not together with `ignore`. Default: none.
---@field productions? lsys.RuleList The productions: rule group 0, always active. Default: none (modules are copied).
---@field decomposition? lsys.RuleList Rules applied after the productions of every step (not to the axiom), recursively within `max_depth.decomposition`. Default: none.
---@field homomorphism? lsys.RuleList Rules applied by `m:expand` only (what the turtle draws), recursively within `max_depth.homomorphism`, with their own generator. Default: none.
---@field max_depth? { decomposition?: integer, homomorphism?: integer } Levels of recursion, whole numbers from 0 (off) to 1024. Default 1 and 1, as cpfg. Other keys raise.
---@field ring? boolean Contexts wrap around the ends of the string. Default false.
---@field sub? table<integer, { productions: lsys.RuleList, ignore?: string, consider?: string }> Sub-L-systems by id >= 1, used between `?(id, scale)` and `$`. Each needs at least one production; its `ignore`/`consider` list replaces the model's inside it. Default: none.
---@field groups? table<integer, lsys.RuleList> Rule groups by number >= 1, activated with `m:use_group(n)`; the active group's rules are tried before group 0's. Default: none.
---@field start? fun(model: lsys.Model) Called by `derive` before the first step. Default: none.
---@field start_each? fun(model: lsys.Model, step: integer) Called by `derive` before each step (`step` from 1); rules are bound to `env` again after it. Default: none.
---@field end_each? fun(model: lsys.Model, s: lsys.Lstring, step: integer): lsys.Lstring? Called by `derive` after each step; an Lstring returned replaces the result, `nil` keeps it, anything else raises `end_each must return an Lstring or nil`. Default: none.
---@field finish? fun(model: lsys.Model, s: lsys.Lstring): lsys.Lstring? Called by `derive` after the last step; an Lstring returned replaces the result, other values are ignored. Default: none.
---@field max_modules? number Largest string (in modules) a step, decomposition, expansion or rule function may build, from 1 to 1e12; beyond it derivation raises `the string would exceed max_modules (N modules)`. Default 50 000 000.
---@field view? table Turtle options (angle increment in degrees, widths, tropisms, ...); kept as `model.view`, not read by derivation. Default `{}`.
---@field name? string Shown by `tostring(model)`. Default: none (the file and line of the `lsys.lsystem` call, or `model`).
---@field homomorphism_seed? number Seed of the homomorphism generator, reset by every `m:expand`. Default: `seed`.
---@field allow_system_calls? boolean For the turtle: `@S` is refused unless true. Not read by derivation. Default false.
---@field system_call? fun(i: integer, name: string, ...: number) With `allow_system_calls`, called after `interpret` once per `@S` drawn, with the module's index, name and parameters. Default: none.
---@field max_memory? number|string The memory budget of this model's steps and interpretations, in bytes or as `"512M"`, `"2G"`, `"unlimited"` (see `lsys.parse_size`). Default: `lsys.max_memory()`.
---@field max_instructions? number Most Lua instructions one call of rule code may run (rule expressions, rule functions, the axiom's expressions, a cpfg file's blocks), at least 1000; `math.huge` for none. Default 100 000 000.
---@field depth_warnings? boolean|{ decomposition?: boolean, homomorphism?: boolean } Whether a derivation warns (once) when the depth limit stops a rule that would apply; false for neither. Default true.
---@field functions? table Positional functions for `func(ID, x)` and `func("name", x)`: `lsys.Func`s and file names (.func, .fset), a list and/or a table by name. Fixed when the model is made (Model:set_func replaces one). Default: the view's `functions`.
---@field threads? integer Threads a derivation step may use, from 1 to 64; the string is the same for every number. Read by every `derive` and `step`. Default: `LSYS_THREADS` from the environment, else the number of processors.
---@field numbers? "double"|"float32" How parameters are stored; "float32" rounds every parameter a step produces to the nearest 32-bit float, as cpfg stores them. Default "double".
---@field after_interpret? fun(model: lsys.Model, scene: lsys.Scene, s: lsys.Lstring) Called by `interpret` with the scene it made, before returning it. Default: none.


-- ===========================================================================================
-- lsys.Model

--- A model made by `lsys.lsystem`. Read again by every `derive`: `axiom` (re-parsed when
--- changed), `steps`, `seed`, `homomorphism_seed`, `env`, the hooks, `lua_expressions`.
--- Fixed when the model is made: the rules, `modules`, `ignore`/`consider`, `ring`,
--- `max_modules`, `max_depth` (assigning those fields later has no effect).
--- `tostring(model)` is `lsys.Model(NAME)`, NAME being `name` or where the model was made.
---@class lsys.Model
---@field axiom string
---@field steps integer
---@field seed number
---@field env table<string, any>
---@field view table
---@field name string?
---@field homomorphism_seed number?
---@field allow_system_calls boolean
---@field max_modules number? Set only when the option was given (the limit in force is 50 000 000 otherwise).
---@field max_memory number? In bytes; set only when the option was given.
---@field max_instructions number? Set only when the option was given.
---@field threads integer? Threads of a derivation step (read by every derive and step); nil: the default (`LSYS_THREADS`, else the number of processors).
---@field system_call (fun(i: integer, name: string, ...: number))?
---@field start fun(model: lsys.Model)?
---@field start_each fun(model: lsys.Model, step: integer)?
---@field end_each (fun(model: lsys.Model, s: lsys.Lstring, step: integer): lsys.Lstring?)?
---@field finish (fun(model: lsys.Model, s: lsys.Lstring): lsys.Lstring?)?
---@field lua_expressions boolean? When true, every rule runs its compiled Lua closure instead of the C expression machine (read when rules are bound: each derive, start_each, step, expand).
local Model = {}

--- Options of `Model:derive`.
---@class lsys.DeriveOptions
---@field progress? fun(step: integer, n: integer, nmodules: integer) Called after each step (after `end_each`) with the step number, the step count and the length of the result.
---@field each? fun(k: integer, s: lsys.Lstring) Receives the string of every step k = 0..n (n: after `finish`); they may be kept.

--- Derives `n` steps from the axiom and returns the result as a new Lstring; `derive(0)`
--- returns the axiom. Reseeds the derivation generator from `seed` and the homomorphism
--- generator from `homomorphism_seed` (or `seed`), binds the rules to `env`, evaluates the
--- axiom, then calls `start`, and per step `start_each`, the step (productions, cut,
--- decomposition), `end_each` and `opts.progress`, and finally `finish`.
---
--- Raises `derive: the number of steps must be a whole number >= 0`;
--- `WHERE: rule N 'TEXT' (line L of productions): unknown name 'X' (not a parameter, not in env)`;
--- `WHERE: rule N 'TEXT' (...), module I: MESSAGE` for an error while rewriting module I
--- (1-based) of the string being rewritten (Lua errors in expressions or rule functions,
--- `value K is nan, not a finite number`, `weight is W, not a finite number >= 0`,
--- `condition is TYPE, not a boolean or number`, produce errors);
--- `WHERE: the string would exceed max_modules (N modules)`;
--- `WHERE: sub-L-system S is not defined (module I)`; `axiom: expression 'E' is nil, not a
--- number`; errors raised by hooks. WHERE is the file and line of the `lsys.lsystem` call,
--- or `model`. The model stays usable after an error.
--- Prints `lsys: WHERE: the decomposition depth limit stopped at modules that have rules
--- (raise max_depth if they should apply)` on stderr, once per call.
---@param n? integer Number of steps, whole >= 0. Default `self.steps`.
---@param opts? lsys.DeriveOptions
---@return lsys.Lstring
function Model:derive(n, opts) end

--- One derivation step (productions, cut, decomposition) from `s`; returns a new Lstring and
--- leaves `s` unchanged. Binds the rules to `env`; calls no hook; does not reseed (the
--- generator continues; before the first `derive` it starts from `seed`).
--- Raises `step: an Lstring expected`, a parse error for text, and as `derive`.
---@param s lsys.Lstring|string An Lstring, or text parsed with the model's declared names.
---@return lsys.Lstring
function Model:step(s) end

--- Applies the homomorphism to `s` and returns a new Lstring (a copy when there are no
--- homomorphism rules): what the turtle interprets. Reseeds the homomorphism generator from
--- `homomorphism_seed` (or `seed`) first, so the same string always expands the same way.
--- Contexts are matched in `s`; modules made by the homomorphism take the context of the
--- module of `s` they came from. Raises `expand: an Lstring expected`, and as `derive`;
--- warns on stderr when `max_depth.homomorphism` cut an expansion short.
---@param s lsys.Lstring|string An Lstring, or text parsed with the model's declared names.
---@return lsys.Lstring
function Model:expand(s) end

--- Reseeds the derivation's generator now, as cpfg's `srand`: from a `start` hook the whole
--- derivation follows `seed`; from `start_each` or `end_each`, the steps after it.
---@param seed number
function Model:srand(seed) end

--- Makes rule group `n` active beside group 0 (`0`: group 0 alone). Takes effect from the
--- next step and stays until changed. An `n` without rules is allowed (only group 0 then
--- applies). Raises `use_group: a group number >= 0 expected`.
---@param n integer Group number, whole >= 0.
function Model:use_group(n) end

--- Parses text with the model's declared `modules` names into a new Lstring whose
--- `tostring` separates names where needed to read back the same modules.
--- Raises `lstring: MESSAGE at character C`.
---@param text string
---@return lsys.Lstring
function Model:lstring(text) end

--- Interprets `s` with the turtle (docs/drawing.md) and returns a Scene. Derives first when
--- `s` is nil; text is parsed with the model's names. `view` replaces view options for this
--- call; `view.records = false` leaves out the turtle records. The homomorphism is applied
--- module by module while drawing. Raises for a bad view option, a module with a non-finite
--- parameter (`module N 'F': parameter 1 is not a finite number`), `@S` without
--- `allow_system_calls`, a bad tropism index, or an error in a homomorphism rule (named
--- like derivation errors).
---@param s? lsys.Lstring|string
---@param view? lsys.View
---@return lsys.Scene
function Model:interpret(s, view) end

--- Replaces the positional function `id` (its position from 1 or its name) by `f` for
--- func(ID, x) and func("name", x) alike, from the next derivation step on (the curve editor,
--- lsys.ui.curve, does this after an edit). Raises `set_func: unknown function 'x'
--- (functions: ...)`, or when a rule of the model calls it.
---@param id integer|string
---@param f lsys.Func
function Model:set_func(id, f) end

--- The model's positional functions: the listed ones by position, then those given only by
--- name; `file` is the path a function was read from.
---@return { id: integer|string, name: string, func: lsys.Func, file?: string }[]
function Model:functions() end

--- A rule of the model, as `Model:rules` lists it.
---@class lsys.RuleInfo
---@field text string The rule as written; for a rule function, its pattern.
---@field set string "productions", "group G", "sub-L-system S", "decomposition" or "homomorphism".
---@field line integer Its line in the set's text, or its entry in the set's list.
---@field fn? function The rule function, for a `{pattern, function}` entry.
---@field weight? number That entry's weight.
---@field where? string "FILE:LINE" of the production, for a model read from a cpfg file.

--- The model's rules, set by set (productions, groups, sub-L-systems, decomposition,
--- homomorphism), each set's in the order given. `tostring` of the list gives one line a
--- rule under the name of its set.
---@return lsys.RuleInfo[]
function Model:rules() end

--- The model as text: `tostring(m)`, its options (axiom, steps, seed, and those given:
--- env, params, view, ignore or consider, the limits, the hooks...) and its rules as
--- `Model:rules` gives them. What the REPL prints for a model.
---@return string
function Model:inspect() end

--- View options (docs/drawing.md §2); every field is optional.
---@class lsys.View
---@field angle? number Angle increment, degrees (90).
---@field step? number Step of F f G g without a parameter (1).
---@field line_width? number Initial width (1): pixels in "line" style, model units otherwise.
---@field width_increment? number What # and ! add or subtract (1).
---@field color? integer Initial colour index (1).
---@field color_increment? integer What ; and , add or subtract (1).
---@field line_style? "line"|"polygon"|"cylinder"
---@field contour_sides? integer Sides of tubes, discs and spheres (8).
---@field tropisms? { vector: number[], angle?: number, elasticity?: number, increment?: number, torque?: boolean }[]
---@field torques? { vector: number[], elasticity?: number, increment?: number }[]
---@field palette? table<integer, number[]|string|{ diffuse: number[], ambient?: number[], specular?: number[], emission?: number[], shininess?: number }>
---@field background? number[] {r, g, b} in 0..1.
---@field viewpoint? number[] Camera position.
---@field target? number[] View reference point.
---@field up? number[] Up vector of the camera.
---@field direction? number[] View direction when no viewpoint is given ({0, 0, -1}).
---@field projection? "parallel"|"perspective"
---@field fov? number Vertical field of view, degrees (30).
---@field twist? number Rotation about the view axis, degrees.
---@field light? number[] Direction the key light comes from.
---@field supersample? integer Anti-aliasing factor (3).
---@field dir? string Base directory of relative file names below (a .v file's directory after view.load).
---@field contours? table<integer, string|{ points: number[][], closed?: boolean }> Contours of generalized cylinders by @# id (>= 1); files as in Appendix B.1 of the cpfg guide (Měch and Prusinkiewicz; docs/manual.md §12) or vlab's versioned `cver` files (docs/drawing.md §3a).
---@field minimize_twist? boolean Rotation-minimising frames along generalized cylinders (true; cpfg "twist of cylinders"); false also turns cylinder textures with the roll.
---@field textures? (string|{ file: string, mag?: "near"|"linear", min?: "near"|"linear", mode?: "modulate"|"decal", per_surface?: boolean, intensity?: boolean })[] PNG textures; @Tx(k) picks the k-th.
---@field surfaces? table<string, string|{ file: string, scale?: number, texture?: integer, precision?: integer[] }> Predefined surfaces (cpfg .s files) drawn by ~name.
---@field functions? (string|lsys.Func|{ file: string, samples?: integer })[] Positional functions for the model's rules (not read by the turtle), as a view file's `function:` lines give them; a model without its own `functions` option takes these.

--- A turtle record (docs/drawing.md §5). Its numbers are stored as 32-bit floats, so points
--- and widths carry about seven significant digits.
---@class lsys.Record
---@field kind "segment"|"sphere"|"disc"|"polygon"|"label"|"system"|"gcyl"|"surface"
---@field module integer 1-based index of the module in the string.
---@field parent? integer The record of the segment this one grows from.
---@field p0 number[] Start point (p1 - length * H for a segment; p1 otherwise).
---@field length number Length of a segment (0 for other kinds).
---@field p1 number[] End point.
---@field H number[] Heading at the end.
---@field L number[]
---@field U number[]
---@field w0 number Width at the start.
---@field w1 number Width at the end.
---@field color integer
---@field stiffness? number[] {sh, su, sl} from Z.

--- The geometry and turtle records of an interpretation; vertices, normals, texture
--- coordinates, line ends and widths are 32-bit floats (docs/drawing.md §5, Precision).
--- A population (lsys.population, docs/population.md) is a Scene too: its sizes, bounds and
--- area are those of every plant drawn.
---@class lsys.Scene
---@field ntriangles integer
---@field nvertices integer
---@field nlines integer Line segments (line style).
---@field nsegments integer Segment records (F and G drawn in any style).
---@field nrecords integer
---@field lstring lsys.Lstring The string the scene was made from (nil for a population).
---@field ninstances integer A population's plants; 0 for other scenes.
---@field nprototypes integer A population's prototypes (meshes shared by its plants); 0 else.
---@field bytes integer The memory the scene's arrays hold (mesh, records, transforms).
local Scene = {}

--- Changes how the scene is looked at: the look fields of a view (background, light,
--- viewpoint, target, up, direction, projection, fov, twist, zoom) and `fit`, a box the
--- camera frames instead of the scene.
---@param opts table
function Scene:look(opts) end

--- Axis-aligned bounds, or nil for an empty scene.
---@return number[]? lo
---@return number[]? hi
function Scene:bounds() end

--- Total area of the triangles.
---@return number
function Scene:area() end

--- The turtle state after module `i` (1-based; 0 is the start), interpreting again.
---@param i integer
---@return number[] pos
---@return number[] H
---@return number[] L
---@return number[] U
---@return number width
---@return integer color
function Scene:turtle(i) end

--- How much each colour index draws: `{[c] = n}`, the number of triangles and line
--- segments in colour index `c` (the turtle's index, 0 to 65535, before the palette's length
--- wraps it), for the indices the scene uses. A population's prototypes count once each.
--- The palette pane (lsys.ui.palette) marks the colours a plant uses with it.
---@return table<integer, integer>
function Scene:colors() end

---@param k integer 1-based record index.
---@return lsys.Record?
function Scene:record(k) end

--- `for k, rec in scene:records() do ... end`
---@return fun(): integer, lsys.Record
function Scene:records() end

--- The index of the first record of module `i`, or nil.
---@param i integer
---@return integer?
function Scene:find(i) end

--- The wireframe of what record `k` drew: the distinct edges of its triangles, each
--- `{{x, y, z}, {x, y, z}}` (a leaf gives its outline and inner edges; a line-style segment
--- none). The arrangement window highlights leaves and flowers with it. Raises
--- `scene:edges: no record K`.
---@param k integer 1-based record index.
---@return number[][][]
function Scene:edges(k) end

--- Writes the geometry: `.obj` (and a `.mtl` next to it), `.ply` (binary) or `.glb`
--- (glTF 2.0 binary), replacing the file atomically. Colours are written linear in GLB and
--- MTL (the palette's sRGB through the sRGB transfer function), as 8-bit sRGB in PLY.
--- Line-style segments are lines unless `opts.lines = "tubes"`: then closed tubes of
--- `opts.sides` sides (3 to 1024; default the view's `contour_sides`, else 8) whose diameter
--- is the line width (pixels) times `opts.pixel_size` scene units (> 0; default the scene's
--- largest extent / 720: as thick as in an 800 x 800 render). docs/drawing.md, section 5.
--- A population is written as `.glb` with EXT_mesh_gpu_instancing (one mesh per prototype)
--- unless `opts.instancing = false`; as `.obj` and `.ply` with every plant written out, which
--- must fit `opts.max_memory` bytes (default the process's budget: `cannot write 'PATH': the
--- population written out needs N, more than max_memory (M)`). docs/population.md.
--- Raises `cannot open 'PATH' for writing: REASON`, `scene:save: unknown format of 'PATH'
--- (use .obj, .ply or .glb)`, `scene:save: unknown option 'K' (use lines, sides,
--- pixel_size, instancing, max_memory)` and `scene:save: opts.K must be ...` for a bad option.
--- Returns what the file holds: its vertices, triangles and line segments (with tubes, the
--- tubes' triangles and no lines; a population written out, every plant's; with instancing,
--- each prototype's once, and `instances` the plants; else `instances` is 0).
---@param path string
---@param opts? { lines?: "lines"|"tubes", sides?: integer, pixel_size?: number, instancing?: boolean, max_memory?: integer }
---@return { vertices: integer, triangles: integer, lines: integer, instances: integer }
function Scene:save(path, opts) end

--- Plant `i` of a population (1-based): its prototype, its transform M = T R S as 16
--- numbers (column-major), and T, R (a unit quaternion x, y, z, w) and S; nil past the end.
---@param i integer
---@return { prototype: integer, matrix: number[], at: number[], rotation: number[], scale: number[] }?
function Scene:instance(i) end

--- Prototype `k` of a population (1-based): its sizes (`vertices`, `triangles`, `lines`,
--- `records`), its number of `instances`, and what made it: `model`, `seed`, `steps`,
--- `env`, `view`, `lstring` (unless made with `records = false`), `plant` (its first
--- plant). nil past the end.
---@param k integer
---@return table?
function Scene:prototype(k) end

--- A new Scene with every plant of the population written out under its transform (no
--- records; a scene that is no population is copied). Raises `scene:flatten: the flattened
--- scene needs N, more than max_memory (M)` beyond `opts.max_memory` bytes (default the
--- process's budget).
---@param opts? { max_memory?: integer }
---@return lsys.Scene
function Scene:flatten(opts) end

--- Deforms the scene in place (docs/components.md, "Deformations: FFD and Hyperpatch"): by a
--- Hyperpatch, or by a function `f(x, y, z) -> x, y, z` whose normals come from central
--- differences. Normals go through the inverse transpose of the map's Jacobian. Without
--- `opts`, every vertex and line; `opts.modules = {m0, m1}` (1-based, inclusive, as records
--- number modules): what those modules drew, without vertices shared with earlier geometry;
--- `opts.vertices = {v0, v1}` (1-based, inclusive). A function's error or bad result raises
--- `scene:deform: the function failed at vertex N: MSG` or `... at vertex N its x is a
--- string`, and leaves the scene as it was.
---@param map lsys.Hyperpatch|fun(x: number, y: number, z: number): number, number, number
---@param opts? {modules?: integer[], vertices?: integer[]}
---@return integer moved The number of vertices in the range.
function Scene:deform(map, opts) end

--- The affine map `m` (rows `{{a, b, c, d}, {e, f, g, h}, {i, j, k, l}}`, optionally a fourth
--- row `{0, 0, 0, 1}`) applied as `scene:deform` applies a map, with the same `opts`.
---@param m number[][]
---@param opts? {modules?: integer[], vertices?: integer[]}
---@return integer moved
function Scene:transform(m, opts) end

--- The vertices modules `m0` to `m1` (default `m0`; 1-based, inclusive) drew, as 1-based
--- inclusive indices, or nil when they drew no triangles.
---@param m0 integer
---@param m1? integer
---@return integer? v0
---@return integer? v1
function Scene:module_range(m0, m1) end

--- Vertex `i` (1-based): its position and normal. Raises `scene:vertex: no vertex I`.
---@param i integer
---@return number x, number y, number z, number nx, number ny, number nz
function Scene:vertex(i) end

--- A plant of lsys.population: a model placed by M = T R S (docs/population.md).
---@class lsys.Plant
---@field model lsys.Model|lsys.Scene|lsys.Lstring Derived and interpreted (a Model), used as it is (a Scene), or interpreted by the model that made it (an Lstring).
---@field at? number[] Where the plant's origin goes. Default {0, 0, 0}.
---@field rotate? number|{axis: number[], angle: number}|number[][] Degrees about +y (right-handed), an axis and an angle in degrees, or a 3 x 3 rotation matrix by rows.
---@field scale? number|number[] Positive, or {sx, sy, sz} along the plant's own axes. Default 1.
---@field seed? integer Default: the model's.
---@field steps? integer Default: the model's.
---@field env? table Names over the model's env.
---@field lstring? lsys.Lstring|string Drawn instead of deriving.
---@field view? table View fields for drawing this plant.

---@class lsys.PopulationOptions
---@field view? table How the scene is looked at: viewpoint, target, up, direction, projection, fov, twist, background, light, supersample.
---@field records? boolean false: no turtle records nor Lstrings of the prototypes. Default true.
---@field progress? fun(phase: "prototype"|"place", k: integer, n: integer)
---@field count? integer With `place`: the number of plants.
---@field place? fun(i: integer): lsys.Plant With `count`: plant i.

--- Many plants in one scene (docs/population.md): `plants` is a list of lsys.Plant, or
--- `{ count = N, place = function (i) return plant end }` (the options may be keys of it
--- too). Plants with the same model, lstring, seed, steps, env and view share a prototype,
--- derived and interpreted once; each plant is an instance of it. The same list gives the
--- same scene. Raises `lsys.population: plant I: 'FIELD' must be ...` (or `place(I): ...`,
--- `plant I (prototype K): ...` when its model fails).
---@param plants lsys.Plant[]|lsys.PopulationOptions
---@param opts? lsys.PopulationOptions
---@return lsys.Scene
function lsys.population(plants, opts) end

--- Renders a Scene (or a Model: derived and interpreted) headless with OSMesa. With
--- `opts.out` writes a PNG and returns true; otherwise returns the RGBA pixels (top row
--- first), the width and the height. Other fields of `opts` (or `opts.view`) are view options
--- for this picture: camera, background, light, supersample. Raises `lsys.render: an options
--- table expected`, `lsys.render: a Scene or a Model expected`, `lsys.render: unknown option
--- 'K'`, a view error, and, in a build without OSMesa, `lsys was built without OSMesa: ...`.
---@param x lsys.Scene|lsys.Model
---@param opts? lsys.RenderOptions
---@return true|string pixels
---@return integer? width
---@return integer? height
function lsys.render(x, opts) end

--- Options of `lsys.render` besides view fields (lsys.View: camera, background, light,
--- supersample), which may also be given here directly.
---@class lsys.RenderOptions: lsys.View
---@field out? string The PNG file to write (atomically). Without it the pixels are returned.
---@field width? integer Pixels (800).
---@field height? integer Pixels (800).
---@field zoom? number Magnifies about the centre of the picture (1).
---@field transparent? boolean A transparent background (an RGBA PNG). Default false.
---@field wireframe? boolean Triangles drawn as their edges. Default false.
---@field fit? number[] A box {x0, y0, z0, x1, y1, z1} the camera frames instead of the scene.
---@field view? lsys.View View fields for this picture.

--- Writes one PNG picture per derivation step of `m` (a Model or a component graph's root)
--- into `opts.dir`, all through one camera fitted to the last step, so the plant grows in
--- place (docs/drawing.md, section 6). Returns the paths written and the steps they show.
--- Raises `lsys.frames: option 'K' ...` for a bad option, and naming the folder or file
--- that cannot be written.
---@param m lsys.Model
---@param opts lsys.FramesOptions
---@return string[] files
---@return integer[] steps
function lsys.frames(m, opts) end

--- Writes an animation of `m` growing (one frame per step, one camera) to `opts.out`, an
--- .mp4 (H.264, yuv420p) or a .gif, through ffmpeg. Returns `out`, the number of frames,
--- the width and the height. Raises when ffmpeg is not installed (saying how to install it),
--- when it fails (with the last lines it printed), and for bad options.
---@param m lsys.Model
---@param opts lsys.AnimateOptions
---@return string out
---@return integer frames
---@return integer width
---@return integer height
function lsys.animate(m, opts) end

--- Writes a turntable of `x` (a Model, a component graph's root or a Scene): its final plant
--- seen by a camera going once around it about the view's up (or `opts.axis`), fitted once
--- to the plant's bounding sphere, to `opts.out` (an .mp4 or .gif, through ffmpeg) or as PNG
--- pictures orbit-0000.png, ... into `opts.dir` (docs/drawing.md, section 6). Returns `out`
--- (or the list of pictures), the number of frames, the width, the height, the frames'
--- cameras ({ angle =, viewpoint =, target =, up =, zoom = }) and the box `fit` they go
--- with. Raises `lsys.orbit: option 'K' ...` for a bad option.
---@param x lsys.Model|lsys.Scene
---@param opts lsys.OrbitOptions
---@return string|string[] out
---@return integer frames
---@return integer width
---@return integer height
---@return table[] cameras
---@return number[] fit
function lsys.orbit(x, opts) end

---@class lsys.OrbitOptions
---@field out? string The .mp4 or .gif file (or `dir`).
---@field dir? string The folder for PNG pictures (or `out`).
---@field frames? integer Frames in the turn (72).
---@field seconds? number The turn's length at `fps` (instead of `frames`).
---@field fps? number Frames a second (24).
---@field axis? number[] The axis {x, y, z} (the view's up, else +y).
---@field steps? integer A model's steps (`m.steps`).
---@field width? integer Pixels (800; even for .mp4).
---@field height? integer Pixels (800; even for .mp4).
---@field view? lsys.View View fields (a model's interpretation; a scene's camera).
---@field zoom? number Magnifies the fitted picture (1).
---@field wireframe? boolean As lsys.render.
---@field transparent? boolean As lsys.render (PNG pictures only).
---@field progress? fun(phase: string, k: integer, n: integer, detail: any, what: any)
---@field ffmpeg? string The program ("ffmpeg" on PATH).

---@class lsys.SeriesOptions
---@field every? integer Steps 0, K, 2K, ... and always the last (1).
---@field steps? integer The steps derived (`m.steps`).
---@field width? integer Pixels (800).
---@field height? integer Pixels (800).
---@field view? lsys.View View fields for the interpretation.
---@field zoom? number As lsys.render.
---@field wireframe? boolean As lsys.render.
---@field progress? fun(phase: "derive"|"frame"|"encode", k: integer, n: integer, detail: any, step: integer?) "derive": step k of n derived (detail: modules); "frame": picture k of n written (detail: its path; k = 0 before the first); "encode": before ffmpeg runs.

---@class lsys.FramesOptions: lsys.SeriesOptions
---@field dir string The folder (made when missing).
---@field pattern? string The file names, %d the step ("step-%04d.png").
---@field transparent? boolean As lsys.render.

---@class lsys.AnimateOptions: lsys.SeriesOptions
---@field out string The .mp4 or .gif file (written whole or not at all).
---@field fps? number Frames a second (4).
---@field hold? number Seconds the last frame stays (0).
---@field ffmpeg? string The program ("ffmpeg", on PATH).

--- Shows a Model (every step, the last first), an Lstring, a Scene or a list of Scenes in
--- the viewer window, opening it if needed, and returns at once (docs/viewer.md). Raises
--- `lsys.show: ...` for bad options, and when no window can be opened (no display, lsys
--- built without the viewer).
---@param x lsys.Model|lsys.Lstring|lsys.Scene|lsys.Scene[]
---@param opts? lsys.ShowOptions
function lsys.show(x, opts) end

--- Handles the window's events until it is closed (`lsys.viewer.wait`).
function lsys.wait() end

---@class lsys.ShowOptions
---@field step? integer The step shown first (default: the last).
---@field steps? boolean `false`: only a model's last step is interpreted.
---@field rate? number Animation speed, steps per second (default 2).
---@field view? lsys.View View fields replacing the model's for this show.
---@field title? string Window title (after "lsys: ").
---@field width? integer Width of a new window (800).
---@field height? integer Height of a new window (800).
---@field samples? integer Multisampling of a new window (4; none on software renderers).
---@field status? boolean The status line (true).
---@field keep_camera? boolean Keep the window's camera instead of fitting.
---@field on_pick? fun(info: lsys.Pick) Called by `poll` for a click on a module.
---@field on_event? fun(ev: table) Called by `poll` for every window event.
---@field progress? fun(k: integer, n: integer) Called before interpreting step k of n.
---@field history? number The bytes a model's kept steps may take (default `lsys.viewer.HISTORY`, 256 MiB); beyond it the window keeps every 2nd, 4th, ... step and the last, with a warning.
---@field model? lsys.Model The model to interpret an Lstring that has none.
---@field lines? lsys.Line[] For a Scene: segments drawn over it.
---@field capture? boolean A tool takes the keys and Ctrl-drags: they come to `on_event` as `{ type = "key", key =, ctrl =, shift = }` and `{ type = "drag", phase = "begin"|"move"|"end", x =, y = }` (the arrows no longer step).
---@field frames_dir? string Where S, pressed while animating, saves every step ("NAME-frames").
---@field light_colours? boolean `true`: the leaves coloured by the light they receive from the first picture (the L key); `false`: the model's colours; nil: as the window had them.

--- An overlay segment of `lsys.show(scene, { lines = ... })`.
---@class lsys.Line
---@field p0 number[]
---@field p1 number[]
---@field color? number[] {r, g, b[, a]} in 0..1.
---@field width? number Pixels.
---@field ontop? boolean Drawn over the model instead of depth-tested.

--- What a click in the window hit.
---@class lsys.Pick
---@field module integer Index of the module in the string of that step (1-based).
---@field text? string The module in cpfg notation.
---@field name? string The module's name.
---@field lstring? lsys.Lstring The string of that step.
---@field step? integer The derivation step shown.
---@field frame integer The frame shown (1-based).
---@field kind string The turtle record kind ("segment", "gcyl", "sphere", ...).
---@field x number Window x of the click (pixels from the left).
---@field y number Window y of the click (pixels from the top).

--- The viewer window (docs/viewer.md). Without a window (none open, no display, lsys built
--- without the viewer) `open`, `show`, `key`, `screenshot` and `light` raise; `poll`,
--- `sync`, `pending`, `state`, `project`, `colour`, `wait` and `close` do nothing and answer
--- as for a closed window (false, 0, nil).
---@class lsys.viewer
---@field on_pick? fun(info: lsys.Pick) Called for picks of shows without their own on_pick.
---@field last_pick? lsys.Pick The last pick.
---@field HISTORY number The default of the show option `history`: 256 MiB.
lsys.viewer = {}

--- The same as `lsys.show`.
---@param x lsys.Model|lsys.Lstring|lsys.Scene|lsys.Scene[]
---@param opts? lsys.ShowOptions
function lsys.viewer.show(x, opts) end

--- Handles the window's events (callbacks run here), waiting up to `timeout` seconds (0)
--- for the first. Returns true while the window is open.
---@param timeout? number
---@return boolean
function lsys.viewer.poll(timeout) end
--- Polls until the window is closed.
function lsys.viewer.wait() end
--- Opens an empty window unless one is open. Raises `lsys.viewer.open: ...` for bad options
--- and when no window can be opened.
---@param opts? { width?: integer, height?: integer, samples?: integer, status?: boolean }
function lsys.viewer.open(opts) end
--- True while the window is open. Deprecated: `lsys.viewer.state()`, nil without a window
--- and with `open` false once it was closed; the first call warns once.
---@deprecated
---@return boolean
function lsys.viewer.isopen() end
function lsys.viewer.close() end
--- Saves the next picture as the S key does; returns the path (default lsys-NNN.png).
---@param path? string
---@param timeout? number seconds (10)
---@return string
function lsys.viewer.screenshot(path, timeout) end
--- Waits until everything shown or keyed so far is on screen; true when it is.
---@param timeout? number seconds (10)
---@return boolean
function lsys.viewer.sync(timeout) end
--- The window's state, nil before the first window.
---@return { open: boolean, drawn: integer, drawms: number, serial: integer, width: integer, height: integer, fbwidth: integer, fbheight: integer, frame: integer, nframes: integer, step?: integer, playing: boolean, wireframe: boolean, light: boolean, scene: integer[] }?
function lsys.viewer.state() end
--- Window coordinates (pixels from the top left) and depth of a world point, with the
--- camera last drawn; nil when it is behind the eye or nothing was drawn.
---@param p number[]
---@return number? x
---@return number? y
---@return number? depth
function lsys.viewer.project(p) end
--- Presses a key of the window: "right" "left" "home" "end" "space" "r" "f" "w" "s" "h"
--- "l" "q" "escape" "+" "-" "redraw".
---@param name string
function lsys.viewer.key(name) end
--- The light colours of frame `k`'s leaves (default: the frame shown), computed unless they
--- were (docs/viewer.md, "Light on the leaves"). Raises `lsys.viewer.light: ...` without a
--- window, for a frame not shown and for bad options.
---@param k? integer
---@param opts? { threads?: integer, max_memory?: number }
---@return { frame: integer, leaves: integer, min: number, max: number, mean: number, msg?: string }
function lsys.viewer.light(k, opts) end
--- The colour triangle `t` of frame `k` (default: the frame shown) is drawn in now: its light
--- colour while the L key is on, else the model's; nil without a window.
---@param t integer
---@param k? integer
---@return number r
---@return number g
---@return number b
function lsys.viewer.colour(t, k) end
--- The colour of light `x` (0 to 1) on the L key's ramp.
---@param x number
---@return number r
---@return number g
---@return number b
function lsys.viewer.ramp(x) end
--- Events waiting for `poll`.
---@return integer
function lsys.viewer.pending() end
--- Shows a scene that changes in place (a growing world's) and returns at once; `patch`
--- then sends only what changed (docs/grow.md).
---@param scene lsys.Scene
---@param opts? { title?: string, width?: integer, height?: integer, samples?: integer, status?: boolean, fit?: number[], help?: string, on_event?: fun(ev: table) }
function lsys.viewer.live(scene, opts) end
--- Sends the window what changed in the scene shown by `live` since the last patch, with
--- the status line's tick, count and note; returns the request's serial number, which
--- `state().serial` reaches once it is drawn.
---@param scene lsys.Scene
---@param tick? integer
---@param count? integer
---@param note? string
---@return integer
function lsys.viewer.patch(scene, tick, count, note) end
--- The component instance that drew module `i` of `s`, and its path, or nil (what a pick
--- reports; `m`: the model that made `s`, default its owner or the last model shown).
---@param s lsys.Lstring
---@param i integer
---@param m? lsys.Model
---@return table? instance
---@return string? path
function lsys.viewer.instance(s, i, m) end

--- The directory of the Lua file that calls this ("." when not a file). A model's view
--- reads its relative file names from the folder of the file that made the model already;
--- `lsys.here()` gives that folder to other code (a file written next to the script).
---@return string
function lsys.here() end

--- The REPL (`lsys` with no arguments; docs/viewer.md#the-repl) sets `lsys.repl` to its
--- module, `require "lsys.repl"`.
lsys.repl = {}

--- How many significant digits the REPL shows of the floats in Lstrings and tables: 1 to
--- 17 (17 shows every value exactly: the shortest text that reads back as the same
--- number); nothing restores the defaults, 15 in Lstrings (`F(0.49)`) and 6 in tables.
--- Numbers on their own print as in `lua` whatever the setting; `tostring` and `print`
--- always give every digit. Raises `digits: give a whole number from 1 to 17, or nothing
--- for the defaults`.
---@param n? integer
function lsys.repl.digits(n) end

--- View options and cpfg view files (docs/drawing.md §2). The file readers live in
--- lsys.viewfile; this module gives them under the same names.
---@class lsys.view
---@field PALETTE table<integer, number[]> The default palette, `[0]` to `[12]`: 1 bark, 2 leaf green, 3 young green, 4 yellow, 5 red, 6 petal pink, 7 purple, 8 dark green, 9 blue, 10 white, 11 light wood, 12 dark grey (`{r, g, b}` in 0..1).
---@field DEFAULTS lsys.View The defaults `normalize` fills in (angle 90, step 1, line_width 1, line_style "line", contour_sides 8, projection "parallel", fov 30, supersample 3, ...).
---@field KINDS table<string, string> Every view option and the kind of value it takes ("number", "integer", "vec", "color", "contours", ...): the names `normalize` accepts.
---@field VIEWFILE_IGNORED table<string, true> View-file commands that lsys reads past with a warning (`front distance`, `z buffer`, `render mode`, ...).
lsys.view = {}

--- Checks a view table and returns a complete copy: defaults filled in, vectors and
--- colours normalised, the files it names (contours, surfaces, textures, a palette file)
--- read and parsed into lsys.Contour, lsys.Surface and lsys.Texture objects. Every
--- interpretation calls it; parsed files are cached while their bytes are unchanged.
--- Raises `WHERE: unknown view option 'K' (known: ...)`, `WHERE: 'view.K' must be ...`,
--- and file errors naming the option and the file.
---@param v? lsys.View Default `{}`.
---@param where? string Names the model in messages. Default `"view"`.
---@return lsys.View
function lsys.view.normalize(v, where) end

--- A copy of `v` with the fields of `over` replacing its own (both plain view tables;
--- either may be nil). Nothing is checked.
---@param v? lsys.View
---@param over? lsys.View
---@return lsys.View
function lsys.view.merge(v, over) end

--- The options table `core.interpret` and `core.query` read, from a normalised view: its
--- turtle fields under the view's own names (angle, step, line_width, line_style,
--- contour_sides, tropisms, torques, palette, contours, surfaces, textures, ...), how the
--- scene is to be looked at (background, light, viewpoint, target, up, direction,
--- projection, fov, twist: the scene keeps them) and `allow_system_calls`.
---@param v lsys.View A result of `normalize`.
---@param allow_system_calls? boolean Default false.
---@return table
function lsys.view.turtle_options(v, allow_system_calls) end

--- The options with which `core.render` looks at a scene another way, from a normalised
--- view: camera, light, background, supersample and the textures (left out when there
--- are none).
---@param v lsys.View A result of `normalize`.
---@return table
function lsys.view.render_options(v) end

---@deprecated Use `lsys.view.turtle_options` (the same function; warns once).
function lsys.view.turtle(v, allow_system_calls) end

---@deprecated Use `lsys.view.render_options` (the same function; warns once).
function lsys.view.render(v) end

--- Reads the text of a cpfg view file into a view table, as `load` does for a file.
--- Raises `NAME:LINE: ...`; `lsys.view.parse: the text must be a string`.
---@param text string
---@param name? string Names the text in messages. Default `"view"`.
---@param opts? { dir?: string, quiet?: boolean } `dir` becomes the view's `dir`; `quiet`: do not send the warnings to `warn`.
---@return lsys.View view
---@return string[] warnings
function lsys.view.parse(text, name, opts) end

--- Reads a cpfg view file (.v) into a view table; relative file names inside are resolved
--- against its directory. Returns the view and the list of warnings about recognised but
--- unsupported commands (also sent to Lua's `warn` unless `opts.quiet`: shown by the lsys
--- program and by `lua -W`). Raises `file:LINE: ...`, `lsys.view.load: cannot open ...`.
---@param path string
---@param opts? { quiet?: boolean }
---@return lsys.View view
---@return string[] warnings
function lsys.view.load(path, opts) end

--- Reads a cpfg colour map (.map: 256 RGB byte triples) into a palette table.
---@param path string
---@return table palette
function lsys.view.load_colormap(path) end

--- Reads a cpfg material file (.mat: 15-byte records) into a palette of materials.
---@param path string
---@return table palette
function lsys.view.load_materials(path) end

--- Whether `x` is a Scene. Deprecated: `lsys.type(x) == "scene"`; the first call warns once.
---@deprecated
---@return boolean
function lsys.isscene(x) end


-- ===========================================================================================
-- lsys.arrange: arranging a plant by inverse kinematics (docs/arrange.md; Power et al. 1999)

--- Starts arranging `s` (an Lstring of `model`, or its text, read by `model:lstring`;
--- default `model:derive()`), which is copied: the arrangement works on its own string.
--- The same as `require("lsys.arrange")(model, s, opts)`. Raises `lsys.arrange: a model
--- expected`, `lsys.arrange: an Lstring or its text expected`, `lsys.arrange: lstring: ...`
--- for malformed text, `lsys.arrange: an options table expected`, `lsys.arrange: unknown
--- option 'K'`, `lsys.arrange: option 'K' must be a TYPE`, `lsys.arrange: option 'radii'
--- must be 'width' or 'davinci'`, `lsys.arrange: option 'K' must be > 0`.
---@param model lsys.Model
---@param s? lsys.Lstring|string
---@param opts? lsys.ArrangeOptions
---@return lsys.Arrangement
function lsys.arrange(model, s, opts) end

--- Options of `lsys.arrange`. Section numbers and equations are those of Power et al. 1999.
---@class lsys.ArrangeOptions
---@field r0? number Trunk radius for the da Vinci rule (1), > 0.
---@field s0u? number Flexural stiffness of the trunk (1), > 0: c_f = s0u / r0^4 (eq. 4).
---@field s0h? number Torsional stiffness of the trunk (1), > 0: c_t = s0h / r0^4 (eq. 5).
---@field radii? "width"|"davinci" Branch radii from the turtle widths (radius = width / 2) or the da Vinci rule (eq. 6). Default: widths when the model sets them.
---@field wp? number Weight of the end position in eq. 1 (1000), divided by the squared length of the path's axis.
---@field wt? number Weight of the end's twist vectors (1).
---@field we? number Weight of the stiffness energy (1); the stiffness is divided by its mean along the path.
---@field ws? number Weight of smoothness between neighbouring joints (0.1; 0 when the string has Z stiffness).
---@field max_iter? integer Iterations of the solver per dragger call (200).
---@field view? lsys.View View fields used when interpreting the arranged string.
---@field leaf_length? number Length of the virtual segment of a leaf or flower picked as the end (default: its size).

--- What a dragger returns: the solver's result.
---@class lsys.SolveResult
---@field status "gtol"|"ftol"|"maxiter"|"maxeval"|"linesearch" Why it stopped ("gtol" and "ftol": converged).
---@field iterations integer
---@field evaluations integer Evaluations of the objective.
---@field f0 number The objective at the start.
---@field f number The objective at the end.
---@field dist number Distance of the path's end from its target.

--- An arrangement: a copy of the string with `@J(h, u, l)` joint modules (degrees) that the
--- draggers set, and the selected branch path. Module indices are those of the arranged
--- string (`a:lstring()`); selecting adds missing `@J` modules, which shifts the indices
--- after them. Methods take positional arguments (an optional table of settings last), and
--- their errors begin with the method's name (`select: ...`).
---@class lsys.Arrangement
---@field model lsys.Model
---@field scene lsys.Scene The scene of the arranged string as last interpreted.
local Arrangement = {}

--- Selects the branch path (§3.2): `fixed` is the segment at whose start the path is held,
--- `moved` the segment, leaf or flower whose end the draggers move (default `fixed`); both
--- module indices or picks (lsys.Pick). `moved` must be in the active branch of `fixed`.
--- Adds the missing `@J` modules. Raises `select: ...` (e.g. `the fixed point must be on a
--- segment`, `module I is not in the active branch of module J (above it)`, `fixed: module I
--- (NAME) draws nothing that can be arranged`). The table `{ fixed =, moved = }` of 0.1.0
--- still works for one release and warns once that it is deprecated.
---@param fixed integer|lsys.Pick
---@param moved? integer|lsys.Pick
---@return integer joints The number of joints of the path.
function Arrangement:select(fixed, moved) end

--- Moves the fixed point as ilsa's arrow keys do: "up" along its axis towards the branch
--- end, "down" towards the base, "left" and "right" to the sibling branches. The path
--- becomes the fixed segment alone. Raises without a selection or for another direction.
---@param dir "up"|"down"|"left"|"right"
---@return integer? module The new fixed module, or nil when there is nowhere to go.
function Arrangement:move_fixed(dir) end

--- The module indices of the selected path's segments, root first.
---@return integer[]
function Arrangement:path_modules() end

--- The module indices of every segment from the fixed point up (the active branch), in
--- order.
---@return integer[]
function Arrangement:active_modules() end

--- Spherical dragger: turns the path about its fixed point by `angle` degrees about `axis`
--- (end and twist vectors turned together), then solves. Raises `spherical: select a branch
--- path first`. The table `{ axis =, angle = }` of 0.1.0 still works for one release and
--- warns once that it is deprecated.
---@param axis number[] `{x, y, z}`, world space.
---@param angle number Degrees.
---@return lsys.SolveResult
function Arrangement:spherical(axis, angle) end

--- Disc dragger: twists the path by `angle` degrees about its axis; the end stays.
---@param angle number Degrees.
---@return lsys.SolveResult
function Arrangement:disc(angle) end

--- Axis dragger: moves the end by `distance` along the path's axis; the twist stays.
---@param distance number Model units.
---@return lsys.SolveResult
function Arrangement:axis(distance) end

--- 2D-plane dragger: moves the end by `dx`, `dy` in the plane of `view.right` and `view.up`
--- (world vectors; default the xy plane); the twist stays.
---@param dx number
---@param dy number
---@param view? { right?: number[], up?: number[] }
---@return lsys.SolveResult
function Arrangement:plane(dx, dy, view) end

--- Keeps the current arrangement as the start of the next dragger call (a new drag):
--- draggers set their targets relative to where the last commit or select left the path.
function Arrangement:commit() end

--- Undoes the last dragger call or prune. Returns false when there is nothing to undo.
---@return boolean
function Arrangement:undo_last() end

--- Prunes the branch that starts at module `k` (a segment: it and everything drawn after
--- it up to the end of its branch), leaving the marker `@X`, which the turtle ignores and
--- productions may rewrite. Clears the selection.
---@param k integer|lsys.Pick
---@return integer removed The number of modules removed.
function Arrangement:prune(k) end

--- The arranged string: a copy, so arranging on does not change it.
---@return lsys.Lstring
function Arrangement:lstring() end

--- The scene of the arranged string, interpreted again when it changed.
---@return lsys.Scene
function Arrangement:interpret() end

--- The stiffness `{sh, su, sl}` of the joint before the segment drawn by module `i` (from
--- `Z`, or computed from the radii, eqs. 4 and 5).
---@param i integer
---@return number[]?
function Arrangement:stiffness(i) end

--- The radius the stiffness of module `i`'s segment was computed with (nil with `Z`).
---@param i integer
---@return number?
function Arrangement:radius(i) end

--- The arrangement window (`lsys arrange MODEL`), `require "lsys.arrange_ui"`.
---@class lsys.arrange_ui
---@field RED number[] Colour of the active branch's highlight.
---@field YELLOW number[] Colour of the branch path's highlight.
local arrange_ui = {}

--- The highlight of the paper's figure 6 as overlay lines (`lines` of `lsys.show`): the
--- active branch red, the branch path yellow; segments as thick lines, leaves and flowers
--- as their wireframe (`Scene:edges`).
---@param arr lsys.Arrangement
---@param scene lsys.Scene `arr:interpret()`, before it is shown.
---@return lsys.Line[]
function arrange_ui.highlight(arr, scene) end

--- Runs an arrangement session in the viewer window until it is closed (clicks select,
--- Ctrl-drags drag, arrow keys move the fixed point, Delete prunes, U undoes, Ctrl-S saves).
---@param arr lsys.Arrangement
---@param opts? { out?: string, width?: integer, height?: integer, title?: string, say?: fun(msg: string), on_change?: fun() } `out`: where Ctrl-S saves the arranged string; `say` prints messages (default: stdout); `on_change` is called after every change.
function arrange_ui.run(arr, opts) end


-- ===========================================================================================
-- lsys.func: positional functions (lua/lsys/func.lua, csrc/lua/lua_func.c; manual §5,
-- "Positional functions")

--- cpfg's B-spline functions y = f(x) of a relative position x in [0, 1].
---@class lsys.func
lsys.func = {}

--- A function from its control points: at least 4, x nondecreasing from 0 to 1 (within
--- 1e-6). `samples` 0 gives exact values; N > 2 cpfg's table of N values, interpolated.
--- Raises `lsys.func.new: point 3: x is 0.4, less than the x of point 2 (0.5)`, ...
---@param opts {points: number[][], name?: string, samples?: integer}
---@return lsys.Func
function lsys.func.new(opts) end

--- A `.func` file as an lsys.Func; a `.fset` file as a list of Funcs that is also a table
--- by name. Raises `lsys.func.load: FILE:LINE: ...`.
---@param path string
---@return lsys.Func|table<string|integer, lsys.Func>
function lsys.func.load(path) end

--- Writes `f` as a cpfg `fver 1 1` file, atomically.
---@param f lsys.Func
---@param path string
function lsys.func.save(f, path) end

--- Writes the Funcs as a cpfg function set (`funcgalleryver 1 1`, `.fset`), atomically.
---@param fs lsys.Func[] At least one.
---@param path string
function lsys.func.save_set(fs, path) end

--- A positional function (metatable "lsys.Func"): `f(x)` evaluates it, x clamped into
--- [0, 1]. Rules call it on the expression machine: by name in `env`, or `func(ID, x)`.
---@class lsys.Func
---@overload fun(x: number): number
local Func = {}

---@param x number
---@return number
function Func:eval(x) end
--- The control points, `{ {x, y}, ... }`.
---@return number[][]
function Func:points() end
---@return string
function Func:name() end
--- 0 for exact values, else the number of table samples.
---@return integer
function Func:samples() end
--- The `.func` file's text.
---@return string
function Func:format() end


-- ===========================================================================================
-- lsys.sketch: sketch-based parameterization (Anastacio et al. 2009; docs/sketch.md).
-- `require "lsys.sketch"`, or `lsys.sketch` (loaded at first use). Its `read`, `organ` and
-- `plot` fields load those modules at first use; reading a sketch needs lua-cjson (JSON)
-- and lua-expat (SVG), and raises naming the Debian package when one is missing.

---@class lsys.sketch
---@field read lsys.sketch.read Sketch files: JSON, SVG, tables.
---@field organ lsys.sketch.organ Organs from three views (§6).
---@field plot lsys.sketch.plot Plots of the functions and drawings of sketches.
---@field geometry table The analysis steps (§3), for the tests and the window.
---@field functions table The positional functions' construction (§4).
---@field templates table The phyllotaxis templates (§5).
---@field Sketch lsys.Sketch The Sketch metatable.
lsys.sketch = {}

---@class lsys.SketchLoadOptions
---@field nodes_per_layer? integer Overrides the file's (default 3).
---@field phyllotaxis? "distichous"|"decussate"|"fibonacci" Overrides the file's.
---@field depth? boolean true: a 3D stem from the pressure; false: 2D; nil: 3D when the stem's pressure is not 0.5 everywhere.
---@field near? number Depth of pressure 1 in stem lengths (0.3).
---@field far? number Depth of pressure 0 (-0.3).
---@field resolution? number The longest straight piece of the drawn stem, in stem lengths (1/32).
---@field name? string Names a table sketch in messages.

--- Loads a sketch (a `.json` or `.svg` file, or a table as the JSON file). Raises naming
--- the file and the stroke (`plant.json: stroke 4 (boundary_left): lies right of the stem`
--- comes later, from the analysis).
---@param src string|table
---@param opts? lsys.SketchLoadOptions
---@return lsys.Sketch
function lsys.sketch.load(src, opts) end

--- The rules of a template as text (2D unless `threed`).
---@param name "distichous"|"decussate"|"fibonacci"
---@param threed? boolean
---@return string
function lsys.sketch.template(name, threed) end

--- True when `x` is a Sketch (also `lsys.type(x) == "sketch"`).
---@return boolean
function lsys.sketch.issketch(x) end

--- One Model of two or more plants drawn on one stem (§7.2): the first draws its stem, the
--- others' names take the suffixes 2, 3, ... and their stems move without drawing.
--- Raises `lsys.sketch.compose: ...` for fewer than two Models or one not made by sk:model.
---@param models lsys.Model[] Models made by sk:model.
---@param opts? {name?: string, view?: lsys.View}
---@return lsys.Model
function lsys.sketch.compose(models, opts) end

--- Writes a Model made by sk:model or lsys.sketch.compose as a Lua model file (as
--- sk:save_model). Returns `path`.
---@param m lsys.Model
---@param path string
---@return string
function lsys.sketch.save_model(m, path) end

--- Writes a Model made by sk:model or lsys.sketch.compose as cpfg's files (as
--- sk:save_cpfg).
---@param m lsys.Model
---@param path string A `.l` file.
---@return string[] files, integer inexact
function lsys.sketch.save_cpfg(m, path) end

---@class lsys.SketchModelOptions
---@field phyllotaxis? "distichous"|"decussate"|"fibonacci"
---@field nodes_per_layer? integer
---@field organ? string|lsys.Organ|lsys.Surface|lsys.Sketch|lsys.Model nil: a flat leaf; "~X": the view's surface X; an organ or surface, drawn as ~P; a Sketch or a Model of sk:model: composition (§7.2).
---@field steps? integer Default: enough to finish the plant.
---@field depth? boolean Force a 3D or 2D stem.
---@field width? number Stem diameter in stem lengths (0.01).
---@field color? integer Stem colour index (1).
---@field organ_color? integer (2)
---@field name? string
---@field view? lsys.View More view options.

--- A loaded sketch (lua/lsys/sketch/init.lua). Lengths are in stem lengths, x the relative
--- position along the stem.
---@class lsys.Sketch
---@field file string? The file it was read from.
---@field nodes_per_layer integer
---@field phyllotaxis string
local Sketch = {}

--- The positional functions of §4: `internode`, `stem_shape` (2D) or `yaw` and `pitch`
--- (3D), `angle_left`, `angle_right`, `size_left`, `size_right`.
---@param opts? {depth?: boolean, nodes_per_layer?: integer}
---@return table<string, lsys.Func>
function Sketch:functions(opts) end
--- The functions' polylines, `{ name = { {x, y}, ... } }`.
---@param opts? {depth?: boolean, nodes_per_layer?: integer}
---@return table<string, number[][]>
function Sketch:function_points(opts) end
--- The geometry of §3 (docs/sketch.md, The pipeline): threed, length, base, stem, left,
--- right, lines, layers, nodes.
---@param opts? {depth?: boolean, nodes_per_layer?: integer}
---@return table
function Sketch:analysis(opts) end
--- An lsys Model of the sketch: the template of the phyllotaxis with its functions, on
--- the expression machine. Raises `model: unknown option 'K'`, geometric errors naming
--- the file and stroke.
---@param opts? lsys.SketchModelOptions
---@return lsys.Model
function Sketch:model(opts) end
--- Writes a Lua model file that `dofile` makes into the same Model; an organ of
--- lsys.sketch.organ is written beside it (plant.lua: plant.organ.s). Returns `path`.
---@param path string
---@param opts? lsys.SketchModelOptions
---@return string
function Sketch:save_model(path, opts) end
--- Writes the plant as cpfg's files (docs/sketch.md, cpfg and L-studio): `path` (a `.l`
--- file), its `.v` view file, a `.func` file a function, a `.map` colour map and the organ's
--- surface beside it, which cpfg derives to lsys's string. Returns the files written and
--- how many function readings lie closer together than cpfg tells apart (0 but for very
--- dense nodes).
---@param path string
---@param opts? lsys.SketchModelOptions
---@return string[] files, integer inexact
function Sketch:save_cpfg(path, opts) end
--- Writes the sketch as JSON (lsys.sketch.read's save). Returns `path`.
---@param path string
---@return string
function Sketch:save(path) end
---@param n integer
function Sketch:set_nodes_per_layer(n) end
---@param p "distichous"|"decussate"|"fibonacci"
function Sketch:set_phyllotaxis(p) end

--- Sketch files (lua/lsys/sketch/read.lua; docs/sketch.md, Sketch files). Each returns the
--- normalized sketch table `{ file, width, height, nodes_per_layer, phyllotaxis, depth,
--- strokes = { {role, index, id, points}, ... }, warnings }`.
---@class lsys.sketch.read
local read = {}
---@param path string A `.json` or `.svg` file.
---@return table
function read.file(path) end
---@param text string
---@param name? string
---@return table
function read.json(text, name) end
---@param text string
---@param name? string
---@return table
function read.svg(text, name) end
---@param t table
---@param name? string
---@return table
function read.table(t, name) end
---@param sk table
---@return string
function read.to_json(sk) end
---@param sk table
---@param path string
function read.save(sk, path) end

--- Organs drawn in three views (Anastacio et al. 2009, §6; lua/lsys/sketch/organ.lua).
--- Strokes are `{ {x, y}, ... }` in pixels, y down. `organ(t)` is `organ.build(t)`.
---@class lsys.sketch.organ
---@overload fun(t: lsys.OrganStrokes): lsys.Organ
---@field Organ lsys.Organ The metatable.
local organ = {}

---@class lsys.OrganStrokes
---@field top {left?: number[][], right?: number[][]} The boundaries in the top view (one is mirrored when the other is missing).
---@field side? number[][] The midrib seen from the left.
---@field front? number[][] The cross-section seen from the base.
---@field resolution? integer[] `{across, along}` patches (default: fitted, 2 x 4 up to 16 x 32).
---@field precision? integer[] `{s, t}` lines of the surface file.
---@field name? string Default "organ".
---@field width_scale? number Multiplies the width (1).
---@field capture? boolean Stroke capture of §3.1 (true).

--- An Organ from its strokes. Raises `lsys.sketch.organ: top left stroke: ...`.
---@param t lsys.OrganStrokes
---@return lsys.Organ
function organ.build(t) end
--- An Organ from a JSON file `{"organ": {...}}` or such a table.
---@param x string|table
---@return lsys.Organ
function organ.load(x) end
--- The strokes of a common leaf, built.
---@param o? {shape?: "ovate"|"lanceolate"|"elliptic"|"obovate"|"linear"|"cordate", width?: number, curl?: number, section?: "flat"|"v"|"cup", depth?: number, length?: number, name?: string, resolution?: integer[], precision?: integer[]}
---@return lsys.Organ
function organ.leaf(o) end

--- An organ surface: 1 long from its base (the contact point) along +y, x across, z up;
--- `~P(h)` draws it h long. A view's `surfaces` take it as a file name.
---@class lsys.Organ
---@field name string
---@field size number
---@field resolution integer[] `{across, along}` patches.
---@field precision integer[]
---@field fit_error number The patches' distance from the blended surface over `size`.
local Organ = {}
--- The lsys.Surface (made once).
---@return lsys.Surface
function Organ:surface() end
--- The cpfg surface file's text.
---@return string
function Organ:text() end
--- Writes the surface file, atomically. Raises `save: ...`.
---@param path string
---@return lsys.Organ
function Organ:save(path) end
--- Writes the strokes as JSON (needs lua-cjson).
---@param path string
function Organ:save_json(path) end
--- Writes the organ alone as `.obj`, `.ply` or `.glb`.
---@param path string
---@param view? lsys.View
function Organ:save_mesh(path, view) end
--- `{ organ = { ... } }`: the strokes and options, for JSON.
---@return table
function Organ:to_table() end
--- The blended surface at (s, t), in the organ's frame.
---@return number x
---@return number y
---@return number z
function Organ:blend(s, t) end
--- The fitted patches at (s, t).
---@return number x
---@return number y
---@return number z
function Organ:point(s, t) end

--- Plots of a sketch's functions and drawings of sketches (§7; lua/lsys/sketch/plot.lua).
---@class lsys.sketch.plot
---@field PANELS table[] The panels, in order.
---@field COLORS table<string, string> Colours of the function plots.
---@field SKETCH_COLORS table<string, string> Colours of the sketch drawing.
local plot = {}
--- Draws the functions' panels. Returns the canvas and the panels
--- `{ key, title, x, y, w, h, ymin, ymax, min, max }`.
---@param funcs table<string, lsys.Func|function|table> `sk:functions()`.
---@param opts? {width?: integer, height?: integer, background?: string, colors?: table, points?: boolean, marker?: number, scale?: integer, line_width?: number, canvas?: lsys.Canvas, region?: number[]}
---@return lsys.Canvas
---@return table[] panels
function plot.functions(funcs, opts) end
--- The same, written to a PNG (atomically).
---@param what lsys.Sketch|table
---@param path string
---@param opts? table As `functions`.
---@return lsys.Canvas
---@return table[] panels
function plot.png(what, path, opts) end
--- Draws a normalized sketch into `c` (opts: region, margin, analysis, background, colors).
--- Returns where a sketch point (u, v) lands: `(x + u * scale, y + v * scale)`.
---@param sk table
---@param c lsys.Canvas
---@param opts? table
---@return {x: number, y: number, scale: number}
function plot.sketch(sk, c, opts) end
--- Draws a sketch's analysis (its nodes and the rays of §3.4) into `c`, a sketch point
--- (u, v) at `(map.x + u * map.scale, map.y + v * map.scale)`.
---@param c lsys.Canvas
---@param an table `sk:analysis()`
---@param map {x: number, y: number, scale: number}
---@param opts? {colors?: table, line_width?: number}
---@return lsys.Canvas
function plot.analysis(c, an, map, opts) end
--- The stem colour of pen pressure p (§3.5, §7.3).
---@param p number
---@param colors? table
---@return number[]
function plot.depth_color(p, colors) end
--- The y range shown for sampled values lo..hi.
---@return number ymin
---@return number ymax
function plot.yrange(lo, hi) end

-- ===========================================================================================
-- lsys.Lstring (C: csrc/lua/lua_lstring.c, metatable "lsys.Lstring")

--- A module string: symbol codes and a pool of double parameters in C arrays. Made by
--- derive, step, expand, lsys.lstring and Model:lstring; no method but `set` changes it.
--- `tostring(s)` gives cpfg text (numbers in the shortest form that reads back to the same
--- double, integral values without a decimal point, spaces only where names would run
--- together). `a == b` is true when both have the same modules and bit-identical
--- parameters (`F(0)` and `F(-0)` differ). `a .. b` makes a new Lstring; both operands must
--- be Lstrings (raises `bad argument #2 to 'concat' (lsys.Lstring expected, got TYPE)`).
--- `local s <close> = ...` frees the memory when `s` goes out of scope; a closed Lstring is
--- empty.
---@class lsys.Lstring
---@operator len: integer
---@operator concat(lsys.Lstring): lsys.Lstring
local Lstring = {}

--- Modules `i` to `j` (inclusive) as a new Lstring with their parameters. Indices work as in
--- `string.sub`: negative ones count from the end, out-of-range ones are clamped, `i > j`
--- gives an empty Lstring.
---@param i integer
---@param j? integer Default -1 (the last module).
---@return lsys.Lstring
function Lstring:sub(i, j) end

--- The text of modules `i` to `j`, like `tostring(s:sub(i, j))` without making an Lstring.
--- With `digits`, parameters are rounded to that many significant digits (`F(0.49)` for
--- 0.48999999999999994 with 15; whole numbers below 1e15 stay whole): what the REPL shows.
--- Raises `bad argument #4 to 'text' (digits must be from 1 to 17)`.
---@param i? integer Default 1.
---@param j? integer Default -1.
---@param digits? integer 1 to 17. Default: exact (the shortest text that reads back as the same double).
---@return string
function Lstring:text(i, j, digits) end

--- The name and the parameters (floats) of module `i`; negative `i` counts from the end.
--- Raises `bad argument #1 to 'module' (module index out of range)`.
---@param i integer
---@return string name
---@return number ... # the parameters, as many as the module has
function Lstring:module(i) end

--- An iterator over the modules: `for i, name, p1, p2 in s:modules() do ... end` gives the
--- 1-based index, the name and the parameters (floats) of each module in order. Makes no
--- table per module.
---@return fun(): integer?, string, ...
function Lstring:modules() end

--- Number of modules named `name` (0 when no module of any model has that name).
---@param name string
---@return integer
function Lstring:count(name) end

--- Count of every module name in the string.
---@return table<string, integer>
function Lstring:counts() end

--- A new Lstring with the same modules.
---@return lsys.Lstring
function Lstring:copy() end

--- Writes the text of the string (the bytes of `tostring(s)`), then `tail`, to `target`: an
--- open file, or a path replaced atomically once everything was written. Streamed from C in
--- 64 KiB pieces: no Lua string of the whole text is made. Raises when the file cannot be
--- written (the file at the path is then left as it was).
---@param target file*|string
---@param tail? string written after the text (default: nothing)
---@return lsys.Lstring s
function Lstring:write(target, tail) end

--- Memory held by the string's arrays, in bytes (capacity, not length).
---@return integer
function Lstring:bytes() end

--- Replaces the parameters of module `i` in place (negative `i` counts from the end); as
--- many values as the module has. The arrangement (lsys.arrange) moves its `@J` joints this
--- way. Raises `bad argument #1 to 'set' (module index out of range)`,
--- `set: module I has N parameters, got M`, `bad argument #K to 'set' (not a finite number)`.
---@param i integer
---@param ... number The new parameters, finite.
function Lstring:set(i, ...) end

--- A new Lstring with `piece` inserted before each of the module indices in `positions`, in
--- one pass (`#s + 1` appends). Raises `insert: positions must be ascending module indices
--- from 1 to N (entry K)`.
---@param positions integer[] Ascending (repeats allowed: one copy of `piece` each).
---@param piece lsys.Lstring
---@return lsys.Lstring
function Lstring:insert(positions, piece) end


-- ===========================================================================================
-- lsys.core: the C module (csrc/lua/). lsys.lsystem, Model:interpret, lsys.render,
-- lsys.view and lsys.viewer are built on it; use it directly only to write another front
-- end. Its names are the raw ones the C side registers, mostly noun first (contour_load,
-- surface_parse, png_read); the public names of `require "lsys"` are verb first within
-- their module (lsys.view.load, lsys.view.load_colormap, lsys.parse_size).

---@class lsys.core
---@field has_render boolean Whether this build renders (OSMesa); false with `LSYS_WITH_OSMESA=OFF`.
---@field has_viewer boolean Whether this build has the window (GLFW); false with `LSYS_WITH_VIEWER=OFF`.
---@field MAXPARAMS integer Parameters per module at most: 31.
---@field MAXTROPISMS integer Tropisms and torques of a view together at most (the turtle's limit).
---@field RF_CALL integer Rule flag 1: the rule has a condition or computed values (a callback or machine program).
---@field RF_DYN integer Rule flag 2: a Lua function produces the successor.
---@field RF_STOCH integer Rule flag 4: the rule has a weight.
---@field RF_WEXPR integer Rule flag 8: the weight is computed (the first value the callback returns).
local core = {}

--- A new, empty rule store: the C side of one model. All stores of a Lua state share one
--- alphabet of at most 2047 module names.
---@param names? string Declared multi-character module names (`"Apex Leaf"`).
---@return lsys.Rules
function core.rules(names) end

--- Parses text into an Lstring without declared names. Raises `lstring: MESSAGE at
--- character C`.
---@param text string
---@return lsys.Lstring
function core.lstring(text) end

--- The Rules that made the Lstring `s` (its owner), or nil for a string made without rules:
--- how lsys.model finds the model of a string. Raises for anything but an Lstring; answers
--- for a closed one too (the user value it reads stays after a close).
---@param s lsys.Lstring
---@return lsys.Rules?
function core.lstring_rules(s) end

--- Same as `lsys.produce`.
---@param template string
---@param ... number
---@return true
function core.produce(template, ...) end

--- Same as `lsys.nproduce`.
---@param template string
---@param ... number
---@return true
function core.nproduce(template, ...) end


-- ===========================================================================================
-- lsys.Rules (metatable "lsys.Rules")

--- Rule kinds: 0 productions, 1 decomposition, 2 homomorphism.
---@alias lsys.RuleKind 0|1|2

--- A module of a parsed rule.
---@class lsys.ParsedModule
---@field sym integer Symbol id in the shared alphabet.
---@field name string
---@field pos integer 1-based byte offset of the name in the rule text.
---@field params string[] Formal names (patterns) or expression texts (successors).

--- The parts of a rule, from `Rules:parse`.
---@class lsys.ParsedRule
---@field lc lsys.ParsedModule[] Left context.
---@field pred lsys.ParsedModule? Predecessor (absent in "successor" mode).
---@field rc lsys.ParsedModule[] Right context.
---@field succ lsys.ParsedModule[] Successor (empty for `*` and in "pattern" mode).
---@field cond string? Condition text.
---@field weight string? Weight text.
---@field empty boolean The successor is `*`.

--- A compiled rule for `Rules:add`. Module lists are flat `{sym, np, sym, np, ...}`;
--- `src` has one `{kind, idx, value}` triple per successor parameter: kind 0 constant
--- `value`, 1 formal parameter `idx` (0-based over lc, pred, rc), 2 computed value `idx`.
---@class lsys.RuleSpec
---@field lc? integer[]
---@field pred integer[] `{sym, np}`
---@field rc? integer[]
---@field succ? integer[]
---@field src? number[]
---@field flags? integer Sum of `core.RF_*`. Default 0.
---@field nvals? integer Values the callback returns after `true` (the weight first when RF_WEXPR). Default 0.
---@field weight? number Constant weight (RF_STOCH). Default 1.
---@field id? integer The caller's rule number, for messages. Default 0.
---@field fn? function The callback: a closure `(formals...) -> true, values... | false` (RF_CALL) or a rule function that calls produce (RF_DYN).

--- Keys of `Rules:config`.
---@alias lsys.ConfigKey
---| "ring"                # boolean: contexts wrap around
---| "max_modules"         # number from 1 to 1e12
---| "group"               # integer from 0 to 999999: the active rule group
---| "depth_decomposition" # integer from 0 to 1024
---| "depth_homomorphism"  # integer from 0 to 1024
---| "seed"                # number: reseeds the derivation generator
---| "hseed"               # number: reseeds the homomorphism generator
---| "max_memory"          # number of bytes >= 0: this model's memory budget (0: the process-wide one)

--- The compiled rules of one model, their settings and the two generators.
---@class lsys.Rules
local Rules = {}

--- Splits one rule into its parts without adding it. Module names are interned.
---@param text string
---@param mode? "rule"|"pattern"|"successor" `"rule"` (default): a full rule; `"pattern"`: `lc < pred > rc` only (function rules); `"successor"`: a successor or axiom (brackets must balance).
---@return lsys.ParsedRule? rule
---@return string? message When the text is malformed, e.g. `missing '-->'`.
---@return integer? position 1-based byte offset of the problem.
function Rules:parse(text, mode) end

--- Adds a compiled rule to the set (kind, sub, group) and returns its 0-based index among
--- all the store's rules. Raises `bad rule kind`, `rule without predecessor`,
--- `bad successor module`, `pattern too long (limit is 64 modules)`, `too many parameters`,
--- `bad parameter source`, `a rule with a function cannot have a weight`.
---@param kind lsys.RuleKind
---@param sub integer Sub-L-system id (0: the main one).
---@param group integer Rule group (0: always active).
---@param spec lsys.RuleSpec
---@return integer idx
function Rules:add(kind, sub, group, spec) end

--- Sets the ignore list (`consider` false) or consider list (true) of sub-L-system `sub`,
--- replacing any earlier one. Raises `bad module name at '...'`.
---@param sub integer 0 for the main L-system.
---@param consider boolean
---@param names string Module names, white space allowed between them.
function Rules:skiplist(sub, consider, names) end

--- Changes a setting. Seeds in [-9.2e18, 9.2e18] are truncated to 64-bit integers; other
--- numbers seed with their bit pattern. Raises for an unknown key or a value out of range
--- (`max_modules must be between 1 and 1e12`, `maximum depth must be between 0 and 1024`,
--- `bad group number`).
---@param key lsys.ConfigKey
---@param value boolean|number
function Rules:config(key, value) end

--- Number of rules in the set (kind, sub, group), or -1 when the set does not exist.
---@param kind lsys.RuleKind
---@param sub? integer Default 0.
---@param group? integer Default 0.
---@return integer
function Rules:size(kind, sub, group) end

--- One derivation step from `src` into `dst` (a new Lstring when absent; its buffer is
--- reused otherwise) and returns `dst`. Raises the core's message without location
--- (`the string would exceed max_modules (N modules)`, a rule's error, ...);
--- `Rules:current` then tells which rule and module. Raises
--- `source and destination are the same string` when `dst` is `src`.
---@param src lsys.Lstring
---@param dst? lsys.Lstring
---@return lsys.Lstring dst
function Rules:step(src, dst) end

--- Applies the homomorphism (kind 2, default) or the decomposition (kind 1) to `src`,
--- recursively within the configured depth; returns a new Lstring. Kind 2 draws from the
--- homomorphism generator. Raises as `Rules:step`, and `bad rule kind`.
---@param src lsys.Lstring
---@param kind? 1|2
---@return lsys.Lstring
function Rules:expand(src, kind) end

--- After an error in `step` or `expand`: the 0-based index of the rule being evaluated (nil
--- when no rule was) and the 1-based index of the module being rewritten; also whether a
--- depth limit stopped at a module that has rules during the last call. Clears the rule.
---@return integer? idx
---@return integer module
---@return boolean depth_hit
function Rules:current() end

--- Parses text with this store's declared names into a new Lstring that knows those names.
---@param text string
---@return lsys.Lstring? s
---@return string? message
---@return integer? position 1-based byte offset of the problem.
function Rules:lstring(text) end

--- The functions `ran(x)` (uniform in [0, x), x default 1) and `nran(mean, sd)` (normal),
--- drawing from the generator in use: the derivation's, or the homomorphism's during an
--- expansion.
---@return fun(x?: number): number ran
---@return fun(mean: number, sd: number): number nran
function Rules:ran() end

--- Sets the expression-machine program of rule `idx` (flat `{op, a, k, ...}` triples, see
--- csrc/core/expr.h), or clears it with nil. Returns false when the program does not fit the rule
--- (the rule has no RF_CALL, is a function rule, or the program is malformed or writes the
--- wrong number of values). Raises `bad rule index`, `program too long` (over 1024
--- instructions).
---@param idx integer 0-based rule index.
---@param code? number[]
---@return boolean
function Rules:setvm(idx, code) end

--- Whether rule `idx` currently runs on the expression machine.
---@param idx integer 0-based rule index.
---@return boolean
function Rules:hasvm(idx) end

--- Adds an empty rule set (kind, sub, group): a sub-L-system may exist without rules.
--- Raises `bad rule kind`, and while the model derives.
---@param kind lsys.RuleKind
---@param sub integer
---@param group? integer Default 0.
function Rules:newset(kind, sub, group) end

--- Whether the model is deriving now (a rule function of it is running): the Lua side
--- refuses to derive, step, expand, interpret or change rules from inside its own rules.
---@return boolean
function Rules:busy() end

--- The table of the rules' Lua functions, which lsys.model fills (entry k: the function of
--- the rules whose function index is k) and a derivation's callbacks call: the table
--- itself, not a copy. Raises `the model's rules were closed`.
---@return table<integer, function>
function Rules:functions() end

--- Parses an axiom into a template without a Lua table per module: parameters are numbers
--- or expressions (brackets must balance). Returns the template and the list of its
--- distinct expression texts, in order, or nil, a message and a 1-based position.
---@param text string
---@return lsys.Template? template
---@return string[]|string expressions The expression texts, or the message.
---@return integer? position
function Rules:axiom(text) end

--- Makes the Lstring of a template, its expression slots filled from `values` (the values
--- of the expressions `Rules:axiom` listed, in order). Raises `value K is not a finite
--- number`.
---@param template lsys.Template
---@param values number[]
---@return lsys.Lstring
function Rules:fill(template, values) end

--- A parsed axiom (`Rules:axiom`), metatable "lsys.Template".
---@class lsys.Template

--- Same as `lsys.ran`.
---@param x? number
---@return number
function core.ran(x) end

--- Same as `lsys.nran`.
---@param mean number
---@param sd number
---@return number
function core.nran(mean, sd) end

--- The Rules deriving now (nil outside a derivation); with an argument, sets it. The Lua
--- side restores it after a step that raised.
---@param v? lsys.Rules|nil
---@return lsys.Rules?
function core.producing(v) end

--- The process-wide memory budget in bytes; with an argument, sets it first (0: back to the
--- default, half the physical memory). Also returns the physical memory.
---@param bytes? number
---@return number limit
---@return number physical
function core.max_memory(bytes) end

-- ---------------------------------------------------------------------------------------------
-- The turtle and scenes (csrc/lua/lua_scene.c). `opts` is `lsys.view.turtle_options(v)`
-- of a normalised view; the homomorphism of `rules` is applied while drawing.

--- Interprets `s` into a new Scene. The scene keeps the look fields of `opts` (camera,
--- light, background; the view schema's defaults where absent) and its textures.
---@param rules lsys.Rules
---@param s lsys.Lstring
---@param opts table
---@return lsys.Scene
function core.interpret(rules, s, opts) end

--- Fills the query modules (?P ?H ?U ?L) of `s` in place from an interpretation.
---@param rules lsys.Rules
---@param s lsys.Lstring
---@param opts table
---@return integer n The number of query modules filled.
function core.query(rules, s, opts) end

--- The turtle state after module `i` of `s` (0: the start), interpreting again.
---@param rules lsys.Rules
---@param s lsys.Lstring
---@param i integer
---@param opts table
---@return number[] pos
---@return number[] H
---@return number[] L
---@return number[] U
---@return number width
---@return integer color
function core.turtle_state(rules, s, i, opts) end

--- The options table a Scene keeps: the normalised view it was interpreted with, or what
--- lsys.population gave it (`{ population = true, view = ... }`); nil when it keeps none.
--- Raises for anything but a Scene; answers for a closed one too.
---@param scene lsys.Scene
---@return table?
function core.scene_options(scene) end

--- The turtle's symbol table (csrc/core/symbols.h): one row per named turtle symbol, in
--- the table's order. `split` says how the turtle on several threads treats the symbol:
--- "cross" (its effect crosses branches: the string stays on one thread), "state", "open",
--- "close", "segment", "shape" or "record". `query` is true for ?P ?H ?U ?L. The predefined
--- surfaces `~X` are named by the view and not listed. A new table each call.
---@return { name: string, op: string, split: string, query: boolean }[]
function core.symbols() end

--- The export formats of `Scene:save` (csrc/core/export.h), in their order: `name`, `ext`
--- (the file name's extension, lower case, without the dot), `title`, `companion` (the
--- extension of a file written beside it: OBJ's material file; absent when none),
--- `textures` (textured triangles name or embed their image) and `instancing` (a population
--- is written with instancing unless `opts.instancing = false`). A new table each call.
---@return { name: string, ext: string, title: string, companion?: string, textures: boolean, instancing: boolean }[]
function core.formats() end

-- ---------------------------------------------------------------------------------------------
-- Free-form deformation (csrc/lua/lua_ffd.c; docs/components.md)

--- A Hyperpatch: a trivariate Bezier volume of degrees 1 to 4 over the box `origin` +
--- [0, 1]^3 of its edge vectors (`size`: the axis-aligned box; `axes`: any three that are not
--- in one plane), its control points on the regular lattice (the identity map). Defaults:
--- degree 3, origin {0, 0, 0}, size {1, 1, 1}. Raises `core.hyperpatch: 'degree' is 5:
--- degrees are 1 (linear) to 4 (quartic)`, `... axes are degenerate ...`, `... unknown option`.
---@param opts? {degree?: integer|integer[], origin?: number[], size?: number[], axes?: number[][]}
---@return lsys.Hyperpatch
function core.hyperpatch(opts) end

---@class lsys.Hyperpatch
local Hyperpatch = {}

--- Control point (i, j, k), 0-based lattice indices. Raises `hyperpatch:point: no control
--- point (I, J, K): indices are 0..DL, 0..DM, 0..DN`.
---@return number x, number y, number z
function Hyperpatch:point(i, j, k) end

--- Moves control point (i, j, k) to (x, y, z).
function Hyperpatch:set(i, j, k, x, y, z) end

--- The image of a point (outside the box: the same polynomial, extrapolated).
---@return number x, number y, number z
function Hyperpatch:map(x, y, z) end

---@return integer dl, integer dm, integer dn
function Hyperpatch:degree() end

--- The number of control points, (dl + 1)(dm + 1)(dn + 1).
---@return integer
function Hyperpatch:count() end

-- ---------------------------------------------------------------------------------------------
-- Rendering, PNG and files (csrc/lua/lua_render.c)

---@type boolean True when built with OSMesa (offscreen rendering).
core.has_render = true

--- Draws a Scene offscreen (`lsys.render` gives it its options) as the scene says (its
--- camera, light, background, palette and textures). `opts`: out, width, height,
--- supersample, zoom, transparent, wireframe, and the fields of
--- `lsys.view.render_options(v)`, each of which replaces the scene's own for this picture
--- (`textures`: the list of lsys.Texture the scene's texture indices refer to). With `out`
--- writes the PNG and returns true, else the RGBA pixels, width and height. Raises
--- `lsys.render: ...`.
---@param scene lsys.Scene
---@param opts? table
---@return true|string pixels
---@return integer? width
---@return integer? height
function core.render(scene, opts) end

--- Reads a PNG file: its RGBA pixels (a string, top row first), width and height.
---@param path string
---@return string pixels
---@return integer width
---@return integer height
function core.png_read(path) end

--- Writes RGBA pixels (top row first) as a PNG, atomically: RGBA when `alpha` is true, RGB
--- when false, and when absent RGBA only if some pixel is not opaque. Raises
--- `lsys.png_write: W x H RGBA pixels need N bytes, got M` and for unwritable files.
---@param path string
---@param pixels string
---@param w integer
---@param h integer
---@param alpha? boolean
---@return true
function core.png_write(path, pixels, w, h, alpha) end

--- Writes `bytes` to `path` atomically (a temporary file renamed onto it).
---@param path string
---@param bytes string
---@return true
function core.write_file(path, bytes) end

--- The bytes of a regular file of at most `max` bytes, or nil and a message naming the
--- file.
---@param path string
---@param max number
---@return string? bytes
---@return string? message
function core.read_file(path, max) end

--- The absolute name of `path` without symbolic links, `.` or `..`, and what it is:
--- "file" (regular), "directory" or "other" (a device, a FIFO, a socket); nil and
--- "PATH: why" when it does not exist. Opens nothing (a FIFO does not block it).
---@param path string
---@return string? real
---@return "file"|"directory"|"other"|string kind_or_message
function core.realpath(path) end

-- ---------------------------------------------------------------------------------------------
-- The writers (csrc/lua/lua_outfile.c): every file the Lua side writes goes through them
-- (manual §9, "Output files"), whole or absent.

--- A new output for `path` (manual §9): a temporary file made new (O_EXCL) in its folder,
--- which replaces `path` at `commit` and is removed at `abort`, at an error through a
--- to-be-closed variable, at collection and at Ctrl-C. Raises `cannot open 'PATH' for
--- writing: REASON`.
---@param path string
---@return lsys.Outfile
function core.outfile(path) end

---@class lsys.Outfile
local Outfile = {}
--- Writes strings or numbers; a failed write removes the temporary file and raises
--- `cannot write 'PATH': REASON`.
---@param ... string|number
---@return lsys.Outfile self
function Outfile:write(...) end
--- The file another program (dot, ffmpeg) writes instead of this object: the temporary
--- file (or the target itself when that is a device). No `write` after it.
---@return string
function Outfile:name() end
--- Flushes, closes and renames the temporary file onto the target; raises `cannot write
--- 'PATH': REASON` (the target then stays as it was).
---@return true
function Outfile:commit() end
--- Removes the temporary file; the target stays as it was. Idempotent (also `__close`).
function Outfile:abort() end

--- A new private folder `PARENT/PREFIX-XXXXXX` (mode 0700, a name never used before) for
--- files that are not outputs. PARENT: `parent`, else `$TMPDIR`, else `/tmp`. Removed with
--- the files in it by `remove`, `__close`, collection and Ctrl-C. Raises `cannot make a
--- temporary folder in 'PARENT' (TMPDIR): REASON`.
---@param parent? string
---@param prefix? string Default "lsys"; no '/'.
---@return lsys.Tempdir
function core.tempdir(parent, prefix) end

---@class lsys.Tempdir
local Tempdir = {}
---@return string
function Tempdir:path() end
--- Removes the folder and the files and links in it (a link is removed, never followed);
--- raises `cannot remove the temporary folder 'PATH': REASON`.
---@return true
function Tempdir:remove() end

-- ---------------------------------------------------------------------------------------------
-- Contours, surfaces and textures (csrc/lua/lua_contour.c, lua_surface.c, lua_texture.c):
-- what `lsys.view.normalize` makes of the files a view names. All are immutable once made;
-- every method of a closed one raises.

--- Reads a contour file: cpfg's (Appendix B.1 of the cpfg guide) or vlab's versioned one
--- (`cver 1 1`, `1 2`, `1 3`; docs/drawing.md §3a). Raises `PATH:LINE: ...`.
---@param path string
---@return lsys.Contour
function core.contour_load(path) end

--- A contour from points, all with 2 or all with 3 coordinates; at least 3 points for a
--- closed contour, 4 for an open one.
---@param points number[][]
---@param closed? boolean Default true.
---@return lsys.Contour
function core.contour(points, closed) end

--- The cross-section of generalized cylinders (`@#(id)`): a uniform cubic B-spline.
---@class lsys.Contour
local Contour = {}

--- `p + 1` vertices and their normals, `{x, y, z}` each, at equal arc length.
---@param p integer From 3 to 65536.
---@return number[][] vertices
---@return number[][] normals
function Contour:sample(p) end
---@return integer n The number of control points.
function Contour:size() end
---@return boolean
function Contour:closed() end
---@return 2|3
function Contour:dim() end
--- The control points, `{x, y}` or `{x, y, z}` each (as many numbers as `dim`).
---@return number[][]
function Contour:points() end

-- ---------------------------------------------------------------------------------------------
-- B-spline curves and stroke capture (csrc/lua/lua_bspline.c; docs/sketch.md, Curves).
-- Messages begin with the function or method name ("bspline: ...", "ray: ...").

--- A uniform B-spline curve of at least degree + 1 control points (copied).
---@param points number[][] `{x, y}` or `{x, y, z}`, all of one dimension.
---@param opts? {degree?: 2|3, clamped?: boolean} Defaults: degree 3, uniform (not clamped).
---@return lsys.BSpline
function core.bspline(points, opts) end

--- The polyline at equal spacing along it (`L / round(L / spacing)`), both ends kept.
---@param points number[][]
---@param spacing number > 0
---@return number[][]
function core.bspline_resample(points, spacing) end

--- Chaikin's corner cutting, ends kept: n points give 2n per step.
---@param points number[][]
---@param steps? integer 0 to 30, default 1.
---@return number[][]
function core.chaikin(points, steps) end

--- Chaikin reverse subdivision (filter -1/4, 3/4, 3/4, -1/4), ends kept: n points give
--- (n + 1) // 2 per step; stops at 2 points. Undoes core.chaikin exactly.
---@param points number[][]
---@param steps? integer 0 to 30, default 1.
---@return number[][]
function core.chaikin_reverse(points, steps) end

--- Stroke capture (Anastacio et al. 2009, §3.1): resample, reverse-subdivide, and return the
--- control points of a curve of `degree` (use them with `clamped = true`).
---@param points number[][]
---@param opts? {spacing?: number, steps?: integer, degree?: 2|3} Defaults 1, 3, 2.
---@return number[][]
function core.stroke_curve(points, opts) end

--- A B-spline curve; `t` is in [0, 1] over the whole curve (clamped into it). `#c` is the
--- number of control points.
---@class lsys.BSpline
local BSpline = {}

---@param t number
---@return number x
---@return number y
---@return number? z
function BSpline:eval(t) end
--- The first or second derivative with respect to t.
---@param t number
---@param k? 1|2 Default 1.
---@return number dx
---@return number dy
---@return number? dz
function BSpline:deriv(t, k) end
--- Arc length of the curve, or from t0 to t1.
---@param t0? number
---@param t1? number
---@return number
function BSpline:length(t0, t1) end
--- The t at arc length s from the start.
---@param s number
---@return number t
function BSpline:at_length(s) end
--- n points at equal steps of t.
---@param n integer >= 2
---@return number[][]
function BSpline:sample(n) end
--- n points at equal arc length, each `{x, y [, z], t = t}`.
---@param n integer >= 2
---@return table[]
function BSpline:sample_length(n) end
--- The crossings with the ray o + s d (s >= 0), `{ {t =, s =, x =, y =}, ... }` sorted by s.
--- 2D curves only.
---@return table[]
function BSpline:ray(ox, oy, dx, dy) end
--- The crossings with another 2D curve, `{ {t =, u =, x =, y =}, ... }` sorted by t.
---@param other lsys.BSpline
---@return table[]
function BSpline:intersect(other) end
--- The closest point of the curve: its t and distance.
---@return number t
---@return number distance
function BSpline:closest(x, y, z) end
---@return number[][]
function BSpline:points() end
---@return 2|3
function BSpline:dim() end
---@return 2|3
function BSpline:degree() end
---@return boolean
function BSpline:clamped() end

-- ---------------------------------------------------------------------------------------------
-- A 2D RGBA8 canvas (csrc/core/canvas.c, csrc/lua/lua_canvas.c; docs/sketch.md, Canvas).
-- Coordinates are pixels, x right, y down. Colours are `{r, g, b [, a]}` in [0, 1] or
-- "#rrggbb" / "#rrggbbaa". A closed canvas raises `the canvas was closed`.

--- A canvas of w x h pixels (1..16384), filled with `colour` (transparent black).
---@param w integer
---@param h integer
---@param colour? number[]|string
---@return lsys.Canvas
function core.canvas(w, h, colour) end

---@class lsys.Canvas
local Canvas = {}
--- Sets every pixel, ignoring the clip.
---@param colour? number[]|string
function Canvas:clear(colour) end
--- An anti-aliased line with round caps.
---@param width? number Default 1.
---@param colour? number[]|string
function Canvas:line(x0, y0, x1, y1, width, colour) end
--- Lines through `{ {x, y}, ... }` or `{ x1, y1, x2, y2, ... }`.
---@param points number[][]|number[]
---@param width? number
---@param colour? number[]|string
function Canvas:polyline(points, width, colour) end
--- A filled rectangle, or a 1-pixel outline inside its edges.
---@param colour? number[]|string
---@param fill? boolean
function Canvas:rect(x, y, w, h, colour, fill) end
--- A filled anti-aliased disc.
---@param colour? number[]|string
function Canvas:circle(x, y, r, colour) end
--- Text in the 5x7 font, its top left at (x, y). Returns its width in pixels.
---@param s string
---@param scale? integer 1..64, default 1.
---@param colour? number[]|string
---@return integer
function Canvas:text(x, y, s, scale, colour) end
--- `6 * scale` per character less the last gap.
---@param s string
---@param scale? integer
---@return integer
function Canvas:text_width(s, scale) end
--- Draws only on pixels whose centres are inside the rectangle; without arguments,
--- anywhere.
function Canvas:clip(x, y, w, h) end
--- Writes a PNG, atomically. Raises `save: ...`.
---@param path string
function Canvas:save(path) end
--- The pixels: w * h * 4 bytes, RGBA, top row first.
---@return string
function Canvas:pixels() end
---@return integer w
---@return integer h
function Canvas:size() end


--- Reads a cpfg surface file (.s; docs/surfaces.md). Raises `PATH:LINE: ...`.
---@param path string
---@return lsys.Surface
function core.surface_load(path) end

--- The same from a string.
---@param text string
---@param name? string Starts the messages. Default `"surface"`.
---@return lsys.Surface
function core.surface_parse(text, name) end

--- A point of one bicubic patch.
---@param basis 1|2|3|"bezier"|"bspline"|"cardinal"
---@param ctrl number[][] 16 `{x, y, z}`, row by row (row r, column c at 4 r + c + 1).
---@param s number
---@param t number
---@return number x
---@return number y
---@return number z
function core.patch_eval(basis, ctrl, s, t) end

--- A predefined surface: bicubic Bézier patches with a contact point and frame.
---@class lsys.Surface
local Surface = {}

--- What the file gave: `{ patches =, contact =, heading =, up =, ["end"] =, lo =, hi =,
--- size =, precision = {s, t}, names = {...} }` (lo, hi: the bounds of the control points).
---@return table
function Surface:info() end

--- The 16 control points `{x, y, z}` of patch `i` (from 1), row by row as core.patch_eval
--- takes them. Raises `patch index must be from 1 to N`.
---@param i integer
---@return number[][]
function Surface:patch(i) end

--- A copy of the surface (names, neighbours, frame, size, precision) with other control
--- points: 16 `{x, y, z}` per patch, patch after patch (point `16 (i - 1) + k` is point k of
--- patch i), bounds computed again. Raises `expected N points (16 per patch), got M`,
--- `point 5: coordinate 2 is not finite`.
---@param points number[][]
---@return lsys.Surface
function Surface:with_points(points) end

--- The surface as a cpfg surface file's text (every line written, numbers in the shortest
--- form that reads back the same; HEADING and UP as normalised when read).
---@return string
function Surface:format() end

--- Reads a PNG texture.
---@param path string
---@param opts? { mag?: "near"|"linear"|"n"|"l", min?: "near"|"linear"|"n"|"l", mode?: "modulate"|"decal"|"m"|"d", per_surface?: boolean, intensity?: boolean } Filters default "near", mode "modulate", per_surface false, intensity true for a grey image.
---@return lsys.Texture
function core.texture_load(path, opts) end

---@class lsys.Texture
local Texture = {}
---@return integer width
---@return integer height
function Texture:size() end
--- `{ path =, width =, height =, mag =, min =, mode =, per_surface =, intensity =, alpha = }`
--- with the long names of the settings.
---@return table
function Texture:info() end

-- ---------------------------------------------------------------------------------------------
-- The window (csrc/lua/lua_viewer.c); lsys.viewer is the interface to use.

---@type boolean True when built with the viewer (GLFW).
core.has_viewer = true

--- Opens the window (one per process; its own thread).
---@param opts? { width?: integer, height?: integer, samples?: integer, visible?: boolean, status?: boolean }
---@return lsys.Viewer
function core.viewer_open(opts) end

--- The X input devices and the pressure range of those that report one (a drawing tablet's
--- pen; docs/sketch.md), or nil and why. Only in a build with the viewer.
---@return { id: integer, name: string, pressure?: { min: number, max: number, value: number } }[]?
---@return string? why
function core.pen_devices() end

--- The colour of light x (clamped to [0, 1]) on the ramp of the window's L key. Only in a
--- build with the viewer.
---@param x number
---@return number r
---@return number g
---@return number b
function core.light_ramp(x) end

--- The modification time (seconds, with a fraction) and size of a file, or nil and a
--- message: `lsys view` reloads a model when they change.
---@param path string
---@return number? mtime
---@return integer|string size
function core.filestamp(path) end

--- The open window, metatable "lsys.Viewer"; closed when collected.
---@class lsys.Viewer
local Viewer = {}

--- Hands the window a snapshot to draw (a deep copy, or with `take` the scene's own mesh):
--- `frames` is a list of `{ scene =, step =, modules =, render = lsys.render options,
--- world =, take =, lines = }`.
---@param frames table[]
---@param opts? { first?: integer, rate?: number, title?: string, keep_camera?: boolean, capture?: boolean, textures?: lsys.Texture[], light?: boolean } `light`: the L key on (the first frame's light colours computed before posting) or off; nil leaves it.
function Viewer:post(frames, opts) end

--- The next event, waiting up to `timeout` seconds (0): `{ type = "pick"|"miss"|
--- "screenshot"|"step"|"closed"|"key"|"drag"|"light", frame, step, module, kind, x, y, path,
--- ok, msg, key, ctrl, shift, phase, on }` (the fields of its type; "light": the L key, `on`),
--- or nil.
---@param timeout? number
---@return table?
function Viewer:poll(timeout) end
---@return integer
function Viewer:pending() end
--- Asks for a screenshot of the next frame (as the S key); the "screenshot" event tells.
---@param path? string
function Viewer:screenshot(path) end
--- Presses a key (see lsys.viewer.key); the window has drawn it once `state().serial` has
--- reached the number returned.
---@param name string
---@return integer serial
function Viewer:key(name) end
--- `{ open, drawn, serial, width, height, fbwidth, fbheight, frame, nframes, playing,
--- wireframe, light, scene }` (scene: the scene's rectangle in the window, `{x, y, w, h}`).
---@return table
function Viewer:state() end
--- The light colours of frame k of the snapshot last posted (csrc/gl/vlight.h), computed on
--- this thread unless they were, and handed to the window: `{ frame, leaves, min, max, mean,
--- msg }`; nil and a message once the window is closed.
---@param k integer
---@param opts? { threads?: integer, max_memory?: number }
---@return table
function Viewer:light(k, opts) end
--- The colour triangle t of frame k is drawn in now (r, g, b).
---@param k integer
---@param t integer
---@return number r
---@return number g
---@return number b
function Viewer:colour(k, t) end
--- Splits the window into the scene and image panes (csrc/gl/vpanes.c), rectangles in
--- fractions of the window, y down; nil: the scene fills it again. While a layout is on,
--- every key comes back as a "key" event, and the mouse over a pane as "pointer" (`pane`,
--- `phase` "down"|"move"|"up", `button`, `x`, `y` in the image's pixels, `ctrl`, `shift`)
--- and "scroll" (`pane`, `x`, `y`, `dy`) events. Returns the request's serial (as `key`).
---@param lay? { scene: number[], panes: { [1]: number, [2]: number, [3]: number, [4]: number, bg?: number[] }[] }
---@return integer serial
function Viewer:layout(lay) end
--- Shows an RGBA image (w * h * 4 bytes, top row first; copied) in pane k (1 to 4), as
--- large as fits with its aspect kept.
---@param k integer
---@param pixels string
---@param w integer
---@param h integer
---@return integer serial
function Viewer:image(k, pixels, w, h) end
--- Replaces the status line (`""`: the usual one) and the help text (nil: unchanged).
---@param status? string
---@param help? string
---@return integer serial
function Viewer:text(status, help) end
---@param p number[]
---@return number? x
---@return number? y
---@return number? depth
function Viewer:project(p) end
function Viewer:close() end

-- ---------------------------------------------------------------------------------------------
-- Branch-path inverse kinematics (csrc/lua/lua_ik.c), for lsys.arrange.

--- A chain of 3-joints along a branch path. Vectors are `{x, y, z}`, angles degrees;
--- `alpha` is the joint's `@J` angles as the segment is drawn now, `rest` the rest angles
--- (0), `stiff` the stiffness (1), `free` a mask of the free axes (7: h, u and l).
---@param chain { base: { H: number[], U: number[], p: number[] }, joints: { p0: number[], p1: number[], H: number[], U: number[], alpha: number[], rest?: number[], stiff?: number[], free?: integer }[] }
---@return lsys.IK
function core.ik_chain(chain) end

--- A branch-path chain, metatable "lsys.IK"; `#ik` is the number of joints.
---@class lsys.IK
---@operator len: integer
local IK = {}

--- Minimises the objective (eq. 1 of Power et al. 1999) for the targets: end `p`, twist
--- vectors `s` and `t`, with weights wp, wt, we (1) and ws (0). Raises `ik: MESSAGE`.
---@param goal { p: number[], s: number[], t: number[], wp?: number, wt?: number, we?: number, ws?: number, max_iter?: integer, gtol?: number }
---@return lsys.SolveResult
function IK:solve(goal) end
--- The joint angles, `{ {h, u, l}, ... }` in degrees.
---@return number[][]
function IK:angles() end
--- Sets the joint angles (a list as `angles` returns).
---@param list number[][]
function IK:set_angles(list) end
--- Forward kinematics: the end point, its twist vectors s (U x H) and t (U), and the
--- joints' segments `{ {start, end}, ... }`.
---@return number[] p
---@return number[] s
---@return number[] t
---@return number[][][] segments
function IK:forward() end

-- ------------------------------------------------------------------------------------------
-- lsys.components: component graphs (Lintermann and Deussen 1999; docs/components.md).
-- `require "lsys.components"`, or `lsys.components` (loaded at first use).

---@class lsys.components
---@field KINDS table<string, table> Each kind's own parameters: name -> { type, default }.
---@field BASIC table<string, table> The basic parameters of every kind.
---@field ORDER string[] The eleven kinds in the article's order.
---@field MULTIPLIERS table<string, boolean> hydra, wreath, phiball.
lsys.components = {}

--- A prototype of kind `simple`, `revo`, `horn`, `leaf`, `tree`, `hydra`, `wreath`,
--- `phiball`, `ffd`, `hyperpatch` or `world`: `C.tree { length = 2, n = 12 }`. Every kind takes
--- `name`, `recursion` and the basic parameters; numbers may be ranges `{v0, v1[, f = fn]}` or
--- functions of `ctx`. Raises `lsys.components: KIND 'name': ...` for an unknown parameter
--- (listing the known ones) or a bad value.
---@param params table
---@return lsys.components.Proto
function lsys.components.tree(params) end

--- True when `x` is a component prototype.
---@return boolean
function lsys.components.isproto(x) end

--- The i-tree of the p-graph at `root`. opts: seed (1), max_instances (2e6), frame.
---@param root lsys.components.Proto
---@param opts? { seed?: integer, max_instances?: integer, frame?: table }
---@return lsys.components.Tree
function lsys.components.expand(root, opts) end

--- The plant as an ordinary lsys model (derives its Lstring in 0 steps); `m.components`
--- holds `tree`, `lstring`, `owner` and `instance(i)` (the instance that drew module i).
---@param root lsys.components.Proto
---@param opts? { seed?: integer, max_instances?: integer, view?: table, name?: string, detail?: integer }
---@return lsys.Model
function lsys.components.model(root, opts) end

--- `C.model(root, opts):interpret()`.
---@return lsys.Scene
function lsys.components.scene(root, opts) end

--- The p-graph as Graphviz DOT text. opts: params (true or a list of names), max_params.
---@return string
function lsys.components.graph(root, opts) end

--- Writes the p-graph to `path` (.dot/.gv as text; .png/.svg/.pdf through Graphviz's dot).
function lsys.components.graph_render(root, path, opts) end

--- Puts component plants into an L-system: each module `P(s)` or `P(s, seed)` of `model`'s
--- derived string is followed by the plant `plants.P` scaled by s (lsys.components.mix.place).
---@param model lsys.Model
---@param plants table<string, lsys.components.Proto>
---@param opts? { seed?: integer, max_instances?: integer }
function lsys.components.place(model, plants, opts) end

---@class lsys.components.Proto
---@field kind string
---@field name string|nil
---@field params table The parameters as given.
---@field links { type: "child"|"branch"|"leaf", to: lsys.components.Proto, flags?: table }[]
local Proto = {}
--- Links `b` as a child (placed on this component's geometry); returns self.
---@param flags? { only?: integer[], except?: integer[] }
---@return lsys.components.Proto
function Proto:child(b, flags) end
--- Links `b` as a branch (multiplied along a Tree's stem; a child elsewhere); returns self.
---@return lsys.components.Proto
function Proto:branch(b, flags) end
--- Links `b` as a leaf link (made once where this component's recursion ends); returns self.
---@return lsys.components.Proto
function Proto:leaf(b, flags) end
--- The value of parameter `key` as given, or its default.
function Proto:param(key) end

---@class lsys.components.Tree
local CTree = {}
--- The instances in depth-first order: { index, proto, kind, name, path, parent, children,
--- i, n, depth, link, frame = {p, H, U, s}, tip, stem, params, modules, at }; frame, tip
--- and stem are new read-only copies of the C frame arena at each read.
---@return table[]
function CTree:instances() end
--- How many instances: by the label their paths show (a string: the prototype's name, its
--- kind when it has none), by kind (`{ kind = "leaf" }`), or all (nil).
---@param what? string|{kind: string}
---@return integer
function CTree:count(what) end
--- The instance at `path` ("tree#1/twig#3/leaf#17"), or nil.
---@return table|nil
function CTree:find(path) end

-- {===========================================================================================
-- lsys.grow (docs/grow.md)

--- Incremental growth: kinds of limbs with if-then rules, worlds of plants grown by ticks.
---@class lsys.grow
---@field Limb lsys.grow.Limb The plain kind every kind extends.
---@field World table The world metatable.
local grow = {}

--- A new kind of limb named `name`, extending `base` (its rules copied at creation).
---@param name string
---@param base? lsys.grow.Limb
---@return lsys.grow.Limb
function grow.kind(name, base) end

--- A world of plants: seed (1), max_limbs (100,000), sides (8), shoot_color, leaf_color,
--- ticks (its length), view (how it is looked at), leaf (every leaf's shape: "quad", a
--- surface file's name, an lsys.Surface, an organ, an lsys.Scene, or { surface | file,
--- precision = {s, t} }), dir (where file names are looked up; default the calling file's
--- folder).
---@param opts? {seed?: integer, max_limbs?: integer, sides?: integer, shoot_color?: string|number[], leaf_color?: string|number[], ticks?: integer, view?: table, leaf?: string|lsys.Surface|lsys.Organ|lsys.Scene|table, dir?: string}
---@return lsys.grow.World
function grow.world(opts) end

--- Limbs from the segments an Lstring draws, in a new world.
---@param s lsys.Lstring
---@param opts? table model, kind, color, seed, max_limbs, sides
---@return lsys.grow.World
function grow.from_lstring(s, opts) end

--- A limb (a kind is a class of them): its state and the paper's five groups of methods.
---@class lsys.grow.Limb
local Limb = {}
--- Declares a rule: a function (limb, world), or { when = "condition", scale_length,
--- scale_radius, color, blend = {colour, t}, fn }; a condition reads length, radius, age,
--- level, leaves and root as at the start of the tick, count (its plant's living limbs) and
--- total (the world's) as they are when it runs. Replaces one of the same name.
---@param name string
---@param spec function|table
function Limb:rule(name, spec) end
---@return number
function Limb:length() end
---@return number
function Limb:radius() end
---@return number[]
function Limb:color() end
---@return integer
function Limb:age() end
---@return integer
function Limb:level() end
---@return integer
function Limb:leaves() end
---@return boolean
function Limb:has_leaves() end
---@return boolean
function Limb:is_root() end
---@return boolean
function Limb:alive() end
---@return integer The living limbs of its plant, with those made so far in the tick.
function Limb:count() end
---@return number[]
function Limb:base() end
---@return number[]
function Limb:tip() end
---@return lsys.grow.Limb?
function Limb:parent() end
---@return lsys.grow.Limb[]
function Limb:children() end
---@return lsys.grow.Limb[]
function Limb:siblings() end
---@param f number
function Limb:scale_length(f) end
---@param f number
function Limb:scale_radius(f) end
---@param x number
function Limb:set_length(x) end
---@param x number
function Limb:set_radius(x) end
---@param c string|number[]
function Limb:set_color(c) end
---@param c string|number[]
---@param t number
function Limb:blend_color(c, t) end
---@param n integer
---@param opts? {size?: number, color?: string|number[]}
function Limb:add_leaves(n, opts) end
function Limb:drop_leaves() end
--- Removes the limb and its subtree at the end of the tick.
function Limb:remove() end
---@param a? number
---@param b? number
---@return number
function Limb:random(a, b) end
--- A child at the tip (or `at` along the limb): angle, axis ("x", "y", "z" or {x, y, z}),
--- roll, length, radius, color, kind. Nil when the world's limb cap is reached.
---@param opts table
---@return lsys.grow.Limb?
function Limb:spawn(opts) end
---@param opts table angle, axis, roll
function Limb:turn(opts) end
---@return integer
function Limb:id() end
---@return string
function Limb:kind() end

---@class lsys.grow.World
---@field ticks integer Ticks grown so far.
---@field length? integer How long it grows (world{ticks = N}).
---@field capped boolean The limb cap was reached.
local World = {}
---@param opts? {kind?: lsys.grow.Limb, position?: number[], seed?: integer, length?: number, radius?: number, color?: string|number[]}
---@return lsys.grow.Limb?
function World:plant(opts) end
---@param n? integer
---@return lsys.grow.World
function World:tick(n) end
--- Ticks to the world's length (else `n`).
---@param n? integer
---@return lsys.grow.World
function World:grow(n) end
---@return lsys.grow.Limb[]
function World:limbs() end
---@param id integer
---@return lsys.grow.Limb?
function World:limb(id) end
--- The living limbs (of plant `plant`), with those made so far in the tick.
---@param plant? integer
---@return integer
function World:count(plant) end
---@return lsys.Scene
function World:scene() end
---@param model? lsys.Model
---@return lsys.Lstring
---@return fun(k: integer): lsys.grow.Limb?
function World:lstring(model) end
---@param a? number
---@param b? number
---@return number
function World:random(a, b) end

-- }===========================================================================================

-- {===========================================================================================
-- lsys.testing (docs/testing.md)

--- Assertions for specs of models, registered with luassert (busted's `assert`) when the
--- module is required: `assert.lstring_equal(expected, actual [, tol])`, `assert.near(expected,
--- actual, tol)`, `assert.error_contains(fn, text, ...)`, `assert.scene_stats(x, expected [,
--- tol])`, `assert.image_matches(x, golden [, opts])`. The functions below are what they call:
--- each returns true, or false and a message; misuse raises.
---@class lsys.testing
---@field TOLERANCE {mean: number, pixel: integer, fraction: number} Image comparison defaults: mean absolute difference per channel below 2 (of 255), fewer than 1% of the pixels off by more than 40.
local testing = {}

--- Whether this lsys can render (built with OSMesa).
---@return boolean
function testing.can_render() end

--- Two L-strings module by module: names and parameter counts exactly, parameters within
--- `tol` (nil: 1e-9 relative; an integer 1 to 17: significant digits; another number:
--- absolute; or { digits, tol, names }).
---@param expected lsys.Lstring|string
---@param actual lsys.Lstring|string
---@param tol? number|{digits?: integer, tol?: number, names?: string}
---@return boolean ok
---@return string? message the first module that differs, its index and neighbours
function testing.compare_lstrings(expected, actual, tol) end

--- |expected - actual| <= tol for numbers, or elementwise for (nested, keyed) tables.
---@param expected number|table
---@param actual number|table
---@param tol number
---@return boolean ok
---@return string? message
function testing.near(expected, actual, tol) end

--- Whether fn() raises an error whose message contains every text (plain text).
---@param fn function
---@param ... string
---@return boolean ok
---@return string? message
function testing.error_contains(fn, ...) end

---@class lsys.testing.Stats
---@field modules integer
---@field triangles integer
---@field vertices integer
---@field lines integer
---@field segments integer
---@field records integer
---@field area number
---@field bounds? number[][] {{xmin, ymin, zmin}, {xmax, ymax, zmax}}; nil when nothing was drawn
---@field size number[] {dx, dy, dz}

--- Statistics of a scene (a Model is derived and interpreted first).
---@param x lsys.Scene|lsys.Model
---@return lsys.testing.Stats
function testing.stats(x) end

--- Compares some statistics with stats(x): |actual - expected| <= tol * max(1, |expected|)
--- (tol default 1e-6; a table: one per statistic). Raises for an unknown statistic.
---@param x lsys.Scene|lsys.Model
---@param expected table
---@param tol? number|table<string, number>
---@return boolean ok
---@return string? message
function testing.compare_stats(x, expected, tol) end

--- Compares two RGBA pictures of w x h pixels (tol: nil, the fraction of pixels that may
--- differ, or some fields of TOLERANCE).
---@param a string
---@param b string
---@param w integer
---@param h integer
---@param tol? number|table
---@return boolean ok
---@return string? message
function testing.compare_images(a, b, w, h, tol) end

--- Compares the picture of x (a Scene or Model rendered at opts.size, a PNG file, or
--- { pixels, w, h }) with the PNG file `golden`: a missing golden is written (and fails
--- once), LSYS_UPDATE_GOLDEN=1 writes it (and passes), a mismatch is written to opts.actual
--- (default NAME.actual.png next to the golden).
---@param x lsys.Scene|lsys.Model|string|table
---@param golden string
---@param opts? {size?: string|integer|integer[], tolerance?: number|table, render?: table, actual?: string}
---@return boolean ok
---@return string? message
function testing.match_golden(x, golden, opts) end

-- }===========================================================================================


-- {===========================================================================================
-- lsys.batch (docs/batch.md)

--- Batch runs: the jobs of a spec (a CSV file, a Lua file or a table) run in this process,
--- all or one shard of them, with a manifest; what `lsys batch SPEC` runs. Loaded at first
--- use (`lsys.batch`, or `require "lsys.batch"`).
---@class lsys.batch
---@field SIZE integer A picture's width and height when the spec gives none (800).
---@field MAX_SIZE integer The largest picture width and height (16384).
---@field MAX_JOBS integer The most jobs a spec may make (10^9); more is an error that gives the count.
lsys.batch = {}

--- A job of a spec, as `lsys.batch.jobs` returns it.
---@class lsys.batch.Job
---@field n integer Its number in the spec (1, 2, ...): a CSV record's, or the sweep's.
---@field id string Its id: given (a CSV column or field `id`), or `n` padded with zeros to 4 digits (more from 10,000 jobs).
---@field where string Where the spec gives it: "plants.csv:7", "sweep.lua: vary R=1.4 seed=2", "spec: jobs[3]".
---@field model string The model file as the spec names it (relative to the spec's folder).
---@field path string The model file opened.
---@field name? string The model picked from a file that returns a table of models.
---@field seed integer Given, or `lsys.batch.seed(spec seed, n)`.
---@field steps? integer Derivation steps (nil: the model's).
---@field width? integer Picture width (nil: 800).
---@field height? integer Picture height (nil: 800).
---@field params table<string, number> The model variables it sets (`model.env`).
---@field outputs { format: "png"|"glb"|"obj"|"ply"|"lstring"|"stats", path: string }[] Inside the output folder, relative to it, normalized (no ".", ".." or empty segment).
---@field rep? integer The replicate of a sweep with `replicates`.
---@field status? "done"|"failed"|"todo" From `lsys.batch.plan`.

--- The jobs of `spec`: a CSV file (.csv), a Lua file (.lua) returning a spec table, or a
--- spec table (`dir`: the folder its model paths are relative to, default "."). Returns
--- them and { file, dir, total }: a list that makes job n when it is read (`jobs[n]`,
--- `#jobs`, `ipairs`), a new table each time, and holds none. Raises naming the spec's file
--- and line (`plants.csv:7: column 'R': 'abc' is not a number`) or field (`sweep.lua:
--- vary.R[2]: ...`): a bad value, an output that leaves the output folder, two jobs that
--- write one file, more jobs than `lsys.batch.MAX_JOBS`.
---@param spec string|table
---@return lsys.batch.Job[] jobs
---@return { file?: string, dir: string, total: integer } info
function lsys.batch.jobs(spec) end

--- What `lsys.batch.run(spec, opts)` would do, running nothing: this shard's jobs, each
--- with its `status` (made when read, as those of `lsys.batch.jobs`), and `total`, `k`, `n`,
--- `dir`, `manifest`, `file`.
---@param spec string|table
---@param opts? lsys.batch.RunOptions
---@return { jobs: lsys.batch.Job[], total: integer, k: integer, n: integer, dir: string, manifest: string, file?: string }
function lsys.batch.plan(spec, opts) end

---@class lsys.batch.RunOptions
---@field out? string The output folder (made when missing; default "."), with the manifest.
---@field shard? string|integer[] "K/N", "slurm" or { K, N }: the jobs n with (n - 1) % N == K - 1.
---@field force? boolean Run the jobs that are done as well.
---@field progress? fun(ev: { phase: "start"|"job"|"end", jobs: integer, todo: integer, done: integer, ok: integer, failed: integer, skipped: integer, removed: integer, seconds: number, job?: lsys.batch.Job, record?: table })

--- Runs the jobs of `spec` (all, or one shard's), skipping those done, and appends a JSON
--- line per job to the shard's manifest (DIR/manifest.jsonl or DIR/manifest-K-of-N.jsonl).
--- A failing job is recorded and the others run; a job that would write through a symbolic
--- link of the output folder fails. The temporaries dead runs left of the shard's files are
--- removed first (`removed`). Returns { jobs, ok, failed, skipped, removed, seconds,
--- manifest, failures = { { id, where, error } }, k, n, total }. Raises when the manifest
--- cannot be written.
---@param spec string|table
---@param opts? lsys.batch.RunOptions
---@return table result
function lsys.batch.run(spec, opts) end

--- The seed of job number `n` of a spec whose seed is `base`: mix(base + n * 0x9E3779B97F4A7C15)
--- >> 33, splitmix64's n-th number from `base`, its top 31 bits.
---@param base integer
---@param n integer
---@return integer
function lsys.batch.seed(base, n) end

--- The shard, 1 to `count`, of job number `n`: (n - 1) % count + 1.
---@param n integer
---@param count integer
---@return integer
function lsys.batch.shard_of(n, count) end

--- K, N of "K/N" or "slurm" (Slurm's SLURM_ARRAY_TASK_ID, _MIN, _STEP, _COUNT through
--- `getenv`, default os.getenv); nil and a message when there is none.
---@param s string
---@param getenv? fun(name: string): string?
---@return integer? k
---@return integer|string n
function lsys.batch.parse_shard(s, getenv) end

--- The records of CSV text (RFC 4180), each a list of fields with `line`; raises
--- "name:line: ..." for broken quoting.
---@param text string
---@param name string
---@return table[]
function lsys.batch.csv(text, name) end

-- }===========================================================================================
