--- A growing world (lsys.grow) in the viewer window, live, and as a series of pictures:
-- what `lsys grow FILE` runs.
--
-- The window gets the world's scene once and then, after each tick, only the vertex ranges
-- that changed and what was appended (`lsys.viewer.patch`; csrc/gl/vlive.c), never a whole
-- snapshot. Both the window and the pictures look through one camera framing the plants'
-- final size, so the plants grow in place: a first run grows a fresh world to its end
-- headless to find that size (worlds are seeded, so the second run grows the same plants).
--
-- A grow file returns a World (planted; `lsys.grow.world{ticks = N}` says how long it grows)
-- or a table whose `world(opts)` makes one (a module such as examples/grow/davison.lua,
-- called with `{ seed = S }` when a seed is given, else `{}`).
--
-- Its documented name is lsys.growview (lua/lsys/growview.lua gives this module); the code
-- lives with the other window sessions in lua/lsys/ui/.
-- @module lsys.ui.grow
local grow = require "lsys.grow"
local core = require "lsys.core"
local series = require "lsys.frames"
local render = require("lsys.render").render
local clock = require("lsys.program").clock

local type, pcall, tostring, error, require, getmetatable =
      type, pcall, tostring, error, require, getmetatable
local math, string, table = math, string, table
local table_remove = table.remove
local format = string.format
local _ENV = nil

local M = {}

M.DEFAULT_TICKS = 100       -- how long a world grows that does not say (world{ticks = N})

local function isworld (x) return getmetatable(x) == grow.World end

--- From what a grow file returned (`x`; `where` names the file in errors): a function that
-- makes a fresh world at each call. A World returned as such is the first one made; the
-- next ones come from running `again()` (the file once more), when given.
function M.maker (x, where, opts, again)
  opts = opts or {}
  if isworld(x) then
    local first = x
    return function ()
      if first ~= nil then local w = first first = nil return w end
      if again == nil then error(where .. ": a world is grown once (give a file)", 0) end
      local w = again()
      if not isworld(w) then error(where .. " returned no World the second time", 0) end
      return w
    end
  end
  if type(x) == "table" and type(x.world) == "function" then
    return function ()
      local ok, w = pcall(x.world, { seed = opts.seed })
      if not ok then error(tostring(w), 0) end
      if not isworld(w) then
        error(format("%s: world(opts) returned %s, not a World", where, type(w)), 0)
      end
      return w
    end
  end
  error(format("%s returned %s: a grow file returns a World (lsys.grow.world{...}, planted) "
    .. "or a table with a world(opts) function", where, type(x)), 0)
end

-- The number of ticks to grow: the option, the world's length, or the default.
local function length (w, ticks) return ticks or w.length or M.DEFAULT_TICKS end

--- Grows a fresh world from `make` to its end, headless: the box {x0, y0, z0, x1, y1, z1}
-- holding the grown plants (what one camera must frame) and the world.
function M.final (make, ticks)
  local w = make()
  w:tick(math.max(0, length(w, ticks) - w.ticks))
  return series.box(w:scene()), w
end

--- Writes one PNG per tick (every `every`-th, and the last) into `dir`: tick-0000.png, ...
-- opts: `ticks`, `every` (1), `width`, `height` (800), `progress(k, n)` (after each tick).
-- Returns the number of pictures and the last one's path.
function M.frames (make, dir, opts)
  opts = opts or {}
  local box = M.final(make, opts.ticks)
  local w = make()
  local n, every = length(w, opts.ticks), opts.every or 1
  local ok, err = core.mkdir(dir)
  if not ok then error(err, 0) end
  local count, path = 0, nil
  for t = w.ticks, n do
    if t > w.ticks then w:tick() end
    if series.keep(t, n, every) then
      path = format("%s/tick-%04d.png", dir, t)
      render(w:scene(), { out = path, fit = box, width = opts.width or 800,
                          height = opts.height or 800 })
      count = count + 1
    end
    if opts.progress then opts.progress(t, n) end
  end
  return count, path
end

local HELP = "drag: orbit   right-drag / shift-drag: pan   scroll: zoom\n"
  .. "space: pause / grow   right: one tick   + / -: faster / slower\n"
  .. "backspace: start again   R: reset view   F: fit   W: wireframe   S: screenshot\n"
  .. "G: sky and ground   H: this help   Esc / Q: quit"

local RATES = { 1, 2, 5, 10, 20, 30, 60, math.huge }   -- ticks a second; huge: as fast as drawn

-- The ticks a second of a live world that does not say: Davison's system "is activated every
-- 100ms (the time interval between rewrites)" (002_f23b3156d9f0bdc0.txt, "Incremental
-- rules"), a pace at which one sees the plants grow; as fast as the window draws (about 60
-- a second) a world of 60 ticks is grown in a second.
M.RATE = 10

