-- Draws the example sketches of examples/sketch/ (the figures of Anastacio, Prusinkiewicz
-- and Sousa 2009, §7): this script is the hand that drew them. Each stroke is given here by
-- a few guide points; the script runs a smooth curve through them and samples it the way a
-- mouse or a tablet reports a stroke (one point every 2-6 pixels, slower at the ends, a
-- little tremor), with a fixed seed, so the files are the same on every run. Stems drawn
-- with a tablet carry a pressure profile (§3.5: above 0.5 nearer the viewer, below farther).
--
--   lua5.4 tools/draw_sketches.lua [DIR]       (default examples/sketch)
--
-- Before writing, it checks what the pipeline will check (every inclination line crosses
-- the stem and both boundaries, each boundary lies on its side) and prints, per inclination
-- line, where it crosses the stem and the angles of its two arms, so a sketch can be tuned
-- by reading numbers as well as by looking at the plant. Organ strokes (the 3-view strokes
-- of §6) are written by the same script, as organ files.
local dir = arg and arg[1] or "examples/sketch"

local floor, sqrt, abs, atan, deg = math.floor, math.sqrt, math.abs, math.atan, math.deg

-- A Catmull-Rom curve through the guide points (end points doubled), 24 samples a span.
local function smooth (g)
  local out = {}
  local n = #g
  for i = 1, n - 1 do
    local p0, p1, p2, p3 = g[math.max(i - 1, 1)], g[i], g[i + 1], g[math.min(i + 2, n)]
    for k = 0, 23 do
      local t = k / 24
      local t2, t3 = t * t, t * t * t
      local function c (j)
        return 0.5 * (2 * p1[j] + (-p0[j] + p2[j]) * t + (2 * p0[j] - 5 * p1[j] + 4 * p2[j]
          - p3[j]) * t2 + (-p0[j] + 3 * p1[j] - 3 * p2[j] + p3[j]) * t3)
      end
      out[#out + 1] = { c(1), c(2) }
    end
  end
  out[#out + 1] = { g[n][1], g[n][2] }
  return out
end

local function cumlen (pts)
  local s = { 0 }
  for i = 2, #pts do
    local dx, dy = pts[i][1] - pts[i - 1][1], pts[i][2] - pts[i - 1][2]
    s[i] = s[i - 1] + sqrt(dx * dx + dy * dy)
  end
  return s
end

local function at (pts, s, d)
  local i = 2
  while i < #pts and s[i] < d do i = i + 1 end
  local seg = s[i] - s[i - 1]
  local t = seg > 0 and (d - s[i - 1]) / seg or 0
  t = math.max(0, math.min(1, t))
  return pts[i - 1][1] + t * (pts[i][1] - pts[i - 1][1]),
         pts[i - 1][2] + t * (pts[i][2] - pts[i - 1][2])
end

-- A profile { {u, value}, ... } at u in [0, 1]: a smooth curve through the values (a
-- Catmull-Rom spline in u, its tangents from the neighbours), flat before the first and
-- after the last. A hand's pressure changes smoothly and does not pause at each key.
local function profile (prof, u)
  local n = #prof
  if u <= prof[1][1] then return prof[1][2] end
  if u >= prof[n][1] then return prof[n][2] end
  local i = 2
  while prof[i][1] < u do i = i + 1 end
  local a, b = prof[i - 1], prof[i]
  local function slope (k)
    local p, q = prof[math.max(k - 1, 1)], prof[math.min(k + 1, n)]
    return (q[2] - p[2]) / (q[1] - p[1])
  end
  local h = b[1] - a[1]
  local t = (u - a[1]) / h
  local m0, m1 = slope(i - 1) * h, slope(i) * h
  local t2, t3 = t * t, t * t * t
  return (2 * t3 - 3 * t2 + 1) * a[2] + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * b[2]
    + (t3 - t2) * m1
end

-- The points a pointing device reports along the guide curve: steps of 2-6 pixels (shorter
-- near the ends, where the hand is slow), a slow sideways wobble of about half a pixel and
-- rounding to whole pixels (a mouse) or tenths (a tablet, which also reports pressure,
-- smoothly: 1024 levels, a slow swell and little noise).
local function stroke (guide, opts)
  local curve = smooth(guide)
  local s = cumlen(curve)
  local total = s[#s]
  local phase, freq = math.random() * 6.28, 0.02 + 0.02 * math.random()
  local pts, d = {}, 0
  local function push (x, y, u)
    -- the normal of the curve for the wobble
    local x2, y2 = at(curve, s, math.min(total, u * total + 1))
    local x1, y1 = at(curve, s, math.max(0, u * total - 1))
    local nx, ny = -(y2 - y1), x2 - x1
    local nl = sqrt(nx * nx + ny * ny)
    if nl > 0 then nx, ny = nx / nl, ny / nl end
    local w = 0.6 * math.sin(phase + freq * u * total) + (math.random() - 0.5) * 0.5
    if u == 0 or u == 1 then w = 0 end
    x, y = x + w * nx, y + w * ny
    local p
    if opts.pressure then
      -- a pen's pressure: the profile, a slow swell of the hand and a little sensor noise,
      -- read at 1024 levels (a cheap tablet's; better ones have 2048 to 8192)
      p = profile(opts.pressure, u) + 0.008 * math.sin(phase + 0.5 * freq * u * total)
        + (math.random() - 0.5) * 0.003
      p = math.max(0, math.min(1, p))
      pts[#pts + 1] = { floor(x * 10 + 0.5) / 10, floor(y * 10 + 0.5) / 10,
                        floor(p * 1024 + 0.5) / 1024 }
    else
      pts[#pts + 1] = { floor(x + 0.5), floor(y + 0.5) }
    end
  end
  while d < total do
    local x, y = at(curve, s, d)
    push(x, y, d / total)
    local u = d / total
    local ends = math.min(u, 1 - u)
    local step = (ends < 0.1 and 2 or 3) + math.random() * (ends < 0.1 and 2 or 3)
    d = d + step
  end
  local x, y = at(curve, s, total)
  push(x, y, 1)
  return pts
end

-- Segment intersection (for the checks): the points where polylines a and b cross.
local function crossings (a, b)
  local out = {}
  for i = 2, #a do
    local p, r = a[i - 1], { a[i][1] - a[i - 1][1], a[i][2] - a[i - 1][2] }
    for j = 2, #b do
      local q, s = b[j - 1], { b[j][1] - b[j - 1][1], b[j][2] - b[j - 1][2] }
      local den = r[1] * s[2] - r[2] * s[1]
      if den ~= 0 then
        local t = ((q[1] - p[1]) * s[2] - (q[2] - p[2]) * s[1]) / den
        local u = ((q[1] - p[1]) * r[2] - (q[2] - p[2]) * r[1]) / den
        if t >= 0 and t < 1 and u >= 0 and u < 1 then
          out[#out + 1] = { p[1] + t * r[1], p[2] + t * r[2] }
        end
      end
    end
  end
  return out
end

local function check (name, sk)
  local by = {}
  for _, st in ipairs(sk.strokes) do
    by[st.role] = by[st.role] or {}
    table.insert(by[st.role], st)
  end
  local stem = by.stem[1].points
  local L = cumlen(stem)
  io.write(string.format("%s: stem %.0f px, %d strokes\n", name, L[#L], #sk.strokes))
  for k, st in ipairs(by.inclination or {}) do
    local c = crossings(st.points, stem)
    local l = crossings(st.points, by.boundary_left[1].points)
    local r = crossings(st.points, by.boundary_right[1].points)
    assert(#c == 1 and #l == 1 and #r == 1, string.format(
      "%s: inclination %d crosses the stem %d, left %d, right %d times", name, k, #c, #l, #r))
    local function ang (p)   -- from the screen's up direction, in degrees
      return deg(atan(abs(p[1] - c[1][1]), c[1][2] - p[2]))
    end
    local function dist (p) return sqrt((p[1] - c[1][1]) ^ 2 + (p[2] - c[1][2]) ^ 2) end
    io.write(string.format("  incl %d at y %5.1f: left %5.1f deg %5.1f px, right %5.1f deg "
      .. "%5.1f px\n", k, c[1][2], ang(l[1]), dist(l[1]), ang(r[1]), dist(r[1])))
    assert(l[1][1] < c[1][1] and r[1][1] > c[1][1], name .. ": a boundary on the wrong side")
  end
end

-- JSON by hand: one stroke a line block, points in rows, so the files diff well.
local function num (x) return (string.format("%.2f", x):gsub("0+$", ""):gsub("%.$", "")) end

local function write_json (path, text)
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
end

local function points_json (pts, indent)
  local rows, line = {}, {}
  for i, p in ipairs(pts) do
    local items = {}
    for j = 1, #p do items[j] = num(p[j]) end
    line[#line + 1] = "[" .. table.concat(items, ", ") .. "]"
    if #line == 8 or i == #pts then
      rows[#rows + 1] = indent .. table.concat(line, ", ")
      line = {}
    end
  end
  return "[\n" .. table.concat(rows, ",\n") .. "\n" .. indent:sub(3) .. "]"
end

local function sketch_json (sk)
  local out = { "{\n" }
  out[#out + 1] = string.format('  "width": %d, "height": %d, "nodes_per_layer": %d, '
    .. '"phyllotaxis": "%s",\n  "strokes": [\n', sk.width, sk.height, sk.nodes_per_layer,
    sk.phyllotaxis)
  for i, st in ipairs(sk.strokes) do
    out[#out + 1] = string.format('    {"role": "%s", "points": %s}%s\n', st.role,
      points_json(st.points, "      "), i < #sk.strokes and "," or "")
  end
  out[#out + 1] = "  ]\n}\n"
  return table.concat(out)
end

-- Sketch helpers: a chevron inclination line through the stem at (xc, yc), its arms
-- reaching x = xl and x = xr and rising (negative) or falling (positive) by dl and dr
-- pixels; a slight sag in the middle of each arm as a hand draws it.
local function chevron (xc, yc, xl, dl, xr, dr)
  return { { xl, yc + dl }, { (xl + xc) / 2, yc + dl / 2 + 1.5 }, { xc, yc },
           { (xr + xc) / 2, yc + dr / 2 + 1.5 }, { xr, yc + dr } }
end

-- The mirror of a left boundary about the vertical line x = axis, with a little change of
-- each point by (dx, dy), since no hand draws two sides alike.
local function mirror (g, axis, wob)
  local out = {}
  for i, p in ipairs(g) do
    local w = wob and wob[i] or { 0, 0 }
    out[i] = { 2 * axis - p[1] + w[1], p[2] + w[2] }
  end
  return out
end

local SKETCHES = {}

-- Fig. 7: a pine cone. An ovoid silhouette widest below the middle and pointed at the top,
-- many thin layers; the lower scales point outward and down, the upper ones up.
SKETCHES.fig7_cone = function ()
  local left = { { 197, 566 }, { 160, 548 }, { 118, 500 }, { 94, 430 }, { 90, 350 },
                 { 104, 270 }, { 132, 190 }, { 166, 118 }, { 196, 62 } }
  local sk = { width = 400, height = 600, nodes_per_layer = 55, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = { { 200, 575 }, { 199, 470 }, { 201, 330 }, { 199, 190 },
                                 { 200, 68 } } },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 200, { { 0, 0 }, { 2, -3 },
        { -3, 2 }, { 2, 0 }, { 4, 4 }, { -2, 3 }, { 0, -2 }, { 3, 2 }, { 0, 0 } }) },
    } }
  local lines = { { 535, 34 }, { 478, 22 }, { 420, 8 }, { 362, -6 }, { 305, -20 },
                  { 250, -34 }, { 196, -48 }, { 145, -60 }, { 82, -72 } }
  for _, l in ipairs(lines) do
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(200, l[1], 70, l[2], 330, l[2] + 2) })
  end
  return sk
end

-- Fig. 7: a flower on a stalk. The layers are at the top, close together: long outer petals
-- spread almost level, the inner ones shorter and more upright (a rosette-like head).
SKETCHES.fig7_flower = function ()
  local left = { { 197, 364 }, { 140, 362 }, { 70, 350 }, { 38, 318 }, { 56, 280 },
                 { 100, 250 }, { 150, 230 }, { 196, 224 } }
  local sk = { width = 400, height = 500, nodes_per_layer = 13, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = { { 203, 488 }, { 200, 420 }, { 198, 330 }, { 200, 259 } } },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 200, { { 0, 0 }, { -3, 2 },
        { 2, -2 }, { 4, 1 }, { 0, 3 }, { -2, 0 }, { 2, -1 }, { 0, 0 } }) },
    } }
  local lines = { { 340, 6 }, { 318, -10 }, { 298, -36 }, { 280, -64 }, { 266, -92 } }
  for _, l in ipairs(lines) do
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(200, l[1], 25, l[2] * 1.2, 375, l[2] * 1.2) })
  end
  return sk
end

-- Fig. 8: one herb for the three phyllotaxis patterns, three nodes per layer: a gently
-- swaying stem, a lanceolate silhouette, leaves rising at 50-70 degrees.
SKETCHES.fig8_herb = function ()
  local left = { { 198, 572 }, { 150, 540 }, { 104, 470 }, { 84, 380 }, { 92, 280 },
                 { 122, 190 }, { 166, 110 }, { 200, 66 } }
  local sk = { width = 400, height = 600, nodes_per_layer = 3, phyllotaxis = "decussate",
    strokes = {
      { role = "stem", guide = { { 200, 580 }, { 205, 460 }, { 197, 320 }, { 201, 180 },
                                 { 207, 70 } } },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 202, { { 0, 0 }, { 3, 2 }, { 4, -3 },
        { 6, 0 }, { 2, 4 }, { -3, 2 }, { 1, 0 }, { 0, 0 } }) },
    } }
  local lines = { { 530, -26 }, { 450, -40 }, { 370, -50 }, { 290, -60 }, { 210, -70 },
                  { 140, -76 } }
  for _, l in ipairs(lines) do
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(201, l[1], 55, l[2], 350, l[2] - 3) })
  end
  return sk
