-- The cut symbol % (the cpfg guide, Appendix A; docs/manual.md §6.6).
local H = require "tests.helper"
local lsys = require "lsys"

describe("cut %", function()
  it("is still followed by its branch in the step that produced it", function()
    assert.equal("F[%FF]F", H.derive("F[AFF]F", "A --> %", 1))
  end)

  it("removes itself and the rest of its branch in the next step, keeping the ]", function()
    assert.equal("F[]F", H.derive("F[AFF]F", "A --> %", 2))
  end)

  it("removes nested branches inside the cut part", function()
    assert.equal("F[B%[G]F]F", H.derive("F[BA[G]F]F", "A --> %", 1))
    assert.equal("F[B]F", H.derive("F[BA[G]F]F", "A --> %", 2))
  end)

  it("removes to the end of the string when there is no unmatched ]", function()
    assert.equal("F", H.derive("FAFF[G]F", "A --> %", 2))
  end)

  it("cuts a % that is already in the axiom in the first step", function()
    assert.equal("F[]F", H.derive("F[%FF]F", "X --> Y", 1))
  end)

  it("rewrites the modules before the cut and the modules after its branch", function()
    assert.equal("G[G]G", H.derive("F[F%FF]F", "F --> G", 1))
  end)

  it("keeps the modules that follow the cut branch's closing bracket", function()
    assert.equal("F[G[]H]I", H.derive("F[G[%X]H]I", "Z --> Z", 1))
  end)

  it("does not call the rules of the modules that are cut off", function()
    local calls = 0
    local s = H.derive("F[%BB]FB", { { "B", function()
      calls = calls + 1
      return lsys.produce("C")
    end } }, 1)
    assert.equal("F[]FC", s)
    assert.equal(1, calls)
  end)

  it("cuts a % made by decomposition in the next step", function()
    local m = lsys.lsystem { axiom = "F[A]F", productions = "X --> X", decomposition = "A --> %B" }
    assert.equal("F[%B]F", tostring(m:derive(1)))
    assert.equal("F[]F", tostring(m:derive(2)))
  end)

  it("is prevented by a production that rewrites %", function()
    assert.equal("F[XFF]F", H.derive("F[%FF]F", "% --> X", 1))
  end)

  it("cuts in the same step as other modules are rewritten", function()
    assert.equal("F[%C]F", H.derive("F[AB]F", "A --> %\nB --> C", 1))
    assert.equal("F[]F", H.derive("F[AB]F", "A --> %\nB --> C", 2))
  end)
end)
