-- Runs vlab's example models through cpfg and through lsys.cpfg and compares the derived
-- strings module by module (parameters within cpfg's printed precision).
-- Usage: lua5.4 tools/cpfg-compare.lua VLAB_EXT CPFG [--timeout S] [--homo]
--                                       [MODEL_DIR ...] [--all FOLDER ...]
--   VLAB_EXT: vlab's oofs/ext folder (git archive HEAD oofs/ext of the vlab repository);
--   CPFG: the cpfg program, built for batch use (docs/cpfg.md, "cpfg as a reference");
--   MODEL_DIR: object folders under VLAB_EXT (default: the fidelity list of issue 18);
--   --all FOLDER: every object folder under VLAB_EXT/FOLDER (nested ext/ folders too) whose
--     specifications run cpfg; each cpfg command there is one model;
--   --timeout S: seconds each program may take per model (default 300);
--   --homo: compare the strings after the homomorphism (cpfg -homo, lsys m:expand; cpfg
--     stops writing that string at its first query module ?E ?P ..., shown as "?").
-- Prints one line per model: identical, differs at module k (both modules shown), lsys
-- refuses (its message), cpfg fails (its message); "stochastic:" before a difference
-- when lsys's own string changes with the seed (cpfg's drand48 cannot be matched string
-- for string: see tools/cpfg-stats.lua). A view lsys refuses is reported and the strings
-- are compared without it. The environment program of `-e` is not run.
-- Run from the checkout after a build (it sets package.path to ./lua and ./build).
package.path = "./lua/?.lua;./lua/?/init.lua;" .. package.path
package.cpath = "./build/?.so;" .. package.cpath

