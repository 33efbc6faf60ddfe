-- The forest growing in the viewer window: examples/grow/forest.lua, five trees
-- growing to 20,000 limbs, shown live by `lsys grow` (lsys.growview): after each tick the
-- window receives only the vertex ranges that changed and what was appended, and draws one
-- tick while the next one grows.
--
--   DISPLAY=:N build/bin/lsys bench/grow_view.lua [RUNS] [WxH]
--
-- Needs a display (Xvfb: `Xvfb :57 &` then DISPLAY=:57; llvmpipe draws there). Prints, for
-- the best of RUNS (3) runs, the pictures drawn a second from the tick the forest first has
-- its 20,000 limbs to its end, the time to draw one picture then, and the rate over the whole
-- growth; one line for scripts:
--   grow view 20000 limbs: 30.9 frames/s, 31.3 ms a frame, whole growth 98.4 frames/s
-- then whether it reaches the target of 30 frames a second.

local B = dofile(((arg and arg[0] or "bench/grow_view.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local RUNS = tonumber(arg and arg[1]) or 3
local W, H = (arg and arg[2] or "1000x600"):match("^(%d+)x(%d+)$")
W, H = tonumber(W) or 1000, tonumber(H) or 600

if os.getenv("DISPLAY") == nil or not require("lsys.core").has_viewer then
  print("grow view: no display (set DISPLAY, e.g. Xvfb :57 & DISPLAY=:57) or no viewer; "
    .. "nothing measured")
  return
end

local GV = require "lsys.growview"
local F = dofile(B.root .. "/examples/grow/forest.lua")
local shot = os.tmpname() .. ".png"
print(string.format("lsys %s, %s; %s, %dx%d window, best of %d", lsys.version, B.clock_name,
  "examples/grow/forest.lua", W, H, RUNS))
local best
for _ = 1, RUNS do
  local r = GV.live(function () return F.world() end,
                    { width = W, height = H, screenshot = shot, title = "bench" })
  if r.full and (best == nil or r.full.fps > best.full.fps) then best = r end
end
os.remove(shot)
if best == nil then print("grow view: the forest never reached its final size") return end
print(string.format("grow view %d limbs: %.1f frames/s, %.1f ms a frame, whole growth %.1f "
  .. "frames/s", best.full.limbs, best.full.fps, best.drawms, best.fps))
print(string.format("  the last %d ticks at %d limbs: %d pictures in %.2f s; %d ticks in all",
  best.full.ticks, best.full.limbs, best.full.drawn, best.full.seconds, best.ticks))
print(string.format("target: at least 30 frames a second at 20,000 limbs: %s",
  best.full.fps >= 30 and "PASS" or "FAIL"))
