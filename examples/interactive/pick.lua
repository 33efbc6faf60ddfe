-- A script (not a model file): shows a growing plant in the viewer window and prints what
-- a click hits: the module, its parameters and the segments of the branch above it.
-- Run it with `build/bin/lsys examples/interactive/pick.lua`; close the window to end.
-- Keys in the window: left/right step through the derivation, space animates, S saves a
-- screenshot, H lists the rest (docs/viewer.md).
local lsys = require "lsys"

local plant = lsys.lsystem {
  name = "branching pick demo",
  axiom = "!(1) F(1) A(1)",
  steps = 6,
  productions = {
    "A(k) --> !(0.7) F(1) [ +(35) /(90) A(k+1) ] [ -(35) /(90) A(k+1) ] F(1) A(k+1)",
    "F(l) --> F(l*1.1)",
    "!(w) --> !(w*1.3)",
  },
  view = { line_style = "cylinder", line_width = 0.08, background = {1, 1, 1} },
}

-- the modules of the branch that starts right after module i (up to its closing bracket)
local function branch_after (s, i)
  local depth, n = 0, 0
  for j = i + 1, #s do
    local name = s:module(j)
    if name == "[" then depth = depth + 1
    elseif name == "]" then
      if depth == 0 then break end
      depth = depth - 1
    elseif name == "F" then n = n + 1 end
  end
  return n
end

lsys.show(plant, {
  title = "click a segment",
  on_pick = function (p)
    print(("step %d, module %d: %s; %d segments above it on its axis and branches"):format(
      p.step, p.module, p.text, branch_after(p.lstring, p.module)))
  end,
})
print("click the plant; close the window (Esc) to end")
lsys.wait()
