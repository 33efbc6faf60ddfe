-- The light environment from Lua (csrc/lua/lua_light.c): core.light's options and errors,
-- light:query's points, normals and directions, a closed Light, the light under a leaf and a
-- line of scenes made by lsys.lsystem{...}:interpret(), and a population's instances (the C
-- side is tests/c/test_light.c).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

-- a 2 x 2 square leaf, horizontal at height 2 over the origin
local function leaf ()
  return lsys.lsystem { axiom = "f(2) &(90) [ -(90) f(1) +(90) f(1) { . +(90) f(2) . +(90) "
                          .. "f(2) . +(90) f(2) . } ]", view = { angle = 90 } }:interpret()
end

local function sum (t)
  local s = 0
  for i = 1, #t do s = s + t[i] end
  return s
end

describe("core.light", function ()
  it("shadows a point under a leaf from the sun straight above, and not one beside it",
     function ()
    local light = core.light(leaf(), { sky = { sun = { 0, 1, 0 } } })
    assert.same({ 0, 1, 1 }, light:query { 0, 0, 0, 5, 0, 0, 0, 3, 0 })
    assert.matches("^lsys%.Light: 2 triangles, 0 capsules, 1 directions$", tostring(light))
  end)

  it("gives 1 in the open and the blocked directions' share under a leaf, overcast", function ()
    local light = core.light(leaf())
    local v = light:query { 0, 0, 0, 0, 3, 0 }
    local dirs, w = light:sky()
    assert.equal(64 * 3, #dirs)
    assert.equal(64, #w)
    assert.near(1, sum(w), 1e-12)
    local blocked = 0                              -- the directions through the square
    for k = 1, 64 do
      local x, y, z = dirs[3 * k - 2], dirs[3 * k - 1], dirs[3 * k]
      assert.is_true(y > 0)
      if math.abs(2 * x / y) < 1 and math.abs(2 * z / y) < 1 then blocked = blocked + w[k] end
    end
    assert.is_true(blocked > 0.05)
    assert.near(1 - blocked, v[1], 1e-12)
    assert.near(1, v[2], 1e-12)
  end)

  it("weighs a leaf's directions by the cosine to its normal", function ()
    local light = core.light(leaf(), { sky = { sun = { 1, 1, 0 } } })
    local v = light:query({ 0, 5, 0, 0, 5, 0, 0, 5, 0 }, { 0, 1, 0, 1, 1, 0, -1, 0, 0 })
    assert.near(math.sqrt(0.5), v[1], 1e-12)
    assert.near(1, v[2], 1e-12)
    assert.equal(0, v[3])                          -- the sun behind the leaf
  end)

  it("gives the mean unoccluded direction on request", function ()
    local light = core.light(leaf(), { sky = { { 0, 1, 0, 1 }, { 1, 1, 0, 3 } } })
    local v, d = light:query({ 0, 0, 0, 0, 3, 0 }, nil, { directions = true })
    assert.same({ 0.75, 1 }, v)                    -- the first direction blocked
    assert.near({ math.sqrt(0.5), math.sqrt(0.5), 0 }, { d[1], d[2], d[3] }, 1e-12)
    local e = 3 * math.sqrt(0.5)                   -- 1 * (0, 1, 0) + 3 * (1, 1, 0) / sqrt 2
    local n = math.sqrt(e * e + (1 + e) ^ 2)
    assert.near({ e / n, (1 + e) / n, 0 }, { d[4], d[5], d[6] }, 1e-12)
    local v2, d2 = light:query({ 0, 0, 0 }, { directions = true, threads = 1 })
    assert.same({ 0.75 }, v2)                      -- the options in the normals' place
    assert.equal(3, #d2)
  end)

  it("lets light through leaves by their transmittance", function ()
    local two = lsys.lsystem { axiom = "f(2) &(90) [ -(90) f(1) +(90) f(1) { . +(90) f(2) . "
      .. "+(90) f(2) . +(90) f(2) . } ] ^(90) f(1) &(90) [ -(90) f(1) +(90) f(1) { . +(90) "
      .. "f(2) . +(90) f(2) . +(90) f(2) . } ]", view = { angle = 90 } }:interpret()
    local light = core.light(two, { sky = { sun = { 0, 1, 0 } }, transmittance = 0.5 })
    assert.same({ 0.25, 0.5, 1 }, light:query { 0.1, 0, 0.2, 0.1, 2.5, 0.2, 0.1, 4, 0.2 })
  end)

  it("makes lines occlude as capsules of line_radius", function ()
    local line = lsys.lsystem { axiom = "f(2) &(90) f(-1) F(2)" }:interpret()
    assert.equal(1, line.nlines)
    local opts = { sky = { sun = { 0, 1, 0 } } }
    assert.same({ 1 }, core.light(line, opts):query { 0, 0, 0 })
    opts.line_radius = 0.1
    local light = core.light(line, opts)
    assert.same({ 0, 1, 1 }, light:query { 0, 0, 0.5, 0.2, 0, 0.5, 0, 2, 0 })   -- in it: lit
    assert.equal(1, light:stats().capsules)
  end)

  it("places a population's instances", function ()
    local pop = core.population {}
    core.population_add(pop, leaf(), false)
    core.population_place(pop, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1, 10, 0, 0)
    local light = core.light(pop, { sky = { sun = { 0, 1, 0 } } })
    assert.same({ 1, 0 }, light:query { 0, 0, 0, 10, 0, 0 })
  end)

  it("owns its geometry: the scene may be closed", function ()
    local s = leaf()
    local light = core.light(s, { sky = { sun = { 0, 1, 0 } } })
    getmetatable(s).__close(s)
    assert.same({ 0 }, light:query { 0, 0, 0 })
  end)

  it("gives the same numbers on every number of threads", function ()
    local s = dofile("examples/abop/fig2_08.lua").a:interpret()
    local light = core.light(s, { radiance = "cie", samples = 32 })
    local lo, hi = s:bounds()
    local p = {}
    for i = 0, 999 do
      for c = 1, 3 do p[3 * i + c] = lo[c] + (hi[c] - lo[c]) * ((i * 7919 + c * 104729) % 1000)
        / 1000 end
    end
    local a = light:query(p, nil, { threads = 1 })
    local b = light:query(p, nil, { threads = 3 })
    assert.same(a, b)
    local st = light:stats()
    assert.equal(32, st.directions)
    assert.is_true(st.triangles > 1000 and st.nodes > 10 and st.bytes > 0 and st.offset > 0)
  end)

  it("raises clear errors for bad options", function ()
    local s = leaf()
    assert.equal("core.light: unknown option 'sun' (known: sky, radiance, samples, "
      .. "transmittance, max_hits, line_radius, offset, threads, max_memory)",
      H.errof(core.light, s, { sun = { 0, 1, 0 } }))
    assert.equal("core.light: opts.sky must be 'overcast', {sun = {x, y, z}, ambient = a} or a "
      .. "list of directions {x, y, z, w}, got 'sunny'", H.errof(core.light, s, { sky = "sunny" }))
    assert.equal("core.light: opts.sky.sun must be a list {x, y, z} of numbers",
                 H.errof(core.light, s, { sky = { sun = { 0, 1 } } }))
    assert.equal("core.light: the sun is not a finite non-zero vector",
                 H.errof(core.light, s, { sky = { sun = { 0, 0, 0 } } }))
    assert.equal("core.light: opts.sky.ambient must be a number in [0, 1], got 2",
                 H.errof(core.light, s, { sky = { sun = { 0, 1, 0 }, ambient = 2 } }))
    assert.equal("core.light: unknown sky option 'moon' (known: sun, ambient)",
                 H.errof(core.light, s, { sky = { sun = { 0, 1, 0 }, moon = 1 } }))
    assert.equal("core.light: opts.sky[2][3] must be a finite number, got string",
                 H.errof(core.light, s, { sky = { { 0, 1, 0, 1 }, { 0, 1, "z" } } }))
    assert.equal("core.light: direction 1 is not a finite non-zero vector",
                 H.errof(core.light, s, { sky = { { 0, 0, 0, 1 } } }))
    assert.equal("core.light: opts.radiance must be 'uniform', 'cosine' or 'cie', got 'dark'",
                 H.errof(core.light, s, { radiance = "dark" }))
    assert.equal("core.light: opts.samples must be an integer in [1, 65536], got 0",
                 H.errof(core.light, s, { samples = 0 }))
    assert.equal("core.light: opts.transmittance must be a number in [0, 1), got 1",
                 H.errof(core.light, s, { transmittance = 1 }))
    assert.equal("core.light: opts.line_radius must be a finite number >= 0, got -1",
                 H.errof(core.light, s, { line_radius = -1 }))
    assert.equal("core.light: opts.offset must be a finite number > 0, got 0",
                 H.errof(core.light, s, { offset = 0 }))
    assert.equal("core.light: opts.threads must be an integer in [0, 64], got 65",
                 H.errof(core.light, s, { threads = 65 }))
    assert.equal("core.light: the hierarchy needs 280 bytes, more than max_memory (100 bytes)",
                 H.errof(core.light, s, { max_memory = 100 }))
    assert.matches("lsys.Scene expected", H.errof(core.light, {}, {}))
  end)

  it("raises clear errors for bad queries", function ()
    local light = core.light(leaf())
    assert.equal("light:query: points must be a flat list {x1, y1, z1, x2, ...} of at most "
      .. "2^28 points, got 2 numbers", H.errof(light.query, light, { 0, 0 }))
    assert.equal("light:query: points[2] must be a finite number, got string",
                 H.errof(light.query, light, { 0, "y", 0 }))
    assert.equal("light:query: points[3] must be a finite number, got a non-finite number",
                 H.errof(light.query, light, { 0, 0, 0 / 0 }))
    assert.equal("light:query: 1 normals for 2 points",
                 H.errof(light.query, light, { 0, 0, 0, 1, 1, 1 }, { 0, 1, 0 }))
    assert.equal("light:query: normal 1 is not a finite non-zero vector",
                 H.errof(light.query, light, { 0, 0, 0 }, { 0, 0, 0 }))
    assert.equal("light:query: the normals must be a flat list {x1, y1, z1, ...} or nil, got "
      .. "number", H.errof(light.query, light, { 0, 0, 0 }, 5))
    assert.equal("light:query: unknown option 'direction' (known: directions, threads)",
                 H.errof(light.query, light, { 0, 0, 0 }, nil, { direction = true }))
    assert.same({}, light:query {})
  end)

  it("refuses every method once closed, and closes twice", function ()
    local light = core.light(leaf())
    light:close()
    light:close()
    assert.equal("lsys.Light (closed)", tostring(light))
    assert.equal("light:query: the light was closed", H.errof(light.query, light, { 0, 0, 0 }))
    assert.equal("light:sky: the light was closed", H.errof(light.sky, light))
    assert.equal("light:stats: the light was closed", H.errof(light.stats, light))
    do
      local l2 <close> = core.light(leaf())
      assert.equal(1, #l2:query { 0, 0, 0 })
    end
  end)

  it("survives a points table whose metamethods close it", function ()
    local light = core.light(leaf())
    local p = setmetatable({}, { __len = function () return 3 end,
                                 __index = function () light:close() return 0 end })
    assert.equal("light:query: the light was closed", H.errof(light.query, light, p))
  end)

  it("survives a finalizer that closes it while sky() makes its lists", function ()
    -- with the collector at every allocation, the garbage's finalizer runs inside sky():
    -- it either answers the whole sky or says the light was closed (under the sanitizers
    -- the copy of a freed sky shows)
    local saved = collectgarbage("incremental", 1, 1000)
    local answered, refused = 0, 0
    for _ = 1, 20 do
      local light = core.light(leaf(), { samples = 4096 })
      setmetatable({}, { __gc = function () light:close() end })
      local ok, d, w = pcall(light.sky, light)
      if ok then
        answered = answered + 1
        assert.equal(3 * 4096, #d)
        assert.near(1, sum(w), 1e-9)
      else
        refused = refused + 1
        assert.matches("the light was closed", d, 1, true)
      end
    end
    collectgarbage("incremental", 200, 100)       -- Lua's defaults
    if saved == "generational" then collectgarbage("generational") end
    assert.equal(20, answered + refused)
  end)
end)
