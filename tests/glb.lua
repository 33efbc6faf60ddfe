--- A small glTF binary (.glb) reader for the specs, in plain Lua 5.4.
--
--   local glb = require "tests.glb"
--   local doc, bin = glb.read("tree.glb")    -- the JSON chunk as a table, the BIN chunk (or nil)
--   local prims = glb.primitives(doc, bin)   -- per primitive: counts, modes, bounds (see below)
--   local vals, n = glb.accessor(doc, bin, i) -- the numbers of accessor i (0-based), n per element
--   local t = glb.json_decode(text)           -- the JSON decoder on its own
--
-- JSON null decodes to glb.null (so arrays keep their length). Every malformed input raises an
-- error naming what is wrong and where.
local string, math, table = string, math, table
local error, tonumber, setmetatable, pcall = error, tonumber, setmetatable, pcall
local ipairs, pairs = ipairs, pairs
local io, utf8 = io, utf8
local _ENV = nil

local M = {}

M.null = setmetatable({}, { __tostring = function () return "null" end })

-- ---------------------------------------------------------------------------------------------
-- JSON

local escapes = { ['"'] = '"', ["\\"] = "\\", ["/"] = "/", b = "\b", f = "\f", n = "\n", r = "\r",
                  t = "\t" }

local function fail (s, i, what)
  local line = 1
  for _ in s:sub(1, i - 1):gmatch("\n") do line = line + 1 end
  error(("JSON: %s at byte %d (line %d)"):format(what, i, line), 0)
end

local function skip (s, i)
  return s:find("[^ \t\r\n]", i) or #s + 1
end

local value   -- forward

