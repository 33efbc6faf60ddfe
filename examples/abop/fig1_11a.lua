-- Hexagonal Gosper curve (flowsnake) by edge rewriting, n = 4 (ABOP fig. 1.11a).
-- Fl and Fr are two-letter modules; the homomorphism draws both as F.
local lsys = require "lsys"

return lsys.lsystem {
  modules = "Fl Fr",
  axiom = "Fl",
  steps = 4,
  productions = [[
    Fl --> Fl+Fr++Fr-Fl--FlFl-Fr+
    Fr --> -Fl+FrFr++Fr+Fl--Fl-Fr
  ]],
  homomorphism = [[
    Fl --> F
    Fr --> F
  ]],
  view = { angle = 60, line_width = 1.5, palette = { "#24426e" } },
}
