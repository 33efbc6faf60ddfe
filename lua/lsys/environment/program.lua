--- An environmental program as an environment: the master side of cpfg's protocol with
-- vlab's programs (honda81, chiba, density, ...), which run unmodified (docs/open.md §3).
--
-- `lsys.environment.program("field.e" [, { timeout = 30 }])` reads the communication file
-- (lsys.environment.efile) and returns an environment object. Each derivation starts the
-- program afresh (cpfg starts it again on every rewind) and ends it after its last step;
-- before each step the queries go to it as cpfg sends them, one text item a ?E:
--
--   <id> E(p1,...,pn)<the following module>
--   <the turtle values the file asks for, each line in the file's own format>
--
-- in chunks of at most `max` items (100 over pipes, 1000 over files, 50000 bytes in shared
-- memory), each ended by `Control: <flag> <step>` (flag 5 for a step in one chunk, else 1,
-- 0, ..., 4; the step on the last chunk only). The program answers `<id> E(a1,...)` lines
-- and its own Control line; an empty field keeps that parameter. The id is cpfg's: the
-- byte offset of the ?E in cpfg's string from the first ?E of the pass (a module takes its
-- name's length, and 1 + 5n bytes for n > 0 parameters), 1 for a ?E the homomorphism made.
-- Values travel as text: %g of the value rounded to a 32-bit float, as cpfg sends them.
-- When the file names interpreted modules (`interpreted modules:`, `when interpret:`) and
-- the module after a ?E is one, its item ends with "Dbegin", the module's drawing follows
-- as cpfg's GLS text (from info.scene's records of that module), and "Dend" starts the next
-- item or the step's last Control line (docs/open.md §3 says what is sent and what differs).
-- @module lsys.environment.program
local core = require "lsys.core"
local efile = require "lsys.environment.efile"

local setmetatable, ipairs, tonumber, error, pcall, type, tostring =
      setmetatable, ipairs, tonumber, error, pcall, type, tostring
local io, string, table, math = io, string, table, math
local format, pack, unpack, concat = string.format, string.pack, string.unpack, table.concat
local unpackl, floor = table.unpack, math.floor
local _ENV = nil

local M = {}

local Program = {}
Program.__index = Program
M.Program = Program

local MEMORY = 49999 - 25        -- the bytes of a chunk in shared memory, as cpfg cuts them

local function f32 (x) return (unpack("f", pack("f", x))) end

-- A list of numbers as cpfg writes parameters: "(a,b,c)", or "" for none.
local function params (p)
  if #p == 0 then return "" end
  local t = {}
  for k, x in ipairs(p) do t[k] = format("%g", f32(x)) end
  return "(" .. concat(t, ",") .. ")"
end

-- The module after a ?E as cpfg sends it: its name and parameters; a ?E or a
-- sub-L-system's ? as "?" alone; of a longer @ or ~ name only the first two characters.
local function following (q)
  local name = q.following
  if name == nil then return "" end
  if name:sub(1, 1) == "?" then return "?" end
  if (name:sub(1, 1) == "@" or name:sub(1, 1) == "~") and #name > 2 then
    return name:sub(1, 2)
  end
  return name .. params(q.following_params or {})
end

-- The ids of the queries, by query: cpfg's, which the pass counts (core.environment's
-- cpfg_id: the byte offset of the ?E in cpfg's string from the first ?E of the pass; 1 for
-- a ?E the homomorphism made).
local function ids (queries)
  local out = {}
  for k, q in ipairs(queries) do out[k] = q.cpfg_id or 1 end
  return out
end

--- An environment speaking to the program of the communication file `path`.
-- opts: timeout (seconds a start or an answer may take; 30).
function M.program (path, opts)
  if type(path) ~= "string" then
    error("lsys.environment.program: the communication file (.e) expected", 2)
  end
  local ok, spec = pcall(efile.read, path)
  if not ok then error(spec, 2) end
  local timeout = opts and opts.timeout or 30
  if type(timeout) ~= "number" or not (timeout > 0) then
    error("lsys.environment.program: timeout must be a number of seconds > 0", 2)
  end
  return setmetatable({ spec = spec, timeout = timeout }, Program)
