--- What the editing panes edit (lsys.ui.edit's subjects): a Lua model's tunable
-- parameters (lsys.params) and a cpfg model's vlab control panels (lsys.cpfg.panel).
--
-- Saving (Ctrl+S, the form's save button):
--   * a Lua model's values are written back into its file where that is safe: each
--     parameter's declaration `NAME = { value, ...` appears exactly once in the file and
--     its first entry is a literal (a number, true, false or a quoted string without
--     escapes); the file is replaced atomically. Otherwise (a model made by a function,
--     names built at run time) the values go to the sidecar file beside the model,
--     `plant.params` for `plant.lua`: lines `NAME = value`, which loading the model reads
--     (lsys.load; `read_sidecar`) and applies over the declared defaults.
--   * a vlab panel's values are written as vlab's awkped writes them: the `#define` lines
--     of the L-system file (the panel's target) get the values (lsys.cpfg.panel.edit).
-- @module lsys.ui.tune
local core = require "lsys.core"
local panel = require "lsys.cpfg.panel"
local cpfg = require "lsys.cpfg"
local palette = require "lsys.ui.palette"
local curve = require "lsys.ui.curve"
local codegen = require "lsys.codegen"
local form = require "lsys.ui.form"
local graph = require "lsys.ui.graph"

local type, pairs, ipairs, error, pcall, tostring, tonumber, setmetatable =
      type, pairs, ipairs, error, pcall, tostring, tonumber, setmetatable
local math, string, table, io = math, string, table, io
local format = string.format
local _ENV = nil

local M = {}
local unquote

-- {=========================================================================================
-- A Lua model's params

--- The form items of model m's tunable parameters (in the order of `pairs(m.params)`).
function M.param_items (m)
  local items = {}
  if m.params == nil then return items end
  for name in pairs(m.params) do
    local d = m:param(name)
    items[#items + 1] = {
      name = name, label = d.label, kind = d.kind, default = d.default, min = d.min,
      max = d.max, step = d.step, choices = d.choices,
      get = function () return m.params[name] end,
      set = function (v) m.params[name] = v end,
    }
  end
  return items
end

--- A value as a Lua literal that reads back equal.
function M.literal (v)
  if type(v) == "boolean" then return tostring(v) end
  if type(v) == "string" then return codegen.string(v) end
  if math.type(v) == "integer" then return format("%d", v) end
  for _, f in ipairs({ "%.15g", "%.17g" }) do
    local s = format(f, v)
    if math.tointeger(v) and not s:find("[.eEn]") then s = s .. ".0" end
    if tonumber(s) == v then return s end
  end
  return format("%.17g", v)
end

-- The declarations `NAME = { literal` in `text`: the places of the literal (i, j) of each
-- name, or nil and why.
local LITERAL = { "^%-?%d[%w%.+-]*", "^%-?%.%d[%w%.+-]*", "^true%f[^%w_]",
                  "^false%f[^%w_]", '^"[^"\\\n]*"', "^'[^'\\\n]*'" }
local function places (text, names)
  local at = {}
  for _, name in ipairs(names) do
    local found, n = nil, 0
    local init = 1
    while true do
      local s, e = text:find("%f[%w_]" .. name .. "%s*=%s*{%s*", init)
      if s == nil then break end
      if s == 1 or text:sub(s - 1, s - 1) ~= "." then
        n = n + 1
        for _, p in ipairs(LITERAL) do
          local i, j = text:find(p, e + 1)
          if i then found = { i, j } break end
        end
      end
      init = e + 1
    end
    if n ~= 1 then
      return nil, format("'%s = {' appears %d times in the file", name, n)
    end
    if found == nil then return nil, format("the default of '%s' is not a literal", name) end
    at[name] = found
  end
  return at
end

--- The model file's text `text` with the defaults of `values` ({ NAME = v }) rewritten,
-- or nil and why it is not safe.
function M.rewrite (text, values)
  local names = {}
  for k in pairs(values) do names[#names + 1] = k end
  table.sort(names)
  local at, why = places(text, names)
  if at == nil then return nil, why end
  table.sort(names, function (a, b) return at[a][1] > at[b][1] end)   -- from the end
  for _, k in ipairs(names) do
    local p = at[k]
    text = text:sub(1, p[1] - 1) .. M.literal(values[k]) .. text:sub(p[2] + 1)
  end
  return text
end

--- The sidecar file of model file `path`: plant.lua -> plant.params.
function M.sidecar (path)
  return (path:gsub("%.lua$", "")) .. ".params"
end

-- A string as a sidecar line holds it: in double quotes, with \\, \" and \n escaped.
local function quote (v)
  return '"' .. v:gsub('[\\"\n]', { ["\\"] = "\\\\", ['"'] = '\\"', ["\n"] = "\\n" }) .. '"'
end

-- The string of a quoted sidecar value, or nil when it is not one quote writes.
function unquote (v)
  local body = v:sub(2, -2)
  local out, i = {}, 1
  while i <= #body do
    local c = body:sub(i, i)
    if c == '"' then return nil end
    if c == "\\" then
      local e = body:sub(i + 1, i + 1)
      c = e == "\\" and "\\" or e == '"' and '"' or e == "n" and "\n" or nil
      if c == nil then return nil end
      i = i + 1
    end
    out[#out + 1] = c
    i = i + 1
  end
  return table.concat(out)
end

-- The value's text of a line's `NAME = ...` part: a quoted string up to its closing quote,
-- else the words before a `--` comment; nil when something follows a closing quote.
local function value_text (v)
  if v:sub(1, 1) ~= '"' then return (v:gsub("%s*%-%-.*$", "")) end
  local i = 2
  while i <= #v do
    local c = v:sub(i, i)
    if c == "\\" then i = i + 1
    elseif c == '"' then
      local rest = v:sub(i + 1)
      if rest:match("^%s*$") or rest:match("^%s*%-%-") then return v:sub(1, i) end
      return nil
    end
    i = i + 1
  end
  return nil
end

--- A value as a sidecar line writes it (a string quoted as `read_sidecar` reads it).
function M.side_literal (v)
  if type(v) == "string" then return quote(v) end
  return M.literal(v)
end

--- Reads a sidecar's `NAME = value` lines: { NAME = value } (numbers, true, false, quoted
-- strings); raises "file:line: ..." for anything else. Nil when there is no such file.
function M.read_sidecar (path)
  local f = io.open(path, "rb")
  if f == nil then return nil end
  local text = f:read(64 * 1024 + 1) or ""
  f:close()
  if #text > 64 * 1024 then error(format("%s: over 64 kB: not a sidecar file", path), 0) end
  local t, n = {}, 0
  for line in (text .. "\n"):gmatch("([^\n]*)\n") do
    n = n + 1
    local k, v = line:match("^%s*([%a_][%w_]*)%s*=%s*(.-)%s*$")
    if v then v = value_text(v) end
    if k ~= nil or not line:match("^%s*%-%-") and line:match("%S") then
      local x
      if v == "true" then x = true elseif v == "false" then x = false
      elseif v and v:match('^".*"$') then x = unquote(v)
      elseif v then
        x = math.tointeger(v) or (v:match("^[-+%d.eE]+$") and tonumber(v))
        if x and not (x == x and x - x == 0) then x = nil end    -- 1e999: not a value
      end
      if k == nil or x == nil then
        error(format("%s:%d: a line 'NAME = value' expected (a number, true, false or a "
                     .. "quoted string)", path, n), 0)
      end
      t[k] = x
    end
  end
  return t
end

--- Applies a sidecar's values to model m (raising "file: params.R: ..." for a value the
-- model refuses); returns how many.
function M.apply_sidecar (m, values, path)
  local n = 0
  for k, v in pairs(values) do
    if m.params == nil or m:param(k) == nil then
      error(format("%s: the model has no parameter '%s'", path, k), 0)
    end
    local ok, err = pcall(function () m.params[k] = v end)
    if not ok then error(format("%s: %s", path, tostring(err):gsub("^[^\n]-:%d+: ", "")), 0) end
    n = n + 1
  end
  return n
end

--- Saves model m's current values for its file `path`: in the file when safe, else in
-- the sidecar. Returns the message.
function M.save_params (m, path)
  if path == nil then error("the model has no file to save its values to", 0) end
  local values = {}
  for k, v in pairs(m.params) do values[k] = v end
  local f = io.open(path, "rb")
  local text = f and f:read("a")
  if f then f:close() end
  local new, why = nil, "the model file cannot be read"
  if text then new, why = M.rewrite(text, values) end
  if new then
    if new ~= text then core.write_file(path, new) end
    return path
  end
  local side = M.sidecar(path)
  local lines = { codegen.comment("the values lsys view saved for " .. path:match("[^/]*$")
                                  .. " (" .. why .. ")") }
  local names = {}
  for k in pairs(values) do names[#names + 1] = k end
  table.sort(names)
  for _, k in ipairs(names) do lines[#lines + 1] = k .. " = " .. M.side_literal(values[k]) end
  core.write_file(side, table.concat(lines, "\n") .. "\n")
  return side
end

--- The panes beside the form for model m (lsys.ui.edit's subjects): the palette, and
-- those the model's kind has. `changed()` is the session's. A pane that cannot be made
-- for this model (a palette file that cannot be read) is left out; `warn(msg)` hears why.
function M.panes (m, changed, warn)
  local list = {}
  local ok, targets = pcall(curve.targets, m)
  if ok and #targets > 0 then
    local cp
    ok, cp = pcall(curve.new, targets, { on_change = function () changed() end })
    if ok then list[#list + 1] = cp elseif warn then warn(tostring(cp)) end
  elseif not ok and warn then
    warn(tostring(targets))
  end
  local p
  ok, p = pcall(palette.new, m, { on_change = function () changed() end })
  if ok then list[#list + 1] = p elseif warn then warn(tostring(p)) end
  return list
end

-- Sessions by model: the callback m:on_param registers once reaches the current one.
local live = setmetatable({}, { __mode = "k" })

--- The subject (lsys.ui.edit) of Lua model m with params; opts: file (its path, for
-- saving), title, view (view fields over the model's).
function M.params (m, opts)
  opts = opts or {}
  local subject = { title = opts.title, form_title = "parameters" }
  subject.items = function () return M.param_items(m) end
  subject.build = function (check)
    local s = m:derive(m.steps, { progress = function () check() end })
    check()
    return m:interpret(s, opts.view)
  end
  subject.save = function () return M.save_params(m, opts.file) end
  subject.model = m
  subject.panes = M.panes(m, function () local s = live[m]; if s then s:changed() end end)
  subject.attach = function (session)
    if live[m] == nil and m.params ~= nil and #m.params > 0 then
      m:on_param(function () local s = live[m]; if s then s:changed() end end)
    end
    live[m] = session
  end
  subject.stop = function () live[m] = false end
  return subject
end

--- Whether model m is a component graph's (lsys.components.model): its root prototype.
function M.graph_root (m)
  local c = type(m) == "table" and m.components
  local t = type(c) == "table" and c.tree
  return type(t) == "table" and t.root or nil
end

--- The subject of a component graph (lsys.components; Lintermann and Deussen 1999, the
-- p-graph edited as in their modeller): model m made by lsys.components.model. The graph
-- pane comes first, over the selected component's parameters; a click on a box or on the
-- plant selects one, an edit expands the graph again (lsys.ui.graph.rebuild: only the
-- drawing again when only drawn parameters changed). Ctrl+S writes the graph as a Lua
-- model file beside the model's: `NAME-edited.lua` (opts.file: the model file; the
-- hand-written file is never overwritten). opts: file, title.
function M.graph (m, opts)
  opts = opts or {}
  local root = M.graph_root(m)
  if root == nil then error("lsys.ui.tune.graph: a component graph's model expected", 2) end
  local session
  local function changed () if session then session:changed() end end
  local out = opts.file and (opts.file:gsub("%.lua$", "") .. "-edited.lua") or nil
  local c = m.components            -- what the model was made with (not its view, which
  local pane = graph.new(root, {     -- holds the surfaces the emission made)
    on_change = changed, seed = c.seed or m.seed, view = c.view or m.VIEW, detail = c.detail,
    path = out, name = m.name })
  pane:select(root)                  -- its parameters in the form from the start
  local subject = { title = opts.title, form_name = "params", first = pane, model = m }
  subject.panes = {}
  for _, p in ipairs(M.panes(m, changed)) do subject.panes[#subject.panes + 1] = p end
  subject.build = function (check)
    local sc, nm = graph.rebuild(root, pane.model_opts)
    check()
    subject.model = nm
    return sc
  end
  subject.save = function ()
    if out == nil then error("the graph has no model file to save beside", 0) end
    pane:save(out)
    return out .. " (the edited graph as a model file: lsys view it)"
  end
  pane.save = nil                    -- (saved once, through the subject)
  subject.attach = function (s) session = s end
  subject.stop = function () session = nil end
  return subject
end

-- }=========================================================================================

-- {=========================================================================================
-- vlab panels

-- What an item's message does now, for the form: "(NAME value)" for a #define, "(plant.v:20
-- field 1 value)" for a line's field, "(plant.v:3 on)".
local function note (P, it, target)
  local ok, def, y, out = pcall(panel.apply, P, it)
  if not ok then return "(" .. form.bare(def) .. ")" end
  local m = it.message
  if m.kind == "d" then return format("(%s %s)", def, panel.number(y)) end
  local file = (target or "?"):match("([^/]*)$")
  if m.kind == "o" then return format("(%s:%d %s)", file, out.line, y ~= 0 and "on" or "off") end
  return format("(%s:%d field %d %s)", file, out.line, out.field, panel.number(y))
end

-- The items of one panel: its sliders (the panel's integer values, beside them what the
-- message makes of the value) and its buttons (a group's buttons one choice, a lone button
-- a toggle). `target` is the file its line edits change.
local function panel_items (P, target, changed)
  local items, groups = {}, {}
  local function withnote (item, it)
    return setmetatable(item, { __index = function (_, k)    -- the value as it is now
      if k == "note" then return note(P, it, target) end
    end })
  end
  for _, it in ipairs(P.items) do
    local m = it.message
    local sends = m and m.kind ~= nil
    if it.type == "SLIDER" and sends then
      local item = { name = it.name, label = it.name, kind = "number", min = it.min,
                     max = it.max, step = 1, default = it.default or it.value }
      item.get = function () return it.value end
      item.set = function (v) it.value = math.tointeger(v) or math.floor(v + 0.5); changed() end
      items[#items + 1] = withnote(item, it)
    elseif it.type == "BUTTON" and sends then
      if it.group then
        local g = groups[it.group]
        if g == nil then
          local gname = it.group.name or format("group %d", it.group.line or #items + 1)
          g = { name = gname, label = gname, kind = "choice", choices = {}, buttons = {} }
          g.get = function ()
            for k, b in ipairs(g.buttons) do if b.value == 1 then return g.choices[k] end end
            return g.choices[1]
          end
          g.set = function (v)
            for k, b in ipairs(g.buttons) do b.value = g.choices[k] == v and 1 or 0 end
            changed()
          end
          groups[it.group] = g
          items[#items + 1] = g
        end
        g.choices[#g.choices + 1] = it.name
        g.buttons[#g.buttons + 1] = it
        if it.value == 1 then g.default = it.name end
      else
        local item = { name = it.name, label = it.name, kind = "boolean",
                       default = it.value == 1 }
        item.get = function () return it.value == 1 end
        item.set = function (v) it.value = v and 1 or 0; changed() end
        items[#items + 1] = withnote(item, it)
      end
    end
  end
  for _, g in pairs(groups) do g.default = g.default or g.choices[1] end
  return items
end

--- The subject of a cpfg model whose vlab panels drive it. `files` = { l =, v = },
-- `panels` a list of panel tables (lsys.cpfg.panel.read) or of { panel = P, target = the
-- file its messages edit (default the .l file), editor = "awkped" | "ped" }; opts: title,
-- load (the lsys.cpfg.load options besides `edits` and `texts`), model (the model as
-- loaded: its palette and curve panes). A panel's #define messages (`d`) set the .l
-- file's #defines as awkped does, its line messages (`n`, `o`, `L F V S`) the fields of
-- its target's lines as its editor does, both in memory (lsys.cpfg.load's `edits` and
-- `texts`); a panel for a file lsys does not read (an animation file, .a) is left out.
function M.panels (files, panels, opts)
  opts = opts or {}
  local list, skipped = {}, {}
  for _, x in ipairs(panels) do
    local P, target, editor = x, files.l, nil
    if x.panel then P, target, editor = x.panel, x.target or files.l, x.editor end
    if target == files.l or target == files.v then
      list[#list + 1] = { P = P, target = target, editor = editor }
    else skipped[#skipped + 1] = P.path:match("([^/]*)$") .. " (sets " ..
      tostring(target):match("([^/]*)$") .. ")" end
  end
  local subject = { title = opts.title, form_name = "panels",
                    form_title = #list == 1 and list[1].P.name or "vlab panels" }
  local items, session = {}, nil
  local function changed () if session then session:changed() end end
  for _, e in ipairs(list) do
    for _, it in ipairs(panel_items(e.P, e.target, changed)) do items[#items + 1] = it end
  end
  subject.panel_count = #list
  subject.items = items
  if #skipped > 0 then                    -- said in the form's message line
    subject.note = "not shown: " .. table.concat(skipped, ", ") .. ": a file lsys does not read"
  end
  local function readtext (path)
    local f = io.open(path, "rb")
    if f == nil then error(path .. ": cannot be read", 0) end
    local t = f:read("a")
    f:close()
    return t
  end
  -- the #defines of every panel, and the texts its line edits make of their targets
  local function edits ()
    local d, texts, n = {}, {}, 0
    for _, e in ipairs(list) do
      for k, v in pairs(panel.defines(e.P)) do d[k] = v end
      local le = panel.line_edits(e.P)
      if #le > 0 then
        local t, c = panel.edit_lines(texts[e.target] or readtext(e.target), le, e.editor)
        texts[e.target], n = t, n + c
      end
    end
    return d, texts, n
  end
  subject.model = opts.model
  local pal, curves
  if opts.model then
    subject.panes = M.panes(opts.model, changed)
    for _, p in ipairs(subject.panes) do
      if p.name == "palette" then pal = p elseif p.name == "curves" then curves = p end
    end
  end
  subject.load = function ()
    local o = {}
    for k, v in pairs(opts.load or {}) do o[k] = v end
    o.edits, o.texts = edits()
    local m = cpfg.load(files.l, files.v, o)
    if pal and pal.dirty then m.view.palette = pal.view.palette end   -- edited colours
    if curves then curves:retarget(m) end                             -- and curves
    subject.model = m
    return m
  end
  subject.build = function (check)
    local m = subject.load()
    check()
    local s = m:derive(m.steps, { progress = function () check() end })
    check()
    return m:interpret(s)
  end
  subject.save = function ()
    local defs, texts = edits()
    local saved = {}
    local ltext = texts[files.l] or readtext(files.l)
    local new = panel.edit(ltext, defs)
    if new ~= readtext(files.l) then
      core.write_file(files.l, new)
      saved[#saved + 1] = files.l
    end
    if files.v and texts[files.v] and texts[files.v] ~= readtext(files.v) then
      core.write_file(files.v, texts[files.v])
      saved[#saved + 1] = files.v
    end
    for _, e in ipairs(list) do                  -- the panels keep their values too
      local pt = panel.text(e.P)
      if pt then
        core.write_file(e.P.path, pt)
        saved[#saved + 1] = e.P.path
      end
    end
    if #saved == 0 then return "nothing (no value changed)" end
    return table.concat(saved, ", ")
  end
  subject.attach = function (s) session = s end
  subject.stop = function () session = nil end
  return subject
end

-- }=========================================================================================

return M
