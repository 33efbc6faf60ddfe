-- Runs vlab's example models through cpfg and through lsys.cpfg and compares the derived
-- strings module by module (parameters within cpfg's printed precision).
-- Usage: lua5.4 tools/cpfg-compare.lua VLAB_EXT CPFG [--timeout S] [--homo | --geometry]
--                                       [--enviro BIN] [MODEL_DIR ...] [--all FOLDER ...]
--   VLAB_EXT: vlab's oofs/ext folder (git archive HEAD oofs/ext of the vlab repository);
--   CPFG: the cpfg program, built for batch use (docs/cpfg.md, "cpfg as a reference");
--   MODEL_DIR: object folders under VLAB_EXT (default: the cpfg fidelity list);
--   --all FOLDER: every object folder under VLAB_EXT/FOLDER (nested ext/ folders too) whose
--     specifications run cpfg; each cpfg command there is one model;
--   --timeout S: seconds each program may take per model (default 300);
--   --homo: compare the strings after the homomorphism (cpfg -homo, lsys m:expand; cpfg
--     stops writing that string at its first query module ?E ?P ..., shown as "?").
-- Prints one line per model: identical, differs at module k (both modules shown), lsys
-- refuses (its message), cpfg fails (its message); "stochastic:" before a difference
-- when lsys's own string changes with the seed (cpfg's drand48 cannot be matched string
-- for string: see tools/cpfg-stats.lua). A view lsys refuses is reported and the strings
-- are compared without it. The environment program of `-e` is not run, and lsys reads ?E
-- with environment = "none", as cpfg without the program, unless --enviro BIN names the
-- folder of vlab's environmental programs (tools/enviro-build.sh): then both run the
-- model's `-e FILE.e` with the program found there ("[environment FILE.e run]").
--   cpfg -g reads the L-system before the view, so the names of a view's function set are
--   undefined in its batch run (an interactive cpfg reads the view first and defines them
--   as 1, 2, ...): cpfg is given a copy of the .l file with those #defines in front.
--   With --homo, a string cpfg stops writing at a query module is compared up to there.
--   --geometry: for an identical string, also the bounding box of what each draws: cpfg's
--   rayshade file (-ray: lines as cylinders of the line width; see raypoints) and lsys's
--   scene (its segments as cylinders of their width); the largest difference of a corner
--   coordinate, in % of the diagonal of cpfg's box (within 1 %: "box within X %").
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
-- The bounding box of a point list: lo, hi (nil when it is empty).
local function boxof (pts)
  if #pts == 0 then return nil end
  local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
  for _, p in ipairs(pts) do
    for k = 1, 3 do
      if p[k] < lo[k] then lo[k] = p[k] end
      if p[k] > hi[k] then hi[k] = p[k] end
    end
  end
  return lo, hi
end

-- Points around a circle of radius r about c, perpendicular to the unit vector n.
local function ring (pts, c, n, r)
  local a = math.abs(n[1]) < 0.9 and { 1, 0, 0 } or { 0, 1, 0 }
  local u = { n[2] * a[3] - n[3] * a[2], n[3] * a[1] - n[1] * a[3], n[1] * a[2] - n[2] * a[1] }
  local lu = math.sqrt(u[1] ^ 2 + u[2] ^ 2 + u[3] ^ 2)
  u = { u[1] / lu, u[2] / lu, u[3] / lu }
  local v = { n[2] * u[3] - n[3] * u[2], n[3] * u[1] - n[1] * u[3], n[1] * u[2] - n[2] * u[1] }
  for k = 0, 63 do
    local t = 2 * math.pi * k / 64
    local cs, sn = math.cos(t) * r, math.sin(t) * r
    pts[#pts + 1] = { c[1] + cs * u[1] + sn * v[1], c[2] + cs * u[2] + sn * v[2],
                      c[3] + cs * u[3] + sn * v[3] }
  end
end

