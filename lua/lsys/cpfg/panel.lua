--- vlab's control panels (panel.l, panel.v, panel.a): the items of a panel file and the
-- messages they send, applied as vlab's editors apply them. `read(path)` returns
--
--   { path =, target = (the `target:` line's value, or nil in the older format), name =,
--     background =, size = { w, h }, font =, items = { item, ... } }
--
-- with each item { type = "SLIDER" | "BUTTON" | "LABEL" | "GROUP" | "PAGE" | "MENU",
-- line = (where its `type:` is), name =, origin = { x, y }, colors = { colour, ... },
-- min =, max =, value =, message =, buttons = (a GROUP's button names), page = (the name of
-- the PAGE it follows, or nil) }; a colour is { r, g, b } (0..255) or the number of the
-- older index-mode files. A message is { text =, kind = "d" | "n" | "o" | "line" | nil,
-- define =, format =, scale =, line =, field = } (kind nil: empty or not understood).
--
-- What a message does (vlab's panel program prints the message with the item's integer
-- value through printf; its editors read the printed words):
--   `d NAME V S`     awkped: `#define NAME` gets V / S
--   `n L F S V`      awkped and ped: field F of line L gets V * 10^S
--   `o L V`          field on/off of line L: V is 0 (off) or 1 (on)
--   `L F V S`        awkped: field F of line L gets V / S
-- A slider's value is clamped to its min/max as the panel clamps it. A button sends its
-- message when pressed; a button in a GROUP is the group's one button that is on.
-- Raises "file:line: message" for what is not a panel file.
-- @module lsys.cpfg.panel
local io, table, tonumber, error, format, ipairs, type, tostring, math =
      io, table, tonumber, error, string.format, ipairs, type, tostring, math
local _ENV = nil

local M = {}

local FIELDS = {
  SLIDER = { name = true, colors = true, origin = true, ["min/max"] = true, value = true,
             message = true },
  BUTTON = { name = true, colors = true, tricolor = true, origin = true, value = true,
             message = true },
  LABEL = { name = true, color = true, origin = true },
  PAGE = { name = true, color = true, origin = true, message = true },
  MENU = { name = true, message = true },
}
local NEEDED = {
  SLIDER = { "name", "origin", "min/max", "value", "message" },
  BUTTON = { "name", "origin", "value", "message" },
  LABEL = { "name", "origin" },
  PAGE = { "name", "origin", "message" },
  MENU = { "name", "message" },
}

local function words (s)
  local t = {}
  for w in s:gmatch("%S+") do t[#t + 1] = w end
  return t
end

local function isint (s) return s ~= nil and s:match("^[-+]?%d+$") ~= nil end

-- The words of a message: what kind of edit it is and its parts (the value may be a
-- printf conversion, filled in by apply).
local function message (text)
  local m = { text = text }
  local w = words(text)
  if #w == 0 then return m end
  if w[1] == "d" and #w >= 4 then
    m.kind, m.define, m.format, m.scale = "d", w[2], w[3], tonumber(w[4])
    m.scaletext = w[4]
  elseif w[1] == "n" and #w >= 5 and isint(w[2]) and isint(w[3]) then
    m.kind, m.line, m.field, m.scale, m.format = "n", tonumber(w[2]), tonumber(w[3]),
      tonumber(w[4]), w[5]
    m.scaletext = w[4]
  elseif w[1] == "o" and #w >= 3 and isint(w[2]) then
    m.kind, m.line, m.format = "o", tonumber(w[2]), w[3]
  elseif isint(w[1]) and #w >= 4 and isint(w[2]) then
    m.kind, m.line, m.field, m.format, m.scale = "line", tonumber(w[1]), tonumber(w[2]),
      w[3], tonumber(w[4])
    m.scaletext = w[4]
  end
  return m
end

local function colour (where, s)
  if isint(s) then return tonumber(s) end
  local r, g, b = s:match("^(%d+),(%d+),(%d+)$")
  if not r then error(where .. "a colour 'r,g,b' or a colour index expected, not '" .. s
                      .. "'", 0) end
  return { tonumber(r), tonumber(g), tonumber(b) }
end

local function ints (where, s, n, what)
  local w = words(s)
  if #w ~= n then error(format("%s%d numbers expected for %s", where, n, what), 0) end
  local t = {}
  for i = 1, n do
    if not isint(w[i]) then
      error(format("%san integer expected for %s, not '%s'", where, what, w[i]), 0)
    end
    t[i] = math.tointeger(tonumber(w[i]))
    if not t[i] then error(format("%s%s: '%s' is out of range", where, what, w[i]), 0) end
  end
  return t
end

-- One field of an item, checked as its keyword asks.
local function field (item, key, val, where)
  if key == "name" then item.name = val
  elseif key == "colors" or key == "tricolor" or key == "color" then
    local cs = {}
    for _, w in ipairs(words(val)) do cs[#cs + 1] = colour(where, w) end
    local want = key == "tricolor" and 3 or key == "colors" and 2 or 1
    if #cs ~= want then
      error(format("%s%s: %d colours expected, not %d", where, key, want, #cs), 0)
    end
    item.colors, item.tricolor = cs, key == "tricolor" or nil
  elseif key == "origin" then item.origin = ints(where, val, 2, "origin")
  elseif key == "min/max" then
    local t = ints(where, val, 2, "min/max")
    if t[1] > t[2] then error(format("%smin %d is above max %d", where, t[1], t[2]), 0) end
    item.min, item.max = t[1], t[2]
  elseif key == "value" then item.value = ints(where, val, 1, "value")[1]
  elseif key == "message" then item.message = message(val)
  end
end

local function finish (P, item, name)
  if not item then return end
  for _, k in ipairs(NEEDED[item.type] or {}) do
    local have = k == "min/max" and item.min or item[k]
    if have == nil then
      error(format("%s:%d: the %s has no '%s:'", name, item.line, item.type, k), 0)
    end
  end
  if item.type == "SLIDER" then
    item.default = item.value
    item.value = math.max(item.min, math.min(item.max, item.value))
  end
  if item.type == "GROUP" and not item.closed then
    error(format("%s:%d: the GROUP has no ENDGROUP", name, item.line), 0)
  end
  item.closed = nil
  P.items[#P.items + 1] = item
end

--- Reads a panel file. Returns the panel table described above; raises "file:line: ...".
function M.read (path)
  if type(path) ~= "string" then error("lsys.cpfg.panel.read: a file name expected", 2) end
  local f, err = io.open(path, "rb")
  if not f then error(path .. ": " .. tostring(err), 0) end
  local text = f:read("a")
  f:close()
  local P = { path = path, items = {} }
  local item, page, n = nil, nil, 0
  local header = true
  for raw in (text .. "\n"):gmatch("([^\n]*)\n") do
    n = n + 1
    local s = raw:gsub("\r$", "")
    local where = format("%s:%d: ", path, n)
    if item and item.type == "GROUP" and not item.closed then
      local nm = s:match("^%s*(.-)%s*$")
      if nm == "ENDGROUP" then item.closed = true
      elseif nm ~= "" then
        local c = #item.buttons == 0 and not item.colors and nm:match("^color:%s*(.*)$")
        if c then item.colors = { colour(where, c) }
        else item.buttons[#item.buttons + 1] = nm end
      end
    elseif s:match("^%s*$") then   -- luacheck: ignore 542
      -- a blank line ends nothing by itself: `type:` starts the next item
    else
      local key, val = s:match("^%s*([%a/ ]-):%s?(.*)$")
      if not key then error(where .. "'keyword: value' expected, not '" .. s .. "'", 0) end
      val = val:gsub("%s+$", "")
      if key == "type" then
        finish(P, item, path)
        header = false
        local t = val:match("^(%u+)$")
        if not (FIELDS[t] or t == "GROUP") then
          error(where .. "unknown item type '" .. val .. "'", 0)
        end
        if t == "PAGE" then page = nil end
        item = { type = t, line = n, page = page }
        if t == "GROUP" then item.buttons = {} end
      elseif header then
        if key == "target" then
          if n ~= 1 then error(where .. "'target:' must be the first line", 0) end
          P.target = val
        elseif key == "panel name" then P.name = val
        elseif key == "background" then P.background = colour(where, val)
        elseif key == "size" then
          local t = ints(where, val, 2, "size")
          P.size = t
        elseif key == "font" then P.font = val
        elseif key == "colourmap" then P.colourmap = val
        else error(where .. "unknown panel field '" .. key .. "'", 0) end
      else
        if not (FIELDS[item.type] or {})[key] then
          error(format("%sunknown field '%s' in a %s", where, key, item.type), 0)
        end
        field(item, key, val, where)
        if item.type == "PAGE" and key == "name" then page = val end
      end
    end
  end
  finish(P, item, path)
  if not P.target and not P.name and #P.items == 0 then
    error(path .. ": not a panel file (no 'target:', 'panel name:' nor items)", 0)
  end
  -- a group's names are buttons of its page
  for _, g in ipairs(P.items) do
    if g.type == "GROUP" then
      for _, nm in ipairs(g.buttons) do
        local found
        for _, b in ipairs(P.items) do
          if b.type == "BUTTON" and b.name == nm and b.page == g.page then
            found = true
            b.group = b.group or g
          end
        end
        if not found then
          error(format("%s:%d: the GROUP names no button '%s'", path, g.line, nm), 0)
        end
      end
    end
  end
  return P
end

-- printf of the message's value word with the item's integer value: %d and %i take the
-- value, %% is a percent sign; vlab's messages use nothing else.
local function fill (where, word, v)
  if word == nil then return nil end
  local bad
  local s = word:gsub("%%(.?)", function (c)
    if c == "%" then return "%" end
    if c == "d" or c == "i" then return format("%d", v) end
    bad = c
  end)
  if bad then error(format("%sthe conversion '%%%s' is not supported", where, bad), 0) end
  return s
end

-- awk's number of a word: its leading numeric part, 0 without one.
local function awknum (s)
  local p = s and s:match("^%s*([-+]?%d*%.?%d*[eE][-+]?%d+)") or
            s and s:match("^%s*([-+]?%d*%.?%d*)")
  return tonumber(p) or 0
end

--- What an item's message does with `value` (default: the item's value; a slider's is
-- clamped to its min/max): returns the define's name (nil for an edit by line and field),
-- the number it gets, and the message's table with `line`, `field` and `text` (the text as
-- the panel prints it). Raises for an item without a message or with a scale of 0.
function M.apply (P, item, value)
  if type(item) ~= "table" then error("lsys.cpfg.panel.apply: an item expected", 2) end
  local m = item.message
  local where = format("%s:%d: ", P and P.path or "panel", item.line or 0)
  if not m or not m.kind then
    error(where .. "the " .. tostring(item.type) .. " has no message lsys can apply", 0)
  end
  value = value or item.value or 0
  if math.type(value) ~= "integer" then
    local v = math.tointeger(value)
    if not v then error(where .. "an integer value expected, not " .. tostring(value), 0) end
    value = v
  end
  if item.type == "SLIDER" then value = math.max(item.min, math.min(item.max, value)) end
  local word = fill(where, m.format, value)
  local out = { kind = m.kind, define = m.define, line = m.line, field = m.field,
                text = fill(where, m.text, value) }
  local x
  if m.kind == "n" then
    if not m.scale then error(where .. "the scale '" .. m.scaletext .. "' is not a number", 0) end
    x = awknum(word) * 10.0 ^ m.scale
  elseif m.kind == "o" then
    x = awknum(word)
  else
    if not m.scale then error(where .. "the scale '" .. m.scaletext .. "' is not a number", 0) end
    if m.scale == 0 then error(where .. "the message divides by a scale of 0", 0) end
    x = awknum(word) / m.scale
  end
  local xi = math.tointeger(x)
  if xi then x = xi end
  out.value = x
  return m.define, x, out
end

-- Whether an item sends its message in its current state.
local function sends (item)
  if not item.message or not item.message.kind then return false end
  if item.type == "SLIDER" then return true end
  if item.type == "BUTTON" then
    return item.value == 1 or (item.group == nil and item.value ~= 2 and
                               item.message.format:find("%%[di]") ~= nil)
  end
  return false
end

--- The #defines the panel's items give in their current state: { NAME = value } from each
-- slider and each button that is on (or a lone button whose message carries its value);
-- labels, groups, pages and menus give none. A later item overrides an earlier one.
function M.defines (P)
  local t = {}
  for _, item in ipairs(P.items) do
    if sends(item) and item.message.kind == "d" then
      local k, v = M.apply(P, item)
      t[k] = v
    end
  end
  return t
end

--- A text with the line edits of `edits` made, as vlab's editors make them: each edit is
-- { line = L, field = F, value = x } or { line = L, on = true | false } (the line's on/off
-- word). `editor` "awkped" (the default) counts fields as awk does, the line's words from
-- the first, and joins the edited line's words with single spaces; "ped" counts the words
-- after the line's label (the text up to its first ':'). The value is written as awk
-- prints it. Returns the text and how many lines changed; an edit of a line or field the
-- text does not have changes nothing.
function M.edit_lines (text, edits, editor)
  local by = {}
  for _, e in ipairs(edits) do
    local t = by[e.line]
    if t == nil then t = {}; by[e.line] = t end
    t[#t + 1] = e
  end
  local out, n, changed = {}, 0, 0
  for line, nl in text:gmatch("([^\n]*)(\n?)") do
    n = n + 1
    local list = by[n]
    if list then
      local head, rest = nil, line
      if editor == "ped" then head, rest = line:match("^([^:]*:)(.*)$") end
      if head == nil then head, rest = "", line end
      local w = words(rest)
      local before = line
      for _, e in ipairs(list) do
        if e.on ~= nil then
          for i, x in ipairs(w) do
            if x == "on" or x == "off" then w[i] = e.on and "on" or "off" end
          end
        elseif w[e.field] ~= nil then
          w[e.field] = M.number(e.value)
        end
      end
      line = head .. (head ~= "" and " " or "") .. table.concat(w, " ")
      if line ~= before then changed = changed + 1 end
    end
    out[#out + 1] = line .. nl
    if nl == "" then break end
  end
  return table.concat(out), changed
end

--- The line edits the panel's items give in their current state (messages `n`, `o` and
-- the older `L F V S`), for `edit_lines`.
function M.line_edits (P)
  local t = {}
  for _, item in ipairs(P.items) do
    local m = item.message
    if sends(item) and m.kind ~= "d" then
      local _, v, out = M.apply(P, item)
      if m.kind == "o" then t[#t + 1] = { line = out.line, on = v ~= 0 }
      else t[#t + 1] = { line = out.line, field = out.field, value = v } end
    end
  end
  return t
end

--- The number as awk prints a field it computed: an integer as one, otherwise "%.6g".
function M.number (x)
  if math.type(x) == "integer" then return format("%d", x) end
  if x == math.floor(x) and x > -2^53 and x < 2^53 then return format("%d", math.floor(x)) end
  return format("%.6g", x)
end

--- An L-system text with the `#define NAME value` lines of `defs` ({ NAME = value })
-- rewritten as awkped rewrites them: the third word becomes the value, the line's words
-- joined by single spaces. Returns the text and how many lines changed.
function M.edit (text, defs)
  local out, changed = {}, 0
  for line, nl in text:gmatch("([^\n]*)(\n?)") do
    local w = words(line)
    if w[1] == "#define" and w[2] and defs[w[2]] ~= nil then
      w[3] = M.number(defs[w[2]])
      line = table.concat(w, " ")
      changed = changed + 1
    end
    out[#out + 1] = line .. nl
    if nl == "" then break end
  end
  return table.concat(out), changed
end

--- The panel file's text with the `value:` line of each slider and button giving its
-- current value (what vlab's panel writes when it saves itself); nil and why when the
-- file cannot be read.
function M.text (P)
  local f, err = io.open(P.path, "rb")
  if not f then return nil, err end
  local text = f:read("a")
  f:close()
  local at = {}                 -- the line of each item's `type:` -> its value
  for _, item in ipairs(P.items) do
    if (item.type == "SLIDER" or item.type == "BUTTON") and item.line then
      at[item.line] = item.value
    end
  end
  local out, n, pending = {}, 0, nil
  for line, nl in text:gmatch("([^\n]*)(\n?)") do
    n = n + 1
    if line:match("^%s*type:") then pending = at[n] end
    if pending ~= nil and line:match("^%s*value:") then
      line = line:match("^(%s*value:%s?)") .. M.number(pending) .. (line:match("\r$") or "")
      pending = nil
    end
    out[#out + 1] = line .. nl
    if nl == "" then break end
  end
  return table.concat(out)
end

local function exists (path)
  local f = io.open(path, "rb")
  if f then f:close() end
  return f ~= nil
end

--- The panels of a vlab object's folder: { { panel = path, target = path or nil,
-- editor = "awkped" | "ped" | nil }, ... }, from the `panel FILE | awkped TARGET` commands
-- of its `specifications` file, or else its panel.l, panel.v and panel.a.
function M.find (dir)
  if type(dir) ~= "string" then error("lsys.cpfg.panel.find: a folder expected", 2) end
  local list, seen = {}, {}
  local f = io.open(dir .. "/specifications", "rb")
  if f then
    for line in f:lines() do
      local p, rest = line:match("^%s*panel%s+(%S+)[^|]*|%s*(.*)$")
      if p and not seen[p] and exists(dir .. "/" .. p) then
        local ed, target = rest:match("^(%S+)%s+(%S+)")
        list[#list + 1] = { panel = dir .. "/" .. p, target = target and dir .. "/" .. target,
                            editor = ed }
        seen[p] = true
      end
    end
    f:close()
  end
  if #list == 0 then
    for _, p in ipairs({ "panel.l", "panel.v", "panel.a" }) do
      if exists(dir .. "/" .. p) then list[#list + 1] = { panel = dir .. "/" .. p } end
    end
  end
  return list
end

return M
