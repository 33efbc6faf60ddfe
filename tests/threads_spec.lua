-- The derivation step on several threads: the option `threads`, LSYS_THREADS, and
-- the same string for every number of threads (docs/manual.md §10).
-- ctest: slow (derives large strings on 1 to 8 threads)
local H = require "tests.helper"
local lsys = require "lsys"

local THREADS = { 1, 2, 3, 8 }
local MAXT = 64             -- the most threads a step may use

-- tostring of model `opts` derived `n` steps with each number of threads in THREADS; the
-- strings are long enough (over 8192 modules) for the steps to run on the worker threads.
local function derived (opts, n)
  local out = {}
  for _, t in ipairs(THREADS) do
    local o = {}
    for k, v in pairs(opts) do o[k] = v end
    o.threads = t
    out[#out + 1] = tostring(lsys.lsystem(o):derive(n))
  end
  return out
end

local function same_for_all (opts, n, min)
  local out = derived(opts, n)
  assert.is_true(#out[1] >= (min or 1), "a short string: " .. #out[1])
  for k = 2, #out do
    assert.is_true(out[k] == out[1], ("threads = %d differs from threads = 1"):format(THREADS[k]))
  end
  return out[1]
end

describe("threads", function()
  it("give the same D0L string for 1, 2, 3 and 8 threads", function()
    same_for_all({ axiom = "F", productions = "F --> F[+F]F[-F]F" }, 7, 100000)
  end)

  it("give the same parametric string (the expression machine)", function()
    same_for_all({ axiom = "A(1)", env = { R = 1.456 },
                   productions = "A(s) --> F(s)[+A(s/R)][-A(s/R)]\nF(x) : x > 0.1 --> F(x*1.01)" },
                 14, 50000)
  end)

  it("give Lua's values for conditions and values of one operation (run without the stack)",
     function()
    -- the worker threads run such programs directly (expr.h, lsys_expr_fast): the same
    -- string as the rules written as Lua functions, which run on the calling thread
    local axiom = H.rep("A(0,2)A(1,3)A(2.5,0.7)E(4)G(3)", 3000)
    local text = lsys.lsystem { axiom = axiom, threads = 2, productions = {
      "A(x, y) : x < 3 --> A(x + 1, y) B(x * y, 3 - x, x / 4, 5 / y, y - x, x)",
      "A(x, y) : x >= 3 --> C(y)",
      "B(a, b, c, d, e, f) --> B(a + 0.5, b, c, d, e, f)",
      "C(y) : y == 2 --> D",
      "C(y) : y ~= 3 --> C(y * 1.5)",
      "E(z) : z <= 4 --> E(z - 0.25)",
      "E(z) : z > 3.5 --> F",
      "G(x) : x - 1 > 0 --> G(x * 0.5 + 0.25)",
    } }
    local P = lsys.produce
    local lua = lsys.lsystem { axiom = axiom, productions = {
      { "A(x, y)", function (x, y)
          if x < 3 then
            return P("A(?,?)B(?,?,?,?,?,?)", x + 1, y, x * y, 3 - x, x / 4, 5 / y, y - x, x)
          end
          if x >= 3 then return P("C(?)", y) end
        end },
      { "B(a, b, c, d, e, f)", function (a, b, c, d, e, f)
          return P("B(?,?,?,?,?,?)", a + 0.5, b, c, d, e, f)
        end },
      { "C(y)", function (y)
          if y == 2 then return P("D") end
          if y ~= 3 then return P("C(?)", y * 1.5) end
        end },
      { "E(z)", function (z)
          if z <= 4 then return P("E(?)", z - 0.25) end
          if z > 3.5 then return P("F") end
        end },
      { "G(x)", function (x) if x - 1 > 0 then return P("G(?)", x * 0.5 + 0.25) end end },
    } }
    local a, b = tostring(text:derive(5)), tostring(lua:derive(5))
    assert.equal(594000, #a)
    assert.is_true(a == b, "the strings differ")
    assert.equal("DB(5,1,0.5,2.5,0,2)B(3.5,2,0.25,2.5,1,1)B(2,3,0,2.5,2,0)C(3)"
      .. "B(7.5,1,0.5,1.6666666666666667,1,2)", a:sub(1, 95))
  end)

  it("give the same stochastic string", function()
    same_for_all({ axiom = "F", seed = 7, productions = "F --> F[+F]F : 1\nF --> F[-F]F : 2\n"
                   .. "F --> FF : 1" }, 9, 20000)
  end)

  it("give the same numbers from ran and nran, in conditions, values and weights", function()
    local s = same_for_all({ axiom = H.rep("A(1)", 3000), seed = 11, productions = {
      "A(x) : ran(1) < 0.5 --> B(ran(x), nran(x, 2)) A(x + ran(1)) C",
      "A(x) --> A(x + 1) : ran(2)",
      "A(x) --> D(nran(0, 1)) : 1",
      "B(x, y) --> B(x + ran(1), y)",
    } }, 4, 8000)
    assert.is_truthy(s:find("B(", 1, true) and s:find("D(", 1, true))
  end)

  it("give the same context-sensitive string", function()
    local s = same_for_all({ axiom = "b" .. H.rep("a", 12000),
                             productions = "b < a --> b\nb --> a" }, 300, 12000)
    assert.is_true(s == H.rep("a", 300) .. "b" .. H.rep("a", 11700), "the signal is not at 301")
    same_for_all({ axiom = H.rep("A(1)B(2)[C(3)]", 3000), ignore = "+", productions = {
      "A(a) < B(b) > [C(c)] --> B(a + b + c)", "B(b) > [C(c)] --> B(b * c) +",
      "C(c) --> C(c + 1)" } }, 3, 12000)
  end)

  it("give the same string with groups, cuts, sub-L-systems and decomposition", function()
    same_for_all({ axiom = H.rep("A", 10000), productions = "A --> AB", seed = 3,
                   groups = { [1] = "B --> C(ran(1))" },
                   start_each = function (m, k) m:use_group(k % 2) end }, 3, 10000)
    same_for_all({ axiom = H.rep("F[AFF]F", 3000), productions = "A --> %\nF --> FF" }, 2, 10000)
    same_for_all({ axiom = H.rep("A?(2,1)A$", 3000), productions = "A --> AC",
                   sub = { [2] = { productions = "A --> B" } } }, 2, 10000)
    same_for_all({ axiom = H.rep("X", 10000), seed = 5, productions = "X --> A(1)",
                   decomposition = "A(x) --> B(x + ran(1)) C" }, 1, 10000)
  end)

  it("give the same string with rule functions (run on the calling thread)", function()
    same_for_all({ axiom = H.rep("A", 10000), seed = 9, productions = {
      { "A", function () return lsys.produce("B(?)A", lsys.ran(1)) end },
      "B(x) --> B(x + ran(1))" } }, 2, 20000)
  end)

  it("give the same errors, at the same module", function ()
    local function err (opts)
      local msgs = {}
      for _, t in ipairs(THREADS) do
        local o = { threads = t }
        for k, v in pairs(opts) do o[k] = v end
        msgs[#msgs + 1] = H.errof(function () lsys.lsystem(o):derive(1) end)
      end
      for k = 2, #msgs do assert.equal(msgs[1], msgs[k]) end
      return msgs[1]
    end
    local m = err { axiom = H.rep("A(1)", 9000) .. "A(0)" .. H.rep("A(1)", 9000),
                    productions = "A(x) --> A(1/x)" }
    assert.truthy(m:find("module 9001: value 1 is infinite", 1, true), m)
    -- rules of short programs are counted by their conditions alone: their values are
    -- checked when filling, in place too
    m = err { axiom = H.rep("A(1)", 9000) .. "A(0)" .. H.rep("A(1)", 9000),
              productions = "A(x) : x < 5 --> A(1 / x) B\nA(x) : x >= 5 --> A(x)" }
    assert.truthy(m:find("module 9001: value 1 is infinite", 1, true), m)
    m = err { axiom = H.rep("A(1)", 9000) .. "A(0)" .. H.rep("A(1)", 9000),
              productions = "A(x) : x < 5 --> A(1 / x)\nA(x) : x >= 5 --> A(x)" }
    assert.truthy(m:find("module 9001: value 1 is infinite", 1, true), m)
    -- two failing modules in different chunks, filled in place: the first one is named
    -- (chunks filled on several threads copy their modules aside first)
    m = err { axiom = H.rep("A(1)", 9000) .. "A(0)" .. H.rep("A(1)", 30000) .. "A(0)"
                .. H.rep("A(1)", 9000), productions = "A(x) --> A(1/x) B" }
    assert.truthy(m:find("module 9001: value 1 is infinite", 1, true), m)
    m = err { axiom = H.rep("A", 20000), productions = "A --> AA", max_modules = 30000 }
    assert.truthy(m:find("the string would exceed max_modules (30000 modules)", 1, true), m)
    m = err { axiom = H.rep("A", 20000), productions = "A --> AAAA", max_memory = 200000 }
    assert.truthy(m:find("would need more than max_memory", 1, true), m)
    -- many steps, each on the workers but the last: the buffers they leave are the same
    local msgs = {}
    for _, t in ipairs(THREADS) do
      local model = lsys.lsystem { axiom = "A(1,2,3)", max_memory = "64M", threads = t,
                                   productions = "A(x,y,z) --> A(x,y,z) A(x,y,z)" }
      msgs[#msgs + 1] = H.errof(function () model:derive(30) end)
      assert.equal(msgs[1], msgs[#msgs])
    end
    assert.truthy(msgs[1]:find("would need more than max_memory (64 MiB) at module", 1, true))
  end)

  it("give the same string derived in steps and derived at once", function()
    local m = lsys.lsystem { axiom = "A(1)", seed = 2, threads = 2,
                             productions = "A(s) --> F(s)[+A(s*ran(1))][-A(s/2)] : 1\n"
                               .. "A(s) --> F(s)A(s) : 1" }
    local s = m:derive(0)
    m.threads = 1
    for _ = 1, 16 do s = m:step(s) end
    m.threads = 3
    assert.equal(tostring(s), tostring(m:derive(16)))
  end)

  it("keep a derived string without parameters at a byte a module until it is read", function()
    local s = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F" }:derive(7)
    assert.equal(195311, #s)
    assert.is_true(s:bytes() < #s + 64, "bytes: " .. s:bytes())
    assert.equal(78125, s:count("F"))             -- reading it makes it two bytes a module
    assert.is_true(s:bytes() >= 2 * #s, "bytes: " .. s:bytes())
  end)

  it("rewrite a model with cpfg's generator on the worker threads when it draws nothing",
     function()
    -- a step on the calling thread widens the string to two bytes a module; the worker
    -- threads keep it at one, so the byte count tells which ran
    local plain = lsys.lsystem { axiom = "F", random = "cpfg", threads = 2,
                                 productions = "F --> F[+F]F[-F]F" }:derive(7)
    assert.is_true(plain:bytes() < #plain + 64, "bytes: " .. plain:bytes())
    -- ran() and a stochastic set take cpfg's numbers in the order of a scan: one thread
    for _, p in ipairs { "F --> F[+F]F[-F]F : 1\nF --> F[-F]F : 1",
                         "F : ran(1) < 0.5 --> F[+F]F[-F]F\nF --> FF" } do
      local out = {}
      for _, t in ipairs { 1, 2, 3 } do
        local s = lsys.lsystem { axiom = "F", random = "cpfg", seed = 5, threads = t,
                                 productions = p }:derive(7)
        assert.is_true(#s > 8192, "a short string: " .. #s)
        assert.is_true(s:bytes() >= 2 * #s, "bytes: " .. s:bytes())
        out[t] = tostring(s)
      end
      assert.is_true(out[2] == out[1] and out[3] == out[1], "threads differ: " .. p)
    end
  end)

  it("leave the strings each and end_each receive as they were", function()
    for _, t in ipairs(THREADS) do
      local kept, ended = {}, {}
      local m = lsys.lsystem { axiom = H.rep("A(1)", 9000), threads = t,
                               productions = "A(x) --> A(x + 1)" }
      local s = m:derive(4, { each = function (k, x) kept[k] = x end })
      m.end_each = function (_, x, k) ended[k] = x end
      m:derive(4)
      for k = 0, 4 do
        local x = kept[k]
        assert.equal(9000, #x)
        assert.same({ "A", k + 1 }, { x:module(1) })
        assert.same({ "A", k + 1 }, { x:module(9000) })
        if k > 0 then assert.same({ "A", k + 1 }, { ended[k]:module(4500) }) end
      end
      assert.equal(kept[4], s)
    end
  end)

  it("must be a whole number from 1 to " .. MAXT, function()
    for _, bad in ipairs { 0, -1, 1.5, MAXT + 1, 0 / 0 } do
      assert.error_contains(function () lsys.lsystem { threads = bad } end,
        "option 'threads' must be a whole number from 1 to " .. MAXT)
    end
    assert.error_contains(function () lsys.lsystem { threads = "2" } end,
      "option 'threads' must be a number (got string)")
    local m = lsys.lsystem { axiom = "F", threads = 4 }
    assert.equal(4, m.threads)
    m.threads = 0
    assert.error_contains(function () m:derive(1) end,
      "derive: threads must be a whole number from 1 to " .. MAXT .. " (got 0)")
  end)

  it("default to LSYS_THREADS when it is set", function()
    local script = [[
      local lsys = require "lsys"
      local s = lsys.lsystem { axiom = "F", seed = 1,
                               productions = "F --> F[+F]F : 1\nF --> F[-F] : 1" }:derive(9)
      io.write(#s, " ", s:count("+"), "\n")
    ]]
    local outs = {}
    for _, t in ipairs { "1", "2", "5", "junk" } do
      local out, code = H.lsys(script, { env = "LSYS_THREADS=" .. t })
      assert.equal(0, code, out)
      outs[#outs + 1] = out
    end
    for k = 2, #outs do assert.equal(outs[1], outs[k]) end
  end)
end)

-- The scene of `opts` derived `n` steps and interpreted with `threads`: its glb bytes
-- (vertices, normals, triangles, lines) and its records as text.
local function drawn (opts, n, threads, dir)
  local m = lsys.lsystem(opts)
  local s = m:derive(n)
  m.threads = threads
  local sc = m:interpret(s)
  local path = dir .. "/t" .. threads .. ".glb"
  sc:save(path)
  local recs = {}
  for i, r in sc:records() do
    if i % 7 == 1 or r.stiffness then
      recs[#recs + 1] = table.concat({ i, r.kind, r.module, tostring(r.parent), r.color,
        r.p1[1], r.p1[2], r.p1[3], r.H[1], r.H[2], r.U[3], r.w0, r.w1, r.length,
        r.stiffness and table.concat(r.stiffness, ",") or "-" }, " ")
    end
  end
  return H.read(path), table.concat(recs, "\n"), sc.ntriangles, #s
end

describe("interpretation on threads", function()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  local function same_scene (opts, n)
    local glb1, rec1, ntri, len = drawn(opts, n, 1, dir)
    assert.is_true(len > 65536, "a short string: " .. len)    -- long enough to be cut
    for _, t in ipairs { 2, 3 } do
      local glb, rec = drawn(opts, n, t, dir)
      assert.is_true(glb == glb1, ("threads = %d: other geometry"):format(t))
      assert.is_true(rec == rec1, ("threads = %d: other records"):format(t))
    end
    return ntri, #rec1
  end

  it("give the same lines and records for 1, 2 and 3 threads", function()
    local _, nrec = same_scene({ axiom = "F", productions = "F --> F[+F]F[-F]F",
                                 view = { angle = 25.7 } }, 7)
    assert.is_true(nrec > 10000)
  end)

  it("give the same cylinders, discs, spheres and stiffnesses", function()
    local ntri = same_scene({ axiom = "F", productions = "F --> FZ(1,2,3)[+F@O(0.2)]F[-!F@c(0.3)]F",
                              view = { angle = 25.7, line_style = "cylinder",
                                       contour_sides = 4, line_width = 0.2,
                                       tropisms = { { vector = {0, -1, 0},
                                                      elasticity = 0.05 } } } }, 7)
    assert.is_true(ntri > 100000)
  end)

  it("give the same cylinders when @!(n) changes their sides along the string", function()
    same_scene({ axiom = "F", productions = "F --> F[+@!(3)F@O(0.1)]F[-@!(24)F]@!(5)F",
                 view = { angle = 25.7, line_style = "cylinder", contour_sides = 4,
                          line_width = 0.2 } }, 7)
  end)

  it("warn about the first undefined surface on any number of threads", function()
    H.write(dir .. "/w.lua", 'local lsys = require "lsys"\n'
      .. 'local m = lsys.lsystem { axiom = "F", threads = tonumber(arg[1]) }\n'
      .. 'local s = m:lstring(("F[+F]"):rep(20000) .. "~Q" .. ("F[-F]~R"):rep(20000))\n'
      .. 'm:interpret(s)\n')
    for _, t in ipairs { 1, 2, 3 } do
      local out, code = H.sh(H.BIN .. " " .. dir .. "/w.lua " .. t)
      assert.equal(0, code, out)
      assert.equal("Lua warning: lsys: module 100001 '~Q': no such surface in the view "
                   .. "(view.surfaces); nothing drawn there, as in cpfg\n", out)
    end
  end)

  it("give the same ribbons, with a parametric string", function()
    same_scene({ axiom = "A(1)", productions = "A(s) --> F(s)[+A(s/1.456)][-A(s/1.456)]",
                 view = { angle = 30, line_style = "polygon" } }, 16)
  end)

  it("name the module one thread names when two pieces fail", function()
    local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F" }
    local text, k = tostring(m:derive(7)), 0
    text = text:gsub("F", function ()             -- the 90,000th and 30,000th F: no contour
      k = k + 1
      if k == 30000 or k == 90000 then return "@#(3)" end
    end)
    local s = m:lstring(text)
    local msgs = {}
    for _, t in ipairs { 1, 2, 3 } do
      m.threads = t
      local ok, err = pcall(m.interpret, m, s)
      assert.is_false(ok)
      msgs[t] = tostring(err)
    end
    assert.equal(msgs[1], msgs[2])
    assert.equal(msgs[1], msgs[3])
    assert.matches("contour 3 is not defined", msgs[1])
    local first = text:find("@#", 1, true)
    local before = text:sub(1, first - 1):gsub("%(.-%)", "")   -- one character a module
    assert.matches("module " .. (#before + 1) .. "[^%d]", msgs[1])
  end)
end)
