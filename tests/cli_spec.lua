-- The lsys program: derive, errors that name the model file.
local H = require "tests.helper"
local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"

local function run (args)
  local p = io.popen(BIN .. " " .. args .. " 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return out:gsub("exit:%d+%s*$", ""), code
end

local function tmpmodel (text)
  local path = os.tmpname()
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
  return path
end

describe("lsys derive", function()
  it("prints the derived string of a model file", function()
    local path = tmpmodel('local lsys = require "lsys"\n' ..
      'return lsys.lsystem { axiom = "F", steps = 2, productions = "F --> F+F" }\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(0, code)
    assert.equal("F+F+F+F\n", out)
  end)

  it("prints counts with --stats and honours --steps and --set", function()
    local path = tmpmodel('local lsys = require "lsys"\n' ..
      'return lsys.lsystem { axiom = "A(1)", env = { K = 2 }, productions = "A(x) --> A(x*K)B" }\n')
    local out, code = run("derive " .. path .. " --steps 3 --set K=3 --stats")
    local out2 = run("derive " .. path .. " --steps 3 --set K=3")
    os.remove(path)
    assert.equal(0, code)
    assert.truthy(out:find("modules 4", 1, true))
    assert.truthy(out:find("B 3", 1, true))
    assert.equal("A(27)BBB\n", out2)
  end)

  it("names the model file when `return lsys.lsystem{...}` has a bad rule", function()
    local path = tmpmodel('local lsys = require "lsys"\n\nreturn lsys.lsystem {\n' ..
      '  axiom = "A",\n  productions = "A(s --> B",\n}\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(1, code)
    assert.truthy(out:find("lsys: " .. path .. ": rule 1 'A(s --> B' (line 1 of productions): " ..
                           "unbalanced parentheses: '(' without ')' at character 2", 1, true))
  end)

  it("names file and line when the model is returned through a local", function()
    local path = tmpmodel('local lsys = require "lsys"\nlocal m = lsys.lsystem {\n' ..
      '  productions = "A --> B\\nA(s) --> B(s*)",\n}\nreturn m\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(1, code)
    assert.truthy(out:find(path .. ":2: rule 2 'A(s) --> B(s*)' (line 2 of productions): " ..
                           "bad expression 's*' in parameter 1 of 'B'", 1, true))
  end)

  it("exits with 2 and a hint on an unknown option", function()
    local out, code = run("derive --bogus")
    assert.equal(2, code)
    assert.truthy(out:find("unknown option '--bogus'", 1, true))
  end)
end)

describe("lsys render and export", function()
  local has_render = require("lsys.core").has_render
  local dir
  before_each(function()
    dir = os.tmpname()
    os.remove(dir)
    assert(os.execute("mkdir -p " .. dir))
  end)
  after_each(function() os.execute("rm -rf " .. dir) end)

  local function size_of (path)
    local f = io.open(path, "rb")
    if not f then return nil end
    local n = f:seek("end")
    f:close()
    return n
  end

  it("renders the default plant to tree.png with no MODEL #gl", function()
    if not has_render then return pending("built without OSMesa") end
    local out, code = run("render -o " .. dir .. "/tree.png --size 200x150")
    assert.equal(0, code, out)
    assert.truthy(out:find("wrote " .. dir .. "/tree.png (200x150, ", 1, true))
    local px, w, h = require("lsys.core").png_read(dir .. "/tree.png")
    assert.equal(200, w); assert.equal(150, h); assert.equal(200 * 150 * 4, #px)
  end)

  it("applies --view and --set #gl", function()
    if not has_render then return pending("built without OSMesa") end
    local path = tmpmodel('local lsys = require "lsys"\n' ..
      'return lsys.lsystem { axiom = "F(L)", env = { L = 1 }, view = { angle = 30 } }\n')
    local out, code = run("render " .. path .. " -o " .. dir .. "/a.png --size 64x64" ..
      " --view background=1,0,0 --view supersample=1 --set L=2")
    os.remove(path)
    assert.equal(0, code, out)
    local px = require("lsys.core").png_read(dir .. "/a.png")
    assert.equal(string.char(255, 0, 0, 255), px:sub(1, 4))      -- the corner is background
  end)

  it("exports OBJ, PLY and GLB", function()
    for _, ext in ipairs { "obj", "ply", "glb" } do
      local out, code = run("export abop/fig1_24a -o " .. dir .. "/t." .. ext ..
        " --view line_style=cylinder --steps 2")
      assert.equal(0, code, out)
      assert.truthy(out:find("wrote " .. dir .. "/t." .. ext .. " (", 1, true))
      assert.is_true(size_of(dir .. "/t." .. ext) > 1000)
    end
    assert.is_true(size_of(dir .. "/t.mtl") > 0)
  end)

  it("reports usage errors with exit status 2", function()
    local out, code = run("export abop/fig1_24a -o " .. dir .. "/t.stl")
    assert.equal(2, code)
    assert.truthy(out:find("must end in .obj, .ply or .glb", 1, true))
    out, code = run("export abop/fig1_24a")
    assert.equal(2, code)
    assert.truthy(out:find("-o OUT.obj", 1, true))
    out, code = run("render --size 12 -o " .. dir .. "/x.png")
    assert.equal(2, code)
    assert.truthy(out:find("--size expects WxH", 1, true))
    out, code = run("render -o " .. dir .. "/x.jpg")
    assert.equal(2, code)
    assert.truthy(out:find("must be a .png, .svg, .eps or .pdf file", 1, true))
  end)

  it("reports a bad view option (a usage error) and an unwritable output", function()
    local out, code = run("export abop/fig1_24a -o " .. dir .. "/t.obj --view line_style=tube")
    assert.equal(2, code)
    assert.truthy(out:find("--view line_style=tube: 'line_style' must be", 1, true))
    out, code = run("export abop/fig1_24a -o /nonexistent/dir/t.obj --steps 1")
    assert.equal(1, code)
    assert.truthy(out:find("cannot open '/nonexistent/dir/t.obj'", 1, true), out)
  end)
end)

-- `lsys ARGS`: what it wrote on stdout, what on stderr, and its exit status (`env`: the
-- variables set for it, "DISPLAY=:1 ").
local function run3 (args, env)
  local err = os.tmpname()
  local p = io.popen((env or "") .. BIN .. " " .. args .. " 2>" .. err .. "; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  local f = assert(io.open(err))
  local errout = f:read("a")
  f:close()
  os.remove(err)
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return (out:gsub("exit:%d+%s*$", "")), errout, code
end

-- The lines a usage error of `lsys CMD` prints.
local function usage_text (cmd, msg)
  return "lsys: " .. cmd .. ": " .. msg .. "\nRun 'lsys " .. cmd .. " --help' for its options.\n"
end

describe("lsys -V and -v", function()
  it("prints the version with -V and --version, and with -v, the old spelling, warning", function()
    local out, err, code = run3("-V")
    assert.equal(0, code, err)
    assert.matches("^lsys %S+ %(Lua 5%.4%)\n$", out)
    assert.equal("", err)
    local out2, err2, code2 = run3("--version")
    assert.equal(0, code2, err2)
    assert.equal(out, out2)
    assert.equal("", err2)
    local out3, err3, code3 = run3("-v")
    assert.equal(0, code3, err3)
    assert.equal(out, out3)
    assert.equal("Lua warning: lsys: 'lsys -v' is deprecated; use 'lsys -V' (--version)\n", err3)
  end)

  it("says in the help that -V is the version and -v verbose", function()
    local out, code = run("--help")
    assert.equal(0, code, out)
    assert.truthy(out:find("\n  -V, --version   show the version\n", 1, true), out)
    assert.truthy(out:find("-v is --verbose where a command has a verbose mode", 1, true), out)
    assert.falsy(out:find("-v, --version", 1, true), out)
    out = run("help test")
    assert.truthy(out:find("\n  -v, --verbose      more output", 1, true), out)
  end)
end)

describe("a model without a name", function()
  local dir
  before_each(function() dir = H.tmpdir() end)
  after_each(function() H.rmdir(dir) end)

  it("is named after its model file, through a tail call, a command or dofile", function()
    H.write(dir .. "/plant.lua", 'local lsys = require "lsys"\n'
      .. 'return lsys.lsystem { axiom = "F", productions = "F --> FF" }\n')
    H.write(dir .. "/named.lua", 'local lsys = require "lsys"\n'
      .. 'local m = lsys.lsystem { axiom = "F", name = "tree" }\nreturn m\n')
    H.write(dir .. "/show.lua", ("local a, b = dofile(%q), dofile(%q)\n"
      .. "print(tostring(a), a.name, tostring(b))\n"
      .. 'print(tostring(require("lsys").lsystem { axiom = "F" }):match("%%((.*)%%)"))\n')
      :format(dir .. "/plant.lua", dir .. "/named.lua"))
    local out, code = run(dir .. "/show.lua")
    assert.equal(0, code, out)
    -- a model the script makes itself is no model file's: its file and line
    assert.equal("lsys.Model(plant)\tplant\tlsys.Model(tree)\n" .. dir .. "/show.lua:3\n", out)
    -- the commands' loader, and lsys.batch's
    local load = require "lsys.load"
    assert.equal("plant", load.model(dir .. "/plant.lua").name)
    assert.equal("tree", load.model(dir .. "/named.lua").name)
    -- dofile keeps Lua's errors and results
    H.write(dir .. "/many.lua", 'error("no")')
    H.write(dir .. "/show.lua", ("print(pcall(dofile, %q))\nprint(pcall(dofile, %q))\n"
      .. "print(select('#', dofile(%q)))\n"):format(dir .. "/none.lua", dir .. "/many.lua",
      dir .. "/three.lua"))
    H.write(dir .. "/three.lua", "return 1, nil, 3\n")
    out, code = run(dir .. "/show.lua")
    assert.equal(0, code, out)
    assert.equal("false\tcannot open " .. dir .. "/none.lua: No such file or directory\n"
                 .. "false\t" .. dir .. "/many.lua:1: no\n3\n", out)
  end)
end)

describe("--threads, --max-memory and --max-modules", function()
  local paths = {}
  local function model (text)
    local path = tmpmodel('local lsys = require "lsys"\nreturn lsys.lsystem ' .. text .. "\n")
    paths[#paths + 1] = path
    return path
  end
  after_each(function()
    for _, p in ipairs(paths) do os.remove(p) end
    paths = {}
  end)

  it("--max-modules sets the model's max_modules, over the model's own", function()
    local path = model '{ axiom = "F", steps = 5, productions = "F --> FF" }'
    local out, code = run("derive " .. path .. " --max-modules 10")
    assert.equal(1, code, out)
    assert.equal("lsys: " .. path .. ": step 4 of 5: the string would exceed max_modules (10 "
                 .. "modules)\n", out)
    path = model '{ axiom = "F", steps = 5, productions = "F --> FF", max_modules = 10 }'
    out, code = run("derive " .. path)
    assert.equal(1, code, out)
    out, code = run("derive " .. path .. " --max-modules=1e6")
    assert.equal(0, code, out)
    assert.equal(("F"):rep(32) .. "\n", out)
  end)

  it("--max-memory sets the model's max_memory, over the model's own", function()
    local rules = 'axiom = "A(1,2,3)", steps = 14, productions = "A(x,y,z) --> A(x,y,z) A(x,y,z)"'
    local path = model("{ " .. rules .. " }")
    local out, code = run("derive " .. path .. " --stats --max-memory 64K")
    assert.equal(1, code, out)
    assert.equal("lsys: " .. path .. ": step 11 of 14: the derivation would need more than "
      .. "max_memory (64 KiB) at module 513 (set max_memory in the model, or LSYS_MAX_MEMORY)\n",
      out)
    out, code = run("derive " .. path .. " --stats --max-memory 65536")
    assert.equal(1, code, out)
    assert.truthy(out:find("more than max_memory (64 KiB) at module 513", 1, true), out)
    path = model("{ " .. rules .. ', max_memory = "64K" }')
    out, code = run("derive " .. path .. " --stats")
    assert.equal(1, code, out)
    for _, size in ipairs { "64M", "unlimited" } do
      out, code = run("derive " .. path .. " --stats --max-memory " .. size)
      assert.equal(0, code, out)
      assert.truthy(out:find("\nmodules 16384\n", 1, true), out)
    end
  end)

  it("--threads sets the model's threads, and 1 and 2 threads give the same string", function()
    local path = model [[{ axiom = "F", threads = 1,
      start = function (m) io.stderr:write("threads ", m.threads, "\n") end }]]
    local out, err, code = run3("derive " .. path .. " --threads 2")
    assert.equal(0, code, err)
    assert.equal("F\n", out)
    assert.equal("threads 2\n", err)
    -- a string long enough for a step to run on several threads (8192 modules)
    path = model [[{ axiom = "A(1)", seed = 5, steps = 13,
                     productions = "A(s) --> F(s)[+A(s*ran(1))][-A(s/2)]" }]]
    local one, code1 = run("derive " .. path .. " --threads 1")
    local two, code2 = run("derive " .. path .. " --threads=2")
    assert.equal(0, code1, one:sub(1, 200))
    assert.equal(0, code2, two:sub(1, 200))
    assert.is_true(#one > 100000, #one)
    assert.is_true(one == two)
  end)

  it("are usage errors (exit 2) with a bad value, for every command that loads a model",
  function()
    local path = model '{ axiom = "F" }'
    local bad = {
      { "--threads 0", "--threads expects a whole number from 1 to 64, got '0'" },
      { "--threads 65", "--threads expects a whole number from 1 to 64, got '65'" },
      { "--threads 1.5", "--threads expects a whole number from 1 to 64, got '1.5'" },
      { "--threads=many", "--threads expects a whole number from 1 to 64, got 'many'" },
      { "--max-modules 0", "--max-modules expects a whole number from 1 to 1e12, got '0'" },
      { "--max-modules 2e12",
        "--max-modules expects a whole number from 1 to 1e12, got '2e12'" },
      { "--max-modules ten", "--max-modules expects a whole number from 1 to 1e12, got 'ten'" },
      { "--max-memory lots", "--max-memory: 'lots' is not a size (use a number of bytes, or "
        .. 'e.g. "512M", "2G", "unlimited")' },
      { "--max-memory 0", "--max-memory: '0' is not a size (use a number of bytes, or "
        .. 'e.g. "512M", "2G", "unlimited")' },
    }
    for _, b in ipairs(bad) do
      local out, err, code = run3("derive " .. path .. " " .. b[1])
      assert.equal(2, code, err)
      assert.equal("", out)
      assert.equal(usage_text("derive", b[2]), err)
    end
    -- the other commands check them as derive does, before any window or file
    local dir = os.tmpname()
    for _, cmd in ipairs { "render", "export", "animate", "view", "arrange" } do
      local o = ({ render = " -o " .. dir .. ".png", export = " -o " .. dir .. ".obj",
                   animate = " -o " .. dir .. ".gif" })[cmd] or ""
      local _, err, code = run3(cmd .. " " .. path .. o .. " --threads 0")
      assert.equal(2, code, err)
      assert.equal(usage_text(cmd, "--threads expects a whole number from 1 to 64, got '0'"), err)
    end
    os.remove(dir)
  end)

  it("apply to a model, not to a file returning a Scene", function()
    local path = tmpmodel('local lsys = require "lsys"\n'
      .. 'return lsys.population { { model = lsys.lsystem { axiom = "F" } } }\n')
    paths[#paths + 1] = path
    local _, err, code = run3("export " .. path .. " -o " .. path .. ".obj --max-modules 5")
    assert.equal(2, code, err)
    assert.equal(usage_text("export", path .. " returns a Scene (a population): --threads, "
      .. "--max-memory, --max-modules and --environment apply to a model"), err)
  end)
end)

describe("a file returning a Scene (a population) on the command line", function()
  local path = tmpmodel('local lsys = require "lsys"\n'
    .. 'local m = lsys.lsystem { axiom = "F(1)[+F(1)]F(1)", view = { angle = 30 } }\n'
    .. 'return lsys.population { { model = m }, { model = m, at = { 2, 0, 0 } } }\n')
  teardown(function() os.remove(path) end)

  it("#gl takes --view for the picture (background, camera), as a model does", function()
    local png = os.tmpname() .. ".png"
    local out, code = run("render " .. path .. " -o " .. png
      .. " --size 64x64 --view background=0,0,1")
    assert.equal(0, code, out)
    local px = require("lsys.core").png_read(png)
    os.remove(png)
    assert.equal(string.char(0, 0, 255, 255), px:sub(1, 4))     -- a corner: the background
  end)

  it("refuses a --view that changes how the turtle draws, naming it", function()
    local _, err, code = run3("render " .. path .. " -o " .. path .. ".png --view angle=10")
    assert.equal(2, code, err)
    assert.equal(usage_text("render", path .. " returns a Scene (a population): --view "
      .. "angle=10 changes how the turtle draws, which applies to a model"), err)
  end)
end)

describe("lsys render's messages", function()
  it("name no library function, as export's do", function()
    local _, err, code = run3("render examples/default.lua --steps 1 -o /nonexistent/x.png")
    assert.equal(1, code)
    assert.equal("lsys: cannot open '/nonexistent/x.png' for writing: No such file or "
      .. "directory\n", err)
    _, err, code = run3("export examples/default.lua --steps 1 -o /nonexistent/x.obj")
    assert.equal(1, code)
    assert.equal("lsys: cannot open '/nonexistent/x.obj' for writing: No such file or "
      .. "directory\n", err)
  end)
end)

describe("lsys view --show", function()
  local D = require "tests.display"
  teardown(function() D.stop() end)

  it("checks --show K, and --step K, its old spelling, which warns", function()
    local out, err, code = run3("view --show x examples/default.lua")
    assert.equal(2, code, out)
    assert.equal(usage_text("view", "--show expects a step number (0 or more), got 'x'"), err)
    out, err, code = run3("view --step x examples/default.lua")
    assert.equal(2, code, out)
    assert.equal("Lua warning: lsys: 'lsys view --step K' is deprecated; use 'lsys view --show K'\n"
      .. usage_text("view", "--step expects a step number (0 or more), got 'x'"), err)
    out, err, code = run3("view --last --show 1 examples/default.lua")
    assert.equal(2, code, out)
    assert.equal(usage_text("view", "--last and --show exclude each other"), err)
    out, err, code = run3("view --show 1 --step 1 examples/default.lua")
    assert.equal(2, code, out)
    assert.equal(usage_text("view", "--step is the old spelling of --show: give one of them"), err)
    out = run("view --help")
    assert.truthy(out:find("\n  --show K             the step shown first (default: the last)",
      1, true), out)
  end)

  it("says once, without a display, that the window cannot open", function()
    if not require("lsys.core").has_viewer then pending("built without the window") return end
    local env = "env -u DISPLAY -u WAYLAND_DISPLAY "
    local out, err, code = run3("view examples/abop/fig1_24a.lua", env)
    assert.equal(1, code, out)
    assert.equal("", out)
    local why = err:match("^lsys: (cannot start GLFW: [^\n]*%(no display: DISPLAY is not set; "
                          .. "`lsys render` draws PNG files without one%))\n$")
    assert.truthy(why, err)
    -- a model that fails too: its error, then the window's
    local bad = os.tmpname()
    local f = assert(io.open(bad, "w"))
    f:write("return 1 +")
    f:close()
    out, err, code = run3("view " .. bad, env)
    os.remove(bad)
    assert.equal(1, code, out)
    assert.equal("lsys: " .. bad .. ":1: unexpected symbol near <eof>\nlsys: " .. why .. "\n", err)
  end)

  it("#gl shows step K first with --show K, as with --step K", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    local dir = os.tmpname()
    os.remove(dir)
    assert(os.execute("mkdir -p " .. dir))
    local function shot (opts, name)
      local out, err, code = run3("view examples/abop/fig1_24a.lua --steps 3 --size 120x120 "
        .. "--no-status " .. opts .. " --screenshot " .. dir .. "/" .. name, D.env)
      assert.equal(0, code, err)
      assert.truthy(out:find("wrote " .. dir .. "/" .. name, 1, true), out)
      return err, (require("lsys.core").png_read(dir .. "/" .. name))
    end
    local err0, show0 = shot("--show 0", "show0.png")
    local err1, step0 = shot("--step 0", "step0.png")
    local _, last = shot("", "last.png")
    os.execute("rm -rf " .. dir)
    assert.falsy(err0:find("deprecated", 1, true), err0)
    assert.truthy(err1:find("Lua warning: lsys: 'lsys view --step K' is deprecated; use "
      .. "'lsys view --show K'\n", 1, true), err1)
    assert.is_true(show0 == step0)
    assert.is_false(show0 == last)
  end)
end)
