--- A sketched plant as a cpfg model (Anastacio et al. 2009, §7: their sketching program
-- launched cpfg and exported the model to L-studio for further editing): the L-system file
-- `plant.l`, its view file `plant.v` naming the positional functions, one cpfg function
-- file `plant.NAME.func` each, a colour map `plant.map` and the organ surfaces
-- (`plant.organ.s`, ...). cpfg derives the same string as lsys does (the specs compare).
--
-- What changes on the way: cpfg's module names are single characters, so each plant's
-- modules become letters (A S B C L R and O for Organ in the first plant, others for the
-- next ones; a comment lists them); functions are called as `func(id, x)` through a
-- macro of their name (`#define internode(x) func(1, x)`), the template's constants are
-- `#define`s; cpfg's `%` takes the integer parts of its operands, so the Fibonacci
-- divergence reduces i * 137.5 to [0, 360) with floor instead; sub-L-systems (organs that
-- are plants) are numbered from 2, the main L-system being 1.
-- @module lsys.sketch.cpfg
local templates = require "lsys.sketch.templates"
local view = require "lsys.view"
local write = require "lsys.sketch.write"
local functions = require "lsys.sketch.functions"
local model = require "lsys.model"
local num = require("lsys.util.text").number

local type, pairs, ipairs, error, pcall, string, table, math =
      type, pairs, ipairs, error, pcall, string, table, math
local format, concat = string.format, table.concat
local sorted = write.sorted
local _ENV = nil

local M = {}

-- The letters of plant k's modules (templates: A S B C L R Organ). cpfg draws or moves
-- with F f G g, reads s as an old sphere, and Z z mean something to lsys: none of those;
-- nor D, a constant of the templates (a #define would replace it).
local FIRST = { A = "A", S = "S", B = "B", C = "C", L = "L", R = "R", Organ = "O" }
local SPARE = "EHIJKMNPQTUVWXYabcdehijklmnopqrtuvwxy"
local MODULES = { "A", "S", "B", "C", "L", "R", "Organ" }

-- Text for a /* */ comment: printable ASCII, no end of comment inside.
local function comment (s)
  s = s:gsub("§", "section "):gsub("[^\32-\126]", "?"):gsub("%*/", "* /")
  return "/* " .. s .. " */"
end

-- The letter of every module name of the plants of `d`.
local function letters (d)
  local map, free = {}, SPARE:gmatch("%a")
  for k, p in ipairs(d.plants) do
    for _, m in ipairs(MODULES) do
      local name = m .. p.suffix
      if k == 1 then map[name] = FIRST[m]
      else
        local c = free()
        if c == nil then error("cpfg: too many plants for cpfg's one-letter modules", 0) end
        map[name] = c
      end
    end
  end
  return map
end

-- Rule text `l` in cpfg's words: module names as their letters (a word after @ or ~ is a
-- command or a surface: it stays), sub-L-system ids moved up by one, the Fibonacci
-- divergence reduced without %.
local function rule (l, map)
  l = l:gsub("()([%a_][%w_]*)", function (at, word)
    local before = at > 1 and l:sub(at - 1, at - 1) or ""
    if map[word] and before ~= "@" and before ~= "~" then return map[word] end
  end)
  l = l:gsub("%?%((%d+),", function (id) return format("?(%d,", id + 1) end)
  local div = num(templates.DIVERGENCE)
  l = l:gsub("%(i %* " .. div:gsub("%.", "%%.") .. "%) %% 360",
             format("i * %s - 360 * floor(i * %s / 360)", div, div))
  return l
end

