-- Helpers of the sketch examples (not a model file): the files next to them, organs as
-- surfaces that face up and the look of the pictures. (Two sketched plants composed into
-- one L-system, §7.2 of Anastacio et al. 2009, are lsys.sketch.compose's.) The figures'
-- files load it with `dofile(lsys.here() .. "/common.lua")`.
local lsys = require "lsys"
local sketch = require "lsys.sketch"
local organ = require "lsys.sketch.organ"
local core = require "lsys.core"

local M = {}
local DIR = lsys.here()
M.dir = DIR

--- The sketch examples/sketch/NAME.json, as lsys.sketch.load reads it.
function M.sketch (name, opts)
  return sketch.load(DIR .. "/" .. name .. ".json", opts)
end

--- The organ of examples/sketch/organ_NAME.json (drawn in three views, §6) as an
-- lsys.Surface rolled a quarter turn about its length. The templates place an organ with
-- the organ's upper side on the turtle's up vector, which after +(angle) still points out
-- of the plane of stem and organ (towards the viewer, for a leaf on the left). A leaf's
-- upper side faces the apex of the stem: with UP along the surface's -x, the surface's
-- +z goes to the turtle's -L (cpfg's placement, docs/surfaces.md: x l + y h + z u with
-- l = h x u, along the turtle's L, H, U; the left vector is H x U), which after +(angle)
-- points up the stem. `flat`: the surface as drawn, not rolled: its upper side on the
-- turtle's up vector, out of the plane of stem and organ, so that a compound leaf's
-- leaflets lie in the plane of its rachis (the frond's plane, fig. 9).
function M.organ (name, flat)
  local org = organ.load(DIR .. "/organ_" .. name .. ".json")
  if flat then return core.surface_parse(org:text(), "organ_" .. name .. ".s") end
  local text, n = org:text():gsub("\nUP  X: 0%.000000 Y: 0%.000000 Z: 1%.000000\n",
                                  "\nUP  X: -1.000000 Y: 0.000000 Z: 0.000000\n")
  assert(n == 1, "organ_" .. name .. ": the surface's UP line is not the expected one")
  return core.surface_parse(text, "organ_" .. name .. ".s")
end

-- Colour indices of the examples' palette.
M.STEM, M.LEAF, M.SCALE, M.PETAL, M.RED, M.BELL, M.DARK, M.PALE =
  1, 2, 3, 4, 5, 6, 7, 8
M.PALETTE = {
  [1] = { 0.36, 0.42, 0.20 },   -- stem
  [2] = { diffuse = { 0.22, 0.50, 0.16 }, specular = { 0.1, 0.1, 0.1 }, shininess = 20 },
  [3] = { diffuse = { 0.52, 0.33, 0.17 }, specular = { 0.05, 0.05, 0.05 }, shininess = 10 },
  [4] = { diffuse = { 0.93, 0.60, 0.72 }, specular = { 0.2, 0.2, 0.2 }, shininess = 30 },
  [5] = { diffuse = { 0.85, 0.12, 0.16 }, specular = { 0.2, 0.2, 0.2 }, shininess = 30 },
  [6] = { diffuse = { 0.72, 0.40, 0.72 }, specular = { 0.2, 0.2, 0.2 }, shininess = 25 },
  [7] = { diffuse = { 0.20, 0.36, 0.18 }, specular = { 0.1, 0.1, 0.1 }, shininess = 20 },
  [8] = { diffuse = { 0.45, 0.62, 0.30 }, specular = { 0.1, 0.1, 0.1 }, shininess = 20 },
}

--- View options of the pictures: white ground, the palette above, looking along `dir`
-- (default a little from above), and `over` merged on top.
function M.view (dir, over)
  local v = { background = { 1, 1, 1 }, palette = M.PALETTE,
              direction = dir or { 0, -0.35, -1 } }
  for k, x in pairs(over or {}) do v[k] = x end
  return v
end

return M
