-- Anastacio et al. 2009, fig. 10 and fig. 5 (§3.5, §4.2.2, §7.3): a stem drawn with pen
-- pressure (fig10_depth.json): harder in its lower half, so the stem comes towards the
-- viewer, lighter towards the top, so it leans away, while the drawn line bends to the
-- right. The stem's yaw and pitch functions turn the turtle in the global frame; decussate
-- pairs of ovate leaves (organ_leaf.json). The same plant seen from the front (the view it
-- was drawn in: it looks like the drawing), from the diagonal and from the side (the depth
-- appears). `flat` is the plant with the pressure ignored (depth = false), for comparison.
local lsys = require "lsys"
local common = dofile(lsys.here() .. "/common.lua")

local sk = common.sketch("fig10_depth")
local leaf = common.organ("leaf")
local function plant (dir, depth)
  return sk:model { organ = leaf, organ_color = common.LEAF, width = 0.012, depth = depth,
                    view = common.view(dir) }
end

return {
  front = plant({ 0, 0, -1 }),
  diagonal = plant({ 1, 0, -1 }),
  side = plant({ 1, 0, 0 }),
  flat = plant({ 1, 0, 0 }, false),
}
