-- Compares a stochastic cpfg model in cpfg and in lsys.cpfg by the statistics of the
-- derived strings: cpfg's drand48 cannot be matched string for string, so each program
-- runs N times with different seeds and the counts of every module name, the string
-- length and the mean of each parameter of a module name are compared with Welch's t.
-- Usage: lua5.4 tools/cpfg-stats.lua CPFG [-n N] [--seed S] [--homo] MODEL ...
--   CPFG: the cpfg program; MODEL: a vlab object folder (its specifications' first cpfg
--   command names the files) or an L-system file, optionally followed by its view file;
--   -n N: runs per program (default 30); --seed S: seeds the choice of the seeds (1);
--   --homo: the strings after the homomorphism (cpfg -homo, lsys m:expand; not for
--     models with query modules, where cpfg stops writing at the first one).
-- Seeds: cpfg reads them from the model, so every run has its copy of the model's folder
-- (in a temporary folder, removed afterwards) with its .l changed: the value of `seed:`
-- (drand48, stochastic productions), the argument of every srand() call, or, when the
-- model calls ran(), nran(), bran() or biran() without srand, a `Start: {srand(k);}`
-- (cpfg's random functions have their own generator, seeded only by srand). lsys loads
-- the same copy, with model.seed = k as well. Seeds are drawn from 1..65535: cpfg seeds
-- drand48 with seed48({seed, 0, 155}), so consecutive seeds give nearly the same first
-- draws.
-- Prints, per model, a table (mean and standard deviation in each program, t) and a
-- verdict: "consistent" when no |t| exceeds 4, else the quantities that differ.
-- Run from the checkout after a build (it sets package.path to ./lua and ./build).
package.path = "./lua/?.lua;./lua/?/init.lua;" .. package.path
package.cpath = "./build/?.so;" .. package.cpath
local lsys = require "lsys"

local LIMIT = 4          -- |t| above this is flagged

local T = dofile(((arg and arg[0] or "tools/x.lua"):match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local q, read, write = T.q, T.read, T.write

-- The files of a model: an object folder's first cpfg command, or FILE.l [FILE.v].
local function files (arg1, arg2)
  if arg1:match("%.l$") then
    local dir, l = arg1:match("^(.*)/([^/]*)$")
    if not dir then dir, l = ".", arg1 end
    local v = arg2 and arg2:match("%.v$") and arg2:match("([^/]*)$")
    return { dir = dir, l = l, v = v }, v and 2 or 1
  end
  local spec = read(arg1 .. "/specifications") or ""
  for line in spec:gmatch("[^\n]+") do
    local cmd = line:match("^%s*cpfg%s(.*)$")
    if cmd then
      local c, words, i = { dir = arg1 }, {}, 1
      for w in cmd:gmatch("%S+") do words[#words + 1] = w end
      while i <= #words do
        local w = words[i]
        if w:match("^%-[mM]1?$") then c.pal = c.pal or words[i + 1]; i = i + 1
        elseif w:match("^%-[mM]%d+$") or w == "-e" or w == "-c" or w == "-wt" then i = i + 1
        elseif w == "-w" or w == "-wp" then i = i + 2
        elseif w:match("%.l$") then c.l = c.l or w
        elseif w:match("%.v$") then c.v = c.v or w end
        i = i + 1
      end
      if c.l then return c, 1 end
    end
  end
  error(arg1 .. ": no cpfg command with a .l file in its specifications", 0)
end

-- The text without its comments (cpp removes them anyway), line numbers kept: a srand in
-- a comment must not count.
local function uncomment (text)
  return (text:gsub("/%*.-%*/", function (c) return (c:gsub("[^\n]", "")) end)
              :gsub("//[^\n]*", ""))
end

-- The L-system text with its randomness seeded by k.
local function reseed (text, k)
  text = uncomment(text)
  local s, n = text:gsub("\n([ \t]*[Ss]eed[ \t]*:)[^\n]*", "\n%1 " .. k)
  local m
  s, m = s:gsub("%f[%w_]srand%s*%b()", "srand(" .. k .. ")")
  if m == 0 and s:find("%f[%w_][nb]?i?ran%s*%(") then
    local a
    s, a = s:gsub("\n([ \t]*[Ss]tart[ \t]*:[ \t]*{)", "\n%1srand(" .. k .. ");", 1)
    if a == 0 then
      s, a = s:gsub("\n([ \t]*[Ll]system[ \t]*:[^\n]*)", "\n%1\nStart: {srand(" .. k .. ");}", 1)
    end
    m = a
  end
  return s, n + m
end

-- Statistics of one string: counts per module name, parameter sums, the length.
local function stats (s)
  local count, sums, len = {}, {}, 0
  local f, st, c = s:modules()
  while true do
    local r = table.pack(f(st, c))
    if r[1] == nil then break end
    c = r[1]
    local name = r[2]
    len = len + 1
    count[name] = (count[name] or 0) + 1
    for i = 3, math.min(r.n, 5) do
      local key = name .. "." .. (i - 2)
      sums[key] = (sums[key] or 0) + r[i]
    end
  end
  local t = { ["(length)"] = len }
  for name, n in pairs(count) do t["#" .. name] = n end
  for key, x in pairs(sums) do t["mean " .. key] = x / count[key:match("^(.*)%.%d+$")] end
  return t
end

local function moments (xs, n)
  local sum = 0
  for i = 1, n do sum = sum + (xs[i] or 0) end
  local mean = sum / n
  local ss = 0
  for i = 1, n do ss = ss + ((xs[i] or 0) - mean) ^ 2 end
  return mean, n > 1 and math.sqrt(ss / (n - 1)) or 0
end

-- Welch's t of two samples given by mean, standard deviation and size; 0 when the means
-- agree to float32's precision (cpfg keeps parameters as floats).
local function welch (m1, s1, n1, m2, s2, n2)
  if math.abs(m1 - m2) <= 1e-5 * math.max(math.abs(m1), math.abs(m2)) + 1e-9 then return 0 end
  local se = math.sqrt(s1 ^ 2 / n1 + s2 ^ 2 / n2)
  if se == 0 then return math.huge * (m1 < m2 and -1 or 1) end
  return (m1 - m2) / se
end

local function run (cpfg, c, n, seed0, homo)
  local tmp = io.popen("mktemp -d"):read("l")
  assert(os.execute("cp -r " .. q(c.dir) .. "/. " .. q(tmp)))
  local text = assert(read(c.dir .. "/" .. c.l), c.l .. ": cannot be read")
  math.randomseed(seed0)
  local seeds, used = {}, {}
  while #seeds < n do
    local k = math.random(1, 65535)
    if not used[k] then used[k] = true; seeds[#seeds + 1] = k end
  end
  local A, B = {}, {}               -- per run: cpfg's and lsys's statistics
  local empty, out = tmp .. "/.stats.map", tmp .. "/.stats.str"
  write(empty, "")
  local changed = 0
  local t0 = os.time()
  for i, k in ipairs(seeds) do
    local s, nchanged = reseed(text, k)
    changed = nchanged
    write(tmp .. "/" .. c.l, s)
    os.remove(out)
    os.execute("cd " .. q(tmp) .. " && timeout 300 " .. q(cpfg) .. (homo and " -homo" or "")
               .. " -g -m " .. q(empty) .. " -str " .. q(out) .. " " .. q(c.l) ..
               (c.v and " " .. q(c.v) or "") .. " </dev/null >/dev/null 2>&1")
    local ref = (read(out) or ""):gsub("\n", "")
    local opts = {}
    if c.pal then
      if c.pal:match("%.mat$") then opts.materials = c.pal else opts.colormap = c.pal end
    end
    local ok, m = pcall(lsys.cpfg.load, tmp .. "/" .. c.l, c.v and tmp .. "/" .. c.v or nil,
                        opts)
    if not ok and c.v then
      -- a view lsys refuses (a contour or texture format it does not read): a copy
      -- without the lines that name files, for lsys only
      local keep = {}
      for line in ((read(tmp .. "/" .. c.v) or "") .. "\n"):gmatch("([^\n]*)\n") do
        if not line:find("^%s*t?surface%s*:") and not line:find("^%s*contour%s*:") and
           not line:find("^%s*texture%s*:") then
          keep[#keep + 1] = line
        end
      end
      write(tmp .. "/.stats-lsys.v", table.concat(keep, "\n"))
      if i == 1 then print("(lsys refuses the view: " .. tostring(m) .. "; using it without "
                           .. "its contour, surface and texture lines)") end
      m = lsys.cpfg.load(tmp .. "/" .. c.l, tmp .. "/.stats-lsys.v", opts)
    elseif not ok then
      error(m, 0)
    end
    m.seed = k
    local saved = io.output()
    io.output("/dev/null")                  -- the model's printf
    local ok2, ls = pcall(m.derive, m)
    if ok2 and homo then ok2, ls = pcall(m.expand, m, ls) end
    io.output():close()
    io.output(saved)
    if not ok2 then error(ls, 0) end
    if ref == "" then error("cpfg wrote no string (seed " .. k .. ")", 0) end
    A[i] = stats(lsys.lstring(ref, m.modules))
    B[i] = stats(ls)
  end
  os.execute("rm -rf " .. q(tmp))
  return A, B, changed, os.time() - t0
end

local function report (name, A, B, n, changed)
  local keys, seen = {}, {}
  for _, list in ipairs({ A, B }) do
    for _, t in ipairs(list) do
      for k in pairs(t) do if not seen[k] then seen[k] = true; keys[#keys + 1] = k end end
    end
  end
  table.sort(keys, function (a, b)
    local ca, cb = a:sub(1, 1) == "(" and 0 or a:sub(1, 1) == "#" and 1 or 2,
                   b:sub(1, 1) == "(" and 0 or b:sub(1, 1) == "#" and 1 or 2
    if ca ~= cb then return ca < cb end
    return a < b
  end)
  print(string.format("== %s: %d runs each%s", name, n,
                      changed == 0 and " (nothing to reseed: deterministic in cpfg?)" or ""))
  print(string.format("%-16s %12s %10s %12s %10s %8s", "quantity", "cpfg mean", "std",
                      "lsys mean", "std", "t"))
  local flagged, shown = {}, 0
  for _, k in ipairs(keys) do
    local xa, xb = {}, {}
    for i = 1, n do
      xa[i] = A[i][k] or (k:sub(1, 1) ~= "m" and 0 or nil)
      xb[i] = B[i][k] or (k:sub(1, 1) ~= "m" and 0 or nil)
    end
    -- parameter means exist only in runs where the module does
    local function compact (xs)
      local t = {}
      for i = 1, n do if xs[i] then t[#t + 1] = xs[i] end end
      return t
    end
    local ca, cb = compact(xa), compact(xb)
    local ma, sa = moments(ca, #ca)
    local mb, sb = moments(cb, #cb)
    local t = (#ca > 0 and #cb > 0) and welch(ma, sa, #ca, mb, sb, #cb) or math.huge
    local vary = sa > 0 or sb > 0 or math.abs(t) > LIMIT
    if k:sub(1, 1) ~= "m" or vary then
      shown = shown + 1
      print(string.format("%-16s %12.5g %10.4g %12.5g %10.4g %8.2f%s", k:sub(1, 16), ma, sa,
                          mb, sb, t, math.abs(t) > LIMIT and "  <--" or ""))
    end
    if math.abs(t) > LIMIT then flagged[#flagged + 1] = k end
  end
  if #flagged == 0 then
    print("verdict: consistent (no |t| > " .. LIMIT .. ")")
  else
    print("verdict: DIFFERENT: " .. table.concat(flagged, ", "))
  end
  return #flagged == 0
end

local cpfg = arg[1]
if not cpfg then
  io.stderr:write("usage: lua5.4 tools/cpfg-stats.lua CPFG [-n N] [--seed S] [--homo] "
                  .. "MODEL [FILE.v] ...\n")
  os.exit(2)
end
local n, seed0, homo, models = 30, 1, false, {}
local i = 2
while i <= #arg do
  if arg[i] == "-n" then n = assert(tonumber(arg[i + 1]), "-n N"); i = i + 2
  elseif arg[i] == "--seed" then seed0 = assert(tonumber(arg[i + 1]), "--seed S"); i = i + 2
  elseif arg[i] == "--homo" then homo = true; i = i + 1
  else
    local c, used = files(arg[i], arg[i + 1])
    c.name = arg[i]
    models[#models + 1] = c
    i = i + used
  end
end
local bad = 0
for _, c in ipairs(models) do
  local ok, A, B, changed, dt = pcall(run, cpfg, c, n, seed0, homo)
  if ok then
    if not report(c.name, A, B, n, changed) then bad = bad + 1 end
    print(string.format("(%d s)", dt))
  else
    print("== " .. c.name .. ": fails: " .. tostring(A))
    bad = bad + 1
  end
  print()
end
os.exit(bad == 0 and 0 or 1)
