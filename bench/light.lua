-- The light environment (core.light): ray casting from query points to the sky through the
-- hierarchy over a scene's triangles. Two scenes of about a million triangles, each in a fresh
-- process: the broadleaf tree of examples/default.lua (720,696 triangles) and the meadow of
-- examples/population/field.lua (973,682 triangles drawn by 10,001 instances, flattened by
-- the build). For each it prints the build time (best of 3), the hierarchy's size, and for
-- 100,000 queries of the 64-direction uniform overcast sky on 2 threads (best of 3, with
-- the lists to and from Lua) the time of the batch, rays per second, and the process's peak
-- memory (VmHWM, the interpreter and the scene included), for two sets of points: random in
-- the scene's bounding box (many rays escape through the crown: the slow case), and buds
-- (segment ends moved just outside their stem, every record several times with a small
-- jitter: rays from inside the crown). It prints its figures next to the target (the whole
-- query under 1 s on 2 cores) and never fails on them.
--
-- On the project's two-core machine (AMD EPYC, Release build, -O2; the best of three runs with
-- other builds sharing it) a batch took 0.73 s (random points) and 0.90 s (buds) on the tree
-- and 0.72 s on the meadow, the whole script 18 s of user CPU time; before the rays of a
-- direction went through the hierarchy in packets (csrc/core/light_ray.c) it took 1.57, 1.55
-- and 1.09 s, and 30 s.
--
--   build/bin/lsys bench/light.lua               both scenes, as a table
--   build/bin/lsys bench/light.lua tree          one (or "field"): a RESULT line
local B = dofile((arg and arg[0] or "bench/light.lua"):match("^(.*)/[^/]*$") .. "/common.lua")
local format = string.format

local N = 100000
local THREADS = 2


-- a small deterministic generator (the same points every run)
local function lcg (seed)
  local s = seed
  return function ()
    s = (s * 1103515245 + 12345) % 2147483648
    return s / 2147483648
  end
end

-- N points uniformly in the box lo .. hi, as a flat list
local function boxpoints (lo, hi)
  local r, p = lcg(7), {}
  for i = 0, N - 1 do
    for c = 1, 3 do p[3 * i + c] = lo[c] + (hi[c] - lo[c]) * r() end
  end
  return p
end

-- N buds: the ends of the scene's segments, each moved out of its stem along its record's L
-- by its radius and 1 % more, taken in turn with a jitter of 1 % of the stem's length
local function budpoints (scene)
  local ends = {}
  for _, rec in scene:records() do
    if rec.kind == "segment" and rec.length > 0 then ends[#ends + 1] = rec end
  end
  local r, p = lcg(11), {}
  for i = 0, N - 1 do
    local rec = ends[i % #ends + 1]
    local out, j = 0.505 * rec.w1, 0.01 * rec.length
    for c = 1, 3 do p[3 * i + c] = rec.p1[c] + out * rec.L[c] + j * (r() - 0.5) end
  end
  return p, #ends
end

local SCENES = {
  tree = function () return dofile(B.root .. "/examples/default.lua"):interpret() end,
  field = function () return dofile(B.root .. "/examples/population/field.lua") end,
}

-- child: one scene, measured in this process
local function child (which)
  B.load_lsys()
  local core = require "lsys.core"
  local scene = SCENES[which]()
  local lo, hi = scene:bounds()
  local box = boxpoints(lo, hi)
  local bud, nbud
  if which == "tree" then bud, nbud = budpoints(scene) end
  collectgarbage()
  local light
  local build = B.best(function ()
    if light then light:close() end
    light = core.light(scene, { threads = THREADS })
  end, 3)
  local st = light:stats()
  local function query (p)
    local v
    local t = B.best(function () v = light:query(p) end, 3)
    local sum = 0
    for i = 1, #v do sum = sum + v[i] end
    return t, sum / #v
  end
  local tbox, mbox = query(box)
  local tbud, mbud = -1, -1
  if bud then tbud, mbud = query(bud) end
  io.write(format("RESULT scene=%s triangles=%d nodes=%d bytes=%d build=%.6f box=%.6f "
    .. "boxmean=%.4f bud=%.6f budmean=%.4f ends=%d peak_mib=%.1f\n", which, st.triangles,
    st.nodes, st.bytes, build, tbox, mbox, tbud, mbud, nbud or 0, B.peak_mib() or -1))
end

local measure = B.measure

local mode = arg and arg[1]
if SCENES[mode] then
  child(mode)
  return
end
if mode ~= nil then
  io.stderr:write("usage: lsys bench/light.lua [tree | field]\n")
  os.exit(2)
end

local rays = N * 64
print(format("core.light: %d queries x 64 overcast directions = %d rays a batch, %d threads, "
             .. "%s", N, rays, THREADS, B.clock_name))
for _, which in ipairs { "tree", "field" } do
  local r = measure(which)
  print(format("\n%s: %d triangles; hierarchy %d nodes, %.1f MiB; build %.0f ms (best of 3)",
               which, r.triangles, r.nodes, r.bytes / 1048576, 1000 * r.build))
  local function row (name, t, mean)
    print(format("  %-34s %7.0f ms  %5.2f M rays/s  mean light %.3f  target < 1 s: %s",
                 name, 1000 * t, rays / t / 1e6, mean, B.verdict(t < 1)))
  end
  row("points random in the bounds", r.box, r.boxmean)
  if r.bud > 0 then row(format("buds (%d segment ends)", r.ends), r.bud, r.budmean) end
  print(format("  peak memory (VmHWM) %.0f MiB", r.peak_mib))
end
