-- The corpora of the Lua fuzzer (tests/fuzz/lua/fuzz.lua) replayed through their targets:
-- every saved input must load or fail with the expected error, without a finding (a Lua
-- runtime error inside lsys, a failed check, a rule expression or translated cpfg code that
-- reaches a global, a hang). Fuzzing itself is
-- `lua5.4 tests/fuzz/lua/fuzz.lua TARGET --time 600`.
-- ctest: slow (replays every corpus of the Lua fuzzer)
require "tests.helper"
local fuzz = dofile "tests/fuzz/lua/fuzz.lua"
local have_core = pcall(require, "lsys.core")

-- seconds per input, times LSYS_TEST_SLOW (tools/memcheck-all.sh sets 30: valgrind)
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
local BUDGET = 10 * SLOW

local function replay (name)
  local dir = "tests/fuzz/corpus_" .. name
  local found, counts = fuzz.replay(fuzz.target(name), dir, { budget = BUDGET })
  local msgs = {}
  for _, f in ipairs(found) do msgs[#msgs + 1] = f.file .. ": " .. fuzz.show(f.message, 600) end
  assert.equal(0, #found, table.concat(msgs, "\n"))
  assert.equal(0, counts.budget, "inputs over budget in " .. dir)
  return counts
end

describe("the Lua fuzzer's corpora", function ()
  it("load or fail with file and line as view files", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("view")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("load or fail naming the file as colour maps and material files", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("palette")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("derive or fail naming the rule as rule expressions, without reaching globals", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("ruleexpr")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail naming the file as JSON sketch files, and write back equal", function ()
    local counts = replay("sketch")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail naming the file as cpfg's communication files (.e)", function ()
    local counts = replay("efile")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail naming the file and line as parameter sidecar files", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("sidecar")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail naming the file and line as vlab's control panel files", function ()
    local counts = replay("panel")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail naming the file and line as SVG sketch files", function ()
    local counts = replay("svg")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("read or fail with file and line as batch specs in CSV, and write back equal", function ()
    local counts = replay("batch")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("give jobs or fail naming the spec as batch specs in Lua, a table and a file alike",
  function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("batchspec")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("expand, draw and graph or fail naming lsys.components as component definitions",
  function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("components")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("grow the same limbs with their rules in C and in Lua as grow rules", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("grow")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("import to a file that loads alone and derives what the cpfg model derives", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("import")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)

  it("load and derive or fail with file and line as cpfg L-system files, without reaching "
     .. "globals", function ()
    if not have_core then return pending("lsys.core is not built") end
    local counts = replay("cpfg")
    assert.is_true(counts.ok > 0 and counts.error > 0)
  end)
end)

describe("the Lua fuzzer", function ()
  it("finds a CSV parser that keeps a quote written twice", function ()
    local batch = require "lsys.batch"
    local t = fuzz.target("batch")
    local F = fuzz.new(t)
    local csv = batch.csv
    batch.csv = function (text, name)                -- "" stays two quotes
      local rows = csv(text, name)
      for _, row in ipairs(rows) do
        for k, c in ipairs(row) do row[k] = c:gsub('"', '""') end
      end
      return rows
    end
    local ok, kind, msg = pcall(F.exec, 'model,out\nm.lua,"a""b.png"\n')
    batch.csv = csv
    t.finish()
    assert.is_true(ok, kind)
    assert.equal("finding", kind)
    assert.equal("the records written back parse to other fields", msg)
  end)

  -- each target against a bug planted in what it checks: the input runs clean without it
  local function planted (name, input, plant)
    local t = fuzz.target(name)
    local F = fuzz.new(t)
    local unplant = plant()
    local ok, kind, msg = pcall(F.exec, input)
    unplant()
    local kind2, msg2 = F.exec(input)
    if t.finish then t.finish() end
    assert.is_true(ok, kind)
    assert.equal("ok", kind2, msg2)
    return kind, msg
  end

  it("finds a batch spec whose sweep lsys.batch.jobs makes a job short", function ()
    if not have_core then return pending("lsys.core is not built") end
    local batch = require "lsys.batch"
    local kind, msg = planted("batchspec",
      '{ model = "m.lua", vary = { R = { 1, 2, 3 } }, outputs = { "{id}.png" } }', function ()
        local jobs = batch.jobs
        batch.jobs = function (spec)
          local list, info = jobs(spec)     -- a list made as it is read: copy all but one
          local short = {}
          for i = 1, #list - 1 do short[i] = list[i] end
          return short, info
        end
        return function () batch.jobs = jobs end
      end)
    assert.equal("finding", kind)
    assert.equal("the spec makes 3 jobs, lsys.batch.jobs gave 2", msg)
  end)

  it("finds a grow condition that C reads otherwise than Lua", function ()
    if not have_core then return pending("lsys.core is not built") end
    local compile = require "lsys.compile"
    local kind, msg = planted("grow", "ticks 3\nrule length < 0.5 | scale_length 2\n",
      function ()
        local parse = compile.parseexpr           -- the machine's `<` becomes `<=`
        compile.parseexpr = function (text) return parse((text:gsub("<", "<="))) end
        return function () compile.parseexpr = parse end
      end)
    assert.equal("finding", kind)
    assert.equal("after tick 1: limb 1: length 1.0 with the rules in C, 0.5 in Lua", msg)
  end)

  it("finds a p-graph's DOT text that leaves a quote of a name unescaped", function ()
    if not have_core then return pending("lsys.core is not built") end
    local C = require("lsys").components
    local kind, msg = planted("components", '{ { "leaf", { name = "a \\"big\\" leaf" } } }',
      function ()
        local graph = C.graph
        C.graph = function (root, opts) return (graph(root, opts):gsub('\\"', '"')) end
        return function () C.graph = graph end
      end)
    assert.equal("finding", kind)
    assert.equal('DOT line 6: an attribute\'s value followed by big:   n1 [label="a "big" '
                 .. 'leaf\\nleaf"];', msg)
  end)

  it("finds an imported file that derives another string, or reads a global", function ()
    if not have_core then return pending("lsys.core is not built") end
    local import = require "lsys.cpfg.import"
    local l = "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> AB\nendlsystem\n"
    local source = import.source
    local kind, msg = planted("import", l, function ()
      import.source = function (...) return (source(...):gsub('axiom = "', 'axiom = "F')) end
      return function () import.source = source end
    end)
    assert.equal("finding", kind)
    assert.equal("the written file derives FABB, the direct load ABB", msg)
    kind, msg = planted("import", l, function ()
      import.source = function (...)
        return (source(...):gsub("\nreturn ", "\nlocal _ = os.time\nreturn "))
      end
      return function () import.source = source end
    end)
    assert.equal("finding", kind)
    assert.equal("the written file reads global os", msg)
  end)

  it("finds a rule expression that reaches a global", function ()
    if not have_core then return pending("lsys.core is not built") end
    -- the tripwire itself, on a model whose rule closure sees _G on purpose
    local t = fuzz.target("ruleexpr")
    local F = fuzz.new(t)
    local run = t.run
    t.run = function ()
      return load("return os", "=rule")()   -- code that is not in a file reads `os`
    end
    local kind, msg = F.exec("")
    t.run = run
    assert.equal("finding", kind)
    assert.equal("rule expression reached global 'os'", msg)
    assert.equal("table", type(os))          -- _G is back
  end)

  it("finds translated cpfg code that reaches a global", function ()
    if not have_core then return pending("lsys.core is not built") end
    local t = fuzz.target("cpfg")
    local F = fuzz.new(t)
    local run = t.run
    t.run = function ()
      return load("return io", "=main.l:1")()   -- as the translation compiles rule code
    end
    local kind, msg = F.exec("")
    t.run = run
    t.finish()
    assert.equal("finding", kind)
    assert.equal("translated code reached global 'io'", msg)
    assert.equal("table", type(io))          -- _G is back
  end)

  it("counts a cpfg load that is slow only under its line hook as a budget stop", function ()
    if not have_core then return pending("lsys.core is not built") end
    if SLOW > 1 then return pending("valgrind") end
    local t = fuzz.target("cpfg")
    local F = fuzz.new(t, { budget = 0.05 })
    local kind = F.exec(fuzz.readfile("tests/fuzz/corpus_cpfg/finding-include-chain.l"))
    t.finish()
    assert.equal("budget", kind)
  end)

  it("reports an input that overruns its time budget", function ()
    local F = fuzz.new({ run = function () while true do end end }, { budget = 0.05 })
    local kind, msg = F.exec("")
    assert.equal("finding", kind)
    assert.truthy(msg:find("over budget (time", 1, true), msg)
  end)

  it("finds nothing in 3000 fixed-seed mutations of view files", function ()
    if not have_core then return pending("lsys.core is not built") end
    local _, sum = fuzz.fuzz(fuzz.target("view"), { runs = 3000, seed = 7, quiet = true })
    assert.equal(0, sum.findings)
    -- both outcomes occur: the mutations neither break every file nor none of them
    assert.is_true(sum.ok > 0 and sum.errors > 1000, sum.ok .. " loaded, " .. sum.errors ..
                   " rejected")
    assert.is_true(sum.edges > 500, sum.edges .. " edges")
  end)

  it("finds new edges in lsys's Lua files", function ()
    local view = require "lsys.view"
    local F = fuzz.new({ run = function (s) view.parse(s, "fuzz.v", { quiet = true }) end,
                         clean = function () return true end })
    local _, _, new = F.exec("angle factor: 4\n")
    assert.is_true(new)
    assert.is_true(F.nedges > 10)
    _, _, new = F.exec("angle factor: 5\n")
    assert.is_false(new)
    local kind, _, new2 = F.exec("bogus: 1\n")
    assert.equal("error", kind)
    assert.is_true(new2)
  end)
end)