local T = dofile(((arg and arg[0] or "tools/x.lua"):match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local q, read, write = T.q, T.read, T.write

local function modules (s)
  local t = {}
  local f, st, c = s:modules()
  while true do
    local r = table.pack(f(st, c))
    if r[1] == nil then break end
    c = r[1]
    t[#t + 1] = { r[2], { table.unpack(r, 3, r.n) } }
  end
  return t
end

local function close (a, b)
  return a == b or math.abs(a - b) <= 1e-5 * math.max(math.abs(a), math.abs(b)) + 1e-6
end

local function show (e)
  if not e then return "(end)" end
  local p = {}
  for i, z in ipairs(e[2]) do p[i] = string.format("%.7g", z) end
  return e[1] .. (#p > 0 and "(" .. table.concat(p, ",") .. ")" or "")
end

-- nil when the module lists a and b are the same, else where and how they differ
local function diff (a, b)
  for k = 1, math.max(#a, #b) do
    local x, y = a[k], b[k]
    local same = x and y and x[1] == y[1] and #x[2] == #y[2]
    if same then
      for i = 1, #x[2] do if not close(x[2][i], y[2][i]) then same = false end end
    end
    if not same then
      return string.format("differs at module %d of %d/%d: lsys %s, cpfg %s", k, #a, #b,
                           show(x), show(y))
    end
  end
end

-- The lsys side, run in a child process (so a crash or a runaway derivation costs one
-- model): loads L, V, the palette, derives, compares with cpfg's string in REF and
-- returns the verdict. A model whose string changes with the seed is "stochastic".
local function child (l, v, pal, ref, homo)
  local lsys = require "lsys"
  local opts = {}
  if pal ~= "" then
    if pal:match("%.mat$") then opts.materials = pal else opts.colormap = pal end
  end
  local ok, m = pcall(lsys.cpfg.load, l, v ~= "" and v or nil, opts)
  local note = ""
  if not ok and v ~= "" then
    -- a view lsys refuses: compare the strings with a copy of it without the lines that
    -- name files (in a folder of links to the model's files), else without it
    local tmp = io.popen("mktemp -d"):read("l")
    local dir, name = v:match("^(.*)/([^/]*)$")
    os.execute("ln -s " .. q(dir) .. "/* " .. q(tmp) .. "/ && rm " .. q(tmp .. "/" .. name))
    local keep = {}
    for line in ((read(v) or "") .. "\n"):gmatch("([^\n]*)\n") do
      if not line:find("^%s*t?surface%s*:") and not line:find("^%s*contour%s*:") and
         not line:find("^%s*texture%s*:") and not line:find("^%s*line style%s*:") then
        keep[#keep + 1] = line
      end
    end
    write(tmp .. "/" .. name, table.concat(keep, "\n"))
    local ok2, m2 = pcall(lsys.cpfg.load, l, tmp .. "/" .. name, opts)
    local how = "its contour, surface, texture and line style lines removed"
    if not ok2 then
      ok2, m2 = pcall(lsys.cpfg.load, l, nil, opts)
      how = "no view"
    end
    os.execute("rm -r " .. q(tmp))
    if ok2 then
      note = " [lsys refuses the view: " .. tostring(m) .. "; compared with " .. how .. "]"
      ok, m = true, m2
    end
  end
  if not ok then return "lsys refuses: " .. tostring(m) end
  local t0 = os.clock()
  local ok2, s = pcall(m.derive, m)
  if not ok2 then return "lsys fails to derive: " .. tostring(s) .. note end
  if homo == "homo" then
    -- cpfg -g interprets the string once (its view-volume pass) before it writes the
    -- string after the homomorphism, drawing random numbers (from the derivation's
    -- generator, or the homomorphism's own, and nran's pair): cpfg's string is that of
    -- the second expansion
    if m.random == "cpfg" then
      pcall(m.expand, m, s)
      m._seed = function () end    -- and its writer does not start a homomorphism seed again
    end
    ok2, s = pcall(m.expand, m, s)
    m._seed = nil
    if not ok2 then return "lsys fails to apply the homomorphism: " .. tostring(s) .. note end
  end
  local dt = os.clock() - t0
  local text = (read(ref) or ""):gsub("\n", "")
  local ok3, r = pcall(lsys.lstring, text, m.modules)
  if not ok3 then return "cannot read cpfg's string: " .. tostring(r) .. note end
  local a = modules(s)
  local d = diff(a, modules(r))
  if not d then
    return string.format("identical (%d modules, %d steps, lsys %.2f s)", #a, m.steps, dt)
           .. note
  end
  m.seed = (m.seed or 0) + 7919
  m.random = "lsys"               -- cpfg's generator is the same for every seed but one
  local ok4, s2 = pcall(m.derive, m)
  if ok4 and homo == "homo" then ok4, s2 = pcall(m.expand, m, s2) end
  if ok4 and diff(a, modules(s2)) then d = "stochastic: " .. d end
  return d .. note
end

if arg[1] == "--child" then
  io.output("/dev/null")          -- the model's printf output
  local ok, r = pcall(child, arg[2], arg[3], arg[4], arg[5], arg[6])
  io.stdout:write((ok and r or "error: " .. tostring(r)), "\n")
  os.exit(0)
end

local root, cpfg = arg[1], arg[2]
if not root or not cpfg then
  io.stderr:write("usage: lua5.4 tools/cpfg-compare.lua VLAB_EXT CPFG [--timeout S] "
                  .. "[MODEL_DIR ...] [--all FOLDER ...]\n")
  os.exit(2)
end

local DEFAULT = {
  "11-CPFG/ext/01-Introduction/ext/01-quadratic-Koch",
  "11-CPFG/ext/01-Introduction/ext/02-snowflake-exercise",
  "11-CPFG/ext/01-Introduction/ext/03-snowflake",
  "11-CPFG/ext/01-Introduction/ext/04-compound",
  "11-CPFG/ext/01-Introduction/ext/05-compound-homo",
  "11-CPFG/ext/01-Introduction/ext/06-compound-param",
  "11-CPFG/ext/01-Introduction/ext/07-fractal-ferns",
  "11-CPFG/ext/01-Introduction/ext/08-continuous-time",
  "11-CPFG/ext/01-Introduction/ext/09-continuous-decomp",
  "11-CPFG/ext/01-Introduction/ext/10-recursive",
  "11-CPFG/ext/01-Introduction/ext/11-alternating-exercise",
  "11-CPFG/ext/01-Introduction/ext/12-alternating",
  "11-CPFG/ext/04-Signaling/ext/01-hormone-up",
  "11-CPFG/ext/04-Signaling/ext/02-hormone-down",
  "11-CPFG/ext/04-Signaling/ext/03-signal-down",
  "11-CPFG/ext/04-Signaling/ext/04-florigen",
  "11-CPFG/ext/04-Signaling/ext/05-florigen-param",
  "11-CPFG/ext/04-Signaling/ext/06-florigen+auxin",
  "11-CPFG/ext/04-Signaling/ext/07-acrotonic-2-signals",
  "11-CPFG/ext/04-Signaling/ext/08-basipetal-2-signals",
  "11-CPFG/ext/04-Signaling/ext/11-acropetal-1-signal",
  "11-CPFG/ext/04-Signaling/ext/12-basipetal-1-signal",
  "11-CPFG/ext/04-Signaling/ext/13-mesotonic-1-signal",
  "11-CPFG/ext/04-Signaling/ext/21-insect-schematic",
  "11-CPFG/ext/05-Quantitative-info-flow/ext/01-pipe-model",
  "11-CPFG/ext/03-inverse-modeling/ext/04-paintbrush",
  "10-manuals/ext/11-CPFG/ext/Shedding",
  "10-manuals/ext/11-CPFG/ext/Ring",
  "10-manuals/ext/11-CPFG/ext/Sedge",
  "10-manuals/ext/11-CPFG/ext/Lilac",
  "10-manuals/ext/11-CPFG/ext/WeepingBirch",
}

-- The cpfg commands of a specifications file: { l =, v =, pal = } each.
local function commands (dir)
  local spec = read(dir .. "/specifications") or ""
  local list = {}
  for line in spec:gmatch("[^\n]+") do
    local cmd = line:match("^%s*cpfg%s(.*)$")
    if cmd then
      local words, c = {}, {}
      for w in cmd:gmatch("%S+") do words[#words + 1] = w end
      local i = 1
      while i <= #words do
        local w = words[i]
        if w:match("^%-[mM]1?$") then c.pal = c.pal or words[i + 1]; i = i + 1
        elseif w:match("^%-[mM]%d+$") or w == "-wt" or w == "-c" then i = i + 1
        elseif w == "-e" or w == "-w" then c.env = c.env or w == "-e" and words[i + 1]
          i = i + (w == "-w" and 2 or 1)
        elseif w:match("%.l$") then c.l = c.l or w
        elseif w:match("%.v$") then c.v = c.v or w end
        i = i + 1
      end
      if c.l then list[#list + 1] = c end
    end
  end
  return list
end

-- Does the L-system file call a random function (ran, nran, bran, biran, srand)?
local function random (path)
  local s = (read(path) or ""):gsub("/%*.-%*/", ""):gsub("//[^\n]*", "")
  return s:find("%f[%w_][nb]?i?ran%s*%(") ~= nil or s:find("%f[%w_]srand%s*%(") ~= nil
end

local timeout, homo = 300, false

local function compare (dir, c)
  local out, empty, err, ref = os.tmpname(), os.tmpname(), os.tmpname(), os.tmpname()
  local cmd = "cd " .. q(dir) .. " && timeout " .. timeout .. " " .. q(cpfg) ..
              (homo and " -homo" or "") .. " -g -m " ..
              q(empty) .. " -str " .. q(out) .. " " .. q(c.l) .. (c.v and " " .. q(c.v) or "")
              .. " </dev/null >/dev/null 2>" .. q(err)
  local _, _, code = os.execute(cmd)
  local text = read(out) or ""
  local msg = (read(err) or ""):gsub("\n+$", "")
  for _, f in ipairs({ out, empty, err }) do os.remove(f) end
  if text == "" then
    os.remove(ref)
    local first = msg:match("[^\n]*[Ee]rror[^\n]*") or msg:match("[^\n]+") or ""
    if code == 124 then first = "timed out after " .. timeout .. " s" end
    return "cpfg fails: " .. (first ~= "" and first or "no string written")
  end
  write(ref, text)
  local p = io.popen("timeout " .. timeout .. " lua5.4 " .. q(arg[0]) .. " --child " ..
                     q(dir .. "/" .. c.l) .. " " .. q(c.v and dir .. "/" .. c.v or "") .. " " ..
                     q(c.pal and dir .. "/" .. c.pal or "") .. " " .. q(ref) ..
                     (homo and " homo" or "") .. " 2>&1")
  local r = p:read("a")
  local ok, _, code2 = p:close()
  os.remove(ref)
  r = r:gsub("\n+$", ""):match("[^\n]*$")
  if not ok and code2 == 124 then r = "lsys timed out after " .. timeout .. " s" end
  if r == "" then r = "lsys crashed (exit " .. tostring(code2) .. ")" end
  local cerr = msg:match("[^\n]*[Ee]rror[^\n]*") or msg:match("[^\n]*Invalid[^\n]*")
  if cerr then r = r .. " [cpfg: " .. cerr .. "]" end
  if r:find("^differs") and random(dir .. "/" .. c.l) then r = "stochastic: " .. r end
  if c.env then r = r .. " [environment " .. c.env .. " not run]" end
  return r
end

-- Object folders at and under `dir` (vlab nests them as dir/ext/NAME/...) whose
-- specifications run cpfg.
local function walk (dir, list)
  if #commands(dir) > 0 then list[#list + 1] = dir end
  local p = io.popen("ls -1 " .. q(dir .. "/ext") .. " 2>/dev/null")
  local names = {}
  for n in p:lines() do names[#names + 1] = n end
  p:close()
  for _, n in ipairs(names) do walk(dir .. "/ext/" .. n, list) end
end

local list, i = {}, 3
while i <= #arg do
  if arg[i] == "--all" then
    local found = {}
    walk(root .. "/" .. arg[i + 1], found)
    table.sort(found)
    for _, d in ipairs(found) do list[#list + 1] = d:sub(#root + 2) end
    i = i + 2
  elseif arg[i] == "--homo" then
    homo = true
    i = i + 1
  elseif arg[i] == "--timeout" then
    timeout = tonumber(arg[i + 1]) or timeout
    i = i + 2
  else
    list[#list + 1] = arg[i]
    i = i + 1
  end
end
if #list == 0 then list = DEFAULT end
for _, d in ipairs(list) do
  local dir = root .. "/" .. d
  local cs = commands(dir)
  if #cs == 0 then print(d .. ": no cpfg command with a .l file in specifications") end
  for _, c in ipairs(cs) do
    local name = #cs > 1 and d .. " [" .. c.l .. "]" or d
    local ok, r = pcall(compare, dir, c)
    print(name .. ": " .. (ok and r or "error: " .. tostring(r)))
    io.stdout:flush()
  end
end
