--- The component-graph pane of the editing window: the p-graph of a component model
-- (lsys.components) drawn as Lintermann and Deussen 1999 show it in their modeler (section
-- "Component types and their combination", fig. 3: a camera at the root, every link
-- pointing away from it, child links thin, branch links bold, leaf links dashed, the links
-- of a recursion doubled, the return to a recursion's start a dashed copy of that
-- component). A click selects a component; its parameters go to the host's form as items
-- (numbers, flags, choices; ranges as curves for the curve editor); after an edit the host
-- rebuilds the plant with M.rebuild. The pane obeys the panes' interface of lsys.ui.edit:
--
--   local pane = M.new(root_or_model, { on_change =, dot =, seed =, view =, path = })
--   pane:draw(c)  pane:pointer(phase, x, y, button)  pane:scroll(dy)  pane:key(name)
--   pane:items()  pane:selected()  pane:select(proto)  pane:pick(info)  pane:save([path])
--   pane:node_at(x, y)  pane:box(name)           (where a box is, for tests and the host)
--   M.layout(root [, opts])  M.rebuild(root [, opts]) -> Scene  M.save_lua(root, path [, opts])
--
-- Node positions come from Graphviz's `dot -Tplain` when the program runs, else from a
-- layered tree layout of this module (each subtree in a column band of its own, parents
-- centred over their children), so both give boxes that do not overlap.
-- @module lsys.ui.graph
local core = require "lsys.core"
local C = require "lsys.components"
local proto = require "lsys.components.proto"
local G = require "lsys.components.graph"
local lfunc = require "lsys.func"
local W = require "lsys.components.write"

local type, pairs, ipairs, error, tostring, pcall, setmetatable, tonumber =
      type, pairs, ipairs, error, tostring, pcall, setmetatable, tonumber
local io, math, string, table = io, math, string, table
local format, concat = string.format, table.concat
local floor, max, min, abs, sqrt = math.floor, math.max, math.min, math.abs, math.sqrt
local _ENV = nil

local M = {}

-- {=========================================================================================
-- Looks

local TEXT = 2                              -- text scale (the 5 x 7 font, 12 px a character)
local PAD, LINE = 8, 18                     -- inside a box; one text line
local HGAP, VGAP = 16, 34                   -- between boxes side by side; between layers
local MARGIN = 12
M.TEXT, M.HGAP, M.VGAP = TEXT, HGAP, VGAP

local BG = { 0.95, 0.95, 0.95, 1 }
local INK = { 0.1, 0.1, 0.1, 1 }
local GREY = { 0.42, 0.42, 0.42, 1 }
local WHITE = { 1, 1, 1, 1 }
local SELECT_FILL = { 1, 0.9, 0.55, 1 }
local SELECT_EDGE = { 0.1, 0.35, 0.85, 1 }
M.SELECT_FILL = SELECT_FILL

-- A box's border by what the component does: geometry green, the Tree brown, the
-- multipliers blue, the global components violet, the camera grey.
local KIND_COLOUR = {
  simple = { 0.2, 0.55, 0.25, 1 }, revo = { 0.2, 0.55, 0.25, 1 },
  horn = { 0.2, 0.55, 0.25, 1 }, leaf = { 0.2, 0.55, 0.25, 1 },
  tree = { 0.5, 0.32, 0.12, 1 },
  hydra = { 0.15, 0.35, 0.75, 1 }, wreath = { 0.15, 0.35, 0.75, 1 },
  phiball = { 0.15, 0.35, 0.75, 1 },
  ffd = { 0.5, 0.2, 0.6, 1 }, hyperpatch = { 0.5, 0.2, 0.6, 1 }, world = { 0.5, 0.2, 0.6, 1 },
}

-- }=========================================================================================

