-- Curve pane benchmark: what one step of a drag costs in the curve editor (lsys.ui.curve):
-- the pointer move (the new Func, Contour or Surface made and put into the model) and the
-- redraw of the 420 x 700 pane, for a function of 12 points, the 15-point contour of
-- examples/cpfg/contours/fig16a.con and the 2 patches of examples/cpfg/surfaces/leaf.s.
-- Prints the best of several runs of 50 moves in ms per move; the pane follows the mouse,
-- so a move and a redraw together should stay under one frame at 60 Hz (16 ms).
--
--   build/bin/lsys bench/curvepane.lua
--   LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;' lua5.4 bench/curvepane.lua
local script = arg and arg[0] or "bench/curvepane.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local lsys = B.load_lsys()
local core = require "lsys.core"
local P = require "lsys.ui.curve"

local RUNS, MOVES = 5, 50
local root = B.root .. "/"

local pts = {}
for i = 0, 11 do pts[#pts + 1] = { i / 11, 0.5 + 0.3 * math.sin(i) } end
local m = lsys.lsystem {
  axiom = "A(0.5)", productions = "A(x) --> B(func(1, x))",
  functions = { lsys.func.new { points = pts, name = "internode" } },
  view = { contours = { [1] = root .. "examples/cpfg/contours/fig16a.con" },
           surfaces = { l = root .. "examples/cpfg/surfaces/leaf.s" } } }
local changes = 0
local pane = P.new(P.targets(m), { on_change = function () changes = changes + 1 end })
local canvas = core.canvas(420, 700)

print(string.format("lsys.ui.curve: %d moves of a drag, 420 x 700 pane (%s, best of %d)",
                    MOVES, B.clock_name, RUNS))
local worst = 0
for k, what in ipairs { "function (12 points)", "contour (15 points)", "surface (2 patches)" } do
  pane:select_target(k)
  pane:draw(canvas)
  local i0 = k == 3 and 12 or 5
  changes = 0
  local move = B.best(function ()
    local x, y = pane:to_pixels(i0)
    pane:pointer("down", x, y, "left")
    for i = 1, MOVES do pane:pointer("move", x + i % 7, y - i % 5, "left") end
    pane:pointer("up", x, y, "left")
  end, RUNS) / MOVES * 1000
  assert(changes == RUNS * MOVES, "the drag did not edit")
  local draw = B.best(function () pane:draw(canvas) end, RUNS) * 1000
  worst = math.max(worst, move + draw)
  print(string.format("  %-22s move %7.3f ms   draw %7.3f ms", what, move, draw))
end
print(string.format("  worst move + draw %7.3f ms  (target 16 ms: %s)", worst,
                    B.verdict(worst < 16)))
