--- The viewer window from Lua (docs/viewer.md): `lsys.show(x)` and what goes with it.
--
-- One window per process, opened by the first `show` and reused by the next ones (a
-- closed window is opened again). The window runs on its own thread (csrc/gl/glfw_viewer.c):
-- `show` hands it a snapshot and returns at once, and Lua goes on while the window draws.
-- What happens in the window (a click on a module, a screenshot written, the window
-- closed) comes back as events, which `poll` turns into callbacks on the Lua thread.
-- The `lsys` REPL polls while it waits at the prompt, and `lsys view` polls in its loop;
-- a script polls with `lsys.wait()` (until the window closes) or `lsys.viewer.poll()`.
--
-- Showing a model derives it keeping the string of every step, interprets each, and
-- lets the window step through them (left/right arrows, space animates); the camera
-- is fitted to the step shown first (the last, by default) and kept while stepping, so
-- the plant grows in place. The model's `view` is read at each show: change it and show
-- again. The S key pressed while animating saves every step through that camera to a
-- folder (`frames_dir`), a picture series as lsys.frames writes. The L key colours the
-- leaves by the light they receive: `poll` computes the colours of each frame shown while
-- it is on (core.light, on this thread: the window draws on meanwhile) and hands them to
-- the window (csrc/gl/vlight.h; docs/viewer.md, "Light on the leaves").
--
-- Without a window (none opened yet, closed, or none possible: no display, or lsys built
-- without the viewer) every function follows one rule. The ones asked to act on a window
-- raise: `open` and `show` open one, and say why none can be; `key`, `screenshot` and
-- `light` say "no window open" (they never open one). The ones that ask about the window or
-- wait for it do nothing and answer as for a closed window: `poll` and `sync` false,
-- `pending` 0, `state`, `project` and `colour` nil; `wait` and `close` return at once.
-- @module lsys.viewer
local core = require "lsys.core"
local model = require "lsys.model"
local load = require "lsys.load"
local warning = require "lsys.warning"
local edit = require "lsys.ui.edit"
local tune = require "lsys.ui.tune"
local lrender = require "lsys.render"

local type, pairs, ipairs, error, pcall, tostring, getmetatable =
      type, pairs, ipairs, error, pcall, tostring, getmetatable
local io, os, string, math = io, os, string, math
local format = string.format
local _ENV = nil

local M = {}

local S = {             -- the one window and what it shows
  viewer = nil,         -- core Viewer, nil before the first show or after close
  strings = {},         -- frame index -> the Lstring it was drawn from
  populations = {},     -- frame index -> the population it shows (lsys.population)
  steps = {},           -- frame index -> derivation step (or nil)
  model = nil,          -- the model shown, if any
  on_pick = nil,        -- callback of the last show (or M.on_pick)
  on_event = nil,
  nframes = 0,          -- frames of the snapshot last posted
  current = nil,        -- the frame shown, as the last poll knew it
  light = false,        -- the L key is on (as the window last said, or a show set it)
  lit = {},             -- frame index -> true once its light colours were asked for
  nlit = 0,             -- light colours computed so far (sync waits for them too)
  want = nil,           -- the frame to give its light colours at the end of a poll
  editor = nil,         -- the editing panes' session (lsys.ui.edit), while one is shown
}

--- Called with the pick information when a click hits a module and the show did not
-- give its own `on_pick`; nil by default. The `lsys` REPL sets it to print the pick;
-- `lsys view` prints picks through its show's own `on_pick` unless this is set.
M.on_pick = nil

--- The last pick (see `show`), or nil.
M.last_pick = nil

--- Called by `poll` when the S key, pressed while animating, saved every step through the
-- window's camera (or failed): with the event { path = the folder, ok, count = pictures
-- written, first, last = their steps, msg = why not }. By default it prints where the
-- pictures went on stderr; set it to nil to print nothing.
function M.on_frames (ev)
  if ev.ok then
    io.stderr:write(format("lsys: saved %d pictures of steps %d to %d to %s/ (one camera)\n",
      ev.count, ev.first, ev.last, ev.path))
  else
    io.stderr:write(format("lsys: could not save the steps to %s/: %s%s\n", ev.path, ev.msg,
      ev.count > 0 and format(" (%d saved)", ev.count) or ""))
  end
