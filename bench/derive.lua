-- Derivation benchmark: modules produced per second and peak memory of lsys on two
-- fixed models, side by side with the npm package lindenmayer (peer, bench/peers/).
--
--   build/bin/lsys bench/derive.lua          run everything and print the table
--   build/bin/lsys bench/derive.lua a [N]    one model in this process (the table run launches
--                                            one such process per model)
--
-- (a) F --> F[+F]F[-F]F from F, 10 steps;  (b) A(s) --> F(s)[+A(s/R)][-A(s/R)] from A(1),
-- R = 1.456, 21 steps. Modules/s = sum of the string lengths over all steps / derivation time
-- (best of 3; the lsys program's monotonic wall clock, or os.clock CPU time under plain Lua).
-- Peak memory = VmHWM of a fresh process per model, so it includes the interpreter, like the
-- cpfg figures the targets are derived from.
-- Plain Lua works too: LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;'
-- lua5.4 bench/derive.lua
--
-- With cpfg (`--cpfg PATH`, or the environment variable CPFG: a cpfg built for batch use as
-- docs/cpfg.md, "cpfg as a reference", describes, which honours CPFG_SKIP_VV), both programs
-- are also timed the same way: whole process, wall clock, best of 5, minus the
-- same process on the model with 0 steps (start-up); cpfg runs `-g` with CPFG_SKIP_VV=1
-- (no view-volume pass) writing its string in binary (-strb: no number formatting) to
-- /dev/null, lsys derives in a fresh process. Peak memory is each process's maximum
-- resident size (GNU time's %M). Targets: D0L >= 5x cpfg, parametric >= 3x, peak memory at
-- most cpfg's.

local MODELS = {
  a = {
    title = "(a) F --> F[+F]F[-F]F", steps = 10,
    rate_target = 300e6, mem_target = 90,      -- 2 x cpfg (45 MiB)
    spec = { axiom = "F", productions = "F --> F[+F]F[-F]F" },
    cpfg = "Axiom: F\nF --> F[+F]F[-F]F\n", cpfg_ratio = 5,
  },
  b = {
    title = "(b) A(s) --> F(s)[+A(s/R)][-A(s/R)]", steps = 21,
    rate_target = 100e6, mem_target = 154,     -- 2 x cpfg (77 MiB)
    spec = { axiom = "A(1)", env = { R = 1.456 },
             productions = "A(s) --> F(s)[+A(s/R)][-A(s/R)]" },
    cpfg = "#define R 1.456\nAxiom: A(1)\nA(s) --> F(s)[+A(s/R)][-A(s/R)]\n", cpfg_ratio = 3,
  },
}
-- vlab's parametric models, run from their own files (`--vlab DIR`, or VLAB=DIR: vlab's
-- oofs/ext folder): the object folder is copied to a temporary one, its `#define STEPS` set
-- to `steps` so that the string reaches millions of modules, and both programs derive it
-- from there (cpfg as its specifications file runs it).
local VLAB = {
  { title = "(v1) vlab 07-fractal-ferns", steps = 36,
    dir = "11-CPFG/ext/01-Introduction/ext/07-fractal-ferns",
    l = "leaf.l", v = "leaf.v", palette = "-m leaf.map" },
  { title = "(v2) vlab 10-sympodial", steps = 340,
    dir = "11-CPFG/ext/02-Mod-vis-3D/ext/10-sympodial",
    l = "plant.l", v = "plant.v", palette = "-M material.mat" },
}
local RUNS = 3
local PEER_TIMEOUT = 600          -- seconds per peer process

local script = arg and arg[0] or "bench/derive.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local root, load_lsys = B.root, B.load_lsys

local shell_quote, read_file, capture, node_path =
  B.shell_quote, B.read_file, B.capture, B.node_path

local clock = B.clock
local clock_name = B.clock_name

local function peak_kib ()
  local status = read_file("/proc/self/status") or ""
  return tonumber(status:match("VmHWM:%s*(%d+)"))
end

-- The command that started this script (interpreter and its options), to launch it again.
local function self_command ()
  local lo = 0
  while arg and arg[lo - 1] do lo = lo - 1 end
  local parts = {}
  for i = lo, -1 do parts[#parts + 1] = shell_quote(arg[i]) end
  if #parts == 0 then
    local pid = (read_file("/proc/self/stat") or ""):match("^%d+") or "self"
    local p = io.popen("readlink /proc/" .. pid .. "/exe")
    parts[1] = shell_quote(p and p:read("l") or "lua5.4")
    if p then p:close() end
  end
  parts[#parts + 1] = shell_quote(script)
  return table.concat(parts, " ")
end

------------------------------------------------------------------------------------------
-- child: one model in this process; prints one machine-readable line

local function run_child (name, steps)
  local lsys = load_lsys()
  local m = MODELS[name]
  local spec = {}
  for k, v in pairs(m.spec) do spec[k] = v end
  spec.steps = steps
  local model = lsys.lsystem(spec)

  local best, length = math.huge, 0
  for _ = 1, RUNS do
    collectgarbage()
    local t0 = clock()
    local s = model:derive()
    local t1 = clock()
    best = math.min(best, t1 - t0)
    length = #s
    s = nil                                     -- luacheck: ignore
  end
  collectgarbage()
  local hwm = peak_kib()

  -- produced modules: the lengths of the strings of steps 1..n (untimed, after the peak reading)
  local modules = 0
  local s = model:lstring(spec.axiom)
  for _ = 1, steps do
    s = model:step(s)
    modules = modules + #s
    collectgarbage()
  end
  assert(#s == length, "step-by-step derivation disagrees with derive()")

  io.write(string.format("RESULT model=%s steps=%d modules=%d length=%d seconds=%.9f peak_kib=%d\n",
    name, steps, modules, length, best, hwm or -1))
end

-- child "vlab": the vlab object folder `dir` derived once ("whole"), or its modules over all
-- steps ("count", printed)
local function run_vlab (how, dir)
  local lsys = load_lsys()
  local m = lsys.cpfg.load_object(dir)
  if how == "count" then
    local modules = 0
    m:derive(nil, { each = function (k, s) if k > 0 then modules = modules + #s end end })
    io.write("MODULES ", modules, "\n")
  else
    io.write(#m:derive(), "\n")
  end
end

-- child "whole": derive once and exit, for the whole-process timing beside cpfg
local function run_whole (name, steps)
  local lsys = load_lsys()
  local spec = {}
  for k, v in pairs(MODELS[name].spec) do spec[k] = v end
  spec.steps = steps
  local s = lsys.lsystem(spec):derive()
  io.write(#s, "\n")
end

------------------------------------------------------------------------------------------
-- parent: launch the children and the peer, print the table

local function parse_result (out)
  local r = {}
  local line = out:match("RESULT ([^\n]*)")
  if not line then return nil end
  for k, v in line:gmatch("([%w_]+)=(%S+)") do r[k] = tonumber(v) or v end
  return r
end

local function measure_lsys (name, steps)
  local out = capture(self_command() .. " " .. name .. " " .. steps)
  local r = parse_result(out)
  if not r then error("lsys run of model " .. name .. " failed:\n" .. out, 0) end
  return r
end

-- lindenmayer at `steps`; on failure (out of memory, time out) retries with fewer steps.
local function measure_peer (node, name, steps)
  local js = root .. "/bench/peers/derive_lindenmayer.js"
  local notes = {}
  for n = steps, math.max(1, steps - 6), -1 do
    local cmd = string.format("timeout %d %s %s %s %d", PEER_TIMEOUT, shell_quote(node),
      shell_quote(js), name, n)
    local out, ok = capture(cmd)
    local json = out:match("(%b{})")
    if ok and json then
      local r = {}
      for k, v in json:gmatch('"([%w_]+)":"?([^,"}]*)"?') do r[k] = tonumber(v) or v end
      r.notes = notes
      return r
    end
    local why = out:match("heap out of memory") and "ran out of memory"
      or (out == "" and "timed out or was killed") or "failed"
    notes[#notes + 1] = string.format("lindenmayer %s at %d steps (%s)", why, n,
      (out:match("[^\n]*Error[^\n]*") or out:match("[^\n]+") or "no output"):sub(1, 80))
  end
  return nil, notes
end

local function mib (kib) return kib / 1024 end

-- Whole-process timing (bench/common.lua), the string to /dev/null.
local TIME = B.has_time

-- lsys and cpfg on one model, timed as `whole` does, start-up subtracted.
local function versus_cpfg (cpfg, dir, name, modules)
  local m = MODELS[name]
  local function lfile (steps)
    local path = string.format("%s/%s%d.l", dir, name, steps)
    local f = assert(io.open(path, "w"))
    f:write(string.format("lsystem: 1\nderivation length: %d\n%sendlsystem\n", steps,
      m.cpfg:gsub("(#define[^\n]*\n)", "") ))
    f:close()
    local defs = m.cpfg:match("(#define[^\n]*\n)")
    if defs then                                   -- cpp lines go first
      local text = read_file(path)
      f = assert(io.open(path, "w")) f:write(defs, text) f:close()
    end
    return path
  end
  local function cpfg_cmd (steps)
    return string.format("env CPFG_SKIP_VV=1 %s -g -m %s/e.map -strb /dev/null %s %s/e.v",
      shell_quote(cpfg), dir, shell_quote(lfile(steps)), dir)
  end
  local lsys_cmd = function (steps) return self_command() .. " whole " .. name .. " " .. steps end
  local R = 5
  local q = " >/dev/null"
  local ct, lt, cpeak, lpeak, c0, l0 = B.versus(cpfg_cmd(0) .. q, cpfg_cmd(m.steps) .. q,
                                                lsys_cmd(0) .. q, lsys_cmd(m.steps) .. q, R)
  return { cpfg = modules / ct, lsys = modules / lt,
           cpeak = cpeak, lpeak = lpeak, cstart = c0, lstart = l0 }
end

-- A copy of vlab model `v` in `dir` (a fresh folder) with its STEPS set to `steps`.
local function vlab_copy (vlab, v, dir, steps)
  assert(os.execute("rm -rf " .. shell_quote(dir) .. " && cp -r " ..
    shell_quote(vlab .. "/" .. v.dir) .. " " .. shell_quote(dir)))
  local path = dir .. "/" .. v.l
  local text = assert(read_file(path), "cannot read " .. path)
  local n
  text, n = ("\n" .. text):gsub("\n#define STEPS [^\n]*", "\n#define STEPS " .. steps, 1)
  text = text:sub(2)
  assert(n == 1, path .. " has no #define STEPS")
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
end

-- lsys and cpfg on vlab model `v`, whole processes as `whole` times them, start-up (the
-- model at 0 steps) subtracted.
local function versus_vlab (cpfg, vlab, tmp, v)
  local R = 5
  local function at (steps)
    local dir = string.format("%s/m%d", tmp, steps)
    vlab_copy(vlab, v, dir, steps)
    return dir
  end
  local d0, d1 = at(0), at(v.steps)
  local counted = capture(self_command() .. " vlab count " .. shell_quote(d1))
  local modules = tonumber(counted:match("MODULES (%d+)"))
  if not modules then error("lsys failed on " .. v.dir .. ":\n" .. counted, 0) end
  local function cpfg_cmd (dir)
    return "sh -c " .. shell_quote(string.format(                 -- in the model's folder
      "cd %s && CPFG_SKIP_VV=1 exec %s -g %s -strb /dev/null %s %s",
      shell_quote(dir), shell_quote(cpfg), v.palette, v.l, v.v))
  end
  local function lsys_cmd (dir)
    return self_command() .. " vlab whole " .. shell_quote(dir)
  end
  local q = " >/dev/null"
  local ct, lt, cpeak, lpeak, c0, l0 = B.versus(cpfg_cmd(d0) .. q, cpfg_cmd(d1) .. q,
                                                lsys_cmd(d0) .. q, lsys_cmd(d1) .. q, R)
  return { cpfg = modules / ct, lsys = modules / lt,
           cpeak = cpeak, lpeak = lpeak, cstart = c0, lstart = l0, modules = modules }
end

-- One row of the table against cpfg.
local function cpfg_row (title, r, target)
  local ratio = r.lsys / r.cpfg
  local mratio = r.lpeak and r.cpeak and r.lpeak / r.cpeak
  print(string.format("%-38s %10.1f %10.1f %6.2fx %-12s %9s %9s %7s %-10s", title,
    r.lsys / 1e6, r.cpfg / 1e6, ratio,
    string.format(">=%dx %s", target, ratio >= target and "PASS" or "MISS"),
    r.lpeak and string.format("%.1f", mib(r.lpeak)) or "?",
    r.cpeak and string.format("%.1f", mib(r.cpeak)) or "?",
    mratio and string.format("%.2fx", mratio) or "?",
    mratio and ("<=1x " .. (mratio <= 1 and "PASS" or "MISS")) or ""))
  print(string.format("  (start-up: lsys %.1f ms, cpfg %.1f ms%s)", r.lstart * 1e3,
    r.cstart * 1e3, r.modules and string.format("; %d modules", r.modules) or ""))
end

local function cpfg_table (cpfg, results, vlab)
  local dir = B.cpfg_folder()
  print()
  print("cpfg: " .. cpfg .. " (-g -strb, CPFG_SKIP_VV=1); whole process, wall clock, best of 5, "
        .. "start-up subtracted" .. (TIME and "" or "; no /usr/bin/time: no peak memory"))
  print(string.format("%-38s %10s %10s %7s %-12s %9s %9s %7s %-10s", "model", "lsys M/s",
    "cpfg M/s", "ratio", "target", "lsys MiB", "cpfg MiB", "ratio", "target"))
  for _, name in ipairs { "a", "b" } do
    local m = MODELS[name]
    local ok, r = pcall(versus_cpfg, cpfg, dir, name, results[name].modules)
    if not ok then
      print(string.format("%-38s cpfg run failed: %s", m.title, tostring(r)))
    else
      cpfg_row(m.title, r, m.cpfg_ratio)
    end
  end
  if vlab then
    for _, v in ipairs(VLAB) do
      local ok, r = pcall(versus_vlab, cpfg, vlab, dir, v)
      if not ok then print(string.format("%-38s failed: %s", v.title, tostring(r)))
      else cpfg_row(string.format("%s, %d steps", v.title, v.steps), r, 3) end
    end
  else
    print("vlab models: not given (--vlab DIR or VLAB=DIR, vlab's oofs/ext folder)")
  end
  B.rmdir(dir)
end
local function mrate (r) return r.modules / r.seconds / 1e6 end

local function main (cpfg, vlab)
  local lsys = load_lsys()
  print(string.format("lsys %s derivation benchmark (%s; best of %d, %s)",
    lsys.version or "?", _VERSION, RUNS, clock_name))
  print()
  print(string.format("%-38s %5s %11s %9s %9s %-14s %8s %-12s",
    "model", "steps", "modules", "time s", "Mmod/s", "target", "peak MiB", "target"))
  local results = {}
  for _, name in ipairs { "a", "b" } do
    local m = MODELS[name]
    local r = measure_lsys(name, m.steps)
    results[name] = r
    local rate, mem = mrate(r), mib(r.peak_kib)
    print(string.format("%-38s %5d %11d %9.4f %9.1f %-14s %8.1f %-12s",
      m.title, r.steps, r.modules, r.seconds, rate,
      string.format(">=%d %s", m.rate_target / 1e6,
        rate * 1e6 >= m.rate_target and "PASS" or "MISS"),
      mem, string.format("<=%d %s", m.mem_target, mem <= m.mem_target and "PASS" or "MISS")))
  end

  if cpfg then
    cpfg_table(cpfg, results, vlab)
  else
    print()
    print("cpfg: not given (--cpfg PATH or CPFG=PATH; docs/cpfg.md says how to build it): "
          .. "lsys alone")
  end

  print()
  local node = node_path()
  local installed = read_file(root .. "/bench/peers/node_modules/lindenmayer/package.json")
  if not node then
    print("peer: skipped, node is not installed")
    return
  elseif not installed then
    print("peer: skipped, lindenmayer is not installed: npm ci --prefix " .. root .. "/bench/peers")
    return
  end
  local v = capture(shell_quote(node) .. " --version"):match("%S+") or "?"
  print(string.format("peer: lindenmayer %s (node %s); ratio = lsys / lindenmayer",
    installed:match('"version"%s*:%s*"([^"]+)"') or "?", v))
  print(string.format("%-38s %5s %11s %9s %9s %8s %12s %12s",
    "model", "steps", "modules", "time s", "Mmod/s", "peak MiB", "speed ratio", "memory ratio"))
  for _, name in ipairs { "a", "b" } do
    local m = MODELS[name]
    local p, notes = measure_peer(node, name, m.steps)
    notes = p and p.notes or notes
    for _, n in ipairs(notes) do print("  note: " .. n) end
    if not p then
      print(string.format("%-38s  lindenmayer failed down to %d steps; no comparison",
        m.title, math.max(1, m.steps - 6)))
    else
      local l = results[name]
      if p.steps ~= m.steps then
        print(string.format("  note: comparing both at %d steps (lsys measured again at that size)",
          p.steps))
        l = measure_lsys(name, p.steps)
      end
      print(string.format("%-38s %5d %11d %9.4f %9.1f %8.1f %12s %12s",
        "  lindenmayer " .. m.title:match("^%(%a%)"), p.steps, p.modules, p.seconds, mrate(p),
        mib(p.peak_kib), string.format("%.1fx", mrate(l) / mrate(p)),
        string.format("%.2fx", l.peak_kib / p.peak_kib)))
      if p.steps ~= m.steps then
        print(string.format("%-38s %5d %11d %9.4f %9.1f %8.1f",
          "  lsys " .. m.title:match("^%(%a%)"),
          l.steps, l.modules, l.seconds, mrate(l), mib(l.peak_kib)))
      end
    end
  end
end

local mode = arg and arg[1]
if MODELS[mode] then
  run_child(mode, tonumber(arg[2]) or MODELS[mode].steps)
elseif mode == "whole" and MODELS[arg[2]] then
  run_whole(arg[2], tonumber(arg[3]) or MODELS[arg[2]].steps)
elseif mode == "vlab" and (arg[2] == "whole" or arg[2] == "count") and arg[3] then
  run_vlab(arg[2], arg[3])
else
  local opts, k = { cpfg = os.getenv("CPFG"), vlab = os.getenv("VLAB") }, 1
  while arg and arg[k] do
    local o = arg[k]:match("^%-%-(%a+)$")
    if (o ~= "cpfg" and o ~= "vlab") or not arg[k + 1] then
      io.stderr:write("usage: derive.lua [--cpfg PATH] [--vlab DIR] | [a|b [STEPS]]\n")
      os.exit(2)
    end
    opts[o] = arg[k + 1]
    k = k + 2
  end
  main(opts.cpfg ~= "" and opts.cpfg or nil, opts.vlab ~= "" and opts.vlab or nil)
end
