--- The geometry of an i-tree (issue 16; Lintermann and Deussen 1999, section "A geometry
-- generation example": each instance of the i-tree produces its geometry in its own frame).
-- The instances become turtle modules in one Lstring, so the plant is an ordinary lsys model:
-- the turtle draws it, and rendering, export, the viewer, picking and the arrangement work
-- on it unchanged.
--
-- Every instance is a branch `[` ... `]` that moves the turtle from where its parent left it
-- to the instance's frame with relative modules only (a roll, a pitch and `f` to get there,
-- then roll, pitch, roll to take its orientation), so a plant can be placed anywhere by an
-- L-system and the arrangement's joints move what hangs on them. Stems (Horn, Tree) are
-- generalized cylinders `@Gs ... @Gc ... @Ge` through the stem frames of the expansion, with
-- a Tree's branches emitted where they grow along it; leaves are `~` surfaces made by
-- lsys.sketch.organ, one per distinct shape; primitives are the turtle's own (`@O` sphere,
-- `F` cylinder, `@c` disc, a cone as a generalized cylinder) or a surface (cube); the point
-- set primitives continue the generalized cylinder of the instance before them (Tube: a
-- closed circle contour, Area: an open line contour), which is the article's
-- "triangulated with those of the following instances".
-- @module lsys.components.emit
local X = require "lsys.components.expand"
local core = require "lsys.core"

local ipairs, setmetatable, rawget, tostring, require, math, string, table, utf8, select =
      ipairs, setmetatable, rawget, tostring, require, math, string, table, utf8, select
local format, concat, sort = string.format, table.concat, table.sort
local sqrt, atan, deg, cos, sin, abs, floor, max, pi =
      math.sqrt, math.atan, math.deg, math.cos, math.sin, math.abs, math.floor, math.max, math.pi
local cross = X.cross
local _ENV = nil

local M = {}

-- The angles (degrees) of a roll `/`, a pitch `&` and a roll `/` that turn the turtle's
-- orientation (AH, AU) onto (BH, BU); with BU nil only the first two (aim H at BH). The
-- turtle's conventions (measured): `/` turns L towards U, `&` turns H towards -U, L = H x U.
local function angles (AH, AU, BH, BU)
  local h1, h2, h3, u1, u2, u3 = AH[1], AH[2], AH[3], AU[1], AU[2], AU[3]
  local l1, l2, l3 = h2 * u3 - h3 * u2, h3 * u1 - h1 * u3, h1 * u2 - h2 * u1   -- L = H x U
  local b1, b2, b3 = BH[1], BH[2], BH[3]
  local h, l, u = b1 * h1 + b2 * h2 + b3 * h3, b1 * l1 + b2 * l2 + b3 * l3,
                  b1 * u1 + b2 * u2 + b3 * u3
  local sb = sqrt(l * l + u * u)
  local a = sb > 1e-12 and atan(l, -u) or 0
  local b = atan(sb, h)
  if BU == nil then
    -- aiming only: a roll past a quarter turn is the opposite roll and a pitch the other way
    if a > 0.5 * pi then a, b = a - pi, -b elseif a <= -0.5 * pi then a, b = a + pi, -b end
    return deg(a), deg(b)
  end
  local ca, sa, cb, s2 = cos(a), sin(a), cos(b), sin(b)
  -- L1 = L ca + U sa, U1 = U ca - L sa, U2 = U1 cb + H s2
  local x1, x2, x3 = BU[1], BU[2], BU[3]
  local bl = x1 * (l1 * ca + u1 * sa) + x2 * (l2 * ca + u2 * sa) + x3 * (l3 * ca + u3 * sa)
  local bu = x1 * ((u1 * ca - l1 * sa) * cb + h1 * s2) + x2 * ((u2 * ca - l2 * sa) * cb + h2 * s2)
             + x3 * ((u3 * ca - l3 * sa) * cb + h3 * s2)
  local g = atan(-bl, bu)
  -- (a -+ 180, -b, g + 180) turns the same way; take it when it needs fewer modules: a
  -- pure pitch up is then `&(-b)`, not `/(180)&(b)/(-180)`
  if abs(a) > 1e-11 then
    local a2, g2 = a > 0 and a - pi or a + pi, g > 0 and g - pi or g + pi
    local n1 = (abs(a) > 1e-11 and 1 or 0) + (abs(g) > 1e-11 and 1 or 0)
    local n2 = (abs(a2) > 1e-11 and 1 or 0) + (abs(g2) > 1e-11 and 1 or 0)
    if n2 < n1 or n2 == n1 and abs(a2) + abs(g2) < abs(a) + abs(g) then a, b, g = a2, -b, g2 end
  end
  return deg(a), deg(b), deg(g)
