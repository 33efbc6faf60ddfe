-- The floor of the Lua bindings (csrc/lua/lua_aux.c): the option readers that every binding
-- shares, core errors raised with or without the caller's position, and the checks that an
-- object is alive. Messages are API: these are the ones the restructuring of the bindings
-- had to keep byte for byte.
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"

-- The message of the error f raises, as raised (with the position, if any).
local errof = H.errof

local function close (x) getmetatable(x).__close(x) end

local m = lsys.lsystem { axiom = "F+F" }

describe("option readers", function ()
  local function render (opts) return core.render(m:interpret(), opts) end

  it("show what a render option got", function ()
    if not core.has_render then pending("built without OSMesa") return end
    local cases = {
      { { width = 0 }, "lsys.render: opts.width must be a positive integer at most 16384, got 0" },
      { { supersample = {} },
        "lsys.render: opts.supersample must be a positive integer at most 16, got table" },
      { { fov = "30" }, "lsys.render: opts.fov must be a number of degrees in (0, 180), got '30'" },
      { { zoom = 1 / 0 }, "lsys.render: opts.zoom must be a positive number, got inf" },
      { { wireframe = 1 }, "lsys.render: opts.wireframe must be a boolean, got 1" },
      { { projection = "fish" },
        "lsys.render: opts.projection must be 'perspective' or 'parallel', got 'fish'" },
      { { light = { 1, "x", 0 } },
        "lsys.render: opts.light must be {x, y, z} with 3 finite numbers" },
      { { background = { 2, 0, 0 } },
        "lsys.render: opts.background must be {r, g, b} with numbers in [0, 1]" },
      { { out = 5 }, "lsys.render: opts.out must be a file name, got 5" },
      { { [2.5] = 1 }, "lsys.render: unknown option 2.5" },
    }
    for _, c in ipairs(cases) do assert.has_error(function () render(c[1]) end, c[2]) end
  end)

  it("read sizes also as numerals, other render numbers only as numbers", function ()
    if not core.has_render then pending("built without OSMesa") return end
    local _, w, h = render { width = "8", height = 8, supersample = "1" }
    assert.same({ 8, 8 }, { w, h })
  end)

  it("name the type of a bad viewer option, not its value", function ()
    if not core.has_viewer then pending("built without the viewer") return end
    -- the options are read before a window opens: no display needed
    assert.has_error(function () core.viewer_open { width = "800" } end,
                     "viewer: opts.width must be an integer, got string")
    assert.has_error(function () core.viewer_open { width = 0 } end,
                     "viewer: opts.width must be an integer in [1, 16384]")
    assert.has_error(function () core.viewer_open { status = "no" } end,
                     "viewer: opts.status must be a boolean, got string")
  end)

  it("name the file in texture options", function ()
    local dir = os.tmpname()
    os.remove(dir)
    local p = dir .. ".png"
    core.png_write(p, ("\255\0\0\255"):rep(4), 2, 2, false)
    local head = "lsys.texture_load: '" .. p .. "': "
    assert.has_error(function () core.texture_load(p, { mag = 5 }) end,
                     head .. "opts.mag must be 'linear', 'near', 'l' or 'n', got number")
    assert.has_error(function () core.texture_load(p, { mode = "q" }) end,
                     head .. "opts.mode must be 'modulate', 'decal', 'm' or 'd', got 'q'")
    assert.has_error(function () core.texture_load(p, { intensity = "x" }) end,
                     head .. "opts.intensity must be a boolean, got string")
    assert.equal("linear", core.texture_load(p, { mag = "l" }):info().mag)
    os.remove(p)
  end)

  it("read view options, numbers also as numerals", function ()
    local R, s = m._rules, m:derive(1)
    local function interpret (o) return core.interpret(R, s, o) end
    assert.has_error(function () interpret { angle = "1e999" } end,
                     "view option 'angle' must be a finite number, got a non-finite number")
    assert.has_error(function () interpret { step = {} } end,
                     "view option 'step' must be a finite number, got table")
    assert.has_error(function () interpret { color = 1e8 } end,
                     "view option 'color' must be between 0 and 65535, got 1e+08")
    assert.has_error(function () interpret { tropisms = { { vector = { 1, "x", 0 } } } } end,
                     "view tropism 1: 'vector'[2] must be a finite number")
    assert.equal(2, interpret({ angle = "45", color = "2" }):record(1).color)
  end)

  it("read the turtle's options under the view schema's names", function ()
    local R, s = m._rules, m:derive(1)
    local function interpret (o) return core.interpret(R, s, o) end
    local v = lsys.view.normalize { line_style = "cylinder", contour_sides = 5, line_width = 3 }
    local sc = interpret(lsys.view.turtle_options(v))
    assert.equal(2 * 2 * 5 + 4 * 5, sc.ntriangles)  -- 2 cylinders of 5 sides, 4 fan caps
    assert.equal(3, sc:record(1).w0)
    assert.has_error(function () interpret { line_style = "tube" } end,
      "view option 'line_style' must be \"line\", \"polygon\" or \"cylinder\", got \"tube\"")
    assert.has_error(function () interpret { contour_sides = 2 } end,
                     "view option 'contour_sides' must be between 3 and 1024, got 2")
    -- tropisms and torques share the turtle's limit, which the schema reads from the core
    local t = { vector = { 0, -1, 0 }, elasticity = 0.1 }
    local trop, torq = {}, {}
    for i = 1, 10 do trop[i] = t; torq[i] = t end
    assert.equal(16, core.MAXTROPISMS)
    assert.has_error(function () interpret { tropisms = trop, torques = torq } end,
                     "the view has 20 tropisms and torques; at most 16 are supported")
    assert.equal(2, interpret({ tropisms = { t }, torques = { t } }).nrecords)
  end)

  it("name the table of an IK field", function ()
    local v = { 0, 1, 0 }
    local base = { H = v, U = { 0, 0, 1 }, p = { 0, 0, 0 } }
    local joint = { p0 = { 0, 0, 0 }, p1 = v, H = v, U = { 0, 0, 1 } }
    assert.has_error(function () core.ik_chain { base = { U = v, p = v }, joints = { joint } } end,
                     "ik: base.H must be a table of 3 numbers")
    local ik = core.ik_chain { base = base, joints = { joint } }
    assert.has_error(function () ik:solve { p = v, s = v, t = v, wp = -1 } end,
                     "ik: goal.wp must be a number >= 0")
    assert.has_error(function () ik:solve { p = v, s = v, t = { 0, 1 / 0, 0 } } end,
                     "ik: goal.t must be a table of 3 finite numbers")
  end)
end)

