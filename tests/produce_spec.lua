-- Rules written as Lua functions: { pattern, function } with lsys.produce / lsys.nproduce.
local H = require "tests.helper"
local lsys = require "lsys"

describe("function rules", function()
  it("produce fills ? marks in order with the given values", function()
    local rules = { { "A(s)", function(s)
      return lsys.produce("B(?)C(?,?)", s + 1, s * 2, -s)
    end } }
    assert.equal("B(3)C(4,-2)", H.derive("A(2)", rules, 1))
  end)

  it("produce without ? marks gives a fixed successor", function()
    local rules = { { "A", function() return lsys.produce("F[+F]") end } }
    assert.equal("F[+F]F[+F]", H.derive("AA", rules, 1))
  end)

  it("receive the formals of left context, predecessor and right context in order", function()
    local rules = { { "A(a) < B(b) > C(c)", function(a, b, c)
      return lsys.produce("B(?)", a * 100 + b * 10 + c)
    end } }
    assert.equal("A(1)B(123)C(3)", H.derive("A(1)B(2)C(3)", rules, 1))
  end)

  it("follow the example of the design: produce, or nproduce pieces then produce", function()
    local rules = { { "A(s) < B(t)", function(s, t)
      if t < 1 then return lsys.produce("B(?)", t + s) end
      for i = 1, 3 do lsys.nproduce("[/(?) +(30) L]", i * 120) end
      return lsys.produce("B(0)")
    end } }
    assert.equal("A(1)B(1.5)", H.derive("A(1)B(0.5)", rules, 1))
    assert.equal("A(1)[/(120)+(30)L][/(240)+(30)L][/(360)+(30)L]B(0)",
      H.derive("A(1)B(2)", rules, 1))
  end)

  it("reuse one template with different values for different modules", function()
    local rules = { { "A(s)", function(s) return lsys.produce("B(?)", s * 10) end } }
    assert.equal("B(10)B(20)B(30)", H.derive("A(1)A(2)A(3)", rules, 1))
  end)

  it("a function that returns without producing does not apply; the next rule does", function()
    local rules = {
      { "A(s)", function(s) if s > 1 then return lsys.produce("B") end end },
      "A(s) --> C",
    }
    assert.equal("CB", H.derive("A(1)A(2)", rules, 1))
  end)

  it("a function that produces nothing anywhere leaves the module unchanged", function()
    local rules = { { "A(s)", function() end } }
    assert.equal("A(1)", H.derive("A(1)", rules, 1))
  end)

  it("mixes with rule strings in declaration order", function()
    local rules = {
      "A(s) : s > 5 --> X",
      { "A(s)", function(s) return lsys.produce("Y(?)", s) end },
      "A(s) --> Z",
    }
    assert.equal("XY(1)", H.derive("A(9)A(1)", rules, 1))
  end)

  it("can produce a branch and the empty string", function()
    local rules = { { "A", function() return lsys.produce("") end },
                    { "B", function() return lsys.produce("[+F]") end } }
    assert.equal("F[+F]F", H.derive("FABF", rules, 1))
  end)

  it("are called once per matching module per step", function()
    local calls = 0
    local rules = { { "A", function() calls = calls + 1; return lsys.produce("A") end } }
    H.derive("AAAA", rules, 3)
    assert.equal(12, calls)
  end)

  it("a function that calls nproduce but not produce does not apply; its pieces are dropped",
  function()
    local rules = { { "A(x)", function(x)
      lsys.nproduce("N")
      if x > 1 then return lsys.produce("B") end
    end } }
    assert.equal("A(1)NB", H.derive("A(1)A(2)", rules, 1))
  end)

  it("nproduce pieces may open a bracket that produce closes", function()
    local rules = { { "A", function()
      lsys.nproduce("[+F")
      return lsys.produce("A]")
    end } }
    assert.equal("[+FA]", H.derive("A", rules, 1))
  end)

  it("produce still works after the function derived another model", function()
    local other = lsys.lsystem { axiom = "X", productions = "X --> XY" }
    local rules = { { "A(x)", function()
      local t = other:derive(3)
      return lsys.produce("A(?)", #t)
    end } }
    assert.equal("A(4)", H.derive("A(1)", rules, 1))
  end)

  it("can be used in decomposition rules", function()
    local m = lsys.lsystem { axiom = "X", productions = "X --> A(2)",
      decomposition = { { "A(x)", function(x) return lsys.produce("B(?)B", x) end } } }
    assert.equal("B(2)B", tostring(m:derive(1)))
  end)

  it("can be used in homomorphism rules", function()
    local m = lsys.lsystem { axiom = "A(2)",
      homomorphism = { { "A(x)", function(x) return lsys.produce("F(?)", x * 3) end } } }
    assert.equal("F(6)", tostring(m:expand(m:derive(0))))
  end)

  it("produce outside a rule function raises", function()
    assert.has_error(function() lsys.produce("A") end)
    assert.has_error(function() lsys.nproduce("A") end)
  end)

  it("raise when produce gets fewer values than ? marks", function()
    local rules = { { "A", function() return lsys.produce("B(?,?)", 1) end } }
    assert.has_error(function() H.derive("A", rules, 1) end)
  end)

  it("raise when produce gets more values than ? marks", function()
    local rules = { { "A", function() return lsys.produce("B(?)", 1, 2) end } }
    assert.has_error(function() H.derive("A", rules, 1) end)
  end)

  it("raise when produce gets a non-number value", function()
    local rules = { { "A", function() return lsys.produce("B(?)", "x") end } }
    assert.has_error(function() H.derive("A", rules, 1) end)
  end)

  it("raise when the template is malformed, naming the template", function()
    local rules = { { "A", function() return lsys.produce("B(?") end } }
    assert.error_contains(function() H.derive("A", rules, 1) end, "B(?")
  end)
end)
