-- Helpers of the sketch examples (not a model file): the files next to them, organs as
-- surfaces that face up, the look of the pictures, and the composition of two sketched
-- plants into one L-system (Anastacio et al. 2009, §7.2). The figures' files load it with
-- `dofile(lsys.here() .. "/common.lua")`.
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

-- The names a sketch's template uses (docs/sketch.md, "Templates"): its modules and the
-- functions and constants of its env. Other words of the rules (x, d, i, t, h, F, @R) stay.
local MODULES = { A = true, S = true, B = true, C = true, L = true, R = true, Organ = true }

-- The rule text with the modules and env names of `names` suffixed by `suffix`. A word
-- after '@' or '~' is a command or a surface, not a module: it stays.
local function rename (text, names, suffix)
  return (text:gsub("()([%a_][%w_]*)", function (at, word)
    local before = at > 1 and text:sub(at - 1, at - 1) or ""
    if names[word] and before ~= "@" and before ~= "~" then return word .. suffix end
  end))
end

--- One L-system from two plants drawn on one stem, made by sk:model with surface organs
-- (§7.2: "combining the grammars of two parameterized L-systems"): the rules of `b` are
-- renamed (modules and functions take the suffix 2, its organ surface is ~Q), its stem
-- pieces move without drawing (f instead of F: the distribution of the organs edited in
-- the rules), and its apex starts in a branch before `a`'s, so both place their organs
-- along the same stem in one derivation. opts: name, view (more view options).
function M.compose (a, b, opts)
  opts = opts or {}
  local oa, ob = a.sketch.description.options, b.sketch.description.options
  local names = {}
  for k in pairs(MODULES) do names[k] = true end
  for k in pairs(ob.env) do names[k] = true end
  local productions, homomorphism, env = {}, {}, {}
  for _, l in ipairs(oa.productions) do productions[#productions + 1] = l end
  for _, l in ipairs(oa.homomorphism) do homomorphism[#homomorphism + 1] = l end
  for k, v in pairs(oa.env) do env[k] = v end
  for _, l in ipairs(ob.productions) do
    l = rename(l, names, "2")
    l = l:gsub("F%(d%)", "f(d)")
    productions[#productions + 1] = l
  end
  for _, l in ipairs(ob.homomorphism) do
    homomorphism[#homomorphism + 1] = rename(l, names, "2"):gsub("~P%(", "~Q(")
  end
  for k, v in pairs(ob.env) do env[k .. "2"] = v end
  local view = {}
  for k, v in pairs(oa.view) do view[k] = v end
  view.surfaces = { P = oa.view.surfaces.P, Q = ob.view.surfaces.P }
  for k, v in pairs(opts.view or {}) do view[k] = v end
  local axiom = "[" .. rename(ob.axiom, names, "2") .. "] " .. oa.axiom
  return lsys.lsystem {
    axiom = axiom, productions = productions, homomorphism = homomorphism, env = env,
    modules = "Organ Organ2 A2 S2 B2 C2 L2 R2", steps = math.max(oa.steps, ob.steps),
    view = view, name = opts.name,
  }
end

return M
