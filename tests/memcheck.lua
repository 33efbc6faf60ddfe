-- Exercises the Lua module end to end for the `memcheck` ctest, which runs
-- it under valgrind: every path that allocates in C (parsing, derivation
-- with contexts, stochastic rules, decomposition, homomorphism, function
-- rules, the expression machine, errors raised from inside a step) and the
-- finalizers at exit. It prints "memcheck ok" when every check held.
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
print("memcheck ok")
