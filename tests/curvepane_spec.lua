-- The curve editor pane (lsys.ui.curve) driven by pointer events in its canvas's pixels:
-- dragging a function's points (end points keep x, inner points stay between their
-- neighbours), adding and removing points, the targets of a model and the model's next
-- derivation and interpretation after an edit, saving back into .func, .fset and .con files,
-- surfaces' control points moved and saved, switching targets, the picture, and the messages
-- for bad targets.
local H = require "tests.helper"
local core = require "lsys.core"
local lsys = require "lsys"
local func = require "lsys.func"
local P = require "lsys.ui.curve"

-- The message of the error f(...) raises, without the position error() put before it.
local function message (f, ...)
  return (H.errof(f, ...):gsub("^[^:\n]*:%d+: ", ""))
end

-- A flat function whose x are equally spaced: with 4 points the curve is one Bézier span
-- and x(t) = t, so f(x) = 3 x (1 - x)^2 y2 + 3 x^2 (1 - x) y3 + x^3 y4 (y1 = 0 here).
local function flat (name)
  return func.new { points = { { 0, 0 }, { 1 / 3, 0 }, { 2 / 3, 0 }, { 1, 0 } },
                    name = name or "internode" }
end

local function bezier (x, y2, y3, y4)
  return 3 * x * (1 - x) ^ 2 * y2 + 3 * x * x * (1 - x) * y3 + x ^ 3 * y4
end

-- Drags from (x0, y0) by (dx, dy) pixels in n steps.
local function drag (pane, x0, y0, dx, dy, n, button)
  button, n = button or "left", n or 4
  pane:pointer("down", x0, y0, button)
  for i = 1, n do pane:pointer("move", x0 + dx * i / n, y0 + dy * i / n, button) end
  return pane:pointer("up", x0 + dx, y0 + dy, button)
end

local function drag_point (pane, i, dx, dy)
  local x, y = pane:to_pixels(i)
  return drag(pane, x, y, dx, dy)
end

local SQUARE = { { 1, 1 }, { -1, 1 }, { -1, -1 }, { 1, -1 } }

