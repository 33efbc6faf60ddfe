--- cpfg's own model files as lsys Models: `lsys.cpfg.load(lfile [, vfile])` preprocesses
-- (lsys.cpfg.cpp) and parses (lsys.cpfg.parse) an L-system file (.l), translates it to
-- `lsys.lsystem` options (lsys.cpfg.translate) and makes the Model, with the view file's
-- view and functions; `options` gives the translated options themselves, `object_files`
-- and `load_object` read vlab object folders. Errors name the .l file and line.
-- See docs/cpfg.md.
-- @module lsys.cpfg
local type, pairs, ipairs, error, pcall, tostring, tonumber, next =
  type, pairs, ipairs, error, pcall, tostring, tonumber, next
local format = string.format
local cpp = require "lsys.cpfg.cpp"
local parse = require "lsys.cpfg.parse"
local translator = require "lsys.cpfg.translate"
local H = require "lsys.cpfg.helpers"
local model = require "lsys.model"
local func = require "lsys.func"
local viewmod = require "lsys.view"
local viewfile = require "lsys.viewfile"
local environment = require "lsys.environment"
local panel = require "lsys.cpfg.panel"
local _ENV = nil

local translate, untakable = translator.translate, translator.untakable
local numlit, LUA_KEYWORDS = translator.numlit, translator.LUA_KEYWORDS

local M = {}

local function cpfgerror (e)
  if type(e) == "table" and e.cpfg then return e.msg end
  return e
end

-- #define NAME i for the functions of a function set, as cpfg does for func(NAME, x)
local function funcdefines (v)
  local defs = {}
  local fs = v and v.functions
  if type(fs) ~= "table" then return defs end
  local fromset = false
  for _, x in ipairs(fs) do
    local file = type(x) == "table" and x.file or x
    if type(file) == "string" and file:match("%.fset$") then fromset = true end
  end
  if not fromset then return defs end
  local ok, list = pcall(func.collect, fs, v.dir, "functions")
  if not ok then return defs end
  for i, f in ipairs(list) do
    local name = f:name():gsub("%.[^.]*$", "")
    if name:find("^[%a_][%w_]*$") then defs[name] = i end
  end
  return defs
end

local function checkopts (opts, fname)
  if opts == nil then return {} end
  if type(opts) ~= "table" then error(fname .. ": opts must be a table", 3) end
  for k in pairs(opts) do
    if k ~= "cpp" and k ~= "colormap" and k ~= "materials" and k ~= "defines" and
       k ~= "functions" and k ~= "random" and k ~= "environment" and k ~= "edits" and
       k ~= "texts" then
      error(format("%s: unknown option '%s'", fname, tostring(k)), 3)
    end
  end
  if opts.edits ~= nil and type(opts.edits) ~= "table" then
    error(format("%s: option 'edits' must be a table { NAME = value }", fname), 3)
  end
  if opts.texts ~= nil and type(opts.texts) ~= "table" then
    error(format("%s: option 'texts' must be a table { [file] = text }", fname), 3)
  end
  if opts.functions ~= nil and opts.functions ~= "cpfg" and opts.functions ~= "exact" then
    error(format("%s: option 'functions' must be \"cpfg\" or \"exact\"", fname), 3)
  end
  if opts.random ~= nil and opts.random ~= "cpfg" and opts.random ~= "lsys" then
    error(format("%s: option 'random' must be \"cpfg\" or \"lsys\"", fname), 3)
  end
  local e = opts.environment
  if e ~= nil and e ~= "none" and not (type(e) == "string" and e:find("%.e$")) and
     environment.check(e) ~= nil then
    error(format("%s: option 'environment' must be \"none\", a communication file (.e) or "
                 .. "an environment (a function, an object with an answer method, or a list "
                 .. "of those; docs/open.md)", fname), 3)
  end
  return opts
end

-- An open L-system's ?E modules exchange values with an environment, which cpfg runs
-- beside the model as a program (cpfg -e; Mech and Prusinkiewicz 1996). A model that
-- relies on one would silently draw another plant without it, so ?E is refused unless
-- the caller gives an environment (lsys.environment) or asks for cpfg's behaviour without
-- one (environment = "none": the modules keep the values the rules give them, as
-- `cpfg -g` without -e does).
local function envcheck (P, opts)
  if P.envq and opts.environment == nil then
    P:fail(P.envq, "?E (a query of the environment) needs an environment: give the model "
           .. "one (option 'environment', docs/open.md), or environment = \"none\" "
           .. "(--environment none) to derive it as cpfg does without one")
  end
end

-- The model option of the load option `environment`: false for "none" (no environment,
-- and no warning about the ?E modules), else the environment itself.
local function envoption (e)
  if e == "none" then return false end
  if type(e) == "string" then return environment.program(e) end   -- a .e file: its program
  return e
end

