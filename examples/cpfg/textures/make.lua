-- Writes the texture images of the cpfg examples (small PNGs, committed next to this file):
--   chessboard.png  128x128, 8x8 squares, red and white (fig31.lua)
--   bark.png        128x128 bark with vertical fissures; it tiles in both directions, as
--                   §5.2 of the guide asks of a texture repeated along a stem (fig33.lua)
--   venation.png    128x128 a leaf blade with a midrib and side veins (fig34.lua)
--   aloe.png        64x128 dark green with broken pale bands across, the leaf pattern of
--                   Aloe variegata (fig15.lua); it tiles in both directions
-- Run with the lsys module on the path, e.g. `build/bin/lsys examples/cpfg/textures/make.lua`;
-- an argument names another directory to write to (tests/examples_spec.lua does that).
-- Everything is computed from a fixed seed, so the files come out the same each time.
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."  -- this file's folder
local dir = ... or here
local T = dofile(here .. "/../../texture.lua")
local floor = math.floor
local rand = T.generator(12345)
local function write (name, w, h, f) T.write(dir .. "/" .. name, w, h, f, false) end
local function noise (nx, ny) return T.noise(rand, nx, ny) end

write("chessboard.png", 128, 128, function (x, y)
  if (floor(x * 8) + floor(y * 8)) % 2 == 0 then return 0.85, 0.12, 0.10 end
  return 0.97, 0.97, 0.94
end)

-- Bark: ridges across u (around the stem) wavering along v; dark fissures between them.
local n1, n2, n3 = noise(8, 4), noise(16, 16), noise(32, 32)
write("bark.png", 128, 128, function (x, y)
  local u = x * 6 + 0.6 * n1(x, y) + 0.15 * n2(x, y)     -- 6 ridges around
  local ridge = math.abs(math.sin(math.pi * u))           -- 0 in a fissure, 1 on a ridge
  local t = ridge ^ 0.35 * (0.75 + 0.25 * n3(x, y))
  return 0.16 + 0.42 * t, 0.11 + 0.30 * t, 0.07 + 0.18 * t
end)

-- Venation: x across the blade, y along it (the midrib at x = 0.5); side veins leave the
-- midrib at 45° every 1/7 of the length.
write("venation.png", 128, 128, function (x, y)
  local d = math.abs(x - 0.5)
  local vein = math.max(0, 1 - d / 0.018)                 -- the midrib
  local s = (y - d * 0.9) * 7                             -- side veins, slanting up
  local k = math.abs(s - floor(s + 0.5))
  vein = math.max(vein, math.max(0, 1 - k / 0.06) * (1 - d * 1.6))
  local shade = 0.85 + 0.15 * n2(x, y)
  return (0.22 + 0.45 * vein) * shade, (0.48 + 0.35 * vein) * shade, (0.16 + 0.25 * vein) * shade
end)

-- Aloe: v (along the leaf) crosses four pale bands, broken up by noise around u.
local a1, a2 = noise(8, 8), noise(16, 32)
write("aloe.png", 64, 128, function (x, y)
  local band = math.sin(2 * math.pi * (4 * y + 0.35 * a1(x, y)))
  local pale = math.max(0, band - 0.35 + 0.5 * (a2(x, y) - 0.5)) / 0.65
  pale = math.min(1, pale * 1.6)
  local g = 0.85 + 0.15 * a2(x, y)
  return (0.16 + 0.62 * pale) * g, (0.30 + 0.55 * pale) * g, (0.14 + 0.58 * pale) * g
end)
