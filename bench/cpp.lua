-- The built-in cpfg preprocessor on hostile inputs: how long lsys.cpfg.load
-- takes to refuse each of the files the cpfg fuzz target found (tests/cpfg_errors_spec.lua
-- checks their messages; timing lives here, not in the suite).
--
--   build/bin/lsys bench/cpp.lua
--
-- Each case is loaded with cpp = "builtin" from a scratch folder, best of 3 (CPU time of this
-- process or the lsys program's wall clock), and printed with the time it must stay under.
-- Plain Lua works too: LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;'
-- lua5.4 bench/cpp.lua

local script = arg and arg[0] or "bench/cpp.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local lsys = B.load_lsys()

local function lsystem (axiom)
  return "Lsystem: 1\nderivation length: 1\nAxiom: " .. axiom .. "\nendlsystem\n"
end

-- { name, target seconds, files { name = text } (main.l is loaded), the message expected }
local function cases ()
  local out = {}
  local defs = "#define A0 x\n"
  for i = 1, 30 do defs = defs .. ("#define A%d A%d A%d\n"):format(i, i - 1, i - 1) end
  out[#out + 1] = { "a macro doubling its text 30 times", 2,
                    { ["main.l"] = defs .. lsystem("X(A30)") }, "macro expansion longer" }
  out[#out + 1] = { "20,000 unclosed macro calls on one line", 1,
                    { ["main.l"] = "#define G(x) x\n" .. lsystem("A(" .. ("G(x "):rep(20000)) },
                    "expected to close" }
  local f = { ["main.l"] = '#include "f1.l"\n' .. lsystem("A"), ["f23.l"] = "\n" }
  for i = 1, 22 do f["f" .. i .. ".l"] = ('#include "f%d.l"\n'):rep(2):format(i + 1, i + 1) end
  out[#out + 1] = { "22 files including the next twice", 1, f, "more than 100000 lines" }
  local g = { ["main.l"] = '#include "f1.l"\n' .. lsystem("A"),
              ["f13.l"] = "#define X x\n" .. ("X + "):rep(500) .. "\n" }
  for i = 1, 12 do g["f" .. i .. ".l"] = ('#include "f%d.l"\n'):rep(2):format(i + 1, i + 1) end
  out[#out + 1] = { "12 files including the next twice, long lines", 3, g, "MiB of text" }
  return out
end

local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir -m 700 " .. B.shell_quote(dir)))

print(("built-in preprocessor, %s, best of 3"):format(B.clock_name))
print(("%-48s %10s %10s  %s"):format("case", "seconds", "target", ""))
local missed = 0
for _, c in ipairs(cases()) do
  os.execute("rm -f " .. B.shell_quote(dir) .. "/*.l")
  for name, text in pairs(c[3]) do B.write_file(dir .. "/" .. name, text) end
  local msg
  local t = B.best(function ()
    local ok, e = pcall(lsys.cpfg.load, dir .. "/main.l", nil, { cpp = "builtin" })
    msg = not ok and tostring(e) or "loaded"
  end, 3)
  local ok = t < c[2] and msg:find(c[4], 1, true) ~= nil
  if not ok then missed = missed + 1 end
  print(("%-48s %10.3f %10.1f  %s%s"):format(c[1], t, c[2], B.verdict(ok),
        msg:find(c[4], 1, true) and "" or "  (message: " .. msg .. ")"))
end
os.execute("rm -rf " .. B.shell_quote(dir))
print(missed == 0 and "all within their targets" or missed .. " missed")
