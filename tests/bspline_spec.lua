-- B-spline curves and stroke capture (Anastacio et al. 2009, §3.1, §3.4): core.bspline and
-- its methods, core.bspline_resample, core.chaikin, core.chaikin_reverse, core.stroke_curve.
-- Expected values are computed by hand from the basis functions (see tests/c/test_bspline.c).
require "tests.helper"
local core = require "lsys.core"

-- The exact message (assert.has_error would strip a leading "file:line: ").
local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return msg
end

local P = { { 0, 0 }, { 1, 2 }, { 3, 3 }, { 4, 0 }, { 6, 1 } }
local ARCH = { { -1, 0 }, { 0, 2 }, { 1, 0 } }      -- clamped quadratic: y = 1 - x^2
local QC = { degree = 2, clamped = true }

describe("core.bspline", function()
  it("evaluates a uniform quadratic curve at hand-computed points", function()
    local c = core.bspline({ P[1], P[2], P[3], P[4] }, { degree = 2 })
    assert.near({ 0.5, 1 }, { c:eval(0) }, 1e-14)           -- (P0 + P1) / 2
    assert.near({ 9 / 8, 15 / 8 }, { c:eval(0.25) }, 1e-14)  -- (P0 + 6 P1 + P2) / 8
    assert.near({ 3.5, 1.5 }, { c:eval(1) }, 1e-14)
    assert.near({ 3.5, 1.5 }, { c:eval(7) }, 1e-14)         -- t clamped into [0, 1]
    assert.near({ 3, 3 }, { c:deriv(0.25) }, 1e-13)          -- P2 - P0
    assert.near({ 4, -4 }, { c:deriv(0.25, 2) }, 1e-13)      -- 4 (P0 - 2 P1 + P2)
  end)

  it("evaluates uniform and clamped cubic curves", function()
    local c = core.bspline(P)                                -- degree 3, uniform
    assert.equal(3, c:degree())
    assert.is_false(c:clamped())
    assert.equal(5, #c)
    assert.near({ 7 / 6, 11 / 6 }, { c:eval(0) }, 1e-14)
    assert.near({ 2, 115 / 48 }, { c:eval(0.25) }, 1e-14)
    local b = core.bspline({ P[1], P[2], P[3], P[4] }, { clamped = true })   -- Bezier
    assert.is_true(b:clamped())
    assert.near({ 0, 0 }, { b:eval(0) }, 0)
    assert.near({ 2, 15 / 8 }, { b:eval(0.5) }, 1e-14)
    assert.near({ 3, -9 }, { b:deriv(1) }, 1e-13)            -- 3 (P3 - P2)
  end)

  it("works in 3D", function()
    local c = core.bspline({ { 0, 0, 0 }, { 1, 2, 1 }, { 3, 1, 3 } }, QC)
    assert.equal(3, c:dim())
    assert.near({ 1.25, 1.25, 1.25 }, { c:eval(0.5) }, 1e-15)
    assert.equal(3, select("#", c:deriv(0.5)))
    local t, d = c:closest(1.25, 1.25, 1.25)
    assert.near(0.5, t, 1e-9)
    assert.near(0, d, 1e-9)
  end)

  it("measures arc length and walks it", function()
    local c = core.bspline(ARCH, { degree = 2, clamped = true })
    local L = math.sqrt(5) + math.log(2 + math.sqrt(5)) / 2   -- asinh 2 = log(2 + sqrt 5)
    assert.near(L, c:length(), 1e-10 * L)
    assert.near(L / 2, c:length(0, 0.5), 1e-10 * L)
    assert.near(0.5, c:at_length(L / 2), 1e-12)
    assert.equal(0, c:at_length(-1))
    assert.equal(1, c:at_length(L + 1))
    local s = c:sample_length(5)
    assert.equal(5, #s)
    assert.near({ -1, 0 }, { s[1][1], s[1][2] }, 0)
    assert.near({ 0, 1 }, { s[3][1], s[3][2] }, 1e-12)
    assert.near(0.5, s[3].t, 1e-12)
    for i = 1, 4 do assert.near(L / 4, c:length(s[i].t, s[i + 1].t), 1e-10) end
    local e = c:sample(3)
    assert.near({ { -1, 0 }, { 0, 1 }, { 1, 0 } }, e, 1e-15)
  end)

  it("intersects a ray, sorted by s, and reports a start on the curve with s = 0", function()
    local c = core.bspline(ARCH, { degree = 2, clamped = true })
    local h = c:ray(-2, 0.75, 1, 0)
    assert.equal(2, #h)
    assert.near({ 0.25, 1.5, -0.5, 0.75 }, { h[1].t, h[1].s, h[1].x, h[1].y }, 1e-13)
    assert.near({ 0.75, 2.5, 0.5, 0.75 }, { h[2].t, h[2].s, h[2].x, h[2].y }, 1e-13)
    h = c:ray(0.5, 0.75, -1, 0)
    assert.equal(2, #h)
    assert.near({ 0, 0.75 }, { h[1].s, h[1].t }, 1e-12)
    assert.near({ 1, 0.25 }, { h[2].s, h[2].t }, 1e-12)
    assert.same({}, c:ray(-2, 1.5, 1, 0))
    assert.same({}, c:ray(0, 0.75, 0, -1))                   -- down from inside: misses
  end)

  it("finds 10000 crossings of a zigzag", function()
    local pts = {}
    for i = 0, 10000 do pts[#pts + 1] = { i, i % 2 == 1 and 1 or -1 } end
    local c = core.bspline(pts, { degree = 2 })
    local h = c:ray(-5, 0, 1, 0)
    assert.equal(10000, #h)
    assert.near(0.5, h[1].x, 1e-9)
    assert.near(9999.5, h[10000].x, 1e-9)
  end)

  it("intersects two curves, sorted by t", function()
    local a = core.bspline(ARCH, { degree = 2, clamped = true })
    local b = core.bspline({ { -2, 0.75 }, { 0, 0.75 }, { 2, 0.75 } }, QC)
    local h = a:intersect(b)
    assert.equal(2, #h)
    assert.near({ 0.25, 0.375, -0.5, 0.75 }, { h[1].t, h[1].u, h[1].x, h[1].y }, 1e-12)
    assert.near({ 0.75, 0.625, 0.5, 0.75 }, { h[2].t, h[2].u, h[2].x, h[2].y }, 1e-12)
    local d = core.bspline({ { 0, 2 }, { 1, 1 }, { 2, 0 } }, { degree = 2, clamped = true })
    assert.same({}, a:intersect(d))
  end)

  it("finds the closest point", function()
    local c = core.bspline(ARCH, { degree = 2, clamped = true })
    local t, d = c:closest(0, 2)
    assert.near(0.5, t, 1e-12)
    assert.near(1, d, 1e-12)
    t, d = c:closest(3, -1)
    assert.equal(1, t)
    assert.near(math.sqrt(5), d, 1e-12)
  end)

  it("returns its control points and names itself", function()
    local c = core.bspline(ARCH, { degree = 2, clamped = true })
    assert.same(ARCH, c:points())
    assert.equal("lsys.BSpline(3 points, 2D, degree 2, clamped)", tostring(c))
  end)

  it("refuses bad points and options with clear messages", function()
    assert.equal("bspline: point 2 is not a table of 2 or 3 numbers",
                 errmsg(core.bspline, { { 0, 0 }, { 1 }, { 2, 2 }, { 3, 3 } }))
    assert.equal("bspline: point 3 is not a table of 2 or 3 numbers",
                 errmsg(core.bspline, { { 0, 0 }, { 1, 1 }, "x", { 3, 3 } }))
    assert.equal("bspline: point 2 has 3 coordinates, point 1 has 2",
                 errmsg(core.bspline, { { 0, 0 }, { 1, 1, 1 }, { 2, 2 }, { 3, 3 } }))
    assert.equal("bspline: point 4: coordinate 1 is not finite",
                 errmsg(core.bspline, { { 0, 0 }, { 1, 1 }, { 2, 2 }, { 0 / 0, 3 } }))
    assert.equal("bspline: point 1: coordinate 2 is not finite",
                 errmsg(core.bspline, { { 0, math.huge }, { 1, 1 }, { 2, 2 }, { 3, 3 } }))
    assert.equal("bspline: a curve of degree 3 needs at least 4 control points, got 3",
                 errmsg(core.bspline, ARCH))
    assert.equal("bspline: a curve of degree 2 needs at least 3 control points, got 0",
                 errmsg(core.bspline, {}, { degree = 2 }))
    assert.equal("bspline: opts.degree must be an integer in [2, 3], got 4",
                 errmsg(core.bspline, P, { degree = 4 }))
    assert.equal("bspline: unknown option 'closed'", errmsg(core.bspline, P, { closed = true }))
    local c = core.bspline(P)
    assert.error_contains(function() c:deriv(0.5, 3) end, "must be 1 or 2")
    assert.error_contains(function() c:eval(0 / 0) end, "t is NaN")
    assert.error_contains(function() c:sample(1) end, "must be between 2 and 10000000")
    assert.equal("ray: ray direction must not be zero", errmsg(c.ray, c, 0, 0, 0, 0))
    local c3 = core.bspline({ { 0, 0, 0 }, { 1, 1, 1 }, { 2, 0, 2 } }, { degree = 2 })
    assert.equal("ray: ray intersection needs a 2D curve", errmsg(c3.ray, c3, 0, 0, 1, 0))
    assert.equal("intersect: curve intersection needs 2D curves", errmsg(c.intersect, c, c3))
  end)

  it("raises once closed", function()
    local c
    do
      local d <close> = core.bspline(P)
      assert.equal(5, #d)
      c = d
    end
    getmetatable(c).__close(c)                               -- idempotent
    assert.equal("eval: the curve was closed", errmsg(c.eval, c, 0.5))
    assert.equal("length: the curve was closed", errmsg(c.length, c))
    assert.error_contains(function() return #c end, "#: the curve was closed")
    assert.equal("lsys.BSpline (closed)", tostring(c))
  end)
end)

describe("polylines", function()
  it("resamples to equal spacing keeping the ends", function()
    local L = { { 0, 0 }, { 3, 0 }, { 3, 4 } }
    assert.near({ { 0, 0 }, { 1, 0 }, { 2, 0 }, { 3, 0 }, { 3, 1 }, { 3, 2 }, { 3, 3 }, { 3, 4 } },
                core.bspline_resample(L, 1), 1e-14)
    assert.near({ { 0, 0 }, { 1.75, 0 }, { 3, 0.5 }, { 3, 2.25 }, { 3, 4 } },
                core.bspline_resample(L, 2), 1e-14)
    assert.equal("bspline_resample: spacing must be a positive finite number",
                 errmsg(core.bspline_resample, L, 0))
    assert.equal("bspline_resample: at least 2 points needed, got 1",
                 errmsg(core.bspline_resample, { { 0, 0 } }, 1))
  end)

  it("undoes Chaikin subdivision exactly with the reverse filter", function()
    local c = { { 0, 0 }, { 2, 5 }, { 4, -1 }, { 7, 3 }, { 9, 9 }, { 12, 0 } }
    local f = core.chaikin(c)
    assert.equal(12, #f)
    assert.near({ 0.5, 1.25 }, f[2], 1e-15)                  -- 3/4 c1 + 1/4 c2
    assert.near({ 1.5, 3.75 }, f[3], 1e-15)                  -- 1/4 c1 + 3/4 c2
    assert.near(c, core.chaikin_reverse(f), 1e-13)
    assert.near(c, core.chaikin_reverse(core.chaikin(c, 3), 3), 1e-12)
    assert.equal(48, #core.chaikin(c, 3))
    assert.near({ { 0, 0 }, { 2.5, 0 }, { 4, 0 } },
                core.chaikin_reverse({ { 0, 0 }, { 1, 0 }, { 2, 0 }, { 3, 0 }, { 4, 0 } }), 1e-15)
    assert.equal(2, #core.chaikin_reverse({ { 0, 0 }, { 1, 0 }, { 2, 0 } }, 5))   -- stops at 2
  end)

  it("captures a stroke as the control points of a quadratic curve (§3.1)", function()
    -- 11 points on x: 0..10 -> 0 2.5 4.5 6.5 8.5 10 -> 0 5.5 10 (then too few for a third step)
    assert.near({ { 0, 0 }, { 5.5, 0 }, { 10, 0 } }, core.stroke_curve({ { 0, 0 }, { 10, 0 } }),
                1e-14)
    assert.equal(6, #core.stroke_curve({ { 0, 0 }, { 10, 0 } }, { steps = 1 }))
    assert.near({ { 0, 0 }, { 0.5, 0 }, { 1, 0 } }, core.stroke_curve({ { 0, 0 }, { 1, 0 } }),
                1e-15)
    assert.equal(4, #core.stroke_curve({ { 0, 0 }, { 1, 0 } }, { degree = 3 }))
    local pts = {}
    for i = 0, 200 do pts[#pts + 1] = { i, 20 * math.sin(i / 30), 0.5 } end
    local cp, m = core.stroke_curve(pts), #core.bspline_resample(pts, 1)
    assert.equal((((m + 1) // 2 + 1) // 2 + 1) // 2, #cp)   -- three reverse steps
    assert.equal(3, #cp[1])                                  -- pressure carried along
    local c = core.bspline(cp, { degree = 2, clamped = true })
    local x, y = c:eval(1)
    assert.near({ 200, 20 * math.sin(200 / 30) }, { x, y }, 1e-12)
    assert.equal("stroke_curve: the stroke has no length",
                 errmsg(core.stroke_curve, { { 1, 1 }, { 1, 1 } }))
    assert.equal("stroke_curve: opts.spacing must be a positive number, got 0",
                 errmsg(core.stroke_curve, pts, { spacing = 0 }))
    assert.equal("stroke_curve: unknown option 'step'",
                 errmsg(core.stroke_curve, pts, { step = 2 }))
  end)
end)
