-- Space (core.space, core.markers) and the environments on it. Each case runs in a fresh
-- process, on 2 threads, timed best of 3 (wall clock when run by the lsys program), with the
-- process's peak memory (VmHWM, the interpreter and the inputs included):
--
--   collision  100,000 ?E queries (tables, as a pass hands them over) uniformly in a cube of
--              side 50, radius 1 (about 3.4 neighbours each): a pass of
--              lsys.environment.collision (the lists made in Lua, then the C hash and test),
--              the core alone on flat lists (core.space + space:free), and the Lua algorithm
--              the environment had before (kept below: a hash of cells in Lua tables);
--   density    the same queries: lsys.environment.space { answer = "density" }, and the core
--              alone (core.space + space:density);
--   colonize   100,000 markers in a sphere of radius 20 and 10,000 buds in it, random headings,
--              perception 3, cone 90 degrees, kill radius 0.5: one pass of markers:perceive
--              (fresh markers each run), and of lsys.environment.colonize's answer (the lists
--              made in Lua from 10,000 queries);
--   resource   a field of 128 x 64 x 128 cells (about a million): a pass of
--              lsys.environment.resource with 100,000 ?E queries (a source fed, one unit of
--              time diffused, the takes), and the diffusion alone (field:diffuse, 6 substeps).
--
-- It prints its figures next to the targets (a pass of 100,000 collision queries under
-- 0.1 s; C at least 5 times the Lua algorithm; a colonisation pass under 0.25 s; a resource
-- pass under 0.25 s) and never fails on them.
--
--   build/bin/lsys bench/space.lua               every case, as a table
--   build/bin/lsys bench/space.lua collision     one (or density, colonize, resource): a
--                                                RESULT line
local B = dofile((arg and arg[0] or "bench/space.lua"):match("^(.*)/[^/]*$") .. "/common.lua")
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

-- N queries uniformly in the cube [0, 50)^3, vigours 0 .. 3, one group
local function queries ()
  local r, q = lcg(7), {}
  for i = 1, N do
    q[i] = { position = { 50 * r(), 50 * r(), 50 * r() }, params = { math.floor(4 * r()) },
             heading = { 0, 1, 0 } }
  end
  return q
end

local function flat (q)
  local p, v = {}, {}
  for i = 1, #q do
    local x = q[i].position
    p[3 * i - 2], p[3 * i - 1], p[3 * i] = x[1], x[2], x[3]
    v[i] = q[i].params[1]
  end
  return p, v
end

