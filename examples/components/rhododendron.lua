--- The rhododendron of Lintermann and Deussen 1999 (section "Rhododendron", fig. 5): a
-- bush of 20 twigs on a Phiball. Each twig is a Tree whose branch links carry flag lists:
-- the small twigs grow only at iterations 2 and 13, the leaves everywhere else (section
-- "Rhododendron": "one list forces the creation of components without the numbers 2 and 13,
-- and the other list has the complementary set"). Every twig, small or main, ends in a top
-- (fig. 5b): a Phiball of leaves around the blossom and a Phiball of flowers, each flower a
-- Hydra of five petals. The container is a Revo, as the article made its own.
--
--   build/bin/lsys render examples/components/rhododendron.lua -o rhododendron.png
local C = require "lsys".components

-- the leaf (fig. 5a): long, elliptic, dark green, a little folded
local leaf = C.leaf { name = "leaf", shape = "elliptic", length = 1.5, width = 0.5,
                      lateral = 0.2, longitudinal = 0.15, color = 8 }

-- a flower: a star of five pink petals opening from its centre
local petal = C.leaf { name = "petal", shape = "obovate", length = 0.4, width = 0.3,
                       lateral = 0.25, longitudinal = -0.3, color = 6 }
local flower = C.hydra { name = "flower", n = 5, angle = 55 }
flower:child(petal)

-- the top of a twig (fig. 5b): the truss of flowers on a Phiball, leaves around it on another
local truss = C.phiball { name = "truss", n = 8, radius = 0.3, open = 0, close = 70 }
truss:child(flower)
local collar = C.phiball { name = "collar", n = 8, radius = 0.15, open = 80, close = 120 }
collar:child(leaf)
local top = C.simple { name = "top", primitive = "none" }
top:child(truss)
top:child(collar)

-- a small twig: a short Tree with a few leaves along it and a top
local small = C.tree { name = "small", length = 0.9, radius = 0.035, tip = 0.6, n = 4,
                       first = 0.3, last = 0.85, angle = 55, color = 1 }
small:branch(leaf)
small:child(top)

-- a main twig (fig. 5c): 16 places along it; small twigs at 2 and 13, leaves at the others
local twig = C.tree { name = "twig", length = 3, radius = 0.07, tip = 0.5, n = 16,
                      first = 0.15, last = 0.95, angle = { 60, 40 }, phototropism = 0.15,
                      gnarl = 4, color = 1 }
twig:branch(small, { only = { 2, 13 } })
twig:branch(leaf, { except = { 2, 13 } })
twig:child(top)

-- the bush (fig. 5d): 20 twigs from the centre on a Phiball, the outer ones a bit larger
local bush = C.phiball { name = "bush", n = 20, radius = 0.3, open = 0, close = 80,
                         child_size = { 0.8, 1.05 } }
bush:child(twig)

-- the container: a pot turned as a surface of revolution
local pot = C.revo { name = "pot", profile = { { 0.9, 0 }, { 1.25, 1.2 }, { 1.35, 1.3 },
                                              { 1.2, 1.32 } }, color = 11 }
pot:child(bush)

return C.model(pot, {
  name = "rhododendron", seed = 1,
  view = { viewpoint = { 0, 4.6, 12 }, target = { 0, 2.2, 0 }, up = { 0, 1, 0 },
           projection = "perspective", fov = 40, background = { 0.93, 0.96, 1 } },
})
