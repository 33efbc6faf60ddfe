--- Plots of a sketch's positional functions and drawings of a sketch, on a core.canvas
-- (docs/sketch.md, "Plots"). The panels follow the figures of Anastacio et al. 2009 (§7,
-- figs. 4, 11 and 12): (1) internode length, (2) stem shape, or yaw for a 3D stem, (3, 4)
-- left and right inclination angles, (5, 6) left and right organ sizes, and (7) pitch when
-- the stem is 3D; two columns, three rows (four with pitch). The sketch window draws the
-- same panels live, with a marker where the cursor is.
--
--   plot.functions(funcs [, opts]) -> canvas, panels
--   plot.sketch(sketch, canvas [, opts])
--   plot.png(sketch_or_funcs, path [, opts]) -> canvas, panels
-- @module lsys.sketch.plot
local core = require "lsys.core"

local type, pairs, ipairs, error, pcall, tostring, tonumber, getmetatable =
      type, pairs, ipairs, error, pcall, tostring, tonumber, getmetatable
local math, string = math, string
local format, match = string.format, string.match
local floor, ceil, log, abs, huge, max, min = math.floor, math.ceil, math.log, math.abs,
      math.huge, math.max, math.min
local _ENV = nil

local M = {}

--- The panels in order: the key of the function in a sketch's functions table, the
-- alternative key (yaw when there is no stem_shape), and the titles.
M.PANELS = {
  { key = "internode", title = "internode length" },
  { key = "stem_shape", alt = "yaw", title = "stem shape (deg)", alt_title = "yaw (deg)" },
  { key = "angle_left", title = "left inclination (deg)" },
  { key = "angle_right", title = "right inclination (deg)" },
  { key = "size_left", title = "left organ size" },
  { key = "size_right", title = "right organ size" },
  { key = "pitch", title = "pitch (deg)", optional = true },
}

--- Default colours of the function plots.
M.COLORS = {
  background = "#ffffff", panel = "#fbfbf8", frame = "#5a5a5a", grid = "#e2e2dc",
  text = "#202020", label = "#606060", curve = "#1f5fa8", points = "#d8622a",
  marker = "#c0203a",
}

--- Default colours of sketch drawings: the stem at the drawing plane's pressure (0.5) and
-- at the nearest (1) and farthest (0) pressures (§7.3: nearer darker, farther lighter).
M.SKETCH_COLORS = {
  background = "#ffffff", frame = "#d0d0d0", stem = "#6b4a2b", near = "#1a0f05",
  far = "#e4d4c2", boundary_left = "#2e8b3e", boundary_right = "#2e8b3e",
  inclination = "#3a6fc4", node = "#c0203a", ray = "#e08a3a",
}

local FUNC_OPTS = { width = true, height = true, background = true, colors = true,
                    points = true, marker = true, scale = true, line_width = true,
                    canvas = true, region = true }
local SKETCH_OPTS = { region = true, colors = true, analysis = true, line_width = true,
                      margin = true, background = true }

local function fail (who, fmt, ...)
  error(format("lsys.sketch.plot.%s: " .. fmt, who, ...), 3)
end

local function checkopts (who, opts, known)
  if opts == nil then return {} end
  if type(opts) ~= "table" then fail(who, "opts must be a table, got %s", type(opts)) end
  for k in pairs(opts) do
    if not known[k] then fail(who, "unknown option '%s'", tostring(k)) end
  end
  return opts
end

-- The colours: defaults, with the ones given in opts.colors.
local function palette (who, defaults, given, background)
  local out = {}
  for k, v in pairs(defaults) do out[k] = v end
  if given ~= nil then
    if type(given) ~= "table" then fail(who, "opts.colors must be a table") end
    for k, v in pairs(given) do
      if defaults[k] == nil then fail(who, "unknown colour '%s' in opts.colors", tostring(k)) end
      out[k] = v
    end
  end
  if background ~= nil then out.background = background end
  return out
end

local function callable (f)
  if type(f) == "function" then return true end
  local mt = getmetatable(f)
  return type(mt) == "table" and mt.__call ~= nil
