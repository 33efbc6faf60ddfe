-- The default lights of the renderer (key, fill, sky, ground and ambient: csrc/gl/render.c,
-- docs/drawing.md "Lights"): no organ turned away from the key light renders nearly black,
-- and a leaf keeps its shading. Rendered headless through OSMesa.
--
-- Measures, printed in the failure messages (before the fill, sky and ground lights, with one
-- key light over the material's ambient: foxglove 8.4 % near-black, default tree 0.9 %,
-- chestnut 1.9 %; the turned leaf 42 % of the facing one; the leaf lit from behind 29 %;
-- after: 0 % for each picture, 62 % and 65 %; the squares measured inside their edges):
--   * the near-black share: of the plant's pixels (those that differ from the background,
--     as tests/helper.lua's H.ink counts them), the share whose luminance is below 10 %,
--     in the gallery's pictures (examples/gallery/make.lua: 480 pixels for the default tree,
--     320 for the others);
--   * a two-sided mid-green square facing the camera against the same turned 75 degrees
--     about its vertical edge: the mean luminance of its pixels;
--   * the square with its back to the key light against the same facing it.
--
-- Tagged #gl: `busted --exclude-tags=gl` leaves it out.
local lsys = require "lsys"
local core = require "lsys.core"

-- Luminance of an sRGB-encoded pixel in [0, 1] (ITU-R BT.709 weights on the stored values).
local function luma (r, g, b) return (0.2126 * r + 0.7152 * g + 0.0722 * b) / 255 end

-- Of the pixels of px (w x h) that differ from its top left corner by more than 40 in the sum
-- of R, G and B: how many, their mean luminance, and the share below 10 % luminance.
local function measure (px, w, h)
  local br, bg, bb = px:byte(1, 3)
  local n, dark, sum = 0, 0, 0
  for i = 0, w * h - 1 do
    local r, g, b = px:byte(4 * i + 1, 4 * i + 3)
    if math.abs(r - br) + math.abs(g - bg) + math.abs(b - bb) > 40 then
      local y = luma(r, g, b)
      n, sum = n + 1, sum + y
      if y < 0.10 then dark = dark + 1 end
    end
  end
  return n, n > 0 and sum / n or 0, n > 0 and dark / n or 0
end

-- A mid-green two-sided square in the xy plane facing +z, rolled `roll` degrees about its
-- vertical left edge, lit from `light`, seen along `direction` ({0, 0, -1}: from +z, its
-- front); 96 x 96 pixels, a white background (far from any shade of the leaf). Returns
-- the number of inner pixels of the leaf and their mean luminance.
local function square (roll, light, direction)
  local m = lsys.lsystem {
    axiom = string.format("/(%g) { f + f + f + f }", roll),
    view = { angle = 90, palette = { { 0.30, 0.60, 0.20 } }, background = { 1, 1, 1 },
             light = light, direction = direction },
  }
  local px, w, h = lsys.render(m, { width = 96, height = 96 })
  -- the pixels of the leaf whose eight neighbours are too: its edges, blended with the
  -- background by the anti-aliasing, left out
  local function leaf (x, y)
    local i = 4 * (y * w + x)
    local r, g, b = px:byte(i + 1, i + 3)
    return x >= 0 and y >= 0 and x < w and y < h and r + g + b < 3 * 255 - 40
  end
  local n, sum = 0, 0
  for y = 0, h - 1 do
    for x = 0, w - 1 do
      local inner = true
      for dy = -1, 1 do
        for dx = -1, 1 do inner = inner and leaf(x + dx, y + dy) end
      end
      if inner then
        local i = 4 * (y * w + x)
        n, sum = n + 1, sum + luma(px:byte(i + 1, i + 3))
      end
    end
  end
  return n, n > 0 and sum / n or 0
end

