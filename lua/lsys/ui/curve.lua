--- The curve editor pane of the viewer's editing column: drag the control points of a
-- model's positional functions (lsys.Func, cpfg's .func and .fset files), of the contours
-- of its generalized cylinders (lsys.Contour, .con files) and see the control nets of its
-- bicubic surfaces (lsys.Surface, .s files). vlab has one editor per kind (funcedit,
-- cuspy); here one pane holds every curve of a model, a row of names at the top to switch.
--
-- The pane obeys the pane interface of the editing column (`new`, then `draw`, `pointer`,
-- `key`, `status`, `save`) and is driven in its canvas's own pixels, so it is tested
-- without a window: `pane:to_pixels(i)` says where control point i is drawn.
-- @module lsys.ui.curve
local core = require "lsys.core"
local func = require "lsys.func"
local number = require("lsys.util.text").number
local view = require "lsys.view"

local type, ipairs, pairs, next, error, tostring, pcall, setmetatable, getmetatable =
      type, ipairs, pairs, next, error, tostring, pcall, setmetatable, getmetatable
local math, string, table = math, string, table
local format, concat, insert, remove = string.format, table.concat, table.insert, table.remove
local floor, min, max, abs, huge = math.floor, math.min, math.max, math.abs, math.huge
local _ENV = nil

local M = {}

M.PICK_RADIUS = 10       -- pixels: how near a press must be to take a point or the curve
M.SAMPLES = 200          -- points of a drawn curve
M.WIDTH, M.HEIGHT = 420, 700   -- the canvas size assumed before the first draw
M.MIN_POINTS = { func = 4, closed = 3, open = 4 }
M.UNDO_LIMIT = 100       -- edits kept for Ctrl+Z

local TAB_H, HEAD_H, FOOT_H = 32, 28, 56
local PAD_L, PAD_R, PAD_T, PAD_B = 52, 14, 10, 26

local WHITE, BLACK = { 1, 1, 1, 1 }, { 0, 0, 0, 1 }
local GREY, LIGHT = { 0.55, 0.55, 0.55, 1 }, { 0.88, 0.88, 0.88, 1 }
local CURVE, POINT = { 0.1, 0.3, 0.85, 1 }, { 0.15, 0.15, 0.15, 1 }
local SELECTED, NET = { 0.9, 0.15, 0.1, 1 }, { 0.3, 0.65, 0.3, 1 }

