-- A sketched plant as a cpfg model (lsys.sketch.cpfg; Anastacio et al. 2009, §7, exported
-- their models to L-studio/cpfg): the files written, lsys reading them back to the
-- sketch's plant (with cpfg's own approximation of functions too), and cpfg itself, the
-- oracle, deriving the same string. cpfg is found through LSYS_CPFG (the path of cpfg's
-- wrapper, docs/cpfg.md "cpfg as a reference") or on PATH; without it those cases are
-- pending (it is not built in CI).
local H = require "tests.helper"
local lsys = require "lsys"
local sketch = require "lsys.sketch"
local organ = require "lsys.sketch.organ"
local cpfgw = require "lsys.sketch.cpfg"

local line = require("tests.helper").line

-- The synthetic sketch of tests/sketch_spec.lua with a leaning stem and a tilted right
-- boundary, so that every function has slopes; `p` a pressure (3D) or nil.
local function load (p, n)
  return sketch.load({ width = 400, height = 600, nodes_per_layer = n or 2, strokes = {
    { role = "stem", points = { { 200, 500, p }, { 210, 300, p and 0.6 }, { 230, 100, p } } },
    { role = "boundary_left", points = line(150, 520, 140, 80, 40) },
    { role = "boundary_right", points = line(247.5, 520, 302.5, 80, 40) },
    { role = "inclination", points = line(120, 400, 280, 410, 20) },
    { role = "inclination", points = line(120, 300, 330, 290, 20) },
    { role = "inclination", points = line(120, 200, 330, 200, 20) },
  } }, { name = "syn" })
end

local function rectorgan ()
  return organ.build { top = { left = { { 100, 300 }, { 100, 100 } },
                               right = { { 200, 300 }, { 200, 100 } } } }
end

