-- Stochastic productions: relative weights after the successor, one seeded generator per model.
local H = require "tests.helper"

local AB = "A --> B : 1\nA --> C : 1"

describe("stochastic choice", function()
  it("gives the same string for the same seed", function()
    local axiom = H.rep("A", 64)
    assert.equal(H.derive(axiom, AB, 1, { seed = 1 }), H.derive(axiom, AB, 1, { seed = 1 }))
  end)

  it("gives the same string when one model derives twice", function()
    local m = H.model(H.rep("A", 64), AB, { seed = 11 })
    assert.equal(tostring(m:derive(1)), tostring(m:derive(1)))
  end)

  it("gives a different string for a different seed (64 fair choices)", function()
    local axiom = H.rep("A", 64)
    assert.not_equal(H.derive(axiom, AB, 1, { seed = 1 }), H.derive(axiom, AB, 1, { seed = 2 }))
  end)

  it("only ever produces one of the alternatives", function()
    local s = H.model(H.rep("A", 200), AB, { seed = 4 }):derive(1)
    assert.equal(200, #s)
    assert.equal(200, s:count("B") + s:count("C"))
    assert.is_true(s:count("B") > 0 and s:count("C") > 0)
  end)

  it("treats weights as relative: 1 : 3 gives about 25% and 75%", function()
    local n = 4000
    local s = H.model(H.rep("A", n), "A --> B : 1\nA --> C : 3", { seed = 2024 }):derive(1)
    assert.equal(n, s:count("B") + s:count("C"))
    assert.near(n * 0.25, s:count("B"), H.binomial_tol(n, 0.25, 5))
  end)

  it("treats weights 0.5 : 1.5 like 1 : 3", function()
    local n = 4000
    local s = H.model(H.rep("A", n), "A --> B : 0.5\nA --> C : 1.5", { seed = 99 }):derive(1)
    assert.near(n * 0.25, s:count("B"), H.binomial_tol(n, 0.25, 5))
  end)

  it("chooses with three alternatives in proportion to their weights", function()
    local n = 6000
    local rules = "A --> B : 1\nA --> C : 2\nA --> D : 3"
    local s = H.model(H.rep("A", n), rules, { seed = 5 }):derive(1)
    assert.near(n / 6, s:count("B"), H.binomial_tol(n, 1 / 6, 5))
    assert.near(n / 3, s:count("C"), H.binomial_tol(n, 1 / 3, 5))
    assert.near(n / 2, s:count("D"), H.binomial_tol(n, 1 / 2, 5))
  end)

  it("never chooses an alternative of weight 0", function()
    local n = 20000
    local s = H.model(H.rep("A", n), "A --> B : 0\nA --> C : 1", { seed = 1 }):derive(1)
    assert.equal(0, s:count("B"))
    s = H.model(H.rep("A", n), "A --> B : 1\nA --> C : 0", { seed = 1 }):derive(1)
    assert.equal(0, s:count("C"))
  end)

  it("takes weights from env expressions", function()
    local n = 4000
    local s = H.model(H.rep("A", n), "A --> B : p\nA --> C : 1 - p",
                      { seed = 3, env = { p = 0.25 } }):derive(1)
    assert.near(n * 0.25, s:count("B"), H.binomial_tol(n, 0.25, 5))
  end)

  it("takes weights from the formal parameters", function()
    local n = 4000
    local s = H.model(H.rep("A(3)", n), "A(x) --> B : x\nA(x) --> C : 1", { seed = 3 }):derive(1)
    assert.near(n * 0.75, s:count("B"), H.binomial_tol(n, 0.75, 5))
  end)

  it("a computed negative weight raises naming the rule", function()
    assert.error_contains(function()
      H.derive("A", "A --> B : w\nA --> C : 1", 1, { env = { w = -1 } })
    end, "A --> B : w")
  end)

  it("never chooses an alternative whose condition fails", function()
    local n = 4000
    local rules = "A(x) : x < 0 --> N : 1000\nA(x) --> B : 1\nA(x) --> C : 1"
    local s = H.model(H.rep("A(1)", n), rules, { seed = 3 }):derive(1)
    assert.equal(0, s:count("N"))
    assert.near(n / 2, s:count("B"), H.binomial_tol(n, 0.5, 5))
  end)

  it("never chooses an alternative whose context fails", function()
    local n = 4000
    local rules = "X < A --> N : 1000\nA --> B : 1\nA --> C : 3"
    local s = H.model(H.rep("A", n), rules, { seed = 8 }):derive(1)
    assert.equal(0, s:count("N"))
    assert.near(n / 4, s:count("B"), H.binomial_tol(n, 0.25, 5))
  end)

  it("lets the context-free alternative alone decide where the context fails", function()
    local rules = "X < A --> N : 1\nA --> B : 1"
    local s = H.model("XA" .. H.rep("A", 20), rules, { seed = 1 }):derive(1)
    assert.equal("X", (s:module(1)))
    assert.equal(21, s:count("N") + s:count("B"))
    assert.is_true(s:count("N") <= 1)
    assert.equal(H.rep("B", 20), tostring(s:sub(3, -1)))
  end)

  it("keeps a sequence of steps reproducible", function()
    local rules = "A --> AB : 1\nA --> A[C] : 1\nB --> BA : 2\nB --> * : 1"
    local a = H.model("A", rules, { seed = 12 }):derive(8)
    local b = H.model("A", rules, { seed = 12 }):derive(8)
    assert.equal(tostring(a), tostring(b))
  end)

  it("derive(n) equals n calls of step from derive(0) with the same seed", function()
    local rules = "A --> AB : 1\nA --> A[C] : 1\nB --> BA : 2\nB --> * : 1"
    local m = H.model("A", rules, { seed = 12 })
    local via_steps = H.steps(m, 6)
    assert.equal(tostring(m:derive(6)), via_steps[7])
  end)

  it("reseeds with srand: from a start hook, from a rule function, not elsewhere", function()
    local lsys = require "lsys"
    local axiom = H.rep("A", 64)
    local want = H.derive(axiom, AB, 1, { seed = 9 })
    local m = H.model(axiom, AB, { seed = 1 })
    m.start = function (self) self:srand(9) end       -- the derivation follows seed 9
    assert.equal(want, tostring(m:derive(1)))
    assert.equal(want, tostring(m:derive(1)))
    -- a rule function reseeds mid-step: both Rs then draw the same first number
    local r = lsys.lsystem { axiom = "S R S R", productions = {
      { "S", function () lsys.srand(3); return lsys.produce("S") end },
      "R --> R(ran(1))" } }
    local x, y = tostring(r:derive(1)):match("^SR%(([%d.e-]+)%)SR%(([%d.e-]+)%)$")
    assert.truthy(x and x == y)
    assert.error_matches(function () lsys.srand(1) end, "lsys.srand called outside a derivation")
    assert.error_matches(function () m:srand("x") end, "srand: a number expected, got string")
  end)

  it("chooses among weighted function rules and rule strings by weight", function()
    local lsys = require "lsys"
    local calls = 0
    local m = lsys.lsystem { axiom = H.rep("A", 2000), seed = 5, productions = {
      { "A", function () calls = calls + 1; return lsys.produce("B(1)") end, weight = 1 },
      { "A", function () return lsys.produce("C") end, weight = 3 },
      "A --> D : 0" } }
    local s = m:derive(1)
    assert.equal(2000, s:count("B") + s:count("C"))
    assert.equal(0, s:count("D"))
    assert.is_true(math.abs(s:count("B") - 500) < 80, tostring(s:count("B")))   -- 1 : 3
    assert.equal(2000, calls)            -- every applicable function runs before the choice
    assert.equal(tostring(s), tostring(m:derive(1)))
    -- a function that does not produce is not an alternative
    local n = lsys.lsystem { axiom = H.rep("A", 50), seed = 2, productions = {
      { "A", function () end, weight = 100 }, "A --> C : 1" } }
    assert.equal(H.rep("C", 50), tostring(n:derive(1)))
    assert.error_matches(function ()
      lsys.lsystem { productions = { { "A", function () end, weight = -1 } } }
    end, "productions: entry 1: weight must be a number >= 0")
    assert.error_matches(function ()
      lsys.lsystem { productions = { { "A", function () end, wieght = 1 } } }
    end, "productions: entry 1: unknown key 'wieght' in {pattern, function, weight = w}")
  end)
end)

describe("the generator as docs/manual.md §10 gives it in full", function()
  local GAMMA = 0x9E3779B97F4A7C15
  local function mix (z)   -- SplitMix64's output function, on Lua's 64-bit integers
    z = (z ~ (z >> 30)) * 0xBF58476D1CE4E5B9
    z = (z ~ (z >> 27)) * 0x94D049BB133111EB
    return z ~ (z >> 31)
  end
  -- The j-th number (from 1) of module i (from 0) in step k's productions, seed s.
  local function number (s, k, i, j)
    local b = mix(mix(s + GAMMA) ~ mix((4 * k) ~ 0x5851F42D4C957F2D))
    return (mix(mix(b + (i + 1) * GAMMA) + j * GAMMA) >> 11) * 2.0 ^ -53
  end

  it("gives the numbers of the manual's example, B's ran(1) first, then the choice", function()
    local m = H.model("AAAA", "A --> B(ran(1)) : 1\nA --> C : 1", { seed = 7 })
    local want = {}
    for i = 0, 3 do
      -- two equal weights: B when u times 2 stays below 1
      want[#want + 1] = number(7, 1, i, 2) * 2 < 1 and ("B(%.17g)"):format(number(7, 1, i, 1))
        or "C"
    end
    local s = m:derive(1)
    assert.equal("CB(0.2575682584307001)B(0.5273343562147776)B(0.7335161708747543)", tostring(s))
    for i = 1, 4 do
      local name, x = s:module(i)
      assert.equal(want[i], x and ("B(%.17g)"):format(x) or name)
    end
  end)

  it("draws step 2 from the stream of 4k with k = 2", function()
    local m = H.model("A", "A --> B(ran(1))A", { seed = 3 })
    local s = m:derive(2)            -- B(step 1's) then step 2: B(ran) A -> B B(ran) A
    assert.equal(number(3, 1, 0, 1), select(2, s:module(1)))
    assert.equal(number(3, 2, 1, 1), select(2, s:module(2)))
  end)
end)

describe("cpfg's generator (random = \"cpfg\")", function()
  local lsys = require "lsys"
  -- erand48 from cpfg's start {0x330E, 0, 0} (glibc, the same numbers everywhere)
  local E48 = { "0.17082803610628972", "0.7499019804849638", "0.09637165562356742" }

  local function run (opts, n, lua)
    opts.random = opts.random or "cpfg"
    local m = lsys.lsystem(opts)
    m.lua_expressions = lua or nil
    return tostring(m:derive(n)), m
  end

  it("draws ran as cpfg's erand48, in the order of the string, whatever the seed", function()
    local s = run({ axiom = "A A A", productions = "A --> B(ran(1))", seed = 5 }, 1)
    local t = run({ axiom = "A A A", productions = "A --> B(ran(1))", seed = 6 }, 1)
    assert.equal(("B(%s)B(%s)B(%s)"):format(E48[1], E48[2], E48[3]), s)
    assert.equal(s, t)             -- cpfg's seed: chooses productions; ran starts from srand(0)
  end)

  it("starts nran with the mean (cpfg's nrand flag starts at 10) and srand(a) as cpfg",
     function()
    local s = run({ axiom = "A", productions = "A --> N(nran(3, 1)) R(ran(1))" }, 1)
    assert.equal("N(3)R(" .. E48[1] .. ")", s)
    local m = lsys.lsystem { axiom = "A", productions = "A --> R(ran(1))", random = "cpfg",
                             start = function (mm) mm:srand(42) end }
    assert.equal("R(0.7445250000610066)", tostring(m:derive(1)))
  end)

  it("evaluates a chosen rule's successor after every alternative's condition", function()
    -- cpfg tries each production (condition, probability), chooses, then evaluates the
    -- chosen successor: the closure (replayed) and the machine (run in two parts) agree
    local rules = "A : ran(1) < 0.9 --> B(ran(1)) : 1\nA : ran(1) < 0.9 --> C(ran(1)) : 2"
    local a = run({ axiom = ("A"):rep(30), productions = rules, seed = 3 }, 1)
    local b = run({ axiom = ("A"):rep(30), productions = rules, seed = 3 }, 1, true)
    assert.equal(a, b)
    -- the first module: the conditions draw E48[1] and E48[2], the successor E48[3]
    assert.equal(E48[3], a:match("^[BC]%(([^)]*)%)"))
  end)

  it("is the same on any number of threads (a step runs in order on one)", function()
    local opts = { axiom = ("A[F]"):rep(5000), seed = 9,
                   productions = "A --> A B(ran(1)) : 1\nA --> C(nran(0, 1)) : 1" }
    opts.threads = 1
    local one = run(opts, 2)
    opts.threads, opts.random = 4, nil
    assert.equal(one, (run(opts, 2)))
  end)

  it("refuses another name", function()
    assert.error_contains(function ()
      lsys.lsystem { axiom = "A", random = "drand48" }
    end, "option 'random' must be \"lsys\" or \"cpfg\", not \"drand48\"")
  end)
end)
