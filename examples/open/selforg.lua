-- A self-organizing tree (Palubicki, Horel, Longay, Runions, Lane, Měch and Prusinkiewicz
-- 2009, "Self-organizing tree models for image synthesis"): the buds sense the light in a
-- grid of shadow (§4.1, lsys.environment.shadow), the tree's vigour is shared out among them
-- basipetally and acropetally by the Borchert-Honda model (§4.3, lsys.environment.vigour),
-- and each bud grows a shoot as long as its vigour allows, turned towards the light (§4.4).
-- Branches whose light no longer pays for their internodes are shed (§4.5). Nothing says
-- where the branches go: the crown takes the shape of the space and light it has
-- (wall.lua grows it beside a wall, neighbour.lua under an older tree, forest.lua in a
-- stand).
--
--   lsys render examples/open/selforg.lua -o tree.png
--   lsys animate examples/open/selforg.lua -o tree.mp4
--
-- The modules: I(l, b, w) an internode of length l and width w (b = 1: the first of a
-- lateral branch, where the branch is shed), A an apex, B a lateral bud, L(a) a leaf of age
-- a, each bud and internode followed by the ?E that vigour answers (see its module):
-- ?E(0 or 1, Q, v, x, y, z) for a bud or apex, ?E(2, Q, v, t, n) for an internode. A bud of
-- vigour v grows n = floor(v) metamers of length LEN v / n (§4.4) along the direction
-- vigour gives it; each metamer bears a lateral bud and a leaf. LAMBDA is the apical
-- control: 0.52 gives a spreading (decurrent) crown, 0.58 a conical (excurrent) one.
local lsys = require "lsys"

local LEN = 0.5
-- the ground, as dark as deep shade: no bud turns towards it
local GROUND = { lo = { -1e4, -1e4, -1e4 }, hi = { 1e4, 0, 1e4 }, cast = false }

return lsys.lsystem {
  name = "selforg",
  axiom = "I(LEN, 0, W0) ?E(2, 0, 0, 1, 1) A ?E(1, 1, 0, 0, 1, 0)",
  steps = 16,
  env = { LEN = LEN, W0 = 0.02, PIPE = 2.5, DIV = 137.5, BRANCH = 45, SHED = 0.2,
          LEAFLIFE = 3, LEAF = 0.35, LEAFANGLE = 70 },
  productions = {
    -- a bud or an apex with vigour enough grows a shoot (the first internode of a lateral
    -- branch is marked: the branch is shed from there)
    "A ?E(r, q, v, x, y, z) : v >= 1 --> S(floor(v), LEN * v / floor(v), x, y, z, 0)",
    "B ?E(r, q, v, x, y, z) : v >= 1 --> S(floor(v), LEN * v / floor(v), x, y, z, 1)",
    -- a branch that gets less light than SHED an internode is shed (§4.5)
    "I(l, b, w) ?E(r, q, v, t, n) : b == 1 and q < SHED * n --> %",
    -- the pipe model: the width of the t apices an internode bears, w0 t^(1/PIPE)
    "I(l, b, w) ?E(r, q, v, t, n) --> I(l, b, W0 * t ^ (1 / PIPE)) ?E(2, q, v, t, n)",
    "L(a) : a >= LEAFLIFE --> *",
    -- a seed that waits n steps before it germinates (neighbour.lua's sapling)
    "W(n) : n > 0 --> W(n - 1)",
    "W(n) --> I(LEN, 0, W0) ?E(2, 0, 0, 1, 1) A ?E(1, 1, 0, 0, 1, 0)",
    "L(a) --> L(a + 1)",
  },
  decomposition = {
    -- a shoot of n metamers along (x, y, z), each with a lateral bud and a leaf
    "S(n, l, x, y, z, b) : n > 0 --> @R(x, y, z) I(l, b, W0) ?E(2, 0, 0, 1, 1) "
      .. "[ &(BRANCH) B ?E(0, 1, 0, 0, 1, 0) ] [ &(LEAFANGLE) L(0) ] /(DIV) "
      .. "S(n - 1, l, x, y, z, 0)",
    "S(n, l, x, y, z, b) --> A ?E(1, 1, 0, 0, 1, 0)",
  },
  max_depth = { decomposition = 256 },
  homomorphism = {
    "I(l, b, w) --> !(w) F(l)",
    "L(a) --> ;(2) !(0.01) F(0.1) @c(LEAF)",
  },
  -- the shadow of every bud falls on the voxels below it, 6 deep (§4.1), in voxels as big
  -- as an internode; vigour 3 times the light at the base, shared with apical control 0.52
  environment = lsys.environment.vigour {
    sense = lsys.environment.shadow { voxel = LEN, depth = 6, a = 0.2, b = 2, C = 1,
                                      radius = 1.8, obstacles = { GROUND } },
    alpha = 3, lambda = 0.52, xi = 0.3, tropism = { 0, 0.05, 0 },
  },
  view = { line_style = "cylinder", width_increment = 0,
           palette = { [0] = { 0.45, 0.3, 0.18 }, [1] = { 0.45, 0.3, 0.18 },
                       [2] = { 0.3, 0.6, 0.2 } },
           background = { 1, 1, 1 } },
}