end

-- Fig. 9: a pinnate leaf. A long rachis that bends a little to the right near the tip, a
-- narrow silhouette widest in the lower third, leaflets at about 60 degrees that get
-- shorter towards the tip; a bare petiole below the first pair.
SKETCHES.fig9_leaf = function ()
  local sk = { width = 300, height = 600, nodes_per_layer = 2, phyllotaxis = "distichous",
    strokes = {
      { role = "stem", guide = { { 150, 585 }, { 149, 470 }, { 152, 330 }, { 162, 190 },
                                 { 184, 50 } } },
      { role = "boundary_left", guide = { { 148, 552 }, { 92, 520 }, { 66, 440 },
        { 70, 330 }, { 96, 220 }, { 134, 120 }, { 176, 48 } } },
      { role = "boundary_right", guide = { { 152, 552 }, { 208, 518 }, { 236, 436 },
        { 238, 330 }, { 230, 220 }, { 212, 120 }, { 190, 46 } } },
    } }
  local lines = { { 536, -22 }, { 470, -34 }, { 404, -40 }, { 338, -44 }, { 272, -46 },
                  { 206, -48 }, { 140, -50 }, { 84, -50 } }
  for _, l in ipairs(lines) do
    local xc = 150 + (l[1] < 330 and (330 - l[1]) ^ 2 / 3200 or 0)
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(xc, l[1], xc - 110, l[2], xc + 110, l[2] - 2) })
  end
  return sk
