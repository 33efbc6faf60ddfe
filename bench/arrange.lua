-- Arrangement solver benchmark: the time of one inverse-kinematics solve
-- (lsys_ik_solve: conjugate gradients on objective (1)) for branch paths of 10, 100 and 1000
-- joints, next to the L-BFGS of liblbfgs on the same objective as the reference.
--
--   build/bin/lsys bench/arrange.lua [SECONDS]
--
-- Builds and runs the C program bench/ik_bench.c (CMake target bench_ik, not part of the
-- default build) in the build directory: $LSYS_BUILD_DIR, else the one the running lsys
-- program belongs to, else ./build next to the bench folder. SECONDS (default 0.2) is the least
-- total time spent on each figure. The scenario is one mouse-move step of a drag: the tip
-- target moved sideways by 2% of the path length and the twist turned by 2 degrees, from the
-- unbent start, with lsys.arrange's default weights; and a drag of 60 such steps on 100
-- joints, each solve starting from the previous result (see bench/ik_bench.c).
-- Times are wall clock, best and median over the repetitions. The L-BFGS reference needs
-- liblbfgs-dev (apt-get install liblbfgs-dev) when the build directory is configured;
-- without it the CG figures are printed alone.
-- Plain Lua works too (LSYS_BUILD_DIR=build lua5.4 bench/arrange.lua): it needs no lsys module.

local script = arg and arg[0] or "bench/arrange.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local verdict = B.verdict
local TARGET_MS, TARGET_N = 1, 100           -- the target: < 1 ms for 100 joints

local shell_quote, capture = B.shell_quote, B.capture

local function exists (path)
  local f = io.open(path, "r")
  if f then f:close() end
  return f ~= nil
end

-- the build directory: LSYS_BUILD_DIR, the running program's (<build>/bin/lsys), ./build
local function build_dir ()
  local env = os.getenv("LSYS_BUILD_DIR")
  if env and env ~= "" then return env end
  local host = package.loaded["lsys.host"]
  local exedir = type(host) == "table" and host.exedir
  if type(exedir) == "string" then
    local dir = exedir:match("^(.*)/bin/?$")
    if dir and exists(dir .. "/CMakeCache.txt") then return dir end
  end
  return B.root .. "/build"
end

local function fail (msg)
  io.stderr:write("arrange.lua: ", msg, "\n")
  os.exit(1)
end

