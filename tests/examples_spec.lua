-- The runnable examples of the cpfg guide (examples/cpfg): every model file loads, derives
-- and interprets without error to exactly the geometry it made when its picture was
-- checked, and the files the examples read (contours, surfaces, textures, view files) are
-- what their generators write.
--
-- The counts are { modules in the derived string, triangles, lines } per model. They were
-- taken once from pictures that were looked at (examples/gallery/cpfg); a change in the
-- turtle, the generalized cylinders, contours, surfaces or polygons that changes one of
-- them needs a new look at that picture before the number is updated here. Some are easy
-- to check by hand: fig05 b is 6 strips of 8 quadrilaterals (96 triangles) and two
-- octagonal caps of 6 triangles each; fig12 b is 8 strips of 32 sides and two caps of 30;
-- a petal of fig27 is @PD(0,12,12), 2 * 12 * 12 triangles; fig34 is one polygon of 12
-- vertices.
require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local DIR = "examples/cpfg"

local COUNTS = {
  fig05 = { a = { 21, 836, 2 }, b = { 7, 108, 0 } },
  fig06 = { { 41, 300, 0 } },
  fig07 = { a = { 199, 0, 84 }, b = { 201, 8074, 0 } },
  fig08 = { { 107, 3700, 10 } },
  fig09 = { a = { 103, 0, 49 }, bcd = { 28, 3012, 0 } },
  fig10 = { a = { 8, 1004, 0 }, b = { 6, 308, 0 }, c = { 6, 308, 0 } },
  fig11 = { a = { 355, 22486, 0 }, b = { 383, 30262, 0 } },
  fig12 = { a = { 486, 1440, 208 }, b = { 5, 572, 0 }, c = { 5, 572, 0 } },
  fig13 = { a = { 486, 1440, 208 }, b = { 5, 572, 0 }, c = { 5, 572, 0 } },
  fig14 = { b = { 7, 1052, 0 }, c = { 570, 40684, 0 } },
  fig15 = { a = { 1, 828, 0 }, c = { 182, 25852, 0 } },
  fig16 = { a = { 501, 1800, 208 }, b = { 10, 1280, 0 }, c = { 10, 1280, 0 } },
  fig17 = { a = { 187, 15360, 0 }, b = { 307, 25600, 0 }, c = { 307, 25600, 0 } },
  fig18 = { { 277, 34752, 0 } },
  fig19 = { a = { 8, 1052, 0 }, b = { 8, 1052, 0 }, c = { 100, 9308, 0 } },
  fig21 = { a = { 14, 288, 0 }, b = { 14, 1134, 0 }, c = { 14, 554, 0 } },
  fig22 = { { 140, 1964, 0 } },
  fig23 = { { 2058, 23504, 0 } },     -- the leaflets' edges drawn too, as cpfg
  fig24 = { { 85, 1450, 16 } },
  fig25 = { { 73, 845, 6 } },
  fig27 = { a = { 85, 288, 0 }, b = { 85, 288, 0 }, c = { 85, 288, 0 }, d = { 85, 288, 0 },
            e = { 85, 288, 0 }, all = { 440, 1440, 0 } },
  fig28 = { all = { 528, 1728, 0 }, final = { 85, 288, 0 } },
  fig31 = { a = { 1, 256, 0 }, b = { 1, 256, 0 } },
  fig33 = { a = { 13, 240, 0 }, b = { 111, 5392, 0 } },
  fig34 = { a = { 71, 10, 0 }, b = { 71, 10, 0 } },
}

