-- The geometry of component graphs: the i-tree emitted as relative turtle
-- modules into an ordinary lsys model (lsys.components.emit, lsys.components.model). The
-- turtle must stand exactly on every instance's frame, stems must be generalized cylinders
-- through the stem frames, primitives must have the sizes asked for, and every module must
-- know the instance that drew it.
local C = require "lsys.components"
local lsys = require "lsys"

local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return tostring(msg):gsub("^[^:]*%.lua:%d+: ", "")
end

local function dist (a, b)
  return math.sqrt((a[1] - b[1]) ^ 2 + (a[2] - b[2]) ^ 2 + (a[3] - b[3]) ^ 2)
end

-- Every instance's frame against the turtle's state after its moves.
local function check_frames (m, scene)
  local n = 0
  for _, inst in ipairs(m.components.tree:instances()) do
    local p, H, _, U = scene:turtle(inst.at)
    local f = inst.frame
    assert.is_true(dist(p, f.p) < 1e-9, inst.path .. " position")
    assert.is_true(dist(H, f.H) < 1e-9, inst.path .. " heading")
    assert.is_true(dist(U, f.U) < 1e-9, inst.path .. " up")
    n = n + 1
  end
  return n
end

describe("lsys.components geometry", function ()
  it("puts the turtle exactly on every instance's frame", function ()
    -- a graph with every way of placing: tree branches (divergence, angles, deviation,
    -- curvature, gnarl), a phiball, a hydra, a wreath, translate/rotate/scale, recursion
    local leaf = C.leaf { length = 0.2, rotate = { 10, 20, 30 } }
    local tw = C.tree { name = "twig", length = 1, n = 5, angle = { 60, 30 }, gnarl = 10,
                        curvature = 30, deviation = 5, segments = 7 }
    tw:branch(leaf)
    local ball = C.phiball { n = 13, close = 120 }
    ball:child(C.simple { name = "seed", primitive = "sphere", size = { 0.1, 0.1, 0.1 } })
    local star = C.hydra { n = 4, radius = 0.3, angle = 70, translate = { 0.1, 0.2, 0.3 } }
    star:child(tw)
    local wr = C.wreath { n = 6, radius = 0.5 }
    local D = C.horn { name = "D", length = 0.4, recursion = 3, rotate = { 25, 40, 0 },
                       scale = 0.7 }
    D:child(D)
    wr:child(D)
    local trunk = C.tree { length = 5, n = 8, first = 0.2, angle = 50, scale = 1.3,
                           gravitropism = 0.1 }
    trunk:branch(tw)
    trunk:child(ball)
    trunk:child(star)
    trunk:child(wr)
    local m = C.model(trunk, { seed = 7 })
    local scene = m:interpret()
    local n = check_frames(m, scene)
    assert.equal(m.components.tree:count(), n)
    assert.equal(1 + 8 + 8 * 5 + 1 + 13 + 1 + 4 + 4 * 5 + 1 + 6 * 3, n)
    -- the same with the whole plant started from a tilted frame
    local it = C.expand(trunk, { seed = 7 })
    assert.equal(n, it:count())
  end)

  it("puts a primitive's children at its top, the cube's too", function ()
    -- the cube's surface had its end point at its top, so the turtle stood a width above
    -- where the emitter put it and the children of a cube were that much too high
    for _, prim in ipairs { "cube", "sphere", "cylinder", "cone", "disc" } do
      local s = C.simple { primitive = prim, size = { 1, 2, 3 } }
      s:child(C.leaf {}, { only = { 1 } })
      local m = C.model(s)
      assert.equal(2, check_frames(m, m:interpret()))
      assert.same({ 0, 2, 0 }, m.components.tree.list[2].frame.p)
    end
  end)

  it("draws a leaf without a texture untextured on a textured stem", function ()
    -- the turtle keeps its texture into a branch: the pine's needles were drawn with
    -- their twigs' bark (tests/gallery_spec.lua measured them nearly black)
    local stem = C.tree { name = "stem", length = 4, n = 3, texture = 1 }
    stem:branch(C.leaf { name = "leaf" })
    local view = { dir = "examples/components", textures = { { file = "bark.png" } } }
    local m = C.model(stem, { seed = 1, view = view })
    local text = tostring(m:derive())
    local leaves, untextured = 0, 0
    -- each leaf is a branch `[` ... `~S` whose modules before the surface set its look
    for head in text:gmatch("%[([^%[%]]-)~") do
      leaves = leaves + 1
      if head:find("@Tx(0)", 1, true) then untextured = untextured + 1 end
    end
    assert.equal(3, leaves)
    assert.equal(3, untextured)
    assert.truthy(text:find("@Tx(1)", 1, true))           -- the stem keeps its bark
  end)

  it("names the instance whose texture the view does not have", function ()
    assert.equal("lsys.components: leaf (at leaf#1): 'texture': 53, but the view has 0 " ..
                 "textures (view.textures)", errmsg(C.model, C.leaf { texture = 53 }))
    assert.equal("lsys.components: simple 'box' (at box#1): 'texture': 3, but the view has 0 " ..
                 "textures (view.textures)",
                 errmsg(C.model, C.simple { name = "box", primitive = "cube", texture = 3 }))
    assert.equal("lsys.components: leaf: 'texture' must be a whole number >= 0, got -1",
                 errmsg(C.leaf, { texture = -1 }))
  end)

  it("refuses a Phiball whose cap is too narrow to have an area", function ()
    local ball = C.phiball { n = 13, close = 121e-320 }
    ball:child(C.simple {})
    assert.equal("lsys.components: phiball (at phiball#1): the cap from 'open' (0) to 'close' " ..
                 "(1.2100013512604e-318) is too narrow for the children to have room (give " ..
                 "a radius or open it wider)", errmsg(C.model, ball))
    -- with a radius of its own, the children stand on that sphere
    local b2 = C.phiball { n = 3, close = 1e-6, radius = 2 }
    b2:child(C.simple {})
    local m = C.model(b2)
    assert.equal(4, check_frames(m, m:interpret()))
  end)

  it("draws stems as generalized cylinders through the stem frames, tapered", function ()
    local h = C.horn { length = 2, radius = 0.1, tip = 0.5, segments = 4, curvature = 40 }
    local m = C.model(h)
    local scene = m:interpret()
    local st = m.components.tree:instances()[1].stem
    local recs = {}
    for _, r in scene:records() do
      if r.kind == "gcyl" then recs[#recs + 1] = r end
    end
    assert.equal(4, #recs)
    for k, r in ipairs(recs) do
      assert.is_true(dist(r.p0, st[k].p) < 1e-6)       -- records keep floats
      assert.is_true(dist(r.p1, st[k + 1].p) < 1e-6)
    end
    -- widths: 2 r (1 + (tip - 1) u) at both ends
    assert.near(0.2, recs[1].w0, 1e-7)
    assert.near(0.2 * (1 - 0.5 * 0.25), recs[1].w1, 1e-7)
    assert.near(0.1, recs[4].w1, 1e-7)
    -- a thickness outline instead of the linear taper
    local h2 = C.horn { length = 2, radius = 0.1, segments = 2,
                        thickness = { { 0, 1 }, { 0.5, 2 }, { 1, 0.5 } } }
    local s2 = C.model(h2):interpret()
    local w = {}
    for _, r in s2:records() do if r.kind == "gcyl" then w[#w + 1] = r.w1 end end
    assert.near(0.4, w[1], 1e-7)
    assert.near(0.1, w[2], 1e-7)
  end)

  it("emits a tree's branches where they grow along its stem", function ()
    local leaf = C.leaf { length = 0.1 }
    local t = C.tree { length = 3, n = 6, first = 0.1, last = 0.9, segments = 5 }
    t:branch(leaf)
    local m = C.model(t)
    local s = m.components.lstring
    local text = tostring(s)
    -- the stem's control points and the leaves interleave: the first leaf comes before
    -- the second control point
    local first_leaf = text:find("~", 1, true)
    local second_gc = select(2, text:find("@Gc.-@Gc"))
    assert.is_true(first_leaf < second_gc, text)
    -- a branch tilted straight up from the stem is one pitch, not roll 180, pitch, roll 180
    local up = tostring(C.model(C.tree { n = 1, first = 0.5, angle = 60, segments = 2 }
                                  :branch(C.leaf {})).components.lstring)
    assert.truthy(up:match("%[%^%(%-59%.9999") or up:find("[^(-60)", 1, true), up)
    assert.falsy(up:find("180", 1, true), up)
    check_frames(m, m:interpret())
  end)

  it("gives primitives the size asked for, non-uniform sizes included", function ()
    local function bounds (prim, size)
      local m = C.model(C.simple { primitive = prim, size = size })
      local lo, hi = m:interpret():bounds()
      return lo, hi
    end
    -- the turtle's first frame: right = +x, heading = +y, front = +z
    local lo, hi = bounds("cube", { 2, 1, 0.5 })
    assert.near(-1, lo[1], 1e-6) assert.near(1, hi[1], 1e-6)
    assert.near(0, lo[2], 1e-6) assert.near(1, hi[2], 1e-6)
    assert.near(-0.25, lo[3], 1e-6) assert.near(0.25, hi[3], 1e-6)
    lo, hi = bounds("sphere", { 1, 2, 1 })
    assert.near(0, lo[2], 0.02) assert.near(2, hi[2], 0.02)
    assert.near(-0.5, lo[1], 0.02) assert.near(0.5, hi[1], 0.02)
    lo, hi = bounds("cylinder", { 0.4, 3, 0.4 })
    assert.near(0, lo[2], 1e-6) assert.near(3, hi[2], 1e-6)
    assert.near(0.2, hi[1], 1e-6)
    lo, hi = bounds("disc", { 1, 1, 1 })
    assert.near(0, lo[2], 1e-6) assert.near(0, hi[2], 1e-6)        -- facing the heading
    assert.near(0.5, hi[1], 1e-6)
    lo, hi = bounds("cone", { 1, 2, 1 })
    assert.near(0, lo[2], 1e-6) assert.near(2, hi[2], 1e-6) assert.near(0.5, hi[1], 1e-6)
  end)

  it("draws a primitive without width flat, without dividing by its width", function ()
    local function bounds (prim, size)
      local m = C.model(C.simple { primitive = prim, size = size })
      local lo, hi = m:interpret():bounds()
      return lo, hi
    end
    local lo, hi = bounds("cube", { 0, 1, 0.5 })
    assert.near(0, lo[1], 1e-6) assert.near(0, hi[1], 1e-6)
    assert.near(0, lo[2], 1e-6) assert.near(1, hi[2], 1e-6)
    assert.near(-0.25, lo[3], 1e-6) assert.near(0.25, hi[3], 1e-6)
    lo, hi = bounds("sphere", { 0, 2, 1 })
    assert.near(0, lo[1], 1e-6) assert.near(0, hi[1], 1e-6)
    assert.near(0, lo[2], 0.02) assert.near(2, hi[2], 0.02)
    assert.near(0.5, hi[3], 0.02)
    lo, hi = bounds("cylinder", { 0, 3, 0.4 })
    assert.near(0, lo[1], 1e-6) assert.near(0, hi[1], 1e-6)
    assert.near(3, hi[2], 1e-6) assert.near(0.2, hi[3], 1e-6)
    lo, hi = bounds("disc", { 0, 0, 1 })
    assert.near(0, lo[1], 1e-6) assert.near(0, hi[1], 1e-6) assert.near(0.5, hi[3], 1e-6)
    -- nothing at all: no surface, as cpfg draws none of scale 0 (and nothing divided by 0)
    lo, hi = bounds("cube", { 0, 0, 0 })
    assert.is_nil(lo); assert.is_nil(hi)
    -- a width so much smaller than the depth that depth / width is not finite
    lo, hi = bounds("sphere", { 1e-300, 1, 1e10 })
    assert.near(0, lo[1], 1e-6) assert.near(0, hi[1], 1e-6)
    assert.near(0, lo[2], 0.02) assert.near(1, hi[2], 0.02)
    assert.near(5e9, hi[3], 1e8)
  end)

  it("names the instance whose geometry is too large to be finite", function ()
    local a = C.simple { scale = 1e200 }
    a:child(C.simple { name = "b", scale = 1e200 })
    assert.equal("lsys.components: simple 'b' (at simple#1/b#1): its geometry is not finite " ..
                 "(a length, radius or size too large for its scale)",
                 errmsg(C.model, a))
    local h = C.horn { length = 1e308 }
    h:child(C.horn { name = "h2", length = 1e308 })
    assert.equal("lsys.components: horn (at horn#1): its geometry is not finite (a length, " ..
                 "radius or size too large for its scale)", errmsg(C.model, h))
    -- frames so far away that the move to them overflows (the C writer's moveto)
    assert.equal("lsys.components: simple (at wreath#1/simple#1): its geometry is not " ..
                 "finite (a length, radius or size too large for its scale)",
                 errmsg(C.model, C.wreath { radius = 1e308 }:child(C.simple {})))
  end)

  it("tells lsys.sketch.organ.leaf's ranges in its messages", function ()
    local organ = require "lsys.sketch.organ"
    assert.equal("lsys.sketch.organ.leaf: 'depth' must be a number from -10 to 10",
                 errmsg(organ.leaf, { section = "cup", depth = 20 }))
    assert.equal("lsys.sketch.organ.leaf: 'curl' must be a number from -10 to 10",
                 errmsg(organ.leaf, { curl = -30 }))
    assert.equal("lsys.sketch.organ.leaf: 'width' must be a number > 0 and at most 10",
                 errmsg(organ.leaf, { width = 20 }))
    -- one message when several are wrong: the first of width, curl, depth
    assert.equal("lsys.sketch.organ.leaf: 'width' must be a number > 0 and at most 10",
                 errmsg(organ.leaf, { width = 0, curl = 0 / 0, depth = 11 }))
  end)

  it("continues point-set primitives into the following instances (Tube)", function ()
    local D = C.simple { name = "ring", primitive = "tube", size = { 0.2, 1, 0.2 },
                         translate = { 0, 1, 0 }, rotate = { 15, 0, 0 }, recursion = 5 }
    D:child(D)
    local root = C.simple { primitive = "tube", size = { 0.2, 1, 0.2 } }
    root:child(D)
    local m = C.model(root)
    local scene = m:interpret()
    local n = 0
    for _, r in scene:records() do if r.kind == "gcyl" then n = n + 1 end end
    assert.equal(5, n)              -- six rings, five segments between them
    assert.is_true(scene.ntriangles > 0)
  end)

  it("shares one leaf surface among leaves of the same shape", function ()
    local ball = C.phiball { n = 30 }
    ball:child(C.leaf { length = 0.3, width = 0.1 })
    ball:child(C.leaf { length = 0.6, width = 0.2, shape = "lanceolate" })
    local m = C.model(ball)
    local keys = {}
    for k in pairs(m.view.surfaces) do keys[#keys + 1] = k end
    assert.equal(2, #keys)
    assert.equal(60, m.components.lstring:count("~" .. keys[1]) +
                     m.components.lstring:count("~" .. keys[2]))
  end)

  it("knows the instance that drew each module", function ()
    local leaf = C.leaf { name = "leaf", length = 0.2 }
    local t = C.tree { name = "twig", length = 1, n = 4 }
    t:branch(leaf)
    local root = C.tree { name = "tree", length = 4, n = 3 }
    root:branch(t)
    local m = C.model(root)
    local scene = m:interpret()
    local seen = 0
    for _, r in scene:records() do
      if r.kind == "surface" then
        local inst = m.components.instance(r.module)
        assert.equal("leaf", inst.kind)
        assert.truthy(inst.path:match("^tree#1/twig#%d+/leaf#%d+$"), inst.path)
        seen = seen + 1
      end
    end
    assert.equal(12, seen)
    assert.equal("tree#1", m.components.instance(1).path)
  end)

  it("draws an L-system's string as a component's geometry", function ()
    local ls = lsys.lsystem { axiom = "F(1)+(90)F(2)" }
    local s = C.simple { primitive = "none", translate = { 1, 0, 0 }, geometry = ls }
    local m = C.model(s, { view = { line_style = "line" } })
    local scene = m:interpret()
    local lo, hi = scene:bounds()
    -- from (1, 0, 0) up 1, then left (the turtle's + turns H towards L = -x) 2
    assert.near(-1, lo[1], 1e-6) assert.near(1, hi[1], 1e-6)
    assert.near(0, lo[2], 1e-6) assert.near(1, hi[2], 1e-6)
    -- what follows the geometry starts from the instance's frame, not where the string
    -- left the turtle
    s:child(C.simple { name = "ball", primitive = "sphere", size = { 0.2, 0.2, 0.2 } })
    local m2 = C.model(s)
    assert.equal(2, check_frames(m2, m2:interpret()))
  end)

  it("takes the arrangement: bending the trunk moves what grows on it", function ()
    local leaf = C.leaf { name = "leaf", length = 0.3 }
    local twig = C.tree { name = "twig", length = 1, n = 6, angle = 50, segments = 4 }
    twig:branch(leaf)
    local plant = C.tree { length = 5, n = 6, angle = 60, segments = 8 }
    plant:branch(twig)
    local m = C.model(plant)
    local s = m:derive()
    local scene = m:interpret(s)
    -- generalized cylinder segments chain: each one's parent is the one before it
    local first, last, prev
    for k, r in scene:records() do
      if r.kind == "gcyl" then
        local inst = m.components.instance(r.module)
        if inst.path == "tree#1" then
          if prev then assert.equal(prev, r.parent) end
          prev = k
          first = first or r.module
        end
        if inst.path == "tree#1/twig#6" then last = r.module end
      end
    end
    local a = lsys.arrange(m, s)
    a:select(first, last)
    a:spherical({ 0, 0, 1 }, 30)
    a:commit()
    local s2 = a:lstring()
    assert.is_true(s2:count("@J") > 0)
    local after = m:interpret(s2)
    local moved, kept = 0, 0
    for k, r in scene:records() do
      local r2 = after:record(k)
      if r.kind == "surface" and dist(r.p0 or r.p1, r2.p0 or r2.p1) > 0.1 then moved = moved + 1 end
      if k == 1 or r.kind == "gcyl" and r.module == first then
        kept = kept + (dist(r.p0, after:record(k).p0) < 1e-6 and 1 or 0)
      end
    end
    assert.is_true(moved >= 30, "leaves moved: " .. moved)
    assert.is_true(kept >= 1)
  end)

  it("moves an isolated subtree rigidly with the deformation above it", function ()
    local function plant (shear)
      local leaf = C.leaf { name = "leaf", length = 0.5 }
      local keep = C.ffd { name = "keep", isolate = true }
      keep:child(leaf)
      local stem = C.horn { length = 2, segments = 4 }
      stem:child(keep)
      local ffd = C.ffd { fx = function (x, y) return x + shear * y end }
      ffd:child(stem)
      local m = C.model(ffd)
      return m, m:interpret()
    end
    local function verts (m, scene)
      local k = m.components.tree:find("ffd#1/horn#1/keep#1")
      local v0, v1 = scene:module_range(k.m0, k.m1)
      local out = {}
      for i = v0, v1 do out[#out + 1] = { scene:vertex(i) } end
      return out
    end
    local m0, s0 = plant(0)
    local m1, s1 = plant(0.5)
    local a, b = verts(m0, s0), verts(m1, s1)
    assert.equal(#a, #b)
    assert.is_true(#a > 4)
    -- the leaf's base, on the stem's tip (0, 2, 0), goes where the shear takes it: (1, 2, 0)
    local function nearest (vs, q)
      local d = math.huge
      for _, v in ipairs(vs) do d = math.min(d, dist(v, q)) end
      return d
    end
    assert.is_true(nearest(a, { 0, 2, 0 }) < 1e-6)
    assert.is_true(nearest(b, { 1, 2, 0 }) < 1e-6)
    -- and keeps its shape: every distance between its vertices
    local worst = 0
    for j = 2, #a do
      worst = math.max(worst, math.abs(dist(a[j], a[1]) - dist(b[j], b[1])))
    end
    assert.is_true(worst < 1e-5, worst)
    -- the stem itself was sheared: its top ring moved by about 1
    local lo, hi = s1:bounds()
    assert.is_true(hi[1] > 0.9, hi[1])
    assert.is_true(lo[2] > -1e-6)
  end)

end)
