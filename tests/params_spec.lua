-- A model's tunable parameters (the model option `params`, lsys.params): declared with their
-- ranges, read by the rules as env names, set through m.params with checks, and reported to
-- on_param callbacks.
local lsys = require "lsys"

local function model (extra)
  local o = { axiom = "A(1)", steps = 3,
              productions = "A(x) : leaf --> A(x * R) L\nA(x) --> A(x * R)",
              params = { R = { 2, min = 1, max = 3, step = 0.5, label = "growth" },
                         leaf = { true }, shape = { "round", choices = { "round", "flat" } } } }
  for k, v in pairs(extra or {}) do o[k] = v end
  return lsys.lsystem(o)
end

describe("params", function ()
  it("gives the rules their defaults, and the next derivation a new value", function ()
    local m = model()
    assert.equal("A(8)LLL", tostring(m:derive()))
    m.params.R = 1.26                           -- rounded to the step: 1.5
    assert.equal(1.5, m.params.R)
    assert.equal("A(3.375)LLL", tostring(m:derive()))
    m.params.leaf = false
    assert.equal("A(3.375)", tostring(m:derive()))
    m.params.shape = "flat"
    assert.equal("flat", m.params.shape)
  end)

  it("walks its names in order, and gives each declaration", function ()
    local m = model()
    local seen = {}
    for k, v in pairs(m.params) do seen[#seen + 1] = k .. "=" .. tostring(v) end
    assert.same({ "R=2", "leaf=true", "shape=round" }, seen)
    assert.equal(3, #m.params)
    local d = m:param("R")
    assert.same({ name = "R", kind = "number", default = 2, min = 1, max = 3, step = 0.5,
                  label = "growth" }, d)
    d.min = 0                                    -- a copy
    assert.equal(1, m:param("R").min)
    assert.is_nil(m:param("nope"))
  end)

  it("tells on_param callbacks each change", function ()
    local m, got = model(), {}
    m:on_param(function (k, v) got[#got + 1] = k .. "=" .. tostring(v) end)
    m.params.R = 3
    m.params.leaf = false
    assert.same({ "R=3", "leaf=false" }, got)
    assert.has_error(function () lsys.lsystem { axiom = "A" }:on_param(print) end,
                     "on_param: the model has no params")
  end)

  it("keeps the caller's env table as it was", function ()
    local env = { K = 1 }
    local m = model { env = env }
    assert.same({ K = 1 }, env)
    assert.equal(1, m.env.K)
    assert.equal(2, m.env.R)
  end)

  it("refuses bad values and bad declarations, naming the parameter", function ()
    local m = model()
    assert.has_error(function () m.params.R = 5 end, "params.R: 5 is outside 1 .. 3")
    assert.has_error(function () m.params.R = "x" end, "params.R: a number expected, got x")
    assert.has_error(function () m.params.leaf = 1 end,
                     "params.leaf: true or false expected, got 1")
    assert.has_error(function () m.params.shape = "square" end,
                     "params.shape: 'square' is not one of its choices")
    assert.has_error(function () m.params.Q = 1 end, "params: the model has no parameter 'Q'")
    local function bad (p, env)
      local ok, err = pcall(lsys.lsystem, { axiom = "A", params = p, env = env })
      assert.is_false(ok)
      return err
    end
    assert.matches("params: R: a number needs min and max", bad { R = { 1 } }, 1, true)
    assert.matches("params: R: the default 5 is outside min 1 .. max 2",
                   bad { R = { 5, min = 1, max = 2 } }, 1, true)
    assert.matches("params: R: unknown field 'mx'", bad { R = { 1, min = 0, mx = 2 } }, 1, true)
    assert.matches("params: s: a string needs a list of choices", bad { s = { "a" } }, 1, true)
    assert.matches("params: R is in env too", bad({ R = { true } }, { R = 1 }), 1, true)
    assert.matches("params: '1x' is not a name", bad { ["1x"] = { true } }, 1, true)
  end)
end)
