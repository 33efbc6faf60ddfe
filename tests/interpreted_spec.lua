-- The geometry of interpreted modules (docs/open.md §3): a communication file's
-- `interpreted modules:` and `when interpret:` lines, and what lsys sends after a ?E whose
-- following module they name: "Dbegin", the module's drawing as cpfg's GLS text, "Dend".
-- The bytes expected are those cpfg (vlab 9bf820d, -g -e) sends for the same model and file,
-- captured with the test program tests/c/envslave.c (`log=FILE`).
local lsys = require "lsys"
local H = require "tests.helper"
local efile = require "lsys.environment.efile"
local warning = require "lsys.warning"

local ENVSLAVE = os.getenv("LSYS_ENVSLAVE")
  or H.absolute((os.getenv("LSYS_BUILD_DIR") or "build") .. "/lsys_envslave")
local DATA = "tests/data/cpfg/open/"

-- What cpfg sends for tests/data/cpfg/open/interpreted.l over `communication type: pipes 3`
-- with `interpreted modules: F,Z,{,@` and the colour map of colour i = (i, 2i, 3i): a
-- segment F(2) (its cylinder: the frame at its start, radius and length), the polygon the
-- homomorphism makes of Z (each f and . a vertex), a polygon in the string ({...}: only
-- its . vertices), a sphere; the F(1) of ?E(4) is ended by the F(2) after ?E(5), so its
-- cylinder goes in that section; the last F(1) is never ended (nothing follows it) and is
-- lost; a chunk ends before a Dend.
local CPFG = "0 E(0)F(2)\n"
  .. " 0 1 0\n"
  .. "Dbegin\n"
  .. "material\n"
  .. " 0.000392157 0.000784314 0.00117647 0\n"
  .. " 0.00392157 0.00784314 0.0117647 0\n"
  .. " 0 0 0 0  0 0 0 0  0\n"
  .. "pushmatrix\n"
  .. "translate 0.000000 1.000000 0.000000\n"
  .. "multmatrix\n"
  .. " 0.000000 0.000000 -1.000000 0\n"
  .. " 0.000000 1.000000 0.000000 0\n"
  .. " 1.000000 -0.000000 -0.000000 0\n"
  .. "0 0 0 1\n"
  .. "cylinder 1.500000 2.000000\n"
  .. "popmatrix\n"
  .. "Dend\n"
  .. "22 E(1)Z\n"
  .. " 0 4 0\n"
  .. "Dbegin\n"
  .. "material\n"
  .. " 0.000784314 0.00156863 0.00235294 0\n"
  .. " 0.00784314 0.0156863 0.0235294 0\n"
  .. " 0 0 0 0  0 0 0 0  0\n"
  .. "polygon\n"
  .. " 0 4 0\n"
  .. " 0 5 0\n"
  .. " 0 5 0\n"
  .. " -1 5 0\n"
  .. " -1 5 0\n"
  .. " -1 4 0\n"
  .. " -1 4 0\n"
  .. "Dend\n"
  .. "31 E(2){\n"
  .. " -1 4 0\n"
  .. "Dbegin\n"
  .. "polygon\n"
  .. " -1 4 0\n"
  .. " -1 3 0\n"
  .. " -4.44089e-16 3 0\n"
  .. " -1.9916e-16 4 0\n"
  .. "Control: 1 0\n"
  .. "Dend\n"
  .. "68 E(3)@O(0.5)\n"
  .. " -1.9916e-16 4 0\n"
  .. "Dbegin\n"
  .. "pushmatrix\n"
  .. "translate -1.9916e-16 4 0\n"
  .. "sphere 0.25\n"
  .. "popmatrix\n"
  .. "Dend\n"
  .. "84 E(4)F(1)\n"
  .. " -1.9916e-16 4 0\n"
  .. "Dbegin\n"
  .. "Dend\n"
  .. "99 E(5)F(2)\n"
  .. " 4.57695e-17 5 0\n"
  .. "Dbegin\n"
  .. "pushmatrix\n"
  .. "translate -0.000000 4.000000 0.000000\n"
  .. "multmatrix\n"
  .. " 0.000000 0.000000 -1.000000 0\n"
  .. " 0.000000 1.000000 0.000000 0\n"
  .. " 1.000000 -0.000000 -0.000000 0\n"
  .. "0 0 0 1\n"
  .. "cylinder 1.500000 1.000000\n"
  .. "popmatrix\n"
  .. "pushmatrix\n"
  .. "translate 0.000000 5.000000 0.000000\n"
  .. "multmatrix\n"
  .. " 0.000000 0.000000 -1.000000 0\n"
  .. " 0.000000 1.000000 0.000000 0\n"
  .. " 1.000000 -0.000000 -0.000000 0\n"
  .. "0 0 0 1\n"
  .. "cylinder 1.500000 2.000000\n"
  .. "popmatrix\n"
  .. "Control: 0 0\n"
  .. "Dend\n"
  .. "121 E(6)F(1)\n"
  .. " 7.80558e-16 8 0\n"
  .. "Dbegin\n"
  .. "Dend\n"
  .. "Control: 4 0\n"
  .. "Control: 8 0\n"

