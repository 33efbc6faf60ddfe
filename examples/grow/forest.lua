-- A forest of five trees growing to 20,000 limbs: the interactive-rate example of
-- incremental growth. Davison's rules ("Incremental rules for growing plants",
-- section "Incremental rules"; docs/manual.md §12) with a larger cap: a limb without
-- leaves lengthens by 8 % a tick up to a length that shrinks with its level, thickens while
-- it is thinner than a level's limit, and at age 4 spawns up to two children (each with
-- probability 0.9): a leader nearly straight on and a side branch at 25 to 45 degrees, rolled
-- by the golden angle, so the crowns fill out in three dimensions; twigs of the upper levels
-- leaf out. Every condition runs in C (lsys.grow's native rules);
-- spawning and leaves call Lua only where their conditions hold.
--
--   build/bin/lsys grow examples/grow/forest.lua          grows it live in the window
--   build/bin/lsys grow examples/grow/forest.lua --frames frames/ --every 5
--   build/bin/lsys examples/grow/forest.lua [out.png]      renders the grown forest
--
-- As a module: M.world{ seed =, ticks =, trees =, max_limbs = } -> a planted world. Its
-- pictures stand on the ground that lsys render gives a 3D scene, with the trees' shadows.
local lsys = require "lsys"
local grow = lsys.grow

local M = {}

local BARK, LEAF = "#5e4026", "#3d8a2e"
local VIEW = { projection = "perspective", fov = 30, direction = { 0.15, -0.25, -1 } }

function M.kind ()
  local Tree = grow.kind("forest tree")
  Tree:rule("length", { when = "length < 1.2 - 0.07 * level and leaves == 0",
                        scale_length = 1.08 })
  Tree:rule("thickness", { when = "radius <= -0.025 * level + 0.32 and leaves == 0",
                           scale_radius = 1.04 })
  Tree:rule("spawn", {
    when = "age == 4 and count <= 4000 and leaves == 0 and level < 15",
    fn = function (limb)
      local roll = 137.5 * limb:level()
      if limb:random() < 0.9 then             -- the leader, nearly straight on
        limb:spawn { roll = roll, angle = limb:random(-8, 8), axis = "z",
                     length = 0.4, radius = 0.03 }
      end
      if limb:random() < 0.9 then             -- a side branch
        limb:spawn { roll = roll, angle = limb:random(25, 45), axis = "z",
                     length = 0.4, radius = 0.03 }
      end
    end,
  })
  Tree:rule("bark", { when = "age > 4", blend = { BARK, 0.1 } })
  Tree:rule("leaves", {
    when = "age == 5 and leaves == 0 and level >= 9",
    fn = function (limb) limb:add_leaves(2, { size = 0.45, color = LEAF }) end,
  })
  return Tree
end

--- Five trees (`trees`) on a gentle arc, planted, to grow `ticks` (80) ticks; at most
-- `max_limbs` (20,000) limbs in all.
function M.world (opts)
  opts = opts or {}
  local w = grow.world {
    seed = opts.seed or 8, ticks = opts.ticks or 80, sides = 6,
    max_limbs = opts.max_limbs or 20000,
    view = VIEW,
  }
  local Tree = M.kind()
  local n = opts.trees or 5
  for k = 1, n do
    local x = (k - (n + 1) / 2) * 9
    w:plant { kind = Tree, position = { x, 0, -0.04 * x * x }, radius = 0.04, length = 0.4 }
  end
  return w
end

if arg and arg[0] and arg[0]:match("forest%.lua$") then
  local w = M.world():grow()
  local out = arg[1] or "forest.png"
  local sc = w:scene()
  lsys.render(sc, require("lsys.render").shaded(sc, { out = out, width = 1200, height = 600 }))
  print(string.format("%d limbs after %d ticks -> %s", w:count(), w.ticks, out))
end

return M
