-- Turntables: lsys.orbit (lsys.frames.orbit) and `lsys animate MODEL --orbit`. The cameras
-- the frames report (turned 360 k / N degrees about the axis, at one distance, the
-- elevation kept), frame 0 against a plain render through the same camera, frame N/4
-- against a render of the view turned 90 degrees, the plant inside every frame, the PNG
-- pictures' names, GIF and H.264 outputs read back with ffprobe, and the bad options.
--
-- Tagged #gl (the pictures go through OSMesa). The video specs are pending when ffmpeg or
-- ffprobe is not installed (Debian package ffmpeg).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"
local frames = require "lsys.frames"

local BIN, sh = H.BIN, H.sh
local q = require("lsys.util.text").shq

-- A plant that looks different from every side: a trunk, a long branch leaning towards +x,
-- a short one towards -z in another colour, and a twig at the top towards +x +z.
local PLANT = [[F(4) [ &(60) F(3) ] [ /(90) &(70) ;(2) F(1.5) ] F(1) [ /(45) &(40) ;(3) F(1) ] ]]

local function plant (view)
  local v = { line_width = 4, background = { 1, 1, 1 } }
  for k, x in pairs(view or {}) do v[k] = x end
  return lsys.lsystem { axiom = PLANT, steps = 0, view = v }
end

local function have (prog) return (sh("command -v " .. prog)) ~= "" end

local function probe (path)
  local out = sh("ffprobe -v error -count_frames -select_streams v:0 -show_entries " ..
    "stream=nb_read_frames,width,height,codec_name -of default=nw=1 " .. q(path))
  local r = {}
  for k, v in out:gmatch("([%w_]+)=(%S+)") do r[k] = tonumber(v) or v end
  return r
end

