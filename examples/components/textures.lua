-- Writes the texture images of the component examples (small PNGs, committed next to this
-- file), computed from a fixed seed so they come out the same each time:
--   chestnut_leaf.png  64x128 a horse-chestnut leaflet: dark green, a pale midrib along the
--                      image (y) and some twenty straight side veins running to the margin
--                      (chestnut.lua; the Leaf's texture, laid over the leaflet's bounds)
--   bark.png           64x64 grey-brown bark with shallow vertical plates; it tiles in
--                      both directions (the stems of chestnut.lua, willow.lua, pine.lua)
-- Run with the lsys module on the path: `build/bin/lsys examples/components/textures.lua`;
-- an argument names another directory to write to.
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."  -- this file's folder
local dir = ... or here
local T = dofile(here .. "/../texture.lua")
local floor, max, min, abs = math.floor, math.max, math.min, math.abs
local rand = T.generator(20240601)
local function write (name, w, h, f) T.write(dir .. "/" .. name, w, h, f, true) end
local function noise (nx, ny) return T.noise(rand, nx, ny) end

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
