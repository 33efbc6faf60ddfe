--- Fuzz target: cpfg L-system files, lsys.cpfg.load with the built-in
-- preprocessor (lua/lsys/cpfg/cpp.lua, parse.lua, translate.lua, emit.lua, helpers.lua,
-- init.lua), then a short derivation of the model. Its corpus is tests/fuzz/corpus_cpfg.
--
-- The bytes are the text of main.l in a scratch folder. A line "//@ NAME" (a comment to
-- cpfg) starts another file, NAME (letters, digits, `_ . -`, optionally under `a/`), so an
-- input can make its own #include files. The folder always holds:
--   sub.l     a sub-L-system (Lsystem: 2)        defs.h   #define N 3, GROW(x), SPIKE
--   self.l    includes itself                     twice.l  includes itself twice
--   back.l    includes main.l                     a/up.l   includes ../sub.l (relative)
-- A loaded model derives min(steps, 4) steps with max_modules = 2000 and max_memory =
-- 64M, then its homomorphism is applied (m:expand).
--
-- Expected errors: loading fails with "FILE:LINE: ..." (FILE a path in the folder or an
-- absolute #include: a path from the root; LINE >= 1); the derivation fails with lsys's
-- message naming the rule or with the translation's own "cpfg: ..." message. A FINDING is
-- any other error: a Lua runtime error inside lsys (the fuzzer's rule) or in the
-- translated code ("attempt to", "bad argument", "stack overflow" anywhere in the
-- message), a translated rule that gives a parameter no value ("is nil, not a number"), a
-- load error without file and line, a load that runs over the time budget and over 1 s
-- without the fuzzer's line hook too (a derivation that runs over it is the model's own
-- loop: clean, but counted, as a slow load is), or translated code that reaches
-- a global: while an input runs _G is emptied behind a metatable, and os.execute,
-- os.remove, os.rename, os.exit, os.getenv, os.tmpname, io.open, io.popen, io.lines,
-- io.input, io.output, load, loadfile, dofile and require fail when code that is not in a
-- file (code compiled by `load`) is on the stack; the string metatable and lsys.BUILTIN
-- must be unchanged afterwards. printf output goes to /dev/null.
local lsys = require "lsys"

local pairs, error, tostring, tonumber, getmetatable, ipairs =
      pairs, error, tostring, tonumber, getmetatable, ipairs
local gethook, sethook = debug.gethook, debug.sethook
local format, srep = string.format, string.rep
local concat, insert = table.concat, table.insert
local tmpname, os_remove, execute, open = os.tmpname, os.remove, os.execute, io.open
local io_output, io_stdout = io.output, io.stdout
local min, clock, math_huge = math.min, os.clock, math.huge
local BUILTIN = lsys.BUILTIN
local STRMETA = getmetatable("")
local cpfg = lsys.cpfg

-- 3 s: the fuzzer's line hook slows the preprocessor about 30 times (see budget_clean)
local T = { maxlen = 16384, budget = 3 }

-- --------------------------------------------------------------------------
-- The scratch folder

local DIR = tmpname()
os_remove(DIR)
execute("mkdir -p '" .. DIR .. "/a'")
local MAIN = DIR .. "/main.l"

local function writefile (path, s)
  local f = open(path, "wb")
  if not f then return false end
  f:write(s)
  f:close()
  return true
end

local FIXED = {
  ["sub.l"] = "Lsystem: 2\nderivation length: 1\nAxiom: B\nB --> CC\nendlsystem\n",
  ["defs.h"] = "#define N 3\n#define GROW(x) ((x) * 2)\n#define SPIKE ?(2, 1)B$\n",
  ["self.l"] = '#include "self.l"\n',
  ["twice.l"] = '#include "twice.l"\n#include "twice.l"\n',
  ["back.l"] = '#include "main.l"\n',
  ["a/up.l"] = '#include "../sub.l"\n',
}
for name, text in pairs(FIXED) do writefile(DIR .. "/" .. name, text) end

-- The files of an input: main.l first, then { name, text } for each "//@ NAME" part.
local function split (bytes)
  local files, cur, name = {}, {}, "main.l"
  for line in (bytes .. "\n"):gmatch("([^\n]*)\n") do
    local n = line:match("^//@%s*(%S+)%s*$")
    if n then
      files[#files + 1] = { name = name, text = concat(cur, "\n") }
      cur, name = {}, n
    else
      cur[#cur + 1] = line
    end
  end
  files[#files + 1] = { name = name, text = concat(cur, "\n") }
  return files
end

local function allowed (name)
  local base = name:match("^a/(.*)$") or name
  return base:match("^[%w_][%w_.%-]*$") ~= nil and not FIXED[name] and name ~= "main.l"
end

local written = {}

local function writeinput (bytes)
  local files = split(bytes)
  writefile(MAIN, files[1].text)
  for i = 2, #files do
    local f = files[i]
    if allowed(f.name) and writefile(DIR .. "/" .. f.name, f.text) then
      written[#written + 1] = DIR .. "/" .. f.name
    end
  end
end

local function cleaninput ()
  for _, p in ipairs(written) do os_remove(p) end
  written = {}
end

-- --------------------------------------------------------------------------
-- Tripwires (tests/fuzz/lua/tripwire.lua): code compiled from strings must not reach _G

local wires = require("tests.fuzz.lua.tripwire").new("translated code",
                                                     function () return T.run end)

local function snapshot (t)
  local s = {}
  for k, v in pairs(t) do s[k] = v end
  return s
end
local SNAP = { BUILTIN = snapshot(BUILTIN), stringmeta = snapshot(STRMETA) }
local LIBS = { BUILTIN = BUILTIN, stringmeta = STRMETA }

-- the first difference from SNAP, repaired; nil when there is none
local function libchanges ()
  local msg
  for name, lib in pairs(LIBS) do
    local s = SNAP[name]
    for k, v in pairs(lib) do
      if s[k] ~= v then msg = msg or format("%s.%s changed", name, tostring(k)); lib[k] = s[k] end
    end
    for k, v in pairs(s) do
      if lib[k] ~= v then msg = msg or format("%s.%s changed", name, tostring(k)); lib[k] = v end
    end
  end
  return msg
end

local NULL = open("/dev/null", "w")

-- --------------------------------------------------------------------------
-- The target

local phase          -- "load" or "derive": where the input is
local lastbytes

function T.before (bytes)
  phase, lastbytes = nil, bytes
  writeinput(bytes)
  io_output(NULL)
  wires.arm()
end

local function restore ()
  wires.disarm()
  io_output(io_stdout)
  cleaninput()
end

function T.run ()
  phase = "load"
  local m = cpfg.load(MAIN, nil, { cpp = "builtin" })
  phase = "derive"
  local rules = m._rules
  rules:config("max_modules", 2000)
  rules:config("max_memory", 64 * 1024 * 1024)
  local s = m:derive(min(m.steps, 4))
  m:expand(s)
  phase = "done"
end

-- Lua's runtime errors, and a translated rule that gives a parameter no value
local RUNTIME = { "attempt to ", "bad argument", "stack overflow", "index is NaN",
                  "index is nil", "C stack", "error in error handling", "number has no integer",
                  "is nil, not a number" }

function T.clean (err)
  for _, r in ipairs(RUNTIME) do
    if err:find(r, 1, true) then return false end
  end
  if phase == "load" then
    -- a file of the scratch folder or an absolute #include: a path from the root
    local file, line = err:match("^(/[^\n]-):(%d+): ")
    return file ~= nil and tonumber(line) >= 1
  end
  return phase == "derive"
end

-- The seconds the load of the last input takes without the fuzzer's line hook (a count
-- hook stops it after 10 s), with the tripwires set as for a run.
local BARE = 1
local function bare ()
  local tripped = false
  T.before(lastbytes)
  local t0 = clock()
  local oh, om, oc = gethook()
  sethook(function ()
    if clock() - t0 > 10 then tripped = true; error("fuzz: over 10 s", 0) end
  end, "", 100000)
  local _ = pcall(cpfg.load, MAIN, nil, { cpp = "builtin" })
  sethook(oh, om, oc)
  local el = clock() - t0
  restore()
  return (tripped or #wires.hits > 0) and math_huge or el
end

-- A derivation stopped by the budget is the model's own loop (while (1) {}): clean. A load
-- stopped by it is lsys's: a finding when it takes more than BARE seconds without the
-- line hook too (else it is counted, and saved under FINDINGS/budget for a look).
function T.budget_clean (tripped)
  if phase == "derive" then return true end
  return tripped == "time" and bare() <= BARE
end

function T.after ()
  restore()
  if #wires.hits > 0 then return wires.hits[1] end
  local changed = libchanges()
  if changed then return "translated code changed " .. changed end
  return nil
end

function T.finish ()
  for name in pairs(FIXED) do os_remove(DIR .. "/" .. name) end
  os_remove(MAIN)
  os_remove(DIR .. "/a")
  os_remove(DIR)
end

function T.describe (bytes) return bytes end

-- --------------------------------------------------------------------------
-- Seeds, dictionary, mutators

T.seeds = {}
for _, name in ipairs { "koch.l", "blocks.l", "exprs.l", "decomp.l", "context.l", "multi.l",
                        "ring.l", "stochastic.l", "macros.l" } do
  local f = open("tests/data/cpfg/" .. name, "rb")
  if f then T.seeds[#T.seeds + 1] = f:read("a"); f:close() end
end

local WORDS = {
  "Lsystem: 1\n", "Lsystem: 2\n", "derivation length: 3\n", "Axiom: ", "endlsystem\n",
  "ignore: +-/\n", "consider: AB[]\n", "seed: 5\n", "ring lsystem\n", "define: { ",
  "array a[3] = { 1, 2, 3 }", ", b[2][2]", "; }\n", "Start: { ", "StartEach: { ",
  "EndEach: { ", "End: { ", "}\n", "decomposition\n", "homomorphism\n", "maximum depth: 2\n",
  "warnings\n", "no warnings\n", " --> ", " -o> ", " : ", " < ", " > ", "*", "{", "}", ";",
  "if (", ") {", "} else {", "while (", "do {", "} while (", ");", "x = x + 1;", "printf(\"",
  "%d", "%100d", "%s", "%c", "%5.2f", "\\n\")", "stop(1)", "func(1, x)", "ran(1)",
  "nran(0, 1)", "bran(1, 2)", "biran(3, 0.5)", "sin(", "cos(", "tan(", "asin(", "acos(",
  "atan(", "exp(", "log(", "floor(", "ceil(", "sqrt(", "fabs(", "sign(", "trunc(", "srand(",
  "atan2(", "fopen(", "&x", "a[1]", "a[0][0]", "a[-1]", "a[1e9]", "a[0/0]", "&&", "||", "!",
  "==", "!=", "<>", "<=", ">=", "?", ":", "%", "^", "/", "-", "+", "(", ")", ",", "[", "]",
  "0/0", "1/0", "1e308", "1e-320", "3.5e2", ".5", "1.", "A(x)", "B(x, y)", "leaf(n)",
  "?P(x, y, z)", "?(2, 1)", "$", "[", "]", "F", "+", "\t", "\n\t", "\n", "\r\n", "/*", "*/",
  "//", "\"", "#define X 1\n", "#define F(a, b) ((a) + (b))\n", "#define R R + 1\n",
  "#define A B\n#define B A\n", "#undef X\n", "#ifdef X\n", "#ifndef X\n", "#if X > 1\n",
  "#if defined(X) && !defined Y\n", "#elif 1\n", "#else\n", "#endif\n", "#error no\n",
  "#pragma once\n", "#line 5\n", "#bogus\n", "#include \"sub.l\"\n", "#include \"defs.h\"\n",
  "#include \"self.l\"\n", "#include \"twice.l\"\n", "#include \"back.l\"\n",
  "#include \"a/up.l\"\n", "#include \"missing.l\"\n", "#include \"a/\"\n", "#include <x>\n",
  "#include \"inc.l\"\n", "//@ inc.l\n", "//@ a/inc.l\n", "\\\n", "N", "GROW(2)", "SPIKE",
  "X", "R", "Z", "Q", "_x", "os", "io", "_G", "_ENV", "E", "H", "L", "_n", "end", "nil",
  "function", "local", "return", "and", "or", "not", "pi", "abs", "math", "string",
  "require", "A(E)", "A(H)", "A(L)", "A(pi)",
}
T.dict = WORDS
local DIRECTIVES = {}
for _, w in ipairs(WORDS) do if w:sub(1, 1) == "#" then DIRECTIVES[#DIRECTIVES + 1] = w end end

-- a nest of `n` levels around `x`, of one kind
local NESTS = {
  function (n, x) return srep("(", n) .. x .. srep(")", n) end,
  function (n, x) return srep("-", n) .. x end,
  function (n, x) return srep("!", n) .. x end,
  function (n, x) return x .. srep(" + 1", n) end,
  function (n, x) return x .. srep(" ^ 2", n) end,
  function (n, x) return srep("1 ? ", n) .. x .. srep(" : 0", n) end,
  function (n, x) return srep("sqrt(", n) .. x .. srep(")", n) end,
  function (n, x) return srep("a[", n) .. x .. srep("]", n) end,
  function (n, x) return srep("{ if (1) ", n) .. "{ " .. x .. "; }" .. srep(" }", n) end,
  function (n, x) return srep("{ while (0) ", n) .. "{ " .. x .. "; }" .. srep(" }", n) end,
}
local SIZES = { 10, 30, 60, 100, 150, 199, 200, 201, 250, 400, 1000, 3000 }

T.mutators = {
  function (rnd, s)                        -- a deep nest of one kind at a random place
    local n = SIZES[rnd(#SIZES)]
    local i = rnd(#s + 1)
    return s:sub(1, i - 1) .. NESTS[rnd(#NESTS)](n, "x") .. s:sub(i)
  end,
  function (rnd, s)                        -- a long line: a piece repeated
    if #s == 0 then return s end
    local i = rnd(#s)
    local piece = s:sub(i, i + rnd(16) - 1)
    return s:sub(1, i - 1) .. srep(piece, SIZES[rnd(#SIZES)]) .. s:sub(i)
  end,
  function (rnd, s)                        -- a directive at the start of a line
    local lines = {}
    for l in (s .. "\n"):gmatch("([^\n]*)\n") do lines[#lines + 1] = l end
    local k = rnd(#lines + 1)
    insert(lines, k, (DIRECTIVES[rnd(#DIRECTIVES)]:gsub("\n$", "")))
    return concat(lines, "\n")
  end,
  function (rnd, s)                        -- an included file of the input's own
    local name = rnd(2) == 1 and "inc.l" or "a/inc.l"
    return '#include "' .. name .. '"\n' .. s .. "\n//@ " .. name .. "\n" ..
           (T.seeds[rnd(#T.seeds)] or "")
  end,
}

return T
