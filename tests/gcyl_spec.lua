-- Generalized cylinders through the turtle (cpfg guide §3): control points, strips, caps,
-- radii from the line width, branching from the active control point, contours and their
-- interpolation, twist of cylinders, records, errors. The geometry of one segment is
-- checked in tests/c/test_gcyl.c.
require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local function model (view)
  return lsys.lsystem { axiom = "", view = view or { angle = 45, contour_sides = 8 } }
end

local function scene (text, view)
  local m = model(view)
  return m:interpret(m:lstring(text))
end

describe("generalized cylinders", function ()
  it("draws n strips between two control points, capped at both ends", function ()
    -- figure 5: @Gs f -(45) f @Ge(6); 8 sides: 6 strips x 16 triangles + 2 caps x 6
    local sc = scene("@Gs f -(45) f @Ge(6)")
    assert.equal(6 * 16 + 2 * 6, sc.ntriangles)
    assert.equal(7 * 9 + 2 * 8, sc.nvertices)
    assert.equal(1, sc.nrecords)
    local r = sc:record(1)
    assert.equal("gcyl", r.kind)
    assert.equal(5, r.module)
    assert.near({ 0, 0, 0 }, r.p0, 1e-6)
    local s = math.sqrt(0.5)
    assert.near({ s, 1 + s, 0 }, r.p1, 1e-6)    -- - turns right: toward +x
    assert.equal(1, r.w0); assert.equal(1, r.w1)
  end)

  it("uses one strip without a parameter (figure 6 counts 1 to 5)", function ()
    for n = 1, 5 do
      local sc = scene(("@Gs f -(45) f @Ge(%d)"):format(n))
      assert.equal(n * 16 + 12, sc.ntriangles)
    end
    assert.equal(16 + 12, scene("@Gs f @Ge").ntriangles)
  end)

  it("continues through @Gc, sharing the ring at each control point", function ()
    local sc = scene("@Gs f @Gc(2) f @Gc(3) f @Ge(4)")
    assert.equal((2 + 3 + 4) * 16 + 12, sc.ntriangles)
    assert.equal((1 + 2 + 3 + 4) * 9 + 16, sc.nvertices)
    assert.equal(3, sc.nrecords)
  end)

  it("takes the radius from the line width at each control point", function ()
    local sc = scene("!(0.4) @Gs f(1) !(0.2) @Ge(8)")
    local lo, hi = sc:bounds()
    assert.near({ -0.2, 0, -0.2 }, lo, 1e-6)
    assert.near({ 0.2, 1, 0.2 }, hi, 1e-6)
    -- the longitudinal section bulges with @Gr(30,4.5,0,3.5) (figure 9b)
    sc = scene("!(0.4) @Gs f(1) !(0.2) @Gr(30,4.5,0,3.5) @Ge(20)")
    hi = select(2, sc:bounds())
    assert.is_true(hi[1] > 0.45 and hi[1] < 0.55)
  end)

  it("starts branches from the active control point (§3.4)", function ()
    -- a fork: the two branches continue from the same point and share its ring
    local sc = scene("@Gs f(0.5) @Gc(4) f(0.5) [ +(40) f(0.5) @Gc(4) f(0.5) @Ge(2) ]" ..
                     " [ -(25) f(0.5) @Gc(4) f(0.5) @Ge(2) ]")
    assert.equal(5, sc.nrecords)
    assert.near(sc:record(1).p1, sc:record(4).p0, 1e-6)
    assert.near(sc:record(1).p1, sc:record(2).p0, 1e-6)
    assert.equal((4 + 4 + 2 + 4 + 2) * 16 + 3 * 6, sc.ntriangles)
    assert.equal(9 + 8 + (4 + 4 + 2 + 4 + 2) * 9 + 2 * 8, sc.nvertices)
  end)

  it("restores the active control point with ]", function ()
    -- without the bracket the second @Ge ends nothing
    local sc = scene("@Gs f [ @Ge ] f @Ge")
    assert.equal(2, sc.nrecords)
    sc = scene("@Gs f @Ge f @Ge")
    assert.equal(1, sc.nrecords)
  end)

  it("starts a cylinder at @Gc when none is active", function ()
    local sc = scene("f @Gc f @Ge(2)")
    assert.equal(1, sc.nrecords)
    assert.near({ 0, 1, 0 }, sc:record(1).p0, 1e-6)
  end)

  it("keeps @Gt and @Gr as turtle state until changed", function ()
    local a = scene("@Gs f -(45) @Gt(2,2) f @Gc(4) -(90) f @Ge(4)")
    local b = scene("@Gs f -(45) @Gt(2,2) f @Gc(4) @Gt -(90) f @Ge(4)")
    local la, ha = a:bounds()
    local lb, hb = b:bounds()
    assert.is_true(math.abs(la[1] - lb[1]) + math.abs(ha[2] - hb[2]) > 1e-3)
  end)

  it("needs no records when asked not to keep them", function ()
    local m = model()
    local sc = m:interpret(m:lstring("@Gs f @Ge"), { records = false })
    assert.equal(0, sc.nrecords)
    assert.equal(16 + 12, sc.ntriangles)
  end)

  it("rejects bad parameters with the module named", function ()
    assert.error_contains(function () scene("@Gs f @Gc(0)") end, "module 3", "@Gc", "strips")
    assert.error_contains(function () scene("@Gs f @Ge(1e9)") end, "@Ge", "10000")
    assert.error_contains(function () scene("@Gs f @Gr(1,2,3) @Ge") end, "@Gr", "not 3")
    assert.error_contains(function () scene("@#(3) @Gs f @Ge") end,
                          "module 1", "contour 3 is not defined")
    local nan = lsys.lsystem { axiom = "A", productions = "A --> @Gs f @Gc(0/0)" }
    assert.error_contains(function () nan:interpret(nan:derive(1)) end, "@Gc",
                          "not a finite number")
  end)
end)

