-- lsys.lstring: parsing and printing cpfg text notation, and the Lstring methods.
local H = require "tests.helper"
local lsys = require "lsys"

local function roundtrip (text) return tostring(lsys.lstring(text)) end

describe("lsys.lstring text notation", function()
  it("prints a parsed string with parameters and branches unchanged", function()
    assert.equal("F(1,0.5)[+A]", roundtrip("F(1,0.5)[+A]"))
  end)

  it("prints integral parameters without a decimal point", function()
    assert.equal("F(1)G(100)", roundtrip("F(1.0)G(100.000)"))
  end)

  it("prints 0.1 as 0.1, the shortest text that reads back as the same number", function()
    assert.equal("F(0.1)", roundtrip("F(0.1)"))
  end)

  it("prints 0.30000000000000004 with all the digits it needs", function()
    assert.equal("F(0.30000000000000004)", roundtrip("F(0.30000000000000004)"))
  end)

  it("rounds parameters to the digits asked for with s:text(i, j, digits)", function()
    local s = lsys.lstring("F(0.48999999999999994,2,-0.30000000000000004)G(1e300)")
    assert.equal("F(0.49,2,-0.3)G(1e+300)", s:text(1, -1, 15))
    assert.equal("F(0.5,2,-0.3)", s:text(1, 1, 1))
    assert.equal(s, lsys.lstring(s:text(1, -1, 17)))   -- 17 digits always read back
    assert.equal(tostring(s), s:text())
    assert.error_contains(function () s:text(1, -1, 0) end, "digits must be from 1 to 17")
    assert.error_contains(function () s:text(1, -1, 18) end, "digits must be from 1 to 17")
  end)

  it("prints 1e300 in exponent notation", function()
    assert.equal("F(1e+300)", roundtrip("F(1e300)"))
  end)

  it("prints negative numbers with a minus sign", function()
    assert.equal("F(-2.5)+(-90)", roundtrip("F(-2.5)+(-90)"))
  end)

  it("reads exponents and leading-dot numbers", function()
    assert.equal("F(0.5,1500,0.25)", roundtrip("F(.5,1.5e3,25E-2)"))
  end)

  it("reads -0 as a parameter equal to zero and prints text that reads back the same", function()
    local s = lsys.lstring("F(-0)")
    local _, p = s:module(1)
    assert.equal(0, p)
    assert.equal(tostring(s), roundtrip(tostring(s)))
  end)

  it("keeps every digit of a parameter through print and parse", function()
    local x = 2 / 3
    local s = lsys.lstring("F(" .. string.format("%.17g", x) .. ")")
    local _, p = lsys.lstring(tostring(s)):module(1)
    assert.equal(x, p)
  end)

  it("ignores whitespace between modules and inside parameter lists", function()
    assert.equal("F(1,2)[+A]B", roundtrip("  F(1, 2) [ +A ]\n\tB  "))
  end)

  it("parses the empty string to an empty Lstring", function()
    local s = lsys.lstring("")
    assert.equal(0, #s)
    assert.equal("", tostring(s))
  end)

  it("treats digits and punctuation as one-character module names", function()
    local s = lsys.lstring("F1F1")
    assert.equal(4, #s)
    assert.equal("1", (s:module(2)))
    assert.equal("F1F1", tostring(s))
  end)

  it("treats each of + - & ^ / \\ | ! ; , # % as its own module", function()
    local s = lsys.lstring("+-&^/\\|!;,#%")
    assert.equal(12, #s)
    assert.equal("\\", (s:module(6)))
    assert.equal("+-&^/\\|!;,#%", tostring(s))
  end)

  it("reads @ followed by letters, ?P, ~name, ? and $ as single modules", function()
    local s = lsys.lstring("@Gs+@Gc(4)?P(0,1)~l(2)$?(2,0.5)F$")
    assert.same({ "@Gs", "+", "@Gc", "?P", "~l", "$", "?", "F", "$" },
      (function() local t = {} for i = 1, #s do t[i] = (s:module(i)) end return t end)())
    assert.equal("@Gs+@Gc(4)?P(0,1)~l(2)$?(2,0.5)F$", tostring(s))
  end)

  it("accepts unbalanced brackets (an Lstring is any sequence; only an axiom must balance)",
  function()
    local s = lsys.lstring("F[+F")
    assert.equal(4, #s)
    assert.equal("F[+F", tostring(s))
  end)
end)

describe("lsys.lstring malformed text", function()
  it("raises for an unclosed parameter list", function()
    assert.has_error(function() lsys.lstring("F(1") end)
  end)

  it("raises for an empty parameter between commas", function()
    assert.has_error(function() lsys.lstring("F(1,,2)") end)
  end)

  it("raises for a parameter that is not a number", function()
    assert.has_error(function() lsys.lstring("F(abc)") end)
  end)

  it("raises for a parameter list with a trailing comma", function()
    assert.has_error(function() lsys.lstring("F(1,)") end)
  end)

  it("raises for nan as a parameter (parameters are finite numbers, as in rules)", function()
    assert.has_error(function() lsys.lstring("F(nan)") end)
  end)

  it("raises for a parameter too large to be a finite number", function()
    assert.has_error(function() lsys.lstring("F(1e999)") end)
  end)

  it("raises for inf as a parameter", function()
    assert.has_error(function() lsys.lstring("F(inf)") end)
  end)

  it("reads 31 parameters and raises with the limit for 32", function()
    assert.equal(1, #lsys.lstring("F(" .. string.rep("1,", 30) .. "1)"))
    assert.error_contains(function() lsys.lstring("F(" .. string.rep("1,", 31) .. "1)") end,
      "too many parameters")
  end)

  it("raises when given something other than a string", function()
    assert.has_error(function() lsys.lstring({}) end)
  end)
end)

describe("Lstring methods", function()
  local s
  before_each(function() s = lsys.lstring("F(1,0.5)[+A]") end)

  it("# gives the number of modules", function()
    assert.equal(5, #s)
  end)

  it("count gives the number of modules with a name", function()
    local t = lsys.lstring("F(1)F[F(2,3)]GF")
    assert.equal(4, t:count("F"))
    assert.equal(1, t:count("G"))
    assert.equal(0, t:count("X"))
    assert.equal(1, t:count("["))
  end)

  it("count works for multi-character names", function()
    assert.equal(2, lsys.lstring("@Gs F @Gc(2) @Gs"):count("@Gs"))
  end)

  it("sub(i, j) returns modules i to j inclusive as an Lstring", function()
    local t = s:sub(2, 4)
    assert.equal("[+A", tostring(t))
    assert.equal(3, #t)
  end)

  it("sub keeps the parameters of the modules it copies", function()
    assert.equal("F(1,0.5)[", tostring(s:sub(1, 2)))
  end)

  it("sub counts negative indices from the end", function()
    assert.equal("A]", tostring(s:sub(-2, -1)))
    assert.equal("A]", tostring(s:sub(-2)))
  end)

  it("sub(1, -1) copies the whole string", function()
    assert.equal("F(1,0.5)[+A]", tostring(s:sub(1, -1)))
  end)

  it("sub returns an empty Lstring when i > j", function()
    assert.equal("", tostring(s:sub(3, 2)))
    assert.equal(0, #s:sub(4, 1))
  end)

  it("sub clamps indices outside the string like string.sub", function()
    assert.equal("F(1,0.5)[", tostring(s:sub(-100, 2)))
    assert.equal("A]", tostring(s:sub(4, 100)))
    assert.equal("F(1,0.5)", tostring(s:sub(0, 1)))
    assert.equal("", tostring(s:sub(6, 9)))
  end)

  it("sub does not change the original", function()
    s:sub(2, 3)
    assert.equal("F(1,0.5)[+A]", tostring(s))
  end)

  it("module(i) returns the name and the parameters", function()
    assert.same({ "F", 1, 0.5, n = 3 }, table.pack(s:module(1)))
  end)

  it("module(i) returns only the name for a module without parameters", function()
    assert.same({ "+", n = 1 }, table.pack(s:module(3)))
  end)

  it("module(i) accepts a negative index counted from the end", function()
    assert.same({ "A", n = 1 }, table.pack(s:module(-2)))
  end)

  it("module(i) raises for an index outside the string", function()
    assert.has_error(function() s:module(0) end)
    assert.has_error(function() s:module(6) end)
  end)

  it("modules() iterates index, name and parameters in order", function()
    local seen = {}
    for i, name, a, b in s:modules() do
      seen[#seen + 1] = { i, name, a, b }
    end
    assert.same({ { 1, "F", 1, 0.5 }, { 2, "[" }, { 3, "+" }, { 4, "A" }, { 5, "]" } }, seen)
  end)

  it("modules() on an empty string does not iterate", function()
    local n = 0
    for _ in lsys.lstring(""):modules() do n = n + 1 end
    assert.equal(0, n)
  end)

  it("module parameters are Lua numbers (floats keep their fraction)", function()
    local _, a, b = lsys.lstring("F(3,0.25)"):module(1)
    assert.equal("number", type(a))
    assert.equal(3, a)
    assert.equal(0.25, b)
  end)
end)

describe("declared multi-character module names", function()
  local m
  before_each(function()
    m = lsys.lsystem { axiom = "Apex", modules = "Apex Leaf",
                       productions = "Apex --> Leaf Apex" }
  end)

  it("m:lstring reads a declared name as one module", function()
    local s = m:lstring("Apex(1)[+Leaf]")
    assert.equal(5, #s)
    assert.same({ "Apex", 1, n = 2 }, table.pack(s:module(1)))
    assert.equal("Leaf", (s:module(4)))
  end)

  it("m:lstring reads adjacent declared names without spaces", function()
    local s = m:lstring("LeafApex")
    assert.equal(2, #s)
    assert.equal("Leaf", (s:module(1)))
    assert.equal("Apex", (s:module(2)))
  end)

  it("prints declared names so that m:lstring reads the text back to the same modules", function()
    local s = m:lstring("Apex(1) [ + Leaf ] Leaf Apex LeafA")
    local t = m:lstring(tostring(s))
    assert.equal(9, #t)
    assert.same(H.modules(s), H.modules(t))
  end)

  it("prints declared names as written (spaces between modules aside)", function()
    assert.equal("LeafApex", (tostring(m:lstring("Leaf Apex")):gsub(" ", "")))
    assert.equal("Apex(1)[+Leaf]", (tostring(m:lstring("Apex(1) [ + Leaf ]")):gsub(" ", "")))
  end)

  it("prints single modules that spell a declared name so that they read back apart", function()
    local m2 = lsys.lsystem { axiom = "A B", modules = "AB" }
    local s = m2:lstring("A B AB")
    assert.equal(3, #s)
    assert.equal(1, #m2:lstring("AB"))
    local t = m2:lstring(tostring(s))
    assert.equal(3, #t)
    assert.same(H.modules(s), H.modules(t))
  end)

  it("undeclared letters stay one-character modules in m:lstring", function()
    local s = m:lstring("ApexAB")
    assert.equal(3, #s)
    assert.equal("A", (s:module(2)))
  end)

  it("productions rewrite declared names", function()
    local s = m:derive(2)
    assert.equal(3, #s)
    assert.equal("LeafLeafApex", (tostring(s):gsub(" ", "")))
    assert.equal(2, s:count("Leaf"))
  end)

  it("lsys.lstring does not know a model's declared names", function()
    assert.equal(4, #lsys.lstring("Leaf"))
  end)
end)

describe("axiom", function()
  it("an axiom with an unclosed bracket raises", function()
    assert.has_error(function() lsys.lsystem { axiom = "F[+F", productions = "F --> FF" } end)
  end)

  it("an axiom with an unmatched closing bracket raises", function()
    assert.has_error(function() lsys.lsystem { axiom = "F]F", productions = "F --> FF" } end)
  end)

  it("derive(0) returns the axiom", function()
    local m = lsys.lsystem { axiom = "F(1) [ +A ]", productions = "A --> B" }
    assert.equal("F(1)[+A]", tostring(m:derive(0)))
  end)
end)
