-- Writes the texture images of the component examples (small PNGs, committed next to this
-- file), computed from a fixed seed so they come out the same each time:
--   chestnut_leaf.png  64x128 a horse-chestnut leaflet: dark green, a pale midrib along the
--                      image (y) and some twenty straight side veins running to the margin
--                      (chestnut.lua; the Leaf's texture, laid over the leaflet's bounds)
--   bark.png           64x64 grey-brown bark with shallow vertical plates; it tiles in
--                      both directions (the stems of chestnut.lua, willow.lua, pine.lua)
-- Run with the lsys module on the path: `build/bin/lsys examples/components/textures.lua`;
-- an argument names another directory to write to.
local core = require "lsys.core"

local dir = ... or (arg and arg[0] or ""):match("^(.*)/[^/]*$") or "."
local char, floor, max, min, abs = string.char, math.floor, math.max, math.min, math.abs

local function byte (x) return char(max(0, min(255, floor(x * 255 + 0.5)))) end

-- an image from f(x, y) -> r, g, b in 0..1, x and y in [0, 1)
local function write (name, w, h, f)
  local px = {}
  for j = 0, h - 1 do
    for i = 0, w - 1 do
      local r, g, b = f((i + 0.5) / w, (j + 0.5) / h)
      px[#px + 1] = byte(r) .. byte(g) .. byte(b) .. "\255"
    end
  end
  core.png_write(dir .. "/" .. name, table.concat(px), w, h, false)
end

-- a small linear congruential generator: the same numbers on every machine
local seed = 20240601
local function rand ()
  seed = (seed * 1103515245 + 12345) % 2147483648
  return seed / 2147483648
end

-- periodic value noise: a grid of nx by ny random values, smoothly interpolated, wrapped
local function noise (nx, ny)
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

-- The leaflet: x across (the midrib at x = 0.5), y along from the base. Horse-chestnut
-- leaflets are pinnately veined with many straight, parallel side veins that leave the
-- midrib at about 40 degrees and run to the teeth of the margin.
local n1 = noise(8, 16)
write("chestnut_leaf.png", 64, 128, function (x, y)
  local d = abs(x - 0.5)
  local vein = max(0, 1 - d / 0.03) * (1 - 0.5 * y)        -- the midrib, thinner to the tip
  local s = (y - d * 0.85) * 22                              -- 22 side veins
  local k = abs(s - floor(s + 0.5))
  vein = max(vein, max(0, 1 - k / 0.12) * 0.7 * (1 - d * 1.4))
  local shade = 0.8 + 0.2 * n1(x, y)
  local edge = min(1, 0.75 + d)                              -- a paler margin
  return (0.20 + 0.40 * vein) * shade * edge, (0.42 + 0.40 * vein) * shade * edge,
         (0.12 + 0.22 * vein) * shade * edge
end)

-- Bark: plates across u (around the stem) wavering along v, dark furrows between them.
local b1, b2 = noise(4, 4), noise(16, 16)
write("bark.png", 64, 64, function (x, y)
  local u = x * 5 + 0.8 * b1(x, y)
  local plate = abs(math.sin(math.pi * u)) ^ 0.4
  local t = plate * (0.7 + 0.3 * b2(x, y))
  return 0.25 + 0.35 * t, 0.21 + 0.30 * t, 0.17 + 0.24 * t
end)
