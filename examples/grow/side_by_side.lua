-- One plant written two ways: as an L-system, re-derived and redrawn at each step,
-- and as incremental rules on persistent limbs. Both give the same plant at every step: a
-- shoot grows by 25 % a step up to length 1; at age 2, below level 5, it forks into two
-- shoots 30 degrees either side, the fork turned 90 degrees from the one before.
--
-- The correspondence: a limb is a module L(length, age, level); the limb's rules are the
-- productions' conditions; `spawn{ roll = 90, angle = 30, axis = "z" }` is `[/(-90)+(30)L]`
-- (a positive roll about the limb turns its right side to its back, which the turtle's
-- `/` does with a negative angle; a positive angle about the front axis z turns left: `+`).
--
--   build/bin/lsys examples/grow/side_by_side.lua [STEPS]   prints both plants' tips
local lsys = require "lsys"
local grow = lsys.grow

local M = {}

--- The L-system, derived `steps` steps.
function M.lsystem (steps)
  return lsys.lsystem {
    axiom = "L(0.4, 0, 1)",
    productions = "L(l, a, v) : a == 2 and v < 5 --> L(l < 1 and l * 1.25 or l, a + 1, v)" ..
                  "[/(-90)+(30)L(0.4, 0, v + 1)][/(-90)-(30)L(0.4, 0, v + 1)]\n" ..
                  "L(l, a, v) --> L(l < 1 and l * 1.25 or l, a + 1, v)",
    homomorphism = "L(l, a, v) --> #(0.1)F(l)",
    steps = steps or 12, view = { line_style = "cylinder" },
  }
end

--- The same plant as limbs, grown `ticks` ticks.
function M.world (ticks)
  local Shoot = grow.kind("shoot")
  Shoot:rule("length", { when = "length < 1", scale_length = 1.25 })
  Shoot:rule("fork", { when = "age == 2 and level < 5", fn = function (limb)
    limb:spawn { roll = 90, angle = 30, axis = "z", length = 0.4 }
    limb:spawn { roll = 90, angle = -30, axis = "z", length = 0.4 }
  end })
  local w = grow.world()
  w:plant { kind = Shoot, length = 0.4, radius = 0.05 }
  w:tick(ticks or 12)
  return w
end

-- The tips of a plant, sorted ("x y z" to 4 decimals): of the L-system's segments, of the
-- world's limbs.
local function key (x, y, z)
  local function r (v) return string.format("%.4f", v + 0.0):gsub("^%-(0%.0000)$", "%1") end
  return r(x) .. " " .. r(y) .. " " .. r(z)
end

function M.lsystem_tips (m)
  local out = {}
  for _, rec in m:interpret():records() do
    if rec.kind == "segment" then out[#out + 1] = key(rec.p1[1], rec.p1[2], rec.p1[3]) end
  end
  table.sort(out)
  return out
end

function M.world_tips (w)
  local out = {}
  for _, limb in ipairs(w:limbs()) do out[#out + 1] = key(limb:tip()) end
  table.sort(out)
  return out
end

if arg and arg[0] and arg[0]:match("side_by_side%.lua$") then
  local steps = tonumber(arg[1]) or 12
  local a, b = M.lsystem_tips(M.lsystem(steps)), M.world_tips(M.world(steps))
  local same = #a == #b
  for i = 1, #a do if a[i] ~= b[i] then same = false end end
  print(string.format("%d steps: L-system %d segments, incremental %d limbs, %s", steps, #a,
                      #b, same and "the same tips" or "DIFFERENT tips"))
end

return M
