--- Fuzz target: the rules of incremental growth (lsys.grow, lua/lsys/grow.lua and
-- csrc/lua/lua_grow.c): rules given as tables, whose conditions and declared changes run in
-- C (on the expression machine, or checked directly when the condition is a conjunction of
-- comparisons), against the same rules written as Lua functions. Its corpus is
-- tests/fuzz/corpus_grow.
--
-- The bytes are lines:
--   seed S | ticks N (at most 16) | plants N (at most 4) | max N (the world's max_limbs,
--   at most 600) | kind NAME (the rules after it belong to a kind based on the first)
--   rule WHEN | CHANGE ARGS | ...     WHEN a condition (empty: none); CHANGE one of
--     scale_length F, scale_radius F, color C, blend C T, fn ACTION (spawn, fork, leaves,
--     drop, remove, turn, shorten, paint, grow)
-- Other lines are left out; a value that is not a number is passed on as text.
-- World A is made with the rules as tables; world B (same seed, same plants) with each rule
-- as a function that evaluates WHEN in Lua (the variables as floats, a number true unless
-- 0, as grow.md says) and then makes the declared changes and the action by the limb's
-- methods. Expected errors: lsys.grow's ("lsys.grow: ..."), made while building world A.
-- Checks: world B builds and grows without error when A does, and after every tick both
-- have the same limbs with the same length, radius, colour, age, level, leaves, tip and
-- life; the plants written as an Lstring (world:lstring) and read back
-- (grow.from_lstring) give a limb for each limb of nonzero length, with its length, radius
-- and tip (to 1e-6 of the plant's size).
local lsys = require "lsys"
local grow = lsys.grow

local type, ipairs, pcall, tostring, tonumber, load = type, ipairs, pcall, tostring, tonumber, load
local math, floor, min, abs, max = math, math.floor, math.min, math.abs, math.max
local format = string.format

local T = { maxlen = 2048, budget = 3 }

local _ENV = nil

-- --------------------------------------------------------------------------
-- Inputs

local ACTIONS = {
  spawn = function (limb)
    if limb:random() < 0.8 then
      limb:spawn { angle = limb:random(10, 30), axis = limb:random() < 0.5 and "z" or "x" }
    end
  end,
  fork = function (limb, _, sub)
    limb:spawn { roll = 137.5, angle = 25, at = limb:random(), length = 0.3, radius = 0.02,
                 kind = sub }
    limb:spawn { angle = -15, axis = { 1, 1, 0 }, color = "#804020" }
  end,
  leaves = function (limb) limb:add_leaves(2, { size = 0.3, color = "#30a030" }) end,
  drop = function (limb) limb:drop_leaves() end,
  remove = function (limb) if not limb:is_root() and limb:random() < 0.3 then limb:remove() end end,
  turn = function (limb) limb:turn { angle = 7, axis = "z", roll = 3 } end,
  shorten = function (limb) limb:set_length(limb:length() * 0.9) end,
  paint = function (limb) limb:set_color { 0.2, 0.4, limb:random() } end,
  grow = function (limb) limb:set_radius(limb:radius() + 0.001) end,
}

local function value (s)
  if s == nil then return nil end
  return tonumber(s) or s
end

-- The input as { seed, ticks, plants, max, rules = { { kind, name, when, changes } } }
local function decode (bytes)
  local d = { seed = 1, ticks = 8, plants = 1, max = 500, rules = {}, sub = nil }
  local kind = 1
  for line in (bytes .. "\n"):gmatch("([^\n]*)\n") do
    local word, rest = line:match("^%s*(%a+)%s*(.-)%s*$")
    local n = tonumber(rest)
    if word == "seed" and n then d.seed = n
    elseif word == "ticks" and n then d.ticks = min(max(floor(n), 0), 16)
    elseif word == "plants" and n then d.plants = min(max(floor(n), 1), 4)
    elseif word == "max" and n then d.max = min(max(floor(n), 1), 600)
    elseif word == "kind" then kind = 2; d.sub = rest ~= "" and rest or "sub"
    elseif word == "rule" then
      local parts = {}
      for p in (rest .. "|"):gmatch("([^|]*)|") do parts[#parts + 1] = p:match("^%s*(.-)%s*$") end
      local r = { kind = kind, name = "r" .. #d.rules + 1, changes = {} }
      if parts[1] ~= "" then r.when = parts[1] end
      for i = 2, #parts do
        local words = {}
        for w in parts[i]:gmatch("%S+") do words[#words + 1] = w end
        if words[1] then r.changes[#r.changes + 1] = words end
      end
      d.rules[#d.rules + 1] = r
    end
  end
  return d
end

-- The rule table of world A.
local function tablerule (r)
  local t = { when = r.when }
  for _, c in ipairs(r.changes) do
    local k = c[1]
    if k == "scale_length" or k == "scale_radius" then t[k] = value(c[2])
    elseif k == "color" then t.color = value(c[2])
    elseif k == "blend" then t.blend = { value(c[2]), value(c[3]) }
    elseif k == "fn" then t.fn = ACTIONS[c[2]] or c[2]
    else t[k] = value(c[2]) end
  end
  return t
end

-- The same rule as a Lua function, for world B: its condition in Lua.
local function luarule (r, subkind)
  local cond
  if r.when then
    local env = { math = math }
    local chunk = load("return " .. r.when, "=when", "t", env)
    if chunk == nil then return nil, "the condition does not compile in Lua" end
    cond = function (limb, world)
      env.length, env.radius = limb:length() + 0.0, limb:radius() + 0.0
      env.age, env.level, env.leaves = limb:age() + 0.0, limb:level() + 0.0, limb:leaves() + 0.0
      env.count, env.root = limb:count() + 0.0, limb:is_root() and 1.0 or 0.0
      env.total = world:count() + 0.0
      local v = chunk()
      if type(v) == "number" then return v ~= 0 end
      return v
    end
  end
  local t = tablerule(r)
  local fn = t.fn
  return function (limb, world)
    if cond and not cond(limb, world) then return end
    if t.scale_length then limb:scale_length(t.scale_length) end
    if t.scale_radius then limb:scale_radius(t.scale_radius) end
    if t.blend then limb:blend_color(t.blend[1], t.blend[2]) end
    if t.color then limb:set_color(t.color) end
    if fn then fn(limb, world, subkind) end
  end
end

-- --------------------------------------------------------------------------
-- Worlds

local function plant (w, d, K)
  for p = 1, d.plants do
    w:plant { kind = K, position = { (p - 1) * 3, 0, 0 }, length = 0.4 + 0.1 * p,
              radius = 0.03 }
  end
end

-- World A: the rules as tables. Raises lsys.grow's errors.
local function worldA (d)
  local K = grow.kind("tree")
  local S = d.sub and grow.kind(d.sub, K)
  for _, r in ipairs(d.rules) do
    local t = tablerule(r)
    if type(t.fn) == "function" then
      local f = t.fn
      t.fn = function (limb, world) return f(limb, world, S) end
    end
    ;(r.kind == 2 and S or K):rule(r.name, t)
  end
  local w = grow.world { seed = d.seed, max_limbs = d.max }
  plant(w, d, K)
  return w
end

-- World B: the rules as functions; nil and why when one cannot be made.
local function worldB (d)
  local K = grow.kind("tree")
  local S = d.sub and grow.kind(d.sub, K)
  for _, r in ipairs(d.rules) do
    local f, why = luarule(r, S)
    if f == nil then return nil, why end
    ;(r.kind == 2 and S or K):rule(r.name, f)
  end
  local w = grow.world { seed = d.seed, max_limbs = d.max }
  plant(w, d, K)
  return w
end

local function same3 (a, b)
  return a[1] == b[1] and a[2] == b[2] and a[3] == b[3]
end

local STATE = {
  { "length", function (l) return l:length() end },
  { "radius", function (l) return l:radius() end },
  { "age", function (l) return l:age() end },
  { "level", function (l) return l:level() end },
  { "leaves", function (l) return l:leaves() end },
  { "kind", function (l) return l:kind() end },
}

-- The first difference between the limbs of worlds a and b, or nil.
local function compare (a, b, tick)
  local la, lb = a:limbs(), b:limbs()
  if #la ~= #lb then
    return format("after tick %d: %d limbs with the rules in C, %d with them in Lua", tick,
                  #la, #lb)
  end
  for i, x in ipairs(la) do
    local y = lb[i]
    if x:id() ~= y:id() then return format("after tick %d: limb %d has id %d / %d", tick, i,
                                           x:id(), y:id()) end
    for _, s in ipairs(STATE) do
      local u, v = s[2](x), s[2](y)
      if u ~= v and not (u ~= u and v ~= v) then
        return format("after tick %d: limb %d: %s %s with the rules in C, %s in Lua", tick,
                      x:id(), s[1], tostring(u), tostring(v))
      end
    end
    local ca, cb = x:color(), y:color()
    if not same3(ca, cb) then
      return format("after tick %d: limb %d: colour {%g, %g, %g} / {%g, %g, %g}", tick, x:id(),
                    ca[1], ca[2], ca[3], cb[1], cb[2], cb[3])
    end
    local ta, tb = { x:tip() }, { y:tip() }
    if not same3(ta, tb) then
      return format("after tick %d: limb %d: tip (%g, %g, %g) / (%g, %g, %g)", tick, x:id(),
                    ta[1], ta[2], ta[3], tb[1], tb[2], tb[3])
    end
  end
  return nil
end

-- world:lstring() read back by grow.from_lstring: a limb for each segment the turtle draws
-- (a limb of nonzero length), with the length, radius and tip of the limb that wrote it.
-- Not for plants beyond float range (the scene's coordinates are floats).
local function roundtrip (w)
  local size = 1
  for _, l in ipairs(w:limbs()) do
    for _, c in ipairs { l:tip() } do size = max(size, abs(c)) end
    size = max(size, l:length(), l:radius())
  end
  if not (size < 1e30) then return nil end
  local s, owner = w:lstring()
  local w2, bylimb = grow.from_lstring(s, { max_limbs = 4000 })
  local scene = lsys.lsystem({ axiom = tostring(s), steps = 0 }):interpret()
  local k, n = 0, 0
  for _, l in ipairs(w:limbs()) do if l:length() > 0 then n = n + 1 end end
  if #bylimb ~= n or #w2:limbs() ~= n then
    return format("world:lstring() read back gives %d limbs for %d of nonzero length",
                  #bylimb, n)
  end
  local tol = 1e-6 * size
  for _, r in scene:records() do
    if r.kind == "segment" then
      k = k + 1
      local l, g = owner(r.module), bylimb[k]
      if l == nil or g == nil then
        return format("segment %d (module %d) has no limb", k, r.module)
      end
      if abs(g:length() - l:length()) > tol or abs(g:radius() - l:radius()) > tol then
        return format("limb %d read back: length %.17g radius %.17g, was %.17g %.17g", l:id(),
                      g:length(), g:radius(), l:length(), l:radius())
      end
      local a, b = { l:tip() }, { g:tip() }
      for j = 1, 3 do
        if abs(a[j] - b[j]) > tol then
          return format("limb %d read back: tip (%g, %g, %g), was (%g, %g, %g)", l:id(), b[1],
                        b[2], b[3], a[1], a[2], a[3])
        end
      end
    end
  end
  return nil
end

-- --------------------------------------------------------------------------
-- The target

local phase, finding

function T.clean (err)
  return phase == "A" and err:find("lsys.grow: ", 1, true) ~= nil
end

function T.run (bytes)
  finding = nil
  local d = decode(bytes)
  phase = "A"
  local a = worldA(d)
  phase = "B"
  local b, why = worldB(d)
  if b == nil then finding = "world B: " .. why return end
  for tick = 1, d.ticks do
    phase = "A"
    a:tick(1)
    phase = "B"
    local ok, err = pcall(b.tick, b, 1)
    if not ok then
      finding = format("tick %d: the rules in C ran, in Lua they fail: %s", tick, tostring(err))
      return
    end
    phase = "compare"
    finding = compare(a, b, tick)
    if finding then return end
  end
  phase = "lstring"
  finding = roundtrip(a)
  phase = "done"
end

-- a tick of A that fails is the rule's own (an action on a limb that cannot take it)
function T.after (tripped)
  if tripped then return nil end
  return finding
end

function T.describe (bytes) return bytes end

T.seeds = {
  "seed 3\nticks 20\nplants 2\n"
    .. "rule length < 1.0 and leaves == 0 | scale_length 1.1\n"
    .. "rule radius <= -0.05 * level + 0.25 and leaves == 0 | scale_radius 1.05\n"
    .. "rule age == 5 and count <= 256 and leaves == 0 and level < 10 | fn spawn\n"
    .. "rule age > 3 | blend #6b4a2b 0.15\n"
    .. "rule age == 6 and leaves == 0 and level >= 6 | fn leaves\n",
  "ticks 12\nrule length < 1 | scale_length 1.25\nrule age == 2 and level < 5 | fn fork\n"
    .. "kind twig\nrule age > 1 | color #ff0000 | fn turn\n"
    .. "rule leaves > 0 or root == 1 | fn drop\n",
  "ticks 10\nmax 40\nrule | fn spawn\nrule age >= 2 | fn remove\n"
    .. "rule not (level == 2) | fn paint\n",
  "ticks 6\nrule math.abs(length - 0.7) < 0.2 | scale_length 0.5 | fn shorten\n"
    .. "rule level == 1 * age + 1 | fn spawn\nrule age ~= 2 and count >= 3 | fn grow\n",
  "ticks 6\nrule radius < 0.01 * level + 0.04 | scale_radius 2\n"
    .. "rule length >= 0.5 and level > 1 | fn fork\nrule age < 1 and root == 1 | color #00ff00\n",
  "rule length | scale_length 0\nrule 0/0 ~= 0/0 | scale_radius 1\n"
    .. "rule min(age, 3) > 1 | fn spawn\n",
  "ticks 3\nrule | scale_length 1e308\n",
  "rule length < | scale_length 1\n",
  "rule age > 1 | scale_length -1\n",
  "rule age > 1 | blend #123456 2\n",
  "rule age > 1 | color nope\n",
  "rule age > 1 | fn nothing\n",
  "rule x > 1 | scale_length 2\n",
  "rule age > 1\n",
  "rule os.exit(1) | scale_length 2\n",
  "rule floor(age) // 2 == 1 | scale_length 2\n",
}

T.dict = { "rule ", " | ", "\n", "length", "radius", "age", "level", "leaves", "count", "root",
           "total",
           " and ", " or ", "not ", "<", "<=", ">", ">=", "==", "~=", "+", "-", "*", "/", "//",
           "%", "^", "(", ")", "math.", "math.pi", "math.huge", "abs(", "floor(", "sqrt(",
           "min(", "max(", "fmod(", "atan(", "sin(", "scale_length ", "scale_radius ",
           "color ", "blend ", "fn ", "spawn", "fork", "leaves", "drop", "remove", "turn",
           "shorten", "paint", "grow", "#6b4a2b", "#ff0000", "0", "1", "2", "0.5", "1e308",
           "0/0", "1/0", "-0.0", "seed ", "ticks ", "plants ", "max ", "kind ", "true",
           "false", "2^53" }

return T
