-- A tree that fills a crown of markers by space colonisation (Runions, Lane and
-- Prusinkiewicz 2007, "Modeling trees with a space colonization algorithm"; Palubicki et
-- al. 2009 §4.2): 1500 markers (attraction points) fill an ellipsoid above a trunk, and
-- every bud asks lsys.environment.colonize for those it perceives (within 3 units and 70
-- degrees of its heading, each marker going to the nearest such bud). A bud that won some
-- grows an internode towards them, with a lateral bud beside it; one that won none waits.
-- Markers within 0.6 of a bud are taken for good: the crown fills from below until the
-- markers are used up (after 24 steps: 1581 internodes), and the branches keep apart
-- because they compete for the same space.
--
--   lsys render examples/open/colonize.lua -o colonize.png
local lsys = require "lsys"

local RX, RY, Y = 4.5, 3.5, 7        -- the crown: radii across and up, the height of its centre

return lsys.lsystem {
  name = "colonize",
  axiom = "!(0.07) F(3.5) A ?E(0, 0, 1, 0)",
  steps = 26,
  env = { L = 0.3, W0 = 0.015, DW = 0.006, DIV = 137.5, LAT = 45, OFF = 0.02 },
  productions = {
    -- a bud that won markers: an internode towards them, and a lateral bud just aside,
    -- first in the string (of two buds at one place the first wins a marker; aside, the
    -- lateral one is nearer only to the markers on its side)
    "A ?E(q, x, y, z) : q > 0 --> @R(x, y, z) !(W0) F(L) [ /(DIV) &(LAT) f(OFF) "
      .. "A ?E(0, 0, 0, 0) ] A ?E(0, 0, 0, 0)",
    "A ?E(q, x, y, z) --> A ?E(q, x, y, z)",
    "!(w) --> !(w + DW)",                -- stems thicken as they age
  },
  environment = lsys.environment.colonize {
    markers = { count = 1500, envelope = "sphere", lo = { -RX, Y - RY, -RX },
                hi = { RX, Y + RY, RX }, seed = 7 },
    perception = 3, kill = 0.6, angle = 70,
  },
  view = { line_style = "cylinder", width_increment = 0,
           palette = { [0] = { 0.42, 0.3, 0.2 }, [1] = { 0.42, 0.3, 0.2 } },
           background = { 1, 1, 1 } },
}
