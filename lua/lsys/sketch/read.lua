--- Sketch files: the construction lines of Anastacio et al. 2009, §3.2 (a stem,
-- left and right boundaries, inclination lines), read from JSON or SVG into one checked,
-- normalized table that lsys.sketch's pipeline takes:
--
--   { file = NAME, width = W, height = H, nodes_per_layer = N, phyllotaxis = P,
--     depth = { near = n, far = f } or nil,
--     strokes = { { role = R, index = k, id = ID or nil, points = { {x, y, p}, ... } }, ... },
--     warnings = { ... } or nil }
--
-- Coordinates are pixels (SVG: user units of the viewBox), y down as drawn; p is the pen
-- pressure in [0, 1] (§3.5), 0.5 when the file gives none. `json`, `svg` and `table` read
-- text or a table; `file` reads a file; `to_json` and `save` write a sketch back.
-- Every error is a string that begins with the file's name (and line, in an SVG) and
-- names the stroke by its index and role. Geometry (an inclination line that misses the
-- stem, a boundary on the wrong side) is the pipeline's to check, not this module's.
-- @module lsys.sketch.read
local core = require "lsys.core"
local svgpath = require "lsys.sketch.svgpath"
local cjson_safe = require "cjson.safe"

local type, pairs, ipairs, error, tostring, require, pcall, next =
      type, pairs, ipairs, error, tostring, require, pcall, next
local math, string, table = math, string, table
local format, find, sub, lower, gsub, byte, match =
      string.format, string.find, string.sub, string.lower, string.gsub, string.byte,
      string.match
local concat = table.concat
local mathtype, tointeger, huge, floor, tan, pi =
      math.type, math.tointeger, math.huge, math.floor, math.tan, math.pi
local _ENV = nil

local M = {}

--- Limits: strokes per sketch, points per stroke, points in all, the largest coordinate
-- (pixels), width and height, nodes per layer, and the largest file `file` reads.
M.MAX_STROKES = 1000
M.MAX_POINTS = 100000
M.MAX_TOTAL = 1000000
M.MAX_COORD = 1e7
M.MAX_SIZE = 1e6
M.MAX_NODES = 10000
M.MAX_FILE = 64 * 2 ^ 20

M.ROLES = { "stem", "boundary_left", "boundary_right", "inclination" }
M.PHYLLOTAXIS = { "distichous", "decussate", "fibonacci" }
local ROLE, PHYLLO = {}, {}
for _, r in ipairs(M.ROLES) do ROLE[r] = true end
for _, p in ipairs(M.PHYLLOTAXIS) do PHYLLO[p] = true end
local ROLE_LIST = concat(M.ROLES, ", ")
local TOP_KEYS = { "width", "height", "nodes_per_layer", "phyllotaxis", "depth", "strokes" }
local TOP = {}
for _, k in ipairs(TOP_KEYS) do TOP[k] = true end

local NULL = cjson_safe.null

local function finite (x)
  return type(x) == "number" and x == x and x ~= huge and x ~= -huge
end

-- A JSON array as Lua has it: a table whose keys are exactly 1..#t.
local function isarray (t)
  if type(t) ~= "table" then return false end
  local n, c = #t, 0
  for k in pairs(t) do
    if mathtype(k) ~= "integer" or k < 1 or k > n then return false end
    c = c + 1
  end
  return c == n
end

-- The shortest text of x that reads back as x.
local num = require("lsys.util.text").number

local function show (v)
  if type(v) == "string" then return "'" .. v .. "'" end
  if finite(v) then return num(v) end
  return tostring(v)
end

-- --------------------------------------------------------------------------
-- The checks common to every format: a table of the JSON shape -> a normalized sketch

-- The checker's state: the file's name, the lines of SVG strokes, what a table may hold.
local function fail (c, msg, k)
  local line = k and c.lines and c.lines[k]
  error(format("%s%s: %s", c.name, line and ":" .. line or "", msg), 0)
end

local function failat (c, line, msg)
  error(format("%s:%d: %s", c.name, line, msg), 0)
end

local function stroke_label (k, role, id)
  if role == nil then return format("stroke %d", k) end
  if id ~= nil then return format("stroke %d (%s '%s')", k, role, id) end
  return format("stroke %d (%s)", k, role)
end

