-- The cost of sending the geometry of interpreted modules (docs/open.md §3): one pass of a
-- string of N queries `?E(0)F(1)[+F(1)]` answered by the test program lsys_envslave, with
-- and without `interpreted modules: F` in its communication file.
--
--   build/bin/lsys bench/interpreted.lua [N...]       (default 5000 20000)
--
-- Printed: each pass's time (best of 3, the clock B.clock_name says), the time a query
-- adds when its segment is sent, and a verdict against the target (at most 100 µs a query:
-- the scene the pass draws, the records and the text). Needs the build's lsys_envslave.
local B = dofile((arg[0]:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local lsys = B.load_lsys()

local slave = os.getenv("LSYS_ENVSLAVE") or B.root .. "/build/lsys_envslave"
if slave:sub(1, 1) ~= "/" then slave = io.popen("pwd"):read("l") .. "/" .. slave end
if not io.open(slave, "r") then
  print("interpreted: " .. slave .. " is not built: nothing to time")
  return
end
local sizes = {}
for _, a in ipairs(arg) do sizes[#sizes + 1] = tonumber(a) end
if #sizes == 0 then sizes = { 5000, 20000 } end

local function efile (interpreted)
  local path = os.tmpname()
  local f = assert(io.open(path, "w"))
  f:write("executable: " .. slave .. " echo\ncommunication type: pipes 1000\n"
    .. "turtle position: %g %g %g\n" .. (interpreted and "interpreted modules: F\n" or ""))
  f:close()
  return path
end
local with, without = efile(true), efile(false)

local TARGET = 100e-6
local worst = 0
print(("interpreted modules: %s"):format(B.clock_name))
for _, n in ipairs(sizes) do
  local t = {}
  for k, e in ipairs { without, with } do
    local env = lsys.environment.program(e)
    local m = lsys.lsystem { axiom = string.rep("?E(0)F(1)[+F(1)]", n), steps = 1,
                             environment = env }
    t[k] = B.best(function () return m:derive() end, 3)
    env:finish()
  end
  local per = (t[2] - t[1]) / n
  worst = math.max(worst, per)
  print(("  %6d queries: %.3f s plain, %.3f s with the geometry: +%.1f µs a query")
        :format(n, t[1], t[2], per * 1e6))
end
os.remove(with)
os.remove(without)
print(("verdict: %s (target: at most %.0f µs a query)"):format(
  worst <= TARGET and "met" or "missed", TARGET * 1e6))
