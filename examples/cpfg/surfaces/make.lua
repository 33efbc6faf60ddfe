-- Writes the predefined surfaces of the cpfg examples in the cpfg surface format
-- (docs/surfaces.md): petal.s and calyx.s for fig22.lua (apple blossom), leaf.s for
-- fig31.lua (textured surfaces).
-- Run from anywhere: lua5.4 examples/cpfg/surfaces/make.lua [OUTDIR] (default: this file's
-- directory; tests/examples_spec.lua writes to a temporary one and compares).
-- File coordinates: x across the organ (turtle left), y along the turtle heading (up the
-- flower stalk), z along the turtle's up vector (outward from the flower's axis).
local dir = ... or (arg and arg[0] or ""):match("^(.*)/[^/]*$") or "."

local function fmt (p) return string.format("%.4f %.4f %.4f", p[1], p[2], p[3]) end

-- One Bézier patch: rows from base (row 0) to tip (row 3); each row is a list of
-- {a, b, lift}: a along the organ's length, b across it, lift off the organ's midplane.
-- 'along' is the organ's direction and 'lift' the direction of lifting, both as (y, z).
local function patch (rows, along, lift)
  local out = {}
  for r = 1, 4 do
    local line = {}
    for c = 1, 4 do
      local a, b, l = rows[r][c][1], rows[r][c][2], rows[r][c][3] or 0
      line[c] = fmt { b, a * along[1] + l * lift[1], a * along[2] + l * lift[2] }
    end
    out[r] = table.concat(line, "  ")
  end
  return out
end

local function write (name, comment, rows, along, lift)
  local pts = patch(rows, along, lift)
  local f = assert(io.open(dir .. "/" .. name, "w"))
  f:write("-1 1  -1 1  -1 1\n",
          "PRECISION S: 8 T: 8\n",
          "CONTACT POINT  X: 0.00 Y: 0.00 Z: 0.00\n",
          "END POINT  X: 0.00 Y: 0.00 Z: 0.00\n",
          "HEADING  X: 0.00 Y: 1.00 Z: 0.00\n",
          "UP  X: 0.00 Y: 0.00 Z: 1.00\n",
          "SIZE: 1.000000\n",
          comment, "\n",
          "TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00\n",
          "AL: ~ A: ~ AR: ~\n", "L: ~ R: ~\n", "BL: ~ B: ~ BR: ~\n",
          table.concat(pts, "\n"), "\n")
  f:close()
end

-- Petal: a narrow claw at the base, broad and rounded at the tip, cupped (the edges are
-- lifted toward the flower's axis); it leaves the stalk 25° above the horizontal.
local up25 = { math.sin(math.rad(25)), math.cos(math.rad(25)) }       -- (y, z)
local lift = { math.cos(math.rad(25)), -math.sin(math.rad(25)) }      -- normal, inward
write("petal.s", "petal", {
  { { 0, -0.06 }, { 0, -0.02 }, { 0, 0.02 }, { 0, 0.06 } },
  { { 0.30, -0.36, 0.10 }, { 0.32, -0.14 }, { 0.32, 0.14 }, { 0.30, 0.36, 0.10 } },
  { { 0.88, -0.56, 0.16 }, { 1.00, -0.20, 0.02 }, { 1.00, 0.20, 0.02 }, { 0.88, 0.56, 0.16 } },
  { { 1.00, -0.18, 0.08 }, { 1.12, -0.08 }, { 1.12, 0.08 }, { 1.00, 0.18, 0.08 } },
}, up25, lift)

-- Calyx leaf (sepal): a narrow pointed triangle bent 20° below the horizontal.
local down20 = { -math.sin(math.rad(20)), math.cos(math.rad(20)) }
local lift20 = { math.cos(math.rad(20)), math.sin(math.rad(20)) }
write("calyx.s", "sepal", {
  { { 0, -0.16 }, { 0, -0.05 }, { 0, 0.05 }, { 0, 0.16 } },
  { { 0.30, -0.20, 0.03 }, { 0.32, -0.07 }, { 0.32, 0.07 }, { 0.30, 0.20, 0.03 } },
  { { 0.70, -0.10, 0.02 }, { 0.72, -0.03 }, { 0.72, 0.03 }, { 0.70, 0.10, 0.02 } },
  { { 1, 0 }, { 1, 0 }, { 1, 0 }, { 1, 0 } },
}, down20, lift20)

-- Leaf: a flat, slightly arched blade of two patches, base and tip, sharing an edge (row 3
-- of the base is row 0 of the tip), in the plane of x and y (its normal along file z).
local function row (y, w, z)
  local out = {}
  for c, k in ipairs { -1, -1 / 3, 1 / 3, 1 } do
    out[c] = fmt { k * w, y, z * (1 - k * k * 0.3) }
  end
  return table.concat(out, "  ")
end
local f = assert(io.open(dir .. "/leaf.s", "w"))
f:write("-0.5 0.5  0 1  0 0.1\n",
        "PRECISION S: 8 T: 8\n",
        "CONTACT POINT  X: 0.00 Y: 0.00 Z: 0.00\n",
        "END POINT  X: 0.00 Y: 0.00 Z: 0.00\n",
        "HEADING  X: 0.00 Y: 1.00 Z: 0.00\n",
        "UP  X: 0.00 Y: 0.00 Z: 1.00\n",
        "SIZE: 1.000000\n",
        "base\n",
        "TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00\n",
        "AL: ~ A: ~ AR: ~\n", "L: ~ R: ~\n", "BL: ~ B: tip BR: ~\n",
        row(0, 0.03, 0), "\n", row(0.12, 0.22, 0.03), "\n", row(0.30, 0.38, 0.06), "\n",
        row(0.45, 0.38, 0.08), "\n",
        "tip\n",
        "TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00\n",
        "AL: ~ A: base AR: ~\n", "L: ~ R: ~\n", "BL: ~ B: ~ BR: ~\n",
        row(0.45, 0.38, 0.08), "\n", row(0.60, 0.38, 0.10), "\n", row(0.85, 0.22, 0.06), "\n",
        row(1.0, 0.0, 0.0), "\n")
f:close()
