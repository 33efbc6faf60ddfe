-- "Row of trees": a parametric Koch-like curve whose edges split unevenly, δ = 86° (ABOP sec. 2.2).
-- Each F(x) becomes four segments of lengths x·p, x·h, x·h, x·q with q = c - p and h = (p·q)^½;
-- the row runs along the turtle's initial heading, and the view turns the picture a quarter
-- clockwise (twist = -90) so that it runs from left to right with the trees standing up.
local lsys = require "lsys"

local c, p = 1, 0.3
local q = c - p

return lsys.lsystem {
  axiom = "F(1)",
  steps = 6,
  env = { p = p, q = q, h = (p * q) ^ 0.5 },
  productions = "F(x) --> F(x*p) + F(x*h) - - F(x*h) + F(x*q)",
  view = { angle = 86, line_width = 1.5, palette = { "#24426e" }, twist = -90 },
}
