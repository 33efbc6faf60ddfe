-- The philodendron climbing a stick of Lintermann and Deussen 1999, fig. 9b (section
-- "Tropisms": "a cylindrical tropism for modeling a philodendron around a stick"). A World
-- component at the root guides the stems below it onto a helix of radius 0.3 around the
-- stick's axis (the y axis), climbing at a pitch of 30 degrees, turning them by at most 0.3
-- radians a segment: the stem's frames are on the radius from its 6th on. Under the World:
-- a pot (a Revo), the stick (a Simple cylinder) and the climbing stem, a Tree whose
-- branches are petioles (Horns) carrying heart-shaped leaves; each petiole hangs on a World
-- of its own with `cylinder = false`, so the stick does not pull the petioles in.
--
--   1 world, 1 pot, 1 stick, 1 stem, 20 free (Worlds), 20 petioles, 20 leaves.
local lsys = require "lsys"
local C = lsys.components

local POT = 0.8              -- height of the pot; the stick and the stem start on its soil

local function philodendron (opts)
  opts = opts or {}
  local world = C.world {
    name = "world",
    cylinder = { axis = { 0, 1, 0 }, point = { 0, 0, 0 }, radius = 0.3, pitch = 30,
                 strength = 0.3 },
  }
  local pot = C.revo { name = "pot", color = 4,
                       profile = { { 0.45, 0 }, { 0.5, 0.05 }, { 0.62, POT - 0.08 },
                                   { 0.68, POT - 0.04 }, { 0.68, POT } } }
  local soil = C.simple { name = "soil", primitive = "disc", size = { 1.24, 0, 1.24 },
                          translate = { 0, POT - 0.03, 0 }, color = 5 }
  local stick = C.simple { name = "stick", primitive = "cylinder", size = { 0.12, 6.2, 0.12 },
                           translate = { 0, POT - 0.1, 0 }, color = 1 }
  -- heart-shaped leaves, a little cupped and bent back at the tip, on long petioles that
  -- leave the stem on alternate sides
  local leaf = C.leaf { name = "leaf", shape = "cordate", width = 0.8, lateral = 0.15,
                        longitudinal = 0.25, color = 2,
                        length = { 0.55, 0.95, f = function (v, ctx)
                          return v * (0.9 + 0.2 * ctx.random())
                        end } }
  local petiole = C.horn { name = "petiole", length = 0.45, radius = 0.015, tip = 0.7,
                           segments = 4, curvature = -40, color = 3 }
  petiole:child(leaf)
  local stem = C.tree { name = "stem", length = 8.5, radius = 0.035, tip = 0.6,
                        segments = 96, n = opts.leaves or 20, first = 0.12, last = 0.97,
                        angle = { 55, 40 }, divergence = 180, translate = { 0.3, POT - 0.05, 0 },
                        color = 3 }
  -- the petioles leave the stick's pull: a World under the stem switches the cylinder off
  local free = C.world { name = "free", cylinder = false }
  free:child(petiole)
  stem:branch(free)
  world:child(pot)
  world:child(soil)
  world:child(stick)
  world:child(stem)
  return world
end

local VIEW = {
  palette = { { 0.66, 0.50, 0.32 }, { 0.18, 0.45, 0.14 }, { 0.40, 0.58, 0.20 },
              { 0.72, 0.36, 0.22 }, { 0.24, 0.17, 0.11 } },
  background = { 0.92, 0.93, 0.90 },
  viewpoint = { 5, 5, 12 }, target = { 0, 3.4, 0 }, projection = "perspective", fov = 32,
}

local M = C.model(philodendron(), { seed = 1, view = VIEW, name = "philodendron" })
M.graph = philodendron
M.VIEW = VIEW
return M
