-- Power et al. 1999 (ilsa), figure 10 / section 4 "regrowth": grow, arrange, grow again. A
-- plant is derived 4 steps (a), its upper lateral branch is bent down and its trunk top
-- pulled aside with the arrangement (b), and the arranged string is derived 3 more steps
-- (c): the @J joint modules stay before the segments they bend, so the bends survive and the
-- new growth (internodes, laterals, a pruned branch's regrowth from @X) attaches to them.
-- Run: build/bin/lsys examples/ilsa/fig10.lua [OUT.png]  (default examples/gallery/ilsa/fig10.png)
local lsys = require "lsys"

local view = { angle = 35, line_style = "cylinder", line_width = 0.1, background = { 1, 1, 1 } }
local plant = lsys.lsystem {
  axiom = "F(1)A(1)", view = view,
  productions = {
    "A(k) --> F(1)[+(40)B(k)]/(137.5)F(1)[-(40)B(k)]/(137.5)A(k+1)",
    "B(k) --> F(0.6)B(k)",
    "@X --> [&(30)F(0.4)B(1)]",            -- regrowth where a branch was pruned
  },
}
local a_ = plant:derive(4)
local arr = lsys.arrange(plant, a_)

-- (b): the last internode pulled aside, from the base of the trunk
local lastF
for i = #a_, 1, -1 do if a_:module(i) == "F" and arr.depth[i] == 0 then lastF = i break end end
arr:select(1, lastF)
arr:plane(-2.5, -0.5)
arr:commit()
-- one lateral pruned (the second one on the trunk)
local seen = 0
for i = 1, #arr.s do
  if arr.s:module(i) == "[" and arr.depth[i] == 0 then
    seen = seen + 1
    if seen == 2 then arr:prune(i + 2) break end   -- [ +(40) F...: its first segment
  end
end
local b_ = arr:lstring()
local c_ = b_
for _ = 1, 3 do c_ = plant:step(c_) end

local pieces = {}
for k, s in ipairs { a_, b_, c_ } do
  pieces[k] = ("[@M(%d,0,0)%s]"):format(12 * (k - 1), tostring(s))
end
print(("(a) %d modules, (b) %d modules (%d joints), (c) %d modules"):format(#a_, #b_,
  select(2, tostring(b_):gsub("@J", "")), #c_))
local m = lsys.lsystem { axiom = "", view = view }
local scene = m:interpret(m:lstring(table.concat(pieces)), { viewpoint = { 12, 6, 90 },
  target = { 12, 6, 0 }, projection = "parallel" })
local out = arg and arg[1] or "examples/gallery/ilsa/fig10.png"
lsys.render(scene, { out = out, width = 1000, height = 500 })
print("wrote " .. out)
