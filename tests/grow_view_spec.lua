-- A growing world shown and drawn: `lsys grow FILE --frames DIR` (one camera for
-- every tick), the live window (#gl, on a private Xvfb: the patches of csrc/gl/vlive.c draw
-- the same plants as the offscreen renderer; its growth keys pressed through xdotool), the
-- world's length and view, lsys.render's `fit` box and scene:look.
local lsys = require "lsys"
local core = require "lsys.core"
local grow = require "lsys.grow"
local D = require "tests.display"

local H = require "tests.helper"

local BIN, run, tmpdir, write = H.BIN, H.sh, H.tmpdir, H.write

local plant = H.ink

local DAVISON = "examples/grow/davison.lua"

describe("a world's length and view", function ()
  it("grows to its length, and says when it has none", function ()
    local w = grow.world { ticks = 7 }
    w:plant {}
    assert.equal(w, w:grow())
    assert.equal(7, w.ticks)
    w:grow()
    assert.equal(7, w.ticks)                        -- grown: nothing more
    local u = grow.world {}
    u:plant {}
    assert.error_matches(function () u:grow() end, "grow: the world has no length")
    assert.equal(3, u:grow(3).ticks)
    assert.error_matches(function () grow.world { ticks = 2.5 } end, "'ticks' must be a whole")
    assert.error_matches(function () grow.world { ticks = -1 } end, "'ticks' must be a finite")
  end)

  it("takes the look of a view; a bad one is named", function ()
    local w = grow.world { view = { background = { 1, 1, 1 }, projection = "perspective" } }
    w:plant {}
    w:tick(2)
    local px = lsys.render(w:scene(), { width = 16, height = 16 })
    assert.equal("\255\255\255\255", px:sub(1, 4))  -- the corner: the world's background
    assert.error_matches(function () grow.world { view = { colour = 1 } } end,
      "lsys.grow: world: .*unknown option 'colour'")
    assert.error_matches(function () grow.world { view = { projection = "fisheye" } } end,
      "lsys.grow: world: view.projection")
    assert.error_matches(function () grow.world { view = 3 } end, "'view' must be a table")
  end)
end)

describe("lsys.render's fit box", function ()
  local m = lsys.lsystem { axiom = "F", productions = { F = "F[+F]F" }, steps = 3,
                           view = { angle = 30 } }

  it("frames the box instead of the scene", function ()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local sc = m:interpret()
    local lo, hi = sc:bounds()
    local a = lsys.render(sc, { width = 120, height = 120 })
    local b = lsys.render(sc, { width = 120, height = 120,
                                fit = { lo[1], lo[2], lo[3], hi[1], hi[2], hi[3] } })
    assert.equal(a, b)                              -- its own box: the same picture
    local dir = tmpdir()
    lsys.render(sc, { out = dir .. "/big.png", width = 120, height = 120, background = "#ffffff",
                      fit = { lo[1] - 10, lo[2], lo[3], hi[1] + 10, hi[2] + 20, hi[3] } })
    lsys.render(sc, { out = dir .. "/own.png", width = 120, height = 120,
                      background = "#ffffff" })
    local big, own = plant(dir .. "/big.png"), plant(dir .. "/own.png")
    assert.is_true(big.n > 0 and big.n < own.n / 4, big.n .. " " .. own.n)
    assert.is_true(big.box[4] - big.box[2] < (own.box[4] - own.box[2]) / 3)
    H.rmdir(dir)
  end)

  it("checks the box", function ()
    local sc = m:interpret()
    assert.error_matches(function () lsys.render(sc, { fit = { 1, 2 } }) end,
      "opts.fit must be a box {x0, y0, z0, x1, y1, z1} of finite numbers")
    assert.error_matches(function () lsys.render(sc, { fit = { 0, 0, 0, 1, 0 / 0, 1 } }) end,
      "of finite numbers")
    assert.error_matches(function () lsys.render(sc, { fit = { 1, 0, 0, 0, 1, 1 } }) end,
      "its low corner is above its high one")
    assert.error_matches(function () sc:look { fit = "x" } end, "scene:look: opts.fit")
    assert.error_matches(function () sc:look { bogus = 1 } end, "unknown option 'bogus'")
  end)
end)

