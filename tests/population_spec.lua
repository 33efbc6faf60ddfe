-- Populations (docs/population.md): many plants in one scene, plants alike sharing one
-- prototype. What is built (prototypes, instances, transforms, sizes, memory), that the
-- same list builds the same scene, the bounds, pictures and files of a population against
-- those of its flattened copy, glb's EXT_mesh_gpu_instancing, and the error messages.
local H = require "tests.helper"
local lsys = require "lsys"
local glb = require "tests.glb"
local reader = require "tests.export_reader"

-- A small stochastic bush of cylinders and polygon leaves: each seed another shape.
local function bush ()
  return lsys.lsystem {
    axiom = "!(0.15) A", steps = 3, seed = 1, env = { b = 30 },
    productions = [[
A --> F [ + (b) A L ] [ - (b) A ] [ & (b) A ] : 0.4
A --> F [ / (90) + (b) A ] F A L : 0.6
L --> ;(2) { . - (40) f(0.3) . + (80) f(0.3) . }
]],
    view = { angle = 30, line_style = "cylinder", contour_sides = 5 },
  }
end

-- A plant in line style: thin lines and lines wide enough to be drawn as bands.
local function broom ()
  return lsys.lsystem {
    axiom = "#(7) A", steps = 3, seed = 2,
    productions = "A --> F !(0.6) [ + A ] [ - A ] F A",
    view = { angle = 25 },
  }
end

local function tmp (ext)
  local p = os.tmpname()
  os.remove(p)
  return p .. ext
end

local function read (path)
  local f = assert(io.open(path, "rb"))
  local s = f:read("a")
  f:close()
  return s
end

