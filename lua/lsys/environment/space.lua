--- A crowding environment: how much company each query has within a radius (core.space, a
-- hash of cells in C; docs/open.md §2).
--
-- `lsys.environment.space { radius = r, answer = "count" | "density" | "nearest" | "free",
-- scene = false, offset =, threads = }` answers each ?E with what is within distance r of
-- its position, among the other queries of the pass and, with `scene = true`, the plant as
-- the turtle draws the string (`info.scene`: each line segment's end and each triangle's
-- centroid):
--
--   count    how many (the default);
--   density  the sum over them of the biweight kernel (1 - d^2 / r^2)^2 (d their distance):
--            1 for one at the query's place, falling smoothly to 0 at the radius;
--   nearest  the distance to the nearest, or r when there is none within r;
--   free     1 when there is none within r, else 0.
--
-- The scene's points nearer a query than `offset` (default r / 1000) are left out: the end
-- of the segment the ?E stands on. A query never counts itself; two queries at one place
-- count each other.
-- @module lsys.environment.space
local core = require "lsys.core"

local type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Space = {}
Space.__index = Space

local OPTIONS = { radius = true, answer = true, scene = true, offset = true, threads = true }
local ANSWERS = { count = "count", density = "density", nearest = "nearest", free = "count" }

local function bad (msg) error("lsys.environment.space: " .. msg, 3) end

-- core.space's message about point k as one about its query.
local function blame (msg)
  msg = tostring(msg)
  local k = msg:match("^core%.space: points%[(%d+)%] must be a finite number")
  if k then return format("query %d: its position is not finite", (tonumber(k) + 2) // 3) end
  return (msg:gsub("^core%.space: point (%d+)", "query %1: its position"))
end

--- The environment (see the module's header for the options).
function M.space (opts)
  if type(opts) ~= "table" then bad("an options table expected") end
  for k in pairs(opts) do
    if not OPTIONS[k] then bad(format("unknown option '%s'", tostring(k))) end
  end
  local r = opts.radius
  if type(r) ~= "number" or not (r > 0 and r < math.huge) then
    bad("radius must be a number > 0")
  end
  local answer = opts.answer or "count"
  if ANSWERS[answer] == nil then
    bad("answer must be \"count\", \"density\", \"nearest\" or \"free\"")
  end
  if opts.scene ~= nil and type(opts.scene) ~= "boolean" then bad("scene must be a boolean") end
  local off = opts.offset or r / 1000
  if type(off) ~= "number" or not (off >= 0 and off < math.huge) then
    bad("offset must be a number >= 0")
  end
  local t = opts.threads
  if t ~= nil and (math.type(t) ~= "integer" or t < 0 or t > 64) then
    bad("threads must be an integer in [0, 64]")
  end
  return setmetatable({ radius = r, what = answer, scene = opts.scene or false,
                        offset = off, threads = t or 0 }, Space)
end

function Space.__tostring () return "lsys.environment.space" end

--- Answers the queries of a pass (see the module's header).
function Space:answer (queries, info)
  local pts = {}
  for i, q in ipairs(queries) do
    local p = q.position
    pts[3 * i - 2], pts[3 * i - 1], pts[3 * i] = p[1], p[2], p[3]
  end
  local ok, space = pcall(core.space, pts, { radius = self.radius, threads = self.threads,
                                             scene = self.scene and info.scene or nil })
  if not ok then error(blame(space), 0) end
  local _ <close> = space
  local kind = ANSWERS[self.what]
  local values = space[kind](space, nil, { offset = self.offset })
  if self.what == "free" then
    for i = 1, #values do values[i] = values[i] == 0 and 1 or 0 end
  elseif self.what == "nearest" then
    local r = self.radius
    for i = 1, #values do if values[i] > r then values[i] = r end end
  end
  return values
end

return M
