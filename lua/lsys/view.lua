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
--                    { diffuse = {r,g,b}, ambient =, specular =, emission =, shininess = };
--                    or the name of a cpfg colour map (.map) or material file (.mat),
--                    read by load_colormap / load_materials (relative to `dir`)
--   background       {r,g,b} (a pale sky blue)
--   viewpoint, target, up     camera position, view reference point, up vector
--   direction        view direction when no viewpoint is given ({0,0,-1}: from +z)
--   projection       "parallel" or "perspective" ("parallel", as cpfg)
--   fov              field of view for "perspective", degrees (30)
--   twist            rotation of the picture about the view axis, degrees (0)
--   light            direction the key light comes from ({0.4, 0.8, 0.6}), world space
--   supersample      anti-aliasing factor for rendering (3)
--   dir              directory that relative file names of this view are read from
--                    (default: the current directory); `load` sets it to the .v file's
--   contours         { [id] = "file.con" | { points = {{x,y[,z]}, ...}, closed = true } }:
--                    cross-sections of generalized cylinders, selected by @#(id)
--                    (seed 004 §3.2.3, Appendix B.1); ids are integers >= 1 (0 is the
--                    built-in circle). Normalised to { [id] = lsys.Contour }
--   surfaces         { P = "petal.s" | { file = "petal.s", scale = 1, texture = 0,
--                    precision = {s, t} } }: predefined surfaces drawn by ~P (§4.1). The
--                    key is one character; scale > 0 multiplies the surface; texture is
--                    an index into `textures` (1 = first; 0 none) applied to every
--                    instance; precision is the lines per patch in s and t (1..64; the
--                    file's own, at most 64, else 4). Normalised to
--                    { P = { surface = lsys.Surface, scale =, texture =, s =, t = } }
--   textures         list of "image.png" | { file =, mag = "near", min = "near",
--                    mode = "modulate", per_surface = false, intensity = (from the
--                    image) }: textures selected by @Tx(k) (§5, Appendix B.2); filters
--                    "linear"/"near" (or l/n), modes "modulate"/"decal" (or m/d).
--                    Normalised to a list of lsys.Texture
--   minimize_twist   true: generalized cylinders use the twist-minimising frame (cpfg
--                    "twist of cylinders: on", the default, §3.3); false: the turtle's
--                    own twist is kept
--
-- Files named by contours, surfaces, textures and palette are read by `normalize`,
-- which every interpretation calls. Each file is read again each time (a few bytes
-- for contours and surfaces): that is the only way plain Lua has to see that a file
-- changed. What is parsed from it (the contour, surface or decoded image) is kept in a
-- weak cache keyed by path and options and reused for as long as the file's bytes
-- are the same, so unchanged files are not parsed or decoded again and a changed file
-- is never answered from the cache. Nothing is memoised on the view table itself:
-- view tables may be changed between calls.
--
-- `load(path)` reads a cpfg view file (.v) into such a table; `parse(text, name)` does
-- the same for text in memory.
-- @module lsys.view
local type, pairs, ipairs, error, tostring, tonumber, math, string, table, pcall, require,
      setmetatable, getmetatable, rawget, utf8, io =
      type, pairs, ipairs, error, tostring, tonumber, math, string, table, pcall, require,
      setmetatable, getmetatable, rawget, utf8, io
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
  direction = { 0, 0, -1 }, minimize_twist = true,
}
M.DEFAULTS = DEFAULTS

local KINDS = {
  angle = "number", step = "number", line_width = "number", width_increment = "number",
  color = "integer", color_increment = "integer", line_style = "style",
  contour_sides = "integer", tropisms = "list", torques = "list", palette = "palette",
  background = "color", viewpoint = "vec", target = "vec", up = "vec", direction = "vec",
  projection = "projection", fov = "number", twist = "number", light = "vec",
  supersample = "integer", dir = "string", contours = "contours", surfaces = "surfaces",
  textures = "textures", minimize_twist = "boolean",
}
M.KINDS = KINDS

local MAXTROPISMS = 16        -- LSYS_MAXTROPISMS (csrc/core/turtle.h): tropisms and torques

local core                    -- lsys.core, loaded when a view first names a file
local function getcore ()
  if core == nil then core = require "lsys.core" end
  return core
end

local function fail (where, fmt, ...)
  error(format("%s: " .. fmt, where, ...), 0)
end

local function isnum (x) return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge end

local function isint (x) return isnum(x) and x == math.floor(x) end

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

-- --------------------------------------------------------------------------
-- Files

-- `path` read relative to `dir` (nil or "": as given). Absolute paths stay.
local function resolve (dir, path)
  if dir == nil or dir == "" or path:sub(1, 1) == "/" then return path end
  if dir:sub(-1) == "/" then return dir .. path end
  return dir .. "/" .. path
end

-- Largest files read: view files, contours, surfaces and palettes; textures (PNG).
local MAXFILE, MAXIMAGE = 16 * 2 ^ 20, 256 * 2 ^ 20

