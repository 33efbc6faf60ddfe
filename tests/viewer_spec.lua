-- The viewer window (#gl): screenshots through the window, picking by real clicks
-- (xdotool), stepping and animation, the S key, `lsys view` reloading its file, and the
-- error without a display. Everything runs the lsys program on a private Xvfb
-- (tests/display.lua); without Xvfb or a display the specs are reported pending with
-- the reason.
-- ctest: slow (drives the window under Xvfb with waits)
local core = require "lsys.core"
local D = require "tests.display"
local H = require "tests.helper"

local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits

local run = H.sh

local plant, read, write, tmpdir = H.ink, H.read, H.write, H.tmpdir

-- The model file most specs show: F[+F][-F]F with 45 degree branches, as cylinders.
local MODEL = [[
local lsys = require "lsys"
return lsys.lsystem {
  name = "picks", axiom = "F[+F][-F]F", steps = %d,
  productions = "F --> F[+F]F",
  view = { angle = 45, line_style = "%s", line_width = 0.2, background = {1, 1, 1} },
}
]]

local function display ()
  local ok, why = D.start()
  if not ok then pending(why) end
  return ok
end

-- A display, xdotool and a scratch directory, or nil (the spec is then pending).
local function clicks ()
  if not display() then return nil end
  if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return nil end
  return tmpdir()
end

describe("#gl the viewer window", function()
  teardown(function() D.stop() end)

  it("takes a screenshot of an example that shows the plant as lsys render draws it",
  function()
    if not display() then return end
    local dir = tmpdir()
    local out, code = run(D.env .. BIN .. " view examples/abop/fig1_24d.lua --size 400x300 " ..
      "--no-status --screenshot " .. dir .. "/win.png")
    assert.equal(0, code, out)
    assert.truthy(out:find("wrote " .. dir .. "/win.png (400x300)", 1, true), out)
    local _, code2 = run(BIN .. " render examples/abop/fig1_24d.lua --size 400x300 -o " ..
      dir .. "/off.png")
    assert.equal(0, code2)
    local a, b = plant(dir .. "/win.png"), plant(dir .. "/off.png")
    assert.equal(400, a.w)
    assert.equal(300, a.h)
    -- not blank: the plant covers a good part of the picture
    assert.is_true(a.n > 0.02 * a.w * a.h, "plant pixels: " .. a.n)
    -- the same plant in the same place: boxes within 4 pixels, masks mostly shared
    -- (the offscreen renderer supersamples, the window does not)
    for i = 1, 4 do
      assert.is_true(math.abs(a.box[i] - b.box[i]) <= 4, table.concat(a.box, " ") .. " vs " ..
        table.concat(b.box, " "))
    end
    local both, either = 0, 0
    for i = 1, a.w * a.h do
      if a.mask[i] and b.mask[i] then both = both + 1 end
      if a.mask[i] or b.mask[i] then either = either + 1 end
    end
    assert.is_true(both / either > 0.6, "overlap " .. both / either)
    os.execute("rm -rf " .. dir)
  end)

  it("draws a 3D plant with the shadows lsys render gives it with --shadows", function()
    if not display() then return end
    local dir = tmpdir()
    -- a stem under a square, lit from the side: the square's shadow falls on the ground
    write(dir .. "/m.lua", [[
return require("lsys").lsystem {
  axiom = "F(10) &(90) f(-2) -(90) f(-2) { . f(4) . +(90) f(4) . +(90) f(4) . +(90) f(4) . }",
  view = { light = { 0.5, 1, 0.3 }, direction = { 0, -0.6, -1 } },
}]])
    local function shot (flags)
      local out, code = run(D.env .. BIN .. " view " .. dir .. "/m.lua --size 300x240 " ..
        "--no-status " .. flags .. " --screenshot " .. dir .. "/w.png")
      assert.equal(0, code, out)
      return core.png_read(dir .. "/w.png")
    end
    -- the shadow: grey pixels well darker than the lit ground's grey-green (about 205, 215,
    -- 195), neither the brown plant nor the sky
    local function shadow (px)
      local n = 0
      for i = 0, 300 * 240 - 1 do
        local r, g, b = px:byte(4 * i + 1, 4 * i + 3)
        if r + g + b < 540 and r + g + b > 300 and math.abs(r - g) < 25
           and math.abs(g - b) < 25 then n = n + 1 end
      end
      return n
    end
    local plain, shaded = shadow(shot("")), shadow(shot("--shadows"))
    assert.is_true(plain < 20, plain .. " shadow pixels without --shadows")
    assert.is_true(shaded > 200, shaded .. " shadow pixels with --shadows")
    os.execute("rm -rf " .. dir)
  end)

  it("reports the module of the segment clicked, through the turtle records", function()
    local dir = clicks()
    if not dir then return end
    write(dir .. "/picks.lua", MODEL:format(0, "cylinder"))
    -- the script clicks the middle of each segment and a point off the plant
    write(dir .. "/click.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local m = dofile(arg[1])
local events = {}
lsys.show(m, { width = 400, height = 400, title = "click test", status = false,
               on_event = function (ev) events[#events + 1] = ev end })
assert(V.sync(10 * SLOW), "no picture")
local function click (x, y)
  events = {}
  assert(os.execute(("xdotool search --name 'lsys: click test' mousemove --window %1 " ..
    x // 1 .. " " .. y // 1 .. " click 1 >/dev/null 2>&1")))
  for _ = 1, 40 * SLOW do
    V.poll(0.25)
    for _, ev in ipairs(events) do
      if ev.type == "pick" then return "pick " .. ev.module .. " " .. ev.kind end
      if ev.type == "miss" then return "miss" end
    end
  end
  return "nothing"
end
local scene = m:interpret()
for _, r in scene:records() do
  if r.kind == "segment" then
    local mid = { (r.p0[1] + r.p1[1]) / 2, (r.p0[2] + r.p1[2]) / 2, (r.p0[3] + r.p1[3]) / 2 }
    local x, y = V.project(mid)
    print(r.module, click(x, y))
  end
end
-- beside the trunk, within its radius (0.1): still the trunk
local x, y = V.project({ 0.07, 0.5, 0 })
print("edge", click(x, y))
print("corner", click(5, 5))
print("last", V.last_pick and V.last_pick.text)
V.close()
]])
    local out, code = run("cd " .. dir .. " && " .. D.env .. " " ..
      H.absolute(BIN) ..
      " click.lua picks.lua")
    assert.equal(0, code, out)
    -- F[+F][-F]F: the four F are modules 1, 4, 8 and 10
    assert.equal("1\tpick 1 segment\n4\tpick 4 segment\n8\tpick 8 segment\n" ..
      "10\tpick 10 segment\nedge\tpick 1 segment\ncorner\tmiss\nlast\tF\n", out)
    os.execute("rm -rf " .. dir)
  end)

  it("orbits, pans and zooms with the mouse; R resets, F fits, W draws wireframes", function()
    local dir = clicks()
    if not dir then return end
    write(dir .. "/m.lua", MODEL:format(2, "cylinder"))
    write(dir .. "/mouse.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local m = dofile(arg[1])
local dir = arg[2]
lsys.show(m, { width = 300, height = 300, status = false, title = "mouse test",
               view = { projection = "perspective" } })
assert(V.sync(10 * SLOW))
local function x (cmd)
  assert(os.execute("xdotool search --name 'lsys: mouse test' " .. cmd .. " >/dev/null 2>&1"))
  V.poll(0.3)
  assert(V.sync(10 * SLOW))
end
local function shot (name) V.screenshot(dir .. "/" .. name .. ".png") end
shot("home")
x("mousemove --window %1 150 150 mousedown 1 mousemove --window %1 230 120 mouseup 1")
shot("orbit")
V.key("r") assert(V.sync(10 * SLOW)) shot("reset")
x("mousemove --window %1 150 150 mousedown 3 mousemove --window %1 200 150 mouseup 3")
shot("pan")
V.key("r") assert(V.sync(10 * SLOW))
x("mousemove --window %1 150 150 click 5 click 5 click 5")
shot("zoom")
V.key("f") assert(V.sync(10 * SLOW)) shot("fit")
V.key("w") assert(V.sync(10 * SLOW)) shot("wire")
print(V.last_pick == nil and "no pick" or "pick")
V.close()
]])
    local out, code = run(D.env .. BIN .. " " .. dir .. "/mouse.lua " .. dir .. "/m.lua " .. dir)
    assert.equal(0, code, out)
    assert.equal("no pick\n", out)          -- drags are not clicks
    local function png (name) return (core.png_read(dir .. "/" .. name .. ".png")) end
    local home, reset, fit = plant(dir .. "/home.png"), png("reset"), plant(dir .. "/fit.png")
    assert.equal(png("home"), reset)          -- R: exactly the arrival camera
    assert.are_not.equal(png("home"), png("orbit"))
    -- pan: the same picture moved 50 pixels right
    local pan = plant(dir .. "/pan.png")
    assert.near(home.box[1] + 50, pan.box[1], 2)
    assert.near(home.box[2], pan.box[2], 2)
    -- zoom: three wheel steps back, the eye 1 / 0.88^3 = 1.47 times as far: the plant
    -- about 0.7 times as tall on screen
    local zoom = plant(dir .. "/zoom.png")
    local hh, zh = home.box[4] - home.box[2], zoom.box[4] - zoom.box[2]
    assert.is_true(zh > 0.55 * hh and zh < 0.8 * hh, zh .. " vs " .. hh)
    -- F: fitted again, as on arrival
    for i = 1, 4 do assert.near(home.box[i], fit.box[i], 2) end
    -- W: edges only (of thin cylinders: they cover most of what the faces did)
    local wire = plant(dir .. "/wire.png")
    assert.are_not.equal(png("fit"), png("wire"))
    assert.is_true(wire.n < 0.98 * fit.n and wire.n > 0.3 * fit.n, wire.n .. " vs " .. fit.n)
    os.execute("rm -rf " .. dir)
  end)

  it("steps back and forward and animates through the derivation", function()
    if not display() then return end
    local dir = tmpdir()
    write(dir .. "/m.lua", MODEL:format(3, "line"))
    write(dir .. "/steps.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local m = dofile(arg[1])
local dir = arg[2]
lsys.show(m, { width = 300, height = 300, rate = 20, status = false })
assert(V.sync(10 * SLOW))
local st = V.state()
print("shown", st.frame, st.nframes, st.step)
V.screenshot(dir .. "/s3.png")
V.key("left") V.key("left")
assert(V.sync(10 * SLOW))
print("back", V.state().step)
V.screenshot(dir .. "/s1.png")
V.key("home") assert(V.sync(10 * SLOW)) print("home", V.state().step)
V.key("right") assert(V.sync(10 * SLOW)) print("right", V.state().step)
V.key("space")
local t0 = os.time()
repeat V.poll(0.1) until not V.state().playing or os.time() - t0 > 10 * SLOW
print("played", V.state().step, V.state().playing)
lsys.show(m, { step = 2 }) assert(V.sync(10 * SLOW)) print("show step", V.state().step)
m.view.background = { 0, 0, 0 }          -- the view is read again at every show
lsys.show(m, { status = false })
V.screenshot(dir .. "/black.png")
V.close()
]])
    local out, code = run(D.env .. BIN .. " " .. dir .. "/steps.lua " .. dir .. "/m.lua " .. dir)
    assert.equal(0, code, out)
    assert.equal("shown\t4\t4\t3\nback\t1\nhome\t0\nright\t1\nplayed\t3\tfalse\n" ..
      "show step\t2\n", out)
    -- the camera stays: step 1 is a smaller drawing inside step 3's box
    local a, b = plant(dir .. "/s1.png"), plant(dir .. "/s3.png")
    assert.is_true(a.n > 0 and a.n < b.n / 2, a.n .. " vs " .. b.n)
    assert.is_true(a.box[2] >= b.box[2] and a.box[4] <= b.box[4] + 1)
    local px = core.png_read(dir .. "/black.png")
    assert.same({ 0, 0, 0 }, { px:byte(1, 3) })
    os.execute("rm -rf " .. dir)
  end)

  it("keeps the history within its budget: every 2nd, 4th, ... step and the last", function()
    if not display() then return end
    local dir = tmpdir()
    write(dir .. "/m.lua", MODEL:format(7, "line"))
    write(dir .. "/hist.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
local m = dofile(arg[1])
local function steps ()
  assert(V.sync(10 * SLOW))
  V.key("home") assert(V.sync(10 * SLOW))
  local l = { V.state().step }
  for _ = 2, V.state().nframes do
    V.key("right") assert(V.sync(10 * SLOW))
    l[#l + 1] = V.state().step
  end
  return table.concat(l, " ")
end
warn("@on")
lsys.show(m, { width = 200, height = 200, status = false })
print("all", steps())
lsys.show(m, { history = 1300000 })
print("thinned", steps())
lsys.show(m, { history = 1000000 })
print("thinned more", steps())
lsys.show(m, { history = 1 })
print("least", steps())
lsys.show(m, { steps = false })
print("last", steps())
V.close()
]])
    local out, code = run(D.env .. BIN .. " " .. dir .. "/hist.lua " .. dir .. "/m.lua")
    assert.equal(0, code, out)
    assert.matches("all\t0 1 2 3 4 5 6 7\n", out, 1, true)
    -- step k of F --> F[+F]F has 4 * 3^k segments: about 0.4, 1.3, 3.9, 12, 34, 105, 308 and
    -- 940 kB of history (lsys/viewer.lua frame_bytes), 1.41 MB in all
    assert.matches("thinned\t0 2 4 6 7\n", out, 1, true)           -- 1.29 MB
    assert.matches("thinned more\t0 4 7\n", out, 1, true)          -- 0.98 MB
    assert.matches("least\t0 7\nlast\t7\n", out, 1, true)
    assert.matches("lsys.show: the 8 steps would take more memory than the history allows "
                   .. "(1.2 MiB): the window keeps every 2nd step and the last", out, 1, true)
    assert.matches("(1000 kB): the window keeps every 4th step", out, 1, true)
    os.execute("rm -rf " .. dir)
  end)

  it("draws overlay lines depth-tested, or on top when asked", function()
    if not display() then return end
    local dir = tmpdir()
    write(dir .. "/lines.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local dir = arg[1]
local m = lsys.lsystem { axiom = "!(0.5)F(2)", view = { line_style = "cylinder" } }
for _, top in ipairs { false, true } do   -- a red line along the axis, inside the tube
  local sc = m:interpret(m:derive())
  lsys.show(sc, { width = 200, height = 200, status = false, lines = {
    { p0 = { 0, 0, 0 }, p1 = { 0, 2, 0 }, color = { 1, 0, 0 }, width = 4, ontop = top } } })
  assert(V.sync(10 * SLOW))
  V.screenshot(dir .. "/" .. tostring(top) .. ".png")
end
V.close()
]])
    local out, code = run(D.env .. BIN .. " " .. dir .. "/lines.lua " .. dir)
    assert.equal(0, code, out)
    local function red (name)
      local px = core.png_read(dir .. "/" .. name .. ".png")
      local n = 0
      for i = 1, #px, 4 do
        local r, g, b = px:byte(i, i + 2)
        if r > 200 and g < 60 and b < 60 then n = n + 1 end
      end
      return n
    end
    assert.equal(0, red("false"))            -- hidden inside the tube
    assert.is_true(red("true") > 200, red("true"))
    os.execute("rm -rf " .. dir)
  end)

  it("lsys view reloads the model when its file changes and keeps the last good one, " ..
     "and the S key saves what the window shows", function()
    local dir = clicks()
    if not dir then return end
    local bin = H.absolute(BIN)
    write(dir .. "/m.lua", MODEL:format(1, "line"))
    os.execute("cd " .. dir .. " && (" .. D.env .. "timeout " .. 60 * SLOW .. " " .. bin ..
      " view m.lua --size 300x300 >out.txt 2>err.txt; echo $? > rc.txt) &")
    local win = D.env .. "timeout " .. 30 * SLOW .. " xdotool search --sync --name 'lsys: m.lua' "
    local function key (k)
      return os.execute(win .. "windowfocus --sync %1 key " .. k .. " >/dev/null 2>&1")
    end
    local function wait_for (file, text)
      for _ = 1, 100 * SLOW do
        local s = read(dir .. "/" .. file)
        if s and s:find(text, 1, true) then return s end
        D.sleep(0.1)
      end
      return read(dir .. "/" .. file) or ""
    end
    assert.truthy(key("s"))
    wait_for("out.txt", "")
    for _ = 1, 50 * SLOW do if read(dir .. "/lsys-001.png") then break end D.sleep(0.1) end
    D.sleep(0.3)
    local first = plant(dir .. "/lsys-001.png", 280)   -- above the status line
    assert.equal(300, first.w)
    assert.is_true(first.n > 100)
    -- a change: two more steps
    D.sleep(1.1)                     -- a new modification time even on coarse clocks
    write(dir .. "/m.lua", MODEL:format(3, "line"))
    local err = wait_for("err.txt", "reloaded m.lua: 3 steps")
    assert.truthy(err:find("reloaded m.lua: 3 steps", 1, true), err)
    -- a syntax error: reported, the last good model stays
    D.sleep(1.1)
    write(dir .. "/m.lua", "local lsys = require 'lsys'\nreturn lsys.lsystem { axiom = }\n")
    err = wait_for("err.txt", "stays on screen")
    assert.truthy(err:find("m.lua:2: unexpected symbol near '}'", 1, true), err)
    assert.truthy(err:find("the last good model stays on screen", 1, true), err)
    -- the camera was kept through the reload; F fits the bigger plant
    assert.truthy(key("f"))
    assert.truthy(key("s"))
    for _ = 1, 50 * SLOW do if read(dir .. "/lsys-002.png") then break end D.sleep(0.1) end
    D.sleep(0.3)
    local second = plant(dir .. "/lsys-002.png", 280)
    assert.is_true(second.n > 2 * first.n, second.n .. " vs " .. first.n)
    key("Escape")             -- (xdotool may complain: the window goes while it works)
    local rc = wait_for("rc.txt", "\n")
    assert.equal("0\n", rc)
    os.execute("rm -rf " .. dir)
  end)
