-- The component-graph pane (lsys.ui.graph): the p-graph laid out with and without
-- Graphviz, boxes that do not overlap, clicks and picks selecting prototypes, the form's
-- items for every component kind, edits that change the plant (numbers, ranges edited as
-- curves, links), the graph written as a Lua model file and loaded back, and bad input.
local H = require "tests.helper"
local core = require "lsys.core"
local lsys = require "lsys"
local C = lsys.components
local P = require "lsys.ui.graph"
local load = require "lsys.load"

local HAVE_DOT = H.sh("command -v dot >/dev/null && echo yes"):match("yes") ~= nil

-- A small plant: a stem with 6 whorls of 3 leaves.
local function small ()
  local leaf = C.leaf { name = "leaf", length = 0.3, width = 0.15 }
  local whorl = C.hydra { name = "whorl", n = 3, angle = 60 }
  whorl:child(leaf)
  local stem = C.tree { name = "stem", length = 2, n = 6, angle = { 60, 30 }, segments = 4 }
  stem:branch(whorl)
  return stem, whorl, leaf
end

-- Two boxes overlap?
local function overlap (a, b)
  return a.x < b.x + b.w and b.x < a.x + a.w and a.y < b.y + b.h and b.y < a.y + a.h
end

local function byid (lay)
  local t = {}
  for _, d in ipairs(lay.nodes) do if not d.copy then t[d.title or d.id] = d end end
  return t
end

-- A graph with a fork, a recursion and a shared leaf: for the layouts.
local function forked ()
  local leaf = C.leaf { name = "lf" }
  local a = C.horn { name = "a" }
  local b = C.horn { name = "b" }
  local r = C.simple { name = "rec", recursion = 3 }
  local root = C.tree { name = "root", n = 4 }
  root:branch(a)
  root:child(b)
  root:child(r)
  a:child(leaf)
  b:leaf(leaf)
  r:child(r)
  return root
end

local function check_layout (lay)
  for i, d in ipairs(lay.nodes) do
    for j = i + 1, #lay.nodes do
      assert.is_false(overlap(d, lay.nodes[j]), d.id .. " overlaps " .. lay.nodes[j].id)
    end
    assert.is_true(d.x >= 0 and d.y >= 0)
    assert.is_true(d.x + d.w <= lay.width and d.y + d.h <= lay.height)
  end
  for _, e in ipairs(lay.edges) do
    if e.tree then
      assert.is_true(e.to.y >= e.from.y + e.from.h + 10, e.from.id .. " -> " .. e.to.id)
    end
  end
end

