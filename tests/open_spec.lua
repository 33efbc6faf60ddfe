-- Open L-systems: ?E modules and the model option `environment` (docs/open.md): when the
-- environment is asked (before each step, of the string before it, never of the final
-- string, as cpfg's environmental pass), what a query holds, how answers replace the ?E's
-- parameters, several environments, and the errors and warnings.
local lsys = require "lsys"
local warning = require "lsys.warning"

-- The warnings fn() gives, in a list.
local function warnings (fn)
  local got, saved = {}, warning.warn
  warning.warn = function (msg) got[#got + 1] = msg end
  local ok, err = pcall(fn)
  warning.warn = saved
  assert(ok, err)
  return got
end

-- A model whose productions are `prods`, asking `env`.
local function model (axiom, prods, env, extra)
  local o = { axiom = axiom, productions = prods, environment = env, steps = 1,
              view = { angle = 90 } }
  for k, v in pairs(extra or {}) do o[k] = v end
  return lsys.lsystem(o)
end

describe("the environment of an open L-system", function ()
  it("is asked before each step about the string before it, never about the final one",
     function ()
    local asked = {}
    local m = model("A(0)", "A(x) --> F(1) ?E(0) A(x + 1)", function (queries, info)
      asked[#asked + 1] = info.step .. ":" .. #queries
      local out = {}
      for i, q in ipairs(queries) do out[i] = 10 * q.position[2] + info.step end
      return out
    end, { steps = 3 })
    assert.equal("F(1)?E(12)F(1)?E(22)F(1)?E(0)A(3)", tostring(m:derive()))
    assert.same({ "1:1", "2:2" }, asked)       -- string 0 (the axiom) holds no ?E
  end)

  it("gives each query its parameters, the turtle's frame, width, scale and the next module",
     function ()
    local got
    local m = model("#(3)F(2)?E(1,2)+(90)F(1)[?E]?E(5)", "", function (queries)
      got = queries
    end, { steps = 1 })
    m:derive()
    assert.equal(3, #got)
    local q = got[1]
    assert.equal(3, q.index)
    assert.same({ 1, 2 }, q.params)
    assert.same({ 0, 2, 0 }, q.position)
    assert.same({ 0, 1, 0 }, q.heading)
    assert.same({ -1, 0, 0 }, q.left)
    assert.same({ 0, 0, -1 }, q.up)
    assert.equal(3, q.width)
    assert.equal(1, q.scale)
    assert.equal("+", q.following)
    assert.same({ 90 }, q.following_params)
    assert.equal(7, got[2].index)
    assert.same({}, got[2].params)
    assert.equal("]", got[2].following)
    assert.near({ -1, 2, 0 }, got[2].position, 1e-12)
    assert.near({ -1, 0, 0 }, got[2].heading, 1e-12)
    assert.equal(9, got[3].index)
    assert.is_nil(got[3].following)           -- the end of the string
    assert.is_nil(got[3].following_params)
  end)

  it("replaces parameters with the answers given, keeps the others, drops extra values " ..
     "with a warning", function ()
    local m = model("?E(1,2,3)?E(4,5)?E(6)?E(7)?E", "", function ()
      return { { 10, nil, 30, n = 3 }, { false, 50 }, 60, false, { 1 } }
    end)
    local s
    local w = warnings(function () s = m:derive() end)
    assert.equal("?E(10,2,30)?E(4,50)?E(60)?E(7)?E", tostring(s))
    assert.equal(1, #w)
    assert.truthy(w[1]:find("the environment gave 1 values for the ?E of 0 parameters "
      .. "at module 5: the rest are dropped (at step 0)", 1, true), w[1])
  end)

  it("sees the ?E the homomorphism makes, and drops their answers", function ()
    local got
    local m = model("A?E(1)", "", function (queries)
      got = queries
      return { 100, 200 }
    end, { homomorphism = "A --> ?E(9)G(2)" })
    assert.equal("A?E(200)", tostring(m:derive()))
    assert.equal(2, #got)
    assert.is_nil(got[1].index)                  -- made by the homomorphism
    assert.same({ 9 }, got[1].params)
    assert.equal("G", got[1].following)
    assert.same({ 2 }, got[1].following_params)
    assert.equal(2, got[2].index)
    assert.same({ 0, 2, 0 }, got[2].position)    -- after the expansion's G(2)
  end)

  it("routes queries by their first parameter to a list of environments", function ()
    local seen = {}
    local function env (name)
      return function (queries)
        local out = {}
        for i, q in ipairs(queries) do
          local t = {}
          for k, x in ipairs(q.params) do t[k] = ("%g"):format(x) end
          seen[#seen + 1] = name .. "(" .. table.concat(t, ",") .. ")"
          out[i] = { q.params[1] * 2 }
        end
        return out
      end
    end
    local obj = { answer = function (self) return { self.k, self.k } end, k = 7 }
    local m = model("?E(2,5)?E(1,3,4)?E(3,0)?E(1,1)", "", { env "a", env "b", obj })
    assert.equal("?E(2,10)?E(1,6,4)?E(3,7)?E(1,2)", tostring(m:derive()))
    assert.same({ "a(3,4)", "a(1)", "b(5)" }, seen)
  end)

  it("runs in a lone step, and a model's step counts from the string given", function ()
    local m = model("", "", function (queries, info)
      assert.is_nil(info.step)
      return { #queries }
    end)
    assert.equal("?E(1)F", tostring(m:step("?E(0)F")))
  end)

  it("says what is wrong with the option, an answer or an environment that fails",
     function ()
    assert.error_contains(function () model("F", "", 3) end,
      "option 'environment' must be a function (queries, info) -> answers, an object with "
      .. "an answer method, or a list of those (got number)")
    assert.error_contains(function () model("F", "", { function () end, 2 }) end,
      "option 'environment': entry 2 of the list is not an environment")
    local m = model("?E(1)", "", function () return { "x" } end)
    assert.error_contains(function () m:derive() end,
      "model: environment: answer 1 must be a number or a list of numbers, got string")
    m = model("?E(1)", "", function () return { 0 / 0 } end)
    assert.error_contains(function () m:derive() end,
      "environment: answer 1, value 1: a finite number expected, got")
    m = model("?E(1)", "", function () error("no light here", 0) end)
    assert.error_contains(function () m:derive() end, "model: environment: no light here")
    m = model("?E(1)", "", function () return 5 end)
    assert.error_contains(function () m:derive() end,
      "environment: the answers must be a table (a list, one entry a query), got number")
    m = model("?E(1)?E(4)", "", { function () end })
    assert.error_contains(function () m:derive() end,
      "model: environment: ?E module 2: its first parameter must be the number of one of "
      .. "the 1 environments, got 4")
  end)

  it("warns once when the string has ?E modules and the model no environment", function ()
    local m = lsys.lsystem { axiom = "A", productions = "A --> ?E(1)A", steps = 3 }
    local w = warnings(function () m:derive() end)
    assert.equal(1, #w)
    assert.truthy(w[1]:find("the string has ?E modules but the model has no "
      .. "environment: they keep the parameters the rules give them", 1, true))
    m = lsys.lsystem { axiom = "A", productions = "A --> ?E(1)A", steps = 3,
                       environment = false }
    assert.same({}, warnings(function () m:derive() end))
  end)

  it("fills ?P in the same pass, and ?E answers are float32 in a float32 model", function ()
    local m = model("F(1)?P(0,0,0)?E(0)", "", function () return { 0.1 } end,
                    { numbers = "float32" })
    local s = m:derive()
    local _, x, y = s:module(2)
    assert.equal(0, x); assert.equal(1, y)
    local _, e = s:module(3)
    assert.equal(string.unpack("f", string.pack("f", 0.1)), e)
  end)
end)

describe("examples/open", function ()
  it("ulam.lua grows Ulam's crystal: cpfg's string with vlab's honda81 program", function ()
    local m = dofile("examples/open/ulam.lua")
    local s = m:derive()
    -- the counts of the string cpfg derives from 07-Open/01-ulam-collide (16 steps, honda81):
    -- 344 segments, 692 sensors still waiting, every one at VIGOR (none left at 1 or 0)
    assert.equal(4143, #s)
    assert.same({ ["+"] = 345, ["-"] = 345, [";"] = 340, ["?E"] = 692, F = 344, ["["] = 692,
                  ["]"] = 692, f = 692, ["|"] = 1 }, s:counts())
    assert.equal(692, #tostring(s):gsub("[^?]", ""))
    assert.truthy(tostring(s):find("^%[F%[%+f%?E%(0%.5%)%]%[%-f%?E%(0%.5%)%];F%[%+;F%["))
    -- the collisions stop growth: without an environment every sensor grows
    local closed = lsys.lsystem { axiom = m.axiom, steps = 6, env = m.env,
      productions = "f ?E(x) --> ;F A", decomposition = "A --> [+f ?E(1)][-f ?E(1)]f ?E(1)",
      environment = false }
    local open = dofile("examples/open/ulam.lua")
    open.steps = 6
    assert.is_true(closed:derive():count("F") > open:derive():count("F"))
  end)
end)