end

-- Fig. 9: the axis of the double compound leaf. A straight axis, pinnae at 55 degrees,
-- long at the base and short at the tip (a triangular silhouette), one pair per layer.
SKETCHES.fig9_axis = function ()
  local left = { { 198, 552 }, { 120, 520 }, { 40, 460 }, { 38, 380 }, { 80, 280 },
                 { 134, 170 }, { 196, 52 } }
  local sk = { width = 400, height = 600, nodes_per_layer = 1, phyllotaxis = "distichous",
    strokes = {
      { role = "stem", guide = { { 200, 585 }, { 201, 440 }, { 199, 260 }, { 201, 50 } } },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 200, { { 0, 0 }, { 2, 3 }, { -3, 2 },
        { 2, -2 }, { 3, 3 }, { -2, 0 }, { 0, 0 } }) },
    } }
  local lines = { { 520, -60 }, { 430, -80 }, { 340, -90 }, { 250, -96 }, { 160, -100 },
                  { 90, -100 } }
  for _, l in ipairs(lines) do
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(200, l[1], 15, l[2], 385, l[2]) })
  end
  return sk
end

-- Fig. 10 / fig. 5: a stem drawn with a tablet. The pen presses harder in the lower half
-- (the stem comes towards the viewer) and lightens towards the top (it leans away), while
-- the drawn line curves to the right: in 3D the stem bends out of the drawing plane.
SKETCHES.fig10_depth = function ()
  local left = { { 196, 560 }, { 140, 520 }, { 100, 440 }, { 96, 340 }, { 118, 240 },
                 { 160, 150 }, { 214, 86 } }
  local sk = { width = 400, height = 600, nodes_per_layer = 2, phyllotaxis = "decussate",
    strokes = {
      { role = "stem", guide = { { 200, 580 }, { 196, 470 }, { 200, 360 }, { 216, 240 },
                                 { 244, 140 }, { 262, 70 } },
        pressure = { { 0, 0.5 }, { 0.15, 0.55 }, { 0.4, 0.85 }, { 0.6, 0.6 }, { 0.8, 0.25 },
                     { 1, 0.15 } } },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = { { 204, 560 }, { 262, 520 }, { 300, 440 },
        { 316, 340 }, { 312, 240 }, { 296, 150 }, { 270, 80 } } },
    } }
  local lines = { { 520, -30 }, { 440, -44 }, { 360, -54 }, { 280, -62 }, { 200, -68 },
                  { 128, -70 } }
  for _, l in ipairs(lines) do
    -- the drawn stem's x at this height (the lines cross it where it is)
    local y = l[1]
    local xc = y > 360 and 198 or 200 + (360 - y) * 0.22
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(xc, y, 60, l[2], 360, l[2]) })
  end
  return sk
