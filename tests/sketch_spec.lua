-- lsys.sketch: the pipeline of Anastacio et al. 2009 (§3-§5) on synthetic sketches whose
-- answers are computed by hand, the templates' organs read back from the turtle, the
-- geometric errors, save_model.
local H = require "tests.helper"
local sketch = require "lsys.sketch"

local line = require("tests.helper").line

-- A vertical stem from (200, 500) up to (200, 100): L = 400 px; boundaries at x = 150 and
-- 250 (d = 50 px = 0.125 stem lengths); horizontal inclination lines at y = 400, 300, 200
-- (x = 0.25, 0.5, 0.75 along the stem). `right` replaces the right boundary.
local function synthetic (over)
  over = over or {}
  local strokes = {
    { role = "stem", points = over.stem or line(200, 500, 200, 100, 80) },
    { role = "boundary_left", points = line(150, 520, 150, 80, 40) },
    { role = "boundary_right", points = over.right or line(250, 520, 250, 80, 40) },
    { role = "inclination", points = line(120, 400, 280, 400, 20) },
    { role = "inclination", points = line(120, 300, 330, 300, 20) },
    { role = "inclination", points = line(120, 200, 330, 200, 20) },
  }
  for _, s in ipairs(over.extra or {}) do strokes[#strokes + 1] = s end
  if over.strokes then strokes = over.strokes(strokes) end
  return { width = 400, height = 600, nodes_per_layer = 2, strokes = strokes }
end

local function load (over, opts)
  opts = opts or {}
  opts.name = "syn"
  return sketch.load(synthetic(over), opts)
end

-- every module of the derived string: { name, p1, ... }
local function organs (m)
  local s = m:derive()
  local out = {}
  for i, mod in ipairs(H.modules(s)) do
    if mod[1] == "Organ" then out[#out + 1] = { index = i, size = mod[2] } end
  end
  return s, out
end

describe("the synthetic sketch (parallel boundaries, horizontal inclination lines)", function ()
  local sk = load()

  it("puts N nodes per layer from the lower inclination line, and P_n on the top one", function ()
    local an = sk:analysis()
    local xs = {}
    for i, nd in ipairs(an.nodes) do xs[i] = nd.x end
    assert.near({ 0.25, 0.375, 0.5, 0.625, 0.75 }, xs, 1e-9)
    assert.equal(2, #an.layers)
    assert.near(0.25, an.layers[1].length, 1e-9)
  end)

  it("gives inclination 90 on both sides and organ size d / L", function ()
    for _, nd in ipairs(sk:analysis().nodes) do
      assert.near(90, nd.alpha, 1e-7)
      assert.near(90, nd.beta, 1e-7)
      assert.near(0.125, nd.size_left, 1e-9)
      assert.near(0.125, nd.size_right, 1e-9)
    end
  end)

  it("makes the positional functions of §4 exact at the nodes", function ()
    local f = sk:functions()
    assert.near(0.25, f.internode(0), 1e-9)              -- d1
    for _, x in ipairs { 0.25, 0.375, 0.5, 0.625 } do
      assert.near(0.125, f.internode(x), 1e-9)           -- layer length / N
      assert.near(90, f.angle_left(x), 1e-7)
      assert.near(0.125, f.size_right(x), 1e-9)
    end
    assert.near(0.25, f.internode(0.75), 1e-9)           -- d2 at P_n
    assert.near(0, f.stem_shape(0), 1e-9)
    assert.near(0, f.stem_shape(0.5), 1e-9)
    assert.is_nil(f.yaw)
  end)

  it("draws a tilted boundary's sizes as the geometry predicts", function ()
    -- right boundary px = 250 + (500 - py) / 8: at height y (stem lengths) it is at
    -- x = 0.125 + 0.125 y, and a horizontal ray from the node (0, y) meets it there
    local tilted = load { right = line(247.5, 520, 302.5, 80, 40) }
    for _, nd in ipairs(tilted:analysis().nodes) do
      assert.near(0.125 * (1 + nd.x), nd.size_right, 1e-9)
      assert.near(0.125, nd.size_left, 1e-9)
    end
    local f = tilted:functions()
    assert.near(0.125 * 1.375, f.size_right(0.375), 1e-9)
    assert.near(0.125 * 1.25, f.size_right(0.1), 1e-9)   -- constant below the first node
  end)

  it("reads a stroke drawn from the top as the same stem", function ()
    local down = load { stem = line(200, 100, 200, 500, 80) }
    assert.near(0.375, down:analysis().nodes[2].x, 1e-9)
    assert.near({ 0, 0.375, 0 }, down:analysis().nodes[2].pos, 1e-9)
  end)
end)

describe("a 3D stem from the pressure (§3.5, §4.2.2)", function ()
  it("gives yaw and pitch of a helix", function ()
    -- one turn: px = 200 + 60 sin(2 pi t), py = 500 - 400 t, pressure 0.5 + 0.5 cos(2 pi t)
    -- (depth z = 0.3 L2 cos(2 pi t) with L2 the drawn length)
    local pts = {}
    for i = 0, 400 do
      local t = i / 400
      pts[#pts + 1] = { 200 + 60 * math.sin(2 * math.pi * t), 500 - 400 * t,
                        0.5 + 0.5 * math.cos(2 * math.pi * t) }
    end
    local sk = load { stem = pts, strokes = function (s)
      s[2].points = line(100, 520, 100, 80, 40); s[3].points = line(300, 520, 300, 80, 40)
      for k = 4, 6 do s[k].points[1][1], s[k].points[#s[k].points][1] = 60, 340 end
      return s end }
    local an = sk:analysis()
    assert.is_true(an.threed)
    local f = sk:functions()
    assert.is_nil(f.stem_shape)
    local L2 = an.stem.length2d
    -- the helix's tangent at t: (120 pi cos, 400, -0.6 pi L2 sin) px, x right, y up, z near
    local function expected (t)
      local sx, sy = 120 * math.pi * math.cos(2 * math.pi * t), 400
      local sz = -0.6 * math.pi * L2 * math.sin(2 * math.pi * t)
      -- yaw: + turns left (towards L = -x); pitch: & turns towards the viewer (-U = +z)
      return math.deg(math.atan(-sx, sy)), math.deg(math.atan(sz, math.sqrt(sx * sx + sy * sy)))
    end
    local st = an.stem
    for _, q in ipairs { 0.15, 0.35, 0.5, 0.7, 0.85 } do      -- stem sample k: its t from py
      local k = math.floor(q * st.m)
      local t = (500 - st.py[k]) / 400
      local ey, ep = expected(t)
      assert.near(ey, f.yaw(st.s[k]), 1.5)
      assert.near(ep, f.pitch(st.s[k]), 1.5)
    end
  end)
end)

describe("templates (§5)", function ()
  local sk = load { right = line(247.5, 520, 302.5, 80, 40) }

  it("puts two organs per node (distichous), on the nodes, turned by the angles", function ()
    local m = sk:model { phyllotaxis = "distichous" }
    local s, org = organs(m)
    assert.equal(10, #org)
    local sc = m:interpret(s)
    local xs = { 0.25, 0.375, 0.5, 0.625, 0.75 }
    for k, o in ipairs(org) do
      local node = (k + 1) // 2
      local p, h = sc:turtle(o.index - 1)        -- the turtle after the organ's turn
      assert.near({ 0, xs[node], 0 }, p, 1e-9)
      assert.near(k % 2 == 1 and { -1, 0, 0 } or { 1, 0, 0 }, h, 1e-9)
      assert.near(k % 2 == 1 and 0.125 or 0.125 * (1 + xs[node]), o.size, 1e-9)
    end
  end)

  it("turns every other pair by 90 degrees (decussate) with the averaged values", function ()
    local m = sk:model { phyllotaxis = "decussate" }
    local s, org = organs(m)
    assert.equal(10, #org)
    local sc = m:interpret(s)
    local xs = { 0.25, 0.375, 0.5, 0.625, 0.75 }
    for k, o in ipairs(org) do
      local node = (k + 1) // 2
      local _, h = sc:turtle(o.index - 1)
      if node % 2 == 1 then
        assert.near(0, h[3], 1e-9)
        assert.near(1, math.abs(h[1]), 1e-9)
      else
        assert.near(0, h[1], 1e-9)
        assert.near(1, math.abs(h[3]), 1e-9)
        assert.near((0.125 + 0.125 * (1 + xs[node])) / 2, o.size, 1e-9)
      end
    end
  end)

  it("puts one organ per node at 137.5 degrees with the (a, b) weights (Fibonacci)", function ()
    local m = sk:model { phyllotaxis = "fibonacci" }
    local s, org = organs(m)
    assert.equal(5, #org)
    local xs = { 0.25, 0.375, 0.5, 0.625, 0.75 }
    local mods = H.modules(s)
    for k, o in ipairs(org) do
      local th = ((k - 1) * 137.5) % 360
      -- [ /(θ) +(φ) Organ(h) ]
      assert.equal("/", mods[o.index - 2][1])
      assert.near(th, mods[o.index - 2][2], 1e-9)
      local a, b
      if th <= 180 then a, b = 1 - th / 180, th / 180 else a, b = th / 180 - 1, 2 - th / 180 end
      assert.near(a * 0.125 + b * 0.125 * (1 + xs[k]), o.size, 1e-9)
    end
  end)

  it("gives the template's rules as text", function ()
    local t = sketch.template("distichous")
    assert.truthy(t:find("B(x) --> L(x) R(x)", 1, true))
    assert.truthy(t:find("R(x) --> [/(180) +(angle_right(x)) Organ(size_right(x))]", 1, true))
  end)
end)

describe("geometric errors", function ()
  it("names a boundary on the wrong side", function ()
    assert.has_error(function ()
      load { strokes = function (s)
        s[2].points, s[3].points = s[3].points, s[2].points
        return s end }:analysis()
    end, "syn: stroke 2 (boundary_left): lies right of the stem")
  end)

  it("names an inclination line that misses the stem or a boundary", function ()
    assert.has_error(function ()
      load { extra = { { role = "inclination", points = line(120, 350, 220, 350, 10) } } }
        :analysis()
    end, "syn: stroke 7 (inclination): does not cross the right boundary")
    assert.has_error(function ()
      load { extra = { { role = "inclination", points = line(120, 350, 180, 350, 10) } } }
        :analysis()
    end, "syn: stroke 7 (inclination): does not cross the stem")
    assert.has_error(function ()
      load { extra = { { role = "inclination", points = line(170, 350, 280, 350, 10) } } }
        :analysis()
    end, "syn: stroke 7 (inclination): does not cross the left boundary")
  end)

  it("needs two inclination lines", function ()
    assert.has_error(function ()
      load { strokes = function (s) return { s[1], s[2], s[3], s[4] } end }:analysis()
    end, "syn: a sketch needs at least two inclination lines, it has 1")
  end)
end)

describe("models from sketches", function ()
  it("saves a model file that builds the same plant", function ()
    local sk = load()
    local d = H.tmpdir()
    local path = d .. "/plant.lua"
    sk:save_model(path, { phyllotaxis = "decussate" })
    local m2 = dofile(path)
    local m1 = sk:model { phyllotaxis = "decussate" }
    assert.equal(tostring(m1:derive()), tostring(m2:derive()))
    H.rmdir(d)
  end)

  it("keeps the sketch's file name a comment (a carriage return ended it)",
     function ()
    local d = H.tmpdir()
    local marker = d .. "/P"
    local sk = load()
    sk.file = "plant\rio.open('" .. marker .. "', 'w') --\r.json"
    sk:save_model(d .. "/plant.lua", { phyllotaxis = "decussate" })
    local m = dofile(d .. "/plant.lua")
    assert.is_nil(H.read(marker))
    assert.equal(tostring(sk:model { phyllotaxis = "decussate" }:derive()),
                 tostring(m:derive()))
    local first = H.read(d .. "/plant.lua"):match("^[^\n]*")
    assert.equal("-- A plant from the sketch plant\\13io.open('" .. marker .. "', 'w') " ..
                 "--\\13.json (lsys.sketch, after Anastacio, Prusinkiewicz and Sousa", first)
    H.rmdir(d)
  end)

  it("writes the model file whole or not at all (ulimit -f truncated it)",
     function ()
    local d = H.tmpdir()
    H.write(d .. "/plant.lua", "-- the good model\n")
    load():save(d .. "/sk.json")
    H.write(d .. "/save.lua", "local sk = require('lsys.sketch').load('" .. d .. "/sk.json')\n" ..
            "print(pcall(sk.save_model, sk, '" .. d .. "/plant.lua'))\n")
    local out = H.sh("trap '' XFSZ; ulimit -f 4; " .. H.BIN .. " " .. d .. "/save.lua")
    assert.equal("false\tsave_model: ", out:match("^false\tsave_model: "), out)
    assert.equal("-- the good model\n", H.read(d .. "/plant.lua"))
    assert.equal("plant.lua\nsave.lua\nsk.json\n", (H.sh("ls -A " .. d)))
    H.rmdir(d)
  end)

  it("composes a sketch as the organ of another (§7.2)", function ()
    local outer, inner = load(), load()
    local m = outer:model { organ = inner }
    local s = m:derive()
    -- 10 organs of the outer plant, each a plant with 10 organs
    assert.equal(100, s:count("Organ"))
  end)
end)

-- Every rule of model m that has expressions runs on the C expression machine (the aim:
-- no Lua call per module); returns the labels of those that do not.
local function offmachine (m)
  m:derive(1)                       -- binds the rules to env
  local off = {}
  for i, info in pairs(m._info) do
    if info.factory and not m._rules:hasvm(i - 1) then off[#off + 1] = info.label end
  end
  table.sort(off)
  return off
end

-- A rectangle organ 100 px wide and 200 px long: 0.5 wide and 1 long, 2 x 4 patches of
-- 6 x 6 lines, so 12 x 24 x 2 = 576 triangles (tests/sketch_organ_spec.lua).
local function rectorgan ()
  return require("lsys.sketch.organ").build {
    top = { left = { { 100, 300 }, { 100, 100 } }, right = { { 200, 300 }, { 200, 100 } } } }
end
local RECT_TRIANGLES = 576

describe("a composed plant (§7.2)", function ()
  it("draws the inner Model's organs as that Model does (its organ surface)", function ()
    local outer, inner = load(), load()
    local m = outer:model { organ = inner:model { organ = rectorgan() } }
    local s = m:derive()
    assert.equal(100, s:count("Organ"))
    local function tris (model) return model:interpret(model:derive()).ntriangles end
    -- one rectangle organ in place of one default leaf adds d triangles (outer alone: 10)
    local d = (tris(outer:model { organ = rectorgan() }) - tris(outer:model())) / 10
    assert.is_true(d > 0)
    -- composed: 100 inner organs, each the rectangle, against the composition with a Sketch
    -- (the default leaf)
    assert.equal(100 * d, tris(m) - tris(outer:model { organ = inner }))
  end)
end)

describe("plants composed on one stem (lsys.sketch.compose, §7.2)", function ()
  -- the string of plant k alone as it reads in a composition: its names suffixed, its
  -- stem moved along (f)
  local function as_part (s, suffix)
    return (tostring(s):gsub("(%a+)%(", function (w)
      if w == "F" then return "f(" end
      if w ~= "f" then return w .. suffix .. "(" end
    end))
  end

  it("derives each plant as alone, the first drawing the stem, the others moving", function ()
    local a = load():model {}
    local b = load():model { phyllotaxis = "fibonacci", organ_color = 3 }
    local m = sketch.compose({ a, b }, { name = "two" })
    assert.equal("two", m.name)
    local s = m:derive()
    assert.equal("[" .. as_part(b:derive(), "2") .. "]" .. tostring(a:derive()), tostring(s))
    assert.equal(10, s:count("Organ"))
    assert.equal(5, s:count("Organ2"))
    assert.equal(a:derive():count("F"), s:count("F"))
    assert.equal(b:derive():count("F"), s:count("f"))
    -- each plant's organs in its own colour; the name by default joins the plants'
    local one = sketch.compose { a, b }
    assert.equal("syn + syn", one.name)
    local d = one.sketch.description
    assert.same({ "Organ(h) --> " .. d.homomorphism[1]:match("^Organ%(h%) %-%-> (.*)$"),
                  "Organ2(h) --> " .. d.homomorphism[1]:match("^Organ%(h%) %-%-> (.*)$")
                    :gsub("^;%(2%)", ";(3)") }, d.homomorphism)
    assert.is_function(getmetatable(d.env.internode2).__call)
    assert.equal(d.env.XT, d.env.XT2)
    -- three plants: suffixes 2 and 3, one apex each
    local three = sketch.compose { a, b, load():model { phyllotaxis = "decussate" } }
    local s3 = three:derive()
    assert.same({ 10, 5, 10 }, { s3:count("Organ"), s3:count("Organ2"), s3:count("Organ3") })
    assert.equal("Organ A2 S2 B2 C2 L2 R2 Organ2 A3 S3 B3 C3 L3 R3 Organ3",
                 three.sketch.description.modules)
  end)

  it("gives each plant's organ surface and sub-L-systems names of their own", function ()
    local org = rectorgan()
    local function keys (t)
      local out = {}
      for k in pairs(t) do out[#out + 1] = k end
      table.sort(out)
      return out
    end
    local a = load():model { organ = org }
    local b = load():model { organ = org, phyllotaxis = "fibonacci" }
    local m = sketch.compose { a, b }
    local d = m.sketch.description
    assert.same({ "P", "Q" }, keys(d.surfaces))
    assert.same({ "Organ(h) --> ;(2) ~P(h)", "Organ2(h) --> ;(2) ~Q(h)" }, d.homomorphism)
    assert.equal(org, m.view.surfaces.Q)
    local s = m:derive()
    assert.equal(15 * RECT_TRIANGLES + a:interpret(a:derive()).ntriangles -
                 10 * RECT_TRIANGLES, m:interpret(s).ntriangles)
    -- plants as organs (sub-L-systems): one id each
    local inner = load():model { organ = org }
    local pa = load():model { organ = inner }
    local pb = load():model { organ = inner, phyllotaxis = "fibonacci" }
    local pm = sketch.compose { pa, pb }
    assert.same({ 1, 2 }, keys(pm.sketch.description.sub))
    local ps = pm:derive()
    assert.equal(100, ps:count("Organ"))         -- 10 inner plants of 10 organs each
    assert.equal(50, ps:count("Organ2"))         -- 5 of 10
    local text = tostring(ps)
    local _, n1 = text:gsub("%?%(1,", "")
    local _, n2 = text:gsub("%?%(2,", "")
    assert.same({ 10, 5 }, { n1, n2 })
  end)

  it("saves the composition as a model file that builds the same plant", function ()
    local org = rectorgan()
    local a = load():model { organ = org }
    local b = load():model { phyllotaxis = "decussate", organ = org }
    local m = sketch.compose({ a, b }, { name = "pair" })
    local d = H.tmpdir()
    assert.equal(d .. "/pair.lua", sketch.save_model(m, d .. "/pair.lua"))
    assert.equal("pair.lua\npair.organ.Q.s\npair.organ.s\n", (H.sh("ls -A " .. d)))
    local text = H.read(d .. "/pair.lua")
    assert.truthy(text:find("-- plant 2 (names ending in 2): the sketch syn, decussate, " ..
                            "2 nodes per layer, its stem moved along (f)\n", 1, true), text)
    local back = dofile(d .. "/pair.lua")
    assert.equal(tostring(m:derive()), tostring(back:derive()))
    assert.equal(m:interpret(m:derive()).ntriangles, back:interpret(back:derive()).ntriangles)
    H.rmdir(d)
  end)

  it("runs the example of docs/sketch.md as shown", function ()
    local doc = H.read("docs/sketch.md")
    local code = doc:match("\n```lua\n(local sketch = require \"lsys.sketch\"\nlocal leaves.-)```")
    assert.is_string(code, "the composition example")
    local expect = code:match("%-%-> ([^\n]*)")
    local got = {}
    local env = setmetatable({ print = function (...)
      local t = table.pack(...)
      for i = 1, t.n do t[i] = tostring(t[i]) end
      got[#got + 1] = table.concat(t, "\t")
    end }, { __index = _G })
    assert(_G.load(code, "=docs/sketch.md", "t", env))()
    assert.same({ expect }, got)
  end)

  it("says what it cannot compose", function ()
    local a = load():model {}
    local cases = {
      { function () sketch.compose { a } end,
        "lsys.sketch.compose: a list of two or more sketch Models expected" },
      { function () sketch.compose({ a, a }, { nmae = "x" }) end,
        "lsys.sketch.compose: unknown option 'nmae' (name, view)" },
      { function () sketch.compose { a, require("lsys").lsystem { axiom = "F", name = "f" } } end,
        "lsys.sketch.compose: models[2]: a Model made by sk:model or lsys.sketch.compose " ..
        "expected, got the model 'f'" },
      { function () sketch.compose { sketch.compose { a, a }, a } end,
        "lsys.sketch.compose: models[1] is a composition already; compose the plants it " ..
        "was made of" },
      { function () sketch.save_model(a, 3) end, "lsys.sketch.save_model: a file name expected" },
    }
    for _, c in ipairs(cases) do assert.has_error(c[1], c[2]) end
  end)
end)

describe("the templates on the expression machine", function ()
  local flat, deep = load(), load { stem = line(200, 500, 200, 100, 80, 0.7) }

  for _, ph in ipairs { "distichous", "decussate", "fibonacci" } do
    it("runs every rule of " .. ph .. " in C, 2D and 3D, alone and composed", function ()
      for _, sk in ipairs { flat, deep } do
        for _, org in ipairs { false, "sketch", "surface" } do
          local o = org == "sketch" and load() or org == "surface" and rectorgan() or nil
          local m = sk:model { phyllotaxis = ph, organ = o }
          assert.equal(sk == deep, m.sketch.description.threed)
          local n = 0
          for _, info in pairs(m._info) do if info.factory then n = n + 1 end end
          assert.is_true(n >= 6)
          assert.same({}, offmachine(m))
          -- the Lua closures give the same plant
          local s = tostring(m:derive())
          m.lua_expressions = true
          assert.equal(s, tostring(m:derive()))
          assert.is_true(#offmachine(m) >= 6)
        end
      end
    end)
  end

  it("runs the rules of a saved model file in C too", function ()
    local d = H.tmpdir()
    for _, ph in ipairs { "distichous", "decussate", "fibonacci" } do
      deep:save_model(d .. "/plant.lua", { phyllotaxis = ph, organ = flat })
      assert.same({}, offmachine(dofile(d .. "/plant.lua")))
    end
    H.rmdir(d)
  end)
end)

-- The text of lstring s with the stem moved over (F -> f) and only the k-th organ kept.
local function oneorgan (s, k)
  local n = 0
  local text = tostring(s):gsub("F%(", "f("):gsub("Organ%b()", function ()
    n = n + 1
    if n ~= k then return "" end
  end)
  return text
end

describe("organ surfaces in sketch models", function ()
  -- x of the nodes; sizes: left 0.125, right 0.125 (1 + x) (the tilted right boundary)
  local sk = load { right = line(247.5, 520, 302.5, 80, 40) }
  local xs = { 0.25, 0.375, 0.5, 0.625, 0.75 }

  for _, kind in ipairs { "Organ", "lsys.Surface" } do
    it("draws an " .. kind .. " at each node, as long as its size", function ()
      local org = rectorgan()
      local m = sk:model { organ = kind == "Organ" and org or org:surface(),
                           view = { line_style = "line" } }
      local s, org_ = organs(m)
      assert.equal(10, #org_)
      local sc = m:interpret(s)
      assert.equal(10 * RECT_TRIANGLES, sc.ntriangles)
      for k, o in ipairs(org_) do
        local x = xs[(k + 1) // 2]
        local h = k % 2 == 1 and 0.125 or 0.125 * (1 + x)
        assert.near(h, o.size, 1e-12)
        local one = m:interpret(m:lstring(oneorgan(s, k)))
        assert.equal(RECT_TRIANGLES, one.ntriangles)
        local lo, hi = one:bounds()
        -- left organs point along -x, right ones along +x, 0.5 h wide about the node
        if k % 2 == 1 then
          assert.near({ -h, x - 0.25 * h, 0 }, lo, 1e-6)
          assert.near({ 0, x + 0.25 * h, 0 }, hi, 1e-6)
        else
          assert.near({ 0, x - 0.25 * h, 0 }, lo, 1e-6)
          assert.near({ h, x + 0.25 * h, 0 }, hi, 1e-6)
        end
      end
    end)
  end

  it("saves the organ beside the model file, which reloads to the same plant", function ()
    local org = rectorgan()
    local d = H.tmpdir()
    sk:save_model(d .. "/plant.lua", { organ = org, phyllotaxis = "fibonacci" })
    assert.equal(org:text(), H.read(d .. "/plant.organ.s"))
    local m1 = sk:model { organ = org, phyllotaxis = "fibonacci" }
    -- the model file finds its organ next to itself, not in the current folder
    local m2 = dofile(d .. "/plant.lua")
    local s1, s2 = m1:derive(), m2:derive()
    assert.equal(tostring(s1), tostring(s2))
    local t1, t2 = m1:interpret(s1).ntriangles, m2:interpret(s2).ntriangles
    assert.equal(t1, t2)
    assert.is_true(t1 > 5 * RECT_TRIANGLES)
    assert.has_error(function () sk:save_model(d .. "/p2.lua", { organ = org:surface() }) end,
      "save_model: an lsys.Surface organ cannot be written (it keeps no source); give an " ..
      "organ of lsys.sketch.organ")
    assert.has_error(function () sk:model { organ = {} } end,
      "model: organ must be nil, '~X', an organ (lsys.sketch.organ), an lsys.Surface, a " ..
      "Sketch or a Model made from a sketch")
    H.rmdir(d)
  end)
end)

describe("require \"lsys\" and the sketch modules", function ()
  local lsys = require "lsys"
  local core = require "lsys.core"

  it("reaches lsys.sketch and its modules, and names their objects", function ()
    assert.equal(sketch, lsys.sketch)
    assert.equal(require "lsys.sketch.organ", lsys.sketch.organ)
    assert.equal(require "lsys.sketch.plot", lsys.sketch.plot)
    assert.equal(require "lsys.sketch.read", lsys.sketch.read)
    assert.equal(require "lsys.func", lsys.func)
    assert.is_nil(rawget(sketch, "window"))
    assert.equal("sketch", lsys.type(load()))
    assert.equal("organ", lsys.type(rectorgan()))
    assert.equal("surface", lsys.type(rectorgan():surface()))
    assert.equal("canvas", lsys.type(core.canvas(2, 2)))
    assert.equal("bspline", lsys.type(core.bspline { { 0, 0 }, { 1, 1 }, { 2, 0 }, { 3, 1 } }))
    assert.equal("func", lsys.type(load():functions().internode))
    assert.equal("model", lsys.type(load():model()))
    assert.is_nil(lsys.type(setmetatable({}, { __name = "lsys.Organ" })))
    assert.is_nil(lsys.type(setmetatable({}, {})))
  end)

  it("loads without cjson and lxp, and names the Debian package when a sketch is read",
     function ()
    -- a fresh look at the modules with cjson and lxp hidden from require
    local hidden = { cjson = true, ["cjson.safe"] = true, lxp = true }
    local saved, searchers = {}, package.searchers
    for _, k in ipairs { "cjson", "cjson.safe", "lxp", "lsys", "lsys.sketch",
                         "lsys.sketch.read" } do
      saved[k], package.loaded[k] = package.loaded[k], nil
    end
    package.searchers = { function (name)
      if hidden[name] then return "\n\tno module '" .. name .. "' (hidden by the test)" end
      for _, s in ipairs(searchers) do
        local f, extra = s(name)
        if type(f) == "function" then return f, extra end
      end
      return "\n\tnot found"
    end }
    local ok, err = pcall(function ()
      local l = require "lsys"
      assert.equal("table", type(l.sketch))
      assert.has_error(function () l.sketch.load(synthetic()) end,
        "lsys.sketch.load: lsys.sketch.read: the Lua library 'cjson.safe' is missing " ..
        "(install the Debian package lua-cjson)")
    end)
    package.searchers = searchers
    for k, v in pairs(saved) do package.loaded[k] = v end
    package.loaded["lsys.sketch.read"] = saved["lsys.sketch.read"]
    assert(ok, err)
  end)
end)

describe("orientation (the plant as drawn, not mirrored)", function ()
  -- a stem curving to the right as it rises (pixel x grows upwards), the left boundary 60
  -- px left of it and the right one 120 px right: the left organs are the shorter ones
  local function curve (dx, t0, t1, n)
    local c = {}
    for i = 0, n do
      local t = t0 + (t1 - t0) * i / n
      c[#c + 1] = { 200 + 150 * t * t + dx, 500 - 400 * t }
    end
    return c
  end
  local sk = sketch.load({ width = 500, height = 600, nodes_per_layer = 2, strokes = {
    { role = "stem", points = curve(0, 0, 1, 100) },
    { role = "boundary_left", points = curve(-60, -0.05, 1.05, 50) },
    { role = "boundary_right", points = curve(120, -0.05, 1.05, 50) },
    { role = "inclination", points = line(80, 430, 420, 430, 20) },
    { role = "inclination", points = line(80, 300, 460, 300, 20) },
    { role = "inclination", points = line(80, 180, 500, 180, 20) } } }, { name = "right" })

  -- in 3D too (depth = true: yaw and pitch after @R instead of the 2D turns; a 3D stem once
  -- leaned left, its left and right organs swapped, under the paper's @R(0,1,0,0,0,1))
  for _, depth in ipairs { false, true } do
    it("leans right with the left organs on the left" .. (depth and ", 3D" or ""), function ()
      local m = sk:model { depth = depth }
      local s, org = organs(m)
      local sc = m:interpret(s)
      assert.equal(10, #org)
      assert.equal(depth, s:text():find("@R", 1, true) ~= nil)
      local lastx = 0
      for k, o in ipairs(org) do
        local p, h = sc:turtle(o.index - 1)
        if k % 2 == 1 then
          assert.is_true(p[1] > lastx)                -- each node further right than the last
          lastx = p[1]
          assert.is_true(h[1] < -0.5)                 -- the left organ points left
        else
          assert.is_true(h[1] > 0.5)                  -- and the right one right
          assert.is_true(o.size > 1.5 * org[k - 1].size)
        end
        assert.near(0, p[3], 1e-12)
      end
      -- the node on the top line: where the stroke is, x = 150 t^2 / L at y = 320 / L
      local an = sk:analysis()
      local top = an.nodes[#an.nodes]
      assert.near(150 * 0.8 ^ 2 / an.length, top.pos[1], 1e-3)
      assert.near(320 / an.length, top.pos[2], 1e-3)
    end)
  end

  it("puts the parts drawn with more pressure nearer the viewer (+z)", function ()
    local pts = {}
    for i = 0, 100 do pts[i + 1] = { 200, 500 - 4 * i, 0.5 + 0.5 * (i / 100) ^ 2 } end
    local deep = load { stem = pts }
    local m = deep:model()
    local s, org = organs(m)
    local sc = m:interpret(s)
    local lastz = 0
    for k = 1, #org, 2 do
      local p = sc:turtle(org[k].index - 1)
      assert.is_true(p[3] > lastz)
      lastz = p[3]
    end
    local lo, hi = sc:bounds()
    assert.is_true(hi[3] > 0.25 and lo[3] > -0.01)   -- the tip at pressure 1: z = near
  end)
end)
