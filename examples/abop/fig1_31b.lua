-- Context-sensitive plant: 0/1 signals travel along branches, n = 30, δ = 22.5° (ABOP fig. 1.31b).
-- After Hogeweg and Hesper. Digits are module names; F, + and - are ignored as context.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F1F1F1",
  steps = 30,
  ignore = "+-F",
  productions = [[
    0 < 0 > 0 --> 1
    0 < 0 > 1 --> 1[-F1F1]
    0 < 1 > 0 --> 1
    0 < 1 > 1 --> 1
    1 < 0 > 0 --> 0
    1 < 0 > 1 --> 1F1
    1 < 1 > 0 --> 1
    1 < 1 > 1 --> 0
    + --> -
    - --> +
  ]],
  view = { angle = 22.5, line_width = 1.5, color = 8 },
}
