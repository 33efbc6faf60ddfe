--- Where the commands of the `lsys` program get their model: a Lua file, an example, a cpfg
-- .l file with its view file or a vlab object folder, loaded with --steps, --seed, --set.
-- @module lsys.cli.source
local core = require "lsys.core"
local A = require "lsys.cli.args"
local load = require "lsys.load"
local lmodel = require "lsys.model"
local lenvironment = require "lsys.environment"
local lview = require "lsys.view"
local suggest = require "lsys.util.suggest"
local normalize = require("lsys.util.text").normpath
local host = require("lsys.program").host
local tune = require "lsys.ui.tune"

local type, ipairs, tostring, tonumber, error, pcall, require =
      type, ipairs, tostring, tonumber, error, pcall, require
local io, string, table, math, debug = io, string, table, math, debug
local format = string.format
local usage, isatty, clock, isfile, isdir = A.usage, A.isatty, A.clock, A.isfile, A.isdir
local _ENV = nil

local M = {}

-- Directories that may hold the examples, most specific first.
local function example_dirs ()
  local dirs = {}
  local src = debug.getinfo(1, "S").source
  local root = src:match("^@(.*)[/\\]lsys[/\\]cli[/\\]source%.lua$")
  if root ~= nil then
    dirs[#dirs + 1] = normalize(root .. "/../examples")          -- source tree: lua/..
    dirs[#dirs + 1] = normalize(root .. "/../../lsys/examples")  -- share/lua/5.4/../../lsys
  end
  for _, d in ipairs(host().datadirs or {}) do
    dirs[#dirs + 1] = normalize(d .. "/examples")
  end
  return dirs
end

-- The path of the model file named by 'arg' (nil: the default example).
local function find_model (arg)
  local dirs = example_dirs()
  if arg ~= nil and isfile(arg) then return arg end
  local names = arg == nil and { "default.lua" } or { arg, arg .. ".lua" }
  if arg == nil or not arg:find("^/") then
    for _, d in ipairs(dirs) do
      for _, n in ipairs(names) do
        if isfile(d .. "/" .. n) then return d .. "/" .. n end
      end
    end
  end
  if arg == nil then
    error(format("no MODEL given and examples/default.lua was not found (looked in %s)",
      table.concat(dirs, ", ")), 0)
  end
  error(format("cannot open model '%s'", arg), 0)
end

-- A --map or --mat file: from the shell's folder when it is there, else as lsys.cpfg.load
-- takes it, from the .l file's folder (where vlab runs cpfg).
local function palette_file (p)
  if p == nil or p:sub(1, 1) == "/" or not isfile(p) then return p end
  return core.realpath(p) or p
end

-- The cpfg options of a command line (--map, --mat, --define) as lsys.cpfg.load options,
-- or nil when none is given.
local function cpfg_opts (cmd, opts)
  if opts.map == nil and opts.mat == nil and opts.define == nil and opts.environment == nil then
    return nil
  end
  if opts.map ~= nil and opts.mat ~= nil then usage(cmd, "give --map or --mat, not both") end
  local e = opts.environment
  if e ~= nil and e ~= "none" and not (e:find("%.e$") and isfile(e)) then
    usage(cmd, "--environment must be none or a communication file (FILE.e) that exists, "
          .. "got '%s'", e)
  end
  local defines
  for _, d in ipairs(opts.define or {}) do
    local k, v = d:match("^([%a_][%w_]*)=(.*)$")
    if k == nil and d:find("^[%a_][%w_]*$") then k, v = d, "1" end
    if k == nil then usage(cmd, "--define expects NAME=VALUE, got '%s'", d) end
    defines = defines or {}
    defines[k] = v
  end
  return { colormap = palette_file(opts.map), materials = palette_file(opts.mat),
           defines = defines, environment = opts.environment }
end

--[[
The model the positional arguments name: { path =, kind =, vfile =, lopts = }. A MODEL
ending in .l is a cpfg L-system file ("l"), and a second argument ending in .v its view
file; a folder with a `specifications` file is a vlab object ("object"); anything else is
a Lua model file or an example ("lua", find_model). lopts: the lsys.cpfg.load options of
--map, --mat and --define. Raises usage errors for arguments that do not go together.
]]
local function model_source (cmd, opts, pos)
  local arg, kind = pos[1], "lua"
  if arg ~= nil and arg:find("%.l$") then
    kind = "l"
  elseif arg ~= nil and isdir(arg) then
    if not isfile(arg .. "/specifications") then
      error(format("%s is a folder without a specifications file (a vlab object has one)",
                   arg), 0)
    end
    kind = "object"
  end
  local view = pos[2]
  if view ~= nil and kind == "lua" and view:find("%.v$") then
    usage(cmd, "a view file (%s) goes with a cpfg MODEL (.l), not with a Lua model", view)
  elseif view ~= nil and kind == "object" then
    usage(cmd, "unexpected argument '%s' (a vlab object names its view file in its "
          .. "specifications)", view)
  elseif view ~= nil and kind == "l" and not view:find("%.v$") then
    usage(cmd, "unexpected argument '%s' (after MODEL.l comes its view file, VIEW.v)", view)
  end
  if #pos > (kind == "l" and 2 or 1) then
    usage(cmd, "unexpected argument '%s' (%s)", pos[kind == "l" and 3 or 2],
          kind == "l" and "MODEL.l and VIEW.v at most" or "one MODEL at most")
  end
  local lopts = cpfg_opts(cmd, opts)
  if kind == "lua" then
    if lopts ~= nil and (lopts.colormap or lopts.materials or lopts.defines) then
      usage(cmd, "--map, --mat and --define apply to a cpfg MODEL (a .l file or a vlab "
            .. "object folder)")
    end
    -- --environment FILE.e (or none) gives a Lua model the program as its environment too
    return { path = find_model(arg), kind = kind, environment = opts.environment }
  end
  if opts.name ~= nil then usage(cmd, "--name applies to a Lua file that returns models") end
  if kind == "l" then
    local f, err = io.open(arg, "r")
    if f == nil then error(err, 0) end
    f:close()
  end
  for _, o in ipairs { "map", "mat" } do          -- neither here nor beside the model
    local p = opts[o]
    local dir = kind == "object" and arg or (arg:match("^(.*)/[^/]*$") or ".")
    if p ~= nil and p:sub(1, 1) ~= "/" and not isfile(p) and not isfile(dir .. "/" .. p) then
      error(format("--%s %s: no such file in the current folder nor in the model's (%s)", o,
                   p, normalize(dir)), 0)
    end
  end
  return { path = arg, kind = kind, vfile = view, lopts = lopts or {} }
end

-- Loads the model of model_source's `src`: a Lua model file through lsys.load.model (`name`
-- picks one of a table of models, `seed` expands a component graph), a cpfg model here.
local function load_source (src, name, seed)
  if src.kind == "lua" then return load.model(src.path, name, seed) end
  local cpfg = require "lsys.cpfg"
  local ok, m
  if src.kind == "object" then ok, m = pcall(cpfg.load_object, src.path, src.lopts)
  else ok, m = pcall(cpfg.load, src.path, src.vfile, src.lopts) end
  if not ok then      -- the loader names the file and line; its own name is no news
    error((tostring(m):gsub("^lsys%.view%.load: ", ""):gsub("^lsys%.cpfg%.%a+: ", "")), 0)
  end
  return m
end

-- The files a model comes from, for `lsys view` to watch: the Lua file; or the .l file,
-- the files it includes, the view file and the palette.
local function source_files (src)
  if src.kind == "lua" then return { src.path } end
  local cpfg, cpp = require "lsys.cpfg", require "lsys.cpfg.cpp"
  local files, seen = {}, {}
  local function add (f) if f and not seen[f] then seen[f] = true; files[#files + 1] = f end end
  local l, v, pal = src.path, src.vfile, src.lopts.colormap or src.lopts.materials
  if src.kind == "object" then
    add(src.path .. "/specifications")
    local ok, l2, v2, p2 = pcall(cpfg.object_files, src.path)
    if not ok then return files end
    l, v, pal = l2, v2, pal or p2
  end
  -- the files it #includes, in every branch of #if (a missing one is no obstacle); only the
  -- model's own files, as its preprocessing reads (never /dev/zero or /etc/shadow)
  local function scan (file, depth)
    if seen[file] or depth > 32 then return end
    if depth > 0 and not cpp.ismodelfile(l, file) then return end
    add(file)
    local text = cpp.readfile(file)
    for inc in (text or ""):gmatch('#%s*include%s*"([^"\n]+)"') do
      scan(inc:sub(1, 1) == "/" and inc or cpp.dirof(file) .. "/" .. inc, depth + 1)
    end
  end
  scan(l, 0)
  add(v)
  if pal then add(pal:sub(1, 1) == "/" and pal or cpp.dirof(l) .. "/" .. pal) end
  return files
end

-- A value given on the command line: a number, a list of numbers (1,2,3), a boolean, or text.
local function value (v)
  local n = tonumber(v)
  if n ~= nil then return math.tointeger(n) or n end
  if v == "true" then return true elseif v == "false" then return false end
  if v:find("^[-+%d.eE]+,[-+%d.eE,]+$") then
    local l = {}
    for x in v:gmatch("[^,]+") do
      l[#l + 1] = tonumber(x)
      if l[#l] == nil then return v end
    end
    return l
  end
  return v
end

-- Applies --set NAME=VALUE to the model's env. A name the model has no variable of is a
-- usage error, as it is for a job of lsys batch: a misspelt name would otherwise change
-- nothing without a word. (A model that reads a variable it may lack, `env.n or 5`, lists
-- it in its env to take it from the command line.)
local function set_env (cmd, model, sets, src)
  if model.env == nil then model.env = {} end
  local cpfg = src.kind ~= "lua"            -- (its env holds the translator's names too)
  local names = load.variables(model.env, cpfg)
  for _, kv in ipairs(sets) do
    if model.env[kv[1]] == nil or load.hidden(kv[1], cpfg) then
      local hint = suggest.hint(kv[1], names)
      local have = hint ~= "" and hint
        or #names == 0 and (cpfg and " (the model has no variables)"
                            or " (the model has no variables: its env is empty)")
        or " (the model's variables: " .. table.concat(names, ", ") .. ")"
      if src.kind ~= "lua" then
        have = have .. "; the preprocessor replaces a #define's name by its value (--define "
          .. "NAME=VALUE sets one), and `lsys import` writes a model file whose #defines of "
          .. "numbers are variables"
      end
      usage(cmd, "--set %s: the model has no variable %s%s", kv[1], kv[1], have)
    end
    if model.params ~= nil and model.param and model:param(kv[1]) ~= nil then
      local ok, err = pcall(function () model.params[kv[1]] = kv[2] end)   -- in its range
      if not ok then
        error(format("--set %s: %s", kv[1], tostring(err):gsub("^[^\n]-:%d+: ", "")), 0)
      end
    else
      model.env[kv[1]] = kv[2]
    end
  end
end

-- Checks each --view NAME=VALUE as the model's view will, so that a wrong one is blamed on
-- the option rather than on the model file.
local function check_views (cmd, model, vlist)
  local dir = type(model.view) == "table" and model.view.dir or nil
  for _, e in ipairs(vlist) do
    local k, s = e[1], e[2]
    local ok, err = pcall(lview.normalize, { [k] = value(s:match("=(.*)$")), dir = dir }, "")
    if not ok then
      err = tostring(err):gsub("^: ", ""):gsub("'view%.", "'")
      usage(cmd, "--view %s: %s", s, err)
    end
  end
end

-- --threads, --max-memory and --max-modules checked, as the model options they set:
-- { threads =, max_memory = (bytes; math.huge: "unlimited"), max_modules = }; nil when none
-- is given.
local function limit_opts (cmd, opts)
  local t, mem, mods = opts.threads, opts["max-memory"], opts["max-modules"]
  if t == nil and mem == nil and mods == nil then return nil end
  local lim = {}
  if t ~= nil then
    lim.threads = math.tointeger(tonumber(t))
    if lim.threads == nil or not lmodel.checkthreads(lim.threads) then
      usage(cmd, "--threads expects a whole number from 1 to %d, got '%s'", lmodel.MAX_THREADS, t)
    end
  end
  if mem ~= nil then
    local ok, r = pcall(lmodel.parse_size, mem, "--max-memory")
    if not ok then usage(cmd, "%s", (tostring(r):gsub("^[^\n]-:%d+: ", ""))) end
    lim.max_memory = r
  end
  if mods ~= nil then
    local n = tonumber(mods)
    if not (n and n == math.floor(n) and n >= 1 and n <= 1e12) then
      usage(cmd, "--max-modules expects a whole number from 1 to 1e12, got '%s'", mods)
    end
    lim.max_modules = math.tointeger(n) or n
  end
  return lim
end

-- Sets the options of limit_opts on the model `m`, over the model's own (Model:_limits).
local function apply_limits (m, lim)
  if lmodel.ismodel(m) then m:_limits(lim)
  elseif lim.threads ~= nil then m.threads = lim.threads end
end

-- Loads the model named by the positional arguments and applies --steps --seed --set, and
-- --threads --max-memory --max-modules.
local function prepare (cmd, opts, pos)
  local src = model_source(cmd, opts, pos)
  local steps, seed
  if opts.steps ~= nil then
    steps = math.tointeger(tonumber(opts.steps))
    if steps == nil or steps < 0 then
      usage(cmd, "--steps expects a non-negative integer, got '%s'", opts.steps)
    end
    local limit = lmodel.MAX_STEPS
    if steps > limit then
      usage(cmd, "--steps %s is more than the limit of %d steps", opts.steps, limit)
    end
  end
  if opts.seed ~= nil then
    seed = tonumber(opts.seed)
    if seed == nil then usage(cmd, "--seed expects a number, got '%s'", opts.seed) end
    seed = math.tointeger(seed) or seed
  end
  local limits = limit_opts(cmd, opts)
  local sets = {}
  for _, s in ipairs(opts.set or {}) do
    local k, v = s:match("^([%a_][%w_]*)=(.*)$")
    if k == nil then usage(cmd, "--set expects NAME=VALUE, got '%s'", s) end
    local n = tonumber(v)
    if n == nil or n ~= n or n == math.huge or n == -math.huge then
      usage(cmd, "--set %s: the value must be a finite number, got '%s'", k, v)
    end
    sets[#sets + 1] = { k, math.tointeger(n) or n }
  end
  local views, vlist = {}, {}
  for _, s in ipairs(opts.view or {}) do
    local k, v = s:match("^([%a_][%w_]*)=(.*)$")
    if k == nil then usage(cmd, "--view expects NAME=VALUE, got '%s'", s) end
    views[k] = value(v)
    vlist[#vlist + 1] = { k, s }
  end

  local path = src.path
  local model = load_source(src, opts.name, seed)
  if lmodel.isscene(model) then     -- a file returning a population
    if cmd ~= "render" and cmd ~= "export" or opts.frames ~= nil then
      error(format("%s returns a Scene (a population, lsys.population): `lsys render` and "
        .. "`lsys export` take it", path), 0)
    end
    if steps ~= nil or seed ~= nil or #sets > 0 then
      usage(cmd, "%s returns a Scene (a population): --steps, --seed and --set apply to a "
        .. "model", path)
    end
    -- the picture's options (camera, light, background...) apply to the drawn scene too;
    -- what changes how the turtle draws does not
    for _, e in ipairs(vlist) do
      if lview.TURTLE[e[1]] then
        usage(cmd, "%s returns a Scene (a population): --view %s changes how the turtle "
          .. "draws, which applies to a model", path, e[2])
      end
    end
    check_views(cmd, model, vlist)
    if limits ~= nil or src.environment ~= nil then
      usage(cmd, "%s returns a Scene (a population): --threads, --max-memory, "
        .. "--max-modules and --environment apply to a model", path)
    end
    return model, path, views, src
  end
  if src.environment ~= nil then
    if not lmodel.ismodel(model) then
      usage(cmd, "%s does not return a Model: --environment applies to a model", path)
    end
    if src.environment == "none" then model.environment = false
    else model.environment = lenvironment.program(src.environment) end
  end
  if model.components ~= nil and model.components.tree ~= nil and
     (steps ~= nil or #sets > 0) then
    usage(cmd, "%s is a component graph: it has no derivation steps (--steps) nor "
      .. "variables (--set)", path)
  end
  -- the values `lsys view` saved beside a model it could not rewrite (lsys.ui.tune)
  if src.kind == "lua" and lmodel.ismodel(model) and model.params ~= nil and #model.params > 0 then
    local side = tune.sidecar(path)
    local values = tune.read_sidecar(side)
    if values ~= nil and tune.apply_sidecar(model, values, side) > 0 and cmd ~= "view" then
      io.stderr:write(format("lsys: %s: the parameter values of %s\n", path, side))
    end
  end
  if steps ~= nil then model.steps = steps end
  if seed ~= nil then model.seed = seed end
  if limits ~= nil then apply_limits(model, limits) end
  if #sets > 0 then set_env(cmd, model, sets, src) end
  check_views(cmd, model, vlist)
  return model, path, views, src
end

-- Derives the model, with progress on stderr when asked or when stderr is a terminal.
local function derive (model, opts)
  if opts.progress or isatty(2) then
    local function progress (step, nsteps, nmodules)
      io.stderr:write(format("step %d/%d: %d modules\n", step, nsteps, nmodules))
      io.stderr:flush()
    end
    return model:derive(model.steps, { progress = progress })
  end
  return model:derive()
end

-- Derives and interprets the model of a render or export command line: the scene, the
-- model's path, the --view values, whether to print progress, and whether the scene was
-- drawn here with those views (false for a file returning a Scene).
local function scene_of (cmd, opts, pos)
  local model, path, views = prepare(cmd, opts, pos)
  local verbose = opts.progress or isatty(2)
  if lmodel.isscene(model) then return model, path, views, verbose, false end
  local s = derive(model, opts)
  local t0 = clock()
  local scene = model:interpret(s, views)
  if verbose then
    io.stderr:write(format("interpreted %d modules: %d triangles, %d lines (%.2f s)\n", #s,
      scene.ntriangles, scene.nlines, clock() - t0))
  end
  return scene, path, views, verbose, true
end

M.find_model = find_model
M.model_source = model_source
M.source_files = source_files
M.prepare = prepare
M.derive = derive
M.scene_of = scene_of

return M
