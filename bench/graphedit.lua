-- Live editing in the component-graph pane (lsys.ui.graph): the time from a parameter set
-- to the new Scene of the chestnut (examples/components/chestnut.lua, Lintermann and
-- Deussen 1999, fig. 6).
--
--   build/bin/lsys bench/graphedit.lua [RUNS]
--
-- Each case sets one parameter through the pane's form item (alternating between two
-- values, so every run is a change) and rebuilds the plant as the host does
-- (lsys.ui.graph.rebuild); it prints the best of RUNS (default 3) times, after a full
-- collection each, against the 0.5 s target. A parameter only the emitter reads (a leaf's
-- shape, a stem's radius: lsys.components.proto.DRAWN) draws the last i-tree again; any
-- other expands the graph anew. Also: the pane's layout and drawing at 420 x 700.

local B = dofile(((arg and arg[0] or "bench/graphedit.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local core = require "lsys.core"
local P = require "lsys.ui.graph"
local RUNS = tonumber(arg and arg[1]) or 3
local TARGET = 0.5

local chestnut = dofile(B.root .. "/examples/components/chestnut.lua")
local root = chestnut.graph()
local pane = P.new(root, { view = chestnut.VIEW, seed = 1, dot = false })

-- The form item `name` of the component `who` (its name).
local function item (who, name)
  for _, d in ipairs(pane.lay.nodes) do
    if d.proto and d.proto.name == who then pane:select(d.proto) end
  end
  for _, it in ipairs(pane:items()) do
    if it.name == name then return it end
  end
  error("no item " .. who .. "." .. name)
end

local scene0, m0 = pane:rebuild()
local tree = m0.components.tree
print(string.format("lsys %s, %s, best of %d", lsys.version, B.clock_name, RUNS))
print(string.format("chestnut: %d instances (%d leaflets), %d modules, %d triangles",
                    tree:count(), tree:count("leaflet"), #m0.components.lstring,
                    scene0.ntriangles))

local CASES = {
  { "leaflet", "width", 0.3, 0.34, "a leaf's shape (drawn: the i-tree again)" },
  { "twig", "radius", 0.02, 0.015, "a stem's radius (drawn)" },
  { "twig", "angle", 50, 55, "the twigs' leaf angle (expanded anew)" },
  { "branch", "gnarl", 6, 4, "the branches' gnarl (expanded anew)" },
}
local worst = 0
for _, c in ipairs(CASES) do
  local it = item(c[1], c[2])
  local k = 0
  local t, s = B.best(function ()
    k = k + 1
    it.set(k % 2 == 1 and c[3] or c[4])
    return (pane:rebuild())
  end, RUNS)
  worst = math.max(worst, t)
  print(string.format("  %-16s %7.3f s  %d triangles  %s", c[1] .. "." .. c[2], t,
                      s.ntriangles, c[5]))
end
print(string.format("  slowest edit     %7.3f s  (target %.1f s: %s)", worst, TARGET,
                    B.verdict(worst <= TARGET)))

local tl = B.best(function () return P.layout(root, { dot = false }) end, RUNS)
local c = core.canvas(420, 700)
local td = B.best(function () pane:draw(c) end, RUNS)
print(string.format("  pane layout %.4f s, draw %.4f s (420 x 700)", tl, td))
local mib = B.peak_mib()
print(mib and string.format("peak memory (VmHWM): %.0f MiB", mib) or "peak memory: unknown")
