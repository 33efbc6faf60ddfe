--- Fuzz target: vlab's control panel files, lsys.cpfg.panel.read, apply and defines.
--
-- The bytes are written to a temporary panel file (removed after each input) and read.
-- Expected errors are strings naming the file ("PATH: ..." or "PATH:LINE: ..."). Checks on
-- what loads: every item has a known type and its line; a slider's value lies in its
-- min/max; a group's buttons are buttons of the panel; apply of every item with a message
-- gives a number (or fails naming the file); defines gives numbers by names; the line
-- edits apply to a text; and reading the file again gives the same table.
local panel = require "lsys.cpfg.panel"

local type, pairs, ipairs, pcall, tostring, error, os_remove, tmpname, open, mathtype =
      type, pairs, ipairs, pcall, tostring, error, os.remove, os.tmpname, io.open, math.type

local T = { maxlen = 2048 }

T.seeds = {
  "target: Lsystem\npanel name: Test\nbackground: 0,0,0\nsize: 200 100\n\n"
    .. "type: SLIDER\nname: Count\ncolors: 1,2,3 4,5,6\norigin: 10 20\nmin/max: -5 50\n"
    .. "value: 7\nmessage: d COUNT %d 10\n",
  "target: Lsystem\n\ntype: BUTTON\nname: On\ntricolor: 9,9,9 0,0,255 0,0,0\n"
    .. "origin: 1 2\nvalue: 1\nmessage: d FLAG 1 1\n\ntype: BUTTON\nname: Off\n"
    .. "colors: 9,9,9 0,0,255\norigin: 1 30\nvalue: 0\nmessage: d FLAG 0 1\n\n"
    .. "type: GROUP\ncolor: 255,255,255\nOn\nOff\nENDGROUP\n",
  "target: Lsystem\n\ntype: LABEL\nname: Title\ncolor: 255,255,0\norigin: 5 5\n",
  "target: Lsystem\n\ntype: PAGE\nname: First\ncolor: 1,1,1\norigin: 3 4\n"
    .. "message: d PAGE %d 1\n\ntype: SLIDER\nname: Rate\norigin: 0 0\nmin/max: 0 9\n"
    .. "value: 3\nmessage: n 12 7 -1 %d\n",
  "target: Lsystem\n\ntype: MENU\nname: Pick\nmessage: d <name> %d <scale>\n",
  "panel name: Old\nsize: 100 100\ntype: SLIDER\nname: a\ncolors: 3 4\norigin: 1 1\n"
    .. "min/max: 0 1\nvalue: 1\nmessage: 4 2 %d 100\n",
  "target: Lsystem\n\ntype: BUTTON\nname: Sw\norigin: 0 0\nvalue: 0\nmessage: o 3 %d\n",
  "target: Lsystem\n\ntype: SLIDER\nname: z\norigin: 0 0\nmin/max: 0 9\nvalue: 1\n"
    .. "message: d Z %d 0\n",
  "target: Lsystem\n\ntype: GROUP\nNone\nENDGROUP\n",
  "target: Lsystem\n\ntype: KNOB\n",
  "type: SLIDER\nname: q\n",
  "",
}

T.dict = { "target: Lsystem\n", "panel name: ", "background: ", "size: ", "font: ",
           "type: ", "SLIDER", "BUTTON", "LABEL", "GROUP", "ENDGROUP", "PAGE", "MENU",
           "name: ", "colors: ", "color: ", "tricolor: ", "origin: ", "min/max: ",
           "value: ", "message: ", "d ", "n ", "o ", "%d", "%i", "%%", "%s", "255,0,0",
           "-1", "0", "1000", "\n", " ", ":" }

local _ENV = nil

local path = tmpname() .. ".l"

function T.clean (err) return type(err) == "string" and err:find(path, 1, true) == 1 end

local last

function T.run (bytes)
  last = nil
  local f = open(path, "wb")
  f:write(bytes)
  f:close()
  local ok, r = pcall(panel.read, path)
  local ok2, r2 = pcall(panel.read, path)
  os_remove(path)
  last = { ok = ok, r = r, ok2 = ok2, r2 = r2 }
  if not ok then error(r, 0) end
end

local function same (a, b, seen)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  seen = seen or {}
  if seen[a] then return true end
  seen[a] = true
  for k, x in pairs(a) do if not same(x, b[k], seen) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

local KINDS = { SLIDER = true, BUTTON = true, LABEL = true, GROUP = true, PAGE = true,
                MENU = true }

local function check (P)
  if type(P) ~= "table" or type(P.items) ~= "table" then return "read returned no items" end
  for i, it in ipairs(P.items) do
    if not KINDS[it.type] then return "item " .. i .. " of type " .. tostring(it.type) end
    if mathtype(it.line) ~= "integer" then return "item " .. i .. " without its line" end
    if it.type == "SLIDER" and not (it.min <= it.value and it.value <= it.max) then
      return "a slider's value outside its min/max"
    end
    if it.group and it.group.type ~= "GROUP" then return "a button in a non-group" end
    if it.message and it.message.kind then
      local ok, name, v = pcall(panel.apply, P, it)
      if ok and type(v) ~= "number" then return "apply gave a " .. type(v) end
      if ok and it.message.kind == "d" and type(name) ~= "string" then
        return "apply of a define gave no name"
      end
      if not ok and not T.clean(name) then return "apply failed: " .. tostring(name) end
    end
  end
  local lok, le = pcall(panel.line_edits, P)
  if not lok then
    if not T.clean(le) then return "line_edits failed: " .. tostring(le) end
  else
    local eok, text = pcall(panel.edit_lines, "a: 1 2 3\nb c: on\n\n", le)
    if not eok or type(text) ~= "string" then return "edit_lines failed: " .. tostring(text) end
    eok, text = pcall(panel.edit_lines, "a: 1 2 3\nb c: on\n", le, "ped")
    if not eok or type(text) ~= "string" then return "edit_lines failed: " .. tostring(text) end
  end
  local ok, d = pcall(panel.defines, P)
  if not ok then
    if not T.clean(d) then return "defines failed: " .. tostring(d) end
    return nil
  end
  for k, v in pairs(d) do
    if type(k) ~= "string" or type(v) ~= "number" then return "defines gave a bad pair" end
  end
  return nil
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  if r.ok ~= r.ok2 or (r.ok and not same(r.r, r.r2)) or (not r.ok and r.r ~= r.r2) then
    return "two reads of one file differ"
  end
  if not r.ok then return nil end
  return check(r.r)
end

return T
