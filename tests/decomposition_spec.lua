-- Decomposition rules: applied after every derivation step, to a fixed point within max_depth.
local H = require "tests.helper"
local lsys = require "lsys"

local function model (t)
  t.axiom = t.axiom or "X"
  t.productions = t.productions or "X --> A"
  return lsys.lsystem(t)
end

describe("decomposition", function()
  it("is not applied to the axiom", function()
    local m = model { axiom = "D", productions = "X --> Y", decomposition = "D --> EE" }
    assert.equal("D", tostring(m:derive(0)))
  end)

  it("is applied after the first step, also to modules no production rewrote", function()
    local m = model { axiom = "D", productions = "X --> Y", decomposition = "D --> EE" }
    assert.equal("EE", tostring(m:derive(1)))
  end)

  it("is applied to the successors of the step", function()
    local m = model { decomposition = "A --> B[C]" }
    assert.equal("B[C]", tostring(m:derive(1)))
  end)

  it("is applied after every step, and its results stay in the string", function()
    local m = model { productions = "X --> A\nB --> BA", decomposition = "A --> B" }
    assert.same({ "X", "B", "BB", "BBBB" }, H.steps(m, 3))
  end)

  it("is applied after m:step too", function()
    local m = model { decomposition = "A --> B" }
    assert.equal("B", tostring(m:step(lsys.lstring("X"))))
  end)

  it("with max depth 1 decomposes the step's result once", function()
    local m = model { decomposition = "A --> B\nB --> C", max_depth = { decomposition = 1 } }
    assert.equal("B", tostring(m:derive(1)))
  end)

  it("with max depth 2 decomposes the decomposed modules again", function()
    local m = model { decomposition = "A --> B\nB --> C", max_depth = { decomposition = 2 } }
    assert.equal("C", tostring(m:derive(1)))
  end)

  it("stops at a fixed point before max depth", function()
    local m = model { decomposition = "A --> B\nB --> C", max_depth = { decomposition = 8 } }
    assert.equal("C", tostring(m:derive(1)))
  end)

  it("stops a recursive decomposition at max depth", function()
    local m = model { decomposition = "A --> AB", max_depth = { decomposition = 3 } }
    assert.equal("ABBB", tostring(m:derive(1)))
  end)

  it("has max depth 1 by default (cpfg)", function()
    local m = model { decomposition = "A --> B\nB --> C" }
    assert.equal("B", tostring(m:derive(1)))
  end)

  it("computes parameters", function()
    local m = model { productions = "X --> A(3)", decomposition = "A(x) --> B(x*2) [ C(x+1) ]" }
    assert.equal("B(6)[C(4)]", tostring(m:derive(1)))
  end)

  it("reads context from the string before decomposition", function()
    local m = model { productions = "X --> AB", decomposition = "A > B --> Y\nB --> C",
                      max_depth = { decomposition = 4 } }
    assert.equal("YC", tostring(m:derive(1)))
  end)

  it("uses the model's ignore list for its contexts", function()
    local m = model { productions = "X --> A+B", ignore = "+", decomposition = "A > B --> Y" }
    assert.equal("Y+B", tostring(m:derive(1)))
  end)

  it("gives the next step's productions the decomposed modules", function()
    -- step 1: X --> A, decomposed to B; step 2 sees B (no rule), not A (which would give Z)
    local m = model { productions = "X --> A\nA --> Z", decomposition = "A --> B" }
    assert.equal("B", tostring(m:derive(1)))
    assert.equal("B", tostring(m:derive(2)))
  end)

  it("warns once at the depth limit unless depth_warnings says no", function()
    local warning = require "lsys.warning"
    local saved, got = warning.warn, {}
    warning.warn = function (msg) got[#got + 1] = msg end
    local ok, err = pcall(function ()
      for _, dw in ipairs { true, false, { decomposition = false }, { homomorphism = false } } do
        local m = model { decomposition = "A --> B\nB --> C", depth_warnings = dw }
        assert.equal("B", tostring(m:derive(1)))
        assert.equal("B", tostring(m:derive(1)))
      end
    end)
    warning.warn = saved
    assert(ok, err)
    assert.equal(4, #got)          -- once per derive of the first and the last model
    assert.matches("the decomposition depth limit stopped at modules that have rules", got[1])
    assert.error_matches(function () model { depth_warnings = 1 } end,
      "option 'depth_warnings' must be a boolean or a table %(decomposition, homomorphism%)")
    assert.error_matches(function () model { depth_warnings = { decomp = false } } end,
      "depth_warnings: bad entry 'decomp' %(decomposition = or homomorphism = true or false%)")
  end)
end)

describe("decomposition with short conditions", function()
  -- a module whose rules' conditions (of one or two operations) are all false is copied
  -- without choosing (derive.c, nonefast): the same strings as the rules as Lua functions
  it("gives the strings of the same rules written as functions", function()
    local axiom = H.rep("A(2.5)B(0)A(0.5)C", 400)
    local text = lsys.lsystem { axiom = axiom, productions = "A(t) --> A(t + 0.75)",
      decomposition = "A(t) : t - 1 > 0 --> B(t - 1)A(t - 1)\nB(x) : x > 3 --> C" }
    local P = lsys.produce
    local lua = lsys.lsystem { axiom = axiom, productions = "A(t) --> A(t + 0.75)",
      decomposition = {
        { "A(t)", function (t) if t - 1 > 0 then return P("B(?)A(?)", t - 1, t - 1) end end },
        { "B(x)", function (x) if x > 3 then return P("C") end end },
      } }
    for n = 1, 4 do
      local a, b = tostring(text:derive(n)), tostring(lua:derive(n))
      assert.is_true(a == b, "step " .. n .. " differs")
    end
    assert.equal("B(2.25)B(2)A(2)B(0)B(0.25)A(1)CB", tostring(text:derive(2)):sub(1, 32))
  end)
end)

describe("decomposition that rewrites nothing in most steps", function()
  -- when no rule of the expression machine applies, the string is not copied (derive.c,
  -- firstchange); when one does, the modules before it are copied at once: the same strings
  -- as the rules as Lua functions, which are tried module by module
  it("gives the strings of the same rules written as functions", function()
    local axiom = H.rep("B(1)", 3000) .. "A(0)" .. H.rep("B(2)", 3000)
    local prods = "A(t) --> A(t + 0.25)\nB(x) --> B(x + 1)"
    local text = lsys.lsystem { axiom = axiom, productions = prods,
      decomposition = "A(t) : (t - 1) * 2 > 0.1 --> [B(t - 1)]A(t - 1)" }
    local lua = lsys.lsystem { axiom = axiom, productions = prods,
      decomposition = {
        { "A(t)", function (t)
            if (t - 1) * 2 > 0.1 then return lsys.produce("[B(?)]A(?)", t - 1, t - 1) end
          end },
      } }
    local changed = 0
    for n = 1, 12 do
      local a, b = tostring(text:derive(n)), tostring(lua:derive(n))
      assert.is_true(a == b, "step " .. n .. " differs")
      if a:find("[", 1, true) then changed = changed + 1 end
    end
    assert.equal(8, changed)                   -- from step 5 on (t = 1.25 > 1.05)
    assert.equal("B(12)", tostring(text:derive(11)):sub(1, 5))
    assert.truthy(tostring(text:derive(5)):find("B(6)[B(0.25)]A(0.25)B(7)", 1, true))
  end)
end)
