-- Contours of generalized cylinders (cpfg guide §3.2.3, Appendix B.1): core.contour_load
-- (cpfg's files and vlab's versioned "cver" files), core.contour and Contour:sample.
require "tests.helper"
local core = require "lsys.core"

local DIR = "tests/data/contours/"

local function tmpfile (text)
  local path = os.tmpname()
  local f = assert(io.open(path, "wb"))
  f:write(text)
  f:close()
  return path
end

-- The exact message (assert.has_error would strip a leading "file:line: ").
local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return msg
end

local function len2 (v) return math.sqrt(v[1] * v[1] + v[2] * v[2]) end

describe("core.contour_load", function()
  it("reads the three contour files of Appendix B.1", function()
    local a = core.contour_load(DIR .. "fig12a.con")
    assert.equal(12, a:size())
    assert.is_true(a:closed())
    assert.equal(2, a:dim())
    assert.equal("lsys.Contour(12 points, closed)", tostring(a))
    local b = core.contour_load(DIR .. "fig13a.con")
    assert.equal(3, b:dim())
    local c = core.contour_load(DIR .. "fig16a.con")
    assert.equal(15, c:size())
    assert.is_false(c:closed())
    assert.equal("lsys.Contour(15 points, open)", tostring(c))
  end)

  it("accepts CRLF line ends, comments and blank lines", function()
    local path = tmpfile("# square\r\n4 2 closed\r\n\r\n1 -1\r\n1 1 # corner\r\n-1 1\r\n-1 -1\r\n")
    local c = core.contour_load(path)
    os.remove(path)
    assert.equal(4, c:size())
  end)

  it("raises errors that name the file and the line", function()
    local path = tmpfile("3 2 closed\n0 0\n1\n0 1\n")
    assert.equal(path .. ":3: expected 2 numbers, got 1", errmsg(core.contour_load, path))
    local f = assert(io.open(path, "wb"))
    f:write("15 2 open\n0 0\n")
    f:close()
    assert.equal(path .. ":3: file ends after 1 of 15 points", errmsg(core.contour_load, path))
    os.remove(path)
    assert.equal("cannot open '" .. path .. "': No such file or directory",
      errmsg(core.contour_load, path))
    assert.equal("cannot read 'tests/data': Is a directory",
      errmsg(core.contour_load, "tests/data"))
  end)

  it("rejects a file with a NUL byte or a non-finite number", function()
    local path = tmpfile("3 2 closed\n0 0\n1 \0\n0 1\n")
    assert.equal(path .. ":3: bad number '?'", errmsg(core.contour_load, path))
    local f = assert(io.open(path, "wb"))
    f:write("3 2 closed\n0 0\n1 inf\n0 1\n")
    f:close()
    assert.equal(path .. ":3: 'inf' is not a finite number", errmsg(core.contour_load, path))
    os.remove(path)
  end)

  it("refuses files larger than 16 MiB", function()
    local path = tmpfile(("#" .. ("x"):rep(1023) .. "\n"):rep(16 * 1024) .. "\n")
    assert.equal("cannot read '" .. path .. "': larger than 16 MiB",
      errmsg(core.contour_load, path))
    os.remove(path)
  end)
end)