end

-- Figs. 11 and 12: a bromeliad from two sketches. The leaves: a short stem, a wide vase of a
-- silhouette, long leaves that arch out level at the bottom of the rosette and stand up in
-- its middle. The inflorescence: a stalk from the centre of the rosette with short bracts
-- in its upper third. Both are drawn on one stem, the stalk, as the foxglove's are.
-- `pressure` draws the stem with the tablet (fig. 12): the stalk leans away from the viewer.
local BROMELIAD_STEM = { { 250, 492 }, { 251, 400 }, { 249, 260 }, { 250, 150 }, { 251, 70 } }
local BROMELIAD_PRESSURE = { { 0, 0.5 }, { 0.4, 0.45 }, { 1, 0.2 } }
local function bromeliad_leaves (pressure)
  local left = { { 246, 496 }, { 160, 494 }, { 70, 470 }, { 28, 380 }, { 26, 240 },
                 { 66, 110 }, { 110, 30 } }
  local sk = { width = 500, height = 500, nodes_per_layer = 8, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = BROMELIAD_STEM, pressure = pressure and BROMELIAD_PRESSURE,
        seed = pressure and "bromeliad 3D" or "bromeliad" },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 250, { { 0, 0 }, { 3, -2 }, { -4, 3 },
        { 3, 2 }, { -2, -3 }, { 4, 0 }, { 0, 0 } }) },
    } }
  local lines = { { 478, -12, 240 }, { 452, -60, 240 }, { 420, -140, 236 },
                  { 388, -240, 220 }, { 358, -330, 200 } }
  for _, l in ipairs(lines) do
    local r = l[3]
    table.insert(sk.strokes, { role = "inclination",
      guide = { { 250 - r, l[1] + l[2] }, { 250 - r / 2, l[1] + l[2] / 2 + 3 }, { 250, l[1] },
                { 250 + r / 2, l[1] + l[2] / 2 + 3 }, { 250 + r, l[1] + l[2] } } })
  end
  return sk
