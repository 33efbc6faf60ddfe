-- Writes tests/data/cpfg_probes.lua: turtle sequences with query modules (?P position,
-- ?H ?L ?U frame), each run through cpfg, which fills the queries in batch mode. The spec
-- tests/cpfg_probe_spec.lua loads the same .l and .v texts with lsys.cpfg.load and checks
-- that lsys's turtle reports what cpfg's did (positions to 1e-4 of the step).
-- Usage: lua5.4 tools/cpfg-probes.lua CPFG [OUT]
--   CPFG: the cpfg program built for batch use (docs/cpfg.md, "cpfg as a reference");
--   OUT: default tests/data/cpfg_probes.lua.
-- Add a case to CASES below and run the tool again; look at the diff of OUT.
local T = dofile(((arg and arg[0] or "tools/x.lua"):match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local q, read, write = T.q, T.read, T.write

local cpfg, out = arg[1], arg[2] or "tests/data/cpfg_probes.lua"
if not cpfg then
  io.stderr:write("usage: lua5.4 tools/cpfg-probes.lua CPFG [OUT]\n")
  os.exit(2)
end

local Q = "?P(0,0,0)?H(0,0,0)?L(0,0,0)?U(0,0,0)"

-- Each case: name, axiom (Q is the four queries), and optionally view (lines of the .v
-- file), lsystem (more lines of L-system 1: productions, ...), steps (derivation length,
-- default 0), more (further L-systems, whole text) and defines (lines before Lsystem:).
local CASES = {
  { "moves", "F(2)" .. Q .. "f(3)" .. Q .. "G(1.5)" .. Q .. "g(0.5)" .. Q .. "F" .. Q },
  { "turn left and right", "+(30)F(2)" .. Q .. "-(75)F(1)" .. Q .. "+F" .. Q .. "-F" .. Q,
    view = { "angle increment: 20" } },
  { "pitch down and up", "&(45)F(10)" .. Q .. "^(30)F(10)" .. Q .. "&F" .. Q .. "^F" .. Q,
    view = { "angle increment: 25" } },
  { "roll right and left", "/(90)&(45)F(10)" .. Q .. "\\(30)+(20)F(3)" .. Q .. "/&F" .. Q ..
    "\\^F" .. Q, view = { "angle increment: 15" } },
  { "turn around", "+(30)|F(4)" .. Q .. "&(20)|F(2)" .. Q },
  { "roll to vertical", "/(30)&(50)@v" .. Q .. "F(2)&(90)/(30)@v" .. Q .. "+(40)&(10)@vF" .. Q },
  { "set frame and move to", "@R(1,1,0)" .. Q .. "F(2)" .. Q .. "@R(0,0,1,1,0,0)F" .. Q ..
    "@M(1,2,3)" .. Q .. "F(2)" .. Q },
  { "branches restore the turtle",
    "F(1)[+(30)F(2)" .. Q .. "[&(40)F(1)" .. Q .. "]/(70)F(1)" .. Q .. "]F(1)" .. Q },
  { "a 3D spiral", string.rep("F(1)/(137.5)&(23)+(11)", 12) .. Q },
  { "width, colour and discs do not move the turtle",
    "#(3)F(1);(2)!(1),@o(2)@c(1)@O(1)F(1)" .. Q },
  { "polygons", "{.+(30)f(2).-(60)f(2).}F(1)" .. Q .. "{.&(30)F(1).G(1).g(1)}" .. Q },
  { "scale of a sub-L-system", "F(2)?(2,0.5)F(2)" .. Q .. "&(30)F(4)" .. Q .. "$F(2)" .. Q,
    more = "Lsystem: 2\nderivation length: 0\nAxiom: F\n\nendlsystem\n" },
  { "generalized cylinders", "@GsF(2)/(45)@Gc(2)&(20)F(2)@Ge(3)" .. Q },
  { "old-style tropism, bent after each move",
    string.rep("F(1)", 6) .. Q .. "+(60)" .. string.rep("F(1)", 4) .. Q,
    view = { "tropism direction: 0,-1,0", "initial elasticity: 0.2" } },
  { "old-style tropism, elasticity set by _",
    "F(1)F(1)" .. Q .. "_(0.5)F(1)F(1)" .. Q .. "[_(0)F(1)F(1)" .. Q .. "]F(1)" .. Q,
    view = { "tropism direction: 1,0,0", "initial elasticity: 0.1" } },
  { "tropism and the elasticity modules",
    "+(50)F(1)F(1)" .. Q .. "@Ts(1,0.4)F(1)" .. Q .. "@Ti(1)F(1)" .. Q .. "@Td(1,0.3)F(1)" ..
    Q, view = { "tropism: T: 0 -1 0 A: 0 E: 0.1 S: 0.05" } },
  { "diatropism", "&(30)F(1)F(1)F(1)" .. Q .. "/(90)F(1)F(1)" .. Q,
    view = { "tropism: T: 0 1 0 A: 90 E: 0.3 S: 0.05" } },
  { "two tropisms", "+(70)F(1)F(1)F(1)" .. Q,
    view = { "tropism: T: 0 -1 0 A: 0 E: 0.1 S: 0.05", "tropism: T: 1 0 0 A: 0 E: 0.2 S: 0" } },
  { "torque", "&(40)F(1)F(1)F(1)" .. Q .. "/(60)F(1)" .. Q,
    view = { "torque: T: 1 0 0 E: 0.2 S: 0.1" } },
  { "old-style tropism, _ adds the increment, default direction",
    "F(1)" .. Q .. "_F(1)F(1)" .. Q .. "__F(1)F(1)" .. Q .. "_(-0.3)&(30)F(1)F(1)" .. Q,
    view = { "initial elasticity: 0", "elasticity increment: 0.15" } },
  { "intensity of a tropism and a torque", "+(60)&(30)F(1)F(1)F(1)" .. Q,
    view = { "tropism: T: 0 -2 0 A: 0 E: 0.3 S: 0 I: 0.5", "torque: T: 3 0 0 E: 0.4 I: 2" } },
  { "twist under a tropism", "+(40)F(1)/(90)F(1)" .. Q .. "/(90)@TfF(1)" .. Q ..
    "@TpF(1)" .. Q, view = { "tropism: T: 0 -1 0 A: 0 E: 0.1 S: 0.05" } },
}

-- A Lua string literal of s, one line (\n for line ends).
local function lit (s) return (string.format("%q", s):gsub("\\\n", "\\n")) end

local function ltext (c)
  local parts = {}
  for _, d in ipairs(c.defines or {}) do parts[#parts + 1] = d end
  parts[#parts + 1] = "Lsystem: 1"
  parts[#parts + 1] = "derivation length: " .. (c.steps or 0)
  parts[#parts + 1] = "Axiom: " .. c[2]
  for _, d in ipairs(c.lsystem or {}) do parts[#parts + 1] = d end
  parts[#parts + 1] = ""
  parts[#parts + 1] = "endlsystem"
  local s = table.concat(parts, "\n") .. "\n"
  if c.more then s = s .. "\n" .. c.more end
  return s
end

local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir -p " .. q(dir)))
local ok, err = pcall(function ()
  local lines = {
    "-- luacheck: no max line length",
    "-- Made by tools/cpfg-probes.lua from cpfg's batch output: do not edit; add cases to the",
    "-- tool and run it again. Each case: its .l and .v texts and the string cpfg derived,",
    "-- whose query modules hold cpfg's turtle (?P position, ?H ?L ?U frame).",
    "return {",
  }
  for _, c in ipairs(CASES) do
    local l, v = ltext(c), table.concat(c.view or {}, "\n") .. "\n"
    write(dir .. "/p.l", l)
    write(dir .. "/p.v", v)
    write(dir .. "/x.map", "")
    os.remove(dir .. "/out.str")
    local cmd = string.format("cd %s && %s -g -m x.map -str out.str p.l p.v </dev/null " ..
                              ">err.txt 2>&1", q(dir), q(cpfg))
    os.execute(cmd)
    local s = read(dir .. "/out.str")
    local e = read(dir .. "/err.txt") or ""
    if not s or e:find("Error") then
      error(string.format("case '%s': cpfg failed: %s", c[1], e))
    end
    s = s:gsub("\n", "")                 -- cpfg breaks its string into lines of 80
    lines[#lines + 1] = string.format("  { name = %s,\n    l = %s,\n    v = %s,\n    cpfg = %s },",
                                      lit(c[1]), lit(l), lit(v), lit(s))
    io.write(string.format("%-50s %d queries\n", c[1], select(2, s:gsub("%?[PHLU]%(", ""))))
  end
  lines[#lines + 1] = "}"
  write(out .. ".tmp", table.concat(lines, "\n") .. "\n")
  assert(os.rename(out .. ".tmp", out))
end)
os.execute("rm -rf " .. q(dir))
if not ok then io.stderr:write("cpfg-probes: ", tostring(err), "\n"); os.exit(1) end
print("wrote " .. out)