end)

describe("the viewer without a display", function()
  it("says there is none and how to draw without one", function()
    local dir = tmpdir()
    write(dir .. "/show.lua", 'local lsys = require "lsys"\n' ..
      'lsys.show(lsys.lsystem { axiom = "F" })\n')
    local out, code = run("env -u DISPLAY -u WAYLAND_DISPLAY " .. BIN .. " " .. dir ..
      "/show.lua")
    assert.equal(1, code)
    if core.has_viewer then
      assert.truthy(out:find("lsys.show: ", 1, true), out)
      assert.truthy(out:find("no display: DISPLAY is not set; `lsys render` draws PNG files " ..
        "without one", 1, true), out)
    else
      assert.truthy(out:find("built without the viewer window", 1, true), out)
    end
    local out2, code2 = run("env -u DISPLAY -u WAYLAND_DISPLAY " .. BIN ..
      " view examples/default.lua --screenshot " .. dir .. "/x.png")
    assert.equal(1, code2)
    assert.truthy(out2:find("no display", 1, true), out2)
    os.execute("rm -rf " .. dir)
  end)

  it("checks the options of lsys.show", function()
    local lsys = require "lsys"
    local m = lsys.lsystem { axiom = "F" }
    assert.error_contains(function() lsys.show(m, { colour = 1 }) end,
      "lsys.show: unknown option 'colour'")
    assert.error_contains(function() lsys.show(m, { rate = "fast" }) end,
      "lsys.show: option 'rate' must be a number")
    assert.error_contains(function() lsys.show(42) end,
      "lsys.show: a Model, an Lstring, a Scene or a list of Scenes expected")
    local out, code = run(BIN .. " view --size 0x3")
    assert.equal(2, code)
    assert.truthy(out:find("--size expects WxH", 1, true))
    out, code = run(BIN .. " view --screenshot x.jpg")
    assert.equal(2, code)
    assert.truthy(out:find("the screenshot must be a .png file, got 'x.jpg'", 1, true))
  end)
end)
