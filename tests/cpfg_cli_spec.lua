-- The lsys program on cpfg models (docs/cpfg.md, "The command line"): derive, render,
-- export and view take a .l file (with its .v after it) or a vlab object folder, and
-- `lsys import` writes the lsys model file that derives the same string.
-- ctest: slow (runs the program on cpfg models and vlab objects)
local H = require "tests.helper"
local core = require "lsys.core"

local D = "tests/data/cpfg/"
local PLANT = D .. "cli/plant.l"
-- tests/data/cpfg/cli/plant.l as lsys derives it (worked out by hand: F grows by its
-- loop's 2, B makes L(w[1]*x), X reads total after two EndEach blocks)
local PLANT_STRING = "F(5.5)[+(30)L(2)]F(5)[+(30)L(4)]X(2)"

local function lsys (args) return H.sh(H.BIN .. " " .. args) end

-- A cpfg colour map: 256 colours of 3 bytes, colour i grey level i.
local function colormap (path)
  local t = {}
  for i = 0, 255 do t[#t + 1] = string.char(i, i, i) end
  H.write(path, table.concat(t))
end

describe("lsys derive on a cpfg model", function ()
  it("derives a .l file for its derivation length", function ()
    local out, code = lsys("derive " .. PLANT)
    assert.equal(0, code, out)
    assert.equal(PLANT_STRING .. "\n", out)
  end)

  it("takes the view file after the .l file, and a vlab object folder", function ()
    local out, code = lsys("derive " .. D .. "object/plant.l " .. D .. "object/plant.v")
    assert.equal(0, code, out)
    assert.equal("FFFFFFFFFFFFFFX\n", out)
    out, code = lsys("derive " .. D .. "object")
    assert.equal(0, code, out)
    assert.equal("FFFFFFFFFFFFFFX\n", out)
  end)

  it("applies --steps, and --define as cpp's -D", function ()
    local koch = "F+FF-FF-F-F+F+FF-F-FF+F+FF+F-F"
    local out, code = lsys("derive " .. D .. "koch.l --steps 1")
    assert.equal(0, code, out)
    assert.equal(string.rep(koch, 4, "-") .. "\n", out)
    -- plant.h defines STEPS only when it is not defined yet
    out, code = lsys("derive " .. PLANT .. " --define STEPS=1")
    assert.equal(0, code, out)
    assert.equal("F(1.5)[+(30)B(1)]A(2)\n", out)
    out, code = lsys("derive " .. D .. "macros.l --define SLOW")
    assert.equal(1, code)
    assert.equal("lsys: " .. D .. "macros.l:11: #error never\n", out)
  end)

  it("refuses --set with a name the model has no variable of (a #define is none)", function ()
    local out, code = lsys("derive " .. PLANT .. " --set RATE=3")
    assert.equal(2, code, out)
    assert.truthy(out:find("lsys: derive: --set RATE: the model has no variable RATE (the "
      .. "model's variables: ", 1, true), out)
    assert.truthy(out:find("); the preprocessor replaces a #define's name by its value "
      .. "(--define NAME=VALUE sets one)", 1, true), out)
    assert.falsy(out:find(PLANT_STRING, 1, true), out)
    -- the translator's helpers and the derivation length's Q and Z are not the model's
    -- variables: neither listed nor set
    assert.falsy(out:find("_aget", 1, true) or out:find(" Q,", 1, true), out)
    for _, name in ipairs { "_try", "Q", "Z" } do
      out, code = lsys("derive " .. PLANT .. " --set " .. name .. "=3")
      assert.equal(2, code, out)
      assert.truthy(out:find("--set " .. name .. ": the model has no variable " .. name, 1, true),
                    out)
    end
  end)

  it("names the file and line of an error, and a missing file", function ()
    local out, code = lsys("derive " .. D .. "errors_syntax.l")
    assert.equal(1, code)
    assert.equal("lsys: " .. D .. "errors_syntax.l:5: '->' is not a production arrow in cpfg; "
                 .. "write '-->'\n", out)
    out, code = lsys("derive " .. D .. "missing.l")
    assert.equal(1, code)
    assert.equal("lsys: " .. D .. "missing.l: No such file or directory\n", out)
    out, code = lsys("derive " .. D .. "inc")
    assert.equal(1, code)
    assert.equal("lsys: " .. D .. "inc is a folder without a specifications file (a vlab "
                 .. "object has one)\n", out)
  end)

  it("refuses a view file or cpfg options with a Lua model (usage errors)", function ()
    local out, code = lsys("derive examples/abop/fig1_24a.lua plant.v")
    assert.equal(2, code)
    assert.truthy(out:find("lsys: derive: a view file (plant.v) goes with a cpfg MODEL (.l), "
                           .. "not with a Lua model", 1, true), out)
    out, code = lsys("derive examples/abop/fig1_24a.lua --map x.map")
    assert.equal(2, code)
    assert.truthy(out:find("--map, --mat and --define apply to a cpfg MODEL", 1, true), out)
    out, code = lsys("derive " .. PLANT .. " plant.txt")
    assert.equal(2, code)
    assert.truthy(out:find("unexpected argument 'plant.txt' (after MODEL.l comes its view "
                           .. "file, VIEW.v)", 1, true), out)
    out, code = lsys("derive " .. PLANT .. " --map a.map --mat b.mat")
    assert.equal(2, code)
    assert.truthy(out:find("give --map or --mat, not both", 1, true), out)
  end)

  it("derives and imports a model with ?E only with --environment none", function ()
    local out, code = lsys("derive " .. D .. "envq.l")
    assert.equal(1, code)
    assert.truthy(out:find("envq.l:5: ?E (a query of the environment) needs an "
                           .. "environment", 1, true), out)
    out, code = lsys("derive " .. D .. "envq.l --environment none")
    assert.equal(0, code, out)
    assert.equal("A(3)?E(7,6)\n", out)                                  -- cpfg
    out, code = lsys("derive " .. D .. "envq.l --environment all")
    assert.equal(2, code)
    assert.truthy(out:find("--environment must be none", 1, true), out)
    local dir = H.tmpdir()
    out, code = lsys("import " .. D .. "envq.l -o " .. dir .. "/e.lua --environment none")
    assert.equal(0, code, out)
    out, code = lsys("derive " .. dir .. "/e.lua")
    H.rmdir(dir)
    assert.equal(0, code, out)
    assert.equal("A(3)?E(7,6)\n", out)
  end)
end)

describe("lsys render and export on a cpfg model", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("renders a .l file with its view file and colour map to a PNG file", function ()
    if not core.has_render then pending("built without OSMesa") return end
    H.write(dir .. "/plant.l", H.read(PLANT))
    H.write(dir .. "/plant.h", H.read(D .. "cli/plant.h"))
    H.write(dir .. "/plant.v", H.read(D .. "cli/plant.v"))
    colormap(dir .. "/plant.map")
    local out, code = lsys(("render %s/plant.l %s/plant.v --map plant.map -o %s/p.png "
                            .. "--size 64x48"):format(dir, dir, dir))
    assert.equal(0, code, out)
    assert.equal("wrote " .. dir .. "/p.png (64x48, 0 triangles, 2 lines)\n", out)
    assert.equal("\137PNG", H.read(dir .. "/p.png"):sub(1, 4))
  end)

  it("finds --map from the shell's folder first, then from the .l file's", function ()
    assert(os.execute("mkdir " .. dir .. "/sub"))
    for _, f in ipairs { "plant.l", "plant.h", "plant.v" } do
      H.write(dir .. "/sub/" .. f, H.read(D .. "cli/" .. f))
    end
    local function map (path, r, g, b)       -- colour 2, the plant's, pure; the rest black
      H.write(path, ("\0"):rep(6) .. string.char(r, g, b) .. ("\0"):rep(768 - 9))
    end
    local function kd (m)                    -- the colour the .mtl gives colour 2
      local out, code = H.sh(("cd %s && %s export sub/plant.l sub/plant.v --map %s -o x.obj")
                             :format(dir, H.ABSBIN, m))
      if code ~= 0 then return out end
      return H.read(dir .. "/x.mtl"):match("newmtl m2\n[^\n]*\nKd ([^\n]*)")
    end
    map(dir .. "/sub/c.map", 0, 0, 255)
    assert.equal("0 0 1", kd("sub/c.map"))   -- the shell's path (was looked for in sub/sub/)
    assert.equal("0 0 1", kd("c.map"))       -- the .l file's folder
    map(dir .. "/c.map", 255, 0, 0)
    assert.equal("1 0 0", kd("c.map"))       -- both: the shell's first
    assert.equal("lsys: --map no.map: no such file in the current folder nor in the model's "
                 .. "(sub)\n", kd("no.map"))
  end)

  it("exports a vlab object to glTF", function ()
    local out, code = lsys("export " .. D .. "object -o " .. dir .. "/o.glb")
    assert.equal(0, code, out)
    assert.equal("wrote " .. dir .. "/o.glb (0 vertices, 0 triangles, 14 lines)\n", out)
    assert.equal("glTF", H.read(dir .. "/o.glb"):sub(1, 4))
  end)
end)

describe("lsys import", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("writes a model file that derives the string of every test .l file that loads",
     function ()
    local p = io.popen("ls " .. D .. "*.l " .. D .. "*/*.l")
    local n = 0
    for l in p:lines() do
      local want, code = lsys("derive " .. l)
      want = want:gsub("Lua warning: [^\n]*\n", "")     -- the loader's warnings (depth.l)
      if code == 0 then
        local out = dir .. "/" .. l:match("([^/]*)%.l$") .. ".lua"
        local msg, icode = lsys("import " .. l .. " -o " .. out)
        assert.equal(0, icode, msg)
        assert.equal("wrote " .. out .. "\n", (msg:gsub("Lua warning: [^\n]*\n", "")))
        local got, dcode = lsys("derive " .. out)
        assert.equal(0, dcode, got)
        assert.equal(want, got, l)
        n = n + 1
      end
    end
    p:close()
    assert.is_true(n >= 10, n .. " files")
  end)

  it("keeps the #defines of numbers as env entries that the rules read by name", function ()
    local out = dir .. "/plant.lua"
    assert.equal(0, select(2, lsys("import " .. PLANT .. " -o " .. out)))
    local text = H.read(out)
    assert.truthy(text:find("\n  RATE = 1.5,  -- growth per step\n  LIMIT = 3.0,\n", 1, true),
                  text)
    assert.truthy(text:find('"A(x) : x < LIMIT --> F(x * RATE)[+(ANGLE)B(x)]A(x + 1.0)",',
                            1, true), text)
    local got, code = lsys("derive " .. out .. " --set RATE=2")
    assert.equal(0, code, got)
    assert.equal("F(6)[+(30)L(2)]F(6)[+(30)L(4)]X(2)\n", got)
  end)

  it("writes statement blocks as Lua functions and the hooks that reset cpfg's variables",
     function ()
    local out = dir .. "/plant.lua"
    assert.equal(0, select(2, lsys("import " .. PLANT .. " -o " .. out)))
    local text = H.read(out)
    for _, s in ipairs {
      '    { "F(l)", function (l)\n',
      "      L1.n = 0.0\n",
      '      return lsys.produce("F(?)", L1.s',
      "  end_each = function ()\n    env.total = env.total + 1.0\n  end,\n",
      '  env.w = array("w", { 3 }, { 1.0, 2.0, 3.0 })\n',
    } do
      assert.truthy(text:find(s, 1, true), s)
    end
    assert.truthy(text:find("\n      while %(?L1%.n[^\n]* < 2%.0 do\n"), text)
  end)

  it("writes the view, its files found from where the model file is", function ()
    local src = dir .. "/cpfg"
    os.execute("mkdir -p " .. src .. " " .. dir .. "/lua")
    for _, f in ipairs { "plant.l", "plant.h", "plant.v" } do
      H.write(src .. "/" .. f, H.read(D .. "cli/" .. f))
    end
    colormap(src .. "/plant.map")
    local out = dir .. "/lua/plant.lua"
    local msg, code = lsys(("import %s/plant.l %s/plant.v --map plant.map -o %s")
                           :format(src, src, out))
    assert.equal(0, code, msg)
    local text = H.read(out)
    assert.truthy(text:find('    dir = lsys.here() .. "/../cpfg",\n', 1, true), text)
    assert.truthy(text:find('    palette = "plant.map",\n', 1, true), text)
    assert.truthy(text:find("    angle = 30,\n", 1, true), text)
    if core.has_render then
      -- the same picture: same view, same colours
      local _, c1 = lsys(("render %s/plant.l %s/plant.v --map plant.map -o %s/a.png "
                          .. "--size 64x48"):format(src, src, dir))
      local _, c2 = lsys(("render %s -o %s/b.png --size 64x48"):format(out, dir))
      assert.equal(0, c1)
      assert.equal(0, c2)
      assert.equal(H.read(dir .. "/a.png"), H.read(dir .. "/b.png"))
    end
  end)

  it("calls the view's positional functions from a statement block through the model",
     function ()
    local l, v = D .. "cli/func/bump.l", D .. "cli/func/bump.v"
    local want, code = lsys("derive " .. l .. " " .. v)
    assert.equal(0, code, want)
    local out = dir .. "/bump.lua"
    local msg, icode = lsys("import " .. l .. " " .. v .. " -o " .. out)
    assert.equal(0, icode, msg)
    assert.equal(want, (lsys("derive " .. out)))
    local text = H.read(out)
    assert.truthy(text:find("local function func (id, x) return m._func(id, x) end", 1, true))
    assert.truthy(text:find("      L1.y = func(1.0, x)\n", 1, true), text)
  end)

  it("imports a vlab object folder", function ()
    local out = dir .. "/object.lua"
    local msg, code = lsys("import " .. D .. "object -o " .. out)
    assert.equal(0, code, msg)
    assert.equal("FFFFFFFFFFFFFFX\n", (lsys("derive " .. out)))
    assert.truthy(H.read(out):find('    "leaf(n) : n > 0.0 --> Fleaf(n - 1.0)",', 1, true),
                  H.read(out))
  end)

  it("writes only the file -o names, whole", function ()
    local bin = H.ABSBIN
    local l = H.absolute(PLANT)
    local out, code = H.sh("cd " .. dir .. " && " .. bin .. " import " .. l)
    assert.equal(2, code)
    assert.equal("lsys: import: -o OUT.lua is required: the lsys model file to write\n"
                 .. "Run 'lsys import --help' for its options.\n", out)
    assert.equal("", (H.sh("ls -A " .. dir)))
    out, code = H.sh("cd " .. dir .. " && " .. bin .. " import " .. l .. " -o p.lua")
    assert.equal(0, code, out)
    assert.equal("p.lua\n", (H.sh("ls -A " .. dir)))
  end)

  it("runs no text of the .l file (a carriage return ended its comment)",
     function ()
    local marker = dir .. "/P"
    local l = dir .. "/evil\ros.exit(3) --\r.l"
    H.write(l, "/* x\ros.execute(\"touch " .. marker .. "\") --\r */\n#define N 2 /* n\r"
            .. "os.exit(3) */\nLsystem: 1\nderivation length: 1\nAxiom: A(N)\n"
            .. "A(x) --> B(x)\nendlsystem\n")
    local out = dir .. "/evil.lua"
    local msg, code = lsys("import " .. require("lsys.util.text").shq(l) .. " -o " .. out)
    assert.equal(0, code, msg)
    assert.is_nil(H.read(marker))
    local text = H.read(out)
    assert.truthy(text:find("\n-- x\\13os.execute(\"touch " .. marker .. "\") --\n", 1, true),
                  text)
    assert.truthy(text:find("the cpfg model evil\\13os.exit(3) --\\13.l,", 1, true), text)
    assert.is_nil(text:find("\r", 1, true))
    local got, dcode = lsys("derive " .. out)
    assert.equal(0, dcode, got)
    assert.equal("B(2)\n", got)
    assert.is_nil(H.read(marker))
  end)

  it("names the file and line of an error, and refuses what is not a cpfg model", function ()
    local out, code = lsys("import " .. D .. "errors_syntax.l -o " .. dir .. "/e.lua")
    assert.equal(1, code)
    assert.equal("lsys: " .. D .. "errors_syntax.l:5: '->' is not a production arrow in cpfg; "
                 .. "write '-->'\n", out)
    assert.is_nil(H.read(dir .. "/e.lua"))
    out, code = lsys("import examples/default.lua -o " .. dir .. "/d.lua")
    assert.equal(2, code)
    assert.truthy(out:find("'examples/default.lua' is not a cpfg model: MODEL is a .l file or "
                           .. "a vlab object folder", 1, true), out)
    out, code = lsys("import " .. PLANT .. " -o " .. dir .. "/p.txt")
    assert.equal(2, code)
    assert.truthy(out:find("the output must be a .lua file, got '" .. dir .. "/p.txt'", 1,
                           true), out)
  end)
end)

describe("#gl lsys view on a cpfg model", function ()
  local Disp = require "tests.display"
  teardown(function () Disp.stop() end)

  it("loads the model again when a file it #includes changes", function ()
    local ok, why = Disp.start()
    if not ok then pending(why) return end
    if not Disp.have("xdotool") then
      pending("xdotool is not installed (./setup.sh does)")
      return
    end
    local dir = H.tmpdir()
    for _, f in ipairs { "plant.l", "plant.h", "plant.v" } do
      H.write(dir .. "/" .. f, H.read(D .. "cli/" .. f))
    end
    local bin = H.ABSBIN
    local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
    os.execute("cd " .. dir .. " && (" .. Disp.env .. "timeout " .. 60 * SLOW .. " " .. bin ..
      " view plant.l plant.v --size 200x200 >out.txt 2>err.txt; echo $? > rc.txt) &")
    local win = Disp.env .. "timeout " .. 30 * SLOW ..
                " xdotool search --sync --name 'lsys: plant.l' "
    local function wait_for (file, text)
      for _ = 1, 100 * SLOW do
        local s = H.read(dir .. "/" .. file)
        if s and s:find(text, 1, true) then return s end
        Disp.sleep(0.1)
      end
      return H.read(dir .. "/" .. file) or ""
    end
    os.execute(win .. ">/dev/null 2>&1")      -- the window is open
    Disp.sleep(1.1)                  -- a new modification time even on coarse clocks
    H.write(dir .. "/plant.h", "#define STEPS 2\n#define RATE 1.5\n#define LIMIT 3\n"
            .. "#define ANGLE 30\n")
    local err = wait_for("err.txt", "reloaded plant.l: 2 steps")
    assert.truthy(err:find("reloaded plant.l: 2 steps", 1, true), err)
    Disp.sleep(1.1)
    H.write(dir .. "/plant.v", "angle increment: 45\n")
    err = wait_for("err.txt", "reloaded plant.l: 2 steps (")
    local _, n = err:gsub("reloaded plant%.l", "")
    for _ = 1, 50 * SLOW do
      if n >= 2 then break end
      Disp.sleep(0.1)
      _, n = (H.read(dir .. "/err.txt") or ""):gsub("reloaded plant%.l", "")
    end
    assert.equal(2, n)
    os.execute(win .. "windowfocus --sync %1 key Escape >/dev/null 2>&1")
    assert.equal("0\n", wait_for("rc.txt", "\n"))
    H.rmdir(dir)
  end)
end)
