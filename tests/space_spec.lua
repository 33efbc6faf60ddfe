-- Space from Lua (csrc/lua/lua_space.c): core.space's queries on hand-made points, the
-- scene's points, threads, bad options and closed objects; core.markers' associations,
-- removal and errors; core.field's diffusion, takes and sources; the environments on them:
-- lsys.environment.collision (the answers of the Lua algorithm it replaced, kept here as the
-- reference), lsys.environment.space, lsys.environment.colonize and
-- lsys.environment.resource, and examples/open/colonize.lua and roots.lua (the C side is
-- tests/c/test_space.c).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

-- a row along x: 0, 0.5, 1.2 twice, 3, and one off the row
local ROW = { 0, 0, 0, 0.5, 0, 0, 1.2, 0, 0, 1.2, 0, 0, 3, 0, 0, 0, 0, 0.9 }

-- a small deterministic generator (the same points every run)
local function lcg (seed)
  local s = seed
  return function ()
    s = (s * 1103515245 + 12345) % 2147483648
    return s / 2147483648
  end
end

local function randompoints (n, scale, seed)
  local r, p = lcg(seed), {}
  for i = 1, 3 * n do p[i] = scale * r() end
  return p
end

describe("core.space", function ()
  it("counts the points within the radius, each leaving itself out, twins each other",
     function ()
    local S = core.space(ROW, { radius = 1 })
    assert.same({ 2, 3, 2, 2, 0, 1 }, S:count())
    assert.same({ 4, 4, 5, 5, 2, 4 }, S:count(nil, { radius = 2 }))
    assert.same({ 4, 0, 3 }, S:count { 0.6, 0, 0, 10, 10, 10, -0.1, 0, 0 })
    assert.equal(math.type(S:count()[1]), "integer")
    assert.equal(6, #S)
    assert.same({ points = 6, listed = 6, cells = 3, buckets = 64, bytes = S:stats().bytes,
                  radius = 1 }, S:stats())
    assert.equal("lsys.Space: 6 points in 3 cells of 1.0", tostring(S))
  end)

  it("gives the nearest distance (math.huge beyond the radius) and the kernel's density",
     function ()
    local S = core.space(ROW, { radius = 1 })
    local d = S:nearest()
    assert.same({ 0.5, 0.5, 0, 0, math.huge, 0.9 }, d)
    assert.near(0.1, S:nearest({ 0.6, 0, 0 })[1], 1e-15)
    local rho = S:density()
    assert.near(0.75 ^ 2 + 0.19 ^ 2, rho[1], 1e-15)               -- (1 - d^2 / r^2)^2 each
    assert.near(0.75 ^ 2 + 2 * 0.51 ^ 2, rho[2], 1e-15)
    assert.equal(0, rho[5])
    assert.near(1 + 0.75 ^ 2 + 0.19 ^ 2, S:density({ 0, 0, 0 })[1], 1e-15)   -- 1 at 0
  end)

  it("answers Honda's collision test: 1 unless one of the group and no less vigour is near",
     function ()
    local S = core.space({ 0, 0, 0, 0.3, 0, 0, 5, 5, 0, 5.2, 5, 0, 9, 0, 0, 9, 0.5, 0,
                           20, 0, 0, 20.51, 0, 0 },
                         { radius = 0.5, groups = { 0, 0, 0, 1, 0, 0, 0, 0 },
                           vigour = { 1, 2, 1, 1, 1, 1, 1, 1 } })
    assert.same({ 0, 1, 1, 1, 0, 0, 1, 1 }, S:free())
    assert.same({ 0, 1, 1 }, S:free({ 0.1, 0, 0, 0.1, 0, 0, 0.1, 0, 0 },
                                    { groups = { 0, 0, 1 }, vigour = { 2, 2.5, 0 } }))
    assert.same({ 0 }, S:free { 0.1, 0, 0 })                      -- group 0, vigour 0
  end)

  it("takes a scene's segment ends and triangles' centroids, left out within an offset",
     function ()
    local s = lsys.lsystem { axiom = "F(1) F(1)" }:interpret()
    local S = core.space({ 0, 2.05, 0 }, { radius = 0.5, scene = s })
    assert.equal(3, S:stats().points)
    assert.equal(1, S:stats().listed)
    assert.near(0.05, S:nearest()[1], 1e-6)
    assert.same({ 0 }, S:free())                      -- an obstacle to group 0
    assert.same({ 0 }, S:count(nil, { offset = 0.1 }))
    assert.same({ 3 }, S:count({ 0, 1.5, 0 }, { radius = 0.6 }))   -- the ends, and the point
    local leaf = lsys.lsystem { axiom = "{ . f(3) + . f(3) + . }", view = { angle = 90 } }
    local T = core.space({}, { radius = 1, scene = leaf:interpret() })   -- a triangle
    assert.equal(1, #T)                                       -- its centroid (-1, 2, 0)
    assert.near({ 0, 2 }, T:nearest({ -1, 2, 0, 1, 2, 0 }, { radius = 3 }), 1e-6)
  end)

  it("gives the same numbers on every number of threads", function ()
    local p = randompoints(3000, 4, 5)
    local g, v = {}, {}
    for i = 1, 3000 do g[i] = i % 3; v[i] = i % 4 end
    local S = core.space(p, { radius = 0.3, groups = g, vigour = v })
    local q = randompoints(500, 5, 9)
    for _, kind in ipairs { "count", "density", "nearest", "free" } do
      for _, r in ipairs { 0.3, 0.7 } do
        local a = S[kind](S, nil, { radius = r, threads = 1 })
        assert.same(a, S[kind](S, nil, { radius = r, threads = 3 }))
        assert.same(S[kind](S, q, { radius = r, threads = 1 }),
                    S[kind](S, q, { radius = r, threads = 2 }))
        if kind == "count" and r == 0.3 then
          local busy = 0
          for i = 1, #a do if a[i] > 2 then busy = busy + 1 end end
          assert.is_true(busy > 1000)
        end
      end
    end
  end)

  it("raises clear errors for bad options and points", function ()
    assert.equal("core.space: opts.radius is required (a finite number > 0)",
                 H.errof(core.space, ROW, {}))
    assert.equal("core.space: opts.radius must be a finite number > 0, got 0",
                 H.errof(core.space, ROW, { radius = 0 }))
    assert.equal("core.space: unknown option 'radii' (known: radius, groups, vigour, scene, "
      .. "threads, max_memory)", H.errof(core.space, ROW, { radius = 1, radii = 2 }))
    assert.equal("core.space: opts.groups has 2 entries for 6 points",
                 H.errof(core.space, ROW, { radius = 1, groups = { 1, 2 } }))
    assert.equal("core.space: opts.groups[1] must be an integer, got a number with a fraction",
                 H.errof(core.space, { 0, 0, 0 }, { radius = 1, groups = { 1.5 } }))
    assert.equal("core.space: opts.vigour[1] must be a number, got string",
                 H.errof(core.space, { 0, 0, 0 }, { radius = 1, vigour = { "x" } }))
    assert.equal("core.space: points must be a flat list {x1, y1, z1, x2, ...} of at most "
      .. "2^28 points, got 2 numbers", H.errof(core.space, { 0, 0 }, { radius = 1 }))
    assert.equal("core.space: points[2] must be a finite number, got a non-finite number",
                 H.errof(core.space, { 0, 0 / 0, 0 }, { radius = 1 }))
    assert.equal("core.space: point 1 is too far from the origin for the radius",
                 H.errof(core.space, { 1e300, 0, 0 }, { radius = 1 }))
    assert.matches("lsys.Scene expected", H.errof(core.space, {}, { radius = 1, scene = 1 }))
    assert.matches("^core.space: .* more than max_memory %(100 bytes%)$",
                   H.errof(core.space, ROW, { radius = 1, max_memory = 100 }))
    local S = core.space(ROW, { radius = 1 })
    assert.equal("space:count: the radius must be a number in (0, 16] (16 times the space's)",
                 H.errof(S.count, S, nil, { radius = 17 }))
    assert.equal("space:count: unknown option 'groups' (known: radius, offset, threads)",
                 H.errof(S.count, S, nil, { groups = {} }))
    assert.equal("space:free: opts.groups and opts.vigour are for query points (the space's "
      .. "own points have theirs)", H.errof(S.free, S, nil, { vigour = {} }))
    assert.equal("space:nearest: opts.offset must be a finite number >= 0, got -1",
                 H.errof(S.nearest, S, nil, { offset = -1 }))
    assert.equal("space:density: the points must be a flat list {x1, y1, z1, ...} or nil (the "
      .. "space's own), got number", H.errof(S.density, S, 5))
    assert.same({}, S:count {})
  end)

  it("refuses every method once closed, and closes twice", function ()
    local S = core.space(ROW, { radius = 1 })
    S:close()
    S:close()
    assert.equal("lsys.Space (closed)", tostring(S))
    for _, k in ipairs { "count", "density", "nearest", "free", "stats" } do
      assert.equal("space:" .. k .. ": the space was closed", H.errof(S[k], S))
    end
    assert.matches("space:__len: the space was closed$", H.errof(function () return #S end))
    do
      local S2 <close> = core.space(ROW, { radius = 1 })
      assert.equal(6, #S2:count())
    end
  end)

  it("survives a points table whose metamethods close it", function ()
    local S = core.space(ROW, { radius = 1 })
    local p = setmetatable({}, { __len = function () return 3 end,
                                 __index = function () S:close() return 0 end })
    assert.equal("space:count: the space was closed", H.errof(S.count, S, p))
  end)
end)

describe("core.markers", function ()
  -- two buds: (0, 0, 0) heading +y and (2, 0, 0) heading +x
  local BUDS, HEADS = { 0, 0, 0, 2, 0, 0 }, { 0, 3, 0, 1, 0, 0 }
  local function six ()   -- bud 0's; nearer bud 1; as near each; behind bud 0; killed; far
    return core.markers { 0, 1, 0, 1.2, 0, 0, 1, 0, 0, 0, -1, 0, 2.1, 0, 0, 9, 9, 9 }
  end

  it("gives each marker to the nearest bud that perceives it, and removes those killed",
     function ()
    local M = six()
    assert.equal("lsys.Markers: 6 markers", tostring(M))
    local c, d = M:perceive(BUDS, HEADS, { perception = 1.5, angle = 180, kill = 0.2 })
    assert.same({ 3, 1 }, c)
    assert.same({ 1, 0, 0, -1, 0, 0 }, d)              -- (0,1)+(1,0)+(0,-1), normalised
    assert.equal(5, M:count())
    assert.same({ 0, 1, 0, 1.2, 0, 0, 1, 0, 0, 0, -1, 0, 9, 9, 9 }, M:points())
    c, d = M:perceive(BUDS, HEADS, { perception = 1.5 })   -- 90 degrees: the half ahead
    assert.same({ 3, 0 }, c)                           -- 1.2 is behind bud 1
    assert.near({ 2 / math.sqrt(5), 1 / math.sqrt(5), 0, 0, 0, 0 }, d, 1e-15)
    c = M:perceive(BUDS, HEADS, { perception = 1.5, angle = 89 })
    assert.same({ 1, 0 }, c)
    c = M:perceive(BUDS, HEADS, { perception = 0.9, angle = 180 })
    assert.same({ 0, 1 }, c)                           -- only 1.2, from bud 1 (0.8)
    assert.equal(4, M:remove({ 0, 0, 0, 2, 0, 0 }, 1.05))
    assert.equal(1, #M)
    assert.same({ 9, 9, 9 }, M:points())
  end)

  it("gives the same fates on every number of threads", function ()
    local m = randompoints(5000, 10, 3)
    local b, h = randompoints(400, 10, 4), randompoints(400, 1, 6)
    for i = 1, #h do h[i] = h[i] - 0.5 end
    local M1, M3 = core.markers(m), core.markers(m, { threads = 3 })
    local opts = { perception = 1.5, angle = 60, kill = 0.3 }
    local c1, d1 = M1:perceive(b, h, opts)
    local c3, d3 = M3:perceive(b, h, opts)
    assert.same(c1, c3)
    assert.same(d1, d3)
    assert.same(M1:points(), M3:points())
    assert.is_true(#M1 < 5000 and #M1 > 2500)
    local won = 0
    for i = 1, #c1 do won = won + c1[i] end
    assert.is_true(won > 1000 and won <= #M1)
  end)

  it("raises clear errors for bad options, buds and closed markers", function ()
    local M = six()
    assert.equal("markers:perceive: opts.perception is required (a finite number > 0)",
                 H.errof(M.perceive, M, BUDS, HEADS, {}))
    assert.equal("markers:perceive: opts.angle must be a number of degrees in (0, 180], "
      .. "got 181", H.errof(M.perceive, M, BUDS, HEADS, { perception = 1, angle = 181 }))
    assert.equal("markers:perceive: opts.angle must be a number of degrees in (0, 180], got 0",
                 H.errof(M.perceive, M, BUDS, HEADS, { perception = 1, angle = 0 }))
    assert.equal("markers:perceive: opts.kill must be a finite number >= 0, got -1",
                 H.errof(M.perceive, M, BUDS, HEADS, { perception = 1, kill = -1 }))
    assert.equal("markers:perceive: the kill radius must be a number in [0, 16 times the "
      .. "perception radius]", H.errof(M.perceive, M, BUDS, HEADS, { perception = 1,
                                                                      kill = 17 }))
    assert.equal("markers:perceive: unknown option 'radius' (known: perception, angle, kill, "
      .. "threads)", H.errof(M.perceive, M, BUDS, HEADS, { radius = 1 }))
    assert.equal("markers:perceive: 1 headings for 2 buds",
                 H.errof(M.perceive, M, BUDS, { 0, 1, 0 }, { perception = 1 }))
    assert.equal("markers:perceive: heading 2 is not a finite non-zero vector",
                 H.errof(M.perceive, M, BUDS, { 0, 1, 0, 0, 0, 0 }, { perception = 1 }))
    assert.equal("markers:perceive: buds[1] must be a finite number, got string",
                 H.errof(M.perceive, M, { "x", 0, 0 }, { 0, 1, 0 }, { perception = 1 }))
    assert.equal(6, #M)                                -- nothing changed by the failures
    assert.equal("core.markers: points[1] must be a finite number, got a non-finite number",
                 H.errof(core.markers, { 1 / 0, 0, 0 }))
    assert.matches("^core.markers: .* more than max_memory %(10 bytes%)$",
                   H.errof(core.markers, { 0, 0, 0 }, { max_memory = 10 }))
    assert.matches("bad argument #3 to '%?' %(a finite radius > 0 expected%)",
                   H.errof(M.remove, M, BUDS, 0))
    M:close()
    M:close()
    assert.equal("lsys.Markers (closed)", tostring(M))
    assert.equal("markers:perceive: the markers were closed",
                 H.errof(M.perceive, M, BUDS, HEADS, { perception = 1 }))
    for _, k in ipairs { "count", "points" } do
      assert.equal("markers:" .. k .. ": the markers were closed", H.errof(M[k], M))
    end
    assert.equal("markers:remove: the markers were closed", H.errof(M.remove, M, BUDS, 1))
    local M2 = six()
    local hostile = setmetatable({}, { __len = function () return 6 end,
                                       __index = function () M2:close() return 0 end })
    assert.equal("markers:perceive: the markers were closed",
                 H.errof(M2.perceive, M2, hostile, HEADS, { perception = 1 }))
  end)
end)

-- The collision environment as it was written in Lua before core.space, kept as the
-- reference its answers must equal.
local function luacollision (queries, r)
  local floor = math.floor
  local r2 = r * r
  local function cell (p) return floor(p[1] / r), floor(p[2] / r), floor(p[3] / r) end
  local function key (x, y, z) return x * 73856093 ~ y * 19349663 ~ z * 83492791 end
  local cells = {}
  for i, q in ipairs(queries) do
    local k = key(cell(q.position))
    cells[k] = cells[k] or {}
    table.insert(cells[k], i)
  end
  local answers = {}
  for i, q in ipairs(queries) do
    local p, v, g = q.position, q.params[1] or 0, q.params[2] or 0
    local cx, cy, cz = cell(p)
    local free = 1
    for dx = -1, 1 do for dy = -1, 1 do for dz = -1, 1 do
      for _, j in ipairs(cells[key(cx + dx, cy + dy, cz + dz)] or {}) do
        local o = queries[j]
        if j ~= i and (o.params[2] or 0) == g and v <= (o.params[1] or 0) then
          local ex, ey, ez = p[1] - o.position[1], p[2] - o.position[2], p[3] - o.position[3]
          if ex * ex + ey * ey + ez * ez <= r2 then free = 0 end
        end
      end
    end end end
    answers[i] = free
  end
  return answers
end

describe("lsys.environment.collision on core.space", function ()
  it("answers as the Lua algorithm did, on a grid at the radius, twins and odd groups",
     function ()
    local f32 = function (x) return (string.unpack("f", string.pack("f", x))) end
    for _, r in ipairs { 0.01, 0.1, 1 / 3, 1 } do
      local rnd, queries = lcg(17), {}
      for i = 1, 3000 do
        -- points on a lattice of step r (neighbours exactly at the radius), jittered or not,
        -- as float32 as a cpfg model's are, some twins, vigours 0 .. 2, groups 0, 1, 0.5
        local p = { f32(r * math.floor(20 * rnd())), f32(r * math.floor(20 * rnd())),
                    f32(r * math.floor(3 * rnd())) }
        if i % 3 == 0 then for c = 1, 3 do p[c] = f32(p[c] + r * 0.3 * (rnd() - 0.5)) end end
        if i % 11 == 0 then p = queries[i - 1].position end
        local params = { math.floor(3 * rnd()), ({ 0, 1, 0.5, nil })[1 + math.floor(4 * rnd())] }
        if i % 13 == 0 then params = {} end
        queries[i] = { position = p, params = params }
      end
      local want = luacollision(queries, r)
      local got = lsys.environment.collision({ radius = r }):answer(queries)
      assert.same(want, got)
      local stopped = 0
      for i = 1, #got do stopped = stopped + (1 - got[i]) end
      assert.is_true(stopped > 300 and stopped < 2700)     -- both answers, often
      assert.same(got, lsys.environment.collision({ radius = r, threads = 3 }):answer(queries))
    end
  end)

  it("gives NaN vigours and groups the Lua algorithm's answers", function ()
    local nan = 0 / 0
    local function q (x, v, g) return { position = { x, 0, 0 }, params = { v, g } } end
    local queries = { q(0, nan), q(0.1, 1), q(5, 1, nan), q(5.1, 1, nan), q(5.2, 0, 0) }
    assert.same(luacollision(queries, 0.5),
                lsys.environment.collision({ radius = 0.5 }):answer(queries))
    assert.same({ 1, 1, 1, 1, 1 }, lsys.environment.collision({ radius = 0.5 }):answer(queries))
  end)

  it("raises clear errors", function ()
    assert.error_contains(function () lsys.environment.collision { radius = 1, r = 2 } end,
                          "lsys.environment.collision: unknown option 'r'")
    assert.error_contains(function () lsys.environment.collision { radius = 1, threads = -1 } end,
                          "threads must be an integer in [0, 64]")
    local c = lsys.environment.collision { radius = 1 }
    assert.equal("query 2: its position is not finite", H.errof(c.answer, c, {
      { position = { 0, 0, 0 }, params = {} }, { position = { 0 / 0, 0, 0 }, params = {} } }))
    assert.equal("query 1: its position is too far from the origin for the radius",
      H.errof(c.answer, c, { { position = { 1e300, 0, 0 }, params = {} } }))
  end)
end)

describe("lsys.environment.space", function ()
  -- ?E at (0, 1, 0), (0, 2, 0), (0, 3, 0), (0, 3.5, 0), each at the end of a segment
  local function row (env, steps)
    local got
    local m = lsys.lsystem { axiom = "F(1) ?E(0) F(1) ?E(0) F(1) ?E(0) F(0.5) ?E(0)",
                             steps = steps or 1,
                             environment = function (queries, info)
                               got = env:answer(queries, info)
                               return got
                             end }
    local s = m:derive()
    return got, s
  end

  it("answers how many, how dense, how near and whether free, among the other queries",
     function ()
    local n = row(lsys.environment.space { radius = 1 })
    assert.same({ 1, 2, 2, 1 }, n)
    local rho = row(lsys.environment.space { radius = 1, answer = "density" })
    assert.near({ 0, 0, 0.75 ^ 2, 0.75 ^ 2 }, rho, 1e-12)
    local d = row(lsys.environment.space { radius = 0.8, answer = "nearest" })
    assert.same({ 0.8, 0.8, 0.5, 0.5 }, d)                -- the radius: none within it
    local free = row(lsys.environment.space { radius = 0.8, answer = "free" })
    assert.same({ 1, 1, 0, 0 }, free)
  end)

  it("counts the plant's own segment ends with scene = true, not the one it stands on",
     function ()
    assert.same({ 2, 4, 4, 2 }, row(lsys.environment.space { radius = 1, scene = true }))
    assert.same({ 2, 4, 3, 1 }, row(lsys.environment.space { radius = 1, scene = true,
                                                             offset = 0.6 }))
    local _, s = row(lsys.environment.space { radius = 0.8, answer = "free" }, 1)
    assert.equal("F(1)?E(1)F(1)?E(1)F(1)?E(0)F(0.5)?E(0)", tostring(s))   -- the answers kept
  end)

  it("raises clear errors for bad options", function ()
    local S = lsys.environment.space
    assert.error_contains(function () S {} end, "lsys.environment.space: radius must be a "
      .. "number > 0")
    assert.error_contains(function () S { radius = 1, answer = "many" } end,
                          "answer must be \"count\", \"density\", \"nearest\" or \"free\"")
    assert.error_contains(function () S { radius = 1, size = 2 } end, "unknown option 'size'")
    assert.error_contains(function () S { radius = 1, scene = 1 } end, "scene must be a boolean")
    assert.error_contains(function () S { radius = 1, offset = -1 } end,
                          "offset must be a number >= 0")
    assert.equal("lsys.environment.space", tostring(S { radius = 1 }))
  end)
end)

describe("lsys.environment.colonize", function ()
  local function bud (x, y, z, hx, hy, hz, n)
    local params = { 0 }
    for i = 2, n or 1 do params[i] = 0 end
    return { position = { x, y, z }, heading = { hx, hy, hz }, params = params }
  end

  it("answers Q and the direction to a bud's markers, and removes those buds reach",
     function ()
    local env = lsys.environment.colonize {
      markers = { { 0, 1, 0 }, { 1.2, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 2.1, 0, 0 } },
      perception = 1.5, kill = 0.2, angle = 180 }
    local a = env:answer { bud(0, 0, 0, 0, 1, 0, 4), bud(2, 0, 0, 1, 0, 0),
                           bud(9, 9, 9, 0, 1, 0, 4) }
    assert.same({ { 1, 1, 0, 0 }, 1, { 0, 0, 0, 0 } }, a)
    assert.equal(4, env:count())                           -- (2.1, 0, 0) taken
    local c = lsys.environment.colonize { markers = { 0, 1, 0, 1, 0, 0, 0, -1, 0 },
                                          perception = 2, answer = "count" }
    assert.same({ 2 }, c:answer { bud(0, 0, 0, 0, 1, 0) })  -- 90 degrees: not (0, -1, 0)
    assert.same({ 0, 1, 0, 1, 0, 0, 0, -1, 0 }, c:points())
  end)

  it("makes seeded markers in a sphere, a box or a function's envelope", function ()
    local function pts (m)
      return lsys.environment.colonize({ markers = m, perception = 1 }):points()
    end
    local lo, hi = { -1, 0, -2 }, { 1, 4, 2 }
    local s = pts { count = 500, envelope = "sphere", lo = lo, hi = hi, seed = 3 }
    assert.equal(1500, #s)
    for i = 1, #s, 3 do
      assert.is_true(s[i] ^ 2 + ((s[i + 1] - 2) / 2) ^ 2 + (s[i + 2] / 2) ^ 2 <= 1)
    end
    assert.same(s, pts { count = 500, envelope = "sphere", lo = lo, hi = hi, seed = 3 })
    assert.are_not.same(s, pts { count = 500, envelope = "sphere", lo = lo, hi = hi, seed = 4 })
    local b = pts { count = 200, lo = lo, hi = hi }
    local outside = 0
    for i = 1, #b, 3 do
      assert.is_true(b[i] >= -1 and b[i] < 1 and b[i + 1] >= 0 and b[i + 1] < 4)
      if b[i] ^ 2 + ((b[i + 1] - 2) / 2) ^ 2 + (b[i + 2] / 2) ^ 2 > 1 then outside = outside + 1 end
    end
    assert.is_true(outside > 40)                          -- a box, not the sphere in it
    local f = pts { count = 100, lo = lo, hi = hi, envelope = function (x) return x > 0.5 end }
    for i = 1, #f, 3 do assert.is_true(f[i] > 0.5) end
    assert.equal("lsys.environment.colonize: the envelope took 0 of 5 markers in 5000 draws",
      H.errof(pts, { count = 5, lo = lo, hi = hi, envelope = function () return false end }))
  end)

  it("raises clear errors for bad options", function ()
    local C = lsys.environment.colonize
    local m = { { 0, 0, 0 } }
    assert.error_contains(function () C { perception = 1 } end, "markers is required")
    assert.error_contains(function () C { markers = m } end, "perception must be a number > 0")
    assert.error_contains(function () C { markers = m, perception = 1, angle = 0 } end,
                          "angle must be a number of degrees in (0, 180]")
    assert.error_contains(function () C { markers = m, perception = 1, kill = 17 } end,
                          "kill must be a number in [0, 16 times the perception]")
    assert.error_contains(function () C { markers = m, perception = 1, answer = "q" } end,
                          "answer must be \"presence\" or \"count\"")
    assert.error_contains(function () C { markers = m, perception = 1, range = 1 } end,
                          "unknown option 'range'")
    assert.error_contains(function () C { markers = { { 0, 0 } }, perception = 1 } end,
                          "markers[1] must be a list {x, y, z} of finite numbers")
    assert.error_contains(function () C { markers = { 0, 0 }, perception = 1 } end,
                          "markers as a flat list must have 3 numbers a point")
    assert.error_contains(function () C { markers = { count = 5, lo = { 0, 0, 0 },
                                                      hi = { 1, 0, 1 } }, perception = 1 } end,
                          "markers.lo must be below markers.hi in x, y and z")
    assert.error_contains(function () C { markers = { count = 1.5 }, perception = 1 } end,
                          "markers.count must be an integer")
    assert.error_contains(function () C { markers = { count = 5, lo = { 0, 0, 0 },
      hi = { 1, 1, 1 }, envelope = "cone" }, perception = 1 } end,
      "markers.envelope must be \"sphere\", \"box\" or a function (x, y, z) -> boolean")
    local env = C { markers = m, perception = 1 }
    assert.equal("query 1: its heading is not a finite non-zero vector",
                 H.errof(env.answer, env, { bud(0, 0, 0, 0, 0, 0) }))
  end)

  it("grows examples/open/colonize.lua: a crown that uses up its markers, the same twice",
     function ()
    -- the counts of the plant whose picture was looked at: after 12 steps 525 internodes
    -- and 1105 of the 1500 markers left; all taken by step 24, with 1581 internodes
    local half = dofile("examples/open/colonize.lua")
    half.steps = 12
    assert.equal(525, half:derive():count("F"))
    assert.equal(1105, half.environment:count())
    local m = dofile("examples/open/colonize.lua")
    local s = m:derive()
    assert.equal(1581, s:count("F"))
    assert.equal(1581, s:count("?E"))                       -- a bud for each: waiting
    assert.equal(0, m.environment:count())
    assert.equal(tostring(s), tostring(m:derive()))         -- the markers made afresh
    local m1 = dofile("examples/open/colonize.lua")        -- one thread as three
    m1.environment.popts.threads = 1
    local m3 = dofile("examples/open/colonize.lua")
    m3.environment.popts.threads = 3
    assert.equal(tostring(m1:derive()), tostring(m3:derive()))
    -- the crown fills the ellipsoid (radii 4.5 across, 3.5 up, centred 7 high), not beyond
    local lo, hi = m:interpret(s):bounds()
    assert.near({ -4.07, 0, -3.98 }, { lo[1], lo[2], lo[3] }, 0.01)
    assert.near({ 4.12, 9.91, 4.32 }, { hi[1], hi[2], hi[3] }, 0.01)
  end)
end)

describe("core.field", function ()
  it("diffuses, shares what is taken, adds sources and gives gradients", function ()
    local F = core.field { lo = { 0, 0, 0 }, hi = { 2.5, 0, 0 }, cell = 0.5 }
    assert.same({ 5, 1, 1, 0.5 }, { F:dims() })
    assert.equal("lsys.Field: 5 x 1 x 1 cells of 0.5", tostring(F))
    F:set { 0, 0, 1, 0, 0 }
    assert.equal(2, F:diffuse(0.25, 1))                 -- D t / h^2 = 1: 2 substeps of 1/2
    assert.same({ 0.25, 0, 0.5, 0, 0.25 }, F:values())
    assert.same({ -0.5, 0, 0, 0, 0, 0, -0.25, 0, 0, 0, 0, 0 },
                F:gradient { 0.25, 0, 0, 1.25, 0, 0, 1.75, 0, 0, 9, 0, 0 })
    local got = F:take({ 1.2, 0, 0, 1.3, 0, 0, 0.1, 0, 0, 9, 0, 0 }, { 0.4, 0.6, 0.1, 1 })
    assert.near({ 0.2, 0.3, 0.1, 0 }, got, 1e-15)       -- too little: shared 2 : 3
    assert.near({ 0.15, 0, 0, 0, 0.25 }, F:values(), 1e-15)
    assert.equal(1, F:add({ 0.1, 0, 0, 7, 0, 0 }, { 1, 1 }))
    assert.near({ 1.15, 0 }, F:at { 0.1, 0, 0, 7, 0, 0 }, 1e-15)
    assert.near(1.4, F:total(), 1e-15)
    F:fill(2)
    assert.same({ 2, 2, 2, 2, 2 }, F:values())
  end)

  it("gives the same amounts on every number of threads", function ()
    local function run (threads)
      local F = core.field { lo = { 0, 0, 0 }, hi = { 4, 3, 5 }, cell = 0.25, threads = threads }
      local amounts = {}
      for i = 1, 200 do amounts[i] = i % 7 end
      assert.equal(200, F:add(randompoints(200, 3, 8), amounts))
      F:diffuse(0.3, 2)
      return F:values(), F:total()
    end
    local a, ta = run(1)
    local b, tb = run(3)
    assert.same(a, b)
    assert.near(ta, tb, 0)
  end)

  it("raises clear errors for bad options and amounts, and once closed", function ()
    assert.equal("core.field: opts.lo is required (a list {x, y, z} of finite numbers)",
                 H.errof(core.field, { hi = { 1, 1, 1 }, cell = 1 }))
    assert.equal("core.field: opts.cell is required (a finite number > 0)",
                 H.errof(core.field, { lo = { 0, 0, 0 }, hi = { 1, 1, 1 } }))
    assert.equal("core.field: the box must have finite lo <= hi on each axis",
                 H.errof(core.field, { lo = { 0, 0, 0 }, hi = { 1, -1, 1 }, cell = 1 }))
    assert.equal("core.field: unknown option 'size' (known: lo, hi, cell, threads, max_memory)",
                 H.errof(core.field, { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cell = 1, size = 2 }))
    assert.matches("^core.field: .* more than max_memory %(100 bytes%)$",
      H.errof(core.field, { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cell = 0.1, max_memory = 100 }))
    local F = core.field { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cell = 0.5 }
    assert.equal("field:set: 2 values for 8 cells", H.errof(F.set, F, { 1, 2 }))
    assert.equal("field:take: amount 1 must be a finite number >= 0",
                 H.errof(F.take, F, { 0, 0, 0 }, { -1 }))
    assert.equal("field:take: 2 wants for 1 points", H.errof(F.take, F, { 0, 0, 0 }, { 1, 2 }))
    assert.equal("field:diffuse: the diffusion needs 2400000 substeps, more than 100000: make "
      .. "the cells larger", H.errof(F.diffuse, F, 1e5, 1))
    F:close()
    F:close()
    assert.equal("lsys.Field (closed)", tostring(F))
    for _, k in ipairs { "dims", "values", "total" } do
      assert.equal("field:" .. k .. ": the field was closed", H.errof(F[k], F))
    end
    assert.equal("field:take: the field was closed", H.errof(F.take, F, {}, {}))
  end)
end)

describe("lsys.environment.resource", function ()
  local function q (x, want, n)
    local params = { want }
    for i = 2, n or 1 do params[i] = 0 end
    return { position = { x, 0, 0 }, heading = { 0, 1, 0 }, params = params }
  end

  it("gives each ?E what it asks, or its share, then diffuses and feeds between passes",
     function ()
    local env = lsys.environment.resource { lo = { 0, 0, 0 }, hi = { 2.5, 0, 0 }, cell = 0.5,
      initial = function (x) return x < 1 and 1 or 0 end, diffusion = 0.25,
      sources = { { 2.4, 0, 0, 1 } } }
    assert.near(2, env:total(), 1e-15)                  -- cells 0 and 1
    -- the first pass: the source adds 1 to cell 4, diffusion spreads [1, 1, 0, 0, 1]
    -- over 2 substeps of 1/2 to [1, 0.75, 0.5, 0.5, 0.25 + ...]; then the takes
    local a = env:answer { q(0.1, 0.5), q(1.1, 0.3, 4), q(1.2, 0.3), q(9, 1) }
    assert.equal(0.5, a[1])
    assert.near(0.25, a[2][1], 1e-15)                   -- cell 2 had 0.5 for 0.6 asked
    assert.near(0.25, a[3], 1e-15)
    assert.equal(0, a[4])                               -- outside the box
    assert.same({ -1, 0, 0 }, { a[2][2], a[2][3], a[2][4] })   -- more water at x < 1
    assert.near(0, env:at(1.1, 0, 0), 1e-15)
    assert.near(3 - 1, env:total(), 1e-12)              -- 2 + 1 in, 1 taken
  end)

  it("grows examples/open/roots.lua towards its spring, the same on every number of threads",
     function ()
    -- the counts of the roots whose picture was looked at: 510 internodes, 154 apices,
    -- reaching from the origin to the spring at (5, -6, 0)
    local m = dofile("examples/open/roots.lua")
    local s = m:derive()
    assert.equal(510, s:count("F"))
    assert.equal(154, s:count("R"))
    local lo, hi = m:interpret(s):bounds()
    assert.near({ -0.07, -6.57, -1.36 }, { lo[1], lo[2], lo[3] }, 0.01)
    assert.near({ 5.50, 0, 1.47 }, { hi[1], hi[2], hi[3] }, 0.01)
    assert.equal(tostring(s), tostring(m:derive()))     -- the field made afresh
    local m1 = dofile("examples/open/roots.lua")
    m1.environment.threads = 1
    local m3 = dofile("examples/open/roots.lua")
    m3.environment.threads = 3
    assert.equal(tostring(m1:derive()), tostring(m3:derive()))
  end)

  it("raises clear errors for bad options", function ()
    local R = lsys.environment.resource
    local ok = { lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, cell = 0.5 }
    local function with (k, v)
      local o = {}
      for key, x in pairs(ok) do o[key] = x end
      o[k] = v
      return function () R(o) end
    end
    assert.error_contains(with("lo", { 0, 0 }), "lo must be a list {x, y, z} of finite numbers")
    assert.error_contains(with("hi", { 1, -1, 1 }), "lo must not be above hi in x, y or z")
    assert.error_contains(with("cell", 0), "cell must be a number > 0")
    assert.error_contains(with("diffusion", -1), "diffusion must be a number >= 0")
    assert.error_contains(with("initial", "wet"), "initial must be a number >= 0 or a function")
    assert.error_contains(with("sources", { { 0, 0, 0 } }),
                          "sources[1] must be a list {x, y, z, rate} of finite numbers")
    assert.error_contains(with("rain", 1), "unknown option 'rain'")
    local env = R(ok)
    env.initial = function () return -1 end
    assert.equal("lsys.environment.resource: initial gave -1 at cell 1, not a number >= 0",
                 H.errof(env.total, env))
  end)
end)
