-- Quadratic Gosper curve by edge rewriting, 25 edges per generator, n = 2 (ABOP fig. 1.11b).
-- Fl and Fr are two-letter modules; the homomorphism draws both as F.
local lsys = require "lsys"

return lsys.lsystem {
  modules = "Fl Fr",
  axiom = "-Fr",
  steps = 2,
  productions = [[
    Fl --> FlFl-Fr-Fr+Fl+Fl-Fr-FrFl+Fr+FlFlFr-Fl+Fr+FlFl+Fr-FlFr-Fr-Fl+Fl+FrFr-
    Fr --> +FlFl-Fr-Fr+Fl+FlFr+Fl-FrFr-Fl-Fr+FlFrFr-Fl-FrFl+Fl+Fr-Fr-Fl+Fl+FrFr
  ]],
  homomorphism = [[
    Fl --> F
    Fr --> F
  ]],
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
