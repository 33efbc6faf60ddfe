--- The organ in the sketch window: the four strokes of Anastacio et al. 2009, §6 (the left
-- and right boundaries in a top view, the midrib in a side view, the cross-section in a
-- front view) drawn in three regions of the sketch pane, which lsys.sketch.organ makes
-- into the surface the plant draws at its nodes. lsys.ui.sketch's state machine holds the
-- strokes; this module knows the views: where each is in the pane, how a view's strokes
-- map to the pane (an organ file's strokes keep their own pixels, the pane shows them
-- scaled into their region, so an organ read and saved again is the same organ), the
-- table lsys.sketch.organ.load takes, and the frames drawn under the strokes.
-- @module lsys.ui.sketch_organ
local ipairs, pairs, type, math = ipairs, pairs, type, math
local huge, min, max = math.huge, math.min, math.max
local _ENV = nil

local M = {}

M.ROLES = { "top_left", "top_right", "side", "front" }
M.LABELS = { top_left = "1 top L", top_right = "2 top R", side = "3 side", front = "4 front" }
M.VIEW = { top_left = "top", top_right = "top", side = "side", front = "front" }
M.RGB = { top_left = { 0.15, 0.35, 0.85 }, top_right = { 0.1, 0.55, 0.8 },
          side = { 0.2, 0.55, 0.2 }, front = { 0.85, 0.4, 0.1 } }
M.TITLES = { top = "top: 1 left, 2 right", side = "side: 3 midrib", front = "front: 4 section" }
-- the options of an organ file kept as they are (lsys.sketch.organ.build's)
local OPTIONS = { "name", "width_scale", "resolution", "precision", "capture" }
local MARGIN = 24      -- pixels inside a region left free (its title above)

--- The regions of the three views in a w x h sketch pane: { top = {x, y, w, h}, ... }:
-- the top view the left half, the side view the upper right quarter, the front view the
-- lower right one.
function M.regions (w, h)
  local hw, hh = w / 2, h / 2
  return { top = { 0, 0, hw, h }, side = { hw, 0, w - hw, hh }, front = { hw, hh, w - hw, h - hh } }
end

--- The transforms of the views: pane = o + s * p for a point p of a stroke of that view.
-- A view with strokes is fitted into its region (scaled uniformly, centred); an empty one
-- draws in pane pixels (s = 1, o = 0).
function M.fit (strokes, w, h)
  local regions, views = M.regions(w, h), {}
  local box = {}
  for _, s in ipairs(strokes) do
    local v = M.VIEW[s.role]
    local b = box[v] or { huge, huge, -huge, -huge }
    for _, p in ipairs(s.points) do
      b[1], b[2] = min(b[1], p[1]), min(b[2], p[2])
      b[3], b[4] = max(b[3], p[1]), max(b[4], p[2])
    end
    box[v] = b
  end
  for v, r in pairs(regions) do
    local b = box[v]
    if b == nil then views[v] = { s = 1, ox = 0, oy = 0 }
    else
      local bw, bh = b[3] - b[1], b[4] - b[2]
      local aw, ah = max(1, r[3] - 2 * MARGIN), max(1, r[4] - 2 * MARGIN)
      local s = min(bw > 0 and aw / bw or huge, bh > 0 and ah / bh or huge)
      if s == huge then s = 1 end
      views[v] = { s = s, ox = r[1] + r[3] / 2 - s * (b[1] + b[3]) / 2,
                   oy = r[2] + MARGIN / 2 + r[4] / 2 - s * (b[2] + b[4]) / 2 }
    end
  end
  return views
end

--- The pane point of a point (x, y) of view transform t, and back.
function M.to_pane (t, x, y) return t.ox + t.s * x, t.oy + t.s * y end
function M.from_pane (t, x, y) return (x - t.ox) / t.s, (y - t.oy) / t.s end

--- The strokes and options of an organ table ({ organ = { top = { left =, right = },
-- side =, front =, ... } }, as lsys.sketch.organ.load reads it and org:to_table() gives).
function M.strokes (t)
  local o = type(t) == "table" and t.organ or {}
  local list, opts = {}, {}
  local function add (role, pts)
    if type(pts) ~= "table" then return end
    local q = {}
    for i, p in ipairs(pts) do q[i] = { p[1], p[2], p[3] or 0.5 } end
    list[#list + 1] = { role = role, points = q }
  end
  local top = type(o.top) == "table" and o.top or {}
  add("top_left", top.left)
  add("top_right", top.right)
  add("side", o.side)
  add("front", o.front)
  for _, k in ipairs(OPTIONS) do opts[k] = o[k] end
  return list, opts
end

--- The organ table of strokes (roles of M.ROLES) and options, or nil when there are no
-- strokes.
function M.table (strokes, opts)
  if #strokes == 0 then return nil end
  local o = { top = {} }
  for _, s in ipairs(strokes) do
    local q = {}
    for i, p in ipairs(s.points) do q[i] = { p[1], p[2] } end
    if s.role == "top_left" then o.top.left = q
    elseif s.role == "top_right" then o.top.right = q
    else o[s.role] = q end
  end
  for _, k in ipairs(OPTIONS) do o[k] = opts and opts[k] end
  return { organ = o }
end

--- Draws the frames and titles of the views into canvas c (w x h).
function M.frames (c, w, h)
  for v, r in pairs(M.regions(w, h)) do
    c:rect(r[1] + 4, r[2] + 4, r[3] - 8, r[4] - 8, { 0.8, 0.8, 0.8, 1 })
    c:text(r[1] + 10, r[2] + 9, M.TITLES[v], 1, { 0.35, 0.35, 0.35, 1 })
  end
end

return M
