-- The editing panes without a window: the parameter form (lsys.ui.form), what it edits
-- (lsys.ui.tune: a model's params, vlab panels; saving them) and the session that builds
-- the plant again (lsys.ui.edit), driven through a stand-in for the window.
local H = require "tests.helper"
local have_core = pcall(require, "lsys.core")
if not have_core then
  describe("lsys.ui.edit", function ()
    it("needs lsys.core", function () pending("lsys.core is not built") end)
  end)
  return
end
local lsys = require "lsys"
local form = require "lsys.ui.form"
local tune = require "lsys.ui.tune"
local edit = require "lsys.ui.edit"
local core = require "lsys.core"

local tmpdir, write, read = H.tmpdir, H.write, H.read

-- a binary tree k levels deep: 2^k - 1 F and as many brackets
local TREE = [[
local lsys = require "lsys"
return lsys.lsystem {
  axiom = "A(0)",
  steps = 8,
  params = {
    k = { 3, min = 1, max = 6, step = 1, label = "levels" },
    angle = { 30, min = 5, max = 80 },
    leaves = { false },
    shape = { "fan", choices = { "fan", "spire" } },
  },
  productions = {
    "A(i) : i < k --> F [ +(angle) A(i+1) ] [ -(angle) A(i+1) ]",
    "A(i) : i >= k and leaves --> L",
  },
  homomorphism = "L --> { . +(30) f . -(60) f . }",
}
]]

local function tree (k)
  local m = load(TREE:gsub("^local lsys = require \"lsys\"\n", ""), "tree", "t",
                 setmetatable({ lsys = lsys }, { __index = _G }))()
  if k then m.params.k = k end
  return m
end

local function count (s, name)
  local n = 0
  for i = 1, #s do if s:module(i) == name then n = n + 1 end end
  return n
end

describe("lsys.ui.form", function ()
  local function items ()
    local log = {}
    local vals = { n = 5, x = 0.5, b = false, c = "one" }
    local list = {
      { name = "n", kind = "number", min = 0, max = 10, step = 1, default = 5 },
      { name = "x", kind = "number", min = 0, max = 1, default = 0.5 },
      { name = "b", kind = "boolean", default = false },
      { name = "c", kind = "choice", choices = { "one", "two", "three" }, default = "one" },
    }
    for _, it in ipairs(list) do
      it.get = function () return vals[it.name] end
      it.set = function (v) vals[it.name] = v; log[#log + 1] = it.name .. "=" .. tostring(v) end
    end
    return list, vals, log
  end

  it("sets a slider where the pointer is, on its step, and drags it", function ()
    local list, vals, log = items()
    local f = form.new(list)
    local c = core.canvas(432, 736)
    f:draw(c)
    local x, y = f:point_of(1, 8, 432)
    assert.is_true(f:pointer("down", x + 0.4, y, "left"))
    assert.equal(8, vals.n)
    assert.equal(math.type(vals.n), "integer")
    local x2 = f:point_of(1, 2, 432)
    f:pointer("move", x2, y + 30, "left")          -- the drag holds the row it began on
    assert.equal(2, vals.n)
    f:pointer("move", -500, y, "left")              -- beyond the track: its end
    assert.equal(0, vals.n)
    f:pointer("up", -500, y, "left")
    f:pointer("move", x, y, "left")                 -- no drag after the release
    assert.equal(0, vals.n)
    assert.same({ "n=8", "n=2", "n=0" }, log)
    -- a number without a step lands where the pointer is
    local px, py = f:point_of(2, 0.25, 432)
    f:pointer("down", px, py, "left")
    assert.near(0.25, vals.x, 1e-9)
    f:pointer("up", px, py, "left")
  end)

  it("toggles, chooses, resets with a right click and the buttons", function ()
    local list, vals = items()
    local f = form.new(list)
    local c = core.canvas(432, 736)
    f:draw(c)
    local _, yb = f:row_rect(3, 432)
    f:pointer("down", 20, yb + 30, "left")
    assert.is_true(vals.b)
    local _, yc = f:row_rect(4, 432)
    f:pointer("down", 432 - 20, yc + 30, "left")    -- the last of three choices
    assert.equal("three", vals.c)
    f:pointer("down", 100, yc + 30, "right")        -- right click: its default
    assert.equal("one", vals.c)
    f:set(1, 9)
    f.selected = 1
    f:pointer("down", form.button_point(1, 432, 736))   -- reset
    assert.equal(5, vals.n)
    f:set(1, 9)
    f:set(2, 0.9)
    f:pointer("down", form.button_point(2, 432, 736))   -- reset all
    assert.same({ 5, 0.5, false, "one" }, { vals.n, vals.x, vals.b, vals.c })
    local saved = 0
    local g = form.new(list, { on_save = function () saved = saved + 1 return "saved x" end })
    g:draw(c)
    g:pointer("down", form.button_point(3, 432, 736))
    assert.equal(1, saved)
    assert.equal("saved x", g.message)
  end)

  it("keys: select rows, step a value, reset", function ()
    local list, vals = items()
    local f = form.new(list)
    assert.is_true(f:key("down"))
    assert.equal(1, f.selected)
    f:key("right")
    f:key("right", false, true)                      -- shift: ten steps, clamped
    assert.equal(10, vals.n)
    f:key("r", true)
    assert.equal(5, vals.n)
    f:key("down")
    f:key("left")
    assert.near(0.49, vals.x, 1e-12)                 -- a hundredth of the range
    f:key("down"); f:key("down")
    f:key("right")
    assert.equal("two", vals.c)
    f:key("left"); f:key("left")
    assert.equal("three", vals.c)                    -- round the choices
    f:key("r", true, true)
    assert.same({ 5, 0.5, false, "one" }, { vals.n, vals.x, vals.b, vals.c })
    assert.is_false(f:key("q"))
  end)

  it("draws the rows: the knob where the value is, the selection", function ()
    local list = items()
    local f = form.new(list, { title = "test" })
    local c = core.canvas(432, 736)
    f:draw(c)
    local px = c:pixels()
    local function rgb (x, y)
      local i = 4 * (math.floor(y) * 432 + math.floor(x))
      return px:byte(i + 1, i + 3)
    end
    local x, y = f:point_of(1, 5, 432)
    local r, g, b = rgb(x, y)
    assert.is_true(b > 150 and r < 100, ("knob colour %d %d %d"):format(r, g, b))
    local r2, g2, b2 = rgb(f:point_of(1, 9, 432))   -- the track beyond the knob: light grey
    assert.is_true(r2 > 180 and g2 > 180 and b2 > 180)
  end)

  it("refuses items it cannot draw, naming them", function ()
    local ok, err = pcall(form.new, { { name = "n", kind = "number", min = 1, max = 1,
                                        set = print } })
    assert.is_false(ok)
    assert.matches("item 1 %(n%): a number needs min < max", err)
    ok, err = pcall(form.new, { { name = "n", kind = "slider", set = print } })
    assert.is_false(ok)
    assert.matches("kind must be number, boolean, choice or curve, got slider", err)
    ok, err = pcall(form.new, { { name = "n", kind = "boolean" } })
    assert.is_false(ok)
    assert.matches("a set function expected", err)
  end)

  it("shows a set that raised in the pane and keeps the value", function ()
    local v = 1
    local f = form.new({ { name = "n", kind = "number", min = 0, max = 10, step = 1,
                           get = function () return v end,
                           set = function () error("model.lua:3: no thanks") end } })
    assert.is_false(f:set(1, 4))
    assert.equal(1, v)
    assert.equal("no thanks", f.message)
    assert.matches("| no thanks", f:status(), 1, true)
  end)
end)

describe("lsys.ui.tune", function ()
  it("gives a model's params as items whose set is the model's", function ()
    local m = tree()
    local items = tune.param_items(m)
    local names = {}
    for i, it in ipairs(items) do names[i] = it.name .. ":" .. it.kind end
    assert.same({ "angle:number", "k:number", "leaves:boolean", "shape:choice" }, names)
    assert.equal("levels", items[2].label)
    assert.same({ 1, 6, 1, 3 }, { items[2].min, items[2].max, items[2].step, items[2].default })
    items[2].set(5)
    assert.equal(5, m.params.k)
    assert.equal(5, items[2].get())
    assert.equal(31, count(m:derive(), "F"))          -- 2^5 - 1
  end)

  it("writes the values back into the model file where that is safe", function ()
    local d = tmpdir()
    local path = d .. "/tree.lua"
    write(path, TREE)
    local m = lsys.load and dofile(path) or dofile(path)
    m.params.k = 5
    m.params.angle = 42.5
    m.params.leaves = true
    m.params.shape = "spire"
    assert.equal(path, tune.save_params(m, path))
    local text = read(path)
    assert.matches('k = { 5, min = 1', text, 1, true)
    assert.matches('angle = { 42.5, min = 5', text, 1, true)
    assert.matches('leaves = { true }', text, 1, true)
    assert.matches('shape = { "spire", choices', text, 1, true)
    local back = dofile(path)
    assert.same({ 5, 42.5, true, "spire" },
                { back.params.k, back.params.angle, back.params.leaves, back.params.shape })
    assert.is_nil(io.open(tune.sidecar(path)))
  end)

  it("uses a sidecar when the file cannot be rewritten safely, and reads it back", function ()
    local d = tmpdir()
    local path = d .. "/made.lua"
    -- the declaration appears twice: not safe to rewrite
    write(path, TREE:gsub("k = { 3, min = 1, max = 6, step = 1, label = \"levels\" },",
                          "k = { 3, min = 1, max = 6, step = 1 }, -- k = { 3 } once more"))
    local m = dofile(path)
    m.params.k = 4
    local side = tune.save_params(m, path)
    assert.equal(d .. "/made.params", side)
    local text = read(side)
    assert.matches("'k = {' appears 2 times", text, 1, true)
    assert.matches("\nk = 4\n", text, 1, true)
    assert.matches('\nshape = "fan"\n', text, 1, true)
    local vals = tune.read_sidecar(side)
    assert.same({ angle = 30, k = 4, leaves = false, shape = "fan" }, vals)
    local fresh = dofile(path)
    assert.equal(4, tune.apply_sidecar(fresh, vals, side))
    assert.equal(4, fresh.params.k)
    write(side, "k = 4\nk = lots\n")
    local ok, err = pcall(tune.read_sidecar, side)
    assert.is_false(ok)
    assert.matches("made.params:2: a line 'NAME = value' expected", err, 1, true)
    ok, err = pcall(tune.apply_sidecar, fresh, { k = 99 }, side)
    assert.is_false(ok)
    assert.matches("made.params: params.k: 99 is outside 1 .. 6", err, 1, true)
    ok, err = pcall(tune.apply_sidecar, fresh, { zz = 1 }, side)
    assert.is_false(ok)
    assert.matches("made.params: the model has no parameter 'zz'", err, 1, true)
    assert.is_nil(tune.read_sidecar(d .. "/none.params"))
    -- strings as choices may be: quotes, backslashes, newlines and "--" kept
    write(side, table.concat({ "a = " .. tune.side_literal('say "hi" -- \\ \n'),
                               "b = \"x\" -- a note", "c = 1e999", "" }, "\n"))
    ok, err = pcall(tune.read_sidecar, side)
    assert.is_false(ok)
    assert.matches("made.params:3: a line 'NAME = value' expected", err, 1, true)
    write(side, table.concat({ "a = " .. tune.side_literal('say "hi" -- \\ \n'),
                               "b = \"x\" -- a note", "" }, "\n"))
    assert.same({ a = 'say "hi" -- \\ \n', b = "x" }, tune.read_sidecar(side))
    write(side, "")
    assert.same({}, tune.read_sidecar(side))
  end)

  it("writes literals that read back equal", function ()
    for _, v in ipairs({ 1, -3, 0.1, 1 / 3, 1e-12, 2.0, true, false, "a b" }) do
      local back = load("return " .. tune.literal(v))()
      assert.equal(v, back)
      assert.equal(math.type(v), math.type(back))
    end
    assert.is_nil((tune.rewrite("x = { y }", { x = 1 })))
    assert.equal("R = { 2, min = 1 }", tune.rewrite("R = { 1.5, min = 1 }", { R = 2 }))
    assert.equal("m.R = { 1 } R = { 3 }", tune.rewrite("m.R = { 1 } R = { 2 }", { R = 3 }))
  end)
end)

describe("vlab panels as form items", function ()
  local PANEL = table.concat({
    "panel name: Tree",
    "background: 0,0,0",
    "size: 300 200",
    "font: -*-*",
    "type: SLIDER",
    "name: Levels",
    "colors: 1 2",
    "origin: 10 10",
    "min/max: 1 6",
    "value: 3",
    "message: d LEVELS %d 1",
    "type: SLIDER",
    "name: Angle",
    "colors: 1 2",
    "origin: 10 40",
    "min/max: 50 800",
    "value: 300",
    "message: d ANGLE %d 10",
    "type: BUTTON",
    "name: Leaves",
    "colors: 1 2",
    "origin: 10 70",
    "value: 0",
    "message: d LEAVES %d 1",
    "",
  }, "\n")
  local L = table.concat({
    "#define LEVELS 3",
    "#define ANGLE 30",
    "#define LEAVES 0",
    "Lsystem: 1",
    "derivation length: 8",
    "Axiom: A(0)",
    "A(i) : i < LEVELS --> F[+(ANGLE)A(i+1)][-(ANGLE)A(i+1)]",
    "A(i) : i >= LEVELS && LEAVES --> L",
    "endlsystem",
    "",
  }, "\n")

  local function object ()
    local d = tmpdir()
    write(d .. "/panel.l", PANEL)
    write(d .. "/tree.l", L)
    return d, require("lsys.cpfg.panel").read(d .. "/panel.l")
  end

  it("gives sliders with the define they set, buttons as toggles; builds with them", function ()
    local d, P = object()
    local s = tune.panels({ l = d .. "/tree.l" }, { P }, {})
    local names = {}
    for i, it in ipairs(s.items) do names[i] = it.name .. ":" .. it.kind end
    assert.same({ "Levels:number", "Angle:number", "Leaves:boolean" }, names)
    assert.equal("(ANGLE 30)", s.items[2].note)
    s.items[2].set(455)
    assert.equal("(ANGLE 45.5)", s.items[2].note)
    local built = {}
    local function check () built[#built + 1] = true end
    local sc = s.build(check)
    assert.equal(7, count(sc.lstring, "F"))
    s.items[1].set(5)
    s.items[3].set(true)
    sc = s.build(check)
    assert.equal(31, count(sc.lstring, "F"))
    assert.equal(32, count(sc.lstring, "L"))
    assert.is_true(#built >= 8)
    -- saved as awkped writes: the #define lines get the values, the rest stays
    assert.equal(d .. "/tree.l, " .. d .. "/panel.l", s.save())
    local text = read(d .. "/tree.l")
    local back = require("lsys.cpfg.panel").read(d .. "/panel.l")
    assert.same({ 5, 455, 1 }, { back.items[1].value, back.items[2].value, back.items[3].value })
    assert.matches("\nvalue: 455\nmessage: d ANGLE %d 10\n", read(d .. "/panel.l"), 1, true)
    assert.matches("^#define LEVELS 5\n#define ANGLE 45.5\n#define LEAVES 1\nLsystem: 1\n", text)
    assert.matches("A(i) : i < LEVELS --> ", text, 1, true)
  end)

  it("sets a view file's fields from a panel that ped drives, and saves them", function ()
    local d = object()
    write(d .. "/tree.v", "line style: cylinder\ninitial line width: 2\n")
    write(d .. "/view.panel", table.concat({ "panel name: View", "type: SLIDER",
      "name: Width x 10", "origin: 0 0", "min/max: 1 50", "value: 20",
      "message: n 2 1 -1 %d", "type: BUTTON", "name: Anim", "origin: 0 0", "value: 1",
      "message: o 1 %d", "" }, "\n"))
    local panel = require "lsys.cpfg.panel"
    local VP = panel.read(d .. "/view.panel")
    local AP = panel.read(d .. "/panel.l")
    write(d .. "/one.l", "Lsystem: 1\nderivation length: 1\nAxiom: F(5)\nendlsystem\n")
    local s = tune.panels({ l = d .. "/one.l", v = d .. "/tree.v" }, {
      { panel = VP, target = d .. "/tree.v", editor = "ped" },
      { panel = AP, target = d .. "/tree.a", editor = "ped" } }, {})
    assert.equal(2, #s.items)                         -- the .a panel is not shown
    assert.matches("not shown: panel.l %(sets tree.a%)", s.note)
    assert.equal("(tree.v:2 field 1 2)", s.items[1].note)
    local function depth (sc)          -- one segment: the ribbon's width
      local lo, hi = sc:bounds()
      return hi[1] - lo[1]
    end
    local w2 = depth(s.build(function () end))
    s.items[1].set(40)
    assert.equal("(tree.v:2 field 1 4)", s.items[1].note)
    local w4 = depth(s.build(function () end))
    assert.near(2, w2, 1e-6)
    assert.near(4, w4, 1e-6)
    assert.matches("tree.v", s.save(), 1, true)
    assert.equal("line style: cylinder\ninitial line width: 4\n", read(d .. "/tree.v"))
  end)

  it("loads a cpfg model with edits (a #define in the file loses to them)", function ()
    local d = object()
    for _, how in ipairs({ "builtin", "system" }) do
      if how == "builtin" or os.execute("command -v cpp >/dev/null 2>&1") then
        local m = lsys.cpfg.load(d .. "/tree.l", nil, { cpp = how, edits = { LEVELS = 2 } })
        assert.equal(3, count(m:derive(), "F"), how)
        m = lsys.cpfg.load(d .. "/tree.l", nil, { cpp = how, defines = { LEVELS = 2 } })
        assert.equal(7, count(m:derive(), "F"), how)      -- cpp's -D: the file's wins
      end
    end
    local ok, err = pcall(lsys.cpfg.load, d .. "/tree.l", nil, { edits = 3 })
    assert.is_false(ok)
    assert.matches("option 'edits' must be a table", err)
  end)
end)

describe("lsys.ui.edit", function ()
  -- a stand-in for the window: it records what the session posts
  local function window ()
    local w = { images = {}, texts = {} }
    function w:layout (lay) self.lay = lay end
    function w:image (k, px, iw, ih) self.images[k] = { #px, iw, ih } end
    function w:text (st, help) self.texts[#self.texts + 1] = st; self.help = help end
    return w
  end

  it("builds the plant again after an edit, from the params, and reports it", function ()
    local m = tree()
    local w = window()
    local posted = {}
    local s = edit.session(w, tune.params(m), {
      post = function (sc) posted[#posted + 1] = sc end })
    assert.equal(2, #w.lay.panes)
    assert.same({ 432 * 36 * 4, 432, 36 }, w.images[1])
    assert.same({ 432 * 736 * 4, 432, 736 }, w.images[2])
    s:changed()
    assert.is_true(s:idle())
    assert.equal(7, count(posted[1].lstring, "F"))
    assert.is_false(s:idle())                        -- nothing changed since
    -- a slider of the form: the model's value, the plant built again
    local f = s.form
    local x, y = f:point_of(2, 5, 432)                -- k is row 2 (angle, k, leaves, shape)
    s:event({ type = "pointer", pane = 2, phase = "down", x = x, y = y, button = "left" })
    s:event({ type = "pointer", pane = 2, phase = "up", x = x, y = y, button = "left" })
    assert.equal(5, m.params.k)
    assert.is_true(s.dirty)
    assert.is_true(s:idle())
    assert.equal(31, count(posted[2].lstring, "F"))
    assert.matches("k 5", w.texts[#w.texts], 1, true)
    assert.matches("modules", w.texts[#w.texts], 1, true)
    -- from a script (the REPL): m.params.k = 2 makes the plant again in the next idle
    m.params.k = 2
    assert.is_true(s:idle())
    assert.equal(3, count(posted[3].lstring, "F"))
    -- Ctrl+Z: the value before the last edit made in the pane
    s:event({ type = "key", key = "z", ctrl = true })
    assert.equal(3, m.params.k)
    s:idle()
    s:stop()
    m.params.k = 4                                   -- a stopped session hears nothing
    assert.is_false(s.dirty)
  end)

  it("abandons a build when a newer value comes meanwhile, and builds the newest", function ()
    local m = tree()
    local w = window()
    local posted = {}
    local polls = 0
    local s
    s = edit.session(w, tune.params(m), {
      post = function (sc) posted[#posted + 1] = sc end,
      poll = function ()            -- the window's events while building: a newer value
        polls = polls + 1
        if polls == 2 then m.params.k = 6 end
        return true
      end,
    })
    m.params.k = 4
    assert.is_true(s:idle())
    assert.equal(1, #posted)                        -- the value 4 was never posted
    assert.equal(63, count(posted[1].lstring, "F"))
    assert.same({ 1, 1 }, { s.superseded, s.builds })
  end)

  it("stops building when the window closes while building", function ()
    local m = tree()
    local posted = 0
    local s = edit.session(window(), tune.params(m), {
      post = function () posted = posted + 1 end, poll = function () return false end })
    s:changed()
    assert.is_false(s:idle())
    assert.equal(0, posted)
  end)

  it("keeps the last plant and says why when a build fails", function ()
    local m = tree()
    local w = window()
    local subject = tune.params(m)
    local build = subject.build
    local fail = false
    subject.build = function (check)
      if fail then error("./lua/lsys/model.lua:9: plant.lua:7: the rule broke", 0) end
      return build(check)
    end
    local posted = 0
    local s = edit.session(w, subject, { post = function () posted = posted + 1 end })
    s:changed()
    s:idle()
    fail = true
    m.params.k = 2
    assert.is_false(s:idle())
    assert.equal(1, posted)
    assert.equal("plant.lua:7: the rule broke", s.error)
    assert.matches("error: plant.lua:7: the rule broke", w.texts[#w.texts], 1, true)
  end)

  it("switches panes with the tabs and Tab, and saves with Ctrl+S", function ()
    local m = tree()
    local w = window()
    local saved = {}
    local other = {
      name = "other", draw = function (_, c) c:clear({ 1, 1, 1, 1 }) end,
      pointer = function () return true end, status = function () return "other pane" end,
      save = function () saved[#saved + 1] = "other"; return { "x.func" } end,
    }
    local subject = tune.params(m)
    subject.panes = { other }
    subject.save = function () saved[#saved + 1] = "params"; return "tree.lua" end
    local outs = {}
    local s = edit.session(w, subject, { out = function (x) outs[#outs + 1] = x end })
    assert.equal(1, s.active)
    assert.is_true(s:event({ type = "pointer", pane = 1, phase = "down", x = 400, y = 10 }))
    assert.equal(2, s.active)
    s:draw()
    assert.matches("^other pane", w.texts[#w.texts])
    assert.is_true(s:event({ type = "key", key = "tab" }))
    assert.equal(1, s.active)
    s:event({ type = "key", key = "s", ctrl = true })
    assert.same({ "params", "other" }, saved)
    assert.same({ "saved tree.lua; x.func\n" }, outs)
    assert.matches("Ctrl+S: save", w.help, 1, true)
  end)

  it("edits a component graph: a box clicked, its parameter set, the plant expanded", function ()
    local C = lsys.components
    local leaf = C.leaf { name = "leaf", length = 0.3, width = 0.15 }
    local whorl = C.hydra { name = "whorl", n = 3, angle = 60 }
    whorl:child(leaf)
    local stem = C.tree { name = "stem", length = 2, n = 6, angle = { 60, 30 }, segments = 4 }
    stem:branch(whorl)
    local m = C.model(stem)
    local w = window()
    local posted = {}
    local d = tmpdir()
    local subject = tune.graph(m, { file = d .. "/plant.lua" })
    local s = edit.session(w, subject, { post = function (sc) posted[#posted + 1] = sc end })
    assert.equal("graph", s.tabs[1].name)
    assert.equal(3, #w.lay.panes)                   -- the graph over its values
    assert.same({ 432 * 400 * 4, 432, 400 }, w.images[2])
    s:changed()
    s:idle()
    local t0 = posted[1].ntriangles
    -- a click on the whorl's box selects it; its values come into the form below
    s:draw()
    local g = s.tabs[1]
    local bx, by, bw, bh = g:box("whorl")
    local cx, cy = bx + bw / 2, by + bh / 2
    s:event({ type = "pointer", pane = 2, phase = "down", x = cx, y = cy, button = "left" })
    s:event({ type = "pointer", pane = 2, phase = "up", x = cx, y = cy, button = "left" })
    assert.equal(whorl, g:selected())
    s:draw()
    local f = s.itemform
    local row
    for i, it in ipairs(f.items) do if it.name == "n" then row = i end end
    assert.truthy(row, "no item n")
    local x, y = f:point_of(row, 5, 432)
    s:event({ type = "pointer", pane = 3, phase = "down", x = x, y = y, button = "left" })
    s:event({ type = "pointer", pane = 3, phase = "up", x = x, y = y, button = "left" })
    assert.equal(5, whorl.params.n)
    assert.is_true(s:idle())
    -- 6 whorls of 5 leaves for 6 of 3: the leaves' triangles grow by 6 * 2 leaves' worth
    local per = (t0 - C.model(C.tree { name = "stem", length = 2, n = 6, angle = { 60, 30 },
                                       segments = 4 }):interpret().ntriangles) / 18
    assert.near(t0 + 12 * per, posted[2].ntriangles, 0.5)
    -- a click on the plant: the component whose instance drew the module is selected
    local cm = subject.model.components
    local k
    for i = 1, #cm.lstring do
      local inst = cm.instance(i)
      if inst and inst.proto == leaf then k = i break end
    end
    assert.truthy(k, "no module drawn by a leaf")
    assert.is_true(s:event({ type = "pick", info = { module = k, lstring = cm.lstring,
                                                     instance = cm.instance(k) } }))
    assert.equal(leaf, g:selected())
    -- Ctrl+S: the edited graph as a model file beside the model's, which loads back
    s:event({ type = "key", key = "s", ctrl = true })
    local back = dofile(d .. "/plant-edited.lua")
    back = require("lsys.load").tomodel(back)
    assert.equal(posted[2].ntriangles, back:interpret().ntriangles)
  end)

  it("maps pane pixels to the window as the panes are laid out", function ()
    local x, y = edit.to_window(2, 0, 0, 1200, 800)
    assert.near(768, x, 1)
    assert.near(36, y, 1)
    local x2, y2 = edit.to_window(2, 432, 736, 1200, 800)
    assert.near(1200, x2, 1)
    assert.near(772, y2, 1)
  end)
end)

