--- View options (docs/drawing.md §2; cpfg guide, Appendix B): how a model is drawn.
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
--                    (cpfg guide §6; `angle` is the diatropism angle); an entry with
--                    `torque = true` is a twist response (§6.1)
--   torques          list of { vector = {x,y,z}, elasticity = 0, increment = 0 }, numbered
--                    after the tropisms by @Ts @Ti @Td; a tropism or torque may have an
--                    `intensity` (1) that multiplies its elasticity
--   old_tropism      { vector = {0,1,0}, elasticity = 0, increment = 0 }: cpfg's old-style
--                    tropism, which bends H after each move with the elasticity `_(e)`
--                    sets (`_` adds the increment); it acts whenever that elasticity is not
--                    0, with the default vector when the view has none
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
--   lights           a view's own lights, replacing the default key, fill, sky and ground
--                    lights (as cpfg's "light:" lines do): at most 8, each { direction =
--                    {x,y,z} or position = {x,y,z}, ambient =, diffuse =, specular = }
--   supersample      anti-aliasing factor for rendering (3)
--   dir              directory that relative file names of this view are read from
--                    (default: the current directory); `load` sets it to the .v file's
--   contours         { [id] = "file.con" | { points = {{x,y[,z]}, ...}, closed = true } }:
--                    cross-sections of generalized cylinders, selected by @#(id)
--                    (cpfg guide §3.2.3, Appendix B.1); ids are integers >= 1 (0 is the
--                    built-in circle). Normalised to { [id] = lsys.Contour }
--   surfaces         { P = "petal.s" | { file = "petal.s", scale = 1, texture = 0,
--                    precision = {s, t} } }: predefined surfaces drawn by ~P (§4.1). The
--                    key is one character; scale > 0 multiplies the surface; texture is
--                    an index into `textures` (1 = first; 0 none) applied to every
--                    instance; precision is the lines per patch in s and t (1..64; the
--                    file's own, at most 64, else 4). Normalised to
--                    { P = { surface = lsys.Surface, scale =, texture =, s =, t = } }.
--                    An entry may also be an lsys.Surface or an Organ (lsys.sketch.organ),
--                    alone or as the table's `surface`
--   textures         list of "image.png" | { file =, mag = "near", min = "near",
--                    mode = "modulate", per_surface = false, intensity = (from the
--                    image) }: textures selected by @Tx(k) (§5, Appendix B.2); filters
--                    "linear"/"near" (or l/n), modes "modulate"/"decal" (or m/d).
--                    Normalised to a list of lsys.Texture
--   minimize_twist   true: generalized cylinders use the twist-minimising frame (cpfg
--                    "twist of cylinders: on", the default, §3.3); false: the turtle's
--                    own twist is kept
--   functions        list of lsys.Func | "file.func" | "set.fset" | { file =, samples = }:
--                    the positional functions of cpfg's "function:" / "functions:" lines;
--                    a model without its own `functions` option takes these (kept as
--                    given; lsys.model reads the files, relative to `dir`)
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
-- the same for text in memory; `load_colormap` and `load_materials` read palettes. They
-- are lsys.viewfile's, given here under the same names.
-- @module lsys.view
local core = require "lsys.core"
local viewfile = require "lsys.viewfile"
local warning = require "lsys.warning"
local suggest = require "lsys.util.suggest"

local type, pairs, ipairs, error, tostring, tonumber, math, string, table, pcall,
      setmetatable, getmetatable, rawget, utf8 =
      type, pairs, ipairs, error, tostring, tonumber, math, string, table, pcall,
      setmetatable, getmetatable, rawget, utf8
local format = string.format
local _ENV = nil

local M = {}

-- the cpfg file readers (lsys.viewfile)
M.load, M.parse = viewfile.load, viewfile.parse
M.load_colormap, M.load_materials = viewfile.load_colormap, viewfile.load_materials
M.VIEWFILE_IGNORED = viewfile.VIEWFILE_IGNORED

--- The default palette: bark, foliage, and bright organ colours.
local OVERLAY = {}      -- the metatable of merge's palette overlays

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
  old_tropism = "oldtropism",
  background = "color", viewpoint = "vec", target = "vec", up = "vec", direction = "vec",
  projection = "projection", fov = "number", twist = "number", light = "vec",
  lights = "lights",
  supersample = "integer", dir = "string", contours = "contours", surfaces = "surfaces",
  textures = "textures", minimize_twist = "boolean", functions = "functions",
}
M.KINDS = KINDS