-- The bytes of a regular file of at most `max` bytes (default MAXFILE), or nil and a
-- message naming the file ("cannot open 'x': ...", "cannot read 'x': not a regular
-- file"): a view can name any path, /dev/zero included.
local function readfile (path, max)
  return getcore().read_file(path, max or MAXFILE)
end

-- The type name of a userdata made by lsys.core ("lsys.Contour", ...), else nil.
local function udname (x)
  if type(x) ~= "userdata" then return nil end
  local mt = getmetatable(x)
  return type(mt) == "table" and rawget(mt, "__name") or nil
end

-- Parsed objects by path (plus options): weak values; and the bytes each was made
-- from (weak keys), so an entry lives exactly as long as its object.
local cache_obj = setmetatable({}, { __mode = "v" })
local cache_src = setmetatable({}, { __mode = "k" })

-- The lsys.core function `fn`, or an error saying this build lacks it.
local function corefn (ctx, name, fn)
  local f = getcore()[fn]
  if f == nil then fail(ctx.where, "%s: this build of lsys.core has no %s", name, fn) end
  return f
end

-- The object that lsys.core's `fn`(path, arg) makes from the file `rel` (relative to
-- ctx.dir); from the cache when the file's bytes are unchanged. `name` names the view
-- option in messages; `extra` tells apart objects made from one file with other options.
local function fileobj (ctx, name, rel, extra, fn, arg)
  if type(rel) ~= "string" or rel == "" then
    fail(ctx.where, "%s: a file name expected, got %s", name, type(rel))
  end
  local path = resolve(ctx.dir, rel)
  local bytes = ctx.bytes[path]
  if bytes == nil then
    local err
    bytes, err = readfile(path, fn == "texture_load" and MAXIMAGE or MAXFILE)
    if bytes == nil then fail(ctx.where, "%s: %s", name, err) end
    ctx.bytes[path] = bytes
  end
  local key = extra and (path .. "\0" .. extra) or path
  local obj = cache_obj[key]
  if obj ~= nil and cache_src[obj] == bytes then return obj end
  local ok, r = pcall(corefn(ctx, name, fn), path, arg)
  if ok and r == nil then ok, r = false, "nothing was read" end
  if not ok then
    fail(ctx.where, "%s: %s", name, (tostring(r):gsub("^lsys%.[%w_]+: ", "")))
  end
  cache_obj[key], cache_src[r] = r, bytes
  return r
end

local function contours (ctx, x, name)
  if type(x) ~= "table" then
    fail(ctx.where, "'%s' must be a table { [id] = file or { points = ... } }", name)
  end
  local out = {}
  for id, c in pairs(x) do
    if math.type(id) ~= "integer" or id < 0 then
      fail(ctx.where, "'%s': keys must be contour ids, integers >= 1", name)
    elseif id == 0 then
      fail(ctx.where, "'%s': contour 0 is the built-in circle; use ids >= 1", name)
    end
    local nm = format("%s[%d]", name, id)
    if type(c) == "string" then
      out[id] = fileobj(ctx, nm, c, nil, "contour_load")
    elseif udname(c) == "lsys.Contour" then
      out[id] = c
    elseif type(c) == "table" then
      for k in pairs(c) do
        if k ~= "points" and k ~= "closed" then
          fail(ctx.where, "%s: unknown field '%s' (known: points, closed)", nm, tostring(k))
        end
      end
      if type(c.points) ~= "table" then fail(ctx.where, "%s: 'points' must be a list", nm) end
      if c.closed ~= nil and type(c.closed) ~= "boolean" then
        fail(ctx.where, "%s: 'closed' must be a boolean", nm)
      end
      local ok, r = pcall(corefn(ctx, nm, "contour"), c.points, c.closed ~= false)
      if not ok then
        local msg = tostring(r):gsub("^bad argument #1 to '[^']*' %((.*)%)$", "%1")
        fail(ctx.where, "%s: %s", nm, msg)
      end
      out[id] = r
    else
      fail(ctx.where, "%s must be a file name or { points = ..., closed = }", nm)
    end
  end
  return out
end

local SURFACE_FIELDS = { file = true, surface = true, scale = true, texture = true,
                         precision = true, s = true, t = true }

local function precision (ctx, nm, p)
  if type(p) ~= "table" or #p ~= 2 then
    fail(ctx.where, "%s: 'precision' must be {s, t}", nm)
  end
  for i = 1, 2 do
    if not isint(p[i]) or p[i] < 1 or p[i] > 64 then
      fail(ctx.where, "%s: 'precision'[%d] must be a whole number from 1 to 64", nm, i)
    end
  end
  return math.tointeger(p[1]), math.tointeger(p[2])
end

