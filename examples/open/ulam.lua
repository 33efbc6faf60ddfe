-- Ulam's crystal growth as an open L-system (Mech and Prusinkiewicz 1996, §5.1 and fig. 4;
-- vlab's 07-Open/01-ulam-collide runs the same model with the honda81 program): four
-- tentacles grow on a square grid; each apex sends a sensor ahead (f ?E), and the
-- environment answers 0 to a sensor that lands where another sensor of at least its vigour
-- lands too, so two apices never grow into one cell. The environment here is that rule
-- written in Lua (Honda 1981's collision test), over a hash of the sensors' cells.
--
--   lsys render examples/open/ulam.lua -o ulam.png
local lsys = require "lsys"

local VIGOR = 0.5          -- all sensors alike: any other sensor in reach stops one
local RADIUS = 0.01        -- two sensors closer than this collide

-- 1 for a sensor that may grow, 0 for one another sensor of at least its vigour reaches.
local function collisions (queries)
  local cells, key = {}, function (p)
    return string.format("%d,%d,%d", math.floor(p[1] / RADIUS + 0.5),
                         math.floor(p[2] / RADIUS + 0.5), math.floor(p[3] / RADIUS + 0.5))
  end
  for i, q in ipairs(queries) do
    local k = key(q.position)
    cells[k] = cells[k] or {}
    table.insert(cells[k], i)
  end
  local answers = {}
  for i, q in ipairs(queries) do
    local free, p = 1, q.position
    local cx, cy, cz = math.floor(p[1] / RADIUS + 0.5), math.floor(p[2] / RADIUS + 0.5),
                       math.floor(p[3] / RADIUS + 0.5)
    for dx = -1, 1 do for dy = -1, 1 do for dz = -1, 1 do
      for _, j in ipairs(cells[string.format("%d,%d,%d", cx + dx, cy + dy, cz + dz)] or {}) do
        local r = queries[j]
        if j ~= i and q.params[1] <= r.params[1] then
          local ex, ey, ez = p[1] - r.position[1], p[2] - r.position[2], p[3] - r.position[3]
          if ex * ex + ey * ey + ez * ez <= RADIUS * RADIUS then free = 0 end
        end
      end
    end end end
    answers[i] = free
  end
  return answers
end

return lsys.lsystem {
  name = "ulam",
  axiom = "[FA][+FA][-FA][|FA]",
  steps = 16,
  env = { VIGOR = VIGOR },
  productions = [[
    f ?E(x) : x == 1 --> ;F A
    f ?E(x) : x == 0 --> f ?E(VIGOR)
  ]],
  decomposition = "A --> [+f ?E(VIGOR)][-f ?E(VIGOR)]f ?E(VIGOR)",
  environment = collisions,
  view = { angle = 90, line_width = 2, background = { 1, 1, 1 } },
}
