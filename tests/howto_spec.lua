-- The manual's "How do I …" section (docs/manual.md, end of §1) runs as written: its first
-- block is the model file plant.lua, each other block a script run by the lsys program in a
-- scratch folder next to it, the last one a spec run by `lsys test`; what each prints and
-- writes is checked here. Tagged #gl: the pictures go through OSMesa.
local H = require "tests.helper"
local core = require "lsys.core"

-- The lua blocks of the section, in order.
local function blocks ()
  local text = H.read("docs/manual.md")
  local from = assert(text:find("\n### How do I", 1, true), "no 'How do I' section")
  local to = assert(text:find("\n## 2%. ", from), "the section does not end")
  local l = {}
  for code in text:sub(from, to):gmatch("```lua\n(.-)```") do l[#l + 1] = code end
  return l
end

-- How many pixels of a PNG are mostly blue, and how many mostly orange.
local function hues (path)
  local px, w, h = core.png_read(path)
  local blue, orange = 0, 0
  for i = 0, w * h - 1 do
    local r, g, b = px:byte(4 * i + 1, 4 * i + 3)
    if b > r + 60 and b > g + 30 then blue = blue + 1 end
    if r > b + 60 and r > g + 20 then orange = orange + 1 end
  end
  return blue, orange
end

describe("#gl the manual's How do I section", function()
  local dir, code
  setup(function()
    code = blocks()
    dir = H.tmpdir()
    H.write(dir .. "/plant.lua", code[1])
  end)
  teardown(function() H.rmdir(dir) end)

  -- Runs block k as a script in the scratch folder: its output and exit status.
  local function run (k)
    H.write(dir .. "/howto" .. k .. ".lua", code[k])
    return H.sh("cd " .. dir .. " && " .. H.ABSBIN .. " howto" .. k .. ".lua")
  end

  it("has the model and the six answers", function()
    assert.equal(7, #code)
    assert.matches("^%-%- plant%.lua", code[1])
  end)

  it("changes the leaf colour, for one picture and for all", function()
    local out, status = run(2)
    assert.equal(0, status, out)
    local blue, orange = hues(dir .. "/blue-leaves.png")
    assert.is_true(blue > 500 and orange == 0, blue .. " blue, " .. orange .. " orange")
    blue, orange = hues(dir .. "/orange-leaves.png")
    assert.is_true(orange > 500 and blue == 0, blue .. " blue, " .. orange .. " orange")
  end)

  it("sets the camera", function()
    local out, status = run(3)
    assert.equal(0, status, out)
    local side, close = H.ink(dir .. "/side.png"), H.ink(dir .. "/close.png")
    H.write(dir .. "/plain.lua", "require('lsys').render(dofile('plant.lua'), "
            .. "{ out = 'plain.png' })\n")
    assert.equal(0, select(2, H.sh("cd " .. dir .. " && " .. H.ABSBIN .. " plain.lua")))
    local plain = H.ink(dir .. "/plain.png")
    assert.is_true(close.n > 2 * plain.n, close.n .. " vs " .. plain.n)   -- zoom 2
    assert.is_true(side.n > 0 and side.n ~= plain.n)                      -- another view
  end)

  it("gives the position of module i", function()
    local out, status = run(4)
    assert.equal(0, status, out)
    assert.equal("5\tL(0.6)\tat 0.000 1.100 0.000 heading 0.00 0.64 -0.77\n"
                 .. "11\tL(0.5)\tat 0.000 2.100 0.000 heading 0.52 0.64 0.56\n", out)
  end)

  it("makes a growth animation", function()
    if not os.execute("command -v ffmpeg >/dev/null 2>&1") then
      pending("ffmpeg is not installed (./setup.sh installs it)")
      return
    end
    local out, status = run(5)
    assert.equal(0, status, out)
    assert.equal("growth.gif\t9\n", out)
    assert.equal("GIF8", H.read(dir .. "/growth.gif"):sub(1, 4))
  end)

  it("saves a picture series", function()
    local out, status = run(6)
    assert.equal(0, status, out)
    assert.equal("5\tframes/step-0000.png\t0 2 4 6 8\n", out)
    -- step 0 draws nothing (the axiom is !(0.1) A); step 2 is small in step 8's frame
    local s0, s2 = H.ink(dir .. "/frames/step-0000.png"), H.ink(dir .. "/frames/step-0002.png")
    local s8 = H.ink(dir .. "/frames/step-0008.png")
    assert.equal(0, s0.n)
    assert.is_true(s2.n > 0 and s2.n < s8.n / 4, s2.n .. " vs " .. s8.n)
    assert.is_true(s2.box[4] >= s8.box[4] - 1)      -- both stand on the same ground
  end)

  it("tests the model with lsys test", function()
    assert.equal(0, os.execute("mkdir -p " .. dir .. "/spec") and 0)
    H.write(dir .. "/spec/plant_spec.lua", code[7])
    local out, status = H.sh("cd " .. dir .. " && " .. H.ABSBIN .. " test -o plainTerminal")
    assert.equal(0, status, out)
    assert.matches("2 successes / 0 failures / 0 errors", out, 1, true)
  end)
end)
