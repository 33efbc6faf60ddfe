-- Rule parsing: the text forms of productions, and the errors for malformed rules.
local H = require "tests.helper"
local lsys = require "lsys"

describe("rule text", function()
  it("rewrites every module in parallel, leaving modules without a rule unchanged", function()
    assert.equal("ABC", H.derive("AC", "A --> AB\nB --> A", 1))
  end)

  it("* is the empty successor", function()
    assert.equal("BB", H.derive("BAB", "A --> *", 1))
  end)

  it("ignores whitespace around and inside the parts of a rule", function()
    assert.equal("BC(2)", H.derive("A(1)", "   A( x )   -->   B  C( x + 1 )   ", 1))
  end)

  it("takes one rule per line in a string", function()
    assert.equal("BA", H.derive("AB", "A --> B\nB --> A", 1))
  end)

  it("skips blank and whitespace-only lines", function()
    assert.equal("BC", H.derive("AB", "\n\n  A --> B\n\n   \t\n B --> C\n", 1))
  end)

  it("accepts tabs as whitespace", function()
    assert.equal("CDB", H.derive("AB", "A\t-->\tC\tD", 1))
  end)

  it("accepts CRLF line ends", function()
    assert.equal("CD", H.derive("AB", "A --> C\r\nB --> D\r\n", 1))
  end)

  it("takes a list of rule strings", function()
    assert.equal("BA", H.derive("AB", { "A --> B", "B --> A" }, 1))
  end)

  it("accepts a model with no productions and leaves the axiom unchanged", function()
    assert.equal("F[+F]", tostring(lsys.lsystem { axiom = "F[+F]" }:derive(3)))
  end)

  it("rewrites brackets and punctuation when a rule names them", function()
    assert.equal("F-F", H.derive("F+F", "+ --> -", 1))
  end)

  it("rewrites @ and ?P modules (?P filled with the turtle position first)", function()
    assert.equal("@Gc(2)F(3)F(3)",
                 H.derive("@Gs(1)F(3)?P(1,2)", "@Gs(x) --> @Gc(x+1)\n?P(x,y) --> F(x+y)", 1))
  end)

  it("rewrites $ outside any sub-L-system like any module", function()
    assert.equal("BA", H.derive("$A", "$ --> B", 1))
  end)

  it("splits successor parameters only at top-level commas", function()
    assert.equal("B(2,3)", H.derive("A(0)", "A(x) --> B(math.max(x, 2), 3)", 1))
  end)

  it("does not end a parameter expression at a ) inside a Lua string", function()
    assert.equal("B(1)", H.derive("A(0)", "A(x) --> B(#')')", 1))
  end)

  it("reads < and > inside successor expressions as Lua operators", function()
    assert.equal("B(1,2)", H.derive("A(0)", "A(x) --> B(x < 1 and 1 or 2, x > -1 and 2 or 3)", 1))
  end)

  it("rewrites digit modules", function()
    assert.equal("F0F1", H.derive("F1F0", "0 --> 1\n1 --> 0", 1))
  end)
end)

describe("derive and step", function()
  it("derive(n) applies n steps", function()
    assert.equal("ABAAB", H.derive("A", "A --> AB\nB --> A", 3))
  end)

  it("derive() uses the model's steps field", function()
    local m = lsys.lsystem { axiom = "A", steps = 4, productions = "A --> AB\nB --> A" }
    assert.equal("ABAABABA", tostring(m:derive()))
  end)

  it("derive() sees a changed steps field", function()
    local m = lsys.lsystem { axiom = "A", steps = 4, productions = "A --> AB\nB --> A" }
    m.steps = 2
    assert.equal("ABA", tostring(m:derive()))
  end)

  it("step(s) applies one more step to a given Lstring", function()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB\nB --> A" }
    local s = m:derive(2)
    assert.equal("ABAAB", tostring(m:step(s)))
    assert.equal("ABA", tostring(s))
  end)

  it("step accepts an Lstring from lsys.lstring", function()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB\nB --> A" }
    assert.equal("AAB", tostring(m:step(lsys.lstring("BA"))))
  end)

  it("the same model derives the same string twice", function()
    local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F" }
    assert.equal(tostring(m:derive(3)), tostring(m:derive(3)))
    assert.equal(5 ^ 3, m:derive(3):count("F"))
  end)
end)

describe("malformed rules", function()
  local function build (productions)
    return function() lsys.lsystem { axiom = "A", productions = productions } end
  end

  it("an unclosed parenthesis in the successor names the rule text and its line", function()
    assert.error_contains(build("B --> C\n\nA(s) --> B(s"), "A(s) --> B(s", "line 3")
  end)

  it("an unclosed parenthesis in the predecessor names the rule", function()
    assert.error_contains(build("A(s --> B"), "A(s --> B", "line 1")
  end)

  it("an unclosed bracket in the successor names the rule and its line", function()
    assert.error_contains(build("B --> C\nA --> F[+F"), "A --> F[+F", "line 2")
  end)

  it("an unmatched closing bracket in the successor names the rule", function()
    assert.error_contains(build("A --> F]F"), "A --> F]F", "line 1")
  end)

  it("a rule without --> names the rule and its line", function()
    assert.error_contains(build("B --> C\nC --> D\nA -> B"), "A -> B", "line 3")
  end)

  it("an arrow other than --> names the rule and its line", function()
    assert.error_contains(build("B --> C\nA => B"), "A => B", "line 2")
  end)

  it("a parameter expression that is not valid Lua names the rule", function()
    assert.error_contains(build("A(x) --> B(x ** 2)"), "A(x) --> B(x ** 2)", "line 1")
  end)

  it("a condition that is not valid Lua names the rule", function()
    assert.error_contains(build("A(x) : x >> --> B"), "A(x) : x >> --> B", "line 1")
  end)

  it("a negative weight names the rule", function()
    assert.error_contains(build("A --> B : -1"), "A --> B : -1", "line 1")
  end)

  it("a weight that is not a number names the rule", function()
    assert.error_contains(build("A --> B : heavy!"), "A --> B : heavy!", "line 1")
  end)

  it("a formal parameter that is not a name names the rule", function()
    assert.error_contains(build("A(1) --> B"), "A(1) --> B", "line 1")
  end)

  it("a formal parameter used twice names the rule", function()
    assert.error_contains(build("A(x) < A(x) --> B(x)"), "A(x) < A(x) --> B(x)", "line 1")
  end)

  it("a rule without a predecessor names the rule", function()
    assert.error_contains(build(" --> B"), "--> B", "line 1")
  end)

  it("a bracket as predecessor names the rule", function()
    assert.error_contains(build("[ --> X"), "[ --> X", "line 1")
  end)

  it("a bracket inside a predecessor of several modules names the rule", function()
    assert.error_contains(build("A[B --> C"), "A[B --> C", "line 1",
                          "a bracket cannot be in a predecessor")
  end)

  it("names the rule in a list of strings", function()
    assert.error_contains(build({ "B --> C", "A(s --> B" }), "A(s --> B")
  end)

  it("names the malformed rule in decomposition rules", function()
    assert.error_contains(function()
      lsys.lsystem { axiom = "A", decomposition = "A --> F[" }
    end, "A --> F[")
  end)

  it("names the malformed rule in homomorphism rules", function()
    assert.error_contains(function()
      lsys.lsystem { axiom = "A", homomorphism = "A(x --> F" }
    end, "A(x --> F")
  end)
end)