end

-- A function of the funcs table as eval(x) and its control points (or nil): a Func
-- (callable, f:points()), a plain function, or { eval = fn, points = {...}, name = "..." }.
local function accessor (key, f)
  if type(f) == "function" then return f, nil end
  if type(f) == "table" and type(f.eval) == "function" then return f.eval, f.points end
  if callable(f) then
    local pts
    if type(f) == "userdata" or type(f) == "table" then
      local ok, p = pcall(function () return f:points() end)
      if ok and type(p) == "table" then pts = p end
    end
    return function (x) return f(x) end, pts
  end
  error(format("lsys.sketch.plot.functions: funcs.%s must be a function, got %s", key,
               type(f)), 0)
end

-- The point i of a list of points given as {{x, y}...} or flat {x1, y1, ...}.
local function point (pts, i)
  if type(pts[1]) == "table" then
    local p = pts[i]
    if p then return p[1] or p.x, p[2] or p.y end
    return nil
  end
  return pts[2 * i - 1], pts[2 * i]
end

-- A step of 1, 2 or 5 times a power of ten giving about n intervals over 'span'.
local function nicestep (span, n)
  local raw = span / n
  local p = 10 ^ floor(log(raw, 10))
  for _, m in ipairs { 1, 2, 5, 10 } do
    if m * p >= raw then return m * p end
  end
  return 10 * p
end

local function label (v, step)
  local d = max(0, -floor(log(step, 10) + 1e-9))
  local s = format("%." .. d .. "f", v)
  if s:match("^%-0%.?0*$") then s = s:sub(2) end
  return s
end

-- The samples of f at n + 1 evenly spaced x, and their finite min and max.
local function sample (key, eval, n)
  local ys, lo, hi = {}, huge, -huge
  for i = 0, n do
    local ok, y = pcall(eval, i / n)
    if not ok then
      error(format("lsys.sketch.plot.functions: function %s failed at x = %g: %s", key, i / n,
                   tostring(y)), 0)
    end
    if type(y) ~= "number" then
      error(format("lsys.sketch.plot.functions: function %s returned %s at x = %g, not a "
                   .. "number", key, type(y), i / n), 0)
    end
    ys[i + 1] = y
    if y == y and y > -huge and y < huge then
      if y < lo then lo = y end
      if y > hi then hi = y end
    end
  end
  if lo > hi then lo, hi = 0, 1 end
  return ys, lo, hi
end

--- The y range of a panel for values in [lo, hi]: padded by 8% of the span, or, for a
-- constant c, by |c| / 10 (1 for 0) on each side, so a constant runs along the middle.
function M.yrange (lo, hi)
  local span = hi - lo
  if span <= 1e-9 * max(abs(lo), abs(hi)) or span == 0 then
    local pad = lo ~= 0 and abs(lo) / 10 or 1
    return lo - pad, hi + pad
  end
  return lo - 0.08 * span, hi + 0.08 * span
end

-- The panel's layout inside the cell (x, y, w, h) at text scale s: the plot area.
local function plotarea (x, y, w, h, s)
  local ml, mr, mt, mb = 6 * s * 7 + 8, 6 * s * 2 + 4, 7 * s + 16, 7 * s + 18
  return x + ml, y + mt, max(w - ml - mr, 1), max(h - mt - mb, 1)
end

