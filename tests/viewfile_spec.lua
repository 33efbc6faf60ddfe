-- View options that name files (contours, surfaces, textures, palette files) and cpfg
-- view files (.v), colour maps (.map) and material files (.mat): cpfg guide, Appendix B,
-- docs/drawing.md §2. The reader is fuzzed by tests/fuzz/lua/fuzz.lua (target view;
-- tests/fuzzlua_spec.lua).
local H = require "tests.helper"
local view = require "lsys.view"
local lsys = require "lsys"
local core = require "lsys.core"

local DATA = "tests/data/views"

local function parse (text) return view.parse(text, "x.v", { quiet = true }) end

-- The message `fn` raises (luassert's has_error would drop a leading "file:line: ").
local function errmsg (fn, ...)
  local ok, err = pcall(fn, ...)
  assert(not ok, "no error raised")
  return err
end

local function assert_error (fn, msg) assert.equal(msg, errmsg(fn)) end

-- A fresh temporary directory, removed by the returned function.
local function tempdir ()
  local d = os.tmpname()
  os.remove(d)
  assert(os.execute("mkdir -p '" .. d .. "'"))
  return d, function () os.execute("rm -rf '" .. d .. "'") end
end

local function write (path, bytes)
  local f = assert(io.open(path, "wb"))
  f:write(bytes)
  f:close()
end

local function copy (from, to)
  local f = assert(io.open(from, "rb"))
  write(to, f:read("a"))
  f:close()
end

-- busted's `pending` when lsys.core lacks `fn` (a build without that part).
local function needs (fn)
  if core[fn] == nil then
    pending("lsys.core." .. fn .. " is not in this build")
    return false
  end
  return true
end

describe("view files", function ()
  it("load every supported command into the view table", function ()
    local v, warnings = view.load(DATA .. "/plant.v", { quiet = true })
    assert.same({
      dir = DATA,
      angle = 22.5, color = 2, color_increment = 3,
      line_width = 0.5, line_style = "cylinder", width_increment = 0.1,
      viewpoint = { 0, 10, 30 }, target = { 0, 5, 0 }, twist = 15.0,
      projection = "perspective", fov = 40, light = { 1, 2, 3 },
      background = { 0.1, 0.2, 0.3 },
      contours = { [1] = "leaf.con", [2] = "sub/stem.con" },
      contour_sides = 12, minimize_twist = false,
      textures = {
        { file = "bark.png", mag = "linear", min = "near", mode = "decal", per_surface = false },
        { file = "leaf.png", mag = "near", min = "linear", mode = "modulate", per_surface = true },
      },
      tropisms = {
        { vector = { 0, -1, 0 }, angle = 30, elasticity = 0.2, increment = 0.05 },
        { vector = { 0, 1, 0 }, elasticity = 0.1, increment = 0, torque = true },
        { vector = { 1, 0, 0 }, angle = 0, elasticity = 0, increment = 0 },
      },
      surfaces = {
        P = { file = "petal.s", scale = 2.5 },
        L = { file = "leaf.s", scale = 1, precision = { 8, 4 }, texture = 2 },
      },
    }, v)
    assert.same({
      DATA .. "/plant.v:28: 'z buffer' is not supported; ignored",
      DATA .. "/plant.v:29: 'front distance' is not supported; ignored",
      DATA .. "/plant.v:30: 'render mode' is not supported; ignored",
    }, warnings)
  end)

  it("read older commands: angle increment, pixel lines, lights, the single tropism", function ()
    local v, warnings = view.load(DATA .. "/legacy.v", { quiet = true })
    assert.same({
      dir = DATA, angle = 22.5, color = 3, line_width = 2, line_style = "line",
      contour_sides = 16, light = { 5, 3, 1 },
      lights = { { direction = { 5, 3, 1 }, diffuse = { 1.3, 1.5, 1.3 } },
                 { direction = { -1, -1, 0 } } },
      old_tropism = { vector = { 0, -2, 0 }, elasticity = 0.05, increment = 0.01 },
      surfaces = { c = { file = "calyx.s", scale = 2.0 } },
    }, v)
    assert.same({
      DATA .. "/legacy.v:4: 'initial color': a second (back) colour is not supported; ignored",
    }, warnings)
  end)

  it("give a view that normalize accepts once the files are left out", function ()
    local v = view.load(DATA .. "/plant.v", { quiet = true })
    v.contours, v.surfaces, v.textures = nil, nil, nil
    local n = view.normalize(v, "plant")
    assert.equal(22.5, n.angle)
    assert.equal(3, #n.tropisms)
    assert.is_true(n.tropisms[2].torque)
    assert.is_false(n.minimize_twist)
  end)

  it("apply commands in file order, later ones winning", function ()
    local v = parse("angle factor: 8\nangle increment: 30\ninitial line width: 2 pixels\n" ..
                    "line style: polygon\ncontour sides: 5\npolygonization level: 2\n")
    assert.same({ angle = 30, line_width = 2, line_style = "polygon", contour_sides = 8 }, v)
    v = parse("line style: cylinder\ninitial line width: 3\n")
    assert.same({ line_width = 3, line_style = "polygon" }, v)   -- no unit: polygons
    assert.same({ line_style = "line" }, parse("line style: 1"))  -- cpfg's digits 1..3
    -- cpfg reads only the unit's first letter: p pixels, s cylinders, else polygons
    assert.same({ line_width = 0.1, line_style = "cylinder" }, parse("initial line width: 0.1 s"))
    assert.same({ line_width = 2, line_style = "line" }, parse("initial line width: 2 pnts"))
    local iv, iw = parse("initial line width: 1 inches")
    assert.same({ line_width = 1, line_style = "polygon" }, iv)
    assert.same({ "x.v:1: 'initial line width': unknown unit 'inches' read as polygons "
                  .. "(as cpfg does)" }, iw)
  end)

  it("strip /* */ and // comments, keeping line numbers", function ()
    local v = parse("/* a\n   b */ angle factor: 4 /* c */\n// angle factor: 5\n" ..
                    "contour: 1 /* x */ a.con // y\n")
    assert.same({ angle = 90, contours = { "a.con" } }, v)
    assert.equal("x.v:4: unknown view command 'foo'", errmsg(parse, "/* a\n*/\n\nfoo: 1"))
  end)

  it("name file and line for an unknown command", function ()
    assert.equal("x.v:2: unknown view command 'step size'",
                 errmsg(parse, "angle factor: 3\nstep size: 2\n"))
    assert.equal("x.v:1: unknown view command 'angle'", errmsg(parse, "angle: 3"))
    assert.equal("x.v:1: 'angle factor' expects one number, got '3: 4'",
                 errmsg(parse, "angle factor:3: 4"))
  end)

  it("warn once per unsupported command, through warn() unless quiet", function ()
    local text = {}
    for _, k in ipairs { "z buffer: on", "cue range: 2", "shade mode: 3", "font: x",
                         "window size: 500 500", "bounding box: x: 0,1", "render mode: shaded" } do
      text[#text + 1] = k
    end
    local v, w = parse(table.concat(text, "\n"))
    assert.same({}, v)
    assert.equal(7, #w)
    assert.equal("x.v:5: 'window size' is not supported; ignored", w[5])
    for k in pairs(view.VIEWFILE_IGNORED) do                       -- every one of them
      local _, ws = parse(k .. ": 1")
      assert.equal(("x.v:1: '%s' is not supported; ignored"):format(k), ws[1])
    end
    -- Lua's warn(): the lsys program turns it on, as `lua -W` does
    -- once per kind in a process (a viewer reloading its model says it once); the list
    -- each parse returns has them all
    local out, code = H.lsys('local view = require "lsys.view"\n' ..
      'view.parse("z buffer: on\\nangle factor: 4\\n", "y.v")\n' ..
      'view.parse("z buffer: on\\n", "q.v", { quiet = true })\n' ..
      'local _, w = view.parse("z buffer: on\\ncue range: 1\\n", "r.v")\n' ..
      'print(#w)\n')
    assert.equal(0, code, out)
    assert.equal("Lua warning: y.v:1: 'z buffer' is not supported; ignored\n"
                 .. "Lua warning: r.v:2: 'cue range' is not supported; ignored\n2\n", out)
  end)

  it("ignore what cpfg ignores: an unknown line style, a '?' left for a value", function ()
    -- cpfg keeps the line style it had ("wireframe" in vlab's 07-Open models) and says
    -- "Invalid parameters for angle increment:" for vlab's exercise "angle increment: ?"
    local v, w = parse("line style: cylinder\nline style: wireframe\nangle increment: ?\n" ..
                       "viewpoint: 0,?,1\ninitial color: 3\n")
    assert.same({ line_style = "cylinder", color = 3 }, v)
    assert.same({
      "x.v:2: 'line style' must be pixel, polygon or cylinder, got 'wireframe'; ignored",
      "x.v:3: 'angle increment': '?' is not a value; the line is ignored",
      "x.v:4: 'viewpoint': '?' is not a value; the line is ignored",
    }, w)
  end)

  it("skip as cpfg skips a surface line without its name, an old texture line", function ()
    -- cpfg reads `surface: petal.s 1 4 6` as the name 'p' and the file "etal.s", and a
    -- texture line whose first word is no field fails (vlab's VlabTools/Lychnis)
    local v, w = parse("surface: petal.s 1 4 6\ntexture: leafs.png\ninitial color: 2\n")
    assert.same({ color = 2 }, v)
    assert.same({
      "x.v:1: 'surface': no name before the file 'petal.s': cpfg reads the name 'p' and the "
        .. "file 'etal.s', which does not exist, and skips the line",
      "x.v:2: 'texture': 'leafs.png' is not a field (F: file, H, L, E, S, R): cpfg skips "
        .. "the line",
    }, w)
    local dir = os.tmpname()
    os.remove(dir)
    os.execute("mkdir -p " .. dir)
    local f = io.open(dir .. "/etal.s", "w")
    f:write("x")
    f:close()
    local v2 = view.parse("surface: petal.s 1 4 6\n", "x.v", { dir = dir, quiet = true })
    assert.same({ p = { file = "etal.s", scale = 1, precision = { 4, 6 } } }, v2.surfaces)
    os.execute("rm -rf " .. dir)
  end)

  it("reject malformed values with file and line", function ()
    local cases = {
      { "angle factor: abc", "x.v:1: 'angle factor': 'abc' is not a number" },
      { "angle factor: 0", "x.v:1: 'angle factor' must not be 0" },
      { "angle increment: 1 2", "x.v:1: 'angle increment' expects one number, got '1 2'" },
      { "\n\nviewpoint: 1,2", "x.v:3: 'viewpoint' expects three numbers x,y,z, got '1,2'" },
      { "viewpoint: 1,2,x", "x.v:1: 'viewpoint': 'x' is not a number" },
      { "viewpoint: 1,2,1e999", "x.v:1: 'viewpoint': '1e999' is not a number" },
      { "view reference point: nan,0,0", "x.v:1: 'view reference point': 'nan' is not a number" },
      { "initial color: 1.5",
        "x.v:1: 'initial color': '1.5' is not a whole number from 0 to 65535" },
      { "initial color: 70000",
        "x.v:1: 'initial color': '70000' is not a whole number from 0 to 65535" },
      { "color increment: 1 2 3",
        "x.v:1: 'color increment' expects an increment (and a back increment), got '1 2 3'" },
      { "initial line width: -1", "x.v:1: 'initial line width' must not be negative" },
      { "projection: oblique",
        "x.v:1: 'projection' must be parallel or perspective, got 'oblique'" },
      { "viewing angle: 180", "x.v:1: 'viewing angle' must be between 0 and 180 degrees" },
      { "light direction: 0,0,0", "x.v:1: 'light direction': the vector is zero" },
      { "light: V: 1 2", "x.v:1: 'light': 'V:' needs 3 numbers" },
      { "light: X: 1", "x.v:1: 'light': unknown field 'X' (known: V, O, A, D, S, P, T)" },
      { "contour: 0 a.con", "x.v:1: 'contour': id 0 is the built-in circle; use ids from 1" },
      { "contour: a.con", "x.v:1: 'contour' expects an id and a file, got 'a.con'" },
      { "contour: 1 a.con\ncontour: 1 b.con", "x.v:2: 'contour': id 1 is already defined" },
      { "contour sides: 2", "x.v:1: 'contour sides': '2' is not a whole number from 3 to 1024" },
      { "polygonization level: 10",
        "x.v:1: 'polygonization level': '10' is not a whole number from 0 to 9" },
      { "twist of cylinders: maybe", "x.v:1: 'twist of cylinders' expects on or off, got 'maybe'" },
      { "texture: H: l", "x.v:1: 'texture' needs the image file F:" },
      { "texture: F: a.png H: x", "x.v:1: 'texture': H: must be l(inear) or n(ear), got 'x'" },
      { "texture: F: a.png E: q", "x.v:1: 'texture': E: must be m(odulate) or d(ecal), got 'q'" },
      { "texture: F:", "x.v:1: 'texture': 'F:' needs a value" },
      { "tropism: A: 10", "x.v:1: 'tropism' needs the vector T: x y z" },
      { "tropism: T: 0 0 0", "x.v:1: 'tropism': the vector is zero" },
      { "tropism: T: 1 2", "x.v:1: 'tropism': 'T:' needs 3 numbers" },
      { "tropism: T: 0 1 0 A: x", "x.v:1: 'tropism': 'A:' needs 1 number" },
      { "torque: T: 0 1 0 Q: 1", "x.v:1: 'torque': unknown field 'Q' (known: T, E, S)" },
      { "surface: PQ p.s 1", "x.v:1: 'surface': the name must be one character, got 'PQ'" },
      { "surface: P p.s",
        "x.v:1: 'surface' expects a name, a file, a scale, [s t] and [a texture], got 'P p.s'" },
      { "surface: P p.s 0", "x.v:1: 'surface': the scale must be > 0" },
      { "surface: P p.s 1 4 0",
        "x.v:1: 'surface': the precisions s t must both be 1..64 (or both 0: the file's)" },
      { "surface: P p.s 1 65 4", "x.v:1: 'surface': '65' is not a whole number from 0 to 64" },
      { "surface: P p.s 1\nsurface: P q.s 1", "x.v:2: 'surface': 'P' is already defined" },
      { "texture: F: a.png\nsurface: P p.s 1 2",
        "x.v:2: 'surface': texture 2, but the file defines 1 texture" },
      { "tropism direction: 0,0,0", "x.v:1: 'tropism direction': the vector is zero" },
      { "no colon here", "x.v:1: expected 'command: values', got 'no colon here'" },
      { "#define W 2",
        "x.v:1: preprocessor line '#define W 2' is not supported "
        .. "(expand the file with cpp first)" },
      { "angle factor: 2\n/* open\n\n", "x.v:2: the comment that starts here is not closed" },
      { ("tropism: T: 0 1 0\n"):rep(17), "x.v:17: more than 16 tropisms and torques" },
    }
    for _, c in ipairs(cases) do
      local ok, err = pcall(parse, c[1])
      assert.is_false(ok, c[1])
      assert.equal(c[2], err)
    end
  end)

  it("fit a parallel view to the model as cpfg does, keeping only its direction", function ()
    -- cpfg fits a parallel window to the model's box: the points give only the direction
    local v = parse("viewpoint: 0,0,10\nview reference point: 5,2,0\n")
    assert.same({ 5, 2, -10 }, v.direction)
    assert.is_nil(v.viewpoint) assert.is_nil(v.target)
    v = parse("projection: parallel\nview reference point: 1,2,3\n")   -- viewpoint 0,0,1
    assert.same({ 1, 2, 2 }, v.direction)
    -- a perspective view keeps both points, in any order of the commands
    v = parse("viewpoint: 0,0,10\nview reference point: 5,2,0\nprojection: perspective\n")
    assert.same({ 0, 0, 10 }, v.viewpoint) assert.same({ 5, 2, 0 }, v.target)
    assert.is_nil(v.direction)
  end)

  it("read twist of cylinders as cpfg draws it: on turns contours with the rolls", function ()
    -- cpfg's gen_cyl_twist: "on" spreads the turtle's roll at each @Gc along the strips
    -- (lsys's minimize_twist = false); "off", the default, carries the contour untwisted
    assert.is_false(parse("twist of cylinders: on\n").minimize_twist)
    assert.is_true(parse("twist of cylinders: off\n").minimize_twist)
    assert.is_nil(parse("angle increment: 10\n").minimize_twist)
  end)

  it("read cpfg's abbreviations and optional texture, tropism and torque fields", function ()
    local v, w = parse("texture: F: a.png H: linear L: mipmap E: b R: 2\n" ..
                       "texture: F: b.png E: decal\n" ..
                       "tropism: T: 1,0,0 I: 0.5\ntorque: T: 0 0 1 A: 10 S: 0.5\n" ..
                       "surface: A a.s 2 2\nsurface: B b.s 1 0 0 -1\nsurface: C c.s 1 2 3 1\n")
    assert.same({
      textures = {
        { file = "a.png", mag = "linear", min = "linear", mode = "modulate", per_surface = false },
        { file = "b.png", mag = "near", min = "near", mode = "decal", per_surface = false },
      },
      tropisms = {
        { vector = { 1, 0, 0 }, angle = 0, elasticity = 0, increment = 0, intensity = 0.5 },
        { vector = { 0, 0, 1 }, elasticity = 0, increment = 0.5, torque = true },
      },
      surfaces = {
        A = { file = "a.s", scale = 2, texture = 2 },       -- one number after the scale: a texture
        B = { file = "b.s", scale = 1 },                     -- 0 0: the file's precision; -1: none
        C = { file = "c.s", scale = 1, precision = { 2, 3 }, texture = 1 },
      },
    }, v)
    assert.same({
      "x.v:1: 'texture': mipmaps (L: mipmap) are not supported; linear used",
      "x.v:1: 'texture': E: blend is not supported; modulate used",
      "x.v:1: 'texture': R: (the texture's aspect on cylinders) is not supported; ignored",
      "x.v:4: 'torque': a torque has no angle; A: ignored",
    }, w)
  end)

  it("set dir to the file's directory and name missing files", function ()
    local d, clean = tempdir()
    write(d .. "/a.v", "angle factor: 4\n")
    local v = view.load(d .. "/a.v")
    clean()
    assert.same({ dir = d, angle = 90 }, v)
    assert.same({ dir = "sub", angle = 90 }, (view.parse("angle factor: 4", "sub/a.v",
                                                         { dir = "sub" })))
    assert_error(function () view.load(DATA .. "/missing.v") end, "lsys.view.load: cannot open '"
                 .. DATA .. "/missing.v': No such file or directory")
  end)

  it("is lsys.view, with load", function ()
    assert.equal(view, lsys.view)
    assert.equal("function", type(lsys.view.load))
  end)
end)

describe("colour maps and material files", function ()
  local d, clean
  before_each(function () d, clean = tempdir() end)
  after_each(function () clean() end)

  local function colormap ()
    local b = {}
    for i = 0, 255 do b[#b + 1] = string.pack("BBB", i, 255 - i, (i * 7) % 256) end
    return table.concat(b)
  end

  it("read a .map as 256 RGB byte triples, indices 0..255", function ()
    write(d .. "/c.map", colormap())
    local p = view.load_colormap(d .. "/c.map")
    assert.near({ 0, 1, 0 }, p[0], 1e-12)
    assert.near({ 1 / 255, 254 / 255, 7 / 255 }, p[1], 1e-12)
    assert.near({ 1, 0, (255 * 7 % 256) / 255 }, p[255], 1e-12)
    assert.is_nil(p[256])
    local n = 0
    for _ in pairs(p) do n = n + 1 end
    assert.equal(256, n)
  end)

  it("reject a .map that is not 768 bytes, naming the file", function ()
    write(d .. "/short.map", colormap():sub(1, 767))
    assert_error(function () view.load_colormap(d .. "/short.map") end,
                     d .. "/short.map: a colour map is 768 bytes (256 colours of 3 bytes), not 767")
    assert_error(function () view.load_colormap(d .. "/none.map") end,
                     "cannot open '" .. d .. "/none.map': No such file or directory")
  end)

  local function record (idx, tr, amb, dif, emi, spe, sh)
    return string.pack("BB", idx, tr) .. string.pack("BBB", table.unpack(amb))
      .. string.pack("BBB", table.unpack(dif)) .. string.pack("BBB", table.unpack(emi))
      .. string.pack("BBB", table.unpack(spe)) .. string.pack("B", sh)
  end

  it("read a .mat as 15-byte records, filling gaps with cpfg's default", function ()
    write(d .. "/m.mat", record(1, 0, { 51, 0, 0 }, { 255, 102, 0 }, { 0, 0, 0 },
                                { 255, 255, 255 }, 64)
                      .. record(3, 51, { 0, 0, 0 }, { 0, 0, 255 }, { 0, 51, 0 }, { 0, 0, 0 }, 0))
    local p = view.load_materials(d .. "/m.mat")
    assert.same({ 0, 1, 2, 3 }, (function ()
      local k = {}
      for i in pairs(p) do k[#k + 1] = i end
      table.sort(k)
      return k
    end)())
    assert.near({ 0.2, 0, 0 }, p[1].ambient, 1e-12)
    assert.near({ 1, 0.4, 0 }, p[1].diffuse, 1e-12)
    assert.near({ 0, 0, 0 }, p[1].emission, 1e-12)
    assert.near({ 1, 1, 1 }, p[1].specular, 1e-12)
    assert.equal(64, p[1].shininess)
    assert.near({ 0, 0, 1, 0.8 }, p[3].diffuse, 1e-12)      -- transparency 51: alpha 0.8
    assert.near({ 0, 0.2, 0, 0.8 }, p[3].emission, 1e-12)
    local default = { ambient = { 0, 0, 0 }, diffuse = { 1, 1, 1 }, emission = { 0, 0, 0 },
                      specular = { 0, 0, 0 }, shininess = 0 }
    assert.same(default, p[0])
    assert.same(default, p[2])
  end)

  it("reject a .mat of the wrong size or with shininess above 128", function ()
    write(d .. "/odd.mat", string.rep("\0", 16))
    assert_error(function () view.load_materials(d .. "/odd.mat") end,
                     d .. "/odd.mat: a material file is a sequence of 15-byte records; "
                     .. "16 bytes is not")
    write(d .. "/empty.mat", "")
    assert_error(function () view.load_materials(d .. "/empty.mat") end,
                     d .. "/empty.mat: a material file is a sequence of 15-byte records; "
                     .. "0 bytes is not")
    write(d .. "/shiny.mat", record(0, 0, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, 0)
                          .. record(7, 0, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, 200))
    assert_error(function () view.load_materials(d .. "/shiny.mat") end,
                     d .. "/shiny.mat: record 2 (material 7): shininess 200 is above 128")
  end)

  it("can be the palette of a view, relative to its dir", function ()
    write(d .. "/c.map", colormap())
    write(d .. "/m.mat", record(2, 0, { 0, 0, 0 }, { 0, 255, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, 10))
    local v = view.normalize({ dir = d, palette = "c.map" }, "model")
    assert.near({ 1 / 255, 254 / 255, 7 / 255 }, v.palette[1].diffuse, 1e-12)
    assert.near({ 0, 1, 0 }, v.palette[0].diffuse, 1e-12)
    assert.equal(255, #v.palette)
    v = view.normalize({ dir = d, palette = "m.mat" }, "model")
    assert.near({ 0, 1, 0 }, v.palette[2].diffuse, 1e-12)
    assert.equal(10, v.palette[2].shininess)
    assert.same({ 1, 1, 1 }, v.palette[1].diffuse)
    assert_error(function () view.normalize({ dir = d, palette = "p.txt" }, "model") end,
                     "model: 'view.palette': a palette file must be a colour map (.map) or "
                     .. "materials (.mat), got 'p.txt'")
    assert_error(function () view.normalize({ dir = d, palette = "no.map" }, "model") end,
                     "model: view.palette: cannot open '" .. d .. "/no.map': "
                     .. "No such file or directory")
  end)
end)

describe("view options naming files", function ()
  it("check contour ids, surface names, texture lists and their fields", function ()
    local cases = {
      { { contours = { [0] = "a.con" } },
        "m: 'view.contours': contour 0 is the built-in circle; use ids >= 1" },
      { { contours = { a = "a.con" } },
        "m: 'view.contours': keys must be contour ids, integers >= 1" },
      { { contours = { [-1] = "a.con" } },
        "m: 'view.contours': keys must be contour ids, integers >= 1" },
      { { contours = "a.con" },
        "m: 'view.contours' must be a table { [id] = file or { points = ... } }" },
      { { contours = { 42 } },
        "m: view.contours[1] must be a file name or { points = ..., closed = }" },
      { { contours = { { points = {}, open = true } } },
        "m: view.contours[1]: unknown field 'open' (known: points, closed)" },
      { { contours = { { closed = true } } }, "m: view.contours[1]: 'points' must be a list" },
      { { contours = { { points = {}, closed = 1 } } },
        "m: view.contours[1]: 'closed' must be a boolean" },
      { { surfaces = { PQ = "p.s" } },
        "m: 'view.surfaces': keys must be single characters (the name after ~), got 'PQ'" },
      { { surfaces = { [1] = "p.s" } },
        "m: 'view.surfaces': keys must be single characters (the name after ~), got '1'" },
      { { surfaces = { P = 3 } },
        "m: view.surfaces.P must be a file name or { file = ..., scale = ... }" },
      { { surfaces = { P = { scale = 2 } } }, "m: view.surfaces.P: a 'file' is needed" },
      { { surfaces = { P = { file = "p.s", size = 2 } } },
        "m: view.surfaces.P: unknown field 'size' (known: file, scale, texture, precision)" },
      { { surfaces = { P = { surface = {} } } },
        "m: view.surfaces.P: 'surface' must be an lsys.Surface" },
      { { textures = "a.png" }, "m: 'view.textures' must be a list" },
      { { textures = { x = "a.png" } },
        "m: 'view.textures' must be a list (indices 1..0), not key 'x'" },
      { { textures = { 7 } },
        "m: view.textures[1] must be a file name or { file = ..., mag = ... }" },
      { { textures = { { file = "a.png", mag = "cubic" } } },
        "m: view.textures[1]: 'mag' must be \"linear\" or \"near\"" },
      { { textures = { { file = "a.png", min = 1 } } },
        "m: view.textures[1]: 'min' must be \"linear\" or \"near\"" },
      { { textures = { { file = "a.png", mode = "blend" } } },
        "m: view.textures[1]: 'mode' must be \"modulate\" or \"decal\"" },
      { { textures = { { file = "a.png", per_surface = 1 } } },
        "m: view.textures[1]: 'per_surface' must be a boolean" },
      { { textures = { { file = "a.png", wrap = true } } },
        "m: view.textures[1]: unknown field 'wrap' "
        .. "(known: file, mag, min, mode, per_surface, intensity)" },
      { { textures = { { mag = "l" } } }, "m: view.textures[1]: a file name expected, got nil" },
      { { minimize_twist = "yes" }, "m: 'view.minimize_twist' must be true or false" },
      { { dir = 3 }, "m: 'view.dir' must be a string" },
    }
    for _, c in ipairs(cases) do
      local ok, err = pcall(view.normalize, c[1], "m")
      assert.is_false(ok)
      assert.equal(c[2], err)
    end
  end)

  it("name the option and the file when a file is missing", function ()
    assert_error(function ()
      view.normalize({ dir = DATA, contours = { [2] = "nope.con" } }, "model")
    end, "model: view.contours[2]: cannot open '" .. DATA .. "/nope.con': "
         .. "No such file or directory (looked for in '" .. DATA .. "' (view.dir: the model's "
         .. "folder unless set), then in the current folder)")
    assert_error(function ()
      view.normalize({ surfaces = { P = DATA .. "/nope.s" } }, "model")
    end, "model: view.surfaces.P: cannot open '" .. DATA .. "/nope.s': No such file or directory"
         .. " (looked for in the current folder; view.dir names another)")
    assert_error(function ()
      view.normalize({ dir = DATA .. "/", textures = { "x/nope.png" } }, "model")
    end, "model: view.textures[1]: cannot open '" .. DATA .. "/x/nope.png': "
         .. "No such file or directory (looked for in '" .. DATA .. "/' (view.dir: the model's "
         .. "folder unless set), then in the current folder)")
    assert_error(function ()
      view.normalize({ dir = DATA, contours = { "sub" } }, "model")
    end, "model: view.contours[1]: cannot read '" .. DATA .. "/sub': Is a directory")
  end)

  it("default to no files and minimize_twist = true, and pass them to turtle and renderer",
  function ()
    local v = view.normalize({}, "m")
    assert.same({}, v.contours)
    assert.same({}, v.surfaces)
    assert.same({}, v.textures)
    assert.is_true(v.minimize_twist)
    local t = view.turtle_options(v)
    assert.equal(v.contours, t.contours)
    assert.equal(v.surfaces, t.surfaces)
    assert.equal(v.textures, t.textures)
    assert.is_true(t.minimize_twist)
    assert.is_false(view.turtle_options(view.normalize({ minimize_twist = false })).minimize_twist)
    assert.is_nil(view.render_options(v).textures)                        -- none: left out
    local tv = { textures = { "a" } }
    assert.equal(tv.textures, view.render_options(tv).textures)
  end)

  it("load the contours, surfaces and textures of a view file", function ()
    if not (needs "contour_load" and needs "surface_load" and needs "texture_load") then return end
    local v = view.normalize(view.load(DATA .. "/plant.v", { quiet = true }), "plant")
    assert.equal("lsys.Contour", getmetatable(v.contours[1]).__name)
    assert.equal(6, v.contours[1]:size())
    assert.equal(4, v.contours[2]:size())                  -- sub/stem.con, from the .v's dir
    assert.equal(3, v.contours[2]:dim())
    assert.equal("lsys.Texture", getmetatable(v.textures[1]).__name)
    assert.same({ 2, 2 }, { v.textures[1]:size() })
    assert.same({ 4, 2 }, { v.textures[2]:size() })
    local i1, i2 = v.textures[1]:info(), v.textures[2]:info()
    assert.same({ "linear", "near", "decal", false }, { i1.mag, i1.min, i1.mode, i1.per_surface })
    assert.same({ "near", "linear", "modulate", true }, { i2.mag, i2.min, i2.mode, i2.per_surface })
    local P, L = v.surfaces.P, v.surfaces.L
    assert.equal("lsys.Surface", getmetatable(P.surface).__name)
    assert.same({ 2.5, 0, 6, 3 }, { P.scale, P.texture, P.s, P.t })  -- petal.s: PRECISION 6 3
    assert.same({ 1, 2, 8, 4 }, { L.scale, L.texture, L.s, L.t })
    local lp = L.surface:info().precision                   -- leaf.s: the reader's default
    local n = view.normalize({ dir = DATA, surfaces = { L = "leaf.s" } })
    assert.same({ math.min(lp[1], 64), math.min(lp[2], 64) }, { n.surfaces.L.s, n.surfaces.L.t })
  end)

  it("make contours from points", function ()
    if not needs "contour" then return end
    local v = view.normalize({ contours = {
      [3] = { points = { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } } },
      [4] = { points = { { 0, 0, 0 }, { 0, 0, 0 }, { 1, 1, 0 }, { 2, 0, 0 }, { 2, 0, 0 } },
              closed = false },
    } }, "m")
    assert.is_true(v.contours[3]:closed())
    assert.equal(4, v.contours[3]:size())
    assert.is_false(v.contours[4]:closed())
    assert.equal(3, v.contours[4]:dim())
    local ok, err = pcall(view.normalize, { contours = { [5] = { points = { { 1, 0 } } } } }, "m")
    assert.is_false(ok)
    assert.matches("^m: view%.contours%[5%]: a closed contour needs at least 3 points", err)
  end)

  it("keep a parsed file while it is unchanged and read it again when it changes", function ()
    if not needs "contour_load" then return end
    local d, clean = tempdir()
    copy(DATA .. "/leaf.con", d .. "/c.con")
    local a = view.normalize({ dir = d, contours = { "c.con", "c.con" } }, "m").contours
    local b = view.normalize({ dir = d, contours = { [7] = "c.con" } }, "m").contours
    assert.is_true(rawequal(a[1], a[2]))
    assert.is_true(rawequal(a[1], b[7]))
    write(d .. "/c.con", "3 2 closed\n1 0\n0 1\n-1 0\n")
    local c = view.normalize({ dir = d, contours = { "c.con" } }, "m").contours
    assert.is_false(rawequal(a[1], c[1]))
    assert.equal(6, a[1]:size())
    assert.equal(3, c[1]:size())
    write(d .. "/c.con", "3 2 closed\n1 0\n0 1\n")
    local ok, err = pcall(view.normalize, { dir = d, contours = { "c.con" } }, "m")
    clean()
    assert.is_false(ok)
    assert.matches("^m: view%.contours%[1%]: " .. d:gsub("%p", "%%%0") .. "/c%.con:%d+: ", err)
  end)

  it("accept an already normalised view (lsys.render merges into one)", function ()
    if not (needs "contour_load" and needs "surface_load" and needs "texture_load") then return end
    local v = view.normalize(view.load(DATA .. "/plant.v", { quiet = true }), "plant")
    local w = view.normalize(view.merge(v, { supersample = 2 }), "again")
    assert.is_true(rawequal(v.contours[2], w.contours[2]))
    assert.is_true(rawequal(v.textures[1], w.textures[1]))
    assert.is_true(rawequal(v.surfaces.P.surface, w.surfaces.P.surface))
    assert.same({ 2.5, 0, 6, 3 }, { w.surfaces.P.scale, w.surfaces.P.texture, w.surfaces.P.s,
                                   w.surfaces.P.t })
    assert.equal(2, w.supersample)
  end)

  it("check surface texture indices and precision against the view", function ()
    if not (needs "surface_load" and needs "texture_load") then return end
    local ok, err = pcall(view.normalize,
                          { dir = DATA, textures = { "bark.png" },
                            surfaces = { P = { file = "petal.s", texture = 2 } } }, "m")
    assert.is_false(ok)
    assert.equal("m: 'view.surfaces.P': texture 2, but the view has 1 textures", err)
    ok, err = pcall(view.normalize, { dir = DATA, surfaces = { P = { file = "petal.s",
                                                                    precision = { 0, 4 } } } }, "m")
    assert.is_false(ok)
    assert.equal("m: view.surfaces.P: 'precision'[1] must be a whole number from 1 to 64", err)
    local v = view.normalize({ dir = DATA, textures = { "bark.png" },
                               surfaces = { P = { file = "petal.s", texture = 1, scale = 3,
                                                  precision = { 2, 9 } } } }, "m")
    assert.same({ 3, 1, 2, 9 }, { v.surfaces.P.scale, v.surfaces.P.texture, v.surfaces.P.s,
                                 v.surfaces.P.t })
  end)
end)
