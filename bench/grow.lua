-- Incremental growth benchmark: Davison's growth model ("Incremental rules for
-- growing plants", section "Incremental rules"; docs/manual.md §12) run both ways for the
-- same seed:
--
--   incremental  lsys.grow: five trees whose limbs persist; a tick runs the rules (their
--                conditions and changes in C, spawning in Lua), updates the world frames of
--                what moved and rewrites those limbs' vertices in place
--   regenerate   the equivalent parametric L-system: each tick derives the whole string one
--                step and interprets it into a new scene (8-sided cylinders, as the limbs)
--
--   build/bin/lsys bench/grow.lua [TICKS]
--
-- For each size (about 100, 1,000, 4,000 and 20,000 limbs) the L-system is derived until it
-- has that many limbs or more, and one step plus the interpretation is timed (mean of 3);
-- the incremental world grows until it has as many limbs (its cap) and the TICKS (20) ticks
-- after that are timed (its young limbs still grow then). One line per size, for scripts:
--   grow 4000 limbs: incremental 0.62 ms/tick, regenerate 31.0 ms/tick, ratio 50.0
-- then the targets at 4,000 limbs (a tick under 1 ms, at least 20 times faster), whether
-- memory stays flat over 200 ticks once grown, and the process's peak memory.

local B = dofile(((arg and arg[0] or "bench/grow.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()
local grow = lsys.grow
local TICKS = tonumber(arg and arg[1]) or 20
local SIZES = { 100, 1000, 4000, 5000, 20000 }   -- 5000: the first over 30,000 modules
local SEED = 1
local LEVELS = 30       -- the paper stops at level 10 (and 256 limbs a tree): too few limbs here

-- The paper's rules, in C where they can be: 'length', 'thickness', and 'child limbs
-- spawning' (age 5, no leaves, level below 10; two children, each with probability 0.85, at
-- 10..30 and -30..-10 degrees about a random axis). The paper's limits on the limb count
-- and the level (256 and 10) would keep the plants below the sizes measured: the count is
-- the world's cap here (the L-system, which has no global count, is derived until it has
-- as many limbs) and the level LEVELS.
local function tree ()
  local K = grow.kind("tree")
  K:rule("length", { when = "length < 1.0 and leaves == 0", scale_length = 1.1 })
  K:rule("thickness", { when = "radius <= -0.05 * level + 0.25 and leaves == 0",
                        scale_radius = 1.05 })
  K:rule("spawn", { when = "age == 5 and leaves == 0 and level < " .. LEVELS, fn = function (l)
    if l:random() < 0.85 then
      l:spawn { angle = l:random(10, 30), axis = l:random() < 0.5 and "z" or "x" }
    end
    if l:random() < 0.85 then
      l:spawn { angle = l:random(-30, -10), axis = l:random() < 0.5 and "z" or "x" }
    end
  end })
  return K
end

local function world (cap)
  local w = grow.world { seed = SEED, max_limbs = cap, sides = 8 }
  local K = tree()
  for k = 0, 4 do w:plant { kind = K, position = { (k - 2) * 6, 0, 0 } } end
  return w
end

-- The same model as a parametric L-system: L(length, radius, age, level). The paper's "if
-- length < 1" is a factor 1 + 0.1 s(1 - length) with s(x) = ceil(max(0, min(1, x))) (1 for
-- x > 0, else 0), so that the expression machine runs every rule (none stays in Lua); a
-- roll of 0 or 90 degrees picks the axis; the two children come with the probabilities
-- 0.85 * 0.85, 0.85 * 0.15 (each alone) and 0.15 * 0.15 (none).
local function step (x) return "math.ceil(math.max(0, math.min(1, " .. x .. ")))" end
local GROWN = "L(l * (1 + 0.1 * " .. step("1 - l") .. "), r * (1 + 0.05 * " ..
              step("-0.05 * v + 0.25 - r + 1e-12") .. "), a + 1, v)"
local CHILD = "[/(90.0 * math.floor(ran(2)))%s(10 + ran(20))#(0.1)L(0.5, 0.05, 0, v + 1)]"