end

local SHOW_OPTS = {
  step = "number", steps = "boolean", rate = "number", title = "string", width = "number",
  height = "number", on_pick = "function", on_event = "function", view = "table",
  keep_camera = "boolean", progress = "function", samples = "number", status = "boolean",
  model = "table", lines = "table", capture = "boolean", history = "number",
  frames_dir = "string", light_colours = "boolean", edit = "boolean", file = "string",
  out = "function", on_build = "function", flat = "boolean", shadows = "boolean",
  ao = "boolean",
}

-- The sky and ground of a window showing `scene` (post options): as lsys render shades a
-- 3D plant (the window draws them under a frame that is one: csrc/gl/render.h's
-- lsys_render_solid), no sky over a view's own background; none with `flat`.
local function backdrop (scene, flat)
  if flat then return false, false end
  return not lrender.ownbackground(scene), true
end

-- The scene window v shows for `scene`: with opts.shadows or opts.ao, a 3D plant baked with
-- them and its ground grown to what a picture of the window's scene pane sees
-- (lsys.render.bake), and true.
local function baked (v, scene, opts, sky)
  if not (opts.shadows or opts.ao) or not lrender.solid(scene) then return scene, false end
  local st = v:state()
  local r = st and st.scene
  return lrender.bake(scene, { shadows = opts.shadows or nil, ao = opts.ao or nil,
                               ground = true, sky = sky or nil,   -- (the colour it fades to)
                               width = r and r[3] > 0 and r[3] or nil,
                               height = r and r[4] > 0 and r[4] or nil }), true
end

-- Errors of `show` are lsys.show's (the public name of lsys.viewer.show); `open` names
-- itself.
local function fail (msg, level, name)
  error((name or "lsys.show") .. ": " .. msg, level + 1)
end

local function checkopts (opts, name)
  if opts == nil then return {} end
  if type(opts) ~= "table" then fail("an options table expected", 3, name) end
  for k, v in pairs(opts) do
    local t = SHOW_OPTS[k]
    if t == nil then fail(format("unknown option '%s'", tostring(k)), 3, name) end
    if type(v) ~= t then fail(format("option '%s' must be a %s", k, t), 3, name) end
  end
  return opts
end

-- Widths in world units (cylinders, ribbons) or in pixels (lines), for picking.
local function world (v)
  return v ~= nil and v.line_style ~= nil and v.line_style ~= "line"
end

-- A frame table for the core from a scene (which keeps how it is to be looked at).
local function frame (scene, step, nmodules, take)
  local v = model.sceneview(scene)
  return { scene = scene, step = step, modules = nmodules, take = take, world = world(v) }, v
end

-- The memory a frame of the history holds, in bytes: its mesh (in the window and again on
-- the GPU side, which software GL keeps in the process), what clicks are picked from, and
-- the Lstring kept to name what was clicked (csrc/core/mesh.h, csrc/gl/viewer.h).
local function frame_bytes (scene, s)
  local mesh = scene.nvertices * 37 + scene.ntriangles * 12 + scene.nlines * 34
  return 2 * mesh + scene.nrecords * 32 + s:bytes()
end

--- The memory the steps a shown model keeps may take, in bytes, unless the show says
-- (`history`); beyond it the window keeps every 2nd, 4th, ... step and the last.
M.HISTORY = 256 * 1024 * 1024

