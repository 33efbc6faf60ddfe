--- The geometry of an i-tree (Lintermann and Deussen 1999, section "A geometry
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
local C = require "lsys.components.proto"
local X = require "lsys.components.expand"
local core = require "lsys.core"
local model = require "lsys.model"

local ipairs, setmetatable, rawget, tostring, require, pcall, error, type =
      ipairs, setmetatable, rawget, tostring, require, pcall, error, type
local math, string, table, utf8 = math, string, table, utf8
local format, concat, sort = string.format, table.concat, table.sort
local floor, max, huge, mtype, abs = math.floor, math.max, math.huge, math.type, math.abs
local _ENV = nil

local M = {}

-- {=========================================================================================
-- Shared surfaces: leaves by shape, and the unit cube.

local leafcache = setmetatable({}, { __mode = "v" })   -- key -> organ surface

-- A cpfg surface file of flat quads (each a bicubic patch whose control points lie on the
-- bilinear quad): the cube primitive, base at the contact point, 1 wide, high and deep. Its
-- end point is its base too: the turtle stays where the emitter (which places the children
-- from the base) believes it is.
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
                "CONTACT POINT X: 0 Y: 0 Z: 0", "END POINT X: 0 Y: 0 Z: 0",
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
-- The writer: a C writer (core.cwriter, compgeo.c) makes the Lstring, the owner of each
-- module and each instance's module range, and keeps the turtle's place; here the module
-- codes by name and what the scene's finish needs (surfaces, scales, deformers).

local W = {}
W.__index = W

-- The plant's size for the leaves' automatic detail: the largest side of the box around
-- at most 257 of its frames' positions, taken evenly (the first and the last among them).
local function extent (frames)
  local n = frames:count()
  local lo, hi = { huge, huge, huge }, { -huge, -huge, -huge }
  local step = n > 256 and n / 256 or 1
  local k = 1
  while k <= n + 0.5 do
    local p = frames:get(floor(k + 0.5)).p
    for j = 1, 3 do
      if p[j] < lo[j] then lo[j] = p[j] end
      if p[j] > hi[j] then hi[j] = p[j] end
    end
    k = k + step
  end
  local e = 0
  for j = 1, 3 do if hi[j] - lo[j] > e then e = hi[j] - lo[j] end end
  return e
end

local function newwriter (rules, tree, detail, rename)
  local wr = core.cwriter(rules, tree.frames)
  return setmetatable({ wr = wr, frames = tree.frames, detail = detail, rename = rename,
                        extent = detail == nil and extent(tree.frames) or nil,
                        sym = {}, surf = {}, leaves = {}, leafq = {}, nsurf = 0, post = {},
                        deformers = {} }, W)
end

-- The symbol id of a module name (renamed first when the caller renames).
function W:code (name)
  local id = self.sym[name]
  if id == nil then
    local n2 = self.rename and self.rename(name) or name
    id = self.wr:symbol(n2)
    self.sym[name] = id
  end
  return id
end

-- Texture index tex of instance inst, which the view must have (its ntextures).
function W:texture (inst, tex)
  if tex > self.ntextures then
    X.fail(inst, "texture", "%d, but the view has %d textures (view.textures)", tex,
           self.ntextures)
  end
  return tex
end

function W:op (name, ...)
  self.wr:op(self:code(name), ...)
end

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
-- Geometry of each kind

local emit      -- emit(w, tree, inst)

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
-- is not what the turtle's primitive draws is made by a scale afterwards (w.post): the
-- primitive drawn wd wide, scaled by h / wd and d / wd. When those are not finite (a width
-- of 0, flat across, or far smaller than the rest) it is drawn as wide as its largest size
-- instead, and every scale is at most 1. The point sets have only a width.
local function primitive (w, inst, prim, wd, h, d)
  local m0 = w.wr:count() + 1
  local p, H, U = w.wr:turtle()
  local base = { p = p, H = H, U = U, s = 1 }
  local r = wd
  if prim ~= "tube" and prim ~= "area" and not (h / wd < huge and d / wd < huge) then
    r = max(wd, h, d)
  end
  local uniform = PRIMDRAW[prim](w, inst, r, h, d)
  if not uniform or r ~= wd then      -- r is 0 only when all three are: then uniform
    w.post[#w.post + 1] = { m0 = m0, m1 = w.wr:count(), frame = base,
                            sx = wd / r, sy = uniform == false and h / r or 1, sz = d / r,
                            prim = prim }
  end
end

PRIMDRAW = {
  sphere = function (w, _, wd, h, d)
    w.wr:forward(wd / 2, false)            -- drawn wd round, then scaled to h and d
    w:op("@O", wd)
    return wd == h and wd == d or false
  end,
  cylinder = function (w, _, wd, h, d)
    w:op("#", wd)
    w.wr:forward(h, true)
    return wd == d or nil
  end,
  cone = function (w, _, wd, h, d)
    w:op("#", wd)
    w:op("@Gs")
    w.wr:forward(h, false)
    w:op("#", wd * 1e-3)
    w:op("@Ge", 4)
    return wd == d or nil
  end,
  disc = function (w, _, wd, _, d)
    w:op("&", 90)                          -- the disc faces H (turned to the frame's -z)
    w:op("@c", wd)
    w:op("^", 90)
    return wd == d or nil
  end,
  cube = function (w, _, wd, h, d)
    local c = w:surface("cube", cubesurface(), {})
    w:op("~" .. c, wd)
    return wd == h and wd == d or false
  end,
  tube = function (w, inst, wd)
    if inst and w.area then w:op("@#", 0) end
    w:op("#", wd)
    w:op("@Gc", 4)
    return true
  end,
  area = function (w, _, wd)
    w.area = true
    w:op("@#", M.AREA)
    w:op("#", wd)
    w:op("@Gc", 4)
    return true
  end,
}
M.AREA = 63        -- the contour id of the Area primitive's open line

-- The turtle keeps its texture into a branch: an instance without a texture of its own
-- under a textured one (a leaf on a bark-textured twig) turns it off (w.tex: the texture
-- the turtle has where the instance is drawn).
local function setcolor (w, inst, default)
  local c = inst.proto:param("color") or default
  if c then w:op(";", c) end
  local tex = inst.proto:param("texture")
  if tex and tex ~= 0 then
    w:op("@Tx", w:texture(inst, tex))
    w.tex = tex
  elseif (w.tex or 0) ~= 0 then
    w:op("@Tx", 0)
    w.tex = 0
  end
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
local function stem (w, tree, inst)
  local wr, st, ns = w.wr, inst.st, inst.ns
  local segs = ns - 1
  local s = w.frames:scale(inst.fi)
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
  local drawn = prim == "cylinder"
  local width, gc, ge = w:code("#"), w:code("@Gc"), w:code("@Ge")
  local k = 1
  for j = 1, segs do
    local seg, au, bu = wr:segment(st + j)       -- turned to the piece's end frame
    local done = 0
    if drawn then wr:op(width, 2 * s * radius(inst, (au + bu) / 2)) end
    while along[k] and (along[k].u <= bu + 1e-12 or j == segs) do
      local c = along[k]
      local x = (c.u - au) / (bu - au) * seg
      if x < done then x = done end
      if x > seg then x = seg end
      wr:forward(x - done, drawn)
      done = x
      emit(w, tree, c)
      k = k + 1
    end
    wr:forward(seg - done, drawn)
    wr:setpos(st + j)
    if tube then
      wr:op(width, 2 * s * radius(inst, bu))
      wr:op(j == segs and ge or gc, 4)
    elseif prim ~= "none" and not drawn then
      local r = 2 * s * radius(inst, bu)
      primitive(w, inst, prim, r, r, r)
      wr:setpos(st + j)
    end
  end
  return tip
end

-- A Revo: a generalized cylinder through the profile {radius, height} (size x: radius,
-- size y: height, times the scale).
local function revo (w, inst)
  local prof = inst.proto:param("profile")
  local s, size = w.frames:scale(inst.fi), inst.params.size
  setcolor(w, inst, nil)
  if w.area then w:op("@#", 0) end
  for k, q in ipairs(prof) do
    if k > 1 then w.wr:forward((q[2] - prof[k - 1][2]) * size[2] * s, false) end
    w:op("#", 2 * q[1] * size[1] * s)
    w:op(k == 1 and "@Gs" or k == #prof and "@Ge" or "@Gc", 4)
  end
end

local LEAFPARAMS = { "length", "width", "lateral", "longitudinal" }

-- The module name ("~" and the surface character) of a leaf instance's surface.
-- `len`, `width`, `lat`, `lon`: the values when the caller has them (a parameter function
-- is called once per instance: it may draw random numbers).
-- The leaves' automatic detail (the model option `detail` not given): by the leaf's drawn
-- length relative to the plant's size (M.SIZES: the relative lengths from which each
-- detail after 1 is used), one more for a leaf bent across or along (|lateral| +
-- |longitudinal| at least M.BENT) once it is drawn finer than 1, at most #M.SIZES + 1.
local function autodetail (w, len, lat, lon)
  local r = w.extent > 0 and len / w.extent or 1
  local d = 1
  for k, v in ipairs(M.SIZES) do if r >= v then d = k + 1 end end
  if d > 1 and d <= #M.SIZES and abs(lat) + abs(lon) >= M.BENT then d = d + 1 end
  return d
end

local function leafname (w, inst, len, width, lat, lon, detail)
  local p = inst.proto
  len = len or inst.length or X.get(inst, "length")
  width = width or X.get(inst, "width")
  if p:param("outline") == nil and not (width / len <= C.MAX_LEAF_RATIO) then
    X.fail(inst, "width", "gave %s, more than %d times the length (%s)", C.show(width),
           C.MAX_LEAF_RATIO, C.show(len))
  end
  local surf, key = leafsurface(p, width, len, lat or X.get(inst, "lateral"),
                                lon or X.get(inst, "longitudinal"), detail)
  local tex = p:param("texture")
  local entry = {}
  if tex and tex ~= 0 then
    entry.texture = w:texture(inst, tex)
    key = key .. "|t" .. tex
  end
  return "~" .. w:surface(key, surf, entry)
end

-- Leaves whose shape parameters are constants or ranges (no function) share the surface by
-- prototype and iteration (i of n); the symbol id of the surface module is kept with it.
local function leaf (w, inst)
  local p = inst.proto
  local byp = w.leaves[p]
  if byp == nil then
    byp = {}
    for _, k in ipairs(LEAFPARAMS) do if X.calls(p, k) then byp = false end end
    w.leaves[p] = byp
  end
  local code
  local s = w.frames:scale(inst.fi)
  local detail = w.detail
  if byp then
    if detail == nil then    -- constants: read in any order; most leaves of a tree are small
      local len = (inst.length or X.get(inst, "length")) * s
      detail = len < w.small and 1 or
               autodetail(w, len, X.get(inst, "lateral"), X.get(inst, "longitudinal"))
    end
    local k = (inst.n * 16777216 + inst.i) * 32 + detail
    code = byp[k]
    if code == nil then
      code = w:code(leafname(w, inst, nil, nil, nil, nil, detail))
      byp[k] = code
    end
  else
    -- a function among the shape's parameters: the surface is still one of those of the
    -- quantized numbers (leafsurface), kept by them for this prototype
    local byq = w.leafq[p]
    if byq == nil then byq = {} w.leafq[p] = byq end
    local len = inst.length or X.get(inst, "length")
    local width = X.get(inst, "width")
    local lat, lon = X.get(inst, "lateral"), X.get(inst, "longitudinal")
    if detail == nil then detail = len * s < w.small and 1 or autodetail(w, len * s, lat, lon) end
    local k = ((floor(width / len * 50 + 0.5) * 1001 + floor(lat * 50 + 0.5) + 500) * 1001 +
               floor(lon * 50 + 0.5) + 500) * 32 + detail
    code = k == k and byq[k] or nil
    if code == nil or p:param("outline") == nil and not (width / len <= C.MAX_LEAF_RATIO) then
      -- raises on a bad width
      code = w:code(leafname(w, inst, len, width, lat, lon, detail))
      if k == k then byq[k] = code end
    end
  end
  local wr = w.wr
  wr:op(w:code(";"), p:param("color") or 2)
  local tex = p:param("texture")
  if (tex or 0) == 0 and (w.tex or 0) ~= 0 then      -- (a textured leaf's surface has its own)
    w:op("@Tx", 0)
    w.tex = 0
  end
  wr:op(code, (inst.length or X.get(inst, "length")) * s)
end

-- A component given as an L-system's geometry (`geometry` = a model or an Lstring): its
-- modules, as they are, on the instance's frame, in a branch of their own so that what
-- follows (a primitive, the children) starts from the frame again.
local function geometry (w, g)
  local s = g
  if model.ismodel(g) then
    w.derived = w.derived or {}
    s = w.derived[g]
    if s == nil then s = g:derive() w.derived[g] = s end
  end
  w:op("[")
  for i = 1, #s do
    local t = { s:module(i) }
    w:op(t[1], table.unpack(t, 2))
  end
  w:op("]")
end

emit = function (w, tree, inst)
  local wr = w.wr
  local outer, outertex = w.inst, w.tex
  w.inst = inst
  wr:open(inst.index, inst.fi)    -- `[` and the move to the instance's frame
  local kind = inst.kind
  local p = inst.proto
  local kids
  if kind == "horn" or kind == "tree" then
    kids = stem(w, tree, inst)
  else
    if kind == "leaf" then leaf(w, inst)
    elseif kind == "revo" then revo(w, inst)
    end
    local g = p:param("geometry")
    if g ~= nil then geometry(w, g) end
    local prim = p:param("primitive")
    if prim ~= "none" then
      setcolor(w, inst, nil)
      local size = inst.params.size
      local s = w.frames:scale(inst.fi)
      primitive(w, inst, prim, size[1] * s, size[2] * s, size[3] * s)
    end
    local ch = rawget(inst, "children")
    if ch ~= nil then
      local list = tree.list
      for _, ci in ipairs(ch) do emit(w, tree, list[ci]) end
    end
  end
  if kids ~= nil then
    for _, c in ipairs(kids) do emit(w, tree, c) end
  end
  wr:close()                      -- `]`: the turtle as its parent left it
  if kind == "ffd" or kind == "hyperpatch" then w.deformers[#w.deformers + 1] = inst end
  w.inst, w.tex = outer, outertex
end

-- The writer refuses numbers that are not finite: the lengths and widths that finite
-- parameters made too large (scales multiplied down the graph, a length times a scale).
-- Its error (an argument error of the writer's) is told as the instance being emitted's.
local function emitall (w, tree)
  local ok, err = pcall(emit, w, tree, tree.list[1])
  if ok then return end
  local inst = w.inst
  if inst ~= nil and type(err) == "string" and err:find("not a finite number", 1, true) then
    error(format("lsys.components: %s (at %s): its geometry is not finite (a length, " ..
                 "radius or size too large for its scale)", C.who(inst.proto), inst.path), 0)
  end
  error(err, 0)
end

-- }=========================================================================================

-- How finely leaves are drawn: each leaf is 2 x 2 bicubic patches of `detail` x
-- (`detail` + 1) quads, 8 d (d + 1) triangles at detail d (16 at 1, 48, 96, 160 at 4). The
-- model option `detail` gives every leaf the same; without it each leaf's is chosen by
-- autodetail from M.SIZES and M.BENT, so that the many small leaves of a tree stay at 1 and
-- a leaf drawn large (a fifth of the plant) is smooth.
M.SIZES = { 0.06, 0.12, 0.2 }
M.BENT = 0.2

--- Emits the i-tree `tree` (lsys.components.expand) with `rules` (a model's lsys.Rules),
-- the leaves' `detail` (nil: each leaf's own, autodetail), `rename` (nil, or a function
-- that renames a module name before it is interned: lsys.components.mix gives each plant's
-- surfaces their own characters) and `ntextures` (how many textures the view has; 0 when
-- nil). Returns
-- { lstring =, owner = (module index -> instance index), surfaces = (view surfaces),
-- post = (scales of primitives), deformers = (FFD and Hyperpatch instances, deepest
-- first), area = (an Area primitive was used) }; the instances' module ranges (inst.m0,
-- m1, at, modules) are this emission's from now on.
function M.emit (tree, rules, detail, rename, ntextures)
  local w = newwriter(rules, tree, detail, rename)
  w.ntextures = ntextures or 0
  if detail == nil then w.small = M.SIZES[1] * w.extent end    -- drawn at 1 below it
  emitall(w, tree)
  local wr = w.wr
  tree.writer = wr
  local owner = setmetatable({}, {
    __index = function (_, k) if mtype(k) == "integer" then return wr:owner(k) end end,
    __len = function () return wr:count() end,
  })
  return { lstring = wr:lstring(), owner = owner, surfaces = w.surfaces or {}, post = w.post,
           deformers = w.deformers, area = w.area }
end

return M
