-- What a new user trips over (issue 19): each item of the issue that is a behaviour of the
-- library has its spec here, under the item's number.
local H = require "tests.helper"
local lsys = require "lsys"

local function errof (f, ...)
  local ok, msg = pcall(f, ...)
  assert.is_false(ok, "expected an error")
  return tostring(msg)
end

describe("issue 19 §8: the number of steps is bounded", function ()
  local m = lsys.lsystem { axiom = "A", productions = "A --> B" }

  it("refuses math.huge and 1e300 steps with a clear error, at once", function ()
    assert.matches("derive: infinitely many steps is more than the limit of 10000000",
                   errof(m.derive, m, math.huge), 1, true)
    assert.matches("derive: 1e+300 steps is more than the limit of 10000000",
                   errof(m.derive, m, 1e300), 1, true)
    assert.matches("option 'steps' is inf, more than the limit of 10000000",
                   errof(lsys.lsystem, { axiom = "A", steps = math.huge }), 1, true)
    m.steps = 1e8
    assert.matches("derive: 100000000 steps is more than the limit of 10000000",
                   errof(m.derive, m), 1, true)
    m.steps = 1
    assert.equal("B", tostring(m:derive()))
  end)

  it("says so on the command line", function ()
    local out, code = H.sh(H.BIN .. " derive --steps 100000000 examples/default.lua")
    assert.equal(1, code)
    assert.matches("100000000 steps is more than the limit of 10000000", out, 1, true)
  end)
end)

describe("issue 19 §9: long quoted text is elided in messages", function ()
  local big = H.rep("F(1)", 200000)

  it("keeps a message about a 800 kB axiom short and shows where it is wrong", function ()
    local e = errof(lsys.lsystem, { axiom = big .. "F(" .. H.rep("F(1)", 100) })
    assert.is_true(#e < 400, #e .. " characters")
    assert.matches("^axiom 'F%(1%)F%(1%)", e)
    assert.matches("F%(F%(1%)", e)                          -- the unclosed F( is shown
    assert.matches("unbalanced parentheses after 'F' at character 800001", e, 1, true)
  end)

  it("keeps a message about a long rule short, at definition and in a step", function ()
    local e = errof(lsys.lsystem, { axiom = "A", productions = "A --> " .. big .. "F(" })
    assert.is_true(#e < 400, #e .. " characters")
    assert.matches("F%(1%)F%(' %(line 1 of productions%): unbalanced parentheses: '%(' "
                   .. "without '%)' at character 800008", e)
    local m = lsys.lsystem { axiom = "A", productions = "A --> " .. big .. "F(x)" }
    e = errof(m.derive, m, 1)
    assert.is_true(#e < 500, #e .. " characters")
    assert.matches("unknown name 'x'", e, 1, true)
  end)

  it("quotes short text whole", function ()
    local q = require("lsys.warning").quote
    assert.equal("A --> B", q("A --> B", 3))
    local s = H.rep("a", 1000) .. "X" .. H.rep("b", 1000)
    local shown = q(s, 1001)
    assert.truthy(shown:find("aaaXbbb", 1, true), shown)
    assert.matches("^a+%.%.%.a+Xb+%.%.%.b+$", shown)
    assert.is_true(#shown < 240)
  end)
end)

describe("issue 19 §12: a model that fails leaves no module names behind", function ()
  it("lets later models use names after one failed with too many", function ()
    local names = {}
    for i = 1, 2100 do names[#names + 1] = "m" .. i end
    local list = table.concat(names, " ")
    for _ = 1, 3 do       -- each attempt fails the same way; none poisons the state
      local e = errof(lsys.lsystem, { modules = list, axiom = list })
      assert.matches("too many module names (limit is 2047)", e, 1, true)
      local m = lsys.lsystem { axiom = "Q", productions = "Q --> R[S]T" }
      assert.equal("R[S]T", tostring(m:derive(1)))
    end
    -- names of a model that was made stay: its strings still read them
    local ok = lsys.lsystem { modules = "leaf stem", axiom = "leaf stem" }
    local s = ok:derive(0)
    errof(lsys.lsystem, { modules = list, axiom = list })
    assert.equal("leaf", (s:module(1)))
    assert.equal("stem", (s:module(2)))
    assert.equal(2, #ok:derive(0))
  end)
end)

describe("issue 19 §13: a rule that derives its own model", function ()
  it("gets one clear message for its own model", function ()
    local m
    m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
      m:derive(1)
      return lsys.produce("B")
    end } } }
    local e = errof(m.derive, m, 1)
    assert.matches("rule 1 'A' %(entry 1 of productions%), module 1: .*a rule called derive on "
                   .. "the model it belongs to$", e)
    assert.equal(1, select(2, e:gsub("rule 1 'A'", "")))
  end)

  it("gets one clear message, not a C stack overflow, for fresh copies of itself", function ()
    local function make ()
      local m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
        make():derive(1)
        return lsys.produce("B")
      end } } }
      return m
    end
    local e = errof(function () return make():derive(1) end)
    assert.matches("derivations nested 32 deep: a rule function derives a model whose rules "
                   .. "derive again", e, 1, true)
    assert.is_nil(e:find("rule 1 'A'", 1, true))      -- said once, not 32 times
    assert.is_nil(e:find("stack overflow", 1, true))
    -- and the state is fine afterwards
    assert.equal("B", tostring(lsys.lsystem { axiom = "A", productions = "A --> B" }:derive(1)))
  end)
end)
