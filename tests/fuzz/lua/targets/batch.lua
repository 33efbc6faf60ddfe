--- Fuzz target: batch specs in CSV (lsys.batch.csv and lsys.batch.jobs, lua/lsys/batch/).
--
-- The bytes are a CSV spec: they are parsed by lsys.batch.csv under the name "fuzz.csv",
-- and written to a scratch folder's fuzz.csv (next to a model file m.lua, which the spec may
-- name) whose jobs lsys.batch.jobs reads. Expected errors name the file and, for what a line
-- says, its line: "fuzz.csv:LINE: ..." from the parser, "DIR/fuzz.csv..." from the jobs.
-- Checks: every record's line is a line of the input (line ends CRLF, LF or CR alone) and
-- the records come in order; the
-- records, written back as CSV with every field quoted, parse to the same fields; the
-- parser and the jobs agree (the jobs fail only after the parser succeeded, or both fail
-- on the same line); every job has an id, a whole seed, its `where` naming the file and a
-- line, and at least one output whose path has no control character and is normalized
-- inside the output folder (not absolute, no empty, "." or ".." segment).
local batch = require "lsys.batch"

local type, pairs, ipairs, pcall, error, tostring, os_remove, open, mathtype, execute =
      type, pairs, ipairs, pcall, error, tostring, os.remove, io.open, math.type, os.execute
local format = string.format
local concat = table.concat

local T = { maxlen = 4096 }

T.seeds = {
  "model,seed,out\nm.lua,1,out/{id}.png\nm.lua,2,out/{id}.png;out/{id}.json\n",
  "\239\187\191model,R,png,stats\r\nm.lua,1.5,a/{id}.png,a/{id}.json\r\nm.lua,2,b.png,b.json\r\n",
  'model,"na,me",out\nm.lua,"x ""y"" z",o.png\n',
  'id,model,seed,steps,width,height,out\nfirst,m.lua,7,3,64,64,"p/{id}-{seed}.png"\n',
  'model,out\n"m.lua","multi\nline.png"\n',
  "model,seed,out\nm.lua,abc,o.png\n",
  "model,out\nm.lua,o.avi\n",
  "model,out\nnone.lua,o.png\n",
  "model,out\nm.lua,o.png\nm.lua,o.png\n",
  'model,out\nm.lua,"open\n',
  'model,out\nm.lua,x"y.png\n',
  "model\nm.lua\n",
  "",
}

T.dict = { ",", '"', '""', "\r\n", "\n", " ", ";", "model", "seed", "steps", "width",
           "height", "id", "name", "out", "png", "glb", "obj", "ply", "lstring", "stats",
           "m.lua", "{id}", "{seed}", "{n}", "{model}", "{R}", "{", "}", ".png", ".json",
           ".txt", "R", "-1", "1e999", "nan", "0x10", "2.5", "9007199254740993", "\239\187\191",
           "\0", "outputs", "params" }

-- the target's own mutation: a record of random cells from the dictionary
T.mutators = {
  function (rnd, s)
    local cells = {}
    for i = 1, rnd(5) do
      local c = T.dict[rnd(#T.dict)]
      cells[i] = rnd(3) == 1 and '"' .. c:gsub('"', '""') .. '"' or c
    end
    local at = rnd(#s + 1)
    return s:sub(1, at - 1) .. concat(cells, ",") .. "\n" .. s:sub(at)
  end,
}

local DIR = os.tmpname()
os_remove(DIR)

local _ENV = nil

local SPEC = DIR .. "/fuzz.csv"
local DIRPAT = DIR:gsub("%p", "%%%0")

local function setup ()
  if open(DIR .. "/m.lua", "rb") then return end
  execute("mkdir -p '" .. DIR .. "'")
  local f = open(DIR .. "/m.lua", "wb")
  f:write("return require('lsys').lsystem { axiom = 'F', steps = 1 }\n")
  f:close()
end

function T.clean (err)
  return err:find("^fuzz%.csv:%d+: ") ~= nil or err:find("^" .. DIRPAT .. "/fuzz%.csv") ~= nil
end

local last

function T.run (bytes)
  last = nil
  setup()
  local r = { bytes = bytes }
  r.ok, r.rows = pcall(batch.csv, bytes, "fuzz.csv")
  local f = open(SPEC, "wb")
  f:write(bytes)
  f:close()
  r.jok, r.jobs = pcall(batch.jobs, SPEC)
  last = r
  if not r.ok then error(r.rows, 0) end
  if not r.jok then error(r.jobs, 0) end
end

-- The rows written back as CSV, every field quoted.
local function unparse (rows)
  local out = {}
  for i, row in ipairs(rows) do
    local cells = {}
    for k, c in ipairs(row) do cells[k] = '"' .. c:gsub('"', '""') .. '"' end
    out[i] = concat(cells, ",")
  end
  return concat(out, "\n")
end

local function check (r)
  if not r.ok then
    if r.jok then return "the jobs were read from a file the parser refuses" end
    local l1 = tostring(r.rows):match("^fuzz%.csv:(%d+):")
    local l2 = tostring(r.jobs):match("^" .. DIRPAT .. "/fuzz%.csv:(%d+):")
    if l1 ~= l2 then
      return format("the parser and the jobs fail on different lines: %s / %s", tostring(r.rows),
                    tostring(r.jobs))
    end
    return nil
  end
  local nlines = 1             -- line ends: CRLF, LF, or CR alone, as the parser reads them
  for _ in r.bytes:gsub("\r\n?", "\n"):gmatch("\n") do nlines = nlines + 1 end
  local prev = 0
  for i, row in ipairs(r.rows) do
    if mathtype(row.line) ~= "integer" or row.line < prev or row.line > nlines then
      return format("record %d: line %s (input of %d lines, previous %d)", i, tostring(row.line),
                    nlines, prev)
    end
    prev = row.line
  end
  local ok, again = pcall(batch.csv, unparse(r.rows), "again.csv")
  if not ok then return "the records written back do not parse: " .. tostring(again) end
  local same = #again == #r.rows
  for i = 1, same and #again or 0 do
    if #again[i] ~= #r.rows[i] then same = false break end
    for k = 1, #again[i] do
      if again[i][k] ~= r.rows[i][k] then same = false break end
    end
  end
  if not same then return "the records written back parse to other fields" end
  if not r.jok then return nil end
  for _, job in ipairs(r.jobs) do
    if type(job.id) ~= "string" or job.id == "" then return "a job without an id" end
    if mathtype(job.seed) ~= "integer" then return "job " .. job.id .. ": seed not whole" end
    if type(job.where) ~= "string" or not job.where:find("^" .. DIRPAT .. "/fuzz%.csv:%d+$") then
      return "job " .. job.id .. ": where is " .. tostring(job.where)
    end
    if type(job.outputs) ~= "table" or #job.outputs == 0 then
      return "job " .. job.id .. ": no outputs"
    end
    for _, o in pairs(job.outputs) do
      if type(o.path) ~= "string" or o.path:find("%c") then
        return "job " .. job.id .. ": output path " .. tostring(o.path)
      end
      local p = "/" .. o.path .. "/"        -- inside the output folder, normalized
      if p:find("//", 1, true) or p:find("/%.%.?/") then
        return "job " .. job.id .. ": output path not normalized: " .. o.path
      end
    end
  end
  return nil
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  return check(r)
end

function T.finish ()
  os_remove(SPEC)
  os_remove(DIR .. "/m.lua")
  os_remove(DIR)
end

function T.describe (bytes) return bytes end

return T
