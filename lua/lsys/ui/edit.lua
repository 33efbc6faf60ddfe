--- Editing a plant live in the viewer window (docs/viewer.md, "Editing a plant"): the
-- scene on the left, on the right a row of tabs over one pane (the parameter form,
-- lsys.ui.form, and the panes a subject brings: curves, the component graph, the
-- palette). The panes follow one interface (draw into a canvas, pointer, scroll, key,
-- status, and optionally pick, items, save; lsys.ui.form's header says it).
--
-- A SUBJECT is what is edited and how the plant is made again:
--
--   { title =, items = function () -> form items, panes = { pane, ... },
--     build = function (check) -> Scene (check() between derivation steps: it raises
--                                        when a newer edit came meanwhile),
--     save = function () -> message (Ctrl+S and the form's save button), stop = fn }
--
-- An edit marks the plant stale; `idle` (called by lsys.viewer's poll once the window's
-- events are handled) builds it again and posts it. While a build runs, `check` handles
-- the events that came meanwhile: an edit among them abandons the build, which starts
-- again from the newest values, so a slider dragged fast shows the last value at once
-- and never a queue of old ones. The window draws on its own thread all the while.
-- @module lsys.ui.edit
local form = require "lsys.ui.form"
local curve = require "lsys.ui.curve"
local core = require "lsys.core"
local now = require("lsys.program").clock

local type, ipairs, pcall, error, tostring, setmetatable, rawequal =
      type, ipairs, pcall, error, tostring, setmetatable, rawequal
local string, table, math = string, table, math
local format = string.format
local floor = math.floor
local _ENV = nil

local M = {}

M.SPLIT = 0.64             -- the scene's share of the window's width
M.TABS = 0.045             -- the tab row's share of the height
M.BOTTOM = 0.965           -- where the panes end: the status line is below
M.PANE_W, M.PANE_H = 432, 736
M.TABS_H = 36

M.MAIN_H = 400            -- a pane with values of its own: its height over them
M.ITEMS_H = M.PANE_H - M.MAIN_H

--- The layout (lsys.core's v:layout) of the editing window: the scene, the tabs (pane 1),
-- the active pane (pane 2); with `split` (a pane that has values of its own, `items`),
-- the pane over a form of its values (pane 3).
function M.layout (split)
  local lay = {
    scene = { 0, 0, M.SPLIT, 1 },
    panes = {
      { M.SPLIT, 0, 1, M.TABS, bg = { 0.9, 0.9, 0.93 } },
      { M.SPLIT, M.TABS, 1, M.BOTTOM, bg = { 0.97, 0.97, 0.98 } },
    },
  }
  if split then
    local y = M.TABS + (M.BOTTOM - M.TABS) * M.MAIN_H / M.PANE_H
    lay.panes[2][4] = y
    lay.panes[3] = { M.SPLIT, y, 1, M.BOTTOM, bg = { 0.97, 0.97, 0.98 } }
  end
  return lay
end

--- The size of pane k's image (1 tabs, 2 the pane, 3 its values) in the layout.
function M.size (k, split)
  if k == 1 then return M.PANE_W, M.TABS_H end
  if not split then return M.PANE_W, M.PANE_H end
  return M.PANE_W, k == 2 and M.MAIN_H or M.ITEMS_H
end

--- Where the pixel (x, y) of pane k's image is in a winw x winh window (`split` as for
-- `layout`): what the Xvfb tests aim with (the arithmetic of csrc/gl/vpanes.c).
function M.to_window (k, x, y, winw, winh, split)
  local r = M.layout(split).panes[k]
  local w, h = M.size(k, split)
  local function round (v) return floor(v + 0.5) end
  local px, py = round(r[1] * winw), round(r[2] * winh)
  local pw, ph = round(r[3] * winw) - px, round(r[4] * winh) - py
  local s = math.min(pw / w, ph / h)
  return px + (pw - s * w) / 2 + s * x, py + (ph - s * h) / 2 + s * y
end

M.HELP = [[
over the plant: drag orbit, right drag pan, wheel zoom, click pick   R: reset view   F: fit
W: wireframe   G: sky and ground   L: light on the leaves   S: screenshot   H: this help
Esc / Q: quit
the tabs (or Tab): the panes   Ctrl+S: save the edits   Ctrl+Z: undo the last edit]]

local SUPERSEDED = setmetatable({}, { __tostring = function () return "superseded" end })
local CLOSED = setmetatable({}, { __tostring = function () return "closed" end })

local Session = {}
Session.__index = Session

-- The first line of an error, without lsys's own source positions (a model file's stay).
local function first_line (msg)
  msg = tostring(msg):gsub("^lsys: ", "")
  local n
  repeat msg, n = msg:gsub("^[^\n:]*lsys/[%w_/]*%.lua:%d+: ", "", 1) until n == 0
  return (msg:match("^[^\n]*"))
end

--- The session of `subject` in window `v` (a core Viewer or a stand-in with layout, image
-- and text): opts.post(scene) shows a plant (lsys.viewer's), opts.poll() handles the
-- events that are waiting (returns false once the window closed), opts.out(msg).
function M.session (v, subject, opts)
  opts = opts or {}
  local self = setmetatable({
    v = v, subject = subject, post = opts.post, poll = opts.poll, out = opts.out or
    function () end, active = 1, dirty = false, building = false, stats = nil,
    error = nil, superseded = 0, builds = 0, undo = {}, title = subject.title or "edit",
    tabsc = core.canvas(M.PANE_W, M.TABS_H), panec = core.canvas(M.PANE_W, M.PANE_H),
    mainc = core.canvas(M.PANE_W, M.MAIN_H), itemc = core.canvas(M.PANE_W, M.ITEMS_H),
    itemform = nil, split = false,
  }, Session)
  self.form = form.new(subject.items or {}, {
    title = subject.form_title or "parameters", name = subject.form_name,
    on_save = function () return self:save() end,
    on_curve = function (item) self:open_curve(item) end,
  })
  self.form.message = subject.note
  self.tabs = { subject.first or self.form }     -- (a graph's pane before its form)
  for _, p in ipairs(subject.panes or {}) do self.tabs[#self.tabs + 1] = p end
  if subject.attach then subject.attach(self) end
  self:arrange()
  return self
end

--- Opens where session `prev` (of the same window, before a reload) was: the same tab,
-- the same row selected, the same scroll.
function Session:resume (prev)
  if prev.tabs[prev.active] and self.tabs[prev.active] and
     prev.tabs[prev.active].name == self.tabs[prev.active].name then
    self.active = prev.active
  end
  local f = prev.form
  if f.selected and f.selected <= #self.form.items then self.form.selected = f.selected end
  self.form.scroll = f.scroll
  self:draw()
end

--- Marks the plant stale: the next `idle` builds it again (an edit calls it).
function Session:changed ()
  self.dirty = true
end

--- The active pane.
function Session:pane () return self.tabs[self.active] end

function Session:status ()
  local parts = {}
  local p = self:pane()
  local ps = p.status and p:status()
  if ps and ps ~= "" then parts[#parts + 1] = ps end
  if p ~= self.form then
    local fs = self.form:status()
    if fs ~= "" then parts[#parts + 1] = fs end
  end
  if self.error then parts[#parts + 1] = "error: " .. self.error
  elseif self.stats then
    local s = self.stats
    parts[#parts + 1] = format("%s%d triangles  %.1f ms", s.modules and
      format("%d modules  ", s.modules) or "", s.triangles, s.ms)
  end
  if self.message then parts[#parts + 1] = self.message end
  return table.concat(parts, "  |  ")
end

function Session:help ()
  local h = self:pane().help           -- a string, or a list of lines
  if type(h) == "table" then h = table.concat(h, "\n") end
  return M.HELP .. (h and "\n" .. h or "")
end

local function draw_tabs (self, c)
  local w, h = c:size()
  c:clear({ 0.9, 0.9, 0.93, 1 })
  local n = #self.tabs
  local bw = w / n
  for k, p in ipairs(self.tabs) do
    local on = k == self.active
    local x = (k - 1) * bw
    c:rect(x + 2, 3, bw - 4, h - 3, on and { 0.97, 0.97, 0.98, 1 } or { 0.8, 0.8, 0.84, 1 },
           true)
    local name = p.name or "pane"
    local tw = c:text_width(name, 2)
    c:text(x + (bw - tw) / 2, (h - 14) / 2 + 1, name, 2,
           on and { 0.1, 0.1, 0.12, 1 } or { 0.35, 0.35, 0.4, 1 })
  end
end

-- Draws pane p into canvas c, or says why it failed.
local function draw_pane (p, c)
  local ok, err = pcall(p.draw, p, c)
  if not ok then
    c:clear({ 1, 1, 1, 1 })
    c:text(12, 40, "the pane failed: " .. first_line(err):sub(1, 30), 2, { 0.6, 0, 0, 1 })
  end
end

--- Lays the window out for the active pane (over a form of its values when it has any)
-- and draws it.
function Session:arrange ()
  local p = self:pane()
  local split = p ~= self.form and type(p.items) == "function"
  if split then
    self.itemform = form.new(function () return p:items() or {} end,
      { title = (p.name or "pane") .. ": values", name = "values",
        on_curve = function (item) self:open_curve(item) end,
        on_save = function () return self:save() end })
  else
    self.itemform = nil
  end
  self.split = split
  self.v:layout(M.layout(split))
  self:draw()
end

--- Draws the tabs, the active pane (and its values), and the status and help texts.
function Session:draw ()
  draw_tabs(self, self.tabsc)
  self.v:image(1, self.tabsc:pixels(), M.PANE_W, M.TABS_H)
  local p = self:pane()
  if self.split then
    draw_pane(p, self.mainc)
    self.v:image(2, self.mainc:pixels(), M.PANE_W, M.MAIN_H)
    self.itemform:refresh()
    draw_pane(self.itemform, self.itemc)
    self.v:image(3, self.itemc:pixels(), M.PANE_W, M.ITEMS_H)
  else
    draw_pane(p, self.panec)
    self.v:image(2, self.panec:pixels(), M.PANE_W, M.PANE_H)
  end
  self.v:text(self:status(), self:help())
end

--- The tab at x of the tab row (1-based).
function Session:tab_at (x)
  local k = floor(x / (M.PANE_W / #self.tabs)) + 1
  if k >= 1 and k <= #self.tabs then return k end
  return nil
end

function Session:select (k)
  if k == self.active or self.tabs[k] == nil then return false end
  self.active = k
  local p = self:pane()
  if p.refresh then p:refresh() end
  self:arrange()
  return true
end

--- The tab of the pane named `name`, or nil.
function Session:find (name)
  for k, p in ipairs(self.tabs) do if p.name == name then return k end end
  return nil
end

-- A form item of kind "curve" was clicked (a component's range): the curve pane edits it,
-- one made for it when there is none yet.
function Session:open_curve (item)
  local k = self:find("curves")
  if k == nil then
    local ok, p = pcall(curve.new, item, { on_change = function () self:changed() end })
    if not ok then self.message = first_line(p) return end
    self.tabs[#self.tabs + 1] = p
    k = #self.tabs
  else
    local ok, err = pcall(self.tabs[k].edit, self.tabs[k], item)
    if not ok then self.message = first_line(err) return end
  end
  if not self:select(k) then self:draw() end
end

--- Ctrl+S: the subject's values and every pane's edits written back.
function Session:save ()
  local done = {}
  if self.subject.save then done[#done + 1] = self.subject.save() end
  for _, p in ipairs(self.tabs) do
    if p ~= self.form and p.save then
      local files = p:save()
      if type(files) == "table" and #files > 0 then done[#done + 1] = table.concat(files, ", ") end
    end
  end
  local msg = #done > 0 and "saved " .. table.concat(done, "; ") or "nothing to save"
  self.message = msg
  self.out(msg .. "\n")
  return msg
end

-- Remembers the form's values before an edit, for Ctrl+Z.
function Session:remember ()
  local t = {}
  for i, it in ipairs(self.form.items) do
    if it.kind ~= "curve" then t[#t + 1] = { i, self.form:value(i) } end
  end
  self.undo[#self.undo + 1] = t
  if #self.undo > 100 then table.remove(self.undo, 1) end
end

function Session:undo_last ()
  local t = table.remove(self.undo)
  if t == nil then self.message = "nothing to undo" return end
  for _, e in ipairs(t) do self.form:set(e[1], e[2]) end
end

--- One event of the window (lsys.core's): true when the panes must be drawn again.
function Session:event (ev)
  local t = ev.type
  if t == "pointer" then
    if ev.pane == 1 then
      if ev.phase ~= "down" then return false end
      local k = self:tab_at(ev.x)
      return k ~= nil and self:select(k)
    elseif ev.pane == 2 then
      local p = self:pane()
      if p == self.form and ev.phase == "down" then self:remember() end
      return p:pointer(ev.phase, ev.x, ev.y, ev.button, ev.shift, ev.ctrl) and true or false
    elseif ev.pane == 3 and self.itemform then
      return self.itemform:pointer(ev.phase, ev.x, ev.y, ev.button, ev.shift, ev.ctrl)
    end
  elseif t == "scroll" and (ev.pane == 2 or ev.pane == 3) then
    local p = ev.pane == 3 and self.itemform or self:pane()
    return p and p.scroll and p:scroll(ev.dy, ev.x, ev.y) and true or false
  elseif t == "key" then
    local k = ev.key
    if ev.ctrl and k == "s" then self:save() return true end
    if ev.ctrl and k == "z" and self:pane() == self.form then self:undo_last() return true end
    if k == "tab" then
      return self:select(self.active % #self.tabs + 1)
    end
    local p = self:pane()
    if p == self.form and (k == "left" or k == "right" or (ev.ctrl and k == "r")) then
      self:remember()
    end
    return p.key and p:key(k, ev.ctrl, ev.shift) and true or false
  elseif t == "pick" then
    local any = false
    for _, p in ipairs(self.tabs) do
      if p.pick and ev.info and p:pick(ev.info) then any = true end
    end
    return any
  end
  return false
end

--- Builds the plant again when an edit made it stale, and posts it. Returns true when a
-- new plant was posted. An edit that comes while building (the events `poll` handles
-- between derivation steps) abandons the build and starts again from its values.
function Session:idle ()
  if not self.dirty or self.building then return false end
  self.building = true
  local posted = false
  while self.dirty do
    self.dirty = false
    local t0 = now()
    local ok, r = pcall(self.subject.build, function ()
      if self.poll and self.poll() == false then error(CLOSED, 0) end
      if self.dirty then error(SUPERSEDED, 0) end
    end)
    if ok then
      self.builds = self.builds + 1
      local ms = (now() - t0) * 1000
      self.error = nil
      self.stats = { triangles = r.ntriangles, modules = r.lstring and #r.lstring or nil,
                     ms = ms }
      for _, p in ipairs(self.tabs) do      -- the panes that look at the plant, before the
        if p.set_scene then                  -- window takes its mesh
          p:set_scene(r)
          if p.used then p:used() end
        end
      end
      if self.post then self.post(r) end
      if self.report then self.report(self) end
      posted = true
    elseif rawequal(r, SUPERSEDED) then
      self.superseded = self.superseded + 1
    elseif rawequal(r, CLOSED) then
      self.building = false
      return false
    else
      self.error = first_line(r)
    end
  end
  self.building = false
  self.form:refresh()
  self:draw()
  return posted
end

--- Ends the session (the window shows something else): the subject lets go of its model.
function Session:stop ()
  if self.subject.stop then self.subject.stop() end
  self.stopped = true
end

M.first_line = first_line
return M
