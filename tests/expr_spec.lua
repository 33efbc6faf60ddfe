-- Rule expressions run on the C expression machine when they can; these
-- specs check that it gives exactly what the Lua closure gives.
local lsys = require "lsys"

-- derives with the machine and with Lua closures only; returns both texts
local function both (opts, n)
  local a = lsys.lsystem(opts)
  local b = lsys.lsystem(opts)
  b.lua_expressions = true
  local sa, sb = tostring(a:derive(n)), tostring(b:derive(n))
  assert.is_true(a._rules:hasvm(0), "the first rule should run on the machine")
  assert.is_false(b._rules:hasvm(0))
  return sa, sb
end

describe("the expression machine", function()
  local exprs = {
    "x + 2 * y - 1", "x / y", "x % 3", "-x % 3", "x % -3", "x // 2", "2 ^ x", "-x ^ 2",
    "(x + y) * (x - y)", "abs(-x) + floor(y / 3) + ceil(x / 4)", "sqrt(x) + exp(1) + log(y)",
    "sin(x) + cos(y) + tan(1)", "atan(1, 2) + atan(0.5)", "min(x, y, 3) + max(x, y)",
    "math.fmod(x, 3) + math.sqrt(16)", "K * x + pi",
  }
  for _, e in ipairs(exprs) do
    it("computes " .. e .. " as Lua does", function()
      local a, b = both({ axiom = "A(5,7)", env = { K = 1.5 },
                          productions = "A(x,y) --> B(" .. e .. ")A(x+1,y+2)" }, 4)
      assert.equal(b, a)
      assert.truthy(a:match("^B%("))
    end)
  end

  local conds = {
    "x > 6", "x >= 6 and y < 12", "x == 6 or y == 7", "not (x < 7)", "x ~= 6",
    "x - 6", "true", "false", "x > 5 and (y > 100 or x < 8)",
  }
  for _, c in ipairs(conds) do
    it("decides the condition " .. c .. " as Lua does", function()
      local a, b = both({ axiom = "A(5,7)", productions = "A(x,y) : " .. c ..
                          " --> B A(x+1,y+2)\nA(x,y) --> C A(x+1,y+2)" }, 5)
      assert.equal(b, a)
    end)
  end

  it("draws ran and nran from the same generator in the same order", function()
    local a, b = both({ axiom = "A(0)", seed = 7,
      productions = "A(x) : ran(1) > 0.3 --> B(ran(10), nran(5, 2))A(x+1)\n" ..
                    "A(x) --> C(ran())A(x+1)" }, 12)
    assert.equal(b, a)
    assert.truthy(a:match("B%(") and a:match("C%("))
  end)

  it("leaves expressions it cannot run to Lua", function()
    local m = lsys.lsystem { axiom = "A(2)", env = { f = function (v) return v * 10 end },
                             productions = "A(x) --> B(f(x), #'abc')" }
    assert.equal("B(20,3)", tostring(m:derive(1)))
    assert.is_false(m._rules:hasvm(0))
  end)

  it("reports a non-finite value as an error naming the rule", function()
    local m = lsys.lsystem { axiom = "A(0)", productions = "A(x) --> B(1 / x)" }
    local ok, err = pcall(m.derive, m, 1)
    assert.is_false(ok)
    assert.truthy(err:find("rule 1 'A(x) --> B(1 / x)'", 1, true))
    assert.truthy(err:find("module 1: value 1 is infinite, not a finite number", 1, true))
  end)

  it("sees env changes made between derivations", function()
    local m = lsys.lsystem { axiom = "A(1)", env = { K = 2 }, productions = "A(x) --> A(x*K)" }
    assert.equal("A(2)", tostring(m:derive(1)))
    m.env.K = 3
    assert.equal("A(3)", tostring(m:derive(1)))
  end)
end)
