-- The rest of Lintermann and Deussen 1999's figures as component examples
-- (examples/components): fig. 6a and 6b (fig6_ab.lua, the chestnut's first stages), fig. 7
-- (maple.lua), fig. 10a and 10c (fig10_ac.lua, the pine undeformed and deformed whole),
-- fig. C (figC_tree.lua, a Tree's parameters) and fig. D (figD_placement.lua, placement
-- by the multipliers): their instance counts and the property each figure shows, measured
-- on the i-tree or the scene, and golden images of the small ones (160x160, figs. C and D
-- 240 wide; write them again after an intended change, having looked at them, with
-- LSYS_UPDATE_GOLDEN=1).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"
local C = lsys.components

local DIR = "examples/components/"

local function golden (name, scene, w, h)
  if not core.has_render then return pending("lsys was built without OSMesa") end
  H.golden("components_" .. name, lsys.render(scene, { width = w or 160, height = h or 160 }))
end

-- Instances by label (name, or kind when unnamed) of a model's i-tree.
local function counts (m)
  local out = {}
  for _, inst in ipairs(m.components.tree:instances()) do
    out[inst.label] = (out[inst.label] or 0) + 1
  end
  return out
end

local function sub (a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function len (a) return math.sqrt(dot(a, a)) end
local function angle (a, b) return math.deg(math.acos(math.max(-1, math.min(1, dot(a, b))))) end

local function byname (m, name)
  local out = {}
  for _, inst in ipairs(m.components.tree:instances()) do
    if inst.name == name then out[#out + 1] = inst end
  end
  return out
end

describe("fig. 6a and 6b: the chestnut's first stages", function ()
  local F = dofile(DIR .. "fig6_ab.lua")

  it("cuts the chestnut's graph after its second and its fourth Tree", function ()
    assert.same({ trunk = 1, branch = 12 }, counts(F.a))
    assert.same({ trunk = 1, branch = 12, ["sub-branch"] = 96, twig = 576 }, counts(F.b))
    -- the same trunk in both (its gnarl draws the first random numbers): the stages grow
    -- one tree, whose branches the later levels' draws bend differently
    local ta, tb = F.a.components.tree:find("trunk#1"), F.b.components.tree:find("trunk#1")
    assert.near(ta.tip.p, tb.tip.p, 1e-12)
    assert.near(ta.tip.H, tb.tip.H, 1e-12)
    assert.equal(13316, F.a:interpret().ntriangles)
  end)
end)

describe("fig. 7: the maple", function ()
  local M = dofile(DIR .. "maple.lua")

  it("is a cascade of five Trees with 7,560 leaves of five lobes in opposite pairs", function ()
    assert.same({ trunk = 1, limb = 6, branch = 42, branchlet = 252, twig = 1260, node = 3780,
                  petiole = 7560, blade = 7560, lobe = 37800 }, counts(M))
    local t = M.components.tree
    assert.equal(37800, t:count { kind = "leaf" })
    local list = t:instances()
    -- a node's two leaves point opposite ways round the twig, 60 degrees out from it, and
    -- the next node's pair is turned a quarter round (decussate)
    local tw = t:find("trunk#1/limb#1/branch#1/branchlet#1/twig#1")
    local axis
    local function across (v)
      local k = dot(v, axis)
      local w = sub(v, { k * axis[1], k * axis[2], k * axis[3] })
      local l = len(w)
      return { w[1] / l, w[2] / l, w[3] / l }
    end
    local dirs = {}
    for j, ni in ipairs(tw.children) do
      local node = list[ni]
      assert.equal("node", node.name)
      local a, b = list[node.children[1]], list[node.children[2]]
      axis = node.frame.H
      assert.near(60, angle(a.frame.H, axis), 1e-9)
      assert.near(180, angle(across(a.frame.H), across(b.frame.H)), 1e-6)
      dirs[j] = across(a.frame.H)
    end
    assert.equal(3, #dirs)
    axis = tw.stem[1].H
    assert.near(90, angle(across(dirs[1]), across(dirs[2])), 2)   -- the twig bends a little
    -- a leaf: five lobes over 210 degrees, the middle one longest, the outer ones shortest
    local blade = list[list[list[tw.children[1]].children[1]].children[1]]
    assert.equal("blade", blade.name)
    local lens = {}
    for k, ci in ipairs(blade.children) do lens[k] = list[ci].length end
    assert.equal(5, #lens)
    assert.is_true(lens[3] > lens[2] and lens[2] > lens[1], table.concat(lens, " "))
    assert.near(lens[1], lens[5], 1e-12)
    assert.near(lens[2], lens[4], 1e-12)
    -- a broad crown: wider than the tree is tall above its trunk's first limb
    local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
    for _, inst in ipairs(byname(M, "blade")) do
      local p = inst.frame.p
      for k = 1, 3 do lo[k], hi[k] = math.min(lo[k], p[k]), math.max(hi[k], p[k]) end
    end
    assert.is_true(hi[1] - lo[1] > hi[2] - 0.45 * 5, "crown " .. (hi[1] - lo[1]))
  end)

  it("draws a smaller maple like its golden image", function ()
    local small = M.graph { limbs = 3, branches = 3, branchlets = 3, twigs = 3 }
    golden("maple_small", C.model(small, { seed = 1, view = M.VIEW }):interpret())
  end)
end)

describe("fig. 10a and 10c: the pine undeformed and deformed whole", function ()
  local F = dofile(DIR .. "fig10_ac.lua")
  local P = dofile(DIR .. "pine.lua")

  it("leaves the bend out, or deforms the needles with the tree", function ()
    local tree = { trunk = 1, branch = 14, twig = 112, pair = 4480, needle = 8960 }
    assert.same(tree, counts(F.a))
    tree.bend = 1
    assert.same(tree, counts(F.c))
    -- undeformed, the trunk is straight
    local st = F.a.components.tree:find("trunk#1").stem
    assert.near(0, st[#st].p[1], 1e-12)
    -- each needle's size (its farthest vertex from its centre) in 10b and 10c: kept in
    -- 10b, up to 1.7 times in 10c, most at the upper right ("the needles on the right
    -- appear too big")
    local opts = { branches = 14, twigs = 3, pairs = 4 }
    local function sizes (deform)
      opts.deform = deform
      local m = C.model(P.graph(opts), { seed = 1, view = P.VIEW })
      local sc = m:interpret()
      local out = {}
      for _, inst in ipairs(byname(m, "needle")) do
        local v0, v1 = sc:module_range(inst.modules[1], inst.modules[2])
        local vs, c = {}, { 0, 0, 0 }
        for i = v0, v1 do vs[#vs + 1] = { sc:vertex(i) } end
        for _, v in ipairs(vs) do for k = 1, 3 do c[k] = c[k] + v[k] / #vs end end
        local r = 0
        for _, v in ipairs(vs) do r = math.max(r, len(sub(v, c))) end
        out[#out + 1] = { c = c, r = r }
      end
      return out
    end
    local none, twigs, all = sizes("none"), sizes("twigs"), sizes("all")
    assert.equal(14 * 3 * 4 * 2, #all)
    local mid = { 0, 0 }
    for _, n in ipairs(twigs) do
      mid[1], mid[2] = mid[1] + n.c[1] / #twigs, mid[2] + n.c[2] / #twigs
    end
    local kept, ur, rest, nur, nrest, most = 0, 0, 0, 0, 0, 0
    for i, n in ipairs(twigs) do
      kept = math.max(kept, math.abs(n.r - none[i].r))
      local g = all[i].r / n.r
      most = math.max(most, g)
      if n.c[1] > mid[1] and n.c[2] > mid[2] then ur, nur = ur + g, nur + 1
      else rest, nrest = rest + g, nrest + 1 end
    end
    assert.is_true(kept < 1e-5, kept)
    assert.is_true(most > 1.4, most)
    assert.is_true(ur / nur > rest / nrest and ur / nur > 1.1, (ur / nur) .. " " .. (rest / nrest))
  end)
end)

describe("fig. C: a Tree's parameters", function ()
  local M = dofile(DIR .. "figC_tree.lua")
  local t = M.components.tree

  -- The branches of tree `name`, their instances in order up the stem.
  local function branches (name)
    local tr = t:find("row#1/" .. name .. "#1")
    local out = {}
    for _, ci in ipairs(tr.children) do out[#out + 1] = t:instances()[ci] end
    return tr, out
  end

  it("stands six trees in a row, each with one parameter changed", function ()
    assert.equal(1 + 6 * 13, t:count())
    local base, bb = branches("default")
    local st = base.stem
    assert.near({ base.frame.p[1], 4, 0 }, st[#st].p, 1e-12)          -- a straight stem
    for _, b in ipairs(bb) do assert.near(60, angle(b.frame.H, { 0, 1, 0 }), 1e-9) end
    -- 2 gnarled: the stem wanders off the straight line
    local g = branches("gnarl").stem
    local off = 0
    for _, f in ipairs(g) do off = math.max(off, math.abs(f.p[1] - g[1].p[1])) end
    assert.is_true(off > 0.2, off)
    -- 3 density: the branches crowd to the base
    local function mean (list)
      local s = 0
      for _, b in ipairs(list) do s = s + b.frame.p[2] end
      return s / #list
    end
    local _, db = branches("density")
    assert.is_true(mean(db) < mean(bb) - 0.5, mean(db) .. " " .. mean(bb))
    -- 4 angle: 110 degrees at the lowest branch, 25 at the highest
    local _, ab = branches("angle")
    assert.near(110, angle(ab[1].frame.H, { 0, 1, 0 }), 1e-9)
    assert.near(25, angle(ab[#ab].frame.H, { 0, 1, 0 }), 1e-9)
    -- 5 phototropism: every branch ends pointing higher than the default's
    local _, pb = branches("phototropism")
    for k = 1, #pb do
      local a, b = pb[k].stem, bb[k].stem
      assert.is_true(a[#a].H[2] > b[#b].H[2] + 0.1, "branch " .. k)
    end
    -- 6 curvature: the stem's tip turned 70 degrees from its base
    local cv = branches("curvature").stem
    assert.near(70, angle(cv[1].H, cv[#cv].H), 1e-9)
  end)

  it("draws like its golden image", function ()
    golden("figC", M:interpret(), 240, 80)
  end)
end)

describe("fig. D: placement by Hydra, Wreath and Phiball", function ()
  local M = dofile(DIR .. "figD_placement.lua")
  local t = M.components.tree
  local list = t:instances()

  local function children (path)
    local m = t:find(path)
    local out = {}
    for _, ci in ipairs(m.children) do out[#out + 1] = list[ci] end
    return m, out
  end

  it("places the same child as a star, a wreath and a golden-section sphere", function ()
    assert.same({ 9, 9, 40 }, { t:count("child1"), t:count("child2"), t:count("child3") })
    -- the Hydra: 9 round its axis, 40 degrees apart, each 70 degrees out, 0.25 out
    local h, hc = children("row#1/at1#1/hydra#1")
    local az = {}
    for k, c in ipairs(hc) do
      assert.near(70, angle(c.frame.H, h.frame.H), 1e-9)
      local d = sub(c.frame.p, h.frame.p)
      assert.near(0.25, len(d), 1e-12)
      az[k] = math.deg(math.atan(d[3], d[1]))
    end
    for k = 2, 9 do assert.near(40, math.abs((az[k] - az[k - 1] + 180) % 360 - 180), 1e-9) end
    -- the Wreath: 9 on a ring of 1.2, all along the axis, up sides outwards
    local w, wc = children("row#1/at2#1/wreath#1")
    for _, c in ipairs(wc) do
      local d = sub(c.frame.p, w.frame.p)
      assert.near(1.2, len(d), 1e-12)
      assert.near(w.frame.H, c.frame.H, 1e-12)
      assert.near({ d[1] / 1.2, d[2] / 1.2, d[3] / 1.2 }, c.frame.U, 1e-12)
    end
    -- the Phiball: 40 on a sphere of 0.9, each along its normal, 222.5 degrees on from the
    -- one before (2 pi over the golden ratio)
    local p, pc = children("row#1/at3#1/phiball#1")
    local prev
    for _, c in ipairs(pc) do
      local d = sub(c.frame.p, p.frame.p)
      assert.near(0.9, len(d), 1e-12)
      assert.near({ d[1] / 0.9, d[2] / 0.9, d[3] / 0.9 }, c.frame.H, 1e-12)
      local a = math.deg(math.atan(d[3], d[1]))
      if prev then
        local step = (prev - a) % 360              -- round the +y axis, x towards -z
        assert.near(360 / ((1 + math.sqrt(5)) / 2), step, 1e-6)
      end
      prev = a
    end
  end)

  it("draws like its golden image", function ()
    golden("figD", M:interpret(), 240, 94)
  end)
end)
