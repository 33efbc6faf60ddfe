--- Fuzz target: `lsys import` (lua/lsys/cpfg/import.lua), the lsys model file written for
-- a cpfg model: import, load the written file, derive, and compare with the model loaded
-- directly. Its corpus is tests/fuzz/corpus_import.
--
-- The bytes are the text of the .l file in a scratch folder. A first line "//# NAME" names
-- it NAME.l (written as NAME.lua; NAME any bytes but "/" and NUL, at most 64, so that file
-- names reach the written file's comments). A line "//@ NAME" starts another file, NAME
-- (letters, digits, `_ . -`): a file it includes, or the view file when NAME ends in .v.
-- Both loads use the built-in preprocessor; a loaded model derives min(steps, 4) steps
-- with max_modules = 10000 and max_memory = 64M, then m:expand.
--
-- Expected errors: the loader's "FILE:LINE: ..." (as targets/cpfg.lua), the derivation's
-- (the model's own), and the importer's "cannot import: ..." refusals. Checks (a FINDING
-- otherwise): the written file compiles and loads ("cannot import: the written file does
-- not compile / load" is a finding: text of the input broke out of where it was put); the
-- file's own code reads no global but require, the basic functions and math, string,
-- table (it runs with a table of those, and while the importer loads it, with _G sealed
-- as targets/cpfg.lua seals it); it calls no os, io, load or dofile function itself; the
-- model it returns derives the string the direct load derives, and expands it alike, or
-- both fail; rule code (compiled from strings) reaches no global either. A derivation
-- stopped by the budget is the model's own; a load or import stopped by it is a finding
-- when it takes more than 2 s without the fuzzer's line hook too.
local lsys = require "lsys"
local import = require "lsys.cpfg.import"
local tw = require "tests.fuzz.lua.tripwire"

local type, pairs, ipairs, pcall, error, tostring, tonumber, loadfile, require, setmetatable =
      type, pairs, ipairs, pcall, error, tostring, tonumber, loadfile, require, setmetatable
local gethook, sethook = debug.gethook, debug.sethook
local format, srep = string.format, string.rep
local concat, insert = table.concat, table.insert
local tmpname, os_remove, execute, open = os.tmpname, os.remove, os.execute, io.open
local io_output, io_stdout = io.output, io.stdout
local min, clock, math_huge = math.min, os.clock, math.huge
local shq = require("lsys.util.text").shq
local cpfg = lsys.cpfg
local lsys_type = lsys.type
local G = _G

local T = { maxlen = 8192, budget = 5 }

local _ENV = nil

-- --------------------------------------------------------------------------
-- The scratch folder

local DIR = tmpname()
os_remove(DIR)
execute("mkdir -p " .. shq(DIR))

local function writefile (path, s)
  local f = open(path, "wb")
  if not f then return false end
  f:write(s)
  f:close()
  return true
end

-- The files of an input: { lname, parts = { { name, text } }, vname }
local function split (bytes)
  local lname = "main"
  local first, rest = bytes:match("^//#([^\n]*)\n?(.*)$")
  if first then
    local n = first:gsub("^ ", ""):gsub("[/%z]", "_"):sub(1, 64)
    if n ~= "" and n ~= "." and n ~= ".." then lname = n end
    bytes = rest
  end
  local files, cur, name = {}, {}, lname .. ".l"
  for line in (bytes .. "\n"):gmatch("([^\n]*)\n") do
    local n = line:match("^//@%s*([%w_][%w_.%-]*)%s*$")
    if n then
      files[#files + 1] = { name = name, text = concat(cur, "\n") }
      cur, name = {}, n
    else
      cur[#cur + 1] = line
    end
  end
  files[#files + 1] = { name = name, text = concat(cur, "\n") }
  return lname, files
end

local written = {}
local LFILE, VFILE, OUT

local function writeinput (bytes)
  local lname, files = split(bytes)
  LFILE, OUT, VFILE = DIR .. "/" .. lname .. ".l", DIR .. "/" .. lname .. ".lua", nil
  for i, f in ipairs(files) do
    local path = i == 1 and LFILE or DIR .. "/" .. f.name
    if (i == 1 or (path ~= LFILE and path ~= OUT)) and writefile(path, f.text) then
      written[#written + 1] = path
      if i > 1 and f.name:match("%.v$") then VFILE = path end
    end
  end
end

local function cleaninput ()
  for _, p in ipairs(written) do os_remove(p) end
  if OUT then os_remove(OUT) end
  written = {}
end

-- --------------------------------------------------------------------------
-- What the written file may read, as the importer loads it (_G) and as it is loaded here

local BASIC = { require = true, ipairs = true, pairs = true, math = true, string = true,
                table = true, type = true, tostring = true, tonumber = true, error = true,
                assert = true, select = true, next = true, pcall = true, rawget = true,
                rawequal = true, rawlen = true, setmetatable = true, getmetatable = true,
                utf8 = true, print = true }

local function isout (info) return info ~= nil and info.source == "@" .. OUT end

local phase          -- "load", "derive", "import", "written", "derive2": where the input is
local run            -- T.run, for the tripwires' stack walk

local wires = tw.new("the written file or rule code", function () return run end, {
  iscode = function (info) return tw.rulecode(info) or isout(info) end,
  allow = function (info, name) return isout(info) and BASIC[name] == true end,
  direct = true,
})

-- the environment the written file is loaded with here: BASIC, require of lsys only
local readglobal
local function fileenv ()
  local env = {}
  for k in pairs(BASIC) do env[k] = G[k] end
  env.require = function (name)
    if type(name) ~= "string" or (name ~= "lsys" and not name:match("^lsys%.")) then
      readglobal = readglobal or format("require(%s)", tostring(name))
      error("fuzz: the written file requires " .. tostring(name), 0)
    end
    return require(name)
  end
  return setmetatable(env, { __index = function (_, k)
    readglobal = readglobal or tostring(k)
    return nil
  end, __newindex = function (_, k)
    readglobal = readglobal or "(writes) " .. tostring(k)
  end })
end

local NULL = open("/dev/null", "w")

-- --------------------------------------------------------------------------
-- The target

local function derive (m)
  local rules = m._rules
  rules:config("max_modules", 10000)
  rules:config("max_memory", 64 * 1024 * 1024)
  local s = m:derive(min(m.steps, 4))
  return tostring(s), tostring(m:expand(s))
end

local last, lastbytes

function T.before (bytes)
  phase, lastbytes, last, readglobal = nil, bytes, nil, nil
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
  local r = {}
  last = r
  phase = "load"
  local m = cpfg.load(LFILE, VFILE, { cpp = "builtin" })
  phase = "derive"
  r.dok, r.s1, r.e1 = pcall(derive, m)
  phase = "import"
  local text = import.source(LFILE, VFILE, { out = OUT, cpp = "builtin" })
  r.text = text
  wires.disarm()                          -- the file is written and loaded here bare
  writefile(OUT, text)
  phase = "written"
  local chunk, err = loadfile(OUT, "t", fileenv())
  if chunk == nil then r.fail = "the written file does not compile here: " .. err return end
  local ok, m2 = pcall(chunk)
  if not ok then r.fail = "the written file does not load here: " .. tostring(m2) return end
  if lsys_type(m2) ~= "model" then r.fail = "the written file returns " .. type(m2) return end
  wires.arm()
  phase = "derive2"
  r.iok, r.s2, r.e2 = pcall(derive, m2)
  phase = "done"
end
run = T.run

-- Lua's runtime errors, as targets/cpfg.lua has them
local RUNTIME = { "attempt to ", "bad argument", "stack overflow", "index is NaN",
                  "index is nil", "C stack", "error in error handling", "number has no integer",
                  "is nil, not a number" }

function T.clean (err)
  for _, r in ipairs(RUNTIME) do
    if err:find(r, 1, true) then return false end
  end
  if phase == "load" then
    local file, line = err:match("^(/[^\n]-):(%d+): ")
    return file ~= nil and tonumber(line) >= 1
  end
  if phase == "import" then
    return err:find("^cannot import: ") ~= nil and
           not err:find("^cannot import: the written file does not ")
  end
  return false
end

local function check (r)
  if r.fail then return r.fail end
  if readglobal then return "the written file reads global " .. readglobal end
  if r.dok ~= r.iok then
    return format("the direct load %s, the written file %s", r.dok and "derives" or
                  "fails (" .. tostring(r.s1) .. ")", r.iok and "derives" or
                  "fails (" .. tostring(r.s2) .. ")")
  end
  if r.dok then
    if r.s1 ~= r.s2 then
      return format("the written file derives %s, the direct load %s", r.s2:sub(1, 200),
                    r.s1:sub(1, 200))
    end
    if r.e1 ~= r.e2 then return "the written file expands the string otherwise" end
  end
  return nil
end

function T.after (tripped)
  restore()
  if #wires.hits > 0 then return wires.hits[1] end
  local r = last
  last = nil
  if readglobal then return "the written file reads global " .. readglobal end
  if tripped or r == nil or (phase ~= "done" and not r.fail) then return nil end
  return check(r)
end

-- The seconds the load and import of the last input take without the line hook.
local function bare ()
  T.before(lastbytes)
  local t0 = clock()
  local over = false
  local oh, om, oc = gethook()
  sethook(function ()
    if clock() - t0 > 10 then over = true; error("fuzz: over 10 s", 0) end
  end, "", 100000)
  pcall(function ()
    cpfg.load(LFILE, VFILE, { cpp = "builtin" })
    import.source(LFILE, VFILE, { out = OUT, cpp = "builtin" })
  end)
  sethook(oh, om, oc)
  local el = clock() - t0
  restore()
  return (over or #wires.hits > 0) and math_huge or el
end

function T.budget_clean (tripped)
  if phase == "derive" or phase == "derive2" then return true end
  return tripped == "time" and bare() <= 2
end

function T.finish ()
  cleaninput()
  os_remove(DIR)
end

function T.describe (bytes) return bytes end

-- --------------------------------------------------------------------------
-- Seeds, dictionary, mutators

T.seeds = {}
local function seedfile (path, name)
  local f = open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  if name then s = "//# " .. name .. "\n" .. s end
  return s
end
for _, name in ipairs { "koch.l", "blocks.l", "exprs.l", "decomp.l", "context.l", "multi.l",
                        "ring.l", "stochastic.l", "macros.l", "strings.l", "printf.l",
                        "startaxiom.l", "depth.l" } do
  T.seeds[#T.seeds + 1] = seedfile("tests/data/cpfg/" .. name)
end
do   -- the command line's plant: an #include of defines with comments, and its view
  local l, h, v = seedfile("tests/data/cpfg/cli/plant.l", "plant"),
                  seedfile("tests/data/cpfg/cli/plant.h"), seedfile("tests/data/cpfg/cli/plant.v")
  if l and h and v then
    T.seeds[#T.seeds + 1] = l .. "\n//@ plant.h\n" .. h .. "\n//@ plant.v\n" .. v
  end
end
insert(T.seeds, "//# a plant, with 'quotes' and \"doubles\" and ]] brackets\n"
  .. "/* A comment that names [[things]] and --[==[ levels ]==] */\n"
  .. "#define RATE 2 /* per step */\nLsystem: 1\nderivation length: 2\nAxiom: A(1)\n"
  .. "A(x) --> F(x * RATE)A(x + 1)\nendlsystem\n")
insert(T.seeds, "/* ends in a carriage return\r */\nLsystem: 1\nderivation length: 1\n"
  .. "Axiom: F\nF --> FF\nendlsystem\n")

T.dict = {
  "Lsystem: 1\n", "Lsystem: 2\n", "derivation length: 3\n", "Axiom: ", "endlsystem\n",
  "ignore: +-/\n", "consider: AB[]\n", "seed: 5\n", "define: { ", "array a[3] = { 1, 2, 3 }",
  "; }\n", "Start: { ", "StartEach: { ", "EndEach: { ", "End: { ", "}\n", "decomposition\n",
  "homomorphism\n", "maximum depth: 2\n", " --> ", " : ", " < ", " > ", "*", "{", "}", ";",
  "if (", ") {", "} else {", "while (", "x = x + 1;", "printf(\"", "\\n\")", "func(1, x)",
  "ran(1)", "nran(0, 1)", "sin(", "A(x)", "B(x, y)", "F", "+", "[", "]", "?(2, 1)", "$",
  "#define X 1\n", "#define RATE 1.5 /* growth */\n", "#define F(a, b) ((a) + (b))\n",
  "#include \"inc.h\"\n", "//@ inc.h\n", "//@ main.v\n", "//# ", "angle increment: 45\n",
  "initial line width: 3\n", "color increment: 2\n", "/*", "*/", "//", "\r", "\n", "\r\n",
  "\0", "\t", "\27", "--", "--[[", "]]", "[[", "[==[", "]==]", "\"", "'", "\\", "%q", "%s",
  "os.execute(\"touch MARKER\")", "error(\"x\")", "return", "end", "local x = 1", "\127",
  "\226\128\168", "x", "X", "RATE", "LIMIT", "os", "io", "_G", "_ENV", "env", "cpfg",
  "lsys", "L1", "m", "array", "reset", "productions", "pi", "math", "require",
}

T.mutators = {
  function (rnd, s)                        -- a leading comment of the input's own
    local bits = { "\r", "\n", "--", "]]", "]=]", "*/", "\0", "os.exit(3)", " x ", "\"", "\\" }
    local c = {}
    for i = 1, rnd(6) do c[i] = bits[rnd(#bits)] end
    return "/* " .. concat(c) .. " */\n" .. s
  end,
  function (rnd, s)                        -- a file name of the input's own
    local bits = { "p", "\r", "\n", "-- ", "]]", "'", "\"", " ", "\\", "%", "$(x)", "\t" }
    local c = {}
    for i = 1, rnd(5) do c[i] = bits[rnd(#bits)] end
    return "//# " .. concat(c):gsub("\n", "\r") .. "\n" .. (s:gsub("^//#[^\n]*\n", ""))
  end,
  function (rnd, s)                        -- a #define of a number with a comment
    local bits = { "\r", "--", "]]", "*", "/", "x", " ", "\"" }
    local c = {}
    for i = 1, rnd(5) do c[i] = bits[rnd(#bits)] end
    return "#define N" .. rnd(9) .. " " .. rnd(9) .. " /* " .. concat(c) .. " */\n" .. s
  end,
  function (rnd, s)                        -- a long line: a piece repeated
    if #s == 0 then return s end
    local i = rnd(#s)
    return s:sub(1, i - 1) .. srep(s:sub(i, i + rnd(16) - 1), rnd(64)) .. s:sub(i)
  end,
}

return T
