-- The lsys program and the viewer on component graphs: model files that return
-- a prototype, in every command; the pick report of an instance (its path and parameters);
-- a click in the window (#gl, on a private Xvfb as tests/viewer_spec.lua).
local H = require "tests.helper"
local D = require "tests.display"
local C = require "lsys.components"
local R = require "lsys.repl"
local V = require "lsys.viewer"

local BIN = H.BIN
local ABS = H.ABSBIN

local PLANT = [[
local C = require "lsys".components
local leaf = C.leaf { name = "leaf", length = { 0.3, 0.5 }, width = 0.2 }
local twig = C.tree { name = "twig", length = 1, n = 2, angle = 50 }
twig:branch(leaf)
local plant = C.tree { name = "plant", length = 4, n = 3, angle = { 70, 40 } }
plant:branch(twig)
return plant
]]

local function model_file (text)
  local dir = H.tmpdir()
  H.write(dir .. "/plant.lua", text or PLANT)
  return dir, dir .. "/plant.lua"
end

describe("the lsys program on a component graph", function()
  it("derives, renders and exports a file that returns the root prototype", function()
    local dir, path = model_file()
    -- the same string as lsys.components.model gives
    local m = C.model(assert(loadfile(path))())
    local out, code = H.sh(BIN .. " derive " .. path)
    assert.equal(0, code, out)
    assert.equal(tostring(m:derive()) .. "\n", out)
    out, code = H.sh(BIN .. " render " .. path .. " --size 120x100 -o " .. dir .. "/p.png")
    assert.equal(0, code, out)
    local ntri = m:interpret().ntriangles
    assert.truthy(out:find(("wrote %s/p.png (120x100, %d triangles, 0 lines)"):format(dir, ntri),
      1, true), out)
    out, code = H.sh(BIN .. " export " .. path .. " -o " .. dir .. "/p.obj")
    assert.equal(0, code, out)
    assert.truthy(out:find(("%d triangles"):format(ntri), 1, true), out)
    H.rmdir(dir)
  end)

  it("expands with --seed, and picks a graph from a table of models by --name", function()
    local dir, path = model_file([[
local C = require "lsys".components
local function plant ()
  local p = C.tree { name = "p", length = 2, n = 4,
                     angle = function (ctx) return 20 + 50 * ctx.random() end }
  p:branch(C.leaf { length = 0.3 })
  return p
end
return { a = plant(), b = require "lsys".lsystem { axiom = "F(1)" } }
]])
    local s1 = H.sh(BIN .. " derive " .. path .. " --seed 1")
    local s2 = H.sh(BIN .. " derive " .. path .. " --seed 2")
    local s1b = H.sh(BIN .. " derive " .. path .. " --name a --seed 1")
    assert.equal(s1, s1b)
    assert.are_not.equal(s1, s2)
    assert.equal("F(1)\n", (H.sh(BIN .. " derive " .. path .. " --name b")))
    H.rmdir(dir)
  end)

  it("says a graph has no steps nor variables, and what a model file may return", function()
    local dir, path = model_file()
    local out, code = H.sh(BIN .. " derive " .. path .. " --steps 2")
    assert.equal(2, code)
    assert.truthy(out:find("plant.lua is a component graph: it has no derivation steps", 1,
      true), out)
    H.write(path, "return 42\n")
    out, code = H.sh(BIN .. " render " .. path)
    assert.equal(1, code)
    assert.truthy(out:find("returned number, not a model", 1, true), out)
    assert.truthy(out:find("a component graph's root prototype", 1, true), out)
    -- an error in the expansion names the file and the component
    H.write(path, [[
local C = require "lsys".components
return C.tree { name = "bad", length = function () return "long" end }
]])
    out, code = H.sh(BIN .. " derive " .. path)
    assert.equal(1, code)
    assert.truthy(out:find(path, 1, true), out)
    assert.truthy(out:find("length", 1, true) and out:find("bad", 1, true), out)
    H.rmdir(dir)
  end)
end)

describe("the pick report of a component instance", function()
  it("gives the instance path, its iteration and its parameters, ranges evaluated", function()
    local m = C.model(load(PLANT)())
    local s = m:derive()
    -- the leaves: the second leaf of the third twig
    local tree = m.components.tree
    local leaf = tree:find("plant#1/twig#3/leaf#6")
    assert.truthy(leaf, "no such instance")
    local i = leaf.at                       -- the module that put the turtle on its frame
    local inst, path = V.instance(s, i)
    assert.equal(leaf, inst)
    assert.equal("plant#1/twig#3/leaf#6", path)
    -- a click on it, as the REPL and lsys view print it
    local lines = R.instance_lines(inst, path)
    assert.same({
      ("  instance plant#1/twig#3/leaf#6: leaf, iteration %d of %d, depth %d")
        :format(inst.i, inst.n, inst.depth),
      ("    length = {0.3, 0.5} -> %.4g"):format(0.3 + 0.2 * (inst.i - 1) / (inst.n - 1)),
      "    width = 0.2",
    }, lines)
    -- a Tree's angle range runs over its branches, not its own iteration
    local root = R.instance_lines(tree:find("plant#1"))
    assert.equal("    angle = {70, 40} over its branches", root[2])
    -- a module of another string (another step) reports no instance
    assert.is_nil((V.instance(m:lstring("F F"), 1)))
  end)
end)

describe("#gl the viewer on a component graph", function()
  teardown(function() D.stop() end)

  it("shows the plant with lsys view and prints the instance of a click", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not D.have("xdotool") then pending("xdotool is not installed") return end
    local dir, path = model_file()
    local out, code = H.sh(D.env .. BIN .. " view " .. path ..
      " --size 200x200 --no-status --screenshot " .. dir .. "/win.png")
    assert.equal(0, code, out)
    assert.truthy(out:find("wrote " .. dir .. "/win.png (200x200)", 1, true), out)
    -- a click on the middle of the stem, through lsys.show and the REPL's report
    H.write(dir .. "/click.lua", [[
local lsys = require "lsys"
local V = require "lsys.viewer"
local R = require "lsys.repl"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits
local plant = dofile(arg[1])
local picked
lsys.show(plant, { width = 300, height = 300, title = "pick plant", status = false,
                   on_pick = function (info) picked = info R.print_pick(info) end })
assert(V.sync(10 * SLOW), "no picture")
local x, y = V.project({ 0, 1.0, 0 })
os.execute(("xdotool search --name 'lsys: pick plant' mousemove --window %1 " ..
  x // 1 .. " " .. y // 1 .. " click 1 >/dev/null 2>&1"))
for _ = 1, 40 * SLOW do
  V.poll(0.25)
  if picked then break end
end
V.close()
]])
    out, code = H.sh("cd " .. dir .. " && " .. D.env .. ABS .. " click.lua plant.lua")
    assert.equal(0, code, out)
    assert.truthy(out:find("picked module %d+: "), out)
    assert.truthy(out:find("\n  instance plant#1: tree 'plant', iteration 1 of 1, depth 1\n" ..
      "    angle = {70, 40} over its branches\n    length = 4\n    n = 3\n", 1, true), out)
    H.rmdir(dir)
  end)
end)
