-- Procedural texture images for the examples' scripts (examples/cpfg/textures/make.lua,
-- examples/components/textures.lua): an image from a function, a seeded generator that
-- gives the same numbers on every machine, and periodic value noise.
--   local T = dofile(EXAMPLES .. "/texture.lua")
--   T.write(path, w, h, f [, centre])   f(x, y) -> r, g, b in 0..1, x and y in [0, 1);
--                                       centre: sample pixel centres ((i + 0.5) / w)
--   local rand = T.generator(seed)      -> numbers in [0, 1)
--   local n = T.noise(rand, nx, ny)     -> n(x, y) in [0, 1), wraps in x and y
local core = require "lsys.core"

local char, floor, max, min = string.char, math.floor, math.max, math.min

local M = {}

local function byte (x) return char(max(0, min(255, floor(x * 255 + 0.5)))) end

function M.write (path, w, h, f, centre)
  local px = {}
  local o = centre and 0.5 or 0
  for j = 0, h - 1 do
    for i = 0, w - 1 do
      local r, g, b = f((i + o) / w, (j + o) / h)
      px[#px + 1] = byte(r) .. byte(g) .. byte(b) .. "\255"
    end
  end
  core.png_write(path, table.concat(px), w, h, false)
end

-- a small linear congruential generator
function M.generator (seed)
  return function ()
    seed = (seed * 1103515245 + 12345) % 2147483648
    return seed / 2147483648
  end
end

-- a grid of nx by ny random values, smoothly interpolated, wrapped
function M.noise (rand, nx, ny)
  local g = {}
  for j = 0, ny - 1 do
    g[j] = {}
    for i = 0, nx - 1 do g[j][i] = rand() end
  end
  return function (x, y)
    local fx, fy = x * nx, y * ny
    local i0, j0 = floor(fx), floor(fy)
    local tx, ty = fx - i0, fy - j0
    tx, ty = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)
    local i1, j1 = (i0 + 1) % nx, (j0 + 1) % ny
    i0, j0 = i0 % nx, j0 % ny
    local a = g[j0][i0] + (g[j0][i1] - g[j0][i0]) * tx
    local b = g[j1][i0] + (g[j1][i1] - g[j1][i0]) * tx
    return a + (b - a) * ty
  end
end

return M
