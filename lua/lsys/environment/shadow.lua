--- A shadow environment: the light reaching each query estimated without rays, by the
-- shadow-propagation grid of Palubicki et al. 2009, "Self-organizing tree models for image
-- synthesis", §4.1 (core.shadow): space is cut into cubic voxels, every shadow caster
-- darkens the pyramid of voxels below it (a b^-q at q levels down, `depth` levels), and a
-- bud's exposure is Q = max(C - s + a, 0), s the shadow of its voxel (the + a takes away
-- its own). docs/open.md §2.
--
-- `lsys.environment.shadow { voxel =, depth =, a =, b =, C =, angle =, radius =, margin =,
-- casters =, obstacles =, threads = }` builds the grid at each pass over the box of the
-- query points (and of the scene, when it casts), widened by `margin` on every side, and
-- answers each ?E with Q / C, from 0 (deep shade) to 1 (nothing above it); a ?E of four
-- parameters or more also gets the direction of least shadow (x, y, z): the unit vector to
-- the centre of the least-shadowed voxel whose centre is within `radius` voxels and `angle`
-- degrees of the turtle's heading there (of equal shadows, the one nearest the heading; the
-- heading itself when there is none), as the light environment answers the direction of
-- most light.
--
-- obstacles: a list of boxes { lo = { x, y, z }, hi = { x, y, z }, shadow = (C), cast =
-- (true) } that are there at every pass (a wall, a rock, a roof): each adds `shadow` to the
-- voxels it overlaps, so that no bud finds light in it or turns towards it, and with `cast`
-- each of its voxels in the grid casts as a bud does, so that it shades the buds beside and
-- under it (examples/open/wall.lua).
-- casters: "queries" (the default: every ?E is a bud that casts, as in the paper),
-- "scene" (the plant as the turtle draws it, info.scene: each triangle at its centroid,
-- weighing its area over a voxel's face, so that a voxel's face of leaf weighs as much
-- as a bud; a query then has no shadow of its own to take away, and gets max(C - s, 0) / C)
-- or "both". Defaults: voxel 1 (world units: about an internode), depth 4, a 1, b 2, C 8
-- (the shadow, beyond its own, that leaves a bud no light: a bud one voxel under another
-- keeps 1 - 0.5 / 8 of its light; fitted to ray casting, bench/shadow.lua finds C from about
-- 6 to 13), angle 90, radius 2 (voxels), margin (radius + 1) voxels (world units), threads 0
-- (the derivation's default). The directions go to voxel centres, so they come in steps of
-- the grid.
-- @module lsys.environment.shadow
local core = require "lsys.core"
local check = require "lsys.environment.check"

local type, ipairs, pairs, error, pcall, tostring, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Shadow = {}
Shadow.__index = Shadow

local DEFAULTS = { voxel = 1, depth = 4, a = 1, b = 2, C = 8, angle = 90, radius = 2,
                   casters = "queries", threads = 0 }
local CASTERS = { queries = true, scene = true, both = true }

-- A core error said as the environment's: without a position, and with the option's name.
local function reword (msg)
  return (tostring(msg):gsub("^[^\n]-:%d+: ", "")
                       :gsub("^core%.shadow: opts%.", "lsys.environment.shadow: ")
                       :gsub("^shadow:direction: opts%.", "lsys.environment.shadow: ")
                       :gsub("^core%.shadow: ", "lsys.environment.shadow: ")
                       :gsub("^shadow:%w+: ", "lsys.environment.shadow: "))
end

local finite, vec3 = check.finite, check.vec3

-- The option `obstacles` checked: a list of { lo =, hi =, shadow = (C), cast = (true) }.
local function obstacles (list, C)
  if list == nil then return {} end
  if type(list) ~= "table" then
    error("lsys.environment.shadow: obstacles must be a list of boxes { lo =, hi = }", 3)
  end
  local out = {}
  for i, b in ipairs(list) do
    local function bad (what)
      error(format("lsys.environment.shadow: obstacle %d: %s", i, what), 4)
    end
    if type(b) ~= "table" or not vec3(b.lo) or not vec3(b.hi) then
      bad("lo and hi must be points { x, y, z }")
    end
    for c = 1, 3 do if b.hi[c] < b.lo[c] then bad("hi must not be below lo") end end
    local sh = b.shadow == nil and C or b.shadow
    if not (finite(sh) and sh >= 0) then bad("shadow must be a finite number >= 0") end
    if b.cast ~= nil and type(b.cast) ~= "boolean" then bad("cast must be a boolean") end
    out[i] = { lo = { b.lo[1], b.lo[2], b.lo[3] }, hi = { b.hi[1], b.hi[2], b.hi[3] },
               shadow = sh, cast = b.cast ~= false }
  end
  return out
end

-- The centres of the voxels (of the grid lo, voxel v, hi, continued outside it) that lie in
-- box b and whose shadow reaches the grid, `depth` deep: the casters of an obstacle.
local MAXCAST = 4000000
local function centres (b, lo, hi, v, depth)
  local pts, r = {}, {}
  for c = 1, 3 do
    local a = math.max(b.lo[c], lo[c] - (c == 2 and 0 or depth * v))
    local z = math.min(b.hi[c], hi[c] + depth * v)
    if z < a then return pts end
    r[c] = { math.floor((a - lo[c]) / v), math.floor((z - lo[c]) / v) }
  end
  local n = (r[1][2] - r[1][1] + 1) * (r[2][2] - r[2][1] + 1) * (r[3][2] - r[3][1] + 1)
  if n > MAXCAST then
    error(format("lsys.environment.shadow: an obstacle covers %d voxels of the grid (at most "
      .. "%d cast): make the voxels bigger or the obstacle smaller", n, MAXCAST), 0)
  end
  for i = r[1][1], r[1][2] do
    for j = r[2][1], r[2][2] do
      for k = r[3][1], r[3][2] do
        pts[#pts + 1] = lo[1] + (i + 0.5) * v
        pts[#pts + 1] = lo[2] + (j + 0.5) * v
        pts[#pts + 1] = lo[3] + (k + 0.5) * v
      end
    end
  end
  return pts
end

--- The environment (see the module's header for the options).
function M.shadow (opts)
  opts = opts or {}
  if type(opts) ~= "table" then
    error("lsys.environment.shadow: an options table expected", 2)
  end
  local o = {}
  for k, d in pairs(DEFAULTS) do o[k] = d end
  for k, v in pairs(opts) do
    if DEFAULTS[k] == nil and k ~= "margin" and k ~= "obstacles" then
      error(format("lsys.environment.shadow: unknown option '%s'", tostring(k)), 2)
    end
    o[k] = v
  end
  if not CASTERS[o.casters] then
    error("lsys.environment.shadow: casters must be \"queries\", \"scene\" or \"both\"", 2)
  end
  if not (finite(o.C) and o.C > 0) then
    error("lsys.environment.shadow: C must be a finite number > 0", 2)
  end
  if o.margin ~= nil and not (finite(o.margin) and o.margin >= 0) then
    error("lsys.environment.shadow: margin must be a finite number >= 0", 2)
  end
  -- the grid's and the cone's options, checked by the core on a grid of one voxel
  local ok, err = pcall(function ()
    local g <close> = core.shadow { lo = { 0, 0, 0 }, hi = { 0, 0, 0 }, voxel = o.voxel,
      depth = o.depth, a = o.a, b = o.b, threads = o.threads }
    g:direction({ 0, 0, 0 }, { 0, 1, 0 }, { angle = o.angle, radius = o.radius })
  end)
  if not ok then error(reword(err), 2) end
  if o.margin == nil then o.margin = (math.ceil(o.radius) + 1) * o.voxel end
  o.obstacles = obstacles(o.obstacles, o.C)
  return setmetatable({ opts = o }, Shadow)
end

function Shadow.__tostring () return "lsys.environment.shadow" end

-- The grid's box: the points' bounds and the scene's (nil: none), widened by m.
local function box (pts, slo, shi, m)
  local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
  for i = 1, #pts, 3 do
    for c = 1, 3 do
      local x = pts[i + c - 1]
      if x < lo[c] then lo[c] = x end
      if x > hi[c] then hi[c] = x end
    end
  end
  for c = 1, 3 do
    if slo then
      lo[c], hi[c] = math.min(lo[c], slo[c]), math.max(hi[c], shi[c])
    end
    lo[c], hi[c] = lo[c] - m, hi[c] + m
  end
  return lo, hi
end

--- Answers the queries of a pass: each one's exposure, and where the shadow is least.
function Shadow:answer (queries, info)
  local o = self.opts
  if #queries == 0 then return {} end
  local pts, hs, want = {}, {}, false
  for i, q in ipairs(queries) do
    local p, h = q.position, q.heading
    pts[3 * i - 2], pts[3 * i - 1], pts[3 * i] = p[1], p[2], p[3]
    hs[3 * i - 2], hs[3 * i - 1], hs[3 * i] = h[1], h[2], h[3]
    if #q.params >= 4 then want = true end
  end
  local scene, slo, shi = nil, nil, nil
  if o.casters ~= "queries" then
    scene = info.scene
    slo, shi = scene:bounds()
  end
  local lo, hi = box(pts, slo, shi, o.margin)
  local values, dirs
  local ok, err = pcall(function ()
    local g <close> = core.shadow { lo = lo, hi = hi, voxel = o.voxel, depth = o.depth,
                                    a = o.a, b = o.b, threads = o.threads }
    local own = o.casters ~= "scene"
    if own then g:add(pts) end
    if scene and slo then g:add_scene(scene) end
    for _, b in ipairs(o.obstacles) do            -- a wall, a rock: dark, and casting
      if b.shadow > 0 then g:add_box(b.lo, b.hi, b.shadow) end
      if b.cast then
        local c = centres(b, lo, hi, o.voxel, o.depth)
        if #c > 0 then g:add(c) end
      end
    end
    -- a query that cast has its own a taken away by the exposure; one that did not, none
    values = g:exposure(pts, own and o.C or o.C - o.a)
    if want then dirs = g:direction(pts, hs, { angle = o.angle, radius = o.radius }) end
  end)
  if not ok then error(reword(err), 0) end
  local answers = {}
  for i, q in ipairs(queries) do
    local v = math.min(1, values[i] / o.C)
    if #q.params >= 4 then
      answers[i] = { v, dirs[3 * i - 2], dirs[3 * i - 1], dirs[3 * i] }
    else
      answers[i] = v
    end
  end
  return answers
end

return M