local function lsystem ()
  local spawn = "L(l, r, a, v) : a == 5 and v < " .. LEVELS .. " --> "
  local prods = table.concat({
    spawn .. GROWN .. CHILD:format("+") .. CHILD:format("-") .. " : 0.7225",
    spawn .. GROWN .. CHILD:format("+") .. " : 0.1275",
    spawn .. GROWN .. CHILD:format("-") .. " : 0.1275",
    spawn .. GROWN .. " : 0.0225",
    "L(l, r, a, v) --> " .. GROWN,
  }, "\n")
  local axiom = {}
  for k = 0, 4 do
    axiom[#axiom + 1] = string.format("[f(%d)-(90)#(0.1)L(0.5, 0.05, 0, 1)]", (k - 2) * 6)
  end
  return lsys.lsystem {
    axiom = "+(90)" .. table.concat(axiom), productions = prods,
    homomorphism = "L(l, r, a, v) --> #(2 * r)F(l)", seed = SEED, steps = 0,
    view = { line_style = "cylinder", contour_sides = 8 },
  }
end

local function limbs (s) return s:count("L") end

local function rss_mib ()
  local f = io.open("/proc/self/status", "r")
  if not f then return nil end
  local t = f:read("a")
  f:close()
  local kb = t:match("VmRSS:%s*(%d+)")
  return kb and tonumber(kb) / 1024 or nil
end

print(string.format("lsys %s, %s; incremental: %d ticks timed at each size", lsys.version,
                    B.clock_name, TICKS))
local m = lsystem()
local s = m:derive()
for k = 0, 4 do assert(m._rules:hasvm(k), "rule " .. k .. " is not in the expression machine") end
local at4000, at30k
for _, n in ipairs(SIZES) do
  -- the L-system first: derived until it has n limbs or more; the world then grows to as
  -- many, so both run at the same size
  while limbs(s) < n do s = m:step(s) end
  local size = limbs(s)
  local t1 = B.clock()
  for _ = 1, 3 do m:interpret(m:step(s)) end    -- the mean, as for the incremental ticks
  local reg = (B.clock() - t1) * 1000 / 3
  local w = world(size)
  local guard = 0
  while not w.capped and guard < 1000 do w:tick() guard = guard + 1 end
  local t0 = B.clock()
  w:tick(TICKS)                -- the ticks right after: young limbs still grow
  local inc = (B.clock() - t0) * 1000 / TICKS
  print(string.format("grow %d limbs: incremental %.3f ms/tick, regenerate %.1f ms/tick, " ..
                      "ratio %.1f", size, inc, reg, reg / inc))
  print(string.format("  (%d asked; the world's scene %d vertices; %d modules derived and " ..
                      "interpreted)", n, w:scene().nvertices, #s))
  if n == 4000 then at4000 = { inc, reg, size } end
  if n == 5000 then at30k = { reg, #s } end
end

if at4000 then
  print(string.format("target at about 4,000 limbs (%d): a tick under 1 ms (%.3f ms: %s), at " ..
                      "least 20x faster than regenerating (%.1fx: %s)", at4000[3], at4000[1],
                      B.verdict(at4000[1] < 1), at4000[2] / at4000[1],
                      B.verdict(at4000[2] / at4000[1] >= 20)))
end

if at30k then
  print(string.format("target (issue 41): regenerating a plant of 30,000 modules or more (%d) " ..
                      "in under 10 ms (%.1f ms: %s)", at30k[2], at30k[1], B.verdict(at30k[1] < 10)))
end

-- memory once grown: 200 more ticks of the 4,000-limb world
do
  local w = world(4000)
  while not w.capped do w:tick() end
  w:tick(20)
  collectgarbage("collect")
  local lua0, rss0 = collectgarbage("count") / 1024, rss_mib()
  w:tick(200)
  collectgarbage("collect")
  local lua1, rss1 = collectgarbage("count") / 1024, rss_mib()
  print(string.format("memory over 200 ticks once grown: Lua %.2f -> %.2f MiB, RSS %s -> %s MiB",
                      lua0, lua1, rss0 and string.format("%.1f", rss0) or "?",
                      rss1 and string.format("%.1f", rss1) or "?"))
end
local mib = B.peak_mib()
print(mib and string.format("peak memory (VmHWM): %.0f MiB", mib) or "peak memory: unknown")