--- Grows the world in the window, live, until the window is closed. opts: `ticks`, `rate`
-- (ticks a second: default M.RATE, 10, or with `screenshot` as fast as the window draws
-- each one), `width`, `height`,
-- `title`, `flat` (no sky and no ground), `screenshot` (a PNG path: grow to the end, save
-- the window's picture, close),
-- `on_tick(world)`, `on_key(key, state)` (after a growth key was handled: state { ticks,
-- limbs, playing, rate }), `fit` (false: frame the plants as they are, without growing them
-- once first). Returns { ticks, limbs, drawn, fps, seconds, full, drawms, screenshot }: the
-- ticks grown, the limbs then; while growing to the end, the pictures the window drew, their
-- rate and the time taken; `full` the same from the tick the world first had its final
-- number of limbs to the end ({ ticks, drawn, seconds, fps, limbs }); `drawms` the window's
-- time to draw a picture at the end (ms, smoothed).
function M.live (make, opts)
  opts = opts or {}
  local viewer = require "lsys.viewer"
  local box, full          -- the final size, and the limbs then: the rate at full size
  if opts.fit ~= false then
    local grown
    box, grown = M.final(make, opts.ticks)
    full = grown:count()
  end
  local w = make()
  local n = length(w, opts.ticks)
  local rate = opts.rate or (opts.screenshot and math.huge or M.RATE)
  local ri = 1                            -- + and - go on from the nearest step above
  while RATES[ri] < rate and ri < #RATES do ri = ri + 1 end
  local playing, onward = true, false     -- onward: grows past the end (space there)
  local serial, nextt = 0, 0
  local keys = {}
  local run = {}                          -- the figures of growing to the end
  -- the status line's end: what the growth does, at what pace
  local function note ()
    if w.ticks >= n and not onward then return "done" end
    local pace = rate == math.huge and "as fast as drawn" or format("%g ticks/s", rate)
    return (playing and "growing " or "paused, ") .. pace
  end
  -- the window draws one tick while the next grows: a tick waits for the one before the
  -- last to be on screen (prev), so ticks never pile up ahead of the pictures
  local prev = 0
  local function send ()
    prev, serial = serial, viewer.patch(w:scene(), w.ticks, w:count(), note())
  end
  local function show ()
    viewer.live(w:scene(), {
      title = opts.title, width = opts.width, height = opts.height, fit = box, help = HELP,
      flat = opts.flat,
      on_event = function (ev) if ev.type == "key" then keys[#keys + 1] = ev.key end end,
    })
    send()
  end
  local function step ()
    w:tick()
    if opts.on_tick then opts.on_tick(w) end
    send()
  end
  local function key (k)
    if k == "space" then
      playing = not playing
      if w.ticks >= n then onward, playing = true, true end
    elseif k == "right" then playing = false step()
    elseif k == "+" or k == "=" then ri = math.min(ri + 1, #RATES) rate = RATES[ri]
    elseif k == "-" then ri = math.max(ri - 1, 1) rate = RATES[ri]
    elseif k == "backspace" then
      w, playing, onward, run = make(), true, false, {}
      show()
    else return end
    if k ~= "backspace" then send() end
    if opts.on_key then
      opts.on_key(k, { ticks = w.ticks, limbs = w:count(), playing = playing, rate = rate })
    end
  end
  show()
  while true do
    local st = viewer.state()
    if st == nil or not st.open then break end
    local growing = playing and (w.ticks < n or onward)
    if growing and st.serial >= prev and clock() >= nextt then
      if run.t0 == nil then run.t0, run.drawn0 = clock(), st.drawn end
      if run.f0 == nil and full and w:count() >= full then
        run.f0, run.fdrawn0, run.ftick = clock(), st.drawn, w.ticks
      end
      step()
      nextt = rate == math.huge and 0 or clock() + 1 / rate
      if w.ticks == n and not onward then         -- the end: what growing to it took
        viewer.sync()
        local now, drawn = clock(), viewer.state().drawn
        run.seconds, run.drawn = now - run.t0, drawn - run.drawn0
        if run.f0 ~= nil and now > run.f0 then
          run.full = { ticks = n - run.ftick, drawn = drawn - run.fdrawn0, seconds = now - run.f0,
                       fps = (drawn - run.fdrawn0) / (now - run.f0), limbs = full }
        end
        run.drawms = viewer.state().drawms
        send()
        if opts.screenshot then
          run.screenshot = viewer.screenshot(opts.screenshot)
          break
        end
      end
    end
    if not viewer.poll(growing and 0.001 or 0.05) then break end
    while #keys > 0 do key(table_remove(keys, 1)) end
  end
  viewer.close()
  return { ticks = w.ticks, limbs = w:count(), drawn = run.drawn, seconds = run.seconds,
           fps = run.seconds and run.drawn / math.max(run.seconds, 1e-9) or nil,
           full = run.full, drawms = run.drawms, screenshot = run.screenshot }
end

return M
