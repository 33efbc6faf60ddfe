--- View options (DESIGN.md §6; seed 004 Appendix B): how a model is drawn.
-- A view is a plain Lua table; every field is optional:
--
--   angle            angle increment of + - & ^ / \ without a parameter, degrees (90)
--   step             step of F f G g without a parameter (1)
--   line_width       initial line width (1): pixels in "line" style, model units otherwise
--   width_increment  what # and ! add or subtract without a parameter (1)
--   color            initial colour index (1); color_increment for ; and , (1)
--   line_style       "line", "polygon" (flat ribbons) or "cylinder" ("line")
--   contour_sides    sides of cylinders, discs and spheres (8)
--   tropisms         list of { vector = {x,y,z}, angle = 0, elasticity = 0, increment = 0 }
--                    (seed 004 §6; `angle` is the diatropism angle); an entry with
--                    `torque = true` is a twist response (§6.1)
--   torques          list of { vector = {x,y,z}, elasticity = 0, increment = 0 }, numbered
--                    after the tropisms by @Ts @Ti @Td
--   palette          colour index -> colour: a list (index 1 first, [0] optional) whose
--                    entries are {r,g,b} (0..1), "#rrggbb", or materials
--                    { diffuse = {r,g,b}, ambient =, specular =, emission =, shininess = }
--   background       {r,g,b} (a pale sky blue)
--   viewpoint, target, up     camera position, view reference point, up vector
--   direction        view direction when no viewpoint is given ({0,0,-1}: from +z)
--   projection       "parallel" or "perspective" ("parallel", as cpfg)
--   fov              field of view for "perspective", degrees (30)
--   twist            rotation of the picture about the view axis, degrees (0)
--   light            direction the key light comes from ({0.4, 0.8, 0.6}), world space
--   supersample      anti-aliasing factor for rendering (3)
-- @module lsys.view
local type, pairs, ipairs, error, tostring, tonumber, math, string, table =
      type, pairs, ipairs, error, tostring, tonumber, math, string, table
local format = string.format
local _ENV = nil

local M = {}

--- The default palette: bark, foliage, and bright organ colours.
M.PALETTE = {
  [0] = { 0.12, 0.12, 0.12 },
  { 0.42, 0.29, 0.18 },   -- 1 bark
  { 0.30, 0.55, 0.17 },   -- 2 leaf green
  { 0.60, 0.78, 0.28 },   -- 3 young green
  { 0.96, 0.78, 0.20 },   -- 4 yellow
  { 0.84, 0.22, 0.16 },   -- 5 red
  { 0.97, 0.80, 0.88 },   -- 6 petal pink
  { 0.56, 0.32, 0.68 },   -- 7 purple
  { 0.13, 0.34, 0.12 },   -- 8 dark green
  { 0.26, 0.44, 0.80 },   -- 9 blue
  { 0.93, 0.92, 0.88 },   -- 10 white
  { 0.62, 0.45, 0.28 },   -- 11 light wood
  { 0.20, 0.20, 0.20 },   -- 12 dark grey
}

local DEFAULTS = {
  angle = 90, step = 1, line_width = 1, width_increment = 1, color = 1, color_increment = 1,
  line_style = "line", contour_sides = 8, projection = "parallel", fov = 30, twist = 0,
  background = { 0.93, 0.96, 1.0 }, light = { 0.4, 0.8, 0.6 }, supersample = 3,
  direction = { 0, 0, -1 },
}
M.DEFAULTS = DEFAULTS

local KINDS = {
  angle = "number", step = "number", line_width = "number", width_increment = "number",
  color = "integer", color_increment = "integer", line_style = "style",
  contour_sides = "integer", tropisms = "list", torques = "list", palette = "palette",
  background = "color", viewpoint = "vec", target = "vec", up = "vec", direction = "vec",
  projection = "projection", fov = "number", twist = "number", light = "vec",
  supersample = "integer",
}
M.KINDS = KINDS

local function fail (where, fmt, ...)
  error(format("%s: " .. fmt, where, ...), 0)
end

local function isnum (x) return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge end

local function vec (v, where, name)
  if type(v) ~= "table" or #v ~= 3 then
    fail(where, "'%s' must be a list of 3 numbers", name)
  end
  for i = 1, 3 do
    if not isnum(v[i]) then fail(where, "'%s'[%d] must be a finite number", name, i) end
  end
  return { v[1], v[2], v[3] }
end

