--- A coverage-guided fuzzer for the parts of lsys written in Lua, which
-- libFuzzer cannot see: the cpfg view file reader, the colour map and material readers,
-- rule expressions, sketch files in JSON and SVG, cpfg's L-system files,
-- batch specs in CSV and in Lua, component definitions, cpfg's communication files (.e),
-- the rules of incremental growth and `lsys import`.
--
--   lua5.4 tests/fuzz/lua/fuzz.lua TARGET [--time SECONDS] [--runs N] [--seed S]
--          [--corpus DIR] [--findings DIR] [--budget SECONDS] [--mem MB] [--maxlen N]
--   lua5.4 tests/fuzz/lua/fuzz.lua TARGET --replay DIR      (exit 1 on any finding)
--   lua5.4 tests/fuzz/lua/fuzz.lua TARGET --merge DIR       (keep the hand-made seeds of
--                                                 DIR and the saved files that add edges)
--
-- Run from the source directory; without LUA_PATH / LUA_CPATH it reads ./lua and
-- ./build. TARGET is a module tests/fuzz/lua/targets/TARGET.lua returning
--   { seeds = {...}, dict = {...}, run = function (bytes, ctx) ... end,
--     clean = function (err) -> true when err is an expected error,
--     before = fn(bytes), after = fn(tripped) -> nil | finding message (both outside the
--     hooks: checks that need not be covered belong in `after`),
--     budget_clean = true when a stopped runaway input is the input's own fault (or a
--       function, called after `after`, saying so for the input that just ran),
--     mutators = { fn(rnd, s) -> s }, describe = fn(bytes) -> text, maxlen = N,
--     finish = fn() }
-- `budget` is the target's default time per input (seconds). `run` returns or raises;
-- `ctx.finding(msg)` reports a failed check, `ctx.trip(kind, why)` stops the input as over
-- budget.
--
-- Coverage is edge coverage of lsys's Lua files (a line hook; an edge is a pair of
-- consecutive, different lines executed in files lsys/NAME.lua or lsys/DIR/NAME.lua, as
-- lsys/sketch/read.lua), with AFL's hit-count buckets.
-- An input that reaches a new edge or bucket goes into the corpus directory under the
-- FNV-1a hash of its bytes. An input is a FINDING when it raises a non-string error, an
-- error without the expected form, a Lua runtime error inside lsys code
-- ("lsys/view.lua:123: attempt to ..."), fails a target's check, or (unless the target
-- says budget_clean) runs past the per-input time budget (os.clock, checked from the hook)
-- or grows memory past the bound (collectgarbage "count"). Findings are written to
-- the findings directory: the input as HASH and the message as HASH.txt.
--
-- The generator is xorshift64*, so a run with the same seed,
-- corpus and --runs is the same on every machine. `dofile` of this file returns the
-- module (M.new, M.replay, M.fuzz, M.main) without running anything.
local script = debug.getinfo(1, "S").source
local SELF = script:sub(2)
local HERE = SELF:match("^(.*/)[^/]*$") or "./"

if os.getenv("LUA_PATH") == nil and not package.path:find("./lua/?.lua", 1, true) then
  package.path = "./lua/?.lua;./lua/?/init.lua;" .. package.path
end
if os.getenv("LUA_CPATH") == nil and not package.cpath:find("./build/?.so", 1, true) then
  package.cpath = "./build/?.so;" .. package.cpath
end

local type, pairs, ipairs, error, pcall, tostring, tonumber, setmetatable, print, dofile =
      type, pairs, ipairs, error, pcall, tostring, tonumber, setmetatable, print, dofile
local sethook, gethook, getinfo = debug.sethook, debug.gethook, debug.getinfo
local clock, time, exit, execute, removefile = os.clock, os.time, os.exit, os.execute, os.remove
local collectgarbage = collectgarbage
local open, popen, stderr = io.open, io.popen, io.stderr
local format, byte, char = string.format, string.byte, string.char
local concat, sort, insert, table_remove = table.concat, table.sort, table.insert, table.remove
local math_min, math_max = math.min, math.max
local ARG = arg
local shq = require("lsys.util.text").shq
local _ENV = nil   -- no globals below: a target may seal _G while an input runs

