-- Positional functions (lsys.func, csrc/core/func.c): the Lua API, .func files, and
-- functions called from rule expressions on the expression machine and on the closure.
local H = require "tests.helper"
local lsys = require "lsys"

local BUMP = { { 0, 0 }, { 1 / 3, 1 }, { 2 / 3, 1 }, { 1, 0 } }   -- x(t) = t: f(x) = 3x(1-x)

local tmpdir = H.tmpdir

local function write (path, text)
  local f = assert(io.open(path, "wb"))
  f:write(text)
  f:close()
end

local function read (path)
  local f = assert(io.open(path, "rb"))
  local s = f:read("a")
  f:close()
  return s
end

describe("lsys.func", function ()
  it("makes a function that is called as f(x) and f:eval(x), clamped to [0, 1]", function ()
    local f = lsys.func.new { points = BUMP, name = "bump" }
    assert.equal(0.75, f(0.5))
    assert.equal(0.5625, f:eval(0.25))
    assert.equal(0, f(-3))
    assert.equal(0, f(4))
    assert.equal("bump", f:name())
    assert.equal(0, f:samples())
    assert.equal("func", lsys.type(f))
    assert.equal("lsys.Func(bump: 4 points)", tostring(f))
    assert.same({ { 0, 0 }, { 1 / 3, 1 }, { 2 / 3, 1 }, { 1, 0 } }, f:points())
  end)

  it("interpolates cpfg's table of samples", function ()
    local f = lsys.func.new { points = BUMP, samples = 5 }   -- 0 .5625 .75 .5625 0
    assert.equal(5, f:samples())
    assert.equal(0.28125, f(0.125))
    assert.equal("lsys.Func(f: 4 points, 5 samples)", tostring(f))
  end)

  it("approximates as cpfg with approx = \"cpfg\" (float32 points, bisection to 0.001)",
     function ()
    local pts = { { 0, 0.531316 }, { 0.32381, 0.502745 }, { 0.647619, 0.450364 },
                  { 1, 0.417031 } }
    local exact = lsys.func.new { points = pts, samples = 10 }
    local c = lsys.func.new { points = pts, samples = 10, approx = "cpfg" }
    assert.equal("exact", exact:approx())
    assert.equal("cpfg", c:approx())
    assert.equal(0.531316, exact(0))
    assert.near(0.531232, c(0), 5e-7)              -- cpfg's Lilac: +(53.1232)
    assert.near(0.417080, c(1), 5e-7)
    local c0 = lsys.func.new { points = pts, approx = "cpfg" }   -- no table: bisection
    assert.near(0.531232, c0(0), 5e-7)
    assert.is_true(math.abs(c0(0.5) - exact(0.5)) < 1e-3)
    assert.error_matches(function () lsys.func.new { points = pts, approx = "x" } end,
                         'lsys.func.new: approx must be "exact" or "cpfg"')
  end)

  it("raises on bad points, naming the point", function ()
    assert.has_error(function () lsys.func.new { points = { { 0, 0 }, { 1, 1 } } } end,
      "lsys.func.new: a function needs at least 4 points, got 2")
    assert.has_error(function ()
      lsys.func.new { points = { { 0, 0 }, { 0.5, 1 }, { 0.4, 1 }, { 1, 0 } } }
    end, "lsys.func.new: point 3: x is 0.40000000000000002, less than the x of point 2 (0.5)")
    assert.has_error(function ()
      lsys.func.new { points = { { 0, 0 }, { 0.5, "y" }, { 0.6, 1 }, { 1, 0 } } }
    end, "lsys.func.new: point 2: y is a string, not a number")
    assert.has_error(function () lsys.func.new { points = BUMP, samples = -2 } end,
      "lsys.func.new: samples must be a whole number from 0 to 1000000")
    assert.has_error(function () lsys.func.new { points = BUMP, nmae = "x" } end,
      "lsys.func.new: unknown option 'nmae'")
  end)

  it("saves and loads a .func file byte for byte", function ()
    local d = tmpdir()
    local f = lsys.func.new { points = { { 0, 0.1 }, { 0.2, 0.3 }, { 0.2, 0.3 }, { 0.7, 1 / 3 },
                                         { 1, 2 } }, name = "internode", samples = 20 }
    lsys.func.save(f, d .. "/internode.func")
    local text = read(d .. "/internode.func")
    assert.equal("fver 1 1\nname: internode\nsamples: 20\nflip: off\npoints: 4\n0 0.1 1\n" ..
                 "0.2 0.3 2\n0.7 0.3333333333333333 1\n1 2 1\n", text)
    local g = lsys.func.load(d .. "/internode.func")
    assert.same(f:points(), g:points())
    assert.equal(f(0.4), g(0.4))
    lsys.func.save(g, d .. "/again.func")
    assert.equal(text, read(d .. "/again.func"))
    os.execute("rm -rf '" .. d .. "'")
  end)

  it("loads a .fset as a list that is also a table by name", function ()
    local d = tmpdir()
    write(d .. "/set.fset", "funcgalleryver 1 1\nitems: 2\nfver 1 1\nname: A\nsamples: 0\n" ..
      "flip: off\npoints: 4\n0 1\n0.3 1\n0.6 1\n1 1\nfver 1 1\nname: B\nsamples: 0\n" ..
      "flip: off\npoints: 4\n0 0\n0.25 0.25\n0.75 0.75\n1 1\n")
    local set = lsys.func.load(d .. "/set.fset")
    assert.equal(2, #set)
    assert.equal(set[2], set.B)
    assert.equal(1, set.A(0.3))
    assert.equal(0.5, set.B(0.5))
    os.execute("rm -rf '" .. d .. "'")
  end)

  it("names the file and line of a malformed file", function ()
    local d = tmpdir()
    write(d .. "/bad.func", "fver 1 1\nname: a\nsamples: 0\npoints: 4\n0 0\n0.5 x\n")
    local ok, err = pcall(lsys.func.load, d .. "/bad.func")
    assert.is_false(ok)
    assert.equal("lsys.func.load: " .. d .. "/bad.func:6: bad number 'x'", err)
    os.execute("rm -rf '" .. d .. "'")
  end)
end)

describe("functions in rule expressions", function ()
  local f = lsys.func.new { points = BUMP, name = "internode" }
  local g = lsys.func.new { points = { { 0, 0 }, { 0.25, 0.25 }, { 0.75, 0.75 }, { 1, 1 } },
                            name = "angle" }

  -- the string on the machine and on the Lua closure, and whether rule 1 ran on the machine;
  -- then the first parameter of the first module, from each path
  local function both (opts)
    local out, p = {}, {}
    for _, lua in ipairs { false, true } do
      local m = lsys.lsystem(opts)
      m.lua_expressions = lua
      local s = m:derive(1)
      out[#out + 1] = tostring(s)
      out[#out + 1] = m._rules:hasvm(0)
      p[#p + 1] = select(2, s:module(1))
    end
    return out, p
  end

  -- the message of the error fn raises
  local function message (fn)
    local ok, err = pcall(fn)
    assert.is_false(ok)
    return (tostring(err):gsub("^.-:%d+: ", "", 1))
  end

  it("calls a Func in env by its name, with the same value on both paths", function ()
    local x = 0.3
    local r, p = both { axiom = "A(0.3)", env = { internode = f },
                        productions = "A(x) --> B(internode(x))" }
    assert.same({ "B(0.63)", true, "B(0.63)", false }, r)
    assert.equal(f(x), p[1])                   -- the same double on both paths
    assert.equal(f(x), p[2])
    assert.near(3 * x * (1 - x), p[1], 1e-15)
  end)

  it("calls func(ID, x) and func(\"name\", x) from the model's functions", function ()
    local r = both { axiom = "A(0.5)", functions = { f, g, size = f },
                     productions = "A(x) --> B(func(1, x), func(2, x) * 2, func('size', x), " ..
                                   "func(\"angle\", x))" }
    assert.same({ "B(0.75,1,0.75,0.5)", true, "B(0.75,1,0.75,0.5)", false }, r)
  end)

  it("evaluates a function in a condition on the machine", function ()
    local r = both { axiom = "A(0.1)A(0.5)", functions = { f },
                     productions = "A(x) : func(1, x) > 0.5 --> B" }
    assert.same({ "A(0.1)B", true, "A(0.1)B", false }, r)
  end)

  it("keeps a string anywhere but func's first argument on the closure", function ()
    local m = lsys.lsystem { axiom = "A(0.5)", functions = { f }, env = { k = 2 },
                             productions = "A(x) --> B(func(1, x) + #'ab')" }
    assert.equal("B(2.75)", tostring(m:derive(1)))
    assert.is_false(m._rules:hasvm(0))
  end)

  it("raises naming the rule for an unknown function when derivation starts", function ()
    local m = lsys.lsystem { axiom = "A(0.5)", functions = { f, angle = g },
                             productions = "A(x) --> B(func('intrnode', x))", name = "m" }
    assert.equal("rule 1 'A(x) --> B(func('intrnode', x))' (line 1 of productions): " ..
      "unknown function 'intrnode' (functions: angle, internode)", message(function ()
        m:derive(1)
      end))
    m = lsys.lsystem { axiom = "A(0.5)", functions = { f }, name = "m",
                       productions = "A(x) --> B(func(2, x))" }
    assert.equal("rule 1 'A(x) --> B(func(2, x))' (line 1 of productions): unknown " ..
      "function 2 (functions: internode)", message(function () m:derive(1) end))
  end)

  it("raises at run time for an id computed on the closure", function ()
    local m = lsys.lsystem { axiom = "A(3)", functions = { f }, name = "m",
                             productions = "A(x) --> B(func(x, 0.5))" }
    assert.equal("rule 1 'A(x) --> B(func(x, 0.5))' (line 1 of productions), module 1: " ..
      "unknown function 3.0 (functions: internode)", message(function () m:derive(1) end))
  end)

  it("lets rule code neither change a function nor reach globals through it", function ()
    local m = lsys.lsystem { axiom = "A(0.5)", env = { internode = f },
      productions = "A(x) --> B((function () internode.eval = print end)() or 1)" }
    assert.matches("attempt to index a lsys.Func value", message(function () m:derive(1) end))
    m = lsys.lsystem { axiom = "A(0.5)", env = { internode = f },
                       productions = "A(x) --> B(getmetatable(internode) and 1)" }
    assert.matches("unknown name 'getmetatable'", message(function () m:derive(1) end))
    assert.equal(0.75, f(0.5))
  end)

  it("rejects a bad functions option", function ()
    assert.equal("option 'functions'[1]: an lsys.Func or a file name expected, got number",
      message(function () lsys.lsystem { axiom = "A", functions = { 42 } } end))
    assert.matches("^option 'functions'%[1%]: cannot open 'tests/no/such.func'",
      message(function () lsys.lsystem { axiom = "A", functions = { "no/such.func" } } end))
    assert.equal("option 'functions' must be a table (got string)",
      message(function () lsys.lsystem { axiom = "A", functions = "x.func" } end))
  end)

  it("takes the functions of a cpfg view file's function: lines", function ()
    local d = tmpdir()
    write(d .. "/internode.func", "fver 1 1\nname: internode\nsamples: 0\nflip: off\n" ..
      "points: 4\n0 0 1\n0.3333333333333333 1 1\n0.6666666666666666 1 1\n1 0 1\n")
    write(d .. "/old.func", "range: 0.0 1.0\npoints: 4\n0 0\n0.25 0.25\n0.75 0.75\n1 1\n")
    write(d .. "/plant.v", "angle increment: 45\nfunction: internode.func 100\n" ..
      "function: old.func 5\n")
    local v = lsys.view.load(d .. "/plant.v")
    assert.same({ { file = "internode.func", samples = 100 }, { file = "old.func", samples = 5 } },
                v.functions)
    local m = lsys.lsystem { axiom = "A(0.5)", view = v,
      productions = "A(x) --> B(func(1, x), func(2, x), func('old', x))" }
    assert.equal("B(0.75,0.5,0.5)", tostring(m:derive(1)))
    assert.is_true(m._rules:hasvm(0))
    os.execute("rm -rf '" .. d .. "'")
  end)
end)
