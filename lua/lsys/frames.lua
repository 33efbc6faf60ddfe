--- Picture series and growth animations: a model's derivation steps as PNG
-- pictures through one camera (`lsys.frames`), and those pictures as a video or an animated
-- GIF through ffmpeg (`lsys.animate`): what `lsys render MODEL --frames DIR` and
-- `lsys animate MODEL -o OUT` run.
--
-- Every picture of a series looks through the camera fitted to the last step's scene (the
-- `fit` box of lsys.render), so the plant grows in place instead of being fitted anew at
-- each step. lsys.growview does the same for a growing world (M.box, M.keep).
--
-- The strings of the steps kept are kept (not their scenes): each is interpreted, drawn
-- and let go in turn, the last one first, for the camera.
-- @module lsys.frames
local core = require "lsys.core"
local model = require "lsys.model"
local load = require "lsys.load"
local draw = require("lsys.render").draw
local shq = require("lsys.util.text").shq
local fs = require "lsys.util.fs"

local type, pairs, ipairs, error, pcall, tostring =
      type, pairs, ipairs, error, pcall, tostring
local io, os, math, string, table = io, os, math, string, table
local format = string.format
local _ENV = nil

local M = {}

M.PATTERN = "step-%04d.png"      -- the pictures' names: the step's number in %d
M.FPS = 4                        -- frames a second of an animation

--- The box a camera frames for a series of pictures ending with `scene` (the last step,
-- the grown world): {x0, y0, z0, x1, y1, z1}, its bounds (a unit box when it is empty).
function M.box (scene)
  local lo, hi = scene:bounds()
  if lo == nil then lo, hi = { -1, -1, -1 }, { 1, 1, 1 } end
  return { lo[1], lo[2], lo[3], hi[1], hi[2], hi[3] }
end

--- Whether step (or tick) `k` of `n` is drawn when drawing every `every`-th: the multiples
-- of `every`, and the last.
function M.keep (k, n, every)
  return k % every == 0 or k == n
end

-- {===========================================================================================
-- Options

local COMMON = {
  every = "integer", steps = "integer", width = "integer", height = "integer",
  view = "table", zoom = "number", wireframe = "boolean", progress = "function",
}
local FRAMES_OPTS = { dir = "string", pattern = "string", transparent = "boolean" }
local ANIMATE_OPTS = { out = "string", fps = "number", hold = "number", ffmpeg = "string" }
for k, t in pairs(COMMON) do FRAMES_OPTS[k], ANIMATE_OPTS[k] = t, t end

-- The options table `opts` of function `who`, checked against `spec` (error level 3: the
-- caller of lsys.frames or lsys.animate).
local function checkopts (who, opts, spec)
  if opts == nil then opts = {} end
  if type(opts) ~= "table" then error(format("%s: an options table expected", who), 3) end
  for k, v in pairs(opts) do
    local t = spec[k]
    if t == nil then error(format("%s: unknown option '%s'", who, tostring(k)), 3) end
    local ok = t == "integer" and math.type(v) == "integer" or
               t == "integer" and type(v) == "number" and v == math.floor(v) or type(v) == t
    if not ok then
      error(format("%s: option '%s' must be a %s, got %s", who, k,
        t == "integer" and "whole number" or t, type(v) == "string" and "'" .. v .. "'"
        or tostring(v)), 3)
    end
  end
  local function atleast (k, lo, hi)
    local v = opts[k]
    if v ~= nil and (v < lo or (hi and v > hi)) then
      error(format("%s: option '%s' must be %s, got %s", who, k, hi and
        format("from %d to %d", lo, hi) or format(">= %d", lo), tostring(v)), 4)
    end
  end
  atleast("every", 1)
  atleast("steps", 0, model.MAX_STEPS)
  atleast("width", 1, 16384)
  atleast("height", 1, 16384)
  return opts
end

-- The model of lsys.frames and lsys.animate: a Model, or a component graph's root
-- prototype (made one, as lsys.render does).
local function checkmodel (who, m)
  if load.isproto(m) then return load.tomodel(m) end
  if not model.ismodel(m) then
    error(format("%s: a Model (lsys.lsystem{...}) or a component prototype expected, got %s",
      who, type(m)), 3)
  end
  return m
end

-- 'msg' without the name of the lsys function that raised it ("lsys.render: ", "derive: ")
-- and with `who` in front.
local function blame (who, msg)
  msg = tostring(msg):gsub("^lsys%.render: ", ""):gsub("^render: ", "")
  return who .. ": " .. msg
end

-- Makes the folder `dir` and the ones above it that are missing. Raises naming it.
local function mkdirs (who, dir)
  local ok, err = fs.mkdirs(dir)
  if not ok then error(format("%s: %s", who, err), 0) end
end

-- }===========================================================================================