-- A field of n plants of model m on a grid, seeds 1..k, turned and scaled each its own way.
local function field (m, n, k, opts)
  return lsys.population({ count = n, place = function (i)
    return { model = m, at = { (i % 10) * 3, 0, (i // 10) * 3 }, rotate = (i * 37) % 360,
             scale = { 1, 0.8 + 0.01 * (i % 20), 1 }, seed = 1 + i % k }
  end }, opts)
end

describe("lsys.population", function ()
  it("makes one prototype per distinct plant and one instance per plant, in order", function ()
    local m, n = bush(), broom()
    local pop = lsys.population {
      { model = m, at = { 0, 0, 0 } },
      { model = m, at = { 5, 0, 0 }, seed = 7 },
      { model = n, at = { 0, 0, 5 } },
      { model = m, at = { 5, 0, 5 }, seed = 7, rotate = 90 },
      { model = m, at = { 9, 0, 9 }, env = { b = 20 } },
      { model = m, at = { 9, 0, 0 }, seed = 1 },     -- the model's own seed, given: another key
    }
    assert.equal("scene", lsys.type(pop))
    assert.equal(6, pop.ninstances)
    assert.equal(5, pop.nprototypes)
    local protos = {}
    for i = 1, 6 do protos[i] = pop:instance(i).prototype end
    assert.same({ 1, 2, 3, 2, 4, 5 }, protos)
    assert.equal(2, pop:prototype(2).instances)
    assert.equal(7, pop:prototype(2).seed)
    assert.equal(m, pop:prototype(2).model)
    assert.same({ b = 20 }, pop:prototype(4).env)
    assert.is_nil(pop:instance(7))
    assert.is_nil(pop:prototype(6))
    -- the counts are those of the plants drawn
    local t = 0
    for i = 1, 6 do t = t + pop:prototype(pop:instance(i).prototype).triangles end
    assert.equal(t, pop.ntriangles)
    assert.equal(pop:prototype(3).lines, pop.nlines)
    assert.matches("a population of 6 plants of 5 prototypes", tostring(pop))
    -- a plain scene is no population
    assert.equal(0, m:interpret().ninstances)
    assert.equal(0, m:interpret().nprototypes)
  end)

  it("derives a prototype as the model would with that seed, steps and env", function ()
    local m = bush()
    local pop = lsys.population { { model = m, seed = 5, steps = 2, env = { b = 45 } } }
    local ref = lsys.lsystem { axiom = m.axiom, steps = 2, seed = 5, env = { b = 45 },
                               productions = [[
A --> F [ + (b) A L ] [ - (b) A ] [ & (b) A ] : 0.4
A --> F [ / (90) + (b) A ] F A L : 0.6
L --> ;(2) { . - (40) f(0.3) . + (80) f(0.3) . }
]], view = m.view }
    assert.equal(tostring(ref:derive()), tostring(pop:prototype(1).lstring))
    assert.equal(ref:interpret().ntriangles, pop.ntriangles)
    -- the model is left as it was
    assert.equal(1, m.seed)
    assert.same({ b = 30 }, m.env)
  end)

  it("places a plant by at, rotate and scale: T R S", function ()
    local m = lsys.lsystem { axiom = "F" }          -- a line: bounds without widths
    local pop = lsys.population {
      { model = m, at = { 1, 2, 3 } },
      { model = m, rotate = 90 },
      { model = m, rotate = { axis = { 1, 0, 0 }, angle = 90 }, scale = 2 },
      { model = m, rotate = { { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } }, scale = { 1, 3, 1 } },
    }
    local i1, i2, i3, i4 = pop:instance(1), pop:instance(2), pop:instance(3), pop:instance(4)
    assert.near({ 1, 2, 3 }, i1.at, 1e-6)
    assert.near({ 0, 0, 0, 1 }, i1.rotation, 1e-6)
    assert.near({ 0, math.sqrt(0.5), 0, math.sqrt(0.5) }, i2.rotation, 1e-6)
    assert.near({ 2, 2, 2 }, i3.scale, 1e-6)
    assert.near({ 1, 3, 1 }, i4.scale, 1e-6)
    -- the heading +y (the stem) goes to +z about x, to -x by the matrix, three times long
    assert.near({ 0, 0, 2, 0 }, { table.unpack(i3.matrix, 5, 8) }, 1e-6)
    assert.near({ -3, 0, 0, 0 }, { table.unpack(i4.matrix, 5, 8) }, 1e-6)
    local lo, hi = pop:bounds()
    assert.near({ -3, 0, 0 }, lo, 1e-6)
    assert.near({ 1, 3, 3 }, hi, 1e-6)      -- the first one: from (1, 2, 3) to (1, 3, 3)
  end)

  it("has the bounds and area of its flattened copy", function ()
    local pop = field(bush(), 40, 4)
    local flat = pop:flatten()
    assert.equal(0, flat.ninstances)
    assert.equal(pop.ntriangles, flat.ntriangles)
    assert.equal(pop.nvertices, flat.nvertices)
    local a, b = pop:bounds()
    local c, d = flat:bounds()
    assert.near(c, a, 1e-4)
    assert.near(d, b, 1e-4)
    assert.near(flat:area(), pop:area(), 1e-6 * flat:area())
  end)

  it("holds each prototype once: 1,000 plants of 5 prototypes cost the 5 plants and "
     .. "the transforms", function ()
    local m = bush()
    local pop = field(m, 1000, 5)
    assert.equal(5, pop.nprototypes)
    local protos = 0
    for k = 1, 5 do
      protos = protos + lsys.population({ { model = m, seed = pop:prototype(k).seed } }).bytes
    end
    -- the geometry of five plants (arrays grow by doubling), 1,000 transforms of 68 bytes
    assert.is_true(pop.bytes < protos + 1000 * 68 * 2 + 4096,
                   ("%d bytes, prototypes %d"):format(pop.bytes, protos))
    local flat = pop:flatten()
    assert.is_true(flat.bytes > 50 * pop.bytes, ("%d vs %d"):format(flat.bytes, pop.bytes))
  end)

  it("builds the same scene from the same list", function ()
    local a, b = field(bush(), 60, 6), field(bush(), 60, 6)
    local pa, pb = tmp(".glb"), tmp(".glb")
    a:save(pa)
    b:save(pb)
    assert.equal(read(pa), read(pb))
    a:save(pa, { instancing = false })
    b:save(pb, { instancing = false })
    assert.equal(read(pa), read(pb))
    os.remove(pa)
    os.remove(pb)
  end)

  it("takes a list or count and place alike", function ()
    local m = bush()
    local list = {}
    for i = 1, 12 do list[i] = { model = m, at = { i, 0, 0 }, seed = i % 3 } end
    local a = lsys.population(list)
    local b = lsys.population { count = 12, place = function (i) return list[i] end }
    assert.equal(a.nprototypes, b.nprototypes)
    for i = 1, 12 do assert.same(a:instance(i), b:instance(i)) end
    assert.equal(0, lsys.population({}).ninstances)
    assert.equal(0, lsys.population({ count = 0, place = function () end }).ninstances)
  end)

  it("takes Scenes and Lstrings as plants", function ()
    local m = bush()
    local sc = m:interpret()
    local s = m:derive()
    local pop = lsys.population {
      { model = sc, at = { 0, 0, 0 } }, { model = sc, at = { 3, 0, 0 } },
      { model = s, at = { 6, 0, 0 } }, { model = lsys.lstring("F[+F]F"), at = { 9, 0, 0 } },
    }
    assert.equal(3, pop.nprototypes)
    assert.equal(sc.ntriangles * 3, pop.ntriangles)
    assert.equal(sc.ntriangles, sc:area() > 0 and sc.ntriangles)   -- the scene is still open
    assert.equal(3, pop:prototype(3).lines)          -- F [ + F ] F
  end)

  it("keeps the records and Lstrings of its prototypes unless records = false", function ()
    local m = bush()
    local pop = field(m, 20, 2)
    assert.equal(pop:prototype(1).records + pop:prototype(2).records, pop.nrecords)
    assert.truthy(pop:prototype(1).lstring)
    local bare = field(m, 20, 2, { records = false })
    assert.equal(0, bare.nrecords)
    assert.is_nil(bare:prototype(1).lstring)
    assert.equal(pop.ntriangles, bare.ntriangles)
    assert.error_contains(function () pop:turtle(1) end, "a population has no Lstring")
  end)

  it("reports its progress", function ()
    local calls = {}
    field(bush(), 2500, 3, { progress = function (phase, k, n)
      calls[#calls + 1] = phase .. " " .. k .. "/" .. n
    end })
    assert.same({ "prototype 1/3", "prototype 2/3", "prototype 3/3", "place 1000/2500",
                  "place 2000/2500", "place 2500/2500" }, calls)
  end)
end)

describe("lsys.population errors", function ()
  local m = lsys.lsystem { axiom = "F" }
  local cases = {
    { "x", "a list of plants or { count = N, place = function (i) ... end } expected" },
    { { 1 }, "plant 1: a table expected, got 1" },
    { { {} }, "plant 1: 'model' is missing (a Model, a Scene or an Lstring)" },
    { { { model = 3 } }, "plant 1: 'model' must be a Model, a Scene or an Lstring, got 3" },
    { { { model = m }, { model = m, pos = 1 } },
      "plant 2: unknown field 'pos' (model, lstring, at, rotate, scale, seed, steps, env, view)" },
    { { { model = m, at = { 1, 2 } } },
      "'at' must be a list of 3 finite numbers {x, y, z}, got 2 numbers" },
    { { { model = m, at = { 1, 0 / 0, 2 } } },
      "plant 1: 'at' must be a list of 3 finite numbers {x, y, z}, got {1, " },
    { { { model = m, scale = -1 } },
      "plant 1: 'scale' must be a positive number or a list of 3 positive numbers, got -1" },
    { { { model = m, scale = { 1, 0, 1 } } }, "plant 1: 'scale' must be a positive number" },
    { { { model = m, rotate = "x" } }, "plant 1: 'rotate' must be a number of degrees" },
    { { { model = m, rotate = { axis = { 0, 0, 0 }, angle = 5 } } },
      "plant 1: 'rotate.axis' must not be the zero vector" },
    { { { model = m, rotate = { axis = { 0, 1, 0 } } } },
      "plant 1: 'rotate.angle' must be a finite number of degrees, got nil" },
    { { { model = m, rotate = { { 1, 0, 0 }, { 0, 2, 0 }, { 0, 0, 1 } } } },
      "plant 1: 'rotate' is not a rotation: its rows must be orthonormal" },
    { { { model = m, rotate = { { -1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } } },
      "plant 1: 'rotate' is a mirror (determinant -1), not a rotation" },
    { { { model = m, seed = 1.5 } }, "plant 1: 'seed' must be an integer, got 1.5" },
    { { { model = m, steps = -1 } }, "plant 1: 'steps' must be a whole number >= 0, got -1" },
    { { { model = m, env = 3 } }, "plant 1: 'env' must be a table of names, got 3" },
    { { { model = lsys.lstring("F"), seed = 3 } },
      "plant 1: 'seed' needs a Model ('model' is an Lstring, drawn as it is)" },
    { { count = 3 }, "'place' must be a function (i) returning a plant, got nil" },
    { { count = -1, place = print }, "'count' must be a whole number >= 0, got -1" },
    { { { model = m }, count = 1, place = print }, "give a list of plants or count and place" },
    { { count = 2, place = function (i) if i == 2 then return { model = m, at = 5 } end
                                        return { model = m } end },
      "place(2): 'at' must be a list of 3 finite numbers {x, y, z}, got 5" },
    { { count = 2, place = function (i) if i == 2 then error("no room") end
                                        return { model = m } end }, "place(2): ", "no room" },
    { { {model = m}, colour = 1 },
      "unknown option 'colour' (view, records, progress, count, place)" },
    { { { model = m }, view = { line_style = "cylinder" } },
      "view.line_style changes how the plants are drawn: give it in a plant's view" },
    { { { model = m }, view = { projection = "fish" } },
      "lsys.population: 'view.projection' must be" },
  }
  for i, c in ipairs(cases) do
    it("names the plant and the field: case " .. i, function ()
      local msg = H.errof(lsys.population, c[1])
      assert.matches("^lsys.population: ", msg)
      for k = 2, #c do assert.truthy(msg:find(c[k], 1, true), msg) end
    end)
  end

  it("blames the caller", function ()
    local ok, msg = pcall(function () lsys.population { { model = m, at = 1 } } end)
    assert.is_false(ok)
    assert.matches("^[^:]*population_spec.lua:%d+: lsys.population: plant 1: 'at'", msg)
  end)

  it("names the plant whose model fails", function ()
    local bad = lsys.lsystem { axiom = "A", productions = "A --> B(x)" }
    local msg = H.errof(lsys.population, { { model = m }, { model = bad } })
    assert.truthy(msg:find("lsys.population: plant 2 (prototype 2): ", 1, true), msg)
    assert.truthy(msg:find("'x'", 1, true), msg)
  end)
end)

describe("lsys.population and max_memory", function ()
  local core = require "lsys.core"
  local saved
  before_each(function () saved = lsys.max_memory() end)
  after_each(function () lsys.max_memory(saved == math.huge and "unlimited" or saved) end)
  local m = lsys.lsystem { axiom = "F" }

  it("counts the plants' tables and instances before making them", function ()
    lsys.max_memory("64M")
    local placed = 0
    local msg = H.errof(lsys.population, { count = 1000000, place = function (i)
      placed = placed + 1
      return { model = m, at = { i, 0, 0 } }
    end })
    assert.equal("lsys.population: 1000000 plants need 337 MiB, more than max_memory (64 MiB)",
                 msg)
    assert.equal(0, placed)
    assert.equal(100000, lsys.population({ count = 100000, place = function (i)
      return { model = m, at = { i, 0, 0 } }                 -- a tenth of them fit
    end }, { records = false }).ninstances)
  end)

  it("counts the prototypes' tables as they come", function ()
    lsys.max_memory("24M")
    assert.equal("lsys.population: place(4789) makes prototype 4789: the plants and their "
                 .. "prototypes need more than max_memory (24 MiB)",
                 H.errof(lsys.population, { count = 50000, place = function (i)
                   return { model = m, seed = i, at = { i, 0, 0 } }
                 end }))
  end)

  it("counts the plants' tables with the prototypes' geometry", function ()
    local big = lsys.lsystem { axiom = ("F+"):rep(30000),
                               view = { line_style = "cylinder", contour_sides = 8, angle = 1 } }
    lsys.max_memory("64M")
    assert.truthy(big:interpret(big:derive(0)))    -- the plant alone fits
    assert.equal("lsys.population: the prototypes need more than max_memory (64 MiB)",
                 H.errof(lsys.population, { count = 100000, place = function (i)
                   return { model = big, at = { i, 0, 0 } }
                 end }))
  end)

  it("keeps the room for the instances within the budget in the core", function ()
    lsys.max_memory("64M")
    local pop = core.population({})
    local sc = m:interpret(m:derive(0))
    local msg = H.errof(core.population_add, pop, sc, false, 4000000000, 0)
    assert.equal("lsys.population: 4000000000 plants need 253.3 GiB, more than max_memory "
                 .. "(64 MiB)", (msg:gsub("^[^:]*:%d+: ", "")))
    assert.equal(1, core.population_add(pop, sc, false, 1000, 0))
  end)
end)

describe("population files", function ()
  local function ext_data (doc, bin, node)
    local a = node.extensions.EXT_mesh_gpu_instancing.attributes
    return glb.accessor(doc, bin, a.TRANSLATION), glb.accessor(doc, bin, a.ROTATION),
           glb.accessor(doc, bin, a.SCALE)
  end

  -- q (x, y, z, w) applied to v
  local function rotate (q, v)
    local x, y, z, w = q[1], q[2], q[3], q[4]
    local tx = 2 * (y * v[3] - z * v[2])
    local ty = 2 * (z * v[1] - x * v[3])
    local tz = 2 * (x * v[2] - y * v[1])
    return { v[1] + w * tx + (y * tz - z * ty), v[2] + w * ty + (z * tx - x * tz),
             v[3] + w * tz + (x * ty - y * tx) }
  end

  it("writes glb with EXT_mesh_gpu_instancing: a mesh and a node per prototype", function ()
    local pop = field(bush(), 30, 3)
    local path = tmp(".glb")
    pop:save(path)
    local doc, bin = glb.read(path)
    assert.same({ "EXT_mesh_gpu_instancing" }, doc.extensionsUsed)
    assert.same({ "EXT_mesh_gpu_instancing" }, doc.extensionsRequired)
    assert.equal(3, #doc.meshes)
    assert.equal(3, #doc.nodes)
    assert.same({ 0, 1, 2 }, doc.scenes[1].nodes)
    -- every instance, its vertices moved by T R S, lands where the flattened copy has them
    local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
    local count, tris = 0, 0
    for k, node in ipairs(doc.nodes) do
      local t, r, s = ext_data(doc, bin, node)
      local n = #t // 3
      assert.equal(pop:prototype(k).instances, n)
      count = count + n
      local prim = doc.meshes[node.mesh + 1].primitives
      local pos = glb.accessor(doc, bin, prim[1].attributes.POSITION)
      for _, p in ipairs(prim) do tris = tris + n * doc.accessors[p.indices + 1].count // 3 end
      for i = 0, n - 1 do
        local q = { r[4 * i + 1], r[4 * i + 2], r[4 * i + 3], r[4 * i + 4] }
        for v = 0, #pos // 3 - 1 do
          local w = rotate(q, { pos[3 * v + 1] * s[3 * i + 1], pos[3 * v + 2] * s[3 * i + 2],
                                pos[3 * v + 3] * s[3 * i + 3] })
          for c = 1, 3 do
            local x = w[c] + t[3 * i + c]
            if x < lo[c] then lo[c] = x end
            if x > hi[c] then hi[c] = x end
          end
        end
      end
    end
    assert.equal(30, count)
    assert.equal(pop.ntriangles, tris)
    local a, b = pop:bounds()
    assert.near(a, lo, 1e-4)
    assert.near(b, hi, 1e-4)
    os.remove(path)
  end)

  it("writes glb without instancing, OBJ and PLY flattened", function ()
    local pop = field(bush(), 20, 2)
    local g, o, p = tmp(".glb"), tmp(".obj"), tmp(".ply")
    pop:save(g, { instancing = false })
    local doc, bin = glb.read(g)
    assert.is_nil(doc.extensionsUsed)
    assert.equal(1, #doc.nodes)
    local tris = 0
    for _, prim in ipairs(glb.primitives(doc, bin)) do tris = tris + (prim.triangles or 0) end
    assert.equal(pop.ntriangles, tris)
    pop:save(o)
    assert.equal(pop.ntriangles, reader.obj(o).f)
    pop:save(p)
    assert.equal(pop.nvertices, reader.ply(p).counts.vertex)
    for _, f in ipairs { g, o, o:gsub("%.obj$", ".mtl"), p } do os.remove(f) end
  end)

  it("refuses to write out a population larger than max_memory", function ()
    local pop = field(bush(), 50, 2)
    local o = tmp(".obj")
    assert.error_contains(function () pop:save(o, { max_memory = 10000 }) end,
                          "the population written out needs", "more than max_memory")
    assert.is_nil(io.open(o))
    assert.error_contains(function () pop:flatten { max_memory = 10000 } end,
                          "scene:flatten: the flattened scene needs")
    assert.error_contains(function () pop:save(o, { instancing = 1 }) end,
                          "opts.instancing must be a boolean")
  end)

  it("writes lines as tubes per prototype", function ()
    local pop = field(broom(), 10, 2)
    local g, f = tmp(".glb"), tmp(".glb")
    pop:save(g, { lines = "tubes", sides = 4 })
    pop:flatten():save(f, { lines = "tubes", sides = 4, pixel_size = 0.01 })
    local doc, bin = glb.read(g)
    local tris = 0
    for _, node in ipairs(doc.nodes) do
      local n = glb.accessor(doc, bin, node.extensions.EXT_mesh_gpu_instancing.attributes
                             .TRANSLATION)
      for _, p in ipairs(doc.meshes[node.mesh + 1].primitives) do
        assert.equal(4, p.mode)
        tris = tris + (#n // 3) * doc.accessors[p.indices + 1].count // 3
      end
    end
    local d2, b2 = glb.read(f)
    local t2 = 0
    for _, prim in ipairs(glb.primitives(d2, b2)) do t2 = t2 + (prim.triangles or 0) end
    assert.equal(t2, tris)
    os.remove(g)
    os.remove(f)
  end)

  local validator = io.open("tools/node_modules/gltf-validator/package.json")
  if validator then validator:close() end
  local it_ = validator and it or pending
  it_("passes the glTF validator, instanced and flattened", function ()
    local pop = field(bush(), 30, 3)
    local a, b = tmp(".glb"), tmp(".glb")
    pop:save(a)
    pop:save(b, { instancing = false })
    local p = io.popen("node tools/validate_glb.js --strict " .. a .. " " .. b ..
                       " 2>&1; echo rc=$?")
    local out = p:read("a")
    p:close()
    assert.matches("rc=0", out)
    assert.matches("0 errors, 0 warnings", out)
    os.remove(a)
    os.remove(b)
  end)
end)

describe("#gl population pictures", function ()
  local function same (pop, opts)
    local a, w, h = lsys.render(pop, opts)
    local b = lsys.render(pop:flatten(), opts)
    local ok, why = require("lsys.testing").compare_images(a, b, w, h, {
      mean = 0.05, pixel = 40, fraction = 0.001 })
    assert(ok, why)
  end

  it("draws what its flattened copy draws", function ()
    same(field(bush(), 40, 4, { view = { viewpoint = { 14, 20, -25 }, target = { 14, 1, 6 },
                                         projection = "perspective" } }),
         { width = 240, height = 240 })
  end)

  it("draws thin and wide lines as its flattened copy does, and wireframes", function ()
    local pop = field(broom(), 30, 3)
    same(pop, { width = 200, height = 200 })
    same(pop, { width = 200, height = 200, wireframe = true, direction = { 1, -1, -1 } })
  end)

  it("keeps each prototype's textures", function ()
    local leaf = dofile("examples/cpfg/fig31.lua")
    local stem = lsys.lsystem { axiom = "@Tx(1) #(3) F(10)", view = {
      line_style = "cylinder", textures = { "examples/cpfg/textures/bark.png" } } }
    local pop = lsys.population {
      { model = leaf.a }, { model = stem, at = { 15, 0, 0 } },
      { model = leaf.b, at = { 30, 0, 0 }, rotate = 30 }, { model = stem, at = { -10, 0, 0 } },
    }
    assert.equal(3, #require("lsys.model").sceneview(pop).textures)
    same(pop, { width = 150, height = 100, direction = { 0, 0, 1 }, up = { 0, 1, 0 } })
    local path = tmp(".glb")
    pop:save(path)
    local doc = glb.read(path)
    assert.equal(3, #doc.images)
    assert.equal(3, #doc.meshes)
    os.remove(path)
  end)

  it("keeps its look: the view given, and lsys.render's fields over it", function ()
    local pop = field(bush(), 10, 2, { view = { background = { 1, 0, 0 } } })
    local px = lsys.render(pop, { width = 20, height = 20 })
    assert.same({ 255, 0, 0 }, { px:byte(1, 3) })
    px = lsys.render(pop, { width = 20, height = 20, background = { 0, 0, 1 } })
    assert.same({ 0, 0, 255 }, { px:byte(1, 3) })
  end)
end)

describe("#gl a population in the viewer", function ()
  local D = require "tests.display"
  teardown(function () D.stop() end)

  it("reports the plant clicked, its prototype and the module in its Lstring", function ()
    local ok, why = D.start()
    if not ok then return pending(why) end
    if not D.have("xdotool") then return pending("xdotool is not installed (./setup.sh does)") end
    local out, code = H.lsys([[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
local m = lsys.lsystem { axiom = "F G", view = { line_style = "cylinder", line_width = 0.3 } }
local pop = lsys.population {
  { model = m, at = { -2, 0, 0 } }, { model = m, at = { 0, 0, 0 }, seed = 2 },
  { model = m, at = { 2, 0, 0 }, scale = 0.5 } }
local picks = {}
lsys.show(pop, { width = 300, height = 300, title = "population test", status = false,
                 on_pick = function (info) picks[#picks + 1] = info end })
assert(V.sync(10 * SLOW), "no picture")
local function click (p)
  local x, y = V.project(p)
  picks = {}
  assert(os.execute(("xdotool search --name 'lsys: population test' mousemove --window %1 "
    .. x // 1 .. " " .. y // 1 .. " click 1 >/dev/null 2>&1")))
  for _ = 1, 40 * SLOW do
    V.poll(0.25)
    if picks[1] then
      local i = picks[1]
      return ("plant %d prototype %d module %d %s"):format(i.plant, i.prototype, i.module, i.text)
    end
  end
  return "nothing"
end
print(click { -2, 0.5, 0 })
print(click { 0, 1.5, 0 })
print(click { 2, 0.75, 0 })
V.close()
]], { env = D.env })
    assert.equal(0, code, out)
    assert.equal("plant 1 prototype 1 module 1 F\nplant 2 prototype 2 module 2 G\n" ..
                 "plant 3 prototype 1 module 2 G\n", out)
  end)
end)

describe("#gl examples/population/field.lua", function ()
  it("is 10,000 plants of 20 kinds on a ground tile, drawn headless from 21 meshes", function ()
    local meadow = dofile "examples/population/field.lua"
    assert.equal(10001, meadow.ninstances)
    assert.equal(21, meadow.nprototypes)
    local grass = 0
    for i = 1, 10000 do
      if meadow:prototype(meadow:instance(i).prototype).model.name == "grass" then
        grass = grass + 1
      end
    end
    assert.is_true(grass > 5000 and grass < 9500, grass)
    assert.is_true(meadow.bytes < 4 * 1024 * 1024, meadow.bytes)
    local px, w, h = lsys.render(meadow, { width = 160, height = 160, supersample = 1 })
    local sky, green = 0, 0
    for o = 1, w * h * 4, 4 do
      local r, g, b = px:byte(o, o + 2)
      if r == 199 and g == 222 and b == 247 then sky = sky + 1 end
      if g > r and g > b then green = green + 1 end
    end
    assert.is_true(sky > w * h / 20 and sky < w * h / 3, sky)   -- a strip of sky
    assert.is_true(green > w * h / 5, green)                     -- over a meadow
  end)
end)