-- A colour {r,g,b[,a]} in 0..1 or "#rrggbb".
local function color (c, where, name)
  if type(c) == "string" then
    local r, g, b = c:match("^#(%x%x)(%x%x)(%x%x)$")
    if not r then fail(where, "'%s': colour '%s' is not #rrggbb", name, c) end
    return { tonumber(r, 16) / 255, tonumber(g, 16) / 255, tonumber(b, 16) / 255 }
  end
  if type(c) ~= "table" or (#c ~= 3 and #c ~= 4) then
    fail(where, "'%s' must be a colour {r, g, b} or \"#rrggbb\"", name)
  end
  local out = {}
  for i = 1, #c do
    if not isnum(c[i]) or c[i] < 0 or c[i] > 1 then
      fail(where, "'%s'[%d] must be a number from 0 to 1", name, i)
    end
    out[i] = c[i]
  end
  return out
end

local function material (m, where, name)
  if type(m) == "table" and m.diffuse ~= nil then
    local out = { diffuse = color(m.diffuse, where, name .. ".diffuse") }
    for _, k in ipairs { "ambient", "specular", "emission" } do
      if m[k] ~= nil then out[k] = color(m[k], where, name .. "." .. k) end
    end
    if m.shininess ~= nil then
      if not isnum(m.shininess) or m.shininess < 0 or m.shininess > 128 then
        fail(where, "'%s.shininess' must be a number from 0 to 128", name)
      end
      out.shininess = m.shininess
    end
    return out
  end
  return { diffuse = color(m, where, name) }
end

local function tropism (t, where, name, torque)
  if type(t) ~= "table" then fail(where, "'%s' must be a table", name) end
  local out = { vector = vec(t.vector, where, name .. ".vector"), torque = torque or t.torque }
  for _, k in ipairs { "angle", "elasticity", "increment" } do
    local x = t[k]
    if x ~= nil and not isnum(x) then fail(where, "'%s.%s' must be a number", name, k) end
    out[k] = x or 0
  end
  for k in pairs(t) do
    if k ~= "vector" and k ~= "angle" and k ~= "elasticity" and k ~= "increment"
       and k ~= "torque" then
      fail(where, "'%s': unknown field '%s'", name, tostring(k))
    end
  end
  return out
end

--- Checks a view table and returns a complete copy with the defaults filled in.
-- `where` names the model in messages.
function M.normalize (v, where)
  where = where or "view"
  if v == nil then v = {} end
  if type(v) ~= "table" then fail(where, "the view must be a table") end
  local out = {}
  for k, x in pairs(v) do
    local kind = KINDS[k]
    local name = "view." .. tostring(k)
    if kind == nil then
      local known = {}
      for n in pairs(KINDS) do known[#known + 1] = n end
      table.sort(known)
      fail(where, "unknown view option '%s' (known: %s)", tostring(k), table.concat(known, ", "))
    elseif kind == "number" then
      if not isnum(x) then fail(where, "'%s' must be a finite number", name) end
      out[k] = x
    elseif kind == "integer" then
      if math.type(x) ~= "integer" and not (isnum(x) and x == math.floor(x)) then
        fail(where, "'%s' must be a whole number", name)
      end
      out[k] = math.tointeger(x)
    elseif kind == "style" then
      if x ~= "line" and x ~= "polygon" and x ~= "cylinder" then
        fail(where, "'%s' must be \"line\", \"polygon\" or \"cylinder\"", name)
      end
      out[k] = x
    elseif kind == "projection" then
      if x ~= "parallel" and x ~= "perspective" then
        fail(where, "'%s' must be \"parallel\" or \"perspective\"", name)
      end
      out[k] = x
    elseif kind == "vec" then
      out[k] = vec(x, where, name)
    elseif kind == "color" then
      out[k] = color(x, where, name)
    elseif kind == "list" then
      if type(x) ~= "table" then fail(where, "'%s' must be a list", name) end
      local l = {}
      for i, t in ipairs(x) do l[i] = tropism(t, where, format("%s[%d]", name, i), k == "torques") end
      out[k] = l
    elseif kind == "palette" then
      if type(x) ~= "table" then fail(where, "'%s' must be a list of colours", name) end
      local p = {}
      for i, c in pairs(x) do
        if math.type(i) ~= "integer" or i < 0 then
          fail(where, "'%s': keys must be colour indices >= 0", name)
        end
        p[i] = material(c, where, format("%s[%d]", name, i))
      end
      local n = 0
      for i in pairs(p) do if i > n then n = i end end
      for i = 1, n do
        if p[i] == nil then fail(where, "'%s': entry %d is missing", name, i) end
      end
      out[k] = p
    end
  end
  for k, d in pairs(DEFAULTS) do if out[k] == nil then out[k] = d end end
  if out.contour_sides < 3 or out.contour_sides > 1024 then
    fail(where, "'view.contour_sides' must be from 3 to 1024")
  end
  if out.supersample < 1 or out.supersample > 8 then
    fail(where, "'view.supersample' must be from 1 to 8")
  end
  if out.palette == nil then
    local p = {}
    for i = 0, #M.PALETTE do p[i] = { diffuse = M.PALETTE[i] } end
    out.palette = p
  end
  return out
end

--- The options the turtle reads (core.interpret), from a normalised view.
function M.turtle (v, allow_system_calls)
  local trop = {}
  for _, t in ipairs(v.tropisms or {}) do trop[#trop + 1] = t end
  for _, t in ipairs(v.torques or {}) do trop[#trop + 1] = t end
  return {
    angle = v.angle, step = v.step, width = v.line_width, width_increment = v.width_increment,
    color = v.color, color_increment = v.color_increment, style = v.line_style,
    sides = v.contour_sides, tropisms = trop, palette = v.palette,
    allow_system_calls = allow_system_calls or false,
  }
end

--- The options the renderer reads (core.render), from a normalised view.
function M.render (v)
  return {
    background = v.background, light = v.light, viewpoint = v.viewpoint, target = v.target,
    up = v.up, direction = v.direction, projection = v.projection, fov = v.fov,
    twist = v.twist, supersample = v.supersample,
  }
end

--- A copy of `v` with the fields of `over` (both plain view tables) replacing its own.
function M.merge (v, over)
  local out = {}
  for k, x in pairs(v or {}) do out[k] = x end
  for k, x in pairs(over or {}) do out[k] = x end
  return out
end

return M
