-- Leaves, organs and framing of the pictures: the component leaf's automatic detail (finer
-- for a leaf drawn large in its plant, and for a bent one), the double compound leaf of
-- the sketch paper's fig. 9 with its leaflets in the frond's plane, the pine of Lintermann
-- and Deussen's fig. 10 bent enough that a, b and c differ, the chestnut's trunk foot
-- inside its picture and the grow forest on the ground of its picture.
local lsys = require "lsys"
local core = require "lsys.core"
local C = lsys.components

local DIR = "examples/"

-- The triangles of a stem 10 long with `n` leaves `len` long (bent `lat` across), at the
-- model's `detail` (nil: automatic).
local function stemtris (n, len, lat, detail)
  local leaf = C.leaf { name = "leaf", shape = "ovate", length = len, width = 0.5,
                        lateral = lat, longitudinal = 0 }
  local stem = C.tree { name = "stem", length = 10, radius = 0.05, segments = 8, n = n,
                        first = 0.2, last = 0.9, angle = 60 }
  stem:branch(leaf)
  return C.model(stem, { seed = 1, detail = detail }):interpret().ntriangles
end

describe("the component leaf's detail", function()
  it("is 8 d (d + 1) triangles at a given detail d", function()
    local base = stemtris(0, 1, 0, 1)
    for d, t in ipairs { 16, 48, 96, 160 } do
      assert.equal(4 * t, stemtris(4, 1.5, 0, d) - base)
    end
  end)

  it("stays at 16 triangles for leaves small in their plant", function()
    local base = stemtris(0, 1, 0)
    -- a leaf 0.3 long on a stem 10 long: under M.SIZES[1] of the plant
    assert.equal(6 * 16, stemtris(6, 0.3, 0) - base)
    assert.equal(6 * 16, stemtris(6, 0.3, 0.3) - base)      -- bent, but small
  end)

  it("is finer for a leaf drawn large, and finer still when bent", function()
    local base = stemtris(0, 1, 0)
    assert.equal(3 * 48, stemtris(3, 0.8, 0) - base)        -- 0.08 of the plant: 2
    assert.equal(3 * 96, stemtris(3, 0.8, 0.3) - base)      -- bent: 3
    assert.equal(3 * 96, stemtris(3, 1.5, 0) - base)        -- 0.15 of the plant: 3
    assert.equal(3 * 160, stemtris(3, 1.5, 0.3) - base)     -- bent: 4, the most
    assert.equal(3 * 160, stemtris(3, 2.5, 0.3) - base)
  end)

  it("draws a leaf alone, the whole plant, at the finest detail", function()
    local leaf = C.leaf { name = "leaf", shape = "cordate", length = 1, width = 0.8 }
    assert.equal(160, C.model(leaf, { seed = 1 }):interpret().ntriangles)
    assert.equal(16, C.model(leaf, { seed = 1, detail = 1 }):interpret().ntriangles)
  end)

  it("keeps the chestnut's 52,416 leaflets at 16 triangles and gives the philodendron's " ..
     "heart leaves 96 or 160", function()
    local M = dofile(DIR .. "components/chestnut.lua")
    local ch = M.graph { branches = 3, subs = 2, twigs = 2, leaves = 3 }
    assert.equal(C.model(ch, { seed = 1, detail = 1, view = M.VIEW }):interpret().ntriangles,
                 C.model(ch, { seed = 1, view = M.VIEW }):interpret().ntriangles)
    local P = dofile(DIR .. "components/philodendron.lua")
    local auto = C.model(P.graph(), { seed = 1 }):interpret().ntriangles
    local one = C.model(P.graph(), { seed = 1, detail = 1 }):interpret().ntriangles
    -- 20 leaves, each 16 triangles at detail 1 and 96 or 160 automatically
    local extra = (auto - one) / 20
    assert.is_true(extra >= 80 and extra <= 144, "extra triangles a leaf: " .. extra)
    assert.equal(20724 - 18100, auto - one)
  end)

  it("is the same twice (the plant's size is read from the same frames)", function()
    local P = dofile(DIR .. "components/philodendron.lua")
    local a = C.model(P.graph(), { seed = 1 }):interpret()
    local b = C.model(P.graph(), { seed = 1 }):interpret()
    assert.equal(a.nvertices, b.nvertices)
    for i = 1, a.nvertices, 37 do assert.same({ a:vertex(i) }, { b:vertex(i) }) end
  end)
end)

