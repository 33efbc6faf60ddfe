-- Component graphs benchmark: expanding a chestnut-like plant into a scene.
--
--   build/bin/lsys bench/components.lua
--
-- The plant is the article's fig. 6 structure (Lintermann and Deussen 1999, section "A
-- geometry generation example"): a cascade of four Trees, a 12 m trunk with 30 branches,
-- each with 15 sub-branches, each with 10 twigs of 12 leaves: 58,981 instances, 54,000 of
-- them leaves. For each phase it prints the best of RUNS wall-clock times (after a full
-- collection each) and the rate:
--   expand     C.expand: the i-tree (instances/s)
--   emit       C.model less the expansion: the Lstring of turtle modules (modules/s)
--   interpret  the model's interpretation into a Scene (triangles/s)
--   total      C.scene (expand + emit + interpret in one), against the 0.5 s target
-- and the process's peak memory (VmHWM). When examples/components/chestnut.lua exists (a
-- script returning a prototype, or a model whose `graph()` builds it), it is timed the same way.
-- Option: a number after the script sets RUNS (default 3).

local B = dofile(((arg and arg[0] or "bench/components.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local C = lsys.components
local RUNS = tonumber(arg and arg[1]) or 3
local TARGET = 0.5

local function chestnut ()
  local leaf = C.leaf { length = 0.25, width = 0.12, lateral = 0.1, longitudinal = { 0, 0.3 } }
  local twig = C.tree { name = "twig", length = 0.6, n = 12, angle = 50, radius = 0.01,
                        segments = 4 }
  twig:branch(leaf)
  local br2 = C.tree { name = "br2", length = 2, n = 10, angle = { 60, 40 }, radius = 0.03,
                       segments = 8 }
  br2:branch(twig)
  local br = C.tree { name = "br", length = 5, n = 15, angle = { 70, 40 }, radius = 0.08,
                      gravitropism = 0.05 }
  br:branch(br2)
  local plant = C.tree { name = "trunk", length = 12, n = 30, first = 0.3,
                         angle = { 70, 40 }, radius = 0.4 }
  plant:branch(br)
  return plant
end

local function report (title, root, opts)
  local te, tree = B.best(function () return C.expand(root) end, RUNS)
  local tm, m = B.best(function () return C.model(root, opts) end, RUNS)
  local ti, scene = B.best(function () return m:interpret() end, RUNS)
  local tt = B.best(function () return C.scene(root, opts) end, RUNS)
  local n, nl = tree:count(), tree:count { kind = "leaf" }
  local nm, nt = #m.components.lstring, scene.ntriangles
  local emit = math.max(tm - te, 1e-9)
  print(string.format("%s: %d instances (%d leaves), %d modules, %d triangles", title, n, nl,
                      nm, nt))
  print(string.format("  expand     %7.3f s  %6.2f M instances/s", te, n / te / 1e6))
  print(string.format("  emit       %7.3f s  %6.2f M modules/s", emit, nm / emit / 1e6))
  print(string.format("  interpret  %7.3f s  %6.2f M triangles/s", ti, nt / ti / 1e6))
  print(string.format("  total      %7.3f s  (C.scene; target %.1f s: %s)", tt, TARGET,
                      B.verdict(tt <= TARGET)))
end

print(string.format("lsys %s, %s, best of %d", lsys.version, B.clock_name, RUNS))
report("chestnut-like cascade of four Trees", chestnut())
local path = B.root .. "/examples/components/chestnut.lua"
local f = io.open(path, "r")
if f then
  f:close()
  local ok, r = pcall(dofile, path)
  local opts
  if ok and type(r) == "table" and not C.isproto(r) then
    opts = { view = r.VIEW, seed = 1 }
    r = type(r.graph) == "function" and r.graph() or r.root or r.plant
  end
  if ok and C.isproto(r) then report("examples/components/chestnut.lua", r, opts)
  else print("examples/components/chestnut.lua: no prototype to time (" .. tostring(r) .. ")") end
end
local mib = B.peak_mib()
print(mib and string.format("peak memory (VmHWM): %.0f MiB", mib) or "peak memory: unknown")
