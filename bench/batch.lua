-- Batch runs benchmark: jobs a second of `lsys batch` for 1,000 small plants
-- rendered to 256x256 PNG pictures, in one process, as 2 and 4 shards under GNU parallel
-- (`parallel -j2 lsys batch SPEC --shard {}/2 ::: 1 2`), and as a Slurm job array of 1, 2
-- and 4 tasks (`--shard slurm`, docs/batch.md §7) on a one-node cluster of this host's own
-- (tests/slurm.lua; from submission until squeue shows none of the tasks), and whether each
-- gives the same bytes as one process.
--
--   build/bin/lsys bench/batch.lua [JOBS]     # both parts
--   build/bin/lsys bench/batch.lua stream     # the second part only
--
-- The plant: a stochastic bracketed plant of about 1,000 modules (8 steps) drawn as
-- 6-sided cylinders, swept over 10 values of its branching angle with JOBS / 10 seeded
-- replicates each (JOBS = 1000). Each figure is the whole command's wall-clock time (program
-- start-up, spec, derivation, interpretation, rendering, PNG writing, manifest), best of 2
-- runs in fresh folders. Prints lines for scripts:
--   batch 1 process: 1000 jobs in 9.80 s, 102.0 jobs/s
--   batch 2 shards (GNU parallel -j2): 1000 jobs in 5.30 s, 188.7 jobs/s, ratio 1.85; the
--   same bytes: yes
--   batch 4 shards (Slurm job array): 1000 jobs in 7.10 s, 140.8 jobs/s, ratio 1.38; ...
-- Without GNU parallel (Debian package parallel) or Slurm (slurmctld, slurmd, slurm-client,
-- munge; root) it says so and leaves those lines out.
--
-- Then a sweep of 10^6 jobs (once expanded in memory, when its `--list` took 2.26 GB and
-- 115 s): the CPU time, wall-clock time and peak memory (VmHWM) of a fresh `lsys batch`
-- process for `--list` of every job (printed to /dev/null), `--list` of shard 1/100, a run
-- of shard 1/20 (50,000 jobs that derive a 1-module plant and write its L-string, into a
-- fresh folder), the same again and its `--list` (every job done: the manifest read back,
-- each job's line and file checked), and `--list` of shard 1000/1000 of a sweep whose
-- template has no {id} (every job's path checked when the spec is read). Prints lines for scripts:
--   batch stream --list 1000000 jobs: 12.2 s CPU, 38.8 s wall, peak 4.9 MiB

local B = dofile(((arg and arg[0] or "bench/batch.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
B.load_lsys()
local STREAM_ONLY = arg and arg[1] == "stream"
local JOBS = math.tointeger(tonumber(arg and arg[1])) or 1000
local RUNS = 2

local host = package.loaded["lsys.host"]
local BIN = os.getenv("LSYS_BIN") or (type(host) == "table" and host.exe)
            or B.root .. "/build/bin/lsys"

local q, write = B.shell_quote, B.write_file

local function sh (cmd)
  local p = io.popen("(" .. cmd .. ") 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  return (out:gsub("exit:%d+%s*$", "")), tonumber(out:match("exit:(%d+)%s*$"))
end

local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir -p " .. q(dir)))

write(dir .. "/plant.lua", [[
local lsys = require "lsys"
return lsys.lsystem {
  axiom = "A(1)", steps = 8, env = { angle = 30 },
  productions = "A(s) --> F(s)[+(angle)A(s*0.7)][-(angle)/(90)A(s*0.7)] : 3\n"
             .. "A(s) --> F(s)/(137)A(s*0.9) : 1",
  view = { line_style = "cylinder", line_width = 0.08, contour_sides = 6,
           background = { 1, 1, 1 } },
}
]])
local angles = {}
for i = 1, 10 do angles[i] = 15 + 3 * i end
write(dir .. "/spec.lua", ([[
return { model = "plant.lua", seed = 2024, width = 256, height = 256,
         vary = { angle = { %s } }, replicates = %d, outputs = { "png/{id}.png" } }
]]):format(table.concat(angles, ", "), math.max(1, JOBS // 10)))
local njobs = 10 * math.max(1, JOBS // 10)

-- The best wall-clock time of `cmd` (run in `dir` into the fresh folder OUT) over RUNS runs.
local function best (name, cmd)
  local t = math.huge
  for r = 1, RUNS do
    local out = ("%s-%d"):format(name, r)
    local t0 = B.clock()
    local text, code = sh("cd " .. q(dir) .. " && " .. cmd:gsub("OUT", out))
    local dt = B.clock() - t0
    if code ~= 0 then
      io.stderr:write(text)
      error(("%s failed (exit %s)"):format(name, tostring(code)))
    end
    t = math.min(t, dt)
  end
  return t
end

if not STREAM_ONLY then
  print(("batch: %d jobs (%d-module plants, 256x256 PNG), %s, best of %d"):format(njobs,
    (function ()
      local m = dofile(dir .. "/plant.lua")
      return #m:derive()
    end)(), B.clock_name, RUNS))
  local one = best("one", q(BIN) .. " batch spec.lua -d OUT")
  print(("batch 1 process: %d jobs in %.2f s, %.1f jobs/s"):format(njobs, one, njobs / one))
  -- the same bytes as one process (the manifests are named by shard)
  local function same (out)
    local diff = sh("cd " .. q(dir) .. " && diff -r -q -x 'manifest*' one-1 " .. out)
    return diff == "" and "yes" or "NO\n" .. diff
  end
  if (sh("command -v parallel")) == "" then
    print("batch shards: GNU parallel is not installed (Debian: apt-get install parallel); "
      .. "one process only")
  else
    for _, n in ipairs { 2, 4 } do
      local list = {}
      for k = 1, n do list[k] = k end
      local t = best("par" .. n, ("parallel -j%d %s batch spec.lua -d OUT --shard {}/%d ::: %s")
        :format(n, q(BIN), n, table.concat(list, " ")))
      print(("batch %d shards (GNU parallel -j%d): %d jobs in %.2f s, %.1f jobs/s, ratio %.2f; "
        .. "the same bytes: %s"):format(n, n, njobs, t, njobs / t, one / t,
                                        same("par" .. n .. "-1")))
    end
  end
  -- a Slurm job array of 1, 2 and 4 tasks on a one-node cluster of this host's own
  -- (tests/slurm.lua; the figures include Slurm's scheduling)
  local here = (arg and arg[0] or "bench/batch.lua"):match("^(.*)/[^/]*$") or "."
  local S = dofile(here .. "/../tests/slurm.lua")
  local ok, why = S.start()
  if not ok then
    print("batch Slurm: " .. why)
  else
    write(dir .. "/array.sh", "#!/bin/bash\ncd \"$SLURM_SUBMIT_DIR\"\n" .. q(BIN)
      .. " batch spec.lua -d \"$DEST\" --shard slurm\n")
    for _, n in ipairs { 1, 2, 4 } do
      -- (sbatch --wait polls every few seconds: this polls squeue every 0.1 s instead)
      local t = best("slurm" .. n, "export " .. S.env .. "; id=$(DEST=OUT sbatch --parsable "
        .. "--array=0-" .. n - 1 .. " --cpus-per-task=1 --output=/dev/null array.sh) && "
        .. "while squeue -h -j \"$id\" | grep -q .; do sleep 0.1; done")
      print(("batch %d shards (Slurm job array): %d jobs in %.2f s, %.1f jobs/s, ratio %.2f; "
        .. "the same bytes: %s"):format(n, njobs, t, njobs / t, one / t,
                                        same("slurm" .. n .. "-1")))
    end
    S.stop()
  end
end

-- {===== a sweep of 10^6 jobs, streamed

write(dir .. "/one.lua", [[
return require("lsys").lsystem { axiom = "A", steps = 1, env = { a = 1, b = 1, c = 1 },
                                 productions = "A --> F" }
]])
local SWEEP = [[
local v, w = {}, {}
for i = 1, 100 do v[i], w[i] = i, i / 4 end
return { model = "one.lua", seed = 9, vary = { a = v, b = v, c = w }, outputs = { %s } }
]]
write(dir .. "/big.lua", SWEEP:format('"s/{a}/{id}.txt"'))
write(dir .. "/noid.lua", SWEEP:format('"s/{a}/{b}/{c}.txt"'))
-- `lsys batch ARGS` run by the program in a fresh process that reports its times and peak
write(dir .. "/measure.lua", [[
local clock = require("lsys.program").host().clock
local t0, c0 = clock(), os.clock()
local code = require("lsys.cli").main(table.unpack(arg))
local f = io.open("/proc/self/status", "r")
local peak = f and f:read("a"):match("VmHWM:%s*(%d+)")
if f then f:close() end
io.stderr:write(("MEASURE exit=%d cpu=%.3f wall=%.3f peak_kib=%s\n"):format(code,
  os.clock() - c0, clock() - t0, peak or "-1"))
]])
local function measure (what, args)
  local text, code = sh("cd " .. q(dir) .. " && " .. q(BIN) .. " measure.lua batch " .. args
    .. " >/dev/null")
  local cpu, wall, peak = text:match("MEASURE exit=0 cpu=(%S+) wall=(%S+) peak_kib=(%S+)")
  if code ~= 0 or not cpu then
    io.stderr:write(text)
    error(("batch stream %s failed (exit %s)"):format(what, tostring(code)))
  end
  print(("batch stream %s: %.2f s CPU, %.2f s wall, peak %s"):format(what, tonumber(cpu),
    tonumber(wall), tonumber(peak) >= 0 and ("%.1f MiB"):format(tonumber(peak) / 1024)
    or "unknown (no /proc/self/status)"))
end
print("batch stream: a sweep of 1000000 jobs (100 x 100 x 100), a fresh process each")
measure("--list 1000000 jobs", "big.lua -d out --list")
measure("--list --shard 1/100 (10000 jobs)", "big.lua -d out --list --shard 1/100")
measure("run --shard 1/20 (50000 jobs)", "big.lua -d out --shard 1/20")
measure("run --shard 1/20 again (all done: 50000 manifest lines)", "big.lua -d out --shard 1/20")
measure("--list --shard 1/20 (all done)", "big.lua -d out --list --shard 1/20")
measure("--list --shard 1000/1000, no {id} (every path checked)",
  "noid.lua -d out --list --shard 1000/1000")
print("(before specs were streamed: --list of 1000000 jobs took 2.26 GB and 115 s)")

-- }=====

local cores = sh("nproc"):match("%d+")
print(("(%s cores; each process derives and renders one job at a time)"):format(cores or "?"))
os.execute("rm -rf " .. q(dir))
