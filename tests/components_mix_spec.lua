-- Component graphs and L-systems mixed: a component drawing an L-system as its
-- `geometry`, and an L-system placing component plants with a module
-- (lsys.components.mix).
require "tests.helper"
local lsys = require "lsys"
local C = require "lsys.components"
local mix = require "lsys.components.mix"
local V = require "lsys.viewer"

-- The segment records of a scene: { p0, p1 } in order.
local function segments (scene)
  local out = {}
  for _, r in scene:records() do
    if r.kind == "segment" then out[#out + 1] = { r.p0, r.p1 } end
  end
  return out
end

-- A small plant: a 4 long stem with 3 twigs of 2 leaves each (6 leaves).
local function plant ()
  local leaf = C.leaf { name = "leaf", length = 0.4, width = 0.2 }
  local twig = C.tree { name = "twig", length = 1, n = 2, angle = 50 }
  twig:branch(leaf)
  local p = C.tree { name = "plant", length = 4, n = 3, angle = 60 }
  p:branch(twig)
  return p
end

describe("a component's geometry from an L-system", function()
  it("draws the L-system's modules from the instance's frame", function()
    local ls = lsys.lsystem { axiom = "F(2)&(90)F(1)" }
    local root = C.simple { name = "g", primitive = "none", translate = { 1, 0, 0 },
                            geometry = ls }
    local scene = C.scene(root)
    -- the frame: at x = 1 (x is the frame's right), heading +y, up -z: F(2) runs up,
    -- & pitches the heading towards up = -z (as cpfg's &)
    local seg = segments(scene)
    assert.equal(2, #seg)
    assert.near({ { 1, 0, 0 }, { 1, 2, 0 } }, seg[1], 1e-9)
    assert.near({ { 1, 2, 0 }, { 1, 2, -1 } }, seg[2], 1e-9)
  end)

  it("takes an Lstring too, turned with the instance", function()
    -- rotate 90 degrees about the local z (front) axis: the heading +y turns to -x
    -- or +x; the segment's length stays 3 and it starts at the origin
    local root = C.simple { primitive = "none", rotate = { 0, 0, 90 },
                            geometry = lsys.lstring("F(3)") }
    local seg = segments(C.scene(root))
    assert.equal(1, #seg)
    assert.near({ 0, 0, 0 }, seg[1][1], 1e-9)
    assert.near(3, math.abs(seg[1][2][1]), 1e-9)
    assert.near({ 0, 0 }, { seg[1][2][2], seg[1][2][3] }, 1e-9)
  end)
end)

describe("lsys.components.mix.place", function()
  -- a row along x: + turns the heading +y towards -x, so the plants stand at x = 0, -5,
  -- -10 with scales 1, 0.5 and 2
  local function row ()
    local m = lsys.lsystem {
      axiom = "P(1)+(90)f(5)-(90)P(0.5)+(90)f(5)-(90)P(2)",
      view = { line_style = "cylinder", contour_sides = 12 },   -- as C.model's view
    }
    return mix.place(m, { P = plant() })
  end

  it("places a plant after each module P(s), scaled by s, where the turtle is", function()
    local m = row()
    local s = m:derive()
    assert.equal(3, s:count("P"))
    assert.equal(3, s:count("@Di"))
    local scene = m:interpret(s)
    -- the plant alone: its stem from (0,0,0) to (0,4,0)
    local alone = C.scene(plant())
    local lo0, hi0 = alone:bounds()
    local lo, hi = scene:bounds()
    -- heights: 4 * 2 = 8 for the tallest (plus its leaves, scaled too)
    assert.near(hi0[2] * 2, hi[2], 1e-6)
    assert.near(0, lo[2], 1e-9)
    -- x extent: the tallest (scale 2) at x = -10 sets the left end, the first (scale 1)
    -- at x = 0 the right one
    assert.near(-10 + 2 * lo0[1], lo[1], 1e-6)
    assert.near(hi0[1], hi[1], 1e-6)
    -- three times the plant's triangles (the same view: cylinders, 12 sides)
    assert.equal(3 * alone.ntriangles, scene.ntriangles)
  end)

  it("puts each stem's base at the turtle's position (records of the stems)", function()
    local m = row()
    local scene = m:interpret()
    local bases = {}
    for _, r in scene:records() do
      -- the stems' first generalized-cylinder segments start on the ground
      if r.p0[2] == 0 and r.p1[2] > 0 and r.p1[1] == r.p0[1] then
        bases[#bases + 1] = math.floor(r.p0[1] * 1000 + 0.5) / 1000
      end
    end
    table.sort(bases)
    local distinct = {}
    for _, x in ipairs(bases) do
      if distinct[#distinct] ~= x then distinct[#distinct + 1] = x end
    end
    assert.same({ -10, -5, 0 }, distinct)
  end)

  it("draws every leaf of every plant with the surfaces added to the model's view", function()
    local m = row()
    local s = m:derive()
    local leaves = 0
    for name, n in pairs(s:counts()) do
      if name:sub(1, 1) == "~" then
        leaves = leaves + n
        assert.truthy(m.view.surfaces[name:sub(2)], name)
      end
    end
    assert.equal(3 * 6, leaves)
    local tree = C.expand(plant())
    assert.equal(6, tree:count("leaf"))
  end)

  it("expands a plant once per seed: P(s, seed)", function()
    local p = C.tree { name = "p", length = 2, n = 3,
                       angle = function (ctx) return 30 + 40 * ctx.random() end }
    p:branch(C.leaf { length = 0.3 })
    local m = mix.place(lsys.lsystem { axiom = "P(1,1)P(1,1)P(1,2)" }, { P = p })
    local s = m:derive()
    -- the first two pieces are the same modules, the third differs
    local i1 = {}
    for i, name in s:modules() do
      if name == "P" then i1[#i1 + 1] = i end
    end
    local n = (i1[2] - i1[1]) - 1
    local i2 = s:text(i1[1] + 1, i1[1] + n)
    local i3 = s:text(i1[2] + 1, i1[2] + n)
    assert.equal(i2, i3)
    assert.are_not.equal(i2, s:text(i1[3] + 1, #s))
  end)

  it("keeps the model's own finish and after_interpret hooks, which run first", function()
    local calls = {}
    local m = lsys.lsystem {
      axiom = "A",
      finish = function (self) calls[#calls + 1] = "finish" return self:lstring("P(1)") end,
      after_interpret = function () calls[#calls + 1] = "after" end,
    }
    mix.place(m, { P = plant() })
    local s = m:derive()
    assert.equal(1, s:count("P"))
    assert.is_true(#s > 100)
    m:interpret(s)
    assert.same({ "finish", "after" }, calls)
  end)

  it("reports the instance a module of a placed plant comes from, for picking", function()
    local m = row()
    local s = m:derive()
    local second
    for i, name in s:modules() do
      if name == "P" then
        if second == false then second = i break end
        second = false
      end
    end
    -- the second plant's `[` is after its P, then @Di, then the plant's own modules
    local inst, path = V.instance(s, second + 3)
    assert.equal("plant", inst.name)
    assert.equal("P#2/plant#1", path)
    assert.is_nil((V.instance(s, second)))        -- P itself is the L-system's
    assert.is_nil((V.instance(s, 1)))
  end)

  it("raises clear errors for bad plants, names and modules", function()
    local m = lsys.lsystem { axiom = "P(1)" }
    assert.error_contains(function () mix.place(m, { Plant = plant() }) end,
      "'Plant' is not a module name of")
    assert.error_contains(function () mix.place(m, { P = 3 }) end,
      "plant 'P' must be a component prototype", "got number")
    assert.error_contains(function () mix.place(m, { P = plant() }, { sed = 1 }) end,
      "unknown option 'sed'")
    assert.error_contains(function () mix.place({}, { P = plant() }) end, "a model expected")
    local bad = mix.place(lsys.lsystem { axiom = "F P(-1)" }, { P = plant() })
    assert.error_contains(function () bad:derive() end,
      "module 2 P: the scale must be a number > 0, got -1")
    local bad2 = mix.place(lsys.lsystem { axiom = "P(1, 0.5)" }, { P = plant() })
    assert.error_contains(function () bad2:derive() end, "the seed must be a whole number")
    local twice = mix.place(lsys.lsystem { axiom = "P" }, { P = plant() })
    assert.error_contains(function () mix.place(twice, { P = plant() }) end,
      "place all its plants in one call")
  end)

  it("a module of several characters declared with `modules`", function()
    local m = mix.place(lsys.lsystem { axiom = "Plant(0.5)", modules = "Plant" },
                        { Plant = plant() })
    local scene = m:interpret()
    local _, hi = scene:bounds()
    local _, hi0 = C.scene(plant()):bounds()
    assert.near(hi0[2] / 2, hi[2], 1e-6)
  end)
end)
