-- Deriving and writing the string: `lsys derive MODEL > file` against cpfg's
-- `cpfg -g -m x.map -str file model.l view.v` (CPFG_SKIP_VV=1), on the two models of
-- bench/derive.lua: (a) F --> F[+F]F[-F]F, 10 steps; (b) A(s) --> F(s)[+A(s/R)][-A(s/R)],
-- R = 1.456, 21 steps (bench/write_a.lua, write_b.lua and their cpfg twins write_a.l,
-- write_b.l).
--
--   build/bin/lsys bench/write.lua [--cpfg PATH]     (or CPFG=PATH: a cpfg built for batch
--                                                     use, docs/cpfg.md; without one, lsys
--                                                     alone)
--
-- Whole processes, wall clock, best of 5, minus the same process on the model with 0
-- steps (start-up); the file is written to a temporary folder (a real file, not
-- /dev/null). M modules/s = the sum of the string lengths over all steps (bench/derive.lua's
-- count) / time. Peak memory: each process's maximum resident size (GNU time's %M).
-- Target (issue 41): lsys at least 2x cpfg's speed, peak memory at most cpfg's.
-- lsys writes parameters as the shortest of %.15g/%.16g/%.17g that reads back (17 digits
-- at most), cpfg as %g (6 digits), so lsys's file of (b) is the longer one.

local script = arg and arg[0] or "bench/write.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local root, shq = B.root, B.shell_quote
local RUNS = 5

local MODELS = {
  { name = "a", title = "(a) F --> F[+F]F[-F]F, 10 steps", steps = 10 },
  { name = "b", title = "(b) A(s) --> F(s)[+A(s/R)][-A(s/R)], 21 steps", steps = 21 },
}

local whole = B.whole
local TIME = B.has_time

-- the modules of all steps and the final length, derived in this process
local function count (m)
  B.load_lsys()                    -- lsys's modules on the path for the model file
  local model = dofile(string.format("%s/bench/write_%s.lua", root, m.name))
  local s, total = model:lstring(model.axiom), 0
  for _ = 1, m.steps do s = model:step(s) total = total + #s end
  return total, #s
end

local function main ()
  local cpfg = arg[1] == "--cpfg" and arg[2] or os.getenv("CPFG")
  local have_cpfg = cpfg and cpfg ~= "" and io.open(cpfg, "r")
  if have_cpfg then have_cpfg:close() end
  local lsysbin = root .. "/build/bin/lsys"
  local dir = os.tmpname()
  os.remove(dir)
  assert(os.execute("mkdir -p " .. shq(dir)))
  for _, f in ipairs { "e.map", "e.v" } do io.close(assert(io.open(dir .. "/" .. f, "w"))) end
  print(string.format("lsys derive MODEL > file vs cpfg -g -str file (CPFG_SKIP_VV=1); whole "
    .. "process, wall clock, best of %d, start-up subtracted%s", RUNS,
    TIME and "" or "; no /usr/bin/time: no peak memory"))
  if not have_cpfg then
    print("cpfg: skipped, " .. (cpfg and cpfg ~= "" and (cpfg .. " is missing")
      or "not given (--cpfg PATH or CPFG=PATH; docs/cpfg.md says how to build it)"))
  end
  print(string.format("%-48s %9s %9s %7s %8s %8s %6s  %s", "model", "lsys M/s", "cpfg M/s",
    "ratio", "lsys MiB", "cpfg MiB", "ratio", "target >=2x, <=1x"))
  for _, m in ipairs(MODELS) do
    local total = count(m)
    local lua = string.format("%s/bench/write_%s.lua", root, m.name)
    local function lcmd (steps)
      return string.format("%s derive %s --steps %d > %s/l.txt", shq(lsysbin), shq(lua), steps,
        shq(dir))
    end
    local function ccmd (steps)
      local text = assert(B.read_file(string.format("%s/bench/write_%s.l", root, m.name)))
      local l = string.format("%s/c%d.l", dir, steps)
      B.write_file(l, (text:gsub("derivation length: %d+", "derivation length: " .. steps)))
      return string.format("env CPFG_SKIP_VV=1 %s -g -m %s/e.map -str %s/c.str %s %s/e.v",
        shq(cpfg), shq(dir), shq(dir), shq(l), shq(dir))
    end
    local lrate, lpeak, crate, cpeak
    if have_cpfg then                       -- interleaved runs (bench/common.lua, B.versus)
      local ct, lt
      ct, lt, cpeak, lpeak = B.versus(ccmd(0), ccmd(m.steps), lcmd(0), lcmd(m.steps), RUNS)
      lrate, crate = total / lt / 1e6, total / ct / 1e6
    else
      local l0 = whole(lcmd(0), RUNS)
      local l1
      l1, lpeak = whole(lcmd(m.steps), RUNS)
      lrate = total / math.max(l1 - l0, 1e-9) / 1e6
    end
    local ratio = crate and lrate / crate
    local mratio = cpeak and lpeak and lpeak / cpeak
    print(string.format("%-48s %9.1f %9s %7s %8s %8s %6s  %s", m.title, lrate,
      crate and string.format("%.1f", crate) or "-",
      ratio and string.format("%.2fx", ratio) or "-",
      lpeak and string.format("%.1f", lpeak / 1024) or "?",
      cpeak and string.format("%.1f", cpeak / 1024) or "-",
      mratio and string.format("%.2fx", mratio) or "-",
      ratio and mratio and (B.verdict(ratio >= 2) .. " " .. B.verdict(mratio <= 1)) or ""))
  end
  os.execute("rm -rf " .. shq(dir))
end

main()
