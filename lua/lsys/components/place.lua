--- Placement of multiplied children: the Hydra, Wreath and Phiball multipliers of
-- Lintermann and Deussen 1999 (section "Hydra and Wreath", section "Phiball" and the sidebar
-- "Golden Section Placement on a Sphere"). Pure maths, no geometry is made here.
--
-- Every function takes an options table and returns a list, one table per child i = 1..n:
--   { i =, n =, pos = {x, y, z}, H = {x, y, z}, U = {x, y, z}, theta =, phi =, radius = }
-- in the multiplier's LOCAL frame: Z is the multiplier's axis (the sidebar's rotation axis z;
-- the caller maps it to the multiplier instance's heading), X its up, Y = Z x X. H is the
-- child's heading (the direction its geometry grows) and U its up, both unit and orthogonal;
-- its left is L = H x U (the turtle's convention, csrc/core/turtle.h). `theta` is the
-- colatitude of H measured from +Z and `phi` its azimuth from +X towards +Y, both in radians.
--
-- One convention for U throughout: where H is tilted from Z by theta at azimuth phi,
--   H = sin(theta) r + cos(theta) Z,   U = sin(theta) Z - cos(theta) r,
-- with r = (cos phi, sin phi, 0) the radial direction: U is H rotated by 90 degrees further
-- towards the axis, i.e. the unit tangent of the meridian pointing to the pole +Z. A leaf
-- held out horizontally (theta = 90) faces up (U = +Z); a petal pointing up (theta small)
-- shows its upper side to the axis. The formula is defined at the poles too (theta = 0 gives
-- U = -r, the limit of the meridian tangent), so no special case is needed there.
--
-- Angles in options are degrees. Bad options raise "KIND: 'param' must be ..., got X".
-- @module lsys.components.place
local type, pairs, error, tostring, math, string, table =
      type, pairs, error, tostring, math, string, table
local format, concat, sort = string.format, table.concat, table.sort
local sqrt, sin, cos, acos, floor, rad, pi, huge =
      math.sqrt, math.sin, math.cos, math.acos, math.floor, math.rad, math.pi, math.huge
local mtype = math.type
local _ENV = nil

local M = {}

--- The largest number of children one multiplier places (each child is a handful of
-- tables; a graph's total is bounded separately by the expander's instance limit).
M.MAX_N = 1000000

--- The golden section phi = (1 + sqrt 5) / 2 and the sidebar's divergence angle
-- dPhi = 2 pi / phi (radians; 222.4922 degrees, i.e. 137.5078 degrees the other way).
M.GOLDEN = (1 + sqrt(5)) / 2
M.DPHI = 2 * pi / M.GOLDEN

--- Each kind's parameters and their defaults (false: none; phiball's influence is 1 when
-- left out).
M.PARAMS = {
  phiball = { n = false, open = 0, close = 90, radius = false, sizes = false,
              influence = false, area = 1 },
  hydra = { n = false, radius = 0, open = 0, close = 360, angle = 90 },
  wreath = { n = false, radius = 1, open = 0, close = 360 },
}

-- A value as it is shown in an error message.
local function show (v)
  if type(v) == "number" then
    if v ~= v then return "nan" end
    if mtype(v) == "integer" or (v == floor(v) and v > -1e15 and v < 1e15) then
      return format("%d", v)
    end
    return format("%.14g", v)
  elseif type(v) == "string" then
    return format("'%s'", v)
  end
  return tostring(v)
end

local function bad (kind, name, what, v)
  error(format("%s: '%s' must be %s, got %s", kind, name, what, show(v)), 0)
end

-- A finite number in [lo, hi] (open ends when lo_open / hi_open); NaN fails every test.
local function number (kind, name, v, lo, hi, lo_open, hi_open, what)
  if type(v) ~= "number" or v ~= v or v == huge or v == -huge
     or (lo_open and not (v > lo)) or (not lo_open and not (v >= lo))
     or (hi_open and not (v < hi)) or (not hi_open and not (v <= hi)) then
    bad(kind, name, what, v)
  end
  return v
end

-- Unknown keys are errors listing the known ones; returns the options with defaults.
local function options (kind, p)
  if type(p) ~= "table" then
    error(format("%s: an options table expected, got %s", kind, show(p)), 0)
  end
  local known, o = M.PARAMS[kind], {}
  for k, v in pairs(p) do
    if known[k] == nil then
      local names = {}
      for name in pairs(known) do names[#names + 1] = name end
      sort(names)
      error(format("%s: unknown parameter %s (known: %s)", kind, show(k), concat(names, ", ")),
            0)
    end
    o[k] = v
  end
  for k, d in pairs(known) do
    if o[k] == nil and d then o[k] = d end
  end
  local n = o.n
  if type(n) ~= "number" or n ~= floor(n) or n < 1 or n > M.MAX_N then
    bad(kind, "n", format("a positive integer (at most %d)", M.MAX_N), n)
  end
  o.n = floor(n)
  return o
end

-- The child table for colatitude theta and azimuth phi (radians) at position pos.
local function child (i, n, pos, theta, phi, radius)
  local st, ct, sp, cp = sin(theta), cos(theta), sin(phi), cos(phi)
  return { i = i, n = n, pos = pos, theta = theta, phi = phi, radius = radius,
           H = { st * cp, st * sp, ct },
           U = { -ct * cp, -ct * sp, st } }
end

-- The cumulative area fraction A_i / A_N of child i (see M.phiball).
local function fractions (o)
  local n, f = o.n, {}
  local sizes = o.sizes
  if sizes == nil then
    for i = 1, n do f[i] = i / n end
    return f, n * o.area
  end
  if type(sizes) ~= "table" then bad("phiball", "sizes", "a list of n positive numbers", sizes) end
  if #sizes ~= n then
    error(format("phiball: 'sizes' must list n = %d areas, got %d", n, #sizes), 0)
  end
  local total = 0
  for j = 1, n do
    number("phiball", format("sizes[%d]", j), sizes[j], 0, huge, true, true,
           "a positive finite number")
    total = total + sizes[j]
  end
  if total == huge then
    error("phiball: 'sizes' must sum to a finite number, got inf", 0)
  end
  local w, acc = o.influence, 0
  for i = 1, n do
    acc = acc + sizes[i]
    -- the blend of the equal-size and the size-weighted fractions
    f[i] = (1 - w) * (i / n) + w * (acc / total)
  end
  f[n] = 1
  return f, total
end

--- Children on a spherical section by the golden section (Lintermann and Deussen 1999,
-- sidebar "Golden Section Placement on a Sphere").
-- Options: n (children, 1..MAX_N); open = theta1, close = theta2 (degrees, colatitudes
-- from +Z bounding the section S(theta1, theta2), 0 <= theta1 < theta2 <= 180; defaults 0
-- and 90, a hemisphere); radius (R; default: from the children's area, below); sizes (a
-- list of n positive areas a_j; default: all equal); influence (w in [0, 1], how much the
-- sizes move the children: 1 by default, no effect without sizes); area (A_E, each child's
-- area when all are equal; default 1; unused with sizes).
--
-- The section S(theta1, theta2) of a sphere of radius R has area 2 pi R h with
-- h = R (cos theta1 - cos theta2). Asking it to hold the children's total area A_N
-- (n A_E, or the sum of the sizes) gives the sidebar's radius
--   R = sqrt(A_N / (2 pi (cos theta1 - cos theta2))).
-- The first i children cover A_i (i A_E, or a_1 + ... + a_i) of it, the band from theta1
-- down to the colatitude theta with cos theta = cos theta1 - (A_i / A_N)(cos theta1 -
-- cos theta2). The sidebar writes this as theta_i = arcsin(cos theta1 - (A_i/A_N)(...)):
-- the arcsine gives a LATITUDE (pi/2 - theta1 at A_i = 0, pi/2 - theta2 at A_i = A_N), so
-- the colatitude returned here is pi/2 minus it, computed as the arccosine of the same
-- value. With influence w the fraction is (1 - w) i/n + w A_i/A_N.
-- Child i sits at azimuth Phi_i = i dPhi, dPhi = 2 pi / phi (returned reduced to
-- [0, 2 pi)), at R (sin theta cos Phi, sin theta sin Phi, cos theta), heading along the
-- outward normal. Each child table also has `fraction` (A_i / A_N after the blend).
function M.phiball (p)
  local o = options("phiball", p)
  local t1 = number("phiball", "open", o.open, 0, 180, false, true, "a number in [0, 180)")
  local t2 = number("phiball", "close", o.close, t1, 180, true, false,
                    "a number in (open, 180]")
  if o.radius ~= nil then
    number("phiball", "radius", o.radius, 0, huge, true, true, "a positive finite number")
  end
  number("phiball", "area", o.area, 0, huge, true, true, "a positive finite number")
  if o.influence == nil then o.influence = 1 end
  number("phiball", "influence", o.influence, 0, 1, false, false, "a number in [0, 1]")
  local c1, c2 = cos(rad(t1)), cos(rad(t2))
  local f, total = fractions(o)
  local R = o.radius or sqrt(total / (2 * pi * (c1 - c2)))
  if not (R < huge) then      -- cos open == cos close in doubles (a cap ~1e-8 degrees wide)
    error(format("phiball: the cap from 'open' (%s) to 'close' (%s) is too narrow for the " ..
                 "children to have room (give a radius or open it wider)", show(t1), show(t2)),
          0)
  end
  local n, out = o.n, {}
  for i = 1, n do
    local c = c1 - f[i] * (c1 - c2)
    if c > 1 then c = 1 elseif c < -1 then c = -1 end
    local theta = acos(c)
    -- Phi_i = i dPhi = 2 pi (i / golden), reduced by the whole turns of i / golden
    local turns = i / M.GOLDEN
    local phi = 2 * pi * (turns - floor(turns))
    local ch = child(i, n, nil, theta, phi, R)
    ch.pos = { R * ch.H[1], R * ch.H[2], R * ch.H[3] }
    ch.fraction = f[i]
    out[i] = ch
  end
  return out
end

-- The azimuths (radians) of n children on the arc [open, close] (degrees): n equal gaps on
-- a full circle, both ends used on a shorter arc.
local function azimuths (kind, o)
  local a = number(kind, "open", o.open, -360, 360, false, false, "a number in [-360, 360]")
  local b = number(kind, "close", o.close, a, a + 360, true, false,
                   "a number in (open, open + 360]")
  local n, psi = o.n, {}
  for i = 1, n do
    local d
    if b - a == 360 then d = a + (i - 1) * 360 / n
    elseif n == 1 then d = a
    else d = a + (i - 1) * (b - a) / (n - 1) end
    psi[i] = rad(d)
  end
  return psi
end

--- Children in a star (Lintermann and Deussen 1999, section "Hydra and Wreath", fig. D1).
-- Options: n; radius (distance of the children from the axis, >= 0, default 0); open,
-- close (degrees, the arc around Z the children are spread on, default 0 and 360; open in
-- [-360, 360], close in (open, open + 360]); angle (degrees between Z and each heading,
-- [0, 180], default 90: a flat star). Child i sits at azimuth psi_i = open + (i - 1)
-- (close - open) / n on a full circle (n equal gaps) and open + (i - 1)(close - open) /
-- (n - 1) on a shorter arc (both ends used; a single child at open), at
-- radius (cos psi, sin psi, 0); H is Z tilted by `angle` towards (cos psi, sin psi, 0);
-- U follows the module's convention (at angle 90, U = +Z). theta = angle in radians.
function M.hydra (p)
  local o = options("hydra", p)
  local r = number("hydra", "radius", o.radius, 0, huge, false, true,
                   "a finite number >= 0")
  local ang = number("hydra", "angle", o.angle, 0, 180, false, false, "a number in [0, 180]")
  local psi, out, theta = azimuths("hydra", o), {}, rad(ang)
  for i = 1, o.n do
    local ch = child(i, o.n, nil, theta, psi[i], r)
    ch.pos = { r * cos(psi[i]), r * sin(psi[i]), 0 }
    out[i] = ch
  end
  return out
end

--- Children on a circle like candles on a wreath (Lintermann and Deussen 1999, section
-- "Hydra and Wreath", fig. D2). Options: n; radius (>= 0, default 1); open, close as for
-- hydra. Positions as hydra's; every heading is +Z; U is the radial direction outward,
-- (cos psi, sin psi, 0). theta = 0.
function M.wreath (p)
  local o = options("wreath", p)
  local r = number("wreath", "radius", o.radius, 0, huge, false, true,
                   "a finite number >= 0")
  local psi, out = azimuths("wreath", o), {}
  for i = 1, o.n do
    local c, s = cos(psi[i]), sin(psi[i])
    out[i] = { i = i, n = o.n, pos = { r * c, r * s, 0 }, theta = 0, phi = psi[i],
               radius = r, H = { 0, 0, 1 }, U = { c, s, 0 } }
  end
  return out
end

return M
