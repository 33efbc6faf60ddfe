-- The viewer window's light colours (#gl; docs/viewer.md, "Light on the leaves"): the L key
-- through lsys.viewer.key and through a real key press in `lsys view` (xdotool), the colours
-- the window draws each triangle in (lsys.viewer.colour) and the pictures it shows, the frames
-- stepped to coloured as they come, the same colours on every number of threads, and the
-- errors. The scene: a roof (a 40 x 40 square) at height 2 over a small leaf, a leaf in the
-- open beside them, and a stem; at step 2 a wider roof above the first. The colours without
-- a window are tests/c/test_vlight.c's.
-- ctest: slow (drives the window under Xvfb with waits)
local core = require "lsys.core"
local D = require "tests.display"
local H = require "tests.helper"

local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits

local run, read, write, tmpdir = H.sh, H.read, H.write, H.tmpdir

-- Triangles 1, 2: the roof; 3, 4: the leaf under it; 5, 6: the leaf in the open; at step 2
-- 7, 8: the wider roof; then the stem's.
local MODEL = [[
local lsys = require "lsys"
-- a horizontal square of side s at height h over (x, 0, 0), as a polygon
local function square (x, h, s)
  return ("[ +(90) f(%g) -(90) f(%g) &(90) [ -(90) f(%g) +(90) f(%g) { . +(90) f(%g) . +(90) "
    .. "f(%g) . +(90) f(%g) . } ] ]"):format(x, h, s / 2, s / 2, s, s, s)
end
return lsys.lsystem {
  name = "light test", axiom = "A", steps = 2,
  productions = { "A --> ;(2) " .. square(0, 2, 40) .. square(0, 1.9, 0.2) ..
                  square(60, 2, 1) .. " B ;(1) !(0.3) F(1)",
                  "B --> ;(2) " .. square(0, 3, 80) },
  view = { angle = 90, line_style = "cylinder", background = { 1, 1, 1 },
           palette = { [1] = { 0.5, 0.3, 0.1 }, [2] = { 0.2, 0.6, 0.2 } },
           direction = { 0, -1, 0 }, up = { 0, 0, -1 } },
}
]]

local function display ()
  local ok, why = D.start()
  if not ok then pending(why) end
  return ok
end

-- The pixel (x, y) of a PNG, r, g, b.
local function pixel (path, x, y)
  local px, w = core.png_read(path)
  local i = 4 * (math.floor(y) * w + math.floor(x))
  return px:byte(i + 1, i + 3)
end