describe("lsys grow --frames", function ()
  it("writes a picture a tick through one camera: the plants grow in place", function ()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local dir = tmpdir()
    local out, code = run(BIN .. " grow " .. DAVISON .. " --frames " .. dir .. "/f --every 10"
      .. " --ticks 40 --size 240x140")
    assert.equal(0, code, out)
    assert.matches("wrote 5 pictures to " .. dir .. "/f", out, 1, true)
    local boxes = {}
    for t = 0, 40, 10 do
      local p = plant(string.format("%s/f/tick-%04d.png", dir, t))
      assert.equal(240, p.w)
      boxes[#boxes + 1] = p
    end
    for k = 2, #boxes do      -- one camera: the ground stays put while the trees grow
      assert.is_true(math.abs(boxes[k].box[4] - boxes[1].box[4]) <= 2, k)
      assert.is_true(boxes[k].n > boxes[k - 1].n, k)
    end
    -- the last picture is the grown world drawn through its own box
    local D5 = dofile(DAVISON)
    local w = D5.world { ticks = 40 }:grow()
    local lo, hi = w:scene():bounds()
    lsys.render(w:scene(), { out = dir .. "/same.png", width = 240, height = 140,
                             fit = { lo[1], lo[2], lo[3], hi[1], hi[2], hi[3] } })
    assert.is_true(H.read(dir .. "/same.png") == H.read(dir .. "/f/tick-0040.png"))
    H.rmdir(dir)
  end)

  it("says what is wrong with its arguments", function ()
    local out, code = run(BIN .. " grow")
    assert.equal(2, code)
    assert.matches("a FILE is required", out, 1, true)
    out, code = run(BIN .. " grow " .. DAVISON .. " --every 3")
    assert.equal(2, code)
    assert.matches("--every applies to --frames", out, 1, true)
    out, code = run(BIN .. " grow " .. DAVISON .. " --ticks -2 --frames /tmp/x")
    assert.equal(2, code)
    assert.matches("--ticks expects a whole number >= 0, got '-2'", out, 1, true)
    out, code = run(BIN .. " grow " .. DAVISON .. " --frames /tmp/x --rate 3")
    assert.equal(2, code)
    assert.matches("--frames draws no window", out, 1, true)
    local dir = tmpdir()
    write(dir .. "/nothing.lua", "return 42")
    out, code = run(BIN .. " grow " .. dir .. "/nothing.lua --frames " .. dir .. "/f")
    assert.equal(1, code)
    assert.matches("nothing.lua returned number: a grow file returns a World", out, 1, true)
    write(dir .. "/bad.lua", [[
      local grow = require "lsys.grow"
      local K = grow.kind("k")
      K:rule("boom", function (limb) if limb:age() == 2 then error("no sap") end end)
      local w = grow.world { ticks = 5 }
      w:plant { kind = K }
      return w]])
    out, code = run(BIN .. " grow " .. dir .. "/bad.lua --frames " .. dir .. "/g")
    assert.equal(1, code)
    assert.matches("rule 'boom' of kind 'k' failed on limb 1 (tick 3): ", out, 1, true)
    assert.matches("no sap", out, 1, true)
    write(dir .. "/file", "")
    out, code = run(BIN .. " grow " .. DAVISON .. " --frames " .. dir .. "/file")
    assert.equal(1, code)
    assert.matches("cannot make the directory " .. dir .. "/file: a file is in the way", out,
      1, true)
    H.rmdir(dir)
  end)
end)

describe("the pace of a live world", function ()
  -- lsys.growview's loop against a stand-in for lsys.viewer (no window): it presses `keys`
  -- one a poll, then closes (unless the loop ends first, as a screenshot does); what the
  -- status line got (viewer.patch's notes, each change once) and what on_key saw are kept.
  local function session (opts, keys)
    local fake, notes, seen, serial, events, closed = {}, {}, {}, 0, nil, false
    function fake.live (_, o) events = o.on_event end
    function fake.patch (_, _, _, note)
      if notes[#notes] ~= note then notes[#notes + 1] = note end
      serial = serial + 1
      return serial
    end
    function fake.state ()
      return { open = not closed, serial = serial, drawn = serial, drawms = 1 }
    end
    function fake.poll ()
      local k = table.remove(keys, 1)
      if k then events { type = "key", key = k } else closed = not opts.screenshot end
      return true
    end
    function fake.sync () end
    function fake.screenshot (path) return path end
    function fake.close () end
    local saved = package.loaded["lsys.viewer"]
    package.loaded["lsys.viewer"] = fake
    opts.fit = false
    opts.on_key = function (k, st) seen[#seen + 1] = k .. " " .. st.rate end
    local ok, err = pcall(require("lsys.growview").live, function ()
      local w = grow.world { ticks = 3 }
      w:plant {}
      return w
    end, opts)
    package.loaded["lsys.viewer"] = saved
    assert(ok, err)
    return notes, seen
  end

  it("is the paper's tick of 100 ms unless told, and the status line shows it", function ()
    local notes, seen = session({}, { "right", "+", "space" })
    assert.same({ "right 10", "+ 20", "space 20" }, seen)
    assert.same({ "growing 10 ticks/s", "paused, 10 ticks/s", "paused, 20 ticks/s",
                  "growing 20 ticks/s" }, notes)
    notes, seen = session({ rate = 2 }, { "-", "-" })
    assert.same({ "- 1", "- 1" }, seen)
    assert.same({ "growing 2 ticks/s", "growing 1 ticks/s" }, notes)
  end)

  it("grows as fast as the window draws for a screenshot, unless given a rate", function ()
    local notes = session({ screenshot = "x.png" }, {})
    assert.same({ "growing as fast as drawn", "done" }, notes)
    notes = session({ screenshot = "x.png", rate = 30 }, {})
    assert.same({ "growing 30 ticks/s", "done" }, notes)
  end)
end)

describe("#gl lsys grow in the window", function ()
  teardown(function () D.stop() end)
  it("draws a 3D plant over the sky and on the ground, as lsys render does", function ()
    local ok, why = D.start()
    if not ok then return pending(why) end
    local dir = tmpdir()
    local function shot (flags)
      local out, code = run(D.env .. BIN .. " grow " .. DAVISON .. " --ticks 30 --size 300x180 "
        .. flags .. " --screenshot " .. dir .. "/w.png")
      assert.equal(0, code, out)
      local px, w = core.png_read(dir .. "/w.png")
      local function at (x, y) return { px:byte(4 * (y * w + x) + 1, 4 * (y * w + x) + 3) } end
      return at(150, 2), at(5, 150)       -- the top edge's middle, low on the left
    end
    local top, low = shot("")
    -- the sky's top colour (0.55, 0.72, 0.92) above, the ground's grey-green below
    assert.is_true(top[3] > top[1] + 40, table.concat(top, " "))
    assert.is_true(low[2] > low[3] and low[1] < 220, table.concat(low, " "))
    local ftop, flow = shot("--flat")
    assert.same(ftop, flow)                -- the view's background, the same everywhere
  end)

  it("grows the plants live and draws them as the offscreen renderer does", function ()
    local ok, why = D.start()
    if not ok then return pending(why) end
    local dir = tmpdir()
    local out, code = run(D.env .. BIN .. " grow " .. DAVISON .. " --ticks 30 --size 300x180"
      .. " --flat --screenshot " .. dir .. "/live.png")
    assert.equal(0, code, out)
    assert.matches("limbs after 30 ticks; the window drew %d+ frames", out)
    run(BIN .. " grow " .. DAVISON .. " --ticks 30 --size 300x180 --frames " .. dir .. "/f"
      .. " --every 30")
    local live = plant(dir .. "/live.png", 180 - 16)    -- above the status line
    local off = plant(dir .. "/f/tick-0030.png")
    assert.is_true(live.n > 200, live.n)
    for i = 1, 4 do                                     -- one camera: the same box of trees
      assert.is_true(math.abs(live.box[i] - off.box[i]) <= 3,
        string.format("corner %d: %d vs %d", i, live.box[i], off.box[i]))
    end
    -- the window does not antialias here (Xvfb): its twigs are thinner
    assert.is_true(live.n > 0.5 * off.n and live.n < 1.5 * off.n, live.n .. " " .. off.n)
    H.rmdir(dir)
  end)
end)

describe("#gl the growth keys", function ()
  teardown(function () D.stop() end)
  local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
  -- a script growing one tree 5 ticks a second and logging each key's effect
  local SCRIPT = [[
local gv = require "lsys.growview"
local D = dofile("examples/grow/davison.lua")
local log = assert(io.open(arg[1], "w"))
gv.live(function () return D.world { trees = 1, ticks = 400 } end, {
  rate = 5, fit = false, width = 240, height = 160, title = "lsys: growth keys",
  on_key = function (k, s)
    log:write(string.format("%s %d %s %s\n", k, s.ticks, tostring(s.playing), s.rate))
    log:flush()
  end,
})
log:write("closed\n")
log:close()
]]

  it("pause, step, faster, slower and start again, through real key presses", function ()
    local ok, why = D.start()
    if not ok then return pending(why) end
    if not D.have("xdotool") then return pending("xdotool is not installed (./setup.sh does)") end
    local dir = tmpdir()
    write(dir .. "/keys.lua", SCRIPT)
    local log = dir .. "/keys.txt"
    os.execute(D.env .. "timeout " .. 60 * SLOW .. " " .. BIN .. " " .. dir .. "/keys.lua "
      .. log .. " >" .. dir .. "/out.txt 2>&1 &")
    local win = D.env .. "timeout " .. 30 * SLOW
      .. " xdotool search --sync --name 'lsys: growth keys' "
    local lines = {}
    -- presses a key and waits for its line in the log
    local function key (k)
      assert.truthy(os.execute(win .. "windowfocus --sync %1 key " .. k .. " >/dev/null 2>&1"))
      for _ = 1, 50 * SLOW do
        local all = {}
        for line in (H.read(log) or ""):gmatch("[^\n]+") do all[#all + 1] = line end
        if #all > #lines then
          lines = all
          local name, t, playing, rate = all[#all]:match("^(%S+) (%d+) (%S+) (%S+)$")
          return { key = name, ticks = tonumber(t), playing = playing == "true",
                   rate = tonumber(rate) }
        end
        D.sleep(0.1)
      end
      error("no line in the log for key " .. k)
    end
    D.sleep(1)                                        -- a few ticks grow
    local paused = key("space")
    assert.equal("space", paused.key)
    assert.is_false(paused.playing)
    D.sleep(0.6)                                      -- 3 ticks' time: paused, none grows
    local one = key("Right")
    assert.same({ key = "right", ticks = paused.ticks + 1, playing = false, rate = 5 }, one)
    assert.equal(paused.ticks + 2, key("Right").ticks)
    assert.equal(10, key("KP_Add").rate)              -- 5 -> 10 ticks a second
    assert.equal(20, key("equal").rate)               -- = is + unshifted
    local slower = key("minus")
    assert.equal(10, slower.rate)
    assert.equal(paused.ticks + 2, slower.ticks)      -- still paused
    local going = key("space")
    assert.is_true(going.playing)
    D.sleep(0.5)                                      -- 10 a second: about 5 ticks
    local again = key("BackSpace")
    assert.same({ key = "backspace", ticks = 0, playing = true, rate = 10 }, again)
    local resumed = key("space")                      -- pause the new world
    assert.is_false(resumed.playing)
    assert.is_true(resumed.ticks < paused.ticks + 2 + 5, resumed.ticks)
    os.execute(win .. "windowfocus --sync %1 key Escape >/dev/null 2>&1")
    for _ = 1, 50 * SLOW do
      if (H.read(log) or ""):find("closed", 1, true) then break end
      D.sleep(0.1)
    end
    assert.truthy((H.read(log) or ""):find("closed\n", 1, true), H.read(dir .. "/out.txt"))
    H.rmdir(dir)
  end)
end)