-- The points of what cpfg's rayshade file (-ray) draws. cpfg's own OBJ writer turns its
-- predefined surfaces the wrong way (object.c negates the left axis, "should this be
-- -1 ?"), its rayshade writer turns them back (`rotate 0 1 0 180`) and draws what the
-- screen shows, so the geometry is read from there: cylinders, cones, spheres, discs,
-- polygons and triangles, with objects (`name ... end`) placed by scale, rotate,
-- transform and translate. Curved shapes are sampled (64 points a circle).
local function raypoints (path)
  local text = read(path) or ""
  local body = text:match("#else\n(.-)#endif") or ""
  local tok = {}
  for line in body:gmatch("[^\n]+") do
    if not line:find("^#") then
      for w in line:gmatch("%S+") do tok[#tok + 1] = w end
    end
  end
  local i, objs = 1, {}
  local function num () local x = tonumber(tok[i]); i = i + 1; return x end
  local function isnum (k) return tonumber(tok[k or i]) ~= nil end
  local function vec () return { num(), num(), num() } end
  local function surf () if tok[i] and not isnum() then i = i + 1 end end
  local function sub (a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
  local function unit (a)
    local l = math.sqrt(a[1] ^ 2 + a[2] ^ 2 + a[3] ^ 2)
    return l > 0 and { a[1] / l, a[2] / l, a[3] / l } or { 0, 0, 1 }
  end
  local function primitives (pts)
    while tok[i] do
      local w = tok[i]
      i = i + 1
      if w == "end" then return
      elseif w == "cylinder" or w == "cone" then
        surf()
        local r0 = num()
        local p0 = vec()
        local r1 = w == "cone" and num() or r0
        local p1 = vec()
        local n = unit(sub(p1, p0))
        ring(pts, p0, n, r0)
        ring(pts, p1, n, r1)
      elseif w == "sphere" then
        surf()
        local r, c = num(), vec()
        ring(pts, c, { 1, 0, 0 }, r); ring(pts, c, { 0, 1, 0 }, r); ring(pts, c, { 0, 0, 1 }, r)
      elseif w == "disc" then
        surf()
        local r, c, n = num(), vec(), vec()
        ring(pts, c, unit(n), r)
      elseif w == "poly" then
        surf()
        while isnum() do pts[#pts + 1] = vec() end
      elseif w == "triangle" or w == "triangleuv" then
        surf()
        local k = i
        while isnum(k) do k = k + 1 end
        local per = (k - i) // 3              -- 3 numbers a vertex, or with normal and uv
        for _ = 1, 3 do
          pts[#pts + 1] = vec()
          i = i + per - 3
        end
      elseif w == "object" then       -- object [SURFACE] NAME
        if not objs[tok[i]] and tok[i + 1] and objs[tok[i + 1]] then i = i + 1 end
        local obj = objs[tok[i]] or {}
        i = i + 1
        local t = {}
        for n, p in ipairs(obj) do t[n] = { p[1], p[2], p[3] } end
        while tok[i] == "scale" or tok[i] == "translate" or tok[i] == "rotate" or
              tok[i] == "transform" do
          local op = tok[i]
          i = i + 1
          if op == "scale" then
            local f = vec()
            for _, p in ipairs(t) do for k = 1, 3 do p[k] = p[k] * f[k] end end
          elseif op == "translate" then
            local d = vec()
            for _, p in ipairs(t) do for k = 1, 3 do p[k] = p[k] + d[k] end end
          elseif op == "rotate" then
            local ax, deg = unit(vec()), num()
            local c, sn = math.cos(math.rad(deg)), math.sin(math.rad(deg))
            for _, p in ipairs(t) do     -- Rodrigues
              local d = ax[1] * p[1] + ax[2] * p[2] + ax[3] * p[3]
              local x = { ax[2] * p[3] - ax[3] * p[2], ax[3] * p[1] - ax[1] * p[3],
                          ax[1] * p[2] - ax[2] * p[1] }
              for k = 1, 3 do p[k] = p[k] * c + x[k] * sn + ax[k] * d * (1 - c) end
            end
          else                          -- a row vector times the 3 x 3 matrix (+ a move)
            local m = {}
            while isnum() do m[#m + 1] = num() end
            for _, p in ipairs(t) do
              local x, y, z = p[1], p[2], p[3]
              for k = 1, 3 do
                p[k] = x * m[k] + y * m[3 + k] + z * m[6 + k] + (m[9 + k] or 0)
              end
            end
          end
        end
        for _, p in ipairs(t) do pts[#pts + 1] = p end
      elseif w == "name" then
        local n = tok[i]
        i = i + 1
        if tok[i] == "grid" then i = i + 4 end
        local own = {}
        primitives(own)
        objs[n] = own
      elseif w == "grid" then i = i + 3
      elseif w == "applysurf" then i = i + 1
      end
    end
  end
  local top = {}
  primitives(top)
  -- the last name defined is the model (`object FILE` in the header places it)
  local name = ("\n" .. body):match(".*\nname (%S+)")
  return name and objs[name] or top
end

-- "box within X %" or "box differs ..." for lsys's scene of string s against cpfg's OBJ.
local function geometry (m, s, ray)
  local clo, chi = boxof(raypoints(ray))
  -- the segments as cylinders of their width, as cpfg's rayshade writer draws every
  -- line (rings at both ends, as for cpfg's cylinders: how tubes are joined is not the
  -- question), and the other shapes as lsys tessellates them
  local out = os.tmpname() .. ".obj"
  local sc = m:interpret(s, { line_style = "line" })
  sc:save(out)
  local pts = {}
  for line in io.lines(out) do
    local x, y, z = line:match("^v%s+(%S+)%s+(%S+)%s+(%S+)")
    if x then pts[#pts + 1] = { tonumber(x), tonumber(y), tonumber(z) } end
  end
  os.remove(out)
  os.remove((out:gsub("%.obj$", ".mtl")))
  for _, r in sc:records() do
    if r.kind == "segment" and r.length > 0 then
      ring(pts, r.p0, r.H, r.w0 / 2)
      ring(pts, r.p1, r.H, r.w1 / 2)
    end
  end
  local llo, lhi = boxof(pts)
  if not clo and not llo then return "neither draws anything" end
  if not clo then return "lsys draws, cpfg's rayshade file has nothing" end
  if not llo then return "lsys draws nothing, cpfg does" end
  local diag = math.sqrt((chi[1] - clo[1]) ^ 2 + (chi[2] - clo[2]) ^ 2 + (chi[3] - clo[3]) ^ 2)
  local worst = 0
  for k = 1, 3 do
    worst = math.max(worst, math.abs(llo[k] - clo[k]), math.abs(lhi[k] - chi[k]))
  end
  local pct = diag > 0 and 100 * worst / diag or (worst == 0 and 0 or math.huge)
  local function box (lo, hi)
    return string.format("(%.4g,%.4g,%.4g)..(%.4g,%.4g,%.4g)", lo[1], lo[2], lo[3], hi[1],
                         hi[2], hi[3])
  end
  if pct <= 1 then return string.format("box within %.2g %%", pct) end
  return string.format("box differs by %.3g %% of the diagonal: lsys %s, cpfg %s", pct,
                       box(llo, lhi), box(clo, chi))
end

local function child (l, v, pal, ref, homo, obj, env)
  local lsys = require "lsys"
  -- ?E as cpfg without its program (cpfg runs none here), or with the program of env
  local opts = { environment = env ~= "" and env or "none" }
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
    -- (a model with query modules had that pass already: cpfg's last interpretation
    -- between steps, which fills them, is the one after the derivation)
    if m.random == "cpfg" and not m._queries then
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
  local a, b = modules(s), modules(r)
  local upto = ""
  if homo == "homo" and #b > 0 and b[#b][1] == "?" and #b[#b][2] == 0 and #a >= #b and
     a[#b][1]:sub(1, 1) == "?" then
    -- cpfg -homo writes nothing after its first query module: compare up to there
    upto = string.format(" up to cpfg's first query module, %d of %d", #b, #a)
    a = { table.unpack(a, 1, #b - 1) }
    b[#b] = nil
  end
  local d = diff(a, b)
  if not d then
    local g = ""
    if obj ~= "" and homo ~= "homo" then g = "; " .. geometry(m, s, obj) end
    return string.format("identical%s (%d modules, %d steps, lsys %.2f s)%s", upto, #a,
                         m.steps, dt, g) .. note
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
  local ok, r = pcall(child, arg[2], arg[3], arg[4], arg[5], arg[6], arg[7] or "",
                      arg[8] or "")
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

local timeout, homo, geom, enviro = 300, false, false, nil

-- The names of the view's function set (`function set: F.fset`), in order, or nil.
local function setnames (dir, v)
  local text = v and read(dir .. "/" .. v) or ""
  local file = text:gsub("/%*.-%*/", ""):match("\n%s*function set:%s*(%S+)")
               or text:match("^%s*function set:%s*(%S+)")
  local set = file and read(dir .. "/" .. file)
  if not set then return nil end
  local names = {}
  for n in set:gmatch("\nname:%s*([%w_.]+)") do names[#names + 1] = n:gsub("%.[^.]*$", "") end
  return #names > 0 and names or nil
end

-- The folder to run cpfg in: `dir` itself, or a scratch folder of links to its files with
-- a copy of the .l file that defines the function set's names first (see the header).
local function cpfgdir (dir, c)
  local names = setnames(dir, c.v)
  if not names then return dir, nil end
  local tmp = io.popen("mktemp -d"):read("l")
  os.execute("ln -s " .. q(dir) .. "/* " .. q(tmp) .. "/ && rm " .. q(tmp .. "/" .. c.l))
  local defs = {}
  for i, n in ipairs(names) do defs[i] = string.format("#define %s %d\n", n, i) end
  write(tmp .. "/" .. c.l, table.concat(defs) .. (read(dir .. "/" .. c.l) or ""))
  return tmp, tmp
end

local function compare (dir, c)
  local out, empty, err, ref = os.tmpname(), os.tmpname(), os.tmpname(), os.tmpname()
  local obj = geom and not homo and os.tmpname() .. ".ray" or ""
  local cdir, scratch = cpfgdir(dir, c)
  local run = enviro and c.env and not homo
  local path = run and "PATH=" .. q(enviro) .. ":$PATH " or ""
  local cmd = "cd " .. q(cdir) .. " && " .. path .. "timeout " .. timeout .. " " .. q(cpfg) ..
              (run and " -e " .. q(c.env) or "") ..
              (homo and " -homo" or "") .. " -g -m " ..
              q(empty) .. " -str " .. q(out) .. (obj ~= "" and " -ray " .. q(obj) or "") ..
              " " .. q(c.l) .. (c.v and " " .. q(c.v) or "") .. " </dev/null >/dev/null 2>" ..
              q(err)
  local _, _, code = os.execute(cmd)
  if scratch then os.execute("rm -r " .. q(scratch)) end
  local text = read(out) or ""
  local msg = (read(err) or ""):gsub("\n+$", "")
  for _, f in ipairs({ out, empty, err }) do os.remove(f) end
  if text == "" then
    os.remove(ref)
    if obj ~= "" then os.remove(obj) end
    local first = msg:match("[^\n]*[Ee]rror[^\n]*") or msg:match("[^\n]+") or ""
    if code == 124 then first = "timed out after " .. timeout .. " s" end
    return "cpfg fails: " .. (first ~= "" and first or "no string written")
  end
  write(ref, text)
  local p = io.popen(path .. "timeout " .. timeout .. " lua5.4 " .. q(arg[0]) .. " --child " ..
                     q(dir .. "/" .. c.l) .. " " .. q(c.v and dir .. "/" .. c.v or "") .. " " ..
                     q(c.pal and dir .. "/" .. c.pal or "") .. " " .. q(ref) ..
                     (homo and " homo" or " derived") .. " " .. q(obj) .. " " ..
                     q(run and dir .. "/" .. c.env or "") .. " 2>&1")
  local r = p:read("a")
  local ok, _, code2 = p:close()
  os.remove(ref)
  if obj ~= "" then os.remove(obj) end
  r = r:gsub("\n+$", ""):match("[^\n]*$")
  if not ok and code2 == 124 then r = "lsys timed out after " .. timeout .. " s" end
  if r == "" then r = "lsys crashed (exit " .. tostring(code2) .. ")" end
  local cerr = msg:match("[^\n]*[Ee]rror[^\n]*") or msg:match("[^\n]*Invalid[^\n]*")
  if cerr then r = r .. " [cpfg: " .. cerr .. "]" end
  if r:find("^differs") and random(dir .. "/" .. c.l) then r = "stochastic: " .. r end
  if c.env then r = r .. " [environment " .. c.env .. (run and " run]" or " not run]") end
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
  elseif arg[i] == "--geometry" then
    geom = true
    i = i + 1
  elseif arg[i] == "--enviro" then
    enviro = arg[i + 1]
    i = i + 2
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
