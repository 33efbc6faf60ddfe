-- Scene export round trips: OBJ (+ MTL), binary PLY and glTF binary written by scene:save and
-- read back by independent readers (tests/export_reader.lua, tests/glb.lua).
require "tests.helper"
local lsys = require "lsys"
local R = require "tests.export_reader"
local glb = require "tests.glb"

local tmp = os.tmpname()
os.remove(tmp)
local function path (ext) return tmp .. ext end

-- triangles and line segments in a .glb, summed over its primitives
local function glb_counts (file)
  local doc, bin = glb.read(file)
  local tris, segs = 0, 0
  for _, pr in ipairs(glb.primitives(doc, bin)) do
    if pr.mode == 4 then tris = tris + pr.triangles
    elseif pr.mode == 1 then segs = segs + pr.segments end
  end
  return tris, segs
end

local function cleanup ()
  for _, e in ipairs { ".obj", ".mtl", ".ply", ".glb" } do os.remove(path(e)) end
end

-- the sRGB transfer function: glTF's colour factors are linear, the palette's are display
-- values (Blender reads MTL colours as linear too)
local function linear (c)
  if type(c) == "table" then
    local t = {}
    for i = 1, 3 do t[i] = linear(c[i]) end
    return t
  end
  return c <= 0.04045 and c / 12.92 or ((c + 0.055) / 1.055) ^ 2.4
end

-- cylinders in two colours, a leaf polygon (two-sided) and a line set from a second scene
local plant = lsys.lsystem {
  axiom = ";(1) F [ +F ;(2) { . -f . +f . +f . } ] F",
  view = { line_style = "cylinder", contour_sides = 6, angle = 45 },
}