-- The colour map of view `v` (768 bytes: 256 colours of 3 bytes): its palette (the
-- default one when it gives none), a material's diffuse colour; grey past its end.
local function colormap (v)
  local ok, nv = pcall(view.normalize, v)
  local palette = ok and nv.palette or {}
  local b = {}
  for i = 0, 255 do
    local c = palette[i]
    if type(c) == "table" and type(c.diffuse) == "table" then c = c.diffuse end
    local rgb = type(c) == "table" and type(c[1]) == "number" and c or { 0.5, 0.5, 0.5 }
    for j = 1, 3 do
      b[#b + 1] = string.char(math.floor(math.max(0, math.min(1, rgb[j])) * 255 + 0.5))
    end
  end
  return concat(b)
end

-- The start of sub-L-system `id`: what follows its ?(id, ...) in the productions.
local function substart (d, id)
  local pat = "%?%(" .. id .. ",[^)]*%)%s*(.-)%s*%$"
  for _, l in ipairs(d.productions) do
    local a = l:match(pat)
    if a then return a end
  end
  for _, s in pairs(d.sub or {}) do
    for _, l in ipairs(s.productions) do
      local a = l:match(pat)
      if a then return a end
    end
  end
  return "A(0)"
end

-- {=========================================================================================
-- Functions that cpfg reads as lsys does
--
-- cpfg evaluates a function at x by bisection on the spline's parameter until the point's
-- x is within 0.001 of the argument (splinefun.cpp, SplineFunction::_Value), so on a
-- slope s its value is off by up to 0.001 s: 0.2 degrees of a stem's turn, 0.5 % of an
-- organ. The exported functions are therefore the sketch's made flat within PLATEAU of
-- every point where the plant reads them (found by deriving the model once and recording
-- the arguments): there cpfg's value is the exact one, elsewhere the function is the
-- sketch's. Points of one function closer than 2 PLATEAU share the gap; those left a
-- plateau narrower than cpfg's 0.001 (dense nodes) are counted as `inexact`.

M.PLATEAU = 0.0015
local CPFG_TOL = 0.001

-- The arguments of every function call of the model of `d`, by function name, sorted.
local function readings (d)
  local rec, env = {}, {}
  for k, v in pairs(d.env) do
    if type(v) == "number" then env[k] = v
    else
      local t, f = {}, v
      rec[k] = t
      env[k] = function (x) t[#t + 1] = x; return f(x) end
    end
  end
  local o = {}
  for k, v in pairs(d.options) do o[k] = v end
  o.env, o.view = env, nil
  local m = model.lsystem(o)
  m.lua_expressions = true
  m:derive()
  for k, t in pairs(rec) do
    table.sort(t)
    local u = {}
    for _, x in ipairs(t) do if x ~= u[#u] then u[#u + 1] = x end end
    rec[k] = u
  end
  return rec
end

-- The polyline `pts` (the function f) flat at f(e) on [e - w, e + w] around each reading
-- e of `xs`. Returns the polyline and how many readings got less than cpfg's tolerance.
local function plateaus (f, pts, xs)
  local iv = {}            -- { a, b, v }, increasing, not overlapping
  for i, e in ipairs(xs) do
    local v = f(e)
    local wl = i > 1 and (e - xs[i - 1]) / 2 or M.PLATEAU
    local wr = i < #xs and (xs[i + 1] - e) / 2 or M.PLATEAU
    local last = iv[#iv]
    if last and last.v == v and e - last.b < 2 * M.PLATEAU then
      last.b, last.wr = math.min(1, e + math.min(M.PLATEAU, wr)), math.min(M.PLATEAU, wr)
    else
      iv[#iv + 1] = { a = math.max(0, e - math.min(M.PLATEAU, wl)),
                      b = math.min(1, e + math.min(M.PLATEAU, wr)), v = v,
                      wl = math.min(M.PLATEAU, wl), wr = math.min(M.PLATEAU, wr) }
    end
  end
  local inexact = 0
  for _, p in ipairs(iv) do
    if p.wl < CPFG_TOL or p.wr < CPFG_TOL then inexact = inexact + 1 end
  end
  local out = {}
  local function add (x, y)
    local q = out[#out]
    if not (q and q[1] == x and q[2] == y) then out[#out + 1] = { x, y } end
  end
  local j = 1
  for _, p in ipairs(iv) do
    while j <= #pts and pts[j][1] < p.a do add(pts[j][1], pts[j][2]); j = j + 1 end
    add(p.a, f(p.a)); add(p.a, p.v); add(p.b, p.v); add(p.b, f(p.b))
    while j <= #pts and pts[j][1] <= p.b do j = j + 1 end
  end
  while j <= #pts do add(pts[j][1], pts[j][2]); j = j + 1 end
  -- the ends at 0 and 1 (a plateau there replaced them)
  if out[1][1] ~= 0 then table.insert(out, 1, { 0, f(0) }) end
  if out[#out][1] ~= 1 then add(1, f(1)) end
  -- vertical pieces at the ends are not needed
  while #out > 2 and out[1][1] == out[2][1] do table.remove(out, 1) end
  while #out > 2 and out[#out][1] == out[#out - 1][1] do table.remove(out) end
  return out, inexact
end
M.plateaus = plateaus

-- }=========================================================================================

--- Writes the cpfg model of description `d` (lsys.sketch's, of sk:model or
-- lsys.sketch.compose) to `path` (a `.l` file) and the files beside it. Returns the list
-- of the files written. Raises "who: ...".
function M.write (d, path, who)
  if not path:match("%.l$") then error(format("%s: the L-system file must end in .l", who), 0) end
  local dir, base = path:match("^(.-)([^/]*)%.l$")
  local map = letters(d)
  -- the functions: one .func file each, numbered in name order
  local fnames, files = sorted(d.funcs), {}
  local funcfile, reads, inexact = {}, readings(d), 0
  for _, k in ipairs(fnames) do
    local pts, n = plateaus(d.env[k], d.funcs[k], reads[k] or {})
    inexact = inexact + n
    local f = functions.polyline((k:gsub("^o1_", "")), pts)
    funcfile[k] = format("%s.%s.func", base, k)
    files[#files + 1] = { dir .. funcfile[k], f:format() }
  end
  local surfiles = write.surfaces(d, path, who)
  for _, x in ipairs(sorted(surfiles)) do
    files[#files + 1] = { surfiles[x].path, surfiles[x].text }
  end
  -- the L-system file
  local L = {}
  local function w (...) L[#L + 1] = format(...) end
  for _, l in ipairs(write.header(d)) do w("%s", comment(l)) end
  w("%s", comment(format("For cpfg and L-studio: cpfg -m %s.map %s.l %s.v", base, base, base)))
  w("")
  w("/* the positional functions (section 4): func(id, x) of the view file's functions */")
  for i, k in ipairs(fnames) do w("#define %s(x) func(%d, x)", k, i) end
  w("/* the template's constants: XT stops the nodes at the top inclination line, XE the */")
  w("/* stem at its tip, D is the longest straight piece of stem (stem lengths) */")
  for _, k in ipairs(sorted(d.env, function (v) return type(v) == "number" end)) do
    w("#define %s %s", k, format("%.17g", d.env[k]))
  end
  w("/* modules: %s */", (function ()
    local t = {}
    for _, k in ipairs(sorted(map)) do t[#t + 1] = format("%s = %s", map[k], k) end
    return concat(t, ", ")
  end)())
  w("")
  local function section (id, axiom, productions, homomorphism)
    w("Lsystem: %d", id)
    w("derivation length: %d", d.steps)
    w("Axiom: %s", rule(axiom, map))
    for _, l in ipairs(productions) do w("%s", rule(l, map)) end
    if homomorphism then
      w("homomorphism")
      for _, l in ipairs(homomorphism) do w("%s", rule(l, map)) end
    end
    w("endlsystem")
  end
  section(1, d.axiom, d.productions, d.homomorphism)
  for _, id in ipairs(sorted(d.sub or {})) do
    w("")
    section(id + 1, substart(d, id), d.sub[id].productions)
  end
  local ltext = concat(L, "\n") .. "\n"
  -- the view file
  local V = {}
  V[#V + 1] = format("initial line width: %s polygons", num(d.view.line_width))
  V[#V + 1] = format("line style: %s", d.view.line_style == "cylinder" and "cylinder" or
                     d.view.line_style == "line" and "pixel" or "polygon")
  V[#V + 1] = format("initial color: %d", d.view.color)
  V[#V + 1] = "line width increment: 0"
  for _, k in ipairs(fnames) do V[#V + 1] = format("function: %s", funcfile[k]) end
  for _, x in ipairs(sorted(surfiles)) do
    V[#V + 1] = format("surface: %s %s 1", x, surfiles[x].name)
  end
  local vtext = concat(V, "\n") .. "\n"
  files[#files + 1] = { dir .. base .. ".map", colormap(d.view) }
  files[#files + 1] = { dir .. base .. ".v", vtext }
  files[#files + 1] = { path, ltext }
  -- everything made, then written: the files the L-system file names first, it last
  write.files(files, who)
  local names = {}
  for i, f in ipairs(files) do names[i] = f[1] end
  return names, inexact
end

return M
