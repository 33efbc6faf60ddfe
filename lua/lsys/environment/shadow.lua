--- A shadow environment: the light reaching each query estimated without rays, by the
-- shadow-propagation grid of Palubicki et al. 2009, "Self-organizing tree models for image
-- synthesis", §4.1 (core.shadow): space is cut into cubic voxels, every shadow caster
-- darkens the pyramid of voxels below it (a b^-q at q levels down, `depth` levels), and a
-- bud's exposure is Q = max(C - s + a, 0), s the shadow of its voxel (the + a takes away
-- its own). docs/open.md §2.
--
-- `lsys.environment.shadow { voxel =, depth =, a =, b =, C =, angle =, radius =, margin =,
-- casters =, threads = }` builds the grid at each pass over the box of the query points
-- (and of the scene, when it casts), widened by `margin` on every side, and answers each
-- ?E with Q / C, from 0 (deep shade) to 1 (nothing above it); a ?E of four parameters or
-- more also gets the direction of least shadow (x, y, z): the unit vector to the centre of
-- the least-shadowed voxel whose centre is within `radius` voxels and `angle` degrees of
-- the turtle's heading there (of equal shadows, the one nearest the heading; the heading
-- itself when there is none), as the light environment answers the direction of most
-- light.
--
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

local function finite (x) return type(x) == "number" and x == x and x - x == 0 end

--- The environment (see the module's header for the options).
function M.shadow (opts)
  opts = opts or {}
  if type(opts) ~= "table" then
    error("lsys.environment.shadow: an options table expected", 2)
  end
  local o = {}
  for k, d in pairs(DEFAULTS) do o[k] = d end
  for k, v in pairs(opts) do
    if DEFAULTS[k] == nil and k ~= "margin" then
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