local M = {}

-- --------------------------------------------------------------------------
-- Small helpers

--- xorshift64*: rnd(n) is an integer in 1..n, the same sequence on every platform.
function M.generator (seed)
  local x = seed ~ 0x2545F4914F6CDD1D
  if x == 0 then x = 1 end
  return function (n)
    x = x ~ (x >> 12); x = x ~ (x << 25); x = x ~ (x >> 27)
    local r = (x * 0x2545F4914F6CDD1D) >> 11
    return r % n + 1
  end
end

--- FNV-1a, 64 bits, as 16 hex digits: corpus and finding file names.
function M.hash (s)
  local h = 0xcbf29ce484222325
  for i = 1, #s do h = (h ~ byte(s, i)) * 0x100000001b3 end
  return format("%016x", h)
end

local function readfile (path)
  local f = open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

local function writefile (path, s)
  local f, err = open(path, "wb")
  if not f then error("fuzz: cannot write " .. tostring(err), 0) end
  f:write(s)
  f:close()
end


local function mkdir (d) execute("mkdir -p " .. shq(d)) end

--- The regular files of directory `d` (names, sorted); {} when it does not exist.
function M.listdir (d)
  local p = popen("ls -1Ap " .. shq(d) .. " 2>/dev/null")
  local out = {}
  for l in p:lines() do
    if l:sub(-1) ~= "/" and l:sub(1, 1) ~= "." then out[#out + 1] = l end
  end
  p:close()
  sort(out)
  return out
end

M.readfile, M.writefile = readfile, writefile

-- Text of an input for a message: control bytes as \ddd, at most `n` bytes.
local function show (s, n)
  n = n or 400
  local cut = #s > n
  s = s:sub(1, n):gsub("[%z\1-\31\127-\255]", function (c)
    return format("\\%d", byte(c))
  end)
  return cut and s .. "..." or s
end
M.show = show

-- --------------------------------------------------------------------------
-- Targets

--- Loads tests/fuzz/lua/targets/NAME.lua.
function M.target (name)
  if type(name) ~= "string" or not name:match("^[%w_]+$") then
    error("fuzz: a target name expected (a file of tests/fuzz/lua/targets/)", 0)
  end
  local path = HERE .. "targets/" .. name .. ".lua"
  if readfile(path) == nil then error("fuzz: no target '" .. name .. "' (" .. path .. ")", 0) end
  local t = dofile(path)
  t.name = name
  return t
end

-- --------------------------------------------------------------------------
-- The executor: one input through the target under the coverage and budget hook.

local BUDGET = "fuzz: budget exceeded"

-- a Lua runtime error raised inside lsys code, as Lua formats it
local function lsys_runtime (msg)
  return msg:match("lsys/[%w_/]+%.lua:%d+: .*")
end
M.lsys_runtime = lsys_runtime

local function bucket (c)
  if c < 4 then return c - 1 elseif c < 8 then return 3 elseif c < 16 then return 4
  elseif c < 32 then return 5 elseif c < 128 then return 6 end
  return 7
end

--- A fuzzer state for `target`. opts: budget (seconds per input, 2), mem (MB of growth
-- per input, 256), count (also a count hook every `count` instructions; none by
-- default).
--
-- The budget is checked from the line hook: a loop jumps back and a call enters a new
-- function, and both give a line event, so Lua code cannot run long without one. A count
-- hook adds nothing to that and disturbs coverage: Lua 5.4 runs the count hook just
-- before deciding on the line event of the same instruction, and the calls the hook
-- makes leave a stale "last pc" behind, so extra line events (and edges) appear or not
-- depending on how many instructions the hook itself ran. Replay, where coverage does
-- not matter, adds a count hook anyway.
function M.new (target, opts)
  opts = opts or {}
  local F = { target = target, edges = {}, nedges = 0, features = {}, nfeatures = 0,
              execs = 0, counts = { ok = 0, error = 0, budget = 0, finding = 0 } }
  local tlimit = opts.budget or target.budget or 2
  local mlimit = (opts.mem or 256) * 1024
  local count = opts.count or 0
  local files, nfiles = {}, 0
  F.files = files

  -- function -> file id (lsys sources), 0 (this driver: never interrupted), or false
  local ids = setmetatable({}, { __mode = "k" })
  local function classify (f)
    local info = getinfo(f, "S")
    local src = info.source
    if src == script then return 0 end
    if info.what == "C" then return false end
    local name = src:sub(1, 1) == "@" and src:match("lsys/[%w_/]+%.lua$")
    if not name then return false end
    for i = 1, nfiles do if files[i] == name then return i end end
    nfiles = nfiles + 1
    files[nfiles] = name
    return nfiles
  end

  local cur, prev, n = {}, 0, 0
  local t0, mem0, tripped, tripclock, tripwhy = 0, 0, nil, 0, nil
  local fmsg

  local function trip (kind, why)
    if not tripped then tripped, tripclock, tripwhy = kind, clock(), why end
    error(BUDGET, 0)
  end

  local function hook (ev, line)
    local f = getinfo(2, "f").func
    local id = ids[f]
    if id == nil then id = classify(f); ids[f] = id end
    if id == 0 then return end
    if ev == "line" and id then
      -- a line after itself is left out: Lua 5.4 repeats the line event of a function
      -- that called a Lua function through C (pcall, gsub, ...), depending on what ran
      -- before, so such edges would not reproduce
      local loc = id << 16 | line
      if loc ~= prev then
        local e = prev << 24 | loc
        cur[e] = (cur[e] or 0) + 1
        prev = loc
      end
    end
    if tripped then
      -- stopped: user code stops at once; lsys's own code may unwind, for a while
      if not id or clock() - tripclock > tlimit then error(BUDGET, 0) end
      return
    end
    n = n + 1
    if not id or ev == "count" or n & 63 == 0 then
      if clock() - t0 > tlimit then trip("time")
      elseif collectgarbage("count") - mem0 > mlimit then trip("memory") end
    end
  end

  local ctx = {
    trip = trip,
    finding = function (msg)
      fmsg = fmsg or tostring(msg)
      error("fuzz: " .. tostring(msg), 0)
    end,
  }
  F.ctx = ctx

  --- Runs one input. Returns kind ("ok", "error", "budget", "finding"), the message,
  -- and whether it reached new coverage.
  function F.exec (bytes)
    cur, prev, n, tripped, tripwhy, fmsg = {}, 0, 0, nil, nil, nil
    if target.before then target.before(bytes) end
    local oh, om, oc = gethook()
    mem0, t0 = collectgarbage("count"), clock()
    sethook(hook, "l", count)
    local ok, err = pcall(target.run, bytes, ctx)
    sethook()
    if oh then sethook(oh, om, oc) end
    local elapsed = clock() - t0
    local after = target.after and target.after(tripped)
    local kind, msg
    if after or fmsg then
      kind, msg = "finding", after or fmsg
    elseif tripped then
      local bc = target.budget_clean
      if type(bc) == "function" then bc = bc(tripped) end
      kind = bc and "budget" or "finding"
      msg = format("over budget (%s%s: %.2f s, %.0f MB growth)", tripped,
                   tripwhy and ", " .. tripwhy or "", elapsed,
                   (collectgarbage("count") - mem0) / 1024)
      if tripped == "memory" then collectgarbage("collect") end
    elseif ok then
      kind = "ok"
    elseif type(err) ~= "string" then
      kind, msg = "finding", "a " .. type(err) .. " error: " .. tostring(err)
    elseif lsys_runtime(err) then
      kind, msg = "finding", "runtime error in lsys: " .. err
    elseif target.clean and target.clean(err) then
      kind, msg = "error", err
    else
      kind, msg = "finding", "unexpected error: " .. err
    end
    F.execs = F.execs + 1
    F.counts[kind] = F.counts[kind] + 1
    F.last = cur                        -- edge -> hits of this input
    local new = false
    for e, c in pairs(cur) do
      if not F.edges[e] then F.edges[e] = true; F.nedges = F.nedges + 1; new = true end
      local fk = e * 8 + bucket(c)
      if not F.features[fk] then
        F.features[fk] = true; F.nfeatures = F.nfeatures + 1; new = true
      end
    end
    return kind, msg, new
  end

  return F
end

-- --------------------------------------------------------------------------
-- Mutations

local INTERESTING = { 0, 1, 9, 10, 13, 32, 34, 39, 40, 41, 44, 45, 46, 48, 49, 57, 58, 91,
                      93, 96, 123, 125, 127, 128, 255 }
local NUMBERS = { "0", "1", "-1", "2", "255", "256", "65535", "65536", "1e308", "1e309",
                  "-1e309", "nan", "inf", "0x10", "1e-320", "2^53", "9007199254740993",
                  "0.5", "-0", "1.5", "3", "128", "129", "1024", "1025", "4294967296" }

--- A mutated copy of `s`: 1, 2, 4 or 8 operations among byte and bit flips, interesting
-- bytes, inserted and deleted ranges, duplicated and copied ranges, dictionary tokens,
-- numbers, splices and crossovers with `other` (another corpus entry), and the target's
-- own mutators.
function M.mutate (rnd, s, other, dict, extra, maxlen)
  for _ = 1, 1 << (rnd(4) - 1) do
    local n = #s
    local op = rnd(17)
    if op == 1 and n > 0 then                                   -- flip a bit
      local i = rnd(n)
      s = s:sub(1, i - 1) .. char(byte(s, i) ~ (1 << (rnd(8) - 1))) .. s:sub(i + 1)
    elseif op == 2 and n > 0 then                               -- a random byte
      local i = rnd(n)
      s = s:sub(1, i - 1) .. char(rnd(256) - 1) .. s:sub(i + 1)
    elseif op == 3 and n > 0 then                               -- an interesting byte
      local i = rnd(n)
      s = s:sub(1, i - 1) .. char(INTERESTING[rnd(#INTERESTING)]) .. s:sub(i + 1)
    elseif op == 4 then                                         -- insert random bytes
      local b = {}
      for j = 1, rnd(8) do b[j] = char(rnd(256) - 1) end
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. concat(b) .. s:sub(i)
    elseif op == 5 and n > 0 then                               -- delete a range
      local i = rnd(n)
      local len = rnd(4) == 1 and rnd(n) or rnd(8)
      s = s:sub(1, i - 1) .. s:sub(i + len)
    elseif op == 6 and n > 0 then                               -- duplicate a range
      local i = rnd(n)
      local len = rnd(math_min(n - i + 1, 64))
      local j = rnd(n + 1)
      s = s:sub(1, j - 1) .. s:sub(i, i + len - 1) .. s:sub(j)
    elseif op == 7 and n > 1 then                               -- copy a range over another
      local i, j = rnd(n), rnd(n)
      local len = rnd(math_min(n - i + 1, n - j + 1, 32))
      s = s:sub(1, j - 1) .. s:sub(i, i + len - 1) .. s:sub(j + len)
    elseif (op == 8 or op == 9) and dict and #dict > 0 then     -- insert a dictionary token
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. dict[rnd(#dict)] .. s:sub(i)
    elseif op == 10 and dict and #dict > 0 and n > 0 then       -- overwrite with a token
      local t = dict[rnd(#dict)]
      local i = rnd(n)
      s = s:sub(1, i - 1) .. t .. s:sub(i + #t)
    elseif op == 11 and other and #other > 0 then               -- crossover
      local i, j = rnd(n + 1), rnd(#other)
      s = s:sub(1, i - 1) .. other:sub(j)
    elseif op == 12 and other and #other > 0 then               -- insert a piece of another
      local j = rnd(#other)
      local len = rnd(math_min(#other - j + 1, 64))
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. other:sub(j, j + len - 1) .. s:sub(i)
    elseif op == 13 and n > 0 then                              -- byte arithmetic
      local i = rnd(n)
      s = s:sub(1, i - 1) .. char((byte(s, i) + rnd(71) - 36) % 256) .. s:sub(i + 1)
    elseif op == 14 then                                        -- replace a number
      local starts = {}
      for p in s:gmatch("()%-?%d") do starts[#starts + 1] = p end
      if #starts > 0 then
        local i = starts[rnd(#starts)]
        local _, e = s:find("^%-?[%d%.xXa-fA-FeE]+", i)
        s = s:sub(1, i - 1) .. NUMBERS[rnd(#NUMBERS)] .. s:sub(e + 1)
      else
        local i = rnd(n + 1)
        s = s:sub(1, i - 1) .. NUMBERS[rnd(#NUMBERS)] .. s:sub(i)
      end
    elseif op == 15 then                                        -- a line: repeat or move
      local lines = {}
      for l in (s .. "\n"):gmatch("([^\n]*)\n") do lines[#lines + 1] = l end
      local k = rnd(#lines)
      local l = lines[k]
      if other and rnd(2) == 1 then
        local ol = {}
        for x in (other .. "\n"):gmatch("([^\n]*)\n") do ol[#ol + 1] = x end
        l = ol[rnd(#ol)]
      end
      if rnd(3) == 1 then table_remove(lines, k) end
      insert(lines, rnd(#lines + 1), l)
      s = concat(lines, "\n")
    elseif op == 16 then                                        -- truncate
      s = s:sub(1, rnd(n + 1) - 1)
    elseif extra and #extra > 0 then                            -- the target's own
      s = extra[rnd(#extra)](rnd, s, other)
    end
  end
  if maxlen and #s > maxlen then s = s:sub(1, maxlen) end
  return s
end

-- --------------------------------------------------------------------------
-- Replay, merge, fuzz

local function outline (kind, msg, label)
  return format("%s %s: %s", kind:upper(), label, msg and show(msg, 2000) or "")
end

--- Runs every file of `dir` once. Returns the list of findings
-- { file =, message = }, the counts by outcome and the fuzzer state. The time budget is
-- 10 s per input unless opts.budget says otherwise: replay is about outcomes, and may run
-- under valgrind.
function M.replay (target, dir, opts)
  opts = opts or {}
  local F = M.new(target, { budget = opts.budget or 10, mem = opts.mem,
                            count = opts.count or 1000 })
  local found = {}
  for _, name in ipairs(M.listdir(dir)) do
    if not name:match("%.txt$") then
      local bytes = readfile(dir .. "/" .. name)
      local kind, msg = F.exec(bytes)
      if kind == "finding" then found[#found + 1] = { file = dir .. "/" .. name, message = msg } end
      if opts and opts.verbose and (kind == "finding" or kind == "budget") then
        stderr:write(outline(kind, msg, dir .. "/" .. name), "\n")
      end
    end
  end
  if target.finish then target.finish() end
  return found, F.counts, F
end

--- Keeps the hand-made seeds of `dir` (files whose names are not a 16-digit hash) and,
-- of the files the fuzzer saved (named by hash), only those that reach edges the seeds
-- and the smaller files do not. Hit counts are not looked at, so the corpus stays small.
-- Returns the numbers of files kept and removed, and the fuzzer state.
function M.merge (target, dir, opts)
  local F = M.new(target, opts)
  local seeds, items = {}, {}
  for _, name in ipairs(M.listdir(dir)) do
    if not name:match("%.txt$") then
      local it = { name = name, bytes = readfile(dir .. "/" .. name) }
      if name:match("^%x+$") and #name == 16 then items[#items + 1] = it
      else seeds[#seeds + 1] = it end
    end
  end
  for _, it in ipairs(seeds) do F.exec(it.bytes) end
  sort(items, function (a, b)
    if #a.bytes ~= #b.bytes then return #a.bytes < #b.bytes end
    return a.name < b.name
  end)
  local kept, removed = #seeds, 0
  for _, it in ipairs(items) do
    local before = F.nedges
    local kind = F.exec(it.bytes)
    if F.nedges > before and (kind == "ok" or kind == "error") then
      kept = kept + 1
      local h = M.hash(it.bytes)
      if h ~= it.name then
        writefile(dir .. "/" .. h, it.bytes)
        removefile(dir .. "/" .. it.name)
      end
    else
      removed = removed + 1
      removefile(dir .. "/" .. it.name)
    end
  end
  if target.finish then target.finish() end
  return kept, removed, F
end

--- The fuzzing loop. opts: time (seconds), runs, seed, corpus (dir), findings (dir),
-- budget, mem, maxlen, quiet. Returns the fuzzer state and a summary table.
function M.fuzz (target, opts)
  local F = M.new(target, opts)
  local rnd = M.generator(opts.seed or 1)
  local corpusdir, finddir = opts.corpus, opts.findings
  if corpusdir then mkdir(corpusdir) end
  local corpus, inset, nloaded, nnew = {}, {}, 0, 0
  local findings, sigs, nbudget = 0, {}, 0
  local start = time()
  local startclock = clock()
  local function say (s) if not opts.quiet then stderr:write(s, "\n") end end

  local function add (bytes, save)
    if inset[bytes] then return end
    inset[bytes] = true
    corpus[#corpus + 1] = bytes
    if save and corpusdir then
      writefile(corpusdir .. "/" .. M.hash(bytes), bytes)
      nnew = nnew + 1
    end
  end

  local function report (kind, msg, bytes)
    if kind == "budget" then
      nbudget = nbudget + 1
      if nbudget <= 5 then say("budget (clean): " .. msg .. " <- " .. show(bytes, 200)) end
      if finddir and nbudget <= 10 then
        local d = finddir .. "/budget"
        mkdir(d)
        local h = M.hash(bytes)
        writefile(d .. "/" .. h, bytes)
        writefile(d .. "/" .. h .. ".txt", msg .. "\n")
      end
      return
    end
    -- the same problem at the same place counts once
    local sig = (msg:match("lsys/[%w_/]+%.lua:%d+") or msg:gsub("%d+", "N"):sub(1, 120))
    findings = findings + 1
    if sigs[sig] then return end
    sigs[sig] = true
    local h = M.hash(bytes)
    say(format("FINDING %s: %s", h, show(msg, 600)))
    if finddir then
      mkdir(finddir)
      writefile(finddir .. "/" .. h, bytes)
      local text = msg .. "\n"
      if target.describe then
        local ok, d = pcall(target.describe, bytes)
        if ok and d then text = text .. "--- input as run ---\n" .. d .. "\n" end
      end
      writefile(finddir .. "/" .. h .. ".txt", text)
    end
  end

  -- the input being run, for a hang that no hook can stop (a C function that does not
  -- return): kill the fuzzer and the input is in FINDINGS/.current
  local current = finddir and finddir .. "/.current"
  if current then mkdir(finddir) end
  local function run1 (bytes)
    if current then writefile(current, bytes) end
    local kind, msg, new = F.exec(bytes)
    if kind == "finding" or kind == "budget" then report(kind, msg, bytes) end
    return kind, new
  end

  -- the corpus directory first, then the target's seeds (saved when they add coverage)
  if corpusdir then
    for _, name in ipairs(M.listdir(corpusdir)) do
      local bytes = readfile(corpusdir .. "/" .. name)
      if bytes then
        local kind = run1(bytes)
        if kind == "ok" or kind == "error" then add(bytes, false); nloaded = nloaded + 1 end
      end
    end
  end
  for _, s in ipairs(target.seeds or {}) do
    local kind, new = run1(s)
    if kind == "ok" or kind == "error" then add(s, new) end
  end
  if #corpus == 0 then add("", false) end
  say(format("fuzz %s: loaded %d corpus files and %d seeds: %d edges, %d features",
             target.name, nloaded, #(target.seeds or {}), F.nedges, F.nfeatures))

  local maxlen = opts.maxlen or target.maxlen or 4096
  local tlimit, rlimit = opts.time, opts.runs
  if not tlimit and not rlimit then tlimit = 60 end
  local nextstatus, it = 10, 0
  while true do
    if rlimit and it >= rlimit then break end
    local el = time() - start
    if tlimit and el >= tlimit then break end
    it = it + 1
    -- half the time one of the newest fifth of the corpus
    local k = rnd(2) == 1 and rnd(#corpus) or #corpus - rnd(math_max(1, #corpus // 5)) + 1
    local parent = corpus[k]
    local other = corpus[rnd(#corpus)]
    local child = M.mutate(rnd, parent, other, target.dict, target.mutators, maxlen)
    if not inset[child] then
      local kind, new = run1(child)
      if new and (kind == "ok" or kind == "error") then add(child, true) end
    end
    if el >= nextstatus then
      nextstatus = el + 30
      say(format("#%d %ds: %d edges, %d features, corpus %d, %d findings, %d budget stops, "
                 .. "%.0f exec/s", F.execs, el, F.nedges, F.nfeatures, #corpus, findings,
                 nbudget, F.execs / math_max(clock() - startclock, 1e-3)))
    end
  end
  if target.finish then target.finish() end
  if current then removefile(current) end
  local summary = {
    target = target.name, execs = F.execs, edges = F.nedges, features = F.nfeatures,
    corpus = #corpus, new = nnew, findings = findings, unique = 0, budget = nbudget,
    seconds = time() - start, ok = F.counts.ok, errors = F.counts.error,
  }
  for _ in pairs(sigs) do summary.unique = summary.unique + 1 end
  return F, summary
end

-- --------------------------------------------------------------------------
-- Command line

local USAGE = [[
usage: lua5.4 tests/fuzz/lua/fuzz.lua TARGET [--time SECONDS] [--runs N] [--seed S]
         [--corpus DIR] [--findings DIR] [--budget SECONDS] [--mem MB] [--maxlen N]
       lua5.4 tests/fuzz/lua/fuzz.lua TARGET --replay DIR
       lua5.4 tests/fuzz/lua/fuzz.lua TARGET --merge DIR
targets: view, palette, ruleexpr, sketch, svg, cpfg, batch, batchspec, components, grow,
         import (tests/fuzz/lua/targets/)]]

function M.main (args)
  local name = args[1]
  if name == nil or name == "-h" or name == "--help" then print(USAGE); return 0 end
  local opts = { corpus = "tests/fuzz/corpus_" .. name,
                 findings = "tests/fuzz/lua/findings/" .. name }
  local i = 2
  while i <= #args do
    local a, v = args[i], args[i + 1]
    local key = a:match("^%-%-(%w+)$")
    if key == nil or v == nil then stderr:write(USAGE, "\n"); return 2 end
    if key == "time" or key == "runs" or key == "seed" or key == "budget" or key == "mem"
       or key == "maxlen" then
      opts[key] = tonumber(v)
      if opts[key] == nil then stderr:write("fuzz: --" .. key .. " needs a number\n"); return 2 end
    elseif key == "corpus" or key == "findings" or key == "replay" or key == "merge" then
      opts[key] = v
    else
      stderr:write(USAGE, "\n"); return 2
    end
    i = i + 2
  end
  local target = M.target(name)
  if opts.replay then
    local found, counts = M.replay(target, opts.replay, { budget = opts.budget, mem = opts.mem,
                                                          verbose = true })
    print(format("replay %s %s: %d ok, %d clean errors, %d budget stops, %d findings",
                 name, opts.replay, counts.ok, counts.error, counts.budget, #found))
    return #found == 0 and 0 or 1
  elseif opts.merge then
    local kept, removed, F = M.merge(target, opts.merge, opts)
    print(format("merge %s %s: kept %d files, removed %d; %d edges, %d features", name,
                 opts.merge, kept, removed, F.nedges, F.nfeatures))
    return 0
  end
  local _, s = M.fuzz(target, opts)
  print(format("fuzz %s: %d executions in %d s (%d ok, %d clean errors), %d edges covered "
               .. "(%d features), corpus %d (%d new), %d findings (%d unique), "
               .. "%d budget stops (clean)", s.target, s.execs, s.seconds, s.ok, s.errors,
               s.edges, s.features, s.corpus, s.new, s.findings, s.unique, s.budget))
  return s.findings == 0 and 0 or 1
end

if ARG and type(ARG[0]) == "string" and ARG[0]:match("fuzz%.lua$") then
  exit(M.main(ARG))
end

return M