-- The faces of material `mtl` in an OBJ file: their unit normals (from the vertices).
local function objnormals (path, mtl)
  local v, out, cur = {}, {}, nil
  for line in io.lines(path) do
    local x, y, z = line:match("^v (%S+) (%S+) (%S+)")
    if x then v[#v + 1] = { tonumber(x), tonumber(y), tonumber(z) }
    elseif line:match("^usemtl ") then cur = line:match("^usemtl (%S+)")
    elseif line:match("^f ") and cur == mtl then
      local ids = {}
      for i in line:gmatch(" (%d+)") do ids[#ids + 1] = tonumber(i) end
      local a, b, c = v[ids[1]], v[ids[2]], v[ids[3]]
      local u = { b[1] - a[1], b[2] - a[2], b[3] - a[3] }
      local w = { c[1] - a[1], c[2] - a[2], c[3] - a[3] }
      local n = { u[2] * w[3] - u[3] * w[2], u[3] * w[1] - u[1] * w[3],
                  u[1] * w[2] - u[2] * w[1] }
      local l = math.sqrt(n[1] ^ 2 + n[2] ^ 2 + n[3] ^ 2)
      if l > 1e-12 then out[#out + 1] = { n[1] / l, n[2] / l, n[3] / l } end
    end
  end
  return out, v
end

describe("the double compound leaf (sketch fig. 9)", function()
  it("has its leaflets in the frond's plane, for every thread count", function()
    local m = dofile(DIR .. "sketch/fig9.lua").double
    local sc = m:interpret(m:derive())
    for _, th in ipairs { 2, 4 } do
      m.threads = th
      local s2 = m:interpret(m:derive())
      assert.equal(sc.nvertices, s2.nvertices)
      for i = 1, sc.nvertices, 101 do assert.same({ sc:vertex(i) }, { s2:vertex(i) }) end
    end
    local path = os.tmpname() .. ".obj"
    sc:save(path)
    -- the frond: the axis and the rachises (material m1) in the plane z = 0
    local lo, hi = sc:bounds()
    assert.is_true(math.abs(hi[3] - lo[3]) < 0.05 * (hi[2] - lo[2]))
    local normals = objnormals(path, "m2")
    os.remove(path)
    assert.is_true(#normals > 5000, "leaflet faces: " .. #normals)
    -- every leaflet face within 30 degrees of the frond's normal (+-z); most within 15
    local worst, within = 0, 0
    for _, n in ipairs(normals) do
      local a = math.deg(math.acos(math.min(1, math.abs(n[3]))))
      if a > worst then worst = a end
      if a <= 15 then within = within + 1 end
    end
    assert.is_true(worst <= 30, "a leaflet face at " .. worst .. " degrees to the frond")
    assert.is_true(within >= 0.9 * #normals, within .. " of " .. #normals .. " within 15")
  end)
end)

-- The vertices of a scene.
local function positions (sc)
  local out = {}
  for i = 1, sc.nvertices do
    local x, y, z = sc:vertex(i)
    out[i] = { x, y, z }
  end
  return out
end

describe("the pine's deformation (components fig. 10)", function()
  local P = dofile(DIR .. "components/pine.lua")
  local SMALL = { branches = 6, twigs = 3, pairs = 4 }
  local function scene (deform)
    local g = {}
    for k, x in pairs(SMALL) do g[k] = x end
    g.deform = deform
    return C.model(P.graph(g), { seed = 1, view = P.VIEW }):interpret()
  end

  it("moves b and c well away from a, and c's needles away from b's", function()
    local a, b, c = positions(scene("none")), positions(scene("twigs")),
                    positions(scene("all"))
    assert.equal(#a, #b)
    assert.equal(#a, #c)
    local y0, y1 = math.huge, -math.huge
    for _, p in ipairs(a) do y0, y1 = math.min(y0, p[2]), math.max(y1, p[2]) end
    local height = y1 - y0
    local function mean (u, w)
      local s = 0
      for i = 1, #u do
        s = s + math.sqrt((u[i][1] - w[i][1]) ^ 2 + (u[i][2] - w[i][2]) ^ 2 +
                          (u[i][3] - w[i][3]) ^ 2)
      end
      return s / #u
    end
    local ab, ac, bc = mean(a, b), mean(a, c), mean(b, c)
    assert.is_true(ab > 0.15 * height, "b moved " .. ab / height .. " of the height")
    assert.is_true(ac > 0.15 * height, "c moved " .. ac / height .. " of the height")
    assert.is_true(bc > 0.003 * height, "c differs from b by " .. bc / height)
  end)
end)

describe("framing", function()
  -- The rows of the first and the last pixels drawn in a transparent render.
  local function rows (x, w, h)
    local px = lsys.render(x, { width = w, height = h, transparent = true })
    local top, bot
    for y = 0, h - 1 do
      for k = 0, w - 1 do
        if px:byte((y * w + k) * 4 + 4) > 0 then top = top or y; bot = y break end
      end
    end
    return top, bot
  end

  it("keeps the chestnut's trunk foot inside the picture with a margin", function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local M = dofile(DIR .. "components/chestnut.lua")
    local m = C.model(M.graph { branches = 5, subs = 3, twigs = 3, leaves = 5 },
                      { seed = 1, view = M.VIEW })
    local top, bot = rows(m, 200, 200)
    -- the fit leaves at least 5 % of the picture on each side (10 rows of 200); the
    -- trunk's foot is the lowest point drawn
    assert.is_true(top >= 9, "the crown's top at row " .. top)
    assert.is_true(bot >= 150 and bot <= 190, "the trunk's foot at row " .. bot)
  end)

  it("stands the grown forest on the ground of a shaded picture", function()
    if not core.has_render then return pending("lsys was built without OSMesa") end
    local F = dofile(DIR .. "grow/forest.lua")
    local sc = F.world { ticks = 20, max_limbs = 2000 }:grow():scene()
    local ro = require("lsys.render").shaded(sc, { width = 160, height = 90, supersample = 1 })
    assert.is_true(ro.ground and ro.shadows and ro.sky)
    local px = lsys.render(sc, ro)
    -- the bottom row is ground (its grey-green), not the sky's pale bottom colour
    local o = (89 * 160 + 80) * 4
    local r, g, b = px:byte(o + 1, o + 3)
    assert.is_true(g > b + 10 and r < 230, ("%d %d %d"):format(r, g, b))
  end)
end)