describe("export", function ()
  local sc
  setup(function () sc = plant:interpret() end)
  teardown(cleanup)

  it("knows its own counts", function ()
    -- 3 segments: the first and last share a ring; the branch has its own, capped
    assert.equal(3, sc.nsegments)
    assert.equal(3 * 2 * 6 + 2 * 6 + 2 * 6 + 2, sc.ntriangles)
    assert.equal(0, sc.nlines)
  end)

  it("writes OBJ with a material library", function ()
    sc:save(path(".obj"))
    local o = R.obj(path(".obj"))
    assert.equal(sc.nvertices, o.v)
    assert.equal(sc.nvertices, o.vn)
    assert.equal(sc.nvertices, o.vt)
    assert.equal(sc.ntriangles, o.f)
    assert.equal(sc.ntriangles, o.triangles)
    assert.equal(0, o.l)
    assert.matches("%.mtl$", o.mtllib)
    assert.equal(2, #o.materials)
    assert.equal(2, o.faces_by_material.m2)
    local mt = R.mtl(path(".mtl"))
    assert.same({ "m1", "m2" }, mt.names)
    assert.near(linear(lsys.view.PALETTE[2]), mt.m2.Kd, 1e-6)
  end)

  it("writes binary PLY", function ()
    sc:save(path(".ply"))
    local p = R.ply(path(".ply"))
    assert.equal(sc.nvertices, p.counts.vertex)
    assert.equal(sc.ntriangles, p.counts.face)
    assert.equal("binary_little_endian", p.format)
  end)

  it("writes glTF binary with positions inside the declared bounds", function ()
    sc:save(path(".glb"))
    local doc, bin = glb.read(path(".glb"))
    assert.equal("2.0", doc.asset.version)
    local prims = glb.primitives(doc, bin)
    local tris, lo, hi = 0, sc:bounds()
    for _, pr in ipairs(prims) do
      if pr.mode == 4 then tris = tris + pr.triangles end
      for k = 1, 3 do
        assert.is_true(pr.min[k] >= lo[k] - 1e-5 and pr.max[k] <= hi[k] + 1e-5)
        assert.near(pr.declared_min[k], pr.min[k], 1e-6)
      end
    end
    assert.equal(sc.ntriangles, tris)
    assert.equal(2, #doc.materials)
    local double = 0
    for _, m in ipairs(doc.materials) do if m.doubleSided then double = double + 1 end end
    assert.equal(1, double)                      -- the leaf's material
  end)

  it("writes line sets as OBJ l elements and glTF LINES", function ()
    local ls = lsys.lsystem { axiom = "F + F + F", view = { angle = 120 } }:interpret()
    assert.equal(3, ls.nlines)
    ls:save(path(".obj"))
    assert.equal(3, R.obj(path(".obj")).l)
    ls:save(path(".glb"))
    assert.equal(3, select(2, glb_counts(path(".glb"))))
  end)

  it("round-trips the default tree through every format", function ()
    local m = dofile("examples/default.lua")
    local t = m:interpret(m:derive(4), { line_style = "cylinder" })
    assert.is_true(t.ntriangles > 1000)
    t:save(path(".ply"))
    assert.equal(t.ntriangles, R.ply(path(".ply")).counts.face)
    t:save(path(".glb"))
    assert.equal(t.ntriangles, (glb_counts(path(".glb"))))
  end)

  it("fails clearly on unwritable paths and unknown formats", function ()
    assert.error_contains(function () sc:save("/nonexistent/dir/x.obj") end,
                          "/nonexistent/dir/x", "cannot open")
    assert.error_contains(function () sc:save(path(".stl")) end, "unknown format", ".obj")
  end)
end)

describe("export formats", function ()
  local core = require "lsys.core"

  it("are listed by the core in one order, with what each writes", function ()
    local rows = core.formats()
    local names = {}
    for i, f in ipairs(rows) do names[i] = f.name end
    assert.same({ "obj", "ply", "glb" }, names)
    assert.same({ name = "obj", ext = "obj", title = "Wavefront OBJ", companion = "mtl",
                  textures = true, instancing = false }, rows[1])
    assert.same({ name = "ply", ext = "ply", title = "binary PLY", textures = false,
                  instancing = false }, rows[2])
    assert.same({ name = "glb", ext = "glb", title = "glTF 2.0 binary", textures = true,
                  instancing = true }, rows[3])
    assert.not_equal(core.formats(), core.formats())       -- a new table each call
  end)

  it("are what scene:save writes, and what its message lists", function ()
    local sc = lsys.lsystem { axiom = "F+F" }:interpret()
    local exts = {}
    for _, f in ipairs(core.formats()) do
      local file = path("." .. f.ext)
      -- what the file holds: two line segments
      assert.same({ vertices = 0, triangles = 0, lines = 2, instances = 0 }, sc:save(file))
      assert.truthy(io.open(file, "rb")):close()
      if f.companion then assert.truthy(io.open(path("." .. f.companion), "rb")):close() end
      exts[#exts + 1] = "." .. f.ext
    end
    cleanup()
    local list = table.concat(exts, ", ", 1, #exts - 1) .. " or " .. exts[#exts]
    assert.has_error(function () sc:save(path(".stl")) end,
                     "scene:save: unknown format of '" .. path(".stl") .. "' (use " .. list .. ")")
  end)

  it("are the ones the export command and lsys.batch list", function ()
    local names = require("lsys.batch.formats").names
    assert.same({ "png", "glb", "obj", "ply", "lstring", "stats" }, names)
    local help = require("lsys.cli.help")
    assert.truthy(help.usage:find("write a model's geometry to OUT (.obj, .ply or .glb)", 1, true))
    assert.truthy(help.help.export:find("-o OUT.{obj,ply,glb} ", 1, true))
    assert.truthy(help.help.batch:find("), png, glb, obj, ply, lstring, stats, and a", 1, true))
    assert.truthy(help.help.batch:find(" .glb .obj .ply (meshes)", 1, true))
  end)
end)

describe("export colours", function ()
  -- palette entry 1: sRGB (0.5, 0.25, 1) at half opacity, glowing red at 0.5
  local sc
  setup(function ()
    sc = lsys.lsystem {
      axiom = "F", view = { line_style = "cylinder", contour_sides = 4, palette = {
        { diffuse = { 0.5, 0.25, 1, 0.5 }, emission = { 0.5, 0, 0 } } } },
    }:interpret()
  end)
  teardown(cleanup)

  it("writes glTF colour factors linear, alpha as it is", function ()
    sc:save(path(".glb"))
    local m = glb.read(path(".glb")).materials[1]
    local f = m.pbrMetallicRoughness.baseColorFactor
    assert.near({ 0.21404114, 0.050876088, 1, 0.5 }, f, 1e-8)
    assert.near(linear { 0.5, 0.25, 1 }, { f[1], f[2], f[3] }, 1e-7)
    assert.near({ 0.21404114, 0, 0 }, m.emissiveFactor, 1e-8)
    assert.equal("BLEND", m.alphaMode)
  end)

  it("writes MTL colours linear (as Blender reads them)", function ()
    sc:save(path(".obj"))
    local mt = R.mtl(path(".mtl"))
    assert.near({ 0.21404114, 0.050876088, 1 }, mt.m1.Kd, 1e-8)
    assert.near({ 0.21404114, 0, 0 }, mt.m1.Ke, 1e-8)
  end)

  it("keeps PLY vertex colours as 8-bit sRGB", function ()
    sc:save(path(".ply"))
    local v = R.ply(path(".ply")).first_vertex
    assert.same({ 128, 64, 255 }, { v.red, v.green, v.blue })
  end)
end)

describe("export lines as tubes", function ()
  -- F+F in line style: two segments meeting at a right angle, 10 units of extent
  local lines = lsys.lsystem { axiom = "F(10) + F(10)", view = { angle = 90 } }
  local sc
  setup(function () sc = lines:interpret() end)
  teardown(cleanup)

  it("keeps lines as lines by default", function ()
    sc:save(path(".glb"))
    assert.same({ 0, 2 }, { glb_counts(path(".glb")) })
  end)

  it("writes each segment as a closed tube in every format", function ()
    -- two runs (the bend is over 30 degrees): 2 rings and 2 caps each, 4 n triangles
    sc:save(path(".glb"), { lines = "tubes", sides = 6 })
    assert.same({ 48, 0 }, { glb_counts(path(".glb")) })
    sc:save(path(".obj"), { lines = "tubes", sides = 6 })
    local o = R.obj(path(".obj"))
    assert.same({ 48, 0, 56 }, { o.f, o.l, o.v })
    sc:save(path(".ply"), { lines = "tubes", sides = 6 })
    local p = R.ply(path(".ply"))
    assert.same({ 48, 56 }, { p.counts.face, p.counts.vertex })
    assert.is_nil(p.counts.edge)
  end)

  it("shares the rings of a straight run", function ()
    local run = lsys.lsystem { axiom = "F F F" }:interpret()
    run:save(path(".glb"), { lines = "tubes", sides = 6 })
    assert.same({ 4 * 6 + 2 * 2 * 6, 0 }, { glb_counts(path(".glb")) })
  end)

  it("takes the view's contour_sides by default", function ()
    lsys.lsystem { axiom = "F", view = { contour_sides = 5 } }:interpret()
      :save(path(".glb"), { lines = "tubes" })
    assert.equal(20, (glb_counts(path(".glb"))))
    sc:save(path(".glb"), { lines = "tubes" })
    assert.equal(2 * 4 * 8, (glb_counts(path(".glb"))))
  end)

  it("sizes a pixel of line width as one of an 800-pixel render", function ()
    -- the plant spans 10 units, fitted into 720 pixels: a 1-pixel line is 10/720 thick
    local lo, hi = sc:bounds()
    sc:save(path(".glb"), { lines = "tubes", sides = 4 })
    local doc, bin = glb.read(path(".glb"))
    local pr = glb.primitives(doc, bin)[1]
    local r = 0.5 * 10 / 720
    -- rings about the y axis (x in [-r, r]) and about the line y = 10
    assert.near({ lo[1], lo[2], -r }, pr.min, 1e-6)
    assert.near({ hi[1] + r, hi[2] + r, r }, pr.max, 1e-6)
    -- !(4): four pixels wide; pixel_size sets the scale
    lsys.lsystem { axiom = "!(4) F(10) + F(10)", view = { angle = 90 } }:interpret()
      :save(path(".glb"), { lines = "tubes", sides = 4, pixel_size = 0.5 })
    doc, bin = glb.read(path(".glb"))
    assert.near({ hi[1] + 1, hi[2] + 1, 1 }, glb.primitives(doc, bin)[1].max, 1e-6)
  end)

  it("checks its options", function ()
    assert.error_contains(function () sc:save(path(".glb"), { lines = "tube" }) end,
                          "opts.lines must be 'lines' or 'tubes', got 'tube'")
    assert.error_contains(function () sc:save(path(".glb"), { line = "tubes" }) end,
                          "unknown option 'line'")
    assert.error_contains(function () sc:save(path(".glb"), { lines = "tubes", sides = 2 }) end,
                          "opts.sides must be an integer in [3, 1024], got 2")
    assert.error_contains(function () sc:save(path(".glb"), { pixel_size = -1 }) end,
                          "opts.pixel_size must be a positive number, got -1")
    assert.error_contains(function () sc:save(path(".glb"), "tubes") end, "table expected")
  end)
end)

describe("glTF validator", function ()
  local validator = "tools/node_modules/gltf-validator"
  local f = io.open(validator .. "/package.json")
  if f then f:close() end
  local it_ = f and it or pending
  it_("accepts the default tree (tools/validate_glb.js)", function ()
    local m = dofile("examples/default.lua")
    m:interpret(m:derive(3), { line_style = "cylinder" }):save(path(".glb"))
    local p = io.popen("node tools/validate_glb.js " .. path(".glb") .. " 2>&1; echo rc=$?")
    local out = p:read("a")
    p:close()
    assert.matches("rc=0", out)
  end)
  it_("accepts lines as tubes and translucent, glowing materials", function ()
    lsys.lsystem {
      axiom = "F(10) + ;(2) F(10) [ ;(1) - F(5) ] F(5)", view = { angle = 90, palette = {
        { diffuse = { 0.5, 0.25, 1, 0.5 }, emission = { 0.5, 0, 0 } }, "#3050ff" } },
    }:interpret():save(path(".glb"), { lines = "tubes" })
    local p = io.popen("node tools/validate_glb.js --strict " .. path(".glb") ..
                       " 2>&1; echo rc=$?")
    local out = p:read("a")
    p:close()
    assert.matches("rc=0", out)
  end)
end)

describe("export with textures", function ()
  local core = require "lsys.core"
  local dir, files = os.tmpname(), {}
  os.remove(dir)
  local function file (name) return dir .. "/" .. name end
  local sc
  setup(function ()
    assert(os.execute("mkdir -p '" .. dir .. "'"))
    -- a 2 x 2 checker with one transparent texel, and a 1 x 1 brown image
    core.png_write(file("leaf.png"), string.char(255, 0, 0, 255, 0, 255, 0, 0,
                                                 0, 0, 255, 255, 255, 255, 255, 255), 2, 2, true)
    core.png_write(file("bark.png"), string.char(120, 80, 40, 255), 1, 1, false)
    for _, n in ipairs { "leaf.png", "bark.png" } do
      local f = assert(io.open(file(n), "rb"))
      files[n] = f:read("a")
      f:close()
    end
    -- a textured polygon, a textured stem (decal, linear filters) and a plain one
    sc = lsys.lsystem {
      axiom = "@Tx(1) { f + f + f + f } @Tx(2) F @Tx(0) F",
      view = { angle = 90, line_style = "cylinder", contour_sides = 6, textures = {
        file("leaf.png"), { file = file("bark.png"), mode = "decal", mag = "l", min = "l" } } },
    }:interpret()
  end)
  teardown(function () os.execute("rm -rf '" .. dir .. "'") end)

  it("writes OBJ texture coordinates and MTL materials naming the images", function ()
    sc:save(file("t.obj"))
    local o = R.obj(file("t.obj"))
    assert.equal(sc.nvertices, o.vt)
    assert.equal(sc.nvertices, o.max_vt)
    assert.equal(sc.ntriangles, o.triangles)
    assert.same({ "m1", "m1_t1", "m1_t2" }, o.materials)
    assert.equal(2, o.faces_by_material.m1_t1)
    local f = assert(io.open(file("t.mtl")))
    local mtl = f:read("a")
    f:close()
    local maps = {}
    for m in mtl:gmatch("map_Kd ([^\n]*)") do maps[#maps + 1] = m end
    assert.same({ file("leaf.png"), file("bark.png") }, maps)
    assert.matches("newmtl m1_t2\nKa [^\n]*\nKd 1 1 1\n", mtl)      -- decal: white, unlit
    assert.matches("illum 0\nmap_Kd " .. file("bark.png"):gsub("%p", "%%%0"), mtl)
  end)

  it("embeds the images in glTF binary with samplers and textured materials", function ()
    sc:save(file("t.glb"))
    local doc, bin = glb.read(file("t.glb"))
    assert.equal(2, #doc.images)
    assert.equal(2, #doc.textures)
    assert.equal(2, #doc.samplers)
    assert.same({ "KHR_materials_unlit" }, doc.extensionsUsed)
    for i, name in ipairs { "leaf.png", "bark.png" } do
      local im = doc.images[i]
      assert.equal("image/png", im.mimeType)
      local bv = doc.bufferViews[im.bufferView + 1]
      assert.equal(files[name], bin:sub(bv.byteOffset + 1, bv.byteOffset + bv.byteLength))
      assert.same({ sampler = i - 1, source = i - 1 }, doc.textures[i])
    end
    assert.same({ magFilter = 9728, minFilter = 9728, wrapS = 10497, wrapT = 10497 },
                doc.samplers[1])
    assert.equal(9729, doc.samplers[2].magFilter)
    local byname = {}
    for _, m in ipairs(doc.materials) do byname[m.name] = m end
    assert.is_nil(byname.m1.pbrMetallicRoughness.baseColorTexture)
    assert.equal(0, byname.m1_t1.pbrMetallicRoughness.baseColorTexture.index)
    assert.equal("MASK", byname.m1_t1.alphaMode)                  -- the transparent texel
    assert.equal(1, byname.m1_t2.pbrMetallicRoughness.baseColorTexture.index)
    assert.same({ 1, 1, 1, 1 }, byname.m1_t2.pbrMetallicRoughness.baseColorFactor)
    assert.is_table(byname.m1_t2.extensions.KHR_materials_unlit)
    assert.equal(sc.ntriangles, (glb_counts(file("t.glb"))))
    -- TEXCOORD_0 is the OBJ's vt with v turned down (glTF images start at the top)
    sc:save(file("t.obj"))
    local vt, f = {}, assert(io.open(file("t.obj")))
    local obj = f:read("a")
    f:close()
    for u, v in obj:gmatch("\nvt (%S+) (%S+)") do
      vt[#vt + 1] = { tonumber(u), tonumber(v) }
    end
    local uv = glb.accessor(doc, bin, doc.meshes[1].primitives[1].attributes.TEXCOORD_0)
    assert.equal(2 * sc.nvertices, #uv)
    assert.equal(sc.nvertices, #vt)
    for i, t in ipairs(vt) do
      assert.near(t[1], uv[2 * i - 1], 1e-6)
      assert.near(1 - t[2], uv[2 * i], 1e-6)
    end
  end)

  it("writes PLY as without textures", function ()
    sc:save(file("t.ply"))
    assert.equal(sc.ntriangles, R.ply(file("t.ply")).counts.face)
  end)

  local validator = io.open("tools/node_modules/gltf-validator/package.json")
  if validator then validator:close() end
  local it_ = validator and it or pending
  it_("passes the glTF validator with textures (tools/validate_glb.js)", function ()
    sc:save(file("v.glb"))
    local p = io.popen("node tools/validate_glb.js " .. file("v.glb") .. " 2>&1; echo rc=$?")
    local out = p:read("a")
    p:close()
    assert.matches("rc=0", out)
  end)
end)
