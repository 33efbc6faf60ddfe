-- Parametric productions: conditions, parameter expressions, env, ran/nran, number printing.
local H = require "tests.helper"

local derive = H.derive

describe("conditions", function()
  it("a rule applies only where its condition is true", function()
    assert.equal("A(1)B(2)", derive("A(1)A(2)", "A(x) : x > 1 --> B(x)", 1))
  end)

  it("the first applicable rule in declaration order wins", function()
    assert.equal("B", derive("A(2)", "A(x) : x > 0 --> B\nA(x) : x > 1 --> C", 1))
    assert.equal("C", derive("A(2)", "A(x) : x > 1 --> C\nA(x) : x > 0 --> B", 1))
  end)

  it("an unconditional rule declared first shadows a later conditional one", function()
    assert.equal("BB", derive("A(1)A(5)", "A(x) --> B\nA(x) : x > 2 --> C", 1))
  end)

  it("a failed condition falls through to the next rule", function()
    assert.equal("CB", derive("A(1)A(5)", "A(x) : x > 2 --> B\nA(x) --> C", 1))
  end)

  it("a condition that is the number 0 is false and any other number is true (cpfg)", function()
    assert.equal("A(0)B", derive("A(0)A(2)", "A(x) : x --> B", 1))
  end)

  it("a condition that is nil is false", function()
    assert.equal("A(1)", derive("A(1)", "A(x) : nil --> B", 1))
  end)

  it("can combine formals with and/or/not", function()
    assert.equal("XA(1,1)A(2,1)",
      derive("A(2,2)A(1,1)A(2,1)", "A(x,y) : x == y and not (x < 2) --> X", 1))
  end)

  it("can read context formals", function()
    assert.equal("B(1)C(0)B(9)C(9)",
      derive("B(1)C(5)B(9)C(2)", "B(x) < C(y) : x > y --> C(x)\nB(x) < C(y) --> C(0)", 1))
  end)
end)

describe("parameter expressions", function()
  it("compute successor parameters from the formals", function()
    assert.equal("B(7,12)C(0.75)", derive("A(3,4)", "A(x,y) --> B(x+y, x*y) C(x/y)", 1))
  end)

  it("can be any Lua arithmetic (^, %, unary minus, parentheses)", function()
    assert.equal("B(1024,1,-6)", derive("A(2)", "A(x) --> B(x^10, 7 % (x+1), -(x*3))", 1))
  end)

  it("integer division results print as integers", function()
    assert.equal("B(3)", derive("A(7)", "A(x) --> B(x // 2)", 1))
  end)

  it("can use math functions", function()
    assert.equal("B(3,1)", derive("A(9)", "A(x) --> B(math.sqrt(x), math.floor(x/5))", 1))
  end)

  it("a successor module may have no parameters even when the predecessor has some", function()
    assert.equal("FB(2)", derive("A(2)", "A(x) --> F B(x)", 1))
  end)

  it("the same formal can be used in several successor modules", function()
    assert.equal("F(2)[+(2)A(1)]", derive("A(2)", "A(x) --> F(x) [ +(x) A(x/2) ]", 1))
  end)
end)

describe("parameter count", function()
  it("B(x) matches only B with exactly one parameter", function()
    assert.equal("BCB(1,2)", derive("BB(1)B(1,2)", "B(x) --> C", 1))
  end)

  it("B without parameters matches only B without parameters", function()
    assert.equal("CB(1)B(1,2)", derive("BB(1)B(1,2)", "B --> C", 1))
  end)

  it("rules for different counts of the same name coexist", function()
    assert.equal("XY(1)Z(3)", derive("BB(1)B(1,2)", "B --> X\nB(a) --> Y(a)\nB(a,b) --> Z(a+b)", 1))
  end)
end)

describe("env", function()
  it("names in env are visible in expressions", function()
    assert.equal("A(2)", derive("A(1)", "A(x) --> A(x * R)", 1, { env = { R = 2 } }))
  end)

  it("names in env are visible in conditions", function()
    assert.equal("BA(9)", derive("A(1)A(9)", "A(x) : x < LIMIT --> B", 1, { env = { LIMIT = 5 } }))
  end)

  it("a change to model.env between derivations is seen by the next derivation", function()
    local m = H.model("A(1)", "A(x) --> A(x * R)", { env = { R = 2 } })
    assert.equal("A(4)", tostring(m:derive(2)))
    m.env.R = 3
    assert.equal("A(9)", tostring(m:derive(2)))
  end)

  it("replacing model.env with a new table is seen by the next derivation", function()
    local m = H.model("A(1)", "A(x) --> A(x * R)", { env = { R = 2 } })
    m.env = { R = 10 }
    assert.equal("A(100)", tostring(m:derive(2)))
  end)

  it("a formal parameter shadows an env name", function()
    assert.equal("B(1)", derive("A(1)", "A(R) --> B(R)", 1, { env = { R = 2 } }))
  end)

  it("env functions can be called from expressions", function()
    assert.equal("B(6)", derive("A(3)", "A(x) --> B(double(x))", 1,
      { env = { double = function(v) return 2 * v end } }))
  end)
end)

