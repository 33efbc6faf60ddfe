--- The parameter form of the viewer's editing panes (docs/viewer.md, "Editing a plant"):
-- a list of items drawn as sliders (numbers), toggles (booleans) and rows of buttons
-- (choices), driven by pointer events in the canvas's own pixels. An item is
--
--   { name =, label = (default the name), kind = "number" | "boolean" | "choice" | "curve",
--     value =, default =, min =, max =, step = (numbers; optional), choices = { ... },
--     note = (a string shown after the value, e.g. the #define a vlab slider sets),
--     get = function () -> value (optional: the value as the target has it after a set),
--     set = function (v) }
--
-- `set` gets a value already checked against the item: inside min .. max and on a step
-- (numbers), one of the choices. A "curve" item (a range function) is a row that calls
-- opts.on_curve(item) when clicked: the host opens the curve editor on it.
--
-- The mouse does everything: drag a slider (or click on its track), click a toggle or a
-- choice, right-click a row to give it its default again; the buttons at the bottom reset
-- the selected row, reset all, and save (opts.on_save). Keys: up / down select a row,
-- left / right move its slider by a step (shift: ten), Ctrl+R resets it, Ctrl+Shift+R
-- resets all. The wheel scrolls a form longer than the pane.
-- @module lsys.ui.form
local type, ipairs, tostring, pcall, error, setmetatable, math, string, table =
      type, ipairs, tostring, pcall, error, setmetatable, math, string, table
local format = string.format
local floor, max, min, log = math.floor, math.max, math.min, math.log
local _ENV = nil

local M = {}

M.TITLE_H = 30       -- the title row
M.ROW_H = 50         -- one item
M.BAR_H = 40         -- the buttons at the bottom
M.MARGIN = 12
M.BUTTONS = { "reset", "reset all", "save" }

local INK, GREY, LIGHT = { 0.1, 0.1, 0.12, 1 }, { 0.45, 0.45, 0.5, 1 }, { 0.85, 0.85, 0.88, 1 }
local ACCENT, SELECT = { 0.2, 0.45, 0.8, 1 }, { 0.88, 0.93, 1, 1 }

local Form = {}
Form.__index = Form

-- A message without the places in front ("model.lua:3: "), which say nothing in a pane.
local function bare (msg)
  msg = tostring(msg)
  local n
  repeat msg, n = msg:gsub("^[^\n:]*:%d+: ", "", 1) until n == 0
  return msg
end
M.bare = bare

local function isnum (x) return type(x) == "number" and x == x and x - x == 0 end

-- An item, checked: what the form draws and sets.
local function checkitem (it, i)
  local function bad (msg)
    error(format("lsys.ui.form: item %d (%s): %s", i, tostring(it.name), msg), 4)
  end
  if type(it) ~= "table" then bad("a table expected") end
  if type(it.name) ~= "string" then bad("a name expected") end
  if type(it.set) ~= "function" and it.kind ~= "curve" then bad("a set function expected") end
  if it.kind == "number" then
    if not (isnum(it.min) and isnum(it.max) and it.min < it.max) then
      bad("a number needs min < max")
    end
    if it.step ~= nil and not (isnum(it.step) and it.step > 0) then bad("step must be > 0") end
  elseif it.kind == "choice" then
    if type(it.choices) ~= "table" or #it.choices == 0 then bad("a choice needs choices") end
  elseif it.kind ~= "boolean" and it.kind ~= "curve" then
    bad("kind must be number, boolean, choice or curve, got " .. tostring(it.kind))
  end
end

--- A form of `items` (a list, or a function returning the list: asked again by `refresh`).
-- opts: title, on_save() -> message, on_curve(item), on_error(msg) (a set that raised).
function M.new (items, opts)
  opts = opts or {}
  local self = setmetatable({
    source = items, opts = opts, title = opts.title or "parameters", name = opts.name or "params",
    items = {}, selected = nil, scroll = 0, drag = nil, message = nil,
  }, Form)
  self:refresh()
  self.help = "params pane: drag a slider, click a toggle or a choice; right-click a row: "
    .. "its default\nup / down: select   left / right: a step (shift: ten)   "
    .. "Ctrl+R: reset it   Ctrl+Shift+R: reset all\nCtrl+S: save the values"
  return self
end

--- Reads the items again (after the target changed them, or a new selection).
function Form:refresh ()
  local list = self.source
  if type(list) == "function" then list = list() end
  list = list or {}
  for i, it in ipairs(list) do checkitem(it, i) end
  self.items = list
  if self.selected and self.selected > #list then self.selected = nil end
  self.scroll = min(self.scroll, max(0, #list * M.ROW_H - 200))
end

--- The value of item i as the target has it.
function Form:value (i)
  local it = self.items[i]
  if it.get then return it.get() end
  return it.value
end

-- The value `v` for item `it`: clamped, on its step; nil when it is not one it can take.
function M.check (it, v)
  if it.kind == "number" then
    if not isnum(v) then return nil end
    v = max(it.min, min(it.max, v))
    if it.step then
      v = it.min + floor((v - it.min) / it.step + 0.5) * it.step
      if v > it.max then v = v - it.step end
      local iv = math.tointeger(v)
      if iv and math.type(it.step) == "integer" and math.type(it.min) == "integer" then v = iv end
    end
    return v
  elseif it.kind == "boolean" then
    if type(v) ~= "boolean" then return nil end
    return v
  elseif it.kind == "choice" then
    for _, c in ipairs(it.choices) do if c == v then return v end end
    return nil
  end
  return nil
end

--- Sets item i to `v` (checked); true when the value changed. A set that raises leaves
-- the message in `message` (shown in the pane) and returns false.
function Form:set (i, v)
  local it = self.items[i]
  v = M.check(it, v)
  if v == nil or v == self:value(i) then return false end
  local ok, err = pcall(it.set, v)
  if not ok then
    self.message = bare(err)
    if self.opts.on_error then self.opts.on_error(self.message) end
    return false
  end
  if not it.get then it.value = v end
  self.message = nil
  return true
end

--- Gives item i (default: the selected one) its default; true when it changed.
function Form:reset (i)
  i = i or self.selected
  local it = i and self.items[i]
  if it == nil or it.default == nil then return false end
  return self:set(i, it.default)
end

function Form:reset_all ()
  local any = false
  for i in ipairs(self.items) do if self:reset(i) then any = true end end
  return any
end

-- Geometry ---------------------------------------------------------------------------

--- The canvas rectangle of item i's row (x, y, w, h) in a w x h canvas.
function Form:row_rect (i, w)
  return 0, M.TITLE_H + (i - 1) * M.ROW_H - self.scroll, w, M.ROW_H
end

--- The slider track of row i: x0, x1 and its y.
function Form:track (i, w)
  local _, y = self:row_rect(i, w)
  return M.MARGIN + 6, w - M.MARGIN - 6, y + 36
end

-- The fraction along a number item's range of `v`.
local function frac (it, v) return (v - it.min) / (it.max - it.min) end

--- Where to press on a canvas w pixels wide to set number item i to v: x, y (tests aim
-- with it).
function Form:point_of (i, v, w)
  local x0, x1, y = self:track(i, w)
  return x0 + (x1 - x0) * frac(self.items[i], v), y
end

-- The choice buttons of row i: a list of { x, w } in a canvas w wide.
local function choice_boxes (it, w)
  local n = #it.choices
  local x0, x1 = M.MARGIN, w - M.MARGIN
  local bw = (x1 - x0) / n
  local t = {}
  for k = 1, n do t[k] = { x0 + (k - 1) * bw, bw } end
  return t
end

--- The row under canvas point (x, y), or nil; and the bottom button's index there.
function Form:hit (x, y, w, h)
  if y >= h - M.BAR_H then
    local bw = w / #M.BUTTONS
    local b = floor(x / bw) + 1
    if b >= 1 and b <= #M.BUTTONS then return nil, b end
    return nil
  end
  if y < M.TITLE_H then return nil end
  local i = floor((y + self.scroll - M.TITLE_H) / M.ROW_H) + 1
  if i >= 1 and i <= #self.items then return i end
  return nil
end

--- The centre of bottom button b (1 reset, 2 reset all, 3 save) in a w x h canvas.
function M.button_point (b, w, h)
  local bw = w / #M.BUTTONS
  return (b - 0.5) * bw, h - M.BAR_H / 2
end

-- Events ------------------------------------------------------------------------------

-- A drag on number row i at canvas x.
function Form:slide (i, x, w)
  local it = self.items[i]
  local x0, x1 = self:track(i, w)
  local f = max(0, min(1, (x - x0) / (x1 - x0)))
  return self:set(i, it.min + f * (it.max - it.min))
end

function Form:button (b)
  if b == 1 then return self:reset()
  elseif b == 2 then return self:reset_all()
  elseif b == 3 then
    local save = self.opts.on_save
    if save == nil then self.message = "nothing to save to" return true end
    local ok, msg = pcall(save)
    self.message = ok and msg or bare(msg)
    return true
  end
  return false
end

--- A pointer event (the pane interface); `w`, `h` the canvas size (default the last drawn).
function Form:pointer (phase, x, y, button, _shift, _ctrl, w, h)
  w, h = w or self.w or 432, h or self.h or 760
  if phase == "move" then
    if self.drag then self:slide(self.drag, x, w) return true end
    return false
  elseif phase == "up" then
    local was = self.drag ~= nil
    self.drag = nil
    return was
  end
  local i, b = self:hit(x, y, w, h)
  if b then return self:button(b) or true end
  if i == nil then return false end
  self.selected = i
  local it = self.items[i]
  if button == "right" then self:reset(i) return true end
  if it.kind == "number" then
    self.drag = i
    self:slide(i, x, w)
  elseif it.kind == "boolean" then
    self:set(i, not self:value(i))
  elseif it.kind == "choice" then
    for k, box in ipairs(choice_boxes(it, w)) do
      if x >= box[1] and x < box[1] + box[2] then self:set(i, it.choices[k]) end
    end
  elseif it.kind == "curve" and self.opts.on_curve then
    self.opts.on_curve(it)
  end
  return true
end

function Form:scroll (dy)
  local h = self.h or 760
  local room = #self.items * M.ROW_H - (h - M.TITLE_H - M.BAR_H)
  local s = max(0, min(max(0, room), self.scroll - dy * M.ROW_H))
  if s == self.scroll then return false end
  self.scroll = s
  return true
end

--- Moves the selected number by k steps (its step, else a hundredth of its range).
function Form:nudge (k)
  local i = self.selected
  local it = i and self.items[i]
  if it == nil then return false end
  if it.kind == "number" then
    return self:set(i, self:value(i) + k * (it.step or (it.max - it.min) / 100))
  elseif it.kind == "boolean" then
    return self:set(i, k > 0)
  elseif it.kind == "choice" then
    local at = 1
    for c, x in ipairs(it.choices) do if x == self:value(i) then at = c end end
    local n = #it.choices
    return self:set(i, it.choices[(at - 1 + (k > 0 and 1 or -1)) % n + 1])
  end
  return false
end

function Form:key (name, ctrl, shift)
  local n = #self.items
  if name == "down" and n > 0 then
    self.selected = self.selected and min(n, self.selected + 1) or 1
    return true
  elseif name == "up" and n > 0 then
    self.selected = self.selected and max(1, self.selected - 1) or 1
    return true
  elseif name == "right" or name == "left" then
    self:nudge((name == "right" and 1 or -1) * (shift and 10 or 1))
    return true
  elseif name == "r" and ctrl then
    if shift then self:reset_all() else self:reset() end
    return true
  end
  return false
end

--- A value as the row shows it: a number to its step's decimals (else 4 significant
-- digits), on/off, the choice.
function M.show (it, v)
  if it.kind == "number" then
    if math.type(v) == "integer" then return format("%d", v) end
    if it.step then
      local d = max(0, min(6, -floor(log(it.step, 10) + 1e-9)))
      return format("%." .. d .. "f", v)
    end
    return format("%.4g", v)
  elseif it.kind == "boolean" then return v and "on" or "off"
  elseif it.kind == "curve" then return "curve: click to edit"
  end
  return tostring(v)
end

--- One line of the current values, for the status line: "R 1.46  leaf on".
function Form:status ()
  local t = {}
  for i, it in ipairs(self.items) do
    if it.kind ~= "curve" then t[#t + 1] = it.name .. " " .. M.show(it, self:value(i)) end
    if #t >= 6 then t[#t + 1] = "..." break end
  end
  local s = table.concat(t, "  ")
  if self.message then s = s .. "  | " .. self.message end
  return s
end

-- Drawing -----------------------------------------------------------------------------

local function draw_row (self, c, i, w)
  local it = self.items[i]
  local _, y = self:row_rect(i, w)
  local v = self:value(i)
  if i == self.selected then c:rect(0, y, w, M.ROW_H, SELECT, true) end
  c:line(M.MARGIN, y + M.ROW_H - 1, w - M.MARGIN, y + M.ROW_H - 1, 1, LIGHT)
  local label = it.label or it.name
  c:text(M.MARGIN, y + 6, label, 2, INK)
  local shown = M.show(it, v)
  if it.note then shown = shown .. " " .. it.note end
  local lw, scale = c:text_width(label, 2), 2
  if lw + c:text_width(shown, 2) + 3 * M.MARGIN > w then scale = 1 end   -- a long label
  local vw = c:text_width(shown, scale)
  c:text(w - M.MARGIN - vw, y + (scale == 2 and 6 or 10), shown, scale,
         it.kind == "curve" and GREY or ACCENT)
  if it.kind == "number" then
    local x0, x1, ty = self:track(i, w)
    c:rect(x0, ty - 3, x1 - x0, 6, LIGHT, true)
    local kx = x0 + (x1 - x0) * max(0, min(1, frac(it, v)))
    c:rect(x0, ty - 3, kx - x0, 6, ACCENT, true)
    if it.default ~= nil and isnum(it.default) then     -- the default: a tick under the track
      local dx = x0 + (x1 - x0) * max(0, min(1, frac(it, it.default)))
      c:line(dx, ty + 5, dx, ty + 10, 2, GREY)
    end
    c:circle(kx, ty, 8, self.drag == i and INK or ACCENT)
    c:text(x0 - 4, ty + 5, M.show(it, it.min), 1, GREY)
    local mx = M.show(it, it.max)
    c:text(x1 + 4 - c:text_width(mx, 1), ty + 5, mx, 1, GREY)
  elseif it.kind == "boolean" then
    local bx, by = M.MARGIN, y + 26
    c:rect(bx, by, 18, 18, { 1, 1, 1, 1 }, true)
    c:rect(bx, by, 18, 18, GREY)
    if v then c:rect(bx + 4, by + 4, 10, 10, ACCENT, true) end
    c:text(bx + 26, by + 2, v and "on (click: off)" or "off (click: on)", 2, GREY)
  elseif it.kind == "choice" then
    for k, box in ipairs(choice_boxes(it, w)) do
      local on = it.choices[k] == v
      c:rect(box[1] + 1, y + 26, box[2] - 2, 20, on and ACCENT or { 1, 1, 1, 1 }, true)
      c:rect(box[1] + 1, y + 26, box[2] - 2, 20, GREY)
      local s = tostring(it.choices[k])
      local tw = c:text_width(s, 1)
      c:text(box[1] + (box[2] - tw) / 2, y + 32, s, 1, on and { 1, 1, 1, 1 } or INK)
    end
  end
end

--- Draws the form into canvas `c` (the pane interface).
function Form:draw (c)
  local w, h = c:size()
  self.w, self.h = w, h
  c:clear({ 0.97, 0.97, 0.98, 1 })
  c:clip(0, M.TITLE_H, w, h - M.TITLE_H - M.BAR_H)
  for i = 1, #self.items do
    local _, y = self:row_rect(i, w)
    if y + M.ROW_H >= M.TITLE_H and y <= h - M.BAR_H then draw_row(self, c, i, w) end
  end
  c:clip()
  c:rect(0, 0, w, M.TITLE_H, { 0.9, 0.9, 0.93, 1 }, true)
  c:text(M.MARGIN, 8, self.title, 2, INK)
  if #self.items == 0 then
    c:text(M.MARGIN, M.TITLE_H + 16, "no parameters", 2, GREY)
  end
  local msg = self.message
  if msg then
    local y = h - M.BAR_H - 22
    c:rect(0, y - 4, w, 24, { 1, 0.95, 0.85, 1 }, true)
    c:text(M.MARGIN, y, msg:sub(1, floor((w - 2 * M.MARGIN) / 12)), 2, { 0.5, 0.2, 0, 1 })
  end
  local bw = w / #M.BUTTONS
  for b, name in ipairs(M.BUTTONS) do
    local x = (b - 1) * bw
    c:rect(x + 4, h - M.BAR_H + 6, bw - 8, M.BAR_H - 12, { 1, 1, 1, 1 }, true)
    c:rect(x + 4, h - M.BAR_H + 6, bw - 8, M.BAR_H - 12, GREY)
    local tw = c:text_width(name, 2)
    c:text(x + (bw - tw) / 2, h - M.BAR_H + 13, name, 2, INK)
  end
  return c
end

return M