local function surfaces (ctx, x, name)
  if type(x) ~= "table" then fail(ctx.where, "'%s' must be a table { name = file }", name) end
  local out = {}
  for k, sp in pairs(x) do
    if type(k) ~= "string" or utf8.len(k) ~= 1 then
      fail(ctx.where, "'%s': keys must be single characters (the name after ~), got '%s'",
           name, tostring(k))
    end
    local nm = format("%s.%s", name, k)
    if type(sp) == "string" then sp = { file = sp }
    elseif type(sp) ~= "table" then
      fail(ctx.where, "%s must be a file name or { file = ..., scale = ... }", nm)
    end
    for f in pairs(sp) do
      if not SURFACE_FIELDS[f] then
        fail(ctx.where, "%s: unknown field '%s' (known: file, scale, texture, precision)", nm,
             tostring(f))
      end
    end
    local surf
    if sp.surface ~= nil then
      if udname(sp.surface) ~= "lsys.Surface" then
        fail(ctx.where, "%s: 'surface' must be an lsys.Surface", nm)
      end
      surf = sp.surface
    elseif sp.file ~= nil then
      surf = fileobj(ctx, nm, sp.file, nil, "surface_load")
    else
      fail(ctx.where, "%s: a 'file' is needed", nm)
    end
    local scale = sp.scale
    if scale == nil then scale = 1
    elseif not isnum(scale) or scale <= 0 then
      fail(ctx.where, "%s: 'scale' must be a number > 0", nm)
    end
    local tex = sp.texture
    if tex == nil then tex = 0
    elseif not isint(tex) or tex < 0 then
      fail(ctx.where, "%s: 'texture' must be a texture index >= 0", nm)
    end
    local s, t
    if sp.precision ~= nil then
      s, t = precision(ctx, nm, sp.precision)
    elseif sp.s ~= nil or sp.t ~= nil then
      s, t = precision(ctx, nm, { sp.s, sp.t })
    else
      local ok, info = pcall(function () return surf:info() end)
      local p = ok and type(info) == "table" and info.precision
      if type(p) == "table" and isint(p[1]) and isint(p[2]) and p[1] >= 1 and p[2] >= 1 then
        s, t = math.tointeger(math.min(p[1], 64)), math.tointeger(math.min(p[2], 64))
      else
        s, t = 4, 4
      end
    end
    out[k] = { surface = surf, scale = scale, texture = math.tointeger(tex), s = s, t = t }
  end
  return out
end

local FILTERS = { linear = "linear", l = "linear", near = "near", n = "near" }
local MODES = { modulate = "modulate", m = "modulate", decal = "decal", d = "decal" }
local TEXTURE_FIELDS = { file = true, mag = true, min = true, mode = true,
                         per_surface = true, intensity = true }

local function textures (ctx, x, name)
  if type(x) ~= "table" then fail(ctx.where, "'%s' must be a list", name) end
  local n = #x
  for k in pairs(x) do
    if math.type(k) ~= "integer" or k < 1 or k > n then
      fail(ctx.where, "'%s' must be a list (indices 1..%d), not key '%s'", name, n, tostring(k))
    end
  end
  local out = {}
  for i = 1, n do
    local t, nm = x[i], format("%s[%d]", name, i)
    if udname(t) == "lsys.Texture" then
      out[i] = t
    else
      if type(t) == "string" then t = { file = t }
      elseif type(t) ~= "table" then
        fail(ctx.where, "%s must be a file name or { file = ..., mag = ... }", nm)
      end
      for f in pairs(t) do
        if not TEXTURE_FIELDS[f] then
          fail(ctx.where, "%s: unknown field '%s' (known: file, mag, min, mode, per_surface, "
               .. "intensity)", nm, tostring(f))
        end
      end
      local o = { mag = FILTERS[t.mag or "near"], min = FILTERS[t.min or "near"],
                  mode = MODES[t.mode or "modulate"] }
      if o.mag == nil then fail(ctx.where, "%s: 'mag' must be \"linear\" or \"near\"", nm) end
      if o.min == nil then fail(ctx.where, "%s: 'min' must be \"linear\" or \"near\"", nm) end
      if o.mode == nil then
        fail(ctx.where, "%s: 'mode' must be \"modulate\" or \"decal\"", nm)
      end
      for _, f in ipairs { "per_surface", "intensity" } do
        if t[f] ~= nil and type(t[f]) ~= "boolean" then
          fail(ctx.where, "%s: '%s' must be a boolean", nm, f)
        end
      end
      o.per_surface = t.per_surface or false
      o.intensity = t.intensity
      local extra = format("%s %s %s %s %s", o.mag, o.min, o.mode, tostring(o.per_surface),
                           tostring(o.intensity))
      out[i] = fileobj(ctx, nm, t.file, extra, "texture_load", o)
    end
  end
  return out
end

--- Checks a view table and returns a complete copy with the defaults filled in and the
-- files it names loaded. `where` names the model in messages. Raises on any error.
function M.normalize (v, where)
  where = where or "view"
  if v == nil then v = {} end
  if type(v) ~= "table" then fail(where, "the view must be a table") end
  if v.dir ~= nil and type(v.dir) ~= "string" then fail(where, "'view.dir' must be a string") end
  local ctx = { where = where, dir = v.dir, bytes = {} }
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
      if not isint(x) then
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
    elseif kind == "string" then
      out[k] = x                                -- dir, checked above
    elseif kind == "boolean" then
      if type(x) ~= "boolean" then fail(where, "'%s' must be true or false", name) end
      out[k] = x
    elseif kind == "list" then
      if type(x) ~= "table" then fail(where, "'%s' must be a list", name) end
      local l = {}
      for i, t in ipairs(x) do l[i] = tropism(t, where, format("%s[%d]", name, i), k == "torques") end
      out[k] = l
    elseif kind == "contours" then
      out[k] = contours(ctx, x, name)
    elseif kind == "surfaces" then
      out[k] = surfaces(ctx, x, name)
    elseif kind == "textures" then
      out[k] = textures(ctx, x, name)
    elseif kind == "palette" then
      if type(x) == "string" then
        local path = resolve(ctx.dir, x)
        local ext = (path:match("%.(%w+)$") or ""):lower()
        local loader = ext == "map" and M.load_colormap or ext == "mat" and M.load_materials
        if not loader then
          fail(where, "'%s': a palette file must be a colour map (.map) or materials (.mat), "
               .. "got '%s'", name, x)
        end
        local ok, r = pcall(loader, path)
        if not ok then fail(where, "%s: %s", name, tostring(r)) end
        x = r
      end
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
  out.contours = out.contours or {}
  out.surfaces = out.surfaces or {}
  out.textures = out.textures or {}
  if out.contour_sides < 3 or out.contour_sides > 1024 then
    fail(where, "'view.contour_sides' must be from 3 to 1024")
  end
  if out.supersample < 1 or out.supersample > 8 then
    fail(where, "'view.supersample' must be from 1 to 8")
  end
  for k, s in pairs(out.surfaces) do
    if s.texture > #out.textures then
      fail(where, "'view.surfaces.%s': texture %d, but the view has %d textures", k, s.texture,
           #out.textures)
    end
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
    contours = v.contours, surfaces = v.surfaces, textures = v.textures,
    minimize_twist = v.minimize_twist,
    allow_system_calls = allow_system_calls or false,
  }
