-- Power et al. 1999 (ilsa), figure 3: one branch of 11 segments pulled sideways by the same
-- drag, with (b) constant, (c) increasing and (d) decreasing joint stiffness, Z(sh, su, sl)
-- before each segment. Stiff tips keep the bend low on the branch, soft tips take it up.
-- Run: build/bin/lsys examples/ilsa/fig3.lua [OUT.png]  (default examples/gallery/ilsa/fig3.png)
local lsys = require "lsys"

local function branch (stiff)
  local parts = {}
  for i = 1, 11 do
    local s = stiff(i)
    parts[i] = ("Z(%g,%g,%g)F(1)"):format(s, s, s)
  end
  return table.concat(parts)
end

local view = { angle = 30, line_style = "cylinder", line_width = 0.25, background = { 1, 1, 1 },
               palette = { [0] = { 0.35, 0.25, 0.15 }, [1] = { 0.1, 0.5, 0.1 },
                           [2] = { 0.6, 0.1, 0.1 }, [3] = { 0.1, 0.2, 0.6 } } }
local variants = {
  { "original", nil },
  { "constant", function () return 1 end },
  { "increasing", function (i) return i end },
  { "decreasing", function (i) return 12 - i end },
}

local pieces = {}
for k, v in ipairs(variants) do
  local m = lsys.lsystem { axiom = branch(v[2] or function () return 1 end), view = view }
  local s = m:derive(0)
  if v[2] then
    local a = lsys.arrange(m, s, { wt = 0 })   -- position only: no twist target
    a:select(2, #s)   -- Z(..)F: the first F is module 2
    a:plane(5, -3)                       -- the same pull for each
    s = a:lstring()
  end
  pieces[k] = ("[@M(%d,0,0);(%d)%s]"):format(8 * (k - 1), k - 1, tostring(s))
  print(("%-10s %s"):format(v[1], v[2] and "arranged" or ""))
end

local m = lsys.lsystem { axiom = "", view = view }
local scene = m:interpret(m:lstring(table.concat(pieces)), { viewpoint = { 13, 5.5, 60 },
  target = { 13, 5.5, 0 }, projection = "parallel" })
local out = arg and arg[1] or "examples/gallery/ilsa/fig3.png"
lsys.render(scene, { out = out, width = 900, height = 420 })
print("wrote " .. out)
