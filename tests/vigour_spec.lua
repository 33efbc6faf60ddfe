-- lsys.environment.vigour: the Borchert-Honda allocation of a tree's vigour among its buds
-- from the light they sense (Palubicki et al. 2009 §4.3), read from the string's brackets;
-- the values are worked out by hand below.
local lsys = require "lsys"

-- The parameters of the module at index i of s, as a list.
local function params (s, i)
  local t = { s:module(i) }
  table.remove(t, 1)
  return t
end

-- The index of the n-th module named `name` in s.
local function find (s, name, n)
  n = n or 1
  for i, m in s:modules() do
    if m == name then
      n = n - 1
      if n == 0 then return i end
    end
  end
  error("no " .. name)
end

local function near (want, got, tol)
  assert.equal(#want, #got)
  for k = 1, #want do
    assert(math.abs(want[k] - got[k]) <= (tol or 1e-12),
           string.format("value %d: %s expected, got %s", k, want[k], got[k]))
  end
end

-- A bud in the light (y >= 2) senses 1, one lower 0.5.
local function sense (queries)
  local out = {}
  for i, q in ipairs(queries) do out[i] = q.position[2] >= 2 - 1e-9 and 1 or 0.5 end
  return out
end

-- One internode bearing a lateral bud (to the left, at height 1) and the apex (height 2).
local AXIOM = "F(1) I ?E(2, 0, 0, 0, 0) [ +(90) F(1) B ?E(0, 0, 0, 0, 0, 0) ] "
           .. "F(1) A ?E(1, 0, 0, 0, 0, 0)"

local function grown (env, axiom)
  local m = lsys.lsystem { axiom = axiom or AXIOM, steps = 1, environment = env,
                           view = { angle = 90 } }
  return m:derive()
end

describe("lsys.environment.vigour", function ()
  it("shares alpha times the light out at the branching by eq. 2 (lambda 1/2)", function ()
    local s = grown(lsys.environment.vigour { sense = sense })
    -- Q at the base 0.5 + 1; v = 2 x 1.5 = 3; at the branching 0.5 Ql / (0.5 Qm + 0.5 Ql)
    -- = 1/3 of it to the lateral bud
    near({ 2, 1.5, 3, 1, 1 }, params(s, find(s, "?E", 1)))
    local b = params(s, find(s, "?E", 2))
    near({ 0, 0.5, 1 }, { b[1], b[2], b[3] })
    near({ -1, 0, 0 }, { b[4], b[5], b[6] }, 1e-9)        -- its heading: no V, no tropism
    near({ 1, 1, 2, 0, 1, 0 }, params(s, find(s, "?E", 3)), 1e-9)
  end)

  it("favours the main axis with lambda above 1/2, and scales by alpha", function ()
    local s = grown(lsys.environment.vigour { sense = sense, lambda = 0.75, alpha = 1 })
    -- v = 1.5; lateral: 1.5 x 0.25 x 0.5 / (0.75 x 1 + 0.25 x 0.5) = 3/14
    assert.near(1.5 * 0.125 / 0.875, params(s, find(s, "?E", 2))[3], 1e-12)
    assert.near(1.5 - 1.5 * 0.125 / 0.875, params(s, find(s, "?E", 3))[3], 1e-12)
  end)

  it("says what each internode bears: its light, apices and internodes", function ()
    local s = grown(lsys.environment.vigour { sense = sense },
      "I ?E(2, 0, 0, 0, 0) [ +(90) I ?E(2, 0, 0, 0, 0) A ?E(1, 0, 0, 0, 0, 0) ] "
      .. "F(2) I ?E(2, 0, 0, 0, 0) A ?E(1, 0, 0, 0, 0, 0)")
    -- the base bears both apices (0.5 + 1), the lateral's 0.5 and the main's 1; alpha 2
    near({ 2, 1.5, 3, 2, 3 }, params(s, find(s, "?E", 1)))
    near({ 2, 0.5, 1, 1, 1 }, params(s, find(s, "?E", 2)))
    near({ 2, 1, 2, 1, 1 }, params(s, find(s, "?E", 4)))
  end)

  it("turns a shoot towards the sensed direction and the tropism", function ()
    local s = grown(lsys.environment.vigour {
      sense = function (qs)
        local out = {}
        for i in ipairs(qs) do out[i] = { 1, 1, 0, 0 } end
        return out
      end, xi = 1, tropism = { 0, 0, 1 } },
      "A ?E(1, 0, 0, 0, 0, 0)")
    local r = 1 / math.sqrt(3)                      -- (0, 1, 0) + (1, 0, 0) + (0, 0, 1)
    near({ 1, 1, 2, r, r, r }, params(s, 2), 1e-12)
  end)

  it("asks the sense about buds and apices only, as ?E of four parameters", function ()
    local seen = {}
    grown(lsys.environment.vigour { sense = function (qs)
      for i, q in ipairs(qs) do seen[i] = #q.params .. "@" .. q.index end
      return { 1, 1 }
    end })
    assert.same({ "4@8", "4@12" }, seen)
  end)

  it("shares out within each plant of a stand", function ()
    local function plant ()
      return lsys.lsystem { axiom = AXIOM, steps = 1, view = { angle = 90 } }
    end
    local _, strings = lsys.stand({ { model = plant() }, { model = plant(), at = { 5, 0, 0 } } },
      { environment = lsys.environment.vigour { sense = sense } })
    for p = 1, 2 do
      near({ 2, 1.5, 3, 1, 1 }, params(strings[p], find(strings[p], "?E", 1)))
    end
  end)

  it("says what is wrong", function ()
    assert.has_error(function () lsys.environment.vigour {} end,
      "lsys.environment.vigour: sense must be an environment (a function, or an object "
      .. "with an answer method) giving each bud its light")
    assert.has_error(function () lsys.environment.vigour { sense = sense, lamda = 1 } end,
      "lsys.environment.vigour: unknown option 'lamda'")
    assert.has_error(function () lsys.environment.vigour { sense = sense, lambda = 2 } end,
      "lsys.environment.vigour: lambda must be a number from 0 to 1")
    local ok, err = pcall(grown, lsys.environment.vigour { sense = sense }, "A ?E(5)")
    assert.is_false(ok)
    assert.matches("?E module 2: its first parameter says what it is: 0 a bud, 1 an apex, "
                   .. "2 an internode (got 5)", err, 1, true)
    ok, err = pcall(grown, lsys.environment.vigour { sense = function () return { -1 } end },
                    "A ?E(1, 0, 0, 0, 0, 0)")
    assert.is_false(ok)
    assert.matches("sense: answer 1: a light (a finite number >= 0) expected, got -1", err, 1,
                   true)
  end)
end)

-- The segments of a scene whose end lies at x < 0, and all of them.
local function sides (sc)
  local left, all = 0, 0
  for _, r in sc:records() do
    if r.kind == "segment" then
      all = all + 1
      if r.p1[1] < 0 then left = left + 1 end
    end
  end
  return left, all
end

describe("the self-organizing tree (examples/open/selforg.lua)", function ()
  it("grows the same tree on one thread and on two, and sheds its shaded branches",
     function ()
    local m = dofile("examples/open/selforg.lua")
    m.steps = 10
    local s = m:derive()
    assert.same({ 864, 823, 351, 525 }, { s:count("I"), s:count("L"), s:count("A"),
                                          s:count("B") })
    m.threads = 1
    assert.equal(tostring(s), tostring(m:derive()))
    -- without shedding the same tree keeps more internodes
    local keep = dofile("examples/open/selforg.lua")
    keep.steps, keep.env.SHED = 10, 0
    assert.is_true(keep:derive():count("I") > 864)
  end)

  it("grows away from a wall", function ()
    local free, wall = dofile("examples/open/selforg.lua"), dofile("examples/open/wall.lua")
    free.steps, wall.steps = 12, 12
    local l, n = sides(free:interpret(free:derive()))
    assert.is_true(l > 0.3 * n and l < 0.7 * n, l .. " of " .. n)
    l, n = sides(wall:interpret(wall:derive()))
    assert.is_true(l < 0.05 * n, l .. " of " .. n)        -- the wall stands at x = -2.5
  end)

  it("stays small under an older neighbour", function ()
    local _, strings = dofile("examples/open/neighbour.lua")
    local alone = dofile("examples/open/selforg.lua")
    alone.axiom = "W(7)"
    local n, a = strings[2]:count("I"), alone:derive():count("I")
    assert.is_true(n < a / 3, n .. " under the neighbour, " .. a .. " alone")
  end)
end)
