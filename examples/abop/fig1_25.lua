-- A three-dimensional bush-like structure with leaves (ABOP fig. 1.25), n = 7, δ = 22.5°.
-- The book's `'` (next colour) is cpfg's `;`; `!` thins the branches by the width increment.
-- Colours run from bark (1) through greens along the branching order; leaves are three
-- colours further on. Drawn with cylinders and two-sided leaf polygons.
local lsys = require "lsys"

local palette = { [0] = { 0.2, 0.2, 0.2 } }
for i = 1, 24 do            -- bark brown to leaf green
  local t = math.min(1, (i - 1) / 10)
  palette[i] = { 0.40 + (0.22 - 0.40) * t, 0.28 + (0.55 - 0.28) * t, 0.16 + (0.12 - 0.16) * t }
end

return lsys.lsystem {
  axiom = "A",
  steps = 7,
  productions = [[
    A --> [ & F L ! A ] ///// ; [ & F L ! A ] /////// ; [ & F L ! A ]
    F --> S ///// F
    S --> F L
    L --> [ ;;; ^^ { - f + f + f - | - f + f + f } ]
  ]],
  view = {
    angle = 22.5, line_style = "cylinder", line_width = 0.35, width_increment = 0.045,
    contour_sides = 8, palette = palette, projection = "perspective",
    direction = { 0, -0.25, -1 },      -- from a little above
  },
}
