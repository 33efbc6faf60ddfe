-- Shoots that grow where the light is (after Palubicki et al. 2009, "Self-organizing tree
-- models for image synthesis", §4: a bud's fate depends on the light reaching it): every
-- bud asks the light environment (lsys.environment.light: an overcast sky, ray cast through
-- the plant's own leaves) how much of the sky it sees. A bud in enough light grows an
-- internode as long as its light allows, with a leaf and a lateral bud; a bud in shade
-- waits, and one in deep shade dies. The crown fills the light and leaves the inside bare.
--
--   lsys render examples/open/shade.lua -o shade.png
local lsys = require "lsys"

return lsys.lsystem {
  name = "shade",
  axiom = "B(0) ?E(1)",
  steps = 14,
  env = { GROW = 0.45, DIE = 0.15, LEN = 1.2, DIV = 137.5, BRANCH = 38, LEAF = 0.6 },
  productions = {
    "B(age) ?E(q) : q >= GROW --> !(0.12) F(LEN * q / 2) [ &(70) L ] F(LEN * q / 2) "
      .. "[ /(DIV) +(BRANCH) B(0) ?E(1) ] /(DIV) B(age + 1) ?E(1)",
    "B(age) ?E(q) : q < DIE --> %",
    "B(age) ?E(q) --> B(age) ?E(q)",
  },
  -- a leaf: a disc on a short stalk, facing the sky as much as its branch lets it
  homomorphism = "L --> !(0.03) F(0.3) ;(2) @c(LEAF)",
  environment = lsys.environment.light { samples = 48, radiance = "cosine" },
  view = { angle = 20, line_style = "cylinder", width_increment = 0,
           palette = { [0] = { 0.45, 0.3, 0.18 }, [1] = { 0.45, 0.3, 0.18 },
                       [2] = { 0.3, 0.6, 0.2 } },
           background = { 1, 1, 1 } },
}
