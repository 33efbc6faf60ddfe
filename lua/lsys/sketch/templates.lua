--- Phyllotaxis templates (Anastacio et al. 2009, §5): the L-systems that the positional
-- functions of a sketch parameterize. They keep the structure of the paper's productions:
-- an apex A that lays down a piece of stem S, a node B and the next apex; S realigns the
-- turtle with the global frame and turns it by yaw and pitch (3D) or turns it by the stem
-- shape (2D); B places the organs as L and R.
--
-- Deviations from the paper's text, so that organs land exactly on the nodes of §3.3 and the
-- stem follows the drawn curve:
--  * x is where the turtle is: A(x) draws the internode from x to x + internode(x) and puts
--    the node B there (the paper's A(x) -> S(x) B(x) A(x + dx) evaluates the node's
--    functions at the start of the internode, and advances x by "the resolution of the
--    stem" while F draws the internode length).
--  * S(x, d) draws the piece of stem from x to x + d, halved while it is longer than the
--    stem resolution D (the S rule with d > D), so a long internode follows the curve; the
--    yaw and pitch are read at the middle of each piece, the 2D turn at its start.
--  * A stops: no node past the top inclination line (x < XT, XT half an internode below
--    P_n), then the last piece of stem up to the tip (x < XE).
--  * 3D: S realigns with @R(0,1,0,0,0,-1), the turtle's initial frame (H = +y, L = -x,
--    U = -z), where the paper writes @R(0,1,0,0,0,1): with U = +z the left vector is +x, so
--    + would turn to the viewer's right and the L and R organs of a 3D stem would swap sides
--    against those of the 2D template, which keeps the initial frame. In this frame the
--    pitch towards the viewer (+z = -U) is ^, where the paper's & pitches towards its U = +z.
--  * Fibonacci: the organ is rolled by θ about the stem (/(θ)) before it turns out; the
--    paper's production leaves that out. θ and the (a, b) weights are computed by a
--    module C(x, θ) that B makes, so the rules stay one expression per parameter.
--  * Decussate counts nodes with i as the paper does; odd nodes are rolled by 90° and take
--    the averages of the left and right values.
-- @module lsys.sketch.templates
local error, string, table, ipairs =
      error, string, table, ipairs
local format, concat = string.format, table.concat
local _ENV = nil

local M = {}

M.NAMES = { "distichous", "decussate", "fibonacci" }
M.DIVERGENCE = 137.5

-- The default organ (a flat leaf in the plane of H and L, of length h, colour c): a
-- diamond with its widest point at 0.4 h, half as wide as 0.15 h on each side.
local LEAF_ANGLE = 20.556045219583467      -- atan(0.15 / 0.4), degrees
local LEAF_SIDE = 0.42720018726587655      -- sqrt(0.4^2 + 0.15^2)
function M.leaf (color)
  return format("Organ(h) --> ;(%d) { . [+(%.15g) g(h*%.15g) .] [g(h) .] [-(%.15g) g(h*%.15g) .] }",
                color, LEAF_ANGLE, LEAF_SIDE, LEAF_ANGLE, LEAF_SIDE)
end

--- The rules of a template. o: phyllotaxis (one of M.NAMES), threed, prefix (put before
-- the names of functions and constants, for composition), first (a node at x = 0).
-- Returns { axiom =, productions = (lines), names = { functions and constants used } }.
function M.rules (o)
  local p = o.prefix or ""
  local function n (name) return p .. name end
  local I, XT, XE, D = n "internode", n "XT", n "XE", n "D"
  local AL, AR, SL, SR = n "angle_left", n "angle_right", n "size_left", n "size_right"
  local ph = o.phyllotaxis
  local counted = ph ~= "distichous"
  local A = counted and "A(x, i)" or "A(x)"
  local Bn = counted and "B(x + %s(x), i)" or "B(x + %s(x))"
  local An = counted and "A(x + %s(x), i + 1)" or "A(x + %s(x))"
  local r = {
    format("%s : x < %s --> S(x, %s(x)) " .. Bn .. " " .. An, A, XT, I, I, I),
    format("%s : x < %s --> S(x, %s(x))", A, XE, I),
    format("S(x, d) : d > %s --> S(x, d/2) S(x + d/2, d/2)", D),
  }
  if o.threed then
    r[#r + 1] = format("S(x, d) --> @R(0, 1, 0, 0, 0, -1) +(%s(x + d/2)) ^(%s(x + d/2)) F(d)",
                       n "yaw", n "pitch")
  else
    r[#r + 1] = format("S(x, d) --> +(%s(x)) F(d)", n "stem_shape")
  end
  if ph == "distichous" then
    r[#r + 1] = "B(x) --> L(x) R(x)"
    r[#r + 1] = format("L(x) --> [+(%s(x)) Organ(%s(x))]", AL, SL)
    r[#r + 1] = format("R(x) --> [/(180) +(%s(x)) Organ(%s(x))]", AR, SR)
  elseif ph == "decussate" then
    local avga = format("(%s(x) + %s(x)) * 0.5", AL, AR)
    local avgh = format("(%s(x) + %s(x)) * 0.5", SL, SR)
    r[#r + 1] = "B(x, i) : i % 2 == 0 --> [L(x, i) R(x, i)]"
    r[#r + 1] = "B(x, i) --> [/(90) L(x, i) R(x, i)]"
    r[#r + 1] = format("L(x, i) : i %% 2 == 0 --> [+(%s(x)) Organ(%s(x))]", AL, SL)
    r[#r + 1] = format("L(x, i) --> [+(%s) Organ(%s)]", avga, avgh)
    r[#r + 1] = format("R(x, i) : i %% 2 == 0 --> [/(180) +(%s(x)) Organ(%s(x))]", AR, SR)
    r[#r + 1] = format("R(x, i) --> [/(180) +(%s) Organ(%s)]", avga, avgh)
  elseif ph == "fibonacci" then
    r[#r + 1] = format("B(x, i) --> C(x, (i * %.15g) %% 360)", M.DIVERGENCE)
    -- (a, b) = (1 - θ/180, θ/180) for θ <= 180, (θ/180 - 1, 2 - θ/180) above (§5.3)
    local function side (a, b)
      return format("[/(t) +(%s * %s(x) + %s * %s(x)) Organ(%s * %s(x) + %s * %s(x))]",
                    a, AL, b, AR, a, SL, b, SR)
    end
    r[#r + 1] = "C(x, t) : t <= 180 --> " .. side("(1 - t/180)", "t/180")
    r[#r + 1] = "C(x, t) --> " .. side("(t/180 - 1)", "(2 - t/180)")
  else
    error(format("unknown phyllotaxis '%s' (distichous, decussate or fibonacci)",
                 ph), 0)
  end
  local start = counted and "A(0, 0)" or "A(0)"
  if o.first then start = counted and "B(0, 0) A(0, 1)" or "B(0) A(0)" end
  local names = { I, XT, XE, D, AL, AR, SL, SR }
  if o.threed then names[#names + 1] = n "yaw"; names[#names + 1] = n "pitch"
  else names[#names + 1] = n "stem_shape" end
  return { axiom = start, productions = r, names = names }
end

--- The rules of template `name` as text (2D unless `threed`), for reading.
function M.text (name, threed)
  local t = M.rules { phyllotaxis = name, threed = threed }
  local out = { "axiom: " .. t.axiom }
  for _, l in ipairs(t.productions) do out[#out + 1] = l end
  out[#out + 1] = "homomorphism: " .. M.leaf(2)
  return concat(out, "\n") .. "\n"
end

return M
