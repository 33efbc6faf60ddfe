-- Open L-systems: ?E modules and the model option `environment` (docs/open.md): when the
-- environment is asked (before each step, of the string before it, never of the final
-- string, as cpfg's environmental pass), what a query holds, how answers replace the ?E's
-- parameters, several environments, and the errors and warnings.
local lsys = require "lsys"
local warning = require "lsys.warning"

-- The warnings fn() gives, in a list.
local function warnings (fn)
  local got, saved = {}, warning.warn
  warning.warn = function (msg) got[#got + 1] = msg end
  local ok, err = pcall(fn)
  warning.warn = saved
  assert(ok, err)
  return got
end

-- A model whose productions are `prods`, asking `env`.
local function model (axiom, prods, env, extra)
  local o = { axiom = axiom, productions = prods, environment = env, steps = 1,
              view = { angle = 90 } }
  for k, v in pairs(extra or {}) do o[k] = v end
  return lsys.lsystem(o)
end

describe("the environment of an open L-system", function ()
  it("is asked before each step about the string before it, never about the final one",
     function ()
    local asked = {}
    local m = model("A(0)", "A(x) --> F(1) ?E(0) A(x + 1)", function (queries, info)
      asked[#asked + 1] = info.step .. ":" .. #queries
      local out = {}
      for i, q in ipairs(queries) do out[i] = 10 * q.position[2] + info.step end
      return out
    end, { steps = 3 })
    assert.equal("F(1)?E(12)F(1)?E(22)F(1)?E(0)A(3)", tostring(m:derive()))
    assert.same({ "1:1", "2:2" }, asked)       -- string 0 (the axiom) holds no ?E
  end)

  it("gives each query its parameters, the turtle's frame, width, scale and the next module",
     function ()
    local got
    local m = model("#(3)F(2)?E(1,2)+(90)F(1)[?E]?E(5)", "", function (queries)
      got = queries
    end, { steps = 1 })
    m:derive()
    assert.equal(3, #got)
    local q = got[1]
    assert.equal(3, q.index)
    assert.same({ 1, 2 }, q.params)
    assert.same({ 0, 2, 0 }, q.position)
    assert.same({ 0, 1, 0 }, q.heading)
    assert.same({ -1, 0, 0 }, q.left)
    assert.same({ 0, 0, -1 }, q.up)
    assert.equal(3, q.width)
    assert.equal(1, q.scale)
    assert.equal("+", q.following)
    assert.same({ 90 }, q.following_params)
    assert.equal(7, got[2].index)
    assert.same({}, got[2].params)
    assert.equal("]", got[2].following)
    assert.near({ -1, 2, 0 }, got[2].position, 1e-12)
    assert.near({ -1, 0, 0 }, got[2].heading, 1e-12)
    assert.equal(9, got[3].index)
    assert.is_nil(got[3].following)           -- the end of the string
    assert.is_nil(got[3].following_params)
  end)

  it("replaces parameters with the answers given, keeps the others, drops extra values " ..
     "with a warning", function ()
    local m = model("?E(1,2,3)?E(4,5)?E(6)?E(7)?E", "", function ()
      return { { 10, nil, 30, n = 3 }, { false, 50 }, 60, false, { 1 } }
    end)
    local s
    local w = warnings(function () s = m:derive() end)
    assert.equal("?E(10,2,30)?E(4,50)?E(60)?E(7)?E", tostring(s))
    assert.equal(1, #w)
    assert.truthy(w[1]:find("the environment gave 1 values for the ?E of 0 parameters "
      .. "at module 5: the rest are dropped (at step 0)", 1, true), w[1])
  end)

  it("sees the ?E the homomorphism makes, and drops their answers", function ()
    local got
    local m = model("A?E(1)", "", function (queries)
      got = queries
      return { 100, 200 }
    end, { homomorphism = "A --> ?E(9)G(2)" })
    assert.equal("A?E(200)", tostring(m:derive()))
    assert.equal(2, #got)
    assert.is_nil(got[1].index)                  -- made by the homomorphism
    assert.same({ 9 }, got[1].params)
    assert.equal("G", got[1].following)
    assert.same({ 2 }, got[1].following_params)
    assert.equal(2, got[2].index)
    assert.same({ 0, 2, 0 }, got[2].position)    -- after the expansion's G(2)
  end)

  it("routes queries by their first parameter to a list of environments", function ()
    local seen = {}
    local function env (name)
      return function (queries)
        local out = {}
        for i, q in ipairs(queries) do
          local t = {}
          for k, x in ipairs(q.params) do t[k] = ("%g"):format(x) end
          seen[#seen + 1] = name .. "(" .. table.concat(t, ",") .. ")"
          out[i] = { q.params[1] * 2 }
        end
        return out
      end
    end
    local obj = { answer = function (self) return { self.k, self.k } end, k = 7 }
    local m = model("?E(2,5)?E(1,3,4)?E(3,0)?E(1,1)", "", { env "a", env "b", obj })
    assert.equal("?E(2,10)?E(1,6,4)?E(3,7)?E(1,2)", tostring(m:derive()))
    assert.same({ "a(3,4)", "a(1)", "b(5)" }, seen)
  end)

  it("gives the environment the plant as the turtle draws it, closed after the pass",
     function ()
    local kept
    local m = model("F(1)[+F(1)?E(0)]F(1)?E(0)", "", function (queries, info)
      kept = info.scene
      return { info.scene.nlines, #queries }
    end, { view = { angle = 45 } })
    assert.equal("F(1)[+F(1)?E(3)]F(1)?E(2)", tostring(m:derive()))
    assert.error_contains(function () return kept.nlines end, "closed")
  end)

  it("sends the ?E of a sub-L-system with the turtle it scales", function ()
    local got
    lsys.lsystem { axiom = "F(1)?(2,0.5)F(1)?E(0)$F(1)?E(0)", steps = 1,
                   sub = { [2] = { productions = "B --> B" } },
                   environment = function (qs) got = qs end }:derive()
    assert.equal(2, #got)
    assert.same({ 4, 0.5, { 0, 1.5, 0 } }, { got[1].index, got[1].scale, got[1].position })
    assert.same({ 7, 1, { 0, 2.5, 0 } }, { got[2].index, got[2].scale, got[2].position })
  end)

  it("runs in a lone step, and a model's step counts from the string given", function ()
    local m = model("", "", function (queries, info)
      assert.is_nil(info.step)
      return { #queries }
    end)
    assert.equal("?E(1)F", tostring(m:step("?E(0)F")))
  end)

  it("says what is wrong with the option, an answer or an environment that fails",
     function ()
    assert.error_contains(function () model("F", "", 3) end,
      "option 'environment' must be a function (queries, info) -> answers, an object with "
      .. "an answer method, or a list of those (got number)")
    assert.error_contains(function () model("F", "", { function () end, 2 }) end,
      "option 'environment': entry 2 of the list is not an environment")
    local m = model("?E(1)", "", function () return { "x" } end)
    assert.error_contains(function () m:derive() end,
      "model: environment: answer 1 must be a number or a list of numbers, got string")
    m = model("?E(1)", "", function () return { 0 / 0 } end)
    assert.error_contains(function () m:derive() end,
      "environment: answer 1, value 1: a finite number expected, got")
    m = model("?E(1)", "", function () error("no light here", 0) end)
    assert.error_contains(function () m:derive() end, "model: environment: no light here")
    m = model("?E(1)", "", function () return 5 end)
    assert.error_contains(function () m:derive() end,
      "environment: the answers must be a table (a list, one entry a query), got number")
    m = model("?E(1)?E(4)", "", { function () end })
    assert.error_contains(function () m:derive() end,
      "model: environment: ?E module 2: its first parameter must be the number of one of "
      .. "the 1 environments, got 4")
  end)

  it("keeps the queries of a pass within the model's max_memory", function ()
    local m = lsys.lsystem { axiom = "A", steps = 16, max_memory = "8M",
                             productions = "A --> ?E(0)[A]A", environment = function () end }
    assert.error_contains(function () m:derive() end, "the environment's 16383 queries would "
      .. "need more than max_memory (8 MiB) as Lua tables")
  end)

  it("warns once when the string has ?E modules and the model no environment", function ()
    local m = lsys.lsystem { axiom = "A", productions = "A --> ?E(1)A", steps = 3 }
    local w = warnings(function () m:derive() end)
    assert.equal(1, #w)
    assert.truthy(w[1]:find("the string has ?E modules but the model has no "
      .. "environment: they keep the parameters the rules give them", 1, true))
    m = lsys.lsystem { axiom = "A", productions = "A --> ?E(1)A", steps = 3,
                       environment = false }
    assert.same({}, warnings(function () m:derive() end))
  end)

  it("fills ?P in the same pass, and ?E answers are float32 in a float32 model", function ()
    local m = model("F(1)?P(0,0,0)?E(0)", "", function () return { 0.1 } end,
                    { numbers = "float32" })
    local s = m:derive()
    local _, x, y = s:module(2)
    assert.equal(0, x); assert.equal(1, y)
    local _, e = s:module(3)
    assert.equal(string.unpack("f", string.pack("f", 0.1)), e)
  end)
end)

describe("examples/open", function ()
  it("ulam.lua grows Ulam's crystal: cpfg's string with vlab's honda81 program", function ()
    local m = dofile("examples/open/ulam.lua")
    local s = m:derive()
    -- the counts of the string cpfg derives from 07-Open/01-ulam-collide (16 steps, honda81):
    -- 344 segments, 692 sensors still waiting, every one at VIGOR (none left at 1 or 0)
    assert.equal(4143, #s)
    assert.same({ ["+"] = 345, ["-"] = 345, [";"] = 340, ["?E"] = 692, F = 344, ["["] = 692,
                  ["]"] = 692, f = 692, ["|"] = 1 }, s:counts())
    assert.equal(692, #tostring(s):gsub("[^?]", ""))
    assert.truthy(tostring(s):find("^%[F%[%+f%?E%(0%.5%)%]%[%-f%?E%(0%.5%)%];F%[%+;F%["))
    -- the collisions stop growth: without an environment every sensor grows
    local closed = lsys.lsystem { axiom = m.axiom, steps = 6, env = m.env,
      productions = "f ?E(x) --> ;F A", decomposition = "A --> [+f ?E(1)][-f ?E(1)]f ?E(1)",
      environment = false }
    local open = dofile("examples/open/ulam.lua")
    open.steps = 6
    assert.is_true(closed:derive():count("F") > open:derive():count("F"))
  end)
end)

describe("cpfg's communication files (.e)", function ()
  local efile = require "lsys.environment.efile"
  local dir
  before_each(function () dir = os.tmpname(); os.remove(dir); os.execute("mkdir " .. dir) end)
  after_each(function () os.execute("rm -rf " .. dir) end)
  local function efilewith (text)
    local f = assert(io.open(dir .. "/field.e", "w"))
    f:write(text)
    f:close()
    return dir .. "/field.e"
  end

  it("say which program to start, how to talk to it and what each query carries",
     function ()
    local path = efilewith("executable: honda81 density.spec\ncommunication type: files\n"
      .. "turtle position:P:%.4f %.4f %.0f\nturtle line width: %5.2lf\nverbose: off\n")
    local e = efile.read(path)
    assert.equal("files", e.transport)
    assert.equal(1000, e.max)
    assert.same({ "honda81", "-e", "field.e", "density.spec" }, e.argv)
    assert.equal(dir, e.dir)
    assert.same({ position = "P:%.4f %.4f %.0f", width = " %5.2f" }, e.formats)
    assert.is_true(e.following)
    e = efile.read(efilewith("communication type: pipes 50\nexecutable: c -e x.e s &\n"
      .. "following module: no\n"))
    assert.equal(50, e.max)
    assert.same({ "c", "-e", "x.e", "s" }, e.argv)
    assert.is_false(e.following)
    assert.is_nil(efile.read(efilewith("communication type: memory\nexecutable: c\n")).max)
  end)

  it("name the file and line of what lsys cannot do", function ()
    local function err (text) return select(2, pcall(efile.read, efilewith(text))) end
    assert.equal(dir .. "/field.e:1: communication type 'sockets': lsys speaks pipes, files "
      .. "and memory", err("communication type: sockets\nexecutable: a\n"))
    assert.equal(dir .. "/field.e:2: remote host: lsys does not send a program on another "
      .. "host", err("executable: a\nremote host: b\n"))
    assert.equal(dir .. "/field.e:2: the format takes 4 values, the turtle sends 3",
      err("executable: a\nturtle position: %g %g %g %g\n"))
    assert.truthy(err("executable: a\nturtle up: %d %d %d\n"):find("field.e:2: turtle format "
      .. "' %d %d %d': the % at character 2 is not a conversion", 1, true))
    assert.equal(dir .. "/field.e: no 'executable:' line: which program answers the queries?",
      err("communication type: pipes\n"))
    assert.truthy(err("verbose: on\n"):find("no 'executable:' line", 1, true))
  end)

  it("skip unknown directives and blank lines with a warning, as cpfg", function ()
    local w = warnings(function ()
      efile.read(efilewith("executable: a\n\nradius: 2\n"))
    end)
    assert.same({ "lsys: " .. dir .. "/field.e:2: not a directive of a communication file: "
      .. "skipped", "lsys: " .. dir .. "/field.e:3: unknown directive 'radius' in a "
      .. "communication file: skipped" }, w)
  end)
end)

describe("the text cpfg's environmental programs read", function ()
  local program = require "lsys.environment.program"

  it("writes a query as cpfg does: the module, the one after it, the turtle's values",
     function ()
    local spec = { formats = { position = "P:%.4f %.4f %.0f", width = " %g", scale = " %g" },
                   following = true }
    local q = { params = { 0.5 }, position = { -1, 1, 0.4 }, scale = 0.5, following = "]",
                following_params = {} }
    assert.equal("12 E(0.5)]\nP:-1.0000 1.0000 0\n 1\n 0.5\n", program.item(spec, q, 12, 2))
    q.params, q.following, q.following_params = { 0.1, 3 }, "F", { 2.5 }
    assert.equal("0 E(0.1,3)F(2.5)\nP:-1.0000 1.0000 0\n 1\n 0.5\n",
                 program.item(spec, q, 0, 2))
    q.following = "?E"
    assert.truthy(program.item(spec, q, 0, 2):find("^0 E%(0.1,3%)%?\n"))
    q.following = "@Gs"
    assert.truthy(program.item(spec, q, 0, 2):find("^0 E%(0.1,3%)@G\n"))
    spec.following = false
    assert.truthy(program.item(spec, q, 0, 2):find("^0 E%(0.1,3%)\n"))
  end)

  it("reads the answers: an empty field keeps a parameter, the Control line ends them",
     function ()
    local got = {}
    assert.equal(1, program.parse("0 E(0)\n12 E(,5)\nxx\n22 E(1e2,junk)\nControl: 1\n"
      .. "30 E(9)\n", got))
    assert.same({ [0] = { 0, n = 1 }, [12] = { nil, 5, n = 2 }, [22] = { 100, 0, n = 2 } }, got)
  end)
end)

describe("an environmental program as the environment", function ()
  local H = require "tests.helper"
  local ENVSLAVE = os.getenv("LSYS_ENVSLAVE")
    or H.absolute((os.getenv("LSYS_BUILD_DIR") or "build") .. "/lsys_envslave")
  local dir
  setup(function () dir = H.tmpdir() end)
  teardown(function () H.rmdir(dir) end)

  -- a communication file for lsys_envslave answering as `spec` over `transport`
  local function efile (transport, spec, extra)
    local path = dir .. "/" .. transport:gsub(" ", "") .. "-" .. spec .. ".e"
    H.write(path, "executable: " .. ENVSLAVE .. " " .. spec .. "\ncommunication type: "
      .. transport .. "\nturtle position: %g %g %g\n" .. (extra or ""))
    return path
  end

  local function derive (axiom, env, extra)
    local o = { axiom = axiom, steps = 1, view = { angle = 90 }, environment = env }
    for k, v in pairs(extra or {}) do o[k] = v end
    return tostring(lsys.lsystem(o):derive())
  end

  for _, t in ipairs { "pipes", "files", "memory" } do
    it("sends the queries over " .. t .. " and writes the program's answers", function ()
      local env = lsys.environment.program(efile(t, "sum"))
      -- each ?E learns the sum of the coordinates where it stands
      assert.equal("F(2)?E(2)+(90)F(3)?E(-1,7)", derive("F(2)?E(0)+(90)F(3)?E(0,7)", env))
      assert.equal("F(2)?E(2)+(90)F(3)?E(-1,7)", derive("F(2)?E(9)+(90)F(3)?E(0,7)", env))
      assert.equal("", H.sh("ls -A '" .. dir .. "' | grep field || true"))  -- files removed
    end)
  end

  it("sends a step in chunks and reads answers that come in parts", function ()
    local env = lsys.environment.program(efile("pipes 2", "chunks"))
    local axiom = ("?E(%d)"):rep(7):format(1, 2, 3, 4, 5, 6, 7)
    assert.equal("?E(2)?E(3)?E(4)?E(5)?E(6)?E(7)?E(8)", derive(axiom, env))
    env = lsys.environment.program(efile("files 3", "chunks"))
    assert.equal("?E(2)?E(3)?E(4)?E(5)?E(6)?E(7)?E(8)", derive(axiom, env))
  end)

  it("starts the program for each derivation and ends it after", function ()
    local env = lsys.environment.program(efile("pipes", "echo"))
    local m = lsys.lsystem { axiom = "?E(1)", productions = "?E(x) --> ?E(x)", steps = 3,
                             environment = env }
    assert.equal("?E(4)", tostring(m:derive()))           -- strings 0, 1 and 2 answered
    assert.is_nil(env.proc)                               -- ended
    assert.equal("?E(4)", tostring(m:derive()))           -- a fresh program, the same again
  end)

  it("stops the derivation with the program's name when it cannot start or answer",
     function ()
    local path = dir .. "/none.e"
    H.write(path, "executable: lsys-no-such-program x\n")
    local err = H.errof(derive, "?E(1)", lsys.environment.program(path))
    local tail = ": environment: environmental program 'lsys-no-such-program': not found on "
      .. "the PATH"
    assert.equal(tail, err:sub(-#tail))
    local env = lsys.environment.program(efile("pipes", "hang"), { timeout = 0.3 })
    err = H.errof(derive, "?E(1)", env)
    assert.truthy(err:find("0.3", 1, true) and err:find("lsys_envslave", 1, true), err)
    assert.error_contains(function () lsys.environment.program(dir .. "/missing.e") end,
                          "cannot open '" .. dir .. "/missing.e'")
  end)

  it("is given to a Lua model on the command line with --environment FILE.e", function ()
    local e = efile("pipes", "sum")
    local path = dir .. "/m.lua"
    H.write(path, 'return require("lsys").lsystem { axiom = "F(2)?E(0)", view = { angle = 90 } }')
    local out, code = H.sh(H.BIN .. " derive " .. path .. " --environment " .. e)
    assert.equal(0, code, out)
    assert.equal("F(2)?E(2)\n", out)
    out, code = H.sh(H.BIN .. " derive " .. path .. " --environment none")
    assert.equal(0, code, out)
    assert.equal("F(2)?E(0)\n", out)                       -- none: no warning either
    out, code = H.sh(H.BIN .. " derive " .. path .. " --environment nothing.e")
    assert.equal(2, code, out)
    assert.truthy(out:find("--environment must be none or a communication file (FILE.e) that "
                           .. "exists, got 'nothing.e'", 1, true), out)
  end)

  it("with vlab's honda81 gives the string of the Lua environment and of cpfg", function ()
    local bin = os.getenv("LSYS_ENVIRO_BIN")
    if not bin then
      return pending("vlab's environmental programs are not built (tools/enviro-build.sh; "
                     .. "LSYS_ENVIRO_BIN=their folder)")
    end
    local out, code = H.sh("cd tests/data/cpfg/open && PATH='" .. bin .. "':$PATH "
      .. H.absolute(H.BIN) .. " derive ulam.l ulam.v --environment ulam.e 2>/dev/null")
    assert.equal(0, code, out)
    local want = tostring(dofile("examples/open/ulam.lua"):derive())
    assert.equal(want, (out:gsub("\n", "")))
  end)
end)

describe("lsys.environment.collision", function ()
  it("answers as honda81: 0 where another query of the group and of no less vigour reaches",
     function ()
    local c = lsys.environment.collision { radius = 0.5 }
    local function q (x, y, v, g) return { position = { x, y, 0 }, params = { v, g } } end
    assert.same({ 0, 1, 1, 1, 0, 0 }, c:answer {
      q(0, 0, 1), q(0.3, 0, 2),          -- the weaker stops, the stronger goes on
      q(5, 5, 1), q(5.2, 5, 1, 1),       -- other groups never meet
      q(9, 0, 1), q(9, 0.5, 1) })        -- one vigour, within the radius: both stop
    assert.same({ 1, 1 }, c:answer { q(0, 0, 1), q(0.51, 0, 1) })
    assert.error_contains(function () lsys.environment.collision { radius = 0 } end,
                          "radius must be a number > 0")
  end)

  it("grows examples/open/ulam.lua as its own Lua environment does", function ()
    local m = dofile("examples/open/ulam.lua")
    local want = tostring(m:derive())
    m.environment = lsys.environment.collision { radius = 0.01 }
    assert.equal(want, tostring(m:derive()))
  end)
end)

describe("the queries of a pass", function ()
  it("carry cpfg's ids: a ?E's byte offset in cpfg's string from the first", function ()
    local got
    local m = lsys.lsystem { axiom = "?E(1,2)F(2)?E(3)@O(1)[+(90)F?E]/(45)?E(5,6,7)!(2)?E(1)"
      .. "?E(8)A", homomorphism = "A --> ?E(9)G(1)", environment = function (q) got = q end }
    m:derive(1)
    local ids = {}
    for k, q in ipairs(got) do ids[k] = q.cpfg_id end
    assert.same({ 0, 20, 45, 55, 80, 88, 1 }, ids)                  -- cpfg's, with its probe
  end)
end)

describe("lsys.environment.light", function ()
  it("answers the light each ?E sees of the sky through the plant's own geometry", function ()
    -- a bud under a leaf (a disc 0.5 above it) and one in the open
    local m = lsys.lsystem { steps = 1, view = { angle = 90 },
      axiom = "[F(1)?E(0)][+(90)f(3)-(90)F(1)?E(0,0,0,0)][f(1.5)&(90)@c(1.5)]",
      environment = lsys.environment.light { samples = 64 } }
    local s = m:derive()
    local _, shaded = s:module(3)
    assert.is_true(shaded > 0.3 and shaded < 0.8, shaded)   -- the disc hides part of the sky
    local _, open, dx, dy, dz = s:module(10)
    assert.equal(1, open)                                     -- nothing above it
    assert.near({ 0, 1, 0 }, { dx, dy, dz }, 0.05)            -- the sky's light comes from up
    -- a leaf's light: 1 open and facing up, 0 facing down (no light from below)
    local function leaf (axiom, facing)
      return tostring(lsys.lsystem { axiom = axiom, steps = 1,
        environment = lsys.environment.light { facing = facing } }:derive())
    end
    assert.equal("^(90)?E(1)", leaf("^(90)?E(0)", "up"))
    assert.equal("&(90)?E(0)", leaf("&(90)?E(0)", "up"))
    assert.equal("?E(1)", leaf("?E(0)", "heading"))
    assert.error_contains(function () lsys.environment.light { colour = 1 } end,
                          "lsys.environment.light: unknown option 'colour'")
    assert.error_contains(function () lsys.environment.light { facing = "down" } end,
                          "facing must be \"up\" or \"heading\"")
    m.environment = lsys.environment.light { samples = 0.5 }
    assert.error_contains(function () m:derive() end, "environment: lsys.environment.light: "
      .. "samples must be an integer in [1, 65536], got 0.5")
  end)

  it("grows examples/open/shade.lua's crown where the light is, alike on any threads",
     function ()
    local counts = {}
    for _, t in ipairs { 1, 2 } do
      local m = dofile("examples/open/shade.lua")
      m.threads = t
      local s = m:derive()
      counts[t] = { #s, s:count("B"), s:count("L"), s:count("F") }
    end
    -- the stems' tubes shade too, so these counts follow their shape (tubes that keep their
    -- section under a roll shade a little more than pinched ones did)
    assert.same({ 72692, 4002, 5337, 10674 }, counts[1])
    assert.same(counts[1], counts[2])
    -- in the dark every bud dies at its first pass
    local m = dofile("examples/open/shade.lua")
    m.environment = function (qs) local a = {} for i in ipairs(qs) do a[i] = 0 end return a end
    assert.equal(0, m:derive():count("B"))
  end)
end)

describe("lsys.stand", function ()
  it("grows one plant as it grows alone, and two that shade each other", function ()
    local want = tostring(dofile("examples/open/ulam.lua"):derive())
    local m = dofile("examples/open/ulam.lua")
    local own = m.environment
    local scene, s = lsys.stand({ { model = m } }, { environment = own })
    assert.equal(want, tostring(s[1]))
    assert.equal(1, scene.ninstances)
    assert.equal(own, m.environment)                       -- the model's own, given back
    -- two light-seeking plants 4 apart: each grows fewer buds than one alone
    local alone = dofile("examples/open/shade.lua")
    alone.steps = 10
    local n = alone:derive():count("B")
    local a, b = dofile("examples/open/shade.lua"), dofile("examples/open/shade.lua")
    a.steps, b.steps = 10, 10
    local got
    scene, s = lsys.stand({ { model = a, at = { -2, 0, 0 } }, { model = b, at = { 2, 0, 0 } } },
      { environment = { answer = function (self, qs, info)
        got = got or { n = #qs, plants = info.plants, x = qs[#qs].position[1] }
        return self.light:answer(qs, info)
      end, light = lsys.environment.light { samples = 48, radiance = "cosine" } } })
    assert.equal(2, scene.ninstances)
    assert.same({ n = 2, plants = 2, x = 2 }, got)         -- both plants' first buds, placed
    assert.is_true(s[1]:count("B") < n and s[2]:count("B") < n,
                   s[1]:count("B") .. " " .. s[2]:count("B") .. " " .. n)
  end)

  it("keeps a plant done growing in the scene the others see, and gives each one's string",
     function ()
    -- plant 1 stops after one step: at plant 2's third pass it still stands there
    local function plant (steps)
      return lsys.lsystem { axiom = "F(1) A", steps = steps, view = { angle = 90 },
                            productions = "A --> F(1) ?E(0) A" }
    end
    local seen = {}
    lsys.stand({ { model = plant(1) }, { model = plant(4), at = { 3, 0, 0 } } },
      { environment = function (qs, info)
        local _, hi = info.scene:bounds()
        seen[#seen + 1] = string.format("%d:%d:%d:%s:%s", info.step, #qs, info.scene.ninstances,
          tostring(info.lstrings[1] ~= nil), tostring(info.lstrings[2] ~= nil))
        assert(hi[1] >= 3 - 1e-9)                          -- plant 2 is in the scene too
        return {}
      end })
    -- at pass 1 both ask; then plant 1 is done (1 step) but is still drawn
    assert.same({ "1:1:2:false:true", "2:2:2:false:true", "3:3:2:false:true" }, seen)
  end)

  it("says what is wrong with the plants", function ()
    local m = dofile("examples/open/ulam.lua")
    assert.error_contains(function () lsys.stand({ { model = m }, { model = m } },
      { environment = m.environment }) end,
      "lsys.stand: plant 2: its model is plant 1's (each plant of a stand grows a model of "
      .. "its own)")
    assert.error_contains(function () lsys.stand({ { model = m } }, {}) end,
                          "opts.environment (the stand's environment) expected")
    assert.error_contains(function () lsys.stand({ { model = m, at = 3 } },
      { environment = m.environment }) end, "lsys.stand: plant 1: 'at'")
  end)
end)
