-- The development of a petal (cpfg guide §4.3, fig. 28): L-system 2 of the guide,
-- which interpolates the petal of L-system 1 (fig27.lua) from shape e toward shape c over
-- N = 10 steps (the guide says c, but its final values are close to shape b). Modules
-- whose values change carry three parameters (v, V, i): the current value, the final value
-- and the increment; the turtle uses the first. p1–p8 are those of
-- L-system 1 with the initial values; p9–p12 step the values:
--   p9:  f(v,V,i) -> f(v+i,V,i)    and the same for +, - and ^ (p10–p12)
-- Repaired here: the guide's condition v < V never holds for a value that decreases (the
-- base angle 15 -> 0, the tip width 10 -> 5), so the condition is |V - v| > |i|/2 (not yet
-- within half a step of the final value); p7 and p8 use the interpolated tip width where
-- the guide prints a constant TW, which L-system 2 does not define; @PD draws 12 lines.
-- `all`: one picture of the sequence, six petals side by side after 0, 2, ..., 10 steps of
-- interpolation, from left to right: a delay module W(k) turns into P after k steps, so
-- the petals on the left start later. `final`: one petal after all N steps.
local lsys = require "lsys"

local N = 10

local rules = {
  "P --> [ S [ l ] [ r ] B [ L ] [ R ] D ]",
  "S --> @PS(0) f(30)",
  "B --> ^(IBA, FBA, (FBA-IBA)/N) f(ICL, FCL, (FCL-ICL)/N) ^(ITA, FTA, (FTA-ITA)/N)",
  "D --> ;(100) @PD(0,12,12)",
  "l --> +(90) f(IBW, FBW, (FBW-IBW)/N) @PC(0,0,0)"
    .. " +(90+atan(ICL/IBW), 90+atan(FCL/FBW), (atan(FCL/FBW)-atan(ICL/IBW))/N)"
    .. " [ | f(ICL/3, FCL/3, (FCL-ICL)/3/N) @PC(0,1,0) -(90) ^(IBA, FBA, (FBA-IBA)/N)"
    .. " f(IBW*2/3, FBW*2/3, 2/3*(FBW-IBW)/N) @PC(0,1,1) ] [ f(50) @PC(0,0,1) ]",
  "r --> -(90) f(IBW, FBW, (FBW-IBW)/N) @PC(0,0,3)"
    .. " -(90+atan(ICL/IBW), 90+atan(FCL/FBW), (atan(FCL/FBW)-atan(ICL/IBW))/N)"
    .. " [ | f(ICL/3, FCL/3, (FCL-ICL)/3/N) @PC(0,1,3) +(90) ^(IBA, FBA, (FBA-IBA)/N)"
    .. " f(IBW*2/3, FBW*2/3, 2/3*(FBW-IBW)/N) @PC(0,1,2) ] [ f(50) @PC(0,0,2) ]",
  "L --> +(90) f(ITW, FTW, (FTW-ITW)/N) @PC(0,3,0)"
    .. " +(90-atan(50/ITW), 90-atan(50/FTW), (atan(50/ITW)-atan(50/FTW))/N)"
    .. " [ f(ICL/3, FCL/3, (FCL-ICL)/3/N) @PC(0,2,0) +(90) ^(ITA, FTA, (FTA-ITA)/N)"
    .. " f(ITW*2/3, FTW*2/3, 2/3*(FTW-ITW)/N) @PC(0,2,1) ] [ | f(30) @PC(0,3,1) ]",
  "R --> -(90) f(ITW, FTW, (FTW-ITW)/N) @PC(0,3,3)"
    .. " -(90-atan(50/ITW), 90-atan(50/FTW), (atan(50/ITW)-atan(50/FTW))/N)"
    .. " [ f(ICL/3, FCL/3, (FCL-ICL)/3/N) @PC(0,2,3) -(90) ^(ITA, FTA, (FTA-ITA)/N)"
    .. " f(ITW*2/3, FTW*2/3, 2/3*(FTW-ITW)/N) @PC(0,2,2) ] [ | f(30) @PC(0,3,2) ]",
  "f(v,V,i) : abs(V-v) > abs(i)/2 --> f(v+i, V, i)",
  "+(v,V,i) : abs(V-v) > abs(i)/2 --> +(v+i, V, i)",
  "-(v,V,i) : abs(V-v) > abs(i)/2 --> -(v+i, V, i)",
  "^(v,V,i) : abs(V-v) > abs(i)/2 --> ^(v+i, V, i)",
  "W(k) : k > 0 --> W(k-1)",       -- the delay of the sequence picture
  "W(k) --> P",
}

local env = {
  N = N,
  ICL = 50, FCL = 150,   -- central length
  IBW = 15, FBW = 15,    -- base width
  ITW = 10, FTW = 5,     -- tip width
  IBA = 15, FBA = 0,     -- base angle
  ITA = 35, FTA = 50,    -- tip angle
}

local view = {
  palette = { { diffuse = { 0.93, 0.55, 0.70 }, specular = { 0.25, 0.25, 0.25 },
                shininess = 25 } },
  direction = { -0.5, -0.3, -1 },
}

-- W(0) becomes P, P its parts and the parts their modules in three steps; the values then
-- change for N steps
local parts = {}
for k = 0, 5 do parts[#parts + 1] = string.format("[ @M(%d,0,0) W(%d) ]", k * 70, 10 - 2 * k) end

return {
  all = lsys.lsystem { axiom = table.concat(parts, " "), steps = N + 3, env = env,
                       productions = rules, view = view },
  final = lsys.lsystem { axiom = "P", steps = N + 2, env = env, productions = rules,
                         view = view },
}
