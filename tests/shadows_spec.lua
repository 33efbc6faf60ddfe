-- Baked shadows, ambient occlusion, the ground plane and the sky (lsys.render's shadows, ao,
-- ground and sky options): where the shadow of a quad falls on the ground, a population on
-- its ground with its shadows, a ground that reaches the picture's edge, an occluded
-- corner, nothing changed with the options off, the same picture for 1 and 2 threads, and
-- the options' errors.
--
-- Tagged #gl; pending when lsys was built without OSMesa.
local lsys = require "lsys"
local core = require "lsys.core"

-- A square of side 4 in the horizontal plane through the turtle's position, corners from
-- (-4, y, -4) to (0, y, 0); unpitched, the same square stands in the plane z = 0.
local SQUARE = "{ . f(4) . +(90) f(4) . +(90) f(4) . +(90) f(4) . }"

-- The mean luminance (0..255) of the (2r+1)^2 pixels around (x, y) of RGBA pixels px.
local function lum (px, w, x, y, r)
  local sum, n = 0, 0
  for j = y - r, y + r do
    for i = x - r, x + r do
      local o = (j * w + i) * 4
      local R, G, B = px:byte(o + 1, o + 3)
      sum, n = sum + 0.2126 * R + 0.7152 * G + 0.0722 * B, n + 1
    end
  end
  return sum / n
end

-- Looking straight down (-y) in parallel projection: x to the right, -z up the picture.
local TOP = { projection = "parallel", viewpoint = { 0, 100, 0 }, target = { 0, 0, 0 },
              up = { 0, 0, -1 }, width = 200, height = 200, supersample = 1 }

local function opts (extra)
  local o = {}
  for k, v in pairs(TOP) do o[k] = v end
  for k, v in pairs(extra or {}) do o[k] = v end
  return o
end

