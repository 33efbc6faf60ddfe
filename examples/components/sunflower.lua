--- The sunflower of Lintermann and Deussen 1999 (section "Sunflower", fig. 4): leaves on
-- short stalks multiplied as branches of a Tree (the plant's stalk, fig. 4d); at its top,
-- children of one head: a Phiball of green bracts under the head (fig. 4b), a Phiball of
-- tongue-like yellow petals around its rim and a Phiball of small seeds packed by the
-- golden section on a flat spherical section (fig. 4c; the sidebar "Golden Section
-- Placement on a Sphere").
--
--   build/bin/lsys render examples/components/sunflower.lua -o sunflower.png
local C = require "lsys".components

-- a leaf on a tiny stalk (fig. 4a): a Horn for the petiole, a heart-shaped Leaf at its end
local blade = C.leaf { name = "leaf", shape = "cordate", length = 2.2, width = 1.8,
                       lateral = 0.25, longitudinal = 0.3, color = 2 }
local petiole = C.horn { name = "petiole", length = 0.9, radius = 0.05, tip = 0.7,
                         curvature = -30, color = 3 }
petiole:child(blade)

-- the stalk (fig. 4d): the leaves as its branches, larger below, more upright above
local stalk = C.tree { name = "stalk", length = 9, radius = 0.16, tip = 0.55, n = 11,
                       first = 0.08, last = 0.8, angle = { 65, 40 }, branch_scale = { 1.2, 0.6 },
                       curvature = 10, color = 3 }
stalk:branch(petiole)

-- the head: turned to face the viewer a little; everything below it hangs on its frame
local head = C.simple { name = "head", primitive = "none", rotate = { 35, 0, 0 } }
stalk:child(head)

-- the seeds: 500 small brown spheres on a spherical section of radius 3 from the pole to
-- 25 degrees (nearly flat); child_size scales each seed and gives it area child_size^2
local seed = C.simple { name = "seed", primitive = "sphere", size = { 1, 1, 1 }, color = 1 }
local seeds = C.phiball { name = "seeds", n = 500, radius = 3, open = 0, close = 25,
                          child_size = 0.13, translate = { 0, -2.72, 0 } }
seeds:child(seed)

-- the petals: tongue-like yellow leaves in a ring round the rim
local petal = C.leaf { name = "petal", shape = "lanceolate", length = 1.8, width = 0.45,
                       longitudinal = -0.2, lateral = 0.2, color = 4 }
local petals = C.phiball { name = "petals", n = 34, radius = 1.3, open = 80, close = 100 }
petals:child(petal)

-- the bracts: small green leaves under the head
local bract = C.leaf { name = "bract", shape = "ovate", length = 0.8, width = 0.45,
                       longitudinal = 0.3, color = 2 }
local bracts = C.phiball { name = "bracts", n = 21, radius = 1.1, open = 100, close = 150 }
bracts:child(bract)

head:child(seeds)
head:child(petals)
head:child(bracts)

return C.model(stalk, {
  name = "sunflower", seed = 1,
  view = { viewpoint = { 4, 9, 21 }, target = { 0, 6, 0 }, up = { 0, 1, 0 },
           projection = "perspective", fov = 40, background = { 0.93, 0.96, 1 } },
})