local function fail (where, fmt, ...)
  error(format("%s: " .. fmt, where, ...), 0)
end

local function isnum (x)
  return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge
end

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

M.color = color     -- (c, where, name) -> {r, g, b[, a]}: the checked colour (lsys.grow too)

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
  if out.vector[1] == 0 and out.vector[2] == 0 and out.vector[3] == 0 then
    fail(where, "'%s.vector' is {0, 0, 0}: a %s needs a direction", name,
         (torque or t.torque) and "torque" or "tropism")
  end
  for _, k in ipairs { "angle", "elasticity", "increment" } do
    local x = t[k]
    if x ~= nil and not isnum(x) then fail(where, "'%s.%s' must be a number", name, k) end
    out[k] = x or 0
  end
  if t.intensity ~= nil then
    if not isnum(t.intensity) then fail(where, "'%s.intensity' must be a number", name) end
    out.intensity = t.intensity
  end
  for k in pairs(t) do
    if k ~= "vector" and k ~= "angle" and k ~= "elasticity" and k ~= "increment"
       and k ~= "torque" and k ~= "intensity" then
      fail(where, "'%s': unknown field '%s'", name, tostring(k))
    end
  end
  return out
end

-- cpfg's old-style tropism: { vector = {0, 1, 0}, elasticity = 0, increment = 0 }.
-- A view's own lights (cpfg's "light:" lines), which replace the default ones: at most 8,
-- each { direction = {x,y,z} (towards the light) or position = {x,y,z}, ambient = (black),
-- diffuse = (white), specular = (white) }: colours {r,g,b} >= 0 (above 1 brightens).
local function lights (x, where, name)
  if type(x) ~= "table" then fail(where, "'%s' must be a list of lights", name) end
  if #x > 8 then fail(where, "'%s' has %d lights; at most 8 can be drawn", name, #x) end
  local l = {}
  for i, t in ipairs(x) do
    local n = format("%s[%d]", name, i)
    if type(t) ~= "table" then fail(where, "'%s' must be a table", n) end
    if (t.direction == nil) == (t.position == nil) then
      fail(where, "'%s' needs a direction or a position (one of them)", n)
    end
    local o = {}
    if t.direction ~= nil then
      o.direction = vec(t.direction, where, n .. ".direction")
      if o.direction[1] == 0 and o.direction[2] == 0 and o.direction[3] == 0 then
        fail(where, "'%s.direction' must not be the zero vector", n)
      end
    else
      o.position = vec(t.position, where, n .. ".position")
    end
    for _, k in ipairs { "ambient", "diffuse", "specular" } do   -- above 1 brightens
      if t[k] ~= nil then
        o[k] = vec(t[k], where, n .. "." .. k)
        for j = 1, 3 do
          if o[k][j] < 0 then fail(where, "'%s.%s'[%d] must not be negative", n, k, j) end
        end
      end
    end
    l[i] = o
  end
  return l
end

local function oldtropism (t, where, name)
  if type(t) ~= "table" then fail(where, "'%s' must be a table", name) end
  local out = { vector = t.vector ~= nil and vec(t.vector, where, name .. ".vector")
                         or { 0, 1, 0 } }
  if out.vector[1] == 0 and out.vector[2] == 0 and out.vector[3] == 0 then
    fail(where, "'%s.vector' is {0, 0, 0}: a tropism needs a direction", name)
  end
  for _, k in ipairs { "elasticity", "increment" } do
    local x = t[k]
    if x ~= nil and not isnum(x) then fail(where, "'%s.%s' must be a number", name, k) end
    out[k] = x or 0
  end
  for k in pairs(t) do
    if k ~= "vector" and k ~= "elasticity" and k ~= "increment" then
      fail(where, "'%s': unknown field '%s' (known: vector, elasticity, increment)", name,
           tostring(k))
    end
  end
  return out
end

-- --------------------------------------------------------------------------
-- Files

