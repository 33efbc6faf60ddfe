-- Sketch files: lsys.sketch.read reads JSON and SVG into the normalized sketch
-- and refuses bad files with a message that names the file and the stroke;
-- lsys.sketch.svgpath flattens SVG path data.
local H = require "tests.helper"
local read = require "lsys.sketch.read"
local svgpath = require "lsys.sketch.svgpath"
local have_core = pcall(require, "lsys.core")

local DATA = "tests/data/sketch/"

-- A JSON sketch with the given strokes (a list of Lua-literal JSON texts) and top keys.
local function sketch (strokes, top)
  return '{"width": 400, "height": 300' .. (top or "") .. ', "strokes": ['
         .. table.concat(strokes, ", ") .. "]}"
end
local STEM = '{"role": "stem", "points": [[200, 280], [200, 80]]}'
local INCL = '{"role": "inclination", "points": [[100, 230], [300, 230]]}'

-- fn raises exactly msg (assert.has_error would cut a "file:line: " off the message)
local function raises (fn, msg)
  local ok, err = pcall(fn)
  assert.is_false(ok, "no error; expected: " .. msg)
  assert.equal(msg, err)
end

local function points (stroke)
  local out = {}
  for i, p in ipairs(stroke.points) do out[i] = { p[1], p[2], p[3] } end
  return out
end

local function svg (body, attrs)
  return '<svg xmlns="http://www.w3.org/2000/svg" '
         .. (attrs or 'width="400" height="300"') .. ">" .. body .. "</svg>"
end

