-- Vector pictures (lsys.vector): SVG, EPS and PDF through lsys.render and `lsys render -o`:
-- the paths lines join into, their coordinates, widths and colours, the camera shared with
-- the PNG renderer, depth order, the files' structure, the same picture as the PNG, errors.
--
-- Tagged #gl as render_spec is (core.project reads the render options of the OSMesa build).
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"
local vector = require "lsys.vector"
local raster = require "tests.svg_raster"
local testing = require "lsys.testing"

local function project (m, opts)
  local p = core.project(m:interpret(), opts)
  return p, vector.paths(p)
end

local function count (s, pat)
  local n = 0
  for _ in s:gmatch(pat) do n = n + 1 end
  return n
end

-- The SVG, EPS and PDF texts of model m with render options o.
local function files (m, o)
  local dir, out = H.tmpdir(), {}
  for _, e in ipairs { "svg", "eps", "pdf" } do
    local opts = { out = dir .. "/x." .. e }
    for k, v in pairs(o or {}) do opts[k] = v end
    assert.is_true(lsys.render(m, opts))
    out[e] = H.read(dir .. "/x." .. e)
  end
  H.rmdir(dir)
  return out
end

local function xml_ok (text)
  local path = os.tmpname()
  H.write(path, text)
  local _, code = H.sh("python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])' '"
                       .. path .. "' 2>&1")
  os.remove(path)
  return code == 0
end

local square = lsys.lsystem { axiom = "F+F+F+F", view = { angle = 90 } }

