--- The geometry generation example of Lintermann and Deussen 1999 (section "A geometry
-- generation example", fig. 2): A is the root, B a Horn making a stem, C a Hydra making
-- three instances of its child and no geometry of its own, D a Horn making one part of a
-- twig, linked to itself with a recursion depth of 3. C makes D1, D2, D3; each recurses into
-- Di1, Di2, Di3 (the article's naming), so the i-tree holds nine instances of D, and the
-- local frame of each child of the Hydra turns its chain a different way.
--
--   build/bin/lsys render examples/components/fig2_abcd.lua -o fig2.png
local C = require "lsys".components

-- D: one twig part, bent a little, each recursion 0.75 times the size of the one before
local D = C.horn { name = "D", recursion = 3, length = 1.2, radius = 0.08, tip = 0.7,
                   curvature = -14, scale = 0.8, color = 2 }
-- a bud at the end of each part, so the nine instances of D can be told apart
local bud = C.simple { name = "bud", primitive = "sphere", size = { 0.16, 0.16, 0.16 },
                       translate = { 0, -0.08, 0 }, color = 3 }
D:child(D)
D:child(bud)

-- C: three Ds in a star around the stem's tip, 40 degrees out from its axis
local Cm = C.hydra { name = "C", n = 3, angle = 50 }
Cm:child(D)

-- B: the stem
local B = C.horn { name = "B", length = 2.2, radius = 0.12, tip = 0.6, color = 1 }
B:child(Cm)

-- A: the root; a small brown disc as the ground the stem stands on
local A = C.simple { name = "A", primitive = "disc", size = { 1.2, 0, 1.2 }, color = 11 }
A:child(B)

return C.model(A, {
  name = "fig2_abcd", seed = 1,
  view = { viewpoint = { 2.5, 4.5, 7.5 }, target = { 0, 2.4, 0 }, up = { 0, 1, 0 },
           projection = "perspective", fov = 40, background = { 1, 1, 1 } },
})
