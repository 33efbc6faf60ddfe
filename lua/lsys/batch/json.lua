--- JSON text as lsys.batch writes it in its manifests and stats files: the same bytes for
-- the same value in every process.
-- @module lsys.batch.json
local shortest = require("lsys.util.text").number

local type, pairs, ipairs, error, tostring, setmetatable, getmetatable =
      type, pairs, ipairs, error, tostring, setmetatable, getmetatable
local math, string, table = math, string, table
local format = string.format
local _ENV = nil

local M = {}

-- A number in JSON: integers (and floats with whole values below 2^53) as integers, other
-- numbers in the fewest digits that read back as the same double; NaN and infinities null.
local function jsonnum (x)
  if math.type(x) == "integer" then return format("%d", x) end
  if x ~= x or x == math.huge or x == -math.huge then return "null" end
  return shortest(x)
end

local JSON_ESC = { ['"'] = '\\"', ["\\"] = "\\\\", ["\n"] = "\\n", ["\r"] = "\\r",
                   ["\t"] = "\\t", ["\b"] = "\\b", ["\f"] = "\\f" }
local function jsonstr (s)
  return '"' .. s:gsub('[%c"\\]', function (c)
    return JSON_ESC[c] or format("\\u%04x", c:byte())
  end) .. '"'
end

local ARRAY = {}                      -- the metatable that marks a table as a JSON array
local function array (t) return setmetatable(t, ARRAY) end

-- The order of the keys of JSON objects: these first, in this order; any others after them
-- in byte order. Same table, same text, in every process (lua-cjson follows the order of
-- `next`, which changes from one process to the next, and writes 14 digits).
local KEY_ORDER = {}
for i, k in ipairs { "run", "job", "status", "line", "model", "name", "seed", "steps",
                     "params", "width", "height", "outputs", "format", "path", "bytes",
                     "mtime", "modules", "counts", "triangles", "vertices", "lines", "area",
                     "bounds", "min", "max", "seconds", "phases", "error", "shard", "jobs",
                     "todo", "removed", "ok", "failed", "skipped", "spec", "at", "host", "lsys" } do
  KEY_ORDER[k] = i
end
local function keyless (a, b)
  local ra, rb = KEY_ORDER[a], KEY_ORDER[b]
  if ra and rb then return ra < rb end
  if ra or rb then return ra ~= nil end
  return a < b
end

-- `v` (nil, booleans, numbers, strings, tables: sequences and those marked by `array` as
-- arrays, others objects with string keys) as JSON text on one line, the same bytes for the
-- same value in every process.
local function json (v)
  local t = type(v)
  if v == nil then return "null"
  elseif t == "boolean" then return tostring(v)
  elseif t == "number" then return jsonnum(v)
  elseif t == "string" then return jsonstr(v)
  elseif t ~= "table" then error(format("json: cannot write a %s", t), 2) end
  local parts, keys, n = {}, {}, #v
  for k in pairs(v) do
    if type(k) == "string" then
      keys[#keys + 1] = k
    elseif not (math.type(k) == "integer" and k >= 1 and k <= n) then
      error("json: an object's keys must be strings", 2)
    end
  end
  if getmetatable(v) == ARRAY or (n > 0 and #keys == 0) then
    if #keys > 0 then error("json: an array with other keys", 2) end
    for i = 1, n do parts[i] = json(v[i]) end
    return "[" .. table.concat(parts, ",") .. "]"
  end
  if n > 0 then error("json: a table both a list and an object", 2) end
  table.sort(keys, keyless)
  for i, k in ipairs(keys) do parts[i] = jsonstr(k) .. ":" .. json(v[k]) end
  return "{" .. table.concat(parts, ",") .. "}"
end

M.json, M.array = json, array

return M
