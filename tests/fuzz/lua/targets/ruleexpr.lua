--- Fuzz target: rule expressions (lsys.lsystem in lua/lsys/model.lua and
-- lua/lsys/compile.lua, then m:derive). Its corpus is tests/fuzz/corpus_ruleexpr
-- (tests/fuzz/corpus_expr is the C expression machine's, fuzz_expr.c).
--
-- An input is a template letter, a mode letter and the rest:
--   "aF`" .. field1 .. "`" .. field2 .. "`" ...  fields fill the template's holes
--   "aG" .. bytes                                 the bytes drive a generator of
--                                                 expressions (grammar below)
-- Bytes outside printable ASCII, tab and line ends are mapped into it first (the module
-- names of one Lua state are limited to 2047, so the names an input can make must be
-- few), and "MARKER" becomes the path of a file that no input may create. Templates:
--   a  productions "A(x) : H1 --> A(H2) B(H3)"            b  the same as a list entry
--   c  two weighted rules with weights H2 and H4           d  axiom "A(H1)B(H2,H3)C"
--   e  contexts "B(y) < A(x) > C(z) : H1 --> ..."          f  env.v = H1, hooks change env
--   g  decomposition and homomorphism, then m:expand        h  productions H1, axiom H2
--   i  a rule group                                         j  a sub-L-system
-- The model is made with max_modules = 2000 and env = { k = 3, s = "ab", t = {1, 2, 3},
-- b = true, n = 0, big = 2^53, v = 5, f = function (a) return a end }, and derived 3
-- steps, once on the expression machine where rules allow it and once with
-- m.lua_expressions = true (math.random reseeded before each): the two must give the same
-- string, or both fail.
--
-- While an input runs, _G is emptied behind a metatable, and os.execute, os.remove,
-- os.rename, os.exit, os.getenv, os.tmpname, io.open, io.popen, io.lines, io.input,
-- io.output, load, loadfile, dofile and require are tripwires. A FINDING is: a global read
-- or written by code that is not in a file (rule code is compiled from strings: "rule
-- expression reached global 'os'"), a tripwire called with such code on the stack, the
-- marker file existing afterwards, or a change to the string, math or table libraries or
-- to lsys.BUILTIN. print is silenced; string.rep and table.move over 1e7 bytes or 1e6
-- entries, and patterns that may backtrack for long, stop the input as over budget (they
-- would run in C, where no hook can stop them). An input stopped by the budget is the
-- expression's own runaway code: clean, but counted. Expected errors: strings that start
-- with the model's location (the file and line of the lsys.lsystem call here).
local lsys = require "lsys"
local tw = require "tests.fuzz.lua.tripwire"

local type, pairs, pcall, error, tostring, tonumber, getmetatable, rawget, ipairs =
      type, pairs, pcall, error, tostring, tonumber, getmetatable, rawget, ipairs
local getinfo = debug.getinfo
local format, byte, char, sub, gsub =
      string.format, string.byte, string.char, string.sub, string.gsub
local concat = table.concat
local tmpname, os_remove, open = os.tmpname, os.remove, io.open
local randomseed = math.randomseed
local LIBS = { string = string, math = math, table = table, BUILTIN = lsys.BUILTIN,
               stringmeta = getmetatable("") }
local string_lib, table_lib = string, table
local BUILTIN = lsys.BUILTIN
local _ENV = nil

local T = { maxlen = 2048, budget = 1, budget_clean = true }

local MARKER = tmpname()
os_remove(MARKER)

-- --------------------------------------------------------------------------
-- Inputs

local function prepare (bytes)
  return (gsub(bytes, "[^\t\n\r\32-\126]", function (c) return char(byte(c) % 95 + 32) end))
end

-- the generator: `r(n)` reads the next byte as a choice in 1..n (1 when the bytes run out,
-- and choice 1 is always a leaf)
local NUMS = { "1", "0", "2", "3", "0.5", "-1", "10", "1e308", "1e-320", "2^53", "2^63",
               "math.maxinteger", "math.mininteger", "0x7fffffffffffffff", "1/0", "0/0",
               "-0.0", "3.25", "255", "0x10", "7 // 2", "9007199254740993", "1e16", "-2^31" }
local NAMES = { "pi", "huge", "k", "s", "t", "b", "n", "big", "f", "v", "math.pi",
                "math.huge", "unknown", "E", "type_", "error_", "c_", "self", "arg", "_",
                "true", "false", "nil", "ran()", "..." }
local STRINGS = { '"ab"', "'x'", "[[s]]", '"\\65"', '""', "[==[ ]] ]==]", '"\\z  "', '"%d"',
                  '"\\0"', '"1"', '"0x1p4"', "'a\\\"b'" }
local FN1 = { "abs", "floor", "ceil", "sqrt", "exp", "log", "sin", "cos", "tan", "asin",
              "acos", "atan", "math.floor", "math.abs", "math.sqrt", "math.log",
              "math.tointeger", "math.type", "deg", "rad", "tostring", "tonumber", "type",
              "ran", "string.len", "string.upper", "#", "select", "print", "error", "assert",
              "math.random", "string.char", "string.byte", "table.unpack", "ipairs", "pairs",
              "f", "-", "not", "math.fmod", "string.dump" }
local FN2 = { "min", "max", "fmod", "atan", "nran", "math.max", "math.min", "string.rep",
              "string.sub", "string.format", "select", "tonumber", "assert", "error",
              "math.random", "table.concat", "string.find", "string.gsub", "table.insert",
              "math.ult", "string.byte", "ran" }
local BIN = { "+", "-", "*", "/", "//", "%", "^", "..", "==", "~=", "<", "<=", ">", ">=",
              "and", "or", "&", "|", "~", "<<", ">>" }
local UN = { "-", "not ", "#", "~", "- -" }
local BASES = { "math", "string", "table", '("")', "('ab')", "t", "s", "E", "x" }
local FIELDS = { ".pi", ".x", ".rep", ".dump", ".len", "[1]", "[x]", ".__index", ".floor",
                 ".huge", "[0/0]", ".n" }
local METHODS = { ":rep(2)", ":len()", ":upper()", ":sub(1, 1)", ":byte()", ":format(1)",
                  ":gsub('a', 'b')", ":find('b')", ":dump()", ":rep(3, ',')", ":x()" }
local STMTS = { "while true do end", "while true do x = x .. x end",
                "repeat until false", "while true do t[#t + 1] = t end", "string.rep = nil",
                "math.floor = print", "x = 1", "os = 1", "_ENV = nil", "error({})",
                "error(setmetatable({}, {__tostring = error}))", "error()", "goto l ::l::",
                "return ...", "local t = {} t[t] = t return #t", "string.x = 1",
                "table.insert(math, 1)", "return (''):rep(1e18)",
                "return ('x'):rep(1e6):rep(1e6)", "return table.move({1}, 1, 1e12, 2)",
                "return ('a'):rep(40):find(('a*'):rep(20) .. 'b')",
                "local f f = function () return f() end return f()",
                "local function g () return 1 + g() end return g()" }
local HOSTILE = {
  '""..os.execute("touch MARKER")', '""..io.open("MARKER", "w")', '#(""..os.getenv("HOME"))',
  '"" .. os.exit(3)', "_ENV", "_G", "_G.os", "_ENV.os", '(""):rep(2)', '("").rep',
  "string.dump(function () end)", 'load("return 1")', 'require("os")', "debug.getinfo(1)",
  "package.loaded", 'collectgarbage("count")', "setmetatable({}, {})", 'getmetatable("")',
  'getmetatable("").__index', "rawset({}, 1, 1)", 'dofile("MARKER")', 'loadfile("MARKER")',
  "os.exit(3)", "x --\"\n + #os.getenv'HOME' --\"\n", "x --\"\n + #_G.os.getenv'HOME' --\"\n",
  '#([["]]..os.execute("touch MARKER")..[["]])', '#([["]]..tostring(io)..[["]])',
  '1) end os.execute("touch MARKER") local function f_() return (1',
  '1)) end end os.execute("touch MARKER") return (function() return (1',
  "1 --[[\n]] + 0", "(function () return os end)()",
  "(function (...) return select('#', ...) end)(1, 2)",
  "E.os", "E[\"os\"]", "error_(os)", "type_(io)", '#("".."x")', '""..x',
  '#(""..tostring(io))', "x..os", "x .. _G", "x ..\n os", "..os", "x.. --\nos",
  "(('x'):rep(2)).dump", "string.dump(tostring)", '(function () local os = require "os" end)()',
  "(function () E = nil end)()", '(function () print = os end)()', "#E", "next", "rawget",
  "[[", "]]", "--[==[", "]==]", "\n", "end", "function", "\r", "\0",
}
local BREAKERS = { "--[[", "]]", "\n", "end", "function", ")", "(", ",", "--", "[[", "'", '"',
                   "...", "::l::", "goto l", "return", ";", "local", "=", "end)", "end end",
                   "\n)", ")(", "{", "}", "\\", "--\n", "\r" }

local function reader (s, pos)
  local i = pos
  return function (n)
    local b = byte(s, i)
    i = i + 1
    if b == nil then return 1 end
    return b % n + 1
  end
end

local function pick (r, l) return l[r(#l)] end

local function gen (r, d, P)
  local c = r(16)
  if d >= 5 then c = (c - 1) % 4 + 1 end
  if c == 1 then return pick(r, NUMS)
  elseif c == 2 then return pick(r, P)
  elseif c == 3 then return pick(r, NAMES)
  elseif c == 4 then return pick(r, STRINGS)
  elseif c == 5 then return pick(r, UN) .. gen(r, d + 1, P)
  elseif c == 6 or c == 7 then
    return gen(r, d + 1, P) .. " " .. pick(r, BIN) .. " " .. gen(r, d + 1, P)
  elseif c == 8 then return pick(r, FN1) .. "(" .. gen(r, d + 1, P) .. ")"
  elseif c == 9 then
    local args = gen(r, d + 1, P) .. ", " .. gen(r, d + 1, P)
    if r(3) == 1 then args = args .. ", " .. gen(r, d + 1, P) end
    return pick(r, FN2) .. "(" .. args .. ")"
  elseif c == 10 then
    local base = r(2) == 1 and "(" .. gen(r, d + 1, P) .. ")" or pick(r, BASES)
    return base .. (r(2) == 1 and pick(r, FIELDS) or pick(r, METHODS))
  elseif c == 11 then
    local k = r(4)
    if k == 1 then return "{" .. gen(r, d + 1, P) .. ", " .. gen(r, d + 1, P) .. "}"
    elseif k == 2 then return "#{" .. gen(r, d + 1, P) .. "}"
    elseif k == 3 then return "({x = " .. gen(r, d + 1, P) .. "}).x" end
    return "({" .. gen(r, d + 1, P) .. "})[1]"
  elseif c == 12 then
    local k = r(3)
    if k == 1 then
      return "(function (a) return " .. gen(r, d + 1, P) .. " end)(" .. gen(r, d + 1, P) .. ")"
    elseif k == 2 then return "(function () " .. pick(r, STMTS) .. " end)()" end
    return "(function (...) return select('#', ...) end)(" .. gen(r, d + 1, P) .. ")"
  elseif c == 13 then return "(" .. gen(r, d + 1, P) .. ")"
  elseif c == 14 then return pick(r, HOSTILE)
  elseif c == 15 then
    return gen(r, d + 1, P) .. " and " .. gen(r, d + 1, P) .. " or " .. gen(r, d + 1, P)
  end
  return gen(r, d + 1, P) .. " " .. pick(r, BREAKERS) .. " " .. gen(r, d + 1, P)
end

local function value (h)
  if h == nil then return 5 end
  if h == "true" then return true elseif h == "false" then return false end
  return tonumber(h) or h
end

local function newenv (v)
  return { k = 3, s = "ab", t = { 1, 2, 3 }, b = true, n = 0, big = 2 ^ 53, v = v,
           f = function (a) return a end }
end

-- templates: holes (defaults), formal parameters, and the options they build
local TEMPLATES = {
  { -- a
    P = { "x" }, d = { "x > 0", "x + 1", "x * 2" },
    build = function (h)
      return { axiom = "A(1)B(2)",
               productions = format("A(x) : %s --> A(%s) B(%s)", h[1], h[2], h[3]) }
    end },
  { -- b
    P = { "x" }, d = { "x > 0", "x + 1", "x * 2" },
    build = function (h)
      return { axiom = "A(1)",
               productions = { format("A(x) : %s --> A(%s) B(%s)", h[1], h[2], h[3]) } }
    end },
  { -- c
    P = { "x" }, d = { "x + 1", "1", "x * 2", "2" },
    build = function (h)
      return { axiom = "A(1)A(2)A(3)", seed = 7,
               productions = { format("A(x) --> A(%s) : %s", h[1], h[2]),
                               format("A(x) --> B(%s) : %s", h[3], h[4]) } }
    end },
  { -- d
    P = { "x", "y" }, d = { "1", "2", "3", "x < y" },
    build = function (h)
      return { axiom = format("A(%s)B(%s,%s)C", h[1], h[2], h[3]),
               productions = { "A(x) --> A(x + 1)", format("B(x, y) : %s --> B(y, x)", h[4]) } }
    end },
  { -- e
    P = { "x", "y", "z" }, d = { "x + y > z", "x + y + z", "y", "z", "z - 1" },
    build = function (h)
      return { axiom = "B(1)A(2)C(3)",
               productions = { format("B(y) < A(x) > C(z) : %s --> A(%s)[B(%s)]C(%s)", h[1],
                                      h[2], h[3], h[4]),
                               format("C(z) --> C(%s)", h[5]) } }
    end },
  { -- f
    P = { "x" }, d = { "5", "x < v", "x + v", "#s" },
    build = function (h)
      return { axiom = "A(1)",
               productions = { format("A(x) : %s --> A(%s) B(%s)", h[2], h[3], h[4]) },
               env = newenv(value(h[1])),
               start_each = function (model, step) model.env.k = step end }
    end },
  { -- g
    P = { "x" }, d = { "x + 1", "x > 1", "x / 2", "x * 10", "x" }, expand = true,
    build = function (h)
      return { axiom = "A(1)", productions = { format("A(x) --> A(%s) C(x)", h[1]) },
               decomposition = { format("C(x) : %s --> D(%s)", h[2], h[3]) },
               homomorphism = { format("D(x) --> F(%s) ~l(%s)", h[4], h[5]) } }
    end },
  { -- h
    P = { "x" }, d = { "A(x) --> A(x + 1) B(x)", "A(1)" },
    build = function (h, generated)
      if generated then
        return { axiom = "A(1)", productions = format("A(x) --> A(%s) B(%s)", h[1], h[2]) }
      end
      return { axiom = h[2], productions = h[1] }
    end },
  { -- i
    P = { "x" }, d = { "x > 1", "x + k", "nran(0, 1)" }, group = 1,
    build = function (h)
      return { axiom = "A(1)A(2)", productions = "A(x) --> A(x)",
               groups = { [1] = { format("A(x) : %s --> A(%s) B(%s)", h[1], h[2], h[3]) } } }
    end },
  { -- j
    P = { "x" }, d = { "x < 5", "x * 2" },
    build = function (h)
      return { axiom = "A(1)?(1,0.5)A(2)$A(3)", productions = "A(x) --> A(x + 1)",
               sub = { [1] = { productions = { format("A(x) : %s --> A(%s)", h[1], h[2]) } } } }
    end },
}

local function decode (bytes)
  local s = prepare(bytes)
  local ti = ((byte(s, 1) or 97) - 97) % #TEMPLATES + 1
  local tp = TEMPLATES[ti]
  local mode = sub(s, 2, 2)
  local h = {}
  local generated = mode == "G" or mode == "g"
  if generated then
    local r = reader(s, 3)
    for i = 1, #tp.d do h[i] = gen(r, 0, tp.P) end
  else
    local rest = sub(s, 3)
    if sub(rest, 1, 1) == "`" then rest = sub(rest, 2) end
    for f in (rest .. "`"):gmatch("([^`]*)`") do h[#h + 1] = f end
    for i = 1, #tp.d do if h[i] == nil then h[i] = tp.d[i] end end
  end
  for i = 1, #h do h[i] = gsub(h[i], "MARKER", MARKER) end
  return tp, h, generated, ti
end

-- --------------------------------------------------------------------------
-- Tripwires

local CTX
local wires = tw.new("rule expression", function () return T.run end)
local rulecode = tw.rulecode

local real_rep, real_move = string_lib.rep, table_lib.move
local real_find, real_match, real_gmatch, real_gsub =
      string_lib.find, string_lib.match, string_lib.gmatch, string_lib.gsub

-- what a rule expression may run in C for a long time or with much memory: guarded only
-- when called from rule code (lsys's own calls are its business). `level` is the stack
-- level of the wrapper's caller, seen from the function that calls fromrule.
local function fromrule (level) return rulecode(getinfo(level + 1, "S")) end

-- Lua's matcher backtracks: a pattern with q quantifiers can take about len^(q+1) steps
-- on a subject of length len (and a C function is out of the hook's reach)
local function heavy (subject, pat)
  if type(pat) ~= "string" or (type(subject) ~= "string" and type(subject) ~= "number") then
    return false
  end
  local _, q = real_gsub(pat, "[%*%-%+%?]", "")
  local _, b = real_gsub(pat, "%%[bf]", "")
  return (#tostring(subject) + 1) ^ (q + b + 1) > 1e8 and fromrule(3)
end
local LIMITED = {
  { string_lib, "rep", function (s, n, sep)
      if type(n) == "number" and n > 0 then
        local l = (type(s) == "string" or type(s) == "number") and #tostring(s) or 0
        local ls = (type(sep) == "string" or type(sep) == "number") and #tostring(sep) or 0
        if (n > 1e7 or (l + ls) * n > 1e7) and fromrule(2) then
          CTX.trip("memory", "string.rep of " .. tostring(n))
        end
      end
      return real_rep(s, n, sep)
    end },
  { table_lib, "move", function (a, f, e, t, a2)
      if type(f) == "number" and type(e) == "number" and e - f > 1e6 and fromrule(2) then
        CTX.trip("time", "table.move of " .. tostring(e - f))
      end
      return real_move(a, f, e, t, a2)
    end },
  { string_lib, "find", function (s, p, ...)
      if heavy(s, p) then CTX.trip("time", "pattern " .. p) end
      return real_find(s, p, ...)
    end },
  { string_lib, "match", function (s, p, ...)
      if heavy(s, p) then CTX.trip("time", "pattern " .. p) end
      return real_match(s, p, ...)
    end },
  { string_lib, "gmatch", function (s, p, ...)
      if heavy(s, p) then CTX.trip("time", "pattern " .. p) end
      return real_gmatch(s, p, ...)
    end },
  { string_lib, "gsub", function (s, p, ...)
      if heavy(s, p) then CTX.trip("time", "pattern " .. p) end
      return real_gsub(s, p, ...)
    end },
  { BUILTIN, "print", function () end },
}
local REALS = {}
for i, l in ipairs(LIMITED) do REALS[i] = l[1][l[2]] end

-- the libraries as they must be after every input
local function snapshot ()
  local snap = {}
  for name, lib in pairs(LIBS) do
    local s = {}
    for k, v in pairs(lib) do s[k] = v end
    snap[name] = s
  end
  return snap
end
local SNAP = snapshot()

-- the first difference from SNAP, repaired; nil when there is none
local function libchanges ()
  local msg
  local function changed (name, k)
    msg = msg or format("rule expression changed %s.%s", name, tostring(k))
  end
  for name, lib in pairs(LIBS) do
    local s = SNAP[name]
    for k, v in pairs(lib) do
      if s[k] ~= v then changed(name, k); lib[k] = nil end
    end
    for k, v in pairs(s) do
      if rawget(lib, k) ~= v then changed(name, k); lib[k] = v end
    end
  end
  return msg
end

function T.before ()
  for _, l in ipairs(LIMITED) do l[1][l[2]] = l[3] end
  wires.arm()
end

local function restore ()
  wires.disarm()
  for i, l in ipairs(LIMITED) do l[1][l[2]] = REALS[i] end
end

-- --------------------------------------------------------------------------
-- The target

local function make (opts)
  local m = lsys.lsystem(opts)
  return m
end
local WHERE = tostring(make {}):match("^lsys%.Model%((.*)%)$")

function T.clean (err)
  return sub(err, 1, #WHERE + 2) == WHERE .. ": "
end

local last

function T.run (bytes, ctx)
  CTX = ctx
  last = nil
  local tp, h, generated = decode(bytes)
  local opts = tp.build(h, generated)
  opts.max_modules = 2000
  opts.env = opts.env or newenv(5)
  local m = make(opts)
  local function go (lua)
    m.lua_expressions = lua
    randomseed(1)             -- math.random is visible (BUILTIN.math): the same draws twice
    if tp.group then m:use_group(tp.group) end
    local s = m:derive(3)
    local out = tostring(s)
    if tp.expand then out = out .. " | " .. tostring(m:expand(s)) end
    return out
  end
  local r = {}
  r.ok1, r.r1 = pcall(go, nil)
  r.ok2, r.r2 = pcall(go, true)
  last = r
  if not r.ok1 then error(r.r1, 0) end
  if not r.ok2 then error(r.r2, 0) end
end

function T.after (tripped)
  restore()
  local r = last
  last = nil
  local f = open(MARKER, "rb")
  if f then
    f:close()
    os_remove(MARKER)
    return "a rule expression created the marker file"
  end
  if #wires.hits > 0 then return wires.hits[1] end
  local changed = libchanges()
  if changed then return changed end
  if tripped or r == nil then return nil end
  if r.ok1 ~= r.ok2 then
    return format("the expression machine and the Lua closures disagree: %s / %s",
                  r.ok1 and "ok" or tostring(r.r1), r.ok2 and "ok" or tostring(r.r2))
  end
  if r.ok1 and r.r1 ~= r.r2 then
    return format("the expression machine and the Lua closures disagree: %s / %s", r.r1, r.r2)
  end
  return nil
end

function T.describe (bytes)
  local tp, h, generated, ti = decode(bytes)
  local lines = { format("template %s (%s)", char(96 + ti), generated and "generated" or "fields") }
  local opts = tp.build(h, generated)
  for _, k in ipairs { "axiom", "productions", "decomposition", "homomorphism", "groups", "sub" } do
    local x = opts[k]
    if type(x) == "string" then lines[#lines + 1] = k .. " = " .. x
    elseif type(x) == "table" then
      for i, e in pairs(x) do
        if type(e) == "table" then
          for j, e2 in pairs(e) do
            lines[#lines + 1] = format("%s[%s].%s = %s", k, tostring(i), tostring(j),
                                       type(e2) == "table" and concat(e2, " | ") or tostring(e2))
          end
        else
          lines[#lines + 1] = format("%s[%s] = %s", k, tostring(i), tostring(e))
        end
      end
    end
  end
  if opts.env then lines[#lines + 1] = "env.v = " .. tostring(opts.env.v) end
  return (gsub(concat(lines, "\n"), gsub(MARKER, "%p", "%%%0"), "MARKER"))
end

function T.finish () os_remove(MARKER) end

-- --------------------------------------------------------------------------
-- Seeds and dictionary

T.seeds = {
  "aF`x > 0`x + 1`x * 2",
  "aF`x < 3 and x > 0`floor(x * 1.5)`max(x, 2, 3)",
  "aF`x`x // 2`x % 0",
  "aF`x == 1 or nil`-x`2^x",
  "aF`true`math.max(x, 2)`math.pi * x",
  "aF`x ~= 2`1 / x`sqrt(x) + atan(x, 2)",
  "aF`not (x > 2)`ran(x)`nran(x, 1)",
  "bF`x`x + 1 --\n`x * 2",
  "bF`x > 0`#(\"ab\" .. x)`#tostring(x)",
  "bF`type(x) == 'number'`select('#', 1, 2)`({x, 2})[2]",
  "bF`x`(function (a) return a * 2 end)(x)`string.len(s)",
  "cF`x + 1`1`x * 2`3",
  "cF`x`0`x`0",
  "cF`x`x`x`-1",
  "cF`x`ran(2)`x`nran(1, 0.1)",
  "dF`pi`2 * k`ran(1)`x < y",
  "dF`1 + `2`3`x",
  "dF`#s`floor(-0.5)`1e308`y",
  "eF`x + y > z`x + y + z`y`z`z - 1",
  "eF`x < y`min(x, y, z)`max(y, z)`fmod(z, 2)`z",
  "fF`5`x < v`x + v`#s",
  "fF`hello`x < 3`x + #v`#(v .. x)",
  "fF`true`v and x < 2`k + x`b and 1 or 0",
  "gF`x + 1`x > 1`x / 2`x * 10`x",
  "gF`x + 1`x`x`ran()`nran(0, 1)",
  "hF`A(x) --> A(x + 1) B(sqrt(x))\nB(y) : y > 1 --> C`A(1)",
  "hF`A(x) : x < 2 --> A(x + 1) [B(x / 2)]\nB(x) --> F(x)`A(0.5)",
  "hF`A --> AB\nB --> A`A",
  "hF`A(x) --> A(x*2) : 1\nA(x) --> A(x/2) : 1`A(4)",
  "iF`x > 1`x + k`nran(0, 1)",
  "jF`x < 5`x * 2",
  -- hostile: each must fail cleanly, without reaching a global or the marker
  'bF`x`#(""..os.execute("touch MARKER"))`x',
  'bF`""..io.open("MARKER", "w")`x`x',
  'aF`""..os.exit(3)`x`x',
  "bF`x`x --\"\n + #os.getenv'HOME' --\"\n`x",
  "bF`x`x --\"\n + #_G.os.getenv'HOME' --\"\n`x",
  'bF`x`#([["]]..tostring(io)..[["]])`1',
  'bF`x`1) end os.execute("touch MARKER") local function f_() return (1`x',
  "bF`x`x --[[`]] + 1",
  'bF`x`#("").rep("a", 3)`#string.dump(function () end)',
  "bF`x`_ENV`_G",
  "dF`#(\"\"..os.getenv(\"HOME\"))`1`2`x",
  "dF`(function () os = 1 end)() or 1`1`1`x",
  "bF`x`(function () while true do end end)()`1",
  "bF`x`(function () x = 'x' while true do x = x .. x end end)()`1",
  "bF`x`(function () while true do t[#t + 1] = {} end end)()`1",
  "bF`x`#(''):rep(1e18)`1",
  -- generated
  "aG\5\1\2\3\4\5\6\7\8\9\10\11\12\13\14\15",
  "bG\14\0\14\1\14\2\14\3\14\4\14\5\14\6\14\7",
  "eG\6\8\2\9\3\10\4\11\5\12\6\13\7\14",
  "fG\12\2\9\3\12\1\2\15\8\1\2",
  "gG\16\6\1\2\7\3\4\8\5\6\9",
  "cG\9\4\2\1\2\3\4\5\6\7\8\9",
}

T.dict = { "`", "x", "y", "z", " --> ", " : ", "(", ")", "[", "]", ",", "..", "--", "--[[", "]]",
           "[[", "\n", "'", '"', "function", "end", "return", "local", "MARKER", "os", "io",
           "_G", "_ENV", "load", "require", "debug", "string.dump", "string.rep",
           "setmetatable", "getmetatable", "rawset", "collectgarbage", "package", "dofile",
           "loadfile", "E", "type_", "error_", "c_", "ran()", "nran(0, 1)", "pi", "huge", "k",
           "s", "t", "v", "math.", "string.", "table.", ":rep(", "#", "{", "}", " and ", " or ",
           " not ", "//", "%", "^", "~=", "==", "<=", ">=", "<<", ">>", "&", "|", "~", "1e308",
           "0/0", "1/0", "math.maxinteger", "2^53", "(function () ", " end)()", "while true do",
           "A(x)", "B(y)", "C(z)", "<", ">", "?(1)", "$", "%", "*", "@", "~l", "\r\n" }
for _, x in ipairs(HOSTILE) do T.dict[#T.dict + 1] = x end

return T