-- Draws one panel; returns its description.
local function panel (c, spec, cell, s, col, opts)
  local x, y, w, h = cell[1], cell[2], cell[3], cell[4]
  local px, py, pw, ph = plotarea(x, y, w, h, s)
  local n = max(floor(pw), 16)
  local ys, lo, hi = sample(spec.key, spec.eval, n)
  local y0, y1 = M.yrange(lo, hi)
  local function X (v) return px + v * pw end
  local function Y (v) return py + ph - (v - y0) / (y1 - y0) * ph end
  c:clip(x, y, w, h)
  c:text(x + 4, y + 6, spec.title, s, col.text)
  c:rect(px, py, pw, ph, col.panel, true)
  local step = nicestep(y1 - y0, 4)
  for k = ceil(y0 / step), floor(y1 / step) do
    local v = k * step
    local gy = floor(Y(v)) + 0.5
    c:line(px, gy, px + pw, gy, 1, col.grid)
    local t = label(v, step)
    c:text(px - 6 - c:text_width(t, s), gy - 3.5 * s, t, s, col.label)
  end
  -- x in fifths when their labels fit side by side, else in halves
  local nx = pw / 5 >= c:text_width("0.8", s) + 4 * s and 5 or 2
  for k = 0, nx do
    local v = k / nx
    local gx = floor(X(v)) + 0.5
    if k > 0 and k < nx then c:line(gx, py, gx, py + ph, 1, col.grid) end
    local t = format("%g", v)
    c:text(gx - c:text_width(t, s) / 2, py + ph + 6, t, s, col.label)
  end
  c:clip(px, py, pw, ph)
  local xy = {}
  for i = 0, n do
    xy[2 * i + 1], xy[2 * i + 2] = X(i / n), Y(ys[i + 1])
  end
  c:polyline(xy, opts.line_width or max(1.5, s), col.curve)
  if opts.points ~= false and spec.points then
    local i = 1
    while true do
      local cx, cy = point(spec.points, i)
      if cx == nil then break end
      if type(cx) == "number" and type(cy) == "number" then
        c:circle(X(cx), Y(cy), 1.5 + s, col.points)
      end
      i = i + 1
    end
  end
  if opts.marker ~= nil then
    c:line(X(opts.marker), py, X(opts.marker), py + ph, max(1, s * 0.75), col.marker)
  end
  c:clip(x, y, w, h)
  c:rect(px - 0.5, py - 0.5, pw + 1, ph + 1, col.frame)
  c:clip()
  return { key = spec.key, title = spec.title, x = px, y = py, w = pw, h = ph,
           ymin = y0, ymax = y1, min = lo, max = hi }
end