local dir
setup(function () dir = H.tmpdir() end)
teardown(function () H.rmdir(dir) end)

local function write (name, text)
  local path = dir .. "/" .. name
  H.write(path, text)
  return path
end

-- the colour map of colour i = (i, 2i, 3i) bytes
local function colormap ()
  local t = {}
  for i = 0, 255 do t[#t + 1] = string.char(i % 256, 2 * i % 256, 3 * i % 256) end
  return write("c.map", table.concat(t))
end

-- A communication file for the logging test program: the bytes it gets go to `log`.
local function efilelog (name, transport, extra)
  local log = dir .. "/" .. name .. ".log"
  os.remove(log)
  local e = write(name .. ".e", "executable: " .. ENVSLAVE .. " log=" .. log
    .. "\ncommunication type: " .. transport .. "\nturtle position: %g %g %g\n"
    .. (extra or "interpreted modules: F,Z,{,@\n"))
  return e, log
end

-- What the program got when lsys derived interpreted.l with the file.
local function sent (name, transport, extra)
  local e, log = efilelog(name, transport, extra)
  local m = lsys.cpfg.load(DATA .. "interpreted.l", DATA .. "interpreted.v",
                           { colormap = colormap(), environment = e })
  m:derive()
  return H.read(log)
end

describe("the communication file's interpreted modules", function ()
  local function read (text) return efile.read(write("f.e", "executable: a\n" .. text)) end

  it("are the modules named, with any number of parameters or exactly n", function ()
    local e = read("interpreted modules: F,Z;{ @ B(2)\n")
    assert.is_true(efile.interprets(e, "F", 0))
    assert.is_true(efile.interprets(e, "F", 3))
    assert.is_true(efile.interprets(e, "{", 0))
    assert.is_true(efile.interprets(e, "@O", 1))          -- a name's first character, as cpfg
    assert.is_true(efile.interprets(e, "B", 2))
    assert.is_false(efile.interprets(e, "B", 1))
    assert.is_false(efile.interprets(e, "A", 0))
    assert.is_false(efile.interprets(e, nil, 0))          -- the end of the string
    assert.is_false(efile.interprets(read("verbose: on\n"), "F", 0))
    e = read("interpreted modules: all\n")
    assert.is_true(efile.interprets(e, "A", 7))
  end)

  it("are, with when interpret:, the modules of n parameters (all for a negative n)",
     function ()
    local e = read("when interpret: 1, 0\n")
    assert.is_true(efile.interprets(e, "A", 1))
    assert.is_true(efile.interprets(e, "F", 0))
    assert.is_false(efile.interprets(e, "F", 2))
    assert.is_true(efile.interprets(read("when interpret: -1\n"), "Q", 5))
    -- a later `interpreted modules:` replaces what came before for its character, as cpfg
    e = read("when interpret: 0\ninterpreted modules: F(2)\n")
    assert.is_false(efile.interprets(e, "F", 0))
    assert.is_true(efile.interprets(e, "F", 2))
    assert.is_true(efile.interprets(e, "A", 0))
    e = read("interpreted modules: F(2)\nwhen interpret: 0\n")
    assert.is_true(efile.interprets(e, "F", 0))
    assert.is_true(efile.interprets(e, "F", 2))
  end)

  it("name the file and line of what lsys cannot read", function ()
    local function err (text) return select(2, pcall(read, text)) end
    assert.equal(dir .. "/f.e:2: interpreted modules: 'FF' is not a module lsys can name: "
      .. "one character, alone (any parameters) or with its number of parameters, 0 to 6, "
      .. "as in F(1)", err("interpreted modules: F FF\n"))
    assert.truthy(err("interpreted modules: F(7)\n"):find("f.e:2: interpreted modules: 'F(7)'",
                                                          1, true))
    assert.equal(dir .. "/f.e:2: when interpret: 'x' is not a number of parameters (0 to 6, "
      .. "or -1 for all modules)", err("when interpret: 1 x\n"))
    local got = {}
    local saved = warning.warn
    warning.warn = function (msg) got[#got + 1] = msg end
    local ok, e = pcall(read, "when interpret: 7 1\n")
    warning.warn = saved
    assert(ok, e)
    assert.same({ "lsys: " .. dir .. "/f.e:2: when interpret: modules of 7 parameters "
      .. "cannot be told apart (6 at most, as in cpfg): skipped; name them in 'interpreted "
      .. "modules:'" }, got)
    assert.is_true(efile.interprets(e, "A", 1))
    assert.is_false(efile.interprets(e, "A", 7))
  end)
end)

describe("scene:vertices", function ()
  it("gives the vertices of a record's triangles in the turtle's order", function ()
    local m = lsys.lsystem { axiom = "F{.f.+f.+f.}@O(1)", view = { angle = 90 } }
    local sc = m:interpret(m:derive())
    local k = sc:find(12)                                   -- the polygon, at its }
    assert.equal("polygon", sc:record(k).kind)
    local v = sc:vertices(k)
    local want = { { 0, 1 }, { 0, 2 }, { 0, 2 }, { -1, 2 }, { -1, 2 }, { -1, 1 }, { -1, 1 } }
    assert.equal(#want, #v)
    for i, w in ipairs(want) do
      assert.near(w[1], v[i][1], 1e-6)
      assert.near(w[2], v[i][2], 1e-6)
      assert.near(0, v[i][3], 1e-6)
    end
    assert.same({}, sc:vertices(1))                         -- the segment: no triangles
    assert.is_true(#sc:vertices(sc:find(13)) > 3)           -- the sphere's
    assert.has_error(function () sc:vertices(99) end, "scene:vertices: no record 99")
    getmetatable(sc).__close(sc)
    assert.has_error(function () sc:vertices(k) end, "the scene was closed")
  end)
end)

describe("the geometry of an interpreted module", function ()
  it("is sent as cpfg sends it: Dbegin, its GLS text, Dend", function ()
    assert.equal(CPFG, sent("pipes3", "pipes 3"))
  end)

  it("is the same over files and shared memory", function ()
    local one = sent("pipes", "pipes")                 -- the step in one chunk
    assert.equal(1, select(2, one:gsub("Control: 5 0\n", "")))
    assert.equal(one, sent("files", "files"))
    assert.equal(one, sent("memory", "memory"))
    -- the step's text is cpfg's, but for the chunks
    local function unchunked (s) return (s:gsub("Control: [0-5] 0\n", "")) end
    assert.equal(unchunked(CPFG), unchunked(one))
  end)

  it("is not sent for modules the file does not name, nor without the following module",
     function ()
    local s = sent("spheres", "pipes", "interpreted modules: @\n")
    assert.equal(1, select(2, s:gsub("Dbegin\n", "")))
    assert.truthy(s:find("68 E(3)@O(0.5)\n -1.9916e-16 4 0\nDbegin\nmaterial\n", 1, true), s)
    assert.truthy(s:find(" 0 0 0 0  0 0 0 0  0\npushmatrix\ntranslate -1.9916e-16 4 0\n"
      .. "sphere 0.25\npopmatrix\nDend\n84 E(4)F(1)\n", 1, true), s)
    s = sent("nofollow", "pipes", "interpreted modules: all\nfollowing module: no\n")
    assert.is_nil(s:find("D", 1, true))
    assert.truthy(s:find("^0 E%(0%)\n 0 1 0\n22 E%(1%)\n"), s)
  end)

  it("has the colours of cpfg's pass: set by interpreted modules, kept by brackets",
     function ()
    -- ;(5) and ;(7) are not interpreted: cpfg's pass keeps colour 1 (the view's); the ;(9)
    -- after ?E(2) is (when interpret: 1), until the ] restores 1; Y's expansion sets 4
    local l = write("colours.l", "Lsystem: 1\nderivation length: 1\nAxiom: ;(5)?E(0)F(1)"
      .. "[;(7)?E(1)F(1)?E(2);(9)?E(3)F(1)]?E(4)F(1)?E(5)Z?E(6)Y?E(7)F(1)F\n\nA --> A\n\n"
      .. "homomorphism\n\nZ --> {.f(1).+f(1).+f(1).}\nY --> ;(4)F(1)\n\nendlsystem\n")
    local e, log = efilelog("colours", "pipes", "interpreted modules: F,Z,Y\n"
                            .. "when interpret: 1\n")
    lsys.cpfg.load(l, DATA .. "interpreted.v", { colormap = colormap(), environment = e })
      :derive()
    local got, id = {}, nil
    local lines = {}
    for line in H.read(log):gmatch("[^\n]*\n") do lines[#lines + 1] = line end
    for i, line in ipairs(lines) do
      if line:find(" E(", 1, true) then id = line:match("^(%d+)") end
      if line == "material\n" then got[#got + 1] = id .. ":" .. lines[i + 2] end
    end
    assert.same({ "0: 0.00392157 0.00784314 0.0117647 0\n",
                  "38: 0.0352941 0.0705882 0.105882 0\n",
                  "69: 0.00392157 0.00784314 0.0117647 0\n",
                  "93: 0.0156863 0.0313726 0.0470588 0\n" }, got)      -- cpfg's
  end)

  it("is the same for every thread count", function ()
    local function with (threads)
      local e, log = efilelog("threads" .. threads, "pipes")
      local m = lsys.cpfg.load(DATA .. "interpreted.l", DATA .. "interpreted.v",
                               { colormap = colormap(), environment = e })
      m.threads = threads
      local s = tostring(m:derive())
      return H.read(log):gsub("log=[^\n]*", ""), s
    end
    local one, s1 = with(1)
    for _, t in ipairs { 2, 4 } do
      local got, s = with(t)
      assert.equal(one, got)
      assert.equal(s1, s)
    end
  end)

  it("is sent for a Lua model too: the segment after the ?E", function ()
    local e, log = efilelog("lua", "pipes", "when interpret: 1\n")
    local m = lsys.lsystem { axiom = "F(1)?E(0)F(2)F(1)", steps = 1, threads = 2,
                             environment = lsys.environment.program(e),
                             view = { palette = { [0] = { 0, 0, 0 }, { 1, 0.5, 0 } } } }
    m:derive()
    assert.equal("0 E(0)F(2)\n 0 1 0\nDbegin\nmaterial\n 0.1 0.0501961 0 0\n 1 0.501961 0 0\n"
      .. " 0 0 0 0  0 0 0 0  0\npushmatrix\ntranslate 0.000000 1.000000 0.000000\n"
      .. "multmatrix\n 0.000000 0.000000 -1.000000 0\n 0.000000 1.000000 0.000000 0\n"
      .. " 1.000000 -0.000000 -0.000000 0\n0 0 0 1\ncylinder 0.500000 2.000000\npopmatrix\n"
      .. "Dend\nControl: 5 0\nControl: 8 0\n", H.read(log))
  end)

  it("is read by vlab's MonteCarlo as cpfg's: the same triangles", function ()
    local bin = os.getenv("LSYS_ENVIRO_BIN")
    if not bin then
      return pending("vlab's environmental programs are not built (tools/enviro-build.sh; "
                     .. "LSYS_ENVIRO_BIN=their folder)")
    end
    -- MonteCarlo's answers are not compared: they change from run to run of cpfg itself
    -- (values it never sets); what it read is (its verbose log of each triangle).
    local out, code = H.sh("cd " .. DATA .. " && PATH='" .. bin .. "':$PATH "
      .. H.absolute(H.BIN) .. " derive montecarlo.l montecarlo.v --environment montecarlo.e "
      .. "2>&1 >/dev/null")
    assert.equal(0, code, out)
    local got = {}
    for l in out:gmatch("[^\n]+") do
      local v = l:match("^ 9 parameter%(s%) read: (.*)$")     -- a triangle's vertices
      if v then got[#got + 1] = v end
    end
    assert.equal([[
0 0 0 2 1.22465e-16 0 2 1.22465e-16 0
0 0 0 2 1.22465e-16 0 2 2 0
0 0 0 2 2 0 2 2 0
0 0 0 2 2 0 0 2 0
0 0 0 0 2 0 0 2 0
-1.73205 1 0 -2.73205 2.73205 0 -2.73205 2.73205 0
-1.73205 1 0 -2.73205 2.73205 0 -4.4641 1.73205 0
-1.73205 1 0 -4.4641 1.73205 0 -4.4641 1.73205 0
-1.73205 1 0 -4.4641 1.73205 0 -3.4641 4.44089e-16 0
-1.73205 1 0 -3.4641 4.44089e-16 0 -3.4641 4.44089e-16 0
-4.4641 -1.73205 0 -6.19615 -0.732051 0 -6.19615 -0.732051 0
-4.4641 -1.73205 0 -6.19615 -0.732051 0 -7.19615 -2.4641 0
-4.4641 -1.73205 0 -7.19615 -2.4641 0 -7.19615 -2.4641 0
-4.4641 -1.73205 0 -7.19615 -2.4641 0 -5.4641 -3.4641 0
-4.4641 -1.73205 0 -5.4641 -3.4641 0 -5.4641 -3.4641 0
-4.85173 -3.81766 -0.707107 -5.85173 -5.54971 -0.707107 -5.85173 -5.54971 -0.707107
-4.85173 -3.81766 -0.707107 -5.85173 -5.54971 -0.707107 -4.62698 -6.25681 -2.12132
-4.85173 -3.81766 -0.707107 -4.62698 -6.25681 -2.12132 -4.62698 -6.25681 -2.12132
-4.85173 -3.81766 -0.707107 -4.62698 -6.25681 -2.12132 -3.62698 -4.52476 -2.12132
-4.85173 -3.81766 -0.707107 -3.62698 -4.52476 -2.12132 -3.62698 -4.52476 -2.12132
]], table.concat(got, "\n") .. "\n")
  end)
end)
