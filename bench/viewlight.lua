-- The viewer's L key: the time to colour a frame's leaves by the light they receive
-- (lsys.viewer.light: core.light's hierarchy over every triangle of the frame, then one query
-- of the 64-direction overcast sky at each leaf triangle's centroid, on the Lua thread while
-- the window draws on). Frames of examples/open/shade.lua at steps 10, 11 and 14 (74,000 to
-- 429,000 triangles, a tenth of them leaves) and the broadleaf tree of examples/default.lua
-- (721,000 triangles). Each is shown, and its colours computed, 3 times on 2 threads; it
-- prints the best time (wall clock), the triangles and leaf triangles, the rays a second and
-- the mean light, and the target: the frame of about 100,000 triangles (shade, step 11)
-- coloured in under 0.5 s. It never fails on them.
--
--   DISPLAY=:N build/bin/lsys bench/viewlight.lua
--
-- Needs a display (Xvfb: `Xvfb :57 &` then DISPLAY=:57).
local B = dofile(((arg and arg[0] or "bench/viewlight.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local format = string.format

local THREADS, RUNS = 2, 3

if os.getenv("DISPLAY") == nil or not require("lsys.core").has_viewer then
  print("view light: no display (set DISPLAY, e.g. Xvfb :57 & DISPLAY=:57) or no viewer; "
    .. "nothing measured")
  return
end

local V = require "lsys.viewer"

local function shade (n)
  return function ()
    local m = dofile(B.root .. "/examples/open/shade.lua")
    m.steps = n
    return m:interpret(m:derive())
  end
end

local CASES = {
  { "shade, step 10", shade(10) },
  { "shade, step 11", shade(11), target = 0.5 },
  { "shade, step 14", shade(14) },
  { "default tree", function () return dofile(B.root .. "/examples/default.lua"):interpret() end },
}

print(format("lsys %s, %s, best of %d, %d threads; light on each leaf triangle, 64 directions",
  lsys.version, B.clock_name, RUNS, THREADS))
for _, c in ipairs(CASES) do
  local scene = c[2]()
  local info, best = nil, math.huge
  for _ = 1, RUNS do            -- a new show each time: its frames have no colours yet
    lsys.show(scene, { width = 300, height = 300, status = false, light_colours = false })
    collectgarbage()
    local t0 = B.clock()
    info = V.light(1, { threads = THREADS })
    best = math.min(best, B.clock() - t0)
  end
  print(format("  %-16s %8d triangles %7d leaves  %6.0f ms  %5.2f M rays/s  mean light %.2f%s",
    c[1], scene.ntriangles, info.leaves, 1000 * best, info.leaves * 64 / best / 1e6, info.mean,
    c.target and format("  target < %.1f s: %s", c.target, B.verdict(best < c.target)) or ""))
end
V.close()
