-- bench/write.lua's model (b): A(s) --> F(s)[+A(s/R)][-A(s/R)] from A(1), R = 1.456, 21 steps.
local lsys = require "lsys"
return lsys.lsystem { axiom = "A(1)", steps = 21, env = { R = 1.456 },
                      productions = "A(s) --> F(s)[+A(s/R)][-A(s/R)]" }
