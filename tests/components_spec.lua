-- Component graphs (Lintermann and Deussen 1999): prototypes, their parameters and
-- links, and the expansion of the p-graph into the i-tree (recursion, multipliers, ranges
-- and functions per instance, flag lists, leaf links, errors).
local C = require "lsys.components"

local function errmsg (fn, ...)
  local ok, msg = pcall(fn, ...)
  assert.is_false(ok)
  return tostring(msg)
end

-- The article's fig. 2: A the root, B a stem, C a multiplier of three, D a twig part with
-- recursion depth 3.
local function fig2 ()
  local D = C.horn { name = "D", length = 0.5, recursion = 3, rotate = { 20, 0, 0 },
                     scale = 0.8 }
  D:child(D)
  local Cm = C.hydra { name = "C", n = 3, angle = 45 }
  Cm:child(D)
  local B = C.horn { name = "B", length = 2 }
  B:child(Cm)
  local A = C.simple { name = "A", primitive = "none" }
  A:child(B)
  return A, D
end

describe("lsys.components prototypes", function ()
  it("make each kind with defaults and check parameters", function ()
    for _, k in ipairs(C.ORDER) do
      local p = C[k] {}
      assert.equal(k, p.kind)
      assert.is_true(C.isproto(p))
    end
    assert.equal(C, require("lsys").components)
    -- the p-graph as DOT (lsys.components.graph): the camera, then the prototypes
    local dot = C.graph(C.tree { name = "t" }:branch(C.leaf { name = "l" }))
    assert.truthy(dot:find('n2 [label="l\\nleaf"];', 1, true), dot)
    assert.truthy(dot:find("n1 -> n2 [penwidth=3];", 1, true), dot)     -- a branch link
    local t = C.tree { n = 12, angle = { 60, 30 } }
    assert.equal(12, t:param("n"))
    assert.same({ 60, 30 }, t:param("angle"))
    assert.equal(137.50776405003785, t:param("divergence"))
    assert.equal("lsys.components.tree(0 links)", tostring(t))
  end)

  it("reject unknown parameters, listing the known ones", function ()
    local msg = errmsg(C.wreath, { radius = 1, radious = 2 })
    assert.equal("lsys.components: wreath: unknown parameter 'radious' (known: close, color, " ..
                 "geometry, n, name, open, primitive, radius, recursion, rotate, scale, size, " ..
                 "texture, translate)", msg)
    assert.equal("lsys.components: leaf 'l': 'length' must be a number, a range {v0, v1} or " ..
                 "a function, got NaN", errmsg(C.leaf, { name = "l", length = 0 / 0 }))
    assert.equal("lsys.components: tree: 'n' must be a whole number, got 2.5",
                 errmsg(C.tree, { n = 2.5 }))
    assert.equal("lsys.components: simple: 'primitive' must be one of none, cube, sphere, " ..
                 "cylinder, cone, disc, area, tube, got ball",
                 errmsg(C.simple, { primitive = "ball" }))
    assert.equal("lsys.components: horn: 'recursion' must be a whole number from 1 to " ..
                 "1000, got 0", errmsg(C.horn, { recursion = 0 }))
    assert.equal("lsys.components: hydra: child link: a component prototype expected, got " ..
                 "a table", errmsg(function () C.hydra {}:child({}) end))
    assert.equal("lsys.components: hydra: a link's flags: unknown field 'without' (known: " ..
                 "only, except)",
                 errmsg(function () C.hydra {}:child(C.leaf {}, { without = {} }) end))
  end)
  it("check the parameters each kind reads itself, and unknown kinds", function ()
    assert.equal("lsys.components: unknown component kind or function 'bush' (kinds: " ..
                 "simple, revo, horn, leaf, tree, hydra, wreath, phiball, ffd, hyperpatch, " ..
                 "world)", errmsg(function () return C.bush {} end):gsub("^[^:]*:%d+: ", ""))
    assert.equal("lsys.components: hyperpatch: 'degree' must be a whole number from 1 to 4, " ..
                 "or three of them, got 5", errmsg(C.hyperpatch, { degree = 5 }))
    assert.equal("lsys.components: hyperpatch: 'degree' must be a whole number from 1 to 4, " ..
                 "or three of them, got {1, 0, 2}", errmsg(C.hyperpatch, { degree = { 1, 0, 2 } }))
    assert.equal("lsys.components: hyperpatch: 'moves[1]' must be {i, j, k, dx, dy, dz}: " ..
                 "three whole lattice indices and a move of finite numbers",
                 errmsg(C.hyperpatch, { moves = { { 0, 0, 0, 1, 0 / 0, 0 } } }))
    assert.equal("lsys.components: ffd: 'fx' must be a function (x, y, z) -> number, got " ..
                 "number", errmsg(C.ffd, { fx = 3 }))
    assert.equal("lsys.components: world: 'cylinder': unknown field 'radus' (known: axis, " ..
                 "pitch, point, radius, strength)",
                 errmsg(C.world, { cylinder = { radus = 1 } }))
    assert.equal("lsys.components: world: 'cylinder.radius' must be a finite number",
                 errmsg(C.world, { cylinder = { radius = "x" } }))
    assert.equal("lsys.components: world: 'wind.direction' must be a vector {x, y, z} of " ..
                 "finite numbers", errmsg(C.world, { wind = { direction = { 1, 0 } } }))
    assert.equal("lsys.components: world: 'gravity' must be a non-zero vector {x, y, z} or " ..
                 "a function (x, y, z) -> x, y, z", errmsg(C.world, { gravity = { 0, 0, 0 } }))
    assert.equal("lsys.components: simple: 'geometry' must be an L-system model or an " ..
                 "Lstring, got number", errmsg(C.simple, { geometry = 3 }))
    assert.is_true(C.isproto(C.hyperpatch { degree = { 1, 4, 2 },
                                            moves = { { 0, 1, 0, 0.5, 0, 0 } } }))
  end)
end)