end

local function bromeliad_spike (pressure)
  local left = { { 247, 268 }, { 212, 250 }, { 200, 200 }, { 210, 140 }, { 232, 90 },
                 { 249, 66 } }
  local sk = { width = 500, height = 500, nodes_per_layer = 6, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = BROMELIAD_STEM, pressure = pressure and BROMELIAD_PRESSURE,
        seed = pressure and "bromeliad 3D" or "bromeliad" },
      { role = "boundary_left", guide = left },
      { role = "boundary_right", guide = mirror(left, 250, { { 0, 0 }, { 2, 3 }, { -3, 0 },
        { 2, -2 }, { 0, 3 }, { 0, 0 } }) },
    } }
  local lines = { { 258, -14 }, { 222, -24 }, { 186, -30 }, { 150, -34 }, { 114, -38 },
                  { 84, -40 } }
  for _, l in ipairs(lines) do
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(250, l[1], 180, l[2], 320, l[2]) })
  end
  return sk
end

SKETCHES.fig11_leaves = function () return bromeliad_leaves(false) end
SKETCHES.fig11_spike = function () return bromeliad_spike(false) end
SKETCHES.fig12_leaves = function () return bromeliad_leaves(true) end
SKETCHES.fig12_spike = function () return bromeliad_spike(true) end