local function str (s, i)           -- s:sub(i, i) == '"'
  local out, j = {}, i + 1
  while true do
    local k = s:find('["\\%c]', j)
    if not k then fail(s, i, "unterminated string") end
    out[#out + 1] = s:sub(j, k - 1)
    local c = s:sub(k, k)
    if c == '"' then return table.concat(out), k + 1 end
    if c ~= "\\" then fail(s, k, "control character in string") end
    local e = s:sub(k + 1, k + 1)
    if e == "u" then
      local h = s:match("^%x%x%x%x", k + 2)
      if not h then fail(s, k, "bad \\u escape") end
      local cp = tonumber(h, 16)
      j = k + 6
      if cp >= 0xD800 and cp <= 0xDBFF then          -- a surrogate pair
        local l = s:match("^\\u(%x%x%x%x)", j)
        local lo = l and tonumber(l, 16)
        if not lo or lo < 0xDC00 or lo > 0xDFFF then fail(s, k, "lone surrogate") end
        cp = 0x10000 + (cp - 0xD800) * 0x400 + (lo - 0xDC00)
        j = j + 6
      end
      out[#out + 1] = utf8.char(cp)
    elseif escapes[e] then
      out[#out + 1] = escapes[e]
      j = k + 2
    else
      fail(s, k, "bad escape")
    end
  end
end

local function obj (s, i)           -- s:sub(i, i) == "{"
  local t = {}
  i = skip(s, i + 1)
  if s:sub(i, i) == "}" then return t, i + 1 end
  while true do
    if s:sub(i, i) ~= '"' then fail(s, i, "expected a string key") end
    local k
    k, i = str(s, i)
    i = skip(s, i)
    if s:sub(i, i) ~= ":" then fail(s, i, "expected ':'") end
    t[k], i = value(s, skip(s, i + 1))
    i = skip(s, i)
    local c = s:sub(i, i)
    if c == "}" then return t, i + 1 end
    if c ~= "," then fail(s, i, "expected ',' or '}'") end
    i = skip(s, i + 1)
  end
end

local function arr (s, i)           -- s:sub(i, i) == "["
  local t, n = {}, 0
  i = skip(s, i + 1)
  if s:sub(i, i) == "]" then return t, i + 1 end
  while true do
    n = n + 1
    t[n], i = value(s, i)
    i = skip(s, i)
    local c = s:sub(i, i)
    if c == "]" then return t, i + 1 end
    if c ~= "," then fail(s, i, "expected ',' or ']'") end
    i = skip(s, i + 1)
  end
end

function value (s, i)
  local c = s:sub(i, i)
  if c == "{" then return obj(s, i)
  elseif c == "[" then return arr(s, i)
  elseif c == '"' then return str(s, i)
  elseif s:find("^true", i) then return true, i + 4
  elseif s:find("^false", i) then return false, i + 5
  elseif s:find("^null", i) then return M.null, i + 4
  end
  local num = s:match("^-?%d+%.?%d*[eE]?[-+]?%d*", i)
  if not num or num == "" or num == "-" then fail(s, i, "unexpected character") end
  local x = tonumber(num)
  if not x or not num:find("^-?0[%.eE]") and num:find("^-?0%d") then fail(s, i, "bad number") end
  return x, i + #num
end

--- Decodes JSON text into Lua values (objects and arrays as tables, null as glb.null).
function M.json_decode (s)
  local v, i = value(s, skip(s, 1))
  i = skip(s, i)
  if i <= #s then fail(s, i, "trailing characters") end
  return v
end

-- ---------------------------------------------------------------------------------------------
-- The container

local MAGIC, JSON, BIN = 0x46546C67, 0x4E4F534A, 0x004E4942

--- Reads a .glb file: returns the decoded JSON chunk, the BIN chunk as a string (nil when
-- absent) and the header { version, length, json_length, bin_length }.
function M.read (path)
  local f, err = io.open(path, "rb")
  if not f then error(err, 2) end
  local data = f:read("a")
  f:close()
  return M.parse(data, path)
end

--- Like glb.read on the bytes of a file ('name' is used in messages).
function M.parse (data, name)
  name = name or "glb"
  if #data < 20 then error(name .. ": too short for a glb", 2) end
  local magic, version, length = string.unpack("<I4I4I4", data)
  if magic ~= MAGIC then error(name .. ": not a glb (bad magic)", 2) end
  if length ~= #data then
    error(("%s: header says %d bytes, the file has %d"):format(name, length, #data), 2)
  end
  local jlen, jtype = string.unpack("<I4I4", data, 13)
  if jtype ~= JSON then error(name .. ": the first chunk is not JSON", 2) end
  if 20 + jlen > #data then error(name .. ": JSON chunk past the end", 2) end
  local ok, doc = pcall(M.json_decode, data:sub(21, 20 + jlen))
  if not ok then error(name .. ": " .. doc, 2) end
  local bin, blen
  local pos = 21 + jlen
  if pos <= #data then
    if pos + 7 > #data then error(name .. ": truncated BIN chunk header", 2) end
    local btype
    blen, btype = string.unpack("<I4I4", data, pos)
    if btype ~= BIN then error(name .. ": the second chunk is not BIN", 2) end
    if pos + 8 + blen - 1 > #data then error(name .. ": BIN chunk past the end", 2) end
    bin = data:sub(pos + 8, pos + 7 + blen)
  end
  return doc, bin, { version = version, length = length, json_length = jlen, bin_length = blen }
end

-- ---------------------------------------------------------------------------------------------
-- Accessors

local COMPONENT = {   -- componentType -> string.unpack format, size
  [5120] = { "<i1", 1 }, [5121] = { "<I1", 1 }, [5122] = { "<i2", 2 }, [5123] = { "<I2", 2 },
  [5125] = { "<I4", 4 }, [5126] = { "<f", 4 },
}
local NCOMP = { SCALAR = 1, VEC2 = 2, VEC3 = 3, VEC4 = 4, MAT2 = 4, MAT3 = 9, MAT4 = 16 }

--- The numbers of accessor 'i' (0-based) as one flat list, and the number per element.
-- Follows bufferView.byteStride; raises if the data lies outside the BIN chunk.
function M.accessor (doc, bin, i)
  local a = doc.accessors and doc.accessors[i + 1]
  if not a then error(("no accessor %s"):format(i), 2) end
  local ct, n = COMPONENT[a.componentType], NCOMP[a.type]
  if not ct or not n then error(("accessor %d: unknown componentType or type"):format(i), 2) end
  local out = {}
  if a.count == 0 then return out, n end
  local bv = doc.bufferViews[a.bufferView + 1]
  if not bv or not bin then error(("accessor %d: no buffer data"):format(i), 2) end
  local fmt, size = ct[1], ct[2]
  local stride = bv.byteStride or n * size
  local base = (bv.byteOffset or 0) + (a.byteOffset or 0)
  local last = base + (a.count - 1) * stride + n * size
  if last > (bv.byteOffset or 0) + bv.byteLength or last > #bin then
    error(("accessor %d: data past the end of its buffer view"):format(i), 2)
  end
  local k = 0
  for e = 0, a.count - 1 do
    local p = base + e * stride + 1
    for c = 0, n - 1 do
      k = k + 1
      out[k] = string.unpack(fmt, bin, p + c * size)
    end
  end
  return out, n
end

local function bounds (vals, n)
  local lo, hi = {}, {}
  for c = 1, n do lo[c], hi[c] = math.huge, -math.huge end
  for k = 1, #vals, n do
    for c = 1, n do
      local x = vals[k + c - 1]
      if x < lo[c] then lo[c] = x end
      if x > hi[c] then hi[c] = x end
    end
  end
  return lo, hi
end

--- One record per primitive of every mesh, in order:
--   { mesh = m, mode = 4, material = k or nil, vertices = POSITION count,
--     indices = index count or nil, triangles = for mode 4, segments = for mode 1,
--     min = {...}, max = {...}  (positions as read from BIN), declared_min, declared_max,
--     attributes = { POSITION = count, NORMAL = count, ... }, max_index = largest index }
function M.primitives (doc, bin)
  local out, cache = {}, {}
  local function read (i)          -- primitives often share their vertex accessors
    if not cache[i] then cache[i] = { M.accessor(doc, bin, i) } end
    return cache[i][1]
  end
  for m, mesh in ipairs(doc.meshes or {}) do
    for _, p in ipairs(mesh.primitives) do
      local mode = p.mode or 4
      local r = { mesh = m - 1, mode = mode, material = p.material, attributes = {} }
      for name, acc in pairs(p.attributes) do r.attributes[name] = doc.accessors[acc + 1].count end
      local pa = doc.accessors[p.attributes.POSITION + 1]
      r.vertices = pa.count
      r.declared_min, r.declared_max = pa.min, pa.max
      r.min, r.max = bounds(read(p.attributes.POSITION), 3)
      local n = r.vertices
      if p.indices then
        local idx = read(p.indices)
        r.indices = #idx
        n = #idx
        local mx = -1
        for k = 1, #idx do if idx[k] > mx then mx = idx[k] end end
        r.max_index = mx
      end
      if mode == 4 then r.triangles = n // 3 elseif mode == 1 then r.segments = n // 2 end
      out[#out + 1] = r
    end
  end
  return out
end

return M
