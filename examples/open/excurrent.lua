-- examples/open/selforg.lua's tree with stronger apical control (lambda 0.57 for 0.52;
-- Palubicki et al. 2009, §4.3: the Borchert-Honda model's lambda decides how much of the
-- vigour the main axis keeps at each branching) and a stronger pull upwards (tropism 0.15
-- for 0.05, §4.4). The leader keeps more and the laterals less: a conical (excurrent)
-- crown grows from the same rules where the spreading (decurrent) one grew.
--
--   lsys render examples/open/excurrent.lua -o excurrent.png
local lsys = require "lsys"

local m = dofile(lsys.here() .. "/selforg.lua")
m.name = "excurrent"
m.environment.lambda = 0.57
m.environment.tropism = { 0, 0.15, 0 }
return m