local function check_size (c, t, key)
  local v = t[key]
  if v == nil or v == NULL then fail(c, key .. " missing (a number of pixels > 0)") end
  if not finite(v) or not (v > 0) or v > M.MAX_SIZE then
    fail(c, format("%s must be a number > 0 and at most %d, not %s", key, M.MAX_SIZE, show(v)))
  end
  return v
end

local function check_point (c, k, label, j, pt)
  if not isarray(pt) or #pt < 2 or #pt > 3 then
    fail(c, format("%s: point %d is not [x, y] or [x, y, pressure]", label, j), k)
  end
  local x, y, p = pt[1], pt[2], pt[3]
  for i = 1, #pt do
    local v = pt[i]
    local what = i == 1 and "x" or i == 2 and "y" or "pressure"
    if type(v) ~= "number" then
      fail(c, format("%s: point %d: %s is not a number (%s)", label, j, what,
                     v == NULL and "null" or type(v)), k)
    elseif not finite(v) then
      fail(c, format("%s: point %d: %s is not finite (%s)", label, j, what, tostring(v)), k)
    end
  end
  if not (x >= -M.MAX_COORD and x <= M.MAX_COORD and y >= -M.MAX_COORD and y <= M.MAX_COORD) then
    fail(c, format("%s: point %d: (%s, %s) is beyond %s pixels", label, j, show(x), show(y),
                   show(M.MAX_COORD)), k)
  end
  if p == nil then p = 0.5
  elseif not (p >= 0 and p <= 1) then
    fail(c, format("%s: point %d: pressure %s outside [0, 1]", label, j, show(p)), k)
  end
  return { x, y, p }
end

local function check_stroke (c, k, s, total)
  if type(s) ~= "table" or (next(s) ~= nil and isarray(s)) then
    fail(c, format("stroke %d: a stroke is an object with a role and points", k), k)
  end
  local role, id = s.role, s.id
  if role == nil or role == NULL then
    fail(c, format("stroke %d: no role (%s)", k, ROLE_LIST), k)
  elseif type(role) ~= "string" then
    fail(c, format("stroke %d: role must be a string (%s), not %s", k, ROLE_LIST, type(role)), k)
  elseif not ROLE[role] then
    fail(c, format("stroke %d: unknown role '%s' (%s)", k, role, ROLE_LIST), k)
  end
  if id == NULL then id = nil end
  if id ~= nil and type(id) ~= "string" then
    fail(c, format("%s: id must be a string, not %s", stroke_label(k, role), type(id)), k)
  end
  local label = stroke_label(k, role, id)
  for key in pairs(s) do
    if key ~= "role" and key ~= "points" and key ~= "id" and not (c.table and key == "index") then
      fail(c, format("%s: unknown key %s (role, points, id)", label, show(key)), k)
    end
  end
  if c.table and s.index ~= nil and s.index ~= k then
    fail(c, format("%s: index %s is not its position %d", label, show(s.index), k), k)
  end
  local pts = s.points
  if pts == nil or pts == NULL then fail(c, label .. ": no points", k) end
  if type(pts) ~= "table" or (next(pts) ~= nil and not isarray(pts)) then
    fail(c, format("%s: points must be a list of [x, y] or [x, y, pressure]", label), k)
  end
  local n = #pts
  if n < 2 then fail(c, label .. ": fewer than two points", k) end
  if n > M.MAX_POINTS then
    fail(c, format("%s: more than %d points (%d)", label, M.MAX_POINTS, n), k)
  end
  if total + n > M.MAX_TOTAL then
    fail(c, format("%s: more than %d points in all the strokes", label, M.MAX_TOTAL), k)
  end
  local out = {}
  for j = 1, n do out[j] = check_point(c, k, label, j, pts[j]) end
  return { role = role, index = k, id = id, points = out }
end

local function check_depth (c, d)
  if d == nil or d == NULL then return nil end
  local ok = type(d) == "table" and finite(d.near) and finite(d.far)
  if ok then
    for key in pairs(d) do if key ~= "near" and key ~= "far" then ok = false end end
  end
  if not ok then fail(c, "depth must be { near = n, far = f } with two finite numbers") end
  return { near = d.near, far = d.far }
end