-- The view's positional functions as cpfg computes them (lsys.func approx "cpfg"), or
-- nil when the view has none.
local function cpfgfuncs (v)
  if not (v and type(v.functions) == "table") then return nil end
  local list = func.collect(v.functions, v.dir, "view functions")
  local out = {}
  for i, f in ipairs(list) do
    out[i] = f:approx() == "cpfg" and f or
             func.new { points = f:points(), name = f:name(), samples = f:samples(),
                        approx = "cpfg" }
  end
  return out
end

--- A view's `functions` entries marked to be computed as cpfg approximates them
-- ({ file = NAME, samples = N, approx = "cpfg" }), as `lsys import` writes them.
function M.cpfg_functions (list)
  local out = {}
  for i, x in ipairs(list) do
    if type(x) == "table" and x.file then
      out[i] = { file = x.file, samples = x.samples, approx = "cpfg" }
    elseif type(x) == "string" then
      out[i] = { file = x, approx = "cpfg" }
    else
      out[i] = x
    end
  end
  return out
end

--- The lsys.lsystem options of a cpfg L-system file, and the translation's details.
-- opts: cpp ("system", "builtin"; default the system cpp when present), defines
-- ({ NAME = value } for the preprocessor), view (a view table: its function set
-- defines the functions' names, as in cpfg). For lsys.cpfg.import: keep (true: a second
-- result with the Lua source of the function rules, hooks and arrays), names (true: the
-- built-in preprocessor keeps the #defines of plain numbers as names, which the rules
-- read from env; the second result's `defines` lists them, see cpp.builtin).
function M.options (lfile, opts)
  if type(lfile) ~= "string" then error("lsys.cpfg.options: a file name expected", 2) end
  opts = opts or {}
  local ok, o, keep = pcall(function ()
    local defs = funcdefines(opts.view)
    for k, v in pairs(opts.defines or {}) do defs[k] = v end
    local kept = opts.names and { taken = untakable() } or nil
    local lines = kept and cpp.builtin(lfile, defs, kept) or cpp.run(lfile, defs, opts.cpp)
    local P = parse.new(lines)
    local lsystems = P:file()
    envcheck(P, opts)
    local o, T = translate(P, lsystems, { name = lfile, keep = opts.keep, random = opts.random,
                                          globals = kept and kept.values })
    if T.keep then T.keep.defines = kept end
    return o, T.keep
  end)
  if not ok then error(cpfgerror(o), 0) end
  return o, keep
end

--- Loads a cpfg model: the L-system file `lfile` and optionally its view file `vfile`
-- (read with lsys.view.load; contours, surfaces and functions are relative to its
-- folder). opts: colormap or materials (a .map or .mat file, the palette), cpp and
-- defines as for `options`, functions ("cpfg", the default: the view's functions
-- approximated as cpfg does; "exact": lsys's exact values), random ("cpfg", the default:
-- cpfg's random numbers in cpfg's order, on one thread; "lsys": lsys's generator, which
-- does not depend on the order nor on the threads), environment (what the ?E modules
-- query: a communication file FILE.e, whose program is started as cpfg -e does, or the
-- model option's function or object, docs/open.md; "none": they keep
-- their values, as cpfg does without an environmental program; without it a model with
-- ?E modules is refused), edits ({ NAME = value }: the file's `#define NAME` lines get
-- these values, as a vlab panel's awkped writes them, without writing the file; a
-- #define in the file beats `defines`, not `edits`), texts ({ [file] = text }: the text
-- of the .l or .v file read in place of the file's, a panel's line edits). Returns an
-- lsys Model; raises
-- "file:line: message".
function M.load (lfile, vfile, opts)
  if type(lfile) ~= "string" then error("lsys.cpfg.load: a file name expected", 2) end
  if vfile ~= nil and type(vfile) ~= "string" then
    error("lsys.cpfg.load: the view file must be a file name", 2)
  end
  opts = checkopts(opts, "lsys.cpfg.load")
  local texts = opts.texts or {}
  local v
  if vfile and texts[vfile] then            -- the view file as a panel edited it
    v = viewfile.parse(texts[vfile], vfile, { dir = cpp.dirof(vfile), missing = "warn" })
  else
    v = vfile and viewmod.load(vfile, { missing = "warn" }) or { dir = cpp.dirof(lfile) }
  end
  -- what the view leaves unset (or sets to '?') is cpfg's default, not lsys.view's
  for k, x in pairs(viewfile.CPFG_DEFAULTS) do
    if v[k] == nil then v[k] = x end
  end
  local pal = opts.colormap or opts.materials
  if pal then
    local ldir = cpp.dirof(lfile)
    v = v or { dir = ldir }
    v.palette = (pal:sub(1, 1) == "/" or v.dir == ldir) and pal or ldir .. "/" .. pal
  end
  local o, T
  local ok, err = pcall(function ()
    local defs = funcdefines(v)
    for k, x in pairs(opts.defines or {}) do defs[k] = x end
    local text = texts[lfile]
    if opts.edits and next(opts.edits) then      -- a panel's values, as awkped writes them
      local t, why = text, nil
      if t == nil then t, why = cpp.readfile(lfile) end
      if not t then error({ cpfg = true, msg = why }, 0) end
      text = panel.edit(t, opts.edits)
    end
    local lines = cpp.run(lfile, defs, opts.cpp, text)
    local P = parse.new(lines)
    local lsystems = P:file()
    envcheck(P, opts)
    o, T = translate(P, lsystems, { name = lfile, random = opts.random })
  end)
  if not ok then error(cpfgerror(err), 0) end
  o.view = v
  if opts.functions ~= "exact" then o.functions = cpfgfuncs(v) end
  o.random = opts.random or "cpfg"      -- cpfg's numbers in cpfg's order (docs/cpfg.md)
  o.environment = envoption(opts.environment)
  local ok2, m = pcall(model.lsystem, o)
  if not ok2 then
    -- name the cpfg line of a rule lsys refused
    local msg = tostring(m)
    local n, sect = msg:match("entry (%d+) of ([^)]+)%)")
    local pos = sect and T.origin[sect] and T.origin[sect][tonumber(n)]
    if pos then
      local file, line = T.P:where(pos)
      msg = format("%s:%d: %s", file, line, msg)
    end
    error(msg, 0)
  end
  -- messages name the .l file and the production's line, not lsys's list of rules
  m._where = lfile
  for _, info in pairs(m._info) do
    local n, sect = info.label:match("%(entry (%d+) of ([^)]+)%)$")
    local pos = sect and T.origin[sect] and T.origin[sect][tonumber(n)]
    if pos then
      local file, line = T.P:where(pos)
      info.where, info.label = format("%s:%d", file, line), info.label:gsub(" %(entry.*$", "")
    end
  end
  if not vfile then
    m._funchint = "; a cpfg model's functions come from its view file (.v), and none was given"
  end
  T.model = m         -- (srand in Start: blocks run by the axiom, before the start hook)
  if T.usesfunc then T.H.func = function (id, x) return m:func(id, x) end end
  return m
end

--- The files of a vlab object folder, as `load_object` picks them: the L-system file, the
-- view file (or nil) and the palette (a .map or .mat file relative to the folder, or nil),
-- each but the palette with the folder's path in front.
function M.object_files (dir)
  if type(dir) ~= "string" then error("lsys.cpfg.object_files: a folder name expected", 2) end
  local spec = dir .. "/specifications"
  local text, err = cpp.readfile(spec)
  if not text then error("lsys.cpfg.load_object: " .. tostring(err), 0) end
  local files, l, v, pal = {}, nil, nil, nil
  for line in text:gmatch("[^\n]+") do
    local cmd = line:match("^%s*cpfg%s(.*)$")
    if cmd and not l then
      local words = {}
      for w in cmd:gmatch("%S+") do words[#words + 1] = w end
      local i = 1
      while i <= #words do
        local w = words[i]
        if w:match("^%-[mM]1?$") then          -- -m2, -M2: colour map 2, not the palette
          pal = pal or words[i + 1]
          i = i + 1
        elseif w:match("^%-[mM]%d+$") then
          i = i + 1
        elseif w:match("%.l$") then l = l or w
        elseif w:match("%.v$") then v = v or w end
        i = i + 1
      end
    end
  end
  for line in text:gmatch("[^\n]+") do
    if line:match("^ignore:") then break end
    local f = line:match("^(%S+)%s*$")
    if f then files[#files + 1] = f end
  end
  for _, f in ipairs(files) do
    if not l and f:match("%.l$") then l = f end
    if not v and f:match("%.v$") then v = f end
    if not pal and (f:match("%.map$") or f:match("%.mat$")) then pal = f end
  end
  if not l then error(format("%s: no L-system file (.l) named", spec), 0) end
  return dir .. "/" .. l, v and dir .. "/" .. v or nil, pal
end

--- Loads a vlab object folder: its `specifications` file names the files; the first
-- `cpfg` command in it (as in `generate: cpfg -m leaf.map leaf.l leaf.v`) picks the
-- L-system, view and colour map or material file, else the first .l, .v, .map or .mat
-- listed. Returns the Model.
function M.load_object (dir, opts)
  if type(dir) ~= "string" then error("lsys.cpfg.load_object: a folder name expected", 2) end
  opts = checkopts(opts, "lsys.cpfg.load_object")
  local l, v, pal = M.object_files(dir)
  local o2 = {}
  for k, x in pairs(opts) do o2[k] = x end
  if pal and not o2.colormap and not o2.materials then
    if pal:match("%.mat$") then o2.materials = pal else o2.colormap = pal end
  end
  return M.load(l, v, o2)
end

--- cpfg's helper functions as the translated rules call them (H in their Lua source):
-- lsys.cpfg.import's model files use them.
M.helpers = H

-- For lsys.cpfg.import, which writes the same Lua: a number literal as the translated rules
-- hold it, and Lua's reserved words (no variable may take one as its name).
M.numlit = numlit
M.LUA_KEYWORDS = LUA_KEYWORDS

return M
