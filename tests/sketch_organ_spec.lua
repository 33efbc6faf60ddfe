-- Organs from 3-view strokes (Anastacio et al. 2009, §6; lsys.sketch.organ): the blended
-- surface, its Bézier patches, the `~` placement, files and every validation error.
local H = require "tests.helper"
local core = require "lsys.core"
local lsys = require "lsys"
local organ = require "lsys.sketch.organ"

-- A rectangle 100 px wide and 200 px long: the organ is 0.5 wide and 1 long.
local LEFT = { { 100, 300 }, { 100, 100 } }
local RIGHT = { { 200, 300 }, { 200, 100 } }

local function rect (extra)
  local t = { top = { left = LEFT, right = RIGHT } }
  for k, v in pairs(extra or {}) do t[k] = v end
  return organ.build(t)
end

-- The scene of `text` drawn with the view's surface L = org.
local function scene (org, text, view)
  view = view or { surfaces = { L = org } }
  local m = lsys.lsystem { axiom = "", view = view }
  return m:interpret(m:lstring(text))
end

-- Every vertex of what record 1 drew, in the turtle's first frame (x along L = -x,
-- y along H = +y, z along U = -z): the organ's own coordinates.
local function vertices (sc)
  local out = {}
  for _, e in ipairs(sc:edges(1)) do
    for k = 1, 2 do out[#out + 1] = { -e[k][1], e[k][2], -e[k][3] } end
  end
  return out
end

local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return msg
end

describe("lsys.sketch.organ", function ()
  it("makes a flat rectangle of the strokes' proportions, 1 long", function ()
    local org = rect()
    assert.equal("lsys.Organ(organ, 8 patches)", tostring(org))
    assert.near({ -0.25, 0, 0 }, { org:blend(0, 0) }, 1e-12)
    assert.near({ 0.25, 1, 0 }, { org:blend(1, 1) }, 1e-12)
    local sc = scene(org, "~L")
    local lo, hi = sc:bounds()
    assert.near({ -0.25, 0, 0 }, lo, 1e-6)
    assert.near({ 0.25, 1, 0 }, hi, 1e-6)
    assert.near(0.5, sc:area(), 1e-6)
    -- 2 x 4 patches of 6 x 6 lines: 12 lines across and 24 along
    assert.same({ 2, 4 }, org.resolution)
    assert.equal(12 * 24 * 2, sc.ntriangles)
  end)

  it("puts the base on the turtle and the length along its heading, scaled by ~L(h)",
     function ()
    local org = rect()
    local lo, hi = scene(org, "f(3) ~L(2)"):bounds()
    assert.near({ -0.5, 3, 0 }, lo, 1e-6)
    assert.near({ 0.5, 5, 0 }, hi, 1e-6)
    assert.near(2.0, scene(org, "~L(2)"):area(), 1e-6)
    lo, hi = scene(org, "+(90) ~L(2)"):bounds()       -- turned: along -x
    assert.near({ -2, -0.5, 0 }, lo, 1e-6)
    assert.near({ 0, 0.5, 0 }, hi, 1e-6)
    lo, hi = scene(org, "&(90) ~L"):bounds()          -- pitched down: along -z, width on x
    assert.near({ -0.25, 0, -1 }, lo, 1e-6)
    assert.near({ 0.25, 0, 0 }, hi, 1e-6)
    -- the turtle stays where it was (the end point is the contact point)
    local sc = scene(org, "~L(2) F")
    assert.near({ 0, 0, 0 }, sc:record(2).p0, 1e-6)
  end)

  it("bends the surface along the midrib of the side view (orthogonal deformation)",
     function ()
    -- a quarter circle of radius 100 px rising to the right (+z): arc length 1 makes its
    -- radius r = 2 / pi, so every point of the flat organ lies on the cylinder of radius r
    -- about the axis y = 0, z = r
    local side, R = {}, 100
    for i = 0, 200 do
      local phi = math.pi / 2 * i / 200
      side[#side + 1] = { 50 + R - R * math.cos(phi), 400 - R * math.sin(phi) }
    end
    local org = rect { side = side, capture = false }
    local r = 2 / math.pi
    local sc = scene(org, "~L")
    local worst = 0
    for _, p in ipairs(vertices(sc)) do
      worst = math.max(worst, math.abs(math.sqrt(p[2] ^ 2 + (p[3] - r) ^ 2) - r))
    end
    assert.is_true(worst < 2e-3, "off the cylinder by " .. worst)
    local lo, hi = sc:bounds()                         -- world: U is -z
    assert.near({ -0.25, 0, -r }, lo, 2e-3)
    assert.near({ 0.25, r, 0 }, hi, 2e-3)
    -- the midline's z follows the stroke: at arc length a, z = r (1 - cos(a / r))
    for _, a in ipairs { 0.25, 0.5, 0.75 } do
      local _, y, z = org:point(0.5, a)
      assert.near({ r * math.sin(a / r), r * (1 - math.cos(a / r)) }, { y, z }, 2e-3)
    end
  end)

  it("gives a V cross-section its dihedral", function ()
    -- half chord 50 px, depth 20 px: flanks at atan(0.4) below the chord, so the dihedral
    -- is 180 - 2 atan(0.4) degrees and the crease 0.1 below the edges (width 0.5)
    local org = rect { front = { { 0, 0 }, { 50, 20 }, { 100, 0 } }, capture = false }
    for _, p in ipairs(vertices(scene(org, "~L"))) do
      assert.near(-0.1 + 0.4 * math.abs(p[1]), p[3], 1e-5)
    end
    local ax, _, az = org:point(0, 0.5)
    local bx, _, bz = org:point(0.5, 0.5)
    local cx, _, cz = org:point(1, 0.5)
    local u, v = { ax - bx, az - bz }, { cx - bx, cz - bz }
    local cos = (u[1] * v[1] + u[2] * v[2])
                / math.sqrt((u[1] ^ 2 + u[2] ^ 2) * (v[1] ^ 2 + v[2] ^ 2))
    assert.near(180 - 2 * math.deg(math.atan(0.4)), math.deg(math.acos(cos)), 1e-6)
    -- a cup drawn right to left is the same cup
    local cup, back = {}, {}
    for i = 0, 40 do
      local a = math.pi * i / 40
      cup[#cup + 1] = { 50 - 50 * math.cos(a), 50 * math.sin(a) }
      back[41 - i] = cup[#cup]
    end
    assert.equal(rect { front = cup, capture = false }:text(),
                 rect { front = back, capture = false }:text())
  end)

  it("fits the blended surface with patches within 1% of its size", function ()
    for _, shape in ipairs { "ovate", "lanceolate", "cordate", "elliptic", "obovate",
                             "linear" } do
      for _, section in ipairs { "flat", "v", "cup" } do
        local org = organ.leaf { shape = shape, section = section, curl = 0.4 }
        local worst = 0
        for i = 0, 20 do
          for j = 0, 20 do
            local s, t = (j + 0.37) / 21.1, (i + 0.61) / 21.3
            local x, y, z = org:blend(s, t)
            local u, v, w = org:point(s, t)
            worst = math.max(worst, math.sqrt((x - u) ^ 2 + (y - v) ^ 2 + (z - w) ^ 2))
          end
        end
        assert.is_true(worst < 0.01 * org.size, shape .. " " .. section .. ": " .. worst)
        assert.is_true(org.fit_error <= 0.01)
      end
    end
  end)

  it("mirrors a single boundary about its chord, whichever end was drawn first", function ()
    local half = { { 150, 300 }, { 110, 250 }, { 105, 180 }, { 150, 100 } }
    local org = organ.build { top = { left = half }, capture = false }
    for _, st in ipairs { { 0.2, 0.3 }, { 0.4, 0.8 }, { 0, 0.5 } } do
      local x1, y1, z1 = org:blend(st[1], st[2])
      local x2, y2, z2 = org:blend(1 - st[1], st[2])
      assert.near({ -x1, y1, z1 }, { x2, y2, z2 }, 1e-12)
    end
    -- the third point (105, 180) at its arc-length fraction: x = -45/200, y = 120/200
    local d1, d2, d3 = math.sqrt(40 ^ 2 + 50 ^ 2), math.sqrt(5 ^ 2 + 70 ^ 2),
                       math.sqrt(45 ^ 2 + 80 ^ 2)
    assert.near({ -0.225, 0.6, 0 }, { org:blend(0, (d1 + d2) / (d1 + d2 + d3)) }, 1e-9)
    local rev = {}
    for i = #half, 1, -1 do rev[#rev + 1] = half[i] end
    assert.equal(org:text(), organ.build { top = { left = rev }, capture = false }:text())
    local mirrored = {}
    for i, p in ipairs(half) do mirrored[i] = { 300 - p[1], p[2] } end
    assert.equal(org:text(), organ.build { top = { right = mirrored }, capture = false }:text())
  end)

  it("turns strokes drawn at a slant so that base to tip is the heading", function ()
    -- the rectangle turned by 90 degrees on the screen cannot tell base from tip by
    -- height; turned by 30 degrees it can
    local c, s = math.cos(math.rad(30)), math.sin(math.rad(30))
    local function turn (pts)
      local out = {}
      for i, p in ipairs(pts) do
        local x, y = p[1] - 150, p[2] - 300
        out[i] = { 150 + c * x - s * y, 300 + s * x + c * y }
      end
      return out
    end
    local org = organ.build { top = { left = turn(LEFT), right = turn(RIGHT) } }
    assert.near({ -0.25, 0, 0 }, { org:blend(0, 0) }, 1e-9)
    assert.near({ 0.25, 1, 0 }, { org:blend(1, 1) }, 1e-9)
  end)

  it("is a surface of any view: alone, as a Surface, or as an entry's surface", function ()
    local org = rect()
    assert.equal("lsys.Surface", getmetatable(org:surface()).__name)
    assert.equal(org:surface(), org:surface())
    assert.near(0.5, scene(org, "~L", { surfaces = { L = org:surface() } }):area(), 1e-6)
    local sc = scene(org, "~L", { surfaces = { L = { surface = org, scale = 2,
                                                       precision = { 1, 2 } } } })
    assert.near(2.0, sc:area(), 1e-6)
    assert.equal(2 * 4 * 1 * 2 * 2, sc.ntriangles)
    assert.equal("m: view.surfaces.P: 'surface' must be an lsys.Surface",
                 errmsg(lsys.view.normalize, { surfaces = { P = { surface = {} } } }, "m"))
  end)

  it("saves a cpfg surface file that reads back as the same surface", function ()
    local org = organ.leaf { shape = "ovate", section = "v", curl = 0.3, name = "blade" }
    local dir = H.tmpdir()
    org:save(dir .. "/blade.s")
    local text = H.read(dir .. "/blade.s")
    assert.equal(org:text(), text)
    local back = core.surface_load(dir .. "/blade.s")
    local a, b = back:info(), org:surface():info()
    assert.same(b, a)
    assert.same({ 0, 1, 0 }, a.heading)
    assert.same({ 0, 0, 1 }, a.up)
    assert.same({ 0, 0, 0 }, a.contact)
    assert.equal(1, a.size)
    assert.equal(org.resolution[1] * org.resolution[2], a.patches)
    local s1 = scene(org, "~L")
    local s2 = scene(nil, "~L", { surfaces = { L = dir .. "/blade.s" } })
    assert.equal(s1.ntriangles, s2.ntriangles)
    assert.near(s1:area(), s2:area(), 1e-9)
    H.rmdir(dir)
  end)

  it("saves the organ alone as a mesh", function ()
    local dir = H.tmpdir()
    local org = rect()
    org:save_mesh(dir .. "/leaf.obj")
    local n = 0
    for line in io.lines(dir .. "/leaf.obj") do
      if line:match("^f ") then n = n + 1 end
    end
    assert.equal(12 * 24 * 2, n)
    org:save_mesh(dir .. "/leaf.ply")
    assert.truthy(H.read(dir .. "/leaf.ply"):find("element face 576", 1, true))
    assert.error_contains(function () org:save_mesh(dir .. "/no/such/leaf.obj") end,
                          "save_mesh: ", "leaf.obj")
    H.rmdir(dir)
  end)

  it("round-trips through its JSON table and file", function ()
    local cjson = require "cjson"
    local org = rect { front = { { 0, 0 }, { 50, 20 }, { 100, 0 } }, name = "v",
                       resolution = { 2, 2 }, width_scale = 0.5, capture = false }
    local t = org:to_table()
    assert.same({ { 100, 300 }, { 100, 100 } }, t.organ.top.left)
    assert.same({ 2, 2 }, t.organ.resolution)
    assert.equal(0.5, t.organ.width_scale)
    assert.is_false(t.organ.capture)
    local dir = H.tmpdir()
    H.write(dir .. "/v.json", cjson.encode(t))
    assert.equal(org:text(), organ.load(dir .. "/v.json"):text())
    assert.equal(org:text(), organ.load(t):text())
    org:save_json(dir .. "/w.json")
    assert.equal(org:text(), organ.load(dir .. "/w.json"):text())
    assert.near({ 0.125, 1, 0 }, { org:blend(1, 1) }, 1e-12)     -- width_scale
    H.rmdir(dir)
  end)

  it("names the file, the stroke and what is wrong", function ()
    local dir = H.tmpdir()
    local function file (text)
      local p = dir .. "/leaf.json"
      H.write(p, text)
      return errmsg(organ.load, p)
    end
    local P = "organ " .. dir .. "/leaf.json: "
    assert.equal(P .. "side stroke: fewer than two points",
      file('{"organ": {"top": {"left": [[0, 10], [0, 0]]}, "side": [[1, 2]]}}'))
    assert.equal(P .. "top right stroke: point 2: y is not a finite number",
      file('{"organ": {"top": {"right": [[0, 10], [1, -1e999]]}}}'))
    assert.truthy(file('{"organ": {"top": {"right": [[0, 10], [1, NaN]]}}}')
      :find(P .. "malformed JSON: ", 1, true))
    assert.truthy(file('{"organ": {"top": '):find(P .. "malformed JSON: ", 1, true))
    assert.equal(P .. "expected an object {\"organ\": {...}}", file('[1, 2]'))
    assert.equal(P .. "front stroke: must be a list of points {x, y}, got userdata",
      file('{"organ": {"top": {"left": [[5, 10], [0, 5], [5, 0]]}, "front": null}}'))
    assert.equal("organ " .. dir .. "/none.json: cannot open '" .. dir .. "/none.json': " ..
                 "No such file or directory", errmsg(organ.load, dir .. "/none.json"))
    H.rmdir(dir)

    local B = "lsys.sketch.organ: "
    local ok = { { 5, 10 }, { 0, 5 }, { 5, 0 } }
    local cases = {
      { 42, B .. "a table { top = ..., side = ..., front = ... } expected, got number" },
      { { top = { left = ok }, stem = {} },
        B .. "unknown field 'stem' (known: top, side, front, resolution, precision, name, " ..
        "width_scale, capture)" },
      { { top = { left = ok }, capture = 1 }, B .. "'capture' must be true or false" },
      { { side = ok }, B .. "'top' must be { left = points, right = points }" },
      { { top = {} }, B .. "top view: a left or a right boundary stroke is needed" },
      { { top = { middle = ok } }, B .. "top: unknown field 'middle' (known: left, right)" },
      { { top = { left = ok }, side = { { 1, 2 } } }, B .. "side stroke: fewer than two points" },
      { { top = { left = "abc" } },
        B .. "top left stroke: must be a list of points {x, y}, got string" },
      { { top = { left = { { 0, 1 }, { 1 } } } },
        B .. "top left stroke: point 2 must be {x, y} or {x, y, pressure}" },
      { { top = { left = { { 0, 1 }, { 1, 2, 3, 4 } } } },
        B .. "top left stroke: point 2 must be {x, y} or {x, y, pressure}" },
      { { top = { left = { { 0, 1 }, { 1 / 0, 2 } } } },
        B .. "top left stroke: point 2: x is not a finite number" },
      { { top = { left = { { 0, 1 }, { 2, 3, 0 / 0 } } } },
        B .. "top left stroke: point 2: pressure is not a finite number" },
      { { top = { left = { { 0, 1 }, { 2, 3e6 } } } },
        B .. "top left stroke: point 2: y is out of range (limit 1e6)" },
      { { top = { left = { { 3, 3 }, { 3, 3 } } } },
        B .. "top left stroke: has no length (all its points are the same)" },
      { { top = { left = { { 0, 0 }, { 0, 10 } } } },
        B .. "top left stroke: a single straight boundary, mirrored, encloses nothing" },
      { { top = { left = { { 0, 0 }, { 5, 5 }, { 0, 0 } } } },
        B .. "top view: the boundaries end where they begin (the organ has no length)" },
      { { top = { left = RIGHT, right = LEFT } },
        B .. "top left stroke: lies right of the midline (base to tip); draw the left " ..
        "boundary on the left" },
      { { top = { left = { { 100, 300 }, { 40, 200 }, { 100, 100 } },
                right = { { 110, 300 }, { 90, 200 }, { 110, 100 } } } },
        B .. "top right stroke: lies left of the midline (base to tip); draw the right " ..
        "boundary on the right" },
      { { top = { left = ok }, front = { { 0, 0 }, { 5, 9 }, { 0, 0 } } },
        B .. "front stroke: its ends meet (the cross-section spans no width between the " ..
        "boundaries)" },
      { { top = { left = ok }, resolution = { 0, 2 } },
        B .. "'resolution' must be {across, along}, whole numbers from 1 to 64" },
      { { top = { left = ok }, resolution = { 65, 2 } },
        B .. "'resolution' must be {across, along}, whole numbers from 1 to 64" },
      { { top = { left = ok }, precision = { 1.5, 2 } },
        B .. "'precision' must be {across, along}, whole numbers from 1 to 256" },
      { { top = { left = ok }, name = "a b" },
        B .. "'name' must be a word of at most 63 letters, digits, '_', '-' or '.'" },
      { { top = { left = ok }, width_scale = 0 },
        B .. "'width_scale' must be a number > 0 and at most 1000" },
    }
    for _, c in ipairs(cases) do
      assert.equal(c[2], errmsg(organ.build, c[1]))
    end
    local big = {}
    for i = 1, 100001 do big[i] = { i % 7, i } end
    assert.equal(B .. "top left stroke: more than 100000 points",
                 errmsg(organ.build, { top = { left = big } }))
    assert.equal(B .. "side stroke: fewer than two points",
                 errmsg(organ, { top = { left = ok }, side = {} }))
  end)

  it("smooths hand-drawn strokes with the stroke capture of §3.1", function ()
    if core.stroke_curve == nil or core.bspline == nil then
      return pending("this build has no core.stroke_curve")
    end
    -- a straight boundary drawn with a 2 px tremor: captured, it wavers far less
    local shaky = {}
    for i = 0, 200 do shaky[#shaky + 1] = { 100 + (i % 2 == 0 and 2 or -2), 300 - i } end
    local function wobble (org)            -- the spread of the left edge's x
      local lo, hi = math.huge, -math.huge
      for i = 200, 800 do
        local x = org:blend(0, i / 1000)
        lo, hi = math.min(lo, x), math.max(hi, x)
      end
      return hi - lo
    end
    local raw = organ.build { top = { left = shaky, right = RIGHT }, capture = false }
    local cap = organ.build { top = { left = shaky, right = RIGHT } }
    assert.is_true(wobble(raw) > 0.015, "raw wobble " .. wobble(raw))   -- 4 px of 200
    assert.is_true(wobble(cap) < wobble(raw) / 3, "captured wobble " .. wobble(cap))
  end)

  it("makes common leaf shapes", function ()
    local o = organ.leaf { shape = "ovate", width = 0.6 }
    assert.equal("lsys.Organ(ovate, " .. o.resolution[1] * o.resolution[2] .. " patches)",
                 tostring(o))
    assert.near({ 0, 0, 0 }, { o:blend(0, 0) }, 1e-12)
    assert.near({ 0, 1, 0 }, { o:blend(0.5, 1) }, 1e-12)
    local lo, hi = scene(o, "~L"):bounds()
    assert.near(0, lo[2], 1e-6); assert.near(1, hi[2], 1e-6)
    assert.near(hi[1], -lo[1], 1e-6)
    assert.is_true(hi[1] > 0.25 and hi[1] < 0.45)
    -- a cordate leaf reaches below its base (its lobes)
    local heart = organ.leaf { shape = "cordate" }
    lo = scene(heart, "~L"):bounds()
    assert.is_true(lo[2] < -0.1 and lo[2] > -0.2, lo[2])
    -- and keeps the notch between its lobes open: the rows under the base bend up through
    -- it, so nothing of the fitted surface lies on the midline below the base
    assert.near({ 0, 0, 0 }, { heart:blend(0.5, 0.1) }, 1e-9)
    local inner = math.huge
    for i = 0, 200 do
      for j = 0, 200 do
        local x, y = heart:point(i / 200, j / 200)
        if y > -0.07 and y < -0.05 then inner = math.min(inner, math.abs(x)) end
      end
    end
    assert.is_true(inner > 0.02 and inner < 0.06, "inner edge of the lobes at " .. inner)
    assert.equal("lsys.sketch.organ.leaf: unknown shape 'round' (known: ovate, lanceolate, " ..
                 "elliptic, obovate, linear, cordate)", errmsg(organ.leaf, { shape = "round" }))
    assert.equal("lsys.sketch.organ.leaf: unknown option 'size'",
                 errmsg(organ.leaf, { size = 2 }))
  end)
end)
