-- lsys.cpfg.panel: vlab's control panel files read item by item, their messages applied as
-- vlab's awkped and ped apply them, and a vlab object's panel driving its model's #defines.
require "tests.helper"
local panel = require "lsys.cpfg.panel"
local have_core, lsys = pcall(require, "lsys")

local function write (text, ext)
  local path = os.tmpname() .. (ext or ".l")
  local f = assert(io.open(path, "wb"))
  f:write(text)
  f:close()
  return path
end

local function read (text)
  local path = write(text)
  local ok, r = pcall(panel.read, path)
  os.remove(path)
  if not ok then error(r, 0) end
  return r, path
end

local function two (a, b) return { a, b } end

local function fails (text, want)
  local path = write(text)
  local ok, err = pcall(panel.read, path)
  os.remove(path)
  assert.is_false(ok)
  assert.equal(path .. want, err)
end

local ALL = table.concat({
  "target: Lsystem",
  "panel name: Test panel",
  "background: 0,0,0",
  "size: 300 200",
  "font: Arial,14,-1,5,50,0,0,0,0,0",
  "",
  "type: PAGE",
  "name: One",
  "color: 255,255,255",
  "origin: 60 180",
  "message: d NOTHING %d 1",
  "",
  "type: SLIDER",
  "name: Count",
  "colors: 255,255,255 255,0,0",
  "origin: 10 20",
  "min/max: -20 200",
  "value: 75",
  "message: d COUNT %d 100",
  "",
  "type: BUTTON",
  "name: Yes",
  "tricolor: 255,255,255 0,0,255 0,0,0",
  "origin: 30 80",
  "value: 1",
  "message: d GRID 1 1",
  "",
  "type: BUTTON",
  "name: No",
  "colors: 255,255,255 0,0,255",
  "origin: 30 110",
  "value: 0",
  "message: d GRID 0 1",
  "",
  "type: GROUP",
  "color: 255,255,255",
  "Yes",
  "No",
  "ENDGROUP",
  "",
  "type: LABEL",
  "name: Grid",
  "color: 255,255,0",
  "origin: 60 140",
  "",
  "type: MENU",
  "name: Menu",
  "message: d <name> %d <scale>",
  "",
  "type: SLIDER",
  "name: Stretch",
  "colors: 255,255,255 255,0,0",
  "origin: 10 50",
  "min/max: 0 100",
  "value: 16",
  "message: n 14 7 -1 %d",
  "",
}, "\n")

