-- Arrangement by inverse kinematics (lsys.arrange; Power et al. 1999): branch paths and their
-- @J joints, the four draggers, the turtle drawing what the solver computed, stiffness from Z,
-- widths and the da Vinci rule (eqs. 4-6), pruning, grow-arrange-grow (fig. 10).
-- ctest: slow (drives the arrangement window under Xvfb)
require "tests.helper"
local lsys = require "lsys"

local function near3 (a, b, tol)
  for k = 1, 3 do
    if math.abs(a[k] - b[k]) > tol then return false end
  end
  return true
end

local function count (s, name)
  local n = 0
  for _, m in s:modules() do if m == name then n = n + 1 end end
  return n
end

-- A trunk of 4 segments with a lateral of 2 at the third, then 2 more trunk segments.
local function plant ()
  return lsys.lsystem { axiom = "F(1)F(1)F(1)F(1)[+(30)F(1)F(1)]F(1)F(1)", view = { angle = 30 } }
end

describe("lsys.arrange", function()
  it("puts an @J before each segment of the selected path, once", function()
    local m = plant()
    local a = lsys.arrange(m, m:derive(0))
    assert.equal(5, a:select(2, 8))
    assert.equal("F(1)@J(0,0,0)F(1)@J(0,0,0)F(1)@J(0,0,0)F(1)[+(30)@J(0,0,0)F(1)" ..
      "@J(0,0,0)F(1)]F(1)F(1)", tostring(a:lstring()))
    assert.same({ 3, 5, 7, 11, 13 }, a:path_modules())
    assert.same({ 3, 5, 7, 11, 13, 15, 16 }, a:active_modules())
    -- again, on the same path: nothing added
    assert.equal(5, a:select(3, 13))
    assert.equal(5, count(a:lstring(), "@J"))
  end)

  it("draws exactly the pose the solver found", function()
    local m = plant()
    local a = lsys.arrange(m, m:derive(0))
    a:select(2, 8)
    local r = a:spherical({ 0, 0, 1 }, -30)
    assert.is_true(r.dist < 0.05 * 4.4, "dist " .. r.dist)
    local p, _, t = a.ik:forward()
    local sc = a:interpret()
    local rec = sc:record(sc:find(13))   -- the moved segment
    assert.is_true(near3(rec.p1, p, 1e-5))
    assert.is_true(near3(rec.U, t, 1e-5))
    -- the spherical dragger turned the end about r by -30 degrees around z
    local b = a.bar
    local c, sn = math.cos(math.rad(-30)), math.sin(math.rad(-30))
    local v = { b.v[1] * c - b.v[2] * sn, b.v[1] * sn + b.v[2] * c, b.v[3] }
    assert.is_true(near3(p, { b.r[1] + v[1], b.r[2] + v[2], b.r[3] + v[3] }, 0.05 * 4.4))
  end)

  it("twists with the disc, pulls along the axis and moves in a plane", function()
    local m = plant()
    local a = lsys.arrange(m, m:derive(0))
    a:select(2, 8)
    local b = a.bar
    a:disc(40)
    local p, s = a.ik:forward()
    assert.is_true(near3(p, b.p, 0.05))           -- the end stays
    local cos = s[1] * b.s[1] + s[2] * b.s[2] + s[3] * b.s[3]
    local turned = math.deg(math.acos(math.max(-1, math.min(1, cos))))
    assert.is_true(turned > 20, "twist " .. turned)
    a:undo_last()
    a:axis(-0.5)                                  -- pulled in along v-bar
    p = a.ik:forward()
    local len = math.sqrt(b.v[1] ^ 2 + b.v[2] ^ 2 + b.v[3] ^ 2)
    local want = {}
    for k = 1, 3 do want[k] = b.p[k] - 0.5 * b.v[k] / len end
    assert.is_true(near3(p, want, 0.05))
    a:undo_last()
    a:plane(0.5, -0.3, { right = { 1, 0, 0 }, up = { 0, 1, 0 } })
    p = a.ik:forward()
    assert.is_true(near3(p, { b.p[1] + 0.5, b.p[2] - 0.3, b.p[3] }, 0.05))
  end)

  it("assigns stiffness by the da Vinci rule, from widths, or from Z", function()
    -- trunk radius r0 = 1 with two laterals: each gets r = 1 / sqrt(2), r^4 = 1/4
    local m = lsys.lsystem { axiom = "F(1)F(2)[+F(1)]F(1)[-F(1)]F(1)", view = { angle = 30 } }
    local a = lsys.arrange(m, m:derive(0), { s0u = 2, s0h = 3 })
    -- eq. 4: s^u = 2 c_f r^4 / (l_{i-1} + l_i), c_f = s0u / r0^4 = 2; eq. 5 with c_t = 3
    assert.same({ 3, 2, 2 }, a:stiffness(1))                -- first joint: l_{i-1} = l_i = 1
    assert.near({ 2, 4 / 3, 4 / 3 }, a:stiffness(2), 1e-12) -- 2 * 2 / (1 + 2)
    assert.near({ 0.5, 1 / 3, 1 / 3 }, a:stiffness(5), 1e-12)  -- 2*2/4/(2+1), a lateral
    assert.near(1 / math.sqrt(2), a:radius(5), 1e-12)
    -- widths: radius = width / 2 where the model sets widths
    local w = lsys.lsystem { axiom = "!(2)F(1)!(1)F(1)", view = { angle = 30 } }
    local aw = lsys.arrange(w, w:derive(0))
    assert.near(1, aw:radius(2), 1e-12)
    assert.near(0.5, aw:radius(4), 1e-12)
    assert.near({ 0.0625, 0.0625, 0.0625 }, aw:stiffness(4), 1e-12)   -- 2 * 0.5^4 / 2
    -- Z(sh, su, sl) in the string wins
    local z = lsys.lsystem { axiom = "Z(5,6,7)F(1)F(1)", view = { angle = 30 } }
    local az = lsys.arrange(z, z:derive(0))
    assert.same({ 5, 6, 7 }, az:stiffness(2))
  end)

  it("bends stiff paths less where they are stiff (fig. 3)", function()
    -- 11 segments, stiffness increasing (Z) towards the tip: the bend stays low
    local parts = {}
    for i = 1, 11 do parts[i] = ("Z(%d,%d,%d)F(1)"):format(i, i, i) end
    local inc = lsys.lsystem { axiom = table.concat(parts), view = { angle = 30 } }
    for i = 1, 11 do parts[i] = ("Z(%d,%d,%d)F(1)"):format(12 - i, 12 - i, 12 - i) end
    local dec = lsys.lsystem { axiom = table.concat(parts), view = { angle = 30 } }
    local function centre (m)
      local a = lsys.arrange(m, m:derive(0))
      a:select(2, 22)
      a:plane(4, -2)
      local num, den = 0, 0
      for i, ang in ipairs(a.ik:angles()) do
        local bend = math.sqrt(ang[2] ^ 2 + ang[3] ^ 2)
        num, den = num + i * bend, den + bend
      end
      return num / den
    end
    assert.is_true(centre(inc) + 1 < centre(dec))
  end)

  it("prunes a branch, leaving @X for productions to regrow", function()
    local m = lsys.lsystem { axiom = "F(1)[+(30)F(1)F(1)]F(1)", view = { angle = 30 },
                             productions = "@X --> [-(20)F(0.5)]" }
    local a = lsys.arrange(m, m:derive(0))
    assert.equal(2, a:prune(4))              -- F(1)F(1): from module 4 to the end of its branch
    assert.equal("F(1)[+(30)@X]F(1)", tostring(a:lstring()))
    assert.equal("F(1)[+(30)[-(20)F(0.5)]]F(1)", tostring(m:step(a:lstring())))
    assert.is_true(a:undo_last())
    assert.equal("F(1)[+(30)F(1)F(1)]F(1)", tostring(a:lstring()))
  end)

  it("grows, arranges and grows again; the bend survives and new growth attaches (fig. 10)",
  function()
    local m = lsys.lsystem { axiom = "F(1)A", steps = 3, view = { angle = 30 },
                             productions = "A --> F(1)[+(40)F(0.5)]A" }
    local s = m:derive()                      -- F F[+F] F[+F] F[+F] A
    local a = lsys.arrange(m, s)
    a:select(1, #s - 5)    -- the last internode
    a:plane(-1.5, -0.5)
    local arranged = a:lstring()
    local before = m:interpret(arranged)
    local njoints = count(arranged, "@J")
    local grown = m:step(arranged)
    local after = m:interpret(grown)
    -- the arranged segments are where they were; their joints are kept, not added to
    assert.equal(njoints, count(grown, "@J"))
    for k = 1, before.nrecords do
      assert.is_true(near3(before:record(k).p1, after:record(k).p1, 1e-9))
    end
    -- the new internode starts at the old tip (the last trunk segment before A)
    local tip = before:record(before:find(#arranged - 5))   -- the last internode
    local newrec = after:record(before.nrecords + 1)
    assert.is_true(near3(newrec.p0, tip.p1, 1e-6))
    -- and a second arrangement updates the same @J modules
    local a2 = lsys.arrange(m, grown)
    a2:select(2, #grown - 5)
    a2:plane(0.5, 0)
    assert.equal(njoints + 1, count(a2:lstring(), "@J"))   -- only the new segment's joint
  end)

  it("reports bad selections and options", function()
    local m = plant()
    local a = lsys.arrange(m, m:derive(0))
    assert.error_contains(function() a:select(8, 2) end,
      "select: module 2 is not in the active branch of module 8 (above it)")
    assert.error_contains(function() a:select(5, 8) end,
      "select: fixed: module 5 ([) draws nothing that can be arranged")
    assert.error_contains(function() lsys.arrange(m, nil, { r0 = -1 }) end,
      "lsys.arrange: option 'r0' must be > 0")
    assert.error_contains(function() lsys.arrange(m, nil, { colour = 1 }) end,
      "lsys.arrange: unknown option 'colour'")
    assert.error_contains(function() a:disc(10) end, "select a branch path first")
  end)
end)

describe("the arrange window's highlight (fig. 6)", function()
  local UI = require "lsys.arrange_ui"
  local function colors (lines)
    local red, yellow = 0, 0
    for _, l in ipairs(lines) do
      if l.color == UI.RED then
        red = red + 1
      elseif l.color == UI.YELLOW then
        yellow = yellow + 1
      end
    end
    return red, yellow
  end

  it("draws segments as lines and leaves as their wireframe", function()
    -- a trunk of 3, a lateral F ending in a square leaf (4 vertices: 2 triangles, 5 edges)
    local m = lsys.lsystem { axiom = "F(1)F(1)[+(30)F(1){.-(30)f(1).+(60)f(1).+(120)f(1).}]F(1)",
                             view = { angle = 30 } }
    local arr = lsys.arrange(m, m:derive())
    local sc = arr:interpret()
    local leafrec
    for k, r in sc:records() do if r.kind == "polygon" then leafrec = k end end
    assert.equal(5, #sc:edges(leafrec))
    assert.equal(0, #sc:edges(1))                       -- a segment drawn as a line
    assert.has_error(function() sc:edges(99) end, "scene:edges: no record 99")
    assert.same({}, UI.highlight(arr, sc))              -- nothing selected
    arr:select(2)
    local lines = UI.highlight(arr, arr:interpret())
    -- the active branch: trunk segments 2 and 3, the lateral F and the leaf's 5 edges
    assert.same({ 8, 0 }, { colors(lines) })
    local corners = 0                                   -- the leaf's edges meet at its vertices
    for _, l in ipairs(lines) do
      if l.width == 2 and near3(l.p0, { -0.5, 2 + math.sqrt(3) / 2, 0 }, 1e-6) then
        corners = corners + 1
      end
    end
    assert.equal(2, corners)
    -- the leaf as the manipulated point: its wireframe turns yellow
    local leaf
    for _, r in arr:interpret():records() do if r.kind == "polygon" then leaf = r.module end end
    arr:select(arr.fixed.module, leaf)
    assert.is_true(arr.leaf)
    assert.same({ 8, 5 }, { colors(UI.highlight(arr, arr:interpret())) })
  end)

  it("outlines only the shape itself, over tubes", function()
    -- a sphere after a tube: the tube is emitted when the sphere's module begins, and its
    -- triangles are not the sphere's
    local function sphere_edges (axiom)
      local m = lsys.lsystem { axiom = axiom, view = { line_style = "cylinder" } }
      local sc = m:interpret(m:derive())
      for k, r in sc:records() do if r.kind == "sphere" then return #sc:edges(k), sc end end
    end
    local alone = sphere_edges("@O(0.4)")
    assert.is_true(alone > 20)
    assert.equal(alone, (sphere_edges("!(0.3)F(1)@O(0.4)")))
    -- highlights are drawn on top: a centre line inside a tube stays visible
    local m = lsys.lsystem { axiom = "!(0.3)F(1)F(1)@O(0.4)", view = { line_style = "cylinder" } }
    local arr = lsys.arrange(m, m:derive())
    arr:select(3)
    local lines = UI.highlight(arr, arr:interpret())
    assert.equal(1 + alone, #lines)                     -- F(1) at module 3 and the sphere
    for _, l in ipairs(lines) do assert.is_true(l.ontop) end
  end)
end)

describe("#gl lsys arrange in the window", function()
  local D = require "tests.display"
  teardown(function() D.stop() end)

  it("selects by clicks, bends by a real Ctrl-drag and saves with Ctrl-S", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return end
    local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
    local dir = os.tmpname()
    os.remove(dir)
    os.execute("mkdir -p " .. dir)
    local f = assert(io.open(dir .. "/m.lua", "w"))
    f:write('local lsys = require "lsys"\nreturn lsys.lsystem { axiom = ' ..
      '"F(1)F(1)F(1)F(1)[+(30)F(1)F(1)]F(1)F(1)", steps = 0, view = { angle = 30 } }\n')
    f:close()
    f = assert(io.open(dir .. "/drive.lua", "w"))
    f:write([[
local lsys = require "lsys"
local V = require "lsys.viewer"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local UI = require "lsys.arrange_ui"
local m = dofile(arg[1])
local arr = lsys.arrange(m, m:derive())
local function x (cmd)
  assert(os.execute("xdotool search --name 'lsys: arrange test' " .. cmd .. " >/dev/null 2>&1"))
  for _ = 1, 5 * SLOW do V.poll(0.1) end
  assert(V.sync(10 * SLOW))
end
local function at (module)         -- the window point of a segment's middle
  local sc = arr:interpret()
  local r = sc:record(sc:find(module))
  local px, py = V.project({ (r.p0[1] + r.p1[1]) / 2, (r.p0[2] + r.p1[2]) / 2, 0 })
  return px // 1, py // 1
end
V.wait = function ()
  assert(V.sync(10 * SLOW))
  x(("mousemove --window %%1 %d %d click 1"):format(at(2)))       -- fixed: the 2nd internode
  local fixed = arr.fixed.module       -- 3: an @J went in before it
  x(("mousemove --window %%1 %d %d click 1"):format(at(fixed + 6)))   -- the lateral's 2nd F
  print("path", #arr.path)
  local b = arr.bar
  local px, py = V.project(b.p)
  x(("mousemove --window %%1 %d %d keydown ctrl mousedown 1 mousemove --window %%1 %d %d " ..
     "mousemove --window %%1 %d %d mouseup 1 keyup ctrl"):format(px // 1, py // 1,
     px // 1 - 20, py // 1, px // 1 - 60, py // 1 + 30))
  local p = arr.ik:forward()
  print("moved", p[1] < b.p[1] - 0.5)
  x("windowfocus --sync %1 key ctrl+s")
  -- the arrow keys move the fixed point: up along the trunk (F2 -> F5), right and left
  -- between the siblings at the branching (the lateral's first F and F5), down back to F4
  local f0 = arr.fixed.module
  x("windowfocus --sync %1 key Up")
  print("up", arr.recs[arr.fixed.parent].module == f0, arr.fixed.lateral)
  x("windowfocus --sync %1 key Up Up")
  local f5 = arr.fixed.module
  x("windowfocus --sync %1 key Right")
  print("right", arr.fixed.lateral, arr.fixed.module < f5)   -- [+F F] comes before F5
  x("windowfocus --sync %1 key Left")
  print("left", arr.fixed.lateral, arr.fixed.module == f5)
  x("windowfocus --sync %1 key Down")
  print("down", arr.fixed.module < f5, #arr.fixed.children)
  local n0 = #arr:lstring()
  x("windowfocus --sync %1 key Delete")     -- prunes from F4 up: only F1..F3 and @X stay
  local pruned = tostring(arr:lstring())
  print("pruned", pruned:find("@X") ~= nil, select(2, pruned:gsub("F%(", "")))
  x("windowfocus --sync %1 key u")
  print("undone", #arr:lstring() == n0, (tostring(arr:lstring()):find("@X")))
  os.execute("xdotool search --name 'lsys: arrange test' windowfocus --sync %1 key Escape " ..
    ">/dev/null 2>&1")                 -- (xdotool may complain: the window goes)
  for _ = 1, 10 * SLOW do V.poll(0.1) end
end
UI.run(arr, { width = 400, height = 400, title = "arrange test", out = arg[2],
              say = function () end })
]])
    f:close()
    local p = io.popen(D.env .. BIN .. " " .. dir .. "/drive.lua " .. dir .. "/m.lua " ..
      dir .. "/out.txt 2>&1; echo exit:$?")
    local out = p:read("a")
    p:close()
    assert.truthy(out:find("path\t5\nmoved\ttrue\nup\ttrue\tfalse\nright\ttrue\ttrue\n" ..
      "left\tfalse\ttrue\ndown\ttrue\t2\npruned\ttrue\t3\nundone\ttrue\tnil\n", 1, true), out)
    assert.truthy(out:find("exit:0", 1, true), out)
    local saved = io.open(dir .. "/out.txt"):read("a")
    assert.truthy(saved:find("^F%(1%)@J%(0,%-?[%d.e-]+,0%)F%(1%)"), saved)
    assert.equal(5, select(2, saved:gsub("@J", "")))
    os.execute("rm -rf " .. dir)
  end)
end)

describe("the ilsa examples (figures 3, 4, 10)", function()
  it("run and draw their pictures", function()
    local core = require "lsys.core"
    if not core.has_render then pending("built without rendering") return end
    local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
    for _, fig in ipairs { "fig3", "fig4", "fig10" } do
      local out = os.tmpname() .. ".png"
      local p = io.popen(BIN .. " examples/ilsa/" .. fig .. ".lua " .. out .. " 2>&1; echo exit:$?")
      local text = p:read("a")
      p:close()
      assert.truthy(text:find("wrote " .. out, 1, true), text)
      assert.truthy(text:find("exit:0", 1, true), text)
      local px, w, h = core.png_read(out)
      local dark = 0
      for i = 1, #px, 4 * 37 do if px:byte(i) < 128 then dark = dark + 1 end end
      assert.is_true(w > 0 and h > 0 and dark > 20, fig .. ": " .. dark)
      os.remove(out)
    end
  end)
end)
