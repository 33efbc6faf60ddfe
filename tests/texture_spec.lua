-- Textures (cpfg guide §5, Appendix B.2): core.texture_load, its options and errors, and the
-- lsys.Texture methods. The images are written by the spec itself with core.png_write, and
-- SGI images (cpfg's .rgb) with the small writer below.
require "tests.helper"
local core = require "lsys.core"
local lsys = require "lsys"
local view = require "lsys.view"

local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir -p '" .. dir .. "'"))
local function path (name) return dir .. "/" .. name end

-- RGBA pixels from a list of {r, g, b, a} (top row first)
local function pixels (list)
  local t = {}
  for i, p in ipairs(list) do t[i] = string.char(p[1], p[2], p[3], p[4] or 255) end
  return table.concat(t)
end

local checker = pixels { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 255, 255, 255 } }
local grey = pixels { { 0, 0, 0 }, { 90, 90, 90 }, { 180, 180, 180 } }

-- An SGI image file (Haeberli's format, RLE) of the w x h pixels `px` (as `pixels` makes
-- them, top row first) with z channels: 1 grey (the red bytes), 2 grey and alpha, 3 RGB,
-- 4 RGBA. The file stores the rows bottom first; a row of equal values is one repeat run,
-- any other one literal run.
local function sgi (px, w, h, z)
  assert(w <= 127)
  local head = string.pack(">I2BBI2I2I2I2I4I4", 474, 1, 1, 3, w, h, z, 0, 255)
  head = head .. string.rep("\0", 512 - #head)
  local byte = z == 2 and { 1, 4 } or { 1, 2, 3, 4 }
  local starts, lens, rows, off = {}, {}, {}, 512 + 8 * h * z
  for c = 1, z do
    for r = 0, h - 1 do                           -- the file's row r: the picture's h - 1 - r
      local v = {}
      for i = 0, w - 1 do v[#v + 1] = px:sub(((h - 1 - r) * w + i) * 4 + byte[c]):sub(1, 1) end
      local row = table.concat(v)
      row = row == v[1]:rep(w) and string.char(w) .. v[1] .. "\0"
            or string.char(0x80 | w) .. row .. "\0"
      starts[#starts + 1], lens[#lens + 1] = string.pack(">I4", off), string.pack(">I4", #row)
      rows[#rows + 1] = row
      off = off + #row
    end
  end
  return head .. table.concat(starts) .. table.concat(lens) .. table.concat(rows)
end

local function write (name, bytes)
  local f = assert(io.open(path(name), "wb"))
  f:write(bytes)
  f:close()
end

setup(function ()
  core.png_write(path("checker.png"), checker, 2, 2, false)
  core.png_write(path("grey.png"), grey, 3, 1, false)
  core.png_write(path("alpha.png"), pixels { { 10, 20, 30, 0 } }, 1, 1, true)
  write("fake.png", "GIF89a, not a PNG at all")
  write("checker.rgb", sgi(checker, 2, 2, 3))
  write("grey.bw", sgi(grey, 3, 1, 1))
  write("alpha.rgba", sgi(pixels { { 10, 20, 30, 0 }, { 1, 2, 3 } }, 1, 2, 4))
  write("sgi.png", sgi(checker, 2, 2, 3))         -- the content counts, not the name
  core.png_write(path("png.rgb"), checker, 2, 2, false)
  write("cut.rgb", sgi(checker, 2, 2, 3):sub(1, -3))
  write("light08.rgb", sgi(pixels { { 200, 180, 40 }, { 200, 180, 40 }, { 10, 10, 10 },
                                    { 10, 10, 10 } }, 2, 2, 3))
  write("plant.v", "texture: F: light08.rgb H: l E: d\n")
end)

local FILES = { "checker.png", "grey.png", "alpha.png", "fake.png", "checker.rgb", "grey.bw",
                "alpha.rgba", "sgi.png", "png.rgb", "cut.rgb", "light08.rgb", "plant.v" }
teardown(function ()
  for _, n in ipairs(FILES) do os.remove(path(n)) end
  os.remove(dir)
end)

describe("texture_load", function ()
  it("reads a PNG with the default settings", function ()
    local t = core.texture_load(path("checker.png"))
    assert.equal("lsys.Texture", getmetatable(t).__name)
    local w, h = t:size()
    assert.equal(2, w)
    assert.equal(2, h)
    assert.same({ path = path("checker.png"), width = 2, height = 2, mag = "near", min = "near",
                  mode = "modulate", per_surface = false, intensity = false, alpha = false },
                t:info())
    assert.equal("Texture(" .. path("checker.png") .. ", 2x2)", tostring(t))
  end)

  it("takes long and one-letter option values", function ()
    local t = core.texture_load(path("checker.png"),
      { mag = "linear", min = "l", mode = "decal", per_surface = true })
    local i = t:info()
    assert.equal("linear", i.mag)
    assert.equal("linear", i.min)
    assert.equal("decal", i.mode)
    assert.is_true(i.per_surface)
    i = core.texture_load(path("checker.png"), { mag = "n", min = "near", mode = "m" }):info()
    assert.same({ "near", "near", "modulate" }, { i.mag, i.min, i.mode })
  end)

  it("makes a grey image an intensity texture unless told otherwise", function ()
    assert.is_true(core.texture_load(path("grey.png")):info().intensity)
    assert.is_false(core.texture_load(path("grey.png"), { intensity = false }):info().intensity)
    assert.is_true(core.texture_load(path("checker.png"), { intensity = true }):info().intensity)
    assert.same({ 3, 1 }, { core.texture_load(path("grey.png")):size() })
  end)

  it("notes transparent texels", function ()
    assert.is_true(core.texture_load(path("alpha.png")):info().alpha)
  end)

  it("names the file when it cannot be read", function ()
    assert.error_contains(function () core.texture_load(path("missing.png")) end,
                          "lsys.texture_load", "cannot open '" .. path("missing.png"))
    assert.error_contains(function () core.texture_load(path("fake.png")) end,
                          path("fake.png"), "is not a PNG or SGI image")
    assert.error_contains(function () core.texture_load(dir) end, dir)
  end)

  it("rejects bad option values, naming the option and the file", function ()
    local p = path("checker.png")
    local head = "lsys.texture_load: '" .. p .. "': "
    assert.has_error(function () core.texture_load(p, { mag = "cubic" }) end,
      head .. "opts.mag must be 'linear', 'near', 'l' or 'n', got 'cubic'")
    assert.has_error(function () core.texture_load(p, { min = 1 }) end,
      head .. "opts.min must be 'linear', 'near', 'l' or 'n', got number")
    assert.has_error(function () core.texture_load(p, { mode = "blend" }) end,
      head .. "opts.mode must be 'modulate', 'decal', 'm' or 'd', got 'blend'")
    assert.has_error(function () core.texture_load(p, { per_surface = 1 }) end,
      head .. "opts.per_surface must be a boolean, got number")
    assert.has_error(function () core.texture_load(p, { intensity = "yes" }) end,
      head .. "opts.intensity must be a boolean, got string")
    assert.has_error(function () core.texture_load(p, { filter = "linear" }) end,
      head .. "unknown option 'filter' (known: mag, min, mode, per_surface, intensity)")
    assert.error_contains(function () core.texture_load(p, "linear") end, "table expected")
    assert.error_contains(function () core.texture_load() end, "string expected")
  end)

  it("checks the options before reading the file", function ()
    assert.error_contains(function () core.texture_load(path("missing.png"), { mag = "x" }) end,
                          "opts.mag")
  end)

  it("is closed and collected cleanly", function ()
    local t = core.texture_load(path("checker.png"))
    getmetatable(t).__close(t)
    assert.error_contains(function () t:size() end, "the texture was closed")
    assert.error_contains(function () t:info() end, "the texture was closed")
    getmetatable(t).__gc(t)                       -- idempotent
    assert.equal("Texture (closed)", tostring(t))
    assert.error_contains(function () t.size(42) end, "lsys.Texture expected")
  end)
end)

describe("texture_load of SGI images (cpfg's .rgb)", function ()
  it("reads them, chosen by their content, not their name", function ()
    local t = core.texture_load(path("checker.rgb"))
    assert.same({ 2, 2 }, { t:size() })
    assert.same({ path = path("checker.rgb"), width = 2, height = 2, mag = "near", min = "near",
                  mode = "modulate", per_surface = false, intensity = false, alpha = false },
                t:info())
    assert.same({ 3, 1 }, { core.texture_load(path("grey.bw")):size() })
    assert.is_true(core.texture_load(path("grey.bw")):info().intensity)
    local a = core.texture_load(path("alpha.rgba")):info()
    assert.same({ 1, 2, true, false }, { a.width, a.height, a.alpha, a.intensity })
    assert.same({ 2, 2 }, { core.texture_load(path("sgi.png")):size() })
    assert.same({ 2, 2 }, { core.texture_load(path("png.rgb")):size() })
  end)

  it("names the file and the damage", function ()
    assert.error_contains(function () core.texture_load(path("cut.rgb")) end,
      "lsys.texture_load: cannot read '" .. path("cut.rgb") .. "': RLE row 1 of channel 2 runs "
      .. "past the end of the file")
  end)

  it("is drawn as the same PNG would be: the rows turned over, top row first", function ()
    if not core.has_render then
      pending("lsys was built without OSMesa: the pixels are checked by tests/c/test_sgi.c")
      return
    end
    local function square (file)
      local m = lsys.lsystem { axiom = "@Tx(1) { f + f + f + f }",
        view = { angle = 90, palette = { { 1, 1, 1 } },
                 textures = { { file = path(file), mode = "decal" } } } }
      return lsys.render(m, { width = 64, height = 64, supersample = 1 })
    end
    local px = square("checker.rgb")
    assert.equal(square("checker.png"), px)
    -- the centre of the top left quadrant: the first pixel of the image, red
    local o = (18 * 64 + 18) * 4
    assert.same({ 255, 0, 0, 255 }, { px:byte(o + 1, o + 4) })
  end)

  it("goes into a .glb as a PNG of its pixels (glTF has no SGI images)", function ()
    local glb = require "tests.glb"
    local sc = lsys.lsystem { axiom = "@Tx(1) { f + f + f + f } @Tx(2) { f + f + f + f }",
      view = { angle = 90, textures = { path("alpha.rgba"), path("checker.png") } },
    }:interpret()
    sc:save(path("t.glb"))
    local doc, bin = glb.read(path("t.glb"))
    assert.equal(2, #doc.images)
    local function image (i)
      local bv = doc.bufferViews[doc.images[i].bufferView + 1]
      return bin:sub(bv.byteOffset + 1, bv.byteOffset + bv.byteLength)
    end
    assert.equal("image/png", doc.images[1].mimeType)
    write("t1.png", image(1))
    local px, w, h = core.png_read(path("t1.png"))
    assert.same({ 1, 2 }, { w, h })                      -- RGBA: a texel is transparent
    assert.equal(pixels { { 10, 20, 30, 0 }, { 1, 2, 3 } }, px)
    local f = assert(io.open(path("checker.png"), "rb"))
    assert.equal(f:read("a"), image(2))                  -- a PNG goes in as it is
    f:close()
    os.remove(path("t.glb"))
    os.remove(path("t1.png"))
  end)

  it("loads from a view file's texture: line", function ()
    local v = view.load(path("plant.v"), { quiet = true })
    assert.same({ { file = "light08.rgb", mag = "linear", min = "near", mode = "decal",
                    per_surface = false } }, v.textures)
    local n = view.normalize(v, "plant")
    local t = n.textures[1]
    assert.equal("lsys.Texture", getmetatable(t).__name)
    assert.same({ 2, 2 }, { t:size() })
    local i = t:info()
    assert.same({ path("light08.rgb"), "linear", "decal", false },
                { i.path, i.mag, i.mode, i.intensity })
  end)
end)
