-- Plots of positional functions and drawings of sketches (lsys.sketch.plot, docs/sketch.md
-- "Plots"): the panels (6, or 7 with pitch), where the curve of a known function must put
-- its pixels, the stem's colour by pen pressure (Anastacio et al. 2009, §7.3), PNG output
-- and the errors.
local H = require "tests.helper"
local plot = require "lsys.sketch.plot"

local CURVE = { 0x1f, 0x5f, 0xa8 }             -- plot.COLORS.curve

local function px (c, i, j)
  local w = c:size()
  local k = (j * w + i) * 4
  return { c:pixels():byte(k + 1, k + 3) }
end

local function const (v) return function () return v end end

-- Six functions; `extra` adds or replaces some.
local function funcs (extra)
  local f = { internode = const(0.05), stem_shape = function (x) return 10 * x end,
              angle_left = const(60), angle_right = const(45),
              size_left = function (x) return x end, size_right = const(0.25) }
  for k, v in pairs(extra or {}) do f[k] = v end
  return f
end

local function find (panels, key)
  for _, p in ipairs(panels) do if p.key == key then return p end end
end

describe("lsys.sketch.plot.functions", function ()
  it("draws six panels in two columns of three rows", function ()
    local c, panels = plot.functions(funcs())
    assert.same({ 800, 900 }, { c:size() })
    assert.equal(6, #panels)
    local keys = {}
    for i, p in ipairs(panels) do keys[i] = p.key end
    assert.same({ "internode", "stem_shape", "angle_left", "angle_right", "size_left",
                  "size_right" }, keys)
    assert.equal(panels[1].y, panels[2].y)       -- a row
    assert.equal(panels[1].x, panels[3].x)       -- a column
    assert.is_true(panels[3].y > panels[1].y and panels[2].x > panels[1].x)
  end)

  it("draws seven panels with pitch, yaw in place of the stem shape", function ()
    local f = funcs { pitch = const(5), yaw = const(3) }
    f.stem_shape = nil
    local c, panels = plot.functions(f, { width = 600 })
    assert.same({ 600, 1200 }, { c:size() })
    assert.equal(7, #panels)
    assert.equal("yaw", panels[2].key)
    assert.equal("pitch", panels[7].key)
    assert.matches("^2  yaw", panels[2].title)
    assert.matches("^7  pitch", panels[7].title)
  end)

  it("puts a constant along the middle of its panel", function ()
    local c, panels = plot.functions(funcs())
    local p = find(panels, "size_right")
    assert.near({ 0.225, 0.275 }, { p.ymin, p.ymax }, 1e-12)   -- 0.25 padded by a tenth
    local mid = p.y + p.h / 2
    local col = math.floor(p.x + p.w * 0.37)
    for row = p.y + 1, p.y + p.h - 2 do
      local on = px(c, col, row)[1] == CURVE[1] and px(c, col, row)[3] == CURVE[3]
      assert.equal(math.abs(row + 0.5 - mid) < 1, on, "row " .. row)
    end
  end)

  it("draws y = x through the points the axes give", function ()
    local c, panels = plot.functions(funcs())
    local p = find(panels, "size_left")
    assert.near({ -0.08, 1.08 }, { p.ymin, p.ymax }, 1e-12)
    for _, x0 in ipairs { 0.2, 0.5, 0.8 } do
      -- at a pixel centre X, the curve (width 2) is within 0.5 of the centre of its row
      local X = math.floor(p.x + x0 * p.w) + 0.5
      local x = (X - p.x) / p.w
      local Y = p.y + p.h - (x - p.ymin) / (p.ymax - p.ymin) * p.h
      assert.same(CURVE, px(c, math.floor(X), math.floor(Y)))
      assert.are_not.same(CURVE, px(c, math.floor(X), math.floor(Y) - 6))
      assert.are_not.same(CURVE, px(c, math.floor(X), math.floor(Y) + 6))
    end
  end)

  it("puts the x grid at fifths when their labels fit, at halves in narrow panels", function ()
    local function hex (c, i, j)
      return string.format("#%02x%02x%02x", table.unpack(px(c, i, j)))
    end
    local grid = plot.COLORS.grid
    for _, case in ipairs { { 900, 5 }, { 250, 2 } } do
      local c, panels = plot.functions(funcs(), { width = case[1] })
      local p = find(panels, "internode")
      local row = p.y + 3                       -- above the curve (it lies in the middle)
      for k = 1, 4 do
        assert.equal(case[2] == 5, hex(c, math.floor(p.x + k / 5 * p.w), row) == grid, k)
      end
      assert.equal(case[2] == 2, hex(c, math.floor(p.x + 0.5 * p.w), row) == grid)
    end
  end)

  it("draws control points and a marker when asked", function ()
    local f = funcs { angle_left = { eval = function (x) return 40 + 30 * x end,
                                     points = { { 0, 40 }, { 0.5, 55 }, { 1, 70 } } } }
    local c, panels = plot.functions(f, { marker = (math.floor(0.25 * 280) + 0.5) / 280 })
    local p = find(panels, "angle_left")
    assert.equal(280, p.w)                   -- the marker above is at a pixel centre
    local Y = p.y + p.h - (55 - p.ymin) / (p.ymax - p.ymin) * p.h
    assert.same({ 0xd8, 0x62, 0x2a }, px(c, math.floor(p.x + 0.5 * p.w), math.floor(Y)))
    local q = find(panels, "angle_right")
    assert.same({ 0xc0, 0x20, 0x3a }, px(c, math.floor(q.x + 0.25 * q.w), q.y + 5))
    local c2 = plot.functions(f, { points = false })
    assert.are_not.same({ 0xd8, 0x62, 0x2a },
                        px(c2, math.floor(p.x + 0.5 * p.w), math.floor(Y)))
  end)

  it("plots Funcs (core.func) with their control points", function ()
    local core = require "lsys.core"
    -- collinear control points: the clamped cubic B-spline is the line y = x
    local line = core.func({ { 0, 0 }, { 1 / 3, 1 / 3 }, { 2 / 3, 2 / 3 }, { 1, 1 } },
                           { name = "size_left" })
    local c, panels = plot.functions(funcs { size_left = line })
    local p = find(panels, "size_left")
    assert.near({ -0.08, 1.08 }, { p.ymin, p.ymax }, 1e-9)
    local function at (x, y)
      return px(c, math.floor(p.x + x * p.w), math.floor(p.y + p.h - (y - p.ymin) /
                (p.ymax - p.ymin) * p.h))
    end
    assert.same({ 0xd8, 0x62, 0x2a }, at(1 / 3, 1 / 3))        -- a control point's dot
    assert.same({ 0xd8, 0x62, 0x2a }, at(2 / 3, 2 / 3))
    assert.are_not.same({ 0xd8, 0x62, 0x2a }, at(0.5, 0.5))   -- the curve between them
  end)

  it("draws into a region of a given canvas", function ()
    local core = require "lsys.core"
    local c = core.canvas(1000, 700, "#000000")
    local c2, panels = plot.functions(funcs(), { canvas = c, region = { 200, 100, 800, 600 } })
    assert.equal(c, c2)
    assert.same({ 0, 0, 0 }, px(c, 150, 50))
    assert.same({ 255, 255, 255 }, px(c, 201, 101))
    assert.is_true(panels[1].x > 200 and panels[1].y > 100)
  end)

  it("raises clear errors for bad input", function ()
    local f = funcs()
    f.angle_right = nil
    assert.error_contains(function () plot.functions(f) end, "no angle_right (panel 4)")
    f = funcs()
    f.stem_shape = nil
    assert.error_contains(function () plot.functions(f) end, "no stem_shape or yaw (panel 2)")
    assert.error_contains(function () plot.functions(funcs { internode = 3 }) end,
      "funcs.internode must be a function")
    assert.error_contains(function ()
      plot.functions(funcs { size_left = function () return "big" end })
    end, "function size_left returned string at x = 0")
    assert.error_contains(function ()
      plot.functions(funcs { size_left = function () error("boom") end })
    end, "function size_left failed at x = 0", "boom")
    assert.error_contains(function () plot.functions(funcs(), { colour = 1 }) end,
      "unknown option 'colour'")
    assert.error_contains(function () plot.functions("x") end, "funcs must be a table")
  end)

  it("draws NaN values as gaps, not errors", function ()
    local c, panels = plot.functions(funcs { size_left = function (x)
      if x > 0.4 and x < 0.6 then return 0 / 0 end
      return x
    end })
    local p = find(panels, "size_left")
    assert.near({ -0.08, 1.08 }, { p.ymin, p.ymax }, 1e-12)
    local X = p.x + 0.5 * p.w
    local Y = p.y + p.h - (0.5 - p.ymin) / (p.ymax - p.ymin) * p.h
    assert.are_not.same(CURVE, px(c, math.floor(X), math.floor(Y)))
  end)
end)

describe("lsys.sketch.plot.png", function ()
  it("writes the plot of a functions table or of a Sketch", function ()
    local dir = H.tmpdir()
    local core = require "lsys.core"
    plot.png(funcs(), dir .. "/f.png", { width = 400, height = 450 })
    assert.same({ 400, 450 }, { core.texture_load(dir .. "/f.png"):size() })
    local sketch = { functions = function () return funcs { pitch = const(1) } end }
    local _, panels = plot.png(sketch, dir .. "/g.png")
    assert.equal(7, #panels)
    assert.error_contains(function () plot.png(funcs(), dir .. "/no/dir/f.png") end,
      "lsys.sketch.plot.png", "no/dir/f.png")
    H.rmdir(dir)
  end)
end)

describe("lsys.sketch.plot.sketch", function ()
  local core = require "lsys.core"
  local sk = {
    width = 100, height = 200,
    strokes = {
      { role = "stem", points = { { 50, 190, 0.5 }, { 50, 100, 0.5 }, { 50, 60, 1 },
                                  { 50, 20, 1 } } },
      { role = "boundary_left", points = { { 40, 190 }, { 10, 100 }, { 40, 10 } } },
      { role = "boundary_right", points = { { 60, 190 }, { 90, 100 }, { 60, 10 } } },
      { role = "inclination", points = { { 5, 150 }, { 95, 150 } } },
      { role = "inclination", points = { { 5, 50 }, { 95, 50 } } },
    },
  }

  it("scales the sketch uniformly into the canvas and colours the stem by pressure", function ()
    local c = core.canvas(300, 300)
    local m = plot.sketch(sk, c)
    assert.near({ 1.4, 10 + (280 - 200 * 1.4) / 2 }, { m.scale, m.y }, 1e-12)
    assert.near(150 - 50 * 1.4, m.x, 1e-12)
    local function at (u, v)
      return px(c, math.floor(m.x + u * m.scale), math.floor(m.y + v * m.scale))
    end
    assert.same({ 0x6b, 0x4a, 0x2b }, at(50, 130))           -- pressure 0.5: the stem colour
    assert.same({ 0x6b, 0x4a, 0x2b }, at(50, 150))           -- drawn over the inclination
    assert.same({ 0x1a, 0x0f, 0x05 }, at(50, 40))            -- pressure 1: the nearest colour
    assert.same({ 0x3a, 0x6f, 0xc4 }, at(80, 150))           -- an inclination line
    assert.same({ 0x2e, 0x8b, 0x3e }, at(10, 100))           -- the left boundary
    assert.same({ 255, 255, 255 }, at(25, 180))
  end)

  it("mixes the depth colours linearly", function ()
    local c = plot.depth_color(0.75)
    local s, n = { 0x6b, 0x4a, 0x2b }, { 0x1a, 0x0f, 0x05 }
    for i = 1, 3 do assert.near((s[i] + n[i]) / 2 / 255, c[i], 1e-12) end
    local f = plot.depth_color(0)
    assert.near({ 0xe4 / 255, 0xd4 / 255, 0xc2 / 255, 1 }, f, 1e-12)
  end)

  it("draws the nodes and rays of an analysis", function ()
    local c = core.canvas(300, 300)
    local v = 210.5 / 1.4                     -- drawn at y = 10 + v * 1.4, a pixel centre
    local an = { nodes = { { px = { 50, v }, hit_left = { 20, v }, hit_right = { 80, v } } } }
    local m = plot.sketch(sk, c, { analysis = an })
    local node = px(c, math.floor(m.x + 50 * m.scale), math.floor(m.y + v * m.scale))
    assert.same({ 0xc0, 0x20, 0x3a }, node)
    local ray = px(c, math.floor(m.x + 70 * m.scale), math.floor(m.y + v * m.scale))
    assert.same({ 0xe0, 0x8a, 0x3a }, ray)
  end)

  it("names a stroke with an unknown role", function ()
    local bad = { width = 10, height = 10, strokes = { { role = "stem", points = {} },
                                                       { role = "twig", points = {} } } }
    assert.error_contains(function () plot.sketch(bad, core.canvas(50, 50)) end,
      "stroke 2 (twig): unknown role")
    assert.error_contains(function () plot.sketch({ width = 0, height = 5, strokes = {} },
      core.canvas(50, 50)) end, "width and height must be positive")
  end)
end)
