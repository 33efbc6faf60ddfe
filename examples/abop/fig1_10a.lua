-- Dragon curve by edge rewriting: left and right edges Fl and Fr, n = 10 (ABOP fig. 1.10a).
-- Fl and Fr are two-letter modules; the homomorphism draws both as F.
local lsys = require "lsys"

return lsys.lsystem {
  modules = "Fl Fr",
  axiom = "Fl",
  steps = 10,
  productions = [[
    Fl --> Fl+Fr+
    Fr --> -Fl-Fr
  ]],
  homomorphism = [[
    Fl --> F
    Fr --> F
  ]],
  view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
}