-- {===========================================================================================
-- The series

--[[
Derives model `m` (opts.steps, default m.steps) and writes one picture for every kept step
(M.keep with opts.every) through one camera, the last step's: the file `name(i, step)` for
the i-th picture. opts.progress(phase, k, n, detail): "derive" after step k of n (detail:
the modules), "frame" before the first picture (k = 0) and after picture k of n (detail:
its path; then the step it shows). Returns the paths and the steps.
]]
local function series (who, m, opts, name)
  local n = opts.steps or m.steps or 0
  local every = opts.every or 1
  local progress = opts.progress
  local kept, strings = {}, {}
  local ok, err = pcall(m.derive, m, n, {
    each = function (k, s)
      if M.keep(k, n, every) then kept[#kept + 1], strings[k] = k, s end
    end,
    progress = progress and function (k, nn, nmod) progress("derive", k, nn, nmod) end,
  })
  if not ok then error(blame(who, err), 0) end
  local function scene (k)
    local sok, sc = pcall(m.interpret, m, strings[k], opts.view)
    if not sok then error(blame(who, sc), 0) end
    strings[k] = nil                   -- the string is done with once drawn
    return sc
  end
  local last = scene(n)
  local box = M.box(last)
  local ropts = { fit = box, width = opts.width or 800, height = opts.height or 800,
                  zoom = opts.zoom, wireframe = opts.wireframe,
                  transparent = opts.transparent }
  local files = {}
  if progress then progress("frame", 0, #kept) end
  for i, k in ipairs(kept) do
    local path = name(i, k)
    local sc = k == n and last or scene(k)
    ropts.out = path                   -- the scene keeps its view, and its supersampling
    local rok, rerr = pcall(draw, sc, ropts)
    if not rok then error(blame(who, rerr), 0) end
    files[i] = path
    if progress then progress("frame", i, #kept, path, k) end
  end
  return files, kept
end

-- A picture name pattern: a .png name with one %d (%4d, %04d) for the step, no folder.
local function checkpattern (who, p)
  local _, npct = p:gsub("%%", "")
  if npct ~= 1 or not p:find("%%0?%d?d") or p:find("/") or not p:lower():find("%.png$") then
    error(format("%s: option 'pattern' must be a .png file name with one %%d for the step "
      .. "(as 'step-%%04d.png'), got '%s'", who, p), 3)
  end
end

--- Writes one PNG picture per derivation step of model `m` into a folder, all through one
-- camera fitted to the last step, so the plant grows in place. opts: `dir` (the folder,
-- made with the ones above it when missing; required), `every` (K: steps 0, K, 2K, ...
-- and always the last; default 1), `steps` (default m.steps), `width`, `height` (800),
-- `view` (view fields for the interpretation: camera, background, line_style, ...),
-- `zoom`, `wireframe`, `transparent` (as lsys.render), `pattern` (the file names, with
-- %d for the step: default "step-%04d.png"), `progress(phase, k, n, detail, step)`
-- ("derive": step k of n derived, detail the modules; "frame": picture k of n written,
-- detail its path, `step` the step it shows; k = 0 before the first). Each picture is
-- written whole or not at all (written aside, then renamed); files of the same names are
-- replaced. Returns the list of paths written and the list of the steps they show. Raises
-- naming the option or the file.
function M.frames (m, opts)
  local who = "lsys.frames"
  opts = checkopts(who, opts, FRAMES_OPTS)
  m = checkmodel(who, m)
  if opts.dir == nil then error("lsys.frames: option 'dir' (the folder) is required", 2) end
  if opts.dir == "" then error("lsys.frames: option 'dir' must not be empty", 2) end
  local pattern = opts.pattern or M.PATTERN
  checkpattern(who, pattern)
  mkdirs(who, opts.dir)
  local dir = opts.dir:gsub("/+$", "")
  if dir == "" then dir = "/" end
  return series(who, m, opts, function (_, k)
    return (dir == "/" and "" or dir) .. "/" .. format(pattern, k)
  end)
end

-- }===========================================================================================


-- {===========================================================================================
-- Animations through ffmpeg

-- One word for a POSIX shell: single quotes, a quote inside as '\''.

-- The path of the program `prog` (a name looked up on PATH, or a path), or nil.
local function which (prog)
  if prog:find("/") then return fs.isfile(prog) and prog or nil end
  for d in (os.getenv("PATH") or ""):gmatch("[^:]+") do
    if fs.isfile(d .. "/" .. prog) then return d .. "/" .. prog end
  end
  return nil
end

local FORMATS = { mp4 = "mp4", gif = "gif" }

-- The ffmpeg arguments that turn the pictures `input` (an image2 pattern) at `fps` into
-- the file `part` of format `fmt`, the last picture held `hold` seconds longer.
local function ffmpeg_args (fmt, input, fps, hold, part)
  local args = { "-hide_banner", "-loglevel", "error", "-nostdin", "-y",
                 "-framerate", format("%.17g", fps), "-i", input }
  local pad = hold > 0 and format("tpad=stop_mode=clone:stop_duration=%.17g", hold) or nil
  if fmt == "mp4" then
    if pad then args[#args + 1] = "-vf" args[#args + 1] = pad end
    for _, a in ipairs { "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18",
                         "-movflags", "+faststart" } do
      args[#args + 1] = a
    end
  else          -- one palette made for the whole animation: good colours, no dithering noise
    args[#args + 1] = "-filter_complex"
    args[#args + 1] = (pad and "[0:v]" .. pad .. "[v];[v]" or "[0:v]")
      .. "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse"
    args[#args + 1] = "-loop"
    args[#args + 1] = "0"
  end
  args[#args + 1] = "-f"
  args[#args + 1] = fmt
  args[#args + 1] = "file:" .. part     -- file: a name is never taken for a protocol
  return args
end

-- f(...), raising its error with `who` in front (`level`: error's level as the function
-- calling this one would give it).
local function checked (who, level, f, ...)
  local ok, r = pcall(f, ...)
  if not ok then error(format("%s: %s", who, tostring(r)), level > 0 and level + 1 or 0) end
  return r
end

-- A new output for the file `out` (core.outfile), or an error blaming the caller of the
-- caller: "who: cannot write 'out': why".
local function outfile (who, out)
  local ok, o = pcall(core.outfile, out)
  if not ok then
    error(format("%s: cannot write '%s': %s", who, out, tostring(o):match(": ([^:]*)$")
      or tostring(o)), 3)
  end
  return o
end

-- `p` as a program's argument that is a file: never an option (-x) nor a protocol (x:).
local function filearg (p)
  return p:sub(1, 1) == "/" and p or "./" .. p
end

-- Runs `prog args...`; returns true, or false and the last lines it printed and how it
-- ended.
local function run (prog, args)
  local words = { shq(prog) }
  for i, a in ipairs(args) do words[i + 1] = shq(a) end
  local p, perr = io.popen(table.concat(words, " ") .. " 2>&1", "r")
  if p == nil then return false, "", "not started: " .. tostring(perr) end
  local text, rerr = p:read("a")
  local ok, how, code = p:close()
  if ok and text ~= nil then return true end
  if text == nil then return false, "", "its output unread: " .. tostring(rerr) end
  local lines = {}
  for l in text:gmatch("[^\n]+") do lines[#lines + 1] = l end
  local tail = table.concat(lines, "\n", math.max(1, #lines - 4))
  return false, tail, how == "signal" and "signal " .. tostring(code) or "exit " ..
    tostring(code)
end

-- Raises, blaming the caller of the caller, when the file name `out` holds a control
-- character (a newline would split ffmpeg's messages and the shell's words).
local function refuse (who, out)
  if out:find("%c") then error(format("%s: refusing the file name %q", who, out), 3) end
end

--- Writes an animation of model `m` growing: one frame per derivation step (or every K-th
-- and the last), all through one camera fitted to the last step, encoded by ffmpeg as an
-- H.264 video (.mp4) or an animated GIF (.gif, one palette made for the whole). opts:
-- `out` (the file; required), `fps` (frames a second, default 4), `hold` (seconds the last
-- frame stays, default 0), `every`, `steps`, `width`, `height` (800; an .mp4's are rounded
-- up to even numbers, as H.264 needs), `view`, `zoom`, `wireframe`, `progress(phase, k, n,
-- detail)` (as lsys.frames, and "encode" before ffmpeg runs: k = 0, n = 1, detail the
-- output), `ffmpeg` (the program, default "ffmpeg" on PATH). The pictures are drawn in a
-- temporary folder, removed afterwards; `out` is written whole or not at all. Returns
-- `out`, the number of frames and the width and height. Raises when ffmpeg is missing
-- (saying how to install it) or fails (with the last lines it printed).
function M.animate (m, opts)
  local who = "lsys.animate"
  opts = checkopts(who, opts, ANIMATE_OPTS)
  m = checkmodel(who, m)
  local out = opts.out
  if out == nil then error("lsys.animate: option 'out' (an .mp4 or .gif file) is required", 2) end
  local fmt = FORMATS[(out:match("%.(%w+)$") or ""):lower()]
  if fmt == nil then
    error(format("lsys.animate: '%s': the output must be an .mp4 video or a .gif "
      .. "animation (for PNG pictures use lsys.frames)", out), 2)
  end
  refuse("lsys.animate", out)
  local fps, hold = opts.fps or M.FPS, opts.hold or 0
  if not (fps > 0 and fps <= 1000) then
    error(format("lsys.animate: option 'fps' must be in (0, 1000], got %s", tostring(fps)), 2)
  end
  if not (hold >= 0 and hold <= 3600) then
    error(format("lsys.animate: option 'hold' must be 0 to 3600 seconds, got %s",
      tostring(hold)), 2)
  end
  local prog = opts.ffmpeg or "ffmpeg"
  if which(prog) == nil then
    error(format("lsys.animate: %s is needed to write %s and %s: install it (Debian, "
      .. "Ubuntu: apt-get install ffmpeg), or write the pictures with lsys.frames "
      .. "(`lsys render MODEL --frames DIR`), which needs no ffmpeg", prog, out,
      prog:find("/") and "there is no " .. prog or "was not found on PATH"), 2)
  end
  local w, h = opts.width or 800, opts.height or 800
  if fmt == "mp4" then w, h = w + w % 2, h + h % 2 end
  local fopts = {}
  for k, v in pairs(opts) do if COMMON[k] then fopts[k] = v end end
  fopts.width, fopts.height = w, h
  -- the video: a new file beside `out` (core.outfile: made with O_EXCL, so never a planted
  -- link), which ffmpeg writes and which replaces `out` once it succeeded; the pictures: a
  -- new private folder under TMPDIR. Both go at an error or an interrupt (their __close).
  local video <close> = outfile(who, out)   -- a missing folder: said before any drawing
  local dir <close> = checked(who, 2, core.tempdir, nil, "lsys-frames")
  local pictures = filearg(dir:path()) .. "/frame-%06d.png"
  local files = series(who, m, fopts, function (i) return format(pictures, i) end)
  if opts.progress then opts.progress("encode", 0, 1, out) end
  local rok, tail, how = run(prog, ffmpeg_args(fmt, pictures, fps, hold,
                                               checked(who, 0, video.name, video)))
  if not rok then
    error(format("%s: %s failed (%s) writing '%s'%s", who, prog, how, out,
      tail ~= "" and ":\n" .. tail or ""), 0)
  end
  checked(who, 0, video.commit, video)
  checked(who, 0, dir.remove, dir)
  return out, #files, w, h
end

-- }===========================================================================================


-- {===========================================================================================
-- Turntables

M.ORBIT_PATTERN = "orbit-%04d.png"   -- a turntable's pictures: the frame's number from 0
M.ORBIT_FRAMES = 72                  -- frames of a turntable: one every 5 degrees
M.ORBIT_FPS = 24                     -- frames a second of a turntable
M.ORBIT_MARGIN = 0.9                 -- the share of the picture's half size the sphere fills

local ORBIT_OPTS = {
  out = "string", dir = "string", frames = "integer", seconds = "number", fps = "number",
  axis = "table", steps = "integer", width = "integer", height = "integer", view = "table",
  zoom = "number", wireframe = "boolean", transparent = "boolean", progress = "function",
  ffmpeg = "string",
}

local sqrt, abs, cos, sin, atan, rad = math.sqrt, math.abs, math.cos, math.sin, math.atan,
  math.rad
local LOOK = { "viewpoint", "target", "up", "direction", "projection", "fov", "twist" }

local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function cross (a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end
local function unit (a)
  local l = sqrt(dot(a, a))
  if not (l > 0 and l < math.huge) then return nil end
  return { a[1] / l, a[2] / l, a[3] / l }
end

-- `v` turned by `t` radians about the unit axis `a`, counterclockwise seen from a's tip
-- (Rodrigues' rotation formula).
local function turn (v, a, t)
  local c, s, ad = cos(t), sin(t), dot(a, v)
  local w = cross(a, v)
  local r = {}
  for i = 1, 3 do r[i] = v[i] * c + w[i] * s + a[i] * ad * (1 - c) end
  return r
end

-- The right and up vectors of a camera looking along the unit `f` with up `up`, turned by
-- `twist` degrees as the renderer turns them (an up along f is replaced as it does).
local function camframe (f, up, twist)
  local r = unit(cross(f, up))
  if r == nil or sqrt(dot(cross(f, up), cross(f, up))) < 1e-6 then
    local alt = { 0, 0, f[2] < 0 and -1 or 1 }
    if abs(f[3]) > 0.9 then alt = { 0, 1, 0 } end
    r = unit(cross(f, alt))
  end
  local u = cross(r, f)
  local t = rad(twist or 0)
  local ct, st = cos(t), sin(t)
  local r2, u2 = {}, {}
  for i = 1, 3 do r2[i] = ct * r[i] - st * u[i]; u2[i] = ct * u[i] + st * r[i] end
  return r2, u2
end

-- A 3-vector of numbers, or nil.
local function vec3 (x)
  if type(x) ~= "table" then return nil end
  for i = 1, 3 do if type(x[i]) ~= "number" then return nil end end
  return { x[1], x[2], x[3] }
end

--[[
The cameras of a turntable of `n` frames around scene `sc` drawn `w` x `h`: the view `v`'s
(the scene's, with the orbit's `axis`, else the view's up, else +y) direction turned by
360 k / n degrees about the axis through the centre of the scene's bounding sphere (the
sphere through the corners of its bounds), each fitted to that sphere, which never turns:
the whole plant stays in every picture, at the same size. Returns the cameras
{ angle =, viewpoint =, target =, up =, zoom = } and the box `fit` that goes with them.
]]
local function orbit_cameras (who, sc, v, n, axis, w, h, zoom)
  local b = M.box(sc)
  local c = { (b[1] + b[4]) / 2, (b[2] + b[5]) / 2, (b[3] + b[6]) / 2 }
  local R = sqrt((b[4] - b[1]) ^ 2 + (b[5] - b[2]) ^ 2 + (b[6] - b[3]) ^ 2) / 2
  if not (R > 0) then R = sqrt(3) end                -- a single point: the cube of size 2
  local a = unit(axis or vec3(v.up) or { 0, 1, 0 })
  if a == nil then error(format("%s: the orbit's axis must not be zero", who), 0) end
  local f0
  local eye, tgt = vec3(v.viewpoint), vec3(v.target)
  if eye then
    tgt = tgt or c
    f0 = { tgt[1] - eye[1], tgt[2] - eye[2], tgt[3] - eye[3] }
  else
    f0 = vec3(v.direction) or { 0, 0, -1 }
  end
  f0 = unit(f0)
  if f0 == nil then error(format("%s: the view's direction is zero", who), 0) end
  -- the camera's up: the axis; looking along the axis, the renderer's up for that
  -- direction, turned with the camera, so the picture turns in place
  local up0 = a
  if sqrt(dot(cross(f0, a), cross(f0, a))) < 1e-6 then
    local _, u = camframe(f0, a, 0)
    up0 = u
  end
  local aspect = w / h
  local small = math.min(1, aspect)
  local parallel = v.projection ~= "perspective"
  local ty = math.tan(rad((v.fov and v.fov > 0 and v.fov < 180) and v.fov or 30) / 2)
  local D = R / sin(atan(M.ORBIT_MARGIN * ty * small))   -- perspective: the sphere fits
  local cams = {}
  for k = 0, n - 1 do
    local t = 2 * math.pi * k / n
    local f = k == 0 and f0 or unit(turn(f0, a, t))
    local up = (k == 0 or up0 == a) and up0 or turn(up0, a, t)
    local z = zoom or 1
    local dist = parallel and 3 * R or D
    if parallel then
      -- the renderer fits the box `fit`, whose shadow turns with the camera: the zoom makes
      -- up for it, so the picture shows the sphere at the same size at every angle
      local r, u = camframe(f, up, v.twist)
      local ext = 0
      for i = 0, 7 do
        local q = { i & 1 == 1 and R or -R, i & 2 == 2 and R or -R, i & 4 == 4 and R or -R }
        ext = math.max(ext, abs(dot(q, u)), abs(dot(q, r)) / aspect)
      end
      z = z * ext * small / R
    end
    cams[k + 1] = {
      angle = 360 * k / n, zoom = z, up = { up[1], up[2], up[3] },
      target = { c[1], c[2], c[3] },
      viewpoint = { c[1] - dist * f[1], c[2] - dist * f[2], c[3] - dist * f[3] },
    }
  end
  return cams, { c[1] - R, c[2] - R, c[3] - R, c[1] + R, c[2] + R, c[3] + R }, R
end

-- The scene a turntable turns around: scene `x` itself, or model `x` (a component graph's
-- root made one) derived opts.steps (its own) steps and interpreted with opts.view.
local function orbit_scene (who, x, opts)
  if model.isscene(x) then return x end
  local m = checkmodel(who, x)
  local n = opts.steps or m.steps or 0
  local progress = opts.progress
  local ok, s = pcall(m.derive, m, n, {
    progress = progress and function (k, nn, nmod) progress("derive", k, nn, nmod) end,
  })
  if not ok then error(blame(who, s), 0) end
  local sok, sc = pcall(m.interpret, m, s, opts.view)
  if not sok then error(blame(who, sc), 0) end
  return sc
end

--- Writes a turntable of model or scene `x`: its final plant seen by a camera that goes
-- once around it, 360 / N degrees a frame, counterclockwise seen from the tip of the
-- axis. The axis is opts.axis, else the view's `up`, else +y; it passes through the centre
-- of the plant's bounding sphere (the sphere through the corners of its bounds). The first
-- frame looks along the view's direction (or from its viewpoint), so the elevation, the
-- projection, the field of view, the twist and the light stay the view's; the camera's
-- distance (its scale in a parallel projection) is fitted once, to the sphere, so the whole
-- plant stays in every frame at the same size. opts: `out` (an .mp4 or .gif, through
-- ffmpeg as lsys.animate) or `dir` (a folder for the PNG pictures orbit-0000.png,
-- orbit-0001.png, ...: the frame's number from 0): one of the two; `frames` (N, default 72)
-- or `seconds` (the length at `fps`), `fps` (default 24), `axis` ({x, y, z}), `steps` (a
-- model's, default its own), `width`, `height` (800; an .mp4's rounded up to even),
-- `view` (view fields for a model's interpretation), `zoom`, `wireframe`, `transparent`
-- (PNG pictures only), `progress(phase, k, n, detail, what)` (as lsys.animate; `what` is
-- the frame's angle, "90 degrees"), `ffmpeg`. Every file is written whole or not at all.
-- Returns `out` (or the list of pictures), the number of frames, the width and height,
-- and the cameras of the frames ({ angle =, viewpoint =, target =, up =, zoom = }: the
-- options lsys.render draws that frame with, together with `fit`, the box returned last).
-- Raises naming a bad option.
function M.orbit (x, opts)
  local who = "lsys.orbit"
  opts = checkopts(who, opts, ORBIT_OPTS)
  if not model.isscene(x) and not load.isproto(x) and not model.ismodel(x) then
    error(format("%s: a Model, a Scene or a component prototype expected, got %s", who,
      type(x)), 2)
  end
  local out, dir = opts.out, opts.dir
  if (out == nil) == (dir == nil) then
    error(format("%s: %s", who, out and "options 'out' and 'dir' do not go together: one "
      .. "file or one folder" or "option 'out' (an .mp4 or .gif file) or 'dir' (a folder "
      .. "for PNG pictures) is required"), 2)
  end
  if dir == "" then error(who .. ": option 'dir' must not be empty", 2) end
  local fmt
  if out then
    fmt = FORMATS[(out:match("%.(%w+)$") or ""):lower()]
    if fmt == nil then
      error(format("%s: '%s': the output must be an .mp4 video or a .gif animation (for "
        .. "PNG pictures use the option 'dir')", who, out), 2)
    end
    refuse(who, out)
    if opts.transparent then
      error(who .. ": option 'transparent' is for PNG pictures (option 'dir')", 2)
    end
  end
  local fps = opts.fps or M.ORBIT_FPS
  if not (fps > 0 and fps <= 1000) then
    error(format("%s: option 'fps' must be in (0, 1000], got %s", who, tostring(fps)), 2)
  end
  if opts.frames and opts.seconds then
    error(who .. ": options 'frames' and 'seconds' do not go together: give one", 2)
  end
  local n = opts.frames or M.ORBIT_FRAMES
  if opts.seconds then
    if not (opts.seconds > 0 and opts.seconds <= 3600) then
      error(format("%s: option 'seconds' must be in (0, 3600], got %s", who,
        tostring(opts.seconds)), 2)
    end
    n = math.max(1, math.floor(opts.seconds * fps + 0.5))
  end
  if n < 1 or n > 36000 then
    error(format("%s: option 'frames' must be from 1 to 36000, got %s", who, tostring(n)), 2)
  end
  local axis
  if opts.axis then
    axis = vec3(opts.axis)
    if axis == nil or #opts.axis ~= 3 or unit(axis) == nil then
      error(who .. ": option 'axis' must be a vector {x, y, z} of numbers, not zero", 2)
    end
  end
  if opts.zoom and not (opts.zoom > 0) then
    error(format("%s: option 'zoom' must be > 0, got %s", who, tostring(opts.zoom)), 2)
  end
  local prog = opts.ffmpeg or "ffmpeg"
  if out and which(prog) == nil then
    error(format("%s: %s is needed to write %s and %s: install it (Debian, Ubuntu: apt-get "
      .. "install ffmpeg), or write the pictures with the option 'dir', which needs no "
      .. "ffmpeg", who, prog, out, prog:find("/") and "there is no " .. prog
      or "was not found on PATH"), 2)
  end
  local w, h = opts.width or 800, opts.height or 800
  if fmt == "mp4" then w, h = w + w % 2, h + h % 2 end
  local video <close> = out and outfile(who, out) or nil
  local tmp <close> = out and checked(who, 2, core.tempdir, nil, "lsys-orbit") or nil
  local pattern
  if out then
    pattern = filearg(tmp:path()) .. "/frame-%06d.png"
  else
    mkdirs(who, dir)
    local d = dir:gsub("/+$", "")
    pattern = (d == "" and "" or d) .. "/" .. M.ORBIT_PATTERN
  end
  local sc = orbit_scene(who, x, opts)
  -- the camera to turn: the scene's view's (a model's: with opts.view), or opts.view's
  -- over a scene's
  local v, sv = {}, model.sceneview(sc) or {}
  for _, k in ipairs(LOOK) do
    v[k] = sv[k]
    if model.isscene(x) and opts.view and opts.view[k] ~= nil then v[k] = opts.view[k] end
  end
  local cams, fit = orbit_cameras(who, sc, v, n, axis, w, h, opts.zoom)
  local progress = opts.progress
  local files = {}
  if progress then progress("frame", 0, n) end
  for i, cam in ipairs(cams) do
    local path = format(pattern, i - 1)
    local ropts = { out = path, width = w, height = h, fit = fit, zoom = cam.zoom,
                    viewpoint = cam.viewpoint, target = cam.target, up = cam.up,
                    wireframe = opts.wireframe, transparent = opts.transparent }
    if model.isscene(x) and opts.view then
      for k, val in pairs(opts.view) do if ropts[k] == nil then ropts[k] = val end end
    end
    local rok, rerr = pcall(draw, sc, ropts)
    if not rok then error(blame(who, rerr), 0) end
    files[i] = path
    if progress then progress("frame", i, n, path, format("%g degrees", cam.angle)) end
  end
  if not out then return files, n, w, h, cams, fit end
  if progress then progress("encode", 0, 1, out) end
  local rok, tail, how = run(prog, ffmpeg_args(fmt, pattern, fps, 0,
                                               checked(who, 0, video.name, video)))
  if not rok then
    error(format("%s: %s failed (%s) writing '%s'%s", who, prog, how, out,
      tail ~= "" and ":\n" .. tail or ""), 0)
  end
  checked(who, 0, video.commit, video)
  checked(who, 0, tmp.remove, tmp)
  return out, n, w, h, cams, fit
end

-- }===========================================================================================

return M
