-- Palette pane benchmark (lsys.ui.palette, docs/viewer.md "Palette pane"): what the pane
-- costs the viewer's editing column on a plant of about a million triangles with a
-- 256-colour map. Prints the best of several runs, in ms, of: scene:colors() (one pass
-- over the mesh's triangles and lines), pane:used() on a new scene (colors folded into the
-- palette), pane:draw() into a 420 x 700 canvas (256 swatches and the details), an item's
-- set (the view's palette replaced by a table of 256 entries) and the view normalised
-- again with it, as the next interpretation does. The pane redraws on every click and
-- slider move: draw and set should stay under 16 ms (a frame), colors under 50 ms.
--
--   build/bin/lsys bench/palette.lua
--   LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;' lua5.4 bench/palette.lua
local script = arg and arg[0] or "bench/palette.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local lsys = B.load_lsys()
local core = require "lsys.core"
local view = require "lsys.view"
local P = require "lsys.ui.palette"

local RUNS = 5
local dir = os.tmpname()
os.remove(dir)
os.execute("mkdir -p '" .. dir .. "'")
local bytes = {}
for i = 0, 255 do bytes[#bytes + 1] = string.char(i, (i * 7) % 256, 255 - i) end
local f = assert(io.open(dir .. "/bench.map", "wb"))
f:write(table.concat(bytes))
f:close()

-- a binary tree of cylinders, each branch order in the next colour
local m = lsys.lsystem { axiom = "A", steps = 9,
  productions = "A --> F[+;A][-;A]F,A",
  view = { line_style = "cylinder", contour_sides = 16, angle = 30, palette = "bench.map",
           dir = dir } }
local sc = m:interpret()
local pane = P.new(m, { scene = sc })
local canvas = core.canvas(420, 700)

local tcol = B.best(function () return sc:colors() end, RUNS)
local tused = B.best(function () pane:set_scene(sc); return pane:used() end, RUNS)
local tdraw = B.best(function () pane:draw(canvas) end, RUNS)
local item = pane:items()[1]
local k = 0
local tset = B.best(function () k = (k + 1) % 256; item.set(k) end, RUNS)
local tnorm = B.best(function () return view.normalize(m.view) end, RUNS)
os.execute("rm -rf '" .. dir .. "'")

print(string.format("palette pane: %d triangles, %d colours used (%s, best of %d)",
                    sc.ntriangles, #pane:used(), B.clock_name, RUNS))
local function row (name, t, target)
  print(string.format("  %-40s %7.2f ms   target < %d ms: %s", name, 1000 * t, target,
                      B.verdict(1000 * t < target)))
end
row("scene:colors()", tcol, 50)
row("pane:used() on a new scene", tused, 50)
row("pane:draw() 420 x 700, 256 swatches", tdraw, 16)
row("item set (view palette replaced)", tset, 16)
row("view.normalize with the edited palette", tnorm, 16)