-- Figs. 13 and 14: a foxglove from two sketches on one stem. The flowers: a tall raceme on
-- the upper two thirds of the stem, bells that hang (the arms of the inclination lines
-- fall) and get smaller towards the tip. The leaves: a wide rosette at the base whose
-- leaves get shorter and rise up the stem. Drawn with the tablet (fig. 14), the stem leans
-- back and then forward at the top, as a heavy raceme nods.
local FOXGLOVE_STEM = { { 150, 690 }, { 152, 560 }, { 147, 420 }, { 150, 290 }, { 157, 160 },
                        { 168, 40 } }
local FOXGLOVE_PRESSURE = { { 0, 0.5 }, { 0.3, 0.4 }, { 0.6, 0.45 }, { 0.85, 0.7 },
                            { 1, 0.85 } }

local function stem_x (y)     -- the guide's x at height y (linear between guide points)
  local g = FOXGLOVE_STEM
  for i = 2, #g do
    if y >= g[i][2] then
      local t = (y - g[i - 1][2]) / (g[i][2] - g[i - 1][2])
      return g[i - 1][1] + t * (g[i][1] - g[i - 1][1])
    end
  end
  return g[#g][1]
end

local function foxglove_flowers (pressure)
  local sk = { width = 300, height = 700, nodes_per_layer = 6, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = FOXGLOVE_STEM, pressure = pressure and FOXGLOVE_PRESSURE,
        seed = pressure and "foxglove 3D" or "foxglove" },
      { role = "boundary_left", guide = { { 146, 470 }, { 100, 450 }, { 92, 360 },
        { 102, 260 }, { 122, 160 }, { 150, 80 }, { 165, 46 } } },
      { role = "boundary_right", guide = { { 150, 470 }, { 198, 448 }, { 210, 360 },
        { 204, 260 }, { 192, 160 }, { 180, 90 }, { 170, 46 } } },
    } }
  local lines = { { 450, 22 }, { 390, 20 }, { 330, 18 }, { 270, 16 }, { 210, 12 }, { 150, 6 },
                  { 100, 0 }, { 64, -6 } }
  for _, l in ipairs(lines) do
    local xc = stem_x(l[1])
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(xc, l[1], xc - 85, l[2], xc + 85, l[2]) })
  end
  return sk
end

local function foxglove_leaves (pressure)
  local sk = { width = 300, height = 700, nodes_per_layer = 5, phyllotaxis = "fibonacci",
    strokes = {
      { role = "stem", guide = FOXGLOVE_STEM, pressure = pressure and FOXGLOVE_PRESSURE,
        seed = pressure and "foxglove 3D" or "foxglove" },
      { role = "boundary_left", guide = { { 146, 696 }, { 60, 690 }, { 12, 640 }, { 20, 580 },
        { 70, 530 }, { 120, 490 }, { 146, 470 } } },
      { role = "boundary_right", guide = { { 154, 696 }, { 240, 688 }, { 288, 636 },
        { 282, 576 }, { 230, 528 }, { 180, 490 }, { 152, 470 } } },
    } }
  local lines = { { 680, 4 }, { 652, -22 }, { 612, -44 }, { 562, -56 }, { 512, -60 } }
  for _, l in ipairs(lines) do
    local xc = stem_x(l[1])
    table.insert(sk.strokes, { role = "inclination",
      guide = chevron(xc, l[1], xc - 148, l[2], xc + 148, l[2]) })
  end
  return sk
end

SKETCHES.fig13_flowers = function () return foxglove_flowers(false) end
SKETCHES.fig13_leaves = function () return foxglove_leaves(false) end
SKETCHES.fig14_flowers = function () return foxglove_flowers(true) end
SKETCHES.fig14_leaves = function () return foxglove_leaves(true) end

-- --------------------------------------------------------------------------
-- Organs: the 3-view strokes of §6 (lsys.sketch.organ's conventions, docs/sketch.md
-- "Organs"). Top view: the base at the bottom, the tip up; side view: the base at the
-- bottom, the upper side of the organ to the right; front view: the cross-section from the
-- left boundary to the right one, up is the upper side. Each view is drawn on its own
-- 200 x 320 pixel pad with the base of the organ at (100, 300).
local ORGANS = {}

