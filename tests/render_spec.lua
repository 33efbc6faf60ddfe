-- Headless rendering (lsys.render through OSMesa): PNG output, pixels, camera options,
-- anti-aliasing, option errors, and golden images.
--
-- Tagged #gl: `busted --exclude-tags=gl` leaves it out. Pending when lsys was built
-- without OSMesa.
--
-- Golden images live in tests/golden/. After an intended change to the turtle or the
-- renderer, look at the new pictures and write them with
--
--   LSYS_UPDATE_GOLDEN=1 lua5.4 /usr/bin/busted tests/render_spec.lua
--
-- A render matches its golden image when the mean absolute difference of every channel is
-- below 2 (of 255) and fewer than 1% of the pixels differ by more than 40 in some channel,
-- which absorbs rasteriser rounding but not a moved, mirrored or recoloured plant.
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local GOLDEN_DIR = H.GOLDEN_DIR       -- the comparison: H.compare_images (tests/helper.lua)

-- Pixel access on RGBA strings (top row first), x and y from 0.
local function pixel (px, w, x, y)
  local o = (y * w + x) * 4
  return px:byte(o + 1, o + 4)
end

-- Number of pixels in the rectangle [x0, x1] x [y0, y1] that differ from 'bg' (4 bytes).
local function count (px, w, h, bg, x0, y0, x1, y1)
  local n = 0
  for y = y0 or 0, y1 or h - 1 do
    for x = x0 or 0, x1 or w - 1 do
      local o = (y * w + x) * 4
      if px:sub(o + 1, o + 4) ~= bg then n = n + 1 end
    end
  end
  return n
end

-- Bounding box {xmin, ymin, xmax, ymax} of the pixels that differ from 'bg' (nil: none).
local function bbox (px, w, h, bg)
  local x0, y0, x1, y1 = w, h, -1, -1
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local o = (y * w + x) * 4
      if px:sub(o + 1, o + 4) ~= bg then
        if x < x0 then x0 = x end
        if x > x1 then x1 = x end
        if y < y0 then y0 = y end
        if y > y1 then y1 = y end
      end
    end
  end
  if x1 < 0 then return nil end
  return { x0, y0, x1, y1 }
end

-- The distinct pixel values of an image: a set of 4-byte strings, and how many there are.
local function colours (px)
  local set, n = {}, 0
  for o = 1, #px, 4 do
    local p = px:sub(o, o + 3)
    if not set[p] then set[p], n = true, n + 1 end
  end
  return set, n
end