describe("vector pictures #gl", function ()
  if not core.has_render then
    pending("lsys was built without OSMesa")
    return
  end

  it("draws F+F+F+F as one closed square path at the PNG's framing", function ()
    local p, items = project(square, { width = 200, height = 100 })
    assert.equal(1, #items)
    local it = items[1]
    assert.equal("stroke", it.kind)
    assert.is_true(it.closed)
    -- four corners: the square fills the height less the renderer's 5 % margin
    local corners = { 145, 95, 145, 5, 55, 5, 55, 95 }
    assert.equal(8, #it.pts)
    for k = 1, 8 do assert.near(corners[k], it.pts[k], 1e-9) end
    assert.equal(1, it.width)
    assert.equal(2, p.lines[9])                  -- the turtle's first colour, index 1
    assert.equal(p.palette[2], it.color)
    local f = files(square, { width = 200, height = 100 })
    assert.equal(1, count(f.svg, "<path "))
    assert.truthy(f.svg:find('<path d="M145 95L145 5 55 5 55 95Z"', 1, true))
    assert.truthy(f.svg:find('stroke-linecap="round" stroke-linejoin="round"', 1, true))
    assert.truthy(f.svg:find('width="200" height="100" viewBox="0 0 200 100"', 1, true))
    assert.is_true(xml_ok(f.svg))
    assert.truthy(f.eps:find("145 95 m 145 5 l 55 5 l 55 95 l h s", 1, true))
    assert.truthy(f.eps:find("%%BoundingBox: 0 0 200 100", 1, true))
    assert.truthy(f.pdf:find("145 95 m 145 5 l 55 5 l 55 95 l h S", 1, true))
  end)

  it("writes the widths and the palette colours of the lines", function ()
    local m = lsys.lsystem { axiom = "F;F", view = { angle = 90, line_width = 3 } }
    local p, items = project(m, { width = 100, height = 100 })
    assert.equal(2, #items)                       -- a new colour starts a new path
    assert.equal(3, items[1].width)
    local c1, c2 = items[1].color, items[2].color
    assert.are_not.equal(c1, c2)
    assert.equal(p.palette[2], c1)
    assert.equal(p.palette[3], c2)
    local function hex (c)
      return string.format("#%02x%02x%02x", math.floor(c[1] * 255 + 0.5),
                           math.floor(c[2] * 255 + 0.5), math.floor(c[3] * 255 + 0.5))
    end
    local svg = files(m, { width = 100, height = 100 }).svg
    assert.truthy(svg:find('stroke="' .. hex(c1) .. '" stroke-width="3"', 1, true))
    assert.truthy(svg:find('stroke="' .. hex(c2) .. '" stroke-width="3"', 1, true))
    local bg = hex(p.background)
    assert.truthy(svg:find('<rect width="100" height="100" fill="' .. bg .. '"/>', 1, true))
    -- a transparent picture has no background
    local t = files(m, { width = 100, height = 100, transparent = true })
    assert.is_nil(t.svg:find("<rect", 1, true))
    assert.is_nil(t.pdf:find(" re f", 1, true))
    -- a width that changes along a path starts a new one
    local w = lsys.lsystem { axiom = "F#F", view = { angle = 90, line_width = 2 } }
    local _, wi = project(w, { width = 100, height = 100 })
    assert.equal(2, #wi)
    assert.equal(2.5, wi[1].width)                -- tapered from 2 to 3: stroked at the mean
    assert.equal(3, wi[2].width)
  end)

  it("joins a bracketed plant's branches into one path each", function ()
    -- F[+F][-F]F: the first branch continues the stem; the second branch and the stem's
    -- continuation start again at the branch point
    local m = lsys.lsystem { axiom = "F[+F][-F]F", view = { angle = 30 } }
    local p, items = project(m, { width = 100, height = 100 })
    assert.equal(4, #p.lines / 9)
    assert.equal(3, #items)
    assert.equal(6, #items[1].pts)
    assert.equal(4, #items[2].pts)
    assert.equal(4, #items[3].pts)
    -- ABOP fig. 1.24a, one step: F[+F]F[-F]F is three paths (stem+branch, stem+branch, stem)
    local a = lsys.lsystem { axiom = "F", steps = 1, productions = "F --> F[+F]F[-F]F",
                             view = { angle = 25.7 } }
    local _, ai = project(a)
    assert.equal(3, #ai)
    local f = files(a)
    assert.equal(3, count(f.svg, "<path "))
    assert.equal(3, count(f.eps, " s\n"))
    assert.equal(3, count(f.pdf, " S\n"))
  end)

  it("projects 3D lines as the PNG renderer draws them", function ()
    -- one thick segment leaning towards the eye in perspective: the ink of the PNG lies
    -- between the projected ends, widened by half the line width
    local m = lsys.lsystem { axiom = "/(45)&(60)F(3)", view = { line_width = 6 } }
    local o = { width = 160, height = 120, projection = "perspective", fov = 40,
                viewpoint = { 4, 2, 9 }, target = { 0, 1, 0 } }
    local p, items = project(m, o)
    assert.equal(1, #items)
    local L = p.lines
    local dir = H.tmpdir()
    lsys.render(m, { out = dir .. "/x.png", width = 160, height = 120,
                     projection = "perspective", fov = 40, viewpoint = { 4, 2, 9 },
                     target = { 0, 1, 0 } })
    local ink = H.ink(dir .. "/x.png")
    H.rmdir(dir)
    local r = 3
    local box = { math.min(L[1], L[4]) - r, math.min(L[2], L[5]) - r,
                  math.max(L[1], L[4]) + r, math.max(L[2], L[5]) + r }
    for k = 1, 4 do assert.near(box[k], ink.box[k] + (k > 2 and 1 or 0), 1.5) end
    -- a real, oblique projection
    assert.is_true(math.abs(L[1] - L[4]) > 20 and math.abs(L[2] - L[5]) > 20)
    assert.is_true(L[3] < L[6])                         -- the far end deeper
  end)

  it("fills polygons and paints far to near", function ()
    -- two squares one behind the other, seen from the front: the far one first
    local m = lsys.lsystem {
      axiom = "{ f + f + f + f }f(0.5);[&(90)f(3)^(90){ f + f + f + f }]",
      view = { angle = 90 } }
    local p, items = project(m, { width = 100, height = 100, viewpoint = { 0.5, 1, -10 },
                                  target = { 0.5, 1, 0 }, projection = "perspective" })
    assert.equal(4, #p.triangles / 10)
    assert.equal(4, #items)
    for _, it in ipairs(items) do
      assert.equal("fill", it.kind)
      assert.equal(6, #it.pts)
    end
    assert.is_true(items[1].depth > items[3].depth)
    assert.equal(items[1].color, items[2].color)
    assert.are_not.equal(items[2].color, items[3].color)
    local svg = files(m, { width = 100, height = 100, viewpoint = { 0.5, 1, -10 },
                           target = { 0.5, 1, 0 }, projection = "perspective" }).svg
    assert.equal(2, count(svg, "<path "))       -- one element per run of one colour
    assert.equal(4, count(svg, "Z"))
  end)

  it("writes a PDF whose cross-reference table is right and an EPS with its box", function ()
    local a = dofile("examples/abop/fig1_24a.lua")
    local f = files(a, { width = 300, height = 400 })
    local pdf = f.pdf
    assert.equal("%PDF-1.4\n", pdf:sub(1, 9))
    local xref = tonumber(pdf:match("startxref\n(%d+)\n%%%%EOF\n$"))
    assert.equal("xref\n", pdf:sub(xref + 1, xref + 5))
    local n = tonumber(pdf:match("xref\n0 (%d+)\n", xref))
    assert.equal(5, n)
    local k = 0
    for off in pdf:sub(xref + 1):gmatch("(%d%d%d%d%d%d%d%d%d%d) 00000 n \n") do
      k = k + 1
      assert.equal(k .. " 0 obj\n", pdf:sub(tonumber(off) + 1, tonumber(off) + #(k .. " 0 obj\n")))
    end
    assert.equal(4, k)
    local len, stream = pdf:match("<< /Length (%d+) >>\nstream\n()")
    assert.equal("endstream", pdf:sub(stream + tonumber(len), stream + tonumber(len) + 8))
    assert.truthy(f.eps:find("^%%!PS%-Adobe%-3%.0 EPSF%-3%.0\n%%%%BoundingBox: 0 0 300 400\n"))
    assert.equal(count(f.svg, "<path "), count(f.eps, " s\n"))
    assert.equal(count(f.svg, "<path "), count(f.pdf, " S\n"))
    -- the three carry the same points in the same order: the EPS and the PDF are the
    -- picture the SVG is (compared with the PNG below)
    local function svgpts (t)
      local out = {}
      for d in t:gmatch(' d="([^"]*)"') do
        for v in d:gmatch("%-?[%d%.]+") do out[#out + 1] = v end
      end
      return out
    end
    local function pspts (t)
      local out = {}
      for x, y in t:gmatch("(%-?[%d%.]+) (%-?[%d%.]+) [ml]%f[%s]") do
        out[#out + 1] = x; out[#out + 1] = y
      end
      return out
    end
    local sp = svgpts(f.svg)
    assert.is_true(#sp > 1000)
    assert.same(sp, pspts(f.eps))
    assert.same(sp, pspts(f.pdf))
  end)

  it("is the same picture as the PNG", function ()
    local a = dofile("examples/abop/fig1_24a.lua")
    local dir = H.tmpdir()
    lsys.render(a, { out = dir .. "/x.svg", width = 200, height = 300 })
    local px, w, h = raster(H.read(dir .. "/x.svg"))
    local png = lsys.render(a, { width = 200, height = 300 })
    H.rmdir(dir)
    assert.equal(200, w)
    assert.equal(300, h)
    -- the renderer's anti-aliased 1-pixel lines against exact coverage: looser limits than
    -- the golden images', which a moved or mirrored plant still breaks
    local diff, far, n = 0, 0, w * h
    for i = 1, #px, 4 do
      local d = 0
      for c = 0, 2 do d = math.max(d, math.abs(px:byte(i + c) - png:byte(i + c))) end
      diff = diff + d
      if d > 60 then far = far + 1 end
    end
    assert.is_true(diff / n < 3, "mean difference " .. diff / n)
    assert.is_true(far / n < 0.02, "far pixels " .. far / n)
    -- mirrored, the same comparison fails
    local mirror = {}
    for y = 0, h - 1 do
      for x = 0, w - 1 do
        local o = (y * w + (w - 1 - x)) * 4
        mirror[#mirror + 1] = png:sub(o + 1, o + 4)
      end
    end
    assert.is_false((testing.compare_images(px, table.concat(mirror), w, h)))
  end)

  it("gives the same file for every thread count", function ()
    local function svg (threads)
      local m = lsys.lsystem { axiom = "F", steps = 3, threads = threads,
                               productions = "F --> F[+F]F[-F][&F]F", view = { angle = 25 } }
      return files(m, { width = 120, height = 120 }).svg
    end
    local one = svg(1)
    assert.equal(one, svg(4))
    assert.is_true(#one > 1000)
  end)

  it("says which formats it writes", function ()
    local dir = H.tmpdir()
    local err = H.errof(lsys.render, square, { out = dir .. "/x.gif" })
    assert.matches("unknown picture format '.gif': lsys writes .png, .svg, .eps or .pdf", err,
                   1, true)
    assert.is_nil(io.open(dir .. "/x.gif"))
    H.rmdir(dir)
    assert.has_error(function () vector.encode("tiff", {}, {}) end,
                     "unknown vector format 'tiff': lsys writes .png, .svg, .eps or .pdf")
    local sc = square:interpret()
    getmetatable(sc).__close(sc)
    assert.matches("closed", H.errof(core.project, sc))
    local pop = lsys.population { { model = square, at = { 0, 0, 0 } },
                                  { model = square, at = { 3, 0, 0 } } }
    assert.matches("vector output draws one plant, not a population of 2",
                   H.errof(lsys.render, pop, { out = "x.svg" }), 1, true)
  end)

  it("keeps within max_memory and refuses options that only a PNG has", function ()
    local sc = square:interpret()
    local old = core.max_memory()
    core.max_memory(500)                 -- the four segments' numbers need 4 * 9 * 16 bytes
    local ok, err = pcall(core.project, sc)
    core.max_memory(old)
    assert.is_false(ok)
    assert.matches("lsys.render: a vector picture of 4 lines and 0 triangles needs 576 bytes, "
                   .. "more than max_memory (500 bytes)", err, 1, true)
    assert.equal(4, #core.project(sc).lines / 9)
    assert.matches("wireframe applies to .png pictures",
                   H.errof(lsys.render, square, { out = "x.svg", wireframe = true }), 1, true)
  end)

  it("is written by lsys render -o", function ()
    local dir = H.tmpdir()
    local out, code = H.sh(string.format("cd '%s' && '%s' render abop/fig1_24a -o f.svg "
                                         .. "--size 200x300 2>&1", dir, H.ABSBIN))
    assert.equal(0, code, out)
    assert.matches("wrote f.svg (200x300, 0 triangles, 3125 lines)", out, 1, true)
    assert.is_true(xml_ok(H.read(dir .. "/f.svg")))
    out, code = H.sh(string.format("cd '%s' && '%s' render abop/fig1_24a -o f.jpg 2>&1", dir,
                                   H.ABSBIN))
    assert.are_not.equal(0, code)
    assert.matches("the output must be a .png, .svg, .eps or .pdf file, got 'f.jpg'", out, 1,
                   true)
    H.rmdir(dir)
  end)
end)