-- resolution: Bézier patches {across, along} of the fitted surface; precision: lines per
-- patch {across, along} -- kept low, since a plant draws its organ hundreds of times.
local function organ (left, right_wob, side, front, resolution, precision)
  return { top = { left = left, right = mirror(left, 100, right_wob) }, side = side,
           front = front, resolution = resolution or { 2, 4 }, precision = precision or { 2, 2 } }
end

-- A pine-cone scale: a narrow claw widening into a broad, rounded, thick end that turns
-- outward (the apophysis); its back is convex.
ORGANS.scale = function ()
  return organ({ { 97, 300 }, { 88, 262 }, { 70, 200 }, { 50, 140 }, { 44, 100 },
                 { 56, 70 }, { 80, 56 }, { 100, 54 } },
               { { 0, 0 }, { -2, 0 }, { 3, 2 }, { -2, -1 }, { 2, 3 }, { 0, 2 }, { -2, 0 },
                 { 0, 0 } },
               { { 100, 300 }, { 101, 230 }, { 100, 160 }, { 104, 110 }, { 114, 76 },
                 { 126, 56 } },
               { { 20, 200 }, { 60, 186 }, { 100, 180 }, { 140, 186 }, { 180, 200 } },
               { 2, 3 }, { 2, 2 })
end

-- A petal: long and narrow at the base, broad and rounded at the tip, cupped, its tip
-- turning up.
ORGANS.petal = function ()
  return organ({ { 98, 300 }, { 90, 260 }, { 74, 190 }, { 66, 120 }, { 72, 72 },
                 { 86, 48 }, { 99, 42 } },
               { { 0, 0 }, { 1, 2 }, { -3, 0 }, { 2, -2 }, { -1, 1 }, { 2, 0 }, { 0, 0 } },
               { { 100, 300 }, { 100, 220 }, { 104, 150 }, { 114, 90 }, { 128, 48 } },
               { { 20, 180 }, { 60, 196 }, { 100, 200 }, { 140, 195 }, { 180, 180 } },
               { 2, 3 }, { 2, 2 })
end

-- An ovate leaf with a drawn-out tip, folded a little along the midrib (a V), arching.
ORGANS.leaf = function ()
  return organ({ { 98, 300 }, { 78, 280 }, { 54, 230 }, { 46, 170 }, { 58, 110 },
                 { 80, 64 }, { 100, 30 } },
               { { 0, 0 }, { 2, 1 }, { -2, -2 }, { 3, 0 }, { 0, 3 }, { -2, 0 }, { 0, 0 } },
               { { 100, 300 }, { 108, 230 }, { 110, 160 }, { 104, 100 }, { 92, 40 } },
               { { 20, 180 }, { 60, 190 }, { 100, 202 }, { 140, 189 }, { 180, 180 } },
               { 2, 4 }, { 2, 2 })
end

-- A leaflet of the compound leaf: elliptic, flat but for a shallow V.
ORGANS.leaflet = function ()
  return organ({ { 98, 300 }, { 84, 270 }, { 72, 210 }, { 72, 140 }, { 82, 80 },
                 { 100, 40 } },
               { { 0, 0 }, { -1, 2 }, { 2, 0 }, { -2, 1 }, { 0, -2 }, { 0, 0 } },
               nil,
               { { 20, 180 }, { 100, 192 }, { 180, 180 } },
               { 2, 3 }, { 1, 2 })
end

-- A bromeliad leaf: a long strap of even width ending in a point, channelled (a deep U),
-- rising and then arching over (its midrib bends towards its lower side).
ORGANS.strap = function ()
  return organ({ { 94, 300 }, { 86, 270 }, { 84, 200 }, { 85, 130 }, { 88, 70 },
                 { 100, 20 } },
               { { 0, 0 }, { 1, 1 }, { -1, 0 }, { 1, -1 }, { -1, 0 }, { 0, 0 } },
               { { 100, 300 }, { 98, 240 }, { 90, 180 }, { 72, 130 }, { 44, 100 },
                 { 12, 96 } },
               { { 20, 170 }, { 50, 200 }, { 100, 212 }, { 150, 200 }, { 180, 170 } },
               { 2, 6 }, { 2, 2 })
end