end
M.angles = angles

-- The turtle's orientation after a roll a and a pitch b (degrees) from (H, U).
local function rollpitch (H, U, a, b)
  local L = cross(H, U)
  a, b = math.rad(a), math.rad(b)
  local ca, sa, cb, sb = cos(a), sin(a), cos(b), sin(b)
  local U1 = { U[1] * ca - L[1] * sa, U[2] * ca - L[2] * sa, U[3] * ca - L[3] * sa }
  return { H[1] * cb - U1[1] * sb, H[2] * cb - U1[2] * sb, H[3] * cb - U1[3] * sb },
         { U1[1] * cb + H[1] * sb, U1[2] * cb + H[2] * sb, U1[3] * cb + H[3] * sb }
end

-- {=========================================================================================
-- Shared surfaces: leaves by shape, and the unit cube.

local leafcache = setmetatable({}, { __mode = "v" })   -- key -> organ surface

-- A cpfg surface file of flat quads (each a bicubic patch whose control points lie on the
-- bilinear quad): the cube primitive, base at the contact point, 1 wide, high and deep.
local function cubetext ()
  local faces = {
    { { -.5, 0, -.5 }, { .5, 0, -.5 }, { .5, 0, .5 }, { -.5, 0, .5 } },       -- bottom
    { { -.5, 1, -.5 }, { -.5, 1, .5 }, { .5, 1, .5 }, { .5, 1, -.5 } },       -- top
    { { -.5, 0, -.5 }, { -.5, 1, -.5 }, { .5, 1, -.5 }, { .5, 0, -.5 } },
    { { -.5, 0, .5 }, { .5, 0, .5 }, { .5, 1, .5 }, { -.5, 1, .5 } },
    { { -.5, 0, -.5 }, { -.5, 0, .5 }, { -.5, 1, .5 }, { -.5, 1, -.5 } },
    { { .5, 0, -.5 }, { .5, 1, -.5 }, { .5, 1, .5 }, { .5, 0, .5 } },
  }
  local out = { "-0.5 0.5 0 1 -0.5 0.5", "PRECISION S: 1 T: 1",
                "CONTACT POINT X: 0 Y: 0 Z: 0", "END POINT X: 0 Y: 1 Z: 0",
                "HEADING X: 0 Y: 1 Z: 0", "UP X: 0 Y: 0 Z: 1", "SIZE: 1" }
  for k, q in ipairs(faces) do
    out[#out + 1] = "face" .. k
    out[#out + 1] = "TOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0"
    out[#out + 1] = "AL: ~ A: ~ AR: ~"
    out[#out + 1] = "L: ~ R: ~"
    out[#out + 1] = "BL: ~ B: ~ BR: ~"
    for r = 0, 3 do
      local row = {}
      for c = 0, 3 do
        local s, t = c / 3, r / 3
        for j = 1, 3 do
          row[#row + 1] = format("%.6f", (1 - s) * (1 - t) * q[1][j] + s * (1 - t) * q[2][j]
                                         + s * t * q[3][j] + (1 - s) * t * q[4][j])
        end
      end
      out[#out + 1] = concat(row, " ")
    end
  end
  return concat(out, "\n") .. "\n"
end
local cube
local function cubesurface ()
  if cube == nil then cube = core.surface_parse(cubetext(), "cube.s") end
  return cube
end

local function q2 (x) return floor(x * 50 + 0.5) / 50 end     -- 0.02 steps

-- The organ surface of a leaf instance's shape (cached by the quantized parameters).
local function leafsurface (p, width, len, lateral, longitudinal, detail)
  local outline = p:param("outline")
  local ratio = q2(width / len)
  if ratio <= 0 then ratio = 0.02 end
  local key = format("%s|%d|%g|%g|%g", outline and tostring(outline) or p:param("shape"),
                     detail, ratio, q2(lateral), q2(longitudinal))
  local s = leafcache[key]
  if s then return s, key end
  local organ = require "lsys.sketch.organ"
  local o = {
    shape = outline == nil and p:param("shape") or nil, outline = outline,
    curl = q2(longitudinal), name = "leaf", resolution = { 2, 2 },
    precision = { detail, detail + 1 },
    section = lateral ~= 0 and "cup" or nil, depth = lateral ~= 0 and q2(lateral) or nil,
  }
  if outline == nil then
    -- organ.leaf's `width` is the whole width of the length; the shapes' half-width
    -- functions peak at 1/2
    o.width = ratio
  end
  s = organ.leaf(o):surface()
  leafcache[key] = s
  return s, key
end

-- }=========================================================================================

-- {=========================================================================================
-- The writer: module codes, parameters and the owning instance of each module, in three
-- flat lists (rules:build makes the Lstring in C).

local W = {}
W.__index = W

local function newwriter (rules)
  local w = setmetatable({ rules = rules, codes = {}, vals = {}, owner = {}, nc = 0, nv = 0,
                           cur = 0, sym = {}, c0 = {}, c1 = {}, surf = {}, leaves = {},
                           nsurf = 0, spans = {}, post = {}, deformers = {} }, W)
  return w
end

function W:code (name, np)
  local id = self.sym[name]
  if id == nil then
    id = self.rules:symbol(name)
    self.sym[name] = id
  end
  return id * 32 + np
end

function W:op (name, ...)
  local np = select("#", ...)
  local nc = self.nc + 1
  self.nc = nc
  self.codes[nc] = self:code(name, np)
  self.owner[nc] = self.cur
  local vals, nv = self.vals, self.nv
  for k = 1, np do vals[nv + k] = (select(k, ...)) end
  self.nv = nv + np
end

-- The hot writers: a module without parameters, and one with one (codes cached by name).
local function op0 (w, name)
  local c = w.c0[name]
  if c == nil then c = w:code(name, 0) w.c0[name] = c end
  local nc = w.nc + 1
  w.nc = nc
  w.codes[nc] = c
  w.owner[nc] = w.cur
end

local function op1 (w, name, a)
  local c = w.c1[name]
  if c == nil then c = w:code(name, 1) w.c1[name] = c end
  local nc = w.nc + 1
  w.nc = nc
  w.codes[nc] = c
  w.owner[nc] = w.cur
  local nv = w.nv + 1
  w.nv = nv
  w.vals[nv] = a
end

-- A rotation op unless it is a no-op.
local function turn (w, name, a)
  if a > 1e-9 or a < -1e-9 then op1(w, name, a) end
end
function W:turn (name, a) turn(self, name, a) end

-- The surface character of a `~` surface (keys from U+0100 up, clear of the user's).
function W:surface (key, s, entry)
  local c = self.surf[key]
  if c then return c end
  self.nsurf = self.nsurf + 1
  c = utf8.char(0x100 + self.nsurf)
  self.surf[key] = c
  entry.surface = s
  self.surfaces = self.surfaces or {}
  self.surfaces[c] = entry
  return c
end

-- }=========================================================================================

-- {=========================================================================================
-- Moving the turtle. T = { p, H, U } is where the turtle is (as the emitted modules leave it).

-- Turns the turtle from orientation T to (H, U).
local function orient (w, T, H, U)
  local a, b, g = angles(T.H, T.U, H, U)
  turn(w, "/", a)
  turn(w, "&", b)
  turn(w, "/", g)
  T.H, T.U = H, U
end

-- Moves the turtle from T to frame f (position and orientation).
local function moveto (w, T, f)
  local fp, tp = f.p, T.p
  local d1, d2, d3 = fp[1] - tp[1], fp[2] - tp[2], fp[3] - tp[3]
  local len = sqrt(d1 * d1 + d2 * d2 + d3 * d3)
  if len > 1e-12 * max(1, abs(fp[1]) + abs(fp[2]) + abs(fp[3])) then
    local a, b = angles(T.H, T.U, { d1 / len, d2 / len, d3 / len })
    turn(w, "/", a)
    turn(w, "&", b)
    T.H, T.U = rollpitch(T.H, T.U, a, b)
    op1(w, "f", len)
  end
  T.p = f.p
  orient(w, T, f.H, f.U)
end

local function forward (w, T, d, draw)
  if d <= 1e-15 then return end
  op1(w, draw and "F" or "f", d)
  local p, H = T.p, T.H
  T.p = { p[1] + d * H[1], p[2] + d * H[2], p[3] + d * H[3] }
end

-- }=========================================================================================

-- {=========================================================================================
-- Geometry of each kind

local emit      -- emit(w, tree, inst, T)

-- The radius of a stem at u (0 base, 1 tip): `thickness` points {u, factor} if given, else
-- a linear taper from 1 to `tip`.
local function radius (inst, u)
  local p = inst.proto
  local r = X.get(inst, "radius")
  local th = p:param("thickness")
  if th == nil then return r * (1 + (X.get(inst, "tip") - 1) * u) end
  if u <= th[1][1] then return r * th[1][2] end
  for k = 2, #th do
    if u <= th[k][1] then
      local a, b = th[k - 1], th[k]
      local t = (b[1] > a[1]) and (u - a[1]) / (b[1] - a[1]) or 1
      return r * (a[2] + t * (b[2] - a[2]))
    end
  end
  return r * th[#th][2]
end

local PRIMDRAW   -- kind -> function (w, T, inst, wd, h, d)

-- A primitive of size (wd, h, d) on the turtle's frame, base at the turtle; a size that
-- is not what the turtle's primitive draws is made by a scale afterwards (w.post).
local function primitive (w, T, inst, prim, wd, h, d)
  local m0 = w.nc + 1
  local base = { p = T.p, H = T.H, U = T.U, s = 1 }
  local uniform = PRIMDRAW[prim](w, T, inst, wd, h, d)
  if not uniform then
    w.post[#w.post + 1] = { m0 = m0, m1 = w.nc, frame = base,
                            sx = 1, sy = uniform == false and h / wd or 1, sz = d / wd,
                            prim = prim }
  end
end

PRIMDRAW = {
  sphere = function (w, T, _, wd, h, d)
    forward(w, T, wd / 2, false)            -- drawn wd round, then scaled to h and d
    w:op("@O", wd)
    return wd == h and wd == d or false
  end,
  cylinder = function (w, T, _, wd, h, d)
    w:op("#", wd)
    forward(w, T, h, true)
    return wd == d or nil
  end,
  cone = function (w, T, _, wd, h, d)
    w:op("#", wd)
    w:op("@Gs")
    forward(w, T, h, false)
    w:op("#", wd * 1e-3)
    w:op("@Ge", 4)
    return wd == d or nil
  end,
  disc = function (w, _, _, wd, _, d)
    w:op("^", 90)
    w:op("@c", wd)
    w:op("&", 90)
    return wd == d or nil
  end,
  cube = function (w, _, _, wd, h, d)
    local c = w:surface("cube", cubesurface(), {})
    w:op("~" .. c, wd)
    return wd == h and wd == d or false
  end,
  tube = function (w, _, inst, wd)
    if inst and w.area then w:op("@#", 0) end
    w:op("#", wd)
    w:op("@Gc", 4)
    return true
  end,
  area = function (w, _, _, wd)
    w.area = true
    w:op("@#", M.AREA)
    w:op("#", wd)
    w:op("@Gc", 4)
    return true
  end,
}
M.AREA = 63        -- the contour id of the Area primitive's open line

local function setcolor (w, inst, default)
  local c = inst.proto:param("color") or default
  if c then w:op(";", c) end
  local tex = inst.proto:param("texture")
  if tex and tex ~= 0 then w:op("@Tx", tex) end
end

-- Children of a Tree along its stem, in the order of u.
local function branchkids (tree, inst)
  local along, tip = {}, {}
  for _, ci in ipairs(rawget(inst, "children") or along) do
    local c = tree.list[ci]
    if c.link == "branch" and c.u ~= nil then along[#along + 1] = c else tip[#tip + 1] = c end
  end
  sort(along, function (a, b)
    if a.u ~= b.u then return a.u < b.u end
    return a.index < b.index
  end)
  return along, tip
end

-- A Horn's or Tree's stem: the primitive along the stem frames, branches where they grow.
local function stem (w, tree, inst, T)
  local st = inst.stem
  local segs = #st - 1
  local s = inst.frame.s
  local prim = inst.proto:param("primitive")
  local along, tip = branchkids(tree, inst)
  setcolor(w, inst, 1)
  local tube = prim == "tube" or prim == "area"
  if tube then
    if prim == "area" then w.area = true w:op("@#", M.AREA)
    elseif w.area then w:op("@#", 0) end
    w:op("#", 2 * s * radius(inst, 0))
    w:op("@Gs")
  end
  local k = 1
  for j = 1, segs do
    local a, b = st[j], st[j + 1]
    orient(w, T, b.H, b.U)
    local seg = sqrt((b.p[1] - a.p[1]) ^ 2 + (b.p[2] - a.p[2]) ^ 2 + (b.p[3] - a.p[3]) ^ 2)
    local done = 0
    local drawn = prim == "cylinder"
    if drawn then op1(w, "#", 2 * s * radius(inst, (a.u + b.u) / 2)) end
    while along[k] and (along[k].u <= b.u + 1e-12 or j == segs) do
      local c = along[k]
      local x = (c.u - a.u) / (b.u - a.u) * seg
      if x < done then x = done end
      if x > seg then x = seg end
      forward(w, T, x - done, drawn)
      done = x
      local sp, sH, sU = T.p, T.H, T.U
      emit(w, tree, c, T)
      T.p, T.H, T.U = sp, sH, sU
      w.cur = inst.index
      k = k + 1
    end
    forward(w, T, seg - done, drawn)
    T.p = b.p
    if tube then
      op1(w, "#", 2 * s * radius(inst, b.u))
      op1(w, j == segs and "@Ge" or "@Gc", 4)
    elseif prim ~= "none" and not drawn then
      local r = 2 * s * radius(inst, b.u)
      primitive(w, T, inst, prim, r, r, r)
      T.p = b.p
    end
  end
  return tip
end

-- A Revo: a generalized cylinder through the profile {radius, height} (size x: radius,
-- size y: height, times the scale).
local function revo (w, inst, T)
  local prof = inst.proto:param("profile")
  local s, size = inst.frame.s, inst.params.size
  setcolor(w, inst, nil)
  if w.area then w:op("@#", 0) end
  for k, q in ipairs(prof) do
    if k > 1 then forward(w, T, (q[2] - prof[k - 1][2]) * size[2] * s, false) end
    w:op("#", 2 * q[1] * size[1] * s)
    w:op(k == 1 and "@Gs" or k == #prof and "@Ge" or "@Gc", 4)
  end
end

local LEAFPARAMS = { "length", "width", "lateral", "longitudinal" }

-- The module name ("~" and the surface character) of a leaf instance's surface.
local function leafname (w, inst)
  local p = inst.proto
  local len = inst.length or X.get(inst, "length")
  local surf, key = leafsurface(p, X.get(inst, "width"), len, X.get(inst, "lateral"),
                                X.get(inst, "longitudinal"), w.detail)
  local tex = p:param("texture")
  local entry = {}
  if tex and tex ~= 0 then
    entry.texture = tex
    key = key .. "|t" .. tex
  end
  return "~" .. w:surface(key, surf, entry)
end

-- Leaves whose shape parameters are constants or ranges (no function) share the name by
-- prototype and iteration (i of n).
local function leaf (w, inst)
  local p = inst.proto
  local byp = w.leaves[p]
  if byp == nil then
    byp = {}
    for _, k in ipairs(LEAFPARAMS) do if X.calls(p, k) then byp = false end end
    w.leaves[p] = byp
  end
  local name
  if byp then
    local k = inst.n * 16777216 + inst.i
    name = byp[k]
    if name == nil then name = leafname(w, inst) byp[k] = name end
  else
    name = leafname(w, inst)
  end
  op1(w, ";", p:param("color") or 2)
  op1(w, name, (inst.length or X.get(inst, "length")) * inst.frame.s)
end

-- A component given as an L-system's geometry (`geometry` = a model or an Lstring): its
-- modules, as they are, on the instance's frame.
local function geometry (w, g)
  local s = g
  local model = require "lsys.model"
  if model.ismodel(g) then
    w.derived = w.derived or {}
    s = w.derived[g]
    if s == nil then s = g:derive() w.derived[g] = s end
  end
  for i = 1, #s do
    local t = { s:module(i) }
    w:op(t[1], table.unpack(t, 2))
  end
end

emit = function (w, tree, inst, T)
  w.cur = inst.index
  local m0 = w.nc + 1
  op0(w, "[")
  local f = inst.frame
  moveto(w, T, f)
  inst.at = w.nc          -- the turtle stands on the instance's frame after this module
  local kind = inst.kind
  local p = inst.proto
  local kids
  local prim = p:param("primitive")
  if kind == "horn" or kind == "tree" then
    kids = stem(w, tree, inst, T)
  else
    if kind == "leaf" then leaf(w, inst)
    elseif kind == "revo" then revo(w, inst, T)
    end
    local g = p:param("geometry")
    if g ~= nil then geometry(w, g) end
    if prim ~= "none" and kind ~= "horn" and kind ~= "tree" then
      setcolor(w, inst, nil)
      local size = inst.params.size
      local s = f.s
      primitive(w, T, inst, prim, size[1] * s, size[2] * s, size[3] * s)
    end
    local ch = rawget(inst, "children")
    if ch ~= nil then
      kids = {}
      for k, ci in ipairs(ch) do kids[k] = tree.list[ci] end
    end
  end
  if kids ~= nil then
    for _, c in ipairs(kids) do
      local sp, sH, sU = T.p, T.H, T.U
      emit(w, tree, c, T)
      T.p, T.H, T.U = sp, sH, sU
      w.cur = inst.index
    end
  end
  op0(w, "]")
  inst.m0, inst.m1 = m0, w.nc             -- inst.modules = { m0, m1 } (made when read)
  if kind == "ffd" or kind == "hyperpatch" then w.deformers[#w.deformers + 1] = inst end
end

-- }=========================================================================================

-- How finely leaves are drawn by default: each leaf is 2 x 2 bicubic patches of
-- `detail` x (`detail` + 1) quads, 16 triangles at 1 (the model option `detail`).
M.DETAIL = 1

--- Emits the i-tree `tree` (lsys.components.expand) with `rules` (a model's lsys.Rules) and
-- the leaves' `detail` (M.DETAIL):
-- returns { lstring =, owner = (module index -> instance index), surfaces = (view
-- surfaces), post = (scales of primitives), deformers = (FFD and Hyperpatch instances) }.
function M.emit (tree, rules, detail)
  local w = newwriter(rules)
  w.detail = detail or M.DETAIL
  local T = { p = { 0, 0, 0 }, H = { 0, 1, 0 }, U = { 0, 0, -1 } }
  emit(w, tree, tree.list[1], T)
  local s = rules:build(w.codes, w.vals, w.nc)
  return { lstring = s, owner = w.owner, surfaces = w.surfaces or {}, post = w.post,
           deformers = w.deformers, area = w.area }
end

return M
