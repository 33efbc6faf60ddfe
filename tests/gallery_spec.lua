-- No organ of a gallery picture is nearly black (issue: pictures worth publishing): every
-- picture of examples/gallery that draws polygons, drawn as the gallery draws it (its
-- model's view, the shading `lsys render` gives a 3D plant: shadows, examples/gallery/
-- pictures.lua), has under 2 % of its plant's pixels darker than 10 % luminance. The
-- plant's pixels are those the plant covers at least half, found with a transparent
-- background and without the sky and the ground. Before the default key, fill, sky and
-- ground lights the foxglove (sketch fig. 14) had 8.4 %; the pine 67 % (its needles and
-- the willow's leaves were drawn with their twigs' bark texture); now the most is 0.11 %
-- (cpfg fig. 15c), the diagrams below aside.
--
-- ctest: slow (draws the 84 pictures that have polygons, the forest stand of 1.7 M
-- triangles with its shadows among them: about 40 s)
--
-- Tagged #gl: `busted --exclude-tags=gl` leaves it out.
local lsys = require "lsys"
local core = require "lsys.core"

-- Drawn black on purpose: the cpfg guide's diagrams of a generalized cylinder's control
-- polygon and tangents, in the guide's black.
local BLACK = { ["cpfg/fig05_a.png"] = true, ["cpfg/fig08.png"] = true,
                ["cpfg/fig21_b.png"] = true }

local SIZE = 240         -- the ABOP pictures' side (the gallery's 480, scaled down)

local function luma (r, g, b) return (0.2126 * r + 0.7152 * g + 0.0722 * b) / 255 end

describe("the gallery's pictures #gl", function()
  if not core.has_render then
    pending("lsys was built without OSMesa: the gallery is not drawn")
    return
  end
  local gallery = dofile("examples/gallery/pictures.lua")
  local measured = 0
  for _, p in ipairs(gallery.PICTURES) do
    local png = gallery.png(p)
    if not p.plot and not BLACK[png] then
      it(png .. " has no nearly black organ", function()
        local sc, ro, info = gallery.scene(p, SIZE, "examples")
        if info.tris == 0 or ro.wireframe then return end      -- a line drawing
        measured = measured + 1
        ro.transparent, ro.sky, ro.ground = true, false, false
        local px, w, h = lsys.render(sc, ro)
        local n, dark = 0, 0
        for i = 0, w * h - 1 do
          local r, g, b, a = px:byte(4 * i + 1, 4 * i + 4)
          if a >= 128 then
            n = n + 1
            if luma(r, g, b) < 0.10 then dark = dark + 1 end
          end
        end
        assert.is_true(n > 0, "no pixel of the plant")
        assert.is_true(dark / n < 0.02, ("%.1f %% of %d pixels"):format(100 * dark / n, n))
      end)
    end
  end

  it("measured every picture with polygons", function()
    assert.is_true(measured >= 70, measured .. " pictures measured")
  end)
end)