describe("lsys.cpfg.panel.read", function ()
  it("reads every item kind with its fields", function ()
    local P = read(ALL)
    assert.equal("Lsystem", P.target)
    assert.equal("Test panel", P.name)
    assert.same({ 0, 0, 0 }, P.background)
    assert.same({ 300, 200 }, P.size)
    assert.equal("Arial,14,-1,5,50,0,0,0,0,0", P.font)
    local types = {}
    for i, it in ipairs(P.items) do types[i] = it.type end
    assert.same({ "PAGE", "SLIDER", "BUTTON", "BUTTON", "GROUP", "LABEL", "MENU", "SLIDER" },
                types)
    local pg, s, yes, no, g, l, m, n = table.unpack(P.items)
    assert.same({ type = "PAGE", line = 7, name = "One", colors = { { 255, 255, 255 } },
                  origin = { 60, 180 },
                  message = { text = "d NOTHING %d 1", kind = "d", define = "NOTHING",
                              format = "%d", scale = 1, scaletext = "1" } }, pg)
    assert.equal("Count", s.name)
    assert.equal(13, s.line)
    assert.equal("One", s.page)
    assert.same({ { 255, 255, 255 }, { 255, 0, 0 } }, s.colors)
    assert.same({ 10, 20 }, s.origin)
    assert.same({ -20, 200, 75, 75 }, { s.min, s.max, s.value, s.default })
    assert.same({ "d", "COUNT", "%d", 100 },
                { s.message.kind, s.message.define, s.message.format, s.message.scale })
    assert.is_true(yes.tricolor)
    assert.same({ { 255, 255, 255 }, { 0, 0, 255 }, { 0, 0, 0 } }, yes.colors)
    assert.same({ 1, 0 }, { yes.value, no.value })
    assert.same({ "Yes", "No" }, g.buttons)
    assert.equal(g, yes.group)
    assert.equal(g, no.group)
    assert.same({ { 255, 255, 255 } }, g.colors)
    assert.same({ "LABEL", "Grid", { 60, 140 } }, { l.type, l.name, l.origin })
    assert.same({ "MENU", "Menu", "d", "<name>" }, { m.type, m.name, m.message.kind,
                                                      m.message.define })
    assert.same({ "n", 14, 7, -1, "%d" }, { n.message.kind, n.message.line, n.message.field,
                                            n.message.scale, n.message.format })
  end)

  it("reads the older format: panel name first, colour indices", function ()
    local P = read("panel name: Old\nsize: 100 90\ntype: SLIDER\nname: a b\ncolors: 3 4\n"
                   .. "origin: 1 2\nmin/max: 0 10\nvalue: 12\nmessage: 4 2 %d 100\n")
    assert.is_nil(P.target)
    assert.equal("Old", P.name)
    local s = P.items[1]
    assert.same({ 3, 4 }, s.colors)
    assert.equal("a b", s.name)
    assert.same({ 10, 12 }, { s.value, s.default })      -- clamped to max, as the panel does
    assert.same({ "line", 4, 2, "%d", 100 }, { s.message.kind, s.message.line,
                                               s.message.field, s.message.format,
                                               s.message.scale })
  end)

  it("raises file:line errors for bad input", function ()
    fails("target: Lsystem\n\ntype: KNOB\n", ":3: unknown item type 'KNOB'")
    fails("target: Lsystem\n\ntype: SLIDER\nname: a\norigin: 1 2\nvalue: 3\nmessage: x\n",
          ":3: the SLIDER has no 'min/max:'")
    fails("target: Lsystem\ntype: SLIDER\nname: a\norigin: 1\n",
          ":4: 2 numbers expected for origin")
    fails("target: Lsystem\ntype: SLIDER\nname: a\nmin/max: 5 1\n", ":4: min 5 is above max 1")
    fails("target: Lsystem\ntype: LABEL\nname: a\ncolor: red\n",
          ":4: a colour 'r,g,b' or a colour index expected, not 'red'")
    fails("target: Lsystem\ntype: LABEL\nname: a\nvalue: 3\n",
          ":4: unknown field 'value' in a LABEL")
    fails("target: Lsystem\ntype: GROUP\nA\n", ":2: the GROUP has no ENDGROUP")
    fails("target: Lsystem\ntype: GROUP\nA\nENDGROUP\n", ":2: the GROUP names no button 'A'")
    fails("target: Lsystem\nwhat is this\n", ":2: 'keyword: value' expected, not 'what is this'")
    fails("panel name: a\ntarget: Lsystem\n", ":2: 'target:' must be the first line")
    fails("", ": not a panel file (no 'target:', 'panel name:' nor items)")
    local ok, err = pcall(panel.read, "/nonexistent/panel.l")
    assert.is_false(ok)
    assert.matches("^/nonexistent/panel.l: ", err)
  end)
end)

describe("lsys.cpfg.panel.apply", function ()
  local P = read(ALL)
  local _, s, yes, no, _, l, m, n = table.unpack(P.items)

  it("divides a define's value by the message's scale, as awkped does", function ()
    assert.same({ "COUNT", 0.75 }, two(panel.apply(P, s)))
    assert.same({ "COUNT", 2 }, two(panel.apply(P, s, 200)))
    assert.same({ "COUNT", -0.2 }, two(panel.apply(P, s, -20)))
    -- clamped to the slider's min/max
    assert.same({ "COUNT", 2 }, two(panel.apply(P, s, 500)))
    local _, _, out = panel.apply(P, s, 42)
    assert.equal("d COUNT 42 100", out.text)
    assert.equal(math.type(select(2, panel.apply(P, s, 100))), "integer")
  end)

  it("gives a button's constant message whatever its value", function ()
    assert.same({ "GRID", 1 }, two(panel.apply(P, yes)))
    assert.same({ "GRID", 0 }, two(panel.apply(P, no)))
  end)

  it("multiplies by 10^scale for line and field edits", function ()
    local name, v, out = panel.apply(P, n, 16)
    assert.is_nil(name)
    assert.near(1.6, v, 1e-12)
    assert.same({ "n", 14, 7, "n 14 7 -1 16" }, { out.kind, out.line, out.field, out.text })
  end)

  it("refuses items without a message, non-numeric scales and a scale of 0", function ()
    local ok, err = pcall(panel.apply, P, l)
    assert.is_false(ok)
    assert.equal(P.path .. ":41: the LABEL has no message lsys can apply", err)
    ok, err = pcall(panel.apply, P, m)
    assert.is_false(ok)
    assert.equal(P.path .. ":46: the scale '<scale>' is not a number", err)
    local Z = read("target: Lsystem\ntype: SLIDER\nname: z\norigin: 0 0\nmin/max: 0 9\n"
                   .. "value: 1\nmessage: d Z %d 0\n")
    ok, err = pcall(panel.apply, Z, Z.items[1])
    assert.is_false(ok)
    assert.equal(Z.path .. ":2: the message divides by a scale of 0", err)
  end)
end)