describe("shadows and ambient occlusion #gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa")
    return
  end

  -- a stem of 10 up from the origin and the square centred on its top; the light from
  -- (0.5, 1, 0) puts the square's shadow 5 units towards -x on the ground at y = 0
  local quad = lsys.lsystem { axiom = "F(10) &(90) f(-2) -(90) f(-2) " .. SQUARE }
  -- the camera frames the plant, not its ground: these pictures frame the ground's 20
  -- units across (x and z from -10 to 10) to see the shadow beside the plant
  local GROUND = { -10, 0, -10, 10, 10, 10 }

  it("a quad above the ground casts its shadow where the light puts it", function()
    local px, w, h = lsys.render(quad, opts { light = { 0.5, 1, 0 }, shadows = true,
                                              ground = { size = 4 }, fit = GROUND })
    assert.are.equal(200, w)
    assert.are.equal(200, h)
    -- the ground is 4 x 5 = 20 units across (the plant's height over 2 is its widest
    -- extent), framed with a margin: 9 pixels a unit about the centre (100, 100); the
    -- shadow's centre (-5, 0, 0) is at x = 55, the open ground mirrored at x = 145
    local shadow, open = lum(px, w, 55, 100, 4), lum(px, w, 145, 100, 4)
    assert.is_true(shadow < 0.8 * open, ("shadow %.1f, open %.1f"):format(shadow, open))
    -- and the ground in front of and behind the shadow is as open as beside it
    assert.is_near(open, lum(px, w, 55, 40, 4), 1.5)
    assert.is_near(open, lum(px, w, 55, 160, 4), 1.5)
    -- without shadows the same ground is even
    local flat = lsys.render(quad, opts { light = { 0.5, 1, 0 }, ground = { size = 4 },
                                          fit = GROUND })
    assert.is_near(lum(flat, w, 145, 100, 4), lum(flat, w, 55, 100, 4), 1)
  end)

  it("the light from the other side moves the shadow to the other side", function()
    local px, w = lsys.render(quad, opts { light = { -0.5, 1, 0 }, shadows = true,
                                           ground = { size = 4 }, fit = GROUND })
    assert.is_true(lum(px, w, 145, 100, 4) < 0.8 * lum(px, w, 55, 100, 4))
  end)

  it("ambient occlusion darkens the inside of a concave corner", function()
    -- a wall (x in [-4, 0], y in [0, 4], z = 0) standing on the ground, a grid of quads: the
    -- two corners where they meet, seen from above with x = -2 in the middle and -z up
    local wall = lsys.lsystem { axiom = SQUARE }
    local box = { -5.2, 0, -3.2, 1.2, 4, 3.2 }      -- the ground's 6.4 across, framed
    local o = opts { light = { 0, 1, 0 }, ground = true, ao = { samples = 32, distance = 4 },
                     viewpoint = { -2, 100, 0 }, target = { -2, 0, 0 }, fit = box }
    local px, w = lsys.render(wall, o)
    local plain = lsys.render(wall, opts { light = { 0, 1, 0 }, ground = true, fit = box,
                                           viewpoint = { -2, 100, 0 }, target = { -2, 0, 0 } })
    -- without occlusion the ground is even; with it, darker at the wall's foot (rows 96 and
    -- 104, either side of the wall) than at the open edges (rows 16 and 184)
    local flat = lum(plain, w, 100, 16, 2)
    for _, y in ipairs { 30, 96, 104, 170, 184 } do
      assert.is_near(flat, lum(plain, w, 100, y, 2), 1)
    end
    for _, rows in ipairs { { 96, 16 }, { 104, 184 } } do
      local near, open = lum(px, w, 100, rows[1], 2), lum(px, w, 100, rows[2], 2)
      assert.is_true(near < 0.9 * open, ("at the wall %.1f, open %.1f"):format(near, open))
      assert.is_true(open > 0.95 * flat)           -- the open ground keeps most of its light
    end
    -- the darkening falls off with the distance from the wall
    assert.is_true(lum(px, w, 100, 96, 2) < lum(px, w, 100, 50, 2))
    assert.is_true(lum(px, w, 100, 50, 2) < lum(px, w, 100, 16, 2))
  end)

  it("changes nothing when the options are off", function()
    local tree = lsys.lsystem { axiom = "F(10) [ +(30) F(6) " .. SQUARE .. " ] F(5)" }
    local base = lsys.render(tree, opts())
    assert.is_true(base == lsys.render(tree, opts { shadows = false, ao = false,
                                                    ground = false, sky = false }))
    -- the shading path with nothing to darken gives the same pixels too
    assert.is_true(base == lsys.render(tree, opts { shadows = { strength = 0 },
                                                    ao = { strength = 0 } }))
    -- and the square's shadow on the ground does change them
    local lit = { ground = { size = 4 }, light = { 0.5, 1, 0 }, fit = GROUND }
    local ground = lsys.render(quad, opts(lit))
    lit.shadows = true
    assert.is_false(ground == lsys.render(quad, opts(lit)))
  end)

  it("puts no ground under a plant seen from below, and frames the plant, not its ground",
     function()
    -- from below (a shell's view), a ground would hide the plant: there is none
    local below = { viewpoint = { 0, -100, 0.01 }, target = { 0, 0, 0 } }
    local o1, o2 = opts(below), opts(below)
    o1.ground = true
    assert.is_true(lsys.render(quad, o1) == lsys.render(quad, o2))
    -- from above, the ground is drawn but the camera fits the plant alone: the square
    -- covers the same pixels with and without its ground
    local side = { viewpoint = { 0, 40, 100 }, target = { 0, 5, 0 }, up = { 0, 1, 0 } }
    local a = lsys.render(quad, opts(side))
    local g = opts(side)
    g.ground = { size = 4 }
    local b = lsys.render(quad, g)
    assert.is_false(a == b)                         -- the ground is seen
    local lo, hi = quad:interpret():bounds()
    g.fit = { lo[1], lo[2], lo[3], hi[1], hi[2], hi[3] }
    assert.is_true(b == lsys.render(quad, g))        -- framed as the plant's own box
  end)

  it("stands a population on the ground, each plant shadowing it and the others", function()
    -- two of the quads 12 apart as a population (instances of one prototype): the light
    -- from (0.5, 1, 0) puts each square's shadow 5 units towards -x, so the right plant's
    -- falls on the left plant's stem region and both fall on the ground
    local pop = lsys.population({ { model = quad, at = { -6, 0, 0 } },
                                  { model = quad, at = { 6, 0, 0 } } })
    assert.equal(2, pop.ninstances)
    local view = { light = { 0.5, 1, 0 }, fit = { -16, 0, -10, 16, 10, 10 },
                   background = { 0, 0, 0 } }
    local bare = lsys.render(pop, opts(view))
    view.ground = true
    local ground = lsys.render(pop, opts(view))
    view.shadows = true
    local shadowed = lsys.render(pop, opts(view))
    -- the picture is 32 units across in 200 pixels (with the fit's margin): x = -11 (the
    -- left shadow's centre) and x = 1 (the right one's) against the open ground at x = 12
    local function at (x) return math.floor(100 + x * 200 / 32 * 0.9 + 0.5) end
    local open = lum(ground, 200, at(12), 100, 3)
    assert.is_true(open > lum(bare, 200, at(12), 100, 3) + 20, "the ground is drawn")
    for _, x in ipairs { -11, 1 } do
      local sh = lum(shadowed, 200, at(x), 100, 3)
      assert.is_true(sh < 0.8 * lum(shadowed, 200, at(12), 100, 3),
                     ("x = %g: shadow %.1f, open %.1f"):format(x, sh, open))
      assert.is_true(lum(ground, 200, at(x), 100, 3) > 0.95 * open)   -- none without
    end
  end)

  it("grows the ground to the picture's bottom edge in a view from the side", function()
    -- a camera looking 11 degrees down: the square ground of 1.6 plant extents would end
    -- above the bottom edge; the ground reaches it now
    local m = lsys.lsystem { axiom = "#(0.5) F(10) [+(40) F(6)] [-(40) F(6)]",
                             view = { line_style = "cylinder", direction = { 0, -0.2, -1 } } }
    local px = lsys.render(m, { width = 120, height = 120, supersample = 1, ground = true,
                                background = { 1, 1, 1 } })
    for _, x in ipairs { 2, 60, 117 } do      -- the bottom row, left to right
      local o = (119 * 120 + x) * 4
      local r, g, b = px:byte(o + 1, o + 3)
      assert.is_true(r + g + b < 3 * 250, ("bottom row x = %d: %d %d %d"):format(x, r, g, b))
    end
  end)

  it("keeps the plant's colours when the ground's colours join the palette", function()
    -- colour 3 of a palette of two is its first (c % n): with the ground's colours appended
    -- it was the ground's own (cpfg fig. 27's petals were drawn grey)
    local m = lsys.lsystem { axiom = ";(3) F(10) &(90) f(-2) -(90) f(-2) " .. SQUARE,
                             view = { palette = { { 0.9, 0.1, 0.1 }, { 0.1, 0.1, 0.9 } } } }
    local side = { viewpoint = { 0, 40, 100 }, target = { 0, 5, 0 }, up = { 0, 1, 0 } }
    local a = lsys.render(m, opts(side))
    local g = opts(side)
    g.ground = true
    local b = lsys.render(m, g)
    -- the square's middle: red in both
    local o = (20 * 200 + 100) * 4
    local ra, ga, ba = a:byte(o + 1, o + 3)
    local rb, gb, bb = b:byte(o + 1, o + 3)
    assert.is_true(ra > 2 * ga and ra > 2 * ba, ("%d %d %d"):format(ra, ga, ba))
    assert.is_true(rb > 2 * gb and rb > 2 * bb, ("%d %d %d"):format(rb, gb, bb))
  end)

  it("bakes the shading into a Scene that draws the same picture (lsys.render.bake)", function()
    local render = require "lsys.render"
    local view = { light = { 0.5, 1, 0 }, fit = GROUND, ground = { size = 4 }, shadows = true }
    local sc = quad:interpret()
    local b = render.bake(sc, opts(view))
    assert.is_true(b.ntriangles > sc.ntriangles)           -- the ground is in its mesh
    local want = lsys.render(sc, opts(view))
    local got = lsys.render(b, opts { fit = GROUND })
    -- 16 steps of each colour: within a step (1/16 of the colour) of the picture's
    local worst = 0
    for i = 0, 200 * 200 - 1 do
      for c = 1, 3 do
        local d = math.abs(want:byte(4 * i + c) - got:byte(4 * i + c))
        if d > worst then worst = d end
      end
    end
    assert.is_true(worst <= 16, "worst " .. worst)
    assert.is_true(lum(got, 200, 55, 100, 4) < 0.8 * lum(got, 200, 145, 100, 4))  -- shadow
    -- a population's plants are written out, with the ground under them
    local pop = lsys.population({ { model = quad, at = { -6, 0, 0 } },
                                  { model = quad, at = { 6, 0, 0 } } })
    local bp = render.bake(pop, { ground = true, shadows = true })
    assert.equal(0, bp.ninstances)
    assert.is_true(bp.ntriangles > 2 * sc.ntriangles)
    assert.has_error(function () render.bake(sc, { out = "x.png" }) end,
                     "lsys.render.bake: opts.out: bake makes a Scene, it writes no file")
  end)

  it("gives the same picture for 1 and 2 threads", function()
    local m = dofile("examples/default.lua")
    m.steps = 5
    local function shot (n)
      return (lsys.render(m, { width = 160, height = 160, supersample = 1,
                               shadows = { threads = n, softness = 4 },
                               ao = { threads = n, samples = 8 }, ground = true, sky = true }))
    end
    local one = shot(1)
    assert.is_true(one == shot(2))
    assert.is_false(one == (lsys.render(m, { width = 160, height = 160, supersample = 1 })))
  end)

  it("draws the sky as a vertical gradient from its top colour to its bottom one", function()
    local px, w = lsys.render(quad, opts { sky = { top = { 0, 0, 1 }, bottom = { 1, 1, 0 } } })
    local function rgb (x, y)
      local o = (y * w + x) * 4
      return px:byte(o + 1, o + 3)
    end
    local r0, g0, b0 = rgb(2, 0)
    local r1, g1, b1 = rgb(2, 199)
    local rm = rgb(2, 100)
    assert.is_true(r0 < 5 and g0 < 5 and b0 > 250)
    assert.is_true(r1 > 250 and g1 > 250 and b1 < 5)
    assert.is_near(127, rm, 5)
  end)

  it("names a bad option", function()
    local cases = {
      { { shadows = 3 }, "opts.shadows must be true, false or a table" },
      { { ao = { samples = 0 } }, "opts.ao.samples must be an integer in %[1, 1024%]" },
      { { ao = { samples = 2.5 } }, "opts.ao.samples must be an integer" },
      { { ao = { distance = -1 } }, "opts.ao.distance must be a number" },
      { { shadows = { softness = 90 } }, "opts.shadows.softness must be a number in %[0, 30%]" },
      { { ground = { colour = { 1, 0, 0 } } }, "opts.ground: unknown field 'colour'" },
      { { ground = { color = { 2, 0, 0 } } }, "opts.ground.color must be a colour" },
      { { sky = { top = "blue" } }, "opts.sky.top must be a colour" },
    }
    for _, c in ipairs(cases) do
      local ok, err = pcall(lsys.render, quad, opts(c[1]))
      assert.is_false(ok)
      assert.matches(c[2], tostring(err))
      assert.matches("^lsys.render: ", tostring(err))
    end
  end)
end)