end

function Program:__tostring ()
  return format("lsys.environment.program(%s)", self.spec.path)
end

--- Starts the program (ending one still running): at the start of each derivation.
function Program:start ()
  self:finish()
  local spec = self.spec
  local ok, p = pcall(core.envproc, { transport = spec.transport, dir = spec.dir,
                                      argv = spec.argv, timeout = self.timeout })
  if not ok then error((tostring(p):gsub("^[^\n]-:%d+: ", "")), 0) end
  self.proc = p
end

--- Ends the program (cpfg's exit message, then it is reaped): after each derivation.
function Program:finish ()
  local p = self.proc
  self.proc = nil
  if p then p:close() end
end
Program.__gc = Program.finish
Program.__close = Program.finish

-- The format of an item and the turtle fields it takes, made once a file: the formats are
-- checked (lsys.environment.efile: conversions of numbers only, as many as the values).
local function layout (spec)
  local L = spec.layout
  if L then return L end
  local fmts, fields = { "%d E%s%s" }, {}
  for _, field in ipairs(efile.ORDER) do
    local fmt = spec.formats[field]
    if fmt then fmts[#fmts + 1], fields[#fields + 1] = fmt, field end
  end
  L = { fmt = concat(fmts, "\n") .. "\n", fields = fields }
  spec.layout = L
  return L
end

-- The text item of query q (id `id`) with the turtle lines the file asks for.
local function item (spec, q, id, width0)
  local L = layout(spec)
  local a = { id, params(q.params), spec.following and following(q) or "" }
  local n = 3
  for _, field in ipairs(L.fields) do
    if field == "width" then
      -- cpfg sends the view's line width as the sub-L-systems scale it, not !'s and #'s
      n = n + 1
      a[n] = f32(width0 * q.scale)
    elseif field == "scale" then
      n = n + 1
      a[n] = f32(q.scale)
    else
      local v = q[field]
      a[n + 1], a[n + 2], a[n + 3] = f32(v[1]), f32(v[2]), f32(v[3])
      n = n + 3
    end
  end
  return format(L.fmt, unpackl(a, 1, n))
end

-- The chunks of the units: lists of texts, at most spec.max items (or, in shared memory,
-- MEMORY bytes) each, as cpfg cuts them: before an item when the chunk has `max` (the
-- geometry after an item never starts a chunk of its own over pipes and files), before
-- any text that would not fit in shared memory. `units` is a list of texts, `isitem[k]`
-- true for the items.
local function chunks (spec, units, isitem)
  local out, cur, items, bytes = {}, {}, 0, 0
  for k, t in ipairs(units) do
    local full
    if spec.max then full = isitem[k] and items >= spec.max
    else full = bytes + #t >= MEMORY end
    if full and #cur > 0 then
      out[#out + 1] = cur
      cur, items, bytes = {}, 0, 0
    end
    cur[#cur + 1] = t
    if isitem[k] then items = items + 1 end
    bytes = bytes + #t
  end
  out[#out + 1] = cur
  return out
end

-- ---------------------------------------------------------------------------------------
-- The geometry of interpreted modules: after the item of a ?E whose following module the
-- file's `interpreted modules:` or `when interpret:` names, the item ends with "Dbegin",
-- the module's drawing follows as cpfg's GLS text (what it writes with -gls), and "Dend"
-- starts the next item (or the Control line of the step's last chunk). Each text below is
-- one of cpfg's strings (a chunk in shared memory may end between two of them).

local function gf (fmt, x) return format(fmt, f32(x)) end     -- a float32 as cpfg prints it

-- Modules at which cpfg ends the segment it drew last (its EndNode): its cylinder is sent
-- there, in the section of the ?E before them, or lost when that ?E's module is not
-- interpreted.
local ENDS = { F = true, G = true, f = true, g = true, ["["] = true, ["]"] = true,
               ["{"] = true, ["}"] = true }
local function ends (name)
  local c = name:sub(1, 1)
  return ENDS[name] or c == "@" or c == "~"
end

-- The material text of colour `c` when it is not the last one sent (cpfg sends it before a
-- primitive whose colour changed): a colour map's entry as bytes over 2550 (ambient) and
-- 255 (diffuse), a material file's entry as its four colours and shininess.
local function material (G, c)
  if c == G.colour then return end
  G.colour = c
  local out = G.out
  out[#out + 1] = "material\n"
  local pal = G.palette
  local e = type(pal) == "table" and pal[c] or nil
  if type(e) == "table" and (e.ambient or e.specular or e.emission) then
    for _, key in ipairs { "ambient", "diffuse", "specular", "emission" } do
      local v = e[key] or {}
      for j = 1, 4 do out[#out + 1] = gf(" %g", v[j] or (j == 4 and 1 or 0)) end
      out[#out + 1] = "\n"
    end
    out[#out + 1] = gf(" %g\n", e.shininess or 0)
    return
  end
  local b, rgb = {}, type(e) == "table" and (e.diffuse or e) or {}
  for j = 1, 3 do
    local x = tonumber(rgb[j]) or 0
    b[j] = floor(x * 255 + 0.5)
  end
  out[#out + 1] = gf(" %g", b[1] / 2550.0)
  out[#out + 1] = gf(" %g", b[2] / 2550.0)
  out[#out + 1] = gf(" %g 0\n", b[3] / 2550.0)
  out[#out + 1] = gf(" %g", b[1] / 255.0)
  out[#out + 1] = gf(" %g", b[2] / 255.0)
  out[#out + 1] = gf(" %g 0\n", b[3] / 255.0)
  out[#out + 1] = " 0 0 0 0  0 0 0 0  0\n"
end

-- A segment's text (cpfg's cylinder): the frame at its start (position, up, heading and
-- minus left as the rows of a matrix), its radius and length.
local function cylinder (c)
  local out = {}
  out[1] = "pushmatrix\ntranslate"
  for j = 1, 3 do out[#out + 1] = gf(" %f", c.pos[j]) end
  out[#out + 1] = "\nmultmatrix\n"
  for j = 1, 3 do out[#out + 1] = gf(" %f", c.U[j]) end
  out[#out + 1] = " 0\n"
  for j = 1, 3 do out[#out + 1] = gf(" %f", c.H[j]) end
  out[#out + 1] = " 0\n"
  for j = 1, 3 do out[#out + 1] = format(" %f", -f32(c.L[j])) end
  out[#out + 1] = " 0\n"
  out[#out + 1] = "0 0 0 1\n"
  out[#out + 1] = gf("cylinder %f", c.width / 2)
  out[#out + 1] = gf(" %f\npopmatrix\n", c.len)
  return out
end

-- Sends the segment waiting for its end (when `open`: the current ?E's module is
-- interpreted; else cpfg loses it).
local function flush (G, open)
  local c = G.pending
  if c == nil then return end
  G.pending = nil
  if open then
    local out = G.out
    for _, t in ipairs(cylinder(c)) do out[#out + 1] = t end
  end
end

-- The vertices of polygon record k, as cpfg sends them: after a ?E whose module is the `{`
-- at string index m, cpfg takes only the vertices of its `.` modules (its F and f add none
-- then), so lsys's vertices of F and f are left out.
local function polygon (G, k, m)
  local v = G.scene:vertices(k)
  if m == nil then return v end
  local s, keep, depth, i = G.lstring, {}, 1, m
  while depth > 0 and i < #s do
    i = i + 1
    local name = s:module(i)
    if name == "{" then depth = depth + 1
    elseif name == "}" then depth = depth - 1
    elseif depth == 1 and name == "." then keep[#keep + 1] = true
    elseif depth == 1 and (name == "F" or name == "f") then keep[#keep + 1] = false end
  end
  if #keep ~= #v then return v end          -- not the polygon lsys drew: all its vertices
  local out = {}
  for j, x in ipairs(v) do if keep[j] then out[#out + 1] = x end end
  return out
end

-- The colour cpfg draws record r of the module after query q with: its pass changes the
-- colour only in interpreted modules, so a record drawn in the colour the turtle had at the
-- ?E is in cpfg's colour of the pass (G.C); one whose module changed it, in the colour set.
local function colour (G, q, r)
  if r.color == q.color then return G.C end
  return r.color
end

-- The geometry of the module at string index m after query q: its records' texts.
local function geometry (G, q, m)
  local name, p1 = G.lstring:module(m)
  if name == ";" or name == "," then          -- a colour module interpreted: cpfg's changes,
    local c = p1 and (p1 < 0 and -floor(-p1) or floor(p1))            -- C's (int)
              or G.C + (name == ";" and G.dcolor or -G.dcolor)
    if name == ";" and c > 255 then c = c - 256 end
    if name == "," and c < 0 then c = c + 256 end
    G.C = c
    material(G, c)                             -- and its material is sent then
    return
  end
  local k0, nrec = G.records[m], G.nrecords[m]
  local direct = k0 == nil and name == "{" and G.closing(m) or nil
  if direct then k0, nrec = direct, 1 end
  if k0 == nil then
    if ends(name) then flush(G, true) end
    return
  end
  local out = G.out
  for j = 1, nrec do
    local k = k0 + j - 1
    local r = G.scene:record(k)
    local c = colour(G, q, r)
    flush(G, true)                           -- a primitive ends the segment before it
    if j == nrec then G.C = c end
    if r.kind == "segment" then
      material(G, c)
      local seg = { pos = r.p0, H = r.H, L = r.L, U = r.U, len = r.length,
                    width = G.width0 * q.scale }
      if j == 1 and (name == "F" or name == "G") then
        seg.pos, seg.H, seg.L, seg.U = q.position, q.heading, q.left, q.up
      end
      G.pending = seg
    elseif r.kind == "polygon" then
      material(G, c)
      out[#out + 1] = "polygon\n"
      for _, v in ipairs(polygon(G, k, direct and m or nil)) do
        out[#out + 1] = gf(" %g", v[1])
        out[#out + 1] = gf(" %g", v[2])
        out[#out + 1] = gf(" %g", v[3])
        out[#out + 1] = "\n"
      end
    elseif r.kind == "sphere" then
      material(G, c)
      out[#out + 1] = "pushmatrix\ntranslate"
      for i = 1, 3 do out[#out + 1] = gf(" %g", r.p1[i]) end
      out[#out + 1] = gf("\nsphere %g\npopmatrix\n", r.w0 / 2)
    elseif r.kind == "disc" or r.kind == "surface" then
      material(G, c)                         -- cpfg's disc is its material alone
    end
  end
end

-- The state of the geometry of one pass: the scene, the first record of each module and
-- their number, the colour sent last, cpfg's colour, the segment waiting for its end.
local function newgeometry (info, width0)
  local scene = info.scene
  local records, nrecords, closes = {}, {}, {}     -- a module's records follow each other
  for k, r in scene:records() do
    local m = r.module
    if r.kind == "polygon" then closes[m] = k end
    if records[m] == nil then records[m] = k end
    nrecords[m] = (nrecords[m] or 0) + 1
  end
  local s = info.lstring
  local view = info.model and info.model:_view() or {}
  local G = { scene = scene, lstring = s, records = records, nrecords = nrecords, colour = -1,
              palette = view.palette, width0 = width0, C = view.color or 1,
              dcolor = view.color_increment or 1, stack = {} }
  -- the polygon record of the `{` at index m: at its `}`, which draws it
  function G.closing (m)
    local depth, i = 1, m
    while i < #s do
      i = i + 1
      local name = s:module(i)
      if name == "{" then depth = depth + 1
      elseif name == "}" then
        depth = depth - 1
        if depth == 0 then return closes[i] end
      end
    end
    return nil
  end
  return G
end

-- Goes over the string's modules i to j after a query (`open`: its module is interpreted)
-- as cpfg's pass does: a segment waiting for its end ends at the first module that ends
-- one, a bracket keeps and restores cpfg's colour of the pass. `brackets`: only these.
local function scan (G, i, j, open, brackets)
  local s, stack = G.lstring, G.stack
  for k = i, j do
    local name = s:module(k)
    if name == "[" then stack[#stack + 1] = G.C
    elseif name == "]" and #stack > 0 then G.C = stack[#stack]; stack[#stack] = nil end
    if not brackets and G.pending and (ends(name) or G.records[k]) then flush(G, open) end
  end
end

-- The texts of a pass, in order, and which are items: each query's item, after an
-- interpreted module its geometry; the Dend the step's last chunk ends with, if any.
local function units (spec, queries, info, width0)
  local out, isitem, id, opens = {}, {}, ids(queries), {}
  local G, open = nil, false
  local s = info.lstring
  for k, q in ipairs(queries) do
    opens[k] = spec.following and efile.interprets(spec, q.following,
                                                   #(q.following_params or {}))
    if opens[k] and G == nil then G = true end
  end
  local first
  for k, q in ipairs(queries) do
    if q.index then first = k; break end
  end
  if G then G = newgeometry(info, width0) end     -- the scene only when it is sent
  for k, q in ipairs(queries) do
    local t = item(spec, q, id[k], width0)
    local was = open
    open = opens[k]
    if was then t = "Dend\n" .. t end
    if open then t = t .. "Dbegin\n" end
    out[#out + 1] = t
    isitem[#out] = true
    if G and q.index then
      G.out = out
      if k == first then scan(G, 1, q.index - 1, false) end
      local m, stop = q.index + 1, #s
      for j = k + 1, #queries do
        if queries[j].index then stop = queries[j].index - 1; break end
      end
      local i = m
      if open and m <= stop then
        geometry(G, q, m)
        scan(G, m, m, open, true)                 -- an interpreted [ or ] keeps its colour
        i = m + 1
      end
      scan(G, i, stop, open)
    end
  end
  return out, isitem, open and "Dend\n" or ""
end

-- The answers of a reply into `got` (id -> { n =, values }); the Control flag it ends with.
local function parse (reply, got)
  local flag
  for line in reply:gmatch("[^\n]+") do
    if line:sub(1, 8) == "Control:" then
      flag = tonumber(line:match("^Control:%s*(%-?%d+)")) or 5
      break
    end
    local id, rest = line:match("^([^ ,;:]*)(.*)$")
    id = tonumber(id)
    local list = rest and rest:match("E%(([^)]*)%)")
    if id and list then
      local a, n = {}, 0
      for field in (list .. ","):gmatch("([^,]*),") do
        n = n + 1
        if field:match("%S") then
          a[n] = tonumber(field) or tonumber(field:match("^%s*([-+]?[%d.]*[eE]?[-+]?%d*)"))
                 or 0                         -- atof's reading of a field it cannot read
        end
      end
      a.n = n
      got[id] = a
    end
  end
  return flag
end

--- Answers the queries of one pass: sends them, reads what the program says.
function Program:answer (queries, info)
  if self.proc == nil then self:start() end
  local spec, proc = self.spec, self.proc
  local width0 = info.model and info.model:_view().line_width or 1
  local list, isitem, dend = units(spec, queries, info, width0)
  local parts = chunks(spec, list, isitem)
  local got = {}
  for c, part in ipairs(parts) do
    local flag = #parts == 1 and 5 or c == 1 and 1 or c == #parts and 4 or 0
    local step = (flag == 5 or flag == 4) and (info.step or 0) or 0
    local msg = concat(part) .. (c == #parts and dend or "") .. format("Control: %d %d\n",
                                                                        flag, step)
    if spec.verbose then io.stderr:write(msg) end
    local ok, reply = pcall(proc.exchange, proc, msg)
    if not ok then error((tostring(reply):gsub("^[^\n]-:%d+: ", "")), 0) end
    if spec.verbose then io.stderr:write(reply) end
    local f = parse(reply, got)
    local more = 0
    while f ~= nil and f & 4 == 0 do          -- the program's answers come in parts too
      more = more + 1
      if more > 1e6 then error("the program sends parts without end", 0) end
      ok, reply = pcall(proc.more, proc)
      if not ok then error((tostring(reply):gsub("^[^\n]-:%d+: ", "")), 0) end
      if spec.verbose then io.stderr:write(reply) end
      f = parse(reply, got)
    end
  end
  local answers, id = {}, ids(queries)
  for k, q in ipairs(queries) do
    if q.index then answers[k] = got[id[k]] end
  end
  return answers
end

M.item = item
M.parse = parse

return M
