-- Errors a model author can act on: limits, Lua errors in rules, bad axioms, NaN.
local H = require "tests.helper"
local lsys = require "lsys"

describe("max_modules", function()
  it("lets a derivation stay within the limit", function()
    local m = H.model("F", "F --> FF", { max_modules = 1000 })
    assert.equal(512, #m:derive(9))
  end)

  it("allows a string of exactly max_modules modules", function()
    local m = H.model("F", "F --> FF", { max_modules = 1024 })
    assert.equal(1024, #m:derive(10))
  end)

  it("raises an error naming max_modules when a step would exceed it", function()
    local m = H.model("F", "F --> FF", { max_modules = 1000 })
    assert.error_contains(function() m:derive(10) end, "max_modules")
  end)

  it("also limits decomposition", function()
    local m = H.model("X", "X --> A", { max_modules = 100, decomposition = "A --> FFFFFFFFFF[A]",
                                        max_depth = { decomposition = 20 } })
    assert.error_contains(function() m:derive(1) end, "max_modules")
  end)

  it("also limits m:expand", function()
    local m = H.model("A", "X --> X", { max_modules = 100, homomorphism = "A --> FFFFFFFFFF[A]",
                                        max_depth = { homomorphism = 20 } })
    assert.error_contains(function() m:expand(m:derive(0)) end, "max_modules")
  end)
end)

describe("a Lua error inside a rule", function()
  it("names the rule text and the module index", function()
    assert.error_contains(function() H.derive("FA(1)", "A(x) --> B(x.y)", 1) end,
      "A(x) --> B(x.y)", "module 2")
  end)

  it("names the module index in the string being rewritten, not the axiom", function()
    local m = H.model("A(1)", "A(x) : x < 2 --> F F A(x+1)\nA(x) --> B(x.y)")
    assert.error_contains(function() m:derive(2) end, "A(x) --> B(x.y)", "module 3")
  end)

  it("raised by a function rule names the rule pattern, the module and the message", function()
    local rules = { { "A(x)", function() error("boom") end } }
    assert.error_contains(function() H.derive("FFA(1)", rules, 1) end, "A(x)", "module 3", "boom")
  end)

  it("leaves the model usable after the error", function()
    local m = H.model("A(1)", "A(x) : x > 1 --> B(x.y)\nA(x) --> A(x+1)")
    assert.has_error(function() m:derive(2) end)
    assert.equal("A(2)", tostring(m:derive(1)))
  end)
end)

describe("axiom errors", function()
  it("an axiom with an unclosed bracket raises", function()
    assert.error_contains(function() lsys.lsystem { axiom = "F[+F" } end, "axiom")
  end)

  it("an axiom with an unmatched ] raises", function()
    assert.error_contains(function() lsys.lsystem { axiom = "F]" } end, "axiom")
  end)

  it("a malformed axiom raises naming the axiom", function()
    assert.error_contains(function() lsys.lsystem { axiom = "F(1" } end, "axiom")
  end)

  it("an axiom that is not a string raises naming the option", function()
    assert.error_contains(function() lsys.lsystem { axiom = 5, productions = "A --> B" } end,
      "axiom")
  end)
end)

describe("NaN parameters", function()
  it("a rule that computes NaN raises naming the rule", function()
    assert.error_contains(function() H.derive("A(0)", "A(x) --> B(x/x)", 1) end,
      "A(x) --> B(x/x)")
  end)

  it("a function rule that produces NaN raises", function()
    local rules = { { "A", function() return lsys.produce("B(?)", 0 / 0) end } }
    assert.has_error(function() H.derive("A", rules, 1) end)
  end)
end)

describe("model options", function()
  it("an unknown option raises naming it", function()
    assert.error_contains(function()
      lsys.lsystem { axiom = "A", prodcutions = "A --> B" }
    end, "prodcutions")
  end)

  it("giving both ignore and consider raises", function()
    assert.error_contains(function()
      lsys.lsystem { axiom = "A", ignore = "+", consider = "A" }
    end, "ignore", "consider")
  end)

  it("an option of the wrong type raises naming it", function()
    assert.error_contains(function() lsys.lsystem { axiom = "A", steps = "ten" } end, "steps")
  end)

  it("derive with a negative step count raises", function()
    assert.has_error(function() H.model("A", "A --> B"):derive(-1) end)
  end)

  it("step with something other than an Lstring raises", function()
    assert.has_error(function() H.model("A", "A --> B"):step({}) end)
  end)
end)
