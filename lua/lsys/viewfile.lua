--- cpfg's files for views (docs/drawing.md §2; cpfg guide, Appendix B): view files (.v), colour
-- maps (.map) and material files (.mat), read into the plain tables that lsys.view
-- checks. lsys.view gives these functions under the same names (`lsys.view.load`, ...);
-- this module reads files and never checks a whole view (`lsys.view.normalize` does).
--
-- `load(path)` reads a cpfg view file into a view table; `parse(text, name)` does the
-- same for text in memory. `load_colormap` and `load_materials` read palettes.
-- @module lsys.viewfile
local core = require "lsys.core"
local warning = require "lsys.warning"

local type, ipairs, pairs, next, error, tostring, tonumber, math, string, table,
      setmetatable, utf8, io =
      type, ipairs, pairs, next, error, tostring, tonumber, math, string, table,
      setmetatable, utf8, io
local format = string.format
local _ENV = nil

local M = {}

local function isnum (x)
  return type(x) == "number" and x == x and x ~= math.huge and x ~= -math.huge
end

local function isint (x) return isnum(x) and x == math.floor(x) end

-- Largest file read by default: view files, palettes (and lsys.view's contours and
-- surfaces).
local MAXFILE = 16 * 2 ^ 20

--- The bytes of a regular file of at most `max` bytes (default 16 MiB), or nil and a
-- message naming the file ("cannot open 'x': ...", "cannot read 'x': not a regular
-- file"): a view can name any path, /dev/zero included. lsys.view reads the files of
-- contours, surfaces and textures with it too.
function M.readfile (path, max)
  return core.read_file(path, max or MAXFILE)
end
local readfile = M.readfile

-- --------------------------------------------------------------------------
-- cpfg colour maps and material files

--- Reads a cpfg colour map (.map): 256 colours of 3 bytes each (red, green, blue,
-- 0..255), 768 bytes in all, indices 0..255 in order (vlab cpfg/irisGL.c,
-- load_in_colormaps: the file is read as 256 three-byte entries). Returns a palette
-- { [0] = {r,g,b}, [1] = ..., [255] = ... } with components in 0..1.
-- Raises when the file cannot be read or is not 768 bytes long.
function M.load_colormap (path)
  if type(path) ~= "string" then error("lsys.view.load_colormap: a file name expected", 2) end
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
  if type(path) ~= "string" then error("lsys.view.load_materials: a file name expected", 2) end
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
-- Sources: the cpfg guide (Měch and Prusinkiewicz), Appendix B (contour:, contour sides:,
-- twist of cylinders:, texture: with F H L E S, tropism: and torque: with T A E S); the
-- command list and value syntax of cpfg's view reader (vlab repository
-- AlgorithmicBotany/vlab, cpfg/control.c, ReadViewData); tropism fields from
-- cpfg/movements.c (read_movement), texture fields from cpfg/textures.c (read_texture),
-- light fields from cpfg/irisGL.c (read_light), surface lines from cpfg/control.c and
-- cpfg/patches.c; and the example views of vlab's cpfg manual
-- (oofs/ext/10-manuals/ext/11-CPFG/ext/*/*.v). In short:
--
--   * one command per line, "label: values"; the label is everything before the first
--     colon. /* ... */ comments (across lines) and // comments are removed (cpfg runs
--     view files through the C preprocessor; other preprocessor lines are errors here).
--   * vectors are three numbers "x,y,z" (cpfg reads %f,%f,%f; spaces are accepted too).
--   * angle factor n gives the angle 360/n; twist is in tenths of a degree (control.c
--     turns the picture by 0.1 * twist degrees).
--   * initial line width: w [unit]: cpfg switches the line style to polygons, to pixel
--     lines when the unit starts with 'p' ("line" here) and to cylinders when it starts
--     with 's'; another unit is polygons too, with a warning here.
--   * polygonization level: n is the older form of contour sides: 2^(n+1), at least 3.
--   * light: V: x y z is a directional light, O: x y z a point light at that position;
--     A:, D:, S: its ambient, diffuse and specular colours (cpfg/OpenGL's defaults: black,
--     white, white). A view with light: lines is lit by those (at most 8) and nothing
--     else, as cpfg does; the first one's direction is also the view's `light`.
--   * surface: c file scale [s t] [texture]: one number after the scale is a texture,
--     two are the precision s t, three are s t texture (control.c case 21).

