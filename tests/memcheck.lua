-- Exercises the Lua module end to end for the `memcheck` ctest, which runs
-- it under valgrind: every path that allocates in C (parsing, derivation
-- with contexts, stochastic rules, decomposition, homomorphism, function
-- rules, the expression machine, errors raised from inside a step), the turtle
-- (every style, polygons, deep branching, tropisms, queries, the streamed
-- homomorphism, errors), generalized cylinders with contours, surfaces, patches and
-- textures (and their file parsers and errors), the export writers and the finalizers at
-- exit.
-- Rendering is left out: OSMesa's own allocations are not ours to check. It prints
-- "memcheck ok" when every check held.
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
-- generalized cylinders, contours, surfaces, patches, textures (cpfg guide §3-5)
local core = require "lsys.core"
local png = os.tmpname() .. ".png"
local px = {}
for i = 0, 15 do px[#px + 1] = string.char(i * 16, 255 - i * 16, 80, 255) end
core.png_write(png, table.concat(px), 4, 4, false)
local gv = {
  contour_sides = 7, textures = { png, { file = png, mode = "decal" } },
  contours = { [2] = "tests/data/contours/fig12a.con", [3] = "tests/data/contours/fig16a.con" },
  surfaces = { L = { file = "tests/data/surfaces/leaf.s", scale = 0.5 } },
}
local gc = lsys.lsystem {
  axiom = "@Tx(1) @#(2) @Gs A(1) @Ge(2) [ @#(3) @Gs f @Ge ]", view = gv,
  productions = "A(x) : x < 5 --> f @Gc(3) [ +(30) /(90) @#(3) A(x+1) @Ge(2) ] @Gt(1,2) " ..
                "@Gr(20,1) A(x+1)",
  homomorphism = "A(x) --> ~L(0.3) @PS(1,2) @PC(1,1,2) @PD(1,3,3)",
}
for _, twist in ipairs { true, false } do
  local sc = gc:interpret(gc:derive(4), { minimize_twist = twist })
  check(sc.ntriangles > 100, "generalized cylinders")
  sc:save(tmp .. ".glb"); sc:save(tmp .. ".obj")
end
for _, ext in ipairs { ".obj", ".mtl", ".glb", "" } do os.remove(tmp .. ext) end
os.remove(png)
for _, bad in ipairs { "@#(9)", "@Tx(7)", "~Q", "@PC(0,0,0)", "@Gs f @Gc(0)" } do
  check(not pcall(gc.interpret, gc, bad), "bad geometry module " .. bad)
end
local bad = os.tmpname()
local fh = io.open(bad, "w"); fh:write("3 2 closed\n0 0\n1 1\n"); fh:close()
check(not pcall(core.contour_load, bad), "truncated contour file")
check(not pcall(core.surface_load, bad), "malformed surface file")
check(not pcall(core.texture_load, bad), "not a png")
os.remove(bad)
print("memcheck ok")
