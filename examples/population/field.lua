-- A meadow of 10,000 plants of 20 kinds (lsys.population): five small species, four seeds each.
-- Grass tufts, daisies, lavender, poppies and clover-like shrubs, placed on a jittered grid in
-- patches, each turned and scaled its own way, on one ground tile. Plants of the same model
-- and seed share one prototype, so the scene holds 21 small meshes and 10,001 transforms;
-- it renders headless and exports as glb with EXT_mesh_gpu_instancing:
--
--   build/bin/lsys render examples/population/field.lua -o field.png
--   build/bin/lsys export examples/population/field.lua -o field.glb
--
-- From Lua, `dofile "examples/population/field.lua"` returns the Scene.
local lsys = require "lsys"

local N = 10000          -- plants
local SIDE = 100         -- plants on a side of the grid
local STEP = 0.32        -- grid spacing (a plant is about 0.4 to 0.9 high)

-- Palettes: stem, leaf, flower, flower centre.
local GREEN, LEAF = "#4d7a2a", "#3f8a2e"

local grass = lsys.lsystem {
  name = "grass", axiom = "T(14)", steps = 14,
  productions = "T(n) : n > 0 --> [ /(n * 137.5 + ran(50)) &(6 + ran(30)) ;(1 + floor(ran(3))) "
    .. "B(0.3 + ran(0.35)) ] T(n - 1)",
  homomorphism = "B(l) --> #(0.022) F(l * 0.4) #(0.018) &(12) F(l * 0.35) #(0.011) &(18) "
    .. "F(l * 0.25) #(0.001)",
  view = { line_style = "polygon", palette = { "#5e8f2f", "#7aa83a", "#4a7a26" } },
}

local petal = "{ . -(14) g(%s) . +(28) g(%s) . +(152) g(%s) . }"

local daisy = lsys.lsystem {
  name = "daisy", axiom = ";(1) #(0.018) S", steps = 1,
  productions = "S --> F(0.2 + ran(0.12)) [ L ] /(137) F(0.15 + ran(0.1)) [ L ] /(137) "
    .. "&(ran(14)) F(0.12) H",
  homomorphism = {
    "L --> [ ;(2) &(55 + ran(15)) " .. petal:format(0.09, 0.09, 0.09) .. " ]",
    "H --> [ ;(4) f(0.012) @O(0.075) ] "
      .. ("[ ;(3) &(80) " .. petal:format(0.1, 0.1, 0.1) .. " ] /(30) "):rep(12),
  },
  view = { line_style = "cylinder", contour_sides = 4,
           palette = { GREEN, LEAF, "#f7f4ea", "#f2c21b" } },
}

local lavender = lsys.lsystem {
  name = "lavender", axiom = ";(1) #(0.012) T(5)", steps = 5,
  productions = "T(n) : n > 0 --> [ /(n * 72 + ran(30)) &(4 + ran(16)) F(0.25 + ran(0.15)) "
    .. "K(7) ] T(n - 1)",
  homomorphism = "K(n) --> [ ;(3) " .. ("[ @O(0.036) ] f(0.035) "):rep(7) .. "]",
  view = { line_style = "cylinder", contour_sides = 4, palette = { "#6f8a4a", LEAF, "#9b5fe0" } },
}

local poppy = lsys.lsystem {
  name = "poppy", axiom = ";(1) #(0.014) S", steps = 1,
  productions = "S --> [ L ] F(0.22 + ran(0.12)) /(90) [ L ] &(ran(18)) F(0.2 + ran(0.12)) "
    .. "^(ran(18)) F(0.1) H",
  homomorphism = {
    "L --> [ ;(2) &(60) " .. petal:format(0.1, 0.1, 0.1) .. " ]",
    "H --> [ ;(4) @O(0.03) ] " .. ("[ ;(3) &(35) " .. petal:format(0.08, 0.13, 0.13) .. " ] /(90) ")
      :rep(4),
  },
  view = { line_style = "cylinder", contour_sides = 4,
           palette = { GREEN, LEAF, "#d7261e", "#2a2418" } },
}

local clover = lsys.lsystem {
  name = "clover", axiom = ";(1) #(0.012) A", steps = 3,
  productions = {
    "A --> F(0.1 + ran(0.06)) [ +(35 + ran(20)) A L ] [ -(35 + ran(20)) A ] /(120) A : 0.5",
    "A --> F(0.12) [ &(30 + ran(25)) A L ] /(137.5) L : 0.5",
  },
  homomorphism = "L --> [ ;(2) &(70) " .. (("[ " .. petal:format(0.07, 0.07, 0.07) .. " ] /(120) ")
    :rep(3)) .. "]",
  view = { line_style = "cylinder", contour_sides = 4, palette = { "#5c7d33", "#2f7a2a" } },
}

-- One ground tile, 1 x 1 in the plane y = 0 (the turtle starts heading up, +y): scaled below.
local ground = lsys.lsystem {
  name = "ground", axiom = ";(1) ^(90) { . f(1) . -(90) f(1) . -(90) f(1) . }",
  view = { palette = { "#6d6a3c" } },
}

local SPECIES = { grass, daisy, lavender, poppy, clover }

-- A small generator of our own (xorshift), so the field is the same everywhere.
local state = 2463534242
local function rand ()
  state = state ~ (state << 13) & 0xffffffff
  state = state ~ (state >> 17)
  state = state ~ (state << 5) & 0xffffffff
  return state / 4294967296
end

-- Patches: a few smooth waves decide which species grows where.
local function species (x, z)
  local f = math.sin(x * 0.31) + math.sin(z * 0.27 + 1.3) + math.sin((x + z) * 0.19 + 0.4)
  local g = math.sin(x * 0.17 - 2) * math.cos(z * 0.23 + 0.7)
  local r = rand()
  if f > 1.35 and r < 0.55 then return 2 end            -- daisy patches
  if f < -1.55 and r < 0.6 then return 3 end            -- lavender
  if g > 0.55 and r < 0.35 then return 4 end            -- poppies
  if r < 0.06 then return 5 end                         -- clover here and there
  return 1                                              -- grass
end

local plants = {}
for i = 1, N do
  local gx, gz = (i - 1) % SIDE, (i - 1) // SIDE
  local x = gx * STEP + (rand() - 0.5) * STEP * 0.9
  local z = gz * STEP + (rand() - 0.5) * STEP * 0.9
  local k = species(x, z)
  local s = 0.8 + 0.4 * rand()
  plants[i] = { model = SPECIES[k], seed = 1 + math.floor(rand() * 4), at = { x, 0, z },
                rotate = rand() * 360, scale = k == 1 and { s, 0.8 + 0.5 * rand(), s } or s }
end
local size = SIDE * STEP
plants[N + 1] = { model = ground, at = { -0.5, 0, -0.5 }, scale = { size + 1, 1, size + 1 } }

return lsys.population(plants, {
  view = { projection = "perspective", fov = 40, viewpoint = { size * 0.5, 16, size + 7 },
           target = { size * 0.5, 0, size * 0.5 }, background = { 0.78, 0.87, 0.97 },
           light = { 0.3, 0.9, 0.5 } },
})
