-- The pine with a partial free-form deformation of Lintermann and Deussen 1999, fig. 10
-- (section "Free-form deformations": "the twigs of a tree should be deformed, but not the
-- leaves or needles. Placing another FFD or Hyperpatch component in the subtree affected by
-- a free-form deformation accomplishes this").
--
-- The p-graph: a Hyperpatch "bend" at the root (mode "all": it deforms every triangle of
-- its subtree) -> the trunk (a Tree) -> branches (Trees) -> twigs (Trees) -> on each twig,
-- as its branches, an FFD "keep" with `isolate = true` and no functions -> a needle pair
-- (a Hydra of 2 linear Leaves). "keep" switches the deformations above it off, so the
-- twigs and the trunk bend and the needles keep their shape (fig. 10b); `M.graph{ deform =
-- "all" }` leaves "keep" out, so the needles bend too (fig. 10c), and `deform = "none"`
-- leaves the bend out (fig. 10a).
--
--   1 bend, 1 trunk, 14 branches, 112 twigs, 4,480 keeps, 4,480 pairs, 8,960 needles.
--
-- An isolated subtree follows the deformations above it rigidly (moved and turned with its
-- frame), so the needles stay on the bent twigs with their shape.
local lsys = require "lsys"
local C = lsys.components

-- The bend: a Hyperpatch of degrees 1 (across), 2 (up the tree) and 1 (front to back) on
-- the box around the tree; the middle row of control points moves 1.2 (its left side) and
-- 2.2 (its right side), the top row 4.5 and 7.5 units to the right (local x): the tree
-- leans and curves like a windswept pine, and widens to the upper right, where a bend of
-- the whole tree (fig. 10c) stretches the needles most ("the needles on the right appear
-- too big").
local MOVES = {}
for _, row in ipairs { { 1, 1.2, 2.2 }, { 2, 4.5, 7.5 } } do
  for i = 0, 1 do
    for k = 0, 1 do MOVES[#MOVES + 1] = { i, row[1], k, row[2 + i], 0, 0 } end
  end
end

local function pine (opts)
  opts = opts or {}
  local deform = opts.deform or "twigs"
  local needle = C.leaf { name = "needle", shape = "linear", length = 0.45, width = 0.04,
                          longitudinal = 0.1, color = 2 }
  -- a pair of needles (a pine's short shoot) spread 35 degrees from the twig's side
  local pair = C.hydra { name = "pair", n = 2, angle = 35, rotate = { 90, 0, 0 } }
  pair:child(needle)
  local twig = C.tree { name = "twig", length = 1.1, radius = 0.02, tip = 0.5, segments = 6,
                        n = opts.pairs or 40, first = 0.05, angle = 50, curvature = -15,
                        phototropism = 0.1, color = 3 }
  if deform == "twigs" then
    local keep = C.ffd { name = "keep", isolate = true }
    keep:child(pair)
    twig:branch(keep)
  else
    twig:branch(pair)
  end
  local branch = C.tree { name = "branch", length = { 3.2, 1.2 }, radius = 0.07,
                          segments = 8, n = opts.twigs or 8, first = 0.25, angle = 55,
                          divergence = 180, gravitropism = 0.04, color = 1, texture = 1 }
  branch:branch(twig)
  -- whorl-like branches: the lower ones long and level, the upper ones short and rising
  local trunk = C.tree { name = "trunk", length = 8, radius = 0.22, tip = 0.15,
                         segments = 16, n = opts.branches or 14, first = 0.25, last = 0.95,
                         angle = { 85, 50 }, color = 1, texture = 1 }
  trunk:branch(branch)
  if deform == "none" then return trunk end
  local bend = C.hyperpatch { name = "bend", degree = { 1, 2, 1 }, moves = MOVES }
  bend:child(trunk)
  return bend
end

local VIEW = {
  dir = lsys.here(),
  textures = { { file = "bark.png", mag = "linear", min = "linear" } },
  palette = { { 0.80, 0.62, 0.48 }, { 0.16, 0.36, 0.16 }, { 0.45, 0.36, 0.22 } },
  background = { 0.90, 0.93, 0.96 },
}

local M = C.model(pine(), { seed = 1, view = VIEW, name = "pine" })
M.graph = pine
M.VIEW = VIEW
return M
