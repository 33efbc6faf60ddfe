--- A space colonisation environment: buds compete for markers (attraction points) of the
-- space a crown may fill, and grow towards those they win (Runions, Lane and Prusinkiewicz
-- 2007, "Modeling trees with a space colonization algorithm", §3; Palubicki et al. 2009,
-- "Self-organizing tree models for image synthesis", §4.2; core.markers, in C;
-- docs/open.md §2).
--
-- `lsys.environment.colonize { markers =, perception =, kill =, angle =, answer =,
-- threads = }`: each ?E is a bud at the turtle's position, facing the turtle's heading.
-- At each pass, first every marker within `kill` of a bud is removed (the space the bud
-- now occupies: for good), then every other marker within `perception` of a bud and within
-- its cone of half-angle `angle` (degrees, 90 by default: the half-space ahead) goes to the
-- nearest such bud. A bud's ?E is answered with Q: 1 when it won a marker, else 0 (with
-- `answer = "count"`: how many); a ?E of four parameters or more also gets the direction
-- (x, y, z) of the normalised sum of the unit vectors from the bud to its markers, where
-- its shoot is to grow (0, 0, 0 for none).
--
-- `markers` is a list of points ({ {x, y, z}, ... }, or flat { x1, y1, z1, ... }), or
-- { count = n, envelope = "sphere" | "box" | function (x, y, z) -> boolean, lo = {x, y, z},
-- hi = {x, y, z}, seed = s }: n points uniformly in the box lo .. hi, kept where the
-- envelope says ("sphere": the ellipsoid inscribed in the box; a function: where it
-- returns true), drawn by a seeded generator (SplitMix64; seed 1 by default), so the same
-- options give the same markers everywhere. The markers are made at the first pass of
-- each derivation (the environment's start), so deriving twice grows the same plant.
-- `env:count()` says how many are left, `env:points()` where (a flat list).
-- @module lsys.environment.colonize
local core = require "lsys.core"
local check = require "lsys.environment.check"

local type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Colonize = {}
Colonize.__index = Colonize

local OPTIONS = { markers = true, perception = true, kill = true, angle = true, answer = true,
                  threads = true }
local MARKEROPTS = { count = true, envelope = true, lo = true, hi = true, seed = true }
local MAXCOUNT = 1 << 26            -- markers made from a count
local TRIES = 1000                  -- draws a marker, at most, before an envelope is refused

local function bad (msg) error("lsys.environment.colonize: " .. msg, 3) end

local finite = check.finite

local function vec3 (v, what)
  if not check.vec3(v) then bad(what .. " must be a list {x, y, z} of finite numbers") end
  return v
end

-- A uniform generator of [0, 1) from `seed`: SplitMix64 (Steele, Lea and Flood 2014), in
-- Lua's wrapping 64-bit integers.
local function splitmix (seed)
  local s = seed
  return function ()
    s = s + 0x9E3779B97F4A7C15
    local z = s
    z = (z ~ (z >> 30)) * 0xBF58476D1CE4E5B9
    z = (z ~ (z >> 27)) * 0x94D049BB133111EB
    z = z ~ (z >> 31)
    return (z >> 11) * 2.0 ^ -53
  end
end

-- Checks the option `markers`; returns a maker of the flat list of markers.
local function markermaker (m)
  if type(m) ~= "table" then bad("markers must be a list of points or { count = n, ... }") end
  if m.count == nil then                 -- a list: { {x, y, z}, ... } or flat
    local flat = {}
    if type(m[1]) == "table" then
      for i, p in ipairs(m) do
        vec3(p, format("markers[%d]", i))
        flat[3 * i - 2], flat[3 * i - 1], flat[3 * i] = p[1], p[2], p[3]
      end
    else
      if #m % 3 ~= 0 then bad("markers as a flat list must have 3 numbers a point") end
      for i = 1, #m do
        if not finite(m[i]) then bad(format("markers[%d] must be a finite number", i)) end
        flat[i] = m[i]
      end
    end
    return function () return flat end
  end
  for k in pairs(m) do
    if not MARKEROPTS[k] then bad(format("unknown markers option '%s'", tostring(k))) end
  end
  local n = m.count
  if math.type(n) ~= "integer" or n < 0 or n > MAXCOUNT then
    bad(format("markers.count must be an integer in [0, %d]", MAXCOUNT))
  end
  local lo, hi = vec3(m.lo, "markers.lo"), vec3(m.hi, "markers.hi")
  for c = 1, 3 do
    if not (lo[c] < hi[c]) then bad("markers.lo must be below markers.hi in x, y and z") end
  end
  local env = m.envelope or "box"
  if env ~= "box" and env ~= "sphere" and type(env) ~= "function" then
    bad("markers.envelope must be \"sphere\", \"box\" or a function (x, y, z) -> boolean")
  end
  local seed = m.seed or 1
  if math.type(seed) ~= "integer" then bad("markers.seed must be an integer") end
  local lox, loy, loz, hix, hiy, hiz = lo[1], lo[2], lo[3], hi[1], hi[2], hi[3]
  return function ()
    local rnd, flat, k, tries = splitmix(seed), {}, 0, 0
    local cx, cy, cz = (lox + hix) / 2, (loy + hiy) / 2, (loz + hiz) / 2
    local hx, hy, hz = (hix - lox) / 2, (hiy - loy) / 2, (hiz - loz) / 2
    while k < n do
      tries = tries + 1
      if tries > TRIES * n then
        error(format("lsys.environment.colonize: the envelope took %d of %d markers in %d "
          .. "draws", k, n, tries - 1), 0)
      end
      local x, y, z = lox + (hix - lox) * rnd(), loy + (hiy - loy) * rnd(),
                      loz + (hiz - loz) * rnd()
      local keep = true
      if env == "sphere" then
        local u, v, w = (x - cx) / hx, (y - cy) / hy, (z - cz) / hz
        keep = u * u + v * v + w * w <= 1
      elseif env ~= "box" then
        keep = env(x, y, z)
      end
      if keep then
        k = k + 1
        flat[3 * k - 2], flat[3 * k - 1], flat[3 * k] = x, y, z
      end
    end
    return flat
  end
end

-- core.markers' message about bud or heading k as one about its query.
local function blame (msg)
  msg = tostring(msg)
  local what, k = msg:match("^markers:perceive: (%a+)%[(%d+)%] must be a finite number")
  if k then
    return format("query %d: its %s is not finite", (tonumber(k) + 2) // 3,
                  what == "buds" and "position" or "heading")
  end
  return (msg:gsub("^markers:perceive: bud (%d+)", "query %1: its position")
             :gsub("^markers:perceive: heading (%d+)", "query %1: its heading"))
end

--- The environment (see the module's header for the options).
function M.colonize (opts)
  if type(opts) ~= "table" then bad("an options table expected") end
  for k in pairs(opts) do
    if not OPTIONS[k] then bad(format("unknown option '%s'", tostring(k))) end
  end
  if opts.markers == nil then bad("markers is required (a list of points or { count = n, "
    .. "envelope =, lo =, hi =, seed = })") end
  local make = markermaker(opts.markers)
  local per = opts.perception
  if not finite(per) or per <= 0 then bad("perception must be a number > 0") end
  local kill = opts.kill or 0
  if not finite(kill) or kill < 0 or kill > 16 * per then
    bad("kill must be a number in [0, 16 times the perception]")
  end
  local angle = opts.angle or 90
  if not finite(angle) or angle <= 0 or angle > 180 then
    bad("angle must be a number of degrees in (0, 180]")
  end
  local answer = opts.answer or "presence"
  if answer ~= "presence" and answer ~= "count" then
    bad("answer must be \"presence\" or \"count\"")
  end
  local t = opts.threads
  if t ~= nil and (math.type(t) ~= "integer" or t < 0 or t > 64) then
    bad("threads must be an integer in [0, 64]")
  end
  return setmetatable({ make = make, count_answer = answer == "count",
                        popts = { perception = per, kill = kill, angle = angle,
                                  threads = t or 0 } }, Colonize)
end

function Colonize.__tostring () return "lsys.environment.colonize" end

--- At the start of each derivation: the markers are made afresh at its first pass.
function Colonize:start ()
  if self.set then self.set:close() end
  self.set = nil
end

-- The markers, made when there are none yet.
local function markers (self)
  if self.set == nil then self.set = core.markers(self.make()) end
  return self.set
end

--- The markers left (made if they were not yet).
function Colonize:count () return markers(self):count() end

--- Where the markers left are: a flat list {x1, y1, z1, ...}.
function Colonize:points () return markers(self):points() end

--- Answers the queries of a pass (see the module's header).
function Colonize:answer (queries)
  local set = markers(self)
  local buds, heads = {}, {}
  for i, q in ipairs(queries) do
    local p, h = q.position, q.heading
    buds[3 * i - 2], buds[3 * i - 1], buds[3 * i] = p[1], p[2], p[3]
    heads[3 * i - 2], heads[3 * i - 1], heads[3 * i] = h[1], h[2], h[3]
  end
  local ok, counts, dirs = pcall(set.perceive, set, buds, heads, self.popts)
  if not ok then error(blame(counts), 0) end
  local answers, all = {}, self.count_answer
  for i, q in ipairs(queries) do
    local c = counts[i]
    local a = all and c or (c > 0 and 1 or 0)
    if #q.params >= 4 then
      answers[i] = { a, dirs[3 * i - 2], dirs[3 * i - 1], dirs[3 * i] }
    else
      answers[i] = a
    end
  end
  return answers
end

return M
