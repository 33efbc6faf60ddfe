-- Interpretation and rendering benchmark.
--
--   build/bin/lsys bench/interpret.lua
--
-- (1) turtle throughput in "line" style on the ABOP fig. 1.24a string after 10 steps
--     (F --> F[+F]F[-F]F, 24.4 M modules): modules per second, with and without turtle
--     records (target: >= 50 M/s with records, >= 100 M/s without);
-- (2) triangles generated per second in "cylinder" style (8 sides) on the same model after
--     7 steps (target: >= 50 M triangles/s);
--     both on every core (the model's default threads) and on one thread (threads = 1);
-- (3) OSMesa render time of a scene of about 1 M triangles at 1024x1024, with the default
--     3x supersampling and without.
-- Times are wall clock (the lsys program's monotonic clock; os.clock CPU time under plain
-- Lua), best of 3. Peak memory is this process's VmHWM at the end: (1) with records holds
-- the most (target: at most 1 GiB, half the 2 GiB before it).

local RUNS = 3
local B = dofile(((arg and arg[0] or "bench/interpret.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local clock_name, peak_mib = B.clock_name, B.peak_mib

local function best (f) return B.best(f, RUNS) end
local verdict = B.verdict
local threads = (lsys.core or require "lsys.core").default_threads
threads = type(threads) == "function" and threads() or os.getenv("LSYS_THREADS") or "all"

print(string.format("lsys %s, %s, best of %d; threads: %s (default) and 1", lsys.version,
  clock_name, RUNS, tostring(threads)))

-- Seconds of the best run of m:interpret(s, opts) on the default threads and on one.
local function timed (m, s, opts)
  m.threads = nil
  local t, sc = best(function () return m:interpret(s, opts) end)
  local counts = { segments = sc.nsegments, triangles = sc.ntriangles }
  sc = nil   -- luacheck: ignore 311 (the local would keep the scene alive through the next runs)
  m.threads = 1
  local t1 = best(function () return m:interpret(s, opts) end)
  m.threads = nil
  return t, t1, counts
end

-- (1) line style
local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F",
                         view = { angle = 25.7, line_style = "line" } }
local s = m:derive(10)
local n = #s
local t1, t1one, c1 = timed(m, s)
local t1n, t1none = timed(m, s, { records = false })
print(string.format("(1) line style, fig. 1.24a n=10: %d modules, %d segments", n, c1.segments))
print(string.format("    with records:    %.3f s  %7.1f M modules/s  (target >= 50)  %s"
  .. "   one thread: %.3f s  %5.1f M/s", t1, n / t1 / 1e6, verdict(n / t1 >= 50e6), t1one,
  n / t1one / 1e6))
print(string.format("    without records: %.3f s  %7.1f M modules/s  (target >= 100) %s"
  .. "   one thread: %.3f s  %5.1f M/s", t1n, n / t1n / 1e6, verdict(n / t1n >= 100e6),
  t1none, n / t1none / 1e6))
s = nil  -- luacheck: ignore 311 (frees the string before the next part)
collectgarbage()
local peak1 = peak_mib()

-- (2) cylinder style
local c = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F",
                         view = { angle = 25.7, line_style = "cylinder", contour_sides = 8,
                                  line_width = 0.3 } }
local s7 = c:derive(7)
local t2, t2one, c2 = timed(c, s7, { records = false })
local ntri = c2.triangles
print(string.format("(2) cylinder style, 8 sides, fig. 1.24a n=7: %d modules, %d triangles",
  #s7, ntri))
print(string.format("    %.3f s  %7.1f M triangles/s  (target >= 50)  %s   one thread: %.3f s"
  .. "  %5.1f M/s", t2, ntri / t2 / 1e6, verdict(ntri / t2 >= 50e6), t2one, ntri / t2one / 1e6))
collectgarbage()

-- (3) rendering about 1 M triangles
local r = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F",
                         view = { angle = 25.7, line_style = "cylinder", contour_sides = 6,
                                  line_width = 0.4, projection = "perspective" } }
local rs = r:derive(7)
local rsc = r:interpret(rs, { records = false })
if not (lsys.core or require "lsys.core").has_render then
  print("(3) rendering: not measured (lsys was built without OSMesa)")
else
  local out = os.tmpname() .. ".png"
  local t3 = best(function ()
    return lsys.render(rsc, { out = out, width = 1024, height = 1024 })
  end)
  local t3s = best(function ()
    return lsys.render(rsc, { out = out, width = 1024, height = 1024, supersample = 1 })
  end)
  os.remove(out)
  print(string.format("(3) OSMesa render of %d triangles at 1024x1024:", rsc.ntriangles))
  print(string.format("    supersample 3: %.3f s (%.1f M triangles/s)   supersample 1: %.3f s",
    t3, rsc.ntriangles / t3 / 1e6, t3s))
end

local peak = peak_mib()
if peak then
  print(string.format("peak memory (VmHWM): %.1f MiB, after (1) %.1f MiB  (target <= 1024)  %s",
    peak, peak1 or 0, verdict(peak <= 1024)))
end
