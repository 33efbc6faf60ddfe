-- A family of petals from one bicubic patch (cpfg guide §4.3, figs. 26 and 27):
-- L-system 1 of the guide. The turtle walks a framework and puts the 16 control points of
-- Bézier patch 0 with @PC(0, row, column) (fig. 26: rows from the base, 0, to the tip, 3);
-- @PS(0) starts the patch and @PD(0, s, t) draws it.
--   ω: P
--   p1: P -> [ S [l] [r] B [L] [R] D ]
--   p2: S -> @PS(0) f(30)
--   p3: B -> ^(BA) f(CL) ^(TA)
--   p4: D -> ;(100) @PD(0,12,12)
--   p5: l -> +(90) f(BW) @PC(0,0,0) +(90+atan(CL/BW))
--            [ | f(CL/3) @PC(0,1,0) -(90) ^(BA) f(BW*2/3) @PC(0,1,1) ] [ f(50) @PC(0,0,1) ]
--   p6: r -> the mirror image of p5 (columns 3 and 2)
--   p7: L -> +(90) f(TW) @PC(0,3,0) +(90-atan(50/TW))
--            [ f(CL/3) @PC(0,2,0) +(90) ^(TA) f(TW*2/3) @PC(0,2,1) ] [ | f(30) @PC(0,3,1) ]
--   p8: R -> the mirror image of p7
-- CL is the central length, BW and TW the widths at the base and the tip, BA and TA the
-- angles between base and centre line and between centre line and tip. The five models are
-- the parameter sets of the guide's table (fig. 27 a–e):
--      CL   BW  TW  BA   TA
--   a  150   5   5  25   50
--   b  150  15   5   0   50
--   c  120  20  25  12  -40
--   d  100  10  15  25    0
--   e   50  15  10  12   40
-- As in cpfg, atan returns radians while the turtle turns in degrees, so the +(90+atan(...))
-- turns are within a degree or two of 90° and the control points lie on a nearly regular
-- grid. p1 is taken from L-system 2 (the guide's p1 of L-system 1 is garbled); @PD draws 12
-- lines each way instead of the guide's 4, for a smoother picture.
local lsys = require "lsys"

local function petal (CL, BW, TW, BA, TA)
  return lsys.lsystem {
    axiom = "P",
    steps = 2,
    env = { CL = CL, BW = BW, TW = TW, BA = BA, TA = TA },
    productions = {
      "P --> [ S [ l ] [ r ] B [ L ] [ R ] D ]",
      "S --> @PS(0) f(30)",
      "B --> ^(BA) f(CL) ^(TA)",
      "D --> ;(100) @PD(0,12,12)",
      "l --> +(90) f(BW) @PC(0,0,0) +(90+atan(CL/BW))"
        .. " [ | f(CL/3) @PC(0,1,0) -(90) ^(BA) f(BW*2/3) @PC(0,1,1) ] [ f(50) @PC(0,0,1) ]",
      "r --> -(90) f(BW) @PC(0,0,3) -(90+atan(CL/BW))"
        .. " [ | f(CL/3) @PC(0,1,3) +(90) ^(BA) f(BW*2/3) @PC(0,1,2) ] [ f(50) @PC(0,0,2) ]",
      "L --> +(90) f(TW) @PC(0,3,0) +(90-atan(50/TW))"
        .. " [ f(CL/3) @PC(0,2,0) +(90) ^(TA) f(TW*2/3) @PC(0,2,1) ] [ | f(30) @PC(0,3,1) ]",
      "R --> -(90) f(TW) @PC(0,3,3) -(90-atan(50/TW))"
        .. " [ f(CL/3) @PC(0,2,3) -(90) ^(TA) f(TW*2/3) @PC(0,2,2) ] [ | f(30) @PC(0,3,2) ]",
    },
    view = {
      palette = { { diffuse = { 0.93, 0.55, 0.70 }, specular = { 0.25, 0.25, 0.25 },
                    shininess = 25 } },
      direction = { -0.5, -0.3, -1 },
    },
  }
end

local M = {
  a = petal(150, 5, 5, 25, 50),
  b = petal(150, 15, 5, 0, 50),
  c = petal(120, 20, 25, 12, -40),
  d = petal(100, 10, 15, 25, 0),
  e = petal(50, 15, 10, 12, 40),
}

-- `all`: the five petals side by side at the same scale, a to e from left to right: the
-- derived strings of the five models, each moved into place with @M.
local parts = {}
for i, k in ipairs { "a", "b", "c", "d", "e" } do
  parts[i] = string.format("[ @M(%d,0,0) %s ]", (i - 1) * 110, tostring(M[k]:derive()))
end
M.all = lsys.lsystem { axiom = table.concat(parts, " "), view = M.a.view }

return M