end

--- The options the renderer reads (core.render), from a normalised view. `textures`
-- is left out when the view has none (the same to the renderer).
function M.render (v)
  return {
    background = v.background, light = v.light, viewpoint = v.viewpoint, target = v.target,
    up = v.up, direction = v.direction, projection = v.projection, fov = v.fov,
    twist = v.twist, supersample = v.supersample,
    textures = v.textures and #v.textures > 0 and v.textures or nil,
  }
end

--- A copy of `v` with the fields of `over` (both plain view tables) replacing its own.
function M.merge (v, over)
  local out = {}
  for k, x in pairs(v or {}) do out[k] = x end
  for k, x in pairs(over or {}) do out[k] = x end
  return out
end

-- --------------------------------------------------------------------------
-- cpfg colour maps and material files

--- Reads a cpfg colour map (.map): 256 colours of 3 bytes each (red, green, blue,
-- 0..255), 768 bytes in all, indices 0..255 in order (vlab cpfg/irisGL.c,
-- load_in_colormaps: the file is read as 256 three-byte entries). Returns a palette
-- { [0] = {r,g,b}, [1] = ..., [255] = ... } with components in 0..1.
-- Raises when the file cannot be read or is not 768 bytes long.
function M.load_colormap (path)
  if type(path) ~= "string" then error("load_colormap: a file name expected", 2) end
  local s, err = readfile(path)
  if s == nil then error(err, 0) end
  if #s ~= 768 then
    error(format("%s: a colour map is 768 bytes (256 colours of 3 bytes), not %d", path, #s), 0)
  end
  local p = {}
  for i = 0, 255 do
    local r, g, b = s:byte(3 * i + 1, 3 * i + 3)
    p[i] = { r / 255, g / 255, b / 255 }
  end
  return p
end

-- cpfg's material for indices a material file leaves out (irisGL.c: black ambient,
-- white diffuse, no emission or specular light, shininess 0).
local function default_material ()
  return { ambient = { 0, 0, 0 }, diffuse = { 1, 1, 1 }, emission = { 0, 0, 0 },
           specular = { 0, 0, 0 }, shininess = 0 }
end

--- Reads a cpfg material file (.mat, as written by vlab's material editor medit):
-- a sequence of 15-byte records, each the material's index (0..255) followed by
-- 14 bytes: transparency, ambient r g b, diffuse r g b, emission r g b, specular r g b,
-- shininess (vlab cpfg/irisGL.c, load_in_materials; medit/helpformat.html gives the
-- ranges: colours 0..1, shininess 0..128, transparency 0 opaque .. 1 clear). Colour
-- bytes are divided by 255; a transparency t > 0 becomes the alpha 1 - t/255 of all
-- four colours. Indices up to the largest one that the file leaves out get cpfg's
-- default material (white diffuse). Returns a palette { [i] = material }.
-- Raises when the file cannot be read, is empty or not a whole number of records, or
-- a shininess is above 128.
function M.load_materials (path)
  if type(path) ~= "string" then error("load_materials: a file name expected", 2) end
  local s, err = readfile(path)
  if s == nil then error(err, 0) end
  if #s == 0 or #s % 15 ~= 0 then
    error(format("%s: a material file is a sequence of 15-byte records; %d bytes is not",
                 path, #s), 0)
  end
  local p, top = {}, 0
  for rec = 1, #s // 15 do
    local o = (rec - 1) * 15
    local idx, tr = s:byte(o + 1, o + 2)
    local sh = s:byte(o + 15)
    if sh > 128 then
      error(format("%s: record %d (material %d): shininess %d is above 128", path, rec, idx,
                   sh), 0)
    end
    local function rgb (at)
      local r, g, b = s:byte(o + at, o + at + 2)
      if tr == 0 then return { r / 255, g / 255, b / 255 } end
      return { r / 255, g / 255, b / 255, 1 - tr / 255 }
    end
    p[idx] = { ambient = rgb(3), diffuse = rgb(6), emission = rgb(9), specular = rgb(12),
               shininess = sh }
    if idx > top then top = idx end
  end
  for i = 0, top do
    if p[i] == nil then p[i] = default_material() end
  end
  return p
end

-- --------------------------------------------------------------------------
-- cpfg view files (.v)
--
-- Sources: seed 004 Appendix B (contour:, contour sides:, twist of cylinders:,
-- texture: with F H L E S, tropism: and torque: with T A E S); the command list and
-- value syntax of cpfg's view reader (vlab repository AlgorithmicBotany/vlab,
-- cpfg/control.c, ReadViewData); tropism fields from cpfg/movements.c
-- (read_movement), texture fields from cpfg/textures.c (read_texture), light fields
-- from cpfg/irisGL.c (read_light), surface lines from cpfg/control.c and
-- cpfg/patches.c; and the example views of vlab's cpfg manual
-- (oofs/ext/10-manuals/ext/11-CPFG/ext/*/*.v). In short:
--
--   * one command per line, "label: values"; the label is everything before the first
--     colon. /* ... */ comments (across lines) and // comments are removed (cpfg runs
--     view files through the C preprocessor; other preprocessor lines are errors here).
--   * vectors are three numbers "x,y,z" (cpfg reads %f,%f,%f; spaces are accepted too).
--   * angle factor n gives the angle 360/n; twist is in tenths of a degree (control.c
--     turns the picture by 0.1 * twist degrees).
--   * initial line width: w [pixels|polygons]: cpfg switches the line style to
--     polygons, or to pixel lines when a unit starting with 'p' follows; here "pixels"
--     gives "line" and "polygons" (or no unit) "polygon".
--   * polygonization level: n is the older form of contour sides: 2^(n+1), at least 3.
--   * light: V: x y z is a directional light; cpfg lights the model from the first one.
--   * surface: c file scale [s t] [texture]: one number after the scale is a texture,
--     two are the precision s t, three are s t texture (control.c case 21).

local IGNORED = {}
for _, k in ipairs {
  "front distance", "back distance", "scale factor", "z buffer", "cue range", "shade mode",
  "diffuse reflection", "surface ambient", "surface diffuse", "line", "box", "bounding box",
  "ambient light", "font", "winfont", "blob", "render mode", "tapered lines",
  "background scene", "interpretation step", "interpretation past %", "tsurface",
  "rayshade objects", "rayshade scale", "initial scale", "scale multiplier",
  "environment display", "function", "curve", "antialiasing", "function set", "min zoom",
  "max zoom", "generate on view change", "generate on view changes", "concave polygons",
  "shadow map", "ps linecap", "maximum depth", "window size", "window position",
} do IGNORED[k] = true end
M.VIEWFILE_IGNORED = IGNORED

-- Text of the file shown in a message: a short token, never a whole line (a model can
-- name any file as its view file, as in cpfg): at most 16 characters, a longer one cut
-- to its first 12 and "...", control and non-ASCII bytes as '?'.
local function show (s)
  s = s:gsub("[%c\128-\255]", "?")
  if #s > 16 then s = s:sub(1, 12) .. "..." end
  return s
end

local Parser = {}
Parser.__index = Parser

function Parser:err (fmt, ...)
  error(format("%s:%d: " .. fmt, self.name, self.line, ...), 0)
end

function Parser:warn (fmt, ...)
  self.warnings[#self.warnings + 1] = format("%s:%d: " .. fmt, self.name, self.line, ...)
end

local function words (s)
  local w = {}
  for t in s:gmatch("%S+") do w[#w + 1] = t end
  return w
end

function Parser:number (tok, cmd)
  local x = tonumber(tok)
  if not isnum(x) then self:err("'%s': '%s' is not a number", cmd, show(tok)) end
  return x
end

function Parser:integer (tok, cmd, lo, hi)
  local x = self:number(tok, cmd)
  if not isint(x) or x < lo or x > hi then
    self:err("'%s': '%s' is not a whole number from %d to %d", cmd, show(tok), lo, hi)
  end
  return math.tointeger(x)
end

-- Exactly `n` words, or between `n` and `m`.
function Parser:words (rest, cmd, n, m, what)
  local w = words(rest)
  if #w < n or #w > (m or n) then
    self:err("'%s' expects %s, got '%s'", cmd, what, show(rest))
  end
  return w
end

function Parser:number1 (rest, cmd)
  return self:number(self:words(rest, cmd, 1, 1, "one number")[1], cmd)
end

function Parser:vec3 (rest, cmd)
  local w = {}
  for t in rest:gmatch("[^%s,]+") do w[#w + 1] = t end
  if #w ~= 3 then self:err("'%s' expects three numbers x,y,z, got '%s'", cmd, show(rest)) end
  return { self:number(w[1], cmd), self:number(w[2], cmd), self:number(w[3], cmd) }
end

function Parser:onoff (rest, cmd)
  local w = self:words(rest, cmd, 1, 1, "on or off")[1]
  if w ~= "on" and w ~= "off" then self:err("'%s' expects on or off, got '%s'", cmd, show(w)) end
  return w == "on"
end

-- Fields "K: values" of texture:, tropism:, torque: and light: lines. `spec[K]` is the
-- number of numbers that follow K, "word" for one word, 0 for a flag. Returns the
-- values by key and the keys in order of appearance.
function Parser:fields (rest, cmd, spec, known)
  local toks = {}
  for t in rest:gmatch("[^%s:,]+") do toks[#toks + 1] = t end
  local got, order, i = {}, {}, 1
  while i <= #toks do
    local k = toks[i]
    local n = spec[k]
    if n == nil then self:err("'%s': unknown field '%s' (known: %s)", cmd, show(k), known) end
    i = i + 1
    if n == 0 then
      got[k] = true
    elseif n == "word" then
      if toks[i] == nil then self:err("'%s': '%s:' needs a value", cmd, k) end
      got[k] = toks[i]
      i = i + 1
    else
      local l = {}
      for j = 1, n do
        local x = toks[i] and tonumber(toks[i])
        if not isnum(x) then
          self:err("'%s': '%s:' needs %d number%s", cmd, k, n, n > 1 and "s" or "")
        end
        l[j] = x
        i = i + 1
      end
      got[k] = n == 1 and l[1] or l
    end
    order[#order + 1] = k
  end
  return got, order
end

function Parser:nonzero (x, cmd)
  if x[1] == 0 and x[2] == 0 and x[3] == 0 then self:err("'%s': the vector is zero", cmd) end
  return x
end

function Parser:addtropism (t)
  local l = self.v.tropisms or {}
  if #l >= MAXTROPISMS then self:err("more than %d tropisms and torques", MAXTROPISMS) end
  l[#l + 1] = t
  self.v.tropisms = l
end

local STYLES = { pixel = "line", polygon = "polygon", cylinder = "cylinder",
                 ["1"] = "line", ["2"] = "polygon", ["3"] = "cylinder" }
local UNITS = { pixels = "line", pixel = "line", p = "line", polygons = "polygon",
                polygon = "polygon" }
local VFILTERS = { l = "linear", linear = "linear", n = "near", near = "near" }

local COMMANDS = {}

COMMANDS["angle factor"] = function (P, rest, cmd)
  local n = P:number1(rest, cmd)
  if n == 0 then P:err("'%s' must not be 0", cmd) end
  local a = 360 / n
  if a ~= a or a == math.huge or a == -math.huge then     -- 1e-320: an infinite angle
    P:err("'%s' %s gives an angle of %s degrees", cmd, show(rest), tostring(a))
  end
  P.v.angle = a
end

COMMANDS["angle increment"] = function (P, rest, cmd)
  P.v.angle = P:number1(rest, cmd)
end

COMMANDS["initial color"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 2, "a colour index (and a back colour)")
  P.v.color = P:integer(w[1], cmd, 0, 65535)
  if w[2] then
    P:integer(w[2], cmd, 0, 65535)
    P:warn("'%s': a second (back) colour is not supported; ignored", cmd)
  end
end
COMMANDS["initial colour"] = COMMANDS["initial color"]

COMMANDS["color increment"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 2, "an increment (and a back increment)")
  P.v.color_increment = P:integer(w[1], cmd, -65535, 65535)
  if w[2] then
    P:integer(w[2], cmd, -65535, 65535)
    P:warn("'%s': a second (back) increment is not supported; ignored", cmd)
  end
end
COMMANDS["colour increment"] = COMMANDS["color increment"]

COMMANDS["initial line width"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 2, "a width and optionally pixels or polygons")
  local x = P:number(w[1], cmd)
  if x < 0 then P:err("'%s' must not be negative", cmd) end
  local style = "polygon"
  if w[2] then
    style = UNITS[w[2]]
    if style == nil then
      P:err("'%s': the unit must be pixels or polygons, got '%s'", cmd, show(w[2]))
    end
  end
  P.v.line_width, P.v.line_style = x, style
end

COMMANDS["line width increment"] = function (P, rest, cmd)
  P.v.width_increment = P:number1(rest, cmd)
end

COMMANDS["line style"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 1, "pixel, polygon or cylinder")[1]
  local s = STYLES[w]
  if s == nil then P:err("'%s' must be pixel, polygon or cylinder, got '%s'", cmd, show(w)) end
  P.v.line_style = s
end

COMMANDS["viewpoint"] = function (P, rest, cmd) P.v.viewpoint = P:vec3(rest, cmd) end

COMMANDS["view reference point"] = function (P, rest, cmd) P.v.target = P:vec3(rest, cmd) end

COMMANDS["twist"] = function (P, rest, cmd) P.v.twist = P:number1(rest, cmd) / 10 end

COMMANDS["projection"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 1, "parallel or perspective")[1]
  if w ~= "parallel" and w ~= "perspective" then
    P:err("'%s' must be parallel or perspective, got '%s'", cmd, show(w))
  end
  P.v.projection = w
end

COMMANDS["viewing angle"] = function (P, rest, cmd)
  local a = P:number1(rest, cmd)
  if a <= 0 or a >= 180 then P:err("'%s' must be between 0 and 180 degrees", cmd) end
  P.v.fov = a
end

COMMANDS["light direction"] = function (P, rest, cmd)
  P.v.light = P:nonzero(P:vec3(rest, cmd), cmd)
end

COMMANDS["light"] = function (P, rest, cmd)
  local f, order = P:fields(rest, cmd, { V = 3, O = 3, A = 3, D = 3, S = 3, P = 5, T = 3 },
                            "V, O, A, D, S, P, T")
  P.nlights = P.nlights + 1
  if P.nlights > 1 then
    P:warn("'%s': only the first light is used; this one is ignored", cmd)
    return
  end
  for _, k in ipairs(order) do
    if k ~= "V" then P:warn("'%s': '%s:' is not supported; ignored", cmd, k) end
  end
  if f.V then P.v.light = P:nonzero(f.V, cmd)
  else P:warn("'%s' without a direction V: is ignored", cmd) end
end

local function background (P, rest, cmd)
  local c = P:vec3(rest, cmd)
  for i = 1, 3 do
    if c[i] < 0 or c[i] > 1 then
      P:warn("'%s': components outside 0..1 are not supported; ignored", cmd)
      return
    end
  end
  P.v.background = c
end
COMMANDS["background color"] = background
COMMANDS["background colour"] = background

COMMANDS["contour"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 2, 2, "an id and a file")
  local id = P:integer(w[1], cmd, 0, 65535)
  if id == 0 then P:err("'%s': id 0 is the built-in circle; use ids from 1", cmd) end
  local c = P.v.contours or {}
  if c[id] ~= nil then P:err("'%s': id %d is already defined", cmd, id) end
  c[id] = w[2]
  P.v.contours = c
end

COMMANDS["contour sides"] = function (P, rest, cmd)
  P.v.contour_sides = P:integer(P:words(rest, cmd, 1, 1, "one number")[1], cmd, 3, 1024)
end

COMMANDS["polygonization level"] = function (P, rest, cmd)
  local n = P:integer(P:words(rest, cmd, 1, 1, "one number")[1], cmd, 0, 9)
  P.v.contour_sides = math.max(3, 1 << (n + 1))
end

COMMANDS["twist of cylinders"] = function (P, rest, cmd)
  P.v.minimize_twist = P:onoff(rest, cmd)
end

COMMANDS["texture"] = function (P, rest, cmd)
  local f, order = P:fields(rest, cmd, { F = "word", H = "word", L = "word", E = "word",
                                         S = 0, R = 1 }, "F, H, L, E, S, R")
  if f.F == nil then P:err("'%s' needs the image file F:", cmd) end
  local t = { file = f.F, mag = "near", min = "near", mode = "modulate", per_surface = false }
  for _, k in ipairs(order) do
    local x = f[k]
    if k == "H" then
      t.mag = VFILTERS[x] or P:err("'%s': H: must be l(inear) or n(ear), got '%s'", cmd, show(x))
    elseif k == "L" then
      if x:sub(1, 1) == "m" then
        P:warn("'%s': mipmaps (L: %s) are not supported; linear used", cmd, show(x))
        t.min = "linear"
      else
        t.min = VFILTERS[x] or
                P:err("'%s': L: must be l(inear) or n(ear), got '%s'", cmd, show(x))
      end
    elseif k == "E" then
      if x == "m" or x == "modulate" then t.mode = "modulate"
      elseif x == "d" or x == "decal" then t.mode = "decal"
      elseif x == "b" or x == "blend" then
        P:warn("'%s': E: blend is not supported; modulate used", cmd)
      else
        P:err("'%s': E: must be m(odulate) or d(ecal), got '%s'", cmd, show(x))
      end
    elseif k == "S" then
      t.per_surface = true
    elseif k == "R" then
      P:warn("'%s': R: (the texture's aspect on cylinders) is not supported; ignored", cmd)
    end
  end
  local l = P.v.textures or {}
  l[#l + 1] = t
  P.v.textures = l
end

COMMANDS["tropism"] = function (P, rest, cmd)
  local f = P:fields(rest, cmd, { T = 3, A = 1, E = 1, S = 1, I = 1 }, "T, A, E, S, I")
  if f.T == nil then P:err("'%s' needs the vector T: x y z", cmd) end
  if f.I then P:warn("'%s': the intensity I: is not supported; ignored", cmd) end
  P:addtropism { vector = P:nonzero(f.T, cmd), angle = f.A or 0, elasticity = f.E or 0,
                 increment = f.S or 0 }
end

COMMANDS["torque"] = function (P, rest, cmd)
  local f = P:fields(rest, cmd, { T = 3, A = 1, E = 1, S = 1, I = 1 }, "T, E, S")
  if f.T == nil then P:err("'%s' needs the vector T: x y z", cmd) end
  if f.A then P:warn("'%s': a torque has no angle; A: ignored", cmd) end
  if f.I then P:warn("'%s': the intensity I: is not supported; ignored", cmd) end
  P:addtropism { vector = P:nonzero(f.T, cmd), elasticity = f.E or 0, increment = f.S or 0,
                 torque = true }
end

COMMANDS["tropism direction"] = function (P, rest, cmd)
  P.legacy.vector = P:nonzero(P:vec3(rest, cmd), cmd)
end

COMMANDS["initial elasticity"] = function (P, rest, cmd)
  P.legacy.elasticity, P.legacy.line = P:number1(rest, cmd), P.legacy.line or P.line
end

COMMANDS["elasticity increment"] = function (P, rest, cmd)
  P.legacy.increment, P.legacy.line = P:number1(rest, cmd), P.legacy.line or P.line
end

COMMANDS["surface"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 3, 6, "a name, a file, a scale, [s t] and [a texture]")
  if utf8.len(w[1]) ~= 1 then
    P:err("'%s': the name must be one character, got '%s'", cmd, show(w[1]))
  end
  local scale = P:number(w[3], cmd)
  if scale <= 0 then P:err("'%s': the scale must be > 0", cmd) end
  local s = { file = w[2], scale = scale }
  local tex
  if #w == 4 then
    tex = w[4]
  elseif #w >= 5 then
    local ps = P:integer(w[4], cmd, 0, 64)
    local pt = P:integer(w[5], cmd, 0, 64)
    if (ps == 0) ~= (pt == 0) then
      P:err("'%s': the precisions s t must both be 1..64 (or both 0: the file's)", cmd)
    end
    if ps > 0 then s.precision = { ps, pt } end
    tex = w[6]
  end
  if tex then
    local k = P:integer(tex, cmd, -1, 65535)
    if k >= 0 then s.texture = k end             -- -1: cpfg's "the turtle's texture"
  end
  local l = P.v.surfaces or {}
  if l[w[1]] ~= nil then P:err("'%s': '%s' is already defined", cmd, w[1]) end
  l[w[1]] = s
  P.v.surfaces = l
  P.surfaces[#P.surfaces + 1] = { line = P.line, texture = s.texture }
end

-- One line of a view file, comments removed.
function Parser:command (s)
  s = s:match("^%s*(.-)%s*$")
  if s == "" then return end
  if s:sub(1, 1) == "#" then
    self:err("preprocessor line '%s' is not supported (expand the file with cpp first)",
             show(s))
  end
  local label, rest = s:match("^([^:]*):%s*(.-)$")
  if label == nil then self:err("expected 'command: values', got '%s'", show(s)) end
  local cmd = label:gsub("%s+", " "):match("^ ?(.-) ?$"):lower()
  local h = COMMANDS[cmd]
  if h then
    h(self, rest, cmd)
  elseif IGNORED[cmd] then
    self:warn("'%s' is not supported; ignored", cmd)
  else
    self:err("unknown view command '%s'", show(cmd))
  end
end

--- Reads the text of a cpfg view file into a view table (see `load`). `name` names the
-- file in messages ("view" by default). opts: dir (stored as the view's `dir`), quiet
-- (do not print the warnings). Returns the view and the list of warnings.
function M.parse (text, name, opts)
  if type(text) ~= "string" then error("view.parse: the text must be a string", 2) end
  if name ~= nil and type(name) ~= "string" then
    error("view.parse: the name must be a string", 2)
  end
  if opts ~= nil and type(opts) ~= "table" then error("view.parse: opts must be a table", 2) end
  opts = opts or {}
  local P = setmetatable({ name = name or "view", line = 0, v = {}, warnings = {},
                           nlights = 0, legacy = {}, surfaces = {} }, Parser)
  local incomment, cline = false, 0
  for line in (text .. "\n"):gmatch("([^\n]*)\n") do
    P.line = P.line + 1
    local out, pos = {}, 1
    while pos <= #line do
      if incomment then
        local e = line:find("*/", pos, true)
        if e == nil then break end
        incomment, pos = false, e + 2
        out[#out + 1] = " "
      else
        local c = line:find("/[*/]", pos)
        if c == nil then out[#out + 1] = line:sub(pos); break end
        out[#out + 1] = line:sub(pos, c - 1)
        if line:sub(c + 1, c + 1) == "/" then break end
        incomment, cline, pos = true, P.line, c + 2
      end
    end
    P:command(table.concat(out))
  end
  if incomment then
    P.line = cline
    P:err("the comment that starts here is not closed")
  end
  local lg = P.legacy
  if lg.vector then
    P.line = lg.line or P.line
    P:addtropism { vector = lg.vector, elasticity = lg.elasticity or 0,
                   increment = lg.increment or 0 }
  elseif lg.line then
    P.line = lg.line
    P:warn("'initial elasticity' and 'elasticity increment' without 'tropism direction' "
           .. "are ignored")
  end
  local v = P.v
  local ntex = v.textures and #v.textures or 0
  for _, s in ipairs(P.surfaces) do
    if s.texture and s.texture > ntex then
      P.line = s.line
      P:err("'surface': texture %d, but the file defines %d texture%s", s.texture, ntex,
            ntex == 1 and "" or "s")
    end
  end
  if opts.dir ~= nil then v.dir = opts.dir end
  if not opts.quiet then
    for _, w in ipairs(P.warnings) do io.stderr:write(w, "\n") end
  end
  return v, P.warnings
end

--- Reads a cpfg view file (.v) into a view table that `normalize` accepts; file names
-- in it (contours, surfaces, textures) are relative to the file's directory, which
-- becomes the view's `dir`. Supported commands: angle factor, angle increment,
-- initial color, color increment, initial line width, line width increment, line
-- style, viewpoint, view reference point, twist, projection, viewing angle, light
-- direction, light, background color, contour, contour sides, polygonization level,
-- twist of cylinders, texture, tropism, torque, tropism direction, initial
-- elasticity, elasticity increment, surface. Commands listed in VIEWFILE_IGNORED
-- (front distance, z buffer, render mode, ...) are warnings; any other command and any
-- malformed value raise "file.v:LINE: what is wrong". opts.quiet: do not print the
-- warnings to stderr. Returns the view and the list of warnings.
function M.load (path, opts)
  if type(path) ~= "string" then error("view.load: a file name expected", 2) end
  if opts ~= nil and type(opts) ~= "table" then error("view.load: opts must be a table", 2) end
  local text, err = readfile(path)
  if text == nil then error("view.load: " .. err, 0) end
  local dir = path:match("^(.*)/[^/]*$")
  if dir == "" then dir = "/" end
  return M.parse(text, path, { dir = dir or ".", quiet = opts and opts.quiet })
end

return M