local IGNORED = {}
for _, k in ipairs {
  "front distance", "back distance", "scale factor", "z buffer", "cue range", "shade mode",
  "diffuse reflection", "surface ambient", "surface diffuse", "line", "box", "bounding box",
  "ambient light", "font", "winfont", "blob", "render mode", "tapered lines",
  "background scene", "interpretation step", "interpretation past %", "tsurface",
  "rayshade objects", "rayshade scale", "initial scale", "scale multiplier",
  "environment display", "curve", "antialiasing", "min zoom",
  "max zoom", "generate on view change", "generate on view changes", "concave polygons",
  "shadow map", "ps linecap", "maximum depth", "window size", "window position",
} do IGNORED[k] = true end
M.VIEWFILE_IGNORED = IGNORED
-- The display-only commands warned about (through warn()) in this process: a viewer that
-- reloads its model, or a batch of a hundred vlab models, says each kind once.
local SAID = {}

-- cpfg's values for what a view file does not set, where they differ from lsys.view's
-- defaults (interpret.c, InitializeParameters: angle increment 45, line width increment
-- 0). lsys.cpfg.load fills them in; `load` and `parse` give only what the file says.
M.CPFG_DEFAULTS = { angle = 45, width_increment = 0 }

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
  local max = core.MAXTROPISMS       -- the turtle's limit (LSYS_MAXTROPISMS)
  if #l >= max then self:err("more than %d tropisms and torques", max) end
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
    -- cpfg looks only at the unit's first letter (interpret.c, case 4): p pixels,
    -- s cylinders, anything else polygons
    style = UNITS[w[2]] or (w[2]:sub(1, 1) == "p" and "line")
            or (w[2]:sub(1, 1) == "s" and "cylinder")
    if not style then
      style = "polygon"
      P:warn("'%s': unknown unit '%s' read as polygons (as cpfg does)", cmd, show(w[2]))
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
  if s == nil then           -- cpfg keeps the style it had (vlab's models say "wireframe")
    P:warn("'%s' must be pixel, polygon or cylinder, got '%s'; ignored", cmd, show(w))
    return
  end
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
  if P.nlights >= 8 then
    P:warn("'%s': at most 8 lights are drawn; this one is ignored", cmd)
    return
  end
  for _, k in ipairs(order) do
    if k == "P" or k == "T" then P:warn("'%s': '%s:' is not supported; ignored", cmd, k) end
  end
  if f.V and f.O then P:warn("'%s': both V: and O:; the direction V: is used", cmd) end
  if not f.V and not f.O then
    P:warn("'%s' without a direction V: or a position O: is ignored", cmd)
    return
  end
  local l = f.V and { direction = P:nonzero(f.V, cmd) } or { position = f.O }
  for _, kn in ipairs { { "A", "ambient" }, { "D", "diffuse" }, { "S", "specular" } } do
    local k, name = kn[1], kn[2]
    if f[k] then
      for i = 1, 3 do
        if f[k][i] < 0 then
          P:err("'%s': the components of '%s:' must not be negative", cmd, k)
        end
      end
      l[name] = f[k]
    end
  end
  P.nlights = P.nlights + 1
  P.v.lights = P.v.lights or {}
  P.v.lights[P.nlights] = l
  if P.nlights == 1 and l.direction then P.v.light = l.direction end
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

-- function: NAME.func [SAMPLES] adds a positional function (func(ID, x): ID counts these
-- lines from 1); without SAMPLES, exact values (cpfg: -1). SAMPLES applies to the old
-- "range:" form of the file; an fver 1 1 file has its own (cpfg/splinefun.cpp).
COMMANDS["function"] = function (P, rest, cmd)
  local w = P:words(rest, cmd, 1, 2, "a file and optionally a number of samples")
  local l = P.v.functions or {}
  l[#l + 1] = { file = w[1], samples = w[2] and P:integer(w[2], cmd, -1, 1000000) or 0 }
  P.v.functions = l
end

-- function set: NAME.fset replaces the functions with those of the set (as cpfg does);
-- "functions:" is read the same way.
COMMANDS["function set"] = function (P, rest, cmd)
  P.v.functions = { { file = P:words(rest, cmd, 1, 1, "a file")[1], samples = 0 } }
end
COMMANDS["functions"] = COMMANDS["function set"]

COMMANDS["contour sides"] = function (P, rest, cmd)
  P.v.contour_sides = P:integer(P:words(rest, cmd, 1, 1, "one number")[1], cmd, 3, 1024)
end

COMMANDS["polygonization level"] = function (P, rest, cmd)
  local n = P:integer(P:words(rest, cmd, 1, 1, "one number")[1], cmd, 0, 9)
  P.v.contour_sides = math.max(3, 1 << (n + 1))
end

-- cpfg's "on" (its gen_cyl_twist) turns each generalized cylinder's contour with the
-- turtle's roll at the control points, spread evenly along the strips; "off", its
-- default, carries the contour along without twist, ignoring the rolls: lsys's
-- minimize_twist = false and true (the guide's wording suggests the reverse; what cpfg
-- draws decides: herb-lily's leaves, `/(phi) @Gc(1) \(phi)`, twist with "on").
COMMANDS["twist of cylinders"] = function (P, rest, cmd)
  P.v.minimize_twist = not P:onoff(rest, cmd)
end

local TEXFIELDS = { F = true, H = true, L = true, E = true, S = true, R = true }

COMMANDS["texture"] = function (P, rest, cmd)
  local first = rest:match("^[%s:,]*([^%s:,]+)")
  if first and not TEXFIELDS[first] and first:find("%.") then
    -- `texture: leafs.png` (no F:): cpfg reads the 'l' as an unknown field and skips the
    -- line, its texture not counted (vlab's VlabTools/Lychnis has these)
    return P:warn("'%s': '%s' is not a field (F: file, H, L, E, S, R): cpfg skips the line",
                  cmd, show(first))
  end
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
  P.texlines[#l] = P.line
end

-- cpfg's I: scales the unit vector by I / |T| clamped to [-1, 1], then by |T| (its
-- movements.c): the factor on the elasticity of lsys's unit vector.
local function intensity (f)
  if f.I == nil then return nil end
  local len = math.sqrt(f.T[1] ^ 2 + f.T[2] ^ 2 + f.T[3] ^ 2)
  return len * math.max(-1, math.min(1, f.I / len))
end

COMMANDS["tropism"] = function (P, rest, cmd)
  local f = P:fields(rest, cmd, { T = 3, A = 1, E = 1, S = 1, I = 1 }, "T, A, E, S, I")
  if f.T == nil then P:err("'%s' needs the vector T: x y z", cmd) end
  if f.I == 0 then return P:warn("'%s': intensity 0; cpfg leaves this tropism out", cmd) end
  P:addtropism { vector = P:nonzero(f.T, cmd), angle = f.A or 0, elasticity = f.E or 0,
                 increment = f.S or 0, intensity = intensity(f) }
end

COMMANDS["torque"] = function (P, rest, cmd)
  local f = P:fields(rest, cmd, { T = 3, A = 1, E = 1, S = 1, I = 1 }, "T, E, S")
  if f.T == nil then P:err("'%s' needs the vector T: x y z", cmd) end
  if f.A then P:warn("'%s': a torque has no angle; A: ignored", cmd) end
  if f.I == 0 then return P:warn("'%s': intensity 0; cpfg leaves this torque out", cmd) end
  P:addtropism { vector = P:nonzero(f.T, cmd), elasticity = f.E or 0, increment = f.S or 0,
                 torque = true, intensity = intensity(f) }
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
  if utf8.len(w[1]) ~= 1 and utf8.len(w[1]) and w[1]:match("^[%w_.][%w_.-]*%.s$") then
    -- `surface: petal.s 1 4 6` (no name): cpfg reads the name "p" and the file "etal.s",
    -- which it skips when there is no such file (vlab's VlabTools/Lychnis has these)
    local c = w[1]:sub(1, utf8.offset(w[1], 2) - 1)
    local file = w[1]:sub(#c + 1)
    local dir = P.dir or "."
    local f = io.open(file:sub(1, 1) == "/" and file or dir .. "/" .. file, "rb")
    if f == nil then
      return P:warn("'%s': no name before the file '%s': cpfg reads the name '%s' and the "
                    .. "file '%s', which does not exist, and skips the line", cmd, w[1], c, file)
    end
    f:close()
    table.insert(w, 2, file)
    w[1] = c
    if #w > 6 then w[7] = nil end
  end
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
  P.surfaces[#P.surfaces + 1] = { line = P.line, texture = s.texture, name = w[1] }
end

-- opts.missing = "warn": a surface or texture file found neither in `dir` nor in the
-- current folder is left out with a warning, as cpfg carries on without it (its
-- interpret.c, cases 21 and 35): ~X of a missing surface then draws nothing, and the
-- textures after a missing one move down a place, as in cpfg's table of textures; a
-- surface naming a texture past the end is drawn untextured.
local function exists (path)
  local h = io.open(path, "rb")
  if h then h:close() end
  return h ~= nil
end

local function findable (dir, f)
  if f:sub(1, 1) == "/" or dir == nil then return exists(f) end
  return exists((dir:sub(-1) == "/" and dir or dir .. "/") .. f) or exists(f)
end

function Parser:dropmissing (dir)
  local v = self.v
  local kept = {}
  for i, t in ipairs(v.textures or {}) do
    if findable(dir, t.file) then
      kept[#kept + 1] = t
    else
      self.line = self.texlines[i]
      self:warn("'texture': cannot open '%s'; left out, as cpfg does (the textures after it "
                .. "move down a place)", show(t.file))
    end
  end
  if v.textures then v.textures = #kept > 0 and kept or nil end
  for _, s in ipairs(self.surfaces) do
    local sp = v.surfaces and v.surfaces[s.name]
    if sp and not findable(dir, sp.file) then
      self.line = s.line
      self:warn("'surface': cannot open '%s'; ~%s draws nothing (as in cpfg)", show(sp.file),
                s.name)
      v.surfaces[s.name] = nil
    end
  end
  if v.surfaces and next(v.surfaces) == nil then v.surfaces = nil end
  for _, sp in pairs(v.surfaces or {}) do
    if sp.texture and sp.texture > #kept then sp.texture = nil end
  end
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
  if h and (" " .. rest .. " "):find("[%s,:]%?[%s,]") then
    -- a value left as '?' (vlab's exercise templates: "angle increment: ?"): cpfg says
    -- "Invalid parameters" and keeps the value it had (its default)
    self:warn("'%s': '?' is not a value; the line is ignored", cmd)
  elseif h then
    h(self, rest, cmd)
  elseif IGNORED[cmd] then
    self:warn("'%s' is not supported; ignored", cmd)
    self.display[#self.warnings] = cmd
  else
    self:err("unknown view command '%s'", show(cmd))
  end
end

-- `line` without its comments. A /* comment still open at its end sets self.incomment,
-- and self.cline to the line it started on (for the error when it is never closed).
function Parser:uncomment (line)
  local out, pos = {}, 1
  while pos <= #line do
    if self.incomment then
      local e = line:find("*/", pos, true)
      if e == nil then break end
      self.incomment, pos = false, e + 2
      out[#out + 1] = " "
    else
      local c = line:find("/[*/]", pos)
      if c == nil then out[#out + 1] = line:sub(pos); break end
      out[#out + 1] = line:sub(pos, c - 1)
      if line:sub(c + 1, c + 1) == "/" then break end
      self.incomment, self.cline, pos = true, self.line, c + 2
    end
  end
  return table.concat(out)
end

-- What can be checked only at the end of the file: a comment left open, the legacy
-- tropism lines (one tropism from three commands), and the textures that surfaces name.
function Parser:finish ()
  if self.incomment then
    self.line = self.cline
    self:err("the comment that starts here is not closed")
  end
  -- A parallel view (cpfg's default) is fitted to the model's box, centred on it: cpfg
  -- takes only the direction from the viewpoint to the view reference point (defaults
  -- (0, 0, 1) and the origin); a perspective view keeps both points.
  local v0 = self.v
  if (v0.projection or "parallel") == "parallel" and (v0.viewpoint or v0.target) then
    local e, t = v0.viewpoint or { 0, 0, 1 }, v0.target or { 0, 0, 0 }
    local d = { t[1] - e[1], t[2] - e[2], t[3] - e[3] }
    if d[1] ~= 0 or d[2] ~= 0 or d[3] ~= 0 then
      v0.direction, v0.viewpoint, v0.target = d, nil, nil
    end
  end
  -- the old-style tropism, which `_` controls (cpfg's default direction is +y)
  local lg = self.legacy
  if lg.vector or lg.line then
    self.v.old_tropism = { vector = lg.vector or { 0, 1, 0 }, elasticity = lg.elasticity or 0,
                           increment = lg.increment or 0 }
  end
  local v = self.v
  local ntex = v.textures and #v.textures or 0
  for _, s in ipairs(self.surfaces) do
    if s.texture and s.texture > ntex then
      self.line = s.line
      self:err("'surface': texture %d, but the file defines %d texture%s", s.texture, ntex,
               ntex == 1 and "" or "s")
    end
  end
end

--- Reads the text of a cpfg view file into a view table (see `load`). `name` names the
-- file in messages ("view" by default). opts: dir (stored as the view's `dir`), quiet
-- (do not send the warnings to warn()). Returns the view and the list of warnings.
function M.parse (text, name, opts)
  if type(text) ~= "string" then error("lsys.view.parse: the text must be a string", 2) end
  if name ~= nil and type(name) ~= "string" then
    error("lsys.view.parse: the name must be a string", 2)
  end
  if opts ~= nil and type(opts) ~= "table" then
    error("lsys.view.parse: opts must be a table", 2)
  end
  opts = opts or {}
  local P = setmetatable({ name = name or "view", line = 0, v = {}, warnings = {},
                           nlights = 0, legacy = {}, surfaces = {}, texlines = {},
                           display = {}, dir = opts.dir,
                           incomment = false, cline = 0 }, Parser)
  for line in (text .. "\n"):gmatch("([^\n]*)\n") do
    P.line = P.line + 1
    P:command(P:uncomment(line))
  end
  P:finish()
  if opts.missing == "warn" then P:dropmissing(opts.dir) end
  local v = P.v
  if opts.dir ~= nil then v.dir = opts.dir end
  if not opts.quiet then
    for i, w in ipairs(P.warnings) do
      local kind = P.display[i]         -- display-only commands: once per kind and process
      if not (kind and SAID[kind]) then warning.warn(w) end
      if kind then SAID[kind] = true end
    end
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
-- elasticity, elasticity increment, surface, function, function set (or functions).
-- opts.missing = "warn" leaves out, with a warning, a surface or texture file that
-- cannot be found (cpfg's behaviour; lsys.cpfg.load asks for it). Commands listed in
-- VIEWFILE_IGNORED (front distance, z buffer, render mode, ...) are warnings; any other
-- command and any malformed value raise "file.v:LINE: what is wrong". The warnings go
-- to warn() (off in a plain `lua` unless -W; the lsys program shows them) unless
-- opts.quiet. Returns the view and the list of warnings.
function M.load (path, opts)
  if type(path) ~= "string" then error("lsys.view.load: a file name expected", 2) end
  if opts ~= nil and type(opts) ~= "table" then
    error("lsys.view.load: opts must be a table", 2)
  end
  local text, err = readfile(path)
  if text == nil then error("lsys.view.load: " .. err, 0) end
  local dir = path:match("^(.*)/[^/]*$")
  if dir == "" then dir = "/" end
  return M.parse(text, path, { dir = dir or ".", quiet = opts and opts.quiet,
                               missing = opts and opts.missing })
end

return M
