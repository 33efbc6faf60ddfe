-- Power et al. 1999 (ilsa), figure 4: one manipulation of a plant's lower branch (pulled up
-- and out with the plane dragger) (a) before, (b) with no stiffness and no smoothness, (c)
-- with no stiffness and smoothness, (d) with stiffness from the branch radii (da Vinci
-- rule, eqs. 4-6). The branch path runs from the branch's base to its tip; its side shoots
-- (the rest of the active branch) follow rigidly.
-- Run: build/bin/lsys examples/ilsa/fig4.lua [OUT.png]  (default examples/gallery/ilsa/fig4.png)
local lsys = require "lsys"

local view = { angle = 30, line_style = "cylinder", line_width = 0.12, background = { 1, 1, 1 },
               palette = { [0] = { 0.35, 0.25, 0.15 }, [1] = { 0.15, 0.45, 0.1 } } }
-- a trunk with a long lower branch of 8 internodes carrying short side shoots
local shoot = "[+(35);(1)F(0.6)]"
local lower = "[-(50)" .. ("F(0.8)" .. shoot):rep(7) .. "F(0.8)]"
local plant = lsys.lsystem {
  axiom = "F(1)F(1)" .. lower .. "F(1)F(1)[+(40)F(1)F(1)]F(1)F(1)[-(40)F(1)]F(1)",
  view = view,
}

local variants = {
  { "before" },
  { "no stiffness, no smoothness", { we = 0, ws = 0 } },
  { "no stiffness, smoothness", { we = 0, ws = 1 } },
  { "stiffness (da Vinci)", { we = 1, ws = 0, r0 = 1 } },
}
local pieces = {}
for k, v in ipairs(variants) do
  local s = plant:derive(0)
  if v[2] then
    local a = lsys.arrange(plant, s, v[2])
    -- the lower branch opens at module 3; its first internode is module 5, its last the
    -- F before its closing bracket
    local depth, last = 0, nil
    for i = 3, #s do
      local name = s:module(i)
      if name == "[" then depth = depth + 1 elseif name == "]" then depth = depth - 1 end
      if depth == 0 then last = i - 1 break end
    end
    a:select(5, last)
    a:plane(-2.5, 1)
    s = a:lstring()
  end
  pieces[k] = ("[@M(%d,0,0)%s]"):format(9 * (k - 1), tostring(s))
  print(v[1])
end
local m = lsys.lsystem { axiom = "", view = view }
local scene = m:interpret(m:lstring(table.concat(pieces)), { viewpoint = { 13, 5, 80 },
  target = { 13, 5, 0 }, projection = "parallel" })
local out = arg and arg[1] or "examples/gallery/ilsa/fig4.png"
lsys.render(scene, { out = out, width = 1000, height = 420 })
print("wrote " .. out)
