-- Context-sensitive plant: 0/1 signals travel along branches, n = 24, δ = 25.75° (ABOP fig. 1.31d).
-- After Hogeweg and Hesper. Digits are module names; F, + and - are ignored as context.
local lsys = require "lsys"

return lsys.lsystem {
  axiom = "F0F1F1",
  steps = 24,
  ignore = "+-F",
  productions = [[
    0 < 0 > 0 --> 1
    0 < 0 > 1 --> 0
    0 < 1 > 0 --> 0
    0 < 1 > 1 --> 1F1
    1 < 0 > 0 --> 1
    1 < 0 > 1 --> 1[+F1F1]
    1 < 1 > 0 --> 1
    1 < 1 > 1 --> 0
    + --> -
    - --> +
  ]],
  view = { angle = 25.75, line_width = 1.5, color = 8 },
}