describe("the curve pane on a function", function ()
  it("moves a dragged point and the function's values follow", function ()
    local pane = P.new(flat())
    local x, y = pane:to_pixels(2)
    local a = pane:maps()
    drag(pane, x, y, 0, -150)
    local f = pane:current().object
    local p = f:points()
    assert.near(1 / 3, p[2][1], 1e-9)
    assert.near((a.oy - (y - 150)) / a.sy, p[2][2], 1e-9)   -- under the pointer
    assert.is_true(p[2][2] > 0.2)
    local px = pane:to_pixels(2)
    assert.near(x, px, 1e-6)
    -- the view fits the curve again after the drag: from y 0 - 10 % to y2 + 10 %
    local box = pane:current().box
    assert.near({ -0.1 * p[2][2], 1.1 * p[2][2] }, { box[3], box[4] }, 1e-9)
    for _, t in ipairs { 0.1, 0.25, 0.5, 0.9 } do
      assert.near(bezier(t, p[2][2], 0, 0), f(t), 1e-9)
    end
    assert.near(0.375 * p[2][2], f(0.5), 1e-9)
    assert.equal(0, flat()(0.5))
  end)

  it("keeps the end points at x = 0 and x = 1, y free", function ()
    local pane = P.new(flat())
    local a = pane:maps()
    local _, y1 = pane:to_pixels(1)
    drag_point(pane, 1, 60, -40)
    local b = pane:maps()                            -- refitted after the first drag
    local _, y4 = pane:to_pixels(4)
    drag_point(pane, 4, -60, -80)
    local p = pane:current().object:points()
    assert.equal(0, p[1][1])
    assert.equal(1, p[4][1])
    assert.near((a.oy - (y1 - 40)) / a.sy, p[1][2], 1e-9)
    assert.near((b.oy - (y4 - 80)) / b.sy, p[4][2], 1e-9)
    assert.is_true(p[1][2] > 0.05 and p[4][2] > 0.005)
  end)

  it("keeps an inner point's x between its neighbours' and y in the view", function ()
    local pane = P.new(flat())
    local box = pane:current().box
    drag_point(pane, 2, 1000, -5000)
    local p = pane:current().object:points()
    assert.equal(2 / 3, p[2][1])
    assert.equal(box[4], p[2][2])                    -- the top of the view while dragging
    assert.is_true(pane:current().box[4] > box[4])   -- the view grew when the drag ended
    drag_point(pane, 3, -1000, 0)                    -- now point 3 meets point 2
    p = pane:current().object:points()
    assert.equal(2 / 3, p[3][1])
  end)

  it("adds points by Shift+click and by a click on the curve, in x order", function ()
    local pane = P.new(flat())
    local e = pane:current()
    local a = pane:maps()
    local px, py = a.ox + a.sx * 0.5, a.oy - a.sy * 0.2   -- data (0.5, 0.2), off the curve
    pane:pointer("down", px, py, "left", true)
    pane:pointer("up", px, py, "left", true)
    assert.equal(5, #e.pts)
    assert.near({ 0.5, 0.2 }, e.object:points()[3], 1e-9)
    assert.equal(3, pane.selected)
    -- a plain click on the curve (not on a point) adds one there
    local f = e.object
    a = pane:maps()
    px, py = a.ox + a.sx * 0.85, a.oy - a.sy * f(0.85)
    assert.is_nil(pane:hit(px, py))
    pane:pointer("down", px, py, "left")
    pane:pointer("up", px, py, "left")
    assert.equal(6, #e.pts)
    assert.near({ 0.85, f(0.85) }, e.object:points()[5], 1e-9)
    -- a plain click away from the curve and the points adds nothing and clears the selection
    pane:pointer("down", a.ox + a.sx * 0.1, a.oy - a.sy * (f(0.1) + 0.3), "left")
    assert.equal(6, #e.pts)
    assert.is_nil(pane.selected)
  end)

  it("removes points by right click and Delete, keeping 4 points and the end points", function ()
    local pane = P.new(func.new { points = { { 0, 0 }, { 0.2, 1 }, { 0.4, 0 }, { 0.6, 1 },
                                             { 0.8, 0 }, { 1, 1 } } })
    local e = pane:current()
    local x, y = pane:to_pixels(1)
    pane:pointer("down", x, y, "right")
    assert.equal(6, #e.pts)
    assert.equal("the end points stay (x = 0 and x = 1)", pane.msg)
    x, y = pane:to_pixels(3)
    pane:pointer("down", x, y, "right")
    assert.same({ { 0, 0 }, { 0.2, 1 }, { 0.6, 1 }, { 0.8, 0 }, { 1, 1 } }, e.object:points())
    x, y = pane:to_pixels(2)
    pane:pointer("down", x, y, "left")
    pane:pointer("up", x, y, "left")
    assert.is_true(pane:key("delete"))
    assert.same({ { 0, 0 }, { 0.6, 1 }, { 0.8, 0 }, { 1, 1 } }, e.object:points())
    pane.selected = 2
    pane:key("backspace")
    assert.equal(4, #e.object:points())
    assert.equal("a function needs at least 4 points", pane.msg)
  end)

  it("calls a curve item's set and on_change with the new Func after each edit", function ()
    local got, changes = {}, {}
    local item = { name = "width", label = "leaf width", func = flat("width"),
                   set = function (f) got[#got + 1] = f end }
    local pane = P.new(item, { on_change = function (what, name, obj)
      changes[#changes + 1] = { what, name, obj }
    end })
    local x, y = pane:to_pixels(3)
    pane:pointer("down", x, y, "left")
    pane:pointer("move", x, y - 50, "left")
    pane:pointer("move", x, y - 100, "left")
    pane:pointer("up", x, y - 100, "left")
    assert.equal(2, #got)
    assert.equal(2, #changes)
    assert.equal(pane:current().object, got[2])
    assert.same({ "func", "width" }, { changes[2][1], changes[2][2] })
    assert.equal(got[2], changes[2][3])
    assert.equal("width", got[2]:name())
    assert.is_true(got[2](0.5) > 0)
    assert.matches("^leaf width: 4 points  point 3: x 0.6667 y 0.%d+$", pane:status())
  end)

  it("undoes drags, additions and removals with Ctrl+Z, across curves", function ()
    local pane = P.new({ flat("a"), core.contour(SQUARE, true) })
    local orig = pane:current().object:points()
    drag_point(pane, 2, 0, -100)
    local dragged = pane:current().object:points()
    local a = pane:maps()
    local px, py = a.ox + a.sx * 0.5, a.oy - a.sy * 0.2
    pane:pointer("down", px, py, "left", true)
    pane:pointer("up", px, py, "left", true)
    assert.equal(5, #pane:current().pts)
    pane:key("]")
    pane.selected = 4
    pane:key("delete")
    assert.equal(3, #pane:current().object:points())
    assert.is_true(pane:key("z", true))
    assert.same(SQUARE, pane:current().object:points())
    pane:key("[")
    pane:key("z", true)
    assert.same(dragged, pane:current().object:points())
    pane:key("z", true)
    assert.same(orig, pane:current().object:points())
    assert.equal(orig[2][2], pane.entries[1].object(0.5))      -- flat again: 0
    pane:key("]")
    pane:key("z", true)
    assert.equal(2, pane.cur)                          -- nothing left: the curve stays
    assert.equal("nothing to undo", pane.msg)
  end)

  it("lets the arrows select and nudge points, and leaves Ctrl keys to the host", function ()
    local pane = P.new(flat())
    assert.is_true(pane:key("right"))
    assert.equal(1, pane.selected)
    pane:key("right")
    pane:key("right")
    assert.equal(3, pane.selected)
    local box = pane:current().box
    pane:key("up")
    assert.near((box[4] - box[3]) / 100, pane:current().object:points()[3][2], 1e-12)
    assert.is_false(pane:key("s", true))
    assert.is_false(pane:key("q"))
    assert.is_false(pane:scroll(1, 10, 10))
  end)
end)

describe("the curve pane and a model", function ()
  it("lists a model's functions, contours and surfaces as targets", function ()
    local sq = core.contour(SQUARE, true)
    local m = lsys.lsystem { axiom = "A", functions = { flat("a"), flat("b"), size = flat("c") },
                             view = { contours = { [2] = sq },
                                      surfaces = { l = "examples/cpfg/surfaces/leaf.s" } } }
    local t = P.targets(m)
    local names = {}
    for i, x in ipairs(t) do names[i] = x.kind .. ":" .. x.name end
    assert.same({ "func:a", "func:b", "func:size", "contour:contour 2", "surface:surface l" },
                names)
    assert.equal(sq, t[4].object)
    assert.is_nil(t[4].file)
    assert.equal("examples/cpfg/surfaces/leaf.s", t[5].file)
    assert.equal("lsys.Surface", getmetatable(t[5].object).__name)
    assert.equal("function", type(t[5].set))
    assert.same({ 1, 2, "size" }, { t[1].id, t[2].id, t[3].id })
  end)

  for _, lua in ipairs { false, true } do
    it("makes the model derive a different string after an edit (" ..
       (lua and "Lua closures" or "the expression machine") .. ")", function ()
      local m = lsys.lsystem { axiom = "A(0.5)",
                               functions = { flat("internode"), flat("angle") },
                               productions = "A(x) --> B(func('internode', x), func(2, x))" }
      m.lua_expressions = lua or nil
      assert.same({ "B", 0, 0 }, { m:derive(1):module(1) })
      local before = tostring(m:derive(1))
      local pane = P.new(P.targets(m))
      drag_point(pane, 2, 0, -120)            -- internode
      pane:key("]")
      drag_point(pane, 3, 0, -60)             -- angle
      local s = m:derive(1)
      assert.are_not.equal(before, tostring(s))
      local fi, fa = pane.entries[1].object, pane.entries[2].object
      local _, a, b = s:module(1)
      assert.equal(fi(0.5), a)
      assert.equal(fa(0.5), b)
      assert.near(0.375 * fi:points()[2][2], a, 1e-9)
      assert.near(0.375 * fa:points()[3][2], b, 1e-9)
      assert.equal(fi(0.5), m:func("internode", 0.5))
      assert.equal(fa(0.5), m:func(2, 0.5))
    end)
  end

  it("derives the same string with 1 and 4 threads after an edit", function ()
    local out = {}
    for _, n in ipairs { 1, 4 } do
      local m = lsys.lsystem { axiom = "A(0)", functions = { flat() }, threads = n, steps = 6,
                               productions = "A(x) --> A(x + 0.125) B(func(1, x))" }
      local pane = P.new(P.targets(m))
      drag_point(pane, 2, 0, -100)
      out[n] = tostring(m:derive())
    end
    assert.equal(out[1], out[4])
    assert.matches("B%(0%.%d+", out[1])
  end)

  it("puts an edited contour into the model's view: the next scene changes", function ()
    local m = lsys.lsystem { axiom = "@#(1) @Gs f(2) @Ge(5)",
                             view = { contour_sides = 10, contours = { [1] = core.contour(SQUARE,
                               true) } } }
    local a = m:interpret()
    local t = P.targets(m)
    assert.equal(1, #t)
    local pane = P.new(t)
    drag_point(pane, 1, 80, -80)                     -- (1, 1) outwards
    local c = m.view.contours[1]
    assert.equal(pane:current().object, c)
    assert.is_true(c:points()[1][1] > 1.2)
    local b = m:interpret()
    assert.equal(a.ntriangles, b.ntriangles)
    local la, ha = a:bounds()
    local lb, hb = b:bounds()
    local moved = 0                                  -- the largest change of the bounds
    for k = 1, 3 do moved = math.max(moved, math.abs(la[k] - lb[k]), math.abs(ha[k] - hb[k])) end
    assert.is_true(moved > 0.1)
    assert.equal(ha[2], hb[2])                       -- the same length along the axis
  end)

  it("edits a contour's points: drag, add into the nearest side, remove to 3", function ()
    local pane = P.new(core.contour(SQUARE, true))
    local e = pane:current()
    local a = pane:maps()
    local px, py = a.ox + a.sx * 0, a.oy - a.sy * 1.1     -- near the side (1,1)-(-1,1)
    pane:pointer("down", px, py, "left", true)
    pane:pointer("up", px, py, "left", true)
    assert.near({ { 1, 1 }, { 0, 1.1 }, { -1, 1 }, { -1, -1 }, { 1, -1 } },
                e.object:points(), 1e-9)
    pane.selected = 1
    pane:key("delete")
    pane.selected = 1
    pane:key("delete")
    assert.equal(3, #e.object:points())
    pane.selected = 1
    pane:key("delete")
    assert.equal(3, #e.object:points())
    assert.equal("a closed contour needs at least 3 points", pane.msg)
  end)
end)

describe("saving edited curves", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("writes a .func back and reads the same points", function ()
    local path = dir .. "/w.func"
    func.save(flat("w"), path)
    local m = lsys.lsystem { axiom = "A", functions = { path } }
    local pane = P.new(P.targets(m))
    assert.equal(path, pane:current().file)
    assert.same({}, pane:save())                  -- nothing edited yet
    drag_point(pane, 2, 0, -77)
    assert.same({ path }, pane:save())
    local g = func.load(path)
    assert.same(pane:current().object:points(), g:points())
    assert.equal("w", g:name())
    assert.equal("saved " .. path, pane.msg)
  end)

  it("rewrites a .fset with the edited function in its place", function ()
    local path = dir .. "/set.fset"
    local A = func.new { points = { { 0, 1 }, { 0.3, 1 }, { 0.6, 1 }, { 1, 1 } }, name = "A",
                         samples = 100 }
    func.save_set({ A, flat("B") }, path)
    local m = lsys.lsystem { axiom = "A", functions = { path } }
    local pane = P.new(P.targets(m))
    pane:key("]")
    assert.equal("B", pane:current().name)
    drag_point(pane, 3, 0, -90)
    assert.same({ path }, pane:save())
    local fs = func.load(path)
    assert.equal(2, #fs)
    assert.same(A:points(), fs.A:points())
    assert.equal(100, fs.A:samples())
    assert.equal(fs[2], fs.B)
    assert.same(pane:current().object:points(), fs.B:points())
  end)

  it("round-trips a function set: load, save_set, load", function ()
    local src, path = dir .. "/set.fset", dir .. "/copy.fset"
    H.write(src, "funcgalleryver 1 1\nitems: 2\nfver 1 1\nname: A\nsamples: 100\nflip: off\n" ..
            "points: 4\n0 1\n0.3 1\n0.6 1\n1 1\nfver 1 1\nname: B\nsamples: 0\nflip: off\n" ..
            "points: 4\n0 0 1\n0.5 0 3\n0.5 1 3\n1 1 1\n")
    local a = func.load(src)
    func.save_set(a, path)
    local b = func.load(path)
    assert.equal(#a, #b)
    for i = 1, #a do
      assert.same(a[i]:points(), b[i]:points())
      assert.same({ a[i]:name(), a[i]:samples() }, { b[i]:name(), b[i]:samples() })
    end
    assert.equal(8, #b.B:points())                  -- multiplicities kept
    assert.equal("lsys.func.save_set: a list of at least one lsys.Func expected",
                 message(func.save_set, {}, path))
    assert.equal("lsys.func.save_set: item 2 is a string, not an lsys.Func",
                 message(func.save_set, { a[1], "x" }, path))
  end)

  it("writes contours in cpfg's format and reads back the same points", function ()
    for _, src in ipairs { "examples/cpfg/contours/fig16a.con",
                           "examples/cpfg/contours/pelican_lip.con" } do
      local c = core.contour_load(src)
      local path = dir .. "/c.con"
      P.save_contour(c, path)
      local d = core.contour_load(path)
      assert.same(c:points(), d:points())
      assert.same({ c:closed(), c:dim() }, { d:closed(), d:dim() })
    end
    assert.equal("4 2 closed\n1 1\n-1 1\n-1 -1\n1 -1\n",
                 P.contour_text(core.contour(SQUARE, true)))
    assert.equal("4 3 open\n0.1 0 0\n0.5 0.25 1\n1 0 0\n1.5 0 0\n",
                 P.contour_text(core.contour({ { 0.1, 0, 0 }, { 0.5, 0.25, 1 }, { 1, 0, 0 },
                                               { 1.5, 0, 0 } }, false)))
  end)

  it("saves an edited contour of the view into its .con file", function ()
    local path = dir .. "/sq.con"
    P.save_contour(core.contour(SQUARE, true), path)
    local m = lsys.lsystem { axiom = "@#(1) @Gs f(2) @Ge(5)",
                             view = { contour_sides = 10, contours = { [1] = path } } }
    local pane = P.new(P.targets(m))
    assert.equal(path, pane:current().file)
    drag_point(pane, 2, -40, 0)
    assert.same({ path }, pane:save())
    assert.same(pane:current().object:points(), core.contour_load(path):points())
    -- the model reads the file again: the same contour as the edited one
    local m2 = lsys.lsystem { axiom = "@#(1) @Gs f(2) @Ge(5)",
                              view = { contour_sides = 10, contours = { [1] = path } } }
    local _, h1 = m:interpret():bounds()
    local _, h2 = m2:interpret():bounds()
    assert.near(h1, h2, 1e-6)
  end)

  it("says which edited curves have no file", function ()
    local pane = P.new(flat())
    drag_point(pane, 2, 0, -50)
    assert.same({}, pane:save())
    assert.equal("nothing to save (1 edited curve without a file)", pane.msg)
  end)
end)

describe("the curve pane's surfaces, targets and picture", function ()
  it("moves a surface's points in the front and side views, shared points together", function ()
    local s = core.surface_load("examples/cpfg/surfaces/leaf.s")
    local pane = P.new(s)
    local e = pane:current()
    assert.equal(16 * s:info().patches, #e.pts)
    assert.same(s:patch(1)[5], e.pts[5])
    assert.same(s:patch(1)[13], s:patch(2)[1])      -- the edge the two patches share
    local a = pane:maps()
    local x, y = pane:to_pixels(13)
    drag(pane, x, y, 30, 0)
    local f = pane:current().object
    assert.are_not.equal(s, f)
    local p13, p17 = f:patch(1)[13], f:patch(2)[1]
    assert.near(-0.38 + 30 / a.sx, p13[1], 1e-9)
    assert.near({ 0.45, 0.056 }, { p13[2], p13[3] }, 1e-9)
    assert.same(p13, p17)
    assert.same(s:patch(1)[14], f:patch(1)[14])      -- the others stay
    assert.equal(-0.38, s:patch(1)[13][1])            -- the old surface is unchanged
    local sx, sy = pane:to_pixels(6, true)           -- the side view, below the front one
    assert.is_true(sy > y)
    local b = select(2, pane:maps())
    drag(pane, sx, sy, 20, 0)
    local q = pane:current().object:patch(1)[6]
    assert.near({ -0.0733, 0.12, 0.029 + 20 / b.sx }, q, 1e-9)
    assert.equal(6, pane.selected)
    assert.equal(string.format("surface: 2 patches  patch 1 point 6: x %.4g y %.4g z %.4g",
                               q[1], q[2], q[3]), pane:status())
    pane:key("delete")
    assert.equal("a surface's points are moved, not removed", pane.msg)
    pane:pointer("down", sx, sy + 40, "left", true)
    assert.equal("a surface's points are moved, not added", pane.msg)
    assert.equal("patch index must be from 1 to 2",
                 (H.errof(s.patch, s, 3):gsub("^bad argument #2 to '[^']*' %((.*)%)$", "%1")))
    assert.equal("expected 32 points (16 per patch), got 1",
                 (H.errof(s.with_points, s, { { 0, 0, 0 } })
                   :gsub("^bad argument #2 to '[^']*' %((.*)%)$", "%1")))
  end)

  it("puts an edited surface into the model's view and saves it as a .s file", function ()
    local dir = H.tmpdir()
    local path = dir .. "/leaf.s"
    H.write(path, H.read("examples/cpfg/surfaces/leaf.s"))
    local m = lsys.lsystem { axiom = "~l", view = { surfaces = { l = { file = path,
                                                                         scale = 2 } } } }
    local before = m:interpret()
    local pane = P.new(P.targets(m))
    assert.equal(path, pane:current().file)
    drag_point(pane, 12, 40, 0)                      -- a point of the widest row, outwards
    local sp = m.view.surfaces.l
    assert.equal(pane:current().object, sp.surface)
    assert.equal(2, sp.scale)
    assert.is_nil(sp.file)
    local after = m:interpret()
    assert.equal(before.ntriangles, after.ntriangles)
    local l1, h1 = before:bounds()
    local l2, h2 = after:bounds()
    local moved = 0                                  -- the largest change of the bounds
    for k = 1, 3 do moved = math.max(moved, math.abs(h2[k] - h1[k]), math.abs(l2[k] - l1[k])) end
    assert.is_true(moved > 0.05, "the surface did not grow")
    assert.same({ path }, pane:save())
    local back = core.surface_load(path)
    assert.same(P.points(pane:current().object), P.points(back))
    assert.same({ "base", "tip" }, back:info().names)
    H.rmdir(dir)
  end)

  it("switches targets with [ ], Tab and the names at the top", function ()
    local pane = P.new({ flat("a"), core.contour(SQUARE, true), flat("c") })
    local c = core.canvas(420, 700)
    pane:draw(c)
    pane:key("]")
    assert.equal(2, pane.cur)
    pane:key("tab")
    assert.equal(3, pane.cur)
    pane:key("tab")
    assert.equal(1, pane.cur)
    pane:key("[")
    assert.equal(3, pane.cur)
    pane:key("tab", false, true)
    assert.equal(2, pane.cur)
    pane:draw(c)
    local t = pane.tabs[1]
    assert.is_true(pane:pointer("down", (t[1] + t[2]) / 2, 15, "left"))
    assert.equal(1, pane.cur)
    assert.equal("curves", pane.name)
    assert.matches("Shift%+click", pane.help)
  end)

  it("draws the selection in red where to_pixels says, at 420 x 700 and 240 x 240", function ()
    local m = lsys.lsystem { axiom = "A", functions = {
      func.new { points = { { 0, 0.2 }, { 0.25, 0.9 }, { 0.5, 0.3 }, { 0.75, 0.6 }, { 1, 1 } },
                 name = "internode" }, flat("width") },
      view = { contours = { [1] = "examples/cpfg/contours/fig16a.con" },
               surfaces = { l = "examples/cpfg/surfaces/leaf.s" } } }
    local pane = P.new(P.targets(m))
    for _, size in ipairs { { 420, 700 }, { 240, 240 } } do
      local c = core.canvas(size[1], size[2])
      pane:draw(c)
      local x, y = pane:to_pixels(3)
      pane:pointer("down", x, y, "left")
      pane:pointer("up", x, y, "left")
      pane:draw(c)
      local px = c:pixels()
      local k = (math.floor(y) * size[1] + math.floor(x)) * 4
      local r, g, b = px:byte(k + 1, k + 3)
      assert.is_true(r > 200 and g < 80 and b < 80, "not red at the selection")
      k = (5 * size[1] + size[1] - 3) * 4           -- the background near a corner
      assert.is_true(px:byte(k + 1) > 230)
      if size[1] == 420 then c:save(os.getenv("LSYS_CURVEPANE_PNG") or
                                    (os.getenv("TMPDIR") or "/tmp") .. "/lsys-pane-curves.png") end
    end
  end)

  it("has the new Contour and Surface methods raise once the object was closed", function ()
    local c = core.contour(SQUARE, true)
    local s = core.surface_load("examples/cpfg/surfaces/leaf.s")
    local pts = P.points(s)
    getmetatable(c).__close(c)
    getmetatable(s).__close(s)
    assert.equal("the contour was closed", H.errof(c.points, c))
    assert.equal("the surface was closed", H.errof(s.patch, s, 1))
    assert.equal("the surface was closed", H.errof(s.format, s))
    assert.equal("the surface was closed", H.errof(s.with_points, s, pts))
  end)

  it("raises clear errors for bad targets and options", function ()
    local f = flat()
    local exp = "lsys.ui.curve.new: target: an lsys.Func, lsys.Contour, lsys.Surface, a curve " ..
                "item or a target table expected, got number"
    assert.equal(exp, message(P.new, 42))
    assert.equal("lsys.ui.curve.new: no curves to edit (an empty list)", message(P.new, {}))
    assert.equal("lsys.ui.curve.new: target 2: an lsys.Func, lsys.Contour, lsys.Surface, a " ..
                 "curve item or a target table expected, got string", message(P.new, { f, "x" }))
    assert.equal("lsys.ui.curve.new: target: a curve item's 'func' must be an lsys.Func, got " ..
                 "number", message(P.new, { kind = "curve", name = "w", func = 3 }))
    assert.equal("lsys.ui.curve.new: target: a contour target's 'object' must be an " ..
                 "lsys.Contour, got lsys.Func", message(P.new, { kind = "contour", object = f }))
    assert.equal("lsys.ui.curve.new: target: unknown kind 'spline' (func, contour, surface, " ..
                 "curve)", message(P.new, { kind = "spline" }))
    assert.equal("lsys.ui.curve.new: target: 'set' must be a function, got string",
                 message(P.new, { name = "w", func = f, set = "x" }))
    assert.equal("lsys.ui.curve.new: unknown option 'onchange'",
                 message(P.new, f, { onchange = print }))
    assert.equal("lsys.ui.curve.new: 'on_change' must be a function",
                 message(P.new, f, { on_change = 1 }))
    assert.equal("lsys.ui.curve.new: 'width' must be a number >= 1",
                 message(P.new, f, { width = "wide" }))
    assert.equal("lsys.ui.curve.targets: a model expected, got string", message(P.targets, "m"))
    assert.equal("to_pixels: no point 9 (the curve has 4)",
                 message(P.new(f).to_pixels, P.new(f), 9))
    assert.equal("lsys.ui.curve.save_contour: an lsys.Contour expected, got lsys.Func",
                 message(P.save_contour, f, "/tmp/x.con"))
    local m = lsys.lsystem { axiom = "A", functions = { f } }
    assert.equal("set_func: unknown function 'leaf' (functions: internode)",
                 message(m.set_func, m, "leaf", f))
    assert.equal("set_func: an lsys.Func expected, got number", message(m.set_func, m, 1, 2))
  end)
end)

describe("the curve pane on a sketch's model", function ()
  it("edits the functions a sketch derives (its env's lsys.Funcs): the next derivation", function ()
    local m = dofile("examples/sketch/fig8.lua").distichous
    local names = {}
    for _, t in ipairs(P.targets(m)) do
      if t.kind == "func" then names[#names + 1] = t.name end
    end
    assert.same({ "angle_left", "angle_right", "internode", "size_left", "size_right",
                  "stem_shape" }, names)
    local before = tostring(m:derive())
    local pane = P.new(P.targets(m))
    local e = pane:current()
    assert.equal("angle_left", e.name)
    e.pts[2][2] = e.pts[2][2] + 0.5
    assert.is_true(pane:commit(e))
    assert.is_true(rawequal(m.env.angle_left, e.object))
    assert.not_equal(before, tostring(m:derive()))
  end)
end)
