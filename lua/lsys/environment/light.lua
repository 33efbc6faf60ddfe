--- A light environment: the light reaching each query from a sky, shaded by the plant's own
-- geometry (its leaves, polygons, surfaces and cylinders), by ray casting through a
-- bounding-volume hierarchy built each pass from the plant as the turtle draws it
-- (core.light; Mech and Prusinkiewicz 1996 §5.3, Palubicki et al. 2009 §4: a bud's
-- exposure). docs/open.md §2.
--
-- `lsys.environment.light { sky =, samples =, transmittance =, line_radius =, offset =,
-- facing =, threads = }` answers each ?E with the light at its position, from 0 (in full
-- shade) to 1 (under the open sky); a ?E of four parameters or more also gets the
-- direction light comes from most (the mean unoccluded direction: x, y, z), as vlab's
-- chiba answers. `facing = "up"` or `"heading"` weighs each direction by its cosine with
-- the turtle's up or heading vector there (a leaf's irradiance, 1 for an open leaf facing
-- straight up), and counts none from behind; without it every direction of the sky counts
-- alike (a bud's exposure).
-- sky: "overcast" (default; `samples` directions of the upper hemisphere, 64),
-- { sun = { x, y, z }, ambient = a } (a sun direction, and the overcast sky's share a),
-- or a list of { x, y, z, w } (weighted directions).
-- @module lsys.environment.light
local core = require "lsys.core"

local type, ipairs, pairs, error, pcall, tostring, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Light = {}
Light.__index = Light

local OPTIONS = { sky = true, radiance = true, samples = true, transmittance = true,
                  max_hits = true, line_radius = true, offset = true, facing = true,
                  threads = true }

--- The environment (see the module's header for the options).
function M.light (opts)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.environment.light: an options table expected", 2) end
  local copt = {}
  for k, v in pairs(opts) do
    if not OPTIONS[k] then
      error(format("lsys.environment.light: unknown option '%s'", tostring(k)), 2)
    end
    if k ~= "facing" then copt[k] = v end
  end
  local f = opts.facing
  if f ~= nil and f ~= "up" and f ~= "heading" then
    error("lsys.environment.light: facing must be \"up\" or \"heading\"", 2)
  end
  -- (the sky's and the ray caster's options are checked by core.light at the first pass)
  return setmetatable({ opts = copt, facing = f }, Light)
end

function Light.__tostring () return "lsys.environment.light" end

--- Answers the queries of a pass: the light at each, and where it comes from most.
function Light:answer (queries, info)
  local scene = info.scene
  local okL, L = pcall(core.light, scene, self.opts)
  if not okL then          -- a bad option: said as the environment's, without a position
    error((tostring(L):gsub("^[^\n]-:%d+: ", ""):gsub("^core%.light: opts%.",
                                                       "lsys.environment.light: ")), 0)
  end
  local pts, nrm, want = {}, self.facing and {} or nil, false
  for i, q in ipairs(queries) do
    local p = q.position
    pts[3 * i - 2], pts[3 * i - 1], pts[3 * i] = p[1], p[2], p[3]
    if nrm then
      local v = self.facing == "up" and q.up or q.heading
      nrm[3 * i - 2], nrm[3 * i - 1], nrm[3 * i] = v[1], v[2], v[3]
    end
    if #q.params >= 4 then want = true end
  end
  local ok, values, dirs = pcall(L.query, L, pts, nrm, { directions = want })
  local scale = 1
  if ok and nrm then
    -- a leaf's light relative to an open leaf facing straight up (1), as a bud's is to
    -- the open sky: the core gives the cosine-weighted sum, 1/2 for it under a uniform sky
    local d, w = L:sky()
    local open = 0
    for k = 1, #w do open = open + w[k] * math.max(0, d[3 * k - 1]) end
    if open > 0 then scale = 1 / open end
  end
  L:close()
  if not ok then error(values, 0) end
  if scale ~= 1 then for i = 1, #values do values[i] = values[i] * scale end end
  local answers = {}
  for i, q in ipairs(queries) do
    if #q.params >= 4 then
      answers[i] = { values[i], dirs[3 * i - 2], dirs[3 * i - 1], dirs[3 * i] }
    else
      answers[i] = values[i]
    end
  end
  return answers
end

return M
