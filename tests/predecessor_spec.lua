-- A predecessor of several modules (cpfg's strict predecessor, `,,,@o(s);;; --> *` in vlab's
-- mesotonic model): the modules must follow one another exactly (symbol and parameter
-- count, nothing skipped, not even ignored modules), the rule rewrites them all, and the
-- contexts stand around the whole. The expected strings are cpfg's (one step, `ignore: +`,
-- run with cpfg -g -str; docs/cpfg.md, "cpfg as a reference").
require "tests.helper"
local lsys = require "lsys"

local function step (axiom, rules, opts)
  local o = { axiom = axiom, productions = rules, ignore = "+" }
  for k, v in pairs(opts or {}) do o[k] = v end
  return tostring(lsys.lsystem(o):derive(1))
end

describe("a predecessor of several modules, as cpfg", function ()
  it("rewrites consecutive modules with one rule", function ()
    assert.equal("XXCX", step("ABAB CAB", { "AB --> X" }))
    assert.equal("X+CX", step("AB+CAB", { "AB --> X" }))
    assert.equal("A+B", step("A+B", { "AB --> X" }))       -- ignored modules are not skipped
    assert.equal("AB(1)", step("AB(1)", { "AB --> X" }))   -- parameter counts must match
    assert.equal("A", step("A", { "AB --> X" }))           -- the string ends first
    assert.equal("XYD", step("BCBD", { "BC --> X", "B --> Y" }))
    assert.equal("X", step("AB", { "AB --> X", "A --> Y", "B --> Z" }))
    assert.equal("XC", step("ABC", { "AB --> X", "BC --> Y" }))   -- left to right
    assert.equal("QBC", step("ABC", { "A --> Q", "AB --> X" }))   -- the first rule wins
    assert.equal("XY", step("ABBB", { "ABB --> X", "B --> Y" }))
  end)

  it("binds the parameters of every module, with conditions", function ()
    assert.equal("X(3)A(3)C", step("A(1)B(2)A(3)C", { "A(x)B(y) --> X(x+y)" }))
    assert.equal("A(1)X(5)A(4)",
                 step("A(1)A(2)A(3)A(4)", { "A(x)A(y) : x+y>4 --> X(x+y)" }))
  end)

  it("matches contexts around the whole predecessor", function ()
    assert.equal("AXDBCD", step("ABCDBCD", { "A < BC > D --> X" }))
    assert.equal("XZY", step("XABY", { "X < AB > Y --> Z" }))
    assert.equal("CB", step("AB", { "A > B --> C", "AB --> D" }))
  end)

  it("works in function rules and among weighted rules", function ()
    local m = lsys.lsystem {
      axiom = "Q A(1)B(2)C(3)",
      productions = { { "Q < A(x) B(y) > C(z)", function (x, y, z)
        return lsys.produce("X(?,?,?)", x, y, z)
      end } },
    }
    assert.equal("QX(1,2,3)C(3)", tostring(m:derive(1)))
    -- BC and B compete; whichever is chosen, the string reads as whole choices
    local s = step("BCBCBCBC", { "BC --> X : 1", "B --> Y : 1" }, { seed = 3 })
    assert.truthy(s:match("^[XY C]+$"))
    assert.equal(8, #s:gsub("X", "BC"):gsub("Y", "B"))
  end)

  it("rewrites modules side by side in the homomorphism, drawn and expanded", function ()
    local m = lsys.lsystem { axiom = "F(1,0) #(2) F(3,1) #(4) F(5,0) A #(9)", steps = 0,
      homomorphism = { "F(a, n) #(w) : n == 0 --> !(w) F(a)", "F(a, n) --> !(0.5) F(a)",
                       "A --> F(7,0) #(8)" }, max_depth = { homomorphism = 2 } }
    -- the first F takes its #; the second's condition fails, so its # stands for itself;
    -- the F before A has none after it; what A becomes has no modules after it in the
    -- string (the F it makes does not take A's #(9))
    assert.equal("!(2)F(1)!(0.5)F(3)#(4)!(0.5)F(5)!(0.5)F(7)#(8)#(9)",
                 tostring(m:expand(m:derive())))
    local widths = {}
    for _, r in m:interpret(m:derive()):records() do
      if r.kind == "segment" then widths[#widths + 1] = r.w0 end
    end
    assert.same({ 2, 0.5, 0.5, 0.5 }, widths)
  end)

  it("is refused where it cannot work, naming the rule", function ()
    local function err (o)
      local ok, msg = pcall(function ()
        return lsys.lsystem(o):derive(1)
      end)
      assert.is_false(ok)
      return msg
    end
    assert.matches("rule 2 'A B %-%-> X' %(entry 1 of decomposition%): a predecessor of several "
      .. "modules is for productions and the homomorphism only, not for the decomposition",
      err { axiom = "AB", productions = { "A --> A" }, decomposition = { "A B --> X" } })
    assert.matches("rule 1 'A %[B %-%-> X' %(entry 1 of productions%): a bracket cannot be in a "
      .. "predecessor at character 3", err { axiom = "AB", productions = { "A [B --> X" } })
    assert.matches("module 2 of the predecessor cannot be a bracket, a cut or a sub%-L%-system "
      .. "module", err { axiom = "AB", productions = { "A % --> X" } })
  end)
end)