describe("ran and nran", function()
  local rules = "A --> B(ran(1)) C(nran(10, 2))"
  local axiom = H.rep("A", 50)

  it("give the same numbers for the same seed", function()
    local a = H.derive(axiom, rules, 1, { seed = 7 })
    local b = H.derive(axiom, rules, 1, { seed = 7 })
    assert.equal(a, b)
  end)

  it("give the same numbers when the same model derives again (derive reseeds)", function()
    local m = H.model(axiom, rules, { seed = 7 })
    assert.equal(tostring(m:derive(1)), tostring(m:derive(1)))
  end)

  it("give different numbers for a different seed", function()
    assert.not_equal(H.derive(axiom, rules, 1, { seed = 7 }),
                     H.derive(axiom, rules, 1, { seed = 8 }))
  end)

  it("follow a changed model.seed", function()
    local m = H.model(axiom, rules, { seed = 7 })
    local a = tostring(m:derive(1))
    m.seed = 8
    assert.equal(H.derive(axiom, rules, 1, { seed = 8 }), tostring(m:derive(1)))
    assert.not_equal(a, tostring(m:derive(1)))
  end)

  it("ran(x) is in [0, x) and not constant", function()
    local s = H.model(H.rep("A", 1000), "A --> B(ran(3))", { seed = 1 }):derive(1)
    local lo, hi, sum = math.huge, -math.huge, 0
    for _, _, x in s:modules() do
      lo, hi, sum = math.min(lo, x), math.max(hi, x), sum + x
    end
    assert.is_true(lo >= 0)
    assert.is_true(hi < 3)
    assert.is_true(hi - lo > 2.5)
    assert.near(1.5, sum / 1000, 5 * math.sqrt(0.75 / 1000))   -- sd of a U(0,3) mean
  end)

  it("nran(mean, sd) has the given mean and standard deviation", function()
    local n = 4000
    local s = H.model(H.rep("A", n), "A --> B(nran(10, 2))", { seed = 3 }):derive(1)
    local sum, sq = 0, 0
    for _, _, x in s:modules() do sum, sq = sum + x, sq + x * x end
    local mean = sum / n
    local sd = math.sqrt(sq / n - mean * mean)
    assert.near(10, mean, 5 * 2 / math.sqrt(n))
    assert.near(2, sd, 0.15)
  end)

  it("can be used in conditions", function()
    local s = H.model(H.rep("A", 2000), "A : ran(1) < 0.25 --> B\nA --> C", { seed = 5 }):derive(1)
    assert.equal(2000, s:count("B") + s:count("C"))
    assert.near(500, s:count("B"), H.binomial_tol(2000, 0.25, 5))
  end)
end)

  it("draw once per use: one random expression twice in a successor gives two numbers", function()
    -- Regression: the compiler listed identical expression text once, so
    -- B(ran(10))C(ran(10)) gave B = C in every module.
    local s = H.model(H.rep("A", 200), "A --> B(ran(10)) C(ran(10))", { seed = 2 }):derive(1)
    local b, c, same = {}, {}, 0
    for _, name, x in s:modules() do
      if name == "B" then b[#b + 1] = x else c[#c + 1] = x end
    end
    assert.equal(200, #b)
    assert.equal(200, #c)
    for i = 1, 200 do if b[i] == c[i] then same = same + 1 end end
    assert.equal(0, same)
  end)

  it("call a user's function at each use, and reuse an expression that calls nothing", function()
    local n = 0
    local env = { tick = function() n = n + 1; return n end }
    assert.equal("B(1)C(2)", derive("A", "A --> B(tick()) C(tick())", 1, { env = env }))
    assert.equal("D(2)E(2)F(2)", derive("A(7)", "A(x) --> D(x//3) E(x//3) F(x // 3)", 1))
  end)

describe("number printing", function()
  it("prints 0.1 + 0.2 with every digit needed to read it back", function()
    assert.equal("B(0.30000000000000004)", derive("A", "A --> B(0.1 + 0.2)", 1))
  end)

  it("prints 1/3 as the shortest text that reads back exactly", function()
    assert.equal("B(0.3333333333333333)", derive("A", "A --> B(1/3)", 1))
  end)

  it("prints 2^53 as an integer", function()
    assert.equal("B(9007199254740992)", derive("A", "A --> B(2^53)", 1))
  end)

  it("prints computed integral floats without a fraction", function()
    assert.equal("B(6,-1)", derive("A", "A --> B(1.5 * 4, 0.5 - 1.5)", 1))
  end)
end)

describe("ABOP section 1.10 sample derivation", function()
  -- omega: B(2)A(4,4); p1..p4 from ABOP p. 43
  local rules = [[
    A(x,y) : y <= 3 --> A(x*2, x+y)
    A(x,y) : y > 3 --> B(x) A(x/y, 0)
    B(x) : x < 1 --> C
    B(x) : x >= 1 --> B(x-1)
  ]]

  it("gives the strings of the book for five steps", function()
    assert.same({
      "B(2)A(4,4)",
      "B(1)B(4)A(1,0)",
      "B(0)B(3)A(2,1)",
      "CB(2)A(4,3)",
      "CB(1)A(8,7)",
      "CB(0)B(8)A(1.1428571428571428,0)",
    }, H.steps(H.model("B(2)A(4,4)", rules), 5))
  end)
end)

describe("ABOP fig. 2.6 style monopodial tree (constants in env)", function()
  local env = { r1 = 0.9, r2 = 0.6, a0 = 45, a2 = 45, d = 137.5, wr = 0.707 }
  local rules = [[
    A(l,w) --> !(w) F(l) [ &(a0) B(l*r2, w*wr) ] /(d) A(l*r1, w*wr)
    B(l,w) --> !(w) F(l) [ -(a2) C(l*r2, w*wr) ] C(l*r1, w*wr)
    C(l,w) --> !(w) F(l) [ +(a2) B(l*r2, w*wr) ] B(l*r1, w*wr)
  ]]

  it("gives the exact strings after one and two steps", function()
    local m = H.model("A(1,10)", rules, { env = env })
    assert.equal("!(10)F(1)[&(45)B(0.6,7.069999999999999)]/(137.5)A(0.9,7.069999999999999)",
      tostring(m:derive(1)))
    assert.equal("!(10)F(1)[&(45)!(7.069999999999999)F(0.6)[-(45)C(0.36,4.998489999999999)]"
      .. "C(0.54,4.998489999999999)]/(137.5)!(7.069999999999999)F(0.9)"
      .. "[&(45)B(0.54,4.998489999999999)]/(137.5)A(0.81,4.998489999999999)",
      tostring(m:derive(2)))
  end)

  it("counts 1, 3 and 7 F segments after 1, 2 and 3 steps", function()
    local m = H.model("A(1,10)", rules, { env = env })
    assert.same({ 1, 3, 7 },
                { m:derive(1):count("F"), m:derive(2):count("F"), m:derive(3):count("F") })
  end)
end)

describe("bad values from rule expressions", function()
  it("a parameter expression that gives a string raises naming the rule", function()
    assert.error_contains(function() H.derive("FA(1)", "A(x) --> B('a')", 1) end,
      "A(x) --> B('a')")
  end)

  it("a condition that gives a string raises naming the rule", function()
    assert.error_contains(function() H.derive("FA(1)", "A(x) : 'yes' --> B", 1) end,
      "A(x) : 'yes' --> B")
  end)

  it("a parameter expression that gives nil raises naming the rule", function()
    assert.error_contains(function() H.derive("FA(1)", "A(x) --> B(undefined_name)", 1) end,
      "A(x) --> B(undefined_name)")
  end)

  it("a condition that raises names the rule and the module", function()
    assert.error_contains(function()
      H.derive("FFA(1)", "A(x) : x < t --> B", 1, { env = { t = {} } })
    end, "A(x) : x < t --> B", "module 3")
  end)

  it("a name that is neither a formal nor in env raises naming the rule and the name", function()
    assert.error_contains(function()
      H.model("A(1)", "B --> C\nA(x) : x < nothing --> B"):derive(1)
    end, "A(x) : x < nothing --> B", "line 2", "nothing")
  end)

  it("a name added to env after the model was made is found", function()
    local m = H.model("A(1)", "A(x) : x < later --> B")
    m.env.later = 5
    assert.equal("B", tostring(m:derive(1)))
  end)

  it("an infinite parameter value raises naming the rule", function()
    assert.error_contains(function() H.derive("A(1)", "A(x) --> B(x/0)", 1) end,
      "A(x) --> B(x/0)", "module 1")
  end)
end)
