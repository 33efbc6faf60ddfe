-- Populations: the field of examples/population/field.lua -- 10,000 plants of 20
-- kinds and a ground tile -- built, drawn and exported as instances, beside the same scene
-- written out (scene:flatten()). For each it prints the plants, the prototypes, the
-- triangles drawn, the bytes the scene holds, the time to build it, to render it (800 x 800,
-- supersampled 3 x 3, best of 3) and to write it as .glb (and the file's size), and the peak
-- memory of a fresh process that does just that (VmHWM, the interpreter included).
--
--   build/bin/lsys bench/population.lua            both, as a table
--   build/bin/lsys bench/population.lua instanced  one (or "flattened"): a RESULT line
local B = dofile((arg and arg[0] or "bench/population.lua"):match("^(.*)/[^/]*$") ..
                 "/common.lua")
local format = string.format

local FIELD = B.root .. "/examples/population/field.lua"
local SIZE = 800


-- child: one way of holding the field, measured in this process
local function child (mode)
  local lsys = B.load_lsys()
  local t0 = B.clock()
  local scene = dofile(FIELD)
  local plants, protos = scene.ninstances, scene.nprototypes
  if mode == "flattened" then scene = scene:flatten() end
  local build = B.clock() - t0
  collectgarbage()
  local render = B.best(function ()
    return lsys.render(scene, { width = SIZE, height = SIZE })
  end, 3)
  local path = os.tmpname()
  os.remove(path)
  path = path .. ".glb"
  t0 = B.clock()
  scene:save(path)
  local save = B.clock() - t0
  local f = io.open(path, "rb")
  local glb = f:seek("end")
  f:close()
  os.remove(path)
  io.write(format("RESULT mode=%s plants=%d prototypes=%d triangles=%d bytes=%d build=%.6f "
    .. "render=%.6f save=%.6f glb=%d peak_mib=%.1f\n", mode, plants, protos, scene.ntriangles,
    scene.bytes, build, render, save, glb, B.peak_mib() or -1))
end

local measure = B.measure

local function mib (b) return format("%.1f MiB", b / 1048576) end
local function ms (s) return format("%.0f ms", 1000 * s) end

local mode = arg and arg[1]
if mode == "instanced" or mode == "flattened" then
  child(mode)
  return
end
if mode ~= nil then
  io.stderr:write("usage: lsys bench/population.lua [instanced | flattened]\n")
  os.exit(2)
end

local a, b = measure("instanced"), measure("flattened")
print(format("examples/population/field.lua: %d plants of %d prototypes, %dx%d pictures, %s",
             a.plants, a.prototypes, SIZE, SIZE, B.clock_name))
print(format("%-22s %16s %16s %9s", "", "instanced", "flattened", "ratio"))
local rows = {
  { "triangles drawn", a.triangles, b.triangles, tostring },
  { "scene memory", a.bytes, b.bytes, mib },
  { "build", a.build, b.build, ms },
  { "render (best of 3)", a.render, b.render, ms },
  { "write .glb", a.save, b.save, ms },
  { ".glb size", a.glb, b.glb, mib },
  { "peak memory (VmHWM)", a.peak_mib * 1048576, b.peak_mib * 1048576, mib },
}
for _, r in ipairs(rows) do
  print(format("%-22s %16s %16s %8.2fx", r[1], r[4](r[2]), r[4](r[3]),
               r[3] > 0 and r[2] / r[3] or 0))
end
