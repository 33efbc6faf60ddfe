--- The sketch window (`lsys sketch [FILE]`): draw the construction lines of
-- Anastacio et al. 2009 (§3.2: a stem, left and right boundaries, inclination lines) and
-- see the plant they parameterize beside them, updated while the stroke is drawn. The
-- paper's sketching program and cpfg were two programs without immediate feedback (§7);
-- here one window holds the sketch pane, the 3D plant (the viewer's scene and orbit
-- camera) and the positional functions plotted.
--
-- The logic is a state machine fed events in the sketch's own pixels (`new`, then
-- `pointer`, `scroll`, `key`, `toolbar`), so it is tested without a window; `run` opens
-- the window (lsys.core's viewer with panes) and feeds it. Mice have no pressure: the
-- wheel (or [ and ]) sets the pressure of the points drawn next, shown by the stroke's
-- colour as in §7.3 (farther lighter, nearer darker); §3.5 maps it to depth.
--
-- Its documented name is lsys.sketch.window (lua/lsys/sketch/window.lua gives this module);
-- the code lives with the other window sessions in lua/lsys/ui/.
-- @module lsys.ui.sketch
local core = require "lsys.core"
local model = require "lsys.model"
local sketch = require "lsys.sketch"
local read = require "lsys.sketch.read"
local plot = require "lsys.sketch.plot"
local organs = require "lsys.sketch.organ"
local OV = require "lsys.ui.sketch_organ"
local render = require("lsys.render").render
local now = require("lsys.program").clock
local require = require

local type, ipairs, pairs, pcall, tostring, error, setmetatable =
      type, ipairs, pairs, pcall, tostring, error, setmetatable
local math, string, table = math, string, table
local format, remove = string.format, table.remove
local floor, min, max, huge = math.floor, math.min, math.max, math.huge
local _ENV = nil

local M = {}

M.ROLES = { "stem", "boundary_left", "boundary_right", "inclination" }
M.LABELS = { stem = "1 stem", boundary_left = "2 left", boundary_right = "3 right",
             inclination = "4 incl." }
M.ORGAN_ROLES = OV.ROLES
M.PHYLLOTAXIS = { "distichous", "decussate", "fibonacci" }
M.UNDO_LIMIT = 100           -- sketches kept for Ctrl+Z
M.PICK_RADIUS = 20           -- pixels: how near a right-press must be to move a stroke
M.SCROLL_STEP = 0.05         -- pressure per wheel notch ([ and ] step twice that)

local ONCE = { stem = true, boundary_left = true, boundary_right = true, top_left = true,
               top_right = true, side = true, front = true }

-- {=========================================================================================
-- The state machine

local State = {}
State.__index = State

local function copy_points (pts)
  local out = {}
  for i, p in ipairs(pts) do out[i] = { p[1], p[2], p[3] } end
  return out
end

local function copy_strokes (strokes)
  local out = {}
  for i, s in ipairs(strokes) do out[i] = { role = s.role, points = copy_points(s.points) } end
  return out
end

--- A new sketch session. opts: `sketch` (a sketch table as lsys.sketch.read returns or
-- takes; default an empty one), `width`, `height` (of a new sketch, default 600 x 600),
-- `nodes` (nodes per layer), `phyllotaxis`, `file` (where `save` writes), `organ` (the
-- organ drawn at the nodes: an Organ of lsys.sketch.organ or its table, { organ = {...} },
-- whose strokes the O key shows and edits; default none: the default leaf until one is
-- drawn), `organ_file` (where `save` writes the organ; default FILE.organ.json).
function M.new (opts)
  opts = opts or {}
  local sk = opts.sketch
  local org = opts.organ
  if type(org) == "table" and type(org.to_table) == "function" then org = org:to_table() end
  local ostrokes, oopts = OV.strokes(org)
  local st = setmetatable({
    mode = "plant",          -- or "organ": which strokes the pointer draws
    organ_strokes = ostrokes, organ_opts = oopts,
    organ_role = "top_left",
    organ_version = 0,       -- changes with every change of the organ's strokes
    organ_saved = 0,         -- the version last saved (or read)
    organ_file = opts.organ_file,
    width = sk and sk.width or opts.width or 600,
    height = sk and sk.height or opts.height or 600,
    nodes = opts.nodes or (sk and sk.nodes_per_layer) or 5,
    phyllotaxis = opts.phyllotaxis or (sk and sk.phyllotaxis) or "distichous",
    depth = sk and sk.depth or nil,
    strokes = sk and copy_strokes(sk.strokes) or {},
    file = opts.file,
    role = "stem",
    pressure = 0.5,          -- of the points drawn next (§3.5: 0.5 is the drawing plane)
    drawing = nil,           -- the stroke being drawn: { role, points }
    moving = nil,            -- { index, x, y }: the stroke being moved, the last point
    selected = nil,          -- index of the stroke last drawn or moved
    undo = {},
    changed = true,          -- the sketch changed since the plant was last computed
    status = nil,
    overlay = true,          -- draw the nodes and rays of the analysis over the sketch
  }, State)
  st.views = OV.fit(ostrokes, st.width, st.height)
  return st
end

--- The strokes the pointer works on: the plant's, or the organ's in organ mode.
function State:list ()
  return self.mode == "organ" and self.organ_strokes or self.strokes
end

--- The role of the strokes drawn next.
function State:current_role ()
  return self.mode == "organ" and self.organ_role or self.role
end

-- The points of stroke s in the pane's pixels (an organ's strokes keep their own).
function State:pane_points (s)
  local v = OV.VIEW[s.role]
  if v == nil then return s.points end
  local t, out = self.views[v], {}
  for i, p in ipairs(s.points) do
    local x, y = OV.to_pane(t, p[1], p[2])
    out[i] = { x, y, p[3] }
  end
  return out
end

-- Points drawn in the pane as stroke `role` keeps them.
function State:native (role, pts)
  local v = OV.VIEW[role]
  if v == nil then return pts end
  local t, out = self.views[v], {}
  for i, p in ipairs(pts) do
    local x, y = OV.from_pane(t, p[1], p[2])
    out[i] = { x, y, p[3] }
  end
  return out
end

-- Whether stroke i is stood for by the stroke being drawn (once it has two points): the
-- one redrawn in place, or the old stem or boundary of the role being drawn. The plant and
-- the sketch pane both leave it out.
function State:replaced (i, list)
  local d = self.drawing
  list = list or self:list()
  if d == nil or #d.points < 2 or d.list ~= list then return false end
  return d.replace == i or not d.replace and ONCE[d.role] and list[i].role == d.role
end

-- The strokes of `list` with the one being drawn (in the list's own coordinates).
function State:with_drawing (list)
  local d = self.drawing
  local out = {}
  for i, s in ipairs(list) do
    if not self:replaced(i, list) then
      out[#out + 1] = { role = s.role, points = copy_points(s.points) }
    end
  end
  if d and #d.points >= 2 and d.list == list then
    local at = d.replace and d.replace <= #out + 1 and d.replace or #out + 1
    table.insert(out, at, { role = d.role, points = self:native(d.role, d.points) })
  end
  return out
end

--- The sketch as lsys.sketch.read takes it (JSON shape), with the stroke being drawn when
-- it has two points or more.
function State:sketch ()
  return {
    file = self.file, width = self.width, height = self.height, nodes_per_layer = self.nodes,
    phyllotaxis = self.phyllotaxis, depth = self.depth,
    strokes = self:with_drawing(self.strokes),
  }
end

--- The organ as lsys.sketch.organ.load takes it ({ organ = {...} }, in the strokes' own
-- pixels), with the stroke being drawn; nil when it has no strokes.
function State:organ_table ()
  return OV.table(self:with_drawing(self.organ_strokes), self.organ_opts)
end

-- Remembers the strokes and settings for undo.
function State:push_undo ()
  local u = self.undo
  u[#u + 1] = { strokes = copy_strokes(self.strokes), nodes = self.nodes,
                phyllotaxis = self.phyllotaxis, selected = self.selected,
                organ = copy_strokes(self.organ_strokes), mode = self.mode }
  if #u > M.UNDO_LIMIT then remove(u, 1) end
end

-- Marks the sketch changed (the organ too when `organ`), with a message.
function State:touch (msg, organ)
  self.changed = true
  if organ then self.organ_version = self.organ_version + 1 end
  if msg then self.status = msg end
end

--- Undoes the last change (a stroke drawn, moved or deleted, of the plant or the organ;
-- nodes; phyllotaxis).
function State:undo_last ()
  local u = remove(self.undo)
  if u == nil then self.status = "nothing to undo" return false end
  self.strokes, self.nodes, self.phyllotaxis, self.organ_strokes =
    u.strokes, u.nodes, u.phyllotaxis, u.organ
  self.selected = u.mode == self.mode and u.selected or nil
  self:touch("undone", true)
  return true
end

local function clamp01 (p) return p < 0 and 0 or p > 1 and 1 or p end

-- The stroke nearest (x, y) within M.PICK_RADIUS pixels (distance to its segments).
function State:nearest (x, y)
  local best, bd = nil, M.PICK_RADIUS
  for i, s in ipairs(self:list()) do
    local pts = self:pane_points(s)
    for j = 1, #pts do
      local a, b = pts[j], pts[j + 1] or pts[j]
      local dx, dy = b[1] - a[1], b[2] - a[2]
      local l2 = dx * dx + dy * dy
      local t = l2 > 0 and max(0, min(1, ((x - a[1]) * dx + (y - a[2]) * dy) / l2)) or 0
      local ex, ey = a[1] + t * dx - x, a[2] + t * dy - y
      local d = (ex * ex + ey * ey) ^ 0.5
      if d <= bd then best, bd = i, d end
    end
  end
  return best
end

--- Feeds a pointer event in sketch pixels: phase "down" | "move" | "up"; button "left"
-- (draws a stroke of the current role) or "right" (moves the nearest stroke; also left
-- with shift). A left press with `ctrl` redraws a stroke in place: the selected one, else
-- the nearest, keeps its place and role and takes the points drawn. `pressure`, when a
-- number, is a tablet pen's (§3.5): it becomes the pressure of this point and of the points
-- drawn next. Returns true when the sketch changed.
function State:pointer (phase, x, y, button, shift, pressure, ctrl)
  if type(pressure) == "number" and phase ~= "up" and (self.drawing or phase == "down") then
    self.pressure = floor(clamp01(pressure) * 1000 + 0.5) / 1000
  end
  local list, organ = self:list(), self.mode == "organ"
  if phase == "down" then
    if button == "right" or button == "middle" or shift then
      local k = self:nearest(x, y)
      if k == nil then self.status = "no stroke near the pointer to move" return false end
      self:push_undo()
      self.moving = { index = k, x = x, y = y, list = list }
      self.selected = k
      return false
    end
    if button ~= "left" then return false end
    self.drawing = { role = self:current_role(), points = { { x, y, self.pressure } },
                     list = list }
    if ctrl then
      local k = list[self.selected or 0] and self.selected or self:nearest(x, y)
      if k == nil then
        self.drawing = nil
        self.status = "no stroke to redraw: select one (right click) first"
        return false
      end
      self.drawing.role, self.drawing.replace = list[k].role, k
      self.status = format("redrawing stroke %d (%s)", k, list[k].role)
    end
    return false
  elseif phase == "move" then
    local m = self.moving
    if m then
      local t = self.views[OV.VIEW[m.list[m.index].role]]
      local sc = t and t.s or 1
      local dx, dy = (x - m.x) / sc, (y - m.y) / sc
      for _, p in ipairs(m.list[m.index].points) do p[1], p[2] = p[1] + dx, p[2] + dy end
      m.x, m.y = x, y
      self:touch(nil, m.list == self.organ_strokes)
      return true
    end
    local d = self.drawing
    if d == nil then return false end
    local last = d.points[#d.points]
    local ddx, ddy = x - last[1], y - last[2]
    if ddx * ddx + ddy * ddy < 1 then return false end   -- under a pixel: nothing new
    d.points[#d.points + 1] = { x, y, self.pressure }
    if #d.points >= 2 then self:touch(nil, d.list == self.organ_strokes) end
    return #d.points >= 2
  elseif phase == "up" then
    local m = self.moving
    if m then
      self.moving = nil
      self:touch(format("moved stroke %d (%s)", m.index, m.list[m.index].role),
                 m.list == self.organ_strokes)
      return true
    end
    local d = self.drawing
    if d == nil then return false end
    self:pointer("move", x, y, "left")
    self.drawing = nil
    if #d.points < 2 then
      self.status = "a stroke needs two points or more: drag to draw"
      return false
    end
    self:push_undo()
    local stroke = { role = d.role, points = self:native(d.role, d.points) }
    if d.replace then                -- redrawn in place
      local k = d.replace
      list[k] = stroke
      self.selected = k
      self:touch(format("redrew stroke %d (%s, %d points)", k, d.role, #d.points), organ)
      return true
    end
    if ONCE[d.role] then             -- a new stem (or boundary, organ stroke) replaces the old
      for i = #list, 1, -1 do
        if list[i].role == d.role then remove(list, i) end
      end
    end
    list[#list + 1] = stroke
    self.selected = #list
    self:touch(format("drew stroke %d (%s, %d points)", #list, d.role, #d.points), organ)
    return true
  end
  return false
end

--- The wheel: `dy` notches (up positive) raise the pressure of the points drawn next
-- (nearer) by M.SCROLL_STEP each. Returns the new pressure.
function State:scroll (dy)
  self.pressure = clamp01(self.pressure + dy * M.SCROLL_STEP)
  self.pressure = floor(self.pressure * 1000 + 0.5) / 1000
  self.status = format("pressure %.2f (%s)", self.pressure, self.pressure > 0.5 and "nearer"
    or self.pressure < 0.5 and "farther" or "the drawing plane")
  return self.pressure
end

--- Deletes the selected stroke, else the last one.
function State:delete ()
  local list = self:list()
  local k = self.selected or #list
  if list[k] == nil then self.status = "no stroke to delete" return false end
  self:push_undo()
  local s = remove(list, k)
  self.selected = nil
  self:touch(format("deleted stroke %d (%s)", k, s.role), list == self.organ_strokes)
  return true
end

--- Picks the role of the strokes drawn next (a name of M.ROLES, or in organ mode of
-- M.ORGAN_ROLES, or its index).
function State:set_role (r)
  local roles = self.mode == "organ" and M.ORGAN_ROLES or M.ROLES
  r = roles[r] or r
  for _, x in ipairs(roles) do
    if x == r then
      if self.mode == "organ" then self.organ_role = r else self.role = r end
      self.status = "drawing: " .. r
      return true
    end
  end
  return false
end

M.ORGAN_HELP = "the organ (§6): 1 2 its left and right boundaries in the top view, " ..
               "3 its midrib in the side view, 4 its cross-section in the front view; O: " ..
               "back to the plant"

--- Switches between drawing the plant's construction lines and the organ's strokes.
function State:toggle_organ ()
  self.mode = self.mode == "organ" and "plant" or "organ"
  self.selected, self.drawing, self.moving = nil, nil, nil
  self.status = self.mode == "organ" and M.ORGAN_HELP or "the plant's construction lines"
  return self.mode
end

function State:set_nodes (n)
  n = max(1, min(read.MAX_NODES, floor(n)))
  if n == self.nodes then return false end
  self:push_undo()
  self.nodes = n
  self:touch(format("%d nodes per layer", n))
  return true
end

function State:cycle_phyllotaxis ()
  local i = 1
  for k, p in ipairs(M.PHYLLOTAXIS) do if p == self.phyllotaxis then i = k end end
  self:push_undo()
  self.phyllotaxis = M.PHYLLOTAXIS[i % #M.PHYLLOTAXIS + 1]
  self:touch("phyllotaxis: " .. self.phyllotaxis)
end

--- Where Ctrl+S writes: the file given (a .svg is saved next to it as .json), else
-- sketch.json.
function State:save_path ()
  local f = self.file or "sketch.json"
  if f:lower():find("%.svg$") then f = f:sub(1, -5) .. ".json" end
  return f
end

--- Where Ctrl+S writes the organ: the organ file given, else beside the sketch
-- (sketch.json: sketch.organ.json).
function State:organ_path ()
  return self.organ_file or (self:save_path():gsub("%.[^./]*$", "") .. ".organ.json")
end

--- Saves the sketch as JSON (lsys.sketch.read.save); a sketch that is not complete yet (no
-- stem) is written as it is. The organ, when it has strokes that changed since it was
-- read or saved, goes to its own file (State:organ_path, the form lsys.sketch.organ.load
-- reads). Returns the path, and the organ's when it was written.
function State:save (path)
  path = path or self:save_path()
  local t = self:sketch()
  local ok, err = pcall(read.save, t, path)
  if not ok then
    if not tostring(err):find("no stem stroke", 1, true) then error(err, 0) end
    local cjson = require "cjson"
    t.file = nil
    core.write_file(path, cjson.encode(t) .. "\n")
  end
  self.status = "saved " .. path
  local ot = self:organ_table()
  if ot and self.organ_version ~= self.organ_saved then
    local opath = self:organ_path()
    core.write_file(opath, require("cjson").encode(ot) .. "\n")
    self.organ_saved = self.organ_version
    self.status = format("saved %s and %s", path, opath)
    return path, opath
  end
  return path
end

--- A key, by the viewer's name ("1", "p", "[", "backspace", ...); returns the action the
-- session must take ("save", "export", "plots") or nil.
function State:key (name, ctrl)
  if ctrl then
    if name == "z" then self:undo_last()
    elseif name == "s" then return "save"
    elseif name == "e" then return "export" end
    return nil
  end
  if name == "1" or name == "2" or name == "3" or name == "4" then
    self:set_role(name + 0)
  elseif name == "o" then self:toggle_organ()
  elseif name == "=" or name == "+" then self:set_nodes(self.nodes + 1)
  elseif name == "-" then self:set_nodes(self.nodes - 1)
  elseif name == "p" then self:cycle_phyllotaxis()
  elseif name == "[" then self:scroll(-2)
  elseif name == "]" then self:scroll(2)
  elseif name == "delete" or name == "backspace" then self:delete()
  elseif name == "a" then
    self.overlay = not self.overlay
    self.status = self.overlay and "nodes and rays shown" or "nodes and rays hidden"
  elseif name == "tab" then return "plots" end
  return nil
end

-- The toolbar: four role buttons, then the settings (M.toolbar_hit says which is where).
M.TOOLBAR_W, M.TOOLBAR_H, M.BUTTON_W = 900, 44, 130

--- What a click at x on the toolbar does: a role (its index), "nodes-", "nodes+",
-- "phyllotaxis", or nil.
function M.toolbar_hit (x)
  local k = floor(x / M.BUTTON_W) + 1
  if k >= 1 and k <= 4 then return k end
  local rest = x - 4 * M.BUTTON_W
  if rest >= 0 and rest < 100 then return rest < 50 and "nodes-" or "nodes+" end
  if rest >= 100 then return "phyllotaxis" end
  return nil
end

function State:toolbar (x)
  local h = M.toolbar_hit(x)
  if type(h) == "number" then return self:set_role(h) end
  if h == "nodes-" then return self:set_nodes(self.nodes - 1) end
  if h == "nodes+" then return self:set_nodes(self.nodes + 1) end
  if h == "phyllotaxis" then self:cycle_phyllotaxis() return true end
  return false
end

-- }=========================================================================================

-- {=========================================================================================
-- Pictures: the sketch pane, the toolbar (lsys.core canvases)

local ROLE_RGB = {
  boundary_left = { 0.15, 0.35, 0.85 }, boundary_right = { 0.1, 0.55, 0.8 },
  inclination = { 0.85, 0.4, 0.1 },
}
for r, rgb in pairs(OV.RGB) do ROLE_RGB[r] = rgb end

--- The colour of a stem point of pressure p (§7.3: farther lighter, nearer darker): from
-- a pale green at 0 (farthest) to a near-black green at 1 (nearest).
function M.stem_rgb (p)
  p = clamp01(p)
  return { 0.75 - 0.7 * p, 0.9 - 0.65 * p, 0.75 - 0.7 * p }
end

local function draw_stroke (c, s, width, pts)
  pts = pts or s.points
  local rgb = ROLE_RGB[s.role]
  for j = 1, #pts - 1 do
    local a, b = pts[j], pts[j + 1]
    c:line(a[1], a[2], b[1], b[2], width, rgb or M.stem_rgb((a[3] + b[3]) / 2))
  end
end

--- Draws the sketch of `st` into canvas `c` (its size): the strokes by role, the stem by
-- pressure, the selected stroke wider, the stroke being drawn (which hides the stroke it
-- replaces: one redrawn in place, the old stem or boundary), and, when given and
-- st.overlay is on, the sketch's analysis `an` (the nodes and the rays of §3.4 to the
-- boundaries, lsys.sketch.plot.analysis).
-- In organ mode, the three views of the organ and their strokes instead.
function M.draw_sketch (st, c, an)
  c:clear({ 1, 1, 1, 1 })
  local d = st.drawing
  local list = st:list()
  local drawn = d and #d.points >= 2 and d.list == list
  if st.mode == "organ" then OV.frames(c, st.width, st.height) end
  for i, s in ipairs(list) do
    if not st:replaced(i) then
      draw_stroke(c, s, i == st.selected and 4 or 2.5, st:pane_points(s))
    end
  end
  if drawn then draw_stroke(c, d, 2.5) end
  if an and st.overlay and st.mode == "plant" then
    plot.analysis(c, an, { x = 0, y = 0, scale = 1 }, { line_width = 1.5 })
  end
  return c
end

--- Draws the toolbar (M.TOOLBAR_W x M.TOOLBAR_H) into canvas `c`.
function M.draw_toolbar (st, c)
  local bw, h = M.BUTTON_W, M.TOOLBAR_H
  c:clear({ 0.93, 0.93, 0.93, 1 })
  local organ = st.mode == "organ"
  for k, r in ipairs(organ and M.ORGAN_ROLES or M.ROLES) do
    local x = (k - 1) * bw
    local on = st:current_role() == r
    c:rect(x + 2, 2, bw - 4, h - 4, on and { 0.25, 0.25, 0.3, 1 } or { 1, 1, 1, 1 }, true)
    c:rect(x + 2, 2, bw - 4, h - 4, { 0.5, 0.5, 0.5, 1 })
    local rgb = r == "stem" and M.stem_rgb(st.pressure) or ROLE_RGB[r]
    c:line(x + 8, h / 2, x + 22, h / 2, 3, rgb)
    c:text(x + 27, h / 2 - 7, (organ and OV.LABELS or M.LABELS)[r], 2,
           on and { 1, 1, 1, 1 } or { 0, 0, 0, 1 })
  end
  local x = 4 * bw
  c:text(x + 6, h / 2 - 7, format("-%3d +", st.nodes), 2, { 0, 0, 0, 1 })
  c:text(x + 106, h / 2 - 7, format("%s %.2f", st.phyllotaxis, st.pressure), 2,
         { 0, 0, 0, 1 })
  return c
end

-- }=========================================================================================

-- {=========================================================================================
-- The window

--- Where the panes go, in fractions of the window (y down): the toolbar and the sketch on
-- the left, the plant on the right, the function plots under it (Tab hides them).
function M.layout (plots)
  local lay = {
    scene = { 0.5, 0, 1, plots and 0.68 or 1 },
    panes = {
      { 0, 0, 0.5, 0.05, bg = { 0.93, 0.93, 0.93 } },            -- 1 the toolbar
      { 0, 0.05, 0.5, 1, bg = { 0.8, 0.8, 0.8 } },               -- 2 the sketch
    },
  }
  if plots then lay.panes[3] = { 0.5, 0.68, 1, 1, bg = { 1, 1, 1 } } end   -- 3 the plots
  return lay
end

--- Where the sketch point (x, y) is in a winw x winh window (the arithmetic of the panes in
-- csrc/gl/vpanes.c): for driving the window from tests.
function M.to_window (st, winw, winh, x, y)
  local r = M.layout(true).panes[2]
  local function round (v) return floor(v + 0.5) end
  local px, py = round(r[1] * winw), round(r[2] * winh)
  local pw, ph = round(r[3] * winw) - px, round(r[4] * winh) - py
  local s = min(pw / st.width, ph / st.height)
  return px + (pw - s * st.width) / 2 + s * x, py + (ph - s * st.height) / 2 + s * y
end

--- The pipeline of a sketch table: lsys.sketch's Sketch, its model, derived and
-- interpreted. Raises the pipeline's error (a sketch that makes no plant yet).
-- `org`: the organ (an Organ of lsys.sketch.organ; nil, the default leaf).
function M.pipeline (t, org)
  local sk = sketch.load(t)
  local m = sk:model { phyllotaxis = t.phyllotaxis, organ = org }
  local s = m:derive()
  return { sketch = sk, model = m, lstring = s, scene = m:interpret(s), organ = org }
end

M.HELP = [[
left drag: draw a stroke   1 2 3 4 (or the toolbar): stem, left, right boundary, inclination
right drag / shift drag: move the nearest stroke   Ctrl+left drag: redraw it in place
Delete / Backspace: delete the selected stroke   A: nodes and rays over the sketch
wheel over the sketch, [ ]: pressure of the points drawn next (nearer darker, farther lighter);
a tablet pen's own pressure when X reports one
+ -: nodes per layer   P: phyllotaxis   Tab: function plots   Ctrl+Z: undo
O: draw the organ (1 2 top view boundaries, 3 side view midrib, 4 front view section) or
the plant again
Ctrl+S: save the sketch (and the organ)   Ctrl+E: export the plant (.glb, .obj, .png) and
the model (.lua, and .l for cpfg)
over the plant: drag orbit, right drag pan, wheel zoom   R: reset view   F: fit
S: screenshot   H: this help   Esc / Q: quit]]

local function first_line (msg)
  msg = tostring(msg):gsub("^lsys: ", ""):gsub("^[^:\n]*%.lua:%d+: ", "")
  return (msg:match("^[^\n]*"))
end

-- The session: the state, the window, the last pipeline result.
local Session = {}
Session.__index = Session

function Session:status ()
  local st = self.st
  local head = format("%s%d strokes  %d nodes/layer  %s  pressure %.2f  ",
                      st.mode == "organ" and "ORGAN  " or "", #st:list(), st.nodes,
                      st.phyllotaxis, st.pressure)
  local tail
  if self.error then tail = self.error
  elseif self.organ_error then
    tail = format("organ: %s (the plant shows the default leaf)  |  %d modules  %d triangles",
                  self.organ_error, #self.result.lstring, self.result.scene.ntriangles)
  elseif self.result then
    tail = format("%d modules  %d triangles", #self.result.lstring, self.result.scene.ntriangles)
  else tail = "draw a stem (1), boundaries (2, 3) and inclination lines (4)" end
  if st.status then tail = st.status .. "  |  " .. tail end
  return head .. tail
end

function Session:show_sketch ()
  local st, v = self.st, self.v
  local an
  if st.overlay and self.result and self.result.sketch.analysis then
    local ok, a = pcall(self.result.sketch.analysis, self.result.sketch)
    if ok then an = a end
  end
  M.draw_sketch(st, self.canvas, an)
  v:image(2, self.canvas:pixels(), st.width, st.height)
  M.draw_toolbar(st, self.toolbar)
  v:image(1, self.toolbar:pixels(), M.TOOLBAR_W, M.TOOLBAR_H)
  v:text(self:status(), M.HELP)
end

function Session:show_plots ()
  if not self.plots then return end
  local c
  if self.result and self.result.sketch.functions then
    local pok, pc = pcall(function ()
      return plot.functions(self.result.sketch:functions(), { width = 900, height = 330 })
    end)
    if pok then c = pc end
  end
  if c == nil then
    c = core.canvas(900, 330, { 1, 1, 1, 1 })
    c:text(20, 150, self.error and "no functions: the sketch makes no plant yet"
      or "the function plots appear here", 2, { 0.3, 0.3, 0.3, 1 })
  end
  local w, h = c:size()
  self.v:image(3, c:pixels(), w, h)
end

-- The organ the strokes of the organ make (built again when they changed), or nil and
-- why not (no strokes: nil, nil).
function Session:organ ()
  local st = self.st
  local drawing = st.drawing and st.drawing.list == st.organ_strokes
  local key = st.organ_version .. (drawing and ":" .. #st.drawing.points or "")
  if self.organ_key ~= key then
    local t = st:organ_table()
    self.organ_key, self.organ_built, self.organ_why = key, nil, nil
    if t then
      local ok, o = pcall(organs.load, t)
      if ok then self.organ_built = o
      else self.organ_why = first_line(tostring(o):gsub("^lsys%.sketch%.organ%.load: ", "")) end
    end
  end
  return self.organ_built, self.organ_why
end

-- Runs the pipeline on the sketch and posts the plant and its plots, or the error.
function Session:compute ()
  local st = self.st
  st.changed = false
  local org, why = self:organ()
  self.organ_error = why
  local ok, r = pcall(self.pipeline, st:sketch(), org)
  if ok then
    self.result, self.error = r, nil
    self.v:post({ { scene = r.scene, modules = #r.lstring } },
      { keep_camera = self.posted or nil, title = self.title })
    self.posted = true
  else
    self.result, self.error = nil, first_line(r)
    self.v:post({ { scene = self.empty } }, { keep_camera = true, title = self.title })
  end
  -- the plots follow the plant at every update, while drawing too: a plant beside "no
  -- plant yet" (or functions of a sketch that no longer makes one) would be stale
  self:show_plots()
end

-- Says once, at the first press on the sketch, whether a tablet's pressure is read.
function Session:tell_pen ()
  local ok, vs = pcall(self.v.state, self.v)
  if not ok or type(vs) ~= "table" or vs.pen == nil then return end
  self.pen_told = true
  local msg = vs.pen and "tablet pressure from " .. vs.pen_devices
    or "no tablet pressure (" .. tostring(vs.pen_devices) .. "): the wheel and [ ] set it"
  self.st.status = self.st.status and self.st.status .. "  |  " .. msg or msg
  self.out(msg .. "\n")
end

function Session:export ()
  local r = self.result
  if r == nil then
    self.st.status = "nothing to export: " .. (self.error or "no plant")
    return
  end
  local base = self.st:save_path():gsub("%.[^./]*$", "")
  r.scene:save(base .. ".glb")
  r.scene:save(base .. ".obj")                       -- and its .mtl
  render(r.scene, { out = base .. ".png", width = 800, height = 800 })
  local files = { base .. ".glb", base .. ".obj", base .. ".png" }
  if r.sketch.save_model then
    r.sketch:save_model(base .. ".lua", { organ = r.organ })
    files[#files + 1] = base .. ".lua"
    -- and for cpfg and L-studio, as the paper's program exported it (§7)
    r.sketch:save_cpfg(base .. ".l", { organ = r.organ })
    files[#files + 1] = base .. ".l (cpfg)"
  end
  self.st.status = "exported " .. table.concat(files, ", ")
  self.out(self.st.status .. "\n")
end

-- One event of the window; returns true when the pictures must be drawn again.
function Session:event (ev)
  local st = self.st
  if ev.type == "pointer" then
    if ev.pane == 1 then
      return ev.phase == "down" and st:toolbar(ev.x) or ev.phase == "down"
    elseif ev.pane == 2 then
      st:pointer(ev.phase, ev.x, ev.y, ev.button, ev.shift, ev.pressure, ev.ctrl)
      if ev.phase == "down" and not self.pen_told then self:tell_pen() end
      return true
    end
  elseif ev.type == "scroll" and ev.pane == 2 then
    st:scroll(ev.dy)
    return true
  elseif ev.type == "key" then
    local act = st:key(ev.key, ev.ctrl)
    if act == "save" then
      local ok, err, opath = pcall(st.save, st)
      if ok then self.out(format("saved %s\n", err)) else st.status = first_line(err) end
      if ok and opath then self.out(format("saved %s\n", opath)) end
    elseif act == "export" then
      local ok, err = pcall(self.export, self)
      if not ok then st.status = "cannot export: " .. first_line(err) end
    elseif act == "plots" then
      self.plots = not self.plots
      self.v:layout(M.layout(self.plots))
      self:show_plots()
    end
    return true
  elseif ev.type == "screenshot" and ev.ok then
    self.out(format("wrote %s\n", ev.path))
  end
  return false
end

--- The session of state `st` in window `v` (a core Viewer, or a stand-in with its
-- post, layout, image and text methods): lays the panes out, computes the plant and
-- shows everything. opts: `pipeline`, `out`, `file` as for `run`.
function M.session (v, st, opts)
  local self = setmetatable({
    st = st, v = v, plots = true, pipeline = opts.pipeline or M.pipeline,
    out = opts.out or function () end,
    title = "lsys sketch: " .. (opts.file or "sketch.json"),
    canvas = core.canvas(st.width, st.height), toolbar = core.canvas(M.TOOLBAR_W, M.TOOLBAR_H),
    empty = model.lsystem({ axiom = "", name = "no plant" }):interpret(),
  }, Session)
  v:layout(M.layout(self.plots))
  self:compute()
  self:show_sketch()
  return self
end

--- Opens the sketch window and runs it until it is closed. opts: `file` (the sketch file:
-- read when it exists, where Ctrl+S saves), `width`, `height` (a new sketch's size),
-- `nodes`, `phyllotaxis`, `organ` (an Organ, drawn at the nodes and edited with O),
-- `organ_file` (where Ctrl+S saves the organ), `window` ({w, h}, default 1200 x 800),
-- `pipeline` (default M.pipeline), `out` (function writing the lines the program prints).
function M.run (opts)
  opts = opts or {}
  local sk
  if opts.file and core.filestamp(opts.file) then sk = read.file(opts.file) end
  local st = M.new { sketch = sk, file = opts.file, width = opts.width, height = opts.height,
                     nodes = opts.nodes, phyllotaxis = opts.phyllotaxis, organ = opts.organ,
                     organ_file = opts.organ_file }
  local win = opts.window or { 1200, 800 }
  local v = core.viewer_open { width = win[1], height = win[2] }
  local self = M.session(v, st, opts)
  local last = -huge
  while true do
    local ev = v:poll(st.drawing and 0.01 or 0.1)
    local redraw = false
    while ev ~= nil do
      if ev.type == "closed" then v:close() return st end
      if self:event(ev) then redraw = true end
      ev = v:poll(0)
    end
    -- the plant follows the pen: at most every 50 ms while drawing, always at release
    if st.changed and (st.drawing == nil or now() - last >= 0.05) then
      self:compute()
      last = now()
      redraw = true
    end
    if redraw then self:show_sketch() end
  end
end

-- }=========================================================================================

return M
