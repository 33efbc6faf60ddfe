-- Exercises the Lua module end to end for the `memcheck` ctest, which runs
-- it under valgrind: every path that allocates in C (parsing, derivation
-- with contexts, stochastic rules, decomposition, homomorphism, function
-- rules, the expression machine, errors raised from inside a step), the turtle
-- (every style, polygons, deep branching, tropisms, queries, the streamed
-- homomorphism, errors), the export writers and the finalizers at exit.
-- Rendering is left out: OSMesa's own allocations are not ours to check. It prints "memcheck ok" when every check held.
local lsys = require "lsys"

local function check (cond, what) if not cond then error("memcheck: " .. what, 2) end end

local m = lsys.lsystem {
  axiom = "A(1)B[C]D", seed = 3, modules = "Apex", ignore = "+-",
  productions = [[
    A(x) : x < 4 --> A(x+1)[+B]Apex(x*2)
    A < B > [C] --> B C
    C --> C : 1
    C --> D : 2
    %  --> %
  ]],
  decomposition = "D --> E F", max_depth = { decomposition = 2 },
  homomorphism = "Apex(x) --> F(x)G",
}
local s = m:derive(4)
check(#s > 10, "derivation")
check(#m:expand(s) > #s, "homomorphism")
check(tostring(lsys.lstring("F(1,0.5)[+A]")) == "F(1,0.5)[+A]", "text")

local f = lsys.lsystem { axiom = "A(1)", productions = { { "A(x)", function (x)
  lsys.nproduce("[+F")
  return lsys.produce("A(?)]", x + 1)
end } } }
check(tostring(f:derive(2)) == "[+F[+FA(3)]]", "function rules")

for _, bad in ipairs { "A(s --> B", "A --> [B", "A --> B : -1", "A(x) --> B(x*)" } do
  check(not pcall(lsys.lsystem, { productions = bad }), "malformed rule " .. bad)
end
local r = lsys.lsystem { axiom = "A(0)", productions = "A(x) --> B(1/x)" }
check(not pcall(r.derive, r, 1), "non-finite value")
local e = lsys.lsystem { axiom = "A", productions = { { "A", function () error("boom") end } } }
check(not pcall(e.derive, e, 1), "error in a rule function")
local g = lsys.lsystem { axiom = "F", max_modules = 1000, productions = "F --> FF" }
check(not pcall(g.derive, g, 20), "max_modules")
-- the turtle
local t = lsys.lsystem {
  axiom = "A(1) ?P(0,0,0)", seed = 5,
  productions = "A(x) : x < 5 --> F(x) [ +(30) /(45) A(x+1) ] [ { . -f . +f . +f . } ] A(x+1)",
  homomorphism = "A(x) --> @O(0.2) !(0.1) F(0.2) Z(1,2,3)",
  view = { tropisms = { { vector = { 0, -1, 0 }, elasticity = 0.2 } },
           torques = { { vector = { 1, 0, 0 }, elasticity = 0.1 } } },
}
local ts = t:derive(4)
local tmp = os.tmpname()
for _, style in ipairs { "line", "polygon", "cylinder" } do
  local sc = t:interpret(ts, { line_style = style, contour_sides = 5 })
  check(sc.nrecords > 10, "turtle records " .. style)
  for _, ext in ipairs { ".obj", ".ply", ".glb" } do sc:save(tmp .. ext) end
  check(#sc:turtle(#ts) == 3, "turtle state")
end
for _, ext in ipairs { ".obj", ".mtl", ".ply", ".glb", "" } do os.remove(tmp .. ext) end
check(#t:interpret(ts, { records = false }):bounds() == 3, "no records")
check(t:interpret(lsys.lstring(string.rep("[+F", 300) .. string.rep("]", 300))).nsegments == 300,
      "deep branches")
check(not pcall(t.interpret, t, "@S"), "@S refused")
check(not pcall(t.interpret, t, "@Ts(9,1)"), "bad tropism index")
local he = lsys.lsystem { homomorphism = { { "A", function () error("boom") end } } }
check(not pcall(he.interpret, he, "F A"), "error in a homomorphism rule")
print("memcheck ok")
