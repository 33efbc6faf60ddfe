--- `lsys arrange MODEL`: arranging a plant in the viewer window (Power et al. 1999, §3.2).
--
-- Click a segment: it becomes the fixed point, and the active branch (everything from it
-- up) turns red. Click again within the active branch: the manipulated point; the branch
-- path between the two turns yellow. Ctrl-drag then moves the path's end with the tool
-- chosen: G (or 1) the spherical dragger (default: the end follows the mouse on the sphere
-- about the fixed point), D (2) the disc (twist), A (3) the axis (in and out along the
-- path), P (4) the plane (the end follows the mouse in the view plane). The arrow keys
-- move the fixed point: up towards the branch end, down towards the base, left and right
-- to sibling branches. Delete prunes the active branch (leaving @X), U or Ctrl-Z undoes,
-- Ctrl-S saves the arranged L-string. Plain drags still orbit, scroll zooms.
--
-- Its documented name is lsys.arrange_ui (lua/lsys/arrange_ui.lua gives this module); the
-- code lives with the other window sessions in lua/lsys/ui/.
-- @module lsys.ui.arrange
local V = require "lsys.viewer"
local core = require "lsys.core"
local require = require

local ipairs, tostring, pcall = ipairs, tostring, pcall
local io, math, string = io, math, string
local format = string.format
local _ENV = nil

local M = {}

local RED, YELLOW = { 0.9, 0.15, 0.1, 1 }, { 1, 0.85, 0.1, 1 }
M.RED, M.YELLOW = RED, YELLOW
local TOOLS = { g = "spherical", ["1"] = "spherical", d = "disc", ["2"] = "disc",
                a = "axis", ["3"] = "axis", p = "plane", ["4"] = "plane" }

local vec = require("lsys.arrange").vec
local sub, add, scale, dot, cross, norm = vec.sub, vec.add, vec.scale, vec.dot, vec.cross,
                                          vec.norm

