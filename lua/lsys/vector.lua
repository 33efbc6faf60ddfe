--- Vector pictures: a Scene's line drawing and polygons as SVG, EPS or PDF paths, framed and
-- projected by the same camera as the PNG renderer (core.project: lsys_render_camera_scene and
-- lsys_render_project), for figures that must scale (what cpfg's PostScript output gave).
--
-- Line segments become stroked paths with round caps and joins; a segment that starts where
-- the one before it ended, in the same colour and width, continues its path, so a branch of a
-- bracketed plant is one path and a closed curve is one closed path. Triangles (leaves,
-- polygons) become filled paths. Everything is painted far to near by its mean depth (the
-- painter's algorithm); at equal depth triangles come first and then lines, each in the
-- turtle's order, as the renderer's depth test with GL_LEQUAL shows them. Colours are the
-- palette's diffuse colours, unlit. One unit of the picture is one pixel of the PNG of the
-- same size (a point in EPS and PDF), so line widths are the renderer's.
-- @module lsys.vector
local core = require "lsys.core"

local ipairs, error, pcall, tostring = ipairs, error, pcall, tostring
local math, string, table = math, string, table
local format, floor = string.format, math.floor
local concat, sort = table.concat, table.sort
local _ENV = nil

local M = {}

--- The vector formats by extension (lower case, without the dot).
M.FORMATS = { svg = "SVG", eps = "Encapsulated PostScript", pdf = "PDF" }

--- The extensions lsys.render writes, as a message lists them.
M.KNOWN = ".png, .svg, .eps or .pdf"

local EPS = 1e-4        -- pixels: two ends closer than this meet

-- A number as few characters as 1/100 pixel needs.
local function num (x)
  local s = format("%.2f", x):gsub("(%..-)0+$", "%1"):gsub("%.$", "")
  if s == "-0" then s = "0" end
  return s
end

--- The paths of a projection (core.project's table): a list of items, painted in order, each
-- { kind = "stroke" or "fill", pts = {x1, y1, x2, y2, ...}, closed = true when the path
-- returns to its start, width = pixels (strokes), color = {r, g, b, a}, depth = mean depth }.
function M.paths (p)
  local items, L, T, pal = {}, p.lines, p.triangles, p.palette
  for i = 1, #T, 10 do
    items[#items + 1] = { kind = "fill", pts = { T[i], T[i + 1], T[i + 3], T[i + 4], T[i + 6],
                          T[i + 7] }, closed = true, color = pal[T[i + 9]],
                          depth = (T[i + 2] + T[i + 5] + T[i + 8]) / 3 }
  end
  local cur, dsum, ex, ey, ckey
  local function finish ()
    if not cur then return end
    local pts, n = cur.pts, #cur.pts
    if n >= 8 and math.abs(pts[1] - pts[n - 1]) < EPS and math.abs(pts[2] - pts[n]) < EPS then
      pts[n], pts[n - 1] = nil, nil
      cur.closed = true
    end
    cur.depth = dsum / (n / 2)
    items[#items + 1] = cur
    cur = nil
  end
  for i = 1, #L, 9 do
    local w = (L[i + 6] > 0 and L[i + 6] or 0) + (L[i + 7] > 0 and L[i + 7] or 0)
    w = w / 2
    if w < 1 then w = 1 elseif w > 16384 then w = 16384 end   -- as the renderer draws them
    local key = L[i + 8] .. "/" .. num(w)
    if cur and key == ckey and math.abs(L[i] - ex) < EPS and math.abs(L[i + 1] - ey) < EPS then
      local pts = cur.pts
      pts[#pts + 1], pts[#pts + 2] = L[i + 3], L[i + 4]
      dsum = dsum + L[i + 5]
    else
      finish()
      cur = { kind = "stroke", pts = { L[i], L[i + 1], L[i + 3], L[i + 4] }, closed = false,
              width = w, color = pal[L[i + 8]] }
      dsum, ckey = L[i + 2] + L[i + 5], key
    end
    ex, ey = L[i + 3], L[i + 4]
  end
  finish()
  for k, it in ipairs(items) do        -- far first; ties keep the drawing order
    it.order, it.key = k, floor(it.depth * 16777216)
  end
  sort(items, function (a, b)
    if a.key ~= b.key then return a.key > b.key end
    return a.order < b.order
  end)
  return items
end

local function hex (c)
  local function b (x) return floor(x * 255 + 0.5) end
  return format("#%02x%02x%02x", b(c[1]), b(c[2]), b(c[3]))
end

local function rgb (c) return format("%.3f %.3f %.3f", c[1], c[2], c[3]) end

-- The coordinates of a path with the operators of a format: svg "M x y L x y x y ... Z",
-- PostScript and PDF "x y m x y l ... [closing]".
local function svgpath (it)
  local t, pts = { "M", num(it.pts[1]), " ", num(it.pts[2]), "L" }, it.pts
  for k = 3, #pts, 2 do
    if k > 3 then t[#t + 1] = " " end
    t[#t + 1] = num(pts[k]); t[#t + 1] = " "; t[#t + 1] = num(pts[k + 1])
  end
  if it.closed then t[#t + 1] = "Z" end
  return concat(t)
end

local function pspath (it, close)
  local t, pts = { num(it.pts[1]), " ", num(it.pts[2]), " m" }, it.pts
  for k = 3, #pts, 2 do t[#t + 1] = format(" %s %s l", num(pts[k]), num(pts[k + 1])) end
  if it.closed then t[#t + 1] = " " .. close end
  return concat(t)
end

-- Runs of fills of one colour, painted one after the other, share one path element.
local function runs (items, each)
  local k = 1
  while k <= #items do
    local it, j = items[k], k
    if it.kind == "fill" then
      while items[j + 1] and items[j + 1].kind == "fill" and items[j + 1].color == it.color do
        j = j + 1
      end
    end
    each(it, k, j)
    k = j + 1
  end
end

local function svg (p, items, transparent)
  local w, h = num(p.width), num(p.height)
  local out = { '<?xml version="1.0" encoding="UTF-8"?>\n',
    format('<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="%s" height="%s" '
           .. 'viewBox="0 0 %s %s">\n', w, h, w, h) }
  if not transparent then
    out[#out + 1] = format('<rect width="%s" height="%s" fill="%s"/>\n', w, h,
                           hex(p.background))
  end
  out[#out + 1] = '<g fill="none" stroke-linecap="round" stroke-linejoin="round">\n'
  runs(items, function (it, k, j)
    local a = it.color[4] < 1 and format(' %s-opacity="%s"', it.kind, num(it.color[4])) or ""
    if it.kind == "stroke" then
      out[#out + 1] = format('<path d="%s" stroke="%s" stroke-width="%s"%s/>\n', svgpath(it),
                             hex(it.color), num(it.width), a)
    else
      local d = {}
      for q = k, j do d[#d + 1] = svgpath(items[q]) end
      out[#out + 1] = format('<path d="%s" fill="%s"%s/>\n', concat(d), hex(it.color), a)
    end
  end)
  out[#out + 1] = "</g>\n</svg>\n"
  return concat(out)
end

-- The drawing operators of PostScript or PDF (a content stream), y pointing down as in the
-- PNG: 'ops' names the format's operators.
local function body (p, items, transparent, ops, items_of)
  local out = {}
  if not transparent then
    out[#out + 1] = format("%s %s 0 0 %s %s %s", rgb(p.background), ops.fillcolor,
                           num(p.width), num(p.height), ops.rect)
  end
  runs(items, function (it, k, j)
    if it.kind == "stroke" then
      out[#out + 1] = format("%s %s %s %s %s %s", rgb(it.color), ops.strokecolor, num(it.width),
                             ops.width, pspath(it, ops.close), ops.stroke)
    else
      out[#out + 1] = format("%s %s", rgb(it.color), ops.fillcolor)
      for q = k, j do out[#out + 1] = pspath(items_of(q), ops.close) end
      out[#out + 1] = ops.fill
    end
  end)
  return concat(out, "\n")
end

local function eps (p, items, transparent)
  local w, h = num(p.width), num(p.height)
  return concat {
    "%!PS-Adobe-3.0 EPSF-3.0\n",
    format("%%%%BoundingBox: 0 0 %d %d\n", p.width, p.height),
    format("%%%%HiResBoundingBox: 0 0 %s %s\n", w, h),
    "%%Creator: lsys\n%%LanguageLevel: 2\n%%EndComments\n",
    "save\n/m {moveto} bind def /l {lineto} bind def /h {closepath} bind def\n",
    "/k {setrgbcolor} bind def /w {setlinewidth} bind def /s {stroke} bind def\n",
    "/f {fill} bind def /re {4 2 roll moveto 1 index 0 rlineto 0 exch rlineto neg 0 rlineto ",
    "closepath fill} bind def\n",
    format("1 setlinecap 1 setlinejoin 0 %s translate 1 -1 scale\n", h),
    body(p, items, transparent, { fillcolor = "k", strokecolor = "k", rect = "re",
      width = "w", close = "h", stroke = "s", fill = "f" }, function (q) return items[q] end),
    "\nrestore\nshowpage\n%%EOF\n",
  }
end

local function pdf (p, items, transparent)
  local stream = format("1 J 1 j 1 0 0 -1 0 %s cm\n", num(p.height))
    .. body(p, items, transparent, { fillcolor = "rg", strokecolor = "RG", rect = "re f",
      width = "w", close = "h", stroke = "S", fill = "f" }, function (q) return items[q] end)
    .. "\n"
  local objs = {
    "<< /Type /Catalog /Pages 2 0 R >>",
    "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
    format("<< /Type /Page /Parent 2 0 R /MediaBox [0 0 %s %s] /Contents 4 0 R "
           .. "/Resources << >> >>", num(p.width), num(p.height)),
    format("<< /Length %d >>\nstream\n%sendstream", #stream, stream),
  }
  local out, off = { "%PDF-1.4\n%\xe2\xe3\xcf\xd3\n" }, {}
  local size = #out[1]
  for k, o in ipairs(objs) do
    off[k] = size
    out[#out + 1] = format("%d 0 obj\n%s\nendobj\n", k, o)
    size = size + #out[#out]
  end
  out[#out + 1] = format("xref\n0 %d\n0000000000 65535 f \n", #objs + 1)
  for k = 1, #objs do out[#out + 1] = format("%010d 00000 n \n", off[k]) end
  out[#out + 1] = format("trailer\n<< /Size %d /Root 1 0 R >>\nstartxref\n%d\n%%%%EOF\n",
                         #objs + 1, size)
  return concat(out)
end

local WRITERS = { svg = svg, eps = eps, pdf = pdf }

--- The text of a picture in format `fmt` ("svg", "eps" or "pdf") of projection `p`
-- (core.project) painted as `items` (M.paths); `transparent`: no background.
function M.encode (fmt, p, items, transparent)
  local wr = WRITERS[fmt]
  if not wr then
    error(format("unknown vector format '%s': lsys writes %s", tostring(fmt), M.KNOWN), 2)
  end
  return wr(p, items, transparent)
end

--- Writes Scene `scene` to the file `ro.out` in format `fmt`, through core.project with the
-- render options `ro` (those of core.render). Returns the projection and the items.
function M.write (scene, ro, fmt)
  if ro.wireframe then error("lsys.render: wireframe applies to .png pictures", 0) end
  local ok, p = pcall(core.project, scene, ro)
  if not ok then error(p, 0) end
  local items = M.paths(p)
  local text = M.encode(fmt, p, items, ro.transparent)
  local okw, err = pcall(core.write_file, ro.out, text)
  if not okw then error("lsys.render: " .. tostring(err), 0) end
  return p, items
end

return M
