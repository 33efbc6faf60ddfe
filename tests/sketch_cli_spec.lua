-- `lsys sketch` on the command line: usage errors (exit 2, the command's
-- message), the help, and the plot, model and render subcommands on an example sketch.
local H = require "tests.helper"
local core = require "lsys.core"

local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
local SKETCH = "examples/sketch/fig8_herb.json"

local run = H.sh

local tmpdir = H.tmpdir

describe("lsys sketch", function()
  it("explains itself with --help and lsys help sketch", function()
    local out, code = run(BIN .. " help sketch")
    assert.equal(0, code)
    assert.truthy(out:find("usage: lsys sketch [FILE] [--size WxH] [--nodes N] [--phyllotaxis P]",
                           1, true), out)
    local out2 = run(BIN .. " sketch --help")
    assert.equal(out, out2)
    local list = run(BIN .. " --help")
    assert.truthy(list:find("lsys sketch [FILE] [OPTS]", 1, true), list)
  end)

  it("reports usage errors with exit status 2", function()
    local P = "lsys: sketch: "
    local cases = {
      { "sketch plot", P .. "plot: a sketch FILE is required" },
      { "sketch model a.json b.json", P .. "unexpected argument 'b.json'" },
      { "sketch plot a.json -o a.txt", P .. "plot: the output must be a .png file, got 'a.txt'" },
      { "sketch model a.json -o a.png",
        P .. "model: the output must be a .lua file, got 'a.png'" },
      { "sketch render a.json --nodes 0",
        P .. "--nodes expects a whole number from 1 to 10000, got '0'" },
      { "sketch render a.json --phyllotaxis spiral",
        P .. "--phyllotaxis expects distichous, decussate or fibonacci, got 'spiral'" },
      { "sketch render a.json --size 10", P .. "--size expects WxH (1 to 16384 each), got '10'" },
      { "sketch x.json -o y.png", P .. "-o applies to plot, model and render" },
      { "sketch a.json b.json", P .. "unexpected argument 'b.json' (one FILE at most)" },
      { "sketch --bogus", P .. "unknown option '--bogus'" },
      { "sketch render a.json --cpfg", P .. "render: --cpfg applies to model" },
      { "sketch a.json --cpfg", P .. "--cpfg applies to model" },
      { "sketch model a.json --cpfg -o a.lua",
        P .. "model: the output must be a .l file, got 'a.lua'" },
      { "sketch plot a.json --organ ovate",
        P .. "plot: --organ applies to the window, model and render" },
      { "sketch render a.json --organ oval",
        P .. "--organ expects a leaf shape (ovate, lanceolate, elliptic, obovate, linear, " ..
        "cordate) or an organ file (.json), got 'oval'" },
      { "sketch a.json --organ leaf.s",
        P .. "--organ expects a leaf shape (ovate, lanceolate, elliptic, obovate, linear, " ..
        "cordate) or an organ file (.json), got 'leaf.s'" },
    }
    for _, c in ipairs(cases) do
      local out, code = run(BIN .. " " .. c[1])
      assert.equal(2, code, c[1] .. ": " .. out)
      assert.equal(c[2] .. "\nRun 'lsys sketch --help' for its options.\n", out)
    end
  end)

  it("names the file of a sketch that cannot be read (exit 1)", function()
    local out, code = run(BIN .. " sketch render nosuch.json -o /tmp/never.png")
    assert.equal(1, code)
    assert.equal("lsys: cannot open 'nosuch.json': No such file or directory\n", out)
    local dir = tmpdir()
    local f = io.open(dir .. "/bad.json", "w")
    f:write('{"width": 100, "height": 100, "strokes": [{"role": "boundary_left", ' ..
            '"points": [[0, 0], [0, 50]]}]}')
    f:close()
    out, code = run(BIN .. " sketch model " .. dir .. "/bad.json -o " .. dir .. "/m.lua")
    assert.equal(1, code)
    assert.equal("lsys: " .. dir .. "/bad.json: no stem stroke\n", out)
    os.execute("rm -rf " .. dir)
  end)

  it("writes the model, the plots and the picture of a sketch", function()
    local dir = tmpdir()
    local out, code = run(BIN .. " sketch model " .. SKETCH .. " -o " .. dir .. "/herb.lua " ..
                          "--phyllotaxis fibonacci --nodes 2")
    assert.equal(0, code, out)
    assert.equal("wrote " .. dir .. "/herb.lua\n", out)
    local text = assert(io.open(dir .. "/herb.lua")):read("a")
    assert.truthy(text:find("fibonacci", 1, true))
    assert.truthy(text:find("2 nodes per layer", 1, true), text:sub(1, 600))
    -- the model file runs and makes a plant
    local m = dofile(dir .. "/herb.lua")
    assert.is_true(#m:derive() > 10)
    out, code = run(BIN .. " sketch render " .. SKETCH .. " -o " .. dir ..
                    "/herb.png --size 300x200")
    assert.equal(0, code, out)
    assert.truthy(out:find("^wrote " .. dir .. "/herb%.png %(300x200, %d+ triangles, 0 lines%)\n$"),
                  out)
    local _, w, h = core.png_read(dir .. "/herb.png")
    assert.equal(300, w)
    assert.equal(200, h)
    out, code = run(BIN .. " sketch plot " .. SKETCH .. " -o " .. dir .. "/f.png --size 600x400")
    assert.equal(0, code, out)
    assert.equal("wrote " .. dir .. "/f.png\n", out)
    local _, pw, ph = core.png_read(dir .. "/f.png")
    assert.equal(600, pw)
    assert.equal(400, ph)
    -- default names: in the current directory, after the sketch
    local here = io.popen("pwd"):read("l")      -- not $PWD: ctest starts busted elsewhere
    out, code = run("cd " .. dir .. " && " .. (BIN:sub(1, 1) == "/" and BIN or here .. "/" ..
                    BIN) .. " sketch model " .. here .. "/" .. SKETCH)
    assert.equal(0, code, out)
    assert.equal("wrote fig8_herb.lua\n", out)
    os.execute("rm -rf " .. dir)
  end)

  it("draws the organ given: a leaf shape or an organ file", function()
    local dir = tmpdir()
    local function tris (organ)
      local out, code = run(BIN .. " sketch render " .. SKETCH .. " -o " .. dir .. "/p.png " ..
                            "--size 64x64" .. (organ and " --organ " .. organ or ""))
      assert.equal(0, code, out)
      return tonumber(out:match("(%d+) triangles"))
    end
    -- 32 organs: the default leaf (a polygon, 2 triangles), a lanceolate leaf of 12 x 24
    -- lines, the file's 2 x 4 patches of 2 x 2 lines each
    assert.same({ 752, 752 + 32 * (12 * 24 * 2 - 2), 752 + 32 * (4 * 8 * 2 - 2) },
                { tris(), tris("lanceolate"), tris("examples/sketch/organ_leaf.json") })
    -- the model file takes the organ with it
    local out, code = run(BIN .. " sketch model " .. SKETCH .. " -o " .. dir .. "/h.lua " ..
                          "--organ examples/sketch/organ_leaf.json")
    assert.equal(0, code, out)
    assert.equal(require("lsys.sketch.organ").load("examples/sketch/organ_leaf.json"):text(),
                 H.read(dir .. "/h.organ.s"))
    out, code = run(BIN .. " sketch render " .. SKETCH .. " --organ " .. dir .. "/none.json")
    assert.equal(1, code)
    assert.equal("lsys: organ " .. dir .. "/none.json: cannot open '" .. dir .. "/none.json': " ..
                 "No such file or directory\n", out)
    os.execute("rm -rf " .. dir)
  end)

  it("writes the plant for cpfg and L-studio with --cpfg", function()
    local dir = tmpdir()
    local out, code = run(BIN .. " sketch model " .. SKETCH .. " --cpfg -o " .. dir .. "/herb.l")
    assert.equal(0, code, out)
    local lines = {}
    for _, f in ipairs { "angle_left.func", "angle_right.func", "internode.func", "l", "map",
                         "size_left.func", "size_right.func", "stem_shape.func", "v" } do
      lines[#lines + 1] = "wrote " .. dir .. "/herb." .. f
    end
    lines[#lines + 1] = "cpfg -m herb.map herb.l herb.v (in " .. dir .. ") derives the plant " ..
                        "as lsys does"
    assert.equal(table.concat(lines, "\n") .. "\n", out)
    -- lsys runs them as the sketch's model
    local a = run(BIN .. " derive " .. dir .. "/herb.l " .. dir .. "/herb.v --stats")
    assert.equal(#require("lsys.sketch").load(SKETCH):model():derive(),
                 tonumber(a:match("\nmodules (%d+)\n")), a)
    -- the default name: after the sketch, in the current folder
    local here = io.popen("pwd"):read("l")
    out, code = run("cd " .. dir .. " && " .. (BIN:sub(1, 1) == "/" and BIN or here .. "/" ..
                    BIN) .. " sketch model --cpfg " .. here .. "/" .. SKETCH)
    assert.equal(0, code, out)
    assert.truthy(out:find("\nwrote fig8_herb.l\n", 1, true), out)
    os.execute("rm -rf " .. dir)
  end)
end)
