--- SVG path data and number lists, flattened to polylines (sketch files).
--
-- `flatten(d, opts)` reads the `d` attribute of an SVG `<path>` (SVG 1.1 §8.3, SVG 2 §9.3:
-- M L H V C S Q T A Z, absolute and relative, implicit repeated commands, numbers such as
-- `1e-3`, `.5.5` and `-1-2`, arc flags written together as in `a5 5 0 01 10 0`) and
-- returns one polyline per subpath, curves and arcs flattened after the transform, so the
-- deviation bound holds in the units the caller works in. `numbers(s, what)` reads the
-- number lists of `points`, `viewBox` and `data-pressure`.
--
-- Curves are cut into n equal parameter steps with n from the curve's second derivative
-- (a polynomial piece of degree d deviates from its chord by at most max|B''| / (8 n^2)),
-- so a curve costs no recursion and its point count is known before any point is made;
-- arcs take the angle step that keeps a circle of their largest radius within the bound.
-- Errors name the element (opts.name) and the 1-based character position in the data.
-- @module lsys.sketch.svgpath
local type, error, tonumber = type, error, tonumber
local math, string = math, string
local format, find, sub, byte = string.format, string.find, string.sub, string.byte
local sqrt, abs, ceil, max, cos, sin, asin, atan, pi =
      math.sqrt, math.abs, math.ceil, math.max, math.cos, math.sin, math.asin, math.atan, math.pi
local huge = math.huge
local _ENV = nil

local M = {}

--- Largest deviation of a flattened curve from the true one (output units), and the
-- largest number of points of one element unless opts say otherwise.
M.TOLERANCE = 0.25
M.MAX_POINTS = 100000

local function finite (x) return x == x and x ~= huge and x ~= -huge end

-- --------------------------------------------------------------------------
-- The scanner: numbers and flags separated by comma-wsp (SVG 2 §9.3.9)

local WSP = "^[ \t\r\n\f]*"
local SEP = "^[ \t\r\n\f]*,?[ \t\r\n\f]*"

local function fail (name, what, pos)
  error(format("%s: %s at character %d", name, what, pos), 0)
end

-- The number at `i` (after an optional comma-wsp when `sep`): the value and the index
-- after it, or nil when none starts there.
local function number (s, i, sep, name)
  local _, e = find(s, sep and SEP or WSP, i)
  i = e + 1
  local a, b = find(s, "^[+-]?%d+%.?%d*", i)
  if not a then a, b = find(s, "^[+-]?%.%d+", i) end
  if not a then return nil, i end
  local _, x = find(s, "^[eE][+-]?%d+", b + 1)
  if x then b = x end
  local v = tonumber(sub(s, a, b))
  if v == nil or not finite(v) then fail(name, "number out of range", a) end
  return v, b + 1
end

-- A flag (a single 0 or 1), after an optional comma-wsp.
local function flag (s, i, name)
  local _, e = find(s, SEP, i)
  i = e + 1
  local c = byte(s, i)
  if c == 48 then return false, i + 1 elseif c == 49 then return true, i + 1 end
  fail(name, "an arc flag (0 or 1) expected", i)
end

--- The number at the start of `s` (after white space) and the index after it, or nil
-- when `s` does not begin with one. Raises "NAME: number out of range at character N".
function M.scan (s, name)
  return number(s, 1, false, name or "number")
end

--- The numbers of `s` separated by commas and/or white space (a `points`, `viewBox` or
-- `data-pressure` attribute), as a list. Raises "NAME: bad number at character N"
-- on anything else.
function M.numbers (s, name)
  name = name or "numbers"
  local out, n = {}, 0
  local len = #s
  local _, e = find(s, WSP, 1)
  local i = e + 1
  while i <= len do
    local v, j = number(s, i, n > 0, name)
    if v == nil then
      if find(s, "^[ \t\r\n\f]*$", i) then break end
      local _, k = find(s, SEP, i)
      fail(name, "bad number", k + 1)
    end
    n = n + 1
    out[n] = v
    i = j
    _, e = find(s, WSP, i)
    i = e + 1
  end
  return out
end

-- --------------------------------------------------------------------------
-- Flattening into the current subpath

