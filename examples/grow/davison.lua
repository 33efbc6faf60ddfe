-- Davison's growing trees ("Incremental rules for growing plants", section "Incremental
-- rules" and fig. 1; docs/manual.md §12): five trees grow from saplings in one world, with
-- the paper's three rules --
--   length     a limb without leaves grows by 10 % a tick up to a length of about 1
--   thickness  and by 5 % in radius while it is thinner than -0.05 level + 0.25
--   spawning   at age 5, while the tree has at most 256 limbs, below level 10: two children,
--              each with probability 0.85, at 10..30 and -30..-10 degrees about a random axis
-- -- the limbs counted as they are made, as the paper's treeLimbs.size() (a tree ends with
-- at most 258: a limb that sees 256 makes its two). The paper counts the whole scene's limbs
-- (`treeLimbs.size() <= 256`), which leaves five trees about 50 limbs each; this example
-- counts each tree's, and `M.world{ cap = "scene" }` grows the paper's form (`total <= 256`)
-- -- and the figure's young green shoots turning brown with age, and leaves sprouting at the
-- ends of the twigs that stop branching.
--
--   build/bin/lsys examples/grow/davison.lua [out.png]      renders it after 60 ticks
--
--   build/bin/lsys grow examples/grow/davison.lua           grows them in the window
--
-- As a module (the tests, the gallery, examples/grow/leafy.lua): M.world{ ticks =, trees =,
-- seed =, leaf =, cap = } -> a planted world; its :grow() grows it.
local lsys = require "lsys"
local grow = lsys.grow

local M = {}

local BARK, LEAF = "#6b4a2b", "#3f8f2a"

-- What the spawning rule counts against 256: each tree's limbs, or the scene's.
local CAP = { tree = "count", scene = "total" }

--- The kind of the paper's trees; its conditions run in C, spawning in Lua. `cap`: "tree"
-- (the default: at most 256 limbs a tree before spawning) or "scene" (the paper's: in all).
function M.kind (cap)
  local var = CAP[cap or "tree"]
  if var == nil then error("davison: cap is \"tree\" or \"scene\", not " .. tostring(cap), 2) end
  local Tree = grow.kind("tree")
  Tree:rule("length", { when = "length < 1.0 and leaves == 0", scale_length = 1.1 })
  Tree:rule("thickness", { when = "radius <= -0.05 * level + 0.25 and leaves == 0",
                           scale_radius = 1.05 })
  Tree:rule("spawn", {
    when = "age == 5 and " .. var .. " <= 256 and leaves == 0 and level < 10",
    fn = function (limb)
      if limb:random() < 0.85 then
        limb:spawn { angle = limb:random(10, 30), axis = limb:random() < 0.5 and "z" or "x" }
      end
      if limb:random() < 0.85 then
        limb:spawn { angle = limb:random(-30, -10), axis = limb:random() < 0.5 and "z" or "x" }
      end
    end,
  })
  -- young shoots are green and turn brown from age 3
  Tree:rule("bark", { when = "age > 3", blend = { BARK, 0.15 } })
  -- the twigs of the upper levels leaf out a tick after they branch (and, having leaves,
  -- grow no more: the rules above all ask for none)
  Tree:rule("leaves", {
    when = "age == 6 and leaves == 0 and level >= 6",
    fn = function (limb) limb:add_leaves(4, { size = 0.5, color = LEAF }) end,
  })
  return Tree
end

--- A world of `trees` (5) trees 6 apart, planted, to grow `ticks` (60) ticks from `seed`
-- (3), its leaves of shape `leaf` (quads; see lsys.grow.world), spawning capped per tree or
-- in the whole scene (`cap`, M.kind's): `M.world():grow()`;
-- `lsys grow examples/grow/davison.lua` grows it in the window.
function M.world (opts)
  opts = opts or {}
  local w = grow.world { seed = opts.seed or 3, ticks = opts.ticks or 60, leaf = opts.leaf,
                         view = opts.view or M.VIEW }
  local Tree = M.kind(opts.cap)
  local n = opts.trees or 5
  for k = 1, n do
    w:plant { kind = Tree, position = { (k - (n + 1) / 2) * 6, 0, 0 }, radius = 0.05 }
  end
  return w
end

-- Seen a little from above, so that the ground `lsys render` puts under a 3D plant shows.
M.VIEW = { direction = { 0, -0.2, -1 } }

if arg and arg[0] and arg[0]:match("davison%.lua$") then
  local w = M.world():grow()
  local sc = w:scene()
  lsys.render(sc, require("lsys.render").shaded(sc, { out = arg[1] or "davison.png",
                                                      width = 1000, height = 560 }))
  print(string.format("%d limbs after %d ticks -> %s", w:count(), w.ticks,
                      arg[1] or "davison.png"))
end

return M
