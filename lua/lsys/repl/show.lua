--- How the REPL shows a value (lsys.repl.show): Lstrings abbreviated with their numbers
-- rounded, scenes summarised, tables one level deep, numbers as the `lua` REPL prints them.
-- @module lsys.repl.show
local ismodel = require("lsys.model").ismodel
local inspect = require("lsys.inspect").text
local type, tostring, tonumber, pcall, getmetatable, pairs, next, error =
      type, tostring, tonumber, pcall, getmetatable, pairs, next, error
local math, string, table = math, string, table
local format = string.format
local _ENV = nil

local M = {}

local WIDTH = 60      -- characters of an Lstring shown
local ENTRIES = 20    -- entries of a table shown
local CHARS = 240     -- characters of a table shown (about three lines)
local STRING = 40     -- characters of a string inside a table
local VECTOR = 4      -- a table of at most this many numbers shows inside another
local TABLE_DIGITS = 6      -- significant digits of a float in a table
local LSTRING_DIGITS = 15   -- ... and in an Lstring

local digits = nil    -- set by M.digits: nil for the defaults above

--- Sets the significant digits of the floats the REPL shows in Lstrings and tables:
-- `n` from 1 to 17 (17 shows every value exactly, as `tostring` does: the shortest text that
-- reads back as the same number), or nil for the defaults (15 in Lstrings, 6 in tables).
-- Numbers on their own print as in `lua`, whatever the setting.
function M.digits (n)
  if n ~= nil and (math.type(n) ~= "integer" or n < 1 or n > 17) then
    error("digits: give a whole number from 1 to 17, or nothing for the defaults", 2)
  end
  digits = n
end

local function typename (v)
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__name or nil
end

-- A float with 'd' significant digits (17: the shortest exact text), written as Lua writes
-- floats: with ".0" when it has no point or exponent.
local function float (x, d)
  if x ~= x or x == math.huge or x == -math.huge then return tostring(x) end
  local s
  if d >= 17 then
    for p = 15, 17 do
      s = format("%." .. p .. "g", x)
      if tonumber(s) == x then break end
    end
  else
    s = format("%." .. d .. "g", x)
  end
  if s:find("^-?%d+$") then s = s .. ".0" end
  return s
end

--- A number as the REPL shows it inside a table: integers in full, floats with 6
-- significant digits (or those set by M.digits).
function M.number (x)
  if math.type(x) == "integer" then return tostring(x) end
  return float(x, digits or TABLE_DIGITS)
end

local function num4 (x) return format("%.4g", x) end

-- A scene: its counts and extent.
local function scene_summary (v)
  local ok, s = pcall(function ()
    local lo, hi = v:bounds()
    local ext = lo and format("; x %s..%s, y %s..%s, z %s..%s", num4(lo[1]), num4(hi[1]),
      num4(lo[2]), num4(hi[2]), num4(lo[3]), num4(hi[3])) or "; empty"
    return format("Scene(%d triangles, %d lines, %d turtle records%s)", v.ntriangles,
      v.nlines, v.nrecords, ext)
  end)
  return ok and s or tostring(v)
end

-- An Lstring: its length and the text of its first modules, numbers rounded.
local function lstring_summary (v)
  local n = #v
  local d = digits or LSTRING_DIGITS
  local ok, text = pcall(function ()
    -- convert only a prefix: a million-module string need not become text
    return v:text(1, math.min(n, WIDTH), d < 17 and d or nil)
  end)
  if not ok then text = "?" end
  local more = n > WIDTH or #text > WIDTH
  return format("Lstring(%d module%s): %s%s", n, n == 1 and "" or "s",
    text:sub(1, WIDTH), more and "..." or "")
end

-- A string in a table: quoted, escaped, cut after STRING characters.
local function quote (s)
  local cut = #s > STRING
  if cut then s = s:sub(1, STRING) end
  s = s:gsub('[%c"\\]', function (c)
    local esc = { ["\n"] = "\\n", ["\t"] = "\\t", ["\r"] = "\\r", ['"'] = '\\"',
                  ["\\"] = "\\\\" }
    return esc[c] or format("\\%d", c:byte())
  end)
  return '"' .. s .. (cut and '..."' or '"')