-- A model's steps: derive, interpret each step as it comes, keep the frames. When the
-- history would need more than opts.history bytes, the steps in between are thinned out
-- (every 2nd kept, then every 4th, ...: the spacing stays even) and the last step is
-- always kept; the frames dropped and their strings are freed as the derivation goes on.
local function model_frames (m, opts)
  local n = m.steps
  local budget = opts.history or M.HISTORY
  local kept, total, stride = {}, 0, 1
  -- a frame dropped frees its scene and string now: the collector does not see their size
  -- (the derivation is past its string: each(k) comes after step k read string k - 1)
  -- (a string from a hook, end_each's or finish's, may be held elsewhere: left to the GC)
  local own = m.end_each == nil and m.finish == nil
  local function drop (e)
    getmetatable(e.scene).__close(e.scene)
    if own then getmetatable(e.s).__close(e.s) end
  end
  local function keep (k, s)
    local tail = kept[#kept]
    if tail ~= nil and tail.k % stride ~= 0 and tail.k ~= 0 then   -- was kept as the last
      kept[#kept] = nil
      total = total - tail.bytes
      drop(tail)
    end
    if opts.progress then opts.progress(k, n) end
    local scene = m:interpret(s, opts.view)
    local e = { k = k, s = s, scene = scene, bytes = frame_bytes(scene, s) }
    kept[#kept + 1] = e
    total = total + e.bytes
    while total > budget and #kept > 2 and stride <= n do   -- thin out the steps between
      stride = stride * 2
      local out = {}
      total = 0
      for i, f in ipairs(kept) do
        if i == 1 or i == #kept or f.k % stride == 0 then
          out[#out + 1] = f
          total = total + f.bytes
        else
          drop(f)
        end
      end
      kept = out
    end
  end
  if opts.steps == false then
    keep(n, m:derive(n))
  else
    m:derive(n, { each = keep })
  end
  if stride > 1 then
    local size = budget >= 2 ^ 30 and format("%.1f GiB", budget / 2 ^ 30)
      or budget >= 2 ^ 20 and format("%.1f MiB", budget / 2 ^ 20)
      or format("%.0f kB", budget / 1000)
    warning.warn(format("lsys.show: the %d steps would take more memory than the history "
      .. "allows (%s): the window keeps every %d%s step and the last (show option "
      .. "'history', `lsys view --history SIZE`; `steps = false` or `--last` for the last "
      .. "step alone)", n + 1, size, stride, stride == 2 and "nd" or "th"))
  end
  local frames, textures = {}, nil
  for i, e in ipairs(kept) do
    local f, v = frame(e.scene, e.k, #e.s, true)
    frames[i] = f
    S.strings[i], S.steps[i] = e.s, e.k
    if v and v.textures and #v.textures > 0 then textures = v.textures end
  end
  return frames, textures
end

-- The folder the S key saves every step to while animating, from the name of what is
-- shown (a title, a model's name, its file): "<name>-frames", "lsys-frames" without one.
local function frames_dir (name)
  local stem = name and name:match("([^/]*)$"):gsub(":%d+$", "")
  stem = stem and (stem:match("^(.+)%.[^.]*$") or stem):gsub("[^%w_.-]+", "-")
  if stem == nil or stem == "" or stem == "model" or stem:find("^%.") then stem = "lsys" end
  return stem .. "-frames"
end

-- The model to interpret an Lstring with: its own, the one given, the last shown, or a
-- plain turtle.
local plain
local function model_of (s, opts)
  if opts.model ~= nil then
    if not model.ismodel(opts.model) then fail("option 'model' must be a model", 4) end
    return opts.model
  end
  local m = model.owner(s) or S.model
  if m == nil then
    plain = plain or model.lsystem { axiom = "", name = "plain turtle" }
    m = plain
  end
  return m
end

-- The open window, else a new one; `name` (lsys.show, lsys.viewer.open) begins the
-- messages.
local function open (opts, name)
  opts = opts or {}
  if S.viewer ~= nil and S.viewer:state().open then return S.viewer end
  if S.viewer ~= nil then S.viewer:close() end
  S.viewer = nil
  if not core.has_viewer then
    error(name .. ": lsys was built without the viewer window: install libglfw3-dev and "
      .. "rebuild (./setup.sh does)", 0)
  end
  local ok, v = pcall(core.viewer_open, {
    width = opts.width and math.tointeger(opts.width) or nil,
    height = opts.height and math.tointeger(opts.height) or nil,
    samples = opts.samples and math.tointeger(opts.samples) or nil,
    status = opts.status,
  })
  if not ok then
    local msg = tostring(v)
    if os.getenv("DISPLAY") == nil and os.getenv("WAYLAND_DISPLAY") == nil then
      msg = msg .. " (no display: DISPLAY is not set; `lsys render` draws PNG files "
        .. "without one)"
    end
    error(name .. ": " .. msg, 0)
  end
  S.viewer = v
  return v
end

--- Opens the window, empty (it waits for a `show`), unless it is open. `opts`: width,
-- height, samples, status, as for `show`.
function M.open (opts)
  open(checkopts(opts, "lsys.viewer.open"), "lsys.viewer.open")
end

-- The Lua file a model was made in (for saving its edited values), or nil.
local function modelfile (m)
  local w = model.where(m)
  local f = type(w) == "string" and (w:match("^(.-):%d+$") or w)
  if f and f:match("%.lua$") and core.filestamp(f) then return f end
  return nil
end

-- Ends the editing session, if one is shown: the scene fills the window again.
local function detach ()
  local e = S.editor
  if e == nil then return end
  S.editor = nil
  e:stop()
  if S.viewer ~= nil and S.viewer:state().open then
    S.viewer:layout(nil)
    S.viewer:text("", "")
  end
end

local handle

--- Shows the plant of `subject` (lsys.ui.edit: what is edited and how its plant is made
-- again; lsys.ui.tune makes them for a model's params and for vlab panels) with the
-- editing panes beside it, and returns the session (lsys.ui.edit) at once, after the
-- first plant was built (`session.error` says why there is none). Edits in the panes (and
-- `m.params.R = v` from a script or the REPL) make the plant again in `poll`. `show` of a
-- model with params comes here. opts: as for `show` (title, width, height, samples,
-- status, keep_camera, on_pick, on_event), and `out(msg)` for what saving reports.
function M.edit (subject, opts)
  opts = checkopts(opts, "lsys.viewer.edit")
  if type(subject) ~= "table" or type(subject.build) ~= "function" then
    fail("a subject { build = function, items = ... } expected", 2, "lsys.viewer.edit")
  end
  local v = open(opts, "lsys.viewer.edit")
  local prev = S.editor       -- a reload: the new session opens where the old one was
  detach()
  local first = not opts.keep_camera
  local title = "lsys: " .. (opts.title or subject.title or "edit")
  local session = edit.session(v, subject, {
    post = function (scene)
      local m = subject.model
      local s = scene.lstring
      S.strings, S.populations, S.model = { s }, {}, m
      S.steps = { m and m.steps or nil }
      local f, vw = frame(scene, S.steps[1], s and #s or nil, true)
      local tex = vw and vw.textures
      local sky, ground = backdrop(scene, opts.flat)
      local b
      f.scene, b = baked(v, scene, opts, sky)
      ground = ground and not b
      v:post({ f }, { keep_camera = not first or nil, title = title, sky = sky, ground = ground,
                      textures = tex and #tex > 0 and tex or nil })
      first = false
      S.nframes, S.current, S.lit = 1, 1, {}
      if S.light then S.want = 1 end
    end,
    poll = function ()
      local ev = v:poll(0)
      while ev ~= nil do
        if handle(v, ev) then return false end
        ev = v:poll(0)
      end
      return true
    end,
    out = opts.out,
  })
  S.editor = session
  if prev ~= nil and opts.keep_camera then session:resume(prev) end
  session.report = opts.on_build
  S.on_pick, S.on_event = opts.on_pick, opts.on_event
  session:changed()
  session:idle()
  return session
end

--- Shows `x` in the viewer window, opening it if needed, and returns at once.
-- `x` is a Model (derived; every step is kept and can be stepped through; a component
-- graph's root prototype is made one by lsys.components.model), an Lstring
-- (interpreted with the model that made it, else `opts.model`, else the last model
-- shown, else a plain turtle), a Scene, or a list of Scenes (frames to step through).
-- opts: `step` (the step shown first; default the last), `steps = false` (a model's
-- last step only: less work for big models), `rate` (animation, steps per second,
-- default 2), `title`, `width`, `height` (of a new window, default 800 x 800),
-- `samples` (multisampling of a new window), `status` (the status line, default true),
-- `view` (view fields replacing the model's for this show), `keep_camera` (keep the
-- window's camera instead of fitting), `on_pick(info)` (called by `poll` for a click
-- on a module: info = { module, step, frame, kind, name, text, lstring, x, y }, plus
-- `instance` and `path` when a component instance drew it: see lsys.components; in a
-- population, `plant` (its index in the population) and `prototype`, whose Lstring
-- `lstring` is),
-- `on_event(ev)` (every event), `progress(k, n)` (before interpreting step k of n),
-- `history` (the bytes a model's kept steps may take, default lsys.viewer.HISTORY = 256 MiB;
-- beyond it every 2nd, 4th, ... step is kept, and the last), `model` (for an Lstring),
-- `lines` (for a Scene: { {p0 =, p1 =, color = {r, g, b}, width = pixels, ontop = boolean},
-- ... } drawn over it, depth-tested unless `ontop`),
-- `capture` (a tool takes the keys and Ctrl-drags: they come to `on_event` as
-- { type = "key", key = "up", ctrl =, shift = } and
-- { type = "drag", phase = "begin" | "move" | "end", x =, y = }), `frames_dir` (where
-- the S key, pressed while animating, saves every step through the window's camera as
-- step-NNNN.png: default "<name>-frames" in the current directory, the name of the model's
-- file or the title; see `on_frames`), `light_colours` (true: the leaves coloured by the
-- light they receive, as the L key does, from the first picture; false: in their own
-- colours; default: as the window had them).
function M.show (x, opts)
  opts = checkopts(opts)
  local frames, textures, title
  x = load.tomodel(x)                            -- a component graph's root prototype
  if model.ismodel(x) and opts.edit ~= false and tune.graph_root(x) ~= nil then
    return M.edit(tune.graph(x, { file = opts.file or modelfile(x), title = opts.title }),
                  opts)
  end
  if model.ismodel(x) and (opts.edit or opts.edit == nil and x.params ~= nil and
                           #x.params > 0) then
    return M.edit(tune.params(x, { file = opts.file or modelfile(x), view = opts.view,
                                   title = opts.title }), opts)
  end
  detach()
  S.strings, S.steps, S.populations = {}, {}, {}
  if model.ismodel(x) then
    frames, textures = model_frames(x, opts)
    S.model = x
    title = x.name or model.where(x)
  elseif model.islstring(x) then
    local m = model_of(x, opts)
    local scene = m:interpret(x, opts.view)
    local f, v = frame(scene, nil, #x, true)
    frames = { f }
    S.strings[1] = x
    textures = v and v.textures
    title = format("Lstring (%d modules)", #x)
  elseif model.isscene(x) then
    if opts.view ~= nil then fail("option 'view' needs a model or an Lstring", 2) end
    local ls = x.lstring
    local f, v = frame(x, nil, ls and #ls or nil, false)
    f.lines = opts.lines
    frames = { f }
    S.strings[1] = x.lstring
    if x.ninstances > 0 then S.populations[1] = x end
    textures = v and v.textures
    title = "scene"
  elseif type(x) == "table" and #x > 0 then
    frames = {}
    for i, sc in ipairs(x) do
      if not model.isscene(sc) then fail(format("element %d of the list is not a Scene", i), 2) end
      local f, v = frame(sc, i - 1, nil, false)
      frames[i] = f
      S.strings[i], S.steps[i] = sc.lstring, i - 1
      if sc.ninstances > 0 then S.populations[i] = sc end
      textures = textures or (v and v.textures)
    end
    title = format("%d scenes", #x)
  else
    fail("a Model, an Lstring, a Scene or a list of Scenes expected", 2)
  end
  local first = #frames
  if opts.step ~= nil then
    first = nil
    for i = 1, #frames do if S.steps[i] == opts.step then first = i end end
    if first == nil then
      fail(format("step %s is not among the steps shown (%s to %s)", tostring(opts.step),
        tostring(S.steps[1] or 0), tostring(S.steps[#frames] or #frames - 1)), 2)
    end
  end
  if opts.rate ~= nil and not (opts.rate > 0 and opts.rate <= 1000) then
    fail("option 'rate' must be in (0, 1000] steps per second", 2)
  end
  if opts.frames_dir == "" then fail("option 'frames_dir' must not be empty", 2) end
  local sky, ground = backdrop(frames[#frames].scene, opts.flat)
  local v = open(opts, "lsys.show")
  if opts.shadows or opts.ao then
    for _, f in ipairs(frames) do
      local b
      f.scene, b = baked(v, f.scene, opts, sky)
      ground = ground and not b
    end
  end
  v:post(frames, {
    first = first, rate = opts.rate, title = "lsys: " .. (opts.title or title),
    sky = sky, ground = ground,
    frames_dir = opts.frames_dir or frames_dir(opts.title or model.ismodel(x) and
                                               (x.name or model.where(x)) or nil),
    keep_camera = opts.keep_camera, capture = opts.capture,
    textures = textures and #textures > 0 and textures or nil,
    light = opts.light_colours,      -- true: the first frame's colours come with the post
  })
  v:text(nil, "")
  S.on_pick, S.on_event = opts.on_pick, opts.on_event
  S.nframes, S.lit, S.want, S.current = #frames, {}, nil, first
  if opts.light_colours ~= nil then S.light = opts.light_colours end
  if opts.light_colours then S.lit[first] = true
  elseif S.light then S.want = first end       -- the window keeps them on: poll gives them
end

--- Shows a scene that changes in place (a growing world's, lsys.grow) and returns at
-- once; `patch` then sends the window only what changed. opts: `title`, `width`, `height`,
-- `samples`, `status` (of a new window), `fit` (a box {x0, y0, z0, x1, y1, z1} the camera
-- frames: the plants' final size), `help` (the help text the H key shows), `on_event`
-- (every event; the window's keys come back as { type = "key", key = ... }, as with
-- `capture`).
function M.live (scene, opts)
  opts = opts or {}
  if not model.isscene(scene) then fail("a Scene expected", 2, "lsys.viewer.live") end
  local v = open(opts, "lsys.viewer.live")
  detach()
  S.strings, S.steps, S.populations, S.model = {}, {}, {}, nil
  local f = frame(scene, 0, 0, false)
  local sky, ground = backdrop(scene, opts.flat)
  v:post({ f }, { live = true, fit = opts.fit, capture = true, sky = sky, ground = ground,
                  title = "lsys: " .. (opts.title or "growing") })
  v:text(nil, opts.help or "")
  S.on_pick, S.on_event = nil, opts.on_event
  S.nframes, S.lit, S.want, S.current = 1, {}, nil, 1
end

--- Sends the window what changed in the scene shown by `live` since the last patch (the
-- vertex ranges the scene marked, and what it appended), with the status line's `tick`,
-- `count` (limbs) and `note`. Returns the request's serial number: the window has drawn
-- it once `state().serial` reaches it.
function M.patch (scene, tick, count, note)
  if S.viewer == nil then error("lsys.viewer.patch: no window open", 2) end
  return S.viewer:patch(scene, { step = tick, count = count, note = note })
end

--- The component instance (lsys.components) that drew module `i` of the Lstring `s`, and
-- its path, or nil: what a pick reports. `m` is the model that made `s` (default: the
-- model that owns it, else the last one shown); its `m.components.instance(i, s)` (a
-- component graph's model, lsys.components.model, or an L-system placing plants,
-- lsys.components.mix, which also gives the placing module's path, "P#2") says.
function M.instance (s, i, m)
  m = m or model.owner(s) or S.model
  local c = m ~= nil and m.components
  if type(c) ~= "table" or type(c.instance) ~= "function" then return nil end
  if c.lstring ~= nil and #c.lstring ~= #s then return nil end   -- not the plant's string
  local ok, inst, where = pcall(c.instance, i, s)
  if not ok or type(inst) ~= "table" or inst.path == nil then return nil end
  return inst, where and (where .. "/" .. inst.path) or inst.path
end

-- What a click hit, for the callbacks: in a population, the plant (its index in the
-- population) and its prototype, whose Lstring names the module.
local function pickinfo (ev)
  local s = S.strings[ev.frame]
  local pop = S.populations[ev.frame]
  local info = {
    module = ev.module, step = ev.step, frame = ev.frame, kind = ev.kind, x = ev.x, y = ev.y,
  }
  if pop ~= nil and ev.plant ~= nil then
    local inst = pop:instance(ev.plant)
    info.plant, info.prototype = ev.plant, inst and inst.prototype
    s = inst and pop:prototype(inst.prototype).lstring
  end
  info.lstring = s
  if s ~= nil and ev.module <= #s then
    info.name = s:module(ev.module)
    info.text = tostring(s:sub(ev.module, ev.module))
    info.instance, info.path = M.instance(s, ev.module)
  end
  return info
end

-- One event of the window: the callbacks, the editing panes', and what the L key needs.
-- Returns true when it was "closed" (the window is then forgotten).
function handle (v, ev)
  if S.on_event then S.on_event(ev) end
  local e = S.editor
  if e ~= nil and (ev.type == "pointer" or ev.type == "scroll" or ev.type == "key") then
    if e:event(ev) then e.redraw = true end
  end
  if ev.type == "pick" then
    local info = pickinfo(ev)
    M.last_pick = info
    if e ~= nil and e:event({ type = "pick", info = info }) then e.redraw = true end
    local f = S.on_pick or M.on_pick
    if f then f(info) end
  elseif ev.type == "frames" then
    if M.on_frames then M.on_frames(ev) end
  elseif ev.type == "light" then
    S.light = ev.on
    if ev.on then S.want = ev.frame end
  elseif ev.type == "step" then
    S.current = ev.frame
    if S.light then S.want = ev.frame end
  elseif ev.type == "closed" then
    if S.editor ~= nil then S.editor:stop() end
    S.editor = nil
    v:close()
    S.viewer = nil
    return true
  end
  return false
end

-- Gives the frame last stepped to its light colours while the L key is on, unless it has
-- them: computed here, on the Lua thread, while the window goes on drawing.
local function lighten (v)
  local k = S.want
  S.want = nil
  if k == nil or not S.light or S.lit[k] or k > S.nframes then return end
  S.lit[k] = true
  S.nlit = S.nlit + 1
  v:light(k)                 -- (nil when the window was closed meanwhile)
end

--- Handles the window's events: calls `on_pick` for clicks on modules (and `on_event`
-- for every event), and while the L key is on gives the frame shown the light colours
-- of its leaves. Waits up to `timeout` seconds (default 0) for the first event.
-- Returns true while the window is open.
function M.poll (timeout)
  local v = S.viewer
  if v == nil then return false end
  local e = S.editor
  local ev = v:poll(e ~= nil and e.dirty and 0 or timeout or 0)
  while ev ~= nil do
    if handle(v, ev) then return false end
    ev = v:poll(0)
  end
  e = S.editor
  if e ~= nil then
    if not e:idle() and e.redraw then e:draw() end
    e.redraw = false
    if S.viewer == nil then return false end       -- closed while building
  end
  lighten(v)
  return v:state().open
end

--- The number of window events waiting for `poll` (0 without a window), and 1 more while
-- the editing panes' plant is to be built again (a value set from a script or the REPL):
-- `poll` builds it.
function M.pending ()
  if S.viewer == nil then return 0 end
  return S.viewer:pending() + (S.editor ~= nil and S.editor.dirty and 1 or 0)
end

--- Runs `poll` until the window is closed (Esc, Q or its close button).
function M.wait ()
  while M.poll(0.25) do end
end

-- True while the window is open: `state()` tells (nil without a window, `open` false
-- once it was closed); the predicate stays one release more, with a warning.
M.isopen = warning.alias("lsys.viewer.isopen", "lsys.viewer.state()", function ()
  return S.viewer ~= nil and S.viewer:state().open
end)

--- Closes the window.
function M.close ()
  detach()
  if S.viewer ~= nil then S.viewer:close() end
  S.viewer = nil
end

--- Saves the next picture the window draws as a PNG, as the S key does, and returns
-- its path (`path` nil: lsys-NNN.png in the current directory). Raises when no window
-- is open or the file cannot be written; waits at most `timeout` seconds (10).
function M.screenshot (path, timeout)
  local v = S.viewer
  if v == nil or not v:state().open then error("lsys.viewer.screenshot: no window open", 2) end
  v:screenshot(path)
  local deadline = os.time() + (timeout or 10)
  repeat
    local ev = v:poll(0.25)
    while ev ~= nil do
      if ev.type == "screenshot" then
        if S.on_event then S.on_event(ev) end
        if not ev.ok then error("lsys.viewer.screenshot: " .. ev.msg, 2) end
        return ev.path
      elseif handle(v, ev) then
        error("lsys.viewer.screenshot: the window was closed", 2)
      end
      ev = v:poll(0)
    end
  until os.time() > deadline
  error("lsys.viewer.screenshot: no picture drawn within the time allowed", 2)
end

--- The window's state: { open, drawn, width, height, frame, nframes, playing,
-- wireframe, light, step } (nil when no window was opened).
function M.state ()
  if S.viewer == nil then return nil end
  local st = S.viewer:state()
  st.step = S.steps[st.frame]
  return st
end

--- Where the world point `p` ({x, y, z}) is in the window as last drawn: x, y in
-- window coordinates (y down) and the depth, or nil.
function M.project (p)
  if S.viewer == nil then return nil end
  return S.viewer:project(p)
end

--- Presses a key of the window: "right", "left", "home", "end", "space", "r", "f", "w",
-- "s", "h", "l", "q", "+", "-", "redraw". ("l" turns the light colours on or off: the
-- next `poll` gives the frame shown its colours, and `sync` waits for them.)
function M.key (name)
  if S.viewer == nil then error("lsys.viewer.key: no window open", 2) end
  return S.viewer:key(name)
end

--- Waits until the window has drawn what was last shown, and the light colours this
-- asked for (at most `timeout` seconds, 10); returns true when it has.
function M.sync (timeout)
  if S.viewer == nil then return false end
  local deadline = os.time() + (timeout or 10)
  local st, serial, n
  repeat
    n = S.nlit
    -- the window takes posts and keys in order before drawing: once a picture drawn after
    -- this redraw request is on screen, so is everything asked before it
    serial = S.viewer:key("redraw")
    repeat
      M.poll(0.05)
      if S.viewer == nil then return false end
      st = S.viewer:state()
    until st.serial >= serial or os.time() > deadline
    M.poll(0)                  -- the events before that picture: an L key's among them
    if S.viewer == nil then return false end
  until S.nlit == n or os.time() > deadline
  return st.serial >= serial
end

-- Frame `k` (default: the frame shown, as the last poll knew it) checked for
-- lsys.viewer.<name>.
local function shownframe (name, k)
  local v = S.viewer
  if v == nil or not v:state().open then error("lsys.viewer." .. name .. ": no window open", 3) end
  k = k or S.current
  if math.type(k) ~= "integer" or k < 1 or k > S.nframes then
    error(format("lsys.viewer.%s: no frame %s (the window shows frames 1 to %d)", name,
      tostring(k), S.nframes), 3)
  end
  return v, k
end

-- The results of core function `f`, its errors named as lsys.viewer.<name>'s.
local function named (name, ok, ...)
  if not ok then
    error("lsys.viewer." .. name .. ": " .. tostring((...)):gsub("^viewer:%a+: ", ""), 3)
  end
  return ...
end

--- The light colours of the leaves of frame `k` (default: the frame shown, as the last
-- `poll` knew it; 1-based, as `state().frame`), computed now unless they were, whether the
-- L key is on or not:
-- { frame, leaves = the leaf triangles coloured, min, max, mean = their light (0 in full
-- shade to 1 for an open horizontal leaf; the mean weighted by area), msg = why none are
-- (no leaves, a population, a growing scene, the memory budget) }. `opts`: `threads`
-- (the default: the derivation's; the colours are the same for any number), `max_memory`
-- (bytes; default the process's budget).
function M.light (k, opts)
  local v
  v, k = shownframe("light", k)
  local info, why = named("light", pcall(v.light, v, k, opts))
  if info == nil then error("lsys.viewer.light: " .. why, 2) end
  if not S.lit[k] then
    S.lit[k] = true
    S.nlit = S.nlit + 1
  end
  return info
end

--- The colour triangle `t` (1-based) of frame `k` (default: the frame shown, as the last
-- `poll` knew it) is drawn in now, r, g, b in [0, 1] (its first vertex's material): its
-- light colour while the L key is on and the frame has its colours, else the model's. Nil
-- without a window.
function M.colour (t, k)
  if S.viewer == nil or not S.viewer:state().open then return nil end
  if math.type(t) ~= "integer" then
    error("lsys.viewer.colour: the triangle must be an integer, got " .. tostring(t), 2)
  end
  local v
  v, k = shownframe("colour", k)
  local r, g, b = named("colour", pcall(v.colour, v, k, t))
  return r, g, b
end

--- The colour of light `x` (0 to 1) on the ramp the L key colours leaves with, r, g, b.
function M.ramp (x)
  if not core.has_viewer then error("lsys.viewer.ramp: lsys was built without the viewer", 2) end
  return core.light_ramp(x)
end

return M