-- The output state: the subpath list, the current subpath (flat x, y, s triples), the
-- transform, the tolerance and the points left.
local function newout (opts)
  local m = opts.matrix
  local o = { list = {}, cur = nil, left = opts.max_points or M.MAX_POINTS,
              max = opts.max_points or M.MAX_POINTS, tol = opts.tolerance or M.TOLERANCE,
              name = opts.name or "path", node = -1 }
  if m then
    o.a, o.b, o.c, o.d, o.e, o.f = m[1], m[2], m[3], m[4], m[5], m[6]
  else
    o.a, o.b, o.c, o.d, o.e, o.f = 1, 0, 0, 1, 0, 0
  end
  -- the largest stretch of the linear part (its largest singular value)
  local S = o.a * o.a + o.b * o.b + o.c * o.c + o.d * o.d
  local det = o.a * o.d - o.b * o.c
  o.stretch = sqrt(max(0, (S + sqrt(max(0, S * S - 4 * det * det))) / 2))
  return o
end

local function reserve (o, n, pos)
  if not (n <= o.left) then
    fail(o.name, format("more than %d points once curves are flattened", o.max), pos)
  end
  o.left = o.left - n
end

local function put (o, x, y, s)
  local c = o.cur
  local k = #c
  c[k + 1] = o.a * x + o.c * y + o.e
  c[k + 2] = o.b * x + o.d * y + o.f
  c[k + 3] = s
end

