-- (#gl) Editing a plant in the real window under a private Xvfb, with xdotool: a slider
-- of a Lua model's params dragged (the plant built again: its module count checked against
-- the same model derived here), the values saved into the model file and loaded back; a
-- vlab object's panel slider moved; a script's m.params.k = v reaching an open window.
-- ctest: slow (drives the window under Xvfb with waits)
local H = require "tests.helper"
local D = require "tests.display"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local have_core = pcall(require, "lsys.core")

local TREE = [[
local lsys = require "lsys"
local m = lsys.lsystem {
  axiom = "A(0)",
  steps = 8,
  params = {
    k = { 3, min = 1, max = 7, step = 1, label = "levels" },
    angle = { 30, min = 5, max = 80 },
  },
  productions = { "A(i) : i < k --> F [ +(angle) A(i+1) ] [ -(angle) A(i+1) ]" },
}
-- a script reacting to the sliders
m:on_param(function (name, v) io.stderr:write("param ", name, " = ", tostring(v), "\n") end)
return m
]]

local function bin ()
  local b = os.getenv("LSYS_BIN") or "build/bin/lsys"
  if b:sub(1, 1) ~= "/" then b = io.popen("pwd"):read("l") .. "/" .. b end
  return b
end

-- The window of `name` (xdotool's id), waiting for it to open.
local function window (name, log)
  local p = io.popen(D.env .. "timeout " .. 30 * SLOW .. " xdotool search --sync --name '"
                     .. name .. "' 2>/dev/null")
  local wid = p:read("l")
  p:close()
  assert.truthy(wid, "the window did not open: " .. tostring(H.read(log)))
  return wid
end

-- A drag in window pixels along the points.
local function drag (wid, pts)
  local cmd = { D.env .. "xdotool" }
  for i, p in ipairs(pts) do
    cmd[#cmd + 1] = ("mousemove --window %s %d %d"):format(wid, math.floor(p[1] + 0.5),
                                                          math.floor(p[2] + 0.5))
    if i == 1 then cmd[#cmd + 1] = "mousedown 1" end
  end
  cmd[#cmd + 1] = "mouseup 1"
  local out, code = H.sh(table.concat(cmd, " ") .. " 2>&1")
  assert(code == 0, "xdotool: " .. tostring(out) .. " (window " .. wid .. ")")
end

-- (typed through XTEST with the pointer over the window, which has the focus then: the
-- key sent to the window with --window, XSendEvent, failed here with BadWindow)
local function key (wid, k)
  local out, code = H.sh(D.env .. "xdotool mousemove --window " .. wid .. " 300 300 key " .. k)
  assert(code == 0, "xdotool key " .. k .. ": " .. tostring(out) .. " (window " .. wid .. ")")
end

-- The last "built ...: N modules" line of the log: the values and N.
local function last_built (log)
  local vals, n
  for line in (H.read(log) or ""):gmatch("[^\n]+") do
    local v, m = line:match("^built (.-): (%d+) modules")
    if v then vals, n = v, tonumber(m) end
  end
  return vals, n
end

-- Waits until the log's last build says `pattern` about its values.
local function wait_built (log, pattern, seconds)
  for _ = 1, 10 * (seconds or 20) * SLOW do
    local v = last_built(log)
    if v and v:find(pattern) then return true end
    D.sleep(0.1)
  end
  return false
end

-- A display with xdotool and the core built; else the test is pending, saying which.
local function ready ()
  local ok, why = D.start()
  if not ok then pending(why) return false end
  if not D.have("xdotool") then
    pending("xdotool is not installed (./setup.sh does)")
    return false
  end
  if not have_core then pending("lsys.core is not built") return false end
  return true
end

describe("#gl editing in the window under Xvfb", function ()
  teardown(function () D.stop() end)

  it("drags a params slider, builds the plant again, saves the value into the file", function ()
    if not ready() then return end
    local form = require "lsys.ui.form"
    local edit = require "lsys.ui.edit"
    local dir = H.tmpdir()
    local path = dir .. "/tree.lua"
    H.write(path, TREE)
    local log = dir .. "/log.txt"
    os.execute(("cd %s && %s%s view %s --size 1200x800 >%s 2>&1 &"):format(dir, D.env, bin(),
               path, log))
    local wid = window("lsys: tree.lua", log)
    assert.is_true(wait_built(log, "k 3"), H.read(log))
    -- the slider of k (the form's row 2: angle, k), from its value 3 to 6
    local f = form.new(require("lsys.ui.tune").param_items(dofile(path)))
    local function at (v)
      local x, y = f:point_of(2, v, edit.PANE_W)
      return { edit.to_window(2, x, y, 1200, 800) }
    end
    drag(wid, { at(3), at(4), at(5), at(6) })
    assert.is_true(wait_built(log, "k 6"), H.read(log))
    local vals, n = last_built(log)
    local m = dofile(path)
    m.params.k = 6
    assert.equal(#m:derive(), n, vals)                 -- 63 F, their brackets, 64 A
    assert.equal(63 + 63 * 2 * 2 + 64 + 63 * 2, n)
    -- the model's on_param callback heard the slider
    assert.truthy(H.read(log):find("param k = 6", 1, true), H.read(log))
    -- Ctrl+S writes the value into the model file, which is loaded again
    key(wid, "ctrl+s")
    local out = D.wait_for(log, "reloaded", 20 * SLOW)
    assert.truthy(out:find("saved " .. path, 1, true), out)
    assert.equal(6, dofile(path).params.k)
    assert.truthy(H.read(path):find("k = { 6, min = 1", 1, true))
    -- the reset button: k back to its default (now 6, the saved value) after a change
    key(wid, "Right")                                  -- the selected row: a step up
    assert.is_true(wait_built(log, "k 7"), H.read(log))
    key(wid, "Escape")
    D.sleep(0.5 * SLOW)
  end)

  -- Opens the vlab object `src` (copied: saving writes it) and drags its panel's first
  -- slider (Steps) from `from` to `to`; the plant built must be the model's with that many
  -- steps, loaded here as the window loads it.
  local function panel_drag (src, from, to, first_count)
    local lsys = require "lsys"
    local panel = require "lsys.cpfg.panel"
    local form = require "lsys.ui.form"
    local edit = require "lsys.ui.edit"
    local tune = require "lsys.ui.tune"
    local dir = H.tmpdir()
    local name = src:match("([^/]*)$")
    assert(os.execute(("cp -r '%s' '%s/%s'"):format(src, dir, name)))
    local obj = dir .. "/" .. name
    local log = dir .. "/log.txt"
    os.execute(("cd %s && %s%s view %s --size 1200x800 >%s 2>&1 &"):format(dir, D.env, bin(),
               obj, log))
    local wid = window("lsys: " .. name, log)
    assert.is_true(wait_built(log, "Steps " .. from), H.read(log))
    local _, n0 = last_built(log)
    assert.equal(first_count, n0)
    local P = panel.read(obj .. "/panel.l")
    local f = form.new(tune.panels({ l = obj .. "/plant.l" }, { P }, {}).items)
    local function at (v)
      local x, y = f:point_of(1, v, edit.PANE_W)        -- Steps, the panel's first slider
      return { edit.to_window(2, x, y, 1200, 800) }
    end
    drag(wid, { at(from), at((from + to) / 2), at(to) })
    local vals, n, steps                              -- within a pixel of the window's
    for _ = 1, 200 * SLOW do
      vals, n = last_built(log)
      steps = tonumber(vals:match("^Steps (%d+)"))
      if math.abs(steps - to) <= 1 then break end
      D.sleep(0.1)
    end
    assert.is_true(math.abs(steps - to) <= 1, vals)
    local l, v, pal = lsys.cpfg.object_files(obj)
    local m = lsys.cpfg.load(l, v, { materials = pal and obj .. "/" .. pal,
                                     edits = { STEPS = steps } })
    assert.equal(#m:derive(), n, vals)
    key(wid, "Escape")
    D.sleep(0.5 * SLOW)
    return n
  end

  it("opens a vlab object with its panel and moves a slider", function ()
    if not ready() then return end
    local n = panel_drag(H.absolute("examples/vlab/tunable-tree"), 7, 4, 13119)
    assert.is_true(n < 13119)
  end)

  it("opens vlab's Lychnis with its panel and moves its Steps slider", function ()
    if not ready() then return end
    local EXT = os.getenv("LSYS_VLAB_EXT") or "../vlab/oofs/ext"
    local src = EXT .. "/10-manuals/ext/10-GettingStarted/ext/01-Lychnis"
    if io.open(src .. "/plant.l") == nil then
      pending("no vlab objects at " .. EXT .. " (set LSYS_VLAB_EXT)")
      return
    end
    local n = panel_drag(H.absolute(src), 300, 40, 1370)
    assert.is_true(n < 200)
  end)

  it("drags a curve's control points: the function, the plant and the saved file", function ()
    if not ready() then return end
    local func = require "lsys.func"
    local curve = require "lsys.ui.curve"
    local edit = require "lsys.ui.edit"
    local core = require "lsys.core"
    local dir = H.tmpdir()
    func.save(func.new { points = { { 0, 0.3 }, { 0.33, 0.3 }, { 0.66, 0.3 }, { 1, 0.3 } },
                         name = "levels" }, dir .. "/levels.func")
    H.write(dir .. "/fan.lua", [[
local lsys = require "lsys"
return lsys.lsystem {
  axiom = "A(0)", steps = 10,
  params = { angle = { 30, min = 5, max = 80 } },
  functions = { "levels.func" }, view = { dir = lsys.here() },
  productions = {
    'A(i) : i < 10 * func("levels", 0.5) --> F [ +(angle) A(i+1) ] [ -(angle) A(i+1) ]' },
}
]])
    local log = dir .. "/log.txt"
    os.execute(("cd %s && %s%s view fan.lua --size 1200x800 >%s 2>&1 &"):format(dir, D.env,
               bin(), log))
    local wid = window("lsys: fan.lua", log)
    assert.is_true(wait_built(log, "angle 30"), H.read(log))
    local _, n0 = last_built(log)
    assert.equal(7 * 7 + 8, n0)                          -- 3 levels
    key(wid, "Tab")                                      -- the curves
    -- the same pane here, driven the same way, says where the points are drawn
    local pane = curve.new(curve.targets(dofile(dir .. "/fan.lua")))
    local c = core.canvas(edit.PANE_W, edit.PANE_H)
    pane:draw(c)
    local function move (i, y)
      local x0, y0 = pane:to_pixels(i)
      local e = pane:current()
      -- the pixel of data y at the point's x: the pane's mapping, through to_pixels of a
      -- point moved there and back
      local keep = e.pts[i][2]
      e.pts[i][2] = y
      local _, y1 = pane:to_pixels(i)
      e.pts[i][2] = keep
      local pts = {}
      for k = 0, 4 do
        pts[#pts + 1] = { edit.to_window(2, x0, y0 + (y1 - y0) * k / 4, 1200, 800) }
      end
      D.sleep(0.3 * SLOW)
      drag(wid, pts)
      pane:pointer("down", x0, y0, "left")
      pane:pointer("move", x0, y1, "left")
      pane:pointer("up", x0, y1, "left")
      pane:draw(c)
    end
    move(2, 0.6)
    move(3, 0.6)
    local f = pane:current().object
    assert.is_true(f(0.5) > 0.45, "f(0.5) = " .. f(0.5))
    local levels = math.ceil(10 * f(0.5))
    local want = 7 * (2 ^ levels - 1) + 2 ^ levels
    for _ = 1, 100 * SLOW do
      local _, n = last_built(log)
      if n == want then break end
      D.sleep(0.1)
    end
    local _, n = last_built(log)
    assert.equal(want, n, H.read(log))
    key(wid, "ctrl+s")
    D.wait_for(log, "saved", 10 * SLOW)
    local back = func.load(dir .. "/levels.func")
    assert.near(f(0.5), back(0.5), 0.02)                  -- the window's drag, within a pixel
    local m = dofile(dir .. "/fan.lua")
    assert.equal(n, #m:derive())
    key(wid, "Escape")
    D.sleep(0.5 * SLOW)
  end)

  it("clicks a component graph's box and drags its parameter: the plant expanded", function ()
    if not ready() then return end
    local lsys = require "lsys"
    local form = require "lsys.ui.form"
    local edit = require "lsys.ui.edit"
    local tune = require "lsys.ui.tune"
    local core = require "lsys.core"
    local dir = H.tmpdir()
    local SRC = [[
local lsys = require "lsys"
local C = lsys.components
local leaf = C.leaf { name = "leaf", length = 0.3, width = 0.15 }
local whorl = C.hydra { name = "whorl", n = 3, angle = 60 }
whorl:child(leaf)
local stem = C.tree { name = "stem", length = 2, n = 6, angle = { 60, 30 }, segments = 4 }
stem:branch(whorl)
return C.model(stem, { name = "plant" })
]]
    H.write(dir .. "/plant.lua", SRC)
    local log = dir .. "/log.txt"
    os.execute(("cd %s && %s%s view plant.lua --size 1200x800 >%s 2>&1 &"):format(dir, D.env,
               bin(), log))
    local wid = window("lsys: plant.lua", log)
    local first = D.wait_for(log, "triangles", 20 * SLOW)
    local t0 = tonumber(first:match("(%d+) triangles"))
    assert.truthy(t0, first)
    -- the same pane here says where the whorl's box is; the form below, where n's slider
    local m = dofile(dir .. "/plant.lua")
    local subject = tune.graph(m)
    local g = subject.first
    g:draw(core.canvas(edit.PANE_W, edit.MAIN_H))
    local bx, by, bw, bh = g:box("whorl")
    local wx, wy = edit.to_window(2, bx + bw / 2, by + bh / 2, 1200, 800, true)
    D.sleep(0.3 * SLOW)
    drag(wid, { { wx, wy }, { wx, wy } })               -- a click
    local whorl
    for _, n in ipairs(require("lsys.components.graph").nodes(tune.graph_root(m))) do
      if n.p.name == "whorl" then whorl = n.p end
    end
    g:select(whorl)
    local f = form.new(g:items())
    local row
    for i, it in ipairs(f.items) do if it.name == "n" then row = i end end
    f:draw(core.canvas(edit.PANE_W, edit.ITEMS_H))
    local function at (v)
      local x, y = f:point_of(row, v, edit.PANE_W)
      return { edit.to_window(3, x, y, 1200, 800, true) }
    end
    D.sleep(0.5 * SLOW)
    drag(wid, { at(3), at(4), at(5) })
    -- the plant with 5 leaves a whorl, expanded here; the window's last build must reach
    -- it (a build for n = 4 on the way may come first)
    whorl:set("n", 5)
    local want = lsys.components.model(tune.graph_root(m)):interpret().ntriangles
    assert.is_true(want ~= t0)
    local n5
    for _ = 1, 100 * SLOW do
      local text = H.read(log) or ""
      for t in text:gmatch("(%d+) triangles") do n5 = tonumber(t) end
      if n5 == want then break end
      D.sleep(0.1)
    end
    assert.equal(want, n5, H.read(log))
    key(wid, "Escape")
    D.sleep(0.5 * SLOW)
  end)

  it("hears m.params.k = v from a script while the window is open", function ()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not have_core then pending("lsys.core is not built") return end
    local dir = H.tmpdir()
    H.write(dir .. "/tree.lua", TREE)
    H.write(dir .. "/script.lua", [[
      local lsys = require "lsys"
      local V = require "lsys.viewer"
      local m = dofile("tree.lua")
      local session = lsys.show(m, { width = 900, height = 600 })
      io.write("first ", session.stats.modules, "\n")
      m.params.k = 5                  -- as typed at the REPL, which polls while it waits
      V.poll(0)
      io.write("then ", session.stats.modules, " ", session.builds, "\n")
      V.close()
    ]])
    local out = H.sh(("cd %s && %s%s script.lua 2>&1"):format(dir, D.env, bin()))
    assert.truthy(out:find("first 57\n", 1, true), out)     -- 7 F, 14 +-, 28 brackets, 8 A
    assert.truthy(out:find("then 249 2\n", 1, true), out)
    assert.truthy(out:find("param k = 5", 1, true), out)
    -- the same typed at the REPL: it builds the plant after the line that set the value
    out = H.sh(("cd %s && printf '%%s\\n' 'm = dofile(\"tree.lua\")' "
                .. "'s = lsys.show(m, { width = 900, height = 600 })' 'm.params.k = 6' "
                .. "'print(s.stats.modules .. \" \" .. s.builds)' 'lsys.viewer.close()' "
                .. "| %s%s 2>&1"):format(dir, D.env, bin()))
    assert.truthy(out:find("\n505 2\n", 1, true) or out:find("^505 2\n"), out)
  end)
end)
