-- The World of component graphs (Lintermann and Deussen 1999, section
-- "Tropisms", and "Free-form deformations"): gravity, light, wind and a cylinder bend the
-- stems below a World; leaves turn to the light; FFD and Hyperpatch deform either the
-- drawn geometry ("all") or only the skeleton of frames ("skeleton"), and `isolate`
-- switches them off for a subtree.
local C = require "lsys.components"

local function errmsg (f, ...)
  local ok, e = pcall(f, ...)
  assert.is_false(ok)
  return tostring(e)
end

local function dist (a, b)
  return math.sqrt((a[1] - b[1]) ^ 2 + (a[2] - b[2]) ^ 2 + (a[3] - b[3]) ^ 2)
end

-- A horizontal start (H = +x, U = +y) for the tropism tests.
local FLAT = { p = { 0, 0, 0 }, H = { 1, 0, 0 }, U = { 0, 1, 0 }, s = 1 }

describe("lsys.components World tropisms", function ()
  it("gravity bends a stem down and light bends it up by e |H x T| per segment", function ()
    -- H = +x, T = -y: |H x T| = 1, so the first segment turns by e radians exactly
    local down = C.expand(C.tree { n = 0, gravitropism = 0.2, segments = 5 }, { frame = FLAT })
    local H = down:instances()[1].stem[2].H
    assert.near({ math.cos(0.2), -math.sin(0.2), 0 }, H, 1e-12)
    local up = C.expand(C.tree { n = 0, phototropism = 0.2, segments = 5 }, { frame = FLAT })
    assert.near({ math.cos(0.2), math.sin(0.2), 0 }, up:instances()[1].stem[2].H, 1e-12)
    -- and keeps bending: the tip points further down than the first segment
    local st = down:instances()[1].stem
    assert.is_true(st[#st].H[2] < H[2])
    -- a World's gravity (a function of position) replaces the default below it
    local w = C.world { gravity = function () return 0, 0, 1 end }
    w:child(C.tree { n = 0, gravitropism = 0.3, segments = 4 })
    local t = C.expand(w, { frame = FLAT })
    assert.near({ math.cos(0.3), 0, math.sin(0.3) }, t:instances()[2].stem[2].H, 1e-12)
  end)

  it("wind turns stems towards its horizontal direction", function ()
    -- the direction's vertical part is dropped: {2, 5, 0} blows along +x
    local w = C.world { wind = { direction = { 2, 5, 0 }, strength = 0.1 } }
    w:child(C.horn { length = 1, segments = 10 })
    local t = C.expand(w)
    local st = t:instances()[2].stem
    assert.near({ math.sin(0.1), math.cos(0.1), 0 }, st[2].H, 1e-12)
    assert.is_true(st[11].H[1] > st[2].H[1])
    assert.near(0, st[11].H[3], 1e-12)
    local bad = C.world { wind = { direction = { 0, 1, 0 } } }
    bad:child(C.horn {})
    assert.equal("lsys.components: world (at world#1): 'wind.direction' has no horizontal " ..
                 "part", errmsg(C.expand, bad))
    -- the fields are checked when the World is made
    assert.matches("'cylinder.radius'", errmsg(C.world, { cylinder = { radius = "wide" } }),
                   1, true)
  end)

  it("a cylinder makes a stem climb round its axis on a helix at its radius", function ()
    local w = C.world { cylinder = { axis = { 0, 1, 0 }, point = { 0, 0, 0 }, radius = 0.3,
                                     pitch = 30, strength = 0.5 } }
    w:child(C.horn { length = 12, segments = 600, translate = { 0.3, 0, 0 } })
    local st = C.expand(w):instances()[2].stem
    local turned, last = 0, math.atan(st[1].p[3], st[1].p[1])
    for k = 2, #st do
      local p, q = st[k].p, st[k - 1].p
      local r = math.sqrt(p[1] * p[1] + p[3] * p[3])
      -- the stem starts heading up the axis: it turns 60 degrees to the helix's pitch, at
      -- most 0.5 radians a segment, in 3 segments; from then on every frame lies on it
      if k > 4 then
        assert.near(0.3, r, 1e-12)
        local dy, dh = p[2] - q[2], math.sqrt((p[1] - q[1]) ^ 2 + (p[3] - q[3]) ^ 2)
        assert.near(30, math.deg(math.atan(dy, dh)), 1e-9)
      else
        assert.is_true(math.abs(r - 0.3) < 2e-4, "frame " .. k .. " at " .. r)
      end
      local a = math.atan(p[3], p[1])
      local d = (a - last + math.pi) % (2 * math.pi) - math.pi
      -- a x r seen from above (+y) is clockwise: atan(z, x) decreases
      assert.is_true(d < 0, "frame " .. k .. " goes round one way")
      turned, last = turned - d, a
    end
    -- 12 of stem at 30 degrees climb 6 and go 10.4 round a circle of 0.3: 5.5 turns
    assert.near(12 * math.cos(math.rad(30)) / 0.3, turned, 0.05)
    -- without the World the horn goes straight up
    local st2 = C.expand(C.horn { length = 12, segments = 600 }):instances()[1].stem
    assert.near({ 0, 12, 0 }, st2[#st2].p, 1e-9)
  end)

  it("a cylinder holds its radius from a start off it, or pulls as far as it can", function ()
    -- a stem starting 0.5 out, heading along the axis: segments of 0.1 take it in at the
    -- pitch, 0.094 closer each, and it is on the radius from the 9th frame on
    local w = C.world { cylinder = { radius = 1, pitch = 20, strength = 0.6 } }
    w:child(C.horn { length = 8, segments = 80, translate = { 1.5, 0, 0 } })
    local st = C.expand(w):instances()[2].stem
    local function r (k) return math.sqrt(st[k].p[1] ^ 2 + st[k].p[3] ^ 2) end
    for k = 3, 6 do assert.near(0.1 * math.cos(math.rad(20)), r(k - 1) - r(k), 1e-3) end
    for k = 9, #st do assert.near(1, r(k), 1e-12) end
    -- too weak for a tight helix (each segment would turn 0.38 radians, the guide turns
    -- 0.1): the stem cannot keep to the radius and strays from it
    local weak = C.world { cylinder = { radius = 0.2, pitch = 30, strength = 0.1 } }
    weak:child(C.horn { length = 8, segments = 80, translate = { 0.2, 0, 0 } })
    local stray = 0
    for _, f in ipairs(C.expand(weak):instances()[2].stem) do
      stray = math.max(stray, math.abs(math.sqrt(f.p[1] ^ 2 + f.p[3] ^ 2) - 0.2))
    end
    assert.is_true(stray > 0.1, stray)
  end)

  it("a wall keeps the stems in the plane at its distance, along their own way", function ()
    -- a tree whose branches leave the trunk all round; the wall's plane is z = 0.5
    local function tree ()
      local t = C.tree { name = "t", length = 4, n = 6, angle = 60, segments = 20,
                         translate = { 0, 0, 0.5 } }
      t:branch(C.tree { name = "b", length = 1.5, n = 0, segments = 15, gnarl = 10 })
      return t
    end
    local w = C.world { wall = { point = { 0, 0, 0.2 }, normal = { 0, 0, 2 }, distance = 0.3,
                                 strength = 0.4 } }
    w:child(tree())
    local far, spread = 0, 0
    for _, inst in ipairs(C.expand(w):instances()) do
      local st = inst.stem or {}
      for k = 1, #st do
        local q = math.abs(st[k].p[3] - 0.5)
        -- a branch leaves the trunk up to 60 degrees out of the plane, and the wall turns
        -- it at most 0.4 radians a segment: back on the plane within 8 segments
        if k > 9 then far = math.max(far, q) end
        spread = math.max(spread, math.abs(st[k].p[1]))
      end
    end
    assert.is_true(far < 1e-12, far)
    assert.is_true(spread > 1, spread)             -- the branches spread along the wall
    -- the same tree without the wall is not flat
    local out = 0
    for _, inst in ipairs(C.expand(tree()):instances()) do
      for _, f in ipairs(inst.stem or {}) do out = math.max(out, math.abs(f.p[3] - 0.5)) end
    end
    assert.is_true(out > 0.5, out)
    -- a stem already in the plane and along it is not turned
    local w2 = C.world { wall = { normal = { 0, 0, 1 } } }
    w2:child(C.horn { length = 2, segments = 4 })
    local st = C.expand(w2):instances()[2].stem
    assert.near({ 0, 2, 0 }, st[5].p, 1e-15)
  end)

  it("a World's false switches a parent World's cylinder, wall or wind off", function ()
    local w = C.world { cylinder = { radius = 1, strength = 0.5 }, wall = {},
                        wind = { strength = 0.5 } }
    local free = C.world { cylinder = false, wall = false, wind = false }
    w:child(free)
    free:child(C.horn { length = 2, segments = 4, translate = { 0.4, 0, 0 } })
    local st = C.expand(w):instances()[3].stem
    assert.near({ 0.4, 2, 0 }, st[5].p, 1e-12)
    assert.equal("lsys.components: world: 'wall' must be a table or false",
                 errmsg(C.world, { wall = 3 }))
    assert.equal("lsys.components: world: 'wall.strength' must be a number from 0 to 100 " ..
                 "(radians a segment at most), got -1",
                 errmsg(C.world, { wall = { strength = -1 } }))
    assert.equal("lsys.components: world: 'wall': unknown field 'radius' (known: distance, " ..
                 "normal, point, strength)", errmsg(C.world, { wall = { radius = 1 } }))
    assert.equal("lsys.components: world (at world#1): 'wall.normal' must not be zero",
                 errmsg(C.expand, C.world { wall = { normal = { 0, 0, 0 } } }))
  end)

  it("turns a leaf by the fraction e of the rotation that makes U face the light", function ()
    -- U = -z, light +y: 90 degrees about +x; e = 0.5 turns it by 45
    local t = C.expand(C.leaf { phototropism = 0.5 })
    local f = t:instances()[1].frame
    local r = math.sqrt(0.5)
    assert.near({ 0, r, -r }, f.U, 1e-12)
    assert.near({ 0, r, r }, f.H, 1e-12)
    assert.near(45, math.deg(math.acos(f.U[2])), 1e-9)      -- (1 - e) x 90 left
    for _, e in ipairs { 0.2, 1 } do
      local g = C.expand(C.leaf { phototropism = e }):instances()[1].frame
      assert.near(90 * e, 90 - math.deg(math.acos(g.U[2])), 1e-9)
    end
  end)
end)

-- A tree with leaves under `top` (or alone), and the scene's vertices of instance inst.
local function plant ()
  local leaf = C.leaf { name = "leaf", length = 0.3, width = 0.15 }
  local t = C.tree { name = "t", length = 2, n = 4, angle = 50, segments = 6 }
  t:branch(leaf)
  return t
end

local function vertices (scene, inst)
  local v0, v1 = scene:module_range(inst.modules[1], inst.modules[2])
  local out = {}
  for i = v0, v1 do out[#out + 1] = { scene:vertex(i) } end
  return out
end

describe("lsys.components skeleton and all-mode deformations", function ()
  local shear = function (x, y) return x + 0.5 * y end

  it("skeleton mode moves the frames and leaves the leaves' shape as it was", function ()
    local base = C.model(plant())
    local d = C.ffd { mode = "skeleton", fx = shear }
    d:child(plant())
    local m = C.model(d)
    local t0, t1 = base.components.tree, m.components.tree
    local s0, s1 = base:interpret(), m:interpret()
    -- every stem frame p goes to (x + 0.5 y, y, z): the FFD's frame is the world's
    local a, b = t0:find("t#1"), t1:find("ffd#1/t#1")
    for k, f in ipairs(a.stem) do
      assert.near({ f.p[1] + 0.5 * f.p[2], f.p[2], f.p[3] }, b.stem[k].p, 1e-9)
    end
    local moved = 0
    for k = 1, 4 do
      local l0, l1 = t0:find("t#1/leaf#" .. k), t1:find("ffd#1/t#1/leaf#" .. k)
      local p = l0.frame.p
      assert.near({ p[1] + 0.5 * p[2], p[2], p[3] }, l1.frame.p, 1e-9)
      moved = math.max(moved, dist(p, l1.frame.p))
      -- the leaf's vertices keep their distances (a rigid move)
      local v0, v1 = vertices(s0, l0), vertices(s1, l1)
      assert.equal(#v0, #v1)
      assert.is_true(#v0 >= 9)
      for i = 2, #v0 do
        assert.near(dist(v0[1], v0[i]), dist(v1[1], v1[i]), 1e-5)
      end
    end
    assert.is_true(moved > 0.3)
    -- the turtle still reaches every (moved) frame
    for _, inst in ipairs(t1:instances()) do
      local p = s1:turtle(inst.at)
      assert.is_true(dist(p, inst.frame.p) < 1e-6, inst.path)
    end
    -- the same FFD in mode "all" bends the leaves' vertices too
    local da = C.ffd { fx = shear }
    da:child(plant())
    local ma = C.model(da)
    local sa = ma:interpret()
    local la = ma.components.tree:find("ffd#1/t#1/leaf#4")
    local v0, va = vertices(s0, t0:find("t#1/leaf#4")), vertices(sa, la)
    local worst = 0
    for i = 2, #v0 do
      worst = math.max(worst, math.abs(dist(v0[1], v0[i]) - dist(va[1], va[i])))
    end
    assert.is_true(worst > 1e-3)
  end)

  it("isolate below a skeleton deformation keeps its subtree where it was", function ()
    local d = C.ffd { mode = "skeleton", fx = shear }
    local iso = C.ffd { isolate = true }
    iso:child(plant())
    d:child(iso)
    local t = C.expand(d)
    local ref = C.expand(plant())
    for k, f in ipairs(ref:find("t#1").stem) do
      assert.near(f.p, t:find("ffd#1/ffd#2/t#1").stem[k].p, 1e-12)
    end
  end)

  it("all mode: an identity FFD or Hyperpatch leaves the vertices as they were", function ()
    local base = C.scene(plant())
    for _, d in ipairs { C.ffd {}, C.hyperpatch { degree = 2 } } do
      d:child(plant())
      local s = C.scene(d)
      assert.equal(base.nvertices, s.nvertices)
      for i = 1, base.nvertices, 7 do
        assert.near({ base:vertex(i) }, { s:vertex(i) }, 1e-9)
      end
    end
  end)

  it("all mode: a Hyperpatch without moves is not applied (its map is the identity)",
     function ()
    local W = require "lsys.components.world"
    local map, calls = W.map, 0
    W.map = function (...) calls = calls + 1 return map(...) end
    local ok, err = pcall(function ()
      local base = C.scene(plant())
      local d = C.hyperpatch { degree = { 1, 2, 1 } }
      d:child(plant())
      local s = C.scene(d)
      assert.equal(0, calls)           -- no box from the vertices, no deformation
      for i = 1, base.nvertices do assert.same({ base:vertex(i) }, { s:vertex(i) }) end
      d = C.hyperpatch { degree = { 1, 2, 1 }, moves = { { 0, 2, 0, 0.5, 0, 0 } } }
      d:child(plant())
      C.scene(d)
      assert.equal(1, calls)
    end)
    W.map = map
    assert(ok, err)
  end)

  it("all mode: a partial deformation leaves the subtrees outside it untouched", function ()
    local function graph (deform)
      local root = C.tree { name = "root", length = 3, n = 2, angle = 40, segments = 4 }
      local inner = plant()
      if deform then
        local d = C.ffd { fx = shear }
        d:child(inner)
        root:branch(d, { only = { 1 } })
      else
        root:branch(inner, { only = { 1 } })
      end
      local other = C.tree { name = "other", length = 1, n = 3, segments = 3 }
      other:branch(C.leaf { name = "leaf" })
      root:branch(other, { only = { 2 } })
      return root
    end
    local m0, m1 = C.model(graph(false)), C.model(graph(true))
    local s0, s1 = m0:interpret(), m1:interpret()
    local a = vertices(s0, m0.components.tree:find("root#1/other#1"))
    local b = vertices(s1, m1.components.tree:find("root#1/other#1"))
    assert.equal(#a, #b)
    assert.is_true(#a > 50)
    for i = 1, #a do assert.near(a[i], b[i], 1e-12) end
    -- while the deformed subtree moved
    local x = vertices(s0, m0.components.tree:find("root#1/t#1"))
    local y = vertices(s1, m1.components.tree:find("root#1/ffd#1/t#1"))
    local moved = 0
    for i = 1, #x do moved = math.max(moved, dist(x[i], y[i])) end
    assert.is_true(moved > 0.1)
  end)
end)