-- The image mirrored left to right.
local function mirror (px, w, h)
  local rows = {}
  for y = 0, h - 1 do
    local row = {}
    for x = w - 1, 0, -1 do
      local o = (y * w + x) * 4
      row[#row + 1] = px:sub(o + 1, o + 4)
    end
    rows[#rows + 1] = table.concat(row)
  end
  return table.concat(rows)
end

local compare = H.compare_images

-- Renders model source pieces to pixels (w x h, default 64 x 64) with render options 'opts'.
local function draw (axiom, view, opts, productions)
  local m = lsys.lsystem { axiom = axiom, view = view, productions = productions }
  local o = { width = 64, height = 64 }
  for k, v in pairs(opts or {}) do o[k] = v end
  return lsys.render(m, o)
end

local tmpdir = H.tmpdir

describe("rendering #gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa (install libosmesa6-dev and rebuild): "
      .. "rendering specs skipped")
    return
  end

  local dir
  setup(function() dir = tmpdir() end)
  teardown(function() os.execute("rm -rf '" .. dir .. "'") end)

  -- the default background, {0.93, 0.96, 1.0}, as the renderer writes it
  local BG = string.char(237, 245, 255, 255)

  describe("PNG output", function()
    it("writes a PNG that is not blank and shows the plant's colour", function()
      local m = lsys.lsystem {
        axiom = "F", steps = 4, productions = "F --> F[+F]F[-F]F",
        view = { angle = 25.7, line_width = 3, color = 8 },
      }
      local path = dir .. "/plant.png"
      assert.is_true(lsys.render(m, { out = path, width = 128, height = 96 }))
      local px, w, h = core.png_read(path)
      assert.equal(128, w)
      assert.equal(96, h)
      assert.equal(128 * 96 * 4, #px)
      assert.same({ 237, 245, 255, 255 }, { pixel(px, w, 0, 0) })
      local drawn = count(px, w, h, BG)
      assert.is_true(drawn > 0.02 * w * h and drawn < 0.5 * w * h,
        "pixels differing from the background: " .. drawn)
      -- palette colour 8 (0.13, 0.34, 0.12) where a line covers a whole pixel; lines are unlit
      local green = 0
      for y = 0, h - 1 do
        for x = 0, w - 1 do
          local r, g, b = pixel(px, w, x, y)
          if math.abs(r - 33) <= 2 and math.abs(g - 87) <= 2 and math.abs(b - 31) <= 2 then
            green = green + 1
          end
        end
      end
      assert.is_true(green > 0.25 * drawn, ("%d of %d drawn pixels are the plant's green")
        :format(green, drawn))
    end)

    it("returns the pixels, width and height without 'out', the same as the PNG holds", function()
      local m = lsys.lsystem { axiom = "F+F+F", view = { angle = 120, line_width = 2 } }
      local px, w, h = lsys.render(m, { width = 50, height = 30 })
      assert.equal("string", type(px))
      assert.equal(50, w)
      assert.equal(30, h)
      assert.equal(50 * 30 * 4, #px)
      local path = dir .. "/triangle.png"
      lsys.render(m, { out = path, width = 50, height = 30 })
      local fpx, fw, fh = core.png_read(path)
      assert.equal(50, fw)
      assert.equal(30, fh)
      assert.is_true(fpx == px, "the PNG file and the returned pixels differ")
    end)

    it("renders a Scene, 800 x 800 by default", function()
      local m = lsys.lsystem { axiom = "F" }
      local px, w, h = lsys.render(m:interpret(), { supersample = 1 })
      assert.equal(800, w)
      assert.equal(800, h)
      assert.equal(800 * 800 * 4, #px)
    end)

    it("fills the background with the view's colour", function()
      local px, w, h = draw("F", { background = { 1, 0, 0 } })
      for _, c in ipairs { { 0, 0 }, { w - 1, 0 }, { 0, h - 1 }, { w - 1, h - 1 } } do
        assert.same({ 255, 0, 0, 255 }, { pixel(px, w, c[1], c[2]) })
      end
      -- a render option replaces the model's background
      px = draw("F", { background = { 1, 0, 0 } }, { background = "#0000ff" })
      assert.same({ 0, 0, 255, 255 }, { pixel(px, w, 0, 0) })
    end)
  end)

  describe("camera", function()
    it("puts a vertical line in the middle columns in parallel projection", function()
      local px, w, h = draw("F", nil, { projection = "parallel" })
      local b = bbox(px, w, h, BG)
      assert.is_true(b[1] >= 31 and b[3] <= 32, ("columns %d..%d"):format(b[1], b[3]))
      assert.is_true(b[4] - b[2] > 0.8 * h, ("rows %d..%d"):format(b[2], b[4]))
    end)

    it("turns the picture anticlockwise by 'twist' degrees", function()
      local px, w, h = draw("F", nil, { twist = 90 })
      local b = bbox(px, w, h, BG)
      assert.is_true(b[2] >= 31 and b[4] <= 32, ("rows %d..%d"):format(b[2], b[4]))
      assert.is_true(b[3] - b[1] > 0.8 * w, ("columns %d..%d"):format(b[1], b[3]))
      -- F[-F] is drawn as a corner: a stem up the left side, then an arm along the top.
      -- Turned a quarter anticlockwise, the stem lies along the bottom and the arm goes up
      -- the left side.
      local plain = draw("F[-F]")
      assert.is_true(count(plain, w, h, BG, 0, 0, w - 1, 5) > 40, "arm along the top")
      assert.is_true(count(plain, w, h, BG, 0, 0, 5, h - 1) > 40, "stem up the left side")
      assert.is_true(count(plain, w, h, BG, 0, h - 6, w - 1, h - 1) < 12, "only the stem's foot")
      local turned = draw("F[-F]", nil, { twist = 90 })
      assert.is_true(count(turned, w, h, BG, 0, h - 6, w - 1, h - 1) > 40, "stem along the bottom")
      assert.is_true(count(turned, w, h, BG, 0, 0, 5, h - 1) > 40, "arm up the left side")
      assert.is_true(count(turned, w, h, BG, 0, 0, w - 1, 5) < 12, "only the arm's end")
    end)

    it("points the picture's up along 'up'", function()
      -- with +x up, the scene turns a quarter anticlockwise: the same picture as twist = 90
      local w, h = 64, 64
      local up = draw("F[-F]", nil, { up = { 1, 0, 0 } })
      local turned = draw("F[-F]", nil, { twist = 90 })
      assert.truthy(compare(up, turned, w, h))
      assert.falsy(compare(up, draw("F[-F]"), w, h))
    end)

    it("looks from 'viewpoint' at 'target'", function()
      -- from the +x axis, the arm along x of F[-F] is seen end-on: only the stem is left
      local px, w, h = draw("F[-F]", nil, { viewpoint = { 10, 0.5, 0 }, target = { 0, 0.5, 0 } })
      local b = bbox(px, w, h, BG)
      assert.is_true(b[3] - b[1] <= 3, ("columns %d..%d"):format(b[1], b[3]))
      assert.is_true(b[4] - b[2] > 0.8 * h, ("rows %d..%d"):format(b[2], b[4]))
      -- from the other side of +z, the corner is mirrored: the arm goes to the left
      px = draw("F[-F]", nil, { viewpoint = { 0.5, 0.5, -10 }, target = { 0.5, 0.5, 0 } })
      assert.is_true(count(px, w, h, BG, 0, 0, w - 1, 5) > 40, "top arm")
      assert.is_true(count(px, w, h, BG, w - 6, 0, w - 1, h - 1) > 40, "right stem")
      assert.equal(0, count(px, w, h, BG, 0, 8, 5, h - 1), "no stem on the left")
    end)

    -- the vertical extent, in rows, of what is drawn in columns x0..x1
    local function height (px, w, h, x0, x1)
      local y0, y1 = h, -1
      for y = 0, h - 1 do
        if count(px, w, h, BG, x0, y, x1, y) > 0 then
          if y < y0 then y0 = y end
          y1 = y
        end
      end
      return y1 - y0 + 1
    end

    it("shrinks distant lines in perspective and not in parallel projection", function()
      -- two unit lines side by side; the right one 6 units further away
      local opts = { width = 96, height = 96 }
      opts.projection = "parallel"
      local px, w, h = draw("F @M(2,0,-6) F", { line_width = 2 }, opts)
      local near, far = height(px, w, h, 0, 47), height(px, w, h, 48, 95)
      assert.is_true(math.abs(near - far) <= 1, ("parallel: %d and %d rows"):format(near, far))
      opts.projection = "perspective"
      px = draw("F @M(2,0,-6) F", { line_width = 2 }, opts)
      near, far = height(px, w, h, 0, 47), height(px, w, h, 48, 95)
      assert.is_true(far < 0.85 * near, ("perspective: %d and %d rows"):format(near, far))
    end)
  end)

  describe("supersampling", function()
    it("blends edge pixels with the background, and supersample = 1 does not", function()
      local line = string.char(107, 74, 46, 255)     -- palette colour 1, unlit
      local px = draw("+(30) F", nil, { supersample = 1 })
      local set, n = colours(px)
      assert.equal(2, n)
      assert.truthy(set[BG])
      assert.truthy(set[line])
      px = draw("+(30) F", nil, { supersample = 3 })
      set, n = colours(px)
      assert.is_true(n > 3, n .. " colours")
      local between = 0
      for p in pairs(set) do
        local r, g, b = p:byte(1, 3)
        if r > 107 and r < 237 and g > 74 and g < 245 and b > 46 and b < 255 then
          between = between + 1
        end
      end
      assert.is_true(between >= 2, between .. " intermediate colours")
    end)
  end)

  describe("errors", function()
    local m = lsys.lsystem { axiom = "F" }

    it("names a bad size", function()
      assert.has_error(function() lsys.render(m, { width = -5 }) end,
        "lsys.render: opts.width must be a positive integer at most 16384, got -5")
      assert.has_error(function() lsys.render(m, { height = 2.5 }) end,
        "lsys.render: opts.height must be a positive integer at most 16384, got 2.5")
    end)

    it("names an unknown option", function()
      assert.has_error(function() lsys.render(m, { widht = 10 }) end,
        "lsys.render: unknown option 'widht' (did you mean 'width'?)")
      assert.has_error(function() lsys.render(m, { colour = 10 }) end,
        "lsys.render: unknown option 'colour' (did you mean 'color'?)")    -- a view option
      assert.has_error(function() lsys.render(m, { size = 10 }) end,
        "lsys.render: unknown option 'size'")
    end)

    it("names a bad view option", function()
      assert.error_contains(function() lsys.render(m, { projection = "fisheye" }) end,
        "'view.projection' must be \"parallel\" or \"perspective\"")
      assert.error_contains(function() lsys.render(m, { supersample = 0 }) end,
        "'view.supersample' must be from 1 to 8")
      assert.error_contains(function() lsys.render(m, { background = { 2, 0, 0 } }) end,
        "'view.background'[1] must be a number from 0 to 1")
    end)

    it("names a file it cannot write", function()
      local path = dir .. "/no/such/dir/x.png"
      assert.error_contains(function() lsys.render(m, { out = path, width = 8, height = 8 }) end,
        "lsys.render: cannot open '" .. path .. "' for writing")
    end)

    it("wants a Scene, a Model or a component prototype", function()
      assert.has_error(function() lsys.render("F", {}) end,
        "lsys.render: a Scene, a Model or a component prototype expected")
      -- a component graph's root is drawn as C.model(root) draws it
      local C = lsys.components
      local root = C.simple { primitive = "sphere" }
      local a = lsys.render(root, { width = 16, height = 16 })
      local b = lsys.render(C.model(root), { width = 16, height = 16 })
      assert.equal(b, a)
    end)
  end)

  describe("golden images", function()
    local GOLDEN = {
      { name = "fig1_24a", w = 128, h = 128,
        -- ABOP 1.24a in line style
        scene = function()
          return lsys.lsystem {
            axiom = "F", steps = 5, productions = "F --> F[+F]F[-F]F",
            view = { angle = 25.7, line_width = 1, color = 8 },
          }:interpret()
        end },
      { name = "koch_island", w = 128, h = 128,
        -- ABOP 1.6 at n = 2, 1.5-pixel lines
        scene = function()
          return lsys.lsystem {
            axiom = "F-F-F-F", steps = 2, productions = "F --> F-F+F+FF-F-F+F",
            view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
          }:interpret()
        end },
      { name = "default_tree_n5", w = 160, h = 160,
        -- examples/default.lua derived 5 steps: cylinders, leaf polygons, perspective
        scene = function()
          local m = dofile("examples/default.lua")
          return m:interpret(m:derive(5), { line_style = "cylinder" })
        end },
      { name = "polygon_leaf", w = 128, h = 128,
        -- a petiole ribbon and a rolled, raised leaf blade in polygon style
        scene = function()
          return lsys.lsystem {
            axiom = "!(0.6) F(4) ;(2) \\(40) ^(30) "
              .. "{ . -(30) f(5) . +(18) f(5) . +(150) f(5) . +(18) f(5) . }",
            view = { line_style = "polygon" },
          }:interpret()
        end },
    }

    for _, g in ipairs(GOLDEN) do
      local path = GOLDEN_DIR .. "/" .. g.name .. ".png"
      it("matches " .. path, function()
        local px, w, h = lsys.render(g.scene(), { width = g.w, height = g.h })
        H.golden(g.name, px, w, h)
      end)

      it("tells " .. g.name .. " from its mirror image", function()
        local gpx, w, h = core.png_read(path)
        assert.falsy(compare(mirror(gpx, w, h), gpx, w, h))
      end)
    end
  end)
end)

describe("render-only options #gl", function()
  it("passes zoom, transparent and wireframe through lsys.render", function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local m = lsys.lsystem { view = { line_style = "cylinder", background = { 1, 1, 1 } } }
    local sc = m:interpret("F")
    local px = lsys.render(sc, { width = 32, height = 32, transparent = true, supersample = 1 })
    assert.equal(0, px:byte(4))                                   -- corner alpha
    local full = lsys.render(sc, { width = 32, height = 32, supersample = 1 })
    local zoomed = lsys.render(sc, { width = 32, height = 32, supersample = 1, zoom = 2 })
    local function ndark (p)
      local n = 0
      for i = 1, #p, 4 do if p:byte(i) < 200 then n = n + 1 end end
      return n
    end
    assert.is_true(ndark(zoomed) > ndark(full))
    assert.has_no.errors(function ()
      lsys.render(sc, { width = 16, height = 16, wireframe = true })
    end)
  end)
end)

describe("the scene's look #gl", function()
  local m = lsys.lsystem { axiom = "F[+F]F[-F]F", view = { angle = 30, line_width = 3 } }
  local o = { width = 48, height = 48, supersample = 1 }

  it("comes from the view schema's defaults when the options say nothing", function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    -- one owner of the defaults: a scene made without view fields (the core's own
    -- defaults, scene.c) looks exactly like one made with the schema's
    local v = lsys.view.normalize(m.view)
    local s = m:derive()
    local bare = core.interpret(m._rules, s, { angle = 30, line_width = 3,
                                              palette = v.palette })
    local viewed = core.interpret(m._rules, s, lsys.view.turtle_options(v))
    assert.equal(core.render(viewed, o), core.render(bare, o))
    local px = core.render(bare, o)
    assert.same({ 237, 245, 255 }, { px:byte(1, 3) })           -- the pale sky background
  end)

  it("is kept by the scene, and lsys.render's view fields replace it for one picture", function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local sc = m:interpret(nil, { background = { 0, 0, 0 } })
    assert.same({ 0, 0, 0 }, { core.render(sc, o):byte(1, 3) })  -- the scene's own
    assert.same({ 0, 0, 0 }, { lsys.render(sc, o):byte(1, 3) })
    local red = lsys.render(sc, { width = 48, height = 48, supersample = 1,
                                  background = { 1, 0, 0 } })
    assert.same({ 255, 0, 0 }, { red:byte(1, 3) })
    assert.same({ 0, 0, 0 }, { lsys.render(sc, o):byte(1, 3) })  -- for that picture only
    -- raw: each look field given replaces the scene's
    assert.same({ 0, 255, 0 }, { core.render(sc, { width = 8, height = 8,
                                                   background = { 0, 1, 0 } }):byte(1, 3) })
  end)

  it("keeps a look given in C (scene:look) when lsys.render names other view fields",
     function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    -- a grown world's scene and one turned by scene:look have no Lua view: supersample (or
    -- a background) for one picture used to put the default camera back
    local sc = core.interpret(m._rules, m:derive(), { angle = 30, line_width = 3 })
    sc:look { background = { 0, 0, 0 }, direction = { 1, 0, 0 } }   -- the plant edge-on
    local looked = core.render(sc, o)
    assert.is_true(looked == lsys.render(sc, o))
    local red = lsys.render(sc, { width = 48, height = 48, supersample = 1,
                                  background = { 1, 0, 0 } })
    -- the same pixels but the background's: the camera stayed
    local n = 0
    for i = 0, 48 * 48 - 1 do
      local a, b = looked:sub(4 * i + 1, 4 * i + 3), red:sub(4 * i + 1, 4 * i + 3)
      if a ~= b and not (a == "\0\0\0" and b == "\255\0\0") then n = n + 1 end
    end
    assert.is_true(n < 48, n .. " pixels differ beyond the background")
  end)
end)

describe("textures #gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa: texture rendering specs skipped")
    return
  end
  local dir, checker
  -- the 2 x 2 checker, top row first: red green / blue white
  local TEXELS = { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 255, 255, 255 } }
  setup(function()
    dir = tmpdir()
    checker = dir .. "/checker.png"
    local t = {}
    for i, c in ipairs(TEXELS) do t[i] = string.char(c[1], c[2], c[3], 255) end
    core.png_write(checker, table.concat(t), 2, 2, false)
  end)
  teardown(function() os.execute("rm -rf '" .. dir .. "'") end)

  -- a white unit square drawn as a polygon heading up, 64 x 64 without supersampling
  local function square (axiom, textures)
    return draw(axiom or "@Tx(1) { f + f + f + f }",
      { angle = 90, palette = { { 1, 1, 1 } }, textures = textures }, { supersample = 1 })
  end
  -- the centres of the square's quadrants in the picture: top left, top right, bottom left,
  -- bottom right (the square fills 90% of the image)
  local QUAD = { { 18, 18 }, { 45, 18 }, { 18, 45 }, { 45, 45 } }

  it("maps the image upright onto a polygon; decal shows the texels themselves", function()
    local px = square(nil, { { file = checker, mode = "decal" } })
    for k, q in ipairs(QUAD) do
      assert.same({ TEXELS[k][1], TEXELS[k][2], TEXELS[k][3], 255 }, { pixel(px, 64, q[1], q[2]) })
    end
  end)

  it("multiplies the lit colour by the texel in modulate mode", function()
    local plain = square("{ f + f + f + f }")
    local lit = { pixel(plain, 64, 32, 32) }
    assert.is_true(lit[1] > 100 and lit[1] < 250)
    local px = square(nil, { checker })
    for k, q in ipairs(QUAD) do
      local got = { pixel(px, 64, q[1], q[2]) }
      for c = 1, 3 do assert.near(lit[c] * TEXELS[k][c] / 255, got[c], 2) end
    end
  end)

  it("modulates by intensity with a grey texture: I = 0.299 R + 0.587 G + 0.114 B", function()
    local lit = pixel(square("{ f + f + f + f }"), 64, 32, 32)
    local px = square(nil, { { file = checker, intensity = true } })
    for k, q in ipairs(QUAD) do
      local r, g, b = pixel(px, 64, q[1], q[2])
      local I = math.floor(0.299 * TEXELS[k][1] + 0.587 * TEXELS[k][2] + 0.114 * TEXELS[k][3]
                           + 0.5)
      assert.near(lit * I / 255, r, 2)
      assert.equal(r, g)
      assert.equal(g, b)
    end
  end)

  it("draws untextured geometry exactly as without textures", function()
    local with = square("{ f + f + f + f } @Tx(0) { f - f - f - f }", { checker })
    assert.equal(square("{ f + f + f + f } { f - f - f - f }"), with)
  end)

  it("wraps a stem in cylinder style, repeating along it", function()
    local m = lsys.lsystem { axiom = "@Tx(1) F(12)",
      view = { line_style = "cylinder", palette = { { 1, 1, 1 } },
               textures = { { file = checker, mode = "decal" } } } }
    local px, w, h = lsys.render(m, { width = 64, height = 64, supersample = 1 })
    -- along the middle column: green and white alternate (the front half of the stem is
    -- u > 1/2), about 12 / pi turns of the image
    local changes, last = 0, nil
    for y = 0, h - 1 do
      local r, g, b = pixel(px, w, 32, y)
      local c = (g == 255 and r == 0) and "green"
                or (r == 255 and g == 255 and b == 255) and "white"
      if c and c ~= last then
        if last then changes = changes + 1 end
        last = c
      end
    end
    assert.is_true(changes >= 5 and changes <= 9, "colour changes along the stem: " .. changes)
  end)

  it("takes lsys.Texture values in core.render's opts.textures", function()
    local m = lsys.lsystem { axiom = "@Tx(1) { f + f + f + f }",
      view = { angle = 90, palette = { { 1, 1, 1 } }, textures = { checker } } }
    local sc = m:interpret()
    local t = core.texture_load(checker, { mode = "d" })
    local px = core.render(sc, { width = 64, height = 64, supersample = 1, textures = { t } })
    assert.same({ 255, 0, 0, 255 }, { pixel(px, 64, 18, 18) })
    -- without opts.textures the scene's own (its view's: modulate, lit red)
    local own = core.render(sc, { width = 64, height = 64, supersample = 1 })
    local r, g, b = pixel(own, 64, 18, 18)
    assert.is_true(r > 100 and g == 0 and b == 0, r .. " " .. g .. " " .. b)
    -- (a texture index the scene has no texture for draws untextured: test_render.c)
    assert.has_error(function () core.render(sc, { textures = 5 }) end,
      "lsys.render: opts.textures must be a list of textures (lsys.texture_load), got number")
    assert.has_error(function () core.render(sc, { textures = { t, checker } }) end,
      "lsys.render: opts.textures[2] must be a texture (lsys.texture_load), got string")
  end)
end)