M.HELP = [[
curve editor: [ ] or Tab (the names at the top): the next curve
left drag a point: move it (a function's end points keep x = 0 and x = 1)
left click on the curve, or Shift+click anywhere: add a point there
right click a point, or Delete / Backspace: remove the selected point
Left / Right: select the point before / after   Up / Down: nudge it
F: fit the view   Ctrl+Z: undo   Ctrl+S: save the edited curves into their files
a surface: drag a point in the front view (x, y) or the side view (z, y); the points
at the same place (shared edges, collapsed corners) move with it]]

-- {=========================================================================================
-- Targets

-- The type name of a userdata made by lsys.core ("lsys.Contour", ...), else nil.
local function udname (x)
  if type(x) ~= "userdata" then return nil end
  local mt = getmetatable(x)
  return type(mt) == "table" and mt.__name or nil
end

local KIND_TYPE = { func = "lsys.Func", contour = "lsys.Contour", surface = "lsys.Surface" }

local function copy (pts)
  local out = {}
  for i, p in ipairs(pts) do out[i] = { p[1], p[2], p[3] } end
  return out
end

--- The control points of a Func, Contour or Surface (16 per patch, patch after patch), as
-- lists of numbers.
function M.points (o)
  if udname(o) ~= "lsys.Surface" then return o:points() end
  local pts = {}
  for p = 1, o:info().patches do
    for k, q in ipairs(o:patch(p)) do pts[16 * (p - 1) + k] = q end
  end
  return pts
end

-- The working state of one target: its kind, names, object, file and the points edited.
local function entry (t, what)
  local e
  if func.isfunc(t) then
    e = { kind = "func", name = t:name(), object = t }
  elseif udname(t) == "lsys.Contour" then
    e = { kind = "contour", name = "contour", object = t }
  elseif udname(t) == "lsys.Surface" then
    e = { kind = "surface", name = "surface", object = t }
  elseif type(t) == "table" and (t.kind == "curve" or t.kind == nil and t.func ~= nil) then
    if not func.isfunc(t.func) then
      error(format("%s: a curve item's 'func' must be an lsys.Func, got %s", what,
                   udname(t.func) or type(t.func)), 0)
    end
    e = { kind = "func", name = t.name, label = t.label, object = t.func, set = t.set }
  elseif type(t) == "table" and KIND_TYPE[t.kind] then
    if udname(t.object) ~= KIND_TYPE[t.kind] then
      error(format("%s: a %s target's 'object' must be an %s, got %s", what, t.kind,
                   KIND_TYPE[t.kind], udname(t.object) or type(t.object)), 0)
    end
    if t.file ~= nil and type(t.file) ~= "string" then
      error(format("%s: 'file' must be a path or nil, got %s", what, type(t.file)), 0)
    end
    e = { kind = t.kind, name = t.name, label = t.label, object = t.object, file = t.file,
          set = t.set, id = t.id }
  elseif type(t) == "table" and t.kind ~= nil then
    error(format("%s: unknown kind '%s' (func, contour, surface, curve)", what,
                 tostring(t.kind)), 0)
  else
    error(format("%s: an lsys.Func, lsys.Contour, lsys.Surface, a curve item or a target "
                 .. "table expected, got %s", what, udname(t) or type(t)), 0)
  end
  if e.set ~= nil and type(e.set) ~= "function" then
    error(format("%s: 'set' must be a function, got %s", what, type(e.set)), 0)
  end
  if e.name == nil then e.name = e.kind end
  if type(e.name) ~= "string" then
    error(format("%s: 'name' must be a string, got %s", what, type(e.name)), 0)
  end
  local o = e.object
  e.pts = M.points(o)
  if e.kind == "func" then
    e.fname, e.samples, e.approx = o:name(), o:samples(), o:approx()
  elseif e.kind == "contour" then
    e.closed, e.dim = o:closed(), o:dim()
  end
  return e
end

--- The editable curves of a model: its positional functions (Model:functions, and the
-- lsys.Funcs its env holds: a sketch's), its view's contours and surfaces; each { kind =
-- "func" | "contour" | "surface", name =, id =, object =, file = (the path it was read
-- from, or nil), set = function (obj) that puts an edited object into the model }. The
-- pane calls `set` after every edit, so the model's next derivation and interpretation
-- use the edit.
function M.targets (m)
  if type(m) ~= "table" or type(m.set_func) ~= "function" then
    error(format("lsys.ui.curve.targets: a model expected, got %s", type(m)), 2)
  end
  local out = {}
  local seen = {}
  for _, f in ipairs(m:functions()) do
    local id = f.id
    seen[f.func] = true
    out[#out + 1] = { kind = "func", name = f.name, id = id, object = f.func, file = f.file,
                      set = function (g) m:set_func(id, g) end }
  end
  -- functions the rules read as names of env (a sketch's model: lsys.sketch derives them
  -- from the strokes); edited in env, the next step's rules bind the new one; no file
  local names = {}
  for k, x in pairs(type(m.env) == "table" and m.env or {}) do
    if type(k) == "string" and func.isfunc(x) and not seen[x] then names[#names + 1] = k end
  end
  table.sort(names)
  for _, k in ipairs(names) do
    out[#out + 1] = { kind = "func", name = k, object = m.env[k],
                      set = function (g) m.env[k] = g end }
  end
  if type(m.view) ~= "table" then return out end
  local nv = view.normalize(m.view, "lsys.ui.curve.targets")
  local function path (rel)
    if type(rel) ~= "string" then return nil end
    local p = view.resolve(nv.dir, rel)
    if core.filestamp(p) == nil and core.filestamp(rel) ~= nil then p = rel end
    return p
  end
  local ids = {}
  for id in pairs(nv.contours) do ids[#ids + 1] = id end
  table.sort(ids)
  for _, id in ipairs(ids) do
    local raw = m.view.contours and m.view.contours[id]
    out[#out + 1] = { kind = "contour", name = format("contour %d", id), id = id,
                      object = nv.contours[id], file = path(raw),
                      set = function (c)
                        local t = {}
                        for k, x in pairs(m.view.contours or {}) do t[k] = x end
                        t[id] = c
                        m.view.contours = t
                      end }
  end
  local keys = {}
  for k in pairs(nv.surfaces) do keys[#keys + 1] = k end
  table.sort(keys)
  for _, k in ipairs(keys) do
    local raw = m.view.surfaces and m.view.surfaces[k]
    local file = type(raw) == "string" and raw or type(raw) == "table" and raw.file
    out[#out + 1] = { kind = "surface", name = "surface " .. k, id = k,
                      object = nv.surfaces[k].surface, file = path(file),
                      set = function (s)
                        local t = {}
                        for key, x in pairs(m.view.surfaces) do t[key] = x end
                        local old = t[k]
                        if type(old) == "table" and getmetatable(old) == nil then
                          local sp = {}             -- scale, texture, precision stay
                          for key, x in pairs(old) do sp[key] = x end
                          sp.surface, sp.file = s, nil
                          t[k] = sp
                        else
                          t[k] = s
                        end
                        m.view.surfaces = t
                      end }
  end
  return out
end

-- }=========================================================================================

-- {=========================================================================================
-- The contour file writer

--- The text of contour `c` in cpfg's contour format (the cpfg guide, Appendix B.1): a line
-- "N dim open|closed", then N lines of dim numbers, each in a form that reads back to
-- the same double (lsys.util.text.number).
function M.contour_text (c)
  if udname(c) ~= "lsys.Contour" then
    error(format("lsys.ui.curve.contour_text: an lsys.Contour expected, got %s",
                 udname(c) or type(c)), 2)
  end
  local pts, dim = c:points(), c:dim()
  local lines = { format("%d %d %s", #pts, dim, c:closed() and "closed" or "open") }
  for i, p in ipairs(pts) do
    local t = {}
    for k = 1, dim do t[k] = number(p[k]) end
    lines[i + 1] = concat(t, " ")
  end
  return concat(lines, "\n") .. "\n"
end

--- Writes contour `c` to `path` as contour_text gives it, atomically (the file is replaced
-- only once everything was written).
function M.save_contour (c, path)
  if udname(c) ~= "lsys.Contour" then
    error(format("lsys.ui.curve.save_contour: an lsys.Contour expected, got %s",
                 udname(c) or type(c)), 2)
  end
  if type(path) ~= "string" then error("lsys.ui.curve.save_contour: a file name expected", 2) end
  local ok, err = pcall(core.write_file, path, M.contour_text(c))
  if not ok then error("lsys.ui.curve.save_contour: " .. tostring(err), 0) end
end

-- }=========================================================================================

-- {=========================================================================================
-- The pane: geometry

local Pane = {}
Pane.__index = Pane

--- A curve editor pane on `target`: an lsys.Func, lsys.Contour or lsys.Surface, a curve item
-- { name =, label =, func = lsys.Func, set = function (f) }, a target as `targets` gives
-- them, or a list of these. opts: `on_change` (called as on_change(kind, name, object)
-- after every edit that changes the plant, once the target's own `set` was called),
-- `width`, `height` (the canvas size until the first draw). Raises for a bad target.
function M.new (target, opts)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.ui.curve.new: opts must be a table", 2) end
  for k in pairs(opts) do
    if k ~= "on_change" and k ~= "width" and k ~= "height" then
      error(format("lsys.ui.curve.new: unknown option '%s'", tostring(k)), 2)
    end
  end
  if opts.on_change ~= nil and type(opts.on_change) ~= "function" then
    error("lsys.ui.curve.new: 'on_change' must be a function", 2)
  end
  for _, k in ipairs { "width", "height" } do
    if opts[k] ~= nil and not (type(opts[k]) == "number" and opts[k] >= 1) then
      error(format("lsys.ui.curve.new: '%s' must be a number >= 1", k), 2)
    end
  end
  if type(target) == "table" and getmetatable(target) == nil and next(target) == nil then
    error("lsys.ui.curve.new: no curves to edit (an empty list)", 2)
  end
  local list = target
  if type(target) ~= "table" or target.kind ~= nil or target.func ~= nil
     or target[1] == nil then
    list = { target }
  end
  local entries = {}
  for i, t in ipairs(list) do
    local ok, e = pcall(entry, t, #list > 1 and format("target %d", i) or "target")
    if not ok then error("lsys.ui.curve.new: " .. tostring(e), 2) end
    entries[i] = e
  end
  if #entries == 0 then error("lsys.ui.curve.new: no curves to edit", 2) end
  local self = setmetatable({
    name = "curves", help = M.HELP, entries = entries, cur = 1,
    on_change = opts.on_change, w = opts.width or M.WIDTH, h = opts.height or M.HEIGHT,
    drag = nil, selected = nil, msg = nil, tabs = {}, undo = {},
  }, Pane)
  for _, e in ipairs(entries) do self:fit(e) end
  return self
end

--- The target shown: the entry { kind, name, object, file, pts, ... }.
function Pane:current () return self.entries[self.cur] end

--- Shows `target` (what `new` takes: a form's curve item, a Func, ...), added to the
-- curves, or in place of the one of the same kind and name; the host calls it when a
-- form's curve item is clicked.
function Pane:edit (target)
  local ok, e = pcall(entry, target, "target")
  if not ok then error("lsys.ui.curve.edit: " .. tostring(e), 2) end
  local k = #self.entries + 1
  for i, x in ipairs(self.entries) do
    if x.kind == e.kind and x.name == e.name then k = i end
  end
  self.entries[k] = e
  self:fit(e)
  self.cur, self.selected, self.drag = k, nil, nil
end

--- Points the curves at model m (a new model made from the same files: a vlab panel's
-- reload), by kind and name; the curves edited so far go into it.
function Pane:retarget (m)
  local by = {}
  for _, t in ipairs(M.targets(m)) do by[t.kind .. "\0" .. t.name] = t end
  for _, e in ipairs(self.entries) do
    local t = by[e.kind .. "\0" .. tostring(e.name)]
    if t ~= nil then
      e.set = t.set
      if e.dirty then t.set(e.object) end
    end
  end
end

-- The curve of entry e as a polyline in data coordinates.
local function curve (e)
  local out, n = {}, M.SAMPLES
  if e.kind == "func" then
    local f = e.object
    for i = 0, n do out[i + 1] = { i / n, f(i / n) } end
  elseif e.kind == "contour" then
    local pts = copy(e.pts)
    if e.closed then for k = 1, 3 do pts[#pts + 1] = pts[k] end end
    for _, p in ipairs(pts) do p[3] = nil end
    local b = core.bspline(pts, { degree = 3 })
    for i = 0, n do
      local x, y = b:eval(i / n)
      out[i + 1] = { x, y }
    end
  end
  return out
end

local function bounds (pts, a, b, box)
  for _, p in ipairs(pts) do
    box[1], box[2] = min(box[1], p[a]), max(box[2], p[a])
    box[3], box[4] = min(box[3], p[b]), max(box[4], p[b])
  end
  return box
end

-- Widens box by frac of its size on each side; a flat extent becomes c +- max(|c|, 1) / 2.
local function padded (box, frac)
  for k = 1, 3, 2 do
    local span = box[k + 1] - box[k]
    if span < 1e-9 then
      local mid, half = (box[k] + box[k + 1]) / 2, max(abs(box[k]), 1) / 2
      box[k], box[k + 1] = mid - half, mid + half
    else
      box[k], box[k + 1] = box[k] - frac * span, box[k + 1] + frac * span
    end
  end
  return box
end

--- Fits the view of entry `e` (default the current one) to its points and curve.
function Pane:fit (e)
  e = e or self:current()
  if e.kind == "func" then
    local box = bounds(curve(e), 1, 2, bounds(e.pts, 1, 2, { huge, -huge, huge, -huge }))
    padded(box, 0.1)
    box[1], box[2] = -0.03, 1.03
    e.box = box
  elseif e.kind == "contour" then
    e.box = padded(bounds(curve(e), 1, 2, bounds(e.pts, 1, 2, { huge, -huge, huge, -huge })),
                   0.1)
  else
    e.box = padded(bounds(e.pts, 1, 2, { huge, -huge, huge, -huge }), 0.1)
    e.side = padded(bounds(e.pts, 3, 2, { huge, -huge, huge, -huge }), 0.1)
  end
end

-- The plot rectangles of the canvas: { x, y, w, h } (two for a surface: front, side).
function Pane:rects ()
  local top = (#self.entries > 1 and TAB_H or 0) + HEAD_H
  local x, y = PAD_L, top + PAD_T
  local w, h = self.w - PAD_L - PAD_R, self.h - top - PAD_T - PAD_B - FOOT_H
  if self:current().kind == "surface" then
    local hh = floor((h - PAD_B) / 2)
    return { x, y + 16, w, hh - 16 }, { x, y + hh + PAD_B + 16, w, hh - 16 }
  end
  return { x, y, w, h }
end

-- A mapping of data box `box` into rectangle r: equal aspect unless `stretch`.
local function mapping (box, r, stretch)
  local dx, dy = box[2] - box[1], box[4] - box[3]
  local sx, sy = r[3] / dx, r[4] / dy
  if not stretch then sx = min(sx, sy) sy = sx end
  local ox = r[1] + (r[3] - sx * dx) / 2 - sx * box[1]
  local oy = r[2] + r[4] - (r[4] - sy * dy) / 2 + sy * box[3]
  return { sx = sx, sy = sy, ox = ox, oy = oy, box = box, r = r }
end

local function topx (m, x, y) return m.ox + m.sx * x, m.oy - m.sy * y end
local function todata (m, px, py) return (px - m.ox) / m.sx, (m.oy - py) / m.sy end

-- The mappings of the current entry: a function's view is stretched, the others have equal
-- aspect (a surface's two views share one scale).
function Pane:maps ()
  local e = self:current()
  local r1, r2 = self:rects()
  if e.kind == "func" then return mapping(e.box, r1, true) end
  if e.kind == "contour" then return mapping(e.box, r1) end
  local a, b = mapping(e.box, r1), mapping(e.side, r2)
  local s = min(a.sx, b.sx)
  for _, m in ipairs { a, b } do        -- one scale, each view centred in its rectangle
    local box, r = m.box, m.r
    m.sx, m.sy = s, s
    m.ox = r[1] + (r[3] - s * (box[2] - box[1])) / 2 - s * box[1]
    m.oy = r[2] + r[4] - (r[4] - s * (box[4] - box[3])) / 2 + s * box[3]
  end
  return a, b
end

--- Where control point `i` of the current curve is drawn, in canvas pixels (for a surface,
-- point 16 (p - 1) + k is control point k of patch p; `side` true gives the side view).
function Pane:to_pixels (i, side)
  local e = self:current()
  local p = e.pts[i]
  if p == nil then error(format("to_pixels: no point %s (the curve has %d)", tostring(i),
                                #e.pts), 2) end
  local a, b = self:maps()
  if side and b then return topx(b, p[3], p[2]) end
  return topx(a, p[1], p[2])
end

-- The point nearest (px, py) within M.PICK_RADIUS pixels: its index, where it is drawn
-- (x, y in pixels) and whether that is a surface's side view; or nil.
function Pane:hit (px, py)
  local e = self:current()
  local a, b = self:maps()
  local best, bx, by, bside, bd = nil, nil, nil, false, M.PICK_RADIUS
  for i, p in ipairs(e.pts) do
    local x, y = topx(a, p[1], p[2])
    local d = ((x - px) ^ 2 + (y - py) ^ 2) ^ 0.5
    if d < bd then best, bx, by, bside, bd = i, x, y, false, d end
    if b then
      x, y = topx(b, p[3], p[2])
      d = ((x - px) ^ 2 + (y - py) ^ 2) ^ 0.5
      if d < bd then best, bx, by, bside, bd = i, x, y, true, d end
    end
  end
  return best, bx, by, bside
end

-- The distance in pixels from (px, py) to the drawn curve of the current entry.
function Pane:curve_distance (px, py)
  local e = self:current()
  if e.kind == "surface" then return huge end
  local m = self:maps()
  local pts, best = curve(e), huge
  for j = 1, #pts - 1 do
    local ax, ay = topx(m, pts[j][1], pts[j][2])
    local bx, by = topx(m, pts[j + 1][1], pts[j + 1][2])
    local dx, dy = bx - ax, by - ay
    local l2 = dx * dx + dy * dy
    local t = l2 > 0 and max(0, min(1, ((px - ax) * dx + (py - ay) * dy) / l2)) or 0
    best = min(best, ((ax + t * dx - px) ^ 2 + (ay + t * dy - py) ^ 2) ^ 0.5)
  end
  return best
end

-- }=========================================================================================

-- {=========================================================================================
-- The pane: edits

-- The run of points equal to point i: first and last index.
local function group (pts, i)
  local a, b = i, i
  local p = pts[i]
  local function same (q) return q[1] == p[1] and q[2] == p[2] and q[3] == p[3] end
  while a > 1 and same(pts[a - 1]) do a = a - 1 end
  while b < #pts and same(pts[b + 1]) do b = b + 1 end
  return a, b
end

-- Makes the object of entry e from its points and hands it on: the target's set, then
-- on_change. Returns true, or false with the message in self.msg (the points are then
-- those of the last good object).
function Pane:commit (e)
  local ok, obj
  if e.kind == "func" then
    ok, obj = pcall(func.new, { points = e.pts, name = e.fname, samples = e.samples,
                                approx = e.approx ~= "exact" and e.approx or nil })
  elseif e.kind == "contour" then
    local pts = e.pts
    if e.dim == 2 then
      pts = {}
      for i, p in ipairs(e.pts) do pts[i] = { p[1], p[2] } end
    end
    ok, obj = pcall(core.contour, pts, e.closed)
  else
    ok, obj = pcall(e.object.with_points, e.object, e.pts)
  end
  if not ok then
    self.msg = tostring(obj):gsub("^bad argument #%d+ to '[^']*' %((.*)%)$", "%1")
    e.pts = M.points(e.object)
    return false
  end
  e.object, e.dirty = obj, true
  if e.set then e.set(obj) end
  if self.on_change then self.on_change(e.kind, e.name, obj) end
  return true
end

-- Remembers the points of the current curve for undo.
function Pane:push_undo ()
  local u = self.undo
  u[#u + 1] = { cur = self.cur, pts = copy(self:current().pts) }
  if #u > M.UNDO_LIMIT then remove(u, 1) end
end

--- Undoes the last edit (a drag, a point added, removed or nudged), showing its curve.
-- Returns false when there is nothing to undo.
function Pane:undo_last ()
  local u = remove(self.undo)
  if u == nil then self.msg = "nothing to undo" return false end
  self.cur, self.selected, self.drag = u.cur, nil, nil
  local e = self:current()
  e.pts = u.pts
  self:commit(e)
  self:fit(e)
  self.msg = "undone"
  return true
end

-- Moves the run of points of the selection to data (x, y), within the rules of its kind;
-- a surface's point and those at the same place to (x, y) of the front view, or with
-- `side` to (z, y).
function Pane:move_to (x, y, side)
  local e, i = self:current(), self.selected
  local pts = e.pts
  if e.kind == "surface" then
    local p = pts[i]
    local px, py, pz = p[1], p[2], p[3]
    for _, q in ipairs(pts) do
      if q[1] == px and q[2] == py and q[3] == pz then
        if side then q[3], q[2] = x, y else q[1], q[2] = x, y end
      end
    end
    return self:commit(e)
  end
  local a, b = group(pts, i)
  if e.kind == "func" then
    if a == 1 then x = 0
    elseif b == #pts then x = 1
    else x = max(pts[a - 1][1], min(pts[b + 1][1], x)) end
    y = max(e.box[3], min(e.box[4], y))
  end
  for k = a, b do pts[k][1], pts[k][2] = x, y end
  return self:commit(e)
end

--- Adds a point at data (x, y) to the current curve: a function's by x, a contour's into
-- the nearest side of its control polygon. Returns its index, or nil (self.msg says why).
function Pane:add_point (x, y)
  local e = self:current()
  local pts, at = e.pts, nil
  if e.kind == "surface" then self.msg = "a surface's points are moved, not added" return nil end
  if e.kind == "func" then
    if x <= 0 or x >= 1 then self.msg = "a new point's x must lie between 0 and 1" return nil end
    at = #pts
    for k = 2, #pts do
      if pts[k][1] > x then at = k break end
    end
  else
    local best, n = huge, #pts
    for k = 1, e.closed and n or n - 1 do
      local p, q = pts[k], pts[k % n + 1]
      local dx, dy = q[1] - p[1], q[2] - p[2]
      local l2 = dx * dx + dy * dy
      local t = l2 > 0 and max(0, min(1, ((x - p[1]) * dx + (y - p[2]) * dy) / l2)) or 0
      local d = (p[1] + t * dx - x) ^ 2 + (p[2] + t * dy - y) ^ 2
      if d < best then best, at = d, k + 1 end
    end
  end
  self:push_undo()
  insert(pts, at, { x, y, e.kind == "contour" and e.dim == 3 and 0 or nil })
  if not self:commit(e) then return nil end
  self.selected = at
  self.msg = format("added point %d", at)
  return at
end

--- Removes point `i` (default the selected one) of the current curve, keeping the least
-- number of points of its kind and a function's end points. Returns true when removed.
function Pane:remove_point (i)
  local e = self:current()
  i = i or self.selected
  if e.kind == "surface" then
    self.msg = "a surface's points are moved, not removed"
    return false
  end
  if i == nil or e.pts[i] == nil then self.msg = "no point selected" return false end
  local least = e.kind == "func" and M.MIN_POINTS.func
    or e.closed and M.MIN_POINTS.closed or M.MIN_POINTS.open
  if #e.pts <= least then
    self.msg = format("a %s needs at least %d points", e.kind == "func" and "function"
                      or (e.closed and "closed contour" or "open contour"), least)
    return false
  end
  if e.kind == "func" then
    local a, b = group(e.pts, i)
    if (a == 1 or b == #e.pts) and a == b then
      self.msg = "the end points stay (x = 0 and x = 1)"
      return false
    end
  end
  self:push_undo()
  remove(e.pts, i)
  if not self:commit(e) then return false end
  self.selected = nil
  self.msg = format("removed point %d", i)
  self:fit(e)
  return true
end

--- Shows target k (an index, wrapping around).
function Pane:select_target (k)
  local n = #self.entries
  self.cur = (k - 1) % n + 1
  self.selected, self.drag = nil, nil
  self.msg = nil
  return true
end

-- The target tab at pixel (x, y), or nil.
function Pane:tab_at (x, y)
  if #self.entries < 2 or y < 0 or y >= TAB_H then return nil end
  for k, t in pairs(self.tabs) do
    if x >= t[1] and x < t[2] then return k end
  end
  return nil
end

--- A pointer event in canvas pixels (see the pane interface). Returns whether to redraw.
function Pane:pointer (phase, x, y, button, shift)
  local e = self:current()
  if phase == "down" then
    local k = self:tab_at(x, y)
    if k then return self:select_target(k) end
    local i, px, py, side = self:hit(x, y)
    if button == "right" then
      if i then self.selected = i self:remove_point(i) return true end
      return false
    end
    if button ~= "left" then return false end
    local a, b = self:maps()
    if shift or e.kind ~= "surface" and i == nil and self:curve_distance(x, y) <= M.PICK_RADIUS
    then
      i = self:add_point(todata(a, x, y))
      if i == nil then return true end
      px, py = x, y
    end
    self.selected = i
    if i == nil then self.msg = nil return true end
    self.drag = { map = side and b or a, side = side, dx = px - x, dy = py - y }
    return true
  elseif phase == "move" then
    local d = self.drag
    if d == nil or self.selected == nil then return false end
    if not d.pushed then self:push_undo() d.pushed = true end
    local dx, dy = todata(d.map, x + d.dx, y + d.dy)
    self:move_to(dx, dy, d.side)
    return true
  elseif phase == "up" then
    if self.drag == nil then return false end
    self.drag = nil
    self:fit(e)
    return true
  end
  return false
end

--- The wheel: nothing (the view fits itself). Returns false.
function Pane.scroll () return false end

--- A key (GLFW's lower-case names). Returns whether the pane took it.
function Pane:key (name, ctrl, shift)
  if ctrl then                               -- Ctrl+S and the others are the host's
    if name == "z" then self:undo_last() return true end
    return false
  end
  local e = self:current()
  if name == "[" or name == "tab" and shift then return self:select_target(self.cur - 1)
  elseif name == "]" or name == "tab" then return self:select_target(self.cur + 1)
  elseif name == "delete" or name == "backspace" then
    self:remove_point()
    return true
  elseif name == "left" or name == "right" then
    local n = #e.pts
    local i = self.selected or (name == "left" and 1 or n)
    self.selected = (i - 1 + (name == "left" and -1 or 1)) % n + 1
    return true
  elseif (name == "up" or name == "down") and self.selected then
    local p = e.pts[self.selected]
    local step = (e.box[4] - e.box[3]) / 100 * (name == "up" and 1 or -1)
    self:push_undo()
    self:move_to(p[1], p[2] + step)
    self:fit(e)
    return true
  elseif name == "f" then
    self:fit(e)
    return true
  end
  return false
end

--- One line about the curve and its selected point, for the status bar.
function Pane:status ()
  local e = self:current()
  local head = format("%s: %d points", e.label or e.name, #e.pts)
  if e.kind == "surface" then
    head = format("%s: %d patches", e.label or e.name, #e.pts // 16)
  end
  local i = self.selected
  local p = i and e.pts[i]
  local sel = ""
  if p then
    if e.kind == "surface" then
      sel = format("  patch %d point %d: x %.4g y %.4g z %.4g", (i - 1) // 16 + 1,
                   (i - 1) % 16 + 1, p[1], p[2], p[3])
    else
      local a, b = group(e.pts, i)
      sel = format("  point %d: x %.4g y %.4g%s", i, p[1], p[2],
                   b > a and format(" (x%d)", b - a + 1) or "")
    end
  end
  return head .. sel .. (self.msg and "  |  " .. self.msg or "")
end

--- Writes the edited curves back into their files, in their own formats, atomically: a
-- function read from a .func file with lsys.func.save; one read from a .fset by rewriting
-- that set with the edited functions in place; a contour as a cpfg .con file; a surface
-- as a cpfg .s file (Surface:format). Curves without a file are left (self.msg says so).
-- Returns the list of paths written.
function Pane:save ()
  local sets, order, written, nofile = {}, {}, {}, 0
  for _, e in ipairs(self.entries) do
    if e.dirty and e.file == nil then nofile = nofile + 1
    elseif e.dirty and e.kind == "func" and e.file:match("%.fset$") then
      if sets[e.file] == nil then sets[e.file] = {} order[#order + 1] = e.file end
      local s = sets[e.file]
      s[#s + 1] = e
    elseif e.dirty and e.kind == "func" then
      func.save(e.object, e.file)
      written[#written + 1] = e.file
      e.dirty = false
    elseif e.dirty and e.kind == "contour" then
      M.save_contour(e.object, e.file)
      written[#written + 1] = e.file
      e.dirty = false
    elseif e.dirty then
      local ok, err = pcall(core.write_file, e.file, e.object:format())
      if not ok then error("lsys.ui.curve: cannot save " .. tostring(err), 0) end
      written[#written + 1] = e.file
      e.dirty = false
    end
  end
  for _, path in ipairs(order) do
    local ok, fs = pcall(func.readall, path)
    if not ok then error("lsys.ui.curve: cannot save " .. tostring(fs), 0) end
    for _, e in ipairs(sets[path]) do
      local found = false
      for k, f in ipairs(fs) do
        if f:name() == e.fname then fs[k], found = e.object, true break end
      end
      if not found then
        error(format("lsys.ui.curve: %s has no function '%s' any more", path, e.fname), 0)
      end
    end
    func.save_set(fs, path)
    for _, e in ipairs(sets[path]) do e.dirty = false end
    written[#written + 1] = path
  end
  self.msg = #written > 0 and "saved " .. concat(written, ", ") or "nothing to save"
  if nofile > 0 then
    self.msg = self.msg .. format(" (%d edited curve%s without a file)", nofile,
                                  nofile == 1 and "" or "s")
  end
  return written
end

-- }=========================================================================================

-- {=========================================================================================
-- The pane: drawing

-- About 5 round tick values covering [a, b].
local function ticks (a, b)
  local span = b - a
  if not (span > 0) then return {} end
  local step = 10 ^ floor(math.log(span / 4, 10))
  for _, m in ipairs { 1, 2, 5, 10 } do
    if span / (step * m) <= 5 then step = step * m break end
  end
  local out = {}
  for v = math.ceil(a / step) * step, b + step * 1e-9, step do
    out[#out + 1] = abs(v) < step * 1e-9 and 0 or v
  end
  return out
end

local function label (v) return (format("%.3g", v)) end

-- The frame, grid and tick labels of mapping m; `xy` names the axes ("x y", "z y").
local function axes (c, m, names)
  local r = m.r
  local bx0, by0 = todata(m, r[1], r[2] + r[4])      -- the data the rectangle shows
  local bx1, by1 = todata(m, r[1] + r[3], r[2])
  local box = { bx0, bx1, by0, by1 }
  c:rect(r[1], r[2], r[3], r[4], LIGHT)
  local x0, y1 = topx(m, box[1], box[3])
  local x1, y0 = topx(m, box[2], box[4])
  c:clip(r[1], r[2], r[3], r[4])
  for _, v in ipairs(ticks(box[1], box[2])) do
    local px = topx(m, v, 0)
    c:line(px, y0, px, y1, v == 0 and 1.5 or 1, v == 0 and GREY or LIGHT)
  end
  for _, v in ipairs(ticks(box[3], box[4])) do
    local _, py = topx(m, 0, v)
    c:line(x0, py, x1, py, v == 0 and 1.5 or 1, v == 0 and GREY or LIGHT)
  end
  c:clip()
  for _, v in ipairs(ticks(box[1], box[2])) do
    local px = topx(m, v, 0)
    if px >= r[1] - 1 and px <= r[1] + r[3] + 1 then
      local s = label(v)
      c:text(px - c:text_width(s, 1) / 2, r[2] + r[4] + 6, s, 1, GREY)
    end
  end
  for _, v in ipairs(ticks(box[3], box[4])) do
    local _, py = topx(m, 0, v)
    if py >= r[2] - 1 and py <= r[2] + r[4] + 1 then
      local s = label(v)
      c:text(r[1] - 6 - c:text_width(s, 1), py - 3, s, 1, GREY)
    end
  end
  if names then c:text(r[1], r[2] - 16, names, 2, GREY) end
end

local function polyline (c, m, pts, a, b, width, colour, closed)
  local out = {}
  for i, p in ipairs(pts) do out[i] = { topx(m, p[a], p[b]) } end
  if closed and #out > 0 then out[#out + 1] = out[1] end
  if #out >= 2 then c:polyline(out, width, colour) end
end

function Pane:draw_tabs (c)
  local n, w = #self.entries, self.w
  self.tabs = {}
  if n < 2 then return end
  local widths, x = {}, 4
  for k, e in ipairs(self.entries) do widths[k] = c:text_width(e.label or e.name, 2) + 16 end
  local first, used = 1, 4                   -- the first tab shown keeps the current one in
  for k = self.cur, 1, -1 do
    used = used + widths[k] + 4
    if used > w then break end
    first = k
  end
  if first > 1 then                          -- tabs hidden on the left
    c:text(x, TAB_H / 2 - 7, "<", 2, GREY)
    x = x + 16
  end
  for k = first, n do
    if x + widths[k] > w - (k < n and 16 or 0) then
      c:text(w - 14, TAB_H / 2 - 7, ">", 2, GREY)  -- and on the right
      break
    end
    local on = k == self.cur
    c:rect(x, 3, widths[k], TAB_H - 6, on and { 0.25, 0.25, 0.3, 1 } or WHITE, true)
    c:rect(x, 3, widths[k], TAB_H - 6, GREY)
    local e = self.entries[k]
    c:text(x + 8, TAB_H / 2 - 7, e.label or e.name, 2, on and WHITE or BLACK)
    self.tabs[k] = { x, x + widths[k] }
    x = x + widths[k] + 4
  end
end

local function basename (p) return (p:match("[^/]*$")) end

-- Text at 2x when it fits in the canvas from x, else at 1x.
local function say (c, x, y, s, colour)
  local w = c:size()
  local scale = c:text_width(s, 2) <= w - x - 4 and 2 or 1
  c:text(x, scale == 2 and y or y + 4, s, scale, colour)
end

--- Draws the pane into canvas `c` (any size from 240 x 240): the names of the curves, the
-- current one with its control polygon and points (the selection in red), and the
-- selected point's coordinates.
function Pane:draw (c)
  self.w, self.h = c:size()
  local e = self:current()
  c:clear({ 0.97, 0.97, 0.97, 1 })
  self:draw_tabs(c)
  local top = #self.entries > 1 and TAB_H or 0
  local name = e.label or e.name
  local kind = e.kind == "func" and "function" or e.kind
  local head = (name:sub(1, #e.kind) == e.kind and name or kind .. " " .. name)
               .. (e.dirty and " *" or "")
  say(c, 8, top + 7, head, BLACK)
  if e.file then
    local s = basename(e.file)
    local tw = c:text_width(s, 1)
    c:text(self.w - 8 - tw, top + 11, s, 1, GREY)
  end
  local a, b = self:maps()
  local sel = self.selected
  if e.kind == "surface" then
    axes(c, a, "front: x, y")
    axes(c, b, "side: z, y")
    local info = e.object:info()
    for _, pair in ipairs { { a, 1 }, { b, 3 } } do
      local m, ax = pair[1], pair[2]
      c:clip(m.r[1], m.r[2], m.r[3], m.r[4])
      for p = 1, info.patches do
        local base = 16 * (p - 1)
        for r = 0, 3 do
          local row, col = {}, {}
          for k = 0, 3 do
            row[k + 1] = e.pts[base + 4 * r + k + 1]
            col[k + 1] = e.pts[base + 4 * k + r + 1]
          end
          polyline(c, m, row, ax, 2, 1, NET)
          polyline(c, m, col, ax, 2, 1, NET)
        end
        for k = 1, 16 do
          local q = e.pts[base + k]
          local x, y = topx(m, q[ax], q[2])
          c:circle(x, y, base + k == sel and 5 or 2.5, base + k == sel and SELECTED or POINT)
        end
      end
      c:clip()
    end
  else
    axes(c, a)
    local r = a.r
    c:clip(r[1], r[2], r[3], r[4])
    polyline(c, a, e.pts, 1, 2, 1, GREY, e.kind == "contour" and e.closed)
    polyline(c, a, curve(e), 1, 2, 2.5, CURVE)
    for i, p in ipairs(e.pts) do
      local x, y = topx(a, p[1], p[2])
      if i == sel then
        c:circle(x, y, 7, SELECTED)
      else
        c:circle(x, y, 5, POINT)
        c:circle(x, y, 3, WHITE)
      end
    end
    c:clip()
  end
  local fy = self.h - FOOT_H + 6
  local p = sel and e.pts[sel]
  if p and e.kind == "surface" then
    say(c, 8, fy, format("patch %d point %d", (sel - 1) // 16 + 1, (sel - 1) % 16 + 1), BLACK)
    say(c, 8, fy + 22, format("x %.4g  y %.4g  z %.4g", p[1], p[2], p[3]), BLACK)
  elseif p then
    say(c, 8, fy, format("point %d of %d", sel, #e.pts), BLACK)
    say(c, 8, fy + 22, format("x %.4g  y %.4g", p[1], p[2]), BLACK)
  else
    say(c, 8, fy, format("%d %s", e.kind == "surface" and #e.pts // 16 or #e.pts,
                         e.kind == "surface" and "patches" or "points"), BLACK)
    say(c, 8, fy + 22, self.msg or (e.kind == "surface" and "drag a point: front, side"
      or "drag a point, click curve: add"), GREY)
  end
  return c
end

-- }=========================================================================================

return M
