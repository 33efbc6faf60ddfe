-- A chessboard texture on a predefined surface (cpfg guide §5.1, fig. 31).
-- The surface surfaces/leaf.s (written by surfaces/make.lua) is a leaf blade of two Bézier
-- patches, base and tip. The texture textures/chessboard.png (8x8 squares, written by
-- textures/make.lua) is given to the surface in the view (`texture = 1`), so every
-- instance of ~L has it:
-- `a`: texture per patch (the default): each patch gets the whole image, mapped by its
--      own s and t, so the squares crowd toward the pointed base and tip and meet at an
--      angle where the two patches join;
-- `b`: texture per surface (`per_surface = true`, cpfg's `S:`): the image is laid over the
--      bounding box of the surface in x and y, so the squares are square and run
--      straight across the join.
local lsys = require "lsys"

local function leaf (per_surface)
  return lsys.lsystem {
    axiom = "~L",
    view = {
      dir = lsys.here(),
      textures = { { file = "textures/chessboard.png", per_surface = per_surface,
                     mag = "linear", min = "linear" } },
      surfaces = { L = { file = "surfaces/leaf.s", texture = 1, scale = 10 } },
      palette = { { 1, 1, 1 } },
      direction = { 0, 0, 1 }, up = { 0, 1, 0 }, light = { 0.3, 0.4, -1 },
      background = { 0.62, 0.70, 0.78 },
    },
  }
end

return { a = leaf(false), b = leaf(true) }
