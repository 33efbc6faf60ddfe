-- Sub-L-systems: ?(id, scale) ... $ switch the production set (the cpfg guide, Appendix A).
local lsys = require "lsys"

local function model (axiom, extra)
  local t = {
    axiom = axiom,
    productions = "A --> C\nS --> ?(2,0.5) A $",
    sub = { [2] = { productions = "A --> B" }, [3] = { productions = "A --> D" } },
  }
  for k, v in pairs(extra or {}) do t[k] = v end
  return lsys.lsystem(t)
end

describe("sub-L-systems", function()
  it("use the sub-L-system's productions between ?(id, scale) and $", function()
    assert.equal("C?(2,0.5)B$C", tostring(model("A?(2,0.5)A$A"):derive(1)))
  end)

  it("keep ? and $ with their parameters in the string", function()
    local s = model("A?(2,0.5)A$A"):derive(3)
    assert.equal(1, s:count("?"))
    assert.equal(1, s:count("$"))
    assert.same({ "?", 2, 0.5, n = 3 }, table.pack(s:module(2)))
  end)

  it("leave a module unchanged when only the main L-system has a rule for it", function()
    local m = model("F?(2,1)F$F", { productions = "F --> FF\nA --> C" })
    assert.equal("FF?(2,1)F$FF", tostring(m:derive(1)))
  end)

  it("return to the enclosing production set after a nested $", function()
    assert.equal("C?(2,1)B?(3,1)D$B$C", tostring(model("A?(2,1)A?(3,1)A$A$A"):derive(1)))
  end)

  it("apply inside branches between ? and $", function()
    assert.equal("?(2,1)[B]B$C", tostring(model("?(2,1)[A]A$A"):derive(1)))
  end)

  it("start applying in the step after a production creates ?(id, scale)", function()
    local m = model("S")
    assert.equal("?(2,0.5)A$", tostring(m:derive(1)))
    assert.equal("?(2,0.5)B$", tostring(m:derive(2)))
  end)

  it("use the sub-L-system's own ignore list for contexts", function()
    local m = lsys.lsystem {
      axiom = "B+A?(2,1)B+A$",
      productions = "B < A --> Y",
      sub = { [2] = { productions = "B < A --> X", ignore = "+" } },
    }
    assert.equal("B+A?(2,1)B+X$", tostring(m:derive(1)))
  end)

  it("evaluate parametric sub-L-system rules", function()
    local m = lsys.lsystem {
      axiom = "A(1)?(2,1)A(1)$",
      productions = "A(x) --> A(x+1)",
      sub = { [2] = { productions = "A(x) --> A(x*10)" } },
    }
    assert.equal("A(3)?(2,1)A(100)$", tostring(m:derive(2)))
  end)
end)

-- Checked against cpfg (vlab 9bf820d): a cut stops at the $ closing its sub-L-system, and an
-- L-system already active is not entered again ("Recursive call to Sub-L-system").
describe("sub-L-systems and cut, as cpfg", function()
  local function sub (axiom, rules, n)
    return tostring(lsys.lsystem { axiom = axiom, sub = { [2] = { productions = rules } } }
      :derive(n))
  end

  it("stop a cut inside a sub-L-system at its $, which stays", function()
    assert.equal("B?(2,1)C$E", sub("B?(2,1)CAD$E", "A --> %", 2))
    -- a nested ?( ... $ inside the cut part is cut whole; the next $ stops it
    assert.equal("B$F", tostring(lsys.lsystem { axiom = "B%C?(2,1)A$E$F",
      sub = { [2] = { productions = "A --> H" } } }:derive(1)))
    -- a ] that comes first stops it as before
    assert.equal("B[?(2,1)C]$E", sub("B[?(2,1)CA]$E", "A --> %", 2))
  end)

  it("stop a cut at a $ even outside any sub-L-system, as cpfg does", function()
    assert.equal("B$E", tostring(lsys.lsystem { axiom = "B%CA$E" }:derive(2)))
  end)

  it("refuse to enter an L-system that is active already", function()
    local ok, err = pcall(sub, "B?(2,1)CAD$E", "A --> ?(0,1)F$", 2)
    assert.is_false(ok)
    assert.truthy(tostring(err):find("recursive call to sub-L-system 0 (module 4): it is "
      .. "active already (0 is the main L-system)", 1, true), tostring(err))
    ok, err = pcall(sub, "B?(2,1)CA?(2,1)D$$E", "A --> B", 1)
    assert.is_false(ok)
    assert.truthy(tostring(err):find("recursive call to sub-L-system 2 (module 5): it is "
      .. "active already", 1, true), tostring(err))
    -- the same id again after its $ is not recursion
    assert.equal("B?(2,1)CB$?(2,1)B$", sub("B?(2,1)CA$?(2,1)A$", "A --> B", 1))
  end)
end)