end

local function is_vector (t)
  local n = #t
  if n == 0 or n > VECTOR then return false end
  local count = 0
  for _, x in pairs(t) do
    if type(x) ~= "number" then return false end
    count = count + 1
  end
  return count == n
end

local function has_tostring (v)
  local mt = getmetatable(v)
  return type(mt) == "table" and mt.__tostring ~= nil
end

-- A table inside a table: a short vector of numbers in full, anything else as {...}.
local function inner (t)
  if has_tostring(t) then return tostring(t) end
  if next(t) == nil then return "{}" end
  if is_vector(t) then
    local parts = {}
    for i = 1, #t do parts[i] = M.number(t[i]) end
    return "{ " .. table.concat(parts, ", ") .. " }"
  end
  return "{...}"
end

-- A value inside a table.
local function element (v)
  local tv = type(v)
  if tv == "number" then return M.number(v) end
  if tv == "string" then return quote(v) end
  if tv == "table" then return inner(v) end
  if tv == "function" then return "function" end
  if typename(v) == "lsys.Lstring" then
    local ok, n = pcall(function () return #v end)
    return ok and format("Lstring(%d module%s)", n, n == 1 and "" or "s") or tostring(v)
  end
  if typename(v) == "lsys.Scene" then return "Scene" end
  return tostring(v)
end

local KEYORDER = { number = 1, string = 2, boolean = 3 }

local function keyless (a, b)
  local ta, tb = type(a), type(b)
  if ta ~= tb then return (KEYORDER[ta] or 4) < (KEYORDER[tb] or 4) end
  if ta == "number" or ta == "string" then return a < b end
  return tostring(a) < tostring(b)
end

local function keytext (k)
  if type(k) == "string" and k:find("^[%a_][%w_]*$") then return k end
  if type(k) == "string" then return "[" .. quote(k) .. "]" end
  if type(k) == "number" then return "[" .. M.number(k) .. "]" end
  return "[" .. tostring(k) .. "]"
end

-- A table, one level deep: the list part as values, then the other keys in order, at most
-- ENTRIES entries and about CHARS characters, then how many more there are.
local function table_text (t)
  local n = #t
  local keys = {}
  for k in pairs(t) do
    if not (math.type(k) == "integer" and k >= 1 and k <= n) then keys[#keys + 1] = k end
  end
  table.sort(keys, keyless)
  local total = n + #keys
  if total == 0 then return "{}" end
  local parts, len = {}, 0
  for i = 1, total do
    local part
    if i <= n then part = element(t[i])
    else
      local k = keys[i - n]
      part = keytext(k) .. " = " .. element(t[k])
    end
    if #parts >= ENTRIES or (#parts > 0 and len + #part > CHARS) then
      parts[#parts + 1] = format("... (%d more)", total - #parts)
      break
    end
    parts[#parts + 1] = part
    len = len + #part + 2
  end
  return "{ " .. table.concat(parts, ", ") .. " }"
end

--- How the REPL shows a value: Lstrings as `Lstring(1234 modules): F(0.49)[+F]...` (the
-- first 60 modules, numbers with 15 significant digits), scenes as `Scene(120 triangles, 40
-- lines, 55 turtle records; x -1..1, ...)`, tables without `__tostring` one level deep
-- (`{ 1, 2, a = "x", t = {...} }`, short vectors of numbers in full), anything else as
-- `tostring` shows it (numbers as in `lua`).
function M.show (v)
  local tn = typename(v)
  if type(v) == "userdata" and tn == "lsys.Scene" then return scene_summary(v) end
  if type(v) == "userdata" and tn == "lsys.Lstring" then return lstring_summary(v) end
  if ismodel(v) then return inspect(v) end
  if type(v) == "table" and not has_tostring(v) then
    local ok, s = pcall(table_text, v)
    if ok then return s end
  end
  return tostring(v)
end

return M
