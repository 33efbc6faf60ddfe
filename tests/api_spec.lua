-- One public API style: lsys.type for the kinds of lsys objects, the old
-- names kept one release with a warning, errors that begin with the public name, library
-- warnings through Lua's warn(), lsys.arrange's arguments, and the one rule lsys.viewer
-- follows without a window.
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

-- The message `fn` raises, without the "file:line: " that error() puts in front.
local function errmsg (fn, ...)
  local ok, err = pcall(fn, ...)
  assert(not ok, "no error raised")
  return (tostring(err):gsub("^[^:]*%.lua:%d+: ", ""))
end

-- Runs the Lua text `script` with the lua5.4 interpreter and `flags`, with this process's
-- module paths; returns the output and the exit status, or nil when there is no lua5.4.
local function lua (flags, script)
  if H.sh("command -v lua5.4") == "" then return nil end
  local path = os.tmpname()
  H.write(path, script)
  local out, code = H.sh(("LUA_PATH='%s' LUA_CPATH='%s' lua5.4 %s %s")
                           :format(package.path, package.cpath, flags, path))
  os.remove(path)
  return out, code
end

local function plant ()
  return lsys.lsystem { axiom = "F(1)F(1)[+(30)F(1)]F(1)", view = { angle = 30 } }
end

describe("lsys.type", function()
  it("names every kind of lsys object", function()
    local m = plant()
    local s = m:derive()
    local a = lsys.arrange(m, s)
    a:select(2, 5)
    assert.equal("model", lsys.type(m))
    assert.equal("lstring", lsys.type(s))
    assert.equal("scene", lsys.type(m:interpret(s)))
    assert.equal("arrangement", lsys.type(a))
    assert.equal("ik", lsys.type(a.ik))
    assert.equal("rules", lsys.type(m._rules))
    assert.equal("contour", lsys.type(core.contour({ { 0, 0 }, { 1, 0 }, { 1, 1 } }, true)))
    assert.equal("surface", lsys.type(core.surface_load("tests/data/surfaces/petal.s")))
    assert.equal("texture", lsys.type(core.texture_load("tests/data/views/leaf.png")))
  end)

  it("is nil for any other value", function()
    for _, x in ipairs { 1, 1.5, "F", true, {}, print, io.stdout, coroutine.create(print),
                         lsys, lsys.view, lsys.Model,
                         setmetatable({}, { __name = "lsys.Scene" }) } do
      assert.is_nil(lsys.type(x), tostring(x))
    end
    assert.is_nil(lsys.type(nil))
  end)

  it("keeps the kind of a closed object", function()
    local s = lsys.lstring("F")
    getmetatable(s).__close(s)
    assert.equal("lstring", lsys.type(s))
  end)
end)

