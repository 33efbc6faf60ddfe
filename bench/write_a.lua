-- bench/write.lua's model (a): the D0L F --> F[+F]F[-F]F, 10 steps.
local lsys = require "lsys"
return lsys.lsystem { axiom = "F", steps = 10, productions = "F --> F[+F]F[-F]F" }
