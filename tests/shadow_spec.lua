-- The shadow-propagation grid from Lua (csrc/lua/lua_shadow.c, Palubicki et al. 2009 §4.1):
-- core.shadow's pyramid, weights, obstacles, exposure and directions, a scene's triangles as
-- casters, the same numbers on any threads, bad options and lists, a closed Shadow; and the
-- environment lsys.environment.shadow answering an open L-system's buds (the C side is
-- tests/c/test_shadow.c).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

-- the grid [0, 10]^3 of unit voxels
local function grid (opts)
  local o = { lo = { 0, 0, 0 }, hi = { 10, 10, 10 }, voxel = 1 }
  for k, v in pairs(opts or {}) do o[k] = v end
  return core.shadow(o)
end

describe("core.shadow", function ()
  it("puts a b^-q into the voxels of the pyramid below a caster", function ()
    local S = grid { depth = 2 }
    S:add { 5.5, 8.5, 5.5 }                          -- voxel (5, 8, 5)
    assert.same({ 1, 0.5, 0.5, 0.25, 0.25, 0, 0, 0, 0 }, S:shadow {
      5.5, 8.5, 5.5,     -- its own voxel: a
      5.5, 7.5, 5.5,     -- one down: a / b
      4.2, 7.9, 6.8,     -- one down, one aside (the corner of that level's square)
      5.5, 6.5, 5.5,     -- two down
      3.1, 6.1, 7.9,     -- two down, two aside
      2.5, 6.5, 5.5,     -- two down, three aside: outside the square
      5.5, 5.5, 5.5,     -- three down: below the last level
      5.5, 9.5, 5.5,     -- above the caster
      6.5, 8.5, 5.5 })   -- beside it, in its layer
    assert.matches("^lsys%.Shadow: 10 x 10 x 10 voxels of 1", tostring(S))
  end)

  it("sums casters by weight, and adds obstacle boxes", function ()
    local S = grid { a = 2, b = 4 }
    S:add({ 5.5, 8.5, 5.5, 5.5, 7.5, 5.5 }, { 1, 3 })
    assert.same({ 2 / 4 + 3 * 2, 2 / 16 + 3 * 2 / 4 }, S:shadow { 5.5, 7.5, 5.5, 5.5, 6.5, 5.5 })
    S:add_box({ 1, 1, 1 }, { 3, 2, 2 }, 10)          -- voxels (1 .. 2, 1, 1)
    assert.same({ 10, 10, 0, 0 }, S:shadow { 1.5, 1.5, 1.5, 2.5, 1.1, 1.9, 3.5, 1.5, 1.5,
                                             1.5, 2.5, 1.5 })
    S:clear()
    assert.same({ 0, 0 }, S:shadow { 5.5, 7.5, 5.5, 1.5, 1.5, 1.5 })
  end)

  it("gives each point's exposure max(C - s + a, 0), C 1 unless given", function ()
    local S = grid {}
    S:add { 5.5, 8.5, 5.5, 5.5, 9.5, 5.5 }
    -- the lower bud has its own a and half of the upper one's: 1 - 1.5 + 1
    assert.same({ 0.5, 1, 2 }, S:exposure { 5.5, 8.5, 5.5, 5.5, 9.5, 5.5, 0.5, 9.5, 0.5 })
    -- s = 1 + 1 / 2 at the lower bud, and 1 / 4 + 1 / 8 two voxels under it
    assert.same({ 9.5, 10.625 }, S:exposure({ 5.5, 8.5, 5.5, 5.5, 6.5, 5.5 }, 10))
    assert.same({ 0 }, S:exposure({ 5.5, 8.5, 5.5 }, -3))
  end)

  it("turns a shoot away from a caster above and to the left", function ()
    local S = grid {}
    S:add { 4.5, 7.5, 5.5 }
    local d = S:direction({ 5.5, 5.5, 5.5 }, { 0, 3, 0 }, { radius = 1.5 })
    assert.near({ math.sqrt(0.5), math.sqrt(0.5), 0 }, d, 1e-15)
    -- a narrow cone keeps it on its heading; no voxel within the radius: the heading
    assert.same({ 0, 1, 0 }, S:direction({ 5.5, 5.5, 5.5 }, { 0, 1, 0 },
                                         { angle = 30, radius = 1.5 }))
    assert.same({ 0.6, 0.8, 0 }, S:direction({ 5.5, 5.5, 5.5 }, { 3, 4, 0 }, { radius = 0.5 }))
    -- outside the grid: the heading; heading along z, the least shadow is below (the
    -- pyramid's level 3, a / 8, where the voxels beside have a / 4)
    assert.same({ 0.6, 0.8, 0, 0, -1, 0 }, S:direction({ -1, 5, 5, 5.5, 5.5, 5.5 },
                                                       { 3, 4, 0, 0, 0, 1 }, { radius = 1 }))
  end)

  it("reads 0 outside the grid, and casts from outside what falls inside", function ()
    local S = grid { depth = 4 }
    S:add { 5.5, 12.5, 5.5, -1.5, 8.5, 5.5 }         -- above the top, and beside
    assert.same({ 0.125, 0.125, 0.0625, 0.25, 0, 0, 0 }, S:shadow {
      5.5, 9.5, 5.5,     -- the top layer, three below the first: a / 8
      5.5, 10, 5.5,      -- the top face: in the top layer
      5.5, 8.5, 5.5,     -- four below
      0.5, 6.5, 5.5,     -- two below the one beside: its square reaches x = 0
      0.5, 7.5, 5.5,     -- one below it: not yet
      5.5, 11, 5.5,      -- outside the grid
      -0.5, 6.5, 5.5 })
    assert.same({ 2 }, S:exposure { 20, 20, 20 })
    local st = S:stats()
    assert.same({ nx = 10, ny = 10, nz = 10, voxels = 1000, bytes = st.bytes, voxel = 1,
                  lo = { 0, 0, 0 }, hi = { 10, 10, 10 } }, st)
    assert.is_true(st.bytes >= 8000 and st.bytes < 10000)
    assert.same({ 3, 2, 1 }, (function ()
      local t = core.shadow { lo = { 0, 0, 0 }, hi = { 2.5, 1.5, 0 }, voxel = 1 }:stats()
      return { t.nx, t.ny, t.nz }                    -- hi rounded up to whole voxels
    end)())
  end)

  it("casts a scene's triangles at their centroids, by area over a voxel's face", function ()
    -- a horizontal disc of diameter 2 at height 1.5 over the origin, in one voxel of 4
    local s = lsys.lsystem { axiom = "f(1.5) &(90) @c(2)", view = { angle = 90 } }:interpret()
    assert.is_true(s.ntriangles > 4)
    local S = core.shadow { lo = { -2, 0, -2 }, hi = { 2, 4, 2 }, voxel = 4 }
    S:add_scene(s)
    assert.near(s:area() / 16, S:shadow({ 0, 0, 0 })[1], 1e-6)
    S:add_scene(s, 2)
    assert.near(3 * s:area() / 16, S:shadow({ 0, 0, 0 })[1], 1e-6)
    getmetatable(s).__close(s)
    assert.matches("scene was closed", H.errof(S.add_scene, S, s))
  end)

  it("gives the same numbers on every number of threads", function ()
    local p, w, h = {}, {}, {}
    for i = 0, 19999 do
      for c = 1, 3 do p[3 * i + c] = ((i * 7919 + c * 104729) % 1000) / 50 - 2 end
      w[i + 1] = 0.5 + (i % 7) / 4
    end
    for i = 1, 3000 do h[i] = ((i * 31) % 17) / 17 - 0.4 end
    local q = { table.unpack(p, 1, 3000) }
    local out = {}
    for _, t in ipairs { 1, 2, 3 } do
      local S = core.shadow { lo = { 0, 0, 0 }, hi = { 16, 16, 16 }, voxel = 0.75, depth = 6,
                              b = 1.6, threads = t }
      S:add(p, w)
      out[t] = { S:shadow(q), S:direction(q, h, { angle = 70, radius = 3 }) }
    end
    assert.same(out[1], out[2])
    assert.same(out[1], out[3])
    local shaded = 0
    for _, v in ipairs(out[1][1]) do if v > 0 then shaded = shaded + 1 end end
    assert.is_true(shaded > 300 and shaded < 1000, shaded)   -- a test worth its name
  end)

  it("raises clear errors for bad options", function ()
    local function new (o)
      local t = { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, voxel = 0.5 }
      for k, v in pairs(o) do t[k] = v end
      return H.errof(core.shadow, t)
    end
    assert.equal("core.shadow: unknown option 'size' (known: lo, hi, voxel, depth, a, b, "
      .. "threads, max_memory)", new { size = 1 })
    assert.equal("core.shadow: opts.lo is missing (a list {x, y, z} of numbers)",
                 H.errof(core.shadow, { hi = { 1, 1, 1 }, voxel = 1 }))
    assert.equal("core.shadow: opts.voxel is missing (the voxel's edge, a finite number > 0)",
                 H.errof(core.shadow, { lo = { 0, 0, 0 }, hi = { 1, 1, 1 } }))
    assert.equal("core.shadow: opts.hi must be a list {x, y, z} of numbers",
                 new { hi = { 1, 1 } })
    assert.equal("core.shadow: opts.hi[2] must be a finite number, got string",
                 new { hi = { 1, "y", 1 } })
    assert.equal("core.shadow: lo must not be above hi (on z: 0 > -1)",
                 new { hi = { 1, 1, -1 } })
    assert.equal("core.shadow: opts.voxel must be a finite number > 0, got 0", new { voxel = 0 })
    assert.equal("core.shadow: opts.depth must be an integer in [0, 64], got 65",
                 new { depth = 65 })
    assert.equal("core.shadow: opts.a must be a finite number > 0, got -1", new { a = -1 })
    assert.equal("core.shadow: opts.b must be a finite number > 1, got 1", new { b = 1 })
    assert.equal("core.shadow: opts.threads must be an integer in [0, 64], got 65",
                 new { threads = 65 })
    assert.equal("core.shadow: the grid of 100 x 100 x 100 voxels needs 8 MiB, more than "
      .. "max_memory (1 MiB)", new { hi = { 10, 10, 10 }, voxel = 0.1, max_memory = 2 ^ 20 })
    assert.equal("core.shadow: a grid of 100000000 x 1 x 1 voxels is too big (at most "
      .. "16777216 along an axis)", new { hi = { 1e8, 0, 0 }, voxel = 1 })
    assert.matches("table expected", H.errof(core.shadow))
  end)

  it("raises clear errors for bad lists and arguments", function ()
    local S = grid {}
    assert.equal("shadow:add: points must be a flat list {x1, y1, z1, x2, ...} of at most "
      .. "2^28 points, got 2 numbers", H.errof(S.add, S, { 0, 0 }))
    assert.equal("shadow:add: points[2] must be a finite number, got string",
                 H.errof(S.add, S, { 0, "y", 0 }))
    assert.equal("shadow:add: points[3] must be a finite number, got a non-finite number",
                 H.errof(S.add, S, { 0, 0, 0 / 0 }))
    assert.equal("shadow:add: 1 weights for 2 points",
                 H.errof(S.add, S, { 0, 0, 0, 1, 1, 1 }, { 1 }))
    assert.equal("shadow:add: weights[1] must be a finite number, got a non-finite number",
                 H.errof(S.add, S, { 0, 0, 0 }, { math.huge }))
    assert.equal("shadow:shadow: points must be a flat list {x1, y1, z1, x2, ...}, got number",
                 H.errof(S.shadow, S, 3))
    assert.equal("shadow:exposure: C must be a finite number", H.errof(S.exposure, S, {}, 0 / 0))
    assert.equal("shadow:add_box: hi must be a list {x, y, z} of numbers",
                 H.errof(S.add_box, S, { 0, 0, 0 }, { 1, 1 }, 1))
    assert.equal("shadow:add_box: the box's low corner must not be above its high one (on x: "
      .. "2 > 1)", H.errof(S.add_box, S, { 2, 0, 0 }, { 1, 1, 1 }, 1))
    assert.equal("shadow:add_box: the value must be a finite number",
                 H.errof(S.add_box, S, { 0, 0, 0 }, { 1, 1, 1 }, math.huge))
    assert.equal("shadow:direction: 1 headings for 2 points",
                 H.errof(S.direction, S, { 0, 0, 0, 1, 1, 1 }, { 0, 1, 0 }))
    assert.equal("shadow:direction: heading 1 is not a finite non-zero vector",
                 H.errof(S.direction, S, { 0, 0, 0 }, { 0, 0, 0 }))
    assert.equal("shadow:direction: unknown option 'cone' (known: angle, radius)",
                 H.errof(S.direction, S, { 0, 0, 0 }, { 0, 1, 0 }, { cone = 1 }))
    assert.equal("shadow:direction: opts.angle must be a number of degrees in (0, 180], got 181",
                 H.errof(S.direction, S, { 0, 0, 0 }, { 0, 1, 0 }, { angle = 181 }))
    assert.equal("shadow:direction: opts.radius must be a number of voxels in (0, 32], got 0",
                 H.errof(S.direction, S, { 0, 0, 0 }, { 0, 1, 0 }, { radius = 0 }))
    assert.equal("shadow:add_scene: the weight must be a finite number",
                 H.errof(S.add_scene, S, lsys.lsystem { axiom = "F" }:interpret(), 0 / 0))
    assert.same({}, S:shadow {})
    assert.same({}, S:direction({}, {}))
    -- the meter: the grid fits, an add's blocks do not
    local small = core.shadow { lo = { 0, 0, 0 }, hi = { 10, 10, 10 }, voxel = 1,
                                max_memory = 8000 + 1024 }
    assert.equal("shadow:add: adding the casters needs 2 MiB more, beyond max_memory (9 KiB)",
                 H.errof(small.add, small, (function ()
                     local p = {}
                     for i = 1, 3 * 100000 do p[i] = 5 end
                     return p
                   end)()))
    small:add { 5, 5, 5 }
    assert.same({ 1 }, small:shadow { 5, 5, 5 })
  end)

  it("refuses every method once closed, and closes twice", function ()
    local S = grid {}
    S:close()
    S:close()
    assert.equal("lsys.Shadow (closed)", tostring(S))
    local scene = lsys.lsystem { axiom = "F" }:interpret()
    local calls = {
      add = { { 0, 0, 0 } }, add_scene = { scene }, add_box = { { 0, 0, 0 }, { 1, 1, 1 }, 1 },
      clear = {}, shadow = { { 0, 0, 0 } }, exposure = { { 0, 0, 0 } },
      direction = { { 0, 0, 0 }, { 0, 1, 0 } }, stats = {},
    }
    for name, args in pairs(calls) do
      assert.equal("shadow:" .. name .. ": the shadow grid was closed",
                   H.errof(S[name], S, table.unpack(args)))
    end
    do
      local S2 <close> = grid {}
      assert.equal(1, #S2:shadow { 0, 0, 0 })
    end
  end)

  it("survives lists whose metamethods close it", function ()
    local S = grid {}
    local p = setmetatable({}, { __len = function () return 3 end,
                                 __index = function () S:close() return 0 end })
    assert.equal("shadow:add: the shadow grid was closed", H.errof(S.add, S, p))
    S = grid {}
    assert.equal("shadow:direction: the shadow grid was closed",
                 H.errof(S.direction, S, { 1, 1, 1 }, p))
  end)
end)

describe("lsys.environment.shadow", function ()
  it("gives less exposure to buds under a shading caster, and turns them away", function ()
    -- a bud at (0, 1, 0), two buds above it and to the right, at (1, 2.5, 0) and (1, 3, 0),
    -- and one alone at (-5, 1, 0): every ?E is a bud that casts
    local got
    local env = lsys.environment.shadow { C = 1 }
    local m = lsys.lsystem { steps = 1, view = { angle = 90 },
      axiom = "[F(1)?E(0,0,0,0)][-(90)f(1)+(90)F(2.5)?E(0)][-(90)f(1)+(90)F(3)?E(0)]"
        .. "[+(90)f(5)-(90)F(1)?E(0)]",
      environment = function (qs, info) got = qs return env:answer(qs, info) end }
    local s = m:derive()
    assert.same({ 1, 2.5, 0 }, got[2].position)
    -- with unit voxels from (-8, -2, -3) (the queries' box and 3 voxels), the bud at (0, 1, 0)
    -- is in voxel (8, 3, 3), the upper ones in (9, 4, 3) and (9, 5, 3): a/2 + a/4 on it
    assert.same({ 3, 10, 17, 24 }, { got[1].index, got[2].index, got[3].index, got[4].index })
    local _, low, dx, dy, dz = s:module(3)
    assert.equal(1 - 0.75, low)
    assert.equal(1 - 0.5, select(2, s:module(10)))   -- under the top one
    assert.equal(1, select(2, s:module(17)))         -- the top one, and the one alone
    assert.equal(1, select(2, s:module(24)))
    assert.is_true(dx < 0 and dy > 0, dx .. " " .. dy)   -- up, and away from the others
    assert.near(1, dx * dx + dy * dy + dz * dz, 1e-12)
    -- the default C (8): the same shadow takes less light away
    m.environment = lsys.environment.shadow {}
    assert.equal(1 - 0.75 / 8, select(2, m:derive():module(3)))
  end)

  it("shades by the scene's leaves with casters = \"scene\"", function ()
    -- a bud under a leaf disc and one in the open; the queries do not cast
    local m = lsys.lsystem { steps = 1, view = { angle = 90 },
      axiom = "[F(1)?E(0)][+(90)f(3)-(90)F(1)?E(0)][f(1.5)&(90)@c(1.5)]",
      environment = lsys.environment.shadow { casters = "scene", C = 1 } }
    local s = m:derive()
    local _, shaded = s:module(3)
    assert.is_true(shaded > 0.2 and shaded < 0.8, shaded)
    assert.equal(1, select(2, s:module(10)))
    m.environment = lsys.environment.shadow { casters = "both", C = 1 }
    assert.equal(shaded, select(2, m:derive():module(3)))      -- its own a taken away
    m.environment = lsys.environment.shadow { casters = "queries", C = 1 }
    assert.equal(1, select(2, m:derive():module(3)))           -- the disc casts nothing
  end)

  it("darkens an obstacle's voxels, and shades beside and below it when it casts", function ()
    -- buds at (0, 1, 0) and 3 aside; a box over x in [-1, 0.5], y in [2.2, 2.8]
    local function answers (obstacles)
      local m = lsys.lsystem { steps = 1, view = { angle = 90 },
        axiom = "[F(1)?E(0)][-(90)f(3)+(90)F(1)?E(0)]",
        environment = lsys.environment.shadow { C = 1, a = 0.2, obstacles = obstacles } }
      local s = m:derive()
      return select(2, s:module(3)), select(2, s:module(10))
    end
    assert.same({ 1, 1 }, { answers(nil) })
    local box = { lo = { -1, 2.2, -0.5 }, hi = { 0.5, 2.8, 0.5 } }
    -- cast: the box's voxels above the bud shade it; the far bud stays in the open
    local near, far = answers { box }
    assert.is_true(near < 1 and near > 0, near)
    assert.equal(1, far)
    -- not cast: the box shades nothing outside itself
    assert.same({ 1, 1 }, { answers { { lo = box.lo, hi = box.hi, cast = false } } })
    -- a bud inside it gets the box's shadow
    local inside = { lo = { -0.5, 0.5, -0.5 }, hi = { 0.5, 1.5, 0.5 }, shadow = 0.75,
                     cast = false }
    assert.near(0.25, (answers { inside }), 1e-12)
    for _, case in ipairs {
      { 3, "obstacles must be a list of boxes { lo =, hi = }" },
      { { { lo = { 0, 0 }, hi = { 1, 1, 1 } } }, "obstacle 1: lo and hi must be points" },
      { { { lo = { 0, 2, 0 }, hi = { 1, 1, 1 } } }, "obstacle 1: hi must not be below lo" },
      { { { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, shadow = -1 } },
        "obstacle 1: shadow must be a finite number >= 0" },
      { { { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cast = 1 } },
        "obstacle 1: cast must be a boolean" },
    } do
      assert.error_contains(function () lsys.environment.shadow { obstacles = case[1] } end,
                            "lsys.environment.shadow: " .. case[2])
    end
  end)

  it("grows examples/open/shade.lua alike on any threads", function ()
    local strings = {}
    for _, t in ipairs { 1, 2 } do
      local m = dofile("examples/open/shade.lua")
      m.environment = lsys.environment.shadow { voxel = 0.5, threads = t }
      strings[t] = tostring(m:derive())
    end
    assert.equal(strings[1], strings[2])
    assert.is_true(#strings[1] > 10000, #strings[1])
  end)

  it("raises clear errors for bad options", function ()
    assert.error_contains(function () lsys.environment.shadow { size = 1 } end,
                          "lsys.environment.shadow: unknown option 'size'")
    assert.error_contains(function () lsys.environment.shadow { casters = "leaves" } end,
      "lsys.environment.shadow: casters must be \"queries\", \"scene\" or \"both\"")
    assert.error_contains(function () lsys.environment.shadow { C = 0 } end,
                          "lsys.environment.shadow: C must be a finite number > 0")
    assert.error_contains(function () lsys.environment.shadow { margin = -1 } end,
                          "lsys.environment.shadow: margin must be a finite number >= 0")
    assert.equal("lsys.environment.shadow: voxel must be a finite number > 0, got -1",
                 H.errof(lsys.environment.shadow, { voxel = -1 }))
    assert.equal("lsys.environment.shadow: depth must be an integer in [0, 64], got 1.5",
                 H.errof(lsys.environment.shadow, { depth = 1.5 }))
    assert.equal("lsys.environment.shadow: angle must be a number of degrees in (0, 180], "
      .. "got 200", H.errof(lsys.environment.shadow, { angle = 200 }))
    assert.equal("lsys.environment.shadow", tostring(lsys.environment.shadow()))
    -- a grid too big for the budget, at the pass
    local m = lsys.lsystem { axiom = "?E(0) f(1000) +(90) f(1000) ?E(0)", steps = 1,
                             environment = lsys.environment.shadow { voxel = 0.01 } }
    assert.error_contains(function () m:derive() end, "environment: lsys.environment.shadow: "
      .. "the grid of")
  end)
end)