describe("lsys.cpfg.panel.defines", function ()
  it("gives the sliders' defines and the group's button that is on", function ()
    local P = read(ALL)
    assert.same({ COUNT = 0.75, GRID = 1 }, panel.defines(P))
    P.items[3].value, P.items[4].value = 0, 1
    P.items[2].value = 150
    assert.same({ COUNT = 1.5, GRID = 0 }, panel.defines(P))
  end)

  it("rewrites #define lines as awkped does", function ()
    local text = "#define COUNT 3 /* how many */\n#define  GRID\t0\n#define OTHER 1\nA\n"
    local out, n = panel.edit(text, { COUNT = 0.75, GRID = 1 })
    assert.equal("#define COUNT 0.75 /* how many */\n#define GRID 1\n#define OTHER 1\nA\n",
                 out)
    assert.equal(2, n)
    assert.equal("0.333333", panel.number(1 / 3))
    assert.equal("12", panel.number(12.0))
  end)
end)

describe("lsys.cpfg.panel.edit_lines", function ()
  it("sets a line's field as awkped counts fields (awk's $F) and as ped counts them", function ()
    local text = "scale factor: 0.9\ntexture: F: a.png E: m R: 0.5 H: l\nz buffer: on\n"
    local out, n = panel.edit_lines(text, { { line = 2, field = 7, value = 1.5 } })
    assert.equal("scale factor: 0.9\ntexture: F: a.png E: m R: 1.5 H: l\nz buffer: on\n", out)
    assert.equal(1, n)
    out = panel.edit_lines(text, { { line = 1, field = 1, value = 2 } }, "ped")
    assert.equal("scale factor: 2\n", out:match("^[^\n]*\n"))
    out = panel.edit_lines(text, { { line = 3, on = false } })
    assert.matches("\nz buffer: off\n$", out)
    -- a line or field the text does not have: nothing changes
    local same, k = panel.edit_lines(text, { { line = 9, field = 1, value = 1 },
                                             { line = 1, field = 7, value = 1 } })
    assert.same({ text, 0 }, { same, k })
  end)

  it("gives the line edits of a panel's n, o and older messages", function ()
    local P = read("target: Lsystem\n\ntype: SLIDER\nname: s\norigin: 0 0\nmin/max: 0 99\n"
      .. "value: 25\nmessage: n 12 7 -1 %d\n\ntype: BUTTON\nname: z\norigin: 0 0\n"
      .. "value: 1\nmessage: o 3 %d\n\ntype: SLIDER\nname: t\norigin: 0 0\n"
      .. "min/max: 0 9\nvalue: 3\nmessage: d T %d 1\n")
    assert.same({ { line = 12, field = 7, value = 2.5 }, { line = 3, on = true } },
                panel.line_edits(P))
    -- a line that is not a number is no line edit (the fuzzer's: `o LABEL3 %d`)
    local Q = read("target: Lsystem\n\ntype: BUTTON\nname: Sw\norigin: 0 0\nvalue: 0\n"
                   .. "message: o LABEL3 %d\n")
    assert.is_nil(Q.items[1].message.kind)
    assert.same({}, panel.line_edits(Q))
  end)
end)

describe("lsys.cpfg.panel.find", function ()
  -- vlab's oofs/ext folder: LSYS_VLAB_EXT, or a vlab checkout beside the repository
  local EXT = os.getenv("LSYS_VLAB_EXT") or "../vlab/oofs/ext"
  if EXT:sub(1, 1) ~= "/" then                  -- absolute: the edited copy is elsewhere
    local pwd = io.popen("pwd")
    EXT = pwd:read("l") .. "/" .. EXT
    pwd:close()
  end
  local VLAB = EXT .. "/10-manuals/ext/10-GettingStarted/ext/01-Lychnis"
  local have_vlab = io.open(VLAB .. "/plant.l") ~= nil

  it("finds a vlab object's panel and its target from its specifications", function ()
    if not have_vlab then return pending("no vlab objects at " .. EXT .. " (set LSYS_VLAB_EXT)") end
    assert.same({ { panel = VLAB .. "/panel.l", target = VLAB .. "/plant.l",
                    editor = "awkped" } }, panel.find(VLAB))
  end)

  it("drives vlab's Lychnis model through its panel's defines", function ()
    if not have_vlab then return pending("no vlab objects at " .. EXT .. " (set LSYS_VLAB_EXT)") end
    if not have_core then return pending("lsys.core is not built") end
    local P = panel.read(VLAB .. "/panel.l")
    local d = panel.defines(P)
    assert.same({ 300, 45, 1, 40, 4, 7, 20, 10, 30, 30, 1, 5, 11, 10, 1, 2, 90, 0.05 },
                { d.STEPS, d.VANG, d.S0, d.ANG, d.D1, d.D2, d.LEN1, d.LEN2, d.LENLEAF,
                  d.LENBR, d.T1, d.T2, d.T3, d.T4, d.LEAFSCALE, d.PETALSCALE, d.PHYLLOTAXY,
                  d.TROPISM })
    local f = assert(io.open(VLAB .. "/plant.l"))
    local text = f:read("a")
    f:close()
    local steps
    for _, it in ipairs(P.items) do if it.name == "Steps" then steps = it end end
    local function derive (value)
      steps.value = value
      local edited, changed = panel.edit(text, panel.defines(P))
      assert.equal(18, changed)
      local path = write(edited)
      local ok, m = pcall(lsys.cpfg.load, path, VLAB .. "/plant.v",
                          { materials = VLAB .. "/material.mat" })
      os.remove(path)
      assert(ok, m)
      return m, m:derive()
    end
    local m300, s300 = derive(300)          -- the panel's default: the file as it is
    local m40, s40 = derive(40)
    assert.same({ 300, 40 }, { m300.steps, m40.steps })
    assert.equal(1370, #s300)
    assert.equal(26, #s40)
    steps.value = 300
  end)

  it("opens every cpfg object of vlab's with a panel, as lsys view does, and builds it", function ()
    if not have_vlab then return pending("no vlab objects at " .. EXT .. " (set LSYS_VLAB_EXT)") end
    if not have_core then return pending("lsys.core is not built") end
    local tune = require "lsys.ui.tune"
    local p = io.popen("cd '" .. EXT .. "' && grep -rl '^[[:space:]]*panel ' "
                       .. "--include=specifications . | sort")
    local opened, lpfg, names = 0, 0, {}
    for spec in p:lines() do
      local dir = EXT .. "/" .. spec:gsub("^%./", ""):gsub("/specifications$", "")
      local l, v, pal = lsys.cpfg.object_files(dir)
      local f = io.open(l)
      local head = f:read("a")
      f:close()
      if head:find("lpfgall.h", 1, true) then           -- an lpfg model, not cpfg's
        lpfg = lpfg + 1
      else
        local panels = {}
        for _, x in ipairs(panel.find(dir)) do
          panels[#panels + 1] = { panel = panel.read(x.panel), target = x.target or l,
                                  editor = x.editor }
        end
        local lo = {}
        if pal then lo[pal:match("%.mat$") and "materials" or "colormap"] = pal end
        local m = lsys.cpfg.load(l, v, lo)
        local s = tune.panels({ l = l, v = v }, panels, { load = lo, model = m })
        local sc = s.build(function () end)
        assert.is_true(#sc.lstring > 0, dir)
        opened = opened + 1
        names[#names + 1] = dir:match("([^/]*)$")
      end
    end
    p:close()
    assert.is_true(opened >= 17, table.concat(names, ", "))
    assert.equal(1, lpfg)
  end)
end)