-- The model files of the directory (plot.lua is a helper the files load, not a model).
local function files ()
  local out = {}
  local p = assert(io.popen("ls " .. DIR .. "/*.lua"))
  for f in p:lines() do
    local base = f:match("([^/]*)%.lua$")
    if base ~= "plot" then out[#out + 1] = base end
  end
  p:close()
  table.sort(out)
  return out
end

local function sorted_keys (t)
  local out = {}
  for k in pairs(t) do out[#out + 1] = k end
  table.sort(out, function (a, b) return tostring(a) < tostring(b) end)
  return out
end

local function scene (file, name)
  local t = dofile(DIR .. "/" .. file .. ".lua")
  local m = name and t[name] or t
  local s = m:derive()
  return m:interpret(s), s
end

describe("examples/cpfg", function ()
  it("has a count for every model file and a model file for every count", function ()
    assert.same(sorted_keys(COUNTS), files())
  end)

  for _, file in ipairs(sorted_keys(COUNTS)) do
    local expect = COUNTS[file]
    it(file .. " returns the expected models and draws each with the expected geometry",
    function ()
      local t = dofile(DIR .. "/" .. file .. ".lua")
      if expect[1] then
        assert.is_function(t.derive)
      else
        assert.is_nil(t.derive)
        assert.same(sorted_keys(expect), sorted_keys(t))
      end
      for _, name in ipairs(sorted_keys(expect)) do
        local m = name == 1 and t or t[name]
        local s = m:derive()
        local sc = m:interpret(s)
        local got = { #s, sc.ntriangles, sc.nlines }
        assert.same(expect[name], got, file .. " " .. tostring(name))
      end
    end)
  end
end)

describe("examples/cpfg models", function ()
  it("fig14: the stochastic cactus is the same on every run, another with another seed",
  function ()
    local _, s1 = scene("fig14", "c")
    local _, s2 = scene("fig14", "c")
    assert.equal(tostring(s1), tostring(s2))
    local m = dofile(DIR .. "/fig14.lua").c
    m.seed = 3
    assert.are_not.equal(tostring(s1), tostring(m:derive()))
  end)

  it("fig14: an apex whose heading points down becomes a cut (%) in the next step",
  function ()
    local m = dofile(DIR .. "/fig14.lua").c
    local total = 0
    for k = 6, m.steps - 1 do
      local down, prev = 0, nil
      for _, name, _, y in m:derive(k):modules() do
        if prev == "A" and name == "?H" and y < 0 then down = down + 1 end
        prev = name
      end
      assert.equal(down, m:derive(k + 1):count("%"), "step " .. k)
      total = total + down
    end
    assert.is_true(total > 0)
  end)

  it("fig19: without twist minimisation the roll twists the segment, with it not",
  function ()
    local a, b = scene("fig19", "a"), scene("fig19", "b")
    assert.equal(a.ntriangles, b.ntriangles)
    -- a twisted star prism has the longer (helical) ridges, so the larger area
    assert.is_true(a:area() > b:area() * 1.005)
  end)

  it("fig31: a texture per surface changes texture coordinates, not geometry", function ()
    local a, b = scene("fig31", "a"), scene("fig31", "b")
    assert.near(a:area(), b:area(), 1e-9)
    local function vt (sc)
      local path = os.tmpname() .. ".obj"
      sc:save(path)
      local out, v = {}, {}
      for line in io.lines(path) do
        if line:match("^vt ") then out[#out + 1] = line end
        if line:match("^v ") then v[#v + 1] = line end
      end
      os.remove(path)
      os.remove((path:gsub("%.obj$", ".mtl")))
      return out, v
    end
    local ta, va = vt(a)
    local tb, vb = vt(b)
    assert.equal(162, #ta)
    assert.same(va, vb)
    assert.are_not.same(ta, tb)
  end)

  it("fig27: the five petals side by side are the five models' strings", function ()
    local t = dofile(DIR .. "/fig27.lua")
    local all = tostring(t.all:derive())
    for _, k in ipairs { "a", "b", "c", "d", "e" } do
      assert.truthy(all:find(tostring(t[k]:derive()), 1, true), k)
    end
  end)

  it("fig28: the interpolated values reach the final shape and stop there", function ()
    local m = dofile(DIR .. "/fig28.lua").final
    local s = m:derive()
    local lens = {}
    for _, name, v, V, i in s:modules() do
      if name == "f" and i and i ~= 0 then lens[#lens + 1] = { v, V } end
    end
    assert.is_true(#lens > 0)
    for _, p in ipairs(lens) do assert.near(p[2], p[1], 1e-9) end
    -- two steps more change nothing
    assert.equal(tostring(s), tostring(m:derive(m.steps + 2)))
  end)
end)

describe("examples/cpfg data files", function ()
  it("fig14.v and fig15.v load as view files with their contours", function ()
    local v14 = lsys.view.load(DIR .. "/fig14.v")
    assert.equal(60, v14.angle)
    assert.equal(48, v14.contour_sides)
    assert.same({ 0, 1, 0 }, v14.tropisms[1].vector)
    assert.equal("contours/cactus.con", v14.contours[2])
    local v15 = lsys.view.load(DIR .. "/fig15.v")
    assert.equal(32, v15.contour_sides)
    assert.equal("contours/aloe_leaf.con", v15.contours[2])
    assert.equal("contours/aloe_flower.con", v15.contours[3])
  end)

  it("every contour file parses", function ()
    local p = assert(io.popen("ls " .. DIR .. "/contours/*.con"))
    local n = 0
    for f in p:lines() do
      local c = core.contour_load(f)
      assert.truthy(c, f)
      n = n + 1
    end
    p:close()
    assert.equal(10, n)
  end)

  it("surfaces/make.lua writes the committed surface files", function ()
    local tmp = os.tmpname()
    os.remove(tmp)
    assert(os.execute("mkdir -p " .. tmp))
    assert(loadfile(DIR .. "/surfaces/make.lua"))(tmp)
    for _, f in ipairs { "petal.s", "calyx.s", "leaf.s" } do
      local a = assert(io.open(DIR .. "/surfaces/" .. f)):read("a")
      local b = assert(io.open(tmp .. "/" .. f)):read("a")
      assert.equal(a, b, f)
      assert.truthy(core.surface_load(tmp .. "/" .. f))
      os.remove(tmp .. "/" .. f)
    end
    os.remove(tmp)
  end)

  it("textures/make.lua draws the committed texture images", function ()
    local tmp = os.tmpname()
    os.remove(tmp)
    assert(os.execute("mkdir -p " .. tmp))
    assert(loadfile(DIR .. "/textures/make.lua"))(tmp)
    for _, f in ipairs { "chessboard.png", "bark.png", "venation.png", "aloe.png" } do
      local pa, wa, ha = core.png_read(DIR .. "/textures/" .. f)
      local pb, wb, hb = core.png_read(tmp .. "/" .. f)
      assert.same({ f == "aloe.png" and 64 or 128, 128 }, { wa, ha }, f)
      assert.same({ wa, ha }, { wb, hb }, f)
      assert.is_true(pa == pb, f .. ": pixels differ")
      os.remove(tmp .. "/" .. f)
    end
    os.remove(tmp)
  end)
end)

-- The figures of Anastacio et al. 2009 (examples/sketch): each model file draws the plant
-- its picture in examples/gallery/sketch showed when it was looked at. The counts depend on
-- the sketch pipeline (lsys.sketch) and the organs' patches: a change there that changes
-- one of them needs a new look at that picture before the number is updated here.
describe("examples/sketch", function ()
  local SDIR = "examples/sketch"
  local SCOUNTS = {
    fig7 = { cone = { 3095, 28304, 0 }, flower = { 435, 3920, 0 } },
    fig8 = { decussate = { 268, 2736, 0 }, distichous = { 228, 2736, 0 },
             fibonacci = { 164, 1712, 0 } },
    fig9 = { double = { 2742, 17296, 0 }, single = { 215, 1376, 0 } },
    fig10 = { diagonal = { 318, 2192, 0 }, flat = { 222, 2192, 0 }, front = { 318, 2192, 0 },
              side = { 318, 2192, 0 } },
    fig11 = { { 582, 5728, 0 } },
    fig12 = { { 842, 5728, 0 } },
    fig13 = { { 548, 8400, 0 } },
    fig14 = { { 774, 8400, 0 } },
  }

  it("has a count for every model file and a model file for every count", function ()
    local out = {}
    local p = assert(io.popen("ls " .. SDIR .. "/fig*.lua"))
    for f in p:lines() do out[#out + 1] = f:match("([^/]*)%.lua$") end
    p:close()
    table.sort(out)
    assert.same(sorted_keys(SCOUNTS), out)
  end)

  for _, file in ipairs(sorted_keys(SCOUNTS)) do
    local expect = SCOUNTS[file]
    it(file .. " draws each model with the expected geometry", function ()
      local t = dofile(SDIR .. "/" .. file .. ".lua")
      if expect[1] then assert.is_function(t.derive) else assert.is_nil(t.derive) end
      for _, name in ipairs(sorted_keys(expect)) do
        local m = name == 1 and t or t[name]
        local s = m:derive()
        local sc = m:interpret(s)
        assert.same(expect[name], { #s, sc.ntriangles, sc.nlines }, file .. " " .. tostring(name))
      end
    end)
  end

  it("fig8: the patterns put 2, 2 and 1 leaves on each node of the same sketch", function ()
    local t = dofile(SDIR .. "/fig8.lua")
    local n = t.fibonacci:derive():count("Organ")
    assert.is_true(n > 10)
    assert.equal(2 * n, t.decussate:derive():count("Organ"))
    assert.equal(2 * n, t.distichous:derive():count("Organ"))
  end)

  it("fig13: the composed foxglove has the organs of both sketches and one drawn stem",
  function ()
    local lsys_sketch = require "lsys.sketch"
    local leaves = lsys_sketch.load(SDIR .. "/fig13_leaves.json"):model {}
    local flowers = lsys_sketch.load(SDIR .. "/fig13_flowers.json"):model {}
    local s = dofile(SDIR .. "/fig13.lua"):derive()
    local sl, sf = leaves:derive(), flowers:derive()
    assert.equal(sl:count("Organ"), s:count("Organ"))
    assert.equal(sf:count("Organ"), s:count("Organ2"))
    assert.equal(sl:count("F"), s:count("F"))           -- the leaves' stem, drawn
    assert.equal(sf:count("F"), s:count("f"))           -- the flowers', moved along
  end)

  it("the sketch files load and the organ files build", function ()
    local lsys_sketch, organ = require "lsys.sketch", require "lsys.sketch.organ"
    local p = assert(io.popen("ls " .. SDIR .. "/*.json"))
    local ns, no = 0, 0
    for f in p:lines() do
      if f:match("/organ_[^/]*$") then
        assert.truthy(organ.load(f):surface(), f)
        no = no + 1
      else
        assert.truthy(#lsys_sketch.load(f):analysis().nodes > 0, f)
        ns = ns + 1
      end
    end
    p:close()
    assert.same({ 14, 8 }, { ns, no })
  end)
end)
