/* View of Aloe variegata (fig15.lua, cpfg guide fig. 15): contour 2 is the keeled leaf
   cross-section, contour 3 the six-lobed flower tube. */
contour: 2 contours/aloe_leaf.con
contour: 3 contours/aloe_flower.con
contour sides: 32
projection: perspective
viewing angle: 30
