--- Pictures: lsys.render, a Scene, a Model or a component graph's prototype drawn to a PNG
-- file (or to RGBA pixels) offscreen. Every PNG lsys draws goes through here: the library's
-- lsys.render, lsys.frames (one camera box for a series), lsys.batch, the window sessions'
-- exports and the command line.
-- @module lsys.render
local core = require "lsys.core"
local model = require "lsys.model"
local view = require "lsys.view"
local load = require "lsys.load"
local vector = require "lsys.vector"
local suggest = require "lsys.util.suggest"

local type, pairs, error, pcall, tostring, next = type, pairs, error, pcall, tostring, next
local math_type = math.type
local string, table = string, table
local format = string.format
local _ENV = nil

local M = {}

-- Options of lsys.render that are not view options.
local RENDER_ONLY = { out = true, width = true, height = true, view = true, zoom = true,
                      transparent = true, wireframe = true, fit = true, shadows = true,
                      ao = true, ground = true, sky = true }
M.RENDER_ONLY = RENDER_ONLY
local OPTION_NAMES = {}            -- lsys.render's and the view's, for "did you mean"
for k in pairs(RENDER_ONLY) do OPTION_NAMES[#OPTION_NAMES + 1] = k end
for k in pairs(view.KINDS) do OPTION_NAMES[#OPTION_NAMES + 1] = k end
table.sort(OPTION_NAMES)

-- The fields each of the options shadows, ao, ground and sky may have as a table: the check
-- (a number in [lo, hi], an integer when int; "rgb": a colour) and the field it gives core.
local SHADE_FIELDS = {
  shadows = { softness = { 0, 30, "softness" }, strength = { 0, 1, "shadow_strength" },
              threads = { 1, 64, "threads", int = true } },
  ao = { samples = { 1, 1024, "ao_samples", int = true }, strength = { 0, 1, "ao_strength" },
         distance = { 0, 1e300, "ao_distance" }, threads = { 1, 64, "threads", int = true } },
  ground = { color = { "rgb", "ground_color" }, size = { 1e-9, 1000, "ground_size" },
             cells = { 1, 1024, "ground_cells", int = true } },
  sky = { top = { "rgb", "sky_top" }, bottom = { "rgb", "sky_bottom" } },
}

-- A colour {r, g, b} in [0, 1], or nil.
local function rgb (x)
  if type(x) ~= "table" then return nil end
  for i = 1, 3 do
    if type(x[i]) ~= "number" or not (x[i] >= 0 and x[i] <= 1) then return nil end
  end
  return { x[1], x[2], x[3] }
end

-- opts.shadows, ao, ground and sky (true, false or a table of their fields), checked, as
-- core.render's opts.shade (nil when none is on).
local function shade (opts)
  local out, any = {}, false
  for name, fields in pairs(SHADE_FIELDS) do
    local x = opts[name]
    if x ~= nil and x ~= false then
      if x ~= true and type(x) ~= "table" then
        error(format("lsys.render: opts.%s must be true, false or a table", name), 0)
      end
      out[name], any = true, true
      if type(x) == "table" then
        for k, val in pairs(x) do
          local f = fields[k]
          if f == nil then
            error(format("lsys.render: opts.%s: unknown field '%s'", name, tostring(k)), 0)
          elseif f[1] == "rgb" then
            out[f[2]] = rgb(val) or error(format("lsys.render: opts.%s.%s must be a colour "
                                                 .. "{r, g, b} in [0, 1]", name, k), 0)
          elseif type(val) ~= "number" or not (val >= f[1] and val <= f[2])
                 or (f.int and math_type(val) ~= "integer") then
            error(format("lsys.render: opts.%s.%s must be %s in [%g, %g]", name, k,
                         f.int and "an integer" or "a number", f[1], f[2]), 0)
          else out[f[3]] = val end
        end
      end
    end
  end
  return any and out or nil
end

-- lsys.render, raising its errors at `level` (0: without a position).
local function render (level, x, opts, bake)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.render: an options table expected", level) end
  local ext = type(opts.out) == "string" and opts.out:match("%.([%w]+)$")
  ext = ext and ext:lower()
  if ext and ext ~= "png" and not vector.FORMATS[ext] then  -- not under another format's name
    error(format("lsys.render: '%s': unknown picture format '.%s': lsys writes %s",
                 opts.out, ext, vector.KNOWN), level)
  end
  x = load.tomodel(x)                             -- a component graph's root
  local over, drawn = {}, {}
  for k, val in pairs(opts.view or {}) do over[k] = val end
  for k, val in pairs(opts) do
    if view.KINDS[k] then over[k] = val
    elseif not RENDER_ONLY[k] then
      error(format("lsys.render: unknown option '%s'%s", tostring(k),
                   suggest.hint(k, OPTION_NAMES)), level)
    end
  end
  for k, val in pairs(over) do        -- what changes the drawing goes to the turtle
    if view.TURTLE[k] then drawn[k] = val; over[k] = nil end
  end
  if model.ismodel(x) then
    local ok, sc = pcall(x.interpret, x, nil, next(drawn) and drawn or nil)
    if not ok then error(sc, level) end
    x = sc
  elseif next(drawn) and model.isscene(x) then
    error(format("lsys.render: '%s' changes how the turtle draws: render the model, or "
                 .. "interpret it with the option (m:interpret(s, { %s = ... }))",
                 next(drawn), next(drawn)), level)
  end
  if not model.isscene(x) then
    error("lsys.render: a Scene, a Model or a component prototype expected", level)
  end
  -- the scene keeps its camera, light, background and textures; a render that changes
  -- them passes the whole view they make with the scene's own
  local v = model.sceneview(x)
  local ro = { supersample = v and v.supersample }
  if next(over) then
    local ok, r = pcall(view.normalize, view.merge(v or view.normalize({}, "lsys.render"), over),
                        "lsys.render")
    if not ok then error(r, level) end
    ro = view.render_options(r)
    -- a scene without a view of its own keeps the camera and light it was given in C
    -- (scene:look, a grown world's view): only the fields named here replace them
    if v == nil then
      for k in pairs(ro) do
        if over[k] == nil then ro[k] = nil end
      end
    end
  end
  ro.out, ro.width, ro.height = opts.out, opts.width or 800, opts.height or 800
  ro.zoom, ro.transparent, ro.wireframe = opts.zoom, opts.transparent, opts.wireframe
  ro.fit = opts.fit
  if ext and vector.FORMATS[ext] then   -- (drawn flat: no shading)
    local ok, err = pcall(vector.write, x, ro, ext)
    if not ok then error(err, level) end
    return true
  end
  local sok, sh = pcall(shade, opts)
  if not sok then error(sh, level) end
  ro.shade = sh
  local ok, a, b, c = pcall(bake and core.bake or core.render, x, ro)
  if not ok then error(a, level) end
  return a, b, c
end

--- Renders `x` (a Scene, a Model: derived and interpreted, or a component graph's root
-- prototype: made a Model) to a PNG file, or with `out` naming a .svg, .eps or .pdf file to
-- a vector picture of the same framing (lsys.vector).
-- opts: out (the path; without it the RGBA pixels are returned as a string, plus
-- width and height), width, height (800), zoom (1: magnifies about the centre),
-- transparent (a transparent background, RGBA PNG), wireframe, fit (a box {x0, y0, z0, x1,
-- y1, z1} the camera frames instead of the scene: one camera for a series of pictures of a
-- growing plant), shadows, ao, ground, sky (true or a table of their settings: baked shadows
-- of the key light, ambient occlusion, a ground plane, a sky gradient; docs/drawing.md), and
-- view fields (camera,
-- background, light, supersample) that replace the scene's view for this picture;
-- `opts.view` may hold them. Raises blaming its caller.
--- Whether `scene` draws a 3D plant: triangles, and a box deep in every direction (at
-- least 1/20 of its largest extent), so that a flat drawing in a plane is not one. `lsys
-- render` and the gallery shade such a picture: `M.shaded(scene, opts)`.
function M.solid (scene)
  if scene.ntriangles == 0 then return false end
  local lo, hi = scene:bounds()
  if type(lo) ~= "table" then return false end
  local d = { hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3] }
  local big = d[1] > d[2] and d[1] or d[2]
  big = big > d[3] and big or d[3]
  return d[1] >= big / 20 and d[2] >= big / 20 and d[3] >= big / 20
end

--- Whether the scene's view has a background of its own (not lsys.view's default): then
-- `lsys render` and the window draw no sky behind it.
function M.ownbackground (scene)
  local v = model.sceneview(scene)
  local b, d = v and v.background, view.DEFAULTS.background
  if type(b) ~= "table" then return false end
  return b[1] ~= d[1] or b[2] ~= d[2] or b[3] ~= d[3]
end

--- The render options `opts` with the shading `lsys render` gives a 3D plant (M.solid):
-- shadows and a ground, and a sky unless the picture has a background of its own (the
-- scene's view gives one, or `background` is true: one was given for this picture).
-- Options already set stay. Returns opts.
function M.shaded (scene, opts, background)
  if M.solid(scene) then
    if opts.shadows == nil then opts.shadows = true end
    if opts.ground == nil then opts.ground = true end
    if opts.sky == nil and not background and not M.ownbackground(scene) then opts.sky = true end
  end
  return opts
end

function M.render (x, opts)
  local a, b, c = render(3, x, opts)    -- 3: the caller of this function
  return a, b, c
end

--- The Scene `x` (or a Model, interpreted) as M.render draws it with `opts`' shadows, ao
-- and ground, baked: a new Scene with the ground in its mesh and each vertex's shading in
-- its colour (its palette grows 16 steps of each colour), for the window, which draws no
-- shadows of its own (`lsys view --shadows`); a population's plants are written out.
-- opts: those of M.render but `out`; width and height (800) are the picture's whose
-- camera the ground grows to. Raises blaming its caller.
function M.bake (x, opts)
  if opts ~= nil and type(opts) == "table" and opts.out ~= nil then
    error("lsys.render.bake: opts.out: bake makes a Scene, it writes no file", 2)
  end
  return (render(3, x, opts, true))
end

--- As M.render, raising its errors without a position: for callers that put their own
-- name in front of the message (lsys.frames) or record it (lsys.batch).
function M.draw (x, opts)
  local a, b, c = render(0, x, opts)
  return a, b, c
end

return M
