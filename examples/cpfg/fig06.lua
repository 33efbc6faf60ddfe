-- The generalized cylinder of fig. 5 drawn with 1 to 5 mesh strips (cpfg guide §3.1,
-- fig. 6), left to right: `@Gs f -(45) f @Ge(n)` for n = 1..5, each placed with @M.
-- With one strip the cylinder is a straight, sheared tube between the two end discs; the
-- bend appears as strips are added. Drawn as a wireframe in the gallery so the strips show.
local lsys = require "lsys"

local parts = {}
for n = 1, 5 do
  parts[n] = string.format("[ @M(%g, 0, 0) @Gs f -(45) f @Ge(%d) ]", (n - 1) * 1.4, n)
end

return lsys.lsystem {
  axiom = "!(0.4) " .. table.concat(parts, " "),
  view = { palette = { "#c99a5b" } },
}