describe("lsys.components.expand", function ()
  it("expands fig. 2 into nine instances of D with the right parents", function ()
    local A = fig2()
    local t = C.expand(A)
    assert.equal(1, t:count("A"))
    assert.equal(1, t:count("B"))
    assert.equal(1, t:count("C"))
    assert.equal(9, t:count("D"))
    assert.equal(12, t:count())
    local list = t:instances()
    assert.equal("A#1", list[1].path)
    assert.equal("A#1/B#1/C#1/D#1/D#2/D#3", list[6].path)
    -- each chain of D hangs from C, three deep, with the recursion depth 1, 2, 3
    local c = t:find("A#1/B#1/C#1")
    assert.equal(3, #c.children)
    for k, ci in ipairs(c.children) do
      local d1 = list[ci]
      assert.equal("D", d1.name)
      assert.equal(k, d1.i)
      assert.equal(3, d1.n)
      assert.equal(1, d1.depth)
      local d2 = list[d1.children[1]]
      local d3 = list[d2.children[1]]
      assert.same({ 2, 3, 0 }, { d2.depth, d3.depth, #d3.children })
      assert.equal(d1.index, d2.parent)
    end
  end)

  it("places children at the parent's tip and multiplied children around its axis", function ()
    local t = C.expand((fig2()))
    local c = t:find("A#1/B#1/C#1")
    -- B is 2 long, straight up: C sits at (0, 2, 0)
    assert.near({ 0, 2, 0 }, c.frame.p, 1e-12)
    -- the hydra's three children tilt 45 degrees from the axis (and D's own rotate of 20
    -- degrees more), 120 degrees apart around it
    local az = {}
    for k, ci in ipairs(c.children) do
      local d = t:instances()[ci]
      assert.near(65, math.deg(math.acos(d.frame.H[2])), 1e-9)
      az[k] = math.deg(math.atan(d.frame.H[3], d.frame.H[1]))
    end
    local function gap (a, b) local d = (b - a) % 360 return math.min(d, 360 - d) end
    assert.near(120, gap(az[1], az[2]), 1e-9)
    assert.near(120, gap(az[2], az[3]), 1e-9)
    -- D's scale 0.8 compounds down the chain: 0.8, 0.64, 0.512
    local d3 = t:find("A#1/B#1/C#1/D#1/D#2/D#3")
    assert.near(0.512, d3.frame.s, 1e-12)
  end)

  it("interpolates ranges over the iteration and applies the user's function", function ()
    local seen = {}
    local leaf = C.leaf { name = "L", length = { 1, 2, f = function (v, ctx)
      seen[#seen + 1] = { v, ctx.i, ctx.n, ctx.depth }
      return v * 10
    end } }
    local w = C.wreath { n = 5 }
    w:child(leaf)
    local t = C.expand(w)
    assert.equal(5, t:count("L"))
    assert.same({ { 1, 1, 5, 1 }, { 1.25, 2, 5, 1 }, { 1.5, 3, 5, 1 }, { 1.75, 4, 5, 1 },
                  { 2, 5, 5, 1 } }, seen)
    -- the length sets the tip: the leaf's children would sit 10, 12.5, ... along it
    local l3 = t:instances()[4]
    assert.equal(3, l3.i)
    assert.near(15, math.sqrt(
      (l3.tip.p[1] - l3.frame.p[1]) ^ 2 + (l3.tip.p[2] - l3.frame.p[2]) ^ 2 +
      (l3.tip.p[3] - l3.frame.p[3]) ^ 2), 1e-9)
  end)

  it("counts instances by the label their paths show, or by kind", function ()
    -- named leaves and petals (both of kind leaf) and an unnamed leaf, labelled "leaf"
    local tw = C.tree { name = "twig", n = 4 }
    tw:branch(C.leaf { name = "leaf" })
    local fl = C.hydra { name = "flower", n = 5 }
    fl:child(C.leaf { name = "petal" })
    tw:child(fl)
    fl:child(C.leaf {})
    local t = C.expand(tw)
    assert.same({ 5, 1, 1, 0 }, { t:count("petal"), t:count("flower"), t:count("twig"),
                                  t:count("tree") })      -- the Tree is named twig
    assert.equal(9, t:count("leaf"))                      -- 4 named "leaf", 5 unnamed
    assert.equal(14, t:count { kind = "leaf" })           -- and the 5 petals
    assert.equal(1, t:count { kind = "tree" })
    assert.equal(16, t:count())
    local paths = 0
    for _, inst in ipairs(t:instances()) do
      if inst.path:match("/leaf#%d+$") then paths = paths + 1 end
    end
    assert.equal(t:count("leaf"), paths)
    assert.equal("lsys.components: count: unknown field 'name' (known: kind)",
                 errmsg(t.count, t, { name = "leaf" }))
    assert.equal("lsys.components: count: expected a name or { kind = KIND }, got number",
                 errmsg(t.count, t, 3))
  end)

  it("creates the iterations a flag list allows", function ()
    local tw = C.tree { name = "twig", n = 15 }
    local small = C.horn { name = "small" }
    local lf = C.leaf { name = "leaf" }
    tw:branch(small, { only = { 2, 13 } })
    tw:branch(lf, { except = { 2, 13 } })
    local t = C.expand(tw)
    assert.equal(2, t:count("small"))
    assert.equal(13, t:count("leaf"))
    local is = {}
    for _, inst in ipairs(t:instances()) do
      if inst.name == "small" then is[#is + 1] = inst.i end
    end
    assert.same({ 2, 13 }, is)
    local bad = C.tree { n = 5 }
    bad:branch(C.leaf {}, { only = { 7 } })
    assert.equal("lsys.components: tree (at tree#1): the flags of its branch link to leaf " ..
                 "name iteration 7, but it makes 5", errmsg(C.expand, bad))
    -- an iteration number past what %d formats (found by the components fuzz target)
    local h = C.hydra {}
    h:child(C.leaf {}, { only = { 1e308 } })
    assert.equal("lsys.components: hydra (at hydra#1): the flags of its child link to leaf " ..
                 "name iteration 1e+308, but it makes 5", errmsg(C.expand, h))
  end)

  it("makes a leaf link's target once, where the recursion ends", function ()
    local D = C.horn { name = "D", recursion = 4 }
    D:child(D)
    D:leaf(C.leaf { name = "end" })
    local t = C.expand(D)
    assert.equal(4, t:count("D"))
    assert.equal(1, t:count("end"))
    assert.equal("D#1/D#2/D#3/D#4/end#1", t:instances()[5].path)
    -- without recursion a leaf link is a child link
    local h = C.horn {}
    h:leaf(C.leaf { name = "x" })
    assert.equal(1, C.expand(h):count("x"))
  end)

  it("stops a cycle without a recursion depth, and a graph that grows too big", function ()
    local a, b = C.horn { name = "a" }, C.horn { name = "b" }
    a:child(b)
    b:child(a)
    assert.equal("lsys.components: horn 'a': a cycle (a -> b -> a) but horn 'a' has no " ..
                 "recursion depth (give it recursion = n)", errmsg(C.expand, a))
    local w = C.wreath { n = 100 }
    local v = C.wreath { n = 100 }
    w:child(v)
    v:child(C.leaf {})
    assert.equal("lsys.components: the graph makes more than 5000 instances (at " ..
                 "wreath#1/wreath#51/leaf); raise max_instances or lower a count",
                 errmsg(C.expand, w, { max_instances = 5000 }))
    assert.equal(10101, C.expand(w):count())
  end)

  it("names the instance and parameter when a function gives no number", function ()
    local w = C.wreath { n = 3 }
    w:child(C.leaf { name = "bad", width = function (ctx) return ctx.i == 2 and "x" or 1 end,
                     length = function () return 1 end })
    local t = C.expand(w)       -- width is read by the geometry, not here
    assert.equal(3, t:count("bad"))
    local w2 = C.wreath { n = 3 }
    w2:child(C.leaf { name = "bad", length = function (ctx) return ctx.i == 2 and "x" or 1 end })
    assert.equal("lsys.components: leaf 'bad' (at wreath#1/bad#2): 'length': gave x, not a " ..
                 "finite number", errmsg(C.expand, w2))
  end)

  it("refuses leaf curvatures and widths past lsys.sketch.organ.leaf's range", function ()
    -- what the leaf's surface is made with: organ.leaf takes curvatures from -10 to 10 and
    -- widths up to 10 lengths
    assert.equal("lsys.components: leaf: 'lateral' must be a number from -10 to 10, got 20",
                 errmsg(C.leaf, { lateral = 20 }))
    assert.equal("lsys.components: leaf 'l': 'longitudinal' must be a number from -10 to " ..
                 "10, got {0, -30}", errmsg(C.leaf, { name = "l", longitudinal = { 0, -30 } }))
    assert.equal("lsys.components: leaf: 'width' must be at most 10 times 'length', got 20 " ..
                 "and 1", errmsg(C.leaf, { width = 20 }))
    assert.equal("lsys.components: leaf: 'width' must be at most 10 times 'length', got " ..
                 "{1, 3} and {1, 0.25}", errmsg(C.leaf, { width = { 1, 3 }, length = { 1, 0.25 } }))
    assert.equal("lsys.components: leaf: 'width' must be at most 10 times 'length', got 0.5 " ..
                 "and 0", errmsg(C.leaf, { length = 0 }))
    -- the ends of the ranges are the extremes; an outline has no width of its own
    assert.is_true(C.isproto(C.leaf { lateral = { -10, 10 }, width = { 10, 1 } }))
    assert.is_true(C.isproto(C.leaf { width = 20, outline = { { 0, 0 }, { 0.5, 1 } } }))
    -- a function's value is checked for each instance, when the leaf is drawn
    local w = C.wreath { n = 3 }
    w:child(C.leaf { name = "l", lateral = function (ctx) return 5 * ctx.i end })
    assert.equal("lsys.components: leaf 'l' (at wreath#1/l#3): 'lateral': gave 15, not a " ..
                 "number from -10 to 10", errmsg(C.model, w))
    w = C.wreath { n = 3 }
    w:child(C.leaf { name = "l", longitudinal = { 0, 1, f = function (v) return v * 11 end } })
    assert.equal("lsys.components: leaf 'l' (at wreath#1/l#3): 'longitudinal': gave 11, not " ..
                 "a number from -10 to 10", errmsg(C.model, w))
    w = C.wreath { n = 3 }
    w:child(C.leaf { name = "l", length = 0.5, width = function (ctx) return 2.5 * ctx.i end })
    assert.equal("lsys.components: leaf 'l' (at wreath#1/l#3): 'width': gave 7.5, more " ..
                 "than 10 times the length (0.5)", errmsg(C.model, w))
  end)

  it("refuses primitive sizes below 0 when the prototype is made or a function gives one",
     function ()
    assert.equal("lsys.components: simple: 'size' must be three numbers >= 0, got {1, -1, 1}",
                 errmsg(C.simple, { size = { 1, -1, 1 } }))
    assert.equal("lsys.components: horn: 'size' must be three numbers >= 0, got {{1, 1, 1}, " ..
                 "{-0.5, 1, 1}}", errmsg(C.horn, { size = { { 1, 1, 1 }, { -0.5, 1, 1 } } }))
    assert.is_true(C.isproto(C.simple { size = { 0, 0, 0 } }))
    local w = C.wreath { n = 3 }
    w:child(C.simple { name = "s", size = function (ctx) return { 1, 2 - ctx.i, 1 } end })
    assert.equal("lsys.components: simple 's' (at wreath#1/s#3): 'size': gave {1, -1, 1}, " ..
                 "not three numbers >= 0", errmsg(C.expand, w))
  end)

  it("refuses stems of negative length, which the turtle would draw forwards", function ()
    assert.equal("lsys.components: horn: 'length' must be a number >= 0, got -1",
                 errmsg(C.horn, { length = -1 }))
    assert.equal("lsys.components: tree 't': 'length' must be a number >= 0, got {1, -1}",
                 errmsg(C.tree, { name = "t", length = { 1, -1 } }))
    local w = C.wreath { n = 2 }
    w:child(C.horn { name = "h", length = function (ctx) return 1 - ctx.i end })
    assert.equal("lsys.components: horn 'h' (at wreath#1/h#2): 'length': gave -1, not a " ..
                 "number >= 0", errmsg(C.expand, w))
    assert.equal(4, C.expand(C.tree { length = 0, n = 3 }:branch(C.leaf {})):count())
  end)

  it("bounds the strengths of the tropisms, so that a stem's turn stays finite", function ()
    assert.equal("lsys.components: tree: 'gravitropism' must be a number from -100 to 100, " ..
                 "got 1e+308", errmsg(C.tree, { gravitropism = 1e308 }))
    assert.equal("lsys.components: tree: 'phototropism' must be a number from -100 to 100, " ..
                 "got {0, -101}", errmsg(C.tree, { phototropism = { 0, -101 } }))
    assert.equal("lsys.components: world: 'wind.strength' must be a number from -100 to 100, " ..
                 "got 1e+300", errmsg(C.world, { wind = { strength = 1e300 } }))
    assert.equal("lsys.components: world: 'cylinder.strength' must be a number from 0 to " ..
                 "100 (radians a segment at most), got -200",
                 errmsg(C.world, { cylinder = { strength = -200 } }))
    local w = C.world {}
    w:child(C.tree { name = "t", n = 2, curvature = 30,
                     gravitropism = function (ctx) return ctx.depth * 1e308 end })
    assert.equal("lsys.components: tree 't' (at world#1/t#1): 'gravitropism': gave 1e+308, " ..
                 "not a number from -100 to 100", errmsg(C.expand, w))
    assert.is_true(C.isproto(C.tree { gravitropism = -100, phototropism = { 100, 0 } }))
    -- a leaf's phototropism too (it turned the leaf's frame to NaN)
    assert.equal("lsys.components: leaf: 'phototropism' must be a number from 0 to 1 (the " ..
                 "fraction of the turn to the light), got 1e+308",
                 errmsg(C.leaf, { phototropism = 1e308 }))
  end)

  it("keeps frames orthonormal down a long chain of rotated instances", function ()
    -- rotations about a right axis made from frames a little off unit length amplified the
    -- error: |H| was 0.85 after 80 levels of this chain, and the turtle left the frames
    local root = C.simple { primitive = "disc" }
    local hy = C.hydra { n = 3, radius = 0.5 }
    local D = C.horn { name = "D", length = 0.4, recursion = 129, rotate = { 25, 40, 0 } }
    root:child(hy) hy:child(D) D:child(D)
    local t = C.expand(root, { max_instances = 3000 })
    local worst = 0
    for _, inst in ipairs(t:instances()) do
      local f = inst.frame
      local hh = f.H[1] ^ 2 + f.H[2] ^ 2 + f.H[3] ^ 2
      local uu = f.U[1] ^ 2 + f.U[2] ^ 2 + f.U[3] ^ 2
      local hu = f.H[1] * f.U[1] + f.H[2] * f.U[2] + f.H[3] * f.U[3]
      worst = math.max(worst, math.abs(hh - 1), math.abs(uu - 1), math.abs(hu))
    end
    assert.equal(2 + 3 * 129, #t:instances())
    assert.is_true(worst < 1e-12, "frames off by " .. worst)
  end)

  it("limits every n to the placements' 10^6 when the prototype is made", function ()
    assert.equal(1000000, require("lsys.components.place").MAX_N)
    assert.equal("lsys.components: phiball: 'n' must be from 0 to 1000000, got 6000000",
                 errmsg(C.phiball, { n = 6000000 }))
    assert.equal("lsys.components: tree 't': 'n' must be from 0 to 1000000, got 1000001",
                 errmsg(C.tree, { name = "t", n = 1000001 }))
    assert.equal(1000000, C.hydra { n = 1000000 }:param("n"))
  end)

  it("stops at max_instances before working out a multiplier's or a tree's children",
     function ()
    local calls = 0
    local ball = C.phiball { n = 1000000, child_size = function () calls = calls + 1 return 1 end }
    ball:child(C.simple {})
    assert.equal("lsys.components: the graph makes more than 10 instances (at phiball#1/" ..
                 "simple); raise max_instances or lower a count",
                 errmsg(C.expand, ball, { max_instances = 10 }))
    assert.equal(0, calls)                 -- no child_size, no placement was computed
    -- the flags' count: 1 + 10^6 - 3 instances exactly fit, one fewer does not
    local t = C.tree { n = 1000000, angle = function () calls = calls + 1 return 30 end }
    t:branch(C.leaf {}, { except = { 1, 2, 3, 3 } })
    assert.equal("lsys.components: the graph makes more than 999997 instances (at tree#1/" ..
                 "leaf); raise max_instances or lower a count",
                 errmsg(C.expand, t, { max_instances = 999997 }))
    assert.equal(0, calls)
    local h = C.hydra { n = 4 }
    h:child(C.leaf {}, { only = { 2, 3 } })
    assert.equal(3, C.expand(h, { max_instances = 3 }):count())
    assert.equal("lsys.components: the graph makes more than 2 instances (at hydra#1/leaf); " ..
                 "raise max_instances or lower a count", errmsg(C.expand, h, { max_instances = 2 }))
  end)

  it("is reproducible: the same graph and seed give the same frames", function ()
    local function build ()
      local tw = C.tree { n = 8, gnarl = 15, length = 2 }
      tw:branch(C.leaf {})
      return tw
    end
    local a, b = C.expand(build(), { seed = 7 }), C.expand(build(), { seed = 7 })
    local c = C.expand(build(), { seed = 8 })
    local function tipx (t) return t:instances()[1].tip.p[1] end
    assert.equal(tipx(a), tipx(b))
    assert.are_not.equal(tipx(a), tipx(c))
    -- the generator is splitmix64: its first draws for seed 1 are fixed
    local g = require("lsys.components.expand").generator(1)
    local x = g()
    assert.is_true(x >= 0 and x < 1)
    assert.equal(x, require("lsys.components.expand").generator(1)())
  end)

  it("bends a stem by its curvature and turns it towards gravity", function ()
    local h = C.horn { length = 1, segments = 10, curvature = 90 }
    local t = C.expand(h)
    local H = t:instances()[1].tip.H
    -- a quarter turn about the right axis: heading from +y to -z ... or +z
    assert.near(0, H[2], 1e-12)
    assert.near(1, math.abs(H[3]), 1e-12)
    local w = C.world { gravity = { 0, -1, 0 } }
    local tr = C.tree { n = 0, length = 1, segments = 20, gravitropism = 0.3,
                        rotate = { 60, 0, 0 } }
    w:child(tr)
    local st = C.expand(w):instances()[2]
    assert.is_true(st.tip.H[2] < st.frame.H[2] - 0.1)   -- it droops
  end)
end)
