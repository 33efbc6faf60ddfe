-- The palette pane of the viewer's editing column (lsys.ui.palette, docs/viewer.md,
-- "Palette pane"): its swatches and their hit-testing, selection, the form's items that
-- change the model's colours, picks on the plant, and the .map and .mat writers.
local H = require "tests.helper"
local R = require "tests.export_reader"
local lsys = require "lsys"
local core = require "lsys.core"
local viewfile = require "lsys.viewfile"
local P = require "lsys.ui.palette"

-- A colour map in the manner of vlab's: ramps of browns, greens and greys, 768 bytes.
local function ramp_map ()
  local out = {}
  for i = 0, 255 do
    local k = i % 64
    local band = i // 64
    local r, g, b
    if band == 0 then r, g, b = 60 + 2 * k, 40 + k, 20
    elseif band == 1 then r, g, b = 20, 80 + 2 * k, 30 + k
    elseif band == 2 then r, g, b = 4 * k, 4 * k, 4 * k
    else r, g, b = 255 - 3 * k, 200, 3 * k end
    out[#out + 1] = string.char(r, g, b)
  end
  return table.concat(out)
end

-- A material file: records for indices 0, 1, 2 and 5 (3 and 4 are left out).
local function mat_bytes ()
  local function rec (i, tr, a, d, e, s, sh)
    return string.char(i, tr, a[1], a[2], a[3], d[1], d[2], d[3], e[1], e[2], e[3],
                       s[1], s[2], s[3], sh)
  end
  return rec(0, 0, { 0, 0, 0 }, { 10, 10, 10 }, { 0, 0, 0 }, { 0, 0, 0 }, 0)
      .. rec(1, 0, { 40, 30, 20 }, { 140, 110, 80 }, { 0, 0, 0 }, { 30, 30, 30 }, 20)
      .. rec(2, 51, { 10, 50, 10 }, { 40, 160, 40 }, { 5, 6, 7 }, { 90, 90, 90 }, 64)
      .. rec(5, 0, { 1, 2, 3 }, { 200, 30, 30 }, { 0, 0, 0 }, { 255, 255, 255 }, 128)
end

local dir
setup(function () dir = H.tmpdir() end)
teardown(function () H.rmdir(dir) end)

-- A model drawing four segments as ribbons: colour 1, then ;(2), then a branch in
-- colour 5, and colour 1 again after the branch.
local function plant (palette, name)
  return lsys.lsystem { axiom = "F;(2)F[+;(5)F]-F", name = name,
                        view = { line_style = "polygon", palette = palette, dir = dir } }
end

-- The colours of the triangles as written to PLY (8-bit, the palette's values).
local function ply_colours (scene)
  local path = dir .. "/plant.ply"
  scene:save(path)
  local set = {}
  for _, v in ipairs(R.ply(path).data.vertex) do
    set[v.red * 65536 + v.green * 256 + v.blue] = true
  end
  return set
end

local function rgbkey (r, g, b) return r * 65536 + g * 256 + b end

describe("the palette pane's swatches", function()
  it("lays 256 colours out 16 by 16, and swatch_at finds what swatch_rect gives", function()
    H.write(dir .. "/v.map", ramp_map())
    local pane = P.new(plant("v.map"))
    assert.equal(256, pane:count())
    local c = core.canvas(420, 700)
    pane:draw(c)
    local x0, y0, w, h = pane:swatch_rect(0)
    assert.equal(w, h)
    assert.equal(25, w)                         -- (420 - 2 * 10) / 16
    local x, y = pane:swatch_rect(17)
    assert.same({ x0 + w, y0 + h }, { x, y })   -- row 1, column 1
    x, y = pane:swatch_rect(255)
    assert.same({ x0 + 15 * w, y0 + 15 * h }, { x, y })
    for _, i in ipairs { 0, 1, 15, 16, 100, 255 } do
      local sx, sy, sw, sh = pane:swatch_rect(i)
      assert.equal(i, pane:swatch_at(sx + 1, sy + 1))
      assert.equal(i, pane:swatch_at(sx + sw - 1, sy + sh - 1))
    end
    assert.is_nil(pane:swatch_at(x0 - 1, y0 + 1))
    assert.is_nil(pane:swatch_at(x0 + 16 * w + 1, y0 + 1))
    assert.is_nil(pane:swatch_at(x0 + 1, y0 + 16 * h + 1))
    assert.is_nil(pane:swatch_rect(256))
    assert.is_nil(pane:swatch_rect(-1))
  end)

  it("draws each swatch in its colour and the selected one large", function()
    H.write(dir .. "/v.map", ramp_map())
    local pane = P.new(plant("v.map"))
    local c = core.canvas(420, 700)
    pane:select(70)                             -- band 1, k = 6: 20, 92, 36
    pane:draw(c)
    local px = c:pixels()
    local function at (x, y)
      local o = (y * 420 + x) * 4
      return { px:byte(o + 1, o + 3) }
    end
    local _, y0 = pane:swatch_rect(0)
    local sx, sy, sw, sh = pane:swatch_rect(200)  -- band 3, k = 8: 231, 200, 24
    assert.same({ 231, 200, 24 }, at(sx + sw - 3, sy + sh // 2))
    -- the large swatch is below the grid, at the left margin
    local below = y0 + 16 * sh + 12            -- 16 rows, then a gap of 12
    assert.same({ 20, 92, 36 }, at(P.MARGIN + P.BIG // 2, below + P.BIG // 2))
    c:save(dir .. "/pane.png")
    assert.is_true(#H.read(dir .. "/pane.png") > 1000)
  end)

  it("draws a material palette by its diffuse colours, the selected one's fields listed",
     function()
    H.write(dir .. "/m.mat", mat_bytes())
    local pane = P.new(plant("m.mat"))
    assert.equal("m.mat (6 materials)", pane:source())
    local c = core.canvas(420, 700)
    pane:draw(c)
    local px = c:pixels()
    local x, y, w = pane:swatch_rect(5)
    local o = ((y + w // 2) * 420 + x + w - 4) * 4
    assert.same({ 200, 30, 30 }, { px:byte(o + 1, o + 3) })
    local v = pane:values(1)
    assert.same({ "diffuse", "140 110  80" }, { v[1][1], v[1][3] })
    assert.same({ "ambient", " 40  30  20" }, { v[2][1], v[2][3] })
    assert.same({ "shininess", "20" }, { v[5][1], v[5][3] })
    c:save(dir .. "/pane-mat.png")
  end)

  it("fits a small canvas and a short palette", function()
    local pane = P.new(plant(nil))               -- lsys.view's default palette: 0 .. 12
    assert.equal(13, pane:count())
    local c = core.canvas(240, 240)
    pane:draw(c)
    local x, y, w = pane:swatch_rect(12)
    assert.equal(4, ({ pane:grid() })[1])       -- 4 columns of 13
    assert.is_true(x + w <= 240 and y + w <= 240)
    assert.equal(12, pane:swatch_at(x + 1, y + 1))
  end)
end)

describe("the palette pane's selection", function()
  it("selects the swatch clicked, and the arrow keys move it", function()
    H.write(dir .. "/v.map", ramp_map())
    local pane = P.new(plant("v.map"))
    pane:draw(core.canvas(420, 700))
    local x, y = pane:swatch_rect(130)          -- band 2, k = 2: grey 8 8 8
    assert.is_true(pane:pointer("down", x + 3, y + 3, "left"))
    assert.equal(130, pane.selected)
    assert.is_false(pane:pointer("down", x + 3, y + 3, "left"))   -- already selected
    assert.is_false(pane:pointer("down", 2, 2, "left"))           -- the title
    assert.equal(130, pane.selected)
    assert.is_true(pane:key("right"))
    assert.equal(131, pane.selected)
    assert.is_true(pane:key("down"))
    assert.equal(147, pane.selected)
    assert.is_true(pane:key("up"))
    assert.is_true(pane:key("left"))
    assert.equal(130, pane.selected)
    assert.is_false(pane:key("s", true))       -- Ctrl+S is the host's
    assert.is_false(pane:key("q"))
    assert.equal("colour 130 of 256: 8 8 8, not used by the plant", pane:status())
  end)

  it("marks the indices the plant is drawn with", function()
    local pane = P.new(plant(nil))
    local list, set = pane:used()
    assert.same({ 1, 2, 5 }, list)
    -- ribbons of two triangles each: the first F in 1, the second and the last (after the
    -- branch) in 2, the branch's in 5
    assert.same({ [1] = 2, [2] = 4, [5] = 2 }, set)
    assert.equal("colour 1 of 13: 107 74 46, drawn 2 times", pane:status())
  end)

  it("wraps colour indices as the renderer does", function()
    local m = lsys.lsystem { axiom = ";(14)F", view = { line_style = "polygon" } }
    local pane = P.new(m)
    assert.same({ 1 }, (pane:used()))          -- 14 % 13
    assert.same({ [14] = 2 }, m:interpret():colors())
    assert.equal(2, pane:select(15))
  end)
end)

describe("scene:colors", function()
  it("counts the triangles and lines of each colour index, the same on every thread count",
     function()
    local function counts (threads, style)
      local m = lsys.lsystem { axiom = "A", steps = 6, threads = threads,
        productions = "A --> F[+;A][-,A]F;A",
        view = { line_style = style, angle = 25 } }
      return m:interpret():colors()
    end
    local one = counts(1, "line")
    local n = 0
    for c, k in pairs(one) do
      assert.equal("integer", math.type(c))
      n = n + k
    end
    assert.equal(lsys.lsystem { axiom = "A", steps = 6, productions = "A --> F[+;A][-,A]F;A" }
                   :interpret().nlines, n)
    assert.same(one, counts(4, "line"))
    assert.same(counts(1, "cylinder"), counts(3, "cylinder"))
  end)

  it("raises for a closed scene", function()
    local sc = plant(nil):interpret()
    getmetatable(sc).__close(sc)
    assert.error_contains(function () sc:colors() end, "the scene was closed")
  end)
end)

describe("the palette pane's items", function()
  it("give r, g, b of the selected colour in 0..255", function()
    H.write(dir .. "/v.map", ramp_map())
    local pane = P.new(plant("v.map"))
    pane:select(2)                              -- 64, 42, 20
    local it = pane:items()
    assert.equal(3, #it)
    assert.same({ "r", "g", "b" }, { it[1].name, it[2].name, it[3].name })
    assert.same({ 64, 42, 20 }, { it[1].value, it[2].value, it[3].value })
    for k = 1, 3 do
      assert.same({ "number", 0, 255, 1 }, { it[k].kind, it[k].min, it[k].max, it[k].step })
    end
  end)

  it("change the model's colours: the next interpretation draws with them", function()
    local m = plant(nil)
    local changes = {}
    local pane = P.new(m, { on_change = function (what) changes[#changes + 1] = what end })
    local before = ply_colours(m:interpret())
    assert.is_true(before[rgbkey(77, 140, 43)])          -- entry 2, 0.30 0.55 0.17
    pane:select(2)
    local it = pane:items()
    it[1].set(200)
    it[3].set(10)
    assert.same({ "palette", "palette" }, changes)
    local after = ply_colours(m:interpret())
    assert.is_nil(after[rgbkey(77, 140, 43)])
    assert.is_true(after[rgbkey(200, 140, 10)])
    assert.is_true(after[rgbkey(107, 74, 46)])           -- entry 1 unchanged
    assert.same({ 200, 140, 10 }, { pane:items()[1].value, pane:items()[2].value,
                                    pane:items()[3].value })
    assert.error_contains(function () it[1].set(256) end, "red must be a number from 0 to 255")
  end)

  it("give a material's colours, shininess and alpha", function()
    H.write(dir .. "/m.mat", mat_bytes())
    local m = plant("m.mat")
    local pane = P.new(m)
    assert.is_true(pane.materials)
    assert.equal(6, pane:count())
    pane:select(2)
    local it = pane:items()
    assert.equal(14, #it)
    local by = {}
    for _, x in ipairs(it) do by[x.name] = x end
    assert.same({ 40, 160, 40 }, { by["diffuse.r"].value, by["diffuse.g"].value,
                                   by["diffuse.b"].value })
    assert.same({ 10, 50, 10 }, { by["ambient.r"].value, by["ambient.g"].value,
                                  by["ambient.b"].value })
    assert.equal(7, by["emission.b"].value)
    assert.equal(90, by["specular.g"].value)
    assert.equal(64, by.shininess.value)
    assert.near(1 - 51 / 255, by.alpha.value, 1e-12)
    by["diffuse.g"].set(20)
    by.shininess.set(100)
    assert.near(20 / 255, m.view.palette[2].diffuse[2], 1e-12)
    assert.equal(100, m.view.palette[2].shininess)
    local after = ply_colours(m:interpret())
    assert.is_true(after[rgbkey(40, 20, 40)])
  end)
end)

describe("the palette pane's picks", function()
  it("selects the colour index of the module clicked", function()
    local m = plant(nil)
    local pane = P.new(m)
    local s = m:derive()
    -- modules: F ;(2) F [ + ;(5) F ] - F
    assert.is_true(pane:pick { module = 3, lstring = s })
    assert.equal(2, pane.selected)
    assert.is_true(pane:pick { module = 1, lstring = s })
    assert.equal(1, pane.selected)
    assert.is_true(pane:pick { module = 7, lstring = s })
    assert.equal(5, pane.selected)
    assert.is_true(pane:pick { module = 10, lstring = s })  -- after the branch: 2 again
    assert.equal(2, pane.selected)
    assert.is_false(pane:pick {})
  end)

  it("reads the scene it was given, and the turtle for a module that drew nothing", function()
    local m = plant(nil)
    local sc = m:interpret()
    local pane = P.new(m, { scene = sc })
    assert.is_true(pane:pick { module = 6, lstring = sc.lstring })   -- ;(5) itself
    assert.equal(5, pane.selected)
    assert.is_true(pane:pick { module = 7 })                         -- no lstring: the scene's
    assert.equal(5, pane.selected)
    pane:set_scene(nil)
    assert.error_contains(function () pane:set_scene({}) end, "an lsys.Scene expected")
  end)
end)

describe("the palette pane's save", function()
  it("writes a .map back as 768 bytes: load -> save -> load gives the same", function()
    local bytes = ramp_map()
    H.write(dir .. "/rt.map", bytes)
    local pane = P.new(plant("rt.map"))
    assert.same({ dir .. "/rt.map" }, pane:save())
    assert.equal(bytes, H.read(dir .. "/rt.map"))
    pane:select(7)
    pane:items()[2].set(255)
    assert.same({ dir .. "/rt.map" }, pane:save())
    local p = viewfile.load_colormap(dir .. "/rt.map")
    assert.equal(1, p[7][2])
    assert.same(bytes:sub(1, 21) .. string.char(74, 255, 20) .. bytes:sub(25),
                H.read(dir .. "/rt.map"))
    assert.equal("wrote " .. dir .. "/rt.map", pane:status())
  end)

  it("writes a .mat back with the records it had: load -> save -> load gives the same",
     function()
    local bytes = mat_bytes()
    H.write(dir .. "/rt.mat", bytes)
    local before = viewfile.load_materials(dir .. "/rt.mat")
    local pane = P.new(plant("rt.mat"))
    pane:save()
    assert.equal(bytes, H.read(dir .. "/rt.mat"))
    assert.same(before, viewfile.load_materials(dir .. "/rt.mat"))
    pane:select(3)                                  -- a default material, not in the file
    pane:items()[4].set(128)                        -- ambient red
    pane:save()
    local s = H.read(dir .. "/rt.mat")
    assert.equal(#bytes + 15, #s)
    local after = viewfile.load_materials(dir .. "/rt.mat")
    assert.near(128 / 255, after[3].ambient[1], 1e-12)
    after[3] = nil
    before[3] = nil
    assert.same(before, after)
  end)

  it("writes a palette table of the model beside it, and says so", function()
    local m = lsys.lsystem { axiom = "F", name = "tree", view = { dir = dir,
      palette = { { 1, 0, 0 }, { 0, 0.5, 1 } } } }
    local pane = P.new(m)
    assert.same({ dir .. "/tree.map" }, pane:save())
    assert.truthy(pane:status():find("set view.palette = \"tree.map\"", 1, true))
    local p = viewfile.load_colormap(dir .. "/tree.map")
    -- entries 0 (entry 1 repeated), 1, 2, then wrapped as the renderer wraps 3 entries
    assert.same({ 1, 0, 0 }, p[0])
    assert.same({ 0, 128 / 255, 1 }, p[2])
    assert.same({ 1, 0, 0 }, p[3])
    assert.same({ 0, 128 / 255, 1 }, p[254])
    assert.same({ 1, 0, 0 }, p[255])
    local big = {}
    for i = 0, 299 do big[i] = { i % 2, 0, 0 } end
    local wide = P.new { palette = big, dir = dir }
    assert.same({ dir .. "/palette.map" }, wide:save())
    assert.truthy(wide:status():find("entries 256 to 299 left out", 1, true))
    assert.equal(768, #H.read(dir .. "/palette.map"))
    local mats = lsys.lsystem { axiom = "F", view = { dir = dir,
      palette = { { diffuse = { 1, 1, 0 }, shininess = 12 } } } }
    assert.same({ dir .. "/palette.mat" }, P.new(mats):save())
    local q = viewfile.load_materials(dir .. "/palette.mat")
    assert.same({ 1, 1, 0 }, q[1].diffuse)
    assert.equal(12, q[1].shininess)
  end)
end)

describe("the palette pane's errors", function()
  it("names a colour map of the wrong size", function()
    H.write(dir .. "/short.map", string.rep("\0", 700))
    assert.error_contains(function () P.new(plant("short.map")) end,
                          dir .. "/short.map: a colour map is 768 bytes", "not 700")
  end)

  it("names a material file that is not whole records", function()
    H.write(dir .. "/bad.mat", string.rep("\0", 20))
    assert.error_contains(function () P.new(plant("bad.mat")) end,
                          dir .. "/bad.mat: a material file is a sequence of 15-byte records")
  end)

  it("rejects what is not a model or a view, and unknown options", function()
    assert.error_contains(function () P.new(42) end,
                          "a model (lsys.lsystem) or a view table expected, got number")
    assert.error_contains(function () P.new({}, { colour = 1 }) end, "unknown option 'colour'")
    assert.error_contains(function () P.new({}, { on_change = 1 }) end,
                          "option 'on_change' must be a function")
    assert.error_contains(function () P.new({}, { scene = io.stdout }) end,
                          "option 'scene' must be an lsys.Scene")
  end)

  it("raises naming the file it cannot write", function()
    local pane = P.new { palette = { { 1, 0, 0 } }, dir = dir .. "/no/such/dir" }
    assert.error_contains(function () pane:save() end, dir .. "/no/such/dir/palette.map")
  end)
end)
