-- Textures (cpfg guide §5, Appendix B.2): core.texture_load, its options and errors, and the
-- lsys.Texture methods. The images are written by the spec itself with core.png_write.
require "tests.helper"
local core = require "lsys.core"

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

setup(function ()
  core.png_write(path("checker.png"), checker, 2, 2, false)
  core.png_write(path("grey.png"), grey, 3, 1, false)
  core.png_write(path("alpha.png"), pixels { { 10, 20, 30, 0 } }, 1, 1, true)
  local f = assert(io.open(path("fake.png"), "wb"))
  f:write("GIF89a, not a PNG at all")
  f:close()
end)

teardown(function ()
  for _, n in ipairs { "checker.png", "grey.png", "alpha.png", "fake.png" } do
    os.remove(path(n))
  end
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
                          path("fake.png"), "is not a PNG file")
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
