-- Self-organizing trees (examples/open/selforg.lua: Palubicki et al. 2009, the shadow grid
-- and the Borchert-Honda allocation as open L-system environments), each in a fresh
-- process: one tree grown until it has at least 50,000 internodes, and the stand of
-- examples/open/forest.lua. For each it prints the steps, internodes (modules I), leaves,
-- modules, the time of the whole derivation (the environmental passes included; wall
-- clock) and the process's peak memory (VmHWM), against the targets (the tree in under
-- 30 s, the stand in under 2 minutes), and never fails on them.
--
--   build/bin/lsys bench/selforg.lua            both, as a table
--   build/bin/lsys bench/selforg.lua tree       one (or "forest"): a RESULT line
local B = dofile((arg and arg[0] or "bench/selforg.lua"):match("^(.*)/[^/]*$") .. "/common.lua")
local format = string.format

local TREE_STEPS = 33           -- the steps that take the tree past 50,000 internodes

local function child (which)
  local lsys = B.load_lsys()
  local t0 = B.clock()
  local strings
  if which == "tree" then
    local m = dofile(B.root .. "/examples/open/selforg.lua")
    m.steps = TREE_STEPS
    strings = { m:derive() }
  else
    local _
    _, strings = dofile(B.root .. "/examples/open/forest.lua")
  end
  local t = B.clock() - t0
  local n, leaves, modules = 0, 0, 0
  for _, s in ipairs(strings) do
    n, leaves, modules = n + s:count("I"), leaves + s:count("L"), modules + #s
  end
  io.write(format("RESULT which=%s plants=%d internodes=%d leaves=%d modules=%d time=%.3f "
    .. "peak_mib=%.1f steps=%d\n", which, #strings, n, leaves, modules, t,
    B.peak_mib() or -1, which == "tree" and TREE_STEPS or -1))
  return lsys
end

local measure = B.measure

local mode = arg and arg[1]
if mode == "tree" or mode == "forest" then
  child(mode)
  return
end
if mode ~= nil then
  io.stderr:write("usage: lsys bench/selforg.lua [tree | forest]\n")
  os.exit(2)
end

print(format("self-organizing trees (examples/open/selforg.lua), %s", B.clock_name))
local tree = measure("tree")
print(format("  one tree, %d steps: %d internodes, %d leaves, %d modules in %.1f s "
  .. "(%.0f internodes/s), peak %.0f MiB; target 50,000 internodes in < 30 s: %s",
  tree.steps, tree.internodes, tree.leaves, tree.modules, tree.time,
  tree.internodes / tree.time, tree.peak_mib,
  B.verdict(tree.internodes >= 50000 and tree.time < 30)))
local forest = measure("forest")
print(format("  the stand (examples/open/forest.lua): %d trees, %d internodes, %d leaves in "
  .. "%.1f s, peak %.0f MiB; target < 2 min: %s", forest.plants, forest.internodes,
  forest.leaves, forest.time, forest.peak_mib, B.verdict(forest.time < 120)))
