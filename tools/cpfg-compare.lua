-- Runs vlab's example models through cpfg and through lsys.cpfg.load_object and compares
-- the derived strings module by module (parameters within cpfg's printed precision).
-- Usage: lua5.4 tools/cpfg-compare.lua VLAB_EXT CPFG [MODEL_DIR ...]
--   VLAB_EXT: vlab's oofs/ext folder (git archive HEAD oofs/ext of the vlab repository);
--   CPFG: the cpfg program (see ../shared/tools/cpfg-build.sh);
--   MODEL_DIR: folders under VLAB_EXT (default: the fidelity list of issue 18).
-- Prints one line per model: identical, differs at module k, or fails (and why).
-- Run from the checkout after a build (it sets package.path to ./lua and ./build).
package.path = "./lua/?.lua;./lua/?/init.lua;" .. package.path
package.cpath = "./build/?.so;" .. package.cpath
local lsys = require "lsys"

local root, cpfg = arg[1], arg[2]
if not root or not cpfg then
  io.stderr:write("usage: lua5.4 tools/cpfg-compare.lua VLAB_EXT CPFG [MODEL_DIR ...]\n")
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

local function q (s) return "'" .. s:gsub("'", "'\\''") .. "'" end

local function read (path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

-- the first cpfg command of the specifications: its .l, .v and colour map
local function files (dir)
  local spec = read(dir .. "/specifications") or ""
  for line in spec:gmatch("[^\n]+") do
    local cmd = line:match("^%s*cpfg%s(.*)$")
    if cmd then
      local l, v
      for w in cmd:gmatch("%S+") do
        if w:match("%.l$") then l = l or w elseif w:match("%.v$") then v = v or w end
      end
      if l then return l, v end
    end
  end
end

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

local function compare (dir)
  local l, v = files(dir)
  if not l then return "fails: no cpfg command with a .l file in specifications" end
  local out = os.tmpname()
  local empty = os.tmpname()
  local cmd = "cd " .. q(dir) .. " && timeout 300 " .. q(cpfg) .. " -g -m " .. q(empty) ..
              " -str " .. q(out) .. " " .. q(l) .. (v and " " .. q(v) or "") ..
              " </dev/null >/dev/null 2>&1"
  os.execute(cmd)
  local ref = read(out)
  os.remove(out)
  os.remove(empty)
  if not ref or ref == "" then return "cpfg gave no string" end
  ref = ref:gsub("\n", "")
  local ok, m = pcall(lsys.cpfg.load_object, dir)
  if not ok then return "fails to load: " .. tostring(m) end
  local t0 = os.clock()
  local ok2, s = pcall(m.derive, m)
  if not ok2 then return "fails to derive: " .. tostring(s) end
  local dt = os.clock() - t0
  local ok3, r = pcall(lsys.lstring, ref, m.modules)
  if not ok3 then return "cannot read cpfg's string: " .. tostring(r) end
  local a, b = modules(s), modules(r)
  for k = 1, math.max(#a, #b) do
    local x, y = a[k], b[k]
    local same = x and y and x[1] == y[1] and #x[2] == #y[2]
    if same then
      for i = 1, #x[2] do if not close(x[2][i], y[2][i]) then same = false end end
    end
    if not same then
      local function show (e)
        if not e then return "(end)" end
        local p = {}
        for i, z in ipairs(e[2]) do p[i] = string.format("%.7g", z) end
        return e[1] .. (#p > 0 and "(" .. table.concat(p, ",") .. ")" or "")
      end
      return string.format("differs at module %d of %d/%d: lsys %s, cpfg %s", k, #a, #b,
                           show(x), show(y))
    end
  end
  return string.format("identical (%d modules, %d steps, lsys %.2f s)", #a, m.steps, dt)
end

local list = {}
for i = 3, #arg do list[#list + 1] = arg[i] end
if #list == 0 then list = DEFAULT end
for _, d in ipairs(list) do
  local ok, r = pcall(compare, root .. "/" .. d)
  print(d .. ": " .. (ok and r or "error: " .. tostring(r)))
end
