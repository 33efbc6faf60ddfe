--- `lsys animate`: a model growing, one frame per derivation step, as an .mp4 video or an
-- animated .gif (through ffmpeg).
-- @module lsys.cli.commands.animate
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help
local F = require "lsys.frames"

local tonumber, error, pcall, next, ipairs = tonumber, error, pcall, next, ipairs
local string = string
local format = string.format
local parse, out, usage, clock, model_opts = A.parse, A.out, A.usage, A.clock, A.model_opts
local size_opt, int_opt, default_output = A.size_opt, A.int_opt, A.default_output
local frames_progress, frames_error = A.frames_progress, A.frames_error
local prepare = S.prepare
local _ENV = nil

local ANIMATE_OPTS = model_opts {
  output = "value", size = "value", fps = "value", every = "value", hold = "value",
  progress = "flag", orbit = "flag", frames = "value", seconds = "value", axis = "value",
}

-- `lsys animate MODEL --orbit`: a turntable of the final plant (lsys.orbit).
local function orbit (opts, pos)
  local w, h = size_opt("animate", opts.size)
  local outpath = opts.output or default_output(pos, "-orbit.mp4", "tree-orbit.mp4")
  local ext = (outpath:match("%.(%w+)$") or ""):lower()
  if ext ~= "mp4" and ext ~= "gif" then
    usage("animate", "the output must be an .mp4 video or a .gif animation, got '%s'",
      outpath)
  end
  for _, k in ipairs { "every", "hold" } do
    if opts[k] ~= nil then
      usage("animate", "--%s is for the growth animation, not with --orbit", k)
    end
  end
  if opts.frames and opts.seconds then
    usage("animate", "--frames and --seconds do not go together: give one")
  end
  local n = int_opt("animate", "frames", opts.frames, 1)
  local secs = opts.seconds and tonumber(opts.seconds)
  if opts.seconds ~= nil and not (secs and secs > 0 and secs <= 3600) then
    usage("animate", "--seconds expects a length in (0, 3600], got '%s'", opts.seconds)
  end
  local fps = opts.fps and tonumber(opts.fps)
  if opts.fps ~= nil and not (fps and fps > 0 and fps <= 1000) then
    usage("animate", "--fps expects frames a second in (0, 1000], got '%s'", opts.fps)
  end
  local axis
  if opts.axis ~= nil then
    local x, y, z = opts.axis:match("^%s*([^,]+),([^,]+),([^,]+)%s*$")
    axis = { tonumber(x), tonumber(y), tonumber(z) }
    if not (axis[1] and axis[2] and axis[3]) or (axis[1] == 0 and axis[2] == 0 and
                                                 axis[3] == 0) then
      usage("animate", "--axis expects a vector X,Y,Z that is not zero, got '%s'", opts.axis)
    end
  end
  local model, _, views = prepare("animate", opts, pos)
  local t0 = clock()
  local ok, r, nf, fw, fh = pcall(F.orbit, model, {
    out = outpath, frames = n, seconds = secs, fps = fps, axis = axis, width = w, height = h,
    view = next(views) and views or nil, progress = frames_progress(opts),
  })
  if not ok then error(frames_error(r), 0) end
  out(format("wrote %s (a turntable: %d frame%s, %dx%d, %g a second) in %.1f s\n", r, nf,
    nf == 1 and "" or "s", fw, fh, fps or F.ORBIT_FPS, clock() - t0))
  return 0
end

-- `lsys animate MODEL -o OUT.mp4|OUT.gif`: the model growing, through ffmpeg.
local function run (args)
  local opts, pos = parse("animate", ANIMATE_OPTS, args, 2)
  if opts.help then out(HELP.animate) return 0 end
  if opts.orbit then return orbit(opts, pos) end
  for _, k in ipairs { "frames", "seconds", "axis" } do
    if opts[k] ~= nil then
      usage("animate", "--%s goes with --orbit (a turntable)%s", k, k == "frames" and
        "; for a picture of each step: lsys render MODEL --frames DIR" or "")
    end
  end
  local w, h = size_opt("animate", opts.size)
  local outpath = opts.output or default_output(pos, ".mp4", "tree.mp4")
  local ext = (outpath:match("%.(%w+)$") or ""):lower()
  if ext ~= "mp4" and ext ~= "gif" then
    usage("animate", "the output must be an .mp4 video or a .gif animation, got '%s' (for "
      .. "PNG pictures: lsys render MODEL --frames DIR)", outpath)
  end
  local every = int_opt("animate", "every", opts.every, 1)
  local fps = opts.fps and tonumber(opts.fps)
  if opts.fps ~= nil and not (fps and fps > 0 and fps <= 1000) then
    usage("animate", "--fps expects frames a second in (0, 1000], got '%s'", opts.fps)
  end
  local hold = opts.hold and tonumber(opts.hold)
  if opts.hold ~= nil and not (hold and hold >= 0 and hold <= 3600) then
    usage("animate", "--hold expects seconds from 0 to 3600, got '%s'", opts.hold)
  end
  local model, _, views = prepare("animate", opts, pos)
  local t0 = clock()
  local ok, r, n, fw, fh = pcall(F.animate, model, {
    out = outpath, fps = fps, hold = hold, every = every, width = w, height = h,
    view = next(views) and views or nil, progress = frames_progress(opts),
  })
  if not ok then error(frames_error(r), 0) end
  local held = hold and hold > 0 and format(", the last held %g s", hold) or ""
  out(format("wrote %s (%d frame%s, %dx%d, %g a second%s) in %.1f s\n", r, n,
    n == 1 and "" or "s", fw, fh, fps or F.FPS, held, clock() - t0))
  return 0
end

return run