describe("lsys.ui.graph layout", function ()
  it("lays out a chain in layers without dot: one column, top-down", function ()
    local stem = small()
    local lay = P.layout(stem, { dot = false })
    assert.equal("layers", lay.how)
    assert.equal(4, #lay.nodes)                         -- camera, stem, whorl, leaf
    local n = byid(lay)
    local cx = n.camera.x + n.camera.w / 2
    for _, k in ipairs { "stem", "whorl", "leaf" } do
      assert.is_true(math.abs(n[k].x + n[k].w / 2 - cx) <= 1, k)
    end
    assert.equal(12, n.camera.y)                        -- the margin
    -- layers one box height and VGAP apart: every box here has two lines but the camera
    assert.equal(n.camera.y + n.camera.h + P.VGAP, n.stem.y)
    assert.equal(n.stem.y + n.stem.h + P.VGAP, n.whorl.y)
    assert.equal(n.whorl.y + n.whorl.h + P.VGAP, n.leaf.y)
    -- the box fits its text: "whorl" and "hydra", 5 characters of 12 px less 2, and padding
    assert.equal(5 * 12 - 2 + 16, n.whorl.w)
    check_layout(lay)
    local kinds = {}
    for _, e in ipairs(lay.edges) do kinds[#kinds + 1] = e.label or e.type end
    assert.same({ "root", "branch", "child" }, kinds)
  end)

  it("puts siblings side by side in link order, a recursion's return as a copy", function ()
    local lay = P.layout(forked(), { dot = false })
    local n = byid(lay)
    -- one layer: the boxes centred on one line (rec is a line taller: its recursion)
    assert.equal(n.a.y, n.b.y)
    assert.is_true(math.abs(n.b.y + n.b.h / 2 - (n.rec.y + n.rec.h / 2)) <= 1)
    assert.equal(n.b.h + 18, n.rec.h)
    assert.is_true(n.a.x + n.a.w + P.HGAP <= n.b.x)
    assert.is_true(n.b.x + n.b.w + P.HGAP <= n.rec.x)
    -- the root is centred over its children's band
    local mid = (n.a.x + n.rec.x + n.rec.w) / 2
    assert.is_true(math.abs(n.root.x + n.root.w / 2 - mid) <= 1)
    local copies, doubled = 0, 0
    for _, d in ipairs(lay.nodes) do if d.copy then copies = copies + 1 end end
    for _, e in ipairs(lay.edges) do if e.double then doubled = doubled + 1 end end
    assert.equal(1, copies)                             -- rec -> a copy of rec
    assert.equal(1, doubled)
    assert.equal(7, #lay.nodes)                         -- camera, 5 prototypes, the copy
    check_layout(lay)
  end)

  it("uses dot -Tplain when dot is installed, else the layers", function ()
    local lay = P.layout(forked())
    if HAVE_DOT then
      assert.equal("dot", lay.how)
      local n = byid(lay)
      assert.is_true(n.a.y > n.root.y and n.lf.y > n.a.y)
      assert.is_true(n.a.x < n.b.x and n.b.x < n.rec.x)   -- ordering=out keeps link order
    else
      assert.equal("layers", lay.how)
    end
    check_layout(lay)
  end)

  it("falls back to the layers when the dot program cannot run", function ()
    local lay = P.layout(forked(), { dot = "/nonexistent/lsys-no-dot" })
    assert.equal("layers", lay.how)
    assert.is_string(lay.why)
    check_layout(lay)
  end)
end)

describe("lsys.ui.graph pane", function ()
  it("selects the component whose box is clicked, pans on the background", function ()
    local stem, whorl = small()
    local pane = P.new(stem, { dot = false })
    assert.equal("graph", pane.name)
    assert.is_true(#pane.help >= 5)
    local c = core.canvas(420, 700)
    pane:draw(c)
    local x, y, w, h = pane:box("whorl")
    assert.equal(pane:node_at(x + 1, y + 1).proto, whorl)
    assert.is_nil(pane:node_at(x - 1, y))
    assert.is_true(pane:pointer("down", x + w / 2, y + h / 2, "left"))
    pane:pointer("up", x + w / 2, y + h / 2, "left")
    assert.equal(whorl, pane:selected())
    assert.matches("hydra 'whorl'", pane:status())
    -- the selection is drawn: the fill colour inside the box
    pane:draw(c)
    local px = c:pixels()
    local at = ((y + 4) * 420 + (x + w - 4)) * 4
    assert.same({ 255, 230, 140 }, { px:byte(at + 1), px:byte(at + 2), px:byte(at + 3) })
    -- a drag on the background moves the graph, the selection stays
    assert.is_false(pane:pointer("down", 5, 600, "left"))
    assert.is_true(pane:pointer("move", 25, 590, "left"))
    pane:pointer("up", 25, 590, "left")
    local x2, y2 = pane:box("whorl")
    assert.same({ x + 20, y - 10 }, { x2, y2 })
    assert.equal(whorl, pane:selected())
    assert.is_true(pane:key("home"))
    assert.same({ x, y, w, h }, { pane:box("whorl") })
    -- the camera selects nothing
    local cx, cy = pane:box("camera")
    pane:pointer("down", cx + 2, cy + 2, "left")
    assert.is_nil(pane:selected())
    assert.is_false(pane:key("s", true))            -- Ctrl+S is the host's
  end)

  it("navigates with the arrow keys", function ()
    local stem, whorl, leaf = small()
    local pane = P.new(stem, { dot = false })
    pane:key("down")
    assert.equal(stem, pane:selected())
    pane:key("down")
    assert.equal(whorl, pane:selected())
    pane:key("right")
    assert.equal(leaf, pane:selected())
    pane:key("up")
    assert.equal(whorl, pane:selected())
  end)

  it("selects the prototype of the instance a click on the plant hit", function ()
    local stem, _, leaf = small()
    local m = C.model(stem, { seed = 1 })
    local pane = P.new(m, { dot = false })
    local s = m.components.lstring
    local found = {}
    for i = 1, #s do
      local inst = m.components.instance(i)
      if inst and not found[inst.proto] then found[inst.proto] = i end
    end
    for _, p in ipairs { leaf, stem, leaf } do
      local inst = m.components.instance(found[p])
      local changed = pane:pick({ module = found[p], lstring = s, instance = inst,
                                  path = inst.path })
      assert.is_true(changed)
      assert.equal(p, pane:selected())
    end
    assert.is_false(pane:pick({ module = 1 }))          -- no instance: an L-system module
    assert.is_false(pane:pick({ instance = { proto = C.leaf {} } }))   -- not this graph
    assert.equal(leaf, pane:selected())
  end)
end)

-- The items by name.
local function items (pane)
  local t = {}
  for _, it in ipairs(pane:items()) do t[it.name] = it end
  return t
end

describe("lsys.ui.graph items", function ()
  local function graph_of_kinds ()
    local w = C.world { name = "world" }
    local t = C.tree { name = "tree", n = 5, length = 3, angle = { 60, 30 } }
    local h = C.horn { name = "horn", length = 0.5 }
    local hy = C.hydra { name = "hydra", n = 4 }
    local lf = C.leaf { name = "leaf", length = 0.4, width = 0.2, shape = "cordate" }
    local wr = C.wreath { name = "wreath", n = 6 }
    local si = C.simple { name = "simple", size = { 0.2, 0.2, 0.2 } }
    local ph = C.phiball { name = "phiball", n = 8, radius = 0.5 }
    local rv = C.revo { name = "revo" }
    local ffd = C.ffd { name = "ffd", fx = function (x) return x end, isolate = true }
    local hp = C.hyperpatch { name = "hyperpatch" }
    w:child(hp) hp:child(t) t:branch(h) h:child(hy) hy:child(lf) t:child(wr) wr:child(si)
    t:child(ffd) ffd:child(ph) ph:child(rv)
    return w, { world = w, tree = t, horn = h, hydra = hy, leaf = lf, wreath = wr,
                simple = si, phiball = ph, revo = rv, ffd = ffd, hyperpatch = hp }
  end

  it("gives each kind's numbers, flags and choices with ranges by meaning", function ()
    local root, ps = graph_of_kinds()
    local pane = P.new(root, { dot = false })
    assert.same({}, pane:items())                        -- nothing selected
    local expect = {
      tree = { "length", "radius", "n", "first", "angle", "divergence", "gravitropism" },
      horn = { "length", "radius", "tip", "segments", "curvature", "twist" },
      hydra = { "n", "radius", "open", "close", "angle" },
      leaf = { "length", "width", "shape", "lateral", "longitudinal", "phototropism" },
      wreath = { "n", "radius", "open", "close" },
      phiball = { "n", "radius", "open", "close", "child_size", "influence" },
      ffd = { "mode", "isolate" }, hyperpatch = { "mode", "isolate" },
      simple = { "primitive", "size.x" }, revo = { "primitive" }, world = { "scale" },
    }
    for kind, names in pairs(expect) do
      pane:select(ps[kind])
      local it = items(pane)
      for _, k in ipairs(names) do assert.is_table(it[k], kind .. "." .. k) end
      for _, k in ipairs { "scale", "translate.x", "rotate.z", "size.y", "texture" } do
        assert.is_table(it[k], kind .. " " .. k)
      end
    end
    pane:select(ps.tree)
    local it = items(pane)
    assert.equal("curve", it.angle.kind)                 -- the range {60, 30}
    assert.is_true(lsys.func.isfunc(it.angle.func))
    assert.near(60, it.angle.func(0), 1e-9)
    assert.near(45, it.angle.func(0.5), 1e-9)
    assert.near(30, it.angle.func(1), 1e-9)
    assert.same({ "number", 5, 1, 200, 1 }, { it.n.kind, it.n.value, it.n.min, it.n.max,
                                              it.n.step })
    assert.same({ 0, 9 }, { it.length.min, it.length.max })    -- 0 .. 3 x the length
    assert.same({ 0, 360 }, { it.divergence.min, it.divergence.max })
    assert.same({ 0, 1 }, { it.first.min, it.first.max })
    assert.equal(10, it.n.default + 0)
    pane:select(ps.horn)
    it = items(pane)
    assert.same({ "choice", "tube" }, { it.primitive.kind, it.primitive.value })
    pane:select(ps.leaf)
    it = items(pane)
    assert.same({ "choice", "cordate" }, { it.shape.kind, it.shape.value })
    assert.same({ "ovate", "lanceolate", "elliptic", "obovate", "linear", "cordate" },
                it.shape.choices)
    assert.same({ 0, 1 }, { it.phototropism.min, it.phototropism.max })
    pane:select(ps.hydra)
    it = items(pane)
    assert.same({ 0, 180, 90 }, { it.angle.min, it.angle.max, it.angle.value })
    pane:select(ps.ffd)
    it = items(pane)
    assert.same({ "boolean", true }, { it.isolate.kind, it.isolate.value })
    assert.is_nil(it.fx)                                 -- a function of space: no item
  end)

  it("offers the textures the view has", function ()
    local chestnut = dofile("examples/components/chestnut.lua")
    local pane = P.new(chestnut, { dot = false })
    pane:select(chestnut.components.tree.root)
    local it = items(pane)
    assert.same({ 2, 0, 2, 1 }, { it.texture.value, it.texture.min, it.texture.max,
                                  it.texture.step })
    assert.same({ 1, 1, 16 }, { it.color.value, it.color.min, it.color.max })
  end)

  it("applies a set to the prototype, calls on_change and changes the scene", function ()
    local stem, whorl, leaf = small()
    local what = {}
    local pane = P.new(stem, { dot = false, on_change = function (w) what[#what + 1] = w end })
    local s0 = pane:rebuild()
    pane:select(stem)
    items(pane).n.set(3)
    assert.same({ "component" }, what)
    assert.equal(3, stem.params.n)
    local s1 = pane:rebuild()
    -- half the whorls: the stem is the same, the leaves halve
    pane:select(leaf)
    local leaf_tris = (s0.ntriangles - s1.ntriangles) / 9
    assert.equal(s0.ntriangles - 9 * leaf_tris, s1.ntriangles)
    assert.is_true(leaf_tris > 0)
    -- a leaf's width, through its own check: too wide is an error and changes nothing
    local err = H.errof(items(pane).width.set, 5)
    assert.matches("leaf 'leaf': 'width' must be at most 10 times 'length'", err)
    assert.equal(0.15, leaf.params.width)
    -- a choice
    items(pane).shape.set("linear")
    assert.equal("linear", leaf.params.shape)
    -- a vector component: the whorl turned
    pane:select(whorl)
    local lo1, hi1 = pane:rebuild():bounds()
    items(pane)["rotate.y"].set(90)
    assert.same({ 0, 90, 0 }, whorl.params.rotate)
    local lo2, hi2 = pane:rebuild():bounds()
    assert.is_true(math.abs(lo1[1] - lo2[1]) > 1e-6 or math.abs(hi1[3] - hi2[3]) > 1e-6)
    assert.same({ "component", "component", "component" }, what)
  end)

  it("draws the last i-tree again when only drawn parameters changed", function ()
    local stem, whorl, leaf = small()
    local pane = P.new(stem, { dot = false })
    assert.is_false(P.reuses(stem))
    pane:rebuild()
    assert.is_true(P.reuses(stem))
    local function fresh () return C.scene(stem, { seed = 1 }) end
    local function check (s)
      local f = fresh()
      assert.equal(f.ntriangles, s.ntriangles)
      local lo1, hi1 = s:bounds()
      local lo2, hi2 = f:bounds()
      assert.same({ lo2, hi2 }, { lo1, hi1 })
    end
    pane:select(leaf)
    items(pane).width.set(0.05)                 -- the leaf's shape only: the same i-tree
    assert.is_true(P.reuses(stem))
    local s1, m1 = pane:rebuild()
    check(s1)
    items(pane).length.set(0.6)                 -- moves what is on the leaf: expanded again
    assert.is_false(P.reuses(stem))
    local s2, m2 = pane:rebuild()
    check(s2)
    assert.is_true(m1.components.tree ~= m2.components.tree)
    pane:select(stem)
    items(pane).radius.set(0.2)
    assert.is_true(P.reuses(stem))
    local s3, m3 = pane:rebuild()
    assert.equal(m2.components.tree, m3.components.tree)
    check(s3)
    whorl:child(C.leaf {})                       -- a link: expanded again
    assert.is_false(P.reuses(stem))
    check(pane:rebuild())
    assert.is_false(P.reuses(stem, { seed = 2 }))
    -- a drawn parameter that is a Lua function may draw random numbers: never reused
    leaf:set("lateral", function (ctx) return ctx.random() end)
    pane:rebuild()
    assert.is_false(P.reuses(stem))
    assert.matches("lsys.ui.graph.rebuild: a component prototype expected",
                   H.errof(P.rebuild, 1))
  end)

  it("turns a curve edit into the range the component reads", function ()
    local stem = small()
    local pane = P.new(stem, { dot = false })
    pane:select(stem)
    local s0 = pane:rebuild()
    local lo0, hi0 = s0:bounds()
    local it = items(pane).angle
    assert.equal("curve", it.kind)
    -- the same line as the range: the same plant
    it.set(it.func)
    local lo, hi = pane:rebuild():bounds()
    for k = 1, 3 do
      assert.near(lo0[k], lo[k], 1e-9)
      assert.near(hi0[k], hi[k], 1e-9)
    end
    -- a line from 80 to 20 degrees: branch i of 6 leaves the stem at 80 - 60 (i - 1)/5
    -- degrees (the stem is straight: no gnarl, curvature or tropism)
    it.set(lsys.func.new { points = { { 0, 80 }, { 1 / 3, 60 }, { 2 / 3, 40 }, { 1, 20 } } })
    assert.is_true(lsys.func.isfunc(stem.params.angle))
    local s2 = pane:rebuild()
    assert.equal(s0.ntriangles, s2.ntriangles)
    local lo2, hi2 = s2:bounds()
    assert.is_true(math.abs(lo2[2] - lo0[2]) + math.abs(hi2[2] - hi0[2]) > 1e-3)
    local k = 0
    for _, x in ipairs(C.expand(stem):instances()) do
      if x.kind == "hydra" then
        k = k + 1
        assert.equal(k, x.i)
        assert.near(80 - 60 * (k - 1) / 5, math.deg(math.acos(x.frame.H[2])), 1e-6)
      end
    end
    assert.equal(6, k)
    assert.matches("an lsys.Func expected", H.errof(it.set, 5))
  end)

  it("gives a function parameter as a curve through its samples", function ()
    local lf = C.leaf { name = "lf", length = function (ctx) return 0.1 * ctx.i end }
    local pane = P.new(lf, { dot = false })
    pane:select(lf)
    local it = items(pane).length
    assert.equal("curve", it.kind)
    local pts = it.func:points()
    assert.equal(P.SAMPLES, #pts)
    assert.near(0.1, pts[1][2], 1e-12)
    assert.near(0.7, pts[7][2], 1e-12)
    assert.near(1, pts[7][1], 1e-12)
  end)

  it("edits the links: add, change the type, remove", function ()
    local stem, whorl, leaf = small()
    local what = {}
    local pane = P.new(stem, { dot = false, on_change = function (w) what[#what + 1] = w end })
    local n0 = pane:rebuild().ntriangles
    pane:select(leaf)
    assert.is_true(pane:key("a"))                          -- a Leaf on the leaf's tip
    local added = pane:selected()
    assert.equal("leaf", added.kind)
    assert.equal(added, leaf.links[1].to)
    assert.equal("child", leaf.links[1].type)
    assert.equal(5, #pane.lay.nodes)
    assert.is_true(pane:rebuild().ntriangles > n0)
    assert.is_true(pane:key("l"))
    assert.equal("branch", leaf.links[1].type)
    assert.is_true(pane:key("delete"))
    assert.equal(0, #leaf.links)
    assert.equal(leaf, pane:selected())
    assert.equal(n0, pane:rebuild().ntriangles)
    pane:select(whorl)
    pane:key("delete")
    assert.equal(0, #stem.links)
    pane:select(stem)
    assert.is_false(pane:key("delete"))                    -- not the root
    assert.same({ "graph", "graph", "graph", "graph" }, what)
    assert.matches("unknown kind 'bush'", H.errof(pane.add, pane, "bush", "child"))
  end)
end)

describe("lsys.ui.graph save_lua", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  local function same_scene (a, b)
    assert.equal(a.ntriangles, b.ntriangles)
    local lo1, hi1 = a:bounds()
    local lo2, hi2 = b:bounds()
    for k = 1, 3 do
      assert.near(lo1[k], lo2[k], 1e-9)
      assert.near(hi1[k], hi2[k], 1e-9)
    end
  end

  it("writes a model file that loads back to the same scene", function ()
    local root = forked()
    local stem = small()
    root:child(stem)
    stem.links[1].to:child(C.wreath { n = 3 }, { only = { 1, 3 } })
    root.links[1].to:set("curvature", 30)
    stem:set("angle", lsys.func.new { points = { { 0, 70 }, { 0.4, 20 }, { 0.6, 50 },
                                                 { 1, 10 } } })
    local path = dir .. "/edited.lua"
    local pane = P.new(root, { dot = false, path = path, seed = 3 })
    assert.same({ path }, pane:save())
    local m = load.model(path)
    same_scene(P.rebuild(root, { seed = 3 }), m:interpret())
    local text = H.read(path)
    assert.matches("c%[1%] = C.tree { name = \"root\", n = 4 }", text)
    assert.matches("recursion = 3", text)
    assert.matches("{ only = { 1, 3 } }", text)
    -- the program renders it
    local out, code = H.sh(("%s render %s -o %s/x.png --size 64x64"):format(H.BIN, path, dir))
    assert.equal(0, code, out)
  end)

  it("writes a function as its sampled curve, with a comment", function ()
    local lf = C.leaf { name = "lf", length = function (ctx) return 0.2 + 0.1 * ctx.i end }
    local path = dir .. "/f.lua"
    P.save_lua(lf, path)
    local text = H.read(path)
    assert.matches("%-%- leaf 'lf': 'length' was a Lua function: written as the curve", text)
    local m = load.model(path)
    assert.is_true(lsys.func.isfunc(m.components.tree.root.params.length))
  end)

  it("writes names and strings as literals: nothing in them becomes code", function ()
    local name = 'x"\n]] error("ran") --[['
    local lf = C.leaf { name = name, length = function (ctx) return 0.1 * ctx.i end }
    local path = dir .. "/names.lua"
    P.save_lua(lf, path, { name = name .. "\r--" })
    local text = H.read(path)
    assert.is_nil(text:find("\n]] error", 1, true))
    -- the comment about the function stays one line: its newline written as \10
    assert.is_truthy(text:find("-- leaf 'x\"\\10]] error", 1, true))
    local ok, m = pcall(load.run, path)
    assert.is_true(ok, tostring(m))
    assert.equal(name, m.components.tree.root.name)
    assert.equal(name .. "\r--", m.name)
  end)

  it("writes the view and the chestnut's model options", function ()
    local chestnut = dofile("examples/components/chestnut.lua")
    local root = chestnut.graph { branches = 2, subs = 2, twigs = 2, leaves = 2 }
    local path = dir .. "/chestnut.lua"
    P.save_lua(root, path, { seed = 1, view = chestnut.VIEW, name = "chestnut" })
    local m = load.model(path)
    assert.equal("chestnut", m.name)
    assert.is_true(H.read(path):find("chestnut_leaf.png", 1, true) ~= nil)
    -- the leaflets' length was a function of i and n: sampled at 7 positions, which
    -- are the 7 leaflets' own
    local before = P.rebuild(root, { seed = 1, view = chestnut.VIEW })
    local after = m:interpret()
    assert.equal(before.ntriangles, after.ntriangles)
  end)

  it("refuses what cannot be written, naming it", function ()
    local f = C.ffd { name = "bend", fx = function (x) return x end }
    assert.matches("ffd 'bend': 'fx' cannot be written", H.errof(P.save_lua, f,
                                                                  dir .. "/x.lua"))
    local bad = C.leaf { length = function () error("no") end }
    assert.matches("'length': its function failed", H.errof(P.save_lua, bad, dir .. "/x.lua"))
    assert.matches("a component prototype expected", H.errof(P.save_lua, {}, dir .. "/x.lua"))
    assert.matches("a file name expected", H.errof(P.save_lua, C.leaf {}, 42))
    assert.matches("no file to write", H.errof(P.new(C.leaf {}).save, P.new(C.leaf {})))
    assert.matches("view's view.f", H.errof(P.save_lua, C.leaf {}, dir .. "/x.lua",
                                               { view = { f = print } }))
  end)
end)

describe("lsys.ui.graph bad input", function ()
  it("names what is wrong", function ()
    assert.matches("a component prototype or a component model expected, got number",
                   H.errof(P.new, 42))
    assert.matches("unknown option 'colour'", H.errof(P.new, C.leaf {}, { colour = 1 }))
    assert.matches("on_change must be a function",
                   H.errof(P.new, C.leaf {}, { on_change = 1 }))
    assert.matches("a component prototype expected, got string", H.errof(P.layout, "x"))
    assert.matches("option 'dot'", H.errof(P.layout, C.leaf {}, { dot = 3 }))
    local pane = P.new(small(), { dot = false })
    assert.matches("no component 'nope' %(components: camera, stem, whorl, leaf%)",
                   H.errof(pane.box, pane, "nope"))
    assert.matches("select a component first", H.errof(pane.add, pane, "leaf", "child"))
    local lf = C.leaf { name = "x" }
    assert.matches("unknown parameter 'colour'", H.errof(lf.set, lf, "colour", 1))
    assert.matches("'lateral' must be a number from %-10 to 10", H.errof(lf.set, lf,
                                                                        "lateral", 20))
    assert.is_nil(lf.params.lateral)
  end)
end)

describe("proto:set", function ()
  it("checks as the constructor does, resets with nil, versions the prototype", function ()
    local t = C.tree { name = "t", n = 4 }
    assert.same({ 0, 0 }, { t.version, t.xversion })
    assert.equal(t, t:set("n", 7))
    assert.same({ 7, 1, 1 }, { t.params.n, t.version, t.xversion })
    t:set("radius", 0.2)                           -- drawn only: the i-tree stays
    assert.same({ 2, 1 }, { t.version, t.xversion })
    t:set("n", nil)
    assert.same({ 10, 3, 2 }, { t:param("n"), t.version, t.xversion })
    assert.matches("'n' must be from 0 to", H.errof(t.set, t, "n", 1e9))
    assert.matches("'segments' must be a whole number", H.errof(t.set, t, "segments", 1.5))
    assert.equal(3, t.version)                     -- a refused value changes nothing
    t:set("recursion", 4)
    assert.same({ 4, true }, { t.recursion, t.recursive })
    assert.matches("'recursion' must be a whole number from 1 to 1000",
                   H.errof(t.set, t, "recursion", 0))
    t:set("name", "u")
    assert.equal("u", t.name)
    assert.matches("call it as proto:set", H.errof(t.set, {}, "n", 1))
    -- an lsys.Func for a number, not for a vector
    local f = lsys.func.new { points = { { 0, 1 }, { 0.3, 1 }, { 0.6, 1 }, { 1, 1 } } }
    t:set("length", f)
    assert.equal(f, t.params.length)
    assert.matches("'rotate' must be a vector", H.errof(t.set, t, "rotate", f))
  end)
end)

describe("lsys.ui.graph chestnut", function ()
  it("draws the chestnut's graph into a 420 x 700 pane", function ()
    local chestnut = dofile("examples/components/chestnut.lua")
    local pane = P.new(chestnut, { dot = false })
    local c = core.canvas(420, 700)
    pane:select(chestnut.components.tree.root.links[1].to)      -- the branch
    pane:draw(c)
    local names = { "camera", "trunk", "branch", "sub-branch", "twig", "petiole",
                    "palmate", "leaflet" }
    local lastbottom = 0
    for _, k in ipairs(names) do
      local x, y, w, h = pane:box(k)
      assert.is_true(x >= 0 and x + w <= 420 and y > lastbottom and y + h <= 700 - 24, k)
      lastbottom = y + h
    end
    local path = H.tmpdir() .. "/pane.png"
    c:save(path)
    assert.is_true(#H.read(path) > 1000)
  end)

  it("gives the same plant on 1 and 3 threads after an edit", function ()
    local script = [[
      local P = require "lsys.ui.graph"
      local C = require "lsys".components
      local lf = C.leaf { length = 0.3, width = 0.1 }
      local t = C.tree { n = 40, length = 3, angle = { 70, 20 }, gnarl = 5 }
      t:branch(lf)
      local pane = P.new(t, { dot = false })
      pane:select(t)
      for _, it in ipairs(pane:items()) do if it.name == "n" then it.set(60) end end
      local s = pane:rebuild()
      local lo, hi = s:bounds()
      print(s.ntriangles, ("%.12g %.12g %.12g %.12g"):format(lo[1], lo[3], hi[1], hi[2]))
    ]]
    local a = H.lsys(script, { env = "LSYS_THREADS=1" })
    local b = H.lsys(script, { env = "LSYS_THREADS=3" })
    assert.matches("^%d+\t", a)
    assert.equal(a, b)
  end)
end)
