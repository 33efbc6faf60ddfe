-- Placement of multiplied children (lsys.components.place): Phiball against the sidebar
-- "Golden Section Placement on a Sphere" of Lintermann and Deussen 1999, worked by hand;
-- Hydra and Wreath; orthonormal frames; the error messages.
require "tests.helper"
local place = require "lsys.components.place"

local sqrt, deg, rad, sin, cos, pi = math.sqrt, math.deg, math.rad, math.sin, math.cos, math.pi

local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function len (a) return sqrt(dot(a, a)) end

-- H and U unit and orthogonal for every child; i and n as given.
local function orthonormal (list, n)
  assert.equal(n, #list)
  for i, c in ipairs(list) do
    assert.equal(i, c.i)
    assert.equal(n, c.n)
    assert.near(1, len(c.H), 1e-12)
    assert.near(1, len(c.U), 1e-12)
    assert.near(0, dot(c.H, c.U), 1e-12)
  end
end

local function colatitudes (list)
  local t = {}
  for i, c in ipairs(list) do t[i] = deg(c.theta) end
  return t
end

describe("phiball", function()
  it("sizes the sphere and places equal children by the sidebar's formulas", function()
    -- n = 4, theta1 = 0, theta2 = 90, A_E = 1: A_N = 4, cos 0 - cos 90 = 1,
    -- R = sqrt(4 / (2 pi)) = sqrt(0.6366197724) = 0.7978845608.
    -- Latitudes asin(1 - i/4): asin(0.75) = 48.5903778907, asin(0.5) = 30,
    -- asin(0.25) = 14.4775121859, asin(0) = 0; the colatitudes are 90 minus those.
    local list = place.phiball { n = 4 }
    orthonormal(list, 4)
    assert.near({ 41.4096221093, 60, 75.5224878141, 90 }, colatitudes(list), 1e-9)
    for _, c in ipairs(list) do
      assert.near(0.7978845608, c.radius, 1e-10)
      assert.near(0.7978845608, len(c.pos), 1e-10)
      assert.near({ c.pos[1] / c.radius, c.pos[2] / c.radius, c.pos[3] / c.radius }, c.H,
                  1e-12)
    end
    assert.near({ 0.25, 0.5, 0.75, 1 }, { list[1].fraction, list[2].fraction,
                                          list[3].fraction, list[4].fraction }, 1e-15)
    -- the second child, by hand: colatitude 60, azimuth 2 dPhi = 444.98447 - 360 = 84.98447
    local s, c = sin(rad(84.9844718999)), cos(rad(84.9844718999))
    assert.near({ 0.7978845608 * sin(rad(60)) * c, 0.7978845608 * sin(rad(60)) * s,
                  0.7978845608 * 0.5 }, list[2].pos, 1e-9)
  end)

  it("turns each child by the golden angle, 137.5078 degrees the other way", function()
    -- dPhi = 360 / 1.6180339887 = 222.4922359500 degrees = -137.5077640500 mod 360
    local list = place.phiball { n = 6 }
    assert.near({ 222.4922359500, 84.9844718999, 307.4767078499, 169.9689437998 },
                { deg(list[1].phi), deg(list[2].phi), deg(list[3].phi), deg(list[4].phi) },
                1e-9)
    for i = 2, 6 do
      local d = (deg(list[i].phi) - deg(list[i - 1].phi)) % 360
      assert.near(360 - 137.5077640500, d, 1e-9)
    end
  end)

  it("uses the section between open and close", function()
    -- n = 2, A_E = 2, theta1 = 30, theta2 = 120: cos 30 - cos 120 = 0.8660254038 + 0.5 =
    -- 1.3660254038; R = sqrt(4 / (2 pi 1.3660254038)) = sqrt(0.4660405...) = 0.6826697726.
    -- Child 1: 0.8660254038 - 0.5 * 1.3660254038 = 0.1830127019, latitude asin of it =
    -- 10.5452905895, colatitude 79.4547094105. Child 2 ends on theta2 = 120.
    local list = place.phiball { n = 2, area = 2, open = 30, close = 120 }
    orthonormal(list, 2)
    assert.near(0.6826697726, list[1].radius, 1e-10)
    assert.near({ 79.4547094105, 120 }, colatitudes(list), 1e-9)
    assert.near(0.6826697726, len(list[2].pos), 1e-10)
  end)

  it("places children of unequal sizes by their cumulative areas", function()
    -- sizes 1, 2, 1: A_N = 4, A_i / A_N = 1/4, 3/4, 1 -> cos theta = 0.75, 0.25, 0,
    -- colatitudes 41.4096221093, 75.5224878141, 90; R as for four equal children.
    local list = place.phiball { n = 3, sizes = { 1, 2, 1 } }
    orthonormal(list, 3)
    assert.near({ 41.4096221093, 75.5224878141, 90 }, colatitudes(list), 1e-9)
    assert.near({ 0.25, 0.75, 1 }, { list[1].fraction, list[2].fraction, list[3].fraction },
                1e-15)
    assert.near(0.7978845608, list[3].radius, 1e-10)
  end)

  it("blends equal and sized fractions by the influence", function()
    -- w = 0.5: f1 = 0.5 (1/3) + 0.5 (1/4) = 0.2916666667, f2 = 0.5 (2/3) + 0.5 (3/4) =
    -- 0.7083333333, f3 = 1; colatitudes acos(0.7083333333) = 44.9005279607,
    -- acos(0.2916666667) = 73.0422367000, 90.
    local list = place.phiball { n = 3, sizes = { 1, 2, 1 }, influence = 0.5 }
    assert.near({ 0.2916666667, 0.7083333333, 1 },
                { list[1].fraction, list[2].fraction, list[3].fraction }, 1e-10)
    assert.near({ 44.9005279607, 73.0422367000, 90 }, colatitudes(list), 1e-9)
    -- w = 0: the sizes only size the sphere; the children sit at i/n
    local eq = place.phiball { n = 3, sizes = { 1, 2, 1 }, influence = 0 }
    assert.near({ 1 / 3, 2 / 3, 1 }, { eq[1].fraction, eq[2].fraction, eq[3].fraction },
                1e-15)
  end)

  it("takes a given radius as it is", function()
    local list = place.phiball { n = 4, radius = 2 }
    assert.near({ 41.4096221093, 60, 75.5224878141, 90 }, colatitudes(list), 1e-9)
    for _, c in ipairs(list) do assert.near(2, len(c.pos), 1e-12) end
  end)

  it("points U along the meridian towards the pole", function()
    local list = place.phiball { n = 4 }
    -- on the equator U is +Z
    assert.near({ 0, 0, 1 }, list[4].U, 1e-12)
    for _, c in ipairs(list) do
      -- U = -d(pos)/d(theta) / R: its z is sin theta, its horizontal part points inwards
      assert.near(sin(c.theta), c.U[3], 1e-12)
      assert.near(-cos(c.theta), c.U[1] * cos(c.phi) + c.U[2] * sin(c.phi), 1e-12)
    end
  end)

  it("keeps frames orthonormal over a whole sphere and at the pole", function()
    orthonormal(place.phiball { n = 500, close = 180 }, 500)
    local tiny = place.phiball { n = 2, sizes = { 1e-300, 1 } }
    orthonormal(tiny, 2)
    assert.equal(0, tiny[1].theta)
    -- at the pole U is the meridian's limit, the radial direction turned inwards
    assert.near({ -cos(tiny[1].phi), -sin(tiny[1].phi), 0 }, tiny[1].U, 1e-12)
    local bottom = place.phiball { n = 3, open = 100, close = 180 }
    assert.near({ 0, 0, -1 }, bottom[3].H, 1e-12)
    orthonormal(bottom, 3)
  end)
end)

describe("hydra", function()
  it("spreads n children with equal gaps on a full circle", function()
    local list = place.hydra { n = 4, radius = 2 }
    orthonormal(list, 4)
    local want = { { 2, 0, 0 }, { 0, 2, 0 }, { -2, 0, 0 }, { 0, -2, 0 } }
    for i, c in ipairs(list) do
      assert.near(want[i], c.pos, 1e-12)
      -- angle 90: headings radial and level, U straight up
      assert.near({ want[i][1] / 2, want[i][2] / 2, 0 }, c.H, 1e-12)
      assert.near({ 0, 0, 1 }, c.U, 1e-12)
      assert.near(rad(90 * (i - 1)), c.phi, 1e-12)
    end
  end)

  it("uses both ends of a shorter arc and tilts the headings by angle", function()
    -- psi = 0, 45, 90; H = (sin 30 cos psi, sin 30 sin psi, cos 30);
    -- U = (-cos 30 cos psi, -cos 30 sin psi, sin 30)
    local list = place.hydra { n = 3, radius = 1, close = 90, angle = 30 }
    orthonormal(list, 3)
    local h = sqrt(0.5)
    assert.near({ { 1, 0, 0 }, { h, h, 0 }, { 0, 1, 0 } },
                { list[1].pos, list[2].pos, list[3].pos }, 1e-12)
    local s, c = 0.5, sqrt(3) / 2
    assert.near({ s, 0, c }, list[1].H, 1e-12)
    assert.near({ s * h, s * h, c }, list[2].H, 1e-12)
    assert.near({ 0, s, c }, list[3].H, 1e-12)
    assert.near({ -c * h, -c * h, s }, list[2].U, 1e-12)
    assert.near({ 0, -c, s }, list[3].U, 1e-12)
  end)

  it("puts a single child at open and defaults to the centre", function()
    local one = place.hydra { n = 1, open = 30, close = 90, radius = 1 }
    assert.near({ cos(rad(30)), sin(rad(30)), 0 }, one[1].pos, 1e-12)
    local c = place.hydra { n = 3 }
    orthonormal(c, 3)
    assert.near({ 0, 0, 0 }, c[2].pos, 0)
    assert.near({ cos(rad(120)), sin(rad(120)), 0 }, c[2].H, 1e-12)
    -- a full circle that does not start at 0
    local f = place.hydra { n = 2, open = 90, close = 450, angle = 0 }
    assert.near({ rad(90), rad(270) }, { f[1].phi, f[2].phi }, 1e-12)
    assert.near({ 0, 0, 1 }, f[2].H, 1e-12)
    assert.near({ 0, 1, 0 }, f[2].U, 1e-12)   -- towards the axis from azimuth 270
  end)
end)

describe("wreath", function()
  it("stands candles upright on a full circle", function()
    local list = place.wreath { n = 4 }
    orthonormal(list, 4)
    local want = { { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 } }
    for i, c in ipairs(list) do
      assert.near(want[i], c.pos, 1e-12)
      assert.near({ 0, 0, 1 }, c.H, 0)
      assert.near(want[i], c.U, 1e-12)
    end
  end)

  it("uses both ends of a 90-degree arc", function()
    local list = place.wreath { n = 3, radius = 3, open = -45, close = 45 }
    orthonormal(list, 3)
    local h = 3 * sqrt(0.5)
    assert.near({ { h, -h, 0 }, { 3, 0, 0 }, { h, h, 0 } },
                { list[1].pos, list[2].pos, list[3].pos }, 1e-12)
    assert.near({ sqrt(0.5), sqrt(0.5), 0 }, list[3].U, 1e-12)
  end)
end)

describe("placement errors", function()
  local nan, inf = 0 / 0, math.huge
  local cases = {
    { place.phiball, { n = 4, close = 200 },
      "phiball: 'close' must be a number in (open, 180], got 200" },
    { place.phiball, { n = 4, open = 90, close = 90 },
      "phiball: 'close' must be a number in (open, 180], got 90" },
    { place.phiball, { n = 4, open = -1 },
      "phiball: 'open' must be a number in [0, 180), got -1" },
    { place.phiball, { n = 4, open = nan },
      "phiball: 'open' must be a number in [0, 180), got nan" },
    { place.phiball, { n = 0 },
      "phiball: 'n' must be a positive integer (at most 1000000), got 0" },
    { place.phiball, { n = 2.5 },
      "phiball: 'n' must be a positive integer (at most 1000000), got 2.5" },
    { place.phiball, {}, "phiball: 'n' must be a positive integer (at most 1000000), got nil" },
    { place.phiball, { n = "4" },
      "phiball: 'n' must be a positive integer (at most 1000000), got '4'" },
    { place.phiball, { n = nan },
      "phiball: 'n' must be a positive integer (at most 1000000), got nan" },
    { place.phiball, { n = 1e7 },
      "phiball: 'n' must be a positive integer (at most 1000000), got 10000000" },
    { place.phiball, { n = 2, sizes = { 1 } }, "phiball: 'sizes' must list n = 2 areas, got 1" },
    { place.phiball, { n = 2, sizes = { 1, nan } },
      "phiball: 'sizes[2]' must be a positive finite number, got nan" },
    { place.phiball, { n = 2, sizes = { 0, 1 } },
      "phiball: 'sizes[1]' must be a positive finite number, got 0" },
    { place.phiball, { n = 2, sizes = { 1, inf } },
      "phiball: 'sizes[2]' must be a positive finite number, got inf" },
    { place.phiball, { n = 2, sizes = { 1e308, 1e308 } },
      "phiball: 'sizes' must sum to a finite number, got inf" },
    { place.phiball, { n = 2, sizes = "x" },
      "phiball: 'sizes' must be a list of n positive numbers, got 'x'" },
    { place.phiball, { n = 2, influence = 1.5 },
      "phiball: 'influence' must be a number in [0, 1], got 1.5" },
    { place.phiball, { n = 2, radius = 0 },
      "phiball: 'radius' must be a positive finite number, got 0" },
    { place.phiball, { n = 2, area = -inf },
      "phiball: 'area' must be a positive finite number, got -inf" },
    { place.phiball, { n = 1, foo = 1 },
      "phiball: unknown parameter 'foo' (known: area, close, influence, n, open, radius, sizes)" },
    { place.phiball, "x", "phiball: an options table expected, got 'x'" },
    { place.hydra, { n = 3, close = 400 },
      "hydra: 'close' must be a number in (open, open + 360], got 400" },
    { place.hydra, { n = 3, angle = 190 }, "hydra: 'angle' must be a number in [0, 180], got 190" },
    { place.hydra, { n = 3, radius = -1 }, "hydra: 'radius' must be a finite number >= 0, got -1" },
    { place.hydra, { n = 3, sizes = {} },
      "hydra: unknown parameter 'sizes' (known: angle, close, n, open, radius)" },
    { place.wreath, { n = 3, open = nan },
      "wreath: 'open' must be a number in [-360, 360], got nan" },
    { place.wreath, { n = 3, close = -10 },
      "wreath: 'close' must be a number in (open, open + 360], got -10" },
    { place.wreath, { n = 3, radius = nan },
      "wreath: 'radius' must be a finite number >= 0, got nan" },
  }
  for k, case in ipairs(cases) do
    it("rejects case " .. k .. ": " .. case[3], function()
      assert.has_error(function() case[1](case[2]) end, case[3])
    end)
  end

  it("exports the divergence angle dPhi = 2 pi / golden", function()
    assert.near(2 * pi / ((1 + sqrt(5)) / 2), place.DPHI, 1e-15)
  end)
end)
