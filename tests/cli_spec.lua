-- The lsys program: derive, errors that name the model file.
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
    assert.truthy(out:find("must be a .png file", 1, true))
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
