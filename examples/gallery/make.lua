-- Renders the gallery: every picture of pictures.lua into examples/gallery/*.png (the figures
-- of the cpfg guide into examples/gallery/cpfg/) and the page examples/gallery/README.md that
-- shows them. Each picture uses its model's own view, so `lsys render` of the same file
-- draws the same picture.
--
--   build/bin/lsys examples/gallery/make.lua [SIZE] [PATTERN...]
--
-- SIZE (default 480) is the size of the ABOP pictures; the others are scaled with it.
-- A PATTERN (a Lua pattern) draws only the pictures whose PNG name matches one of the
-- patterns, e.g. `cpfg/fig1[0-3]`, and leaves README.md as it is.
local lsys = require "lsys"

local size, patterns = 480, {}
for _, a in ipairs(arg or {}) do
  if tonumber(a) then size = tonumber(a) else patterns[#patterns + 1] = a end
end
local dir = (arg and arg[0] or "examples/gallery/make.lua"):match("^(.*)/[^/]*$") or "."
local examples = dir .. "/.."

local gallery = dofile(dir .. "/pictures.lua")
local PICTURES = gallery.PICTURES

local function wanted (png)
  if #patterns == 0 then return true end
  for _, pat in ipairs(patterns) do
    if png:find(pat) then return true end
  end
  return false
end

local rows, bytes, drawn = {}, 0, 0
for i, p in ipairs(PICTURES) do
  local file, name, title, caption = p[1], p[2], p[3], p[4]
  local png = gallery.png(p)
  if wanted(png) and p.plot then
    -- a sketch's positional functions (Anastacio et al. 2009, §4), as lsys sketch plot
    local sk = require("lsys.sketch").load(examples .. "/sketch/" .. file .. ".json")
    require("lsys.sketch.plot").png(sk, dir .. "/" .. png, { width = 640 })
    rows[#rows + 1] = { png = png, title = title, caption = caption,
                        file = "sketch/" .. file .. ".json", plot = true }
  elseif wanted(png) then
    local t0 = os.clock()
    local sc, ro, info = gallery.scene(p, size, examples)
    assert(require("lsys.core").mkdir(dir .. "/" .. (png:match("^(.*)/") or ".")))
    ro.out = dir .. "/" .. png
    lsys.render(sc, ro)
    local f = assert(io.open(ro.out, "rb"))
    bytes = bytes + f:seek("end")
    f:close()
    drawn = drawn + 1
    local what = info.limbs and string.format("%8d limbs ", info.limbs)
      or info.plants and string.format("%8d plants", info.plants)
      or string.format("%8d modules", info.n)
    io.stderr:write(string.format("[%2d/%d] %-24s %s %8d triangles %6d lines  %.2f s\n", i,
      #PICTURES, png, what, info.tris, info.lines, os.clock() - t0))
    local row = { png = png, title = title, caption = caption, file = file, name = name }
    for k, v in pairs(info) do row[k] = v end
    rows[#rows + 1] = row
  end
end

if #patterns > 0 then
  io.stderr:write(string.format("%d pictures, %.1f MB of PNG; README.md not rewritten "
    .. "(a pattern was given)\n", drawn, bytes / 1e6))
  return
end

local SECTIONS = {     -- heading, first picture of the section, pictures per row
  { "The default tree", "default.png", 1 },
  { "Bracketed plants (ABOP 1.24)", "fig1_24a.png", 3 },
  { "A bush with leaves and a stochastic plant (ABOP 1.25, 1.27)", "fig1_25.png", 2 },
  { "Monopodial trees (ABOP 2.6)", "fig2_06_a.png", 2 },
  { "Sympodial trees (ABOP 2.7)", "fig2_07_a.png", 2 },
  { "Trees bent by tropism (ABOP 2.8)", "fig2_08_a.png", 2 },
  { "Curves (ABOP 1.6, 1.10a, 1.11a)", "fig1_06.png", 3 },
  { "Generalized cylinders (cpfg guide §3.1–3.2, figs. 5–11)", "cpfg/fig05_a.png", 3 },
  { "Tangent coefficients (fig. 8)", "cpfg/fig08.png", 1 },
  { "Curved cylinders and shells (figs. 10, 11)", "cpfg/fig10_b.png", 2 },
  { "Contours (§3.2.3, figs. 12–18)", "cpfg/fig12_a.png", 3 },
  { "Twist of generalized cylinders (§3.3, fig. 19)", "cpfg/fig19_a.png", 3 },
  { "Branching generalized cylinders (§3.4, fig. 21)", "cpfg/fig21_a.png", 4 },
  { "Surfaces (§4, figs. 22–25)", "cpfg/fig22.png", 2 },
  { "Bicubic petals (§4.3, figs. 27, 28)", "cpfg/fig27_all.png", 1 },
  { "Textures (§5, figs. 31, 33, 34)", "cpfg/fig31_a.png", 3 },
  { "Sketches (Anastacio et al. 2009, figs. 5, 7-14)", "sketch/fig7_cone.png", 3 },
  { "Component graphs (Lintermann and Deussen 1999)", "components/fig2_abcd.png", 2 },
  { "Incremental growth (Davison)", "grow/davison.png", 3 },
  { "Open L-systems (Měch and Prusinkiewicz 1996)", "open/ulam.png", 2 },
  { "Self-organizing trees (Palubicki et al. 2009)", "open/selforg.png", 2 },
}

-- One section: a table of 'cols' pictures per row, each with its caption underneath
-- (a lone picture: the picture, then its caption).
local function section (f, list, cols)
  if #list == 1 then
    local r = list[1]
    f:write(string.format("![%s](%s)\n\n%s `%s`, %d modules, %d triangles.\n\n", r.title,
      r.png, r.caption, r.file, r.n, r.tris))
    return
  end
  f:write("|", string.rep(" |", cols), "\n|", string.rep(":-:|", cols), "\n")
  for i = 1, #list, cols do
    local cells, caps = {}, {}
    for j = i, i + cols - 1 do
      local r = list[j]
      if r then
        cells[#cells + 1] = string.format("![%s](%s)", r.title, r.png)
        caps[#caps + 1] = r.plot and string.format("**%s.** %s<br>`%s`", r.title,
          r.caption, r.file) or r.limbs and string.format("**%s.** %s<br>`%s`, %d limbs, "
          .. "%d triangles", r.title, r.caption, r.file, r.limbs, r.tris)
          or r.plants and string.format("**%s.** %s<br>`%s`, %d plants, %d triangles",
          r.title, r.caption, r.file, r.plants, r.tris)
          or string.format("**%s.** %s<br>`%s`%s, %d modules, %s", r.title, r.caption,
          r.file, r.name and (" `" .. r.name .. "`") or "", r.n,
          r.tris > 0 and (r.tris .. " triangles") or (r.lines .. " lines"))
      else
        cells[#cells + 1], caps[#caps + 1] = "", ""
      end
    end
    f:write("| ", table.concat(cells, " | "), " |\n")
    f:write("| ", table.concat(caps, " | "), " |\n")
  end
  f:write("\n")
end

local f = assert(io.open(dir .. "/README.md", "w"))
f:write([[
# Gallery

Pictures drawn by lsys from the model files in [`examples/`](..): the bracketed plants,
trees and curves of *The Algorithmic Beauty of Plants* (ABOP), chapters 1 and 2, the
default tree, and the figures of the cpfg guide to generalized cylinders, surfaces and
textures ([`examples/cpfg/`](../cpfg), pictures in `cpfg/`). They are rendered headless with
OSMesa, each with the view stored in its model file, so `build/bin/lsys render FILE -o
out.png --size 480x480` draws the same picture (add `--name a` for a file that holds several
models; the cpfg pictures are 320x320 or wider, and the wireframes are drawn with
`lsys.render(scene, { wireframe = true })`). Each caption says what the picture shows, then
gives the model file, the number of modules in the derived string and the size of the
geometry.

To draw them again after a build (a few seconds):

```sh
build/bin/lsys examples/gallery/make.lua          # 480x480; an argument sets another size
build/bin/lsys examples/gallery/make.lua cpfg/fig1[0-3]   # only these; README.md unchanged
```

]])
local k = 1
for si, sec in ipairs(SECTIONS) do
  local stop = SECTIONS[si + 1] and SECTIONS[si + 1][2]
  local list = {}
  assert(rows[k].png == sec[2], "section " .. sec[1] .. " does not start at " .. sec[2])
  while rows[k] and rows[k].png ~= stop do list[#list + 1] = rows[k]; k = k + 1 end
  f:write("## ", sec[1], "\n\n")
  section(f, list, sec[3])
end
f:close()
io.stderr:write(string.format("wrote %s/README.md; %d pictures, %.1f MB of PNG\n", dir, #rows,
  bytes / 1e6))
