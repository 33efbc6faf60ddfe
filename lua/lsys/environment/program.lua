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
-- @module lsys.environment.program
local core = require "lsys.core"
local efile = require "lsys.environment.efile"

local setmetatable, ipairs, tonumber, error, pcall, type, tostring =
      setmetatable, ipairs, tonumber, error, pcall, type, tostring
local io, string, table = io, string, table
local format, pack, unpack, concat = string.format, string.pack, string.unpack, table.concat
local unpackl = table.unpack
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

-- The chunks of the items: lists of item texts, at most spec.max items (or, in shared
-- memory, MEMORY bytes) each.
local function chunks (spec, items)
  local out, cur, bytes = {}, {}, 0
  for _, t in ipairs(items) do
    local full = spec.max and #cur >= spec.max or not spec.max and bytes + #t >= MEMORY
    if full and #cur > 0 then
      out[#out + 1] = cur
      cur, bytes = {}, 0
    end
    cur[#cur + 1] = t
    bytes = bytes + #t
  end
  out[#out + 1] = cur
  return out
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
  local id = ids(queries)
  local items = {}
  for k, q in ipairs(queries) do items[k] = item(spec, q, id[k], width0) end
  local parts = chunks(spec, items)
  local got = {}
  for c, part in ipairs(parts) do
    local flag = #parts == 1 and 5 or c == 1 and 1 or c == #parts and 4 or 0
    local step = (flag == 5 or flag == 4) and (info.step or 0) or 0
    local msg = concat(part) .. format("Control: %d %d\n", flag, step)
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
  local answers = {}
  for k, q in ipairs(queries) do
    if q.index then answers[k] = got[id[k]] end
  end
  return answers
end

M.item = item
M.parse = parse

return M
