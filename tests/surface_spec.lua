-- Bicubic surfaces (seed 004 §4.1, §4.3, Appendix A): core.surface_load, core.surface_parse,
-- Surface:info and core.patch_eval.
require "tests.helper"
local core = require "lsys.core"

local DIR = "tests/data/surfaces/"

-- The exact message of a failing call.
local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return msg
end

local function tmpfile (text)
  local path = os.tmpname()
  local f = assert(io.open(path, "wb"))
  f:write(text)
  f:close()
  return path
end

-- 16 control points (row r, column c) = f(r, c).
local function grid (f)
  local ctrl = {}
  for r = 0, 3 do
    for c = 0, 3 do ctrl[#ctrl + 1] = f(r, c) end
  end
  return ctrl
end

local HEAD = "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n" ..
             "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\n"

describe("core.surface_load", function()
  it("reads the sample leaf", function()
    local s = core.surface_load(DIR .. "leaf.s")
    local i = s:info()
    assert.equal(1, i.patches)
    assert.same({0, 0, 0}, i.contact)
    assert.same({0, 1, 0}, i["end"])
    assert.same({0, 1, 0}, i.heading)
    assert.same({0, 0, 1}, i.up)
    assert.same({-0.45, 0, 0}, i.lo)
    assert.same({0.45, 1, 0.1}, i.hi)
    assert.equal(1, i.size)
    assert.same({5, 8}, i.precision)
    assert.same({"blade"}, i.names)
    assert.equal("lsys.Surface(" .. DIR .. "leaf.s, 1 patch)", tostring(s))
  end)

  it("reads the two-patch petal", function()
    local s = core.surface_load(DIR .. "petal.s")
    local i = s:info()
    assert.equal(2, i.patches)
    assert.same({"base", "tip"}, i.names)
    assert.equal(1.1, i.size)
    assert.same({4, 4}, i.precision)
    assert.equal("lsys.Surface(" .. DIR .. "petal.s, 2 patches)", tostring(s))
  end)

  it("names the file when it cannot be opened", function()
    assert.equal("cannot open '" .. DIR .. "none.s': No such file or directory",
      errmsg(core.surface_load, DIR .. "none.s"))
  end)

  it("names the file and line of a malformed file", function()
    local path = tmpfile(HEAD .. "p\nTOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\n")
    local msg = errmsg(core.surface_load, path)
    os.remove(path)
    assert.equal(path .. ":9: patch 'p' ends early: expected 'AL: name A: name AR: name'", msg)
  end)

  it("checks its argument", function()
    assert.error_contains(function() core.surface_load() end, "bad argument #1")
  end)
end)

describe("core.surface_parse", function()
  it("reads a string, normalising HEADING and making UP orthogonal to it", function()
    local row = "0 0 0 1 0 0 2 0 0 3 0 0\n"
    local s = core.surface_parse("0 3 0 0 0 0\nCONTACT POINT X: 1 Y: 0 Z: 0\n" ..
      "END POINT X: 1 Y: 0 Z: 0\nHEADING X: 3 Y: 0 Z: 4\nUP X: 0 Y: 2 Z: 0\nSIZE: 3\n" ..
      "p\nTOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\n" ..
      "AL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: ~ BR: ~\n" .. row .. row .. row .. row, "x.s")
    local i = s:info()
    assert.near({0.6, 0, 0.8}, i.heading, 1e-15)
    assert.near({0, 1, 0}, i.up, 1e-15)
    assert.same({5, 5}, i.precision)
    assert.equal("lsys.Surface(x.s, 1 patch)", tostring(s))
  end)

  it("reports malformed text with the given name", function()
    assert.equal("x.s:4: HEADING is the zero vector",
      errmsg(core.surface_parse, "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\n" ..
        "END POINT X: 0 Y: 1 Z: 0\nHEADING X: 0 Y: 0 Z: 0\n", "x.s"))
    assert.equal("surface:1: bad bounding box line: 'a' is not a number",
      errmsg(core.surface_parse, "a b c"))
    assert.equal("x.s:7: expected a patch, found the end of the file",
      errmsg(core.surface_parse, HEAD, "x.s"))
  end)
end)

describe("core.patch_eval", function()
  local flat = grid(function(r, c) return {c, r, 0} end)

  it("reproduces a flat Bézier grid at any (s, t), s across columns", function()
    for _, st in ipairs { {0, 0}, {0.25, 0.5}, {1, 0}, {0.3, 0.9}, {1, 1} } do
      assert.near({3 * st[1], 3 * st[2], 0}, {core.patch_eval(1, flat, st[1], st[2])}, 1e-14)
    end
    assert.near({1.5, 1.5, 0}, {core.patch_eval("bezier", flat, 0.5, 0.5)}, 1e-15)
  end)

  it("weights a B-spline grid by (1, 4, 1) / 6 at the corner", function()
    local bump = grid(function(r, c) return {c, r, (r == 1 and c == 1) and 6 or 0} end)
    assert.near({1, 1, 6 * (4 / 6) * (4 / 6)}, {core.patch_eval("bspline", bump, 0, 0)}, 1e-14)
    assert.near({2, 1, 0}, {core.patch_eval(2, flat, 1, 0)}, 1e-14)
  end)

  it("passes a Cardinal patch through the middle control points", function()
    local wavy = grid(function(r, c) return {c * c, r + c, math.sin(r * 4 + c)} end)
    for _, rc in ipairs { {1, 1, 0, 0}, {1, 2, 1, 0}, {2, 1, 0, 1}, {2, 2, 1, 1} } do
      local p = wavy[4 * rc[1] + rc[2] + 1]
      assert.near(p, {core.patch_eval("cardinal", wavy, rc[3], rc[4])}, 1e-14)
    end
  end)

  it("checks its arguments", function()
    assert.error_contains(function() core.patch_eval(4, flat, 0, 0) end,
      "bad argument #1", "basis must be 1 (Bezier), 2 (B-spline) or 3 (Cardinal)")
    assert.error_contains(function() core.patch_eval("nurbs", flat, 0, 0) end,
      "bad argument #1", "invalid option 'nurbs'")
    assert.error_contains(function() core.patch_eval(1, {}, 0, 0) end,
      "bad argument #2", "expected 16 control points")
    local holed = grid(function(r, c) return {c, r, 0} end)
    holed[7] = {1, "x", 0}
    assert.error_contains(function() core.patch_eval(1, holed, 0, 0) end,
      "coordinate 2 of control point 7 is not a number")
    assert.error_contains(function() core.patch_eval(1, flat, 0 / 0, 0) end,
      "bad argument #3", "not a finite number")
  end)
end)
