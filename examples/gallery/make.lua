-- Renders the gallery: every picture listed below into examples/gallery/*.png and the page
-- examples/gallery/README.md that shows them.
--
--   build/bin/lsys examples/gallery/make.lua [SIZE]      (default 480: 480x480 pictures)
local lsys = require "lsys"

local size = tonumber(arg and arg[1]) or 480
local dir = (arg and arg[0] or "examples/gallery/make.lua"):match("^(.*)/[^/]*$") or "."
local examples = dir .. "/.."

-- { file, model name (tables of models), title, view overrides }
local PICTURES = {
  { "default.lua", nil, "The default plant (`lsys render`)" },
  { "abop/fig1_24a.lua", nil, "ABOP 1.24a: bracketed edge rewriting, n = 5" },
  { "abop/fig1_24b.lua", nil, "ABOP 1.24b" },
  { "abop/fig1_24c.lua", nil, "ABOP 1.24c" },
  { "abop/fig1_24d.lua", nil, "ABOP 1.24d: node rewriting" },
  { "abop/fig1_24e.lua", nil, "ABOP 1.24e" },
  { "abop/fig1_24f.lua", nil, "ABOP 1.24f" },
  { "abop/fig1_25.lua", nil, "ABOP 1.25: a 3D bush with leaves" },
  { "abop/fig1_27.lua", nil, "ABOP 1.27: stochastic branching" },
  { "abop/fig2_06.lua", "a", "ABOP 2.6a: monopodial tree (Honda)" },
  { "abop/fig2_06.lua", "b", "ABOP 2.6b" },
  { "abop/fig2_06.lua", "c", "ABOP 2.6c" },
  { "abop/fig2_06.lua", "d", "ABOP 2.6d" },
  { "abop/fig2_07.lua", "a", "ABOP 2.7a: sympodial tree (Aono and Kunii)" },
  { "abop/fig2_07.lua", "b", "ABOP 2.7b" },
  { "abop/fig2_07.lua", "c", "ABOP 2.7c" },
  { "abop/fig2_07.lua", "d", "ABOP 2.7d" },
  { "abop/fig2_08.lua", "a", "ABOP 2.8a: ternary tree with tropism" },
  { "abop/fig2_08.lua", "b", "ABOP 2.8b" },
  { "abop/fig2_08.lua", "c", "ABOP 2.8c" },
  { "abop/fig2_08.lua", "d", "ABOP 2.8d" },
  { "abop/fig1_06.lua", nil, "ABOP 1.6: quadratic Koch island" },
  { "abop/fig1_10a.lua", nil, "ABOP 1.10a: dragon curve" },
  { "abop/fig1_11a.lua", nil, "ABOP 1.11a: hexagonal Gosper curve" },
}

local function load (file, name)
  local v = dofile(examples .. "/" .. file)
  if name then v = v[name] end
  assert(v and v.derive, file .. ": no model " .. tostring(name))
  return v
end

local rows = {}
for i, p in ipairs(PICTURES) do
  local file, name, title, over = p[1], p[2], p[3], p[4]
  local m = load(file, name)
  local t0 = os.clock()
  local s = m:derive()
  local sc = m:interpret(s, over)
  local png = file:gsub("^abop/", ""):gsub("%.lua$", "") .. (name and "_" .. name or "") .. ".png"
  lsys.render(sc, { out = dir .. "/" .. png, width = size, height = size })
  io.stderr:write(string.format("[%2d/%d] %-28s %8d modules %9d triangles %6d lines  %.2f s\n",
    i, #PICTURES, png, #s, sc.ntriangles, sc.nlines, os.clock() - t0))
  rows[#rows + 1] = { png = png, title = title, file = file, name = name, n = #s,
                      tris = sc.ntriangles, lines = sc.nlines }
end

local f = assert(io.open(dir .. "/README.md", "w"))
f:write("# Gallery\n\n",
  "Pictures rendered headless (OSMesa) by `build/bin/lsys examples/gallery/make.lua`, ",
  "from the model files in `examples/`. Each caption gives the file, the number of modules ",
  "and of triangles or line segments.\n\n")
f:write("| | | |\n|---|---|---|\n")
for i = 1, #rows, 3 do
  local cells, caps = {}, {}
  for j = i, math.min(i + 2, #rows) do
    local r = rows[j]
    cells[#cells + 1] = string.format("![%s](%s)", r.title, r.png)
    caps[#caps + 1] = string.format("%s<br>`%s`%s, %d modules, %s", r.title, r.file,
      r.name and (" `" .. r.name .. "`") or "", r.n,
      r.tris > 0 and (r.tris .. " triangles") or (r.lines .. " lines"))
  end
  f:write("| ", table.concat(cells, " | "), " |\n")
  f:write("| ", table.concat(caps, " | "), " |\n")
end
f:close()
io.stderr:write("wrote " .. dir .. "/README.md\n")