describe("default lighting #gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa: lighting specs skipped")
    return
  end

  local PICTURES = {
    { "default.lua", nil, 480 }, { "sketch/fig14.lua", nil, 320 },
    { "components/chestnut.lua", nil, 320 }, { "sketch/fig10.lua", "side", 320 },
    { "sketch/fig8.lua", "decussate", 320 }, { "sketch/fig8.lua", "distichous", 320 },
    { "sketch/fig8.lua", "fibonacci", 320 },
  }
  for _, p in ipairs(PICTURES) do
    local label = p[1] .. (p[2] and " (" .. p[2] .. ")" or "")
    it("leaves under 2 % of the plant nearly black: " .. label, function()
      local v = dofile("examples/" .. p[1])
      if p[2] then v = v[p[2]] end
      local px, w, h = lsys.render(v:interpret(v:derive()), { width = p[3], height = p[3] })
      local n, _, dark = measure(px, w, h)
      assert.is_true(n > 1000, label .. ": only " .. n .. " plant pixels")
      assert.is_true(dark < 0.02, string.format(
        "%s: %.2f %% of %d plant pixels below 10 %% luminance (at most 2 %%)",
        label, 100 * dark, n))
    end)
  end

  it("keeps a leaf turned 75 degrees from the camera at half the facing one or more", function()
    local n0, facing = square(0)
    local n1, turned = square(75)
    -- the turned square is foreshortened to about cos 75 = 0.26 of the facing one
    assert.is_true(n0 > 4000 and n1 > 0.15 * n0 and n1 < 0.4 * n0,
                   "pixels facing " .. n0 .. ", turned " .. n1)
    assert.is_true(turned >= 0.5 * facing, string.format(
      "turned %.3f, facing %.3f: %.0f %% (at least 50 %%)", turned, facing,
      100 * turned / facing))
    -- and the leaf keeps its shape: turning it does change its shade
    assert.is_true(math.abs(turned - facing) > 0.02 * facing, string.format(
      "turned %.3f, facing %.3f: flat shading", turned, facing))
  end)

  it("does not draw a leaf with its back to the key light black", function()
    local n0, lit = square(0, { 0, 0, 1 })
    local n1, back = square(0, { 0, 0, -1 })
    assert.are.equal(n0, n1)
    assert.is_true(back >= 0.35 * lit, string.format(
      "back to the light %.3f, facing it %.3f: %.0f %% (at least 35 %%)", back, lit,
      100 * back / lit))
    -- each face has its own normal: the back seen from behind and lit from behind is the
    -- front seen and lit from the front
    local n2, behind = square(0, { 0, 0, -1 }, { 0, 0, 1 })
    assert.are.equal(n0, n2)
    assert.is_true(math.abs(behind - lit) < 0.005, string.format(
      "back face lit from behind %.3f, front face lit from the front %.3f", behind, lit))
    -- still darker than the lit side: the key light is the brightest
    assert.is_true(back < 0.8 * lit, string.format(
      "back to the light %.3f, facing it %.3f: the key light does not show", back, lit))
  end)

  -- the centre pixel of a white square facing the camera, drawn with the view `view`
  local function centre (view, opts)
    local v = { angle = 90, palette = { { 1, 1, 1 } }, background = { 0, 0, 0 } }
    for k, x in pairs(view or {}) do v[k] = x end
    local m = lsys.lsystem { axiom = "{ f + f + f + f }", view = v }
    local o = { width = 32, height = 32, supersample = 1 }
    for k, x in pairs(opts or {}) do o[k] = x end
    local px = lsys.render(m, o)
    return { px:byte(4 * (16 * 32 + 16) + 1, 4 * (16 * 32 + 16) + 3) }
  end

  it("lights a view with its own lights only, in their colours, as cpfg does", function()
    -- one red light from the front: red diffuse, and OpenGL's ambient 0.2 times the
    -- material's 0.3 in every channel (0.06 of 255 is 15)
    local red = centre { lights = { { direction = { 0, 0, 1 }, diffuse = { 1, 0, 0 } } } }
    assert.near(255, red[1], 1)
    assert.near(15, red[2], 1)
    assert.near(15, red[3], 1)
    -- a light from behind the square lights its back, which the camera does not see
    local behind = centre { lights = { { direction = { 0, 0, -1 } } } }
    assert.same({ 15, 15, 15 }, behind)
    -- a point light 3 in front of the square's centre (the square spans x from -1 to 0),
    -- lit at its corners (OpenGL 1.x lights vertices): cos = 3 / sqrt(9.5); and a light's
    -- own ambient colour
    local point = centre { lights = { { position = { -0.5, 0.5, 3 }, diffuse = { 0, 0.5, 0 },
                                        ambient = { 0, 0, 0.5 } } } }
    assert.near(15, point[1], 1)
    assert.near(15 + 127.5 * 3 / math.sqrt(9.5), point[2], 1)
    assert.near(15 + 0.5 * 0.3 * 255, point[3], 2)
    -- the render's own lights replace the view's; an empty list brings the default back
    assert.same(red, centre(nil, { lights = { { direction = { 0, 0, 1 },
                                                 diffuse = { 1, 0, 0 } } } }))
    assert.same(centre(), centre({ lights = { { direction = { 0, 0, 1 } } } }, { lights = {} }))
    assert.are_not.same(centre(), behind)
  end)

  it("reads a view file's light: lines into lights", function()
    local dir = os.tmpname()
    os.remove(dir)
    local f = assert(io.open(dir, "w"))
    f:write("light: V: 0 0 1 D: 1 0 0\nlight: O: -0.5 0.5 3 D: 0 0.5 0 A: 0 0 0.5\n")
    f:close()
    local v = lsys.view.load(dir, { quiet = true })
    os.remove(dir)
    assert.same({ { direction = { 0, 0, 1 }, diffuse = { 1, 0, 0 } },
                  { position = { -0.5, 0.5, 3 }, diffuse = { 0, 0.5, 0 },
                    ambient = { 0, 0, 0.5 } } }, v.lights)
    assert.same({ 0, 0, 1 }, v.light)
    local c = centre { lights = v.lights }
    assert.near(255, c[1], 1)
    assert.near(15 + 127.5 * 3 / math.sqrt(9.5), c[2], 1)
  end)

  it("says what is wrong with a light", function()
    local function err (lights)
      local ok, e = pcall(centre, { lights = lights })
      assert.is_false(ok)
      return e
    end
    assert.matches("view.lights%[1%]' needs a direction or a position %(one of them%)",
                   err { { diffuse = { 1, 1, 1 } } })
    assert.matches("view.lights%[2%].direction' must not be the zero vector",
                   err { { direction = { 0, 0, 1 } }, { direction = { 0, 0, 0 } } })
    assert.matches("view.lights%[1%].diffuse'%[2%] must not be negative",
                   err { { direction = { 0, 0, 1 }, diffuse = { 1, -1, 0 } } })
    assert.matches("has 9 lights; at most 8 can be drawn", err(
      { {}, {}, {}, {}, {}, {}, {}, {}, {} }))
    -- the same checks in the core, for a caller that gives core.render its options itself
    local sc = lsys.lsystem { axiom = "{ f + f + f + f }", view = { angle = 90 } }:interpret()
    local function cerr (lights)
      local ok, e = pcall(core.render, sc, { width = 16, height = 16, lights = lights })
      assert.is_false(ok)
      return e
    end
    assert.matches("opts.lights%[1%] needs a direction or a position %(one of them%)",
                   cerr { { position = { 1, 2, 3 }, direction = { 1, 0, 0 } } })
    assert.matches("opts.lights%[1%].specular must be {r, g, b} with finite numbers >= 0",
                   cerr { { position = { 1, 2, 3 }, specular = { 1, 0 } } })
    assert.matches("opts.lights%[1%].direction must not be the zero vector",
                   cerr { { direction = { 0, 0, 0 } } })
    assert.matches("opts.lights has 9 lights; at most 8 can be drawn",
                   cerr { {}, {}, {}, {}, {}, {}, {}, {}, {} })
    assert.matches("opts.lights%[2%] must be a table", cerr { { direction = { 1, 0, 0 } }, 5 })
  end)
end)
