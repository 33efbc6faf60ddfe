-- The cost of baked shadows and ambient occlusion (lsys.render's shadows, ao and ground
-- options, csrc/core/shade.c) on the default plant of `lsys render` (examples/default.lua,
-- about 720,000 triangles), at 800 x 800 with the default supersampling (3 x 3): the
-- picture without them, with shadows and the ground (what `lsys render` draws for a 3D
-- plant), and with shadows, ambient occlusion (16 rays a face) and the ground, each the
-- best of 3, on 2 threads. The rays per second count what the shading casts: one shadow
-- ray a vertex (an upper bound: vertices turned away from the light cast none) and 32
-- occlusion rays a face of a vertex (two faces for two-sided vertices; counted as two
-- for all, an upper bound again), over the time the shading adds to the plain picture.
-- The target: `lsys render`'s default picture (shadows and ground) under 5 s on 2 cores.
-- It never fails on its figures.
--
--   build/bin/lsys bench/render.lua
local B = dofile((arg and arg[0] or "bench/render.lua"):match("^(.*)/[^/]*$") .. "/common.lua")
local lsys = B.load_lsys()
local format = string.format

local m = dofile(B.root .. "/examples/default.lua")
local scene = m:interpret()
local nv = scene.nvertices
local function shot (extra)
  local o = { width = 800, height = 800, supersample = 3 }
  for k, v in pairs(extra) do o[k] = v end
  return function () return (lsys.render(scene, o)) end
end
print(format("the default plant: %d triangles, %d vertices; %s", scene.ntriangles, nv,
             B.clock_name))
local plain = B.best(shot {}, 3)
local sg = B.best(shot { shadows = true, ground = true }, 3)
local all = B.best(shot { shadows = true, ground = true, ao = { samples = 16 } }, 3)
print(format("%-34s %9s %14s", "picture", "ms", "rays/s"))
print(format("%-34s %9.0f %14s", "plain", plain * 1000, "-"))
print(format("%-34s %9.0f %14.3g", "shadows + ground", sg * 1000,
             nv / math.max(sg - plain, 1e-9)))
print(format("%-34s %9.0f %14.3g", "shadows + ambient occlusion + ground", all * 1000,
             nv * (1 + 64) / math.max(all - plain, 1e-9)))
print(format("RESULT plain_ms=%.0f shadows_ms=%.0f shadows_ao_ms=%.0f", plain * 1000,
             sg * 1000, all * 1000))
print(format("target: shadows + ground under 5 s: %s", B.verdict(sg < 5)))
