-- Six variations of the quadratic Koch construction from the square F-F-F-F (ABOP fig. 1.9 a–f).
-- Returns a table of named models, one per panel, each with the n printed under it.
local lsys = require "lsys"

local function koch (n, rule)
  return lsys.lsystem {
    axiom = "F-F-F-F",
    steps = n,
    productions = "F --> " .. rule,
    view = { angle = 90, line_width = 1.5, palette = { "#24426e" } },
  }
end

return {
  a = koch(4, "FF-F-F-F-F-F+F"),
  b = koch(4, "FF-F-F-F-FF"),
  c = koch(3, "FF-F+F-F-FF"),
  d = koch(4, "FF-F--F-F"),
  e = koch(5, "F-FF--F-F"),
  f = koch(4, "F-F+F-F-F"),
}
