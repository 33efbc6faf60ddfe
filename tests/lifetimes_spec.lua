-- Objects freed or changed under a call: a binding that holds pointers
-- into an object while Lua code runs (a callback, a metamethod of an argument, or a finalizer
-- run by an allocation) must find the object as it left it. Each test fails before its fix
-- (a crash, a use-after-free under tools/sanitize.sh, or a wrong answer).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"
local grow = require "lsys.grow"
local fin = require "tests.finalizers"

local errof = H.errof

local function close (x) getmetatable(x).__close(x) end

local IN_USE = "cannot close a Scene while it is in use"
local CHANGE = "cannot change a Scene while it is in use"

-- Calls call(x) `times` times on objects x from make(), each time with a fresh object whose
-- finalizer closes x at the collector's next minor cycle, armed to fall at a random point
-- of the first 3000 bytes the call allocates (tests/finalizers.lua). A closed x is replaced.
-- Returns, for each finalizer that ran inside call on its own x, {ok, result of call, the
-- close's ok, its error}.
local function under_finalizers (make, call, times)
  local inside, rand, x = {}, 12345, make()
  collectgarbage()
  fin.start()
  for _ = 1, times or 80 do
    local running, got = false, nil
    local victim = x
    rand = (rand * 1103515245 + 12345) % 2147483648
    fin.arm(rand % 3000)
    setmetatable({}, { __gc = function ()
      if running and x == victim and got == nil then got = { pcall(close, victim) } end
    end })
    running = true
    local ok, res = pcall(call, x)
    running = false
    if got then
      inside[#inside + 1] = { ok, res, got[1], got[2] }
      if got[1] then x = make() end
    end
  end
  fin.stop()
  return inside
end

local function plant ()
  return lsys.lsystem { axiom = "F[+F]F[-F]F[+F]F",
                        view = { angle = 30, line_style = "cylinder", line_width = 0.1 } }
    :interpret()
end

-- The finalizers that ran inside a method of a Scene: either before the method held it (the
-- close went through, and the method raised "the scene was closed"), or after (the close was
-- refused and the method returned what it returns on an open scene). Some were refused.
local function check_held (inside, want)
  local refused = 0
  for _, r in ipairs(inside) do
    if r[3] then
      assert.same({ false, "the scene was closed" }, { r[1], (tostring(r[2]):gsub("^.-: ", "")) })
    else
      refused = refused + 1
      assert.truthy(tostring(r[4]):find(IN_USE, 1, true), r[4])
      assert.same({ true, want }, { r[1], r[2] })
    end
  end
  assert.is_true(refused > 0, "no finalizer ran while the scene was held")
end

describe("a Scene held by one of its methods", function ()
  it("cannot grow under scene:deform: a grow world's tick in the function is refused", function ()
    local Shoot = grow.kind("shoot")
    Shoot:rule("length", function (limb) limb:scale_length(1.1) end)
    local w = grow.world { seed = 1 }
    w:plant { kind = Shoot, position = { 0, 0, 0 } }
    w:tick(2)
    local sc = w:scene()
    local n, before = sc.nvertices, { sc:vertex(1) }
    local err = errof(sc.deform, sc, function (x, y, z) w:tick(1); return x + 1, y, z end)
    assert.truthy(err:find(CHANGE, 1, true), err)
    assert.truthy(err:find("scene:deform: the function failed at vertex 1", 1, true), err)
    assert.equal(n, sc.nvertices)
    assert.same(before, { sc:vertex(1) })             -- left as it was
    w:tick(1)                                         -- and usable after
    assert.equal(3, w.ticks)
  end)

  it("cannot gain a prototype under scene:deform", function ()
    local pop = core.population {}
    core.population_add(pop, plant(), true)
    core.population_place(pop, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
    local p2 = plant()
    local err = errof(pop.deform, pop, function (x, y, z)
      core.population_add(pop, p2, true)
      return x, y, z
    end)
    assert.truthy(err:find(CHANGE, 1, true), err)
    assert.equal(1, pop.nprototypes)
    assert.truthy(errof(pop.deform, pop, function (x, y, z)
      core.population_place(pop, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0)
      return x, y, z
    end):find(CHANGE, 1, true))
    assert.equal(1, pop.ninstances)
  end)

  it("cannot be closed by the function of scene:deform", function ()
    local sc = plant()
    local before = { sc:vertex(2) }
    local err = errof(sc.deform, sc, function (x, y, z) close(sc); return x, y, z end)
    assert.truthy(err:find(IN_USE, 1, true), err)
    assert.same(before, { sc:vertex(2) })
  end)

  it("cannot be closed by a finalizer during scene:edges", function ()
    local function make () return lsys.lsystem { axiom = "F@O(1)" }:interpret() end
    local function edges (sc) return #sc:edges(2) end
    check_held(under_finalizers(make, edges), edges(make()))
  end)

  -- record and records copy the record before they make its tables: a finalizer may close
  -- the scene meanwhile, the table is the record's (under tools/sanitize.sh the code before
  -- read the freed records)
  for _, case in ipairs {
    { "record", function (sc) return sc:record(3).module end },
    { "records", function (sc) local n = 0; for _ in sc:records() do n = n + 1 end; return n end },
  } do
    it("reads its record before a finalizer can close the scene: scene:" .. case[1], function ()
      local want = case[2](plant())
      local inside = under_finalizers(plant, case[2])
      assert.is_true(#inside > 0)
      for _, r in ipairs(inside) do
        assert.is_true(r[3])
        if not r[1] then assert.equal("the scene was closed", (r[2]:gsub("^.-: ", "")))
        else assert.equal(want, r[2]) end
      end
    end)
  end

  it("cannot be closed by a finalizer during a population's scene:instance", function ()
    local function population ()
      local pop = core.population {}
      core.population_add(pop, plant(), true)
      for i = 1, 3 do core.population_place(pop, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1, i, 0, 0) end
      return pop
    end
    check_held(under_finalizers(population, function (pop)
      local at
      for _ = 1, 3 do at = pop:instance(2).at[1] end
      return at
    end), 2)
  end)

  it("is closed normally once its methods returned", function ()
    local sc = plant()
    sc:record(1)
    sc:deform(function (x, y, z) return x, y, z end)
    close(sc)
    assert.equal("lsys.Scene (closed)", tostring(sc))
  end)

  it("is released when a method raises or runs in a coroutine that dies", function ()
    local sc = plant()
    assert.truthy(errof(sc.deform, sc, function () error("boom") end):find("boom", 1, true))
    local co = coroutine.create(function ()
      sc:deform(function () error("in a coroutine") end)
    end)
    assert.is_false((coroutine.resume(co)))
    co = nil                                          -- luacheck: no unused
    collectgarbage()
    collectgarbage()
    close(sc)
    assert.equal("lsys.Scene (closed)", tostring(sc))
  end)
end)

describe("a BSpline whose memory a finalizer frees during a method", function ()
  local pts = {}
  for i = 1, 300 do pts[i] = { i, (i * 7) % 13 } end

  for _, case in ipairs {
    { "sample", function (c) return #c:sample(500) end, 500 },
    { "sample_length", function (c) return #c:sample_length(300) end, 300 },
    { "points", function (c) return #c:points() end, 300 },
    { "ray", function (c) return type(c:ray(0, 5, 1, 0)) end, "table" },
  } do
    it("is refused by " .. case[1] .. " (the curve was closed), never read", function ()
      local inside = under_finalizers(function () return core.bspline(pts) end, case[2])
      local refused = 0
      assert.is_true(#inside > 0)
      for _, r in ipairs(inside) do
        assert.is_true(r[3])                          -- an immutable curve may be closed
        if r[1] then assert.equal(case[3], r[2])     -- when it finished reading first
        else
          refused = refused + 1
          assert.truthy(r[2]:find(case[1] .. ": the curve was closed", 1, true), r[2])
        end
      end
      assert.is_true(refused > 0, "the curve was read after it was closed")
    end)
  end
end)

describe("lsys.core reads its arguments once", function ()
  it("Frames:stem calls a tropism's field function it read before the call", function ()
    local F = core.frames(1)
    local i = F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
    local trop
    local calls = 0
    trop = { { function (_, _, _)
      calls = calls + 1
      trop[1] = 0x41414141                            -- the list entry becomes a number
      return 1, 0, 0
    end, 0.5 } }
    local first = F:stem(i, 1, 4, 0, 0, 0, trop)
    assert.equal(4, calls)
    assert.equal(first + 4, F:count())
  end)

  it("Frames:stem cannot be closed or grown by a field function", function ()
    local F = core.frames(1)
    local i = F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
    local err = errof(F.stem, F, i, 1, 4, 0, 0, 0, { { function () close(F) end, 1 } })
    assert.truthy(err:find("cannot close the frames while they are in use", 1, true), err)
    err = errof(F.stem, F, i, 1, 4, 0, 0, 0, { { function ()
      F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
    end, 1 } })
    assert.truthy(err:find("cannot change the frames while they are in use", 1, true), err)
    local n = F:count()                               -- the stems' first frames stay
    assert.equal(n + 1, F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } })
  end)

  it("core.render takes the scene after reading opts (whose metamethods may close it)",
  function ()
    if not core.has_render then pending("built without OSMesa") return end
    local sc = plant()
    local opts = setmetatable({ width = 8, height = 8 }, { __index = function (_, k)
      if k == "fov" then close(sc) end
    end })
    assert.equal("the scene was closed", (errof(core.render, sc, opts):gsub("^.-: ", "")))
  end)

  it("rules:setfuncs keeps the list it checked, read once", function ()
    local f = core.func { { 0, 0 }, { 1 / 3, 1 }, { 2 / 3, 1 }, { 1, 0 } }
    local reads = 0
    local list = setmetatable({}, {
      __len = function () return 1 end,
      __index = function () reads = reads + 1; return reads == 1 and f or "not a Func" end,
    })
    local R = core.rules()
    R:setfuncs(list)
    assert.equal(1, reads)
    assert.equal(f, debug.getuservalue(R, 3)[1])
  end)

  it("interpretation reads view.surfaces once, even when an entry's metamethod adds more",
  function ()
    local sf = core.surface_parse(H.read("tests/data/surfaces/leaf.s"), "leaf.s")
    local surfaces = {}
    for k = 1, 3 do
      surfaces[string.char(96 + k)] = setmetatable({ surface = sf }, { __index = function (_, key)
        if key == "scale" then
          for j = 1, 20 do surfaces[string.char(64 + j)] = { surface = sf } end
        end
      end })
    end
    local m = lsys.lsystem { axiom = "~a" }
    local sc = core.interpret(m._rules, lsys.lstring("~a"), { surfaces = surfaces })
    assert.is_true(sc.ntriangles > 0)
  end)
end)

describe("methods that the random calls of misuse_spec broke", function ()
  it("rules:kinds names the modules after a finalizer closed the rules", function ()
    local function make () return lsys.lsystem { axiom = "A" }._rules end
    local t = make():axiom("A(1) B(2, 3) A(4)")
    local inside = under_finalizers(make, function (R) return R:kinds(t).B[2] end)
    assert.is_true(#inside > 0)
    for _, r in ipairs(inside) do assert.same({ true, true }, { r[1], r[2] }) end
  end)

  it("W:range of a huge instance index is nothing", function ()
    local F = core.frames(1)
    F:add { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } }
    local W = core.cwriter(lsys.lsystem { axiom = "A" }._rules, F)
    assert.equal(0, select("#", W:range(math.maxinteger)))
    assert.equal(0, select("#", W:range(2 ^ 62)))
  end)
end)

describe("an object a model or an interpretation uses", function ()
  it("a Func closed by a rule function during derivation keeps its values", function ()
    local f = lsys.func.new { points = { { 0, 0 }, { 1 / 3, 1 }, { 2 / 3, 1 }, { 1, 0 } } }
    local m = lsys.lsystem { axiom = "C A(0.5)", functions = { f }, productions = {
      { "C", function () close(f); return lsys.produce("C") end },
      "A(x) --> B(func(1, x))" } }
    assert.equal("CB(0.75)", tostring(m:derive(1)))
    assert.equal("lsys.Func (closed)", tostring(f))
    assert.truthy(errof(f.eval, f, 0.5):find("the function was closed", 1, true))
  end)

  it("a contour closed by a homomorphism rule during interpretation keeps its points",
  function ()
    local c = core.contour({ { 1, 0 }, { 0, 1 }, { -1, 0 } })
    local function model (fn)
      return lsys.lsystem { axiom = "X @#(1) @Gs f(2) @Ge(5)", view = { contours = { c } },
        homomorphism = { { "X", function () fn(); return lsys.produce("f") end } } }
    end
    local want = model(function () end):interpret().ntriangles
    assert.is_true(want > 0)
    assert.equal(want, model(function () close(c); collectgarbage() end):interpret().ntriangles)
    assert.equal("lsys.Contour (closed)", tostring(c))
  end)

  it("a texture dropped from the view after interpretation stays the scene's", function ()
    local p = os.tmpname() .. ".png"
    core.png_write(p, ("\255\0\0\255"):rep(4), 2, 2, false)
    local seen = setmetatable({}, { __mode = "v" })
    local function view ()
      local t = core.texture_load(p)
      seen[1] = t
      return { textures = { t } }
    end
    local v = view()
    local sc = core.interpret(lsys.lsystem { axiom = "F" }._rules, lsys.lstring("F"), v)
    v.textures[1] = nil
    collectgarbage()
    collectgarbage()
    assert.truthy(seen[1], "the scene's texture was collected")
    if core.has_render then
      assert.equal(8, select(2, core.render(sc, { width = 8, height = 8 })))
    end
    os.remove(p)
  end)
end)

describe("Lstring ==", function ()
  it("is false against another userdata instead of raising", function ()
    local s = lsys.lstring("F")
    assert.is_false(s == io.stdout)
    assert.is_false(io.stdout == s)
    assert.is_false(s == plant())
    assert.is_false(plant() == s)
    assert.is_true(s == lsys.lstring("F"))
  end)
end)