-- The panels to draw for a funcs table, in order, each with eval, points and title.
local function specs (funcs)
  local out = {}
  for i, p in ipairs(M.PANELS) do
    local key, title = p.key, p.title
    local f = funcs[key]
    if f == nil and p.alt then key, title, f = p.alt, p.alt_title, funcs[p.alt] end
    if f == nil then
      if not p.optional then
        local want = p.alt and (p.key .. " or " .. p.alt) or p.key
        error(format("lsys.sketch.plot.functions: funcs has no %s (panel %d)", want, i), 0)
      end
    else
      local eval, pts = accessor(key, f)
      out[#out + 1] = { key = key, title = i .. "  " .. title, eval = eval, points = pts }
    end
  end
  return out
end

--- Plots the positional functions `funcs` (a sketch's `sk:functions()`): a Canvas and the
-- list of panels drawn, each { key, title, x, y, w, h (the plot area in pixels), ymin,
-- ymax (the y range shown), min, max (the sampled values) }.
-- opts: width (800), height (300 per row), background, colors (see M.COLORS), points
-- (true: draw the control points), marker (an x in [0, 1]: a vertical line there),
-- scale (text scale; 2 when panels are at least 300 pixels wide, else 1), line_width,
-- canvas and region {x, y, w, h} (draw into that canvas, in that region, instead).
function M.functions (funcs, opts)
  opts = checkopts("functions", opts, FUNC_OPTS)
  if type(funcs) ~= "table" then
    fail("functions", "funcs must be a table of functions, got %s", type(funcs))
  end
  local list = specs(funcs)
  local rows = ceil(#list / 2)
  local c, region = opts.canvas, opts.region
  if c ~= nil then
    if type(region) ~= "table" then
      local w, h = c:size()
      region = { 0, 0, w, h }
    end
  else
    local w, h = opts.width or 800, opts.height or rows * 300
    if type(w) ~= "number" or type(h) ~= "number" then
      fail("functions", "opts.width and opts.height must be numbers")
    end
    c = core.canvas(floor(w), floor(h))
    region = { 0, 0, w, h }
  end
  local col = palette("functions", M.COLORS, opts.colors, opts.background)
  if opts.marker ~= nil and type(opts.marker) ~= "number" then
    fail("functions", "opts.marker must be a number, got %s", type(opts.marker))
  end
  local cw, ch = region[3] / 2, region[4] / rows
  local s = opts.scale or (cw >= 300 and 2 or 1)
  c:clip(region[1], region[2], region[3], region[4])
  c:rect(region[1], region[2], region[3], region[4], col.background, true)
  c:clip()
  local panels = {}
  for i, spec in ipairs(list) do
    local cx = region[1] + ((i - 1) % 2) * cw
    local cy = region[2] + floor((i - 1) / 2) * ch
    panels[i] = panel(c, spec, { floor(cx), floor(cy), floor(cw), floor(ch) }, s, col, opts)
  end
  return c, panels
end

-- A colour as {r, g, b, a} in [0, 1], from a table or "#rrggbb[aa]".
local function rgba (who, v)
  if type(v) == "table" then return { v[1], v[2], v[3], v[4] or 1 } end
  local r, g, b, a = match(type(v) == "string" and v or "", "^#(%x%x)(%x%x)(%x%x)(%x?%x?)$")
  if not r then fail(who, "bad colour %s", tostring(v)) end
  return { tonumber(r, 16) / 255, tonumber(g, 16) / 255, tonumber(b, 16) / 255,
           a ~= "" and #a == 2 and tonumber(a, 16) / 255 or 1 }
end

local function mix (a, b, t)
  return { a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t, a[3] + (b[3] - a[3]) * t,
           a[4] + (b[4] - a[4]) * t }
end

--- The colour of a stem segment drawn at pen pressure p (§3.5, §7.3): the stem colour at
-- 0.5 (the drawing plane), towards `near` (darker) above it and `far` (lighter) below.
function M.depth_color (p, colors)
  local col = colors or M.SKETCH_COLORS
  local base = rgba("depth_color", col.stem)
  if p >= 0.5 then return mix(base, rgba("depth_color", col.near), min(1, (p - 0.5) * 2)) end
  return mix(base, rgba("depth_color", col.far), min(1, (0.5 - p) * 2))
end

--- Draws the normalized sketch `sk` ({ width, height, strokes = {{ role, points =
-- {{x, y, p}...} }...} }, as lsys.sketch.read gives it) into `canvas`, scaled uniformly to
-- fit opts.region {x, y, w, h} (the whole canvas) less opts.margin (10 pixels), centred.
-- The stem's segments are coloured by their pen pressure (M.depth_color); boundaries and
-- inclination lines have their own colours (M.SKETCH_COLORS, opts.colors). opts.analysis
-- (a sketch's analysis, docs/sketch.md "The pipeline") adds its nodes as dots and the rays
-- of §3.4 as thin lines to their boundary hits. opts.background false leaves the region as
-- it is. Returns the mapping { x, y, scale }: a sketch point (u, v) is drawn at
-- (x + u * scale, y + v * scale).
function M.sketch (sk, c, opts)
  opts = checkopts("sketch", opts, SKETCH_OPTS)
  if type(sk) ~= "table" or type(sk.strokes) ~= "table" then
    fail("sketch", "sketch must be a table with strokes, got %s", type(sk))
  end
  local W, H = sk.width, sk.height
  if type(W) ~= "number" or type(H) ~= "number" or not (W > 0 and H > 0) then
    fail("sketch", "the sketch's width and height must be positive numbers")
  end
  local cw, chh = c:size()
  local region = opts.region or { 0, 0, cw, chh }
  local m = opts.margin or 10
  local scale = min((region[3] - 2 * m) / W, (region[4] - 2 * m) / H)
  if not (scale > 0) then fail("sketch", "the region is too small for the sketch") end
  local ox = region[1] + (region[3] - W * scale) / 2
  local oy = region[2] + (region[4] - H * scale) / 2
  local col = palette("sketch", M.SKETCH_COLORS, opts.colors, nil)
  local lw = opts.line_width or 2
  c:clip(region[1], region[2], region[3], region[4])
  if opts.background ~= false then
    c:rect(region[1], region[2], region[3], region[4], opts.background or col.background, true)
  end
  c:rect(ox - 0.5, oy - 0.5, W * scale + 1, H * scale + 1, col.frame)
  local rolecol = { boundary_left = col.boundary_left, boundary_right = col.boundary_right,
                    inclination = col.inclination }
  local function stroke (i, st)
    local pts, role = st.points, st.role
    if role == "stem" then
      for k = 2, #pts do
        local p, q = pts[k - 1], pts[k]
        local pr = ((p[3] or 0.5) + (q[3] or 0.5)) / 2
        c:line(ox + p[1] * scale, oy + p[2] * scale, ox + q[1] * scale, oy + q[2] * scale,
               lw + 1, M.depth_color(pr, col))
      end
    elseif rolecol[role] then
      local xy = {}
      for k, q in ipairs(pts) do
        xy[2 * k - 1], xy[2 * k] = ox + q[1] * scale, oy + q[2] * scale
      end
      c:polyline(xy, lw, rolecol[role])
    else
      fail("sketch", "stroke %d (%s): unknown role", i, tostring(role))
    end
  end
  for i, st in ipairs(sk.strokes) do
    if type(st) ~= "table" or type(st.points) ~= "table" then
      fail("sketch", "stroke %d has no points", i)
    end
    if st.role ~= "stem" then stroke(i, st) end
  end
  for i, st in ipairs(sk.strokes) do              -- the stem last, over the others
    if st.role == "stem" then stroke(i, st) end
  end
  if opts.analysis ~= nil then
    M.analysis(c, opts.analysis, { x = ox, y = oy, scale = scale }, { colors = col,
               line_width = lw })
  end
  c:clip()
  return { x = ox, y = oy, scale = scale }
end

--- Draws a sketch's analysis `an` (docs/sketch.md "The pipeline") into canvas `c`: its
-- nodes as dots and the rays of §3.4 as thin lines to their boundary hits, a sketch point
-- (u, v) at (map.x + u * map.scale, map.y + v * map.scale). opts: `colors` (node, ray),
-- `line_width` (2). Used by M.sketch and by the sketch window's pane.
function M.analysis (c, an, map, opts)
  opts = opts or {}
  if type(an) ~= "table" or type(an.nodes) ~= "table" then
    fail("analysis", "the analysis must be a sketch's analysis (a table with nodes)")
  end
  local col = palette("analysis", M.SKETCH_COLORS, opts.colors, nil)
  local lw = opts.line_width or 2
  local ox, oy, scale = map.x, map.y, map.scale
  for _, nd in ipairs(an.nodes) do
    local p = nd.px
    if type(p) == "table" then
      local x, y = ox + p[1] * scale, oy + p[2] * scale
      for _, side in ipairs { "left", "right" } do
        local hit = nd["hit_" .. side]
        if type(hit) == "table" and not nd["miss_" .. side] and hit[1] then
          c:line(x, y, ox + hit[1] * scale, oy + hit[2] * scale, 1, col.ray)
        end
      end
      c:circle(x, y, lw + 1, col.node)
    end
  end
  return c
end

--- Writes the functions plot of a Sketch (anything with a :functions() method) or of a
-- functions table to the PNG file `path` (replaced atomically); opts as M.functions.
-- Returns the canvas and the panels.
function M.png (what, path, opts)
  if type(path) ~= "string" then fail("png", "path must be a string, got %s", type(path)) end
  local funcs = what
  if (type(what) == "table" or type(what) == "userdata") and
     type(what.functions) == "function" then
    funcs = what:functions()
  end
  local c, panels = M.functions(funcs, opts)
  local ok, err = pcall(c.save, c, path)
  if not ok then error(format("lsys.sketch.plot.png: %s", tostring(err)), 2) end
  return c, panels
end

return M