--- `path` read relative to `dir` (nil or "": as given). Absolute paths stay. (lsys.func
-- reads the view's function files the same way.)
local function resolve (dir, path)
  if dir == nil or dir == "" or path:sub(1, 1) == "/" then return path end
  if dir:sub(-1) == "/" then return dir .. path end
  return dir .. "/" .. path
end
M.resolve = resolve

-- Largest texture (PNG or SGI image) read; contours and surfaces have readfile's default (16 MiB).
local MAXIMAGE = 256 * 2 ^ 20

local readfile = viewfile.readfile

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
  local f = core[fn]
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
    local max = fn == "texture_load" and MAXIMAGE or nil
    local err
    bytes, err = readfile(path, max)
    if bytes == nil and path ~= rel and rel:sub(1, 1) ~= "/" then
      local b2 = readfile(rel, max)  -- not in the model's folder: the current folder's
      if b2 ~= nil then path, bytes = rel, b2 end
    end
    if bytes == nil and not tostring(err):find("No such file", 1, true) then
      fail(ctx.where, "%s: %s", name, err)
    elseif bytes == nil then
      fail(ctx.where, "%s: %s (%s)", name, err, path == rel and
           "looked for in the current folder; view.dir names another"
           or format("looked for in '%s' (view.dir: the model's folder unless set), then in "
                     .. "the current folder", ctx.dir))
    end
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

-- The lsys.Surface that `x` is or makes: an lsys.Surface, or an Organ (lsys.sketch.organ,
-- a table whose metatable is named "lsys.Organ") through its surface(); else nil.
local function surfobj (x)
  if udname(x) == "lsys.Surface" then return x end
  local mt = type(x) == "table" and getmetatable(x)
  if type(mt) == "table" and rawget(mt, "__name") == "lsys.Organ" then return x:surface() end
  return nil
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
    elseif surfobj(sp) ~= nil then sp = { surface = sp }
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
      surf = surfobj(sp.surface)
      if surf == nil then
        fail(ctx.where, "%s: 'surface' must be an lsys.Surface", nm)
      end
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

-- A palette: a list of colours or materials, or the name of a cpfg colour map (.map) or
-- material file (.mat) read by lsys.viewfile.
local function palette (ctx, x, name)
  local where = ctx.where
  local function entries (t)
    if type(t) ~= "table" then fail(where, "'%s' must be a list of colours", name) end
    local p = {}
    for i, c in pairs(t) do
      if math.type(i) ~= "integer" or i < 0 then
        fail(where, "'%s': keys must be colour indices >= 0", name)
      end
      p[i] = material(c, where, format("%s[%d]", name, i))
    end
    return p
  end
  local p
  if type(x) == "table" and getmetatable(x) == OVERLAY then   -- merge's: entries on a base
    p = x.base ~= nil and palette(ctx, x.base, name) or {}
    for i, c in pairs(entries(x.entries)) do p[i] = c end
  else
    if type(x) == "string" then
      local path = resolve(ctx.dir, x)
      local ext = (path:match("%.(%w+)$") or ""):lower()
      local loader = ext == "map" and viewfile.load_colormap or
                     ext == "mat" and viewfile.load_materials
      if not loader then
        fail(where, "'%s': a palette file must be a colour map (.map) or materials (.mat), "
             .. "got '%s'", name, x)
      end
      local ok, r = pcall(loader, path)
      if not ok then fail(where, "%s: %s", name, tostring(r)) end
      x = r
    end
    p = entries(x)
  end
  -- Entries not given are the default palette's, except entry 0 of a palette that gives
  -- entry 1: it repeats entry 1, as it always has, so a list of one colour draws every
  -- colour index (they wrap around) in that colour.
  local n = 0
  for i in pairs(p) do if i > n then n = i end end
  if p[0] == nil and p[1] ~= nil then p[0] = p[1] end
  for i = 0, n do
    if p[i] == nil then
      if M.PALETTE[i] == nil then
        fail(where, "'%s': entry %d is missing (the default palette has 0 to %d)", name, i,
             #M.PALETTE)
      end
      p[i] = { diffuse = M.PALETTE[i] }
    end
  end
  return p
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
      local hint = suggest.hint(k, known)
      if hint ~= "" then fail(where, "unknown view option '%s'%s", tostring(k), hint) end
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
      for i, t in ipairs(x) do
        l[i] = tropism(t, where, format("%s[%d]", name, i), k == "torques")
      end
      out[k] = l
    elseif kind == "oldtropism" then
      out[k] = oldtropism(x, where, name)
    elseif kind == "lights" then
      out[k] = lights(x, where, name)
    elseif kind == "contours" then
      out[k] = contours(ctx, x, name)
    elseif kind == "surfaces" then
      out[k] = surfaces(ctx, x, name)
    elseif kind == "textures" then
      out[k] = textures(ctx, x, name)
    elseif kind == "palette" then
      out[k] = palette(ctx, x, name)
    elseif kind == "functions" then           -- read by the model (lsys.func.collect)
      if type(x) ~= "table" then fail(where, "'%s' must be a list", name) end
      out[k] = x
    end
  end
  for k, d in pairs(DEFAULTS) do if out[k] == nil then out[k] = d end end
  out.contours = out.contours or {}
  out.surfaces = out.surfaces or {}
  out.textures = out.textures or {}
  if out.contour_sides < 3 or out.contour_sides > 1024 then
    fail(where, "'view.contour_sides' must be from 3 to 1024")
  end
  if out.line_width < 0 then
    fail(where, "'view.line_width' must be >= 0, got %g", out.line_width)
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

-- The view options the turtle reads (core.interpret and friends), under the schema's own
-- names: this schema owns names, defaults and checks; the C side only reads them.
local TURTLE = { "angle", "step", "line_width", "width_increment", "color", "color_increment",
                 "line_style", "contour_sides", "tropisms", "torques", "old_tropism",
                 "palette", "contours",
                 "surfaces", "textures", "minimize_twist" }
M.TURTLE = {}                   -- by name: the options that change how the turtle draws
for _, k in ipairs(TURTLE) do M.TURTLE[k] = true end

-- How to look at a scene: the camera, the light and the background, which the scene keeps
-- (csrc/core/scene.h) and the renderer and the viewer read from it.
local LOOK = { "background", "light", "lights", "viewpoint", "target", "up", "direction",
               "projection", "fov", "twist" }

--- The options core.interpret reads, from a normalised view: the turtle's, and how the
-- scene it makes is to be looked at.
function M.turtle_options (v, allow_system_calls)
  if type(v) ~= "table" then
    error("lsys.view.turtle_options: a view table expected (lsys.view.normalize's), got "
          .. type(v), 2)
  end
  local o = { allow_system_calls = allow_system_calls or false }
  for _, k in ipairs(TURTLE) do o[k] = v[k] end
  for _, k in ipairs(LOOK) do o[k] = v[k] end
  return o
end

--- The options core.render reads to look at a scene another way, from a normalised view:
-- the look, the supersampling and the textures (left out when the view has none: the same
-- to the renderer).
function M.render_options (v)
  if type(v) ~= "table" then
    error("lsys.view.render_options: a view table expected (lsys.view.normalize's), got "
          .. type(v), 2)
  end
  local o = { supersample = v.supersample,
              textures = v.textures and #v.textures > 0 and v.textures or nil }
  for _, k in ipairs(LOOK) do o[k] = v[k] end
  return o
end

M.turtle = warning.alias("lsys.view.turtle", "lsys.view.turtle_options", M.turtle_options)
M.render = warning.alias("lsys.view.render", "lsys.view.render_options", M.render_options)

--- A copy of `v` with the fields of `over` (both plain view tables) replacing its own.
function M.merge (v, over)
  for i, x in ipairs { v, over } do
    if x ~= nil and type(x) ~= "table" then
      error(format("lsys.view.merge: argument %d must be a view table or nil, got %s", i,
                   type(x)), 2)
    end
  end
  local out = {}
  for k, x in pairs(v or {}) do out[k] = x end
  for k, x in pairs(over or {}) do out[k] = x end
  -- a palette table over another palette changes only the entries it names
  if v and v.palette ~= nil and over and type(over.palette) == "table" then
    out.palette = setmetatable({ base = v.palette, entries = over.palette }, OVERLAY)
  end
  return out
end

return M
