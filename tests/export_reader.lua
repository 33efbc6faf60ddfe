--- Readers of the OBJ, MTL and PLY files that lsys writes, for the specs (plain Lua 5.4).
--
--   local R = require "tests.export_reader"
--   local o = R.obj("tree.obj")   -- counts: o.v o.vn o.vt o.f o.l, o.materials, o.mtllib, ...
--                                 -- and the values: o.vs[i] = {x,y,z}, o.vts[i] = {u,v}
--   local mt = R.mtl("tree.mtl")  -- mt.names = { "m0", ... }; mt.m0.Kd = { r, g, b }, ...
--   local p = R.ply("tree.ply")   -- p.counts.vertex, p.counts.face, p.first_vertex.x, ...
--
-- Malformed files raise an error naming the file and the line or byte.
local string, math = string, math
local error, tonumber, ipairs, io = error, tonumber, ipairs, io
local _ENV = nil

local M = {}

local function lines (path)
  local f, err = io.open(path, "rb")
  if not f then error(err, 3) end
  local text = f:read("a")
  f:close()
  return text
end

local function nums (rest, path, ln)
  local t = {}
  for w in rest:gmatch("%S+") do
    local x = tonumber(w)
    if not x then error(("%s:%d: bad number '%s'"):format(path, ln, w), 4) end
    t[#t + 1] = x
  end
  return t
end

--- Counts the elements of an OBJ file. Returns a table with
--   v, vn, vt, f, l          numbers of each statement
--   triangles                faces with exactly 3 corners
--   usemtl                   number of usemtl statements; materials = names in order
--   faces_by_material, lines_by_material   name -> count ("" before any usemtl)
--   mtllib                   the file name given, or nil
--   first_v                  { x, y, z } of the first 'v'
--   max_v, max_vn, max_vt    largest index that faces and lines refer to (1-based; 0 if none)
-- Raises on an index out of range or an unknown statement.
function M.obj (path)
  local text = lines(path)
  local r = { v = 0, vn = 0, vt = 0, f = 0, l = 0, triangles = 0, usemtl = 0, materials = {},
              faces_by_material = {}, lines_by_material = {}, max_v = 0, max_vn = 0, max_vt = 0,
              vs = {}, vts = {} }
  local cur, ln = "", 0
  local last = {}                  -- kind -> line of the largest index
  -- A negative index counts back from the elements read so far; a positive one may refer
  -- forward (checked at the end).
  local function ref (l, kind, s)
    if s == "" then return end
    local i = tonumber(s)
    if i < 0 then i = r[kind] + 1 + i end
    if i < 1 then error(("%s:%d: %s index %s out of range"):format(path, l, kind, s), 3) end
    if i > r["max_" .. kind] then r["max_" .. kind], last[kind] = i, l end
  end
  for line in text:gmatch("([^\n]*)\n?") do
    ln = ln + 1
    line = line:gsub("\r$", "")
    local tag, rest = line:match("^%s*(%S+)%s*(.-)%s*$")
    if tag == nil or tag:sub(1, 1) == "#" then
      -- blank or comment
    elseif tag == "v" or tag == "vn" or tag == "vt" then
      local t = nums(rest, path, ln)
      local want = tag == "vt" and 2 or 3
      if #t < want then error(("%s:%d: '%s' needs %d numbers"):format(path, ln, tag, want), 2) end
      r[tag] = r[tag] + 1
      if tag == "v" and not r.first_v then r.first_v = { t[1], t[2], t[3] } end
      if tag == "v" then r.vs[r.v] = { t[1], t[2], t[3] } end
      if tag == "vt" then r.vts[r.vt] = { t[1], t[2] } end
    elseif tag == "f" or tag == "l" then
      local n = 0
      for corner in rest:gmatch("%S+") do
        n = n + 1
        local a, b, c = corner:match("^(-?%d+)/?(-?%d*)/?(-?%d*)$")
        if not a then error(("%s:%d: bad corner '%s'"):format(path, ln, corner), 2) end
        ref(ln, "v", a)
        ref(ln, "vt", b)
        ref(ln, "vn", c)
      end
      if n < (tag == "f" and 3 or 2) then error(("%s:%d: too few corners"):format(path, ln), 2) end
      r[tag] = r[tag] + 1
      local by = tag == "f" and r.faces_by_material or r.lines_by_material
      by[cur] = (by[cur] or 0) + 1
      if tag == "f" and n == 3 then r.triangles = r.triangles + 1 end
    elseif tag == "usemtl" then
      r.usemtl = r.usemtl + 1
      cur = rest
      r.materials[#r.materials + 1] = rest
    elseif tag == "mtllib" then
      r.mtllib = rest
    elseif tag == "o" or tag == "g" or tag == "s" then
      -- names and smoothing groups: ignored
    else
      error(("%s:%d: unknown statement '%s'"):format(path, ln, tag), 2)
    end
  end
  for _, kind in ipairs { "v", "vt", "vn" } do
    if r["max_" .. kind] > r[kind] then
      error(("%s:%d: %s index %d out of range (%d)"):format(path, last[kind], kind,
            r["max_" .. kind], r[kind]), 2)
    end
  end
  return r
end

--- Reads an MTL file: a table name -> { Ka = {..}, Kd = {..}, Ks, Ke, Ns = x, d = x,
-- illum = n }, plus names = the material names in order.
function M.mtl (path)
  local text = lines(path)
  local r, cur, ln = { names = {} }, nil, 0
  for line in text:gmatch("([^\n]*)\n?") do
    ln = ln + 1
    local tag, rest = line:match("^%s*(%S+)%s*(.-)%s*$")
    if tag == nil or tag:sub(1, 1) == "#" then
      -- blank or comment
    elseif tag == "newmtl" then
      cur = {}
      r[rest] = cur
      r.names[#r.names + 1] = rest
    elseif not cur then
      error(("%s:%d: '%s' before newmtl"):format(path, ln, tag), 2)
    else
      local t = nums(rest, path, ln)
      cur[tag] = #t == 1 and t[1] or t
    end
  end
  return r
end

-- PLY scalar types -> string.unpack format (without the byte order)
local PLYTYPE = {
  char = "i1", uchar = "I1", short = "i2", ushort = "I2", int = "i4", uint = "I4",
  float = "f", double = "d", int8 = "i1", uint8 = "I1", int16 = "i2", uint16 = "I2",
  int32 = "i4", uint32 = "I4", float32 = "f", float64 = "d",
}

--- Reads a binary PLY file (either byte order). Returns
--   format, version, comments = { ... }
--   elements = { { name, count, properties = { { name, type } or { name, list = true,
--                  count_type, type } } }, ... }
--   counts = { vertex = n, face = n, edge = n, ... }
--   data = { vertex = { { x = .., y = .., ... }, ... }, face = { { vertex_indices = {..} } }, .. }
--   first_vertex = data.vertex[1], header_length = bytes before the data
-- opts.header_only = true stops after the header. Raises when the data do not end exactly
-- at the end of the file.
function M.ply (path, opts)
  local data = lines(path)
  local hend = data:find("end_header\r?\n")
  if data:sub(1, 4) ~= "ply\n" or not hend then error(path .. ": not a PLY file", 2) end
  local r = { comments = {}, elements = {}, counts = {}, data = {} }
  local header = data:sub(1, hend - 1)
  r.header_length = #data:match("^.-end_header\r?\n")
  local el
  local ln = 0
  for line in header:gmatch("([^\n]*)\n") do
    ln = ln + 1
    local w = {}
    for x in line:gmatch("%S+") do w[#w + 1] = x end
    if ln == 1 or #w == 0 then
      -- "ply"
    elseif w[1] == "format" then
      r.format, r.version = w[2], w[3]
    elseif w[1] == "comment" or w[1] == "obj_info" then
      r.comments[#r.comments + 1] = line:match("^%S+%s(.*)$") or ""
    elseif w[1] == "element" then
      el = { name = w[2], count = math.tointeger(tonumber(w[3])), properties = {} }
      if not el.count then error(("%s: header line %d: bad element count"):format(path, ln), 2) end
      r.elements[#r.elements + 1] = el
      r.counts[el.name] = el.count
    elseif w[1] == "property" then
      if not el then error(("%s: header line %d: property before element"):format(path, ln), 2) end
      local p
      if w[2] == "list" then
        p = { name = w[5], list = true, count_type = PLYTYPE[w[3]], type = PLYTYPE[w[4]] }
        if not p.count_type or not p.type then
          error(("%s: header line %d: unknown type"):format(path, ln), 2)
        end
      else
        p = { name = w[3], type = PLYTYPE[w[2]] }
        if not p.type then
          error(("%s: header line %d: unknown type '%s'"):format(path, ln, w[2]), 2)
        end
      end
      el.properties[#el.properties + 1] = p
    else
      error(("%s: header line %d: unknown keyword '%s'"):format(path, ln, w[1]), 2)
    end
  end
  local bo = r.format == "binary_little_endian" and "<" or r.format == "binary_big_endian" and ">"
  if not bo then error(("%s: format '%s' is not supported"):format(path, r.format), 2) end
  if opts and opts.header_only then return r end
  local pos = r.header_length + 1
  for _, e in ipairs(r.elements) do
    local recs = {}
    for i = 1, e.count do
      local rec = {}
      for _, p in ipairs(e.properties) do
        if pos > #data then
          error(("%s: data end inside element '%s' %d"):format(path, e.name, i), 2)
        end
        if p.list then
          local n
          n, pos = string.unpack(bo .. p.count_type, data, pos)
          local t = {}
          for k = 1, n do t[k], pos = string.unpack(bo .. p.type, data, pos) end
          rec[p.name] = t
        else
          rec[p.name], pos = string.unpack(bo .. p.type, data, pos)
        end
      end
      recs[i] = rec
    end
    r.data[e.name] = recs
  end
  if pos ~= #data + 1 then
    error(("%s: %d bytes after the last element"):format(path, #data + 1 - pos), 2)
  end
  r.first_vertex = r.data.vertex and r.data.vertex[1]
  return r
end

return M