-- The modules of a string as text: { name, {params} }; whitespace (cpfg wraps its lines)
-- is not part of it.
local function modules (text)
  local s, out, i = text:gsub("%s", ""), {}, 1
  while i <= #s do
    local c = s:sub(i, i)
    local name
    if c == "?" and s:sub(i + 1, i + 1) == "(" then name, i = "?", i + 1
    elseif c == "@" or c == "?" then name, i = s:sub(i, i + 1), i + 2
    elseif c:match("%a") then name = s:match("^%a%w*", i); i = i + #name
    else name, i = c, i + 1 end
    local p = {}
    if s:sub(i, i) == "(" then
      local e = s:find(")", i, true)
      for v in s:sub(i + 1, e - 1):gmatch("[^,]+") do p[#p + 1] = tonumber(v) end
      i = e + 1
    end
    out[#out + 1] = { name, p }
  end
  return out
end

-- The names of the modules of the .l file (its "/* modules: A = A, O = Organ */" line).
local function letters (ltext)
  local map = {}
  for a, b in (ltext:match("/%* modules: (.-) %*/") or ""):gmatch("(%a) = (%w+)") do
    map[a] = b
  end
  return map
end

-- Nil when the string `got` (cpfg's names, sub-L-systems numbered from 2) is lsys's
-- string `want` module by module, parameters within `tol` relative (and 1e-9 absolute);
-- else where they part.
local function differs (got, want, map, tol)
  local a, b = modules(got), modules(tostring(want))
  if #a ~= #b then return string.format("%d modules, not %d", #a, #b) end
  for k = 1, #a do
    local name, p = map[a[k][1]] or a[k][1], a[k][2]
    if name == "?" then p[1] = p[1] - 1 end
    if name ~= b[k][1] or #p ~= #b[k][2] then
      return string.format("module %d: %s, not %s", k, name, b[k][1])
    end
    for j, v in ipairs(p) do
      local w = b[k][2][j]
      if math.abs(v - w) > tol * math.abs(w) + 1e-9 then
        return string.format("module %d (%s), parameter %d: %.9g, not %.9g", k, name, j, v, w)
      end
    end
  end
  return nil
end

describe("the cpfg files of a sketch (sk:save_cpfg)", function ()
  it("writes the L-system, its view, the functions, a colour map and the organ", function ()
    local d = H.tmpdir()
    local files, inexact = load():save_cpfg(d .. "/plant.l", { organ = rectorgan() })
    assert.equal(0, inexact)
    table.sort(files)
    local names = {}
    for i, f in ipairs(files) do names[i] = f:sub(#d + 2) end
    assert.same({ "plant.angle_left.func", "plant.angle_right.func", "plant.internode.func",
                  "plant.l", "plant.map", "plant.organ.s", "plant.size_left.func",
                  "plant.size_right.func", "plant.stem_shape.func", "plant.v" }, names)
    assert.equal(table.concat({ "initial line width: 0.01 polygons", "line style: cylinder",
      "initial color: 1", "line width increment: 0", "function: plant.angle_left.func",
      "function: plant.angle_right.func", "function: plant.internode.func",
      "function: plant.size_left.func", "function: plant.size_right.func",
      "function: plant.stem_shape.func", "surface: P plant.organ.s 1" }, "\n") .. "\n",
      H.read(d .. "/plant.v"))
    local l = H.read(d .. "/plant.l")
    for _, want in ipairs {
      "\n#define internode(x) func(3, x)\n", "\n#define stem_shape(x) func(6, x)\n",
      "\n#define D 0.03125\n", "\nLsystem: 1\n", "\nAxiom: A(0)\n",
      "\nA(x) : x < XT --> S(x, internode(x)) B(x + internode(x)) A(x + internode(x))\n",
      "\nL(x) --> [+(angle_left(x)) O(size_left(x))]\n",
      "\nhomomorphism\nO(h) --> ;(2) ~P(h)\nendlsystem\n",
      "/* modules: A = A, B = B, C = C, L = L, O = Organ, R = R, S = S */" } do
      assert.truthy(l:find(want, 1, true), want)
    end
    assert.is_nil(l:find("§", 1, true))                  -- ASCII for cpfg's lexer
    -- the colour map: 256 colours, the default palette's bark (1) and leaf green (2)
    local map = H.read(d .. "/plant.map")
    assert.equal(768, #map)
    assert.same({ 107, 74, 46, 77, 140, 43 }, { map:byte(4, 9) })
    assert.equal(rectorgan():text(), H.read(d .. "/plant.organ.s"))
    H.rmdir(d)
  end)

  it("makes the functions flat where the plant reads them, as cpfg reads them", function ()
    -- cpfg finds x only within 0.001 (splinefun.cpp), so on a slope its value is off;
    -- flat within 0.0015 of each reading, its value there is the exact one
    local f = lsys.func.new { points = { { 0, 0 }, { 0, 0 }, { 1, 10 }, { 1, 10 } } }
    local pts, inexact = cpfgw.plateaus(f, { { 0, 0 }, { 1, 10 } }, { 0.3, 0.5, 0.5015 })
    assert.equal(2, inexact)                     -- 0.5 and 0.5015 are 0.0015 apart
    local g = lsys.func.new { points = require("lsys.sketch.functions").controls(pts) }
    for _, x in ipairs { 0.3 - 0.0014, 0.3 - 0.001, 0.3, 0.3 + 0.0014 } do
      assert.near(3, g(x), 1e-12)
    end
    assert.near(5, g(0.5 - 0.0014), 1e-12)
    assert.near(f(0.5015), g(0.5015), 1e-12)
    assert.near(8, g(0.8), 1e-12)                -- elsewhere the function as it was
    assert.near(1, g(0.1), 1e-12)
    -- as cpfg computes them: the sketch's values at the readings, not 0.001 off
    local cp = lsys.func.new { points = g:points(), approx = "cpfg" }
    local raw = lsys.func.new { points = f:points(), approx = "cpfg" }
    assert.near(3, cp(0.3), 1e-6)
    assert.is_true(math.abs(raw(0.3) - 3) > 1e-4, "cpfg's plain value " .. raw(0.3))
  end)

  for _, ph in ipairs { "distichous", "decussate", "fibonacci" } do
    it("reads back (lsys.cpfg.load) to the sketch's plant, " .. ph .. ", 2D and 3D", function ()
      for _, p in ipairs { false, 0.5 + 0.2 } do
        local sk = load(p or nil)
        local d = H.tmpdir()
        sk:save_cpfg(d .. "/plant.l", { phyllotaxis = ph })
        local map = letters(H.read(d .. "/plant.l"))
        local want = sk:model { phyllotaxis = ph }:derive()
        assert.is_true(#want > 50)
        for _, approx in ipairs { "cpfg", "exact" } do
          local m = lsys.cpfg.load(d .. "/plant.l", d .. "/plant.v", { functions = approx })
          assert.is_nil(differs(tostring(m:derive()), want, map, 2e-6), ph .. " " .. approx)
        end
        H.rmdir(d)
      end
    end)
  end

  it("writes compositions and plants as organs (sub-L-systems from 2)", function ()
    local inner = load():model { organ = rectorgan() }
    local cases = {
      composed = sketch.compose { load():model { organ = rectorgan() },
                                  load(0.7):model { phyllotaxis = "fibonacci" } },
      nested = load():model { organ = inner },
    }
    for name, m in pairs(cases) do
      local d = H.tmpdir()
      local _, inexact = sketch.save_cpfg(m, d .. "/plant.l")
      assert.equal(0, inexact)
      local l = H.read(d .. "/plant.l")
      local back = lsys.cpfg.load(d .. "/plant.l", d .. "/plant.v")
      assert.is_nil(differs(tostring(back:derive()), m:derive(), letters(l), 2e-6), name)
      if name == "nested" then
        assert.truthy(l:find("\nO(h) --> ?(2, h) A(0) $\n", 1, true), l)
        assert.truthy(l:find("\nLsystem: 2\n", 1, true))
      else
        assert.truthy(l:find("E = A2", 1, true), l)
        assert.truthy(l:find("\nsurface: P plant.organ.s 1\n", 1, true) == nil)
        assert.truthy(H.read(d .. "/plant.v"):find("\nsurface: P plant.organ.s 1\n", 1, true))
      end
      H.rmdir(d)
    end
  end)

  it("counts the readings cpfg cannot tell apart, and refuses what it cannot write", function ()
    local d = H.tmpdir()
    -- 400 nodes a layer: nodes 0.0006 of the stem apart
    local _, inexact = load(nil, 400):save_cpfg(d .. "/dense.l")
    assert.is_true(inexact > 500, inexact)
    assert.has_error(function () load():save_cpfg(d .. "/plant.lua") end,
                     "save_cpfg: the L-system file must end in .l")
    assert.has_error(function () load():save_cpfg(d .. "/p.l", { organ = rectorgan():surface() })
      end, "save_cpfg: an lsys.Surface organ cannot be written (it keeps no source); give " ..
           "an organ of lsys.sketch.organ")
    assert.has_error(function () sketch.save_cpfg(lsys.lsystem { axiom = "F" }, d .. "/x.l") end,
      "lsys.sketch.save_cpfg: a Model made by sk:model or lsys.sketch.compose expected, got " ..
      "a table")
    H.rmdir(d)
  end)
end)

-- cpfg: LSYS_CPFG, else on PATH
local CPFG = os.getenv("LSYS_CPFG")
if CPFG == nil or CPFG == "" then
  local p = io.popen("command -v cpfg 2>/dev/null")
  CPFG = p:read("l")
  p:close()
end

describe("cpfg, the oracle, on the files of a sketch", function ()
  local function cpfg (d)
    local cmd = string.format("cd %s && %s -g -m plant.map -str cpfg.str plant.l plant.v " ..
                              "</dev/null >cpfg.out 2>&1", d, CPFG)
    os.execute(cmd)
    return H.read(d .. "/cpfg.str"), H.read(d .. "/cpfg.out")
  end

  local E = "examples/sketch/"
  local cases = {
    { "distichous", function () return load():model { organ = rectorgan() } end },
    { "decussate, 3D", function () return load(0.7):model { phyllotaxis = "decussate" } end },
    { "fibonacci", function () return load():model { phyllotaxis = "fibonacci" } end },
    { "fig. 8's herb", function ()
      return sketch.load(E .. "fig8_herb.json"):model { organ = organ.load(E ..
        "organ_leaf.json") } end },
    { "fig. 10's stem drawn with pressure", function ()
      return sketch.load(E .. "fig10_depth.json"):model {} end },
    { "fig. 9's double compound leaf (a sub-L-system)", function ()
      local single = sketch.load(E .. "fig9_leaf.json"):model {
        organ = organ.load(E .. "organ_leaflet.json") }
      return sketch.load(E .. "fig9_axis.json"):model { organ = single } end },
    { "fig. 14's foxglove (two plants on one stem)", function ()
      local l = sketch.load(E .. "fig14_leaves.json"):model {
        organ = organ.load(E .. "organ_foxleaf.json") }
      local f = sketch.load(E .. "fig14_flowers.json"):model {
        organ = organ.load(E .. "organ_bell.json") }
      return sketch.compose { l, f } end },
  }
  for _, c in ipairs(cases) do
    it("derives " .. c[1] .. " as lsys does", function ()
      if CPFG == nil then
        pending("cpfg is not built: set LSYS_CPFG to its path (docs/cpfg.md, cpfg as a " ..
                "reference)")
        return
      end
      local m = c[2]()
      local d = H.tmpdir()
      assert.equal(0, select(2, sketch.save_cpfg(m, d .. "/plant.l")))
      local str, log = cpfg(d)
      assert.truthy(str, "cpfg wrote no string: " .. tostring(log))
      -- cpfg prints 6 significant digits of float32 parameters
      assert.is_nil(differs(str, m:derive(), letters(H.read(d .. "/plant.l")), 1e-5))
      H.rmdir(d)
    end)
  end
end)
