-- Incremental growth (Davison, "Incremental rules for growing plants"): persistent
-- limbs, if-then rules in parallel ticks, kinds and subclassing, geometry rewritten in place
-- (lsys.grow over csrc/core/grow.c).
local grow = require "lsys.grow"

local errof = require("tests.helper").errof

local function near (a, b, tol) return math.abs(a - b) <= (tol or 1e-9) end

-- The paper's 'child limbs spawning' action: two children, each with probability 0.85.
local function two (l)
  if l:random() < 0.85 then
    l:spawn { angle = l:random(10, 30), axis = l:random() < 0.5 and "z" or "x" }
  end
  if l:random() < 0.85 then
    l:spawn { angle = l:random(-30, -10), axis = l:random() < 0.5 and "z" or "x" }
  end
end

-- The paper's three rules ('length', 'thickness', 'child limbs spawning'), for a kind: at
-- most `cap` (256) limbs a plant before spawning, or in the world with `scene`.
local function davison (K, cap, scene)
  K:rule("length", function (l)
    if l:length() < 1.0 and not l:has_leaves() then l:scale_length(1.1) end
  end)
  K:rule("thickness", function (l)
    if l:radius() <= -0.05 * l:level() + 0.25 and not l:has_leaves() then l:scale_radius(1.05) end
  end)
  K:rule("spawn", function (l, w)
    local n = scene and w:count() or l:count()
    if l:age() == 5 and n <= (cap or 256) and not l:has_leaves() and l:level() < 10 then
      two(l)
    end
  end)
  return K
end