-- The pixels of a PNG (above row 'rows') that are yellow (the ramp's top, lit) and green
-- (the model's leaf colour).
local function hues (path, rows)
  local px, w, h = core.png_read(path)
  local yellow, green = 0, 0
  for k = 0, w * (rows or h) - 1 do
    local r, g, b = px:byte(4 * k + 1, 4 * k + 3)
    if r > 150 and g > 130 and b < 60 then yellow = yellow + 1 end
    if g > 100 and r < 90 and b < 90 then green = green + 1 end
  end
  return yellow, green
end

describe("#gl the viewer's light colours", function()
  teardown(function() D.stop() end)

  it("colour the leaves by their light with the L key, each frame stepped to, and restore "
     .. "the model's colours when pressed again", function()
    if not display() then return end
    local dir = tmpdir()
    write(dir .. "/m.lua", MODEL)
    write(dir .. "/light.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
local m = dofile(arg[1])
local dir = arg[2]
local function rgb (...) return string.format("%.3f %.3f %.3f", ...) end
local function sync () assert(V.sync(10 * SLOW), "no picture") end
print("top", rgb(V.ramp(1)), "bottom", rgb(V.ramp(0)))
lsys.show(m, { width = 300, height = 300, status = false, title = "light test", step = 1 })
sync()
print("off", tostring(V.state().light), rgb(V.colour(1)), rgb(V.colour(7)))
V.screenshot(dir .. "/off.png")
V.key("l") sync()
print("on", tostring(V.state().light))
for t = 1, 7, 2 do print("triangle " .. t, rgb(V.colour(t))) end
local info = V.light()
print("light", info.frame, info.leaves, info.min, info.max, string.format("%.4f", info.mean))
local x, y = V.project({ 10, 2, 10 })             -- on the roof, off its middle line
print("roof at", math.floor(x), math.floor(y))
V.screenshot(dir .. "/on.png")
V.key("right") sync()                             -- step 2: the wider roof above the first
print("step 2", V.state().step, rgb(V.colour(1)), rgb(V.colour(7)))
V.key("left") V.key("left") sync()
print("step 0", V.light().msg)
V.key("right") V.key("l") sync()
print("again", tostring(V.state().light), rgb(V.colour(1)))
V.screenshot(dir .. "/again.png")
-- the same colours for every number of threads
local seen
for _, threads in ipairs { 1, 2, 3 } do
  lsys.show(m, { light_colours = false })
  info = V.light(3, { threads = threads })
  V.key("l") sync()
  local c = { info.leaves, info.min, info.max, info.mean }
  for t = 1, 40 do c[#c + 1] = rgb(V.colour(t)) end
  c = table.concat(c, " ")
  if seen then print("threads " .. threads, tostring(c == seen)) end
  seen = c
  V.key("l") sync()
end
-- light_colours: on from the first picture
lsys.show(m, { light_colours = true, step = 1 })    -- (poll is not asked for them)
sync()
print("drawn on", tostring(V.state().light), rgb(V.colour(1)))
-- what is wrong
lsys.show(m, { light_colours = false })
print(select(2, pcall(V.light, 9)))
print(select(2, pcall(V.light, 2, { thread = 1 })))
print(select(2, pcall(V.colour, 41, 3)))
info = V.light(2, { max_memory = 1000 })
print("budget", info.leaves, info.msg)
V.close()
print(select(2, pcall(V.light)))
]])
    local out, code = run(D.env .. BIN .. " " .. dir .. "/light.lua " .. dir .. "/m.lua " .. dir)
    assert.equal(0, code, out)
    local top, bottom = "0.993 0.906 0.144", "0.267 0.005 0.329"
    local green, brown = "0.200 0.600 0.200", "0.500 0.300 0.100"
    local lines = {}
    for l in out:gmatch("[^\n]+") do lines[#lines + 1] = l end
    assert.equal("top\t" .. top .. "\tbottom\t" .. bottom, lines[1])
    assert.equal("off\tfalse\t" .. green .. "\t" .. brown, lines[2])
    assert.equal("on\ttrue", lines[3])
    assert.equal("triangle 1\t" .. top, lines[4])        -- the roof, in the open
    assert.equal("triangle 3\t" .. bottom, lines[5])     -- the leaf under it, in full shade
    assert.equal("triangle 5\t" .. top, lines[6])        -- the leaf beside them
    assert.equal("triangle 7\t" .. brown, lines[7])      -- the stem keeps its colour
    -- 6 leaf triangles: the roof's 1600 in light 1, the small leaf's 0.04 in 0, 1 more in 1
    assert.equal("light\t2\t6\t0.0\t1.0\t" .. string.format("%.4f", 1601 / 1601.04), lines[8])
    -- step 2: the first roof under the wider one is in the shade; the wider one in the open
    assert.equal("step 2\t2\t" .. bottom .. "\t" .. top, lines[10])
    assert.equal("step 0\tno leaves in this step", lines[11])
    assert.equal("again\tfalse\t" .. green, lines[12])   -- off again: the model's colours
    assert.equal("threads 2\ttrue", lines[13])
    assert.equal("threads 3\ttrue", lines[14])
    assert.equal("drawn on\ttrue\t" .. top, lines[15])   -- colours posted with the show
    assert.equal("lsys.viewer.light: no frame 9 (the window shows frames 1 to 3)", lines[16])
    assert.equal("lsys.viewer.light: unknown option 'thread' (known: threads, max_memory)",
                 lines[17])
    assert.equal("lsys.viewer.colour: no triangle 41 in frame 3 (it has 40)", lines[18])
    assert.matches("^budget\t0\tthe light colours need %d+ KiB, more than max_memory " ..
                   "%(1000 bytes%)$", lines[19])
    assert.equal("lsys.viewer.light: no window open", lines[20])
    -- the pictures: the roof yellow with the colours on, green without, and again after
    local x, y = lines[9]:match("^roof at\t(%d+)\t(%d+)$")
    assert.truthy(x, lines[9])
    local r, g, b = pixel(dir .. "/on.png", x, y)
    assert.is_true(r > 150 and g > 130 and b < 60, r .. " " .. g .. " " .. b)
    for _, name in ipairs { "off", "again" } do
      r, g, b = pixel(dir .. "/" .. name .. ".png", x, y)
      assert.is_true(g > 100 and r < 90 and b < 90, name .. ": " .. r .. " " .. g .. " " .. b)
    end
    -- and the legend at the top right: the ramp's colours, which the plain picture lacks
    local on_y, on_g = hues(dir .. "/on.png")
    local off_y, off_g = hues(dir .. "/off.png")
    assert.is_true(on_y > 1000 and on_g < 100, on_y .. " " .. on_g)
    assert.is_true(off_y == 0 and off_g > 1000, off_y .. " " .. off_g)
    os.execute("rm -rf " .. dir)
  end)

  it("colour them when the L key is pressed in `lsys view`", function()
    if not display() then return end
    if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return end
    local dir = tmpdir()
    write(dir .. "/m.lua", MODEL)
    os.execute("cd " .. dir .. " && (" .. D.env .. "timeout " .. 60 * SLOW .. " " ..
      H.absolute(BIN) .. " view m.lua --show 1 --size 300x300 --no-status >out.txt " ..
      "2>err.txt; echo $? > rc.txt) &")
    local win = D.env .. "timeout " .. 30 * SLOW ..
      " xdotool search --sync --name 'lsys: m.lua' "
    local function key (k)
      return os.execute(win .. "windowfocus --sync %1 key " .. k .. " >/dev/null 2>&1")
    end
    local function shot (n)
      local path = string.format("%s/lsys-%03d.png", dir, n)
      assert.truthy(key("s"))
      for _ = 1, 50 * SLOW do if read(path) then break end D.sleep(0.1) end
      D.sleep(0.3)
      return path
    end
    local plain = shot(1)
    assert.truthy(key("l"))
    D.sleep(1 * SLOW)                 -- lsys view polls, computes and hands the colours over
    local lit = shot(2)
    assert.truthy(key("l"))
    D.sleep(0.5 * SLOW)
    local back = shot(3)
    key("Escape")
    assert.equal("0\n", D.wait_for(dir .. "/rc.txt", "\n", 10 * SLOW))
    local y1, g1 = hues(plain)
    local y2, g2 = hues(lit)
    local y3, g3 = hues(back)
    assert.is_true(y1 == 0 and g1 > 1000, y1 .. " " .. g1)
    assert.is_true(y2 > 1000 and g2 < 100, y2 .. " " .. g2)
    assert.is_true(y3 == 0 and g3 > 1000, y3 .. " " .. g3)
    os.execute("rm -rf " .. dir)
  end)
end)

describe("the viewer's light colours without a window", function()
  it("check the show option and say there is no window", function()
    local lsys = require "lsys"
    local V = require "lsys.viewer"
    local m = lsys.lsystem { axiom = "F" }
    assert.error_contains(function() lsys.show(m, { light_colours = 1 }) end,
      "lsys.show: option 'light_colours' must be a boolean")
    assert.error_contains(function() V.light() end, "lsys.viewer.light: no window open")
    assert.is_nil(V.colour(1))                               -- asks: as for a closed one
    if core.has_viewer then
      assert.same({ core.light_ramp(1) }, { V.ramp(7) })   -- clamped
      local r, g, b = V.ramp(0.5)
      assert.near(0.128, r, 1e-6)
      assert.near(0.567, g, 1e-6)
      assert.near(0.551, b, 1e-6)
    end
  end)
end)
