-- The first two stages of the horse chestnut of Lintermann and Deussen 1999, fig. 6
-- (section "Chestnut tree": "By combining two Tree components we get a simple tree. Changes
-- in the parameters for the number of branches, the spacing of the branches, the branching
-- angle, and shape lead to a more naturalistic tree (see Figure 6a). Now, we add two more
-- Tree components to model the tiny twigs (Figure 6b)"). The graph is chestnut.lua's, cut
-- after its second and its fourth Tree; chestnut.lua itself is fig. 6c, the leaves added.
--
--   a: 1 trunk, 12 branches.   b: and 96 sub-branches, 576 twigs.
--
--   build/bin/lsys render examples/components/fig6_ab.lua --name b -o fig6b.png
local lsys = require "lsys"
local C = lsys.components

local chestnut = dofile(lsys.here() .. "/chestnut.lua")

return {
  a = C.model(chestnut.graph { levels = 2 }, { seed = 1, view = chestnut.VIEW,
                                               name = "fig6a" }),
  b = C.model(chestnut.graph { levels = 4 }, { seed = 1, view = chestnut.VIEW,
                                               name = "fig6b" }),
}
