--- The palette pane of the viewer's editing column: a model's colours (or materials) as a
-- grid of swatches, the one selected shown large with its values, its numbers given to
-- the host's form as items (docs/viewer.md, "Palette pane").
--
-- A palette is what a view's `palette` option names (lsys.view): a cpfg colour map
-- (.map, 256 colours), a material file (.mat, as vlab's medit writes it), a table in the
-- model's Lua view, or lsys.view's default palette. An edit replaces the view's palette
-- with a table of the edited entries, so the model's next interpretation draws with it;
-- `save` writes the palette back in its own format (a table, which a program cannot
-- rewrite in the model's source, goes to a .map or .mat file beside the model).
--
--   local pane = require("lsys.ui.palette").new(model, { on_change = rebuild })
--   pane:draw(canvas); pane:pointer("down", x, y, "left")  -- selects the swatch there
--   for _, it in ipairs(pane:items()) do ... it.set(v) end -- r, g, b (0..255), ...
--   pane:pick(info)        -- selects the colour index the clicked module was drawn with
--   pane:save()            -- { path }: the .map or .mat file written
-- @module lsys.ui.palette
local core = require "lsys.core"
local model = require "lsys.model"
local view = require "lsys.view"
local viewfile = require "lsys.viewfile"

local type, ipairs, pairs, error, tostring, pcall, setmetatable, getmetatable, rawequal =
      type, ipairs, pairs, error, tostring, pcall, setmetatable, getmetatable, rawequal
local math, string, table = math, string, table
local format, char, concat, sort = string.format, string.char, table.concat, table.sort
local floor, min, max, ceil, sqrt = math.floor, math.min, math.max, math.ceil, math.sqrt
local _ENV = nil

local M = {}

M.FIELDS = { "diffuse", "ambient", "specular", "emission" }   -- a material's colours
local RGB = { "red", "green", "blue" }
local BG, INK, GREY = { 0.96, 0.96, 0.96, 1 }, { 0.1, 0.1, 0.1, 1 }, { 0.55, 0.55, 0.55, 1 }
local SELECT = { 0.1, 0.35, 0.95, 1 }
M.MARGIN = 10           -- pixels around the grid
M.MAX_CELL = 56         -- largest swatch of the grid, pixels
M.BIG = 96              -- the selected swatch, pixels

M.help = {
  "Palette: the model's colours (or materials) by colour index.",
  "Click a swatch to select it; its r g b (and a material's fields) are the form's sliders.",
  "A dot marks the indices the plant is drawn with.",
  "Click the plant: selects the colour its module was drawn with.",
  "Arrow keys: move the selection. Ctrl+S writes the palette back (.map or .mat).",
}

local OPTIONS = { on_change = "function", scene = "userdata", name = "string" }

local Pane = {}
Pane.__index = Pane

local function byte (x) return floor(x * 255 + 0.5) end

-- A copy of a checked material (lsys.view.normalize's entries): colour lists copied.
local function copymat (m)
  local out = { shininess = m.shininess }
  for _, k in ipairs(M.FIELDS) do
    local c = m[k]
    if c ~= nil then out[k] = { c[1], c[2], c[3], c[4] } end
  end
  return out
end

-- The palette of view table `v` as lsys.view reads it: {[0] = material, ...}, and its last
-- index. Raises what lsys.view says (a bad file is named).
local function readpalette (v, where)
  local nv = view.normalize({ palette = v.palette, dir = v.dir }, where)
  local p, n = {}, 0
  for i, m in pairs(nv.palette) do
    p[i] = copymat(m)
    if i > n then n = i end
  end
  return p, n
end

-- Whether entry `m` needs a material file: more than a diffuse colour, or transparency.
local function ismaterial (m)
  if m.ambient or m.specular or m.emission or (m.shininess or 0) ~= 0 then return true end
  return m.diffuse[4] ~= nil and m.diffuse[4] ~= 1
end

--- A palette pane on `target`, a model (lsys.lsystem's) or a view table (the model's
-- `view`). opts: `on_change(what)` (called with "palette" after every edit), `scene` (the
-- plant as drawn, for the marks and picks; `set_scene` changes it), `name` (of the file a
-- palette table is saved as, without extension; default the model's name, else
-- "palette"). Raises for another target, an unknown option, or a palette that cannot be
-- read (the message names the file).
function M.new (target, opts)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.ui.palette.new: an options table expected", 2) end
  for k, x in pairs(opts) do
    if OPTIONS[k] == nil then
      error(format("lsys.ui.palette.new: unknown option '%s' (on_change, scene, name)",
                   tostring(k)), 2)
    elseif type(x) ~= OPTIONS[k] then
      error(format("lsys.ui.palette.new: option '%s' must be a %s", k, OPTIONS[k]), 2)
    end
  end
  local m, v
  if model.ismodel(target) then
    m, v = target, target.view
  elseif type(target) == "table" and getmetatable(target) == nil then
    v = target
  else
    error("lsys.ui.palette.new: a model (lsys.lsystem) or a view table expected, got "
          .. type(target), 2)
  end
  if opts.scene ~= nil and not model.isscene(opts.scene) then
    error("lsys.ui.palette.new: option 'scene' must be an lsys.Scene", 2)
  end
  local self = setmetatable({
    name = "palette", help = M.help, model = m, view = v, on_change = opts.on_change,
    filename = opts.name or (m and m.name) or "palette",
    selected = 0, w = 420, h = 700, scene_ = opts.scene, msg = nil, dirty = false,
  }, Pane)
  self:_load()
  -- first selected: the colour the turtle starts with (the view's `color`, default 1)
  self:select(math.tointeger(v.color) or 1)
  return self
end

-- Reads the palette the view names.
function Pane:_load ()
  local v = self.view
  local src = v.palette
  self.file, self.format, self.records, self.src = nil, nil, nil, src
  if type(src) == "string" then
    self.file = view.resolve(v.dir, src)
    self.format = (self.file:match("%.(%w+)$") or ""):lower()
  end
  self.entries, self.last = readpalette(v, self.model and model.where(self.model) or "view")
  if self.format == "mat" then       -- the indices the file has records for, kept by save
    local s = viewfile.readfile(self.file)
    self.records = {}
    for o = 1, #s, 15 do self.records[s:byte(o)] = true end
  end
  self.materials = self.format == "mat"
  if self.format == nil then
    for i = 0, self.last do
      if ismaterial(self.entries[i]) then self.materials = true end
    end
  end
  self.dirty, self.edited, self.used_ = false, {}, nil
end

--- The number of entries (indices 0 .. count - 1); colour index c draws with entry
-- c % count, as the renderer wraps it.
function Pane:count () return self.last + 1 end

--- Entry `i` of the palette: a material { diffuse = {r, g, b[, a]}, ambient =, ... },
-- components 0..1 (the pane's own copy: change it with the items).
function Pane:entry (i) return self.entries[i] end

--- The plant as drawn, for the marks of `used` and for `pick` (the host calls it after
-- each rebuild; nil forgets it: then the model is interpreted when needed).
function Pane:set_scene (scene)
  if scene ~= nil and not model.isscene(scene) then
    error("palette:set_scene: an lsys.Scene expected", 2)
  end
  self.scene_, self.used_ = scene, nil
end

-- The scene to look at: the one set, else the model's interpretation (kept).
function Pane:scene ()
  if self.scene_ == nil and self.model ~= nil then self.scene_ = self.model:interpret() end
  return self.scene_
end

--- The palette entries the plant is drawn with: a sorted list of indices (0 ..
-- count - 1, wrapped as the renderer wraps them) and a set { [i] = triangles and line
-- segments drawn with it }. Empty without a model or scene.
function Pane:used ()
  if self.used_ == nil then
    local set, list = {}, {}
    local sc = self:scene()
    if sc ~= nil then
      local n = self:count()
      for c, k in pairs(sc:colors()) do
        local i = c % n
        if set[i] == nil then list[#list + 1] = i end
        set[i] = (set[i] or 0) + k
      end
    end
    sort(list)
    self.used_ = { list = list, set = set }
  end
  return self.used_.list, self.used_.set
end

-- {=========================================================================================
-- Layout: the grid of swatches, then the selected swatch and its values

-- The text scale of a pane of w x h pixels: 2, or 1 when it is small.
function Pane:scale () return (self.w >= 380 and self.h >= 480) and 2 or 1 end

-- The height of what is drawn below the grid: the selected swatch and its values, the
-- legend, and the big swatch's size.
function Pane:details ()
  local ts = self:scale()
  local big = ts == 2 and M.BIG or M.BIG // 2
  local nlines = self.materials and 7 or 3
  return max(big, 12 * ts + (nlines - 1) * 10 * ts) + 2 * 11 * ts + 12, big
end

-- The grid: columns, rows, cell size, top left; sized to the pane (self.w x self.h).
function Pane:grid ()
  local n, ts = self:count(), self:scale()
  local cols = n > 16 and 16 or max(1, min(n, max(4, ceil(sqrt(n)))))
  local rows = ceil(n / cols)
  local y0 = 7 * ts + 26
  local avail = self.h - y0 - self:details() - M.MARGIN
  local cell = floor(min((self.w - 2 * M.MARGIN) / cols, M.MAX_CELL, avail / rows))
  return cols, rows, max(cell, 6), M.MARGIN, y0
end

--- The rectangle of swatch `i` in the last drawn canvas's pixels (420 x 700 before the
-- first draw): x, y, w, h; nil for an index outside the palette.
function Pane:swatch_rect (i)
  if math.type(i) ~= "integer" or i < 0 or i > self.last then return nil end
  local cols, _, cell, x0, y0 = self:grid()
  return x0 + (i % cols) * cell, y0 + (i // cols) * cell, cell, cell
end

--- The index of the swatch at pixel (x, y), or nil.
function Pane:swatch_at (x, y)
  local cols, rows, cell, x0, y0 = self:grid()
  if x < x0 or y < y0 then return nil end
  local c, r = floor((x - x0) / cell), floor((y - y0) / cell)
  if c >= cols or r >= rows then return nil end
  local i = r * cols + c
  return i <= self.last and i or nil
end

-- {=========================================================================================
-- Drawing

local function luminance (c) return 0.3 * c[1] + 0.59 * c[2] + 0.11 * c[3] end

local function opaque (c) return { c[1], c[2], c[3], 1 } end

-- What the palette is, for the title line.
function Pane:source ()
  local what = self.materials and "materials" or "colours"
  if self.file then
    return format("%s (%d %s)", self.file:match("[^/]*$"), self:count(), what)
  end
  return format("%s (%d %s)", self.view.palette == nil and "default palette" or
                "palette table", self:count(), what)
end

-- The lines of values of entry i: { label, colour or nil, text }.
function Pane:values (i)
  local m = self.entries[i]
  local out = {}
  local function rgb (label, c)
    out[#out + 1] = { label, c, format("%3d %3d %3d", byte(c[1]), byte(c[2]), byte(c[3])) }
    out[#out + 1] = { "", nil, format("%.2f %.2f %.2f", c[1], c[2], c[3]) }
  end
  if not self.materials then
    rgb("rgb", m.diffuse)
    return out
  end
  for _, k in ipairs(M.FIELDS) do
    local c = m[k] or (k == "ambient" and { 0.3 * m.diffuse[1], 0.3 * m.diffuse[2],
                                            0.3 * m.diffuse[3] } or { 0, 0, 0 })
    out[#out + 1] = { k, c, format("%3d %3d %3d", byte(c[1]), byte(c[2]),
                                            byte(c[3])) }
  end
  out[#out + 1] = { "shininess", nil, format("%d", floor((m.shininess or 0) + 0.5)) }
  out[#out + 1] = { "alpha", nil, format("%.2f", m.diffuse[4] or 1) }
  return out
end

-- Draws swatch i: its colour, its number when it fits, the mark of a used index.
function Pane:swatch (c, i, used)
  local x, y, cell = self:swatch_rect(i)
  local col = self.entries[i].diffuse
  c:rect(x, y, cell, cell, opaque(col), true)
  c:rect(x, y, cell, cell, GREY)
  local ink = luminance(col) > 0.5 and INK or { 1, 1, 1, 1 }
  local label = tostring(i)
  local scale = c:text_width(label, 2) + 4 <= cell and cell >= 30 and 2 or 1
  if c:text_width(label, scale) + 3 <= cell and cell >= 10 then
    c:text(x + 2, y + 2, label, scale, ink)
  end
  if used then
    local r = max(2, cell // 7)
    c:circle(x + cell - r - 2, y + cell - r - 2, r, ink)
  end
end

-- Draws the selected entry large at (x0, y) with its values, then the legend.
function Pane:selection (c, y, used)
  local ts = self:scale()
  local _, big = self:details()
  local m = self.entries[self.selected]
  c:rect(M.MARGIN, y, big, big, opaque(m.diffuse), true)
  c:rect(M.MARGIN, y, big, big, INK)
  local x = M.MARGIN + big + 6 * ts
  c:text(x, y, format("index %d%s", self.selected, used and "  (used)" or ""), ts, INK)
  local ly = y + 12 * ts
  for _, l in ipairs(self:values(self.selected)) do
    c:text(x, ly, l[1], ts, GREY)
    if l[2] then
      c:rect(x + 50 * ts, ly - 1, 7 * ts, 7 * ts, opaque(l[2]), true)
      c:rect(x + 50 * ts, ly - 1, 7 * ts, 7 * ts, GREY)
    end
    c:text(x + 60 * ts, ly, l[3], ts, INK)
    ly = ly + 10 * ts
  end
  ly = max(ly, y + big) + 5 * ts
  c:circle(M.MARGIN + 2 * ts, ly + 3 * ts, 2 * ts, INK)
  c:text(M.MARGIN + 8 * ts, ly, "used by the plant", ts, GREY)
  if self.dirty then c:text(M.MARGIN, ly + 11 * ts, "edited: Ctrl+S saves", ts, SELECT) end
end

--- Draws the pane into canvas `c` (any size; it lays itself out to c:size()).
function Pane:draw (c)
  self.w, self.h = c:size()
  c:clear(BG)
  local title = self:source()
  c:text(M.MARGIN, 12, title, c:text_width(title, 2) <= self.w - 2 * M.MARGIN and 2 or 1,
         INK)
  local _, used = self:used()
  local _, rows, cell, _, y0 = self:grid()
  for i = 0, self.last do self:swatch(c, i, used[i]) end
  local x, y = self:swatch_rect(self.selected)     -- the selection, over its neighbours
  for d = 1, 3 do c:rect(x - d, y - d, cell + 2 * d, cell + 2 * d, SELECT) end
  c:rect(x, y, cell, cell, { 1, 1, 1, 1 })
  self:selection(c, y0 + rows * cell + 12, used[self.selected])
end

-- {=========================================================================================
-- Events

--- Selects entry `i` (wrapped into the palette, as a colour index is). Returns it.
function Pane:select (i)
  if math.type(i) ~= "integer" then error("palette:select: a whole number expected", 2) end
  self.selected = i % self:count()
  self.msg = nil
  return self.selected
end

function Pane:pointer (phase, x, y, button)
  if phase ~= "down" or button ~= "left" then return false end
  local i = self:swatch_at(x, y)
  if i == nil or i == self.selected then return false end
  self:select(i)
  return true
end

function Pane.scroll () return false end

local STEP = { left = -1, right = 1 }

function Pane:key (name, ctrl)
  if ctrl then return false end
  local cols = self:grid()
  local d = STEP[name] or (name == "up" and -cols) or (name == "down" and cols)
  if not d then return false end
  local i = self.selected + d
  if i >= 0 and i <= self.last then self:select(i) end
  return true
end

--- One line about the selection: its index, values and use; or what the last save did.
function Pane:status ()
  if self.msg then return self.msg end
  local m = self.entries[self.selected]
  local d = m.diffuse
  local _, used = self:used()
  return format("colour %d of %d: %d %d %d%s%s", self.selected, self:count(), byte(d[1]),
                byte(d[2]), byte(d[3]), self.materials and " (diffuse)" or "",
                used[self.selected] and format(", drawn %d times", used[self.selected]) or
                ", not used by the plant")
end

-- The colour index module `i` of the scene's Lstring was drawn with: its record's, else
-- the turtle's state there (a module that drew nothing).
local function colorof (sc, i)
  local k = sc:find(i)
  if k ~= nil then return sc:record(k).color end
  local _, _, _, _, _, col = sc:turtle(i)
  return col
end

--- A click on the plant (lsys.viewer's pick info: `module`, `lstring`): selects the colour
-- index the module was drawn with. Returns true when it found one.
function Pane:pick (info)
  if type(info) ~= "table" or math.type(info.module) ~= "integer" then return false end
  local sc = self.scene_
  if sc == nil or (info.lstring ~= nil and not rawequal(sc.lstring, info.lstring)) then
    if self.model == nil or info.lstring == nil then return false end
    sc = self.model:interpret(info.lstring)
  end
  local ok, col = pcall(colorof, sc, info.module)
  if not ok or col == nil then return false end
  self:select(col)
  if col ~= self.selected then
    self.msg = format("module %d is drawn in colour index %d: entry %d of %d", info.module,
                      col, self.selected, self:count())
  end
  return true
end

-- {=========================================================================================
-- Items: the selected entry's numbers for the host's form

-- Puts the palette with entry i edited into the view (a table of every entry) and says so.
function Pane:apply (i)
  local p = {}
  for k = 0, self.last do p[k] = copymat(self.entries[k]) end
  self.view.palette = p
  self.dirty, self.msg, self.edited[i] = true, nil, true
  if self.on_change then self.on_change("palette") end
end

-- An item for component k (1..3) of colour `field` of entry i, in bytes 0..255.
function Pane:coloritem (i, field, k, label)
  local m = self.entries[i]
  local c = m[field] or (field == "ambient" and
                         { 0.3 * m.diffuse[1], 0.3 * m.diffuse[2], 0.3 * m.diffuse[3] } or
                         { 0, 0, 0 })
  return {
    name = (self.materials and field .. "." or "") .. ("rgb"):sub(k, k), label = label,
    kind = "number", value = byte(c[k]), default = byte(c[k]), min = 0, max = 255, step = 1,
    set = function (v)
      if type(v) ~= "number" or v ~= v or v < 0 or v > 255 then
        error(format("palette: %s must be a number from 0 to 255", label), 2)
      end
      local e = self.entries[i]
      local cur = e[field] or { c[1], c[2], c[3], e.diffuse[4] }
      cur[k] = v / 255
      e[field] = cur
      self:apply(i)
    end,
  }
end

--- The selected entry's values as number items (pane-api.md): red, green, blue (0..255)
-- of a colour; of a material the four colours' and its shininess (0..128) and alpha
-- (0..1, 1 opaque). Each `set` changes the entry in the model's view and calls on_change.
function Pane:items ()
  local i, out = self.selected, {}
  if not self.materials then
    for k = 1, 3 do out[k] = self:coloritem(i, "diffuse", k, RGB[k]) end
    return out
  end
  for _, f in ipairs(M.FIELDS) do
    for k = 1, 3 do out[#out + 1] = self:coloritem(i, f, k, f .. " " .. RGB[k]) end
  end
  local m = self.entries[i]
  out[#out + 1] = {
    name = "shininess", label = "shininess", kind = "number", value = m.shininess or 0,
    default = m.shininess or 0, min = 0, max = 128, step = 1,
    set = function (v)
      if type(v) ~= "number" or v ~= v or v < 0 or v > 128 then
        error("palette: shininess must be a number from 0 to 128", 2)
      end
      self.entries[i].shininess = v
      self:apply(i)
    end,
  }
  out[#out + 1] = {
    name = "alpha", label = "alpha (1 opaque)", kind = "number", value = m.diffuse[4] or 1,
    default = m.diffuse[4] or 1, min = 0, max = 1, step = 1 / 255,
    set = function (v)
      if type(v) ~= "number" or v ~= v or v < 0 or v > 1 then
        error("palette: alpha must be a number from 0 to 1", 2)
      end
      local e = self.entries[i]
      for _, f in ipairs(M.FIELDS) do
        local c = e[f]
        if c ~= nil then c[4] = v < 1 and v or nil end
      end
      self:apply(i)
    end,
  }
  return out
end

-- {=========================================================================================
-- Writers: .map and .mat

--- The bytes of a cpfg colour map for `p` (entries 0 .. 255 of {diffuse = {r, g, b}}, or
-- fewer: the rest repeat them, as colour indices wrap): 768 bytes.
function M.colormap_bytes (p, last)
  local out = {}
  for i = 0, 255 do
    local d = p[i % (last + 1)].diffuse
    out[i + 1] = char(byte(d[1]), byte(d[2]), byte(d[3]))
  end
  return concat(out)
end

--- The bytes of a cpfg material file for `p`: one 15-byte record per index of `indices`
-- (a sorted list, 0..255): index, transparency, ambient, diffuse, emission, specular
-- (r g b bytes each), shininess; the layout lsys.viewfile.load_materials reads. A
-- colour's alpha a becomes the transparency 255 (1 - a) (the diffuse one's decides).
function M.materials_bytes (p, indices)
  local out = {}
  for _, i in ipairs(indices) do
    local m = p[i]
    local d = m.diffuse
    local amb = m.ambient or { 0.3 * d[1], 0.3 * d[2], 0.3 * d[3] }
    local rec = { i, byte(1 - (d[4] or 1)) }
    for _, c in ipairs { amb, d, m.emission or { 0, 0, 0 }, m.specular or { 0, 0, 0 } } do
      for k = 1, 3 do rec[#rec + 1] = byte(c[k]) end
    end
    rec[15] = floor((m.shininess or 0) + 0.5)
    out[#out + 1] = char(table.unpack(rec))
  end
  return concat(out)
end

--- Writes the palette (atomically) in its file's format next to where it came from: a
-- .map as 768 bytes, a .mat as its records (those the file had and any edited). A table
-- in the model's view becomes NAME.map (colours) or NAME.mat (materials) in the model's
-- folder, and the status says so. Returns the list of paths written; raises naming the
-- file when it cannot be written.
function Pane:save ()
  local path, fmt, note = self.file, self.format, ""
  if path == nil then
    fmt = self.materials and "mat" or "map"
    path = view.resolve(self.view.dir or ".", self.filename .. "." .. fmt)
    note = format(" (the palette is a table in the model: set view.palette = \"%s\" to "
                  .. "use the file)", path:match("[^/]*$"))
  end
  if fmt == "mat" and self.last > 255 then
    error(format("palette: %s: a material file holds indices 0 to 255, the palette has %d",
                 path, self:count()), 0)
  end
  local bytes
  if fmt == "map" then
    bytes = M.colormap_bytes(self.entries, self.last)
    if self.last > 255 then
      note = note .. format("; entries 256 to %d left out (a colour map has 256)", self.last)
    end
  else
    local indices = {}
    for i = 0, self.last do
      if self.records == nil or self.records[i] or self.edited[i] then
        indices[#indices + 1] = i
      end
    end
    bytes = M.materials_bytes(self.entries, indices)
  end
  local ok, err = pcall(core.write_file, path, bytes)
  if not ok then error("palette: " .. tostring(err), 0) end
  if self.file ~= nil then self.view.palette = self.src end    -- the file holds the edits
  self.dirty, self.edited = false, {}
  self.msg = "wrote " .. path .. note
  return { path }
end

return M
