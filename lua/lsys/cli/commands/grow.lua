--- `lsys grow`: a growing world of lsys.grow, live in the window or one picture per tick
-- (--frames DIR).
-- @module lsys.cli.commands.grow
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help

local tonumber, require = tonumber, require
local io, string = io, string
local format = string.format
local parse, out, usage, clock, isatty = A.parse, A.out, A.usage, A.clock, A.isatty
local size_opt, int_opt = A.size_opt, A.int_opt
local find_model = S.find_model
local run_file = require("lsys.load").run
local _ENV = nil

local GROW_OPTS = {
  ticks = "value", seed = "value", rate = "value", size = "value", screenshot = "value",
  frames = "value", every = "value", flat = "flag", help = "flag", short = { h = "help" },
}

-- `lsys grow FILE`: the world live in the window, or --frames DIR.
local function run (args)
  local opts, pos = parse("grow", GROW_OPTS, args, 2)
  if opts.help then out(HELP.grow) return 0 end
  if #pos == 0 then usage("grow", "a FILE is required (try examples/grow/forest.lua)") end
  if #pos > 1 then usage("grow", "unexpected argument '%s' (one FILE)", pos[2]) end
  local w, h = size_opt("grow", opts.size)
  w, h = w or 1000, h or 600
  local ticks = int_opt("grow", "ticks", opts.ticks, 0)
  local seed = int_opt("grow", "seed", opts.seed, 0)
  local every = int_opt("grow", "every", opts.every, 1)
  local rate = opts.rate and tonumber(opts.rate)
  if opts.rate ~= nil and not (rate and rate > 0 and rate <= 1000) then
    usage("grow", "--rate expects ticks a second in (0, 1000], got '%s'", opts.rate)
  end
  if opts.screenshot and not opts.screenshot:lower():find("%.png$") then
    usage("grow", "the screenshot must be a .png file, got '%s'", opts.screenshot)
  end
  if opts.frames and (opts.screenshot or opts.rate) then
    usage("grow", "--frames draws no window: --screenshot and --rate do not apply")
  end
  if every and not opts.frames then usage("grow", "--every applies to --frames") end
  local path = find_model(pos[1])
  local function load () return run_file(path) end
  local GV = require "lsys.ui.grow"
  local make = GV.maker(load(), path, { seed = seed }, load)
  local t0 = clock()
  if opts.frames then
    local verbose = isatty(2)
    local n, last = GV.frames(make, opts.frames, {
      ticks = ticks, every = every, width = w, height = h,
      progress = verbose and function (k, total)
        io.stderr:write(format("\rtick %d/%d", k, total))
        if k == total then io.stderr:write("\n") end
      end or nil,
    })
    out(format("wrote %d pictures to %s (the last: %s) in %.1f s\n", n, opts.frames, last,
      clock() - t0))
    return 0
  end
  local r = GV.live(make, { ticks = ticks, rate = rate, width = w, height = h,
                            screenshot = opts.screenshot, title = pos[1],
                            flat = opts.flat or nil })
  if r.screenshot then
    out(format("wrote %s: %d limbs after %d ticks; the window drew %d frames in %.2f s "
      .. "(%.1f frames a second) while growing\n", r.screenshot, r.limbs, r.ticks, r.drawn,
      r.seconds, r.fps))
    if r.full then
      out(format("at %d limbs (the last %d ticks): %d frames in %.2f s, %.1f frames a second; "
        .. "a frame drawn in %.1f ms\n", r.full.limbs, r.full.ticks, r.full.drawn,
        r.full.seconds, r.full.fps, r.drawms))
    end
  end
  return 0
end

return run
