-- The 2D canvas (core.canvas, docs/sketch.md "Canvas"): exact pixels of lines, rectangles and
-- text read back with c:pixels(), colours as tables and "#rrggbb", clipping, saving a PNG
-- (read back with core.texture_load), and the errors of bad arguments and closed canvases.
local H = require "tests.helper"
local core = require "lsys.core"

-- The pixel (i, j) (0-based) as r, g, b, a bytes.
local function px (c, i, j)
  local w = c:size()
  local s = c:pixels()
  local k = (j * w + i) * 4
  return s:byte(k + 1, k + 4)
end

-- The pixels that are not the background colour byte 'bg' in red, as "i,j" keys.
local function lit (c, bg)
  local w, h = c:size()
  local s, out, n = c:pixels(), {}, 0
  for j = 0, h - 1 do
    for i = 0, w - 1 do
      if s:byte((j * w + i) * 4 + 1) ~= bg then out[i .. "," .. j] = true; n = n + 1 end
    end
  end
  return out, n
end

describe("core.canvas", function ()
  it("makes a canvas of the given size, transparent unless a colour is given", function ()
    local c = core.canvas(7, 3)
    assert.same({ 7, 3 }, { c:size() })
    assert.equal(7 * 3 * 4, #c:pixels())
    assert.same({ 0, 0, 0, 0 }, { px(c, 6, 2) })
    assert.equal("Canvas(7x3)", tostring(c))
    c = core.canvas(2, 2, { 1, 0.5, 0 })
    assert.same({ 255, 128, 0, 255 }, { px(c, 1, 1) })
    c = core.canvas(2, 2, "#10ff8040")
    assert.same({ 16, 255, 128, 64 }, { px(c, 0, 0) })
  end)

  it("draws a horizontal 1-pixel line on exactly one row", function ()
    local c = core.canvas(12, 6, "#000000")
    c:line(2.5, 3.5, 8.5, 3.5, 1, "#ffffff")
    local on, n = lit(c, 0)
    assert.equal(7, n)
    for i = 2, 8 do assert.is_true(on[i .. ",3"]) end
    assert.same({ 255, 255, 255, 255 }, { px(c, 5, 3) })
  end)

  it("blends source over: half-transparent red on black gives 128", function ()
    local c = core.canvas(4, 4, { 0, 0, 0 })
    c:rect(0, 0, 2, 2, { 1, 0, 0, 0.5 }, true)
    assert.same({ 128, 0, 0, 255 }, { px(c, 1, 1) })
    assert.same({ 0, 0, 0, 255 }, { px(c, 2, 2) })
  end)

  it("draws the outline of a rectangle along the inside of its edges", function ()
    local c = core.canvas(10, 10, "#000000")
    c:rect(1, 2, 6, 4, "#ffffff")
    local on, n = lit(c, 0)
    assert.equal(6 + 6 + 2 + 2, n)
    assert.is_true(on["1,2"] and on["6,5"] and on["1,4"])
    assert.is_nil(on["3,3"])
  end)

  it("draws polylines from {x, y} pairs and from flat lists alike", function ()
    local a, b = core.canvas(30, 30, "#000000"), core.canvas(30, 30, "#000000")
    a:polyline({ { 2, 3 }, { 20, 25 }, { 28, 4 } }, 2, "#ffffff")
    b:polyline({ 2, 3, 20, 25, 28, 4 }, 2, "#ffffff")
    assert.equal(a:pixels(), b:pixels())
    local _, n = lit(a, 0)
    assert.is_true(n > 2 * 45)               -- two segments of about 28 and 22 pixels, width 2
    b:clear("#000000")
    b:polyline({ { 2, 3 } }, 2, "#ffffff")   -- one point, no segment
    b:polyline({}, 2, "#ffffff")
    assert.equal(0, select(2, lit(b, 0)))
  end)

  it("draws text in the 5x7 font and returns its width", function ()
    local c = core.canvas(20, 12, "#000000")
    assert.equal(11, c:text(1, 2, "-+", 1, "#ffffff"))
    assert.equal(11, c:text_width("-+"))
    assert.equal(4 * 12 - 2, c:text_width("abcd", 2))
    local on, n = lit(c, 0)
    -- '-': row 3 full (5 pixels); '+': column 2 of rows 1..5 and row 3 full (9 pixels)
    assert.equal(5 + 9, n)
    for i = 1, 5 do assert.is_true(on[i .. ",5"]) end
    for j = 3, 7 do assert.is_true(on["9," .. j]) end
  end)

  it("clips to a rectangle and back to the canvas", function ()
    local c = core.canvas(10, 10, "#000000")
    c:clip(2, 3, 4, 2)
    c:rect(-5, -5, 20, 20, "#ffffff", true)
    local on, n = lit(c, 0)
    assert.equal(8, n)
    assert.is_true(on["2,3"] and on["5,4"])
    c:clip()
    c:rect(-5, -5, 20, 20, "#ffffff", true)
    assert.equal(100, select(2, lit(c, 0)))
  end)

  it("skips shapes with NaN or infinite coordinates", function ()
    local c = core.canvas(10, 10, "#000000")
    c:line(0 / 0, 0, 5, 5)
    c:line(0, 0, math.huge, 5, 2)
    c:circle(5, -math.huge, 3)
    c:polyline({ { 1, 1 }, { 0 / 0, 2 }, { 3, 3 } }, 1, "#ffffff")
    assert.equal(0, select(2, lit(c, 0)))
    c:line(-1e300, 4.5, 1e300, 4.5, 1, "#ffffff")
    assert.equal(10, select(2, lit(c, 0)))
  end)

  it("saves a PNG that reads back with the same size", function ()
    local dir = H.tmpdir()
    local c = core.canvas(9, 4, "#336699")
    c:circle(4, 2, 1.5, "#ffffff")
    c:save(dir .. "/c.png")
    local t = core.texture_load(dir .. "/c.png")
    assert.same({ 9, 4 }, { t:size() })
    assert.error_contains(function () c:save(dir .. "/no/such/dir/c.png") end,
      "save:", "no/such/dir/c.png")
    H.rmdir(dir)
  end)

  it("rejects bad arguments with clear errors", function ()
    local c = core.canvas(4, 4)
    assert.error_contains(function () core.canvas(0, 4) end, "width must be in [1, 16384]")
    assert.error_contains(function () core.canvas(4, 16385) end, "height must be in [1, 16384]")
    assert.error_contains(function () core.canvas(4, 4, "red") end, "colour", "'red'")
    assert.error_contains(function () c:line(0, 0, 1, 1, 0) end, "'line'", "must be a number > 0")
    assert.error_contains(function () c:line(0, 0, 1, 1, 1, { 1, 2, 0 }) end, "'line'", "colour")
    assert.error_contains(function () c:rect(0, 0, -1, 1) end, "'rect'", ">= 0")
    assert.error_contains(function () c:rect(0, 0, 1) end, "'rect'", "number expected")
    assert.error_contains(function () c:text(0, 0, "x", 0) end, "scale must be an integer")
    assert.error_contains(function () c:polyline({ { 1, 2 }, { 3 } }) end,
      "points[2] must be {x, y}")
    assert.error_contains(function () c:polyline({ 1, 2, 3 }) end, "even length")
    assert.error_contains(function () c:polyline({ 1, 2, "x", 4 }) end,
      "points[3] must be a number")
  end)

  it("raises once closed", function ()
    local c = core.canvas(4, 4)
    do local d <close> = c; assert.equal(c, d) end
    assert.equal("Canvas (closed)", tostring(c))
    assert.error_contains(function () c:pixels() end, "the canvas was closed")
    assert.error_contains(function () c:line(0, 0, 1, 1) end, "the canvas was closed")
    assert.error_contains(function () c:size() end, "the canvas was closed")
  end)
end)
