-- lsys.cpfg.load: cpfg's L-system files (tests/data/cpfg/*.l, one per construct) derive
-- the strings cpfg derives. Expected strings marked "cpfg" are cpfg's -str output
-- (cpfg -g -m x.map -str out.str FILE.l view.v; docs/cpfg.md, "cpfg as a reference"); the
-- others are written out by hand.
require "tests.helper"
local lsys = require "lsys"

local D = "tests/data/cpfg/"
local function derive (file, n, opts)
  local m = lsys.cpfg.load(D .. file, nil, opts)
  return tostring(m:derive(n)), m
end

describe("lsys.cpfg.load", function ()
  it("derives a plain L-system for its derivation length", function ()
    local s, m = derive("koch.l")
    assert.equal(2, m.steps)
    assert.equal(2211, #m:derive())
    -- cpfg: the first 60 characters of its string
    assert.equal("F+FF-FF-F-F+F+FF-F-FF+F+FF+F-F+F+FF-FF-F-F+F+FF-F-FF+F+FF+F-", s:sub(1, 60))
  end)

  it("preprocesses macros, #if, #ifdef and #include (sub-L-systems) with the system cpp",
     function ()
    assert.equal("A(4)?(2,1)B$?(2,1)CC$", derive("macros.l", nil, { cpp = "system" }))  -- cpfg
  end)

  it("preprocesses the same with the built-in preprocessor", function ()
    assert.equal("A(4)?(2,1)B$?(2,1)CC$", derive("macros.l", nil, { cpp = "builtin" }))
  end)

  it("evaluates C expressions as cpfg: precedence, ?:, integer %, ^, trig in degrees",
     function ()
    -- cpfg
    assert.equal("B(1,9,0.75,10,1,64)C(0.5,0.5,1,45,30,60)D(-2,2,3,2,-1,4,1,0,1,1,5)",
                 derive("exprs.l"))
  end)

  it("runs statement blocks, globals set by Start/StartEach/EndEach, locals and arrays",
     function ()
    local s, m = derive("blocks.l")
    assert.equal("A(3)B(0,3,3)C(0)C(122)X(3)", s)   -- cpfg
    assert.equal(s, tostring(m:derive()))            -- derive starts afresh
  end)

  it("applies decomposition with its maximum depth", function ()
    local s, m = derive("decomp.l")
    assert.equal("D(6)[C(4)]", s)                    -- cpfg
    assert.equal("F(6)[C(4)]", tostring(m:expand(s)))
  end)

  it("reads * as no context and skips ignored modules in contexts", function ()
    assert.equal("B(6)+A(4)-C(3)", derive("context.l"))   -- cpfg
  end)

  it("evaluates a block local that draws a random number once, at its assignment", function ()
    -- Regression: the local's text was substituted at each use, so
    -- {a = floor(n * ran(1)); b = n - a;} --> B(a)C(b) drew twice and a + b was not n.
    local s = derive("randlocal.l")
    local pairs_, seen = 0, {}
    for a, b in s:gmatch("B%((%d+)%)C%((%d+)%)") do
      pairs_ = pairs_ + 1
      assert.equal(10, tonumber(a) + tonumber(b), s)
      seen[a] = true
    end
    assert.equal(12, pairs_)
    assert.truthy(next(seen, next(seen)), "a is not constant: " .. s)
  end)

  it("reseeds cpfg's generator with srand, in Start: and in a production mid-step", function ()
    assert.equal("EB(266.4441833496094)B(682.0352172851562)", derive("srand.l", 1))  -- cpfg
    assert.equal("EB(266.4441833496094)C(266.4441833496094)B(682.0352172851562)"        -- cpfg
                 .. "C(682.0352172851562)", derive("srand.l", 2))
  end)

  it("reseeds lsys's generator with srand, in Start: and in a production mid-step", function ()
    local m = lsys.cpfg.load(D .. "srand.l", nil, { random = "lsys" })
    local s1 = tostring(m:derive(1))
    local b1, b2 = s1:match("^EB%(([%d.]+)%)B%(([%d.]+)%)$")
    assert.truthy(b1 and b2 and b1 ~= b2, s1)
    -- E reseeds with 7 before the Bs draw: each C draws what its B drew a step earlier
    assert.equal(("EB(%s)C(%s)B(%s)C(%s)"):format(b1, b1, b2, b2), tostring(m:derive(2)))
    assert.equal(tostring(m:derive(2)), tostring(m:derive(2)))
    -- Start: {srand(5);} then E's srand(7): the first step draws from seed 7
    local plain = lsys.lsystem { axiom = "A A", productions = { "A --> B(ran(1000))" },
                                 seed = 7, numbers = "float32" }
    assert.equal(("B(%s)B(%s)"):format(b1, b2), tostring(plain:derive(1)))
  end)

  it("computes positional functions as cpfg approximates them", function ()
    -- cpfg (func.l with func.v): its numbers printed with %g
    local cpfg = "+(53.1232)F(2.02046)+(51.092)F(4.73308)+(48.7088)F(4.84078)"
      .. "+(46.2087)F(4.09045)+(43.803)F(3.86003)+(41.708)F(4.99415)"
    local function g (s) return (s:gsub("[-%d.e]+", function (x) return ("%g"):format(x) end)) end
    local m = lsys.cpfg.load(D .. "func.l", D .. "func.v")
    assert.equal(cpfg, g(tostring(m:derive())))
    assert.equal("cpfg", m._funclist[1]:approx())
    assert.near(0.531232, m:func(1, 0), 1e-6)
    assert.near(0.2020465, m:func("exact", 0), 1e-6)
    -- lsys's exact values on request: the first point's y at x = 0
    local e = lsys.cpfg.load(D .. "func.l", D .. "func.v", { functions = "exact" })
    assert.equal("+(53.1316)F(2)", g(tostring(e:derive())):sub(1, 14))
  end)

  it("keeps quiet at the depth limit after 'no warnings', as cpfg", function ()
    local warning = require "lsys.warning"
    local saved, got = warning.warn, {}
    warning.warn = function (msg) got[#got + 1] = msg end
    local ok, err = pcall(function ()
      assert.equal("B", derive("nowarn.l"))                       -- cpfg, without a warning
      local m = lsys.lsystem { axiom = "X", productions = "X --> A",
                               decomposition = "A --> B\nB --> C" }
      assert.equal("B", tostring(m:derive(1)))
    end)
    warning.warn = saved
    assert(ok, err)
    assert.equal(1, #got)                          -- the plain model warns, as cpfg does
    assert.matches("the decomposition depth limit stopped", got[1])
  end)

  it("chooses among stochastic productions with statement blocks as cpfg", function ()
    -- cpfg with seeds 7, 8, 9: 128, 105, 115 Bs of 512; n = 2046 always (the pre-condition
    -- blocks of both weighted productions run for all 1023 X modules of the derivation)
    local m = lsys.cpfg.load(D .. "stochblocks.l")
    for seed, bs in pairs { [7] = 128, [8] = 105, [9] = 115 } do   -- cpfg's, exactly
      m.seed = seed
      local s = m:derive()
      assert.equal(bs, s:count("B"))
      assert.equal(512, s:count("B") + s:count("C"))
      assert.equal(2046, m.env.n)
      assert.equal(s:count("B"), select(2, tostring(s):gsub("B%(18%)", "")))
    end
    local l = lsys.cpfg.load(D .. "stochblocks.l", nil, { random = "lsys" })
    local total = 0
    for seed = 1, 5 do
      l.seed = seed
      local s = l:derive()
      assert.equal(2046, l.env.n)
      total = total + s:count("B")
    end
    assert.is_true(math.abs(total / 5 - 128) < 20, tostring(total / 5))   -- weights 1 : 3
  end)

  it("reads atan2(y, x) as C's, in degrees, and a local read before it is set as 0",
     function ()
    assert.equal("B(45,135,-90)C(180)", derive("atan2.l"))
  end)

  it("rewrites the letter of an @ module as cpfg's character string does", function ()
    assert.equal("A@o(1.25)o(2)@X", derive("atsphere.l"))                 -- cpfg
  end)

  it("writes printf's C escapes as C does", function ()
    local H = require "tests.helper"
    local dir = H.tmpdir()
    H.write(dir .. "/run.lua", ("require('lsys').cpfg.load(%q):derive()"):format(D .. "printf.l"))
    local out, code = H.sh(H.BIN .. " " .. dir .. "/run.lua")
    H.rmdir(dir)
    assert.equal(0, code, out)
    -- cpfg; a format of 49 characters in EndEach ran into the guard of rule text's string
    -- patterns (the loader's own pattern: vlab's 07-canalization-output)
    assert.equal("a\tb=2.5\nTotal = 12, ray florets = 4, disc =  2.25%\n", out)
  end)

  it("rewrites a predecessor of several modules as cpfg does", function ()
    assert.equal("FFFFFFFFFFFFFFX", derive("multi.l"))    -- cpfg
    local m = lsys.cpfg.load(D .. "strict.l")             -- cpfg, step by step
    assert.equal("S(0)C(1),,,@o(1);;;KB[,,@o(1)]", tostring(m:derive(1)))
    assert.equal("S(0)C(2)[,,@o(1)]B[,,@o(1)]", tostring(m:derive(2)))
    assert.equal("S(0)C(3)[,,@o(1)]B[,,@o(1)]", tostring(m:derive()))
  end)

  it("wraps contexts around the string in a ring L-system", function ()
    assert.equal("XBY", derive("ring.l"))                 -- cpfg
  end)

  it("gives every production of a stochastic L-system a weight (1 by default)", function ()
    local s = lsys.cpfg.load(D .. "stochastic.l"):derive()
    local b, c = s:count("B"), s:count("C")
    assert.equal(100, b + c)
    assert.is_true(b > 55 and b < 95, "B: " .. b)
  end)

  it("loads a vlab object folder through its specifications", function ()
    local m = lsys.cpfg.load_object(D .. "object")
    assert.equal("FFFFFFFFFFFFFFX", tostring(m:derive()))
    assert.equal(45, m.view.angle)
  end)

  it("takes only -m, -m1, -M and -M1 as the palette of an object", function ()
    -- vlab's Sedge: cpfg -m2 sedge.map2 female.l ... (colour map 2, not the palette)
    local m = lsys.cpfg.load_object(D .. "object2")
    assert.is_nil(m.view.palette)
    assert.equal("FFFFFFFFFFFFFFX", tostring(m:derive()))
  end)
end)

describe("lsys.cpfg.load errors", function ()
  local function err (file, opts)
    local ok, msg = pcall(lsys.cpfg.load, D .. file, nil, opts)
    assert.is_false(ok)
    return msg
  end

  it("names the file and line of a syntax error", function ()
    assert.equal(D .. "errors_syntax.l:5: '->' is not a production arrow in cpfg; write '-->'",
                 err("errors_syntax.l"))
  end)

  it("never hands cpp a file name that reads as an option", function ()
    local H = require "tests.helper"
    local dir = H.tmpdir()
    H.write(dir .. "/-o", H.read(D .. "koch.l"))
    H.write(dir .. "/run.lua", 'print(#require("lsys").cpfg.load("-o"):derive())\n')
    local bin = H.ABSBIN
    -- loaded as "-o" from its folder: cpp reads ./-o and writes nothing
    local out, code = H.sh("cd '" .. dir .. "' && " .. bin .. " run.lua")
    assert.equal(0, code, out)
    assert.equal(tostring(#lsys.cpfg.load(D .. "koch.l"):derive()) .. "\n", out)
    local ls = H.sh("ls -A '" .. dir .. "'")
    assert.equal("-o\nrun.lua\n", ls)
    H.rmdir(dir)
  end)

  it("names a missing #include", function ()
    assert.equal(D .. "errors_include.l:6: missing.l: No such file or directory",
                 err("errors_include.l"))
  end)

  it("reads a predecessor of several modules in a homomorphism, and refuses one in a "
     .. "decomposition unless it is a name", function ()
    -- A(x)B: the homomorphism rewrites the two modules as one, as cpfg's does
    local s, m = derive("errors_multi.l")
    assert.equal("A(2)B", s)
    assert.equal("C", tostring(m:expand(m:derive())))
    assert.equal(D .. "errors_multi_decomp.l:6: a strict predecessor of several modules ('AB') "
                 .. "in a decomposition is supported only as letters and digits with "
                 .. "parameters on the last one", err("errors_multi_decomp.l"))
  end)

  it("runs the chosen production's post-condition block only, as cpfg", function ()
    assert.equal("C(10)B(11)C(21)B(22)B(23)C(33)", derive("stochpost.l"))     -- cpfg
  end)

  it("refuses a post-condition block with side effects in a stochastic production with "
     .. "lsys's generator", function ()
    assert.equal(D .. "errors_stoch.l:6: in a stochastic L-system, a post-condition block "
                 .. "that assigns g is not supported (lsys runs the blocks of every production "
                 .. "that applies, cpfg only the chosen one's)",
                 err("errors_stoch.l", { random = "lsys" }))
    assert.truthy(lsys.cpfg.load(D .. "errors_stoch.l"))
  end)

  it("keeps rule code away from globals", function ()
    local o = lsys.cpfg.options(D .. "blocks.l")
    local nfn = 0
    for _, r in ipairs(o.productions) do
      if type(r) == "table" then
        nfn = nfn + 1
        local i = 1
        while true do
          local name, v = debug.getupvalue(r[2], i)
          if not name then break end
          assert.is_not.equal(_G, v)
          i = i + 1
        end
      end
    end
    assert.equal(1, nfn)   -- the A rule (a while loop) is a function rule
  end)
end)

-- Constructs met in vlab's models (tools/cpfg-compare.lua --all); every string from cpfg.
describe("lsys.cpfg.load on vlab's constructs", function ()
  -- numbers as cpfg prints them (6 digits): lsys keeps float32 values, 0.9 is 0.89999998
  local function g (s) return (s:gsub("[-%d.]+", function (x) return ("%g"):format(x) end)) end
  -- the warnings `fn` gives, and its results
  local function warnings (fn)
    local warning = require "lsys.warning"
    local saved, got = warning.warn, {}
    warning.warn = function (msg) got[#got + 1] = msg end
    local r = table.pack(pcall(fn))
    warning.warn = saved
    assert(r[1], r[2])
    return got, table.unpack(r, 2, r.n)
  end

  it("refuses ?E without an environment, derives it as cpfg without one on request, and " ..
     "asks the environment given", function ()
    local ok, msg = pcall(lsys.cpfg.load, D .. "envq.l")
    assert.is_false(ok)
    assert.equal(D .. "envq.l:5: ?E (a query of the environment) needs an environment: give "
                 .. "the model one (option 'environment', docs/open.md), or environment = "
                 .. "\"none\" (--environment none) to derive it as cpfg does without one", msg)
    assert.equal("A(3)?E(7,6)", derive("envq.l", nil, { environment = "none" }))   -- cpfg
    -- string 0 is answered 20, string 1 (A(2)?E(21,6)) 40: the rules add 1 after each
    local function env (_, info) return { { 20 * (info.step + 1) } } end
    assert.equal("A(3)?E(41,6)", derive("envq.l", nil, { environment = env }))
    assert.error_matches(function () lsys.cpfg.load(D .. "envq.l", nil, { environment = 1 }) end,
                         "option 'environment' must be \"none\", a communication file "
                         .. "(.e) or an environment", 1, true)
  end)

  it("takes a number too large for a double as infinite in a block", function ()
    assert.equal("B(1,1)", derive("infinite.l"))                        -- cpfg
  end)

  it("reads a module's parameters after blanks, as cpfg's lexer does", function ()
    assert.equal("A(3)F(2)F(2)B", derive("blankparen.l"))               -- cpfg
  end)

  it("leaves out a surface or texture file that is not there, with a warning, as cpfg",
     function ()
    local got, m = warnings(function ()
      return lsys.cpfg.load(D .. "nofiles.l", D .. "nofiles.v")
    end)
    assert.same({
      D .. "nofiles.v:1: 'texture': cannot open 'gone.rgb'; left out, as cpfg does (the "
        .. "textures after it move down a place)",
      D .. "nofiles.v:3: 'surface': cannot open 'bract.s'; ~b draws nothing (as in cpfg)",
    }, got)
    assert.is_nil(m.view.surfaces.b)
    assert.equal(1, #m.view.textures)                    -- the second moved down
    assert.equal("../views/leaf.png", m.view.textures[1].file)
    assert.is_nil(m.view.surfaces.l.texture)             -- texture 2 is gone: untextured
    local sc = m:interpret()
    assert.equal(3, sc.nlines)                           -- the F's; ~b draws nothing
    assert.equal(50, sc.ntriangles)                      -- ~l: leaf.s
  end)

  it("skips a character cpfg's expression lexer skips, with a warning", function ()
    local got, s = warnings(function () return derive("stray.l") end)
    assert.equal("B(2)B(4)A(3)", s)                                     -- cpfg
    assert.same({ D .. "stray.l:8: stray '\\' in an expression ignored (as cpfg does)",
                  D .. "stray.l:8: stray '\\' in an expression ignored (as cpfg does)" }, got)
  end)

  it("gives a string its number among the file's strings; printf reads \\t, \\n, %lf",
     function ()
    local H = require "tests.helper"
    local dir = H.tmpdir()
    local saved = io.output()
    io.output(dir .. "/out")
    local ok, s = pcall(derive, "strings.l")
    io.output():close()
    io.output(saved)
    assert(ok, s)
    assert.equal("@L(2,1)C(4,1)@L(3,1)@L(1)", s)                        -- cpfg
    assert.equal("start\t1.500000  2.25\n", H.read(dir .. "/out"))     -- cpfg's printf
    H.rmdir(dir)
  end)

  it("runs Start: before it computes the axiom", function ()
    local m = lsys.cpfg.load(D .. "startaxiom.l")
    assert.equal("C(0.9,1)B(1.8,1)", g(tostring(m:derive())))          -- cpfg
    assert.equal("C(0.9,1)B(1.8,1)", g(tostring(m:derive())))          -- and every time
  end)

  it("reads a line starting with the module # as text, with either preprocessor", function ()
    for _, how in ipairs { "system", "builtin" } do
      assert.equal("F(1)#(0.5)F(2)#(0.25)F(3)", derive("hashline.l", nil, { cpp = how }))
    end                                                                 -- cpfg
  end)

  it("takes a maximum depth above 1024 as 1024, with a warning", function ()
    local got, m = warnings(function () return lsys.cpfg.load(D .. "depth.l") end)
    assert.same({ D .. "depth.l:7: maximum depth 3000 taken as 1024, lsys's limit" }, got)
    -- cpfg -homo
    assert.equal(("F"):rep(49) .. "A(50)", tostring(m:expand(m:derive())))
  end)

  it("keeps cpfg's default for a view value left as '?' (angle increment 45)", function ()
    local got, m = warnings(function ()
      return lsys.cpfg.load(D .. "exercise.l", D .. "exercise.v")
    end)
    assert.equal(45, m.view.angle)
    assert.equal(2, m.view.color)
    assert.same({ D .. "exercise.v:1: 'angle increment': '?' is not a value; the line is "
                  .. "ignored" }, got)
    -- cpfg: the positions after + and F at 45 degrees
    assert.equal("+F?P(-0.707107,0.707107)!F?P(-1.41421,1.41421)", g(tostring(m:derive())))
  end)
end)

describe("lsys.cpfg.load with cpfg's random numbers (the default)", function ()
  -- module names and parameters within cpfg's printed precision (6 digits)
  local function same (s, cpfg)
    local a, b = {}, {}
    for n, p in s:gmatch("([^()])(%b())") do a[#a + 1] = { n, p } end
    for n, p in cpfg:gmatch("([^()])(%b())") do b[#b + 1] = { n, p } end
    assert.equal(s:gsub("%b()", ""), (cpfg:gsub("%b()", "")))
    assert.equal(#b, #a)
    for i = 1, #a do
      local x, y = {}, {}
      for v in a[i][2]:gmatch("[^(),]+") do x[#x + 1] = tonumber(v) end
      for v in b[i][2]:gmatch("[^(),]+") do y[#y + 1] = tonumber(v) end
      assert.equal(#y, #x)
      for k = 1, #x do assert.near(y[k], x[k], 1e-5 * math.max(1, math.abs(y[k]))) end
    end
  end

  it("gives cpfg's string: a stochastic choice, ran, nran, bran and biran in cpfg's order",
     function ()
    local m = lsys.cpfg.load(D .. "cpfgrandom.l")
    local s = m:derive()
    same(tostring(s), "A(2)C(0.159248,7)C(0.669283,5)[-D(0.774447)]F(5)F[B(7.49902)]A(3)"   -- cpfg
         .. "C(0.142851,3)[-B(5.76559)]F(4.88299)C(0.698823,5)")
    -- cpfg -homo: the homomorphism draws from the derivation's generator, and cpfg's -g
    -- writes the string of its second interpretation (after the view-volume pass)
    m:expand(s)
    same(tostring(m:expand(s)), "A(2)E(0.960761)G(0.159248)E(0.144375)G(0.669283)"      -- cpfg
         .. "[-D(0.774447)]F(5)F[B(7.49902)]A(3)E(0.446683)G(0.142851)[-B(5.76559)]F(4.88299)"
         .. "E(0.324584)G(0.698823)")
  end)

  it("draws the choice number for every module of a stochastic L-system", function ()
    assert.equal("CFCFCFDFBAFCFDFBAFCFBAF", derive("stochchoice.l"))   -- cpfg
  end)

  it("starts a homomorphism with its own seed again at every interpretation", function ()
    local m = lsys.cpfg.load(D .. "homoseed.l")
    local s = m:derive()
    same(tostring(s), "AB(0.870465)B(0.170828)AB(0.577304)B(0.749902)AB(0.785799)"   -- cpfg
         .. "B(0.0963717)")
    -- cpfg's TurtleDraw starts the homomorphism's erand48 at {0x330E, 99, 0} each time:
    -- C(ran) draws its 1st, 2nd and 7th numbers (nran's pair took 3 to 6), and the first
    -- nran gives the mean (cpfg's nrand flag starts at 10); nran's pair is the process's,
    -- so the second interpretation's nran numbers go on from the first's
    local first, second = tostring(m:expand(s)), tostring(m:expand(s))
    same(first:gsub("C%(([^,]*),[^)]*%)", "C(%1)"), "AC(0.380257)C(0.504358)AC(0.736335)"
         .. "C(0.913879)AC(0.0572016)C(0.0958014)")
    assert.equal("0", first:match("^AC%([^,]*,([^)]*)%)"))
    assert.equal(first:gsub(",[^)]*%)", ")"), (second:gsub(",[^)]*%)", ")")))
    assert.not_equal(first, second)
  end)

  it("gives lsys's generator with random = \"lsys\"", function ()
    local a = lsys.cpfg.load(D .. "stochchoice.l", nil, { random = "lsys" })
    assert.equal("lsys", a.random)
    assert.not_equal("CFCFCFDFBAFCFDFBAFCFBAF", tostring(a:derive()))
    assert.error_contains(function () lsys.cpfg.load(D .. "stochchoice.l", nil, { random = 1 }) end,
                          "option 'random' must be \"cpfg\" or \"lsys\"")
  end)
end)

describe("lsys.cpfg.load on a stochastic model", function ()
  -- cpfg's statistics of stoch_stats.l over 300 runs, each with its own seed written into
  -- a copy of the file (seed: for the productions, Start: {srand(k);} for ran and nran):
  --   lua5.4 tools/cpfg-stats.lua CPFG -n 300 --seed 7 tests/data/cpfg/stoch_stats.l V.v
  -- (V.v an empty view). Mean and standard deviation per run of the count of X, Y, Z and
  -- of the means of I's and X's parameter. Expected: 40 choices with weights 1 : 2 : 0.5,
  -- ran(2) (mean 1) and nran(5, 1).
  local CPFG, RUNS = {
    X = { 11.41, 2.864 }, Y = { 22.883, 2.976 }, Z = { 5.7067, 2.247 },
    ["I.1"] = { 1.0057, 0.09366 }, ["X.1"] = { 4.996, 0.3153 },
  }, 300

  it("matches cpfg's counts and parameter means within 4 standard errors with lsys's "
     .. "generator", function ()
    -- lsys's generator draws ran and nran from the seed too (cpfg's only from srand)
    local m = lsys.cpfg.load(D .. "stoch_stats.l", nil, { random = "lsys" })
    local K, got = 200, {}
    for k in pairs(CPFG) do got[k] = {} end
    for seed = 1, K do
      m.seed = seed
      local s = m:derive()
      local count, sum = {}, {}
      local f, st, c = s:modules()
      while true do
        local i, name, x = f(st, c)
        if i == nil then break end
        c = i
        count[name] = (count[name] or 0) + 1
        if x then sum[name] = (sum[name] or 0) + x end
      end
      for _, n in ipairs { "X", "Y", "Z" } do table.insert(got[n], count[n] or 0) end
      table.insert(got["I.1"], sum.I / count.I)
      if count.X then table.insert(got["X.1"], sum.X / count.X) end
    end
    for k, ref in pairs(CPFG) do
      local xs, mean, ss = got[k], 0, 0
      for _, x in ipairs(xs) do mean = mean + x / #xs end
      for _, x in ipairs(xs) do ss = ss + (x - mean) ^ 2 end
      local sd = math.sqrt(ss / (#xs - 1))
      local tol = 4 * math.sqrt(ref[2] ^ 2 / RUNS + sd ^ 2 / #xs)
      assert(math.abs(mean - ref[1]) <= tol,
             ("%s: lsys %.4g, cpfg %.4g (tolerance %.3g)"):format(k, mean, ref[1], tol))
      assert(sd > ref[2] / 2 and sd < ref[2] * 2,
             ("%s: lsys's spread %.3g, cpfg's %.3g"):format(k, sd, ref[2]))
    end
  end)
end)
