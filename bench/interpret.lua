-- Interpretation and rendering benchmark.
--
--   build/bin/lsys bench/interpret.lua [--cpfg PATH]      (or CPFG=PATH)
--
-- (1) turtle throughput in "line" style on the ABOP fig. 1.24a string after 10 steps
--     (F --> F[+F]F[-F]F, 24.4 M modules): modules per second, with turtle records (the
--     default; target, issue 41: >= 100 M/s on two threads, and on one thread at least
--     cpfg's turtle pass) and without;
-- (2) triangles generated per second in "cylinder" style (8 sides) on the same model after
--     7 steps (target: >= 50 M triangles/s);
--     both on every core (the model's default threads) and on one thread (threads = 1);
-- (3) OSMesa render time of a scene of about 1 M triangles at 1024x1024, with the default
--     3x supersampling and without.
-- Times are wall clock (the lsys program's monotonic clock; os.clock CPU time under plain
-- Lua), best of 3. Peak memory is this process's VmHWM at the end: (1) with records holds
-- the most (target: at most 512 MiB, half the 1 GiB before records were packed).
--
-- With cpfg (a cpfg built for batch use, docs/cpfg.md, which honours CPFG_SKIP_VV), cpfg's
-- turtle pass on the same string is timed beside (1): `cpfg -g -m e.map fig.l e.v` runs a
-- view-volume pass of its turtle over the derived string, which CPFG_SKIP_VV=1 leaves out,
-- so the pass is the difference of the two, whole processes, best of 5 each. Beside it the
-- peak memory (GNU time's %M) of the 24 M-module interpretation with records in a process of
-- its own (`bench/interpret.lua peak`: derive, interpret once) and of cpfg's run.

local B = dofile(((arg and arg[0] or "bench/interpret.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")

-- child "peak": the 24 M-module interpretation with records, alone in its process
if arg and arg[1] == "peak" then
  local lsys = B.load_lsys()
  local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F",
                           view = { angle = 25.7, line_style = "line" } }
  local sc = m:interpret(m:derive(10))
  io.write(sc.nrecords, "\n")
  return
end

local CPFG = arg and arg[1] == "--cpfg" and arg[2] or os.getenv("CPFG")
if arg and arg[1] == "--cpfg" and not arg[2] then
  io.stderr:write("interpret.lua: --cpfg needs the path of a cpfg program\n")
  os.exit(2)
end
if CPFG == "" then CPFG = nil end

local RUNS = 3
local RUNS_WHOLE = 5
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

local TIME = B.has_time
local function whole (cmd, runs) return B.whole(cmd .. " >/dev/null", runs) end

-- cpfg's turtle pass over fig. 1.24a after 10 steps: seconds and cpfg's peak KiB.
local function cpfg_pass (cpfg)
  local dir = B.cpfg_folder(string.format("angle factor: %.6f\n", 360 / 25.7))
  B.write_file(dir .. "/fig.l", "lsystem: 1\nderivation length: 10\nAxiom: F\n"
    .. "F --> F[+F]F[-F]F\nendlsystem\n")
  local function cmd (skip)
    local q = B.shell_quote(dir)
    return string.format("env%s %s -g -m %s/e.map %s/fig.l %s/e.v",
      skip and " CPFG_SKIP_VV=1" or "", B.shell_quote(cpfg), q, q, q)
  end
  local ok, with, kib, without = pcall(function ()   -- interleaved (bench/common.lua)
    local r = B.wholes({ cmd(false) .. " >/dev/null", cmd(true) .. " >/dev/null" }, RUNS_WHOLE)
    return r[1][1], r[1][2], r[2][1]
  end)
  B.rmdir(dir)
  if not ok then return nil, with end
  return math.max(with - without, 1e-9), kib
end

-- (1) line style
local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F",
                         view = { angle = 25.7, line_style = "line" } }
local s = m:derive(10)
local n = #s
local t1, t1one, c1 = timed(m, s)
local t1n, t1none = timed(m, s, { records = false })
print(string.format("(1) line style, fig. 1.24a n=10: %d modules, %d segments", n, c1.segments))
print(string.format("    with records:    %.3f s  %7.1f M modules/s  (target >= 100) %s"
  .. "   one thread: %.3f s  %5.1f M/s", t1, n / t1 / 1e6, verdict(n / t1 >= 100e6), t1one,
  n / t1one / 1e6))
print(string.format("    without records: %.3f s  %7.1f M modules/s"
  .. "                 one thread: %.3f s  %5.1f M/s", t1n, n / t1n / 1e6,
  t1none, n / t1none / 1e6))
s = nil  -- luacheck: ignore 311 (frees the string before the next part)
collectgarbage()
local peak1 = peak_mib()
do
  local lpeak = TIME and select(2, whole(B.self_command() .. " peak", 1))
  local mem = function (kib) return kib and string.format("%.1f MiB", kib / 1024) or "?" end
  if CPFG then
    local tc, ckib = cpfg_pass(CPFG)
    if not tc then
      print("    cpfg: " .. CPFG .. " failed: " .. tostring(ckib))
    else
      local rc = n / tc
      print(string.format("    cpfg's turtle pass (%s -g, view volume: without minus with "
        .. "CPFG_SKIP_VV=1, whole processes, best of %d): %.3f s  %5.1f M modules/s",
        CPFG, RUNS_WHOLE, tc, rc / 1e6))
      print(string.format("    lsys with records / cpfg: %.2fx, one thread %.2fx  (target >= 1x "
        .. "on one thread)  %s", n / t1 / rc, n / t1one / rc, verdict(n / t1one >= rc)))
      print(string.format("    peak memory (GNU time %%M), the interpretation with records in a "
        .. "process of its own: lsys %s (target <= 512 MiB) %s; cpfg %s", mem(lpeak),
        verdict(lpeak ~= nil and lpeak <= 512 * 1024), mem(ckib)))
    end
  else
    print("    cpfg: not given (--cpfg PATH or CPFG=PATH; docs/cpfg.md says how to build it)")
    print(string.format("    peak memory (GNU time %%M), the interpretation with records in a "
      .. "process of its own: lsys %s (target <= 512 MiB) %s", mem(lpeak),
      verdict(lpeak ~= nil and lpeak <= 512 * 1024)))
  end
end

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
  print(string.format("peak memory (VmHWM) of this process, all runs: %.1f MiB, after (1) %.1f "
    .. "MiB (the target is judged on the interpretation's own process, above)", peak,
    peak1 or 0))
end
