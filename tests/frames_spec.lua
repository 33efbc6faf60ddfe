-- Picture series and growth animations: lsys.frames and lsys.animate,
-- `lsys render MODEL --frames DIR` and `lsys animate MODEL -o OUT`. One camera for every
-- picture (the last step's), the steps kept by --every, the files; ffmpeg's videos and GIFs
-- read back with ffprobe; the messages without ffmpeg, when it fails, and for bad options.
--
-- Tagged #gl (the pictures go through OSMesa). The animation specs are pending when ffmpeg
-- or ffprobe is not installed (Debian package ffmpeg; ./setup.sh installs it).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

local BIN, ABSBIN, sh = H.BIN, H.ABSBIN, H.sh

-- A bush that grows fast: step k is about 3.5 times as tall as step k - 1.
local MODEL = [[
local lsys = require "lsys"
return lsys.lsystem {
  axiom = "F", steps = 5, productions = "F --> F[+F]F[-F]F",
  view = { angle = 25.7, background = { 1, 1, 1 } },
}
]]

local function bush ()
  return lsys.lsystem { axiom = "F", steps = 5, productions = "F --> F[+F]F[-F]F",
                        view = { angle = 25.7, background = { 1, 1, 1 } } }
end

local function have (prog) return (sh("command -v " .. prog)) ~= "" end

-- One word for the shell.
local q = require("lsys.util.text").shq

-- The frames, width and height of a video or GIF, as ffprobe counts them.
local function probe (path)
  local out = sh("ffprobe -v error -count_frames -select_streams v:0 -show_entries " ..
    "stream=nb_read_frames,width,height,codec_name,pix_fmt -of default=nw=1 " .. q(path))
  local r = {}
  for k, v in out:gmatch("([%w_]+)=(%S+)") do r[k] = tonumber(v) or v end
  return r
end

-- f(m, opts) raises an error that says `msg`.
local function raises (f, m, opts, msg)
  assert.error_contains(function () f(m, opts) end, msg)
end

-- `lsys CMD ARGS` is a usage error (exit 2) that says `msg`.
local function usage (cmd, args, msg)
  local out, code = sh(BIN .. " " .. cmd .. " " .. args)
  assert.equal(2, code, out)
  assert.truthy(out:find("lsys: " .. cmd .. ": " .. msg, 1, true), out)
  assert.truthy(out:find("Run 'lsys " .. cmd .. " --help' for its options.", 1, true), out)
end

-- The files in a folder, sorted.
local function ls (dir)
  local out = sh("ls -1 " .. q(dir))
  local t = {}
  for f in out:gmatch("[^\n]+") do t[#t + 1] = f end
  return t
end

describe("#gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa (install libosmesa6-dev and rebuild)")
    return
  end
  local dir
  before_each(function() dir = H.tmpdir() end)
  after_each(function() H.rmdir(dir) end)

  describe("picture series", function()

    it("writes steps 0, K, 2K, ... and the last, named by step, all the same size", function()
      local calls = {}
      local files, steps = lsys.frames(bush(), {
        dir = dir .. "/a/b", every = 2, width = 64, height = 48,
        progress = function (phase, k, n, _, step) calls[#calls + 1] = { phase, k, n, step } end,
      })
      assert.same({ 0, 2, 4, 5 }, steps)
      assert.same({ dir .. "/a/b/step-0000.png", dir .. "/a/b/step-0002.png",
                    dir .. "/a/b/step-0004.png", dir .. "/a/b/step-0005.png" }, files)
      assert.same({ "step-0000.png", "step-0002.png", "step-0004.png", "step-0005.png" },
                  ls(dir .. "/a/b"))           -- nothing else: no temporary file left
      for _, f in ipairs(files) do
        local _, w, h = core.png_read(f)
        assert.equal(64, w)
        assert.equal(48, h)
      end
      -- the derivation's 5 steps, then the pictures: 0 of 4 before the first
      assert.same({ "derive", 1, 5 }, { calls[1][1], calls[1][2], calls[1][3] })
      assert.same({ "frame", 0, 4 }, { calls[6][1], calls[6][2], calls[6][3] })
      assert.same({ "frame", 4, 4, 5 }, calls[10])
      assert.equal(10, #calls)
    end)

    it("draws every picture through the last step's camera, so the plant grows in place",
    function()
      local m = bush()
      local files, steps = lsys.frames(m, { dir = dir, width = 64, height = 64 })
      assert.same({ 0, 1, 2, 3, 4, 5 }, steps)
      local ink = {}
      for i, f in ipairs(files) do ink[i] = H.ink(f) end
      for i = 2, #ink do
        -- more ink each step, inside the box of the step after it, from the same root (step 0,
        -- one unit in 125, is under a pixel: no ink)
        assert.is_true(ink[i].n >= ink[i - 1].n, i .. ": " .. ink[i].n .. " < " .. ink[i - 1].n)
        local a, b = ink[i - 1].box, ink[i].box
        if ink[i - 1].n > 0 then
          assert.is_true(a[1] >= b[1] - 1 and a[2] >= b[2] - 1 and a[3] <= b[3] + 1 and
                         a[4] <= b[4] + 1, table.concat(a, " ") .. " vs " .. table.concat(b, " "))
          assert.is_true(math.abs(a[4] - b[4]) <= 1)   -- the base stays put
        end
      end
      assert.is_true(ink[2].n > 0)
      -- the last picture is the last step drawn on its own (fitted to itself)
      local last = m:interpret(m:derive(5))
      local px = lsys.render(last, { width = 64, height = 64 })
      assert.is_true(H.compare_images(core.png_read(files[6]), px, 64, 64))
      -- an early step is not fitted to itself: drawn alone it fills the picture, in the
      -- series it is a small part of the last one
      lsys.render(m:interpret(m:derive(2)), { out = dir .. "/alone.png", width = 64, height = 64 })
      local alone = H.ink(dir .. "/alone.png")
      assert.is_true(ink[3].n < alone.n / 2, ink[3].n .. " vs " .. alone.n)
      assert.is_true(ink[3].box[4] - ink[3].box[2] < (alone.box[4] - alone.box[2]) / 2)
      assert.is_true(ink[3].n < ink[6].n / 4, ink[3].n .. " vs " .. ink[6].n)
    end)

    it("takes view options, a file name pattern and a number of steps", function()
      local files, steps = lsys.frames(bush(), {
        dir = dir, steps = 2, width = 32, height = 32, pattern = "bush_%03d.png",
        view = { background = { 0, 0, 0 } },
      })
      assert.same({ 0, 1, 2 }, steps)
      assert.same({ dir .. "/bush_000.png", dir .. "/bush_001.png", dir .. "/bush_002.png" },
                  files)
      assert.same({ 0, 0, 0 }, { core.png_read(files[1]):byte(1, 3) })
    end)

    it("says what is wrong with an option", function()
      local m = bush()
      local function err (opts, msg) raises(lsys.frames, m, opts, msg) end
      err({ dir = dir, every = 0 }, "lsys.frames: option 'every' must be >= 1, got 0")
      err({ dir = dir, every = 1.5 }, "option 'every' must be a whole number, got 1.5")
      err({ every = 2 }, "lsys.frames: option 'dir' (the folder) is required")
      err({ dir = dir, size = 3 }, "lsys.frames: unknown option 'size'")
      err({ dir = dir, width = 0 }, "option 'width' must be from 1 to 16384, got 0")
      err({ dir = dir, pattern = "step.png" }, "option 'pattern' must be a .png file name "
        .. "with one %d for the step (as 'step-%04d.png'), got 'step.png'")
      err({ dir = dir, pattern = "a/%d.png" }, "got 'a/%d.png'")
      err({ dir = dir, pattern = "%d-%d.png" }, "got '%d-%d.png'")
      assert.error_contains(function () lsys.frames("m", { dir = dir }) end,
        "lsys.frames: a Model (lsys.lsystem{...}) or a component prototype expected, got string")
      H.write(dir .. "/file", "")
      err({ dir = dir .. "/file/x" }, "lsys.frames: cannot make the directory " .. dir ..
        "/file: a file is in the way")
      -- the message is the caller's: it names the line that called lsys.frames
      local ok, msg = pcall(lsys.frames, m, { dir = dir, every = 0 })
      assert.is_false(ok)
      assert.truthy(msg:find("^lsys.frames: ") or msg:find("frames_spec.lua:%d+: lsys.frames"),
                    msg)
    end)

    it("lsys render --frames writes the series, with a line per frame under --progress",
    function()
      H.write(dir .. "/bush.lua", MODEL)
      local out, code = sh(BIN .. " render " .. dir .. "/bush.lua --frames " .. dir ..
        "/fr --every 3 --size 40x30 --progress")
      assert.equal(0, code, out)
      assert.truthy(out:find("frame 1/3: step 0 (", 1, true), out)
      assert.truthy(out:find("frame 3/3: step 5 (", 1, true), out)
      assert.truthy(out:find("step 5/5: 7811 modules", 1, true), out)
      assert.truthy(out:find("wrote 3 pictures of steps 0 to 5 to " .. dir .. "/fr (step-0000.png "
        .. "to step-0005.png, 40x30, one camera) in ", 1, true), out)
      assert.same({ "step-0000.png", "step-0003.png", "step-0005.png" }, ls(dir .. "/fr"))
      local _, w, h = core.png_read(dir .. "/fr/step-0003.png")
      assert.same({ 40, 30 }, { w, h })
      -- the last picture is what `lsys render` draws of the model
      sh(BIN .. " render " .. dir .. "/bush.lua --size 40x30 -o " .. dir .. "/one.png")
      assert.is_true(H.compare_images(core.png_read(dir .. "/fr/step-0005.png"),
                                      (core.png_read(dir .. "/one.png")), 40, 30))
      -- without --progress (and not on a terminal): the result line only
      out, code = sh(BIN .. " render " .. dir .. "/bush.lua --frames " .. dir .. "/fr2 --steps 1"
        .. " --size 16x16")
      assert.equal(0, code, out)
      assert.equal("wrote 2 pictures of steps 0 to 1 to " .. dir .. "/fr2 (step-0000.png to "
        .. "step-0001.png, 16x16, one camera) in ", out:match("^(.-)%d+%.%d s\n$"))
    end)

    it("lsys render says which options do not go together", function()
      H.write(dir .. "/bush.lua", MODEL)
      local function render (args, msg) usage("render", dir .. "/bush.lua " .. args, msg) end
      render("--frames " .. dir .. "/f --every 0", "--every expects a whole number >= 1, got '0'")
      render("--frames " .. dir .. "/f --every x", "--every expects a whole number >= 1, got 'x'")
      render("--frames " .. dir .. "/f -o " .. dir .. "/x.png",
        "--frames DIR writes one picture per step and -o one picture: give one of them")
      render("--every 2", "--every applies to --frames")
      local out, code = sh(BIN .. " export " .. dir .. "/bush.lua -o " .. dir ..
        "/x.obj --frames " .. dir)
      assert.equal(2, code, out)
      assert.truthy(out:find("--frames and --every apply to render only", 1, true), out)
      assert.same({ "bush.lua" }, ls(dir))      -- nothing written
    end)
  end)

  describe("growth animations", function()

    local function ffmpeg ()
      if have("ffmpeg") and have("ffprobe") then return true end
      pending("ffmpeg is not installed (Debian package ffmpeg; ./setup.sh installs it)")
      return false
    end

    it("writes an animated GIF of every step, then removes its pictures", function()
      if not ffmpeg() then return end
      local pictures = {}
      local out, n, w, h = lsys.animate(bush(), { out = dir .. "/bush.gif", width = 64,
        height = 48, progress = function (phase, k, _, path)
          if phase == "frame" and k > 0 then pictures[#pictures + 1] = path end
        end })
      assert.same({ dir .. "/bush.gif", 6, 64, 48 }, { out, n, w, h })
      local p = probe(dir .. "/bush.gif")
      assert.same({ "gif", 6, 64, 48 }, { p.codec_name, p.nb_read_frames, p.width, p.height })
      assert.equal(6, #pictures)
      for _, f in ipairs(pictures) do assert.is_nil(io.open(f)) end
      assert.is_nil(io.open((pictures[1]:match("^(.*)/"))))      -- the folder too
      assert.same({ "bush.gif" }, ls(dir))                         -- no partial file left
    end)

    it("writes an H.264 video with even sizes, every K-th step and the last held", function()
      if not ffmpeg() then return end
      local _, n, w, h = lsys.animate(bush(), { out = dir .. "/bush.mp4", width = 63,
        height = 47, every = 2, fps = 2, hold = 1 })
      assert.same({ 4, 64, 48 }, { n, w, h })        -- steps 0 2 4 5; sizes made even
      local p = probe(dir .. "/bush.mp4")
      -- the 4 frames and the last one held 1 s at 2 frames a second
      assert.same({ "h264", "yuv420p", 6, 64, 48 },
                  { p.codec_name, p.pix_fmt, p.nb_read_frames, p.width, p.height })
    end)

    it("lsys animate writes OUT through a name the shell must not read", function()
      if not ffmpeg() then return end
      H.write(dir .. "/bush.lua", MODEL)
      local name = "it's $(touch pwned) `touch pwned2`.gif"
      local out, code = sh("cd " .. dir .. " && " .. ABSBIN ..
        " animate bush.lua --size 32x32 --every 5 --fps 10 -o \"" .. name:gsub("[$`]", "\\%0")
        .. "\"")
      assert.equal(0, code, out)
      assert.truthy(out:find("wrote " .. name .. " (2 frames, 32x32, 10 a second) in ", 1, true),
                    out)
      assert.same({ "bush.lua", name }, ls(dir))
      assert.equal(2, probe(dir .. "/" .. name).nb_read_frames)
    end)

    it("lsys animate names the video after the model by default, with progress lines",
    function()
      if not ffmpeg() then return end
      H.write(dir .. "/bush.lua", MODEL)
      local out, code = sh("cd " .. dir .. " && " .. ABSBIN ..
        " animate bush.lua --size 32x32 --steps 2 --progress")
      assert.equal(0, code, out)
      assert.truthy(out:find("frame 3/3: step 2 (", 1, true), out)
      assert.truthy(out:find("encoding bush.mp4 with ffmpeg\n", 1, true), out)
      assert.truthy(out:find("wrote bush.mp4 (3 frames, 32x32, 4 a second) in ", 1, true), out)
      assert.equal(3, probe(dir .. "/bush.mp4").nb_read_frames)
    end)

    it("says ffmpeg is needed, how to install it and what works without it", function()
      H.write(dir .. "/bush.lua", MODEL)
      -- no ffmpeg on PATH (the lsys program by its absolute path)
      local out, code = sh("cd " .. dir .. " && PATH=/nonexistent " .. ABSBIN ..
        " animate bush.lua -o bush.mp4")
      assert.equal(1, code, out)
      assert.equal("lsys: ffmpeg is needed to write bush.mp4 and was not found on PATH: install "
        .. "it (Debian, Ubuntu: apt-get install ffmpeg), or write the pictures with "
        .. "lsys.frames (`lsys render MODEL --frames DIR`), which needs no ffmpeg\n", out)
      assert.same({ "bush.lua" }, ls(dir))
      assert.error_contains(function ()
        lsys.animate(bush(), { out = dir .. "/x.gif", ffmpeg = dir .. "/none/ffmpeg" })
      end, "lsys.animate: " .. dir .. "/none/ffmpeg is needed to write " .. dir .. "/x.gif and "
        .. "there is no " .. dir .. "/none/ffmpeg: install it")
    end)

    it("reports ffmpeg's last lines when it fails, and leaves no file behind", function()
      local fake = dir .. "/fake-ffmpeg"
      H.write(fake, "#!/bin/sh\nfor i in 1 2 3 4 5 6 7; do echo \"line $i\" >&2; done\n" ..
        "echo \"Unknown encoder 'libx264'\" >&2\nexit 1\n")
      os.execute("chmod +x '" .. fake .. "'")
      assert.error_contains(function ()
        lsys.animate(bush(), { out = dir .. "/x.mp4", ffmpeg = fake, width = 16, height = 16 })
      end, "lsys.animate: " .. fake .. " failed (exit 1) writing '" .. dir .. "/x.mp4':\n" ..
        "line 4\nline 5\nline 6\nline 7\nUnknown encoder 'libx264'")
      assert.same({ "fake-ffmpeg" }, ls(dir))
    end)

    it("says what is wrong with an option or the output", function()
      local m = bush()
      local function err (opts, msg) raises(lsys.animate, m, opts, msg) end
      err({ out = dir .. "/x.avi" }, "lsys.animate: '" .. dir .. "/x.avi': the output must be "
        .. "an .mp4 video or a .gif animation (for PNG pictures use lsys.frames)")
      err({}, "lsys.animate: option 'out' (an .mp4 or .gif file) is required")
      err({ out = "x.gif", fps = 0 }, "lsys.animate: option 'fps' must be in (0, 1000], got 0")
      err({ out = "x.gif", hold = -1 }, "option 'hold' must be 0 to 3600 seconds, got -1")
      err({ out = "x.gif", every = 0 }, "lsys.animate: option 'every' must be >= 1, got 0")
      err({ out = "x.gif", dir = dir }, "lsys.animate: unknown option 'dir'")
      err({ out = "x.gif", transparent = true }, "lsys.animate: unknown option 'transparent'")
      err({ out = dir .. "/no/x.gif", ffmpeg = "sh" },   -- (found even where ffmpeg is not)
        "lsys.animate: cannot write '" .. dir .. "/no/x.gif': "
        .. "No such file or directory")
      H.write(dir .. "/bush.lua", MODEL)
      local function animate (args, msg) usage("animate", dir .. "/bush.lua " .. args, msg) end
      animate("-o " .. dir .. "/x.avi", "the output must be an .mp4 video or a .gif animation, "
        .. "got '" .. dir .. "/x.avi' (for PNG pictures: lsys render MODEL --frames DIR)")
      animate("-o x.gif --every 0", "--every expects a whole number >= 1, got '0'")
      animate("-o x.gif --fps 0", "--fps expects frames a second in (0, 1000], got '0'")
      animate("-o x.gif --hold x", "--hold expects seconds from 0 to 3600, got 'x'")
      animate("-o x.gif --size 0x3", "--size expects WxH (1 to 16384 each), got '0x3'")
      animate("-o x.gif --frames d", "--frames goes with --orbit (a turntable); for a picture "
        .. "of each step: lsys render MODEL --frames DIR")
      assert.same({ "bush.lua" }, ls(dir))
    end)
  end)
end)

describe("#gl the viewer's S key while animating", function()
  local D = require "tests.display"
  local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
  teardown(function() D.stop() end)

  it("saves every step through the window's camera to MODEL-frames/", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return end
    local dir = H.tmpdir()
    H.write(dir .. "/bush.lua", (MODEL:gsub("steps = 5", "steps = 3")))
    os.execute("cd " .. q(dir) .. " && (" .. D.env .. "timeout " .. 60 * SLOW .. " " .. ABSBIN
      .. " view bush.lua --size 300x240 --rate 1 >out.txt 2>err.txt; echo $? > rc.txt) &")
    local win = D.env .. "timeout " .. 30 * SLOW ..
      " xdotool search --sync --name 'lsys: bush.lua' windowfocus --sync %1 key "
    local function wait_for (file, text) return D.wait_for(dir .. "/" .. file, text, 10 * SLOW) end
    -- space: animate from step 0 (one step a second); S then saves the steps, not one picture
    assert.truthy(os.execute(win .. "space s >/dev/null 2>&1"))
    local err = wait_for("err.txt", "saved")
    assert.truthy(err:find("lsys: saved 4 pictures of steps 0 to 3 to bush-frames/ (one " ..
      "camera)\n", 1, true), err)
    assert.same({ "step-0000.png", "step-0001.png", "step-0002.png", "step-0003.png" },
                ls(dir .. "/bush-frames"))
    assert.is_nil(H.read(dir .. "/lsys-001.png"))       -- no screenshot
    local ink = {}
    for i, f in ipairs(ls(dir .. "/bush-frames")) do
      ink[i] = H.ink(dir .. "/bush-frames/" .. f)
      assert.same({ 300, 240 }, { ink[i].w, ink[i].h })   -- the scene, no status line
    end
    -- one camera, fitted to the last step (shown first): the plant grows in place
    for i = 2, 4 do assert.is_true(ink[i].n > ink[i - 1].n, ink[i].n .. " " .. ink[i - 1].n) end
    assert.is_true(ink[2].n < ink[4].n / 4, ink[2].n .. " vs " .. ink[4].n)
    assert.is_true(math.abs(ink[2].box[4] - ink[4].box[4]) <= 1)
    assert.is_true(ink[4].box[4] - ink[4].box[2] > 150)
    os.execute(win .. "Escape >/dev/null 2>&1")   -- (xdotool may complain: the window goes)
    assert.equal("0\n", wait_for("rc.txt", "\n"))
    H.rmdir(dir)
  end)
end)
