-- The C side of component graphs (csrc/lua/lua_compgeo.c): the frame arena and the turtle
-- writer that lsys.components.expand and .emit drive, their checks, and the i-tree's views of
-- them (inst.frame, inst.stem, inst.tip, module ranges, the owner list).
local lsys = require "lsys"
local core = require "lsys.core"
local C = lsys.components

local errof = require("tests.helper").errof

local START = { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, -1 }, s = 1 }

describe("lsys.components frames (core.frames)", function ()
  it("keeps frames by index and draws the expansion's sequence", function ()
    local F = core.frames(1)
    local i = F:add(START)
    assert.equal(1, i)
    local g = F:get(i)
    assert.same(START, g)
    assert.is_nil(g.u)
    assert.equal(0, F:get(i, true).u)
    local j = F:transform(i, 1, 2, 3, 90, 0, 0, 2)
    local h = F:get(j)
    assert.same({ 1, 2, 3 }, h.p)
    assert.near(1, h.H[3], 1e-15)
    assert.equal(2, F:scale(j))
    F:set(i, { p = { 5, 6, 7 }, H = { 1, 0, 0 }, U = { 0, 1, 0 }, s = 3 })
    assert.same({ 5, 6, 7 }, F:get(i).p)
    assert.same({ 5, 6, 7 }, F:get(F:ahead(i, 0)).p)           -- ahead 0: a copy
    assert.same({ 5 + 2 * 3, 6, 7 }, F:get(F:ahead(i, 2)).p)   -- d times the scale along H
    assert.equal(4, F:count())
    -- splitmix64 from state 1 (tests/c/test_compgeo.c has the values)
    local R = core.frames(1)
    assert.equal(0.5665615751722809, R:random())
    assert.equal(0.7457817572627011, R:random())
    local g1 = require("lsys.components.expand").generator(1)
    assert.equal(0.5665615751722809, g1())
  end)

  it("makes stems, branches and multiplied children", function ()
    local F = core.frames(1)
    local i = F:add(START)
    local st = F:stem(i, 2, 4, 0, 0, 0)
    for k = 0, 4 do
      local f = F:get(st + k, true)
      assert.near(k * 0.5, f.p[2], 1e-15)
      assert.equal(k / 4, f.u)
    end
    local b = F:get(F:branch(st, 5, 0.5, 0, 90, 0.5))
    assert.near(1, b.p[2], 1e-15)
    assert.near(-1, b.H[3], 1e-15)
    assert.equal(0.5, b.s)
    -- a multiplier's child: local X = U, Y = H x U, Z = H
    local c = F:get(F:place(i, 1, 0, 2, 0, 0, 1, 1, 0, 0, 0.5))
    assert.near(0, c.p[1], 1e-15)
    assert.near(2, c.p[2], 1e-15)
    assert.near(-1, c.p[3], 1e-15)
    assert.same({ 0, 1, 0 }, c.H)
    assert.equal(0.5, c.s)
    -- a field of position: called once a segment; nil is "no direction here"
    local calls = 0
    local s2 = F:stem(i, 1, 3, 0, 0, 0, { { function () calls = calls + 1 end, 1 } })
    assert.equal(3, calls)
    assert.same({ 0, 1, 0 }, F:get(s2 + 3).H)
  end)

  it("names what is wrong and refuses closed arenas", function ()
    local F = core.frames(1)
    local i = F:add(START)
    assert.truthy(errof(F.get, F, 2):find("no such frame", 1, true))
    assert.truthy(errof(F.get, F, 0):find("no such frame", 1, true))
    assert.truthy(errof(F.add, F, { p = { 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } })
                  :find("'p'[3] must be a finite number", 1, true))
    assert.truthy(errof(F.transform, F, i, 0, 0, 0, 0 / 0, 0, 0, 1)
                  :find("not a finite number", 1, true))
    assert.truthy(errof(F.branch, F, i, 5, 0.5, 0, 90, 1):find("not a stem", 1, true))
    assert.truthy(errof(F.branch, F, math.maxinteger, 2, 0.5, 0, 90, 1)
                  :find("not a stem", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 0, 0, 0, 0):find("segments must be from 1", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 2, 0, 0, 0, { 5 })
                  :find("tropism 1 must be {direction, strength}", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 2, 0, 0, 0, { { "down", 1 } })
                  :find("the direction must be", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 2, 0, 0, 0, { { function () return "x", 1, 2 end, 1 } })
                  :find("not three finite numbers", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 2, 0, 0, 0, { { function () error("field broke") end,
                                                         1 } }):find("field broke", 1, true))
    assert.truthy(errof(F.stem, F, i, 1, 2, 0, 0, 0, nil, 10, { 0.5 }, {})
                  :find("one roll per branch", 1, true))
    F:close()
    for _, m in ipairs { "get", "count", "random", "scale", "stem" } do
      assert.truthy(errof(F[m], F, 1):find("the frames were closed", 1, true))
    end
  end)
end)

