-- Free-form deformations of a finished scene (csrc/core/ffd.h, csrc/lua/lua_ffd.c): the
-- Hyperpatch of Lintermann and Deussen 1999 (sidebar "FFD and Hyperpatch"), deformations
-- by functions and affine maps, on the whole scene or on the range some modules drew.
require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local function close (x) getmetatable(x).__close(x) end

local function scene (text, style)
  return lsys.lsystem { axiom = "", view = { line_style = style or "cylinder" } }:interpret(text)
end

-- every vertex as {x, y, z, nx, ny, nz}
local function vertices (sc, a, b)
  local out = {}
  for i = a or 1, b or sc.nvertices do out[#out + 1] = { sc:vertex(i) } end
  return out
end

local function errmsg (f, ...)
  local ok, e = pcall(f, ...)
  assert.is_false(ok)
  return e
end

describe("core.hyperpatch", function ()
  it("puts the control points on the lattice of the box", function ()
    local hp = core.hyperpatch { degree = { 1, 3, 4 }, origin = { 1, 2, 3 }, size = { 2, 3, 4 } }
    assert.same({ 1, 3, 4 }, { hp:degree() })
    assert.equal(2 * 4 * 5, hp:count())
    assert.same({ 1, 2, 3 }, { hp:point(0, 0, 0) })
    assert.same({ 3, 5, 7 }, { hp:point(1, 3, 4) })
    assert.near({ 3, 3, 6 }, { hp:point(1, 1, 3) }, 1e-15)        -- 2 + 3/3, 3 + 4 * 3/4
    assert.equal("lsys.Hyperpatch: degree 1 x 3 x 4, 40 control points", tostring(hp))
  end)

  it("is the identity while no control point moved, inside the box and outside it", function ()
    local hp = core.hyperpatch {
      degree = 3, axes = { { 2, 0.5, 0 }, { 0, 1.5, 0.3 }, { 0.2, -0.4, 1 } } }
    for _, p in ipairs { { 0.3, 0.2, 0.1 }, { 1, 1, 1 }, { -2, 5, 0.5 } } do
      assert.near(p, { hp:map(p[1], p[2], p[3]) }, 1e-10)
    end
  end)

  it("moves a point by the Bernstein weights of a moved control point", function ()
    local hp = core.hyperpatch { degree = 1 }                     -- the unit cube
    hp:set(1, 1, 1, 1, 1, 2)                                      -- P_111 up by 1
    -- at (0.5, 0.5, 0.5) the weight of P_111 is 0.5^3
    assert.near({ 0.5, 0.5, 0.625 }, { hp:map(0.5, 0.5, 0.5) }, 1e-15)
    -- at (0.2, 0.5, 1): 0.2 * 0.5 * 1 = 0.1
    assert.near({ 0.2, 0.5, 1.1 }, { hp:map(0.2, 0.5, 1) }, 1e-15)
    -- degree 2 on s: B_1^2(0.3) = 0.42 for P_1jk; moving P_1,1,1 (t = u = 1) by (1, 0, 0)
    local q = core.hyperpatch { degree = { 2, 1, 1 } }
    local x, y, z = q:point(1, 1, 1)
    q:set(1, 1, 1, x + 1, y, z)
    assert.near({ 0.3 + 0.42 * 0.25, 0.5, 0.5 }, { q:map(0.3, 0.5, 0.5) }, 1e-15)
  end)

  it("rejects degrees outside 1..4, bad frames and unknown options", function ()
    assert.equal("core.hyperpatch: 'degree' is 5: degrees are 1 (linear) to 4 (quartic)",
                 errmsg(core.hyperpatch, { degree = 5 }))
    assert.error_contains(function () core.hyperpatch { degree = { 1, 0, 2 } } end,
                          "'degree'[2] is 0", "1 (linear) to 4 (quartic)")
    assert.error_contains(function () core.hyperpatch { degree = 1.5 } end, "must be an integer")
    assert.error_contains(function () core.hyperpatch { size = { 1, 0, 2 } } end, "degenerate")
    assert.error_contains(function ()
      core.hyperpatch { axes = { { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } } }
    end, "degenerate")
    assert.error_contains(function () core.hyperpatch { origin = { 0, 0 / 0, 0 } } end,
                          "'origin'[2] must be a finite number")
    assert.error_contains(function () core.hyperpatch { sizes = { 1, 1, 1 } } end,
                          "unknown option sizes", "known: degree, origin, size, axes")
    assert.error_contains(function () core.hyperpatch { size = { 1, 1, 1 }, axes = {} } end,
                          "'size' or 'axes'")
  end)

  it("checks lattice indices and closed hyperpatches", function ()
    local hp = core.hyperpatch { degree = { 2, 1, 3 } }
    assert.equal("hyperpatch:point: no control point (3, 0, 0): indices are 0..2, 0..1, 0..3",
                 errmsg(hp.point, hp, 3, 0, 0))
    assert.error_contains(function () hp:set(0, -1, 0, 1, 2, 3) end, "no control point (0, -1, 0)")
    assert.error_contains(function () hp:set(0, 0, 0, 1, "y", 3) end,
                          "hyperpatch:set: y must be a finite number")
    close(hp)
    close(hp)                                                     -- idempotent
    assert.equal("lsys.Hyperpatch (closed)", tostring(hp))
    assert.error_contains(function () hp:map(0, 0, 0) end, "the hyperpatch was closed")
    assert.error_contains(function () scene("@O(1)"):deform(hp) end, "the hyperpatch was closed")
  end)
end)

describe("scene:deform", function ()
  it("deforms every vertex and normal by a hyperpatch", function ()
    local sc = scene("@O(1)")                 -- a sphere of diameter 1 at the origin
    local before = vertices(sc)
    -- the top face of the box [-1, 1]^3 raised from z = 1 to z = 3: z' = 2 z + 1
    local hp = core.hyperpatch { degree = 1, origin = { -1, -1, -1 }, size = { 2, 2, 2 } }
    for i = 0, 1 do
      for j = 0, 1 do
        local x, y = hp:point(i, j, 1)
        hp:set(i, j, 1, x, y, 3)
      end
    end
    assert.equal(sc.nvertices, sc:deform(hp))
    assert.equal(#before, sc.nvertices)
    for i, v in ipairs(before) do
      local x, y, z, nx, ny, nz = sc:vertex(i)
      assert.near({ v[1], v[2], 2 * v[3] + 1 }, { x, y, z }, 1e-6)
      -- normals by the inverse transpose of diag(1, 1, 2): (nx, ny, nz / 2), normalized
      local n = { v[4], v[5], v[6] / 2 }
      local l = math.sqrt(n[1] ^ 2 + n[2] ^ 2 + n[3] ^ 2)
      assert.near({ n[1] / l, n[2] / l, n[3] / l }, { nx, ny, nz }, 1e-6)
    end
    local zlo, zhi = math.huge, -math.huge
    for _, v in ipairs(before) do zlo, zhi = math.min(zlo, v[3]), math.max(zhi, v[3]) end
    local lo, hi = sc:bounds()
    assert.near({ 2 * zlo + 1, 2 * zhi + 1 }, { lo[3], hi[3] }, 1e-6)
    assert.is_true(zlo < -0.4 and zhi > 0.4)
  end)

  it("deforms only what the given modules drew, the rest bit for bit", function ()
    local sc = scene("@O(1) f(3) @O(1) f(3) @O(1)")
    local a0, a1 = sc:module_range(1)
    local b0, b1 = sc:module_range(3)
    local c0, c1 = sc:module_range(5)
    assert.same({ 1, b0 - 1, b1 + 1, c1 }, { a0, a1, c0, sc.nvertices })
    assert.is_nil(sc:module_range(2))                                 -- f draws nothing
    local before = vertices(sc)
    assert.equal(b1 - b0 + 1, sc:deform(function (x, y, z) return x + 10, y, z end,
                                        { modules = { 2, 3 } }))
    for i, v in ipairs(before) do
      local now = { sc:vertex(i) }
      if i >= b0 and i <= b1 then
        assert.near(v[1] + 10, now[1], 1e-5)
        assert.equal(v[2], now[2])
      else
        assert.same(v, now)                                           -- untouched, exactly
      end
    end
    -- 1-based inclusive vertex ranges
    assert.equal(2, sc:deform(function (x, y, z) return x, y, z + 1 end, { vertices = { 1, 2 } }))
    assert.equal(before[3][3], (select(3, sc:vertex(3))))
    assert.near(before[2][3] + 1, (select(3, sc:vertex(2))), 1e-6)
  end)

  it("leaves out the ring a cylinder shares with the segment it continues", function ()
    local sc = scene("F @O(1) F")             -- the second F continues the first one's top ring
    local a0, a1 = sc:module_range(1)
    local b0, b1 = sc:module_range(2)
    local c0, c1 = sc:module_range(3)
    assert.same({ 1, a1 + 1, b1 + 1, sc.nvertices }, { a0, b0, c0, c1 })
    local before = vertices(sc)
    assert.equal(c1 - c0 + 1, sc:deform(function (x, y, z) return x, y, z + 1 end,
                                        { modules = { 3, 3 } }))
    for i, v in ipairs(before) do
      if i < c0 then assert.same(v, { sc:vertex(i) })
      else assert.near(v[3] + 1, (select(3, sc:vertex(i))), 1e-6) end
    end
  end)

  it("moves lines drawn by the given modules", function ()
    local sc = scene("F f F", "line")
    assert.equal(2, sc.nlines)
    assert.equal(0, sc:deform(function (x, y, z) return x + 5, y, z end, { modules = { 3, 3 } }))
    local lo, hi = sc:bounds()
    assert.near({ 0, 0, 0 }, lo, 1e-6)                               -- the first line stayed
    assert.near({ 5, 3, 0 }, hi, 1e-6)
    sc:deform(function (x, y, z) return x - 5, y, z end)             -- the whole scene
    lo, hi = sc:bounds()
    assert.near({ -5, 0, 0 }, lo, 1e-6)
    assert.near({ 0, 3, 0 }, hi, 1e-6)
    assert.error_contains(function ()
      sc:deform(function (x, y, z) if x > -1 then error("late") end return x, y, z end)
    end, "the function failed at line 2 end 1", "late")
    lo, hi = sc:bounds()                                             -- as it was
    assert.near({ -5, 0, 0 }, lo, 1e-6)
    assert.near({ 0, 3, 0 }, hi, 1e-6)
  end)

  it("leaves the records of lines where the turtle wrote them", function ()
    local sc = scene("F[+F]F", "line")
    local before = {}
    for k, r in sc:records() do before[k] = r end
    sc:deform(function (x, y, z) return x + 5, y * 2, z end)
    sc:transform({ { 1, 0, 0, 1 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } })
    local lo = sc:bounds()
    assert.near({ 5, 0, 0 }, lo, 1e-6)                               -- the lines moved
    for k, r in sc:records() do assert.same(before[k], r) end       -- the records did not
  end)

  it("takes normals of a function from central differences", function ()
    local sc = scene("{ . f . + f . + f . }")                       -- a flat polygon
    local before = vertices(sc)
    -- the shear z' = z + 0.5 x tilts its plane; the normal of z = 0.5 x is +-(-0.5, 0, 1)
    sc:deform(function (x, y, z) return x, y, z + 0.5 * x end)
    for i, v in ipairs(before) do
      local x, _, z, nx, ny, nz = sc:vertex(i)
      assert.near(0.5 * x, z - v[3], 1e-6)
      local s = v[6] >= 0 and 1 or -1                  -- the side the normal was on
      assert.near({ -0.5 * s / math.sqrt(1.25), 0, s / math.sqrt(1.25) }, { nx, ny, nz }, 1e-5)
    end
  end)

  it("reports a function's error or bad result and leaves the scene as it was", function ()
    local sc = scene("@O(1)")
    local before = vertices(sc)
    local calls = 0
    local e = errmsg(sc.deform, sc, function (x, y, z)
      calls = calls + 1
      if calls > 30 then error("boom") end
      return x + 1, y, z
    end)
    assert.matches("scene:deform: the function failed at vertex 5: .*boom", e)   -- 7 calls each
    assert.same(before, vertices(sc))
    assert.equal("scene:deform: the function must return 3 finite numbers; at vertex 1 its x "
                 .. "is a string", errmsg(sc.deform, sc, function (_, y, z) return "a", y, z end))
    assert.error_contains(function () sc:deform(function (x, y) return x, y end) end,
                          "at vertex 1 its z is nil")
    assert.error_contains(function () sc:deform(function (x, y) return x, y, 0 / 0 end) end,
                          "its z is not finite")
    assert.same(before, vertices(sc))
    assert.error_contains(function ()
      sc:deform(function (x, y, z) close(sc); return x, y, z end)
    end, "cannot close a Scene while it is in use")
    assert.same(before, vertices(sc))                 -- open, as it was
  end)

  it("checks its arguments and closed scenes", function ()
    local sc = scene("@O(1)")
    local hp = core.hyperpatch { degree = 2 }
    assert.error_contains(function () sc:deform(42) end,
                          "argument 1 must be a Hyperpatch or a function, got number")
    assert.error_contains(function () sc:deform(hp, { module = { 1, 1 } }) end,
                          "unknown option module")
    assert.error_contains(function ()
      sc:deform(hp, { modules = { 1, 1 }, vertices = { 1, 2 } })
    end, "not both")
    assert.error_contains(function () sc:deform(hp, { vertices = { 1, sc.nvertices + 1 } }) end,
                          "no vertex " .. (sc.nvertices + 1))
    assert.error_contains(function () sc:deform(hp, { modules = { 2, 1 } }) end,
                          "opts.modules is empty")
    assert.error_contains(function () sc:deform(hp, { vertices = { 0, 1 } }) end,
                          "opts.vertices[1] must be an integer >= 1")
    assert.error_contains(function () sc:vertex(0) end, "no vertex 0")
    close(sc)
    assert.error_contains(function () sc:deform(hp) end, "the scene was closed")
    assert.error_contains(function () sc:module_range(1) end, "the scene was closed")
  end)
end)

describe("scene:transform", function ()
  it("applies a 3 x 4 or 4 x 4 affine map, normals by the inverse transpose", function ()
    local sc = scene("@O(1)")
    local before = vertices(sc)
    assert.equal(sc.nvertices,
                 sc:transform { { 2, 0, 0, 1 }, { 0, 1, 0, 0 }, { 0, 0, 0.5, -1 }, { 0, 0, 0, 1 } })
    for i, v in ipairs(before) do
      local now = { sc:vertex(i) }
      local n = { v[4] / 2, v[5], v[6] * 2 }
      local l = math.sqrt(n[1] ^ 2 + n[2] ^ 2 + n[3] ^ 2)
      assert.near({ 2 * v[1] + 1, v[2], 0.5 * v[3] - 1, n[1] / l, n[2] / l, n[3] / l }, now, 1e-6)
    end
    assert.error_contains(function () sc:transform { { 1, 0, 0, 0 }, { 0, 1, 0, 0 } } end,
                          "3 or 4 rows")
    assert.error_contains(function ()
      sc:transform { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 1, 1 } }
    end, "row 4 must be {0, 0, 0, 1}")
    assert.error_contains(function ()
      sc:transform { { 1, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } }
    end, "row 1 must be a list of 4 numbers")
    assert.error_contains(function ()
      sc:transform { { 1, 0, 0, 0 }, { 0, 1, 0 / 0, 0 }, { 0, 0, 1, 0 } }
    end, "m[2][3] must be a finite number")
  end)
end)
