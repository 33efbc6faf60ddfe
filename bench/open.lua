-- Open L-systems talking to an environmental program: lsys against cpfg on the same model
-- and the same program (vlab's honda81), over each transport (docs/open.md §3).
--
--   build/bin/lsys bench/open.lua [--cpfg PATH] [--enviro DIR] [--steps N]
--
-- The model is tests/data/cpfg/open/ulam.l (Ulam's crystal: every apex sends a sensor each
-- step), derived N steps (default 16 and 40) with its communication file switched to
-- pipes, files and memory. Each figure is a whole process, wall clock, best of 3: lsys
-- `derive MODEL --environment FILE.e`, cpfg `-g -e FILE.e -str` (CPFG or --cpfg; the
-- programs from LSYS_ENVIRO_BIN or --enviro, tools/enviro-build.sh). Printed: the time,
-- the time per derivation step, the queries sent, and cpfg's time and the ratio. Without
-- the program it says so and stops; without cpfg it times lsys alone.
local B = dofile((arg[0]:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local lsys = B.load_lsys()
local q = B.shell_quote

local cpfg, enviro, steps = os.getenv("CPFG"), os.getenv("LSYS_ENVIRO_BIN"), nil
local i = 1
while i <= #arg do
  if arg[i] == "--cpfg" then cpfg = arg[i + 1]; i = i + 2
  elseif arg[i] == "--enviro" then enviro = arg[i + 1]; i = i + 2
  elseif arg[i] == "--steps" then steps = tonumber(arg[i + 1]); i = i + 2
  else error("unknown argument " .. arg[i]) end
end
if not enviro then
  print("open: vlab's honda81 is not built (tools/enviro-build.sh; LSYS_ENVIRO_BIN or "
        .. "--enviro DIR): nothing to time")
  return
end
local function absolute (p)
  if p:sub(1, 1) == "/" then return p end
  return io.popen("pwd"):read("l") .. "/" .. p
end
local BIN = absolute(os.getenv("LSYS_BIN") or B.root .. "/build/bin/lsys")
local SRC = absolute(B.root .. "/tests/data/cpfg/open")
local MAP = os.tmpname() .. ".map"
do                                  -- cpfg -g wants a colour map; a grey ramp will do
  local f = assert(io.open(MAP, "wb"))
  for k = 0, 255 do f:write(string.char(k, k, k)) end
  f:close()
end

local function wall (cmd)
  local t0 = B.clock()
  local ok = os.execute(cmd)
  return B.clock() - t0, ok
end

local function best (cmd, runs)
  local t = math.huge
  for _ = 1, runs or 3 do
    local dt, ok = wall(cmd)
    if not ok then return nil end
    t = math.min(t, dt)
  end
  return t
end

local function setup (transport, n)
  local dir = os.tmpname()
  os.remove(dir)
  os.execute("mkdir " .. q(dir) .. " && cp " .. q(SRC) .. "/* " .. q(dir))
  local function edit (file, from, to)
    local f = assert(io.open(dir .. "/" .. file))
    local s = f:read("a"):gsub(from, to)
    f:close()
    f = assert(io.open(dir .. "/" .. file, "w"))
    f:write(s)
    f:close()
  end
  edit("ulam.e", "communication type: pipes", "communication type: " .. transport)
  edit("ulam.l", "derivation length: 16", "derivation length: " .. n)
  return dir
end

print(string.format("open L-system, Ulam's crystal with honda81 (%s); lsys %s, cpfg %s",
                    enviro, BIN, cpfg or "(not given)"))
for _, n in ipairs(steps and { steps } or { 16, 40 }) do
  local m = lsys.cpfg.load(SRC .. "/ulam.l", SRC .. "/ulam.v", {
    environment = lsys.environment.collision { radius = 0.01 } })
  local nq = 0
  local inner = m.environment
  m.environment = { answer = function (_, qs, info)
    nq = nq + #qs
    return inner:answer(qs, info)
  end }
  local s = m:derive(n)
  print(string.format("%d steps: %d modules, %d queries sent in all", n, #s, nq))
  for _, t in ipairs { "pipes", "files", "memory" } do
    local dir = setup(t, n)
    local path = "PATH=" .. q(enviro) .. ":$PATH "
    local lt = best("cd " .. q(dir) .. " && " .. path .. q(BIN) .. " derive ulam.l ulam.v "
                    .. "--environment ulam.e >/dev/null 2>&1")
    lt = lt or 0 / 0                     -- NaN: lsys failed
    local line = string.format("  %-6s lsys %7.3f s (%.2f ms a step)", t, lt, lt * 1000 / n)
    if cpfg then
      local ct = best("cd " .. q(dir) .. " && " .. path .. q(cpfg) .. " -g -m " .. q(MAP)
                      .. " -e ulam.e -str out.str ulam.l ulam.v </dev/null >/dev/null 2>&1")
      if ct then
        line = line .. string.format("   cpfg %7.3f s (%.2f ms a step)   cpfg / lsys %.1fx",
                                     ct, ct * 1000 / n, ct / lt)
      else
        line = line .. "   cpfg failed"
      end
    end
    print(line)
    os.execute("rm -rf " .. q(dir))
  end
end
os.remove(MAP)
