--- A collision environment: which queries another one reaches (the collision test of
-- Honda 1981 that vlab's honda81 program answers, built in; docs/open.md §2).
--
-- `lsys.environment.collision { radius = r [, threads = n] }` answers each ?E(v [, g]) with
-- 1 when no other query of the same group g (0 without a second parameter) and of a vigour
-- at least v stands within distance r of it, else 0: of two sensors that would meet, the
-- weaker stops, and two of one vigour both stop, as honda81 answers. The queries go into a
-- space (core.space: a hash of cells of side r, in C), so a pass is linear in the number of
-- queries; the distances are compared as |p - q|^2 <= r^2, summed in the order x, y, z.
-- Groups are compared as numbers (a NaN group meets nobody), vigours with <= (a NaN vigour
-- neither stops nor is stopped).
-- @module lsys.environment.collision
local core = require "lsys.core"

local type, ipairs, pairs, error, pcall, setmetatable, tostring, tonumber, math =
      type, ipairs, pairs, error, pcall, setmetatable, tostring, tonumber, math
local format = string.format
local _ENV = nil

local M = {}

local Collision = {}
Collision.__index = Collision

--- The environment; opts: radius (> 0, world units), threads (0 .. 64; 0, the default: the
-- derivation's number).
function M.collision (opts)
  local r = type(opts) == "table" and opts.radius
  if type(r) ~= "number" or not (r > 0 and r < math.huge) then
    error("lsys.environment.collision: radius must be a number > 0", 2)
  end
  for k in pairs(opts) do
    if k ~= "radius" and k ~= "threads" then
      error(format("lsys.environment.collision: unknown option '%s'", tostring(k)), 2)
    end
  end
  local t = opts.threads
  if t ~= nil and (math.type(t) ~= "integer" or t < 0 or t > 64) then
    error("lsys.environment.collision: threads must be an integer in [0, 64]", 2)
  end
  return setmetatable({ radius = r, threads = t or 0 }, Collision)
end

function Collision.__tostring () return "lsys.environment.collision" end

-- core.space's message about point k as one about its query.
local function blame (msg)
  msg = tostring(msg)
  local k = msg:match("^core%.space: points%[(%d+)%] must be a finite number")
  if k then return format("query %d: its position is not finite", (tonumber(k) + 2) // 3) end
  return (msg:gsub("^core%.space: point (%d+)", "query %1: its position"))
end

--- Answers the queries of a pass: 1 for a query no other reaches, else 0.
function Collision:answer (queries)
  local pts, groups, vigour = {}, {}, {}
  local ids, nid = {}, 0               -- the groups' values, numbered (the core's integers)
  for i, q in ipairs(queries) do
    local p, params = q.position, q.params
    pts[3 * i - 2], pts[3 * i - 1], pts[3 * i] = p[1], p[2], p[3]
    vigour[i] = params[1] or 0
    local g = params[2] or 0
    local id
    if g ~= g then                      -- NaN equals nothing, itself neither
      nid = nid + 1
      id = nid
    else
      id = ids[g]
      if id == nil then nid = nid + 1; id = nid; ids[g] = id end
    end
    groups[i] = id
  end
  local ok, space = pcall(core.space, pts, { radius = self.radius, groups = groups,
                                             vigour = vigour, threads = self.threads })
  if not ok then error(blame(space), 0) end
  local _ <close> = space
  return space:free()
end

return M