-- "cg n=100 best_ms=0.42 ..." -> { kind = "cg", n = 100, best_ms = 0.42, ... }
local function parse (out)
  local res = { unavailable = false }
  for line in out:gmatch("[^\n]+") do
    if line == "lbfgs unavailable" then
      res.unavailable = true
    elseif not line:match("^#") then
      local kind, rest = line:match("^([%w_]+)%s+(.*)$")
      if kind and rest:match("=") then
        local r = { kind = kind }
        for k, v in rest:gmatch("([%w_]+)=(%S+)") do r[k] = tonumber(v) or v end
        res[#res + 1] = r
        if r.n then
          res[kind] = res[kind] or {}
          res[kind][r.n] = r
        else
          res[kind] = r
        end
      end
    end
  end
  return res
end

local function main ()
  local seconds = arg and arg[1]
  if seconds and not tonumber(seconds) then
    io.stderr:write("usage: arrange.lua [SECONDS]  (least total time per figure, default 0.2)\n")
    os.exit(2)
  end
  local dir = build_dir()
  if not exists(dir .. "/CMakeCache.txt") then
    fail(string.format("%s is not a configured build directory: cmake -S %s -B %s " ..
      "(or set LSYS_BUILD_DIR)", dir, B.root, dir))
  end
  local out, ok = capture("cmake --build " .. shell_quote(dir) .. " --target bench_ik")
  if not ok then fail("building bench_ik failed:\n" .. out) end
  local exe = dir .. "/bench/bench_ik"
  if not exists(exe) then fail(exe .. " was not built:\n" .. out) end

  out, ok = capture(shell_quote(exe) .. (seconds and " " .. shell_quote(seconds) or ""))
  if not ok then fail(exe .. " failed:\n" .. out) end
  local r = parse(out)
  if not r.cg then fail("no results from " .. exe .. ":\n" .. out) end

  local ns = {}
  for n in pairs(r.cg) do ns[#ns + 1] = n end
  table.sort(ns)

  print(string.format("lsys arrangement solver benchmark (%s; wall clock, best and median " ..
    "of at least %s s of solves per figure)", exe, seconds or "0.2"))
  print("one drag step from a nearby start: tip moved 2% of the path length, twist 2 deg;" ..
    " wp = 1000/|v|^2, wt = we = 1, ws = 0.1")
  print()
  local head = "%-12s %6s %9s %9s %6s %6s %10s %10s %-12s %s"
  local row = "%-12s %6d %9.3f %9.3f %6d %6d %10.2e %10.3e %-12s %s"
  print(string.format(head, "solver", "joints", "best ms", "median ms", "iters", "evals",
    "|p-p^|", "f", "stopped", "target"))
  for _, n in ipairs(ns) do
    local c = r.cg[n]
    local target = n == TARGET_N
      and string.format("< %g ms for %d joints  %s", TARGET_MS, TARGET_N,
                        verdict(c.best_ms < TARGET_MS))
      or ""
    print(string.format(row, "CG", n, c.best_ms, c.median_ms, c.iters, c.evals, c.dist, c.f,
      c.status, target))
  end
  if r.cg_full then
    for _, n in ipairs(ns) do
      local c = r.cg_full[n]
      if c then
        print(string.format(row, "CG, no cap", n, c.best_ms, c.median_ms, c.iters, c.evals,
          c.dist, c.f, c.status, string.format("(max_iter = %d)", c.max_iter)))
      end
    end
  end

  print()
  if r.unavailable or not r.lbfgs then
    print("L-BFGS reference: unavailable, bench_ik was built without liblbfgs.")
    print("  Install it (apt-get install liblbfgs-dev), re-run cmake -S " .. B.root ..
      " -B " .. dir .. " and this script.")
  else
    local l0 = r.lbfgs[ns[1]]
    print(string.format("L-BFGS reference (liblbfgs, lbfgs_parameter_init defaults: m = %d, " ..
      "epsilon = %g, More-Thuente) on lsys_ik_objective, same run;", l0.m, l0.epsilon))
    print("ratio = CG time / L-BFGS time (best times); \"to CG's f\": L-BFGS stopped once its f" ..
      " is down to the CG's final f")
    print(string.format(head, "solver", "joints", "best ms", "median ms", "iters", "evals",
      "|p-p^|", "f", "stopped", "ratio"))
    for _, n in ipairs(ns) do
      for _, v in ipairs { { "lbfgs", "L-BFGS" }, { "lbfgs_to_cg", "to CG's f" } } do
        local l = r[v[1]] and r[v[1]][n]
        if l then
          print(string.format(row, v[2], n, l.best_ms, l.median_ms, l.iters, l.evals, l.dist,
            l.f, l.status, string.format("%.2f", r.cg[n].best_ms / l.best_ms)))
        end
      end
    end
  end

  if r.eval then
    print()
    local parts = {}
    for _, n in ipairs(ns) do
      if r.eval[n] then parts[#parts + 1] = string.format("n=%d %.2f us", n, r.eval[n].us) end
    end
    print("one evaluation of (1) with its gradient (lsys_ik_objective): " ..
      table.concat(parts, ", "))
  end

  print()
  for _, v in ipairs { { "drag", "CG" }, { "lbfgs_drag", "L-BFGS" } } do
    local d = r[v[1]] and r[v[1]][TARGET_N]
    if d then
      print(string.format("drag, %d joints, %d frames, %-6s: %.3f ms per solve on average, " ..
        "%.3f ms at most (best of %d drags per frame), %.1f iterations on average, " ..
        "|p-p^| <= %.2e", d.n, d.frames, v[2], d.mean_ms, d.max_ms, d.reps, d.mean_iters,
        d.max_dist))
    end
  end
  if r.mem and r.mem.peak_kib then
    print(string.format("peak memory of bench_ik (VmHWM): %.1f MiB", r.mem.peak_kib / 1024))
  end
end

main()
