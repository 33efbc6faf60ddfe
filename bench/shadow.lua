-- The shadow-propagation grid (core.shadow; Palubicki et al. 2009 §4.1) and what it costs in
-- accuracy against ray casting (core.light). Each case runs in a fresh process, so that its
-- peak memory (VmHWM: the interpreter and the scenes included) is its own.
--
-- (a) Speed: 50,000 and 100,000 buds of the broadleaf tree of examples/default.lua (segment
-- ends moved just out of their stems, each record several times with a jitter, as
-- bench/light.lua takes them), each a caster and a query, as lsys.environment.shadow uses
-- them, in a grid of 64 voxels across the tree (depth 4, a = 1, b = 2) on 2 threads:
-- making the grid and adding the casters, the exposures, and the directions (a cone of 90
-- degrees, radius 2 voxels), each the best of 3 with the lists to and from Lua.
--
-- (b) Error: on two plants, the tree of examples/default.lua and the final scene of
-- examples/open/shade.lua (grown in its light environment), the light at 10,000 buds by
-- ray casting (core.light: 64 directions of the uniform overcast sky, the reference) and
-- by the grid built from the scene's triangles (S:add_scene: each at its centroid, weighing
-- its area over a voxel's face; the buds do not cast). The grid's exposure is mapped to
-- [0, 1] as lsys.environment.shadow maps it with casters = "scene": max(C - s, 0) / C, with
-- its default C = 8 and with the one C fitted to the rays (least squares over a log-spaced
-- scan of C). It prints, for three voxel sizes, the mean absolute and RMS errors, the rank
-- correlation (Spearman) of -s with the rays' light (which no mapping changes), and the
-- speed ratio: the rays' time (build and query) over the grid's (build, add_scene,
-- exposure), each the best of 3 on 2 threads. For scale, the errors of the constant
-- guess (the rays' mean) are printed too. It never fails on its figures.
--
--   build/bin/lsys bench/shadow.lua               every case, as tables
--   build/bin/lsys bench/shadow.lua speed 100000  one case (or "error tree", "error shade"):
--                                                 a RESULT line
local B = dofile((arg and arg[0] or "bench/shadow.lua"):match("^(.*)/[^/]*$") .. "/common.lua")
local format = string.format

local THREADS = 2
local NERR = 10000
local C_DEFAULT = 8          -- lsys.environment.shadow's
local ACROSS = { 24, 48, 96 }   -- voxels across the plant's largest extent, case (b)


-- a small deterministic generator (the same points every run)
local function lcg (seed)
  local s = seed
  return function ()
    s = (s * 1103515245 + 12345) % 2147483648
    return s / 2147483648
  end
end

-- n buds: the ends of the scene's segments, each moved out of its stem along its record's L
-- by its radius and 1 % more, taken in turn with a jitter of 1 % of the stem's length;
-- their headings (the records' H)
local function buds (scene, n)
  local ends = {}
  for _, rec in scene:records() do
    if rec.kind == "segment" and rec.length > 0 then ends[#ends + 1] = rec end
  end
  local r, p, h = lcg(11), {}, {}
  for i = 0, n - 1 do
    local rec = ends[(i * 7919) % #ends + 1]
    local out, j = 0.505 * rec.w1, 0.01 * rec.length
    for c = 1, 3 do
      p[3 * i + c] = rec.p1[c] + out * rec.L[c] + j * (r() - 0.5)
      h[3 * i + c] = rec.H[c]
    end
  end
  return p, h
end

local function tree () return dofile(B.root .. "/examples/default.lua"):interpret() end
local function shade ()
  local m = dofile(B.root .. "/examples/open/shade.lua")
  return m:interpret(m:derive())
end

-- the box of the scene widened by m on every side, and its largest extent
local function box (scene, m)
  local lo, hi = scene:bounds()
  local ext = math.max(hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3])
  return { lo[1] - m, lo[2] - m, lo[3] - m }, { hi[1] + m, hi[2] + m, hi[3] + m }, ext
end

-- child (a): n casters and queries
local function speed (n)
  B.load_lsys()
  local core = require "lsys.core"
  local scene = tree()
  local p, h = buds(scene, n)
  local _, _, ext = box(scene, 0)
  local voxel = ext / 64
  local lo, hi = box(scene, 3 * voxel)
  scene = nil    -- luacheck: ignore 311 (its memory goes before the measures)
  collectgarbage()
  local S
  local tadd = B.best(function ()
    if S then S:close() end
    S = core.shadow { lo = lo, hi = hi, voxel = voxel, threads = THREADS }
    S:add(p)
  end, 3)
  local q
  local texp = B.best(function () q = S:exposure(p, C_DEFAULT) end, 3)
  local tdir = B.best(function () S:direction(p, h) end, 3)
  local mean = 0
  for i = 1, #q do mean = mean + q[i] / C_DEFAULT end
  local st = S:stats()
  io.write(format("RESULT n=%d voxels=%d nx=%d ny=%d nz=%d add=%.6f exposure=%.6f "
    .. "direction=%.6f meanq=%.4f peak_mib=%.1f\n", n, st.voxels, st.nx, st.ny, st.nz, tadd,
    texp, tdir, mean / #q, B.peak_mib() or -1))
end

-- average ranks of the list v (ties share theirs)
local function ranks (v)
  local idx = {}
  for i = 1, #v do idx[i] = i end
  table.sort(idx, function (a, b) return v[a] < v[b] end)
  local rk, i = {}, 1
  while i <= #idx do
    local j = i
    while j < #idx and v[idx[j + 1]] == v[idx[i]] do j = j + 1 end
    for k = i, j do rk[idx[k]] = (i + j) / 2 end
    i = j + 1
  end
  return rk
end

local function correlation (a, b)
  local n, ma, mb = #a, 0, 0
  for i = 1, n do ma, mb = ma + a[i], mb + b[i] end
  ma, mb = ma / n, mb / n
  local sab, saa, sbb = 0, 0, 0
  for i = 1, n do
    sab = sab + (a[i] - ma) * (b[i] - mb)
    saa = saa + (a[i] - ma) ^ 2
    sbb = sbb + (b[i] - mb) ^ 2
  end
  return sab / math.sqrt(saa * sbb)
end

-- the mean absolute and RMS errors of max(C - s, 0) / C against E
local function errors (s, E, C)
  local ae, se = 0, 0
  for i = 1, #E do
    local d = math.max(C - s[i], 0) / C - E[i]
    ae, se = ae + math.abs(d), se + d * d
  end
  return ae / #E, math.sqrt(se / #E)
end

-- child (b): one plant
local function accuracy (which)
  B.load_lsys()
  local core = require "lsys.core"
  local scene = which == "tree" and tree() or shade()
  local p = buds(scene, NERR)
  collectgarbage()
  local E
  local tray = B.best(function ()
    local L <close> = core.light(scene, { samples = 64, threads = THREADS })
    E = L:query(p)
  end, 3)
  local mean = 0
  for i = 1, #E do mean = mean + E[i] end
  mean = mean / #E
  local cae, cse = 0, 0
  for i = 1, #E do cae, cse = cae + math.abs(E[i] - mean), cse + (E[i] - mean) ^ 2 end
  local rE = ranks(E)
  local out = { format("RESULT scene=%s triangles=%d buds=%d ray=%.6f mean=%.4f cmae=%.4f "
    .. "crms=%.4f", which, scene.ntriangles, #E, tray, mean, cae / #E, math.sqrt(cse / #E)) }
  local _, _, ext = box(scene, 0)
  for k, across in ipairs(ACROSS) do
    local voxel = ext / across
    local lo, hi = box(scene, voxel)
    local s
    local tgrid = B.best(function ()
      local S <close> = core.shadow { lo = lo, hi = hi, voxel = voxel, threads = THREADS }
      S:add_scene(scene)
      s = S:shadow(p)            -- the exposure max(C - s, 0) is made of it below
    end, 3)
    local neg = {}
    for i = 1, #s do neg[i] = -s[i] end
    local rho = correlation(ranks(neg), rE)
    local dmae, drms = errors(s, E, C_DEFAULT)
    local best, bc, bmae = math.huge, nil, nil
    for j = -20, 60 do                     -- C from 0.1 to 1000, 20 a decade
      local C = 10 ^ (j / 20)
      local mae, rms = errors(s, E, C)
      if rms < best then best, bc, bmae = rms, C, mae end
    end
    out[#out + 1] = format("v%d_across=%d v%d_voxel=%.6g v%d_grid=%.6f v%d_rho=%.4f "
      .. "v%d_dmae=%.4f v%d_drms=%.4f v%d_fitc=%.4g v%d_fmae=%.4f v%d_frms=%.4f", k, across,
      k, voxel, k, tgrid, k, rho, k, dmae, k, drms, k, bc, k, bmae, k, best)
  end
  out[#out + 1] = format("peak_mib=%.1f\n", B.peak_mib() or -1)
  io.write(table.concat(out, " "))
end

local measure = B.measure

local mode, what = arg and arg[1], arg and arg[2]
if mode == "speed" and tonumber(what) then
  speed(math.tointeger(tonumber(what)))
  return
elseif mode == "error" and (what == "tree" or what == "shade") then
  accuracy(what)
  return
elseif mode ~= nil then
  io.stderr:write("usage: lsys bench/shadow.lua [speed N | error tree | error shade]\n")
  os.exit(2)
end

print(format("core.shadow: %d threads, %s, best of 3", THREADS, B.clock_name))
print("\n(a) speed: buds of examples/default.lua, each a caster and a query; 64 voxels across, "
      .. "depth 4")
for _, n in ipairs { 50000, 100000 } do
  local r = measure("speed " .. n)
  local total = r.add + r.exposure + r.direction
  print(format("  %6d buds, grid %d x %d x %d: build+add %5.1f ms, exposure %5.1f ms, "
    .. "direction %5.1f ms; peak %.0f MiB; a pass under 100 ms: %s", n, r.nx, r.ny, r.nz,
    1000 * r.add, 1000 * r.exposure, 1000 * r.direction, r.peak_mib, B.verdict(total < 0.1)))
end

print(format("\n(b) error against ray casting (core.light, 64 uniform overcast directions) at "
  .. "%d buds;\n    the grid from the scene's triangles, max(C - s, 0) / C, C = %d or fitted",
  NERR, C_DEFAULT))
for _, which in ipairs { "tree", "shade" } do
  local r = measure("error " .. which)
  print(format("\n  %s: %d triangles; rays %.0f ms (mean light %.3f; the constant guess: "
    .. "MAE %.3f, RMS %.3f)", which == "tree" and "examples/default.lua"
    or "examples/open/shade.lua", r.triangles, 1000 * r.ray, r.mean, r.cmae, r.crms))
  for k = 1, #ACROSS do
    local function f (name) return r["v" .. k .. "_" .. name] end
    print(format("    %2d voxels across (%.3g): rank corr %.2f; C = %d: MAE %.3f RMS %.3f; "
      .. "C = %.3g fitted: MAE %.3f RMS %.3f; grid %.0f ms, %.1fx faster; rank corr > 0.5 "
      .. "and 5x faster: %s", f("across"), f("voxel"), f("rho"), C_DEFAULT, f("dmae"),
      f("drms"), f("fitc"), f("fmae"), f("frms"), 1000 * f("grid"), r.ray / f("grid"),
      B.verdict(f("rho") > 0.5 and r.ray / f("grid") > 5)))
  end
  print(format("    peak memory (VmHWM) %.0f MiB", r.peak_mib))
end