describe("lsys.grow ticks", function ()
  it("ticks a world without plants", function ()
    local w = grow.world {}
    w:tick(1)
    assert.equal(1, w.ticks)
    assert.equal(0, w:count())
    assert.equal(0, w:scene().nvertices)
  end)

  it("takes any finite seed, as a model does: a whole number as itself, others by bits",
     function ()
    -- the grow fuzz target's finding: seed 1e303 has no integer for the generator
    local function draws (seed)
      local w = grow.world { seed = seed }
      w:plant {}
      w:tick(1)
      return { w:random(), w:limb(1):random() }
    end
    assert.same(draws(1e303), draws(1e303))
    assert.are_not.same(draws(1e303), draws(-1e303))
    assert.same(draws(2), draws(2.0))
    assert.same(draws(2), draws(2.5))              -- a plant's seed is the floor, as before
  end)

  it("runs rules in parallel: reads see the start of the tick, new limbs wait", function ()
    local K = grow.kind("k")
    local seen = {}
    K:rule("grow", function (l)
      l:scale_length(2)
      l:scale_length(1.5)                            -- writes compound
      seen[#seen + 1] = { l:id(), l:length() }      -- ... reads do not see them
      if l:is_root() and l:age() == 0 then l:spawn { angle = 30 } end
    end)
    local w = grow.world()
    local root = w:plant { kind = K, length = 1 }
    w:tick()
    assert.same({ { 1, 1 } }, seen)                 -- the child did not run in tick 1
    assert.near(3, root:length(), 1e-12)
    local child = root:children()[1]
    assert.equal(0.5, child:length())
    assert.equal(1, root:age())
    assert.equal(0, child:age())
    w:tick()
    assert.same({ { 1, 1 }, { 1, 3 }, { 2, 0.5 } }, seen)
    assert.near(1.5, child:length(), 1e-12)
    assert.equal(2, root:age())
    assert.equal(1, child:age())
    assert.equal(2, w.ticks)
  end)

  it("keeps levels, parents, children and siblings", function ()
    local w = grow.world()
    local a = w:plant()
    local b, c = a:spawn { angle = 20 }, a:spawn { angle = -20 }
    local d = b:spawn { axis = "x", angle = 30 }
    assert.equal(1, a:level())
    assert.equal(2, b:level())
    assert.equal(3, d:level())
    assert.is_true(a:is_root())
    assert.is_false(d:is_root())
    assert.equal(a, b:parent())
    assert.is_nil(a:parent())
    assert.same({ b, c }, a:children())
    assert.same({ c }, b:siblings())
    assert.same({}, a:siblings())
    assert.equal(4, w:count())
    assert.equal(4, a:count())
    assert.equal("limb", d:kind())
  end)

  it("puts children at the tip, turned about the limb's own axes", function ()
    local w = grow.world()
    local a = w:plant { position = { 1, 0, 2 }, length = 2 }
    local b = a:spawn { angle = 90, axis = "z", length = 1 }
    local c = a:spawn { angle = 90, axis = "x", length = 1, at = 0.5 }
    local x, y, z = b:base()
    assert.is_true(near(x, 1) and near(y, 2) and near(z, 2))
    x, y, z = b:tip()                                -- +90 about z turns +y to -x
    assert.is_true(near(x, 0) and near(y, 2) and near(z, 2))
    x, y, z = c:tip()                                -- +90 about x turns +y to +z
    assert.is_true(near(x, 1) and near(y, 1) and near(z, 3))
    -- the parent grows: its children move with its tip
    a:set_length(3)
    x, y = b:base()
    assert.is_true(near(x, 1) and near(y, 3))
    x, y = c:base()
    assert.is_true(near(x, 1) and near(y, 1.5))
  end)

  it("grows the paper's trees the same for the same seed, and stops at the cap", function ()
    local function run (seed, max)
      local w = grow.world { seed = seed, max_limbs = max }
      local K = davison(grow.kind("tree"))
      for k = 0, 4 do w:plant { kind = K, position = { k * 5, 0, 0 } } end
      w:tick(40)
      local lens = {}
      for _, l in ipairs(w:limbs()) do lens[#lens + 1] = l:length() end
      return w:count(), lens, w
    end
    local n1, l1 = run(1)
    local n2, l2 = run(1)
    local n3 = run(2)
    assert.equal(n1, n2)
    assert.same(l1, l2)
    assert.are_not.equal(n1, n3)
    assert.is_true(n1 > 200, n1)
    local n4, _, w4 = run(1, 100)
    assert.equal(100, n4)
    assert.is_true(w4.capped)
  end)

  it("lets kinds extend kinds: rules inherited, replaced by name, added", function ()
    local log = {}
    local Base = grow.kind("base")
    Base:rule("a", function (l) log[#log + 1] = l:kind() .. ".a" end)
    Base:rule("b", function (l) log[#log + 1] = l:kind() .. ".b" end)
    Base.max_length = 1
    function Base:twice () return 2 * self:length() end
    local Sub = grow.kind("sub", Base)
    Sub:rule("a", function (l) log[#log + 1] = l:kind() .. ".A" end)
    Sub:rule("c", function (l) log[#log + 1] = l:kind() .. ".c" end)
    local w = grow.world()
    w:plant { kind = Base }
    local s = w:plant { kind = Sub, length = 2 }
    w:tick()
    assert.same({ "base.a", "base.b", "sub.A", "sub.b", "sub.c" }, log)
    assert.equal(4, s:twice())
    assert.equal(1, s.max_length)
    s.max_length = 3                                 -- a limb's own field
    assert.equal(3, s.max_length)
    assert.equal(1, Sub.max_length)
    local names = {}
    for _, r in ipairs(Sub:rules()) do names[#names + 1] = r[1] end
    assert.same({ "a", "b", "c" }, names)
  end)

  it("gives a kind its base's rules written as tables: condition, changes and fn", function ()
    local calls = {}
    local Base = grow.kind("base")
    Base:rule("length", { when = "length < 1", scale_length = 1.1 })
    Base:rule("bark", { when = "age >= 0", blend = { "#000000", 0.5 } })
    Base:rule("mark", { when = "root == 1", fn = function (l) calls[#calls + 1] = l:kind() end })
    local Sub = grow.kind("sub", Base)
    local Sub2 = grow.kind("sub2", Sub)
    Sub2:rule("length", { when = "length < 1", scale_length = 2 })   -- replaced here only
    local w = grow.world()
    local a = w:plant { kind = Base, color = "#ffffff" }
    local b = w:plant { kind = Sub, color = "#ffffff" }
    local c = w:plant { kind = Sub2, color = "#ffffff" }
    w:tick()
    assert.near(0.55, a:length(), 1e-12)
    assert.near(0.55, b:length(), 1e-12)
    assert.near(1, c:length(), 1e-12)
    for _, l in ipairs { a, b, c } do assert.same({ 0.5, 0.5, 0.5 }, l:color()) end
    assert.same({ "base", "sub", "sub2" }, calls)
    w:tick()                                         -- c is 1 long: its condition fails
    assert.near(0.605, a:length(), 1e-12)
    assert.near(0.605, b:length(), 1e-12)
    assert.near(1, c:length(), 1e-12)
    assert.same({ "length", "bark", "mark" }, (function ()
      local names = {}
      for _, r in ipairs(Sub:rules()) do names[#names + 1] = r[1] end
      return names
    end)())
  end)

  it("counts a child as soon as it is made, in its plant and in the world", function ()
    -- every new limb spawns two while its plant has at most 3 limbs (Davison's spawning
    -- rule reads treeLimbs.size(), which makeChild appends to)
    local function spawn2 (l) l:spawn {} l:spawn {} end
    local function grown (rule, plants)
      local K = grow.kind("k")
      K:rule("spawn", rule)
      local w = grow.world()
      for _ = 1, plants or 1 do w:plant { kind = K } end
      w:tick(4)
      local per = {}
      for p = 1, plants or 1 do per[p] = w:count(p) end
      return w:count(), per
    end
    local seen = {}
    assert.equal(5, grown(function (l)
      if l:age() == 0 then
        seen[#seen + 1] = l:count()
        if l:count() <= 3 then spawn2(l) end
      end
    end))
    assert.same({ 1, 3, 5, 5, 5 }, seen)             -- the second child sees the first's two
    assert.equal(5, grown { when = "age == 0 and count <= 3", fn = spawn2 })
    -- two plants: per plant, or in the whole world as the paper counts (total)
    local n, per = grown({ when = "age == 0 and count <= 3", fn = spawn2 }, 2)
    assert.equal(10, n)
    assert.same({ 5, 5 }, per)
    n, per = grown({ when = "age == 0 and total <= 3", fn = spawn2 }, 2)
    assert.equal(4, n)
    assert.same({ 3, 1 }, per)
    n, per = grown(function (l, world)
      if l:age() == 0 and world:count() <= 3 then spawn2(l) end
    end, 2)
    assert.equal(4, n)
    assert.same({ 3, 1 }, per)
  end)

  it("adds leaves and removes subtrees at the end of the tick, reusing their geometry", function ()
    local K = grow.kind("k")
    K:rule("leaf", function (l)
      if l:age() == 1 and l:is_root() then
        l:add_leaves(3, { size = 0.2 })
        assert.is_false(l:has_leaves())              -- not yet
      end
    end)
    K:rule("prune", function (l)
      if l:age() == 2 and not l:is_root() then l:remove() end
    end)
    local w = grow.world()
    local a = w:plant { kind = K }
    local b = a:spawn {}
    b:spawn {}
    w:tick(2)
    assert.equal(3, a:leaves())
    assert.is_true(a:has_leaves())
    w:tick()
    assert.equal(1, w:count())
    assert.is_false(b:alive())
    assert.truthy(errof(b.length, b):find("the limb was removed", 1, true))
    assert.same({}, a:children())
    -- a new limb takes a freed range: the scene does not grow
    local before = w:scene().nvertices
    a:spawn {}
    assert.equal(before, w:scene().nvertices)
    a:spawn {}                                       -- only two ranges were freed
    a:spawn {}
    assert.is_true(w:scene().nvertices > before)
  end)
end)

-- A flat unit square in x, y (one Bezier patch) as a cpfg surface file's text.
local function square ()
  local rows = {}
  for r = 0, 3 do
    local pts = {}
    for c = 0, 3 do pts[#pts + 1] = string.format("%g %g 0", c / 3, r / 3) end
    rows[#rows + 1] = table.concat(pts, " ")
  end
  return "0 1 0 1 0 0\nPRECISION S: 1 T: 1\nCONTACT POINT X: 0 Y: 0 Z: 0\n"
    .. "END POINT X: 0 Y: 0 Z: 0\nHEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\n"
    .. "sq\nTOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\n"
    .. "AL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: ~ BR: ~\n" .. table.concat(rows, "\n") .. "\n"
end

-- A world of one limb 1 long and thin as a line, with one leaf of size 2 at its tip.
local function oneleaf (leaf)
  local K = grow.kind("k")
  K:rule("leaf", function (l) if l:age() == 0 then l:add_leaves(1, { size = 2 }) end end)
  local w = grow.world { leaf = leaf }
  w:plant { kind = K, length = 1, radius = 0 }
  w:tick(1)
  return w
end

describe("lsys.grow leaf shapes", function ()
  local core = require "lsys.core"
  local S50, C50 = math.sin(math.rad(50)), math.cos(math.rad(50))

  it("places a surface leaf: contact at the tip, heading 50 degrees off the limb", function ()
    local w = oneleaf(core.surface_parse(square(), "square"))
    local sc = w:scene()
    assert.equal(16 + 4, sc.nvertices)            -- an 8-sided tube, a 1 x 1 patch grid
    assert.equal(16 + 2, sc.ntriangles)
    -- leaf x -> -z, y -> (sin 50, cos 50, 0): the square's corners are the tip, the tip
    -- - 2 z, the tip + 2 (sin 50, cos 50, 0) and the sum of both
    local lo, hi = sc:bounds()
    local want = { { 0, 0, -2 }, { 2 * S50, 1 + 2 * C50, 0 } }
    for k = 1, 3 do
      assert.is_true(near(lo[k], want[1][k], 1e-6), "lo " .. k)
      assert.is_true(near(hi[k], want[2][k], 1e-6), "hi " .. k)
    end
    -- the quad for comparison: 4 vertices a leaf, its far point 2 along the leaf's y
    local q = oneleaf(nil):scene()
    assert.equal(16 + 4, q.nvertices)
    local _, qhi = q:bounds()
    assert.is_true(near(qhi[2], 1 + 2 * C50, 1e-6))
  end)

  it("reads a surface file next to the file making the world, at its precision", function ()
    local base = oneleaf(nil):scene().nvertices - 4
    -- examples/cpfg/surfaces/leaf.s: 2 patches at 8 x 8 lines a patch = 2 x 81 vertices
    local w = oneleaf("../examples/cpfg/surfaces/leaf.s")
    assert.equal(base + 162, w:scene().nvertices)
    assert.equal(16 + 256, w:scene().ntriangles)
    w = oneleaf { file = "../examples/cpfg/surfaces/leaf.s", precision = { 2, 3 } }
    assert.equal(base + 2 * 12, w:scene().nvertices)
    assert.equal(16 + 2 * 12, w:scene().ntriangles)
    -- a file's leaves drop and grow again in the same ranges
    local l = w:limb(1)
    w._T:begin() l:drop_leaves() w._T:finish()
    assert.equal(0, l:leaves())
    w._T:begin() l:add_leaves(1, { size = 1 }) w._T:finish()
    assert.equal(base + 2 * 12, w:scene().nvertices)
  end)

  it("takes a sketched organ and a Scene as the shape", function ()
    local organ = require("lsys.sketch.organ").build {
      top = { left = { { 100, 300 }, { 100, 100 } }, right = { { 200, 300 }, { 200, 100 } } } }
    local w = oneleaf(organ)
    local n = organ:surface():info().patches
    assert.is_true(w:scene().ntriangles > 16 + 2 * n)
    -- a Scene: a triangle drawn by the turtle in its plane (y up, x across)
    local m = require("lsys").lsystem { axiom = "{.f(1)+(90)f(0.5).}" }
    local tri = m:interpret(m:derive())
    assert.equal(1, tri.ntriangles)
    local sc = oneleaf(tri):scene()
    assert.equal(16 + tri.nvertices, sc.nvertices)
    assert.equal(16 + 1, sc.ntriangles)
    local tlo, thi = tri:bounds()
    local lo, hi = sc:bounds()
    -- shape x -> world -z, shape y -> (sin 50, cos 50, 0), scaled by 2 from the tip
    assert.is_true(near(lo[3], math.min(0, -2 * thi[1]), 1e-6))
    assert.is_true(near(hi[3], math.max(0, -2 * tlo[1]), 1e-6))
    assert.is_true(near(hi[2], 1 + 2 * C50 * thi[2], 1e-6))
  end)

  it("names what is wrong with a leaf shape", function ()
    local msg = errof(function () local w = grow.world { leaf = "no-such.s" } return w end)
    assert.truthy(msg:find("world: leaf: cannot open 'tests/no-such.s'", 1, true), msg)
    assert.truthy(msg:find("looked up in 'tests', the folder of the file making the world",
                           1, true), msg)
    -- through a tail call (or pcall) the caller cannot be seen: the current folder, and how
    msg = errof(function () return grow.world { leaf = "no-such.s" } end)
    assert.truthy(msg:find("cannot open 'no-such.s'", 1, true), msg)
    assert.truthy(msg:find("the current folder (give the world dir = lsys.here()", 1, true), msg)
    msg = errof(grow.world, { leaf = "no-such.s", dir = "/nowhere" })
    assert.truthy(msg:find("cannot open '/nowhere/no-such.s'", 1, true), msg)
    assert.truthy(msg:find("looked up in '/nowhere', the world's dir", 1, true), msg)
    assert.truthy(errof(grow.world, { dir = 1 }):find("'dir' must be a folder's name", 1, true))
    msg = errof(grow.world, { leaf = 3 })
    assert.truthy(msg:find("an lsys.Surface, an organ, an lsys.Scene or a file name expected, "
                           .. "got number", 1, true), msg)
    local sq = core.surface_parse(square())
    msg = errof(grow.world, { leaf = { surface = sq, size = 1 } })
    assert.truthy(msg:find("world: leaf: unknown option 'size'", 1, true), msg)
    msg = errof(grow.world, { leaf = { surface = sq, precision = { 0, 4 } } })
    assert.truthy(msg:find("'precision' must be whole numbers 1..256", 1, true), msg)
    msg = errof(grow.world, { leaf = { precision = { 2, 2 } } })
    assert.truthy(msg:find('"quad", a surface file name', 1, true), msg)
    msg = errof(grow.world, { leaf = { surface = sq, precision = { 256, 256 } } })
    assert.truthy(msg:find("more than 65536 vertices (256 x 256 lines a patch)", 1, true), msg)
    -- the shape is set before any leaf: the C table refuses it after
    local w = oneleaf(nil)
    msg = errof(w._T.set_leaf, w._T, nil)
    assert.truthy(msg:find("leaves are made already", 1, true), msg)
    local empty = require("lsys").lsystem { axiom = "F" }
    msg = errof(grow.world, { leaf = empty:interpret(empty:derive()) })
    assert.truthy(msg:find("world: leaf: the scene has no triangles", 1, true), msg)
  end)
end)

describe("lsys.grow rules run in C", function ()
  -- The paper's rules with their conditions in C: the same plants as the Lua functions.
  local function cdavison (K, cap, scene)
    K:rule("length", { when = "length < 1.0 and leaves == 0", scale_length = 1.1 })
    K:rule("thickness", { when = "radius <= -0.05 * level + 0.25 and leaves == 0",
                          scale_radius = 1.05 })
    K:rule("spawn", {
      when = "age == 5 and " .. (scene and "total" or "count") .. " <= " .. (cap or 256)
        .. " and leaves == 0 and level < 10",
      fn = two,
    })
    return K
  end

  local function grown (make, ticks)
    local w = grow.world { seed = 4 }
    local K = make(grow.kind("tree"))
    for k = 0, 2 do w:plant { kind = K, position = { k * 5, 0, 0 } } end
    w:tick(ticks)
    local out = {}
    for _, l in ipairs(w:limbs()) do
      local x, y, z = l:tip()
      out[#out + 1] = { l:length(), l:radius(), l:level(), x, y, z }
    end
    return out, w
  end

  it("grows the same plants as the same rules written as functions", function ()
    local a = grown(davison, 45)
    local b = grown(cdavison, 45)
    assert.is_true(#a > 100, #a)
    assert.same(a, b)
    -- capped at 40 limbs a plant: both count each child as it is made
    local wa, wb
    a, wa = grown(function (K) return davison(K, 40) end, 45)
    b, wb = grown(function (K) return cdavison(K, 40) end, 45)
    assert.same(a, b)
    for p = 1, 3 do
      assert.is_true(wa:count(p) >= 41 and wa:count(p) <= 42, wa:count(p))
      assert.equal(wa:count(p), wb:count(p))
    end
    -- and 40 in the world, as the paper counts
    a, wa = grown(function (K) return davison(K, 40, true) end, 45)
    b = grown(function (K) return cdavison(K, 40, true) end, 45)
    assert.same(a, b)
    assert.is_true(wa:count() >= 41 and wa:count() <= 42, wa:count())
  end)

  it("decides every condition as Lua does, fast path or expression machine", function ()
    local conds = {
      { "length <= 0.75", function (l) return l:length() <= 0.75 end },
      { "length >= 0.5 and level > 1",
        function (l) return l:length() >= 0.5 and l:level() > 1 end },
      { "radius < 0.01 * level + 0.04",
        function (l) return l:radius() < 0.01 * l:level() + 0.04 end },
      { "age ~= 2 and count >= 3", function (l) return l:age() ~= 2 and l:count() >= 3 end },
      { "level == 1 * age + 1", function (l) return l:level() == 1 * l:age() + 1 end },
      { "root == 1 or leaves > 0", function (l) return l:is_root() or l:leaves() > 0 end },
      { "math.abs(length - 0.7) < 0.2", function (l) return math.abs(l:length() - 0.7) < 0.2 end },
      { "not (level == 2)", function (l) return not (l:level() == 2) end },
    }
    for _, c in ipairs(conds) do
      local seen = { C = {}, L = {} }
      local K = grow.kind("k")
      K:rule("grow", function (l)
        if l:age() < 3 then l:spawn { angle = 20 * l:level(), length = 0.3 + 0.2 * l:age() } end
        l:scale_radius(1.0 + 0.1 * l:level())
      end)
      K:rule("c", { when = c[1], fn = function (l) seen.C[#seen.C + 1] = l:id() end })
      K:rule("lua", function (l) if c[2](l) then seen.L[#seen.L + 1] = l:id() end end)
      local w = grow.world()
      w:plant { kind = K, radius = 0.02 }
      w:tick(5)
      assert.is_true(#seen.L > 0 and #seen.L < 200, c[1] .. ": " .. #seen.L)
      assert.same(seen.L, seen.C, c[1])
    end
  end)

  it("applies colours and blends, and calls fn only where the condition holds", function ()
    local calls = 0
    local K = grow.kind("k")
    K:rule("old", { when = "age >= 2", blend = { "#000000", 0.5 } })
    K:rule("young", { when = "age < 1 and root == 1", color = "#ff0000" })
    K:rule("count", { when = "age == 3", fn = function () calls = calls + 1 end })
    local w = grow.world()
    local a = w:plant { kind = K, color = "#808080" }
    w:tick()
    assert.same({ 1, 0, 0 }, a:color())
    w:tick(2)                                        -- ages 1, 2: one blend at age 2
    local c = a:color()
    assert.near(0.5, c[1], 1e-6)
    assert.equal(0, calls)
    w:tick()
    assert.equal(1, calls)
  end)

  it("names the rule, kind and limb of a failing fn, and refuses bad rules", function ()
    local K = grow.kind("shoot")
    K:rule("ok", { scale_length = 1.01 })
    K:rule("bad", { when = "level == 2", fn = function () error("snap") end })
    local w = grow.world()
    w:plant { kind = K }:spawn {}
    local msg = errof(w.tick, w)
    assert.truthy(msg:find("rule 'bad' of kind 'shoot' failed on limb 2 (tick 1)", 1, true), msg)
    assert.truthy(msg:find("snap", 1, true))
    assert.truthy(errof(K.rule, K, "r", { when = "length <" })
                  :find("the condition 'length <' must be", 1, true))
    assert.truthy(errof(K.rule, K, "r", { when = "foo > 1", scale_length = 2 })
                  :find("functions of length, radius, age", 1, true))
    assert.truthy(errof(K.rule, K, "r", { when = "age > 1" }):find("nothing to do", 1, true))
    assert.truthy(errof(K.rule, K, "r", { scale = 2 }):find("unknown field 'scale'", 1, true))
    assert.truthy(errof(K.rule, K, "r", { scale_length = -1 }):find("a factor >= 0", 1, true))
    assert.truthy(errof(K.rule, K, "r", { blend = { "#ffffff", 3 } })
                  :find("'blend' must be {colour, fraction 0..1}", 1, true))
    local core = require "lsys.core"
    local T = core.limbs()
    assert.truthy(errof(T.set_rules, T, 0, { { code = { 99, 0, 0 } } })
                  :find("malformed", 1, true))
    assert.truthy(errof(T.run, T, {}, {}, {}):find("no tick is running", 1, true))
  end)
end)

describe("lsys.grow bridges", function ()
  it("gives an Lstring whose turtle geometry is the grown plant's", function ()
    local lsys = require "lsys"
    local w = grow.world { seed = 2 }
    local K = davison(grow.kind("tree"))
    K:rule("side", function (l)                    -- and a child halfway along, rolled
      if l:age() == 3 and l:level() == 2 then l:spawn { at = 0.5, angle = 60, roll = 45 } end
    end)
    w:plant { kind = K, position = { 2, 0, -1 } }
    w:plant { kind = K, position = { -3, 0, 4 } }
    w:tick(30)
    local m = lsys.lsystem { axiom = "", steps = 0, view = { line_style = "cylinder" } }
    local s, owner = w:lstring(m)
    local scene = m:interpret(s)
    local n = 0
    for _, r in scene:records() do
      if r.kind == "segment" then
        local l = owner(r.module)
        local x, y, z = l:tip()
        assert.is_true(math.abs(r.p1[1] - x) < 1e-5 and math.abs(r.p1[2] - y) < 1e-5 and
                       math.abs(r.p1[3] - z) < 1e-5, tostring(l))
        assert.near(2 * l:radius(), r.w0, 1e-6)
        n = n + 1
      end
    end
    assert.equal(w:count(), n)
    assert.is_true(n > 50, n)
    assert.equal("[", (s:module(1)))
  end)
end)

describe("lsys.grow from an L-system", function ()
  it("takes a derived plant's segments as limbs, and grows it on", function ()
    local lsys = require "lsys"
    local m = lsys.lsystem {
      axiom = "#(0.2)A(1)",
      productions = "A(s) --> F(s)[+(25)/(70)#(0.1)A(s*0.7)][-(40)&(20)A(s*0.6)]f(0.1)F(s*0.5)",
      steps = 3, view = { line_style = "cylinder" },
    }
    local s = m:derive()
    local scene = m:interpret(s)
    local K = grow.kind("from")
    K:rule("longer", { scale_length = 1.5 })
    local w, limbs = grow.from_lstring(s, { model = m, kind = K })
    local segs = {}
    for _, r in scene:records() do if r.kind == "segment" then segs[#segs + 1] = r end end
    assert.equal(#segs, #limbs)
    assert.equal(#segs, w:count())
    local roots = 0
    for k, l in ipairs(limbs) do
      local x, y, z = l:tip()
      local p = segs[k].p1
      assert.is_true(math.abs(p[1] - x) < 1e-5 and math.abs(p[2] - y) < 1e-5 and
                     math.abs(p[3] - z) < 1e-5, tostring(l))
      assert.near(segs[k].w0 / 2, l:radius(), 1e-6)
      if l:is_root() then roots = roots + 1 end
    end
    assert.is_true(roots > 1)                          -- after each f, a plant of its own
    assert.is_true(limbs[2]:level() > 1)
    w:tick()                                           -- it grows on: every limb 1.5 long
    for k, l in ipairs(limbs) do assert.near(1.5 * segs[k].length, l:length(), 1e-5) end
  end)

  it("turns any orientation into an axis and an angle (half turns too)", function ()
    local lsys = require "lsys"
    local m = lsys.lsystem { axiom = "F(1)&(180)F(1)/(180)F(1)+(179.99)F(1)^(90)/(33)F(1)",
                             steps = 0 }
    local s = m:derive()
    local w, limbs = grow.from_lstring(s, { model = m })
    local k = 0
    for _, r in m:interpret(s):records() do
      if r.kind == "segment" then
        k = k + 1
        local x, y, z = limbs[k]:tip()
        assert.is_true(math.abs(r.p1[1] - x) < 1e-5 and math.abs(r.p1[2] - y) < 1e-5 and
                       math.abs(r.p1[3] - z) < 1e-5, k)
      end
    end
    assert.equal(5, k)
    assert.equal(5, w:count())
  end)
end)

describe("lsys.grow and max_memory", function ()
  local lsys = require "lsys"
  local saved
  before_each(function () saved = lsys.max_memory() end)
  after_each(function () lsys.max_memory(saved == math.huge and "unlimited" or saved) end)
  local MSG = "the world would need more than max_memory (64 MiB) with %d limbs (set "
              .. "LSYS_MAX_MEMORY, or lsys.max_memory)"

  it("counts the limbs' arrays and handles as they are made", function ()
    lsys.max_memory("64M")
    local w = grow.world { max_limbs = 1000000 }
    local root = w:plant()
    assert.equal("lsys.grow: " .. MSG:format(116173), errof(function ()
      for _ = 1, 400000 do root:spawn {} end
    end))
    assert.equal(116173, w:count())                -- the limbs made are kept
    assert.equal("lsys.grow: " .. MSG:format(116173), errof(w.scene, w))   -- their geometry
  end)

  it("names the rule and the tick whose limbs or geometry do not fit", function ()
    lsys.max_memory("64M")
    local K = grow.kind("k")
    K:rule("spawn", function (l) l:spawn { angle = 20 } l:spawn { angle = -20 } end)
    local w = grow.world { max_limbs = 1000000 }
    w:plant { kind = K }
    assert.equal("lsys.grow: tick 10: " .. MSG:format(59049), errof(w.tick, w, 30))
    assert.equal(10, w.ticks)
    w = grow.world { max_limbs = 1000000, sides = 3 }
    w:plant { kind = K }
    assert.equal("lsys.grow: rule 'spawn' of kind 'k' failed on limb 3245 (tick 11): "
                 .. MSG:format(65537), errof(w.tick, w, 30))
  end)

  it("estimates what its Lua side keeps per limb and per plant", function ()
    local w = grow.world { max_limbs = 1000000 }
    local root = w:plant()
    local function kib ()
      collectgarbage()
      collectgarbage()
      return collectgarbage("count")
    end
    local a = kib()
    for _ = 1, 20000 do root:spawn {} end
    local limb = (kib() - a) * 1024 / 20000
    a = kib()
    for _ = 1, 20000 do w:plant() end
    local plant = (kib() - a) * 1024 / 20000 - limb        -- a plant has its root limb
    assert.truthy(math.abs(limb - grow._LIMB_BYTES) < 0.15 * grow._LIMB_BYTES, limb)
    assert.truthy(math.abs(plant - grow._PLANT_BYTES) < 0.25 * grow._PLANT_BYTES, plant)
  end)
end)

describe("lsys.grow errors", function ()
  it("names the rule, the kind and the limb when a rule fails", function ()
    local K = grow.kind("shoot")
    K:rule("bad", function (l) if l:id() == 2 then error("boom") end end)
    local w = grow.world()
    w:plant { kind = K }:spawn {}
    local msg = errof(w.tick, w)
    assert.truthy(msg:find("rule 'bad' of kind 'shoot' failed on limb 2 (tick 1)", 1, true), msg)
    assert.truthy(msg:find("boom", 1, true))
    w:tick(0)                                        -- the world still works
  end)

  it("names the caller's line, not lsys.grow's, for a bad rule table or option", function ()
    -- the checks sit at different depths of lsys.grow (found by the grow fuzz target)
    local K = grow.kind("tree")
    local line = debug.getinfo(1, "l").currentline
    local ok1, e1 = pcall(function () K:rule("r1", { scale_length = -1 }) end)
    local ok2, e2 = pcall(function () grow.world { seed = "x" } end)
    local ok3, e3 = pcall(function () K:rule("r1", { color = "nope" }) end)
    assert.is_false(ok1 or ok2 or ok3)
    local here = "tests/grow_spec.lua:"
    assert.equal(here .. (line + 1) .. ": lsys.grow: rule 'r1' of kind 'tree': 'scale_length' " ..
                 "must be a factor >= 0", e1)
    assert.equal(here .. (line + 2) .. ": lsys.grow: world: 'seed' must be a finite number, " ..
                 "got x", e2)
    assert.equal(here .. (line + 3) .. ": lsys.grow: rule 'r1' of kind 'tree': 'color': " ..
                 "colour 'nope' is not #rrggbb", e3)
  end)

  it("says what is not finite: a scale run away, a string beyond the scene's floats", function ()
    local K = grow.kind("tree")
    K:rule("big", { scale_length = 1e300 })
    local w = grow.world()
    w:plant { kind = K }
    assert.truthy(errof(w.tick, w, 3):find("rule 'big' of kind 'tree' failed on limb 1 " ..
      "(tick 2): its scale makes the limb's length or radius too large to be finite", 1, true))
    assert.equal("lsys.grow: from_lstring: segment 1 (module 1) is beyond what the scene's " ..
                 "floats hold", errof(grow.from_lstring, "F(1e39)"):match("lsys%.grow: .*"))
  end)

  it("refuses bad spawns, factors, colours and options", function ()
    local w = grow.world()
    local a = w:plant()
    assert.truthy(errof(a.spawn, a, { angle = 0 / 0 })
                  :find("'angle' must be a finite number", 1, true))
    assert.truthy(errof(a.spawn, a, { axis = "w" }):find("axis 'w' is not", 1, true))
    assert.truthy(errof(a.spawn, a, { axis = { 0, 0, 0 } }):find("non-zero", 1, true))
    assert.truthy(errof(a.spawn, a, { lenght = 1 }):find("unknown option 'lenght'", 1, true))
    assert.truthy(errof(a.spawn, a, { at = 2 }):find("'at' must be from 0 to 1", 1, true))
    assert.truthy(errof(a.spawn, a, { kind = {} }):find("'kind' must be a kind", 1, true))
    assert.truthy(errof(a.scale_length, a, -1):find("a factor >= 0", 1, true))
    assert.truthy(errof(a.set_color, a, "#12"):find("not #rrggbb", 1, true))
    assert.truthy(errof(a.blend_color, a, "#123456", 2):find("fraction 0..1", 1, true))
    assert.truthy(errof(a.add_leaves, a, 1.5):find("a count 0..1000", 1, true))
    assert.truthy(errof(grow.world, { sides = 2 }):find("'sides' must be", 1, true))
    assert.truthy(errof(grow.world, { colour = 1 }):find("unknown option 'colour'", 1, true))
    assert.truthy(errof(grow.kind, ""):find("a name expected", 1, true))
    assert.truthy(errof(grow.kind("k").rule, grow.kind("k"), "r", 5)
                  :find("a function (limb, world) expected", 1, true))
    assert.truthy(errof(w.plant, w, { position = { 1, 2 } }):find("'position' must be", 1, true))
    assert.truthy(errof(w.tick, w, 1.5):find("a whole number of ticks", 1, true))
  end)

  it("keeps a limb's parent fixed (no cycle can be made) and its methods its kind's", function ()
    local K = grow.kind("k")
    function K.bloom () return "bloom" end
    local w = grow.world()
    local a = w:plant { kind = K }
    w:tick()
    local b = a:spawn { angle = 10 }
    w:tick()
    local function set (h, k, v) h[k] = v end
    assert.truthy(errof(set, a, "parent", b)
      :find("limb 1: 'parent' cannot be assigned: a limb's parent is fixed", 1, true))
    assert.truthy(errof(set, b, "children", { a }):find("'children' cannot be assigned", 1, true))
    assert.truthy(errof(set, a, "spawn", 1)
      :find("limb 1: 'spawn' is a method of kind 'k' and cannot be set", 1, true))
    assert.truthy(errof(set, a, "bloom", 1):find("'bloom' is a method of kind 'k'", 1, true))
    assert.truthy(errof(set, a, "_mine", 9):find("'_mine' is internal", 1, true))
    assert.equal(a, b:parent())                     -- unchanged
    assert.equal(b, a:children()[1])
    a.flowering = true                              -- its own data: fine
    assert.is_true(a.flowering)
    a.flowering = false
    assert.is_false(a.flowering)
    w:tick()
    assert.equal("bloom", a:bloom())
  end)

  it("checks the C table's arguments and that it and its scene are alive", function ()
    local core = require "lsys.core"
    local T = core.limbs { sides = 5 }
    local p = T:plant(0, 0, 0)
    local a = T:add(0, p, 1, 0, 0, 1, 0, 0, 1, 0.1, 0.2, 0.5, 0.1)
    assert.truthy(errof(T.length, T, 9):find("no such limb", 1, true))
    assert.truthy(errof(T.add, T, 0, 7, 1, 0, 0, 1, 0, 0, 1, 0.1, 0, 0, 0)
                  :find("no such plant", 1, true))
    assert.truthy(errof(T.set_length, T, a, -1):find("a length is >= 0", 1, true))
    assert.truthy(errof(T.set_turn, T, a, 0, 0, 0, 10, 0):find("the axis is zero", 1, true))
    assert.truthy(errof(T.finish, T):find("finish", 1, true))
    assert.truthy(errof(core.limbs, { sides = 99 }):find("sides must be 3 to 64", 1, true))
    assert.equal(require("lsys").grow, grow)
    do local _ <close> = T:scene() end             -- the user closed its scene
    assert.truthy(errof(T.length, T, a):find("closed", 1, true))
    local T2 = core.limbs()
    T2:close()
    assert.truthy(errof(T2.count, T2):find("the limbs were closed", 1, true))
  end)
end)
