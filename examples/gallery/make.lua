-- Renders the gallery: every picture listed below into examples/gallery/*.png and the page
-- examples/gallery/README.md that shows them. Each picture uses its model's own view, so
-- `lsys render` of the same file draws the same picture.
--
--   build/bin/lsys examples/gallery/make.lua [SIZE]      (default 480: 480x480 pictures)
local lsys = require "lsys"

local size = tonumber(arg and arg[1]) or 480
local dir = (arg and arg[0] or "examples/gallery/make.lua"):match("^(.*)/[^/]*$") or "."
local examples = dir .. "/.."

-- { file, model name (files returning a table of models), title, caption, view overrides }
local PICTURES = {
  { "default.lua", nil, "The default tree",
    "What `lsys render` draws without a model: a ternary tree with random angles, bent down "
    .. "by gravity, with whorls of rhombic leaves on the young shoots; cylinders in perspective." },
  { "abop/fig1_24a.lua", nil, "ABOP 1.24a",
    "Edge rewriting F → F[+F]F[-F]F, n = 5, δ = 25.7°: a tall axis with short side shoots." },
  { "abop/fig1_24b.lua", nil, "ABOP 1.24b",
    "Edge rewriting with a third, straight branch in each successor, n = 5, δ = 20°." },
  { "abop/fig1_24c.lua", nil, "ABOP 1.24c",
    "Edge rewriting with two curved three-segment branches per node, n = 4, δ = 22.5°; "
    .. "the bush leans to the right." },
  { "abop/fig1_24d.lua", nil, "ABOP 1.24d",
    "Node rewriting with an apex X, n = 7, δ = 20°: internodes double each step, so the "
    .. "lower stem is long and bare." },
  { "abop/fig1_24e.lua", nil, "ABOP 1.24e",
    "Node rewriting with opposite branches, n = 7, δ = 25.7°: a symmetric, pinnate plant." },
  { "abop/fig1_24f.lua", nil, "ABOP 1.24f",
    "Node rewriting with a nested bracket, n = 5, δ = 22.5°: a sparse, weed-like plant." },
  { "abop/fig1_25.lua", nil, "ABOP 1.25",
    "A three-dimensional bush, n = 7: branches thin and turn from brown to green with their "
    .. "order, and every internode carries a leaf polygon." },
  { "abop/fig1_27.lua", nil, "ABOP 1.27",
    "Stochastic branching: each F takes one of three successors at random (seed 1); a new "
    .. "seed gives another plant of the same kind." },
  { "abop/fig2_06.lua", "a", "ABOP 2.6a",
    "Monopodial tree after Honda: a straight trunk with lateral branches placed 137.5° "
    .. "apart; branches contract by 0.6." },
  { "abop/fig2_06.lua", "b", "ABOP 2.6b",
    "The same architecture with branch contraction 0.9: long, wide-spreading branches." },
  { "abop/fig2_06.lua", "c", "ABOP 2.6c", "Branch contraction 0.8: in between a and b." },
  { "abop/fig2_06.lua", "d", "ABOP 2.6d",
    "Branching angles of 30° and −30° and contraction 0.7: a narrow, upright crown." },
  { "abop/fig2_07.lua", "a", "ABOP 2.7a",
    "Sympodial tree after Aono and Kunii: each apex forks into two unequal branches "
    .. "(5° and 65°)." },
  { "abop/fig2_07.lua", "b", "ABOP 2.7b", "Branching angles 10° and 60°." },
  { "abop/fig2_07.lua", "c", "ABOP 2.7c", "Branching angles 20° and 50°, contraction 0.8." },
  { "abop/fig2_07.lua", "d", "ABOP 2.7d",
    "Equal angles of 35°: a symmetric fork at every node and a flat, spreading crown." },
  { "abop/fig2_08.lua", "a", "ABOP 2.8a",
    "Ternary branching bent down by a tropism toward −y (elasticity 0.22), n = 6." },
  { "abop/fig2_08.lua", "b", "ABOP 2.8b",
    "Divergence 137.5° between all three shoots and a weaker bend, n = 8: a dense, "
    .. "dome-shaped crown." },
  { "abop/fig2_08.lua", "c", "ABOP 2.8c",
    "Internodes that grow by 1.79 per step, n = 8: a very tall, thin trunk under a small "
    .. "crown of fine twigs." },
  { "abop/fig2_08.lua", "d", "ABOP 2.8d",
    "A tropism vector pointing up and to the left (elasticity 0.4): the whole tree leans "
    .. "as if shaped by wind." },
  { "abop/fig1_06.lua", nil, "ABOP 1.6",
    "Quadratic Koch island, n = 3: every edge of a square replaced three times by an "
    .. "eight-edge generator." },
  { "abop/fig1_10a.lua", nil, "ABOP 1.10a",
    "Dragon curve by edge rewriting with left and right edges, n = 10." },
  { "abop/fig1_11a.lua", nil, "ABOP 1.11a",
    "Hexagonal Gosper curve (flowsnake) by edge rewriting, n = 4, δ = 60°." },
}

local function load (file, name)
  local v = dofile(examples .. "/" .. file)
  if name then v = v[name] end
  assert(v and v.derive, file .. ": no model " .. tostring(name))
  return v
end

local rows, bytes = {}, 0
for i, p in ipairs(PICTURES) do
  local file, name, title, caption, over = p[1], p[2], p[3], p[4], p[5]
  local m = load(file, name)
  local t0 = os.clock()
  local s = m:derive()
  local sc = m:interpret(s, over)
  local png = file:gsub("^abop/", ""):gsub("%.lua$", "") .. (name and "_" .. name or "") .. ".png"
  lsys.render(sc, { out = dir .. "/" .. png, width = size, height = size })
  local f = assert(io.open(dir .. "/" .. png, "rb"))
  bytes = bytes + f:seek("end")
  f:close()
  io.stderr:write(string.format("[%2d/%d] %-16s %8d modules %8d triangles %6d lines  %.2f s\n",
    i, #PICTURES, png, #s, sc.ntriangles, sc.nlines, os.clock() - t0))
  rows[#rows + 1] = { png = png, title = title, caption = caption, file = file, name = name,
                      n = #s, tris = sc.ntriangles, lines = sc.nlines }
end

local SECTIONS = {     -- heading, first picture of the section, pictures per row
  { "The default tree", "default.png", 1 },
  { "Bracketed plants (ABOP 1.24)", "fig1_24a.png", 3 },
  { "A bush with leaves and a stochastic plant (ABOP 1.25, 1.27)", "fig1_25.png", 2 },
  { "Monopodial trees (ABOP 2.6)", "fig2_06_a.png", 2 },
  { "Sympodial trees (ABOP 2.7)", "fig2_07_a.png", 2 },
  { "Trees bent by tropism (ABOP 2.8)", "fig2_08_a.png", 2 },
  { "Curves (ABOP 1.6, 1.10a, 1.11a)", "fig1_06.png", 3 },
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
        caps[#caps + 1] = string.format("**%s.** %s<br>`%s`%s, %d modules, %s", r.title,
          r.caption, r.file, r.name and (" `" .. r.name .. "`") or "", r.n,
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
trees and curves of *The Algorithmic Beauty of Plants* (ABOP), chapters 1 and 2, and the
default tree. They are rendered headless with OSMesa, each with the view stored in its model
file, so `build/bin/lsys render FILE -o out.png --size 480x480` draws the same picture (add
`--name a` for a file that holds several models). Each caption says what the picture shows,
then gives the model file, the number of modules in the derived string and the size of the
geometry.

To draw them again after a build (a few seconds):

```sh
build/bin/lsys examples/gallery/make.lua          # 480x480; an argument sets another size
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
