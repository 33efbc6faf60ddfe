-- Bicubic surfaces (cpfg guide §4.1, §4.3, Appendix A): core.surface_load, core.surface_parse,
-- Surface:info and core.patch_eval.
local H = require "tests.helper"
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

describe("surfaces drawn by the turtle", function()
  local lsys = require "lsys"
  local function model(view)
    view = view or { surfaces = { L = "tests/data/surfaces/leaf.s" } }
    return lsys.lsystem { axiom = "", view = view }
  end
  local function scene(text, view)
    local m = model(view)
    return m:interpret(m:lstring(text))
  end

  it("puts ~X's contact point at the turtle, its heading along H (cpfg guide §4.1)", function()
    local sc = scene("~L")
    assert.equal(5 * 8 * 2, sc.ntriangles)          -- PRECISION S: 5 T: 8
    assert.equal(6 * 9, sc.nvertices)
    local lo, hi = sc:bounds()
    assert.near(0, lo[2], 1e-6); assert.near(1, hi[2], 1e-6)
    assert.is_true(hi[1] > 0.3 and lo[1] < -0.3)    -- the blade's width along L
    -- turned: after +(90) the leaf runs along -x
    lo, hi = scene("+(90) ~L"):bounds()
    assert.near(-1, lo[1], 1e-6); assert.near(0, hi[1], 1e-6)
  end)

  it("turns a surface whose UP is off the axes as cpfg does (x l + y h + z u)", function()
    -- cpfg: ?P after each (tests/data/surfaces/tilted.s: UP 0.6, 0, -0.8; patches.c reads a
    -- point as x l + y h + z u with l = h x u, then along the turtle's L, H, U)
    local v = { surfaces = { t = DIR .. "tilted.s" } }
    local cases = {
      { "~t(1)", { -0.266667, 0.666667, -0.0333333 } },
      { "/(30)&(20)F(1)~t(2)F(1)", { 0.139476, 3.10951, -1.30825 } },
      { "+(40)^(70)\\(10)~t(1.5)", { -0.516047, -0.0113417, 0.946608 } },
    }
    for _, c in ipairs(cases) do
      local m = lsys.lsystem { axiom = c[1] .. "?P(0,0,0)", steps = 0, view = v }
      local s = m:derive()
      assert.near(c[2], { select(2, s:module(#s)) }, 1e-5)
    end
    -- its points are turned so too: the patch's corner (0, 0, 0) is (-1, 0, 0) from the
    -- contact point, 1/3 of it at SIZE 3: x l = (0.8, 0, 0.6) / 3, then along L = (-1, 0, 0)
    -- and U = (0, 0, -1) of the first frame
    local out = os.tmpname() .. ".obj"
    scene("~t", v):save(out)
    local found = false
    for line in io.lines(out) do
      local x, y, z = line:match("^v (%S+) (%S+) (%S+)")
      if x and math.abs(x + 0.8 / 3) < 1e-6 and math.abs(y) < 1e-6 and
         math.abs(z + 0.2) < 1e-6 then found = true end
    end
    os.remove(out)
    os.remove((out:gsub("%.obj$", ".mtl")))
    assert.is_true(found)
  end)

  it("scales along L, H and U with three parameters, as cpfg; by the first with two",
     function()
    -- cpfg: the box of its rayshade output (-ray) and ?P; the end point scales by the first
    local v = { surfaces = { t = DIR .. "tilted.s" } }
    local cases = {
      { "~t(1,2,3)", { -0.26667, 0, -0.6 }, { 0.63333, 2, 0.8 },
        { -0.266667, 0.666667, -0.0333333 } },
      { "/(30)&(20)~t(0.5,1,2)", { -0.076536, -0.13681, -0.68838 },
        { 0.24348, 1.1221, 0.59236 }, { -0.0506359, 0.307531, -0.178963 } },
      { "~t(2,1)", { -0.53333, 0, -0.4 }, { 1.2667, 2, 0.53333 },
        { -0.533333, 1.33333, -0.0666666 } },
    }
    for _, c in ipairs(cases) do
      local m = lsys.lsystem { axiom = c[1] .. "?P(0,0,0)", steps = 0, view = v }
      local s = m:derive()
      local lo, hi = m:interpret(s):bounds()
      assert.near(c[2], lo, 1e-4)
      assert.near(c[3], hi, 1e-4)
      assert.near(c[4], { select(2, s:module(#s)) }, 1e-5)
    end
    assert.equal(0, scene("~t(1,0,1)", v).ntriangles)       -- a scale of 0: nothing drawn
    assert.equal(0, scene("~t(0)", v).ntriangles)
  end)

  it("leaves the turtle at the end point, scaled by the parameter and the entry", function()
    local sc = scene("~L F")
    assert.near({ 0, 1, 0 }, sc:record(2).p0, 1e-6)
    assert.equal("surface", sc:record(1).kind)
    sc = scene("~L(2) F")
    assert.near({ 0, 2, 0 }, sc:record(2).p0, 1e-6)
    sc = scene("~L(2) F",
               { surfaces = { L = { file = "tests/data/surfaces/leaf.s", scale = 0.25 } } })
    assert.near({ 0, 0.5, 0 }, sc:record(2).p0, 1e-6)
  end)

  it("tessellates with the entry's precision", function()
    local sc = scene("~L", { surfaces = { L = { file = "tests/data/surfaces/leaf.s",
                                                precision = { 2, 3 } } } })
    assert.equal(2 * 3 * 2, sc.ntriangles)
  end)

  it("draws L-system defined patches with @PS @PC @PD (§4.3)", function()
    local cps = {}
    for r = 0, 3 do
      for c = 0, 3 do cps[#cps + 1] = ("@M(%d,%d,0) @PC(0,%d,%d)"):format(c, r, r, c) end
    end
    for basis = 1, 3 do
      local sc = scene(("@PS(0,%d) %s @PD(0,3,4)"):format(basis, table.concat(cps, " ")))
      assert.equal(3 * 4 * 2, sc.ntriangles)
      assert.equal(4 * 5, sc.nvertices)
      local lo, hi = sc:bounds()
      if basis == 1 then                             -- Bezier: spans the control net
        assert.near({ 0, 0, 0 }, lo, 1e-6); assert.near({ 3, 3, 0 }, hi, 1e-6)
      elseif basis == 3 then                         -- Cardinal: the middle points
        assert.near({ 1, 1, 0 }, lo, 1e-6); assert.near({ 2, 2, 0 }, hi, 1e-6)
      end
    end
    assert.equal(2 * 4 * 4 * 2, scene("@PS(3) @PD(3) @PD(3,4,4)").ntriangles)
  end)

  it("draws nothing for an undefined surface, as cpfg, and warns naming the first", function()
    local sc = scene("F ~Q(2) F ~Q ~R")
    assert.equal(0, sc.ntriangles)
    assert.equal(2, sc.nlines)                          -- the turtle did not move: 0..1..2
    local p = sc:turtle(5)
    assert.near({ 0, 2, 0 }, p, 1e-12)
    local dir = H.tmpdir()
    H.write(dir .. "/w.lua", 'local lsys = require "lsys"\n'
      .. 'lsys.lsystem { axiom = "F ~Q(2) F ~R" }:interpret()\n')
    local out, code = H.sh(H.BIN .. " " .. dir .. "/w.lua")
    H.rmdir(dir)
    assert.equal(0, code, out)
    assert.equal("Lua warning: lsys: module 2 '~Q': no such surface in the view "
                 .. "(view.surfaces); nothing drawn there, as in cpfg\n", out)
  end)

  it("rejects bad patch modules, naming the module", function()
    assert.error_contains(function() scene("@PD(1,4,4)") end, "module 1 '@PD'",
                          "patch 1 was not started with @PS(1)")
    assert.error_contains(function() scene("@PS(0) @PC(0,4,0)") end, "'@PC'",
                          "the row must be from 0 to 3, got 4")
    assert.error_contains(function() scene("@PS(0,5)") end, "'@PS'", "the basis")
    assert.error_contains(function() scene("@PS(2000)") end, "the patch number")
    assert.error_contains(function() scene("@PS(0) @PD(0,300)") end, "the number of lines")
  end)
end)
