--- Interactive arrangement of a plant by inverse kinematics (Power et al. 1999, ilsa).
--
--   local a = lsys.arrange(model, lstring [, opts])   -- or the string as text
--   a:select(i, j)                        -- fixed, moved: module indices (or pick tables)
--   a:spherical({0, 0, 1}, 30)            -- or a:disc(angle), a:axis(d),
--                                         -- a:plane(dx, dy, view)
--   a:prune(k)                            -- cut the branch that starts at module k
--   local s = a:lstring()                 -- the arranged string; model:step(s) grows it on
--
-- Arguments are positional, what a call needs first, an optional table of settings last
-- (opts, the plane's view), as Model methods take them. Errors of
-- lsys.arrange begin "lsys.arrange: ", those of a method its name ("select: ...").
--
-- The arrangement lives in the string as joint modules @J(h, u, l) (degrees, turtle.c):
-- right-handed turns about the turtle's H, then U, then L, placed right before the segment
-- they bend. Selecting a branch path puts an @J before each of its segments that has none;
-- a second arrangement finds them there and changes their values, so arranging, growing
-- and arranging again (Power et al. 1999, fig. 10) never piles joints up. Pruning replaces
-- the branch by the marker module @X, which productions can rewrite to regrow
-- (`@X --> [+F A]`); the turtle ignores it.
--
-- Joint stiffness (§3.3) comes from Z(sh, su, sl) where the string has it, else from the
-- branch radii: the turtle widths (radius = width / 2) when the model sets widths, else
-- the da Vinci rule from the trunk radius r0 (a branch with n lateral children gives them
-- radius r / sqrt(n), eq. 6); then s^u = s^l = 2 c_f r^4 / (l_{i-1} + l_i) and
-- s^h = 2 c_t r^4 / (l_{i-1} + l_i), c_f = s0u / r0^4, c_t = s0h / r0^4 (eqs. 4, 5).
-- @module lsys.arrange
local core = require "lsys.core"
local model = require "lsys.model"
local warning = require "lsys.warning"

local type, pairs, ipairs, error, tostring, setmetatable, pcall =
      type, pairs, ipairs, error, tostring, setmetatable, pcall
local math, string, table = math, string, table
local format = string.format
local _ENV = nil

local Arr = {}
Arr.__index = Arr

local SEGMENT = { segment = true, gcyl = true }
local OPTS = { r0 = "number", s0u = "number", s0h = "number", radii = "string",
               wp = "number", wt = "number", we = "number", ws = "number",
               max_iter = "number", view = "table", leaf_length = "number" }

-- Raises "where: msg", blaming the caller `level` levels up (1: fail's caller).
local function fail (where, msg, level) error(where .. ": " .. msg, (level or 1) + 1) end

-- vectors
local function sub (a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
local function add (a, b) return { a[1] + b[1], a[2] + b[2], a[3] + b[3] } end
local function scale (a, k) return { a[1] * k, a[2] * k, a[3] * k } end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function cross (a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end
local function norm (a) return math.sqrt(dot(a, a)) end
local function unit (a)
  local n = norm(a)
  return n > 0 and scale(a, 1 / n) or { 0, 0, 0 }
end

-- Rotates v about the unit axis k by deg degrees (Rodrigues, right-handed).
local function rotate (v, k, deg)
  local r = math.rad(deg)
  local c, s = math.cos(r), math.sin(r)
  local kv, d = cross(k, v), dot(k, v)
  return { v[1] * c + kv[1] * s + k[1] * d * (1 - c),
           v[2] * c + kv[2] * s + k[2] * d * (1 - c),
           v[3] * c + kv[3] * s + k[3] * d * (1 - c) }
end

-- {====================================================================
-- the plant's structure from the turtle records

-- Bracket depth of every module (depth[i] of module i).
local function depths (s)
  local d, out = 0, {}
  for i, name in s:modules() do
    if name == "]" then d = d - 1 end
    out[i] = d
    if name == "[" then d = d + 1 end
  end
  return out
end

-- Rebuilds what depends on the string: the scene, records by module, tree links.
function Arr:_refresh ()
  local s = self.s
  self.scene = self.model:interpret(s, self.view)
  local recs, bymod = {}, {}
  for k, r in self.scene:records() do
    r.index = k
    recs[k] = r
    bymod[r.module] = r
  end
  self.recs, self.bymod = recs, bymod
  local depth = depths(s)
  self.depth = depth
  -- children and axes: a child segment drawn at a deeper bracket level than its parent
  -- starts a lateral branch; otherwise it continues its parent's axis
  for _, r in ipairs(recs) do r.children = {} end
  for _, r in ipairs(recs) do
    local p = r.parent and recs[r.parent]
    if p then
      p.children[#p.children + 1] = r
      r.lateral = depth[r.module] > depth[p.module]
    end
  end
  self:_stiffness()
end

-- Joint stiffness of every segment record (§3.3), as r.stiff = {sh, su, sl}.
function Arr:_stiffness ()
  local o = self.opts
  local r0, s0u, s0h = o.r0 or 1, o.s0u or 1, o.s0h or 1
  local cf, ct = s0u / r0 ^ 4, s0h / r0 ^ 4
  local recs = self.recs
  local widths = o.radii == "width"
  if o.radii == nil then                 -- the model sets widths when they differ
    local w
    for _, r in ipairs(recs) do
      if SEGMENT[r.kind] then
        if w == nil then w = r.w0 elseif r.w0 ~= w then widths = true break end
      end
    end
  end
  self.has_z = false
  -- da Vinci: radius per axis, children of an axis share r^2 / n
  local radius = {}
  for _, r in ipairs(recs) do
    if SEGMENT[r.kind] then
      local p = r.parent and recs[r.parent]
      if p == nil then
        radius[r] = r0
      elseif not r.lateral then
        radius[r] = radius[p] or r0
      end
    end
  end
  -- count the lateral children of each axis (its first segment stands for it)
  local axisof, nlat = {}, {}
  for _, r in ipairs(recs) do
    if SEGMENT[r.kind] then
      local p = r.parent and recs[r.parent]
      axisof[r] = (p == nil or r.lateral) and r or axisof[p] or r
      if p ~= nil and r.lateral then
        local ax = axisof[p] or p
        nlat[ax] = (nlat[ax] or 0) + 1
      end
    end
  end
  for _, r in ipairs(recs) do
    if SEGMENT[r.kind] and radius[r] == nil then
      local p = recs[r.parent]
      local ax = axisof[p] or p
      radius[r] = (radius[p] or r0) / math.sqrt(nlat[ax] or 1)
    end
  end
  for _, r in ipairs(recs) do
    if SEGMENT[r.kind] then
      if r.stiffness then
        r.stiff = { r.stiffness[1], r.stiffness[2], r.stiffness[3] }
        self.has_z = true
      else
        local rad = widths and r.w0 / 2 or radius[r]
        local p = r.parent and recs[r.parent]
        local lp = p and SEGMENT[p.kind] and p.length or r.length
        local den = lp + r.length
        local k = den > 0 and 2 * rad ^ 4 / den or 0
        r.stiff = { ct * k, cf * k, cf * k }
        r.radius = rad
      end
    end
  end
end

-- }====================================================================

--- Starts arranging `s` (an Lstring of `model`, or text that model:lstring reads; default:
-- model:derive()).
-- opts: r0 (trunk radius, 1), s0u and s0h (trunk flexural and torsional stiffness, 1),
-- radii ("width" or "davinci"; default: widths when the model sets them), weights wp, wt,
-- we, ws of eq. (1) (1000, 1, 1, and 0 when the string has Z stiffness, 0.1 otherwise; wp
-- is divided by |v-bar|^2 and the stiffness by its mean along the path, so that the
-- defaults suit plants of any size: the targets are met and the stiffness decides where
-- the path gives),
-- max_iter (200), view (view fields for interpreting), leaf_length (the virtual segment of
-- leaves and flowers; default their size).
local function new (m, s, opts)
  local A = "lsys.arrange"
  if not model.ismodel(m) then fail(A, "a model expected", 3) end
  opts = opts or {}
  if type(opts) ~= "table" then fail(A, "an options table expected", 3) end
  for k, v in pairs(opts) do
    if OPTS[k] == nil then fail(A, format("unknown option '%s'", tostring(k)), 3) end
    if type(v) ~= OPTS[k] then fail(A, format("option '%s' must be a %s", k, OPTS[k]), 3) end
  end
  if opts.radii ~= nil and opts.radii ~= "width" and opts.radii ~= "davinci" then
    fail(A, "option 'radii' must be 'width' or 'davinci'", 3)
  end
  for _, k in ipairs { "r0", "s0u", "s0h" } do
    if opts[k] ~= nil and not (opts[k] > 0) then
      fail(A, format("option '%s' must be > 0", k), 3)
    end
  end
  if type(s) == "string" then
    local ok, r = pcall(m.lstring, m, s)
    if not ok then error(A .. ": " .. r, 3) end
    s = r
  elseif s ~= nil and not model.islstring(s) then
    fail(A, "an Lstring or its text expected", 3)
  end
  local self = setmetatable({ model = m, opts = opts, view = opts.view, undo = {} }, Arr)
  self.s = (s or m:derive()):copy()
  self:_refresh()
  return self
end

-- A record from a module index, a record or a pick table.
function Arr:_record (x, what)
  local i = type(x) == "table" and (x.module or x.index and self.recs[x.index].module) or x
  if type(i) ~= "number" then fail(what, "a module index or a pick expected", 3) end
  local r = self.bymod[i]
  if r == nil then
    fail(what, format("module %d (%s) draws nothing that can be arranged", i,
      i >= 1 and i <= #self.s and self.s:module(i) or "out of range"), 3)
  end
  return r
end

-- Where the @J of a record goes: before its module, or before the '{' of a polygon.
function Arr:_jointpos (r)
  local m = r.module
  if r.kind == "polygon" then
    local d = self.depth[m]
    for k = m, 1, -1 do
      if self.s:module(k) == "{" and self.depth[k] == d then return k end
    end
  end
  return m
end

-- The @J before module position k, or nil.
function Arr:_joint (k)
  if k > 1 and self.s:module(k - 1) == "@J" then return k - 1 end
end

--- Selects the branch path: `fixed` is the segment at whose start the path is held (the
-- fixed point r), `moved` the segment (or leaf, flower) whose end is moved; both module
-- indices or picks (lsys.viewer). `moved` (default `fixed`) must be in the active branch:
-- `fixed` or above it. Returns the number of joints of the path.
function Arr:select (fixed, moved)
  if type(fixed) == "table" and moved == nil and fixed.module == nil and fixed.index == nil
     and (fixed.fixed ~= nil or fixed.moved ~= nil) then        -- the table of 0.1.0
    warning.deprecated("Arrangement:select { fixed =, moved = }",
                       "Arrangement:select(fixed, moved)")
    fixed, moved = fixed.fixed, fixed.moved
  end
  fixed = self:_record(fixed, "select: fixed")
  if not SEGMENT[fixed.kind] then fail("select", "the fixed point must be on a segment", 2) end
  moved = moved == nil and fixed or self:_record(moved, "select: moved")
  -- the path: from moved down to fixed through the parents
  local path, r = {}, moved
  local leaf = not SEGMENT[moved.kind]
  if leaf then r = moved.parent and self.recs[moved.parent] end
  while r ~= nil and r ~= fixed do
    path[#path + 1] = r
    r = r.parent and self.recs[r.parent]
  end
  if r ~= fixed then
    fail("select", format("module %d is not in the active branch of module %d (above it)",
      moved.module, fixed.module), 2)
  end
  path[#path + 1] = fixed
  -- root to tip
  for i = 1, #path // 2 do path[i], path[#path + 1 - i] = path[#path + 1 - i], path[i] end
  if leaf then path = { moved } end   -- one virtual segment at the attachment (§3.2)
  -- joints: an @J before each path segment, added where missing (one rebuild)
  local need = {}
  for _, pr in ipairs(path) do
    local k = self:_jointpos(pr)
    if self:_joint(k) == nil then need[#need + 1] = k end
  end
  local fm, mm = fixed.module, moved.module
  if #need > 0 then
    table.sort(need)
    self.s = self.s:insert(need, self.model:lstring("@J(0,0,0)"))
    local function shift (i)
      local n = 0
      for _, k in ipairs(need) do if k <= i then n = n + 1 end end
      return i + n
    end
    fm, mm = shift(fm), shift(mm)
    self:_refresh()
    return self:select(fm, mm)
  end
  self.fixed, self.moved, self.path, self.leaf = fixed, moved, path, leaf
  self:_chain()
  return #path
end

-- Builds the IK chain of the selected path from the current records.
function Arr:_chain ()
  local joints, jmods = {}, {}
  local path = self.path
  local first = path[1]
  local base
  local parent = first.parent and self.recs[first.parent]
  for i, r in ipairs(path) do
    local k = self:_joint(self:_jointpos(r))
    jmods[i] = k
    local _, h, u, l = self.s:module(k)
    local p0, p1, H = r.p0, r.p1, r.H
    if self.leaf then                      -- a virtual segment along H from the attachment
      local at = parent and parent.p1 or r.p1
      local len = self.opts.leaf_length or math.max(r.w0 or 0, r.length or 0, 1e-3)
      if r.kind == "surface" or r.kind == "polygon" then
        len = self.opts.leaf_length or math.max(norm(sub(r.p1, at)), 1e-3)
      end
      p0, p1 = at, add(at, scale(unit(H), len))
    end
    joints[i] = { p0 = p0, p1 = p1, H = H, U = r.U, alpha = { h, u, l },
                  stiff = r.stiff or { 1, 1, 1 } }
  end
  -- the energy term sees stiffness relative to the path's mean: what matters is which
  -- joints give (eqs. 4, 5 are known up to c_f, c_t), not the plant's absolute size
  local sum, cnt = 0, 0
  for _, j in ipairs(joints) do
    for q = 1, 3 do sum, cnt = sum + j.stiff[q], cnt + 1 end
  end
  local mean = sum / cnt
  if mean > 0 then
    for _, j in ipairs(joints) do
      j.stiff = { j.stiff[1] / mean, j.stiff[2] / mean, j.stiff[3] / mean }
    end
  end
  -- the frame before the first joint: the parent segment's; without one, the first
  -- segment's own (its joint angles are then taken out by lsys_ik_setjoint)
  if parent and SEGMENT[parent.kind] then
    base = { H = parent.H, U = parent.U, p = parent.p1 }
  else
    base = { H = first.H, U = first.U, p = joints[1].p0 }
  end
  self.ik = core.ik_chain { base = base, joints = joints }
  self.jmods = jmods
  self:_tool()
end

-- The original values of a new tool (§3.2): p-bar, s-bar, t-bar, the root r, v-bar.
function Arr:_tool ()
  local p, s, t, pts = self.ik:forward()
  self.bar = { p = p, s = s, t = t, r = pts[1][1], v = sub(p, pts[1][1]) }
end

--- Moves the fixed point (§3.2): "up" along its axis towards the branch end, "down"
-- towards the base, "left" and "right" to the sibling branches. Clears the manipulated
-- point (the path is the fixed segment alone). Returns the new fixed module, or nil
-- when there is nowhere to go.
function Arr:move_fixed (dir)
  local f = self.fixed
  if f == nil then fail("move_fixed", "select a fixed point first", 2) end
  local to
  if dir == "up" then
    for _, c in ipairs(f.children) do
      if SEGMENT[c.kind] and not c.lateral then to = c break end
    end
    if to == nil then
      for _, c in ipairs(f.children) do if SEGMENT[c.kind] then to = c break end end
    end
  elseif dir == "down" then
    to = f.parent and self.recs[f.parent]
    if to and not SEGMENT[to.kind] then to = nil end
  elseif dir == "left" or dir == "right" then
    local p = f.parent and self.recs[f.parent]
    local sib = {}
    for _, c in ipairs(p and p.children or {}) do
      if SEGMENT[c.kind] then sib[#sib + 1] = c end
    end
    for i, c in ipairs(sib) do
      if c == f and #sib > 1 then
        to = sib[(i - 1 + (dir == "right" and 1 or -1)) % #sib + 1]
      end
    end
  else
    fail("move_fixed", "'up', 'down', 'left' or 'right' expected", 2)
  end
  if to == nil then return nil end
  self:select(to.module)
  return self.fixed.module
end

--- The selected path: the module indices of its segments, root first.
function Arr:path_modules ()
  local out = {}
  for i, r in ipairs(self.path or {}) do out[i] = r.module end
  return out
end

--- The active branch: the module indices of every segment from the fixed point up.
function Arr:active_modules ()
  local out = {}
  local function walk (r)
    out[#out + 1] = r.module
    for _, c in ipairs(r.children) do walk(c) end
  end
  if self.fixed then walk(self.fixed) end
  table.sort(out)
  return out
end

-- Solves for the targets and writes the angles into the string; `what` is the dragger.
function Arr:_solve (what, p, s, t)
  if self.ik == nil then fail(what, "select a branch path first", 3) end
  local o = self.opts
  local vlen = math.max(norm(self.bar.v), 1e-9)
  local res = self.ik:solve {
    p = p, s = s, t = t,
    wp = (o.wp or 1000) / (vlen * vlen),    -- positions relative to the path's length
    wt = o.wt or 1, we = o.we or 1, ws = o.ws or (self.has_z and 0 or 0.1),
    max_iter = o.max_iter,
  }
  local ang = self.ik:angles()
  local undo = {}
  for i, k in ipairs(self.jmods) do
    local _, h, u, l = self.s:module(k)
    undo[i] = { k, h, u, l }
    self.s:set(k, ang[i][1], ang[i][2], ang[i][3])
  end
  self.undo[#self.undo + 1] = { joints = undo }
  self.dirty = true
  self.last = res
  return res
end

--- Spherical dragger: turns the path about r by `angle` degrees about `axis` ({x, y, z}),
-- the rotation R: p^ = r + R v-bar, s^ = R s-bar, t^ = R t-bar. Returns the solver's
-- result.
function Arr:spherical (axis, angle)
  if type(axis) == "table" and angle == nil and axis.axis ~= nil then   -- 0.1.0's table
    warning.deprecated("Arrangement:spherical { axis =, angle = }",
                       "Arrangement:spherical(axis, angle)")
    axis, angle = axis.axis, axis.angle
  end
  if type(axis) ~= "table" or type(angle) ~= "number" then
    fail("spherical", "an axis {x, y, z} and an angle in degrees expected", 2)
  end
  local k = unit(axis)
  local b = self.bar or fail("spherical", "select a branch path first", 2)
  return self:_solve("spherical", add(b.r, rotate(b.v, k, angle)), rotate(b.s, k, angle),
                     rotate(b.t, k, angle))
end

--- Disc dragger: twists the path by `angle` degrees about its axis v-bar; p^ = p-bar.
function Arr:disc (angle)
  if type(angle) ~= "number" then fail("disc", "an angle in degrees expected", 2) end
  local b = self.bar or fail("disc", "select a branch path first", 2)
  local k = unit(b.v)
  return self:_solve("disc", b.p, rotate(b.s, k, angle), rotate(b.t, k, angle))
end

--- Axis dragger: moves the end along v-bar by `distance`; the twist stays.
function Arr:axis (distance)
  if type(distance) ~= "number" then fail("axis", "a distance expected", 2) end
  local b = self.bar or fail("axis", "select a branch path first", 2)
  return self:_solve("axis", add(b.p, scale(unit(b.v), distance)), b.s, b.t)
end

--- 2D-plane dragger: moves the end by dx, dy in the view plane: `view` = { right = v,
-- up = v } (world vectors; default the xy plane); the twist stays.
function Arr:plane (dx, dy, view)
  if type(dx) ~= "number" or type(dy) ~= "number" then fail("plane", "dx, dy expected", 2) end
  local b = self.bar or fail("plane", "select a branch path first", 2)
  local right = unit(view and view.right or { 1, 0, 0 })
  local up = unit(view and view.up or { 0, 1, 0 })
  return self:_solve("plane", add(b.p, add(scale(right, dx), scale(up, dy))), b.s, b.t)
end

--- Keeps the current arrangement as the start of the next tool (a new drag).
function Arr:commit ()
  if self.ik then self:_refresh() self:_rechain() end
end

-- The selection again after a refresh (same modules).
function Arr:_rechain ()
  local fm, mm = self.fixed.module, self.moved.module
  self.fixed, self.moved = self.bymod[fm], self.bymod[mm]
  self:select(fm, mm)
end

--- Undoes the last dragger step (or prune).
function Arr:undo_last ()
  local u = table.remove(self.undo)
  if u == nil then return false end
  if u.s then
    self.s = u.s
    self.ik, self.path, self.fixed, self.moved, self.bar = nil, nil, nil, nil, nil
    self:_refresh()
    return true
  end
  for i = #u.joints, 1, -1 do
    local j = u.joints[i]
    self.s:set(j[1], j[2], j[3], j[4])
  end
  if self.ik then
    local ang = {}
    for i, j in ipairs(u.joints) do ang[i] = { j[2], j[3], j[4] } end
    self.ik:set_angles(ang)
  end
  self.dirty = true
  return true
end

--- Prunes the branch that starts at module `k` (a segment: it and everything drawn after
-- it up to the end of its branch), leaving the marker @X in its place.
function Arr:prune (x)
  local r = self:_record(x, "prune")
  local s, d = self.s, self.depth
  local a = self:_joint(self:_jointpos(r)) or self:_jointpos(r)
  local b = #s
  for k = r.module + 1, #s do
    if d[k] < d[r.module] then b = k - 1 break end
  end
  self.undo[#self.undo + 1] = { s = s }
  local left = a > 1 and s:sub(1, a - 1) or nil
  local right = b < #s and s:sub(b + 1, #s) or nil
  local mark = self.model:lstring("@X")
  local out = mark
  if left then out = left .. out end
  if right then out = out .. right end
  self.s = out
  self.ik, self.path, self.fixed, self.moved, self.bar = nil, nil, nil, nil, nil
  self:_refresh()
  return b - a + 1
end

--- The arranged string (a copy: arranging on does not change it).
function Arr:lstring ()
  return self.s:copy()
end

--- The scene of the arranged string (interpreted again when it changed).
function Arr:interpret ()
  if self.dirty then
    self.scene = self.model:interpret(self.s, self.view)
    self.dirty = false
  end
  return self.scene
end

--- The stiffness {sh, su, sl} of the joint before the segment drawn by module `i`.
function Arr:stiffness (i)
  local r = self:_record(i, "stiffness")
  return r.stiff and { r.stiff[1], r.stiff[2], r.stiff[3] }
end

--- The radius the stiffness of module `i`'s segment was computed with.
function Arr:radius (i)
  return self:_record(i, "radius").radius
end

-- the vector helpers, for the window's tools (lsys.arrange_ui)
local vec = { sub = sub, add = add, scale = scale, dot = dot, cross = cross, norm = norm }

return setmetatable({ new = new, Arrangement = Arr, vec = vec }, { __call = function (_, ...)
  return new(...)
end })