describe("lsys.components writer (core.cwriter)", function ()
  local function rules () return lsys.lsystem { axiom = "", steps = 0 }._rules end

  it("writes instances as branches with their owners and module ranges", function ()
    local F = core.frames(1)
    local a = F:add(START)
    local b = F:add { p = { 0, 2, 0 }, H = { 0, 1, 0 }, U = { 0, 0, -1 }, s = 1 }
    local W = core.cwriter(rules(), F)
    W:open(1, a)
    W:open(2, b)
    W:op(W:symbol("X"), 1, 2)
    W:close()
    W:close()
    assert.equal("[[f(2)X(1,2)]]", tostring(W:lstring()))
    assert.same({ 1, 2, 2, 2, 2, 1 }, { W:owner(1), W:owner(2), W:owner(3), W:owner(4),
                                        W:owner(5), W:owner(6) })
    assert.is_nil(W:owner(7))
    assert.same({ 2, 5, 3 }, { W:range(2) })
    assert.same({ 1, 6, 1 }, { W:range(1) })
    assert.is_nil(W:range(3))
  end)

  it("names what is wrong and refuses closed writers and strings", function ()
    local F = core.frames(1)
    local a = F:add(START)
    local W = core.cwriter(rules(), F)
    assert.truthy(errof(W.close, W):find("no open instance", 1, true))
    assert.truthy(errof(W.op, W, 100000):find("not a symbol", 1, true))
    assert.truthy(errof(W.symbol, W, "1x"):find("not a module name", 1, true))
    assert.truthy(errof(W.symbol, W, "F("):find("not a module name", 1, true))
    assert.truthy(errof(W.op, W, W:symbol("F"), 0 / 0):find("not a finite number", 1, true))
    local many = {}
    for k = 1, 32 do many[k] = k end
    assert.truthy(errof(W.op, W, W:symbol("F"), table.unpack(many))
                  :find("too many parameters", 1, true))
    assert.truthy(errof(W.open, W, 0, a):find("not an instance index", 1, true))
    assert.truthy(errof(W.open, W, 1, 9):find("no such frame", 1, true))
    assert.truthy(errof(W.forward, W, 1 / 0):find("not a finite number", 1, true))
    do local _ <close> = W:lstring() end         -- the user closed the string
    assert.truthy(errof(W.open, W, 1, a):find("closed", 1, true))
    local W2 = core.cwriter(rules(), F)
    W2:free()
    assert.truthy(errof(W2.count, W2):find("the writer was closed", 1, true))
    F:close()
    local W3 = core.cwriter(rules(), core.frames(1))
    assert.truthy(errof(core.cwriter, rules(), F):find("the frames were closed", 1, true))
    assert.equal(0, W3:count())
  end)
end)

describe("lsys.components i-tree views of the arena", function ()
  it("reads frames, stems, tips and module ranges from C", function ()
    local leaf = C.leaf { length = 0.5 }
    local t = C.tree { length = 2, n = 2, segments = 4, angle = 45 }
    t:branch(leaf)
    local m = C.model(t)
    local tree = m.components.tree
    local root = tree.list[1]
    assert.equal(5, #root.stem)
    assert.equal(0.5, root.stem[3].u)
    assert.same(root.stem[5].p, root.tip.p)
    local l = tree.list[2]
    local f, tip = l.frame, l.tip                 -- a leaf's tip: its length along H
    for k = 1, 3 do assert.near(f.p[k] + 0.5 * f.s * f.H[k], tip.p[k], 1e-12) end
    assert.are_not.equal(l.frame, l.frame)        -- a new table at each read
    -- module ranges and owners of the emission
    local s = m.components.lstring
    assert.equal(1, root.m0)
    assert.equal(#s, root.m1)
    assert.same({ l.m0, l.m1 }, l.modules)
    assert.equal(#s, #m.components.owner)
    for k = l.m0, l.m1 do assert.equal(2, m.components.owner[k]) end
    assert.equal("[", (s:module(l.m0)))
    assert.equal("]", (s:module(l.m1)))
    assert.is_nil(m.components.owner.x)
    assert.equal(l, m.components.instance(l.at))
  end)
end)
