/* View of the cactus Lemaireocereus chende (fig14.lua, cpfg guide fig. 14).
   Contour 2 is the ribbed cross-section of the stems; tropism 1 bends the stems upward
   with the elasticity set by @Ts(1,0.07) in the axiom. */
angle increment: 60
contour: 2 contours/cactus.con
contour sides: 48
tropism: T: 0,1,0 A: 0 E: 0
projection: perspective
viewing angle: 30
