-- The sample parametric L-system of ABOP section 2.2, whose derivation fig. 2.2 shows.
-- Conditions pick between productions: B(2)A(4,4) => B(1)B(4)A(1,0) => B(0)B(3)A(2,1)
-- => CB(2)A(4,3) => CB(1)A(8,7). Strings only: nothing here is drawn.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "B(2)A(4,4)",
  steps = 4,
  productions = [[
    A(x,y) : y <= 3 --> A(x*2, x+y)
    A(x,y) : y > 3  --> B(x) A(x/y, 0)
    B(x) : x < 1    --> C
    B(x) : x >= 1   --> B(x-1)
  ]],
}
