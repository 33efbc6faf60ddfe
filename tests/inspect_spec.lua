-- A model as text (lsys.inspect): m:rules() lists the rules set by set with their lines,
-- m:inspect() the options the model has and its rules, as the REPL prints a model
-- (docs/manual.md §3).
local lsys = require "lsys"
local H = require "tests.helper"

describe("m:rules()", function()
  local m = lsys.lsystem {
    axiom = "A(1)B", steps = 2,
    productions = "A(s) --> F(s)[+A(s/2)]\n\nB --> C",
    groups = { [10] = "B --> G", [2] = "B --> E" },
    sub = { [1] = { productions = "X --> Y" } },
    decomposition = "C --> D", homomorphism = { "D --> F", { "F", function () end, weight = 2 } },
  }

  it("lists every rule set by set, each set's in the order given, with its line", function()
    local rules = m:rules()
    local got = {}
    for i, r in ipairs(rules) do got[i] = ("%s|%d|%s"):format(r.set, r.line, r.text) end
    assert.same({ "productions|1|A(s) --> F(s)[+A(s/2)]", "productions|3|B --> C",
                  "group 2|1|B --> E", "group 10|1|B --> G", "sub-L-system 1|1|X --> Y",
                  "decomposition|1|C --> D", "homomorphism|1|D --> F", "homomorphism|2|F" },
                got)
    assert.is_nil(rules[1].fn)
    assert.is_function(rules[8].fn)
    assert.equal(2, rules[8].weight)
  end)

  it("prints a line a rule under the name of its set", function()
    assert.equal(table.concat({
      "productions:", "  1    A(s) --> F(s)[+A(s/2)]", "  3    B --> C",
      "group 2:", "  1    B --> E", "group 10:", "  1    B --> G",
      "sub-L-system 1:", "  1    X --> Y", "decomposition:", "  1    C --> D",
      "homomorphism:", "  1    D --> F", "  2    F --> (a Lua function), weight 2" }, "\n"),
      tostring(m:rules()))
  end)

  it("gives a new list each time, which the model does not read", function()
    local a = m:rules()
    a[1].text = "changed"
    table.remove(a)
    assert.equal("A(s) --> F(s)[+A(s/2)]", m:rules()[1].text)
    assert.equal(8, #m:rules())
  end)

  it("names the file and line of a cpfg model's productions", function()
    local dir = H.tmpdir()
    H.write(dir .. "/p.l", "lsystem: 1\nderivation length: 2\nAxiom: A\n" ..
      "A --> FA\nendlsystem\n")
    local c = lsys.cpfg.load(dir .. "/p.l")
    H.rmdir(dir)
    local r = c:rules()
    assert.equal(dir .. "/p.l:4", r[1].where)
    -- (the loader also makes the L-system sub-L-system 1, for ?(1))
    assert.equal("productions:\n  " .. dir .. "/p.l:4 A --> FA\n" ..
                 "sub-L-system 1:\n  1    A --> FA", tostring(r))
  end)
end)

describe("m:inspect()", function()
  it("gives the name, the axiom, steps and seed, then the rules", function()
    local m = lsys.lsystem { axiom = "X", steps = 3, name = "bush",
                             productions = "X --> F[+X]F[-X]+X\nF --> FF" }
    assert.equal("lsys.Model(bush)  -- " .. m._where .. "\n" ..
      '  axiom = "X"\n  steps = 3\n  seed = 0\n' ..
      "productions:\n  1    X --> F[+X]F[-X]+X\n  2    F --> FF", m:inspect())
    assert.equal("lsys.Model(bush)", tostring(m))   -- tostring stays short
  end)

  it("shows the options given, those the core keeps included, and the hooks", function()
    local m = lsys.lsystem {
      axiom = "A", seed = 1.5, ignore = "+-", ring = true, random = "cpfg", threads = 2,
      max_modules = 1e6, env = { R = 1.456, _hidden = 1, t = { 1, { 2 } } },
      params = { W = { 2, min = 1, max = 3 } },
      view = { angle = 30, palette = { [2] = "#3050ff" } },
      start = function () end, end_each = function () end,
    }
    assert.equal(table.concat({
      tostring(m),
      '  axiom = "A"', "  steps = 1", "  seed = 1.5", '  random = "cpfg"', "  threads = 2",
      "  max_modules = 1000000", '  ignore = "+-"', "  ring = true",
      "  env = { R = 1.456, t = { 1, {...} } }", "  params = { W = 2 }",
      '  view = { angle = 30, palette = { [2] = "#3050ff" } }',
      "  hooks: start, end_each", "no rules" }, "\n"), m:inspect())
  end)

  it("reads the fields as they are now", function()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB" }
    m.steps, m.axiom, m.env = 5, "AA", { k = "a\nb" }
    local text = m:inspect()
    assert.matches('\n  axiom = "AA"\n  steps = 5\n', text, 1, true)
    assert.matches('\n  env = { k = "a\\nb" }\n', text, 1, true)
  end)

  it("leaves out the view's folder when lsys gave it, not when the model did", function()
    local dir = H.tmpdir()
    H.write(dir .. "/a.lua", 'local lsys = require "lsys"\n' ..
      'local m = lsys.lsystem { axiom = "F", view = { angle = 45 } }\nreturn m')
    H.write(dir .. "/b.lua", 'local lsys = require "lsys"\n' ..
      'local m = lsys.lsystem { axiom = "F", view = { dir = "x" } }\nreturn m')
    local a, b = dofile(dir .. "/a.lua"), dofile(dir .. "/b.lua")
    H.rmdir(dir)
    assert.equal(dir, a.view.dir)
    assert.matches("\n  view = { angle = 45 }\nno rules$", a:inspect())
    assert.matches('\n  view = { dir = "x" }\nno rules$', b:inspect())
  end)
end)