-- The collision environment as it was written in Lua before core.space (lua/lsys/
-- environment/collision.lua), for the comparison.
local function luacollision (qs, r)
  local floor = math.floor
  local r2 = r * r
  local function cell (p) return floor(p[1] / r), floor(p[2] / r), floor(p[3] / r) end
  local function key (x, y, z) return x * 73856093 ~ y * 19349663 ~ z * 83492791 end
  local cells = {}
  for i, q in ipairs(qs) do
    local k = key(cell(q.position))
    local c = cells[k]
    if c == nil then c = {}; cells[k] = c end
    c[#c + 1] = i
  end
  local answers = {}
  for i, q in ipairs(qs) do
    local p, v, g = q.position, q.params[1] or 0, q.params[2] or 0
    local cx, cy, cz = cell(p)
    local free = 1
    for dx = -1, 1 do
      for dy = -1, 1 do
        for dz = -1, 1 do
          for _, j in ipairs(cells[key(cx + dx, cy + dy, cz + dz)] or {}) do
            local o = qs[j]
            if j ~= i and (o.params[2] or 0) == g and v <= (o.params[1] or 0) then
              local ex, ey, ez = p[1] - o.position[1], p[2] - o.position[2],
                                 p[3] - o.position[3]
              if ex * ex + ey * ey + ez * ez <= r2 then free = 0 end
            end
          end
        end
      end
    end
    answers[i] = free
  end
  return answers
end

local CASES = {}

function CASES.collision (lsys, core)
  local q = queries()
  local p, v = flat(q)
  local env = lsys.environment.collision { radius = 1, threads = THREADS }
  local a
  local tenv = B.best(function () a = env:answer(q) end, 3)
  local tcore = B.best(function ()
    local S <close> = core.space(p, { radius = 1, vigour = v, threads = THREADS })
    S:free()
  end, 3)
  local b
  local tlua = B.best(function () b = luacollision(q, 1) end, 3)
  local same, free = 1, 0
  for i = 1, N do
    if a[i] ~= b[i] then same = 0 end
    free = free + a[i]
  end
  return format("env=%.6f core=%.6f lua=%.6f same=%d free=%d", tenv, tcore, tlua, same, free)
end

function CASES.density (lsys, core)
  local q = queries()
  local p = flat(q)
  local env = lsys.environment.space { radius = 1, answer = "density", threads = THREADS }
  local a
  local tenv = B.best(function () a = env:answer(q, {}) end, 3)
  local tcore = B.best(function ()
    local S <close> = core.space(p, { radius = 1, threads = THREADS })
    S:density()
  end, 3)
  local sum = 0
  for i = 1, N do sum = sum + a[i] end
  return format("env=%.6f core=%.6f mean=%.4f", tenv, tcore, sum / N)
end

function CASES.colonize (lsys, core)
  local r = lcg(11)
  local function insphere (R)
    while true do
      local x, y, z = R * (2 * r() - 1), R * (2 * r() - 1), R * (2 * r() - 1)
      if x * x + y * y + z * z <= R * R then return x, y, z end
    end
  end
  local m = {}
  for i = 1, 100000 do m[3 * i - 2], m[3 * i - 1], m[3 * i] = insphere(20) end
  local nb = 10000
  local b, h, qs = {}, {}, {}
  for i = 1, nb do
    local x, y, z = insphere(20)
    local hx, hy, hz = insphere(1)
    b[3 * i - 2], b[3 * i - 1], b[3 * i] = x, y, z
    h[3 * i - 2], h[3 * i - 1], h[3 * i] = hx, hy, hz + 1e-9
    qs[i] = { position = { x, y, z }, heading = { hx, hy, hz + 1e-9 }, params = { 0, 0, 0, 0 } }
  end
  local opts = { perception = 3, angle = 90, kill = 0.5, threads = THREADS }
  local won, left
  local tpass = math.huge                         -- the markers made afresh: not timed
  for _ = 1, 3 do
    local M <close> = core.markers(m)
    collectgarbage()
    local t0 = B.clock()
    local c = M:perceive(b, h, opts)
    tpass = math.min(tpass, B.clock() - t0)
    won, left = 0, #M
    for i = 1, nb do won = won + c[i] end
  end
  local tenv = math.huge
  for _ = 1, 3 do
    local env = lsys.environment.colonize { markers = m, perception = 3, angle = 90, kill = 0.5,
                                            threads = THREADS }
    env:count()                                   -- the markers made: not timed
    collectgarbage()
    local t0 = B.clock()
    env:answer(qs)
    tenv = math.min(tenv, B.clock() - t0)
  end
  return format("pass=%.6f env=%.6f won=%d left=%d", tpass, tenv, won, left)
end

function CASES.resource (lsys, core)
  local q = queries()
  for i = 1, N do
    local p = q[i].position
    p[1], p[2], p[3] = p[1] / 50 * 16, -p[2] / 50 * 8, p[3] / 50 * 16   -- into the soil box
    q[i].params = { 0.01, 0, 0, 0 }
  end
  local opts = { lo = { 0, -8, 0 }, hi = { 16, 0, 16 }, cell = 0.125, initial = 0.1,
                 diffusion = 0.015625, sources = { { 8, -4, 8, 100 } }, threads = THREADS }
  local tenv = math.huge
  for _ = 1, 3 do
    local env = lsys.environment.resource(opts)
    env:total()                                    -- the field made: not timed
    collectgarbage()
    local t0 = B.clock()
    env:answer(q)
    tenv = math.min(tenv, B.clock() - t0)
    env:start()
  end
  local F <close> = core.field { lo = opts.lo, hi = opts.hi, cell = opts.cell,
                                 threads = THREADS }
  F:fill(1)
  local m
  local tdiff = B.best(function () m = F:diffuse(opts.diffusion, 1) end, 3)
  local nx, ny, nz = F:dims()
  return format("env=%.6f diffuse=%.6f substeps=%d cells=%d", tenv, tdiff, m, nx * ny * nz)
end

local mode = arg and arg[1]
if CASES[mode] then
  local lsys = B.load_lsys()
  local core = require "lsys.core"
  local line = CASES[mode](lsys, core)
  io.write(format("RESULT case=%s %s peak_mib=%.1f\n", mode, line, B.peak_mib() or -1))
  return
end
if mode ~= nil then
  io.stderr:write("usage: lsys bench/space.lua [collision | density | colonize | resource]\n")
  os.exit(2)
end

local measure = B.measure

print(format("core.space and core.markers: %d threads, best of 3, %s", THREADS, B.clock_name))
local c = measure("collision")
print(format("\ncollision, %d queries, radius 1 (%d answered 1; the C answers %s the Lua "
  .. "algorithm's):", N, c.free, c.same == 1 and "equal" or "DIFFER FROM"))
print(format("  %-44s %7.1f ms   target < 100 ms: %s", "lsys.environment.collision (a pass)",
             1000 * c.env, B.verdict(c.env < 0.1)))
print(format("  %-44s %7.1f ms", "core.space + space:free on flat lists", 1000 * c.core))
print(format("  %-44s %7.1f ms   C %.1f times faster, target >= 5: %s",
             "the Lua algorithm (before core.space)", 1000 * c.lua, c.lua / c.env,
             B.verdict(c.lua / c.env >= 5)))
print(format("  peak memory (VmHWM) %.0f MiB", c.peak_mib))
local d = measure("density")
print(format("\ndensity, %d queries, radius 1 (mean %.3f):", N, d.mean))
print(format("  %-44s %7.1f ms   target < 100 ms: %s", "lsys.environment.space (a pass)",
             1000 * d.env, B.verdict(d.env < 0.1)))
print(format("  %-44s %7.1f ms", "core.space + space:density on flat lists", 1000 * d.core))
print(format("  peak memory (VmHWM) %.0f MiB", d.peak_mib))
local k = measure("colonize")
print(format("\ncolonisation, 100,000 markers x 10,000 buds, perception 3, 90 degrees, kill 0.5 "
  .. "(%d markers won, %d left):", k.won, k.left))
print(format("  %-44s %7.1f ms   target < 250 ms: %s", "markers:perceive (a pass)",
             1000 * k.pass, B.verdict(k.pass < 0.25)))
print(format("  %-44s %7.1f ms   target < 250 ms: %s", "lsys.environment.colonize (a pass)",
             1000 * k.env, B.verdict(k.env < 0.25)))
print(format("  peak memory (VmHWM) %.0f MiB", k.peak_mib))
local f = measure("resource")
print(format("\nresource, %d cells, %d queries:", f.cells, N))
print(format("  %-44s %7.1f ms   target < 250 ms: %s", "lsys.environment.resource (a pass)",
             1000 * f.env, B.verdict(f.env < 0.25)))
print(format("  %-44s %7.1f ms", format("field:diffuse (%d substeps)", f.substeps),
             1000 * f.diffuse))
print(format("  peak memory (VmHWM) %.0f MiB", f.peak_mib))
