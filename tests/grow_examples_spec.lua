-- The incremental growth examples: examples/grow/davison.lua (the paper's five
-- trees), examples/grow/leafy.lua (leaves as a surface) and examples/grow/side_by_side.lua
-- (one plant as an L-system and as limbs).
local lsys = require "lsys"
local core = require "lsys.core"
local H = require "tests.helper"

local DIR = "examples/grow/"

describe("examples/grow/davison.lua", function ()
  local D = dofile(DIR .. "davison.lua")

  it("grows five trees of the paper's rules: capped, brown with age, leafy at the top", function ()
    local w = D.world { ticks = 60 }:grow()
    assert.equal(1044, w:count())                 -- seed 3
    local per, leafy, brown = {}, 0, 0
    for _, l in ipairs(w:limbs()) do
      local root = l
      while root:parent() do root = root:parent() end
      per[root:id()] = (per[root:id()] or 0) + 1
      if l:has_leaves() then
        leafy = leafy + 1
        assert.is_true(l:level() >= 6)
      end
      local c = l:color()
      if l:age() > 20 then
        assert.is_true(c[1] > c[2], "old limbs are brown")
        brown = brown + 1
      end
      assert.is_true(l:level() <= 10)
      assert.is_true(l:length() < 1.1)
    end
    local sizes = {}
    for _, n in pairs(per) do sizes[#sizes + 1] = n end
    table.sort(sizes)
    -- each child is counted as it is made: a tree stops at 256 + 2 (the last limb that saw
    -- 256 makes its two); one of these does, the others stop for their levels first
    assert.same({ 148, 199, 209, 231, 257 }, sizes)
    assert.is_true(leafy > 100, leafy)
    assert.is_true(brown > 100, brown)
    -- while they grow, the new shoots are green
    local young, green = D.world { ticks = 12 }:grow(), 0
    for _, l in ipairs(young:limbs()) do
      if l:age() <= 1 then
        local c = l:color()
        assert.is_true(c[2] > c[1], "new shoots are green")
        green = green + 1
      end
    end
    assert.is_true(green > 0)
  end)

  it("grows the paper's scene-wide cap: 256 limbs in all before spawning", function ()
    local w = D.world { ticks = 60, cap = "scene" }:grow()
    assert.equal(258, w:count())                  -- seed 3: the last spawner saw 256
    local sum = 0
    for p = 1, 5 do sum = sum + w:count(p) end
    assert.equal(258, sum)
    assert.error_matches(function () D.world { cap = "forest" } end,
      "davison: cap is \"tree\" or \"scene\", not forest")
  end)

  it("draws three young trees like its golden image", function ()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local w = D.world { trees = 3, ticks = 40 }:grow()
    H.golden("grow_davison", lsys.render(w:scene(), { width = 200, height = 120 }))
  end)
end)

describe("examples/grow/leafy.lua", function ()
  local D = dofile(DIR .. "leafy.lua")

  it("gives one tree the cpfg leaf surface, 162 vertices a leaf", function ()
    local w = D.world { ticks = 60 }:grow()
    local leaves, limbs = 0, w:count()
    for _, l in ipairs(w:limbs()) do leaves = leaves + l:leaves() end
    assert.equal(209, limbs)                      -- seed 3, one tree
    assert.equal(4 * 108, leaves)
    assert.equal(limbs * 16 + leaves * 162, w:scene().nvertices)
    assert.equal(limbs * 16 + leaves * 256, w:scene().ntriangles)
    w = D.world { ticks = 60, precision = { 2, 2 } }:grow()
    assert.equal(limbs * 16 + leaves * 2 * 9, w:scene().nvertices)
  end)

  it("draws it like its golden image", function ()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local w = D.world { ticks = 40 }:grow()
    H.golden("grow_leafy", lsys.render(w:scene(), { width = 160, height = 160 }))
  end)
end)

describe("examples/grow/side_by_side.lua", function ()
  local S = dofile(DIR .. "side_by_side.lua")

  it("gives the same plant both ways at every step", function ()
    for steps = 0, 12 do
      local a, b = S.lsystem_tips(S.lsystem(steps)), S.world_tips(S.world(steps))
      assert.same(a, b, "step " .. steps)
    end
    assert.equal(31, #S.world_tips(S.world(12)))
  end)
end)