-- A bract of the bromeliad's inflorescence: short, broad at the base, pointed, cupped.
ORGANS.bract = function ()
  return organ({ { 96, 300 }, { 70, 270 }, { 60, 210 }, { 70, 140 }, { 86, 90 },
                 { 100, 60 } },
               { { 0, 0 }, { 2, -2 }, { -2, 1 }, { 2, 0 }, { -1, 1 }, { 0, 0 } },
               { { 100, 300 }, { 104, 220 }, { 112, 150 }, { 124, 70 } },
               { { 20, 170 }, { 60, 205 }, { 100, 215 }, { 140, 204 }, { 180, 170 } },
               { 2, 3 }, { 2, 2 })
end

-- A foxglove flower: a tube widening from the stalk to a wide mouth (the cross-section an
-- almost closed ring), its end bending down a little.
ORGANS.bell = function ()
  return organ({ { 96, 300 }, { 92, 270 }, { 84, 200 }, { 74, 130 }, { 62, 84 },
                 { 56, 62 } },
               { { 0, 0 }, { 1, 0 }, { -2, 1 }, { 1, -1 }, { 0, 1 }, { -2, 2 } },
               { { 100, 300 }, { 101, 230 }, { 98, 160 }, { 90, 110 }, { 80, 70 } },
               { { 40, 150 }, { 24, 190 }, { 40, 236 }, { 100, 260 }, { 160, 236 },
                 { 176, 190 }, { 160, 150 } },
               { 6, 3 }, { 2, 2 })
end

-- A foxglove leaf: long, ovate-lanceolate, folded along the midrib, arching over.
ORGANS.foxleaf = function ()
  return organ({ { 98, 300 }, { 80, 272 }, { 64, 210 }, { 62, 140 }, { 74, 80 },
                 { 100, 20 } },
               { { 0, 0 }, { 2, 0 }, { -2, 1 }, { 2, -2 }, { -1, 0 }, { 0, 0 } },
               { { 100, 300 }, { 106, 220 }, { 104, 150 }, { 92, 90 }, { 74, 40 } },
               { { 20, 180 }, { 60, 190 }, { 100, 200 }, { 140, 190 }, { 180, 180 } },
               { 2, 4 }, { 2, 2 })
end

local function organ_json (o)
  local out = { '{"organ": {\n  "name": "', o.name, '",\n',
                string.format('  "resolution": [%d, %d], "precision": [%d, %d],\n',
                              o.resolution[1], o.resolution[2], o.precision[1],
                              o.precision[2]),
                '  "top": {\n    "left": ',
                points_json(o.top.left, "      "), ',\n    "right": ',
                points_json(o.top.right, "      "), "\n  }" }
  for _, view in ipairs { "side", "front" } do
    if o[view] then
      out[#out + 1] = ',\n  "' .. view .. '": ' .. points_json(o[view], "    ")
    end
  end
  out[#out + 1] = "\n}}\n"
  return table.concat(out)
end

local function seeded (key)
  local seed = 0
  for k = 1, #key do seed = (seed * 31 + key:byte(k)) % 2147483647 end
  math.randomseed(seed)
end

local function write_all ()
  local names = {}
  for name in pairs(SKETCHES) do names[#names + 1] = name end
  table.sort(names)
  for _, name in ipairs(names) do
    local sk = SKETCHES[name]()
    for i, st in ipairs(sk.strokes) do
      -- a seed from the sketch's name and the stroke's place, so that adding a sketch or a
      -- stroke changes no other; a stroke shared by two sketches (the foxglove's stem)
      -- names its own seed and is the same in both
      seeded(st.seed or (name .. "/" .. i))
      st.points = stroke(st.guide, st)
    end
    check(name, sk)
    write_json(dir .. "/" .. name .. ".json", sketch_json(sk))
  end
  names = {}
  for name in pairs(ORGANS) do names[#names + 1] = name end
  table.sort(names)
  for _, name in ipairs(names) do
    local o = ORGANS[name]()
    seeded("organ " .. name)
    o.name = name
    o.top.left, o.top.right = stroke(o.top.left, {}), stroke(o.top.right, {})
    if o.side then o.side = stroke(o.side, {}) end
    o.front = stroke(o.front, {})
    write_json(dir .. "/organ_" .. name .. ".json", organ_json(o))
  end
end

write_all()