describe("deprecated names", function()
  it("still work", function()
    local m = plant()
    local s = m:derive()
    assert.is_true(lsys.islstring(s))
    assert.is_false(lsys.islstring(m))
    assert.is_true(lsys.ismodel(m))
    assert.is_true(lsys.isscene(m:interpret(s)))
    assert.is_false(lsys.viewer.isopen())
    local a, b = lsys.arrange(m, s), lsys.arrange(m, s)
    assert.equal(a:select(2, 5), b:select { fixed = 2, moved = 5 })
    assert.same(a:path_modules(), b:path_modules())
    assert.equal(a:spherical({ 0, 0, 1 }, 20).f, b:spherical { axis = { 0, 0, 1 }, angle = 20 }.f)
    assert.equal(tostring(a:lstring()), tostring(b:lstring()))
    local v = lsys.view.normalize { angle = 30, fov = 50 }
    assert.same(lsys.view.turtle_options(v, true), lsys.view.turtle(v, true))
    assert.same(lsys.view.render_options(v), lsys.view.render(v))
  end)

  it("warn once each, through warn()", function()
    local out, code = H.lsys([[
local lsys = require "lsys"
local m = lsys.lsystem { axiom = "F(1)F(1)F(1)" }
for _ = 1, 2 do
  lsys.islstring(1); lsys.isscene(1); lsys.ismodel(m); lsys.viewer.isopen()
  local a = lsys.arrange(m)
  a:select { fixed = 1, moved = 3 }
  a:spherical { axis = { 0, 0, 1 }, angle = 10 }
  lsys.view.turtle(lsys.view.normalize {}); lsys.view.render(lsys.view.normalize {})
end
print("done")
]])
    assert.equal(0, code, out)
    local want = {
      'lsys.islstring is deprecated; use lsys.type(x) == "lstring"',
      'lsys.isscene is deprecated; use lsys.type(x) == "scene"',
      'lsys.ismodel is deprecated; use lsys.type(x) == "model"',
      "lsys.viewer.isopen is deprecated; use lsys.viewer.state()",
      "Arrangement:select { fixed =, moved = } is deprecated; use " ..
        "Arrangement:select(fixed, moved)",
      "Arrangement:spherical { axis =, angle = } is deprecated; use " ..
        "Arrangement:spherical(axis, angle)",
      "lsys.view.turtle is deprecated; use lsys.view.turtle_options",
      "lsys.view.render is deprecated; use lsys.view.render_options",
    }
    local n = 0
    for line in out:gmatch("Lua warning: ([^\n]*)") do
      n = n + 1
      assert.equal("lsys: " .. want[n], line)
    end
    assert.equal(#want, n, out)
    assert.truthy(out:find("done\n", 1, true), out)
  end)
end)

describe("library warnings", function()
  local SCRIPT = [[
local lsys = require "lsys"
lsys.view.parse("z buffer: on", "w.v")
print("done")
]]
  it("are off in a plain lua, on with -W", function()
    local out, code = lua("", SCRIPT)
    if out == nil then pending("no lua5.4 to run") return end
    assert.equal(0, code, out)
    assert.equal("done\n", out)
    out, code = lua("-W", SCRIPT)
    assert.equal(0, code, out)
    assert.equal("Lua warning: w.v:1: 'z buffer' is not supported; ignored\ndone\n", out)
  end)

  it("are on in the lsys program", function()
    local out, code = H.lsys(SCRIPT)
    assert.equal(0, code, out)
    assert.equal("Lua warning: w.v:1: 'z buffer' is not supported; ignored\ndone\n", out)
  end)

  it("never read as a control message", function()
    local out, code = H.lsys('require "lsys".view.parse("z buffer: on", "@on")')
    assert.equal(0, code, out)
    assert.equal("Lua warning: @on:1: 'z buffer' is not supported; ignored\n", out)
  end)
end)

describe("errors of the public API", function()
  it("begin with the function's public name", function()
    local m = plant()
    local cases = {
      { "lsys.lsystem: ", lsys.lsystem, 1 },
      { "lsys.lstring: ", lsys.lstring, "F(" },
      { "lsys.lstring: ", lsys.lstring, "Apex(", "Apex" },
      { "lsys.render: ", lsys.render, 1 },
      { "lsys.show: ", lsys.show, 1 },
      { "lsys.show: ", lsys.viewer.show, 1 },            -- the same function
      { "lsys.viewer.open: ", lsys.viewer.open, 1 },
      { "lsys.viewer.key: ", lsys.viewer.key, "f" },
      { "lsys.viewer.screenshot: ", lsys.viewer.screenshot },
      { "lsys.arrange: ", lsys.arrange, m, nil, 1 },
      { "lsys.arrange: ", lsys.arrange, 1 },
      { "lsys.max_memory: ", lsys.max_memory, "lots" },
      { "lsys.parse_size: ", lsys.parse_size, "lots" },
      { "lsys.view.parse: ", lsys.view.parse, 1 },
      { "lsys.view.load: ", lsys.view.load, 1 },
      { "lsys.view.load_colormap: ", lsys.view.load_colormap, 1 },
      { "lsys.view.load_materials: ", lsys.view.load_materials, 1 },
    }
    for _, c in ipairs(cases) do
      local msg = errmsg(c[2], table.unpack(c, 3, 5))
      assert.equal(c[1], msg:sub(1, #c[1]), msg)
    end
  end)

  it("of a method begin with its name", function()
    local m = plant()
    local a = lsys.arrange(m)
    local cases = {
      { "derive: ", m.derive, m, -1 }, { "step: ", m.step, m, 1 },
      { "expand: ", m.expand, m, 1 }, { "interpret: ", m.interpret, m, 1 },
      { "use_group: ", m.use_group, m, -1 }, { "lstring: ", m.lstring, m, "F(" },
      { "select: fixed: ", a.select, a, "x" }, { "select: ", a.select, a, 4, 2 },
      { "spherical: ", a.spherical, a, 1 }, { "spherical: ", a.spherical, a, { 0, 0, 1 }, 5 },
      { "disc: ", a.disc, a, "x" }, { "disc: ", a.disc, a, 5 },
      { "axis: ", a.axis, a, "x" }, { "plane: ", a.plane, a, 1 },
      { "move_fixed: ", a.move_fixed, a, "up" }, { "prune: ", a.prune, a, 99 },
      { "stiffness: ", a.stiffness, a, 99 },
    }
    for _, c in ipairs(cases) do
      local msg = errmsg(c[2], table.unpack(c, 3, 5))
      assert.equal(c[1], msg:sub(1, #c[1]), msg)
    end
  end)
end)

describe("lsys.arrange", function()
  it("takes the string as text, as Model methods do", function()
    local m = plant()
    local text = "F(1)F(1)[+(30)F(1)F(1)]F(1)"
    local a, b = lsys.arrange(m, text), lsys.arrange(m, m:lstring(text))
    assert.equal(a:select(2, 6), b:select(2, 6))
    assert.equal(tostring(b:lstring()), tostring(a:lstring()))
    assert.equal("lsys.arrange: " .. errmsg(m.lstring, m, "F("), errmsg(lsys.arrange, m, "F("))
    assert.equal("lsys.arrange: an Lstring or its text expected", errmsg(lsys.arrange, m, 5))
    assert.equal("lsys.arrange: a model expected", errmsg(lsys.arrange, text))
  end)

  it("takes a pick table where it takes a module index", function()
    local m = plant()
    local a, b = lsys.arrange(m), lsys.arrange(m)
    assert.equal(3, a:select({ module = 1 }, { module = 5 }))
    assert.equal(3, b:select(1, 5))
    assert.same(b:path_modules(), a:path_modules())
  end)
end)

describe("lsys.viewer without a window", function()
  it("raises where it must act on one and answers as for a closed one otherwise",
  function()
    local out, code = H.lsys([[
local lsys = require "lsys"
local V = lsys.viewer
local function try (name, ...)
  local ok, err = pcall(V[name], ...)
  print(name, ok and "ok" or err:match("^[^:]*:") .. (err:find("no window open", 1, true)
        and " no window open" or ""))
end
try("open") try("show", lsys.lsystem { axiom = "F" }) try("key", "f") try("screenshot")
print(V.poll(), V.poll(0.1), V.sync(0.1), V.pending(), V.state(), V.project { 0, 0, 0 })
print(V.wait(), V.close(), V.last_pick)
print(pcall(lsys.wait))
]], { prefix = "unset DISPLAY WAYLAND_DISPLAY;" })
    assert.equal(0, code, out)
    assert.equal(table.concat({
      "open\tlsys.viewer.open:",
      "show\tlsys.show:",
      "key\tlsys.viewer.key: no window open",
      "screenshot\tlsys.viewer.screenshot: no window open",
      "false\tfalse\tfalse\t0\tnil\tnil",
      "nil\tnil\tnil",
      "true",
      "" }, "\n"), out)
  end)

  it("says why no window opens", function()
    local out = H.lsys('print(select(2, pcall(require "lsys".viewer.open)))',
                       { prefix = "unset DISPLAY WAYLAND_DISPLAY;" })
    if core.has_viewer then
      assert.truthy(out:find("^lsys.viewer.open: .*no display: DISPLAY is not set"), out)
    else
      assert.truthy(out:find("^lsys.viewer.open: lsys was built without the viewer window"), out)
    end
  end)
end)
