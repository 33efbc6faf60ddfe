-- Bracketed plant: edge rewriting, n = 4, δ = 22.5° (ABOP fig. 1.24c).
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F",
  steps = 4,
  productions = "F --> FF-[-F+F+F]+[+F-F-F]",
  view = { angle = 22.5, line_width = 1.5, color = 8 },
}