local function sub (a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function cross (a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end

-- The signed angle in degrees (0 to 360) from `a` to `b` about the unit axis `n`, both
-- taken perpendicular to it; and their parts along it.
local function angle_about (a, b, n)
  local pa, pb = dot(a, n), dot(b, n)
  local ua = { a[1] - pa * n[1], a[2] - pa * n[2], a[3] - pa * n[3] }
  local ub = { b[1] - pb * n[1], b[2] - pb * n[2], b[3] - pb * n[3] }
  local t = math.deg(math.atan(dot(cross(ua, ub), n), dot(ua, ub)))
  if t < -1e-9 then t = t + 360 end
  return t, pa, pb
end

describe("#gl turntables", function()
  if not core.has_render then
    pending("lsys was built without OSMesa (install libosmesa6-dev and rebuild)")
    return
  end
  local dir
  before_each(function() dir = H.tmpdir() end)
  after_each(function() H.rmdir(dir) end)

  it("writes N pictures named by frame from 0, with progress, and reports N cameras",
     function()
    local calls = {}
    local files, n, w, h, cams = lsys.orbit(plant(), {
      dir = dir .. "/spin", frames = 8, width = 64, height = 48,
      progress = function (phase, k, nn, _, what)
        calls[#calls + 1] = phase .. " " .. k .. "/" .. nn .. (what and " " .. what or "")
      end,
    })
    assert.equal(8, n)
    assert.same({ 64, 48 }, { w, h })
    assert.equal(8, #files)
    assert.equal(8, #cams)
    for k = 0, 7 do
      assert.equal(dir .. "/spin/" .. string.format("orbit-%04d.png", k), files[k + 1])
      local _, pw, ph = core.png_read(files[k + 1])
      assert.same({ 64, 48 }, { pw, ph })
      assert.near(45 * k, cams[k + 1].angle, 1e-12)
    end
    assert.equal("frame 0/8", calls[1])
    assert.equal("frame 1/8 0 degrees", calls[2])
    assert.equal("frame 3/8 90 degrees", calls[4])
    assert.equal("frame 8/8 315 degrees", calls[#calls])
    assert.equal(9, #calls)                      -- before the first frame, then 8 frames
    assert.equal(frames.orbit, lsys.orbit)
  end)

  it("turns the camera 360 k / N degrees about the axis, at one distance and elevation",
     function()
    for _, case in ipairs {
      { view = { direction = { 0, -0.5, -1 } }, axis = nil, n = 12, up = { 0, 1, 0 } },
      { view = { direction = { 1, 0.3, 0 }, projection = "perspective" }, n = 7,
        up = { 0, 1, 0 } },
      { view = { direction = { 0, -1, -1 } }, axis = { 0, 0, 2 }, n = 5, up = { 0, 0, 1 } },
      { view = { up = { 1, 0, 0 }, direction = { 0, 0, -1 } }, n = 4, up = { 1, 0, 0 } },
    } do
      local _, n, _, _, cams = lsys.orbit(plant(case.view), {
        dir = dir, frames = case.n, axis = case.axis, width = 32, height = 32 })
      assert.equal(case.n, n)
      local c0 = cams[1]
      local e0 = sub(c0.viewpoint, c0.target)
      for k = 1, n do
        local c = cams[k]
        assert.same(c0.target, c.target)
        assert.same(case.up, c.up)
        local e = sub(c.viewpoint, c.target)
        local t, p0, p = angle_about(e0, e, case.up)
        assert.near(360 * (k - 1) / n, t, 1e-9)
        assert.near(p0, p, 1e-9 * math.sqrt(dot(e0, e0)))          -- the elevation stays
        assert.near(math.sqrt(dot(e0, e0)), math.sqrt(dot(e, e)), 1e-9 * math.sqrt(dot(e0, e0)))
      end
      -- the first camera looks along the view's direction
      local d = case.view.direction or { 0, 0, -1 }
      local l = math.sqrt(dot(d, d))
      local le = math.sqrt(dot(e0, e0))
      for i = 1, 3 do assert.near(-d[i] / l, e0[i] / le, 1e-12) end
    end
  end)

  it("looking along the axis, turns the picture in place", function()
    local _, _, _, _, cams = lsys.orbit(plant { direction = { 0, -1, 0 } }, {
      dir = dir, frames = 6, width = 32, height = 32 })
    local e0 = sub(cams[1].viewpoint, cams[1].target)
    for k = 1, 6 do
      local c = cams[k]
      assert.same(e0, sub(c.viewpoint, c.target))
      assert.near(0, dot(c.up, { 0, 1, 0 }), 1e-12)
      assert.near(60 * (k - 1), (angle_about(cams[1].up, c.up, { 0, 1, 0 })), 1e-9)
    end
  end)

  it("draws frame 0 as a plain render through the same camera", function()
    local m = plant()
    local files, _, w, h, cams, fit = lsys.orbit(m, { dir = dir, frames = 8, width = 96,
                                                      height = 96 })
    local px = core.png_read(files[1])
    -- the view's own camera (along -z, fitted to the box), at the frame's zoom
    local plain = lsys.render(m, { fit = fit, zoom = cams[1].zoom, width = w, height = h })
    assert.is_true(H.compare_images(px, plain, w, h))
    -- and not the plain picture fitted to the plant alone: the sphere leaves a margin
    local fitted = lsys.render(m, { width = w, height = h })
    assert.is_false((H.compare_images(px, fitted, w, h)))
  end)

  it("draws frame N/4 as the view turned 90 degrees about the up axis", function()
    for _, proj in ipairs { "parallel", "perspective" } do
      local m = plant { projection = proj }
      local files, _, w, h, cams, fit = lsys.orbit(m, { dir = dir, frames = 8, width = 96,
                                                        height = 96 })
      local quarter = core.png_read(files[3])
      assert.near(90, cams[3].angle, 1e-12)
      -- turned 90 degrees counterclockwise seen from +y: -z becomes -x
      local ropts = { width = w, height = h, fit = fit, zoom = cams[3].zoom }
      if proj == "parallel" then
        ropts.direction = { -1, 0, 0 }
      else                               -- the eye where the sphere fits, on the +x side
        local c, e = cams[1].target, sub(cams[1].viewpoint, cams[1].target)
        local D = math.sqrt(dot(e, e))
        ropts.viewpoint, ropts.target = { c[1] + D, c[2], c[3] }, c
      end
      local turned = lsys.render(m, ropts)
      assert.is_true(H.compare_images(quarter, turned, w, h))
      -- the plant is not the same from the side: the comparison can tell
      assert.is_false((H.compare_images(quarter, core.png_read(files[1]), w, h)))
    end
  end)

  it("keeps the whole plant inside every frame, at the same size", function()
    for _, view in ipairs {
      {}, { projection = "perspective", fov = 40 }, { direction = { 0.3, -0.8, -1 } },
    } do
      local files = lsys.orbit(plant(view), { dir = dir, frames = 12, width = 80,
                                              height = 60 })
      for k, f in ipairs(files) do
        local ink = H.ink(f)
        assert.is_true(ink.n > 20, "frame " .. k)
        local x0, y0, x1, y1 = table.unpack(ink.box)
        assert.is_true(x0 >= 1 and y0 >= 1 and x1 <= 78 and y1 <= 58,
                       string.format("frame %d: ink from (%d, %d) to (%d, %d)", k, x0, y0, x1, y1))
      end
    end
    -- seen level in a parallel projection, the plant's height in the picture never changes
    local files = lsys.orbit(plant(), { dir = dir, frames = 8, width = 120, height = 120 })
    local first = H.ink(files[1]).box
    for k = 2, 8 do
      local box = H.ink(files[k]).box
      assert.is_true(math.abs((box[4] - box[2]) - (first[4] - first[2])) <= 1, "frame " .. k)
      assert.is_true(math.abs(box[4] - first[4]) <= 1, "frame " .. k)     -- the base stays
    end
  end)

  it("writes the same pictures every time, whatever the threads", function()
    local a = lsys.orbit(plant(), { dir = dir .. "/a", frames = 3, width = 40, height = 40 })
    local function grown (threads)
      return lsys.lsystem { axiom = "X", steps = 3, threads = threads,
        productions = "X --> " .. PLANT .. " /(40) X",
        view = { line_width = 4, background = { 1, 1, 1 } } }
    end
    local m, m1 = grown(2), grown(1)
    local b = lsys.orbit(m, { dir = dir .. "/b", frames = 3, width = 40, height = 40 })
    local c = lsys.orbit(m1, { dir = dir .. "/c", frames = 3, width = 40, height = 40 })
    local a2 = lsys.orbit(plant(), { dir = dir .. "/a2", frames = 3, width = 40, height = 40 })
    for i = 1, 3 do
      assert.equal(H.read(a[i]), H.read(a2[i]))
      assert.equal(H.read(b[i]), H.read(c[i]))
    end
  end)

  it("turns a Scene too, with the view's camera fields", function()
    local m = plant()
    local sc = m:interpret(m:derive())
    local _, _, _, _, cams = lsys.orbit(sc, { dir = dir, frames = 4, width = 32, height = 32,
                                              view = { direction = { 1, 0, 0 } } })
    local e = sub(cams[1].viewpoint, cams[1].target)
    assert.is_true(e[1] < 0 and math.abs(e[2]) < 1e-9 and math.abs(e[3]) < 1e-9)
  end)

  it("writes a looping GIF and an H.264 video of N frames", function()
    if not (have("ffmpeg") and have("ffprobe")) then
      pending("ffmpeg and ffprobe are needed (apt-get install ffmpeg)")
      return
    end
    local gif = dir .. "/spin.gif"
    local r, n, w, h = lsys.orbit(plant(), { out = gif, frames = 6, width = 48, height = 40 })
    assert.same({ gif, 6, 48, 40 }, { r, n, w, h })
    local p = probe(gif)
    assert.same({ 6, 48, 40, "gif" }, { p.nb_read_frames, p.width, p.height, p.codec_name })
    local mp4 = dir .. "/spin.mp4"
    r, n, w, h = lsys.orbit(plant(), { out = mp4, seconds = 0.5, fps = 10, width = 47,
                                       height = 33 })
    assert.same({ mp4, 5, 48, 34 }, { r, n, w, h })
    p = probe(mp4)
    assert.same({ 5, 48, 34, "h264" }, { p.nb_read_frames, p.width, p.height, p.codec_name })
    assert.same({ "spin.gif", "spin.mp4" }, (function ()
      local t = {}
      for f in sh("ls -1 " .. q(dir)):gmatch("[^\n]+") do t[#t + 1] = f end
      return t
    end)())
  end)

  it("lsys animate --orbit writes a turntable, with a line per frame under --progress",
     function()
    if not (have("ffmpeg") and have("ffprobe")) then
      pending("ffmpeg and ffprobe are needed (apt-get install ffmpeg)")
      return
    end
    local model = dir .. "/bush.lua"
    H.write(model, "local lsys = require 'lsys'\nreturn lsys.lsystem { axiom = '" .. PLANT
      .. "', view = { line_width = 3 } }\n")
    local out, code = sh("cd " .. q(dir) .. " && " .. H.ABSBIN .. " animate bush.lua --orbit "
      .. "--frames 4 --size 40x40 --progress --axis 0,1,0 2>&1")
    assert.equal(0, code, out)
    assert.truthy(out:find("frame 2/4: 90 degrees", 1, true), out)
    assert.truthy(out:find("wrote bush-orbit.mp4 (a turntable: 4 frames, 40x40, 24 a second)",
                           1, true), out)
    assert.equal(4, probe(dir .. "/bush-orbit.mp4").nb_read_frames)
    out, code = sh(BIN .. " animate " .. q(model) .. " --orbit --seconds 0.25 --fps 8 "
      .. "--size 40x40 -o " .. q(dir .. "/b.gif") .. " 2>&1")
    assert.equal(0, code, out)
    assert.equal(2, probe(dir .. "/b.gif").nb_read_frames)
  end)

  it("says what is wrong with an option", function()
    local m = plant()
    local function raises (opts, msg)
      assert.error_contains(function () lsys.orbit(m, opts) end, msg)
    end
    raises({ frames = 4 }, "lsys.orbit: option 'out' (an .mp4 or .gif file) or 'dir'")
    raises({ out = "a.gif", dir = dir }, "options 'out' and 'dir' do not go together")
    raises({ dir = dir, frames = 0 }, "option 'frames' must be from 1 to 36000, got 0")
    raises({ dir = dir, frames = 2.5 }, "option 'frames' must be a whole number, got 2.5")
    raises({ dir = dir, frames = 3, seconds = 1 }, "'frames' and 'seconds' do not go together")
    raises({ dir = dir, seconds = -1 }, "option 'seconds' must be in (0, 3600], got -1")
    raises({ dir = dir, fps = 0 }, "option 'fps' must be in (0, 1000], got 0")
    raises({ dir = dir, axis = { 0, 0, 0 } }, "option 'axis' must be a vector {x, y, z}")
    raises({ dir = dir, axis = { 1, "y", 0 } }, "option 'axis' must be a vector {x, y, z}")
    raises({ dir = dir, zoom = 0 }, "option 'zoom' must be > 0, got 0")
    raises({ dir = dir, spin = 1 }, "lsys.orbit: unknown option 'spin'")
    raises({ out = dir .. "/a.png" }, "the output must be an .mp4 video or a .gif animation")
    raises({ out = dir .. "/a.gif", transparent = true }, "'transparent' is for PNG pictures")
    raises({ out = dir .. "/a.gif", ffmpeg = dir .. "/none" }, "there is no " .. dir .. "/none")
    assert.error_contains(function () lsys.orbit("F", { dir = dir }) end,
                          "a Model, a Scene or a component prototype expected, got string")
    local function usage (args, msg)
      local out, code = sh(BIN .. " animate " .. args .. " 2>&1")
      assert.equal(2, code, out)
      assert.truthy(out:find("lsys: animate: " .. msg, 1, true), out)
    end
    usage("--orbit --every 2", "--every is for the growth animation, not with --orbit")
    usage("--orbit --hold 1", "--hold is for the growth animation, not with --orbit")
    usage("--frames 4", "--frames goes with --orbit (a turntable); for a picture of each")
    usage("--axis 0,1,0", "--axis goes with --orbit (a turntable)")
    usage("--orbit --frames 0", "--frames expects a whole number >= 1, got '0'")
    usage("--orbit --frames 2 --seconds 1", "--frames and --seconds do not go together")
    usage("--orbit --seconds x", "--seconds expects a length in (0, 3600], got 'x'")
    usage("--orbit --axis 0,0,0", "--axis expects a vector X,Y,Z that is not zero")
    usage("--orbit --axis 1,2", "--axis expects a vector X,Y,Z that is not zero, got '1,2'")
    usage("--orbit -o x.png", "the output must be an .mp4 video or a .gif animation")
  end)
end)
