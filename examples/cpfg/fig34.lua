-- A texture on a polygon (cpfg guide §5.3, fig. 34). @Tx(k) before the polygon
-- selects the texture; texture coordinates come from the polygon's vertices measured along
-- the heading h and the right vector r of the turtle at the first vertex, scaled to [0, 1]
-- over the polygon, so the image is stretched over the polygon's bounding rectangle.
-- The polygon is the leaf blade of fig24.lua: its outline is marked with `.` at the ends
-- of the veins of a branching framework (G moves without adding a vertex).
-- `a`: textures/chessboard.png shows the mapping: the 8x8 squares fill the bounding
--      rectangle of the blade, from the base to the tip and from edge to edge;
-- `b`: a textured polygon: textures/venation.png, a leaf venation pattern, gives the flat
--      blade a midrib and side veins.
local lsys = require "lsys"

local function leaf (texture)
  return lsys.lsystem {
    axiom = "@Tx(1) { . A(1) }",
    steps = 6,
    env = { N = 6 },
    productions = [[
      A(k) : k < N  --> g [ +(60) g(1.6*sin(pi*k/N)) . ] [ A(k+1) ] [ -(60) g(1.6*sin(pi*k/N)) . ]
      A(k) : k == N --> g .
    ]],
    view = {
      dir = lsys.here(),
      textures = { { file = texture, mag = "linear", min = "linear" } },
      palette = { { 1, 1, 1 } }, background = { 0.62, 0.70, 0.78 }, light = { 0.2, 0.3, 1 },
    },
  }
end

return { a = leaf("textures/chessboard.png"), b = leaf("textures/venation.png") }