describe("core errors", function ()
  it("start with the caller's position", function ()
    assert.truthy(errof(function () return core.png_read("/nonexistent.png") end)
                  :match("^[^:]*bindings_spec%.lua:%d+: cannot open '/nonexistent.png'"))
  end)

  it("of a file reader name the file alone", function ()
    assert.equal("cannot open '/nonexistent.con': No such file or directory",
                 errof(function () return core.contour_load("/nonexistent.con") end))
    assert.equal("x.s:1: bad bounding box line: 'garbage' is not a number",
                 errof(function () return core.surface_parse("garbage\n", "x.s") end))
  end)
end)

describe("a closed object", function ()
  it("refuses its methods and says so in tostring", function ()
    local c = core.contour { { 0, 0 }, { 1, 0 }, { 1, 1 } }
    local sc = m:interpret()
    local s = m:derive(1)
    close(c); close(sc); close(s)
    assert.has_error(function () c:size() end, "the contour was closed")
    assert.has_error(function () return sc.ntriangles end, "the scene was closed")
    assert.has_error(function () return #s end, "the Lstring was closed")
    assert.has_error(function () core.interpret(m._rules, s, {}) end, "the Lstring was closed")
    assert.equal("lsys.Contour (closed)", tostring(c))
    assert.equal("lsys.Scene (closed)", tostring(sc))
    assert.equal("lsys.Lstring (closed)", tostring(s))
  end)
end)

describe("what the Lua side reads of an object", function ()
  it("gives a model's rule functions, its Lstrings' rules and a scene's options", function ()
    local mm = lsys.lsystem { axiom = "A", productions = { "A --> F A" } }
    local fns = mm._rules:functions()
    assert.is_table(fns)
    assert.equal(fns, mm._rules:functions())            -- the table itself, not a copy
    assert.equal(mm._rules, core.lstring_rules(mm:derive(2)))
    assert.is_nil(core.lstring_rules(lsys.lstring("F")))  -- made without rules
    local view = { angle = 30 }
    local o = core.scene_options(mm:interpret(nil, view))
    assert.is_table(o)
    assert.equal(30, o.angle)
  end)

  it("checks the type, and the rules' liveness", function ()
    local s, sc = m:derive(1), m:interpret()
    -- (the function's name in the message depends on how it is called)
    local function argerr (f, x) return (errof(f, x):gsub(" to '[^']*' ", " to F ")) end
    assert.equal("bad argument #1 to F (lsys.Lstring expected, got lsys.Scene)",
                 argerr(core.lstring_rules, sc))
    assert.equal("bad argument #1 to F (lsys.Scene expected, got lsys.Lstring)",
                 argerr(core.scene_options, s))
    assert.equal("bad argument #1 to F (lsys.Rules expected, got lsys.Lstring)",
                 argerr(m._rules.functions, s))
    local r = core.rules()
    close(r)
    assert.has_error(function () r:functions() end, "the model's rules were closed")
    -- a closed Lstring or Scene still names its rules and options (only the user values are
    -- read, which a close leaves): the messages of their use name the model
    close(s); close(sc)
    assert.equal(m._rules, core.lstring_rules(s))
    assert.is_table(core.scene_options(sc))
  end)
end)