local function moveto (o, x, y, pos)
  reserve(o, 1, pos)
  o.node = o.node + 1
  o.cur = {}
  o.list[#o.list + 1] = o.cur
  put(o, x, y, o.node)
end

local function lineto (o, x, y, pos)
  reserve(o, 1, pos)
  o.node = o.node + 1
  put(o, x, y, o.node)
end

local function tx (o, x, y) return o.a * x + o.c * y + o.e, o.b * x + o.d * y + o.f end

-- Steps for a polynomial piece whose second derivative is at most `dd` (output units).
local function steps (o, dd, pos)
  local n = ceil(sqrt(dd / (8 * o.tol)))
  if n ~= n then n = huge end
  if n < 1 then n = 1 end
  reserve(o, n, pos)
  return n
end

local function quadto (o, x0, y0, x1, y1, x2, y2, pos)
  local X0, Y0 = tx(o, x0, y0)
  local X1, Y1 = tx(o, x1, y1)
  local X2, Y2 = tx(o, x2, y2)
  local ddx, ddy = X0 - 2 * X1 + X2, Y0 - 2 * Y1 + Y2
  local n = steps(o, 2 * sqrt(ddx * ddx + ddy * ddy), pos)
  local node = o.node
  for k = 1, n - 1 do
    local t = k / n
    local u = 1 - t
    local a, b, c = u * u, 2 * u * t, t * t
    put(o, a * x0 + b * x1 + c * x2, a * y0 + b * y1 + c * y2, node + t)
  end
  o.node = node + 1
  put(o, x2, y2, o.node)
end

local function cubicto (o, x0, y0, x1, y1, x2, y2, x3, y3, pos)
  local X0, Y0 = tx(o, x0, y0)
  local X1, Y1 = tx(o, x1, y1)
  local X2, Y2 = tx(o, x2, y2)
  local X3, Y3 = tx(o, x3, y3)
  local ax, ay = X0 - 2 * X1 + X2, Y0 - 2 * Y1 + Y2
  local bx, by = X1 - 2 * X2 + X3, Y1 - 2 * Y2 + Y3
  local n = steps(o, 6 * sqrt(max(ax * ax + ay * ay, bx * bx + by * by)), pos)
  local node = o.node
  for k = 1, n - 1 do
    local t = k / n
    local u = 1 - t
    local a, b, c, d = u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t
    put(o, a * x0 + b * x1 + c * x2 + d * x3, a * y0 + b * y1 + c * y2 + d * y3, node + t)
  end
  o.node = node + 1
  put(o, x3, y3, o.node)
end

-- An elliptical arc from (x1, y1) to (x2, y2) (SVG 1.1 implementation notes F.6.5 and
-- F.6.6: endpoint to centre parameterization, radii scaled up when too small).
local function arcto (o, x1, y1, rx, ry, phi, large, sweep, x2, y2, pos)
  if x1 == x2 and y1 == y2 then            -- no arc at all (F.6.2); still a node
    return lineto(o, x2, y2, pos)
  end
  rx, ry = abs(rx), abs(ry)
  if rx == 0 or ry == 0 then return lineto(o, x2, y2, pos) end
  local cp, sp = cos(phi * pi / 180), sin(phi * pi / 180)
  local hx, hy = (x1 - x2) / 2, (y1 - y2) / 2
  local xp, yp = cp * hx + sp * hy, -sp * hx + cp * hy
  -- (written with the ratios xp / rx, yp / ry, which do not overflow for huge radii)
  local lambda = (xp / rx) ^ 2 + (yp / ry) ^ 2
  if lambda > 1 then
    local r = sqrt(lambda)
    rx, ry = rx * r, ry * r
    lambda = 1
  elseif not large and lambda < 1e-20 then
    -- the chord is nothing to the radii: the small arc is its chord within rounding
    return lineto(o, x2, y2, pos)
  end
  local coef = sqrt(max(0, (1 - lambda) / lambda))
  if large == sweep then coef = -coef end
  local cxp, cyp = coef * rx * yp / ry, -coef * ry * xp / rx
  local cx = cp * cxp - sp * cyp + (x1 + x2) / 2
  local cy = sp * cxp + cp * cyp + (y1 + y2) / 2
  local t1 = atan((yp - cyp) / ry, (xp - cxp) / rx)
  local t2 = atan((-yp - cyp) / ry, (-xp - cxp) / rx)
  local dt = t2 - t1
  if sweep and dt < 0 then dt = dt + 2 * pi
  elseif not sweep and dt > 0 then dt = dt - 2 * pi end
  if not (finite(cx) and finite(cy) and finite(dt) and finite(rx) and finite(ry)) then
    fail(o.name, "arc out of range", pos)
  end
  -- the angle step that keeps a circle of the largest output radius within tolerance
  -- (1 - cos(step / 2) = tol / r, written with asin to stay exact for large radii)
  local r = max(rx, ry) * o.stretch
  local step = r > o.tol / 2 and 4 * asin(sqrt(o.tol / (2 * r))) or pi / 2
  if not (step <= pi / 2) then step = pi / 2 end
  local n = abs(dt) / step
  n = n == n and ceil(n) or huge
  if n < 1 then n = 1 end
  reserve(o, n, pos)
  local node = o.node
  for k = 1, n - 1 do
    local f = k / n
    local t = t1 + dt * f
    local ex, ey = rx * cos(t), ry * sin(t)
    put(o, cx + cp * ex - sp * ey, cy + sp * ex + cp * ey, node + f)
  end
  o.node = node + 1
  put(o, x2, y2, o.node)
end

-- --------------------------------------------------------------------------
-- The path data grammar

local NARGS = { M = 2, L = 2, H = 1, V = 1, C = 6, S = 4, Q = 4, T = 2, A = 7, Z = 0 }

--- The polylines of path data `d`: a list of subpaths, each a flat list
-- { x1, y1, s1, x2, y2, s2, ... } of output coordinates (the path's coordinates through
-- opts.matrix) and node parameters s: the path's nodes (each M point and each segment's
-- end, Z included, numbered from 0 in the order of the data) have integer s, points
-- inside a curve segment k + t for parameter t of the segment ending at node k + 1.
-- A subpath of a lone moveto has one point. The second result is the number of nodes.
-- opts: matrix = { a, b, c, d, e, f } (x' = a x + c y + e, y' = b x + d y + f; identity),
-- tolerance (output units, 0.25), max_points (of all subpaths, 100000), name (the start
-- of error messages, "path"). Raises "NAME: WHAT at character N" on bad data.
function M.flatten (d, opts)
  opts = opts or {}
  local o = newout(opts)
  local name = o.name
  if type(d) ~= "string" then error(name .. ": path data must be a string", 0) end
  local len = #d
  local i = 1
  local x, y, sx, sy = 0, 0, 0, 0           -- current point, subpath start
  local qx, qy, ckind = 0, 0, nil            -- last control point and its kind (C or Q)
  local cmd, rel = nil, false
  local _, e = find(d, WSP, i)
  i = e + 1
  if i > len then return o.list, 0 end
  local c = sub(d, i, i)
  if c ~= "M" and c ~= "m" then fail(name, "path data must begin with M or m", i) end
  local a = {}
  while true do
    _, e = find(d, WSP, i)
    i = e + 1
    if i > len then break end
    c = sub(d, i, i)
    local up = c:upper()
    local start = i
    if NARGS[up] and find(c, "%a") then
      cmd, rel = up, c ~= up
      i = i + 1
    elseif cmd == nil or cmd == "Z" or not find(d, "^[,+%-%.%d]", i) then
      if cmd == "Z" and find(d, "^[,+%-%.%d]", i) then
        fail(name, "a number after Z", i)
      end
      fail(name, format("unexpected '%s'", c:match("^[%g]$") or format("\\%d", byte(c))), i)
    elseif cmd == "M" then
      cmd = "L"                              -- coordinates after M are line-tos
    end
    -- the arguments
    local na = NARGS[cmd]
    for k = 1, na do
      local v, j
      if cmd == "A" and (k == 4 or k == 5) then
        v, j = flag(d, i, name)
      else
        -- a comma may come between numbers and before a repeated set, not after a letter
        v, j = number(d, i, k > 1 or i == start, name)
        if v == nil then
          fail(name, format("'%s' needs %d numbers", rel and cmd:lower() or cmd, na), j)
        end
      end
      a[k], i = v, j
    end
    local ox, oy = 0, 0
    if rel then ox, oy = x, y end
    local kind = nil
    if cmd == "M" then
      x, y = a[1] + ox, a[2] + oy
      sx, sy = x, y
      moveto(o, x, y, start)
    elseif cmd == "L" then
      x, y = a[1] + ox, a[2] + oy
      lineto(o, x, y, start)
    elseif cmd == "H" then
      x = a[1] + ox
      lineto(o, x, y, start)
    elseif cmd == "V" then
      y = a[1] + oy
      lineto(o, x, y, start)
    elseif cmd == "C" or cmd == "S" then
      local x1, y1, x2, y2, x3, y3
      if cmd == "C" then
        x1, y1, x2, y2, x3, y3 = a[1] + ox, a[2] + oy, a[3] + ox, a[4] + oy, a[5] + ox, a[6] + oy
      else
        if ckind == "C" then x1, y1 = 2 * x - qx, 2 * y - qy else x1, y1 = x, y end
        x2, y2, x3, y3 = a[1] + ox, a[2] + oy, a[3] + ox, a[4] + oy
      end
      cubicto(o, x, y, x1, y1, x2, y2, x3, y3, start)
      x, y, qx, qy, kind = x3, y3, x2, y2, "C"
    elseif cmd == "Q" or cmd == "T" then
      local x1, y1, x2, y2
      if cmd == "Q" then
        x1, y1, x2, y2 = a[1] + ox, a[2] + oy, a[3] + ox, a[4] + oy
      else
        if ckind == "Q" then x1, y1 = 2 * x - qx, 2 * y - qy else x1, y1 = x, y end
        x2, y2 = a[1] + ox, a[2] + oy
      end
      quadto(o, x, y, x1, y1, x2, y2, start)
      x, y, qx, qy, kind = x2, y2, x1, y1, "Q"
    elseif cmd == "A" then
      local x2, y2 = a[6] + ox, a[7] + oy
      arcto(o, x, y, a[1], a[2], a[3], a[4], a[5], x2, y2, start)
      x, y = x2, y2
    else                                     -- Z: back to the start; a later drawing
      lineto(o, sx, sy, start)               -- command starts a new subpath there
      x, y = sx, sy
    end
    if not (finite(x) and finite(y)) then fail(name, "number out of range", start) end
    ckind = kind
    if cmd == "Z" then
      -- a drawing command after Z continues from the start in a new subpath (SVG 2 §9.3.4)
      _, e = find(d, WSP, i)
      local nc = sub(d, e + 1, e + 1)
      local nu = nc:upper()
      if NARGS[nu] and nu ~= "M" and nu ~= "Z" then
        moveto(o, x, y, e + 1)
        o.node = o.node - 1                  -- the same node as the Z's end
        o.cur[3] = o.node
      end
    end
  end
  return o.list, o.node + 1
end

return M