-- {=========================================================================================
-- The display graph: the p-graph as a tree under the camera

local function textw (s, scale)
  return #s * 6 * scale - scale          -- the canvas's font: 5 px glyphs, 1 px apart
end

-- A display node: its text lines and its box size.
local function dnode (id, p, lines, copy)
  local w = 0
  for _, l in ipairs(lines) do w = max(w, textw(l, TEXT)) end
  return { id = id, proto = p, lines = lines, copy = copy or nil,
           w = w + 2 * PAD, h = #lines * LINE + 2 * PAD - (LINE - 7 * TEXT) }
end

-- The nodes and edges to draw for the p-graph from root: the camera, one node per
-- prototype, a dashed copy for each return to a recursion's start; edges { from, to, type,
-- label, double }; each node's `kids`, the nodes it is the first to reach (a tree).
local function display (root)
  local gnodes = G.nodes(root)
  local cam = dnode("camera", nil, { "camera" })
  cam.camera = true
  local nodes, edges, byg = { cam }, {}, {}
  for _, n in ipairs(gnodes) do
    local p = n.p
    local lines = { n.title }
    if p.name ~= nil and p.name ~= p.kind then lines[2] = p.kind end
    if p.recursive and p.recursion > 1 then lines[#lines + 1] = "recursion " .. p.recursion end
    local d = dnode(n.id, p, lines)
    d.title = n.title
    nodes[#nodes + 1], byg[n] = d, d
  end
  edges[1] = { from = cam, to = byg[gnodes[1]], type = "root" }
  for _, n in ipairs(gnodes) do
    for _, e in ipairs(n.out) do
      local to = byg[e.to]
      if e.back then
        to.copies = (to.copies or 0) + 1
        local d = dnode(format("%sr%d", e.to.id, to.copies), e.to.p, { e.to.title }, true)
        d.title = e.to.title
        nodes[#nodes + 1] = d
        to = d
      end
      edges[#edges + 1] = { from = byg[n], to = to, type = e.type,
                            label = e.type .. (e.label and " " .. e.label or ""),
                            double = n.cyclic and n.comp == e.to.comp or nil }
    end
  end
  for _, d in ipairs(nodes) do d.kids = {} end
  local reached = { [cam] = true }
  -- edges are in preorder of their sources, so a first reach is a tree edge
  for _, e in ipairs(edges) do
    if not reached[e.to] then
      reached[e.to] = true
      e.tree = true
      e.from.kids[#e.from.kids + 1] = e.to
    end
  end
  return nodes, edges, cam
end

-- }=========================================================================================

-- {=========================================================================================
-- Layouts: positions (x, y the top-left corner, in pixels) of every display node

-- The layered layout: depth by tree edges; each subtree gets a band as wide as the larger
-- of its box and its children's bands side by side, so no two boxes overlap.
local function layers (nodes, cam)
  local band = {}
  local function width (d)
    local sum = 0
    for i, k in ipairs(d.kids) do sum = sum + width(k) + (i > 1 and HGAP or 0) end
    band[d] = max(d.w, sum)
    return band[d]
  end
  width(cam)
  local depth_h = {}
  local function depths (d, depth)
    d.depth = depth
    depth_h[depth] = max(depth_h[depth] or 0, d.h)
    for _, k in ipairs(d.kids) do depths(k, depth + 1) end
  end
  depths(cam, 1)
  local top, y = {}, MARGIN
  for i = 1, #depth_h do top[i], y = y, y + depth_h[i] + VGAP end
  local function place (d, left)
    d.x = floor(left + (band[d] - d.w) / 2)
    d.y = top[d.depth] + floor((depth_h[d.depth] - d.h) / 2)
    local sum = -HGAP
    for _, k in ipairs(d.kids) do sum = sum + band[k] + HGAP end
    local x = left + (band[d] - sum) / 2
    for _, k in ipairs(d.kids) do
      place(k, x)
      x = x + band[k] + HGAP
    end
  end
  place(cam, MARGIN)
  for _, d in ipairs(nodes) do
    if d.x == nil then d.x, d.y = MARGIN, y end           -- unreachable: not in a p-graph
  end
end

local dot_missing = {}        -- program -> true once it could not be started

-- The DOT text giving dot the boxes' sizes (points: 1 px = 1 pt) and the edges.
local function dottext (nodes, edges)
  local out = { "digraph layout {",
                format("  graph [rankdir=TB, ordering=out, nodesep=%.3f, ranksep=%.3f];",
                       HGAP / 72, VGAP / 72),
                '  node [shape=box, fixedsize=true, label=""];' }
  for _, d in ipairs(nodes) do
    out[#out + 1] = format("  %s [width=%.4f, height=%.4f];", d.id, d.w / 72, d.h / 72)
  end
  for _, e in ipairs(edges) do
    -- only tree edges constrain the ranks: a cross link would pull a layer apart
    out[#out + 1] = format("  %s -> %s%s;", e.from.id, e.to.id,
                           e.tree and "" or " [constraint=false]")
  end
  out[#out + 1] = "}\n"
  return concat(out, "\n")
end

-- Node centres from `dot -Tplain` (prog the program): true, or nil and why not.
local function dotlayout (prog, nodes, edges)
  if dot_missing[prog] then return nil, "not installed" end
  local dir <close> = core.tempdir(nil, "lsys-graphpane")
  local src = dir:path() .. "/layout.dot"
  core.write_file(src, dottext(nodes, edges))
  local f = io.popen(format("%s -Tplain %s 2>&1", G.quote(prog), G.quote(src)), "r")
  if f == nil then return nil, "cannot start it" end
  local text = f:read("a") or ""
  local _, how, code = f:close()
  dir:remove()
  if how ~= "exit" or code ~= 0 then
    if how == "exit" and (code == 127 or code == 126) then dot_missing[prog] = true end
    return nil, format("%s %s: %s", tostring(how), tostring(code), text:sub(1, 200))
  end
  local byid, height = {}, nil
  for _, d in ipairs(nodes) do byid[d.id] = d end
  for line in text:gmatch("[^\n]+") do
    local gh = line:match("^graph %S+ %S+ (%S+)")
    if gh then height = tonumber(gh) * 72 end
    local id, x, y = line:match("^node (%S+) (%S+) (%S+)")
    if id and byid[id] and height then
      local d = byid[id]
      d.x = floor(tonumber(x) * 72 - d.w / 2 + 0.5) + MARGIN
      d.y = floor(height - tonumber(y) * 72 - d.h / 2 + 0.5) + MARGIN
    end
  end
  for _, d in ipairs(nodes) do
    if d.x == nil then return nil, "no position for " .. d.id end
  end
  return true
end

-- Marks the edges that are alone in the band below their source's layer (their labels can
-- be large).
local function alone (edges)
  local count = {}
  for _, e in ipairs(edges) do
    local k = e.from.y + e.from.h
    count[k] = (count[k] or 0) + 1
  end
  for _, e in ipairs(edges) do e.alone = count[e.from.y + e.from.h] == 1 end
end

--- The layout of the p-graph from `root`: { nodes = { { id, proto, lines, x, y, w, h,
-- copy, camera, title } ... }, edges = { { from, to, type, label, double, tree } ... },
-- width, height, how = "dot" | "layers" }. opts.dot: the dot program ("dot" by default;
-- false: the layered layout always). When dot fails (not installed, a bad program) the
-- layered layout is used and `why` says what happened.
function M.layout (root, opts)
  if not proto.isproto(root) then
    error(format("lsys.ui.graph.layout: a component prototype expected, got %s",
                 type(root)), 2)
  end
  opts = opts or {}
  local prog = opts.dot
  if prog == nil then prog = "dot" end
  if prog ~= false and (type(prog) ~= "string" or prog == "") then
    error("lsys.ui.graph.layout: option 'dot' must be the dot program's name or false", 2)
  end
  local nodes, edges, cam = display(root)
  local how, why = "layers", nil
  if prog then
    local ok, r, msg = pcall(dotlayout, prog, nodes, edges)
    if ok and r then how = "dot"
    else
      why = ok and msg or tostring(r)
      for _, d in ipairs(nodes) do d.x, d.y = nil, nil end
    end
  end
  if how == "layers" then layers(nodes, cam) end
  alone(edges)
  local w, h = 0, 0
  for _, d in ipairs(nodes) do w, h = max(w, d.x + d.w), max(h, d.y + d.h) end
  return { nodes = nodes, edges = edges, width = w + MARGIN, height = h + MARGIN, how = how,
           why = why }
end

-- }=========================================================================================

-- {=========================================================================================
-- Drawing

-- A dashed line from (x0, y0) to (x1, y1).
local function dashed (c, x0, y0, x1, y1, width, colour)
  local len = sqrt((x1 - x0) ^ 2 + (y1 - y0) ^ 2)
  local n = max(1, floor(len / 8))
  for k = 0, n - 1, 2 do
    local a, b = k / n, min(1, (k + 1) / n)
    c:line(x0 + a * (x1 - x0), y0 + a * (y1 - y0), x0 + b * (x1 - x0), y0 + b * (y1 - y0),
           width, colour)
  end
end

local function drawedge (c, e, ox, oy)
  local a, b = e.from, e.to
  local x0, y0 = a.x + a.w / 2 + ox, a.y + a.h + oy
  local x1, y1 = b.x + b.w / 2 + ox, b.y + oy
  local width = e.type == "branch" and 3 or 1
  if e.type == "leaf" then
    dashed(c, x0, y0, x1, y1, width, INK)
  elseif e.double then        -- a recursion: two strokes, white between them
    c:line(x0, y0, x1, y1, width + 4, INK)
    c:line(x0, y0, x1, y1, width + 1, BG)
  else
    c:line(x0, y0, x1, y1, width, INK)
  end
  if e.label == nil then return end
  if e.alone then                   -- the only link between two layers: beside its middle
    c:text((x0 + x1) / 2 + 6, (y0 + y1) / 2 - 7, e.label, TEXT, GREY)
  else
    -- a fan: small labels on a backing, near the child's end where the links are apart
    local lx, ly = x0 + 0.7 * (x1 - x0), y0 + 0.7 * (y1 - y0)
    local w = c:text_width(e.label, 1)
    c:rect(lx - w / 2 - 2, ly - 5, w + 4, 10, BG, true)
    c:text(lx - w / 2, ly - 3, e.label, 1, GREY)
  end
end

local function drawnode (c, d, ox, oy, selected)
  local x, y = d.x + ox, d.y + oy
  local edge = d.camera and GREY or KIND_COLOUR[d.proto.kind] or INK
  c:rect(x, y, d.w, d.h, selected and SELECT_FILL or WHITE, true)
  if d.copy then
    dashed(c, x, y, x + d.w, y, 1, edge)
    dashed(c, x, y + d.h, x + d.w, y + d.h, 1, edge)
    dashed(c, x, y, x, y + d.h, 1, edge)
    dashed(c, x + d.w, y, x + d.w, y + d.h, 1, edge)
  else
    c:rect(x, y, d.w, d.h, edge)
    c:rect(x + 1, y + 1, d.w - 2, d.h - 2, edge)
  end
  if selected then
    c:rect(x - 3, y - 3, d.w + 6, d.h + 6, SELECT_EDGE)
    c:rect(x - 2, y - 2, d.w + 4, d.h + 4, SELECT_EDGE)
  end
  for i, l in ipairs(d.lines) do
    c:text(x + PAD, y + PAD + (i - 1) * LINE, l, TEXT, (i == 1 and not d.copy) and INK or GREY)
  end
end

-- }=========================================================================================

-- {=========================================================================================
-- Parameters as form items

-- The parameters the form shows, kind by kind, in the order of docs/components.md; then
-- the basic ones of every kind.
local SHOWN = {
  simple = {}, revo = {},
  horn = { "length", "radius", "tip", "segments", "curvature", "twist" },
  leaf = { "length", "width", "shape", "lateral", "longitudinal", "phototropism" },
  tree = { "length", "radius", "tip", "segments", "n", "first", "last", "density", "angle",
           "divergence", "deviation", "gnarl", "curvature", "phototropism", "gravitropism",
           "branch_scale" },
  hydra = { "n", "radius", "open", "close", "angle" },
  wreath = { "n", "radius", "open", "close" },
  phiball = { "n", "radius", "open", "close", "child_size", "influence" },
  ffd = { "mode", "isolate" }, hyperpatch = { "mode", "isolate" }, world = {},
}
local BASIC_SHOWN = { "primitive", "scale", "translate", "rotate", "size", "color", "texture" }
M.SHOWN = SHOWN

-- Fixed slider ranges from what a parameter means (degrees, fractions, counts); the rest
-- (lengths, sizes, scales) from the current value: RELATIVE = 0 .. 3 x |value|.
local RANGES = {
  angle = { 0, 180 }, divergence = { 0, 360 }, open = { -360, 360 }, close = { -360, 360 },
  deviation = { -90, 90 }, gnarl = { 0, 45 }, curvature = { -360, 360 },
  twist = { -720, 720 }, rotate = { -180, 180 },
  first = { 0, 1 }, last = { 0, 1 }, tip = { 0, 1 }, influence = { 0, 1 },
  density = { 0.1, 5 }, lateral = { -3, 3 }, longitudinal = { -3, 3 },
  phototropism = { -1, 1 }, gravitropism = { -1, 1 },
  n = { 1, 200 }, segments = { 1, 64 }, texture = { 0, 8 }, color = { 1, 16 },
  recursion = { 1, 12 },
}
local SIGNED = { translate = true }          -- relative ranges that go both ways
local RELATIVE = 3
M.RANGES = RANGES

local function bounds (p, key, v)
  local r = RANGES[key]
  local lo, hi
  if p.kind == "leaf" and key == "phototropism" then r = { 0, 1 } end
  if r then lo, hi = r[1], r[2]
  else
    local a = abs(v)
    hi = a > 0 and RELATIVE * a or 1
    lo = SIGNED[key] and -hi or 0
  end
  local sch = proto.schema(p.kind, key)
  local b = sch and sch[3]
  if type(b) == "table" and type(b[1]) == "number" then
    lo, hi = max(lo, b[1]), min(hi, b[2])
  end
  return min(lo, v), max(hi, v)
end

local function label (key) return (key:gsub("_", " ")) end

--- The range or function of a number parameter as an lsys.Func of the position u
-- (lsys.components.write.tofunc).
M.tofunc = W.tofunc
M.SAMPLES = W.SAMPLES

-- The items of parameter `key` of p (appended to out); `apply(key, v)` sets one.
local function additems (out, p, key, apply)
  local sch = proto.schema(p.kind, key)
  local t, def = sch[1], sch[2]
  local v = p:param(key)
  if t == "enum" then
    out[#out + 1] = { name = key, label = label(key), kind = "choice", value = v,
                      default = def, choices = sch[3],
                      set = function (x) apply(key, x) end }
  elseif t == "boolean" then
    out[#out + 1] = { name = key, label = label(key), kind = "boolean", value = v,
                      default = def, set = function (x) apply(key, x) end }
  elseif t == "integer" then
    if v == nil then return end                  -- a colour not given: the parent's
    local lo, hi = bounds(p, key, v)
    out[#out + 1] = { name = key, label = label(key), kind = "number", value = v,
                      default = def, min = lo, max = hi, step = 1,
                      set = function (x) apply(key, floor(x + 0.5)) end }
  elseif t == "number" then
    if type(v) == "number" then
      local lo, hi = bounds(p, key, v)
      out[#out + 1] = { name = key, label = label(key), kind = "number", value = v,
                        default = def, min = lo, max = hi,
                        set = function (x) apply(key, x) end }
    elseif v ~= nil then
      local f = M.tofunc(p, key)
      if f then
        out[#out + 1] = { name = key, label = label(key) .. " (over the instances)",
                          kind = "curve", func = f,
                          set = function (g)
                            if not lfunc.isfunc(g) then
                              error(format("lsys.ui.graph: %s: '%s': an lsys.Func expected, " ..
                                           "got %s", proto.who(p), key, type(g)), 2)
                            end
                            apply(key, g)
                          end }
      end
    end
  elseif t == "vec3" then
    if type(v) ~= "table" or type(v[1]) ~= "number" then return end    -- a range or function
    for k, axis in ipairs { "x", "y", "z" } do
      local lo, hi = bounds(p, key, v[k])
      out[#out + 1] = { name = key .. "." .. axis, label = label(key) .. " " .. axis,
                        kind = "number", value = v[k], default = def[k], min = lo, max = hi,
                        set = function (x)
                          local w = { v[1], v[2], v[3] }
                          w[k] = x
                          apply(key, w)
                        end }
    end
  end
end

-- }=========================================================================================

-- {=========================================================================================
-- The pane

local Pane = {}
Pane.__index = Pane
M.Pane = Pane

M.HELP = {
  "Component graph: the p-graph of the plant (camera at the top).",
  "Click a box: select that component; its parameters go to the form.",
  "A click on the plant selects the component that made it.",
  "Links: thin child, bold branch, dashed leaf, double a recursion.",
  "Drag the background or scroll: move the graph; Home: back.",
  "Up/Down: parent/first child; Left/Right: previous/next component.",
  "A: add a Leaf as a child; B: add a Tree on a branch link.",
  "L: the selected component's link type (child, branch, leaf).",
  "Delete: remove the selected component and its links.",
}

-- The root prototype and the model options of what the pane edits.
local function target_of (x)
  if proto.isproto(x) then return x, nil end
  if type(x) == "table" and type(x.components) == "table" and
     type(x.components.tree) == "table" and proto.isproto(x.components.tree.root) then
    return x.components.tree.root, x.VIEW
  end
  error(format("lsys.ui.graph.new: a component prototype or a component model expected, " ..
               "got %s", type(x)), 3)
end

local OPTS = { on_change = true, dot = true, seed = true, view = true, path = true,
               detail = true, name = true }

--- A new pane on the p-graph `target` (a root prototype, or a model of
-- lsys.components.model: its graph, and its `VIEW` when it has one). opts: `on_change(what)`
-- (called after every edit: "component" for a parameter, "graph" for links), `dot` (as
-- M.layout), `seed`, `view`, `detail`, `name` (the model's options for M.rebuild and
-- save), `path` (where pane:save() writes the graph as a Lua model file).
function M.new (target, opts)
  local root, view = target_of(target)
  opts = opts or {}
  if type(opts) ~= "table" then error("lsys.ui.graph.new: opts must be a table", 2) end
  for k in pairs(opts) do
    if not OPTS[k] then
      error(format("lsys.ui.graph.new: unknown option '%s' (known: detail, dot, name, " ..
                   "on_change, path, seed, view)", tostring(k)), 2)
    end
  end
  if opts.on_change ~= nil and type(opts.on_change) ~= "function" then
    error("lsys.ui.graph.new: on_change must be a function", 2)
  end
  local self = setmetatable({
    name = "graph", help = M.HELP, root = root, on_change = opts.on_change,
    dot = opts.dot, path = opts.path,
    model_opts = { seed = opts.seed or 1, view = opts.view or view, detail = opts.detail,
                   name = opts.name },
    ox = 0, oy = 0, size = { 420, 700 }, sel = nil,
  }, Pane)
  self.lay = M.layout(root, { dot = self.dot })
  return self
end

function Pane:changed (what)
  if self.on_change then self.on_change(what) end
end

-- The layout again after an edit of the graph.
function Pane:relayout ()
  self.lay = M.layout(self.root, { dot = self.dot })
end

--- The selected prototype, or nil.
function Pane:selected () return self.sel end

--- Selects prototype p (nil: none); true when it is part of the graph (or nil).
function Pane:select (p)
  if p == nil then self.sel = nil return true end
  for _, d in ipairs(self.lay.nodes) do
    if d.proto == p then
      self.sel = p
      return true
    end
  end
  return false
end

-- Where the layout's origin is on a canvas of the last size drawn: centred when narrower.
function Pane:origin ()
  local w = self.size[1]
  local ox = self.lay.width < w and floor((w - self.lay.width) / 2) or 0
  return ox + self.ox, self.oy
end

--- The display node under the canvas pixel (x, y), or nil (a dashed copy stands for its
-- prototype: node.proto).
function Pane:node_at (x, y)
  local ox, oy = self:origin()
  local nodes = self.lay.nodes
  for k = #nodes, 1, -1 do
    local d = nodes[k]
    if x >= d.x + ox and x < d.x + ox + d.w and y >= d.y + oy and y < d.y + oy + d.h then
      return d
    end
  end
  return nil
end

--- The box of the component called `name` (its name, else "kind#k" as graph.dot titles
-- it; "camera" for the root) in canvas pixels: x, y, w, h. Raises on an unknown name.
function Pane:box (name)
  local ox, oy = self:origin()
  for _, d in ipairs(self.lay.nodes) do
    if not d.copy and (d.title == name or d.camera and name == "camera") then
      return d.x + ox, d.y + oy, d.w, d.h
    end
  end
  local names = {}
  for _, d in ipairs(self.lay.nodes) do
    if not d.copy then names[#names + 1] = d.title or "camera" end
  end
  error(format("lsys.ui.graph: no component '%s' (components: %s)", tostring(name),
               concat(names, ", ")), 2)
end

--- Draws the pane into canvas c (any size).
function Pane:draw (c)
  local w, h = c:size()
  self.size = { w, h }
  c:clip()
  c:clear(BG)
  local ox, oy = self:origin()
  for _, e in ipairs(self.lay.edges) do drawedge(c, e, ox, oy) end
  for _, d in ipairs(self.lay.nodes) do
    drawnode(c, d, ox, oy, self.sel ~= nil and d.proto == self.sel)
  end
  local hint = self.sel and "selected: " .. (self.sel.name or self.sel.kind)
                        or "click a component"
  c:rect(0, h - 24, w, 24, { 0.88, 0.88, 0.88, 1 }, true)
  c:text(6, h - 19, hint, TEXT, INK)
end

--- A pointer event: a left or right press on a box selects its component, on the
-- background starts moving the graph.
function Pane:pointer (phase, x, y, button)
  if phase == "down" then
    local d = self:node_at(x, y)
    if d then
      local p = d.proto
      self.sel = p
      self.drag = nil
      return true
    end
    if button == "left" or button == "middle" then self.drag = { x, y, self.ox, self.oy } end
    return false
  elseif phase == "move" and self.drag then
    local dr = self.drag
    self.ox, self.oy = dr[3] + x - dr[1], dr[4] + y - dr[2]
    return true
  elseif phase == "up" then
    self.drag = nil
  end
  return false
end

function Pane:scroll (dy)
  self.oy = self.oy + dy * 40
  return true
end

-- The display nodes of prototypes (not copies, not the camera) in preorder.
function Pane:protonodes ()
  local out = {}
  for _, d in ipairs(self.lay.nodes) do
    if d.proto and not d.copy then out[#out + 1] = d end
  end
  return out
end

-- The first link (its source and index) that leads to p, or nil.
function Pane:parentlink (p)
  for _, d in ipairs(self:protonodes()) do
    for i, l in ipairs(d.proto.links) do
      if l.to == p then return d.proto, i end
    end
  end
  return nil
end

--- Adds a new component of `kind` ("leaf", "tree", ...; its defaults) linked from the
-- selected one (`ltype`: "child", "branch" or "leaf"), selects it and returns it.
function Pane:add (kind, ltype)
  local p = self.sel
  if p == nil then error("lsys.ui.graph: add: select a component first", 2) end
  if proto.KINDS[kind] == nil then
    error(format("lsys.ui.graph: add: unknown kind '%s' (kinds: %s)", tostring(kind),
                 concat(proto.ORDER, ", ")), 2)
  end
  local q = C[kind] {}
  if ltype == "branch" then p:branch(q) elseif ltype == "leaf" then p:leaf(q)
  else p:child(q) end
  self:relayout()
  self.sel = q
  self:changed("graph")
  return q
end

--- Removes the selected component: every link to it (and so the part of the graph only it
-- leads to). The root cannot be removed. Returns true when something was.
function Pane:remove ()
  local p = self.sel
  if p == nil or p == self.root then return false end
  local parent = self:parentlink(p)
  for _, d in ipairs(self:protonodes()) do
    local links = d.proto.links
    for i = #links, 1, -1 do
      if links[i].to == p then table.remove(links, i) end
    end
  end
  self:relayout()
  self.sel = parent
  self:changed("graph")
  return true
end

local NEXT_LINK = { child = "branch", branch = "leaf", leaf = "child" }

--- The type of the link to the selected component: child -> branch -> leaf -> child.
function Pane:cyclelink ()
  local p = self.sel
  local src, i = self:parentlink(p)
  if src == nil then return false end
  local l = src.links[i]
  l.type = NEXT_LINK[l.type]
  self:relayout()
  self:changed("graph")
  return true
end

function Pane:key (name, ctrl)
  if ctrl then return false end                 -- Ctrl+S and the like: the host's
  if name == "home" then self.ox, self.oy = 0, 0 return true end
  if name == "delete" or name == "backspace" then return self:remove() end
  if name == "a" and self.sel then self:add("leaf", "child") return true end
  if name == "b" and self.sel then self:add("tree", "branch") return true end
  if name == "l" then return self:cyclelink() end
  local list = self:protonodes()
  local at
  for i, d in ipairs(list) do if d.proto == self.sel then at = i end end
  if name == "left" or name == "right" then
    at = at and (name == "left" and at - 1 or at + 1) or 1
    if list[at] then self.sel = list[at].proto end
    return true
  elseif name == "up" then
    local src = self.sel and self:parentlink(self.sel)
    if src then self.sel = src end
    return true
  elseif name == "down" then
    local p = self.sel
    if p == nil then self.sel = self.root
    elseif p.links[1] then self.sel = p.links[1].to end
    return true
  end
  return false
end

function Pane:status ()
  local p = self.sel
  if p == nil then
    return format("component graph: %d components; click one to edit it",
                  #self:protonodes())
  end
  return format("%s: %d links%s", proto.who(p), #p.links,
                p.recursive and ", recursion " .. p.recursion or "")
end

--- A click on the plant: selects the prototype of the instance that drew what was hit
-- (lsys.viewer's pick info: `instance`). Returns whether the selection changed.
function Pane:pick (info)
  local inst = type(info) == "table" and info.instance
  local p = type(inst) == "table" and inst.proto
  if not proto.isproto(p) or p == self.sel then return false end
  return self:select(p)
end

--- The selected component's parameters as the form's items (nil when nothing is
-- selected): its kind's numbers and choices, then the basic ones; a range or function as
-- a "curve" item whose `set` stores the edited lsys.Func as the parameter.
function Pane:items ()
  local p = self.sel
  if p == nil then return {} end
  local out = {}
  local function apply (key, v)
    p:set(key, v)
    self:changed("component")
  end
  for _, key in ipairs(SHOWN[p.kind]) do additems(out, p, key, apply) end
  for _, key in ipairs(BASIC_SHOWN) do additems(out, p, key, apply) end
  local view = self.model_opts.view
  if type(view) == "table" and type(view.textures) == "table" then
    for _, it in ipairs(out) do     -- a texture index the view has (0: none)
      if it.name == "texture" then it.max = max(#view.textures, it.value) end
    end
  end
  if p.recursive then
    local r = p.recursion
    out[#out + 1] = { name = "recursion", label = "recursion", kind = "number", value = r,
                      default = 1, min = 1, max = max(12, r), step = 1,
                      set = function (x) apply("recursion", floor(x + 0.5)) end }
  end
  return out
end

--- The plant as the host shows it after an edit: M.rebuild of the pane's graph.
function Pane:rebuild () return M.rebuild(self.root, self.model_opts) end

--- Writes the graph to `path` (default: opts.path of M.new) as a Lua model file
-- (M.save_lua); returns the list of paths written.
function Pane:save (path)
  path = path or self.path
  if path == nil then error("lsys.ui.graph: save: no file to write (give a path)", 2) end
  M.save_lua(self.root, path, self.model_opts)
  return { path }
end

-- }=========================================================================================

-- {=========================================================================================
-- Rebuilding the plant

-- The i-tree of the last rebuild of each root (weak: a root no longer used goes), kept with
-- what it was made from: each prototype's `xversion` (bumped by proto:set for every
-- parameter the expansion reads) and its links, in the order of the graph's walk.
local trees = setmetatable({}, { __mode = "k" })

-- What the expansion of the graph depends on, as a flat list: prototypes, their
-- xversions, their links (type, target, flags).
local function signature (root, seed, maxi)
  local sig = { seed, maxi or false }
  for _, n in ipairs(G.nodes(root)) do
    local p = n.p
    sig[#sig + 1] = p
    sig[#sig + 1] = p.xversion or 0
    sig[#sig + 1] = p.recursion
    for _, l in ipairs(p.links) do
      sig[#sig + 1] = l.type
      sig[#sig + 1] = l.to
      sig[#sig + 1] = l.flags or false
    end
    sig[#sig + 1] = "|"
  end
  return sig
end

local function same (a, b)
  if #a ~= #b then return false end
  for i = 1, #a do if a[i] ~= b[i] then return false end end
  return true
end

-- Whether an emission of the graph draws random numbers: a Lua function (which may call
-- ctx.random) in a parameter the emitter reads. Reusing the i-tree would then give other
-- numbers than a fresh expansion, so it is not reused.
local function drawn_calls (root)
  for _, n in ipairs(G.nodes(root)) do
    for k, v in pairs(n.p.params) do
      if proto.drawn(n.p.kind, k) and (type(v) == "function" or type(v) == "table" and
                                      v.f ~= nil) then
        return true
      end
    end
  end
  return false
end

--- The Scene of the p-graph from `root` (opts: seed, view, detail, name, max_instances as
-- lsys.components.model). When nothing the expansion reads changed since the last rebuild
-- of this root (only parameters of lsys.components.proto.DRAWN were set, through
-- proto:set: a leaf's shape, a stem's radius, colours), the i-tree of that rebuild is
-- drawn again instead of expanding the graph anew: the same scene, sooner. Returns the
-- scene and the model (its `components` as lsys.components.model gives them).
function M.rebuild (root, opts)
  if not proto.isproto(root) then
    error(format("lsys.ui.graph.rebuild: a component prototype expected, got %s",
                 type(root)), 2)
  end
  opts = opts or {}
  local seed = opts.seed or 1
  local sig = signature(root, seed, opts.max_instances)
  local last = trees[root]
  local mo = { seed = seed, view = opts.view, detail = opts.detail, name = opts.name,
               max_instances = opts.max_instances }
  if last and same(last.sig, sig) and not drawn_calls(root) then mo.tree = last.tree end
  local ok, m = pcall(C.model, root, mo)
  if not ok then
    trees[root] = nil
    error((tostring(m):gsub("^[^\n]-:%d+: ", ""):gsub("^lsys%.components%.model:",
          "lsys.ui.graph.rebuild:")), 2)
  end
  trees[root] = { sig = sig, tree = m.components.tree }
  return m:interpret(), m
end

--- Whether the next M.rebuild of `root` (same seed) reuses the i-tree of the last.
function M.reuses (root, opts)
  local last = trees[root]
  return last ~= nil and same(last.sig, signature(root, (opts and opts.seed) or 1,
                                                  opts and opts.max_instances)) and
         not drawn_calls(root)
end

-- }=========================================================================================

-- {=========================================================================================
-- Writing the graph as a Lua model file

--- Writes the p-graph from `root` to `path` as a Lua model file (lsys.components.write.save:
-- opts seed, view, detail, name). Returns path.
function M.save_lua (root, path, opts)
  local ok, r = pcall(W.save, root, path, opts)
  if not ok then error((tostring(r):gsub("^lsys%.components%.write%.save:",
                                           "lsys.ui.graph.save_lua:")), 2) end
  return r
end

-- }=========================================================================================

return M
