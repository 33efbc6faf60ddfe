--- A collision environment: which queries another one reaches (the collision test of
-- Honda 1981 that vlab's honda81 program answers, built in; docs/open.md §2).
--
-- `lsys.environment.collision { radius = r }` answers each ?E(v [, g]) with 1 when no
-- other query of the same group g (0 without a second parameter) and of a vigour at least
-- v stands within distance r of it, else 0: of two sensors that would meet, the weaker
-- stops, and two of one vigour both stop, as honda81 answers. The queries are hashed into
-- cells of size r, so a pass is linear in the number of queries.
-- @module lsys.environment.collision
local type, ipairs, error, setmetatable, math = type, ipairs, error, setmetatable, math
local floor = math.floor
local _ENV = nil

local M = {}

local Collision = {}
Collision.__index = Collision

--- The environment; opts: radius (> 0, world units).
function M.collision (opts)
  local r = type(opts) == "table" and opts.radius
  if type(r) ~= "number" or not (r > 0 and r < math.huge) then
    error("lsys.environment.collision: radius must be a number > 0", 2)
  end
  return setmetatable({ radius = r }, Collision)
end

function Collision.__tostring () return "lsys.environment.collision" end

-- The cell of a point: integers for each coordinate, packed into one key.
local function cell (p, r)
  return floor(p[1] / r), floor(p[2] / r), floor(p[3] / r)
end

local function key (x, y, z) return x * 73856093 ~ y * 19349663 ~ z * 83492791 end

function Collision:answer (queries)
  local r = self.radius
  local r2 = r * r
  local cells = {}
  for i, q in ipairs(queries) do
    local k = key(cell(q.position, r))
    local c = cells[k]
    if c == nil then c = {}; cells[k] = c end
    c[#c + 1] = i
  end
  local answers = {}
  for i, q in ipairs(queries) do
    local p, v, g = q.position, q.params[1] or 0, q.params[2] or 0
    local cx, cy, cz = cell(p, r)
    local free = 1
    for dx = -1, 1 do
      for dy = -1, 1 do
        for dz = -1, 1 do
          for _, j in ipairs(cells[key(cx + dx, cy + dy, cz + dz)] or {}) do
            local o = queries[j]
            if j ~= i and (o.params[2] or 0) == g and v <= (o.params[1] or 0) then
              local ex, ey, ez = p[1] - o.position[1], p[2] - o.position[2],
                                 p[3] - o.position[3]
              if ex * ex + ey * ey + ez * ez <= r2 then free = 0 end
            end
          end
        end
      end
    end
    answers[i] = free
  end
  return answers
end

return M
