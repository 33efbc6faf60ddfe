-- The component-graph examples of Lintermann and Deussen 1999 (examples/components): fig. 2
-- (A-B-C-D), fig. 4 (sunflower), fig. 5 (rhododendron) and fig. 8 (agave). Instance counts
-- by name, where instances are (against the sidebar "Golden Section Placement on a
-- Sphere"), flag lists, determinism of the agave's functions, scene statistics and a golden
-- image of each.
--
-- After an intended change to an example or to the geometry, look at the new pictures and
-- write them with
--
--   LSYS_UPDATE_GOLDEN=1 lua5.4 /usr/bin/busted tests/components_examples_spec.lua
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local DIR = "examples/components/"

local function load (name) return dofile(DIR .. name .. ".lua") end

-- Instances by name (or kind when unnamed) of a model's i-tree.
local function counts (m)
  local out = {}
  for _, inst in ipairs(m.components.tree:instances()) do
    local k = inst.name or inst.kind
    out[k] = (out[k] or 0) + 1
  end
  return out
end

local function sub (a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function len (a) return math.sqrt(dot(a, a)) end

-- A 160 x 160 render of the scene against tests/golden/components_NAME.png.
local function golden (name, scene)
  if not core.has_render then return pending("lsys was built without OSMesa") end
  H.golden("components_" .. name, lsys.render(scene, { width = 160, height = 160 }))
end

describe("examples/components", function ()
  it("fig2_abcd: nine instances of D, three chains of three under C", function ()
    local m = load("fig2_abcd")
    assert.same({ A = 1, B = 1, C = 1, D = 9, bud = 9 }, counts(m))
    local t = m.components.tree
    local list = t:instances()
    local c = t:find("A#1/B#1/C#1")
    assert.equal("hydra", c.kind)
    assert.equal(3, #c.children)
    for k, ci in ipairs(c.children) do
      -- D_k, then D_k1 and D_k2 below it (the article's D_i1, D_i2, D_i3 chain)
      local d = list[ci]
      assert.same({ "D", k, 3, 1, c.index }, { d.name, d.i, d.n, d.depth, d.parent })
      for depth = 2, 3 do
        local kids = {}
        for _, x in ipairs(d.children) do kids[#kids + 1] = list[x].name end
        assert.same({ "D", "bud" }, kids)
        local nxt = list[d.children[1]]
        assert.same({ depth, d.index }, { nxt.depth, nxt.parent })
        -- each part 0.8 of the one before
        assert.near(0.8 * d.frame.s, nxt.frame.s, 1e-12)
        d = nxt
      end
      assert.equal(1, #d.children)         -- the last D: its bud, no D (recursion depth 3)
      assert.equal("bud", list[d.children[1]].name)
    end
    -- the three chains leave C 120 degrees apart around the stem, 50 degrees out from it
    local az = {}
    for k, ci in ipairs(c.children) do
      local hd = list[ci].frame.H
      assert.near(50, math.deg(math.acos(hd[2])), 1e-9)
      az[k] = math.deg(math.atan(hd[3], hd[1]))
    end
    local function gap (a, b) local d = (b - a) % 360 return math.min(d, 360 - d) end
    assert.near(120, gap(az[1], az[2]), 1e-9)
    assert.near(120, gap(az[2], az[3]), 1e-9)
    local sc = m:interpret()
    assert.is_true(sc.ntriangles > 7000 and sc.ntriangles < 11000, sc.ntriangles)
    golden("fig2_abcd", sc)
  end)

  it("sunflower: leaves on the stalk, 34 petals, 500 seeds by the golden section", function ()
    local m = load("sunflower")
    assert.same({ stalk = 1, petiole = 11, leaf = 11, head = 1, seeds = 1, seed = 500,
                  petals = 1, petal = 34, bracts = 1, bract = 21 }, counts(m))
    local t = m.components.tree
    local list = t:instances()
    local ball = t:find("stalk#1/head#1/seeds#1")
    local axis = ball.frame.H
    -- seed i of 500 on the section from 0 to 25 degrees, radius 3: the sidebar's
    -- cos(theta_i) = cos(theta_1) - (i/N)(cos(theta_1) - cos(theta_2)) with theta_1 = 0,
    -- theta_2 = 25 degrees, and Phi_i = i dPhi, dPhi = 2 pi / golden ratio
    local c25 = math.cos(math.rad(25))
    local prev
    for _, ci in ipairs(ball.children) do
      local s = list[ci]
      local d = sub(s.frame.p, ball.frame.p)
      assert.near(3, len(d), 1e-9)
      assert.near(1 - s.i / 500 * (1 - c25), dot(d, axis) / 3, 1e-9)
      assert.near(0.13, s.frame.s, 1e-12)
      if prev then
        -- consecutive seeds 137.5 degrees apart around the axis
        local a = sub(d, { axis[1] * dot(d, axis), axis[2] * dot(d, axis),
                           axis[3] * dot(d, axis) })
        local b = sub(prev, { axis[1] * dot(prev, axis), axis[2] * dot(prev, axis),
                              axis[3] * dot(prev, axis) })
        assert.near(360 - 360 / ((1 + math.sqrt(5)) / 2),
                    math.deg(math.acos(dot(a, b) / (len(a) * len(b)))), 1e-6)
      end
      prev = d
    end
    -- the leaves: larger below (branch_scale 1.2 down to 0.6 along the stalk)
    local pets = {}
    for _, inst in ipairs(list) do
      if inst.name == "petiole" then pets[#pets + 1] = inst end
    end
    assert.near(1.2, pets[1].frame.s, 1e-12)
    assert.near(0.6, pets[11].frame.s, 1e-12)
    local sc = m:interpret()
    -- 500 spheres, 66 leaves and the stalk's tubes
    assert.is_true(sc.ntriangles > 60000 and sc.ntriangles < 90000, sc.ntriangles)
    golden("sunflower", sc)
  end)

  it("rhododendron: 20 twigs, small twigs only at 2 and 13, leaves elsewhere", function ()
    local m = load("rhododendron")
    -- leaves: 14 on each twig, 4 on each small twig, 8 around each of the 60 tops
    assert.same({ pot = 1, bush = 1, twig = 20, small = 40, top = 60, truss = 60,
                  flower = 480, petal = 2400, collar = 60,
                  leaf = 20 * 14 + 40 * 4 + 60 * 8 }, counts(m))
    local t = m.components.tree
    -- count: the 920 instances labelled "leaf"; of kind leaf, the 2,400 petals too
    assert.same({ 920, 2400, 3320 }, { t:count("leaf"), t:count("petal"),
                                       t:count { kind = "leaf" } })
    local list = t:instances()
    local seen = 0
    for _, tw in ipairs(list) do
      if tw.name == "twig" then
        seen = seen + 1
        local small, leaves, tops = {}, {}, 0
        for _, ci in ipairs(tw.children) do
          local c = list[ci]
          if c.name == "small" then small[#small + 1] = c.i
          elseif c.name == "leaf" then leaves[#leaves + 1] = c.i
          elseif c.name == "top" then tops = tops + 1 end
        end
        assert.same({ 2, 13 }, small)
        assert.same({ 1, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 14, 15, 16 }, leaves)
        assert.equal(1, tops)
        assert.same({ tw.i, 20 }, { tw.i, tw.n })
      end
    end
    assert.equal(20, seen)
    -- the bush's Phiball scales its twigs from 0.8 (at the top) to 1.05 (the rim)
    assert.near(0.8, t:find("pot#1/bush#1/twig#1").frame.s, 1e-12)
    assert.near(1.05, t:find("pot#1/bush#1/twig#20").frame.s, 1e-12)
    local sc = m:interpret()
    -- the 3320 leaves and petals drawn large in the bush: 96 or 160 triangles each (the
    -- leaves' automatic detail), and the stems, flower stalks and the pot
    assert.equal(471268, sc.ntriangles)
    assert.is_true(sc.ntriangles > 3320 * 96 and sc.ntriangles < 3320 * 170, sc.ntriangles)
    golden("rhododendron", sc)
  end)

  it("agave: leaves longer and more bent outwards, the same plant for the same seed",
     function ()
    local function leaves (seed)
      local m = load("agave")
      if seed then
        m = require("lsys.components").model(m.components.tree.root,
                                              { seed = seed, view = m.view })
      end
      local out = {}
      for _, inst in ipairs(m.components.tree:instances()) do
        if inst.name == "leaf" then
          out[#out + 1] = { i = inst.i, length = len(sub(inst.tip.p, inst.frame.p)),
                            H = inst.frame.H }
        end
      end
      return out, m
    end
    local a, m = leaves()
    assert.same({ base = 1, rosette = 1, leaf = 34 }, counts(m))
    -- length: the range 1.8 .. 3.4 over i, times a random factor in [0.88, 1.12]
    local inner, outer = 0, 0
    for k, l in ipairs(a) do
      assert.equal(k, l.i)
      local v = 1.8 + (k - 1) * 1.6 / 33
      assert.is_true(l.length >= 0.88 * v - 1e-9 and l.length <= 1.12 * v + 1e-9,
                     k .. ": " .. l.length)
      if k <= 6 then inner = inner + l.length end
      if k > 28 then outer = outer + l.length end
    end
    assert.is_true(outer > 1.4 * inner)
    -- the first leaves stand almost upright, the last lie out at 88 degrees
    assert.is_true(a[1].H[2] > 0.95)
    assert.near(math.cos(math.rad(88)), a[34].H[2], 1e-9)
    -- same seed, same plant; another seed, the same counts and another plant
    local b = leaves()
    local c = leaves(2)
    local diff = 0
    for k = 1, 34 do
      assert.equal(a[k].length, b[k].length)
      diff = diff + math.abs(a[k].length - c[k].length)
    end
    assert.is_true(diff > 0.5, diff)
    local s1, s2 = m:interpret(), select(2, leaves(1)):interpret()
    assert.equal(s1.ntriangles, s2.ntriangles)
    assert.same({ s1:bounds() }, { s2:bounds() })
    local s3 = select(2, leaves(2)):interpret()
    assert.are_not.same({ s1:bounds() }, { s3:bounds() })
    golden("agave", s1)
  end)
end)
