-- Sketch benchmark: a synthetic sketch of 2,000 points per stroke, 10 layers of
-- 55 nodes, through the pipeline of lsys.sketch (Anastacio et al. 2009): load (checks),
-- analysis (stroke capture, construction lines, nodes, rays), functions, model, derive and
-- interpret. Prints the best of several runs of each stage in ms and the total; the sketch
-- window redraws the plant while the user draws, so the total should stay under 50 ms.
--
--   build/bin/lsys bench/sketch.lua
--   LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;' lua5.4 bench/sketch.lua
local script = arg and arg[0] or "bench/sketch.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
B.load_lsys()
local sketch = require "lsys.sketch"

local RUNS, PTS, LAYERS, N = 7, 2000, 10, 55

-- a wavy stem, bulging boundaries, LAYERS + 1 inclination lines: PTS points each
local function stroke (role, f)
  local pts = {}
  for i = 0, PTS - 1 do
    local t = i / (PTS - 1)
    local x, y = f(t)
    pts[#pts + 1] = { x, y }
  end
  return { role = role, points = pts }
end
local strokes = {
  stroke("stem", function (t) return 400 + 30 * math.sin(3 * t), 950 - 880 * t end),
  stroke("boundary_left",
         function (t) return 380 - 250 * math.sin(math.pi * t), 970 - 920 * t end),
  stroke("boundary_right",
         function (t) return 420 + 250 * math.sin(math.pi * t), 970 - 920 * t end),
}
for k = 0, LAYERS do
  local y = 900 - 780 * k / LAYERS
  strokes[#strokes + 1] = stroke("inclination", function (t)
    return 60 + 680 * t, y + 60 * math.abs(t - 0.5) * -1 end)
end
local data = { width = 800, height = 1000, nodes_per_layer = N, phyllotaxis = "fibonacci",
               strokes = strokes }

local stages = {}
local function stage (name, f)
  local t, r = B.best(f, RUNS)
  stages[#stages + 1] = { name, t * 1000 }
  return r
end
local sk = stage("load", function () return sketch.load(data, { name = "bench" }) end)
stage("analysis", function () sk._an = nil; return sk:analysis() end)
stage("functions", function () sk._fn = nil; return sk:functions() end)
local m = stage("model", function () return sk:model() end)
local s = stage("derive", function () return m:derive() end)
stage("interpret", function () return m:interpret(s) end)

print(string.format("lsys.sketch: %d points per stroke, %d layers x %d nodes (%s, best of %d)",
                    PTS, LAYERS, N, B.clock_name, RUNS))
local total = 0
for _, st in ipairs(stages) do
  print(string.format("  %-10s %8.2f ms", st[1], st[2]))
  total = total + st[2]
end
print(string.format("  %-10s %8.2f ms  (target 50 ms: %s)", "total", total, B.verdict(total < 50)))
print(string.format("  %d modules, %d organs", #s, s:count("Organ")))
