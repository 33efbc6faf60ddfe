-- The horse chestnut of Lintermann and Deussen 1999, fig. 6 (section "Chestnut tree"): a
-- cascade of four Tree components (trunk -> branches -> sub-branches -> twigs) with the
-- leaves multiplied as branches of the last Tree, and textures on the leaves and the stem.
-- A horse-chestnut leaf is palmate: five to seven obovate leaflets, the middle ones the
-- longest, spread like fingers at the end of a long petiole. Here a Horn is the petiole and a
-- Hydra on its tip spreads 7 Leaf instances over 160 degrees.
--
--   1 trunk, 12 branches, 96 sub-branches, 576 twigs, 7488 leaves of 7 leaflets:
--   52,416 leaflet instances (the benchmark's plant, bench/components.lua).
--
-- `opts` (when loaded as a function by the tests) makes a smaller tree of the same graph:
-- { branches =, subs =, twigs =, leaves = } counts per level; `levels` (default 5) the
-- article's stages: 2 the trunk and its branches (fig. 6a), 4 the two more levels of
-- sub-branches and twigs (fig. 6b), 5 with the leaves (fig. 6c). fig6_ab.lua draws 6a, 6b.
local lsys = require "lsys"
local C = lsys.components

local function chestnut (opts)
  opts = opts or {}
  local levels = opts.levels or 5
  -- the leaflet: textured (texture 1, the view's chestnut_leaf.png), white-ish so the
  -- texture's greens show; the middle leaflet of 7 is the longest (a sine over i of n)
  local leaflet = C.leaf {
    name = "leaflet", shape = "obovate", width = 0.34, lateral = 0.1, longitudinal = 0.2,
    length = function (ctx)
      return 0.2 + 0.14 * math.sin(math.pi * (ctx.i - 1) / (ctx.n - 1))
    end,
    color = 2, texture = 1,
  }
  -- the Hydra's axis is turned to the petiole's up side (rotate 90 about x), so the 7
  -- leaflets fan out in the leaf's plane around the direction the petiole points, each
  -- tilted 10 degrees below it (angle 100)
  local palm = C.hydra { name = "palmate", n = 7, open = -80, close = 80, angle = 100,
                         rotate = { 90, 0, 0 } }
  palm:child(leaflet)
  local petiole = C.horn { name = "petiole", length = 0.2, radius = 0.006, segments = 1,
                           primitive = "cylinder", color = 3 }
  petiole:child(palm)
  -- twigs: a leaf every 90 degrees around (the leaves of a chestnut are opposite and
  -- decussate), bending to the light
  local twig = C.tree { name = "twig", length = 0.9, radius = 0.015, tip = 0.5,
                        n = opts.leaves or 13, first = 0.1, angle = 55, segments = 4,
                        divergence = 90, phototropism = 0.2, color = 1, texture = 2 }
  if levels >= 5 then twig:branch(petiole) end
  local sub = C.tree { name = "sub-branch", length = 2.2, radius = 0.04, n = opts.twigs or 6,
                       first = 0.2, angle = 45, segments = 6, gnarl = 6, color = 1,
                       texture = 2 }
  if levels >= 4 then sub:branch(twig) end
  -- the main branches: the lower ones longer, spreading, slightly hanging
  local branch = C.tree { name = "branch", length = { 6, 3 }, radius = 0.12,
                          n = opts.subs or 8, first = 0.25, angle = 40, segments = 10,
                          gnarl = 4, gravitropism = 0.02, color = 1, texture = 2 }
  if levels >= 3 then branch:branch(sub) end
  local trunk = C.tree { name = "trunk", length = 9, radius = 0.42, n = opts.branches or 12,
                         first = 0.36, angle = { 70, 25 }, segments = 16, gnarl = 2,
                         color = 1, texture = 2 }
  if levels >= 2 then trunk:branch(branch) end
  return trunk
end

local VIEW = {
  dir = lsys.here(),
  textures = {
    { file = "chestnut_leaf.png", per_surface = true, mag = "linear", min = "linear" },
    { file = "bark.png", mag = "linear", min = "linear" },
  },
  palette = { { 1, 1, 1 }, { 0.95, 1, 0.9 }, { 0.55, 0.65, 0.3 } },
  background = { 0.86, 0.92, 0.98 },
  -- a little from above: seen level, the trunk's foot ends in a straight edge, as if cut
  -- off by the frame; from above it is a curve, standing on the (unseen) ground
  direction = { 0, -0.3, -1 },
}

local M = C.model(chestnut(), { seed = 1, view = VIEW, name = "chestnut" })
M.graph = chestnut            -- the p-graph builder, for smaller variants (tests)
M.VIEW = VIEW
return M