-- The roles that may occur once, and the message when one occurs twice.
local function check_counts (c, strokes)
  local seen = {}
  for k, s in ipairs(strokes) do
    if s.role ~= "inclination" then
      local first = seen[s.role]
      if first then
        fail(c, format("two %s strokes (%d and %d)", s.role, first, k), k)
      end
      seen[s.role] = k
    end
  end
  if not seen.stem then fail(c, "no stem stroke") end
end

-- c: { name = file name, lines = stroke index -> SVG line, table = true when a Lua table
-- (which may also hold the normalized form's own keys: file, warnings, index) }.
local function check (c, t)
  if type(t) ~= "table" then
    fail(c, format("a sketch is a JSON object, not %s", t == NULL and "null" or type(t)))
  end
  if t[1] ~= nil then fail(c, "a sketch is a JSON object, not an array") end
  for key in pairs(t) do
    if not TOP[key] and not (c.table and (key == "file" or key == "warnings")) then
      fail(c, format("unknown key %s (%s)", show(key), concat(TOP_KEYS, ", ")))
    end
  end
  local sk = { file = c.name }
  sk.width = check_size(c, t, "width")
  sk.height = check_size(c, t, "height")
  local n = t.nodes_per_layer
  if n == nil or n == NULL then n = 5 end
  local ni = type(n) == "number" and tointeger(n)
  if not ni or ni < 1 or ni > M.MAX_NODES then
    fail(c, format("nodes_per_layer must be an integer from 1 to %d, not %s", M.MAX_NODES,
                   show(n)))
  end
  sk.nodes_per_layer = ni
  local ph = t.phyllotaxis
  if ph == nil or ph == NULL then ph = "distichous" end
  if not PHYLLO[ph] then
    fail(c, format("unknown phyllotaxis %s (%s)", show(ph), concat(M.PHYLLOTAXIS, ", ")))
  end
  sk.phyllotaxis = ph
  sk.depth = check_depth(c, t.depth)
  local st = t.strokes
  if st == nil or st == NULL then fail(c, "strokes missing (a list of strokes)") end
  if type(st) ~= "table" or (next(st) ~= nil and not isarray(st)) then
    fail(c, "strokes must be a list of strokes")
  end
  if #st > M.MAX_STROKES then
    fail(c, format("more than %d strokes (%d)", M.MAX_STROKES, #st))
  end
  local strokes, total = {}, 0
  for k = 1, #st do
    strokes[k] = check_stroke(c, k, st[k], total)
    total = total + #strokes[k].points
  end
  check_counts(c, strokes)
  sk.strokes = strokes
  local w = t.warnings
  if c.table and w ~= nil then
    if not isarray(w) then fail(c, "warnings must be a list of strings") end
    local ws = {}
    for i, m in ipairs(w) do
      if type(m) ~= "string" then fail(c, "warnings must be a list of strings") end
      ws[i] = m
    end
    if #ws > 0 then sk.warnings = ws end
  end
  return sk
end

--- Checks a Lua table of the JSON shape (or a normalized sketch) and returns a new
-- normalized sketch. `name` (default t.file, else "<table>") begins the messages.
function M.table (t, name)
  if name ~= nil and type(name) ~= "string" then
    error("lsys.sketch.read.table: the name must be a string", 2)
  end
  if name == nil then
    name = type(t) == "table" and type(t.file) == "string" and t.file or "<table>"
  end
  return check({ name = name, table = true }, t)
end

-- --------------------------------------------------------------------------
-- JSON

local BOM = "\239\187\191"             -- a UTF-8 byte order mark, which some editors write

local decoder = cjson_safe.new()
decoder.decode_invalid_numbers(false)     -- NaN, Infinity, hex: malformed, as JSON says
decoder.decode_max_depth(32)

--- Reads a sketch from JSON text. `name` (default "<json>") begins the messages.
function M.json (text, name)
  if type(text) ~= "string" then error("lsys.sketch.read.json: a string expected", 2) end
  name = name or "<json>"
  if sub(text, 1, 3) == BOM then text = sub(text, 4) end
  local t, err = decoder.decode(text)
  if t == nil and err ~= nil then
    error(format("%s: malformed JSON: %s", name, err), 0)
  end
  return check({ name = name }, t)
end

-- --------------------------------------------------------------------------
-- SVG

local SVG_NS = "http://www.w3.org/2000/svg"
local INK_NS = "http://www.inkscape.org/namespaces/inkscape"
local SEP = "\1"                           -- between a namespace and a local name
local INK_LABEL = INK_NS .. SEP .. "label"

-- Elements whose content is never drawn where it stands (or that we do not follow).
local HIDDEN = { defs = true, clipPath = true, mask = true, marker = true, symbol = true,
                 pattern = true, metadata = true, title = true, desc = true, style = true,
                 script = true, foreignObject = true, linearGradient = true,
                 radialGradient = true, filter = true }
local CONTAINER = { g = true, a = true, switch = true }
local SHAPE = { path = true, polyline = true, line = true }

-- Pixels per unit at 96 dpi (CSS).
local UNITS = { [""] = 1, px = 1, mm = 96 / 25.4, cm = 96 / 2.54, ["in"] = 96, pt = 96 / 72,
                pc = 16 }

--- The role an element's name gives: "stem", ..., or nil and true when the name looks
-- like one but is not (stem-old, inclination-, boundary). Names compare without case,
-- with spaces, underscores and hyphens alike.
function M.svg_role (s)
  if type(s) ~= "string" then return nil end
  local n = gsub(lower(s), "[%s_%-]+", "-")
  n = gsub(gsub(n, "^%-", ""), "%-$", "")
  if n == "stem" then return "stem" end
  if n == "boundary-left" or n == "left-boundary" then return "boundary_left" end
  if n == "boundary-right" or n == "right-boundary" then return "boundary_right" end
  if n == "inclination" or find(n, "^inclination%-.") or find(n, "^inclination%d") then
    return "inclination"
  end
  if find(n, "^stem") or find(n, "^boundar") or find(n, "^inclin") or find(n, "^left%-bound")
     or find(n, "^right%-bound") then
    return nil, true
  end
  return nil
end

local function mul (m, n)               -- m * n, both { a, b, c, d, e, f }
  return { m[1] * n[1] + m[3] * n[2], m[2] * n[1] + m[4] * n[2],
           m[1] * n[3] + m[3] * n[4], m[2] * n[3] + m[4] * n[4],
           m[1] * n[5] + m[3] * n[6] + m[5], m[2] * n[5] + m[4] * n[6] + m[6] }
end

local NTRANSFORM = { matrix = { 6, 6 }, translate = { 1, 2 }, scale = { 1, 2 },
                     rotate = { 1, 3 }, skewX = { 1, 1 }, skewY = { 1, 1 } }

--- The matrix { a, b, c, d, e, f } of an SVG transform list (SVG 1.1 §7.6): matrix,
-- translate, scale, rotate (degrees, about a point), skewX, skewY. `where` begins the
-- messages.
function M.transform (s, where)
  local m = { 1, 0, 0, 1, 0, 0 }
  local i, len = 1, #s
  while true do
    local _, e = find(s, "^[%s,]*", i)
    i = e + 1
    if i > len then break end
    local a, b, fname = find(s, "^(%a+)%s*%(", i)
    local close = b and find(s, ")", b + 1, true)
    if not a or not close then
      error(format("%s: bad transform at character %d", where, i), 0)
    end
    local nargs = NTRANSFORM[fname]
    if not nargs then
      error(format("%s: unknown transform '%s' at character %d", where, fname, i), 0)
    end
    local ok, v = pcall(svgpath.numbers, sub(s, b + 1, close - 1), "x")
    if not ok or #v < nargs[1] or #v > nargs[2] or (fname == "rotate" and #v == 2) then
      error(format("%s: bad arguments to %s at character %d", where, fname, i), 0)
    end
    local t
    if fname == "matrix" then t = v
    elseif fname == "translate" then t = { 1, 0, 0, 1, v[1], v[2] or 0 }
    elseif fname == "scale" then t = { v[1], 0, 0, v[2] or v[1], 0, 0 }
    elseif fname == "rotate" then
      local r = v[1] * pi / 180
      local co, si = math.cos(r), math.sin(r)
      t = { co, si, -si, co, 0, 0 }
      if v[2] then
        t = mul(mul({ 1, 0, 0, 1, v[2], v[3] }, t), { 1, 0, 0, 1, -v[2], -v[3] })
      end
    elseif fname == "skewX" then t = { 1, 0, tan(v[1] * pi / 180), 1, 0, 0 }
    else t = { 1, tan(v[1] * pi / 180), 0, 1, 0, 0 } end
    m = mul(m, t)
    i = close + 1
  end
  return m
end

-- A length attribute: a number with an optional unit, in pixels.
local function length (c, s, what, line)
  local v, j = svgpath.scan(s, format("%s:%d: %s", c.name, line, what))
  local unit = v and match(s, "^%s*([%a%%]*)%s*$", j)
  if unit == nil then failat(c, line, format("%s '%s' is not a length", what, s)) end
  local k = UNITS[lower(unit)]
  if not k then
    failat(c, line, format("%s '%s': units are px, mm, cm, in, pt and pc", what, s))
  end
  return v * k
end

-- The number list of attribute `s`, with the element in the message.
local function numbers (s, where)
  return svgpath.numbers(s, where)
end

-- The strokes of one shape element: a list of flat { x, y, s, ... } subpaths, the number
-- of nodes (points the data names) for data-pressure.
local function shape_points (kind, attrs, m, where)
  if kind == "path" then
    local d = attrs.d
    if d == nil then error(where .. ": no d attribute", 0) end
    return svgpath.flatten(d, { matrix = m, name = where, max_points = M.MAX_POINTS })
  end
  local v
  if kind == "polyline" then
    if attrs.points == nil then error(where .. ": no points attribute", 0) end
    v = numbers(attrs.points, where .. ": points")
    if #v % 2 == 1 then error(where .. ": an odd number of coordinates in points", 0) end
    if #v > 2 * M.MAX_POINTS then
      error(format("%s: more than %d points", where, M.MAX_POINTS), 0)
    end
  else
    v = {}
    for i, a in ipairs({ "x1", "y1", "x2", "y2" }) do
      local s = attrs[a] or "0"
      local n = numbers(s, where .. ": " .. a)
      if #n ~= 1 then error(format("%s: %s '%s' is not a number", where, a, s), 0) end
      v[i] = n[1]
    end
  end
  local sp = {}
  for i = 1, #v, 2 do
    local x, y = v[i], v[i + 1]
    sp[#sp + 1] = m[1] * x + m[3] * y + m[5]
    sp[#sp + 1] = m[2] * x + m[4] * y + m[6]
    sp[#sp + 1] = (i - 1) // 2
  end
  if #sp == 0 then return {}, 0 end
  return { sp }, #v // 2
end

-- Adds the strokes of one shape element to st.strokes.
local function add_shape (st, kind, attrs, m, line, role, id)
  local c = st.c
  local where = format("%s:%d: %s%s", c.name, line, kind, id and " '" .. id .. "'" or "")
  local subpaths, nodes = shape_points(kind, attrs, m, where)
  local pressure
  if attrs["data-pressure"] then
    pressure = numbers(attrs["data-pressure"], where .. ": data-pressure")
    if #pressure ~= nodes then
      error(format("%s: data-pressure has %d values for %d points", where, #pressure, nodes), 0)
    end
    for i, p in ipairs(pressure) do
      if not (p >= 0 and p <= 1) then
        error(format("%s: data-pressure value %d (%s) outside [0, 1]", where, i, show(p)), 0)
      end
    end
  end
  -- one stroke per subpath that draws something; a lone moveto only when nothing else
  local drawn = {}
  for _, sp in ipairs(subpaths) do if #sp >= 6 then drawn[#drawn + 1] = sp end end
  if #drawn == 0 then
    if subpaths[1] == nil then error(where .. ": no points", 0) end
    drawn[1] = subpaths[1]
  end
  for _, sp in ipairs(drawn) do
    local n = #st.strokes
    if n >= M.MAX_STROKES then
      error(format("%s: more than %d strokes", where, M.MAX_STROKES), 0)
    end
    st.total = st.total + #sp // 3
    if st.total > M.MAX_TOTAL then
      error(format("%s: more than %d points in all the strokes", where, M.MAX_TOTAL), 0)
    end
    local pts = {}
    for j = 1, #sp, 3 do
      local p = 0.5
      if pressure then
        local s = sp[j + 2]
        local k = floor(s)
        local f = s - k
        p = pressure[k + 1]
        if f > 0 then p = p + (pressure[k + 2] - p) * f end
      end
      pts[#pts + 1] = { sp[j], sp[j + 1], p }
    end
    st.strokes[n + 1] = { role = role, id = id, points = pts }
    c.lines[n + 1] = line
  end
end

-- The size and the viewBox origin of the root <svg>, and the settings it may carry.
local function root (st, attrs, line)
  local c = st.c
  local t = st.t
  local vb = attrs.viewBox
  if vb then
    local v = numbers(vb, format("%s:%d: viewBox", c.name, line))
    if #v ~= 4 then failat(c, line, format("viewBox '%s' is not four numbers", vb)) end
    t.width, t.height = v[3], v[4]
    st.base = { 1, 0, 0, 1, -v[1], -v[2] }
  elseif attrs.width and attrs.height then
    t.width = length(c, attrs.width, "width", line)
    t.height = length(c, attrs.height, "height", line)
  else
    failat(c, line, "no viewBox and no width and height (the sketch's size)")
  end
  if not (finite(t.width) and t.width > 0 and finite(t.height) and t.height > 0) then
    failat(c, line, format("the sketch's width and height must be > 0 (%s, %s)",
                           show(t.width), show(t.height)))
  end
  local n = attrs["data-nodes-per-layer"]
  if n then
    local v = numbers(n, format("%s:%d: data-nodes-per-layer", c.name, line))
    t.nodes_per_layer = #v == 1 and v[1] or n
  end
  t.phyllotaxis = attrs["data-phyllotaxis"]
  local near, far = attrs["data-depth-near"], attrs["data-depth-far"]
  if near or far then
    local a = numbers(near or "", format("%s:%d: data-depth-near", c.name, line))
    local b = numbers(far or "", format("%s:%d: data-depth-far", c.name, line))
    t.depth = { near = a[1], far = b[1] }
    if #a ~= 1 or #b ~= 1 then t.depth = false end
  end
end

local function start_element (st, parser, name, attrs)
  local c = st.c
  local ns, loc = match(name, "^(.*)" .. SEP .. "(.*)$")
  if not ns then ns, loc = "", name end
  local svg = ns == SVG_NS or ns == ""
  local stack = st.stack
  local parent = stack[#stack]
  local line = parser:pos()
  if parent == nil then
    if st.rooted then failat(c, line, "a second root element") end
    st.rooted = true
    if not (svg and loc == "svg") then
      failat(c, line, format("not an SVG file (the root element is '%s')", loc))
    end
    root(st, attrs, line)
    stack[1] = { m = st.base or { 1, 0, 0, 1, 0, 0 } }
    return
  end
  if parent.skip or not svg or HIDDEN[loc] then stack[#stack + 1] = { skip = true }; return end
  if loc == "svg" then
    st.warn(format("%s:%d: a nested <svg> is ignored", c.name, line))
    stack[#stack + 1] = { skip = true }
    return
  end
  local m = parent.m
  if attrs.transform then
    m = mul(m, M.transform(attrs.transform, format("%s:%d: transform", c.name, line)))
  end
  if CONTAINER[loc] then stack[#stack + 1] = { m = m }; return end
  stack[#stack + 1] = { skip = true }
  if not SHAPE[loc] then return end
  local label, id = attrs[INK_LABEL], attrs.id
  local role, near = M.svg_role(label)
  local named = label
  if not role then
    local r2, n2 = M.svg_role(id)
    role, named, near = r2, id, near or n2
  end
  if role then
    add_shape(st, loc, attrs, m, line, role, named)
  elseif near then
    local _, by_label = M.svg_role(label)
    st.warn(format("%s:%d: %s '%s' ignored: not a role name (stem, boundary-left, "
                   .. "boundary-right, inclination-*)", c.name, line, loc,
                   by_label and label or id))
  end
end

--- Reads a sketch from SVG text (see docs/sketch.md, "Sketch files"). `name` (default
-- "<svg>") begins the messages.
function M.svg (text, name)
  if type(text) ~= "string" then error("lsys.sketch.read.svg: a string expected", 2) end
  name = name or "<svg>"
  local lxp = require "lxp"
  local c = { name = name, lines = {} }
  local warnings = {}
  local st = { c = c, t = {}, stack = {}, strokes = {}, total = 0,
               warn = function (m) warnings[#warnings + 1] = m end }
  local parser
  local function refuse (p)
    failat(c, (p or parser):pos(), "document type declarations and entities are not read")
  end
  parser = lxp.new({
    StartElement = function (p, n, a) start_element(st, p, n, a) end,
    EndElement = function () st.stack[#st.stack] = nil end,
    StartDoctypeDecl = function (p, _, _, _, internal) if internal then refuse(p) end end,
    EntityDecl = refuse, UnparsedEntityDecl = refuse, NotationDecl = refuse,
  }, SEP)
  local ok, r1, msg, line = pcall(parser.parse, parser, text)
  if ok and r1 then ok, r1, msg, line = pcall(parser.parse, parser) end
  pcall(parser.close, parser)             -- raises after a failed parse: nothing to add
  if not ok then error(r1, 0) end
  if not r1 then error(format("%s:%s: malformed SVG: %s", name, tostring(line), msg), 0) end
  if not st.rooted then error(name .. ": malformed SVG: no root element", 0) end
  local t = st.t
  t.strokes = st.strokes
  if t.depth == false then fail(c, "data-depth-near and data-depth-far must be numbers") end
  local sk = check(c, t)
  if #warnings > 0 then sk.warnings = warnings end
  return sk
end

-- --------------------------------------------------------------------------
-- Files

--- Reads the sketch file `path`: JSON or SVG by the extension (.json, .svg), else by the
-- first character ('{' or '<'). Messages begin with `path`.
function M.file (path)
  if type(path) ~= "string" then error("lsys.sketch.read.file: a file name expected", 2) end
  local text, err = core.read_file(path, M.MAX_FILE)
  if text == nil then error(err, 0) end
  local ext = lower(match(path, "%.(%w+)$") or "")
  if ext == "json" then return M.json(text, path) end
  if ext == "svg" then return M.svg(text, path) end
  local first = match(text, "^%s*(.)", sub(text, 1, 3) == BOM and 4 or 1)
  if first == "{" then return M.json(text, path) end
  if first == "<" then return M.svg(text, path) end
  error(path .. ": not a sketch file (JSON or SVG)", 0)
end

-- --------------------------------------------------------------------------
-- Writing

local ESC = { ['"'] = '\\"', ["\\"] = "\\\\", ["\n"] = "\\n", ["\r"] = "\\r", ["\t"] = "\\t" }
local function str (s)
  return '"' .. gsub(s, '[%c"\\]', function (ch)
    return ESC[ch] or format("\\u%04x", byte(ch))
  end) .. '"'
end

--- The JSON text of a sketch (checked first, as `table` does): one key per line, one
-- point per line, so that two versions diff well; `json` reads it back to an equal
-- sketch. Warnings and the file name are not written.
function M.to_json (sketch)
  local sk = M.table(sketch)
  local out = { "{\n" }
  local function put (s) out[#out + 1] = s end
  put(format('  "width": %s,\n  "height": %s,\n', num(sk.width), num(sk.height)))
  put(format('  "nodes_per_layer": %d,\n  "phyllotaxis": %s,\n', sk.nodes_per_layer,
             str(sk.phyllotaxis)))
  if sk.depth then
    put(format('  "depth": {"near": %s, "far": %s},\n', num(sk.depth.near), num(sk.depth.far)))
  end
  put('  "strokes": [')
  for k, s in ipairs(sk.strokes) do
    put(k == 1 and "\n" or ",\n")
    put(format('    {"role": %s, ', str(s.role)))
    if s.id then put(format('"id": %s, ', str(s.id))) end
    put('"points": [\n')
    local pts = s.points
    for j, p in ipairs(pts) do
      put(format("      [%s, %s, %s]%s\n", num(p[1]), num(p[2]), num(p[3]),
                 j < #pts and "," or ""))
    end
    put("    ]}")
  end
  put("\n  ]\n}\n")
  return concat(out)
end

--- Writes the sketch to `path` as JSON (`to_json`), atomically: a temporary file in the
-- same folder renamed over `path` once written (lsys.core's write_file).
function M.save (sketch, path)
  if type(path) ~= "string" then error("lsys.sketch.read.save: a file name expected", 2) end
  core.write_file(path, M.to_json(sketch))
  return true
end

return M
