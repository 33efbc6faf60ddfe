-- Sierpinski gasket by edge rewriting: left and right edges Fl and Fr, n = 6 (ABOP fig. 1.10b).
-- Fl and Fr are two-letter modules; the homomorphism draws both as F.
local lsys = require "lsys"

return lsys.lsystem {
  modules = "Fl Fr",
  axiom = "Fr",
  steps = 6,
  productions = [[
    Fl --> Fr+Fl+Fr
    Fr --> Fl-Fr-Fl
  ]],
  homomorphism = [[
    Fl --> F
    Fr --> F
  ]],
  view = { angle = 60, line_width = 1.5, palette = { "#24426e" } },
}