describe("contours", function ()
  local square = core.contour({ { 1, 1 }, { -1, 1 }, { -1, -1 }, { 1, -1 } }, true)
  local blade = core.contour({ { -1, 0 }, { -1, 0 }, { -1, 0 }, { 0, 0.3 }, { 1, 0 },
                               { 1, 0 }, { 1, 0 } }, false)

  it("sweeps a contour given in the view (@#)", function ()
    local v = { angle = 45, contour_sides = 16, contours = { [2] = square } }
    local sc = scene("@#(2) @Gs f @Ge(3)", v)
    assert.equal(3 * 32 + 2 * 14, sc.ntriangles)
    -- the rounded square is narrower than the unit circle would make it along U
    local _, hi = sc:bounds()
    assert.is_true(hi[1] < 0.5 and hi[1] > 0.2)
  end)

  it("interpolates between the contours of the two ends", function ()
    local v = { angle = 45, contour_sides = 16, contours = { [2] = square } }
    local a = scene("@#(2) @Gs f @#(0) @Ge(3)", v)
    local b = scene("@#(2) @Gs f @Ge(3)", v)
    assert.equal(a.ntriangles, b.ntriangles)
    local _, ha = a:bounds()
    local _, hb = b:bounds()
    assert.is_true(ha[1] > hb[1])
  end)

  it("leaves open contours uncapped and two-sided", function ()
    local v = { angle = 45, contour_sides = 10, contours = { [1] = blade } }
    local sc = scene("@#(1) @Gs f(2) @Ge(5)", v)
    assert.equal(5 * 20, sc.ntriangles)
  end)

  it("keeps the turtle's twist when twist minimisation is off (figure 19)", function ()
    local v = { angle = 45, contour_sides = 16, contours = { [2] = blade } }
    local flat = scene("@#(2) @Gs f(1) /(90) f(1) @Ge(10)", v)
    v.minimize_twist = false
    local twisted = scene("@#(2) @Gs f(1) /(90) f(1) @Ge(10)", v)
    local l1, h1 = flat:bounds()
    local l2, h2 = twisted:bounds()
    -- untwisted, the blade stays in one plane: thin along one axis; twisted, it is not
    assert.is_true(math.min(h1[1] - l1[1], h1[3] - l1[3]) < 0.7)
    assert.is_true(math.min(h2[1] - l2[1], h2[3] - l2[3]) > 0.8)
  end)
end)

-- The mesh's vertices, read back from an OBJ export.
local R = require "tests.export_reader"
local function vertices (sc)
  local path = os.tmpname()
  sc:save(path .. ".obj")
  local o = R.obj(path .. ".obj")
  for _, ext in ipairs { ".obj", ".mtl", "" } do os.remove(path .. ext) end
  return o
end

-- the centre of ring j (p + 1 vertices each, the last repeating the first) and the
-- direction from it to the ring's first vertex
local function ring (vs, p, j, first)
  local c = { 0, 0, 0 }
  for k = 0, p - 1 do
    local v = vs[first + j * (p + 1) + k]
    for i = 1, 3 do c[i] = c[i] + v[i] / p end
  end
  local v = vs[first + j * (p + 1)]
  local d = { v[1] - c[1], v[2] - c[2], v[3] - c[3] }
  local l = math.sqrt(d[1] ^ 2 + d[2] ^ 2 + d[3] ^ 2)
  return c, { d[1] / l, d[2] / l, d[3] / l }