--- The highlight of figure 6 as overlay lines for the viewer (`lines` of lsys.show): the
-- active branch red, the branch path yellow; segments as thick lines over the model,
-- leaves and flowers (polygons, surfaces, discs, spheres) as their wireframe. `scene` is
-- `arr:interpret()`, before it is shown.
function M.highlight (arr, scene)
  local lines = {}
  local function mark (m, color, width)
    local k = scene:find(m)
    local r = k and scene:record(k)
    if r == nil then return end
    if r.length and r.length > 0 then
      lines[#lines + 1] = { p0 = r.p0, p1 = r.p1, color = color, width = width, ontop = true }
    else
      for _, e in ipairs(scene:edges(k)) do
        lines[#lines + 1] = { p0 = e[1], p1 = e[2], color = color, width = width - 1, ontop = true }
      end
    end
  end
  if arr.fixed then
    for _, m in ipairs(arr:active_modules()) do mark(m, RED, 3) end
    if arr.moved and (arr.moved ~= arr.fixed or arr.leaf) then
      for _, m in ipairs(arr:path_modules()) do mark(m, YELLOW, 5) end
    end
  end
  return lines
end

-- The drag that the Ctrl-drag event `ev` begins at the path's end of `arr`: where it
-- began, the world units per pixel there, and the view's right and up (`st`, the window's
-- state).
local function begindrag (arr, ev, st)
  local b = arr.bar
  local x0, y0 = V.project(b.p)
  local x1, y1 = V.project(add(b.p, st.right))
  local px = x0 and x1 and math.sqrt((x1 - x0) ^ 2 + (y1 - y0) ^ 2) or 0
  return { x = ev.x, y = ev.y, wpp = px > 0 and 1 / px or 1, right = st.right, up = st.up }
end

-- Moves the path's end of `arr` with `tool` as the mouse went from where `drag` began to
-- the event `ev`; try(f, ...) calls the arrangement, saying what went wrong.
local function movedrag (arr, tool, drag, ev, try)
  local dx, dy = ev.x - drag.x, ev.y - drag.y
  local b = arr.bar
  local d = add(scale(drag.right, dx * drag.wpp), scale(drag.up, -dy * drag.wpp))
  if tool == "spherical" then
    -- the end follows the mouse on the sphere about r: turn v-bar towards p-bar + d
    local q = sub(add(b.p, d), b.r)
    local axis = cross(b.v, q)
    local s = norm(axis)
    if s > 1e-12 then
      local ang = math.deg(math.atan(s, dot(b.v, q)))
      try(arr.spherical, arr, axis, ang)
    end
  elseif tool == "disc" then
    try(arr.disc, arr, dx * 0.5)
  elseif tool == "axis" then
    local v = scale(b.v, 1 / math.max(norm(b.v), 1e-12))
    try(arr.axis, arr, dot(d, v))
  else
    try(arr.plane, arr, dx * drag.wpp, -dy * drag.wpp, { right = drag.right, up = drag.up })
  end
end

--- Runs the session until the window closes. `arr` is an lsys.arrange arrangement;
-- opts: out (where Ctrl-S saves), width, height, title, say (a function printing
-- messages; default io.stdout), on_change (called after every change, for tests).
function M.run (arr, opts)
  opts = opts or {}
  local say = opts.say or function (msg) io.stdout:write(msg, "\n") io.stdout:flush() end
  local tool = "spherical"
  local drag

  local handler          -- the window's events, below
  local first = true
  local function redraw ()
    local scene = arr:interpret()
    V.show(scene, { lines = M.highlight(arr, scene), capture = true, keep_camera = not first,
                    width = opts.width, height = opts.height,
                    title = opts.title or "arrange", on_event = handler })
    first = false
    if opts.on_change then opts.on_change(arr) end
  end

  local function try (f, ...)
    local ok, err = pcall(f, ...)
    if not ok then say("arrange: " .. tostring(err)) end       -- "select: ...": the method
    return ok, err
  end

  local function pick (ev)
    local m = ev.module
    local inside = false
    if arr.fixed then
      for _, a in ipairs(arr:active_modules()) do if a == m then inside = true end end
    end
    if inside and m ~= arr.fixed.module then
      if try(arr.select, arr, arr.fixed.module, m) then
        say(format("branch path: %d joints from module %d to module %d", #arr.path,
          arr.fixed.module, arr.moved.module))
      end
    elseif try(arr.select, arr, m) then
      say(format("fixed point: module %d; click within the red branch for the end", m))
    end
    redraw()
  end

  local function key (ev)
    local k = ev.key
    if TOOLS[k] and not ev.ctrl then
      tool = TOOLS[k]
      say("tool: " .. tool)
    elseif k == "up" or k == "down" or k == "left" or k == "right" then
      if arr.fixed and try(arr.move_fixed, arr, k) then redraw() end
    elseif k == "delete" or k == "backspace" then
      if arr.fixed then
        local m = arr.fixed.module
        if try(arr.prune, arr, m) then say(format("pruned the branch at module %d", m)) end
        redraw()
      end
    elseif k == "u" or (k == "z" and ev.ctrl) then
      if arr:undo_last() then
        arr:commit()
        say("undone")
        redraw()
      end
    elseif k == "s" and ev.ctrl then
      local out = opts.out or "arranged.txt"
      local ok, err = pcall(core.write_file, out, tostring(arr:lstring()) .. "\n")
      if not ok then say("arrange: cannot save: " .. tostring(err))
      else say("saved " .. out) end
    end
  end

  local function dragged (ev)
    if arr.bar == nil then
      if ev.phase == "begin" then say("arrange: select a branch path first (two clicks)") end
      return
    end
    local st = V.state()
    if ev.phase == "begin" then
      arr:commit()
      drag = begindrag(arr, ev, st)
      return
    end
    if drag == nil then return end
    movedrag(arr, tool, drag, ev, try)
    if ev.phase == "end" then drag = nil end
    redraw()
  end

  handler = function (ev)
    if ev.type == "pick" then pick(ev)
    elseif ev.type == "key" then key(ev)
    elseif ev.type == "drag" then dragged(ev) end
  end
  redraw()
  say("click a segment for the fixed point, then one above it for the end; Ctrl-drag " ..
      "to arrange (G sphere, D disc, A axis, P plane), arrows move the fixed point, Delete " ..
      "prunes, U undoes, Ctrl-S saves, Esc quits")
  V.wait()
  return arr
end

return M
