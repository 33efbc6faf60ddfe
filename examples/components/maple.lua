-- The maple of Lintermann and Deussen 1999, fig. 7 ("Experienced users can model very
-- complex trees, such as the one shown here, in a few hours"; section "Chestnut tree": the
-- maple "was modeled in five hours"). The article shows the picture, not its p-graph; this
-- one follows its recipe for trees (section "Chestnut tree": "A cascade of Tree components
-- represents the branching structure. Leaves ... multiply as branches of the last Tree"):
-- a short trunk that parts into a few steep limbs, three more levels of branches that
-- spread and lift their ends to the light, and on the twigs opposite pairs of palmately
-- lobed leaves (a Hydra of two at each node), each leaf a Hydra of five pointed lobes
-- (Leaf components, the middle lobe the longest) on a petiole (a Horn). A broad, dense,
-- rounded crown.
--
--   1 trunk, 6 limbs, 42 branches, 252 branchlets, 1,260 twigs, 3,780 nodes, 7,560 leaves
--   of 5 lobes: 37,800 lobe instances.
--
-- `opts` (when the tests call M.graph) makes a smaller tree of the same graph:
-- { limbs =, branches =, branchlets =, twigs =, nodes = } counts per level.
local lsys = require "lsys"
local C = lsys.components

-- One half of a lobe's outline, {half-width, along} as fractions of its length: a broad
-- base, a tooth on each side two thirds up, a long point.
local LOBE = { { 0, 0 }, { 0.10, 0.08 }, { 0.19, 0.22 }, { 0.23, 0.36 }, { 0.21, 0.46 },
               { 0.25, 0.52 }, { 0.17, 0.60 }, { 0.15, 0.70 }, { 0.17, 0.74 },
               { 0.08, 0.86 }, { 0, 1 } }

local function maple (opts)
  opts = opts or {}
  -- the five lobes over 210 degrees: the middle one longest, the basal ones short
  local lobe = C.leaf { name = "lobe", outline = LOBE, width = 0.5, lateral = 0.05,
                        longitudinal = 0.05, color = 2,
                        length = function (ctx)
                          local u = (ctx.i - 1) / (ctx.n - 1)
                          return 0.26 * (0.42 + 0.58 * math.sin(math.pi * u) ^ 1.2)
                        end }
  -- as the chestnut's palmate leaf: the Hydra's axis turned to the petiole's up side, so
  -- the lobes spread in the leaf's plane round the way the petiole points, 5 degrees back
  local blade = C.hydra { name = "blade", n = 5, open = -105, close = 105, angle = 95,
                          rotate = { 90, 0, 0 } }
  blade:child(lobe)
  local petiole = C.horn { name = "petiole", length = 0.1, radius = 0.004, segments = 1,
                           primitive = "cylinder", color = 3 }
  petiole:child(blade)
  -- a node of the twig: a Hydra of two on the twig's own axis, the pair of opposite leaves
  -- 60 degrees out from it
  local node = C.hydra { name = "node", n = 2, angle = 60 }
  node:child(petiole)
  -- twigs: their nodes as branches along the stem without a branching angle, each pair
  -- turned 90 degrees from the one before (opposite, decussate leaves, as a maple's are)
  local twig = C.tree { name = "twig", length = 0.6, radius = 0.008, tip = 0.5, segments = 4,
                        n = opts.nodes or 3, first = 0.2, angle = 0, divergence = 90,
                        phototropism = 0.06, color = 1, texture = 1 }
  twig:branch(node)
  local branchlet = C.tree { name = "branchlet", length = 1.5, radius = 0.025, segments = 5,
                             n = opts.twigs or 5, first = 0.25, angle = 50, gnarl = 8,
                             phototropism = 0.04, color = 1, texture = 1 }
  branchlet:branch(twig)
  local branch = C.tree { name = "branch", length = { 3.6, 2.4 }, radius = 0.06,
                          segments = 8, n = opts.branchlets or 6, first = 0.2, angle = 50,
                          gnarl = 6, phototropism = 0.04, color = 1, texture = 1 }
  branch:branch(branchlet)
  -- the limbs: long and steep, the lower ones spreading wider
  local limb = C.tree { name = "limb", length = { 7, 5 }, radius = 0.2, tip = 0.35,
                        segments = 12, n = opts.branches or 7, first = 0.25, angle = 45,
                        gnarl = 4, phototropism = 0.03, color = 1, texture = 1 }
  limb:branch(branch)
  local trunk = C.tree { name = "trunk", length = 5, radius = 0.5, tip = 0.45, segments = 10,
                         n = opts.limbs or 6, first = 0.45, last = 0.95, angle = { 45, 20 },
                         gnarl = 3, color = 1, texture = 1 }
  trunk:branch(limb)
  return trunk
end

local VIEW = {
  dir = lsys.here(),
  textures = { { file = "bark.png", mag = "linear", min = "linear" } },
  palette = { { 0.80, 0.74, 0.66 }, { 0.30, 0.52, 0.16 }, { 0.42, 0.46, 0.20 } },
  background = { 0.87, 0.92, 0.97 },
  direction = { 0, -0.2, -1 },
}

local M = C.model(maple(), { seed = 1, view = VIEW, name = "maple" })
M.graph = maple
M.VIEW = VIEW
return M
