-- The rule sandbox (docs/manual.md §5): rule text reaches none of the
-- process's library tables, and runs within an instruction budget, the memory budget and
-- bounded string functions. Each reproducer of the audit fails before the fix.
local H = require "tests.helper"
local lsys = require "lsys"
local sandbox = require "lsys.sandbox"

local errof = H.errof

-- The message of deriving `opts` (a model's options) one step, or nil when it derives.
local function derr (opts)
  local ok, e = pcall(function () return lsys.lsystem(opts):derive(opts.steps or 1) end)
  if ok then return nil end
  return (tostring(e):gsub("^[^:]*:%d*:? ?", ""))
end

local function one (productions, extra)
  local o = { axiom = "A(1)", productions = productions }
  for k, v in pairs(extra or {}) do o[k] = v end
  return o
end

-- Every library table of the process, and every function that could reach them or the
-- rest of the process.
local function dangerous ()
  local bad = {}
  for _, name in ipairs { "_G", "math", "string", "table", "os", "io", "debug", "package",
                          "coroutine", "utf8" } do
    local t = name == "_G" and _G or _G[name]
    bad[t] = name
    if name ~= "_G" and name ~= "math" and name ~= "string" and name ~= "table" then
      for k, v in pairs(t) do if type(v) == "function" then bad[v] = name .. "." .. k end end
    end
  end
  for _, name in ipairs { "load", "loadfile", "dofile", "require", "getmetatable",
                          "setmetatable", "rawset", "rawget", "rawequal", "rawlen",
                          "collectgarbage", "next" } do
    bad[_G[name]] = name
  end
  bad[math.randomseed] = "math.randomseed"
  for _, t in pairs(package.loaded) do
    if type(t) == "table" then bad[t] = bad[t] or "module" end
  end
  return bad
end

-- Walks every value reachable from `root` the way rule code can walk it (pairs, which
-- honours __pairs), returning the path to the first dangerous one, or nil.
local function reach (root, bad)
  local seen, queue = {}, { { root, "BUILTIN" } }
  while #queue > 0 do
    local v, path = table.unpack(table.remove(queue))
    if bad[v] then return path .. " is " .. bad[v] end
    if type(v) == "table" and not seen[v] then
      seen[v] = true
      for k, x in pairs(v) do
        queue[#queue + 1] = { k, path .. "[key]" }
        queue[#queue + 1] = { x, path .. "." .. tostring(k) }
      end
    end
  end
  return nil
end

describe("rule text", function ()
  it("cannot change the process's libraries through pairs (the audit's §1)", function ()
    local floor, concat = math.floor, table.concat
    local e = derr(one("A(t) --> A((function (t) t.floor = print; return 1 end)" ..
                       "(select(2, pairs(math))))"))
    assert.equal("rule 1 'A(t) --> A((function (t) t.floor = print; return 1 end)(select(2, " ..
                 "pairs(math))))' (line 1 of productions), module 1: cannot change math.floor " ..
                 "in a rule expression", e)
    assert.equal(floor, math.floor)
    assert.equal(concat, table.concat)
  end)

  it("reaches no library table and no dangerous function from anything it is given", function ()
    local bad = dangerous()
    assert.is_nil(reach(sandbox.BUILTIN, bad))
    -- the walk finds what it looks for: the pre-fix views handed out the real tables
    local leaky = setmetatable({}, { __index = math, __pairs = function () return next, math end })
    assert.truthy(reach({ m = leaky }, bad):find("^BUILTIN%.m%.[%w_]+ is math%."))
    -- and the model's own lookup (ran, nran, func, env, the builtins)
    local m = lsys.lsystem { axiom = "A", env = { k = 1 }, productions = "A --> A" }
    local E = m:_env()
    local given = { ran = E.ran, nran = E.nran, func = E.func }
    for k in pairs(sandbox.BUILTIN) do given[k] = E[k] end
    assert.is_nil(reach(given, bad))
  end)

  it("sees copies whose pairs walk the functions without giving the copy out", function ()
    local m = lsys.lsystem { axiom = "A(1,1)", productions = "A(t,k) --> A((function (t) " ..
                             "for k in pairs(math) do t = t + 1 end; return t end)(0))" }
    local n = 0
    for k in pairs(math) do if k ~= "randomseed" then n = n + 1 end end
    assert.equal("A(" .. n .. ")", tostring(m:derive(1)))
    for _, lib in ipairs { "math", "string", "table" } do
      local e = derr(one("A(x) --> A((function () " .. lib .. ".x = 1 end)() or 1)"))
      assert.equal("rule 1 'A(x) --> A((function () " .. lib .. ".x = 1 end)() or 1)' " ..
                   "(line 1 of productions), module 1: cannot change " .. lib .. ".x in a " ..
                   "rule expression", e)
    end
    assert.truthy(derr(one("A(x) --> A(math.randomseed(1) or 1)")):find(
      "attempt to call a nil value (field 'randomseed')", 1, true))
  end)

  it("finds the sandbox's string functions behind strings' methods while rules run", function ()
    local m = lsys.lsystem(one('A(x) --> A(("").rep == string.rep and 1 or 0) ' ..
                               'B(("").rep == string.rep and 1 or 0)'))
    assert.equal("A(1)B(1)", tostring(m:derive(1)))
    assert.equal(string.rep, ("").rep)             -- put back after the step
    assert.truthy(derr(one("A(x) --> A(1 / nil)")))
    assert.equal(string.rep, ("").rep)             -- and after an error
    assert.is_nil(debug.gethook())
  end)
end)

describe("the instruction budget", function ()
  it("ends an endless loop in a rule with an error naming it (the audit's §7)", function ()
    assert.equal("rule 1 'A(t) --> A((function () while true do end end)())' (line 1 of " ..
                 "productions), module 1: ran more than 100000000 Lua instructions in one call " ..
                 "(set max_instructions in the model)",
                 derr(one("A(t) --> A((function () while true do end end)())")))
  end)

  it("is per call, and max_instructions sets it", function ()
    local loop = "A(t) --> A((function (t) while t < 20000 do t = t + 1 end; return t end)(0))"
    assert.is_nil(derr(one(loop)))
    assert.equal("ran more than 10000 Lua instructions in one call (set max_instructions in " ..
                 "the model)", derr(one(loop, { max_instructions = 10000 })):match(": (ran.*)$"))
    assert.is_nil(derr(one(loop, { max_instructions = math.huge })))
    -- a string of 300 such modules: 300 calls, each within 100,000 instructions
    local m = lsys.lsystem { axiom = ("A(1)"):rep(300), max_instructions = 100000,
                             productions = loop }
    assert.equal(("A(20000)"):rep(300), tostring(m:derive(1)))
    assert.equal("max_instructions must be a number >= 1000 (or math.huge)",
                 errof(lsys.lsystem, one(loop, { max_instructions = 10 })):match("max_ins.*"))
  end)

  it("bounds rule functions, the axiom and a cpfg file's blocks", function ()
    assert.equal("rule 1 'A(x)' (entry 1 of productions), module 1: ran more than 1000000 Lua " ..
                 "instructions in one call (set max_instructions in the model)",
                 derr(one({ { "A(x)", function () while true do end end } },
                          { max_instructions = 1e6 })))
    assert.equal("axiom: expression '(function () while true do end end)()': ran more than " ..
                 "100000000 Lua instructions in one call (set max_instructions in the model)",
                 derr { axiom = "A((function () while true do end end)())" })
    local d = H.tmpdir()
    H.write(d .. "/loop.l", "Lsystem: 1\nderivation length: 1\n" ..
            "Start: { i = 0; while (1) { i = i + 1; } }\nAxiom: A\nendlsystem\n")
    local m = lsys.cpfg.load(d .. "/loop.l", nil, { cpp = "builtin" })
    local e = errof(m.derive, m)
    H.rmdir(d)
    assert.equal("loop.l:3: Start block: ran more than 100000000 Lua instructions in one call " ..
                 "(set max_instructions in the model)", e:match("loop%.l:.*"))
  end)

  it("puts back a hook of the program's own", function ()
    local calls = 0
    local function hook () calls = calls + 1 end
    debug.sethook(hook, "", 1e9)
    local m = lsys.lsystem(one("A(t) --> A(t + 1)"))
    m.lua_expressions = true
    local s = tostring(m:derive(2))
    local h, mask, count = debug.gethook()
    debug.sethook()
    assert.equal("A(3)", s)
    assert.equal(hook, h)
    assert.equal("", mask)
    assert.equal(1e9, count)
  end)
end)

describe("memory used by rule code", function ()
  it("counts against max_memory (the audit's ('x'):rep(2^27) under 32 MiB)", function ()
    assert.equal("rule 1 'A(t) --> A(#((\"x\"):rep(2^27)))' (line 1 of productions), module 1: " ..
                 "needs more than max_memory (32 MiB) for Lua values (set max_memory in the " ..
                 "model, or LSYS_MAX_MEMORY)",
                 derr(one('A(t) --> A(#(("x"):rep(2^27)))', { max_memory = "32M" })))
    assert.is_nil(derr(one('A(t) --> A(#(("x"):rep(2^20)))', { max_memory = "32M" })))
  end)

  it("is freed memory too: many small strings within the budget pass", function ()
    local m = lsys.lsystem(one('A(t) --> A(#(("x"):rep(2^20) .. "y"))', { max_memory = "8M" }))
    m.axiom = ("A(1)"):rep(64)                       -- 128 MiB in all, 2 MiB at a time
    assert.equal(("A(1048577)"):rep(64), tostring(m:derive(1)))
    -- with a big heap the collector waits, and string.rep's buffer asks the allocator
    -- directly (no emergency collection): garbage must not be what reaches the bound
    local heap = {}
    for i = 1, 200000 do heap[i] = { i } end
    assert.equal(("A(1048577)"):rep(64), tostring(m:derive(1)))
    assert.equal(200000, #heap)
  end)
end)

describe("string functions in rule text", function ()
  it("refuse a pattern that could backtrack for hours (the audit's a*a*...b)", function ()
    local want = "string.find: the pattern 'a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a...' could " ..
                 "take 9.92e+49 steps on 40 characters (rule text may take at most 100000000)"
    local e = derr(one('A(t) --> A((("a"):rep(40)):find(("a*"):rep(30) .. "b") or 0)'))
    assert.equal(want, e:match("string%.find: the pattern.*"))
    e = derr(one('A(t) --> A(string.find(("a"):rep(40), ("a*"):rep(30) .. "b") or 0)'))
    assert.equal(want, e:match("string%.find: the pattern.*"))
    e = derr(one('A(t) --> A(#(("a"):rep(40)):gsub(("a*"):rep(30) .. "b", ""))'))
    assert.truthy(e:find("string.gsub: the pattern", 1, true), e)
  end)

  it("keep ordinary patterns, repetitions and moves working", function ()
    local m = lsys.lsystem(one('A(t) --> A(("12ab"):match("%d+") + 0) B(#("a,b,,c"):gsub(",", ' ..
                               '";")) C(#(""):rep(2^53)) D(#table.move({1, 2, 3}, 1, 3, 2))'))
    assert.equal("A(12)B(6)C(0)D(4)", tostring(m:derive(1)))
    assert.equal("table.move: 1099511627776 elements is more than rule text may move (10000000)",
                 derr(one("A(t) --> A(#table.move({}, 1, 2^40, 1))")):match("table%.move: .*"))
  end)

  it("check nothing in a rule written as a Lua function", function ()
    local text = ("word "):rep(20000)
    local m = lsys.lsystem(one({ { "A(x)", function ()
      local n = 0
      for _ in text:gmatch("(%a+) (%a+)") do n = n + 1 end
      lsys.produce("A(" .. n .. ")")
    end } }))
    assert.equal("A(10000)", tostring(m:derive(1)))
  end)

  it("are bounded by their worst case", function ()
    assert.equal(41 * 41 + 40, sandbox.pattern_work("a*b", 40, true))
    assert.equal(1 * 41 + 40, sandbox.pattern_work("^a*b", 40, true))
    assert.equal(41 + 40, sandbox.pattern_work("%d+", 40, true))         -- last: no backtracking
    assert.equal(41 + 40, sandbox.pattern_work("(%d+)", 40, true))
    assert.equal(41 * 41 + 40, sandbox.pattern_work("[%]a]+x", 40, true))
    assert.equal(41 * 2 * 41 + 40, sandbox.pattern_work("a?%b()x", 40, true))
    assert.equal(41 * 41 + 40, sandbox.pattern_work("^a*b", 40, false))  -- gmatch: no anchor
  end)
end)
