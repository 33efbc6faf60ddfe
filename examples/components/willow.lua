-- The weeping willow of Lintermann and Deussen 1999, fig. 9a (section "Tropisms": "a
-- traditional gravitropism"): a short trunk, main branches that rise and arch over, and
-- long thin twigs that a strong gravitropism turns down until they hang like curtains,
-- each with many narrow leaves.
--
--   1 trunk, 7 branches, 42 sub-branches, 336 hanging twigs, 8,064 leaves.
--
-- `opts` (when the tests call M.graph) makes a smaller tree of the same graph:
-- { branches =, subs =, twigs =, leaves = } counts per level.
local lsys = require "lsys"
local C = lsys.components

local function willow (opts)
  opts = opts or {}
  local leaf = C.leaf { name = "leaf", shape = "lanceolate", length = 0.28, width = 0.07,
                        longitudinal = 0.3, color = 2 }
  -- the twig: long and thin, and its gravitropism (the stem turns towards the gravity
  -- vector by e |H x g| per segment, cpfg's tropism) bends it down within its first third
  local twig = C.tree { name = "twig", length = { 5, 3.5 }, radius = 0.012, tip = 0.4,
                        segments = 16, n = opts.leaves or 24, first = 0.08, angle = 35,
                        gravitropism = 0.45, gnarl = 3, color = 3 }
  twig:branch(leaf)
  local sub = C.tree { name = "sub-branch", length = 2.2, radius = 0.05, segments = 8,
                       n = opts.twigs or 8, first = 0.2, angle = 50, gravitropism = 0.06,
                       gnarl = 5, color = 1, texture = 1 }
  sub:branch(twig)
  -- the main branches rise steeply and arch over at their ends
  local branch = C.tree { name = "branch", length = { 6, 4 }, radius = 0.16,
                          segments = 10, n = opts.subs or 6, first = 0.3, angle = 45,
                          curvature = 50, gnarl = 4, color = 1, texture = 1 }
  branch:branch(sub)
  local trunk = C.tree { name = "trunk", length = 4.5, radius = 0.45, tip = 0.45,
                         segments = 10, n = opts.branches or 7, first = 0.55, angle = { 65, 40 },
                         gnarl = 3, color = 1, texture = 1 }
  trunk:branch(branch)
  return trunk
end

local VIEW = {
  dir = lsys.here(),
  textures = { { file = "bark.png", mag = "linear", min = "linear" } },
  palette = { { 0.85, 0.8, 0.7 }, { 0.60, 0.76, 0.30 }, { 0.55, 0.50, 0.22 } },
  background = { 0.88, 0.93, 0.97 },
}

local M = C.model(willow(), { seed = 1, view = VIEW, name = "willow" })
M.graph = willow
M.VIEW = VIEW
return M