describe("lsys.sketch.read.json", function ()
  it("reads a sketch with every key into the normalized form", function ()
    local sk = read.json(H.read(DATA .. "plant.json"), "plant.json")
    assert.equal("plant.json", sk.file)
    assert.equal(400, sk.width)
    assert.equal(300, sk.height)
    assert.equal(3, sk.nodes_per_layer)
    assert.equal("integer", math.type(sk.nodes_per_layer))
    assert.equal("decussate", sk.phyllotaxis)
    assert.same({ near = -50, far = 50 }, sk.depth)
    assert.equal(5, #sk.strokes)
    local s = sk.strokes[1]
    assert.equal("stem", s.role)
    assert.equal(1, s.index)
    assert.equal("main", s.id)
    assert.same({ { 200, 280, 0.5 }, { 201, 180, 0.75 }, { 200, 80, 1 } }, points(s))
    -- pressure 0.5 where the file gives none; no id where the file gives none
    assert.same({ { 110, 270, 0.5 }, { 110, 70, 0.5 } }, points(sk.strokes[2]))
    assert.is_nil(sk.strokes[2].id)
    assert.same({ "stem", "boundary_left", "boundary_right", "inclination", "inclination" },
                { sk.strokes[1].role, sk.strokes[2].role, sk.strokes[3].role,
                  sk.strokes[4].role, sk.strokes[5].role })
    assert.equal(5, sk.strokes[5].index)
    assert.is_nil(sk.warnings)
  end)

  it("gives 5 nodes per layer, distichous phyllotaxis and no depth by default", function ()
    local sk = read.json(sketch { STEM })
    assert.equal("<json>", sk.file)
    assert.equal(5, sk.nodes_per_layer)
    assert.equal("distichous", sk.phyllotaxis)
    assert.is_nil(sk.depth)
  end)

  it("takes null as absent for the optional keys", function ()
    local sk = read.json(sketch({ '{"role": "stem", "id": null, "points": [[0, 0], [0, 1]]}' },
                                ', "depth": null, "phyllotaxis": null'))
    assert.is_nil(sk.strokes[1].id)
    assert.is_nil(sk.depth)
    assert.equal("distichous", sk.phyllotaxis)
  end)

  local function err (text) return function () read.json(text, "plant.json") end end

  it("refuses malformed JSON with cjson's message", function ()
    raises(err('{"width": 400,}'), "plant.json: malformed JSON: Expected object key "
                     .. "string but found T_OBJ_END at character 15")
    -- JSON has no NaN, Infinity or hex numbers
    raises(err(sketch { '{"role": "stem", "points": [[NaN, 0], [0, 1]]}' }),
                     "plant.json: malformed JSON: Expected value but found invalid token at "
                     .. "character 72")
  end)

  it("refuses a top level that is not an object, and unknown keys", function ()
    raises(err("[1, 2]"), "plant.json: a sketch is a JSON object, not an array")
    raises(err("12"), "plant.json: a sketch is a JSON object, not number")
    raises(err("null"), "plant.json: a sketch is a JSON object, not null")
    raises(err(sketch({ STEM }, ', "widht": 3')), "plant.json: unknown key 'widht' "
                     .. "(width, height, nodes_per_layer, phyllotaxis, depth, strokes)")
  end)

  it("checks width, height, nodes_per_layer, phyllotaxis and depth", function ()
    raises(err('{"height": 300, "strokes": []}'),
                     "plant.json: width missing (a number of pixels > 0)")
    raises(err('{"width": 400, "height": -3, "strokes": []}'),
                     "plant.json: height must be a number > 0 and at most 1000000, not -3")
    raises(err('{"width": "400", "height": 3, "strokes": []}'),
                     "plant.json: width must be a number > 0 and at most 1000000, not '400'")
    raises(err(sketch({ STEM }, ', "nodes_per_layer": 2.5')),
                     "plant.json: nodes_per_layer must be an integer from 1 to 10000, not 2.5")
    raises(err(sketch({ STEM }, ', "nodes_per_layer": 0')),
                     "plant.json: nodes_per_layer must be an integer from 1 to 10000, not 0")
    raises(err(sketch({ STEM }, ', "nodes_per_layer": 10001')),
                     "plant.json: nodes_per_layer must be an integer from 1 to 10000, not 10001")
    assert.equal(10000, read.json(sketch({ STEM }, ', "nodes_per_layer": 10000')).nodes_per_layer)
    raises(err(sketch({ STEM }, ', "phyllotaxis": "spiral"')),
                     "plant.json: unknown phyllotaxis 'spiral' (distichous, decussate, fibonacci)")
    raises(err(sketch({ STEM }, ', "depth": {"near": 1}')),
                     "plant.json: depth must be { near = n, far = f } with two finite numbers")
    raises(err(sketch({ STEM }, ', "depth": {"near": 1, "far": 2, "mid": 0}')),
                     "plant.json: depth must be { near = n, far = f } with two finite numbers")
  end)

  it("checks the strokes' roles", function ()
    raises(err('{"width": 1, "height": 1}'),
                     "plant.json: strokes missing (a list of strokes)")
    raises(err(sketch { STEM, '{"role": "stem2", "points": [[0, 0], [1, 1]]}' }),
                     "plant.json: stroke 2: unknown role 'stem2' (stem, boundary_left, "
                     .. "boundary_right, inclination)")
    raises(err(sketch { '{"points": [[0, 0], [1, 1]]}' }),
                     "plant.json: stroke 1: no role (stem, boundary_left, boundary_right, "
                     .. "inclination)")
    raises(err(sketch { "[1, 2]" }),
                     "plant.json: stroke 1: a stroke is an object with a role and points")
    raises(err(sketch { '{"role": "stem", "pts": [[0, 0], [1, 1]]}' }),
                     "plant.json: stroke 1 (stem): unknown key 'pts' (role, points, id)")
    raises(err(sketch { '{"role": "stem", "id": 3, "points": [[0, 0], [1, 1]]}' }),
                     "plant.json: stroke 1 (stem): id must be a string, not number")
  end)

  it("wants exactly one stem and at most one boundary per side", function ()
    raises(err(sketch { INCL }), "plant.json: no stem stroke")
    raises(err(sketch {}), "plant.json: no stem stroke")
    raises(err(sketch { STEM, INCL, INCL, STEM }),
                     "plant.json: two stem strokes (1 and 4)")
    local left = '{"role": "boundary_left", "points": [[0, 0], [0, 1]]}'
    raises(err(sketch { left, STEM, left }),
                     "plant.json: two boundary_left strokes (1 and 3)")
    local right = '{"role": "boundary_right", "points": [[0, 0], [0, 1]]}'
    raises(err(sketch { STEM, right, right }),
                     "plant.json: two boundary_right strokes (2 and 3)")
    -- any number of inclination lines
    assert.equal(4, #read.json(sketch { STEM, INCL, INCL, INCL }).strokes)
  end)

  it("checks every point", function ()
    local function pts (p)
      return sketch { STEM, (STEM:gsub("stem", "inclination"):gsub("%[%[.*%]%]", p)) }
    end
    raises(err(pts "[[1, 2]]"), "plant.json: stroke 2 (inclination): fewer than two points")
    raises(err(pts "[]"), "plant.json: stroke 2 (inclination): fewer than two points")
    raises(err(pts "{}"), "plant.json: stroke 2 (inclination): fewer than two points")
    raises(err(pts '{"a": 1}'), "plant.json: stroke 2 (inclination): points must be "
                     .. "a list of [x, y] or [x, y, pressure]")
    raises(err(pts "[[1, 2], [3]]"), "plant.json: stroke 2 (inclination): point 2 is "
                     .. "not [x, y] or [x, y, pressure]")
    raises(err(pts "[[1, 2], [3, 4, 0.5, 1]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 2 is not [x, y] or [x, y, pressure]")
    raises(err(pts '[[1, 2], [3, "4"]]'), "plant.json: stroke 2 (inclination): "
                     .. "point 2: y is not a number (string)")
    raises(err(pts "[[1, 2], [3, null]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 2: y is not a number (null)")
    -- cjson reads a number too large for a double as inf
    raises(err(pts "[[1e999, 2], [3, 4]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 1: x is not finite (inf)")
    raises(err(pts "[[1, 2], [3, 4, 1.5]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 2: pressure 1.5 outside [0, 1]")
    raises(err(pts "[[1, 2], [3, 4, -0.25]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 2: pressure -0.25 outside [0, 1]")
    raises(err(pts "[[1, 2], [3, 2e7]]"), "plant.json: stroke 2 (inclination): "
                     .. "point 2: (3, 20000000) is beyond 10000000 pixels")
    -- pressure 0 and 1 are in range
    local sk = read.json(pts "[[1, 2, 0], [3, 4, 1]]")
    assert.same({ { 1, 2, 0 }, { 3, 4, 1 } }, points(sk.strokes[2]))
  end)

  it("limits the points of a stroke and the strokes of a sketch", function ()
    local many = {}
    for i = 1, read.MAX_POINTS + 1 do many[i] = "[0, " .. i .. "]" end
    local text = sketch { STEM, '{"role": "inclination", "points": [' .. table.concat(many, ",")
                          .. "]}" }
    raises(err(text), "plant.json: stroke 2 (inclination): more than 100000 points "
                     .. "(100001)")
    local strokes = { STEM }
    for i = 2, read.MAX_STROKES + 1 do strokes[i] = INCL end
    raises(err(sketch(strokes)), "plant.json: more than 1000 strokes (1001)")
  end)

  it("refuses a name that is not a string and text that is not a string", function ()
    assert.has_error(function () read.json(12) end, "lsys.sketch.read.json: a string expected")
    assert.has_error(function () read.table({}, 12) end,
                     "lsys.sketch.read.table: the name must be a string")
  end)
end)

describe("lsys.sketch.read.table", function ()
  local function t ()
    return { width = 10, height = 20, strokes = {
      { role = "stem", points = { { 1, 2 }, { 3, 4, 0.25 } } } } }
  end

  it("checks a Lua table as a JSON text and copies it", function ()
    local src = t()
    local sk = read.table(src)
    assert.equal("<table>", sk.file)
    assert.same({ { 1, 2, 0.5 }, { 3, 4, 0.25 } }, points(sk.strokes[1]))
    assert.are_not.equal(src.strokes[1].points[1], sk.strokes[1].points[1])
    assert.same({ 1, 2 }, src.strokes[1].points[1])       -- the input is not changed
  end)

  it("refuses NaN and infinities, which only a table can hold", function ()
    local x = t()
    x.strokes[1].points[2][1] = 0 / 0
    local ok, msg = pcall(read.table, x, "mine")
    assert.is_false(ok)
    assert.truthy(msg:find("^mine: stroke 1 %(stem%): point 2: x is not finite %(%-?nan%)$"), msg)
    x.strokes[1].points[2][1] = -math.huge
    raises(function () read.table(x, "mine") end,
                     "mine: stroke 1 (stem): point 2: x is not finite (-inf)")
    x = t()
    x.width = math.huge
    raises(function () read.table(x, "mine") end,
                     "mine: width must be a number > 0 and at most 1000000, not inf")
  end)

  it("refuses holes and other keys in lists", function ()
    local x = t()
    x.strokes[1].points = { { 1, 2 }, nil, { 3, 4 } }
    raises(function () read.table(x, "mine") end, "mine: stroke 1 (stem): points "
                     .. "must be a list of [x, y] or [x, y, pressure]")
    x = t()
    x.strokes[1].points[2].z = 1
    raises(function () read.table(x, "mine") end,
                     "mine: stroke 1 (stem): point 2 is not [x, y] or [x, y, pressure]")
    x = t()
    x[1] = true
    raises(function () read.table(x, "mine") end,
                     "mine: a sketch is a JSON object, not an array")
  end)

  it("takes back its own output (file, index and warnings)", function ()
    local sk = read.table(t(), "a.json")
    sk.warnings = { "w" }
    local again = read.table(sk)
    assert.equal("a.json", again.file)
    assert.same(sk, again)
    sk.strokes[1].index = 2
    raises(function () read.table(sk) end,
                     "a.json: stroke 1 (stem): index 2 is not its position 1")
  end)
end)

describe("lsys.sketch.read.to_json", function ()
  it("writes a sketch that reads back equal", function ()
    local sk = read.json(H.read(DATA .. "plant.json"), "plant.json")
    sk.strokes[1].points[2][1] = 1 / 3           -- needs 17 digits
    sk.strokes[1].points[2][2] = -1e-300
    sk.strokes[1].id = 'a "quoted"\n\\name\1'
    local text = read.to_json(sk)
    local back = read.json(text, "plant.json")
    assert.same(sk, back)
    assert.equal(1 / 3, back.strokes[1].points[2][1])
    -- one point per line
    assert.truthy(text:find('\n      %[200, 280, 0.5%],\n'), text)
    assert.truthy(text:find('"depth": {"near": -50, "far": 50}', 1, true))
  end)

  it("writes the SVG sketch too, without its warnings", function ()
    local sk = read.svg(H.read(DATA .. "inkscape.svg"), "x")
    local back = read.json(read.to_json(sk), "x")
    sk.warnings = nil
    assert.same(sk, back)
  end)

  it("refuses what it could not read back", function ()
    raises(function () read.to_json({ width = 1, height = 1, strokes = {} }) end,
                     "<table>: no stem stroke")
  end)
end)

describe("lsys.sketch.read.file and save", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("reads by extension, and by the first character otherwise", function ()
    if not have_core then return pending("lsys.core is not built") end
    local sk = read.file(DATA .. "plant.json")
    assert.equal(DATA .. "plant.json", sk.file)
    assert.equal(5, #sk.strokes)
    assert.equal(6, #read.file(DATA .. "inkscape.svg").strokes)
    H.write(dir .. "/a.sketch", H.read(DATA .. "plant.json"))
    assert.equal("decussate", read.file(dir .. "/a.sketch").phyllotaxis)
    H.write(dir .. "/b.txt",
            "\239\187\191  " .. H.read(DATA .. "inkscape.svg"):gsub("^<%?.-%?>", ""))
    assert.equal(6, #read.file(dir .. "/b.txt").strokes)
    H.write(dir .. "/c.txt", "hello")
    raises(function () read.file(dir .. "/c.txt") end,
                     dir .. "/c.txt: not a sketch file (JSON or SVG)")
    local ok, msg = pcall(read.file, dir .. "/none.json")
    assert.is_false(ok)
    assert.truthy(msg:find(dir .. "/none.json", 1, true), msg)
  end)

  it("saves atomically and reads back the same sketch", function ()
    if not have_core then return pending("lsys.core is not built") end
    local sk = read.file(DATA .. "inkscape.svg")
    local path = dir .. "/s.json"
    assert.is_true(read.save(sk, path))
    local back = read.file(path)
    assert.equal(path, back.file)
    back.file, sk.file, sk.warnings = nil, nil, nil
    assert.same(sk, back)
    -- nothing else is left in the folder (no temporary file)
    local p = io.popen("ls -A " .. dir)
    assert.equal("s.json\n", p:read("a"))
    p:close()
    -- a sketch that does not check is not written
    raises(function () read.save({ width = 1, height = 1, strokes = {} }, path) end,
                     "<table>: no stem stroke")
    assert.equal(6, #read.file(path).strokes)
  end)
end)

describe("lsys.sketch.read.svg", function ()
  it("reads an Inkscape file: layer transform, labels, relative curves, subpaths", function ()
    local sk = read.svg(H.read(DATA .. "inkscape.svg"), "inkscape.svg")
    assert.equal(400, sk.width)
    assert.equal(300, sk.height)
    assert.equal(5, sk.nodes_per_layer)
    local s = sk.strokes
    assert.equal(6, #s)
    -- m 190,300 c (straight) twice, moved by translate(10,-20): a cubic whose control
    -- points lie on its chord needs no points between its ends
    assert.same({ "stem", 1, "stem" }, { s[1].role, s[1].index, s[1].id })
    assert.same({ { 200, 280, 0.5 }, { 200, 190, 0.5 }, { 200, 100, 0.5 } }, points(s[1]))
    -- m 100,290 q 20,-100 0,-200: from (110,270) with control (130,170) to (110,70);
    -- |P0 - 2 P1 + P2| = 40, so 7 steps (40 * 2 / (8 * 7^2) <= 0.25 < 40 * 2 / (8 * 6^2)):
    -- x = 110 + 40 t (1 - t), y = 270 - 200 t
    assert.same({ "boundary_left", "boundary-left" }, { s[2].role, s[2].id })
    local want = {}
    for k = 0, 7 do
      local t = k / 7
      want[#want + 1] = { 110 + 40 * t * (1 - t), 270 - 200 * t, 0.5 }
    end
    assert.near(want, points(s[2]), 1e-9)
    -- M 280,290 280,90: an implicit line-to; the label compares without case
    assert.same({ "boundary_right", "Boundary Right" }, { s[3].role, s[3].id })
    assert.same({ { 290, 270, 0.5 }, { 290, 70, 0.5 } }, points(s[3]))
    -- two subpaths, two strokes with the same id
    assert.same({ "inclination", "inclination-1", 4 }, { s[4].role, s[4].id, s[4].index })
    assert.same({ { 100, 230, 0.5 }, { 300, 230, 0.5 } }, points(s[4]))
    assert.same({ "inclination", "inclination-1", 5 }, { s[5].role, s[5].id, s[5].index })
    assert.same({ { 100, 130, 0.5 }, { 300, 130, 0.5 } }, points(s[5]))
    -- the role from the id when there is no label
    assert.same({ "inclination", "inclination-top" }, { s[6].role, s[6].id })
    assert.same({ { 100, 90, 0.5 }, { 300, 80, 0.5 } }, points(s[6]))
    -- not read: the <defs> path, the <rect>, the path without a role; a near miss warns
    assert.same({ "inkscape.svg:56: path 'stem (old)' ignored: not a role name (stem, "
                  .. "boundary-left, boundary-right, inclination-*)" }, sk.warnings)
  end)

  it("reads polylines and lines", function ()
    local sk = read.svg(svg('<polyline id="stem" points="10,20 30,40 50 60"/>'
                            .. '<line id="inclination-a" x1="1" y1="2" x2="3" y2="4"/>'))
    assert.same({ { 10, 20, 0.5 }, { 30, 40, 0.5 }, { 50, 60, 0.5 } }, points(sk.strokes[1]))
    assert.same({ { 1, 2, 0.5 }, { 3, 4, 0.5 } }, points(sk.strokes[2]))
    raises(function () read.svg(svg('<polyline id="stem" points="10,20 30"/>'), "a.svg") end,
                     "a.svg:1: polyline 'stem': an odd number of coordinates in points")
  end)

  it("applies the transforms of the element and its groups, innermost first", function ()
    local function first (body, attrs)
      return points(read.svg(svg(body, attrs)).strokes[1])
    end
    -- scale(2) then rotate(90): (10,0) -> (20,0) -> (0,20)
    assert.near({ { 0, 20, 0.5 }, { 0, 40, 0.5 } },
                first('<g transform="rotate(90)"><polyline id="stem" points="10,0 20,0" '
                      .. 'transform="scale(2)"/></g>'), 1e-12)
    assert.near({ { 6, 8, 0.5 }, { 16, 8, 0.5 } },
                first('<g transform="matrix(1,0,0,1,5,6)"><g transform="translate(1 2)">'
                      .. '<path id="stem" d="M0 0 10 0"/></g></g>'), 1e-12)
    -- skewX(45): x + y; skewY(45): y + x; rotate about a point
    assert.near({ { 10, 10, 0.5 }, { 30, 10, 0.5 } },
                first('<path id="stem" transform="skewX(45)" d="M0 10 20 10"/>'), 1e-12)
    assert.near({ { 10, 10, 0.5 }, { 10, 30, 0.5 } },
                first('<path id="stem" transform="skewY(45)" d="M10 0 10 20"/>'), 1e-12)
    assert.near({ { 10, 20, 0.5 }, { 10, 10, 0.5 } },
                first('<path id="stem" transform="rotate(90, 10, 10)" d="M20 10 10 10"/>'),
                1e-12)
    assert.near({ { 3, 12, 0.5 }, { 5, 12, 0.5 } },
                first('<path id="stem" transform="translate(1,2) scale(2, 5)" d="M1 2 2 2"/>'),
                1e-12)
    local function bad (tr)
      return function ()
        read.svg(svg('<path id="stem" transform="' .. tr .. '" d="M0 0 1 1"/>'), "t.svg")
      end
    end
    raises(bad "spin(3)", "t.svg:1: transform: unknown transform 'spin' at character 1")
    raises(bad "translate(1) scale(1,2,3)",
           "t.svg:1: transform: bad arguments to scale at character 14")
    raises(bad "rotate(90", "t.svg:1: transform: bad transform at character 1")
  end)

  it("takes the size from the viewBox, with its origin, else from width and height", function ()
    local sk = read.svg(svg('<path id="stem" d="M150 60 150 100"/>',
                            'width="20cm" height="10cm" viewBox="100 50 200 100"'))
    assert.same({ 200, 100 }, { sk.width, sk.height })
    assert.same({ { 50, 10, 0.5 }, { 50, 50, 0.5 } }, points(sk.strokes[1]))
    local function size (w, h)
      local s = read.svg(svg('<path id="stem" d="M0 0 1 1"/>', 'width="' .. w .. '" height="'
                             .. h .. '"'))
      return { s.width, s.height }
    end
    assert.near({ 96, 96 / 2.54 * 10 }, size("1in", "10cm"), 1e-9)
    assert.near({ 96, 96 / 25.4 }, size("72pt", "1mm"), 1e-9)
    assert.near({ 640, 16 }, size(" 640px ", "1pc"), 1e-9)
    local function bad (attrs) return function () read.svg(svg("", attrs), "s.svg") end end
    raises(bad('width="100%" height="10"'),
                     "s.svg:1: width '100%': units are px, mm, cm, in, pt and pc")
    raises(bad('width="ten" height="10"'), "s.svg:1: width 'ten' is not a length")
    raises(bad('height="10"'),
                     "s.svg:1: no viewBox and no width and height (the sketch's size)")
    raises(bad('viewBox="0 0 10"'), "s.svg:1: viewBox '0 0 10' is not four numbers")
    raises(bad('viewBox="0 0 10 0"'),
                     "s.svg:1: the sketch's width and height must be > 0 (10, 0)")
  end)

  it("reads the settings and pressures that data- attributes give", function ()
    local sk = read.svg(svg('<path id="stem" d="M0 0 L 10 0 20 0" data-pressure="0 1 0.5"/>',
                            'width="40" height="30" data-nodes-per-layer="13" '
                            .. 'data-phyllotaxis="fibonacci" data-depth-near="-5" '
                            .. 'data-depth-far="5"'))
    assert.same({ 13, "fibonacci", { near = -5, far = 5 } },
                { sk.nodes_per_layer, sk.phyllotaxis, sk.depth })
    assert.same({ { 0, 0, 0 }, { 10, 0, 1 }, { 20, 0, 0.5 } }, points(sk.strokes[1]))
    -- along a curve, pressure goes linearly with the segment's parameter
    sk = read.svg(svg('<path id="stem" d="M0 0 Q 10 5 20 0" data-pressure="0 1"/>'))
    local p = points(sk.strokes[1])
    assert.equal(5, #p)                      -- |P0 - 2 P1 + P2| = 10: 4 steps
    assert.near({ 0, 0.25, 0.5, 0.75, 1 }, { p[1][3], p[2][3], p[3][3], p[4][3], p[5][3] },
                1e-12)
    local function bad (d, pr)
      return function ()
        read.svg(svg('<path id="stem" d="' .. d .. '" data-pressure="' .. pr .. '"/>'), "p.svg")
      end
    end
    raises(bad("M0 0 1 1", "0.5"),
                     "p.svg:1: path 'stem': data-pressure has 1 values for 2 points")
    raises(bad("M0 0 1 1", "0.5 2"),
                     "p.svg:1: path 'stem': data-pressure value 2 (2) outside [0, 1]")
  end)

  local function err (text) return function () read.svg(text, "plant.svg") end end

  it("refuses document type declarations with entities, and malformed XML", function ()
    raises(err('<?xml version="1.0"?>\n<!DOCTYPE svg [\n<!ENTITY a "aaaa">\n'
                         .. '<!ENTITY b "&a;&a;&a;&a;">\n]>\n<svg/>'),
                     "plant.svg:2: document type declarations and entities are not read")
    -- a DOCTYPE that only names the DTD is fine
    local sk = read.svg('<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" '
                        .. '"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">\n'
                        .. svg('<path id="stem" d="M0 0 1 1"/>'), "plant.svg")
    assert.equal(1, #sk.strokes)
    raises(err(svg('<path id="stem" d="M0 0 1 1">')),
                     "plant.svg:1: malformed SVG: mismatched tag")
    raises(err(""), "plant.svg:1: malformed SVG: no element found")
    raises(err('<html xmlns="http://www.w3.org/1999/xhtml"/>'),
                     "plant.svg:1: not an SVG file (the root element is 'html')")
    raises(err('<svg xmlns="http://example.com/x" width="1" height="1"/>'),
                     "plant.svg:1: not an SVG file (the root element is 'svg')")
  end)

  it("names the element, its line and the character of bad path data", function ()
    raises(err(svg('\n\n<path id="stem" d="M 0 0 L 10 x"/>')),
                     "plant.svg:3: path 'stem': 'L' needs 2 numbers at character 12")
    raises(err(svg('<path inkscape:label="inclination-4" id="p7" d="M 0 0 L 10 10 ?" '
                             .. 'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"/>')),
                     "plant.svg:1: path 'inclination-4': unexpected '?' at character 15")
    raises(err(svg('<path id="stem"/>')), "plant.svg:1: path 'stem': no d attribute")
    raises(err(svg('<path id="stem" d=""/>')), "plant.svg:1: path 'stem': no points")
    -- a lone moveto is a stroke of one point
    raises(err(svg('<path id="stem" d="M 5 5"/>')),
                     "plant.svg:1: stroke 1 (stem 'stem'): fewer than two points")
    -- but not when the path draws something else
    assert.equal(1, #read.svg(svg('<path id="stem" d="M 5 5 M 0 0 1 1"/>')).strokes)
  end)

  it("checks the strokes as in JSON, with the line of the element", function ()
    raises(err(svg('<path id="inclination" d="M 0 0 1 1"/>')),
                     "plant.svg: no stem stroke")
    raises(err(svg('<path id="stem" d="M 0 0 1 1"/>\n<path id="stem" d="M 0 0 1 1"/>')),
                     "plant.svg:2: two stem strokes (1 and 2)")
    raises(err(svg('<path id="stem" d="M 0 0 1 1"/><path id="boundary_left" '
                             .. 'd="M 0 0 1 1 M 3 3 4 4"/>')),
                     "plant.svg:1: two boundary_left strokes (2 and 3)")
    raises(err(svg('<path id="stem" d="M 0 0 1 1"/>\n<path id="inclination" '
                             .. 'd="M 0 0 1 2e7"/>')),
                     "plant.svg:2: stroke 2 (inclination 'inclination'): point 2: "
                     .. "(1, 20000000) is beyond 10000000 pixels")
    local many = {}
    for i = 1, 1001 do many[i] = "M 0 0 1 1" end
    raises(err(svg('<path id="inclination" d="' .. table.concat(many, " ") .. '"/>')),
                     "plant.svg:1: path 'inclination': more than 1000 strokes")
  end)

  it("names roles by id or label, without case, with - _ or space", function ()
    local cases = {
      stem = "stem", STEM = "stem", ["boundary-left"] = "boundary_left",
      ["boundary_left"] = "boundary_left", ["left-boundary"] = "boundary_left",
      ["Left Boundary"] = "boundary_left", ["boundary-right"] = "boundary_right",
      ["right_boundary"] = "boundary_right", inclination = "inclination",
      ["inclination-7"] = "inclination", ["inclination_top"] = "inclination",
      inclination3 = "inclination",
    }
    for name, role in pairs(cases) do assert.equal(role, read.svg_role(name), name) end
    assert.equal("inclination", read.svg_role("-inclination-"))
    for _, name in ipairs { "stem-old", "stem2", "boundary", "inclinations", "inclined",
                            "left-bound" } do
      local r, near = read.svg_role(name)
      assert.is_nil(r, name)
      assert.is_true(near, name)
    end
    for _, name in ipairs { "path12", "leaf", "layer1", "" } do
      local r, near = read.svg_role(name)
      assert.is_nil(r, name)
      assert.is_nil(near, name)
    end
  end)
end)

describe("lsys.sketch.svgpath", function ()
  -- the points of each subpath as { x, y } pairs
  local function flat (d, opts)
    local list, nodes = svgpath.flatten(d, opts)
    local out = {}
    for i, sp in ipairs(list) do
      out[i] = {}
      for k = 1, #sp, 3 do out[i][#out[i] + 1] = { sp[k], sp[k + 1] } end
    end
    return out, nodes
  end

  it("reads numbers as SVG writes them", function ()
    assert.same({ { { 10, 20 }, { 10, 120 } } }, flat "m 10,20 0,100")
    assert.same({ { { 0.5, 0.5 }, { -1, -2 }, { 0.001, 100 } } }, flat "M.5.5-1-2 1e-3 1E+2")
    assert.same({ { { 1, 2 }, { 3, 4 } } }, flat "  M1,2\n\t3 , 4  ")
    assert.same({ { { 1.5, -5 }, { 2, 5 } } }, flat "M1.5e0-5e-0 L 2. 5")
    assert.same({}, flat "")
    assert.same({}, flat " \n")
    assert.same({ 1, 2, 3, -4.5, 0.5, 500 }, svgpath.numbers("1,2 3-4.5.5 5e2"))
  end)

  it("repeats commands, relative forms included, and H V Z", function ()
    -- after m, pairs are relative line-tos; after M absolute ones
    assert.same({ { { 1, 1 }, { 2, 3 }, { 5, 7 } } }, flat "m1 1 1 2 3 4")
    assert.same({ { { 1, 1 }, { 1, 2 }, { 3, 4 } } }, flat "M1 1 1 2 3 4")
    assert.same({ { { 0, 0 }, { 10, 0 }, { 10, 10 }, { 0, 10 }, { 0, 0 } } },
                flat "M0 0 h 10 v 10 H 0 z")
    assert.same({ { { 0, 0 }, { 5, 0 }, { 10, 0 } } }, flat "M0 0 h 5 5")
    -- a drawing command after Z starts a new subpath at the subpath's start
    assert.same({ { { 0, 0 }, { 10, 0 }, { 0, 0 } }, { { 0, 0 }, { 5, 5 } } },
                flat "M 0 0 h 10 z l 5 5")
    -- one subpath per moveto
    assert.same({ { { 1, 2 } }, { { 3, 4 }, { 4, 5 } } }, flat "M 1 2 M 3 4 l 1 1")
  end)

  it("flattens curves within a quarter unit, with exact ends", function ()
    -- a quarter circle by a cubic: every point within 0.25 of the cubic itself
    local list = svgpath.flatten("M 100 0 C 100 55.2285 55.2285 100 0 100")
    local sp = list[1]
    local n = #sp // 3
    assert.same({ 100, 0, 0, 100 }, { sp[1], sp[2], sp[3 * n - 2], sp[3 * n - 1] })
    -- |P0 - 2 P1 + P2| = |(-44.7715, -10.457)| = 45.976 (and the same for P1, P2, P3):
    -- ceil(sqrt(6 * 45.976 / (8 * 0.25))) = 12 steps
    assert.equal(13, n)
    local function bez (t)
      local u = 1 - t
      return u ^ 3 * 100 + 3 * u * u * t * 100 + 3 * u * t * t * 55.2285,
             3 * u * u * t * 55.2285 + 3 * u * t * t * 100 + t ^ 3 * 100
    end
    -- the largest distance from the curve to the chord of its step, sampled finely
    local worst = 0
    for k = 0, 1200 do
      local t = k / 1200
      local x, y = bez(t)
      local seg = math.min(math.floor(t * (n - 1)) + 1, n - 1)
      local ax, ay, bx, by = sp[3 * seg - 2], sp[3 * seg - 1], sp[3 * seg + 1], sp[3 * seg + 2]
      local dx, dy = bx - ax, by - ay
      local d = math.abs((x - ax) * dy - (y - ay) * dx) / math.sqrt(dx * dx + dy * dy)
      worst = math.max(worst, d)
    end
    assert.is_true(worst > 0.1, worst)       -- the bound is used, not wasted
    assert.is_true(worst <= 0.25, worst)
    -- a smooth cubic reflects the last control point; a smooth quadratic likewise
    local s1 = flat "M0 0 C 0 10 10 10 10 0 S 20 -10 20 0"
    local s2 = flat "M0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0"
    assert.near(s2, s1, 1e-12)
    assert.near(flat "M0 0 Q 5 10 10 0 Q 15 -10 20 0", flat "M0 0 Q 5 10 10 0 T 20 0", 1e-12)
    assert.near(flat "M0 0 q 5 10 10 0 t 10 0", flat "M0 0 Q 5 10 10 0 T 20 0", 1e-12)
    -- S after a non-cubic takes the current point as its first control point
    assert.near(flat "M0 0 L 1 1 C 1 1 5 5 9 1", flat "M0 0 L 1 1 S 5 5 9 1", 1e-12)
  end)

  it("flattens arcs, with flags written together", function ()
    -- a half circle of radius 5 from (0,0) to (10,0): 5 steps of 36 degrees
    -- (4 asin(sqrt(0.25 / 10)) = 36.5 degrees)
    local up = flat "M0 0 a5 5 0 01 10 0"
    assert.equal(6, #up[1])
    for _, p in ipairs(up[1]) do
      assert.near(5, math.sqrt((p[1] - 5) ^ 2 + p[2] ^ 2), 1e-9)
      assert.is_true(p[2] <= 1e-12)          -- sweep 1: through y < 0
    end
    local down = flat "M0 0 A 5 5 0 1 0 10 0"
    for _, p in ipairs(down[1]) do assert.is_true(p[2] >= -1e-12) end
    assert.near({ 0, 0 }, up[1][1], 0)
    assert.near({ 10, 0 }, up[1][6], 0)
    -- radii too small are scaled up (F.6.6): the same half circle
    assert.near(up, flat "M0 0 a1 1 0 0 1 10 0", 1e-9)
    -- zero radius: a line; same end points: nothing drawn but the node
    assert.same({ { { 0, 0 }, { 10, 0 } } }, flat "M0 0 A 0 5 0 0 1 10 0")
    assert.same({ { { 0, 0 }, { 0, 0 } } }, flat "M0 0 A 5 5 0 0 1 0 0")
  end)

  it("transforms before flattening, so the bound holds in output units", function ()
    local small = flat "M0 0 Q 1 2 2 0"
    local big = flat("M0 0 Q 1 2 2 0", { matrix = { 100, 0, 0, 100, 0, 0 } })
    assert.equal(3, #small[1])              -- |(0, -4)| * 2 / 2: ceil(sqrt(4)) = 2
    assert.equal(21, #big[1])               -- |(0, -400)| * 2 / 2: ceil(sqrt(400)) = 20
    assert.same({ { { 5, 7 }, { 15, 7 } } }, flat("m 10,20 0,-10", {
      matrix = { 0, 1, -1, 0, 25, -3 } }))
  end)

  it("numbers the nodes for pressure along the path", function ()
    local list, nodes = svgpath.flatten "M0 0 L 10 0 Q 15 5 20 0 Z"
    assert.equal(4, nodes)
    local s = {}
    for k = 3, #list[1], 3 do s[#s + 1] = list[1][k] end
    -- Q from (10,0): |(0, -10)| * 2 / 2 = 10, 4 steps
    assert.same({ 0, 1, 1.25, 1.5, 1.75, 2, 3 }, s)
  end)

  it("refuses bad path data, naming the element and the character", function ()
    local function e (d)
      return function () svgpath.flatten(d, { name = "p.svg:3: path 'x'" }) end
    end
    local P = "p.svg:3: path 'x': "
    raises(e "L 10 10", P .. "path data must begin with M or m at character 1")
    raises(e "M 0 0 L 10", P .. "'L' needs 2 numbers at character 11")
    raises(e "M0,0 L,10,10", P .. "'L' needs 2 numbers at character 7")
    raises(e "M0 0 x", P .. "unexpected 'x' at character 6")
    raises(e "M0 0 Z 5 5", P .. "a number after Z at character 8")
    raises(e "M0 0 1e999 0", P .. "number out of range at character 6")
    raises(e "M0 0 a 5 5 0 2 0 10 0", P .. "an arc flag (0 or 1) expected at character 14")
    raises(e "M0 0 L 1 1 .", P .. "'L' needs 2 numbers at character 12")
    raises(e "M0 0 L 1 1 #", P .. "unexpected '#' at character 12")
    raises(e "M0 0 C 0 1e300 1e300 0 5 5",
                     P .. "more than 100000 points once curves are flattened at character 6")
    raises(e "M0 0 A 1e300 1e300 0 1 0 10 0", P .. "arc out of range at character 6")
    raises(e "M0 0 A 1e9 1e9 0 1 0 10 0",
           P .. "more than 100000 points once curves are flattened at character 6")
    raises(function () svgpath.numbers("1,,2", "pts") end, "pts: bad number at character 3")
  end)

  it("flattens a huge-radius arc of a short chord into a few points", function ()
    local f = flat "M0 0 A 1e300 1e300 0 0 1 10 0"
    assert.is_true(#f[1] <= 3, #f[1])
    assert.near({ 10, 0 }, f[1][#f[1]], 1e-9)
  end)
end)
