--- `lsys render`: a model rendered headless to a PNG file (or an SVG, EPS or PDF picture), or
-- with --frames DIR one picture per derivation step through one camera.
-- @module lsys.cli.commands.render
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help
local frames = require("lsys.frames").frames
local lrender = require "lsys.render"
local render = lrender.render
local vector = require "lsys.vector"

local error, pcall, next, tostring = error, pcall, next, tostring
local io, string = io, string
local format = string.format
local parse, out, usage, clock, RENDER_OPTS = A.parse, A.out, A.usage, A.clock, A.RENDER_OPTS
local size_opt, int_opt, default_output = A.size_opt, A.int_opt, A.default_output
local frames_progress, frames_error = A.frames_progress, A.frames_error
local prepare, scene_of = S.prepare, S.scene_of
local _ENV = nil

-- `lsys render MODEL --frames DIR`: one picture per step through one camera.
local function render_frames (opts, pos, w, h)
  local every = int_opt("render", "every", opts.every, 1)
  local model, _, views = prepare("render", opts, pos)
  local t0 = clock()
  local ok, files, steps = pcall(frames, model, {
    dir = opts.frames, every = every, width = w, height = h,
    view = next(views) and views or nil, progress = frames_progress(opts),
  })
  if not ok then error(frames_error(files), 0) end
  local function base (f) return f:match("([^/]*)$") end
  out(format("wrote %d picture%s of steps %d to %d to %s (%s%s, %dx%d, one camera) in %.1f s\n",
    #files, #files == 1 and "" or "s", steps[1], steps[#steps], opts.frames, base(files[1]),
    #files > 1 and " to " .. base(files[#files]) or "", w, h, clock() - t0))
  return 0
end

local function run (args)
  local opts, pos = parse("render", RENDER_OPTS, args, 2)
  if opts.help then out(HELP.render) return 0 end
  if opts.lines ~= nil then usage("render", "--lines applies to export only") end
  local w, h = size_opt("render", opts.size)
  w, h = w or 800, h or 800
  if opts.frames ~= nil then
    if opts.output ~= nil then
      usage("render", "--frames DIR writes one picture per step and -o one picture: "
        .. "give one of them")
    end
    if opts.frames == "" then usage("render", "--frames expects a folder, got ''") end
    return render_frames(opts, pos, w, h)
  end
  if opts.every ~= nil then usage("render", "--every applies to --frames") end
  local outpath = opts.output or default_output(pos, ".png", "tree.png")
  local ext = outpath:lower():match("%.(%w+)$")
  if ext ~= "png" and not vector.FORMATS[ext or ""] then
    usage("render", "the output must be a %s file, got '%s'", vector.KNOWN, outpath)
  end
  local scene, _, views, verbose, drawn = scene_of("render", opts, pos)
  local t0 = clock()
  -- a model's views went to its interpretation; a population's (a file returning a Scene)
  -- replace its picture's
  -- a 3D plant is shaded: shadows, a ground, a sky unless a background is given
  local ro = { out = outpath, width = w, height = h,
               view = not drawn and next(views) and views or nil }
  if not opts.flat then lrender.shaded(scene, ro, views.background ~= nil) end
  if opts.ao then ro.ao = true end
  local ok, err = pcall(render, scene, ro)
  -- the command's messages name no library function (as export's do)
  if not ok then
    error((tostring(err):gsub("^[^\n]-:%d+: ", ""):gsub("^lsys%.render: ", "")), 0)
  end
  if verbose then
    io.stderr:write(format("rendered %dx%d in %.2f s\n", w, h, clock() - t0))
  end
  out(format("wrote %s (%dx%d, %d triangles, %d lines)\n", outpath, w, h, scene.ntriangles,
    scene.nlines))
  return 0
end

return run
