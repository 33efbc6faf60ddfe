-- Misuse of lsys.core, to make its classes of bug impossible: seeded random calls of every
-- method and metamethod of every userdata type of lsys.core (found in their metatables, so
-- that a new method is called without a change here) and of its functions, on live, closed
-- and wrong objects, with hostile arguments: tables whose metamethods, and functions whose
-- calls, close objects or make random calls of their own, and finalizers that close objects
-- or make such calls at random points of a call (garbage with __gc handlers, the collector's
-- next cycle armed to fall inside the call's allocations: tests/finalizers.lua). Errors are
-- fine; the process must not crash. Run it under tools/sanitize.sh too, where a use of freed
-- memory fails it.
--
-- LSYS_MISUSE_CALLS=N sets the number of calls (default 5000, a few seconds), LSYS_MISUSE_SEED
-- the seed (default 1). The safety audit made 18,000:
--   LSYS_MISUSE_CALLS=18000 lua5.4 /usr/bin/busted --cpath=build/?.so tests/misuse_spec.lua
local H = require "tests.helper"
local fin = require "tests.finalizers"
local lsys = require "lsys"
local core = require "lsys.core"

local CALLS = tonumber(os.getenv("LSYS_MISUSE_CALLS")) or 5000
-- the test environmental program (tests/c/envslave.c): ctest sets LSYS_ENVSLAVE
local ENVSLAVE = os.getenv("LSYS_ENVSLAVE")
  or H.absolute((os.getenv("LSYS_BUILD_DIR") or "build") .. "/lsys_envslave")
local SEED = tonumber(os.getenv("LSYS_MISUSE_SEED")) or 1

-- the functions of lsys.core left out: they write files where they are told, open windows,
-- or change the state the rest of the suite runs in
local SKIP = { write_file = true, png_write = true, mkdir = true, viewer_open = true,
               max_memory = true, names_truncate = true, producing = true, pen_devices = true,
               outfile = true, tempdir = true, sandbox_strings = true }
-- the methods that write the file their first argument names (a string or a number) get a
-- path in the temporary folder, never one of the random arguments
local WRITES = { ["lsys.Scene:save"] = true, ["lsys.Canvas:save"] = true,
                 ["lsys.Lstring:write"] = true }

local function close (x) pcall(function () getmetatable(x).__close(x) end) end

describe("lsys.core under misuse", function ()
  local dir, png, leaf
  local pool, closed, calls = {}, {}, {}
  local target                    -- the object the running call is about
  local depth = 0
  local random = math.random
  local randomcall                -- forward

  local function pick (list) return list[random(#list)] end

  local function model ()
    return lsys.lsystem { axiom = "A(1) F [+B] F(2) C", seed = 3,
      view = { angle = 30, line_style = "cylinder", line_width = 0.1 },
      productions = { "A(x) : x < 4 --> A(x + 1) B", "B --> F [-F]", "C --> C" } }
  end

  -- the makers of one object of each type (more than one of a type: different shapes)
  local makers = {
    Lstring = function () return lsys.lstring("F(1)[+A(2)]B C") end,
    Rules = function () return model()._rules end,
    Template = function () return (model()._rules:axiom("A(1) B(2, 3)")) end,
    Scene = function () return model():interpret() end,
    Sphere = function () return lsys.lsystem { axiom = "F @O(1) F" }:interpret() end,
    Population = function ()
      local pop = core.population {}
      core.population_add(pop, model():interpret(), true)
      core.population_place(pop, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
      return pop
    end,
    Limbs = function ()
      local T = core.limbs { sides = 4 }
      local p = T:plant(0, 0, 0)
      local a = T:add(0, p, 0, 0, 0, 1, 0, 0, 1, 0.1, 0.5, 0.5, 0.5)
      T:add(a, p, 1, 1, 0, 0, 30, 0, 0.5, 0.05, 0.2, 0.8, 0.2)
      T:update()
      return T
    end,
    Contour = function () return core.contour({ { 1, 0 }, { 0, 1 }, { -1, 0 } }) end,
    Surface = function () return core.surface_parse(leaf, "leaf.s") end,
    Texture = function () return core.texture_load(png) end,
    Func = function () return core.func { { 0, 0 }, { 1 / 3, 1 }, { 2 / 3, 1 }, { 1, 0 } } end,
    Canvas = function () return core.canvas(16, 16) end,
    IK = function ()
      return core.ik_chain { base = { H = { 0, 1, 0 }, U = { 0, 0, 1 }, p = { 0, 0, 0 } },
        joints = { { p0 = { 0, 0, 0 }, p1 = { 0, 1, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } },
                   { p0 = { 0, 1, 0 }, p1 = { 0, 2, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } } } }
    end,
    BSpline = function ()
      return core.bspline { { 0, 0 }, { 1, 2 }, { 3, 1 }, { 4, 4 }, { 5, 0 } }
    end,
    Hyperpatch = function () return core.hyperpatch { degree = 2 } end,
    Frames = function ()
      local F = core.frames(1)
      F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
      F:stem(1, 2, 4, 10, 0, 0)
      return F
    end,
    Cwriter = function ()
      local F = core.frames(1)
      F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
      return core.cwriter(model()._rules, F)
    end,
    -- the writers: always in the temporary folder (their targets are their own)
    Outfile = function () return core.outfile(dir .. "/out" .. random(4) .. ".txt") end,
    Tempdir = function () return core.tempdir(dir) end,
    -- an environmental program: the test program over pipes, answering by echo (the random
    -- messages lack their Control line, so they are refused without waiting)
    EnvProcess = function ()
      return core.envproc { argv = { ENVSLAVE, "-e", "x.e", "echo" }, dir = dir, timeout = 10 }
    end,
    -- the light environment: a model's cylinders, and its lines as capsules
    Light = function ()
      return core.light(model():interpret(), { line_radius = 0.05, samples = 8 })
    end,
    -- the shadow-propagation grid
    Shadow = function ()
      return core.shadow { lo = { 0, 0, 0 }, hi = { 4, 3, 4 }, voxel = 0.5 }
    end,
    -- space: a hash of points and a scene's, and space colonisation's markers
    Space = function ()
      return core.space({ 0, 0, 0, 0.5, 0, 0, 1, 1, 1 }, { radius = 1, groups = { 0, 1, 0 },
                                                          scene = model():interpret() })
    end,
    Markers = function () return core.markers { 0, 1, 0, 1, 0, 0, 0, 2, 0 } end,
    Field = function ()
      local F = core.field { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cell = 0.5 }
      F:fill(1)
      return F
    end,
  }
  -- the types of lsys.core no maker makes, and why: the state's alphabet (one a state,
  -- never closed), the pixels, the turtle, the in-use mark and the rule box of limbs:set_rules
  -- of one call and the queries of core.environment (made and freed inside it, never handed
  -- out), the window
  local UNMADE = { Alphabet = true, Pixels = true, Turtle = true, Hold = true, LimbRules = true,
                   Viewer = true, EnvQueries = true }
  local kinds = {}
  for k in pairs(makers) do kinds[#kinds + 1] = k end
  table.sort(kinds)

  local function add (kind, x)
    local list = pool[kind]
    if #list < 6 then list[#list + 1] = x else list[random(#list)] = x end
  end

  local function anyobject ()
    local list = pool[pick(kinds)]
    if #list == 0 or random() < 0.1 then return closed[pick(kinds)] end
    return pick(list)
  end

  -- what a hostile metamethod, function or finalizer does: close the object of the running
  -- call or another, or make a random call of its own (not deeper than 2)
  local function mischief ()
    local r = random()
    if r < 0.4 then close(target or anyobject())
    elseif r < 0.6 then close(anyobject())
    elseif r < 0.9 and depth < 2 then
      depth = depth + 1
      pcall(randomcall)
      depth = depth - 1
    end
  end

  local NUMBERS = { -1, 0, 1, 2, 3, 7, 0.5, 100, 1e300, -1e300, 0 / 0, math.huge, -math.huge,
                    math.maxinteger, math.mininteger, 2 ^ 31, 2 ^ 53 }
  local strings, paths

  local function hostile (t)
    return setmetatable(t, {
      __index = function () mischief(); if random() < 0.5 then return random(3) end end,
      __len = function () mischief(); return random(0, 4) end,
      __newindex = function () mischief() end,
      __call = function () mischief(); return 1, 2, 3 end,
      __tostring = function () mischief(); return "hostile" end,
    })
  end

  local tables = {
    function () return {} end,
    function () return { 1, 2, 3 } end,
    function () return { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } } end,
    function () return { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 1 } } end,
    function () return { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } } end,
    function () return { width = 8, height = 8 } end,
    function () return { modules = { 1, 2 } } end,
    function () return { vertices = { 1, 3 } } end,
    function () return { textures = { anyobject() } } end,
    function () return { contours = { anyobject() }, line_style = "cylinder" } end,
    function () return { surfaces = { l = { surface = anyobject() } } } end,
    function () return { anyobject(), anyobject() } end,
    function () return { function () mischief(); return 1, 0, 0 end, 0.5 } end,
    function () return { { function () mischief(); return 1, 0, 0 end, 0.5 } } end,
    function () return { code = { 0, 0, 0 }, scale_length = 1.1 } end,
    function () return hostile {} end,
    function () return hostile { 1, 2, 3 } end,
    function () return hostile { width = 8, height = 8 } end,
    function () return { hostile {}, hostile { 1, 2, 3 } } end,
  }

  local functions = {
    function (x, y, z) return x, y, z end,
    function () mischief(); return 1, 2, 3 end,
    function () error("a function's error") end,
    function () end,
  }

  local WRONG = { io.stdout, coroutine.create(print), setmetatable({}, { __name = "lsys.Scene" }) }

  local function arg ()
    local r = random()
    if r < 0.27 then return anyobject()
    elseif r < 0.3 then return pick(WRONG)
    elseif r < 0.5 then return pick(NUMBERS)
    elseif r < 0.6 then return pick(strings)
    elseif r < 0.8 then return pick(tables)()
    elseif r < 0.9 then return pick(functions)
    elseif r < 0.95 then return nil
    else return random() < 0.5 end
  end

  -- finalizers that run at the collector's next cycles
  local function bombs ()
    for _ = 1, random(3) do setmetatable({}, { __gc = function () mischief() end }) end
  end

  -- every callable: {name, function, kind of its first argument or nil}
  local targets = {}

  local function collect (kind, x)
    local mt = getmetatable(x)
    local names = {}
    local methods = type(mt.__index) == "table" and mt.__index or mt.__methods
    for k, v in pairs(methods or {}) do
      if type(v) == "function" then names[#names + 1] = k end
    end
    for _, k in ipairs { "__index", "__len", "__tostring", "__eq", "__concat", "__call",
                         "__close", "__gc" } do
      if type(mt[k]) == "function" then names[#names + 1] = k end
    end
    table.sort(names)
    for _, k in ipairs(names) do
      local key = mt.__name .. ":" .. k
      if not calls[key] then
        calls[key] = 0
        targets[#targets + 1] = { key, methods and methods[k] or mt[k], kind }
      end
    end
  end

  randomcall = function ()
    local t = pick(targets)
    local self
    if t[3] then
      local r = random()
      local list = pool[t[3]]
      if r < 0.8 and #list > 0 then self = pick(list)
      elseif r < 0.9 then self = closed[t[3]]
      else self = arg() end
    end
    local args, n = {}, random(0, 6)
    for i = 1, n do args[i] = arg() end
    if t[1] == "render" then args[1] = hostile { width = 8, height = 8 } end
    if WRITES[t[1]] then args[1] = pick(paths) end
    calls[t[1]] = calls[t[1]] + 1
    local saved = target
    target = self
    if depth == 0 and random() < 0.5 then
      fin.arm(random(0, 4000))
      bombs()
    end
    local res
    if t[3] then res = table.pack(pcall(t[2], self, table.unpack(args, 1, n)))
    else res = table.pack(pcall(t[2], table.unpack(args, 1, n))) end
    target = saved
    for i = 2, res.n do                   -- new objects join the pool
      local mt = type(res[i]) == "userdata" and getmetatable(res[i])
      if mt and mt.__name == "lsys.Lstring" then add("Lstring", res[i])
      elseif mt and mt.__name == "lsys.Scene" then add("Scene", res[i])
      elseif mt and mt.__name == "lsys.Frames" then add("Frames", res[i]) end
    end
    return res[1]
  end

  setup(function ()
    dir = H.tmpdir()
    png = dir .. "/t.png"
    core.png_write(png, ("\255\0\0\255\0\255\0\128"):rep(2), 2, 2, true)
    leaf = H.read("tests/data/surfaces/leaf.s")
    strings = { "", "F", "A(1) B", "F(1)[+A(2)]B", "x", "rule", "pattern", "seed",
                "max_modules", "threads", "bezier", "#ff0000", "A(x) --> B", dir .. "/x.obj",
                dir .. "/x.glb", dir .. "/x.ply", dir .. "/x.png", dir .. "/missing/x.obj",
                png, dir .. "/leaf.s", ("A"):rep(300) }
    paths = { dir .. "/x.obj", dir .. "/x.glb", dir .. "/x.ply", dir .. "/x.png",
              dir .. "/x.txt", dir .. "/missing/x.obj" }
    H.write(dir .. "/leaf.s", leaf)
    H.write(dir .. "/x.e", "communication type: pipes\n")
    for _, k in ipairs(kinds) do
      pool[k] = { makers[k](), makers[k]() }
      closed[k] = makers[k]()
      collect(k, pool[k][1])
    end
    for _, k in ipairs(kinds) do close(closed[k]) end
    local names = {}
    for k, v in pairs(core) do
      if type(v) == "function" and not SKIP[k] then names[#names + 1] = k end
    end
    table.sort(names)
    for _, k in ipairs(names) do
      calls[k] = 0
      targets[#targets + 1] = { k, core[k] }
    end
  end)

  teardown(function ()
    fin.stop()
    pool, closed = nil, nil
    collectgarbage()
    collectgarbage()
    H.rmdir(dir)
  end)

  it("makes an object of every type lsys.core has, but for the few listed", function ()
    local missing = {}
    for k, v in pairs(debug.getregistry()) do
      if type(k) == "string" and type(v) == "table" and v.__name == k and k:find("^lsys%.") then
        local name = k:sub(6)
        if not makers[name] and not UNMADE[name] then missing[#missing + 1] = name end
      end
    end
    table.sort(missing)
    assert.same({}, missing)
    assert.is_truthy(makers.Scene and makers.Outfile and makers.Tempdir)
  end)

  it("calls every method on live, closed and wrong objects without crashing", function ()
    math.randomseed(SEED)
    fin.start()
    local failed = 0
    for n = 1, CALLS do
      if not randomcall() then failed = failed + 1 end
      if n % 100 == 0 then                -- fresh objects: many were closed
        for _, k in ipairs(kinds) do add(k, makers[k]()) end
      end
    end
    fin.stop()
    assert.is_true(failed > 0 and failed < CALLS)
    if CALLS >= 2000 then                 -- every method was called
      local missed = {}
      for k, c in pairs(calls) do if c == 0 then missed[#missed + 1] = k end end
      table.sort(missed)
      assert.same({}, missed)
    end
  end)
end)
