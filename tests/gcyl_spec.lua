-- Generalized cylinders through the turtle (seed 004 §3): control points, strips, caps,
-- radii from the line width, branching from the active control point, contours and their
-- interpolation, twist of cylinders, records, errors. The geometry of one segment is
-- checked in tests/c/test_gcyl.c.
local H = require "tests.helper"
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
    lo, hi = sc:bounds()
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
    local lo, hi = sc:bounds()
    assert.is_true(hi[1] < 0.5 and hi[1] > 0.2)
  end)

  it("interpolates between the contours of the two ends", function ()
    local v = { angle = 45, contour_sides = 16, contours = { [2] = square } }
    local a = scene("@#(2) @Gs f @#(0) @Ge(3)", v)
    local b = scene("@#(2) @Gs f @Ge(3)", v)
    assert.equal(a.ntriangles, b.ntriangles)
    local la, ha = a:bounds()
    local lb, hb = b:bounds()
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
