-- Roots that follow water (a resource field; after Měch and Prusinkiewicz 1996 §5.4, roots
-- in soil water): the soil is a grid of cells of side 0.5 with a little water, and a spring
-- at one side feeds it; the water diffuses from cell to cell between steps
-- (lsys.environment.resource). Each root apex asks for water and grows as far as what it
-- gets allows, turning towards where the water grows fastest (and a little down); an apex
-- in wet soil branches. The roots take what they drink: they dry the soil around them, and
-- the system reaches out towards the spring and branches there.
--
--   lsys render examples/open/roots.lua -o roots.png
local lsys = require "lsys"

return lsys.lsystem {
  name = "roots",
  axiom = "@R(0, -1, 0) ;(2) !(0.06) F(0.3) R(0) ?E(WANT, 0, -1, 0)",
  steps = 40,
  env = { WANT = 0.1, RICH = 0.08, ENOUGH = 0.01, L = 0.3, G = 0.5, W0 = 0.015, DW = 0.002,
          BR = 55 },
  productions = {
    -- an apex grows as far as its water allows, towards more; in wet soil it branches
    "R(n) ?E(w, x, y, z) : w >= RICH and n % 2 == 1 --> @R(x, y - G, z) !(W0) F(L * w / WANT) "
      .. "[ /(137.5 * n) +(BR) !(W0) F(L / 2) R(0) ?E(WANT, 0, 0, 0) ] R(n + 1) "
      .. "?E(WANT, 0, 0, 0)",
    "R(n) ?E(w, x, y, z) : w >= ENOUGH --> @R(x, y - G, z) !(W0) F(L * w / WANT) R(n + 1) "
      .. "?E(WANT, 0, 0, 0)",
    "R(n) ?E(w, x, y, z) --> R(n) ?E(WANT, 0, 0, 0)",        -- too dry: waits, asks again
    "!(w) --> !(w + DW)",                                    -- roots thicken as they age
  },
  environment = lsys.environment.resource {
    lo = { -8, -10, -8 }, hi = { 8, 0, 8 }, cell = 0.5,
    initial = function (_, y) return y > -1.5 and 0.09 or 0.03 end,   -- moister topsoil
    diffusion = 0.4,
    sources = { { 5, -6, 0, 30 } },                          -- the spring
  },
  view = { line_style = "cylinder", width_increment = 0,
           palette = { [2] = { 0.55, 0.42, 0.3 } }, background = { 1, 1, 1 } },
}