describe("core.contour_load on vlab's versioned files", function()
  -- a leaf blade in "cver 1 3": 4 point lines, the ends tripled, 8 control points
  local BLADE = "cver 1 3\nname: blade\npoints: 4 8\ntype: or\nsamples: 8\n" ..
    "-2 0 0 3\n-1 0.5 0 1\n1 0.5 0 1\n2 0 0 3\n"

  it("reads cver 1 3, repeating each point as often as its multiplicity says", function()
    local path = tmpfile(BLADE)
    local c = core.contour_load(path)
    os.remove(path)
    assert.equal("lsys.Contour(8 points, open)", tostring(c))
    assert.equal(3, c:dim())
    local v = c:sample(10)
    assert.equal(11, #v)
    assert.near({ 2, 0, 0 }, v[1], 1e-12)      -- the tripled end points are the curve's ends
    assert.near(2, len2(v[11]), 1e-12)
  end)

  it("reads the closed types of cver 1 1 and 1 2", function()
    local path = tmpfile("cver 1 1\nname: square\npoints: 4 4\ntype: closed\n" ..
                         "1 -1 0 1\n1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n")
    local a = core.contour_load(path)
    local f = assert(io.open(path, "wb"))
    f:write("cver 1 2\nname: square\npoints: 4 4\ntype: cr\n" ..
            "1 -1 0 1\n1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n")
    f:close()
    local b = core.contour_load(path)
    os.remove(path)
    assert.equal("lsys.Contour(4 points, closed)", tostring(a))
    assert.same(a:sample(8), b:sample(8))
  end)

  it("sweeps a cver contour named in the view into a generalized cylinder", function()
    local lsys = require "lsys"
    local path = tmpfile(BLADE)
    local m = lsys.lsystem { axiom = "", view = { contour_sides = 10, contours = { [1] = path } } }
    local open = m:interpret(m:lstring("@#(1) @Gs f(2) @Ge(5)"))
    local f = assert(io.open(path, "wb"))
    f:write("cver 1 2\nname: square\npoints: 4 4\ntype: cr\n" ..
            "1 -1 0 1\n1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n")
    f:close()
    m = lsys.lsystem { axiom = "", view = { contour_sides = 10, contours = { [1] = path } } }
    local closed = m:interpret(m:lstring("@#(1) @Gs f(2) @Ge(5)"))
    os.remove(path)
    assert.equal(5 * 20, open.ntriangles)       -- 5 strips of 10 quads, uncapped
    assert.equal(5 * 20 + 2 * 8, closed.ntriangles)   -- and two caps of 8 triangles
  end)

  it("raises errors that name the file and the line", function()
    local path = tmpfile("cver 1 4\nname: x\n")
    assert.equal(path .. ":1: unknown contour format 'cver 1 4' (lsys reads cver 1 1, 1 2 and 1 3)",
      errmsg(core.contour_load, path))
    local f = assert(io.open(path, "wb"))
    f:write((BLADE:gsub("2 0 0 3\n$", "2 0 0 4\n")))
    f:close()
    assert.equal(path .. ":9: the multiplicities add up to more than the 8 points of line 3",
      errmsg(core.contour_load, path))
    os.remove(path)
  end)
end)

describe("core.contour", function()
  it("makes a contour from a list of points", function()
    local c = core.contour({ { 1, -1 }, { 1, 1 }, { -1, 1 }, { -1, -1 } })
    assert.equal(4, c:size())
    assert.is_true(c:closed())
    assert.equal(2, c:dim())
    local o = core.contour({ { 0, 0, 0 }, { 0, 0, 0 }, { 1, 0, 1 }, { 2, 0, 0 } }, false)
    assert.is_false(o:closed())
    assert.equal(3, o:dim())
  end)

  it("checks its arguments", function()
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, 0 } }) end,
      "bad argument #1", "a closed contour needs at least 3 points, got 2")
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, 0 }, { 1, 1 } }, false) end,
      "an open contour needs at least 4 points, got 3")
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, 0 }, { 1, 1, 1 } }) end,
      "point 3 has 3 coordinates, point 1 has 2")
    assert.error_contains(function() core.contour({ { 0 }, { 1 }, { 1 } }) end,
      "point 1 has 1 coordinates, not 2 or 3")
    assert.error_contains(function() core.contour({ { 0, 0 }, 5, { 1, 1 } }) end,
      "point 2 is a number, not a table")
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, "x" }, { 1, 1 } }) end,
      "coordinate 2 of point 2 is a string, not a number")
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, 0 / 0 }, { 1, 1 } }) end,
      "point 2: coordinate 2 is not finite")
    assert.error_contains(function() core.contour({ { 0, 0 }, { 1, 0 }, { 1, 1 } }, "yes") end,
      "bad argument #2", "boolean expected")
    assert.error_contains(function() core.contour("square") end, "table expected")
  end)
end)

describe("Contour:sample", function()
  it("gives p + 1 vertices and unit normals, V_0 on +x and V_p = V_0 when closed", function()
    local c = core.contour_load(DIR .. "fig12a.con")
    local v, n = c:sample(32)
    assert.equal(33, #v)
    assert.equal(33, #n)
    assert.equal(0, v[1][2])
    assert.is_true(v[1][1] > 0)
    assert.same(v[1], v[33])
    for i = 1, 33 do
      assert.equal(3, #v[i])
      assert.near(1, len2(n[i]), 1e-12)
      assert.equal(0, n[i][3])
      assert.equal(0, v[i][3])
    end
  end)

  it("places the vertices of a circle at equal distances, normals outward", function()
    local pts = {}
    for i = 0, 35 do
      local a = 2 * math.pi * (i / 36) ^ 2          -- uneven spacing of the control points
      pts[#pts + 1] = { math.cos(a), math.sin(a) }
    end
    local v, n = core.contour(pts):sample(16)
    local d = {}
    for i = 1, 16 do d[i] = math.sqrt((v[i + 1][1] - v[i][1]) ^ 2 + (v[i + 1][2] - v[i][2]) ^ 2) end
    local mean = 0
    for i = 1, 16 do mean = mean + d[i] / 16 end
    for i = 1, 16 do assert.near(mean, d[i], 0.01 * mean) end
    for i = 1, 17 do
      local r = len2(v[i])
      assert.is_true(r > 0.97 and r < 1)
      assert.is_true((v[i][1] * n[i][1] + v[i][2] * n[i][2]) / r > 0.999)
    end
  end)

  it("starts and ends an open contour at its tripled end points", function()
    local c = core.contour_load(DIR .. "fig16a.con")
    local v = c:sample(7)
    assert.equal(8, #v)
    assert.near({ math.sqrt(0.914286 ^ 2 + 0.4 ^ 2), 0, 0 }, v[1], 1e-12)
    assert.near(math.sqrt(0.971429 ^ 2 + 0.142857 ^ 2), len2(v[8]), 1e-12)
  end)

  it("checks the number of sides", function()
    local c = core.contour_load(DIR .. "fig12a.con")
    assert.error_contains(function() c:sample(2) end, "bad argument #1", "between 3 and 65536")
    assert.error_contains(function() c:sample(1.5) end, "number has no integer representation")
    assert.error_contains(function() core.contour_load(DIR .. "fig12a.con").sample({}, 8) end,
      "lsys.Contour expected")
  end)
end)
