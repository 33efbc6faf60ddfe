-- The turtle (cpfg guide, Appendix A, §2, §4.2, §6; cpfg's conventions, docs/drawing.md §1):
-- positions, frames, records, tropisms, polygons, cylinders, query modules, errors.
local H = require "tests.helper"
local lsys = require "lsys"

local function model (opts)
  opts = opts or {}
  opts.axiom = opts.axiom or ""
  return lsys.lsystem(opts)
end

-- the state after the whole string
local function final (m, text, over)
  local s = m:lstring(text)
  local sc = m:interpret(s, over)
  return sc:turtle(#s)
end

local S2 = math.sqrt(0.5)

describe("turtle frame", function ()
  local m = model { view = { angle = 90 } }

  it("starts at the origin heading up the screen, L = -x, U = -z", function ()
    local sc = m:interpret("")
    local p, h, l, u = sc:turtle(0)
    assert.same({ 0, 0, 0 }, p)
    assert.same({ 0, 1, 0 }, h)
    assert.same({ -1, 0, 0 }, l)
    assert.same({ 0, 0, -1 }, u)
  end)

  it("keeps its frame on a first turn of 0 (the turn cache once started at cos 0)", function ()
    for _, text in ipairs { "+(0)F", "-(0)F", "&(0)F", "^(0)F", "/(0)F", "\\(0)F" } do
      local p, h = final(m, text)
      assert.near({ 0, 1, 0 }, p, 1e-12)
      assert.near({ 0, 1, 0 }, h, 1e-12)
    end
  end)

  it("turns left with + (anticlockwise seen from +z)", function ()
    local p, h = final(m, "+F")
    assert.near({ -1, 0, 0 }, p, 1e-12)
    assert.near({ -1, 0, 0 }, h, 1e-12)
    p = final(m, "-(90)F(2)")
    assert.near({ 2, 0, 0 }, p, 1e-12)
  end)

  it("follows a pitch / roll / turn sequence (hand-computed frames)", function ()
    -- the frames cpfg reports with ?H ?L ?U for these strings
    -- &(90): H toward U -> H = (0,0,-1), U = (0,-1,0)
    local _, h, l, u = final(m, "&(90)")
    assert.near({ 0, 0, -1 }, h, 1e-12); assert.near({ -1, 0, 0 }, l, 1e-12)
    assert.near({ 0, -1, 0 }, u, 1e-12)
    -- /(90): L toward U -> L = (0,-1,0), U = (1,0,0)
    _, h, l, u = final(m, "&(90) /(90)")
    assert.near({ 0, 0, -1 }, h, 1e-12); assert.near({ 0, -1, 0 }, l, 1e-12)
    assert.near({ 1, 0, 0 }, u, 1e-12)
    -- +(90): H toward L -> H = (0,-1,0), L = (0,0,1)
    local p
    p, h, l, u = final(m, "&(90) /(90) +(90) F(3)")
    assert.near({ 0, -1, 0 }, h, 1e-12); assert.near({ 0, 0, 1 }, l, 1e-12)
    assert.near({ 1, 0, 0 }, u, 1e-12)
    assert.near({ 0, -3, 0 }, p, 1e-12)
    -- ^ and \ undo & and /
    _, h, l, u = final(m, "&(37) /(21) \\(21) ^(37)")
    assert.near({ 0, 1, 0 }, h, 1e-12); assert.near({ -1, 0, 0 }, l, 1e-12)
    assert.near({ 0, 0, -1 }, u, 1e-12)
  end)

  it("keeps the frame orthonormal and right-handed (L = H x U)", function ()
    local _, h, l, u = final(m, H.rep("&(13) /(27) +(41) F ", 200))
    local function dot (a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
    local cross = { h[2] * u[3] - h[3] * u[2], h[3] * u[1] - h[1] * u[3],
                    h[1] * u[2] - h[2] * u[1] }
    assert.near(1, dot(h, h), 1e-9); assert.near(1, dot(u, u), 1e-9)
    assert.near(0, dot(h, u), 1e-9)
    assert.near(l, cross, 1e-9)
  end)

  it("turns around with | and rolls U up with @v", function ()
    local p, h = final(m, "F | F(3)")
    assert.near({ 0, -2, 0 }, p, 1e-12); assert.near({ 0, -1, 0 }, h, 1e-12)
    -- L = (+y) x H, horizontal; U = L x H (cpfg's frame for this string)
    local _, h2, l2, u2 = final(m, "&(90) /(30) @v")
    assert.near({ 0, 0, -1 }, h2, 1e-12)
    assert.near({ 0, -1, 0 }, u2, 1e-12)
    assert.near({ -1, 0, 0 }, l2, 1e-12)
  end)

  it("sets position with @M and frame with @R", function ()
    local p, h, l, u = final(m, "@M(1,2,3) @R(1,0,0, 0,1,0) F")
    assert.near({ 2, 2, 3 }, p, 1e-12)
    assert.near({ 1, 0, 0 }, h, 1e-12); assert.near({ 0, 1, 0 }, u, 1e-12)
    assert.near({ 0, 0, 1 }, l, 1e-12)              -- H x U
  end)

  it("uses the view angle and step, and scales with @D @Di @Dd", function ()
    local m30 = model { view = { angle = 30, step = 2 } }
    local p = final(m30, "+F")
    assert.near({ -math.sin(math.pi / 6) * 2, math.cos(math.pi / 6) * 2, 0 }, p, 1e-12)
    assert.near({ 0, 2.5, 0 }, final(m, "@D(2) F @Dd(4) F"), 1e-12)
    assert.near({ 0, 7, 0 }, final(m, "F @Di(3) F F"), 1e-12)
  end)

  it("restores the whole state with [ ], also past 64 nested branches", function ()
    local p, h = final(m, "F [ +F ; # &F ] F")
    assert.near({ 0, 2, 0 }, p, 1e-12); assert.near({ 0, 1, 0 }, h, 1e-12)
    local deep = H.rep("[ +F ", 150) .. H.rep("] ", 150) .. "F"
    assert.near({ 0, 1, 0 }, final(m, deep), 1e-12)
  end)
end)

describe("turtle curves", function ()
  it("closes the quadratic Koch island (ABOP fig. 1.7a) on itself", function ()
    local koch = model { axiom = "F-F-F-F", view = { angle = 90 },
                         productions = "F --> F-F+F+FF-F-F+F" }
    for n = 0, 3 do
      local s = koch:derive(n)
      local sc = koch:interpret(s)
      local p, h = sc:turtle(#s)
      assert.near({ 0, 0, 0 }, p, 1e-9)
      assert.near({ -1, 0, 0 }, h, 1e-9)              -- three right turns in the axiom
      assert.equal(4 * 8 ^ n, sc.nsegments)
    end
  end)

  it("closes the Koch snowflake (angle 60)", function ()
    local flake = model { axiom = "F--F--F", view = { angle = 60 },
                          productions = "F --> F+F--F+F" }
    local s = flake:derive(4)
    assert.near({ 0, 0, 0 }, (flake:interpret(s):turtle(#s)), 1e-9)
  end)

  it("ends the dragon curve where an independent 2D walk ends, 2^(n/2) away", function ()
    local dragon = model { axiom = "FX", view = { angle = 90 },
                           productions = "X --> X+YF+\nY --> -FX-Y" }
    for _, n in ipairs { 4, 7, 10 } do
      local s = dragon:derive(n)
      local x, y, dx, dy = 0, 0, 0, 1
      for _, name in s:modules() do
        if name == "F" then x, y = x + dx, y + dy
        elseif name == "+" then dx, dy = -dy, dx
        elseif name == "-" then dx, dy = dy, -dx end
      end
      local p = dragon:interpret(s):turtle(#s)
      assert.near({ x, y, 0 }, p, 1e-9)
      assert.near(2 ^ (n / 2), math.sqrt(x * x + y * y), 1e-9)
    end
  end)
end)

describe("turtle records", function ()
  local m = model { view = { angle = 90 } }

  it("records every drawing module with its ends, frame, width and colour", function ()
    local sc = m:interpret("#(3) ;(4) F(2) f G(1) @O(0.5)")
    assert.equal(3, sc.nrecords)
    assert.equal(2, sc.nsegments)
    local r = sc:record(1)
    assert.equal("segment", r.kind); assert.equal(3, r.module)
    assert.same({ 0, 0, 0 }, r.p0); assert.same({ 0, 2, 0 }, r.p1)
    assert.same({ 0, 1, 0 }, r.H); assert.same({ -1, 0, 0 }, r.L)
    assert.equal(3, r.w0); assert.equal(4, r.color)
    r = sc:record(2)
    assert.equal(5, r.module); assert.same({ 0, 3, 0 }, r.p0); assert.same({ 0, 4, 0 }, r.p1)
    r = sc:record(3)
    assert.equal("sphere", r.kind); assert.equal(6, r.module); assert.equal(0.5, r.w0)
    assert.is_nil(sc:record(4))
    assert.equal(2, sc:find(5)); assert.is_nil(sc:find(4))
  end)

  it("links each segment to the one it grows from", function ()
    local sc = m:interpret("F [ +F F ] F")
    assert.is_nil(sc:record(1).parent)
    assert.equal(1, sc:record(2).parent)
    assert.equal(2, sc:record(3).parent)
    assert.equal(1, sc:record(4).parent)
  end)

  it("tapers a segment to the width set before the module that ends it, as cpfg", function ()
    local sc = m:interpret("!(2) F !(1) F")
    assert.equal(2, sc:record(1).w0); assert.equal(1, sc:record(1).w1)
    assert.equal(1, sc:record(2).w0); assert.equal(1, sc:record(2).w1)
    -- cpfg (its rayshade output: a cone of radii 1 and 0.5): a turn, a colour or a
    -- module the turtle does not know leaves the segment open; F f G g [ ] { } ~ and
    -- every @ module end it (cpfg's EndNode)
    for _, text in ipairs { "!(2) F + !(1) F", "!(2) F ; , A !(1) [F]", "!(2) F !(1) @O(1) F" } do
      sc = m:interpret(text)
      assert.equal(2, sc:record(1).w0); assert.equal(1, sc:record(1).w1)
    end
    sc = m:interpret("!(2) F [ !(1) F ]")
    assert.equal(2, sc:record(1).w1)
    sc = m:interpret("!(2) F @O(1) !(1) F")
    assert.equal(2, sc:record(1).w1)
    -- the segment keeps its own frame: the turn after it does not tilt it
    sc = m:interpret("!(2) F + !(1) F", { line_style = "cylinder", contour_sides = 4 })
    local _, hi = sc:bounds()
    assert.near(1, hi[1], 1e-9)                  -- the first tube's radius 1 along x
  end)

  it("keeps Z(sh,su,sl) stiffness on the next segment", function ()
    local sc = m:interpret("F Z(1,2,3) F F")
    assert.is_nil(sc:record(1).stiffness)
    assert.same({ 1, 2, 3 }, sc:record(2).stiffness)
    assert.is_nil(sc:record(3).stiffness)
  end)

  it("changes widths and colours by the view increments", function ()
    local mi = model { view = { line_width = 2, width_increment = 0.5, color = 3,
                                color_increment = 2 } }
    local sc = mi:interpret("F # F ! ! F ; F , , F")
    local w, c = {}, {}
    for k, r in sc:records() do w[k], c[k] = r.w0, r.color end
    assert.same({ 2, 2.5, 1.5, 1.5, 1.5 }, w)
    assert.same({ 3, 3, 3, 5, 1 }, c)
  end)

  it("gives a segment's tube or ribbon to its record (scene:edges, scene:vertices)", function ()
    -- the record is made at F and the tube when the segment ends: the tube is its own
    local text = "F(1) F(2) [+F(1)]"
    local sc = m:interpret(text, { line_style = "polygon" })
    assert.same({ { -0.5, 1, 0 }, { 0.5, 1, 0 }, { 0.5, 3, 0 }, { -0.5, 3, 0 } }, sc:vertices(2))
    assert.equal(5, #sc:edges(2))                       -- two triangles
    sc = m:interpret(text, { line_style = "cylinder", contour_sides = 4 })
    local v = sc:vertices(2)                            -- the rings at y = 1 and 3 (seam twice)
    assert.equal(10, #v)
    for i, p in ipairs(v) do
      assert.equal(i <= 5 and 1 or 3, p[2])
      assert.near(0.5, math.sqrt(p[1] ^ 2 + p[3] ^ 2), 1e-12)
    end
    assert.equal(17, #sc:edges(2))       -- 4 quads: 4 + 4 around the rings, 5 along, 4 across
    assert.equal(25, #sc:edges(1))                      -- and the start's cap of 4 triangles
    local n = 0
    for k in sc:records() do n = n + #sc:vertices(k) end
    assert.equal(15 + 10 + 15, n)
    sc = m:interpret(text)                              -- lines: no triangles
    assert.same({}, sc:edges(2))
    assert.same({}, sc:vertices(2))
  end)

  it("skips modules it does not know", function ()
    local sc = m:interpret("A F B(1,2) F Xyz")
    assert.equal(2, sc.nsegments)
    assert.equal(2, sc:record(1).module); assert.equal(4, sc:record(2).module)
  end)
end)

describe("the symbol table", function ()
  local core = require "lsys.core"

  it("lists each named symbol once, with its split class and the query modules", function ()
    local rows, seen, queries = core.symbols(), {}, {}
    local split = { cross = true, state = true, open = true, close = true, segment = true,
                    shape = true, record = true }
    for _, r in ipairs(rows) do
      assert.is_nil(seen[r.name])
      seen[r.name] = r
      assert.is_true(split[r.split])
      if r.query then queries[#queries + 1] = r.name end
    end
    assert.same({ "?P", "?H", "?U", "?L" }, queries)
    assert.equal("open", seen["["].split)
    assert.equal("close", seen["]"].split)
    assert.equal("segment", seen.F.split)
    assert.equal("cross", seen["{"].split)
    assert.equal("LEFT", seen["+"].op)
    assert.not_equal(core.symbols(), core.symbols())      -- a new table each call
  end)

  it("is the table of docs/drawing.md section 1", function ()
    local doc, names = H.read("docs/drawing.md"), {}
    local section = doc:match("\n## 1%. The turtle\n(.-)\n## ")
    for row in section:gmatch("\n(| `[^\n]*)") do
      local first = row:match("^| (.-) |")
      for span in first:gmatch("`([^`]+)`") do
        for word in span:gmatch("%S+") do
          names[(word:gsub("\\|", "|"):match("^[^(]+") or word)] = true
        end
      end
    end
    local missing = {}
    for _, r in ipairs(core.symbols()) do
      if not names[r.name] then missing[#missing + 1] = r.name end
    end
    assert.same({}, missing)
  end)
end)

describe("tropisms", function ()
  it("bends H toward T by e|H x T| before each move (eq. 1)", function ()
    for _, e in ipairs { 0.1, 0.3, 0.6 } do
      local m = model { view = { tropisms = { { vector = { 1, 0, 0 }, elasticity = e } } } }
      local p, h = final(m, "F")
      assert.near({ math.sin(e), math.cos(e), 0 }, p, 1e-12)
      assert.near({ math.sin(e), math.cos(e), 0 }, h, 1e-12)
      -- T at 45 degrees: beta = e sin 45
      m = model { view = { tropisms = { { vector = { 1, 1, 0 }, elasticity = e } } } }
      local b = e * S2
      assert.near({ math.sin(b), math.cos(b), 0 }, (final(m, "F")), 1e-12)
    end
  end)

  it("bends a second segment from the new heading", function ()
    local e = 0.2
    local m = model { view = { tropisms = { { vector = { 1, 0, 0 }, elasticity = e } } } }
    local b2 = e * math.cos(e)           -- |H x T| = cos e after the first bend
    local p = final(m, "F F")
    assert.near({ math.sin(e) + math.sin(e + b2), math.cos(e) + math.cos(e + b2), 0 }, p, 1e-12)
  end)

  it("steers toward the angle gamma with the tropism vector (eq. 2)", function ()
    -- H at 45 degrees to T = +x, plagiotropism gamma = 90:
    -- alpha = e (0 - 1 * cos45 / sin45) (H x T), of length e sin45, away from T
    local e = 0.1
    local m = model { view = { tropisms = { { vector = { 1, 0, 0 }, angle = 90,
                                              elasticity = e } } } }
    local _, h = final(m, "-(45) F")
    local a = math.pi / 4 - e * S2
    assert.near({ math.sin(a), math.cos(a), 0 }, h, 1e-12)
  end)

  it("changes elasticities with @Ts @Ti @Td, restored by ]", function ()
    local m = model { view = { tropisms = { { vector = { 1, 0, 0 }, elasticity = 0,
                                              increment = 0.25 } } } }
    assert.near({ 0, 1, 0 }, (final(m, "F")), 1e-12)
    local _, h = final(m, "@Ts(1, 0.3) F")
    assert.near({ math.sin(0.3), math.cos(0.3), 0 }, h, 1e-12)
    _, h = final(m, "@Ti(1) F")
    assert.near({ math.sin(0.25), math.cos(0.25), 0 }, h, 1e-12)
    _, h = final(m, "@Ts(1, 0.5) @Td(1) @Ti(1, 0.05) F")
    assert.near({ math.sin(0.3), math.cos(0.3), 0 }, h, 1e-12)
    _, h = final(m, "[ @Ts(1, 0.5) ] F")
    assert.near({ 0, 1, 0 }, h, 1e-12)
  end)

  it("removes the twist of rolls unless @Tf forces it", function ()
    local m = model { view = { tropisms = { { vector = { 1, 0, 0 }, elasticity = 0.2 } } } }
    local _, _, _, u = final(m, "F /(90) F")          -- the roll is undone
    assert.near(0, u[1] * 0 + u[2] * 0 + u[3] * -1 - 1, 1e-9)
    local _, h, _, u2 = final(m, "F /(90) @Tf F")     -- kept
    assert.near(0, u2[1] * h[1] + u2[2] * h[2] + u2[3] * h[3], 1e-12)
    assert.near(0, u2[3], 1e-9)
  end)

  it("twists U about H by a torque as cpfg does (§6.1)", function ()
    -- H = +y, U = -z, T = +x: V = (H x T) x H = +x, and U turns by |U x e V| = e radians
    -- away from V (cpfg's rotation turns that way: tests/data/cpfg_probes.lua, "torque")
    local e = 0.4
    local m = model { view = { torques = { { vector = { 1, 0, 0 }, elasticity = e } } } }
    local _, h, _, u = final(m, "F")
    assert.near({ 0, 1, 0 }, h, 1e-12)
    assert.near({ -math.sin(e), 0, -math.cos(e) }, u, 1e-12)
    -- at most one radian per move; the intensity multiplies the elasticity
    m = model { view = { torques = { { vector = { 1, 0, 0 }, elasticity = 5 } } } }
    _, _, _, u = final(m, "F")
    assert.near({ -math.sin(1), 0, -math.cos(1) }, u, 1e-12)
    m = model { view = { torques = { { vector = { 1, 0, 0 }, elasticity = 0.8,
                                       intensity = 0.5 } } } }
    _, _, _, u = final(m, "F")
    assert.near({ -math.sin(e), 0, -math.cos(e) }, u, 1e-12)
  end)

  it("bends after each move by the old-style tropism that _ sets (cpfg's bend)", function ()
    -- T = +x, H = +y, L = -x, U = -z: T . U = 0, then H turns towards L by asin(e T . L)
    local m = model { view = { old_tropism = { vector = { 1, 0, 0 }, increment = 0.25 } } }
    local p, h = final(m, "F(2)")
    assert.near({ 0, 2, 0 }, p, 1e-12) assert.near({ 0, 1, 0 }, h, 1e-12)
    p, h = final(m, "_(0.5) F(2)")                    -- the move first, then the bend
    assert.near({ 0, 2, 0 }, p, 1e-12)
    local a = math.asin(0.5)                           -- towards -L = +x
    assert.near({ math.sin(a), math.cos(a), 0 }, h, 1e-12)
    p = final(m, "_ _ F(1) F(1)")                      -- _ adds the increment twice
    assert.near({ math.sin(a), 1 + math.cos(a), 0 }, p, 1e-12)
    p = final(m, "[ _(0.5) F(1) ] F(1) F(1)")          -- ] restores the elasticity
    assert.near({ 0, 2, 0 }, p, 1e-12)
  end)
end)

describe("geometry", function ()
  it("draws lines in line style with their widths", function ()
    local m = model { view = { line_width = 3 } }
    local sc = m:interpret("F F")
    assert.equal(2, sc.nlines); assert.equal(0, sc.ntriangles)
  end)

  it("draws flat ribbons in polygon style", function ()
    local m = model { view = { line_style = "polygon", line_width = 0.5 } }
    local sc = m:interpret("F(2) F")
    assert.equal(4, sc.ntriangles)
    assert.near(0.5 * 3, sc:area(), 1e-6)
  end)

  it("tessellates cylinders with contour_sides sides, sharing rings and capping ends", function ()
    local m = model { view = { line_style = "cylinder", contour_sides = 6 } }
    assert.equal(2 * 6 + 2 * 6, m:interpret("F").ntriangles)
    assert.equal(2 * 2 * 6 + 2 * 6, m:interpret("F F").ntriangles)   -- one shared ring
    assert.equal(3 * 2 * 6 + 2 * 6 + 2 * 6, m:interpret("F [ -(60) F ] F").ntriangles)
    local m4 = model { view = { line_style = "cylinder", contour_sides = 4 } }
    local lo, hi = m4:interpret("F(3)"):bounds()
    assert.near({ -0.5, 0, -0.5 }, lo, 1e-6)
    assert.near({ 0.5, 3, 0.5 }, hi, 1e-6)
  end)

  it("takes the sides of cylinders from @!(n), one symbol as in cpfg", function ()
    local m = model { view = { line_style = "cylinder", contour_sides = 6 } }
    assert.equal(2 * 5 + 2 * 5, m:interpret("@!(5) F").ntriangles)
    assert.equal(2 * 8 + 2 * 8, m:interpret("@! F").ntriangles)          -- cpfg's default 8
    assert.equal(2 * 3 + 2 * 3, m:interpret("@!(2) F").ntriangles)       -- at least 3
    -- ] restores the sides; a ring of other sides is not shared: both ends capped
    assert.equal(2 * (2 * 12 + 2 * 12) + 2 * 6 + 2 * 6,
                 m:interpret("[ @!(12) F ] [ @!(12) F ] F").ntriangles)
    assert.equal((2 * 4 + 2 * 4) + (2 * 9 + 2 * 9), m:interpret("@!(4) F @!(9) F").ntriangles)
    -- generalized cylinders too: one strip of 7 sides, two caps of 5 triangles
    assert.equal(2 * 7 + 2 * 5, m:interpret("@!(7) @Gs f @Ge(1)").ntriangles)
    assert.equal(1, #m:lstring("@!(5)"))                                  -- not @ and !(5)
    assert.error_contains(function () m:interpret("@!(2000) F") end, "2000 sides",
                          "at most 1024")
  end)

  it("fills { . } polygons, concave ones too", function ()
    local m = model { view = { angle = 90 } }
    -- an L-shaped hexagon of area 3: 4 triangles
    local sc = m:interpret("{ . f(2) . + f . + f . - f . + f . + f(2) . }")
    assert.equal(4, sc.ntriangles)
    assert.near(3, sc:area(), 1e-9)
    assert.equal("polygon", sc:record(1).kind)
  end)

  it("takes polygon vertices from F and f inside braces but not from G and g", function ()
    local m = model { view = { angle = 90 } }
    local sc = m:interpret("{ F + F + F + F }")
    -- F draws its segment too, as cpfg draws the edges (its F calls StartNode in a polygon)
    assert.near(1, sc:area(), 1e-9); assert.equal(4, sc.nlines)
    sc = m:interpret("{ f + f + f + f }")
    assert.near(1, sc:area(), 1e-9); assert.equal(0, sc.nlines)
    sc = m:interpret("{ . G(2) + g . + f . }")                 -- G draws but adds no vertex
    assert.near(0.5, sc:area(), 1e-9)
    assert.equal(1, sc.nlines)
  end)

  it("keeps nested polygons apart on the polygon stack (§4.2, fig. 25)", function ()
    local m = model { view = { angle = 90 } }
    -- outer (0,0) (0,1) ... (-2,0): area 1; inner (-1,1) (-2,1) (-2,0): area 0.5
    local sc = m:interpret("{ . g . { + g . g . + g . } . }")
    assert.equal(2, sc.nrecords)
    assert.near(1.5, sc:area(), 1e-9)
    assert.near({ -2, 0, 0 }, sc:record(1).p1, 1e-6)          -- the inner one ends first
  end)

  it("draws discs and spheres of the line width or their parameter", function ()
    local m = model { view = { contour_sides = 16, line_width = 2 } }
    local sc = m:interpret("@c")
    assert.equal(16, sc.ntriangles)
    assert.near(16 * 0.5 * math.sin(2 * math.pi / 16), sc:area(), 1e-6)
    sc = m:interpret("@O(4)")
    local lo, hi = sc:bounds()
    assert.near({ -2, -2, -2 }, lo, 0.2); assert.near({ 2, 2, 2 }, hi, 0.2)
    assert.near(2, hi[2], 1e-6)                      -- poles on H
  end)
end)

describe("homomorphism while interpreting", function ()
  it("draws the homomorphism's successors in place of the module", function ()
    local m = model { homomorphism = "A(x) --> F(x) + F(x)", view = { angle = 90 } }
    local s = m:lstring("A(2) B A(1)")
    local sc = m:interpret(s)
    assert.equal(4, sc.nsegments)
    assert.equal(1, sc:record(1).module); assert.equal(1, sc:record(2).module)
    assert.equal(3, sc:record(3).module)
    assert.equal("A(2)BA(1)", tostring(s))          -- the string itself is unchanged
    local p = sc:turtle(#s)                  -- up 2, left 2, left 1, down 1
    assert.near({ -3, 1, 0 }, p, 1e-12)
  end)
end)

describe("query modules", function ()
  it("fill ?P ?H ?U ?L from the string of the previous step (cpfg)", function ()
    local m = model {
      axiom = "F(2) +(90) F(1) ?P(0,0,0) ?H(0,0,0) A",
      productions = "?P(x,y,z) ?H(a,b,c) < A --> B(x, y, a)",
      view = { angle = 90 },
    }
    local s = m:derive(1)
    local _, b1, b2, b3 = s:module(#s)
    assert.near({ -1, 2, -1 }, { b1, b2, b3 }, 1e-12)
    local _, x, y, z = s:module(4)              -- the final string gets a pass too
    assert.near({ -1, 2, 0 }, { x, y, z }, 1e-12)
  end)

  it("fill ?U and ?L", function ()
    local m = model { axiom = "&(90) ?U(0,0,0) ?L(0,0,0)", productions = "A --> A" }
    local s = m:derive(0)                           -- the final string gets its pass
    local _, a, b, c = s:module(2)
    assert.near({ 0, -1, 0 }, { a, b, c }, 1e-12)      -- cpfg: ?U(0,-1,-6.12323e-17)
    s = m:derive(1)
    _, a, b, c = s:module(2)
    assert.near({ 0, -1, 0 }, { a, b, c }, 1e-12)
    _, a, b, c = s:module(3)
    assert.near({ -1, 0, 0 }, { a, b, c }, 1e-12)
  end)
end)

describe("turtle errors", function ()
  it("refuses @S unless the model allows system calls", function ()
    local m = model {}
    assert.error_contains(function () m:interpret("F @S") end, "module 2", "@S", "refused",
                          "allow_system_calls")
    local calls = {}
    local ok = model { allow_system_calls = true,
                       system_call = function (i, ...) calls[#calls + 1] = { i, ... } end }
    ok:interpret("F @S(7)")
    assert.same({ { 2, "@S", 7 } }, calls)
  end)

  it("checks tropism indices and view options", function ()
    local m = model { view = { tropisms = { { vector = { 1, 0, 0 } } } } }
    assert.error_contains(function () m:interpret("@Ts(2, 1) F") end, "module 1",
                          "tropism index 2")
    assert.error_contains(function () lsys.lsystem { view = { colour = 1 } } end,
                          "unknown view option 'colour'")
    assert.error_contains(function () lsys.lsystem { view = { line_style = "tube" } } end,
                          "line_style")
    assert.error_contains(function () m:interpret("F", { contour_sides = 2 }) end,
                          "contour_sides")
    assert.error_contains(function ()
      lsys.lsystem { view = { tropisms = { { vector = { 1, 0 } } } } }
    end, "vector")
  end)

  it("reports a Lua error inside a homomorphism rule with the rule", function ()
    local m = model { homomorphism = { { "A(x)", function () error("boom") end } } }
    assert.error_contains(function () m:interpret("F A(1)") end, "homomorphism", "boom")
  end)
end)

describe("view options reaching the turtle", function ()
  it("refuses out-of-range integers before converting them", function ()
    local m = lsys.lsystem { axiom = "F" }
    assert.error_contains(function () m:interpret("F", { color = 1e18 }) end,
                          "view option 'color' must be between 0 and 65535")
    assert.error_contains(function () m:interpret("F", { contour_sides = 1e12 }) end,
                          "contour_sides")
  end)

  it("uses palette entry 1 for colour 0 when the palette has no [0]", function ()
    local m = lsys.lsystem { view = { palette = { { 1, 0, 0 } } } }
    assert.equal(1, m:interpret(";(0) F").nlines)
    local m2 = lsys.lsystem { view = { palette = { [0] = { 0, 0, 1 } } } }
    assert.equal(1, m2:interpret("F").nlines)
  end)
end)
