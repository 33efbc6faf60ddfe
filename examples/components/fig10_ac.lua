-- The pine of Lintermann and Deussen 1999, fig. 10, without and with the whole tree
-- deformed (section "Free-form deformations": "(a) undeformed model; (b) deformation of
-- the twigs (the needles remain unchanged); and (c) deformation of the whole tree", where
-- "the needles on the right appear too big—a result of the strong deformation"). The graph
-- is pine.lua's (which is fig. 10b): `deform = "none"` leaves its Hyperpatch out, `deform =
-- "all"` the FFDs that keep the needles out of it.
--
--   both: 1 trunk, 14 branches, 112 twigs, 4,480 pairs, 8,960 needles (and c: 1 bend).
--
--   build/bin/lsys render examples/components/fig10_ac.lua --name c -o fig10c.png
local lsys = require "lsys"
local C = lsys.components

local pine = dofile(lsys.here() .. "/pine.lua")

return {
  a = C.model(pine.graph { deform = "none" }, { seed = 1, view = pine.VIEW, name = "fig10a" }),
  c = C.model(pine.graph { deform = "all" }, { seed = 1, view = pine.VIEW, name = "fig10c" }),
}