end

describe("generalized cylinder geometry", function ()
  it("follows the Hermite axis: F(1/2) = (P0 + P1)/2 + (T0 - T1)/8 (§3.1)", function ()
    -- P0 = 0, H0 = y; P1 = (s, 1 + s, 0), H1 = (s, s, 0) with s = sqrt(1/2); d = |P1 - P0|
    local o = vertices(scene("@Gs f -(45) f @Ge(2)"))
    local s = math.sqrt(0.5)
    local d = math.sqrt(s ^ 2 + (1 + s) ^ 2)
    local T0, T1 = { 0, 1.2 * d, 0 }, { 1.2 * d * s, 1.2 * d * s, 0 }
    local want = {}
    for i = 1, 3 do
      local P1 = ({ s, 1 + s, 0 })[i]
      want[i] = P1 / 2 + (T0[i] - T1[i]) / 8
    end
    -- the start cap's 8 vertices come first
    local c = ring(o.vs, 8, 1, 9)
    assert.near(want, c, 1e-5)
    c = ring(o.vs, 8, 2, 9)
    assert.near({ s, 1 + s, 0 }, c, 1e-5)
  end)

  it("keeps the frame from flipping along a helix (rotation-minimising, §3.3)", function ()
    -- a helix of 60 control points while the turtle rolls by 25° at every one
    local text = "!(0.2) @Gs" .. string.rep(" f(0.3) +(12) &(4) /(25) @Gc(2)", 60) .. " @Ge"
    local nrings = 1 + 60 * 2 + 2
    -- the largest and the total turn of the rings' first vertices, in degrees
    local function turns (view)
      local o = vertices(scene(text, view))
      local prev, max, sum = nil, 0, 0
      for j = 0, nrings - 1 do
        local _, d = ring(o.vs, 8, j, 9)
        if prev then
          local cos = d[1] * prev[1] + d[2] * prev[2] + d[3] * prev[3]
          local a = math.deg(math.acos(math.min(1, cos)))
          max, sum = math.max(max, a), sum + a
        end
        prev = d
      end
      return max, sum
    end
    local max, sum = turns { angle = 45, contour_sides = 8 }
    -- neighbouring rings turn only with the bend of the axis: no flip, and the rolls
    -- (60 x 25° = 1500°) do not add up
    assert.is_true(max < 20)
    assert.is_true(sum < 1000)
    -- with the twist kept, they do
    local _, tsum = turns { angle = 45, contour_sides = 8, minimize_twist = false }
    assert.is_true(tsum > sum + 700)
  end)

  it("interpolates the radius linearly by default (§3.2.2)", function ()
    local o = vertices(scene("!(0.8) @Gs f(2) !(0.4) @Ge(4)"))
    for j = 0, 4 do
      local c, _ = ring(o.vs, 8, j, 9)
      local v = o.vs[9 + j * 9]
      local r = math.sqrt((v[1] - c[1]) ^ 2 + (v[2] - c[2]) ^ 2 + (v[3] - c[3]) ^ 2)
      assert.near(0.4 - 0.05 * j, r, 1e-6)
    end
  end)

  it("maps textures around and along with the image's aspect (§5.2)", function ()
    local png = os.tmpname() .. ".png"
    core.png_write(png, string.rep("\255\0\0\255", 8 * 4), 8, 4, false)   -- 8 x 4: aspect 2
    local r = 1 / (2 * math.pi)
    local o = vertices(scene(("#(%.17g) @Tx(1) @Gs @Gt(1) f(3) @Ge(3)"):format(2 * r),
                             { contour_sides = 6, textures = { png } }))
    os.remove(png)
    -- rings after the 6 cap vertices; v grows by length x 2 / circumference = 2 per unit
    for j = 0, 3 do
      for k = 0, 6 do
        local uv = o.vts[6 + j * 7 + k + 1]
        assert.near(k / 6, uv[1], 1e-6)
        assert.near(2 * j, uv[2], 1e-5)
      end
    end
  end)

  it("maps textures on polygons from the first vertex's right and heading axes (§5.3)", function ()
    local o = vertices(scene("{ . f(1) -(90) f(2) -(90) f(1) }"))
    assert.equal(4, o.vt)
    assert.near({ { 0, 0 }, { 0, 1 }, { 1, 1 }, { 1, 0 } }, o.vts, 1e-6)
    -- turned: the axes turn with the turtle
    o = vertices(scene("+(90) { . f(1) -(90) f(2) -(90) f(1) }"))
    assert.near({ { 0, 0 }, { 0, 1 }, { 1, 1 }, { 1, 0 } }, o.vts, 1e-6)
  end)
end)
