-- One of Davison's trees (examples/grow/davison.lua) with leaves as a surface: every leaf
-- is the cpfg leaf surface examples/cpfg/surfaces/leaf.s (two Bezier patches, guide §4.1)
-- instead of the default quad. The world tessellates the surface once; each leaf then owns
-- a fixed range of the scene's vertices (the surface's 162 at 8 x 8 lines a patch) that a
-- tick rewrites in place, as it does a limb's cylinder.
--
--   build/bin/lsys examples/grow/leafy.lua [out.png]        renders it after 60 ticks
--   build/bin/lsys grow examples/grow/leafy.lua             grows it in the window
local lsys = require "lsys"

local here = lsys.here()
local davison = dofile(here .. "/davison.lua")

local M = {}

--- One tree with surface leaves: M.world{ seed =, ticks =, precision = {s, t} }.
function M.world (opts)
  opts = opts or {}
  return davison.world {
    seed = opts.seed or 3, ticks = opts.ticks or 60, trees = 1,
    -- the file's name is looked up next to the file that makes the world: davison.lua, here
    leaf = { file = "../cpfg/surfaces/leaf.s", precision = opts.precision },
    view = { background = { 0.93, 0.96, 1 }, direction = { -0.35, -0.25, -1 } },
  }
end

if arg and arg[0] and arg[0]:match("leafy%.lua$") then
  local w = M.world():grow()
  local out = arg[1] or "leafy.png"
  lsys.render(w:scene(), { out = out, width = 800, height = 800 })
  print(string.format("%d limbs, %d triangles after %d ticks -> %s", w:count(),
                      w:scene().ntriangles, w.ticks, out))
end

return M
