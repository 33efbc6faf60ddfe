--- Batch runs (issue 20; docs/batch.md): many jobs -- a model, values for its variables, a
-- seed, the files to write -- listed by a spec (a CSV file, or a Lua file or table that
-- lists jobs or describes a sweep), run one after the other in this process, or split into
-- shards that GNU parallel or a Slurm job array run on any number of hosts. What `lsys batch
-- SPEC` runs.
--
-- Each job's seed comes from the spec alone (M.seed), and a job is in the same shard
-- wherever it runs (M.shard_of), so a sweep gives the same files in one process and in N.
-- Every file is written whole or not at all (core's atomic writer); a manifest of JSON lines
-- records each job that ran; a job whose files and manifest line say it was done is skipped
-- on the next run, so a run that was killed goes on where it stopped. A job that fails is
-- recorded with its message and the others go on.
--
-- Nothing holds every job (issue 34 §9): a spec is a source whose job n is made from n when
-- it is needed, so a listing, a shard and a resumed run take memory that does not grow with
-- the spec's jobs and time in proportion to the jobs they touch. Outputs are paths inside
-- the output folder, normalized before they are compared, written through no symbolic link
-- of the folder (§17); a run removes the temporaries dead runs left of its files (§12).
-- @module lsys.batch
local core = require "lsys.core"
local shortest, shq = require("lsys.text").number, require("lsys.text").shq
local model = require "lsys.model"
local load = require "lsys.load"
local program = require "lsys.program"
local fs = require "lsys.util.fs"
local strip_internal = require("lsys.util.errors").strip_internal

local type, pairs, ipairs, next, error, pcall, tostring, tonumber, require, loadfile, select,
      setmetatable, getmetatable =
      type, pairs, ipairs, next, error, pcall, tostring, tonumber, require, loadfile, select,
      setmetatable, getmetatable
local io, os, math, string, table, collectgarbage, package =
      io, os, math, string, table, collectgarbage, package
local format = string.format
local host, clock, isfile = program.host, program.clock, fs.isfile
local _ENV = nil

local M = {}

M.MAX_SIZE = 16384                  -- the largest picture width and height
M.SIZE = 800                        -- a picture's width and height when the spec gives none

-- The output formats, in the order a job writes them: { name, file extension (none: any) }.
local FORMATS = {
  { "png", "png" }, { "glb", "glb" }, { "obj", "obj" }, { "ply", "ply" }, { "lstring" },
  { "stats", "json" },
}
local FORMAT_RANK, FORMAT_EXT = {}, {}
for i, f in ipairs(FORMATS) do FORMAT_RANK[f[1]], FORMAT_EXT[f[1]] = i, f[2] end
-- The format of a template in a list of outputs (the CSV column `out`), by its extension.
local BY_EXT = { png = "png", glb = "glb", obj = "obj", ply = "ply", json = "stats",
                 txt = "lstring", lstring = "lstring", str = "lstring" }

-- The fields of a job that are not model variables.
local RESERVED = { id = true, model = true, name = true, seed = true, steps = true,
                   width = true, height = true, out = true, outputs = true, params = true,
                   png = true, glb = true, obj = true, ply = true, lstring = true,
                   stats = true, rep = true }

-- {===========================================================================================
-- Helpers: messages, JSON

-- A value in a message: text quoted, anything else as tostring gives it.
local function show (v)
  if type(v) == "string" then return "'" .. v .. "'" end
  return tostring(v)
end

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

-- }===========================================================================================


-- {===========================================================================================
-- Seeds and shards

--- The seed of job number `n` (1, 2, ...) of a spec whose seed is `base` (a whole number;
-- 0 when the spec gives none): the n-th number of splitmix64 started at `base`, its top 31
-- bits -- mix(base + n * 0x9E3779B97F4A7C15) >> 33 in 64-bit arithmetic, a whole number
-- from 0 to 2^31 - 1. It depends on the spec only, not on the shard or the host.
function M.seed (base, n)
  base, n = math.tointeger(base), math.tointeger(n)
  if base == nil or n == nil then
    error("lsys.batch.seed: the spec's seed and the job's number must be whole numbers", 2)
  end
  local z = base + n * 0x9E3779B97F4A7C15
  z = (z ~ (z >> 30)) * 0xBF58476D1CE4E5B9
  z = (z ~ (z >> 27)) * 0x94D049BB133111EB
  return (z ~ (z >> 31)) >> 33
end

--- The shard (1 to `count`) that job number `n` belongs to: jobs are dealt round (job 1 to
-- shard 1, job 2 to shard 2, ...), so that every shard gets its share of a sweep whose
-- jobs grow heavier along the way.
function M.shard_of (n, count)
  n, count = math.tointeger(n), math.tointeger(count)
  if n == nil or count == nil or n < 1 or count < 1 then
    error("lsys.batch.shard_of: the job's number and the count of shards must be whole "
      .. "numbers >= 1", 2)
  end
  return (n - 1) % count + 1
end

local function envint (getenv, name)
  local v = getenv(name)
  if v == nil or v == "" then return nil end
  return math.tointeger(tonumber(v)), v
end

--- The shard `s` names, as K, N (shard K of N): "K/N" with 1 <= K <= N, or "slurm" (K and N
-- from the job array's SLURM_ARRAY_TASK_ID, _MIN, _STEP and _COUNT, read by `getenv`,
-- default os.getenv). Returns nil and a message when `s` names none.
function M.parse_shard (s, getenv)
  if type(s) ~= "string" then
    error(format("lsys.batch.parse_shard: a string expected (\"K/N\" or \"slurm\"), got %s",
      type(s)), 2)
  end
  if getenv ~= nil and type(getenv) ~= "function" then
    error("lsys.batch.parse_shard: getenv must be a function (as os.getenv)", 2)
  end
  getenv = getenv or os.getenv
  if s == "slurm" then
    local id, idtext = envint(getenv, "SLURM_ARRAY_TASK_ID")
    if idtext == nil then
      return nil, "slurm: SLURM_ARRAY_TASK_ID is not set (run it in a Slurm job array: "
        .. "sbatch --array=0-9 ...)"
    end
    local count, ctext = envint(getenv, "SLURM_ARRAY_TASK_COUNT")
    if ctext == nil then
      return nil, "slurm: SLURM_ARRAY_TASK_COUNT is not set (Slurm sets it in a job array: "
        .. "sbatch --array=0-9 ...)"
    end
    local min = envint(getenv, "SLURM_ARRAY_TASK_MIN") or 0
    local step = envint(getenv, "SLURM_ARRAY_TASK_STEP") or 1
    if id == nil or count == nil or count < 1 or step < 1 then
      return nil, format("slurm: SLURM_ARRAY_TASK_ID=%s, SLURM_ARRAY_TASK_COUNT=%s: whole "
        .. "numbers expected", idtext, ctext)
    end
    local k = (id - min) // step + 1
    if (id - min) % step ~= 0 or k < 1 or k > count then
      return nil, format("slurm: task %d is not one of %d tasks from %d by %d: give the array "
        .. "as a range (sbatch --array=0-%d)", id, count, min, step, count - 1)
    end
    return k, count
  end
  local k, n = s:match("^%s*(%d+)%s*/%s*(%d+)%s*$")
  k, n = math.tointeger(tonumber(k)), math.tointeger(tonumber(n))
  if k == nil or n == nil or n < 1 or k < 1 or k > n then
    return nil, format("expects K/N (shard K of N, 1 <= K <= N) or slurm, got '%s'", s)
  end
  return k, n
end

-- }===========================================================================================


-- {===========================================================================================
-- CSV (RFC 4180)

-- The next record of the CSV text `text` of the file `name` from byte `i`, on line `line`
-- (blank lines skipped): the record (a list of fields with `line`), and the byte and line
-- after it; nil when the text ends. Raises as M.csv.
local function csv_record (text, i, line, name)
  local len = #text
  local function fail (l, msg) error(format("%s:%d: %s", name, l, msg), 0) end
  while i <= len do
    local row, blank = { line = line }, true
    while true do
      local field
      if text:byte(i) == 34 then                 -- "..."
        local parts, j, qline = {}, i + 1, line
        while true do
          local q = text:find('"', j, true)
          if q == nil then
            fail(qline, format("field %d: the quote that opens it is not closed", #row + 1))
          end
          local piece = text:sub(j, q - 1)
          parts[#parts + 1] = piece
          line = line + select(2, piece:gsub("\n", ""))
          if text:byte(q + 1) == 34 then
            parts[#parts + 1] = '"'
            j = q + 2
          else
            i = q + 1
            break
          end
        end
        field, blank = table.concat(parts), false
        local c = text:sub(i, i)
        if c ~= "," and c ~= "\n" and c ~= "\r" and c ~= "" then
          local after = text:match("^[ \t]*", i)
          i = i + #after
          c = text:sub(i, i)
          if c ~= "," and c ~= "\n" and c ~= "\r" and c ~= "" then
            fail(line, format("field %d: text after the closing quote (a quote inside a "
              .. "field is written twice: \"a \"\"b\"\" c\")", #row + 1))
          end
        end
      else
        local j = text:find('[,\r\n"]', i) or len + 1
        if text:byte(j) == 34 then
          fail(line, format("field %d: a quote inside an unquoted field (put the field in "
            .. "quotes and write the quote twice: \"a \"\"b\"\" c\")", #row + 1))
        end
        field = text:sub(i, j - 1):match("^[ \t]*(.-)[ \t]*$")
        if field ~= "" then blank = false end
        i = j
      end
      row[#row + 1] = field
      local c = text:sub(i, i)
      if c == "," then
        i, blank = i + 1, false
      else
        if c == "\r" then i = i + (text:sub(i + 1, i + 1) == "\n" and 2 or 1)
        elseif c == "\n" then i = i + 1 end
        if c ~= "" then line = line + 1 end
        break
      end
    end
    if not blank then return row, i, line end
  end
  return nil, i, line
end

-- Where the records of CSV text begin: byte 4 after a UTF-8 byte order mark, else 1.
local function csv_start (text)
  return text:sub(1, 3) == "\239\187\191" and 4 or 1
end

--[[
Parses the CSV text `text` of the file `name`: fields separated by commas, records by CRLF
or LF; a field in double quotes may hold commas, line breaks and quotes written twice ("").
Spaces around an unquoted field are dropped; a UTF-8 byte order mark at the start is
skipped; empty lines are skipped. Returns the records, each a list of fields with `line`, the
line it begins on. Raises "name:line: ..." for a quote left open (the line it opens on), text
after a closing quote, and a quote inside an unquoted field.
]]
function M.csv (text, name)
  if type(text) ~= "string" or type(name) ~= "string" then
    error("lsys.batch.csv: the text and the file's name must be strings", 2)
  end
  local rows, i, line = {}, csv_start(text), 1
  while true do
    local row
    row, i, line = csv_record(text, i, line, name)
    if row == nil then return rows end
    rows[#rows + 1] = row
  end
end

-- }===========================================================================================


-- {===========================================================================================
-- Values of a job

local function tonum (v)
  if type(v) == "number" then return v end
  if type(v) == "string" then return tonumber(v) end
  return nil
end

-- A model variable's value: a finite number. Returns it, or nil and why.
local function conv_number (v)
  local x = tonum(v)
  if x == nil then return nil, format("%s is not a number", show(v)) end
  if x ~= x or x == math.huge or x == -math.huge then
    return nil, format("%s is not a finite number", show(v))
  end
  return math.tointeger(x) or x
end

-- A whole number from lo to hi (hi nil: any), as an integer; or nil and why.
local function conv_whole (v, lo, hi)
  local x = tonum(v)
  local n = x and x == math.floor(x) and x > -2^63 and x < 2^63 and math.tointeger(x)
  if not n then return nil, format("%s is not a whole number", show(v)) end
  if n < lo or (hi and n > hi) then
    return nil, format("%s must be %s", show(v), hi and format("from %d to %d", lo, hi)
      or format(">= %d", lo))
  end
  return n
end

local CONV = {
  seed = function (v) return conv_whole(v, math.mininteger) end,
  steps = function (v) return conv_whole(v, 0, model.MAX_STEPS) end,
  width = function (v) return conv_whole(v, 1, M.MAX_SIZE) end,
  height = function (v) return conv_whole(v, 1, M.MAX_SIZE) end,
  model = function (v)
    if type(v) ~= "string" or v == "" then return nil, "a model file name expected" end
    return v
  end,
  name = function (v)
    if type(v) ~= "string" or v == "" then return nil, "a model name expected" end
    return v
  end,
  id = function (v)
    if type(v) == "number" then v = tostring(math.tointeger(v) or v) end
    if type(v) ~= "string" or not v:find("^[%w][%w_.%-]*$") then
      return nil, format("%s is not a job id (letters, digits, '_', '.' and '-', starting "
        .. "with a letter or a digit)", show(v))
    end
    return v
  end,
}

local function isname (k)
  return type(k) == "string" and k:find("^[%a_][%w_]*$") ~= nil
end

-- The format of an output template `tpl` given under the key `key` (a format's name, or
-- "out" for one told by its extension); or nil and why.
local function output_format (key, tpl)
  if type(tpl) ~= "string" or tpl == "" then
    return nil, format("%s is not a file name template", show(tpl))
  end
  local ext = (tpl:match("%.([%w]+)$") or ""):lower()
  if key == "out" then
    local f = BY_EXT[ext]
    if f == nil then
      return nil, format("'%s': the format is told by the extension: .png, .glb, .obj, .ply, "
        .. ".json (stats) or .txt (the L-string)", tpl)
    end
    return f
  end
  local want = FORMAT_EXT[key]
  if want and ext ~= want then
    return nil, format("'%s': a %s file's name ends in .%s", tpl, key, want)
  end
  return key
end

-- }===========================================================================================


-- {===========================================================================================
-- Specs: CSV files, Lua files and tables
--
-- A spec is read as a source of jobs: its number of jobs, and job n made from n alone when
-- it is asked for (a sweep's from n's digits in the mixed radix of its lists, a CSV
-- record's from the record, a list's from its entry), so that nothing holds every job: a
-- shard, a listing and a resumed run make only the jobs they touch. What is wrong with a
-- spec is said before any job runs (M.check_source below).

M.MAX_JOBS = 1000000000             -- the most jobs a spec may make

local function readfile (path)
  local f, err = io.open(path, "rb")
  if f == nil then error(format("cannot open '%s': %s", path, tostring(err):match(": ([^:]*)$")
    or tostring(err)), 0) end
  local text, rerr = f:read("a")
  f:close()
  if text == nil then error(format("cannot read '%s': %s", path, tostring(rerr)), 0) end
  return text
end

-- `p` relative to the folder `dir` ("." for the current one); an absolute `p` as it is.
local function join (dir, p)
  if p:sub(1, 1) == "/" or dir == "." or dir == "" then return p end
  return (dir:gsub("/+$", "")) .. "/" .. p
end

local function dirname (path)
  return path:match("^(.*)/[^/]*$") or "."
end

-- The value of the placeholder {k} of a job's template, as text; or nil and why.
local function placeholder (job, k)
  local v
  if k == "id" or k == "n" or k == "seed" or k == "name" or k == "steps" or k == "rep" or
     k == "width" or k == "height" then
    v = job[k]
    if v == nil then return nil, format("{%s}: the job has no %s", k, k) end
  elseif k == "model" then
    v = job.model:match("([^/]*)$"):gsub("%.lua$", "")
  elseif isname(k) then
    v = job.params[k]
    if v == nil then return nil, format("{%s}: the job gives no value for %s", k, k) end
  else
    return nil, format("{%s} is not a placeholder (they are {id}, {n}, {seed}, {model}, "
      .. "{name}, {steps}, {rep} and the model's variables, as {R})", k)
  end
  if math.type(v) == "float" then v = format("%.14g", v) end
  return tostring(v)
end

-- The path `path` (a template's expansion) as the file it names in the output folder:
-- empty and "." segments dropped, ".." taking away the segment before it -- the path lsys
-- writes, compares and records. Returns it, or nil and why: an absolute path, a path that
-- leaves the output folder.
local function normalize (path)
  if not path:find("//", 1, true) and not path:find("%.%.?/") and not path:find("/%.%.?$")
     and path:sub(1, 1) ~= "/" then
    return path                              -- nothing to normalize (the usual path)
  end
  if path:sub(1, 1) == "/" then
    return nil, format("'%s' is an absolute path: an output is a file in the output folder, "
      .. "named relative to it", path)
  end
  local segs = {}
  for seg in path:gmatch("[^/]+") do
    if seg == ".." then
      if #segs == 0 then
        return nil, format("'%s' leaves the output folder: an output is a file in it", path)
      end
      segs[#segs] = nil
    elseif seg ~= "." then
      segs[#segs + 1] = seg
    end
  end
  if #segs == 0 then return nil, format("'%s' is not a file name", path) end
  return table.concat(segs, "/")
end

-- The job's template `tpl` with its placeholders replaced, normalized; or nil and why.
local function expand (job, tpl)
  local why
  local path = tpl:gsub("{([^{}]*)}", function (k)
    local v, err = placeholder(job, k)
    if v == nil then why = why or err end
    return v
  end)
  if why then return nil, why end
  if path:find("[{}]") then return nil, format("'%s': an unmatched { or }", tpl) end
  local last = path:match("[^/]*$")
  if path:find("%c") or last == "" or last == "." or last == ".." then
    return nil, format("'%s' is not a file name", path)
  end
  return normalize(path)
end

-- The material file an .obj output writes beside it: the file name's extension becomes
-- .mtl, as export_obj.c's mtlpath does (".obj" alone stays whole).
local function companion (path)
  if path:match("[^/]*$"):find("^%.[^.]*$") then return path .. ".mtl" end
  return (path:gsub("%.[^./]*$", ".mtl"))
end

-- The number of jobs `count` (a float: a sweep's may be past 2^63) as an integer, checked
-- against M.MAX_JOBS; `where` and `what` say where they come from.
local function check_count (where, what, count)
  if count > M.MAX_JOBS then
    error(format("%s: %s %s jobs, more than the limit of %d (lsys.batch.MAX_JOBS)", where, what,
      count < 2^53 and format("%d", math.tointeger(count)) or format("%.3e", count),
      M.MAX_JOBS), 0)
  end
  return math.tointeger(count)
end

local function outputs_order (a, b)
  if a.format ~= b.format then return FORMAT_RANK[a.format] < FORMAT_RANK[b.format] end
  return a.i < b.i
end

--[[
Makes the job `job` (a table of raw fields: where, col, params, templates, and what the spec
gives of id, seed, model, name, steps, width, height, rep) complete as job number `n` of
the source `src`: its id (given, or n padded with zeros to src.width digits), seed (given,
or M.seed(src.base, n)), model file (found from src.dir, checked once per file), outputs
(templates expanded and normalized, sorted by format). Raises naming where the job comes
from (`job.where`, "plants.csv:7") and the field (`job.col(field)`). Returns the job and
its claims: every file it writes, { path, field, of } (`of`: the .obj whose material file
it is).
]]
local function complete (src, job, n)
  local function fail (field, msg)
    local col = field and job.col(field) or ""
    error(format("%s: %s%s", job.where, col, msg), 0)
  end
  job.n = n
  job.id = job.id or format(src.idformat, n)
  if job.seed == nil then job.seed = M.seed(src.base, n) end
  if job.model == nil then fail("model", "no model file given") end
  job.path = join(src.dir, job.model)
  local found = src.models[job.path]
  if found == nil then
    found = isfile(job.path)
    src.models[job.path] = found
  end
  if not found then
    fail("model", format("cannot open '%s'%s", job.path, src.dir ~= "." and
      " (a model's path is relative to the spec's folder)" or ""))
  end
  if #job.templates == 0 then
    fail(nil, "no outputs: give file name templates such as png/{id}.png")
  end
  local outs, claims, mine = {}, {}, {}
  local function claim (path, field, of)
    local prev = mine[path]
    if prev ~= nil then
      local obj = of or (prev ~= true and prev)
      fail(field, format("'%s' is written twice by this job%s", path,
        obj and format(" (the material file of '%s')", obj) or ""))
    end
    mine[path] = of or true
    claims[#claims + 1] = { path = path, field = field, of = of }
  end
  for _, t in ipairs(job.templates) do
    local path, why = expand(job, t.template)
    if path == nil then fail(t.field, why) end
    claim(path, t.field)
    if t.format == "obj" then claim(companion(path), t.field, path) end
    outs[#outs + 1] = { format = t.format, path = path, i = #outs + 1 }
  end
  if #outs > 1 then table.sort(outs, outputs_order) end    -- a job writes its formats in one order
  for _, o in ipairs(outs) do o.i = nil end
  job.outputs, job.templates, job.col = outs, nil, nil
  return job, claims
end

-- A new raw job: `base`'s fields, its params a copy (the templates are never changed).
local function clone (base, where)
  local job = {}
  for k, v in pairs(base) do job[k] = v end
  local params = {}
  for k, v in pairs(base.params) do params[k] = v end
  job.params, job.where = params, where
  return job
end

-- The jobs of the CSV file `path` (text `text`): one job per record after the header. The
-- records are parsed once, to find them and their syntax errors; a job's record is parsed
-- again when the job is made.
local function csv_source (path, text)
  local head, i, line = csv_record(text, csv_start(text), 1, path)
  if head == nil then error(format("%s: no header line and no jobs", path), 0) end
  -- where each record's text begins; its syntax checked, before what the header says
  local at, lines = {}, {}
  while true do
    local row, j, l = csv_record(text, i, line, path)
    if row == nil then break end
    at[#at + 1], lines[#lines + 1] = i, line
    i, line = j, l
  end
  local cols, seen = {}, {}
  local has_out = false
  for c, name in ipairs(head) do
    local function fail (msg) error(format("%s:%d: column %d: %s", path, head.line, c, msg), 0) end
    if name == "" then fail("a column without a name") end
    if seen[name] then fail(format("'%s' is also column %d", name, seen[name])) end
    seen[name] = c
    if name == "outputs" or name == "params" or name == "rep" then
      fail(format("'%s' is a field of Lua specs; a CSV spec gives its outputs in the columns "
        .. "out, png, glb, obj, ply, lstring and stats, and a model variable per column", name))
    end
    if not RESERVED[name] and not isname(name) then
      fail(format("'%s' is not a model variable's name (letters, digits and _, not starting "
        .. "with a digit) nor one of id, model, name, seed, steps, width, height, out, png, "
        .. "glb, obj, ply, lstring, stats", name))
    end
    if name == "out" or FORMAT_RANK[name] then has_out = true end
    cols[c] = name
  end
  if not seen.model then
    error(format("%s:%d: no column 'model' (the model file of each job)", path, head.line), 0)
  end
  if not has_out then
    error(format("%s:%d: no output column: add 'out' (file name templates such as "
      .. "png/{id}.png, separated by ;) or png, glb, obj, ply, lstring, stats", path,
      head.line), 0)
  end
  local src = { count = check_count(path, "the file makes", #at + 0.0),
                col = function (name) return format("column '%s': ", name) end }
  function src.raw (n)
    local row = csv_record(text, at[n], lines[n], path)
    local where = format("%s:%d", path, row.line)
    if #row ~= #head then
      error(format("%s: %d field%s, the header (line %d) has %d", where, #row,
        #row == 1 and "" or "s", head.line, #head), 0)
    end
    local job = { where = where, params = {}, templates = {},
                  col = function (name) return format("column '%s': ", name) end }
    for c, name in ipairs(cols) do
      local v = row[c]
      local function fail (msg) error(format("%s: column '%s': %s", where, name, msg), 0) end
      if v == "" then                         -- an empty cell: the default
        goto next_cell
      end
      if name == "out" or FORMAT_RANK[name] then
        for tpl in v:gmatch("[^;]+") do
          tpl = tpl:match("^%s*(.-)%s*$")
          if tpl ~= "" then
            local f, why = output_format(name, tpl)
            if f == nil then fail(why) end
            job.templates[#job.templates + 1] = { format = f, template = tpl, field = name }
          end
        end
      elseif CONV[name] then
        local x, why = CONV[name](v)
        if x == nil then fail(why) end
        job[name] = x
      else
        local x, why = conv_number(v)
        if x == nil then fail(why) end
        job.params[name] = x
      end
      ::next_cell::
    end
    return job
  end
  return src
end

-- The fields a Lua spec may have, besides a list of jobs in its array part.
local SPEC_FIELDS = { model = true, name = true, seed = true, steps = true, width = true,
                      height = true, params = true, outputs = true, vary = true,
                      replicates = true, jobs = true, dir = true }

-- The outputs of a Lua spec or job, `outs`: a list of templates told by their extension,
-- and/or format = template entries. Returns the list of { format, template, field }.
local function lua_outputs (outs, fail)
  if type(outs) == "string" then outs = { outs } end
  if type(outs) ~= "table" then fail("outputs", "a list of file name templates expected") end
  local list = {}
  for i, tpl in ipairs(outs) do
    local f, why = output_format("out", tpl)
    if f == nil then fail(format("outputs[%d]", i), why) end
    list[#list + 1] = { format = f, template = tpl, field = format("outputs[%d]", i) }
  end
  for _, fmt in ipairs(FORMATS) do
    local tpl = outs[fmt[1]]
    if tpl ~= nil then
      local f, why = output_format(fmt[1], tpl)
      if f == nil then fail("outputs." .. fmt[1], why) end
      list[#list + 1] = { format = f, template = tpl, field = "outputs." .. fmt[1] }
    end
  end
  for k in pairs(outs) do
    if not (math.type(k) == "integer" and k >= 1 and k <= #outs) and not FORMAT_RANK[k] then
      fail("outputs", format("%s is not a format (png, glb, obj, ply, lstring, stats)", show(k)))
    end
  end
  return list
end

-- Sets the field `k` of the job `job` to `v` (a spec's, a job's or a sweep's value), checked;
-- `fail(field, msg)` raises.
local function setfield (job, k, v, field, fail)
  if k == "outputs" or k == "out" then
    job.templates = lua_outputs(v, function (f, msg) fail(f, msg) end)
  elseif k == "params" then
    if type(v) ~= "table" then fail(field, "a table of variable = value expected") end
    for pk, pv in pairs(v) do
      if not isname(pk) then fail(field, format("%s is not a variable's name", show(pk))) end
      local x, why = conv_number(pv)
      if x == nil then fail(field .. "." .. pk, why) end
      job.params[pk] = x
    end
  elseif CONV[k] then
    local x, why = CONV[k](v)
    if x == nil then fail(field, why) end
    job[k] = x
  elseif k == "rep" or k == "replicates" then
    fail(field, "'" .. k .. "' is a field of the spec")
  elseif isname(k) then
    local x, why = conv_number(v)
    if x == nil then fail(field, why) end
    job.params[k] = x
  else
    fail(field, format("%s is not a job's field nor a variable's name", show(k)))
  end
end

-- A raw job with the spec's defaults, from which every job of the spec is cloned.
local function newjob (spec, who)
  local job = { params = {}, templates = {}, col = function (name) return name .. ": " end }
  local function fail (field, msg) error(format("%s: %s: %s", who, field, msg), 0) end
  for _, k in ipairs { "model", "name", "steps", "width", "height", "outputs", "params" } do
    if spec[k] ~= nil then setfield(job, k, spec[k], k, fail) end
  end
  return job
end

-- The sweep's variables, in the order the product runs them: a list of { name, values }.
local function vary_list (vary, fail)
  if type(vary) ~= "table" then fail("vary", "a table of name = { values } expected") end
  local list = {}
  if #vary > 0 then                        -- { { "R", { ... } }, { "seed", { ... } } }
    for i, e in ipairs(vary) do
      if type(e) ~= "table" or type(e[1]) ~= "string" or type(e[2]) ~= "table" then
        fail(format("vary[%d]", i), "a pair { name, { values } } expected")
      end
      list[i] = { e[1], e[2] }
    end
    for k in pairs(vary) do
      if not (math.type(k) == "integer" and k >= 1 and k <= #vary) then
        fail("vary", "give a list of { name, { values } } or name = { values }, not both")
      end
    end
  else
    for k, v in pairs(vary) do
      if type(k) ~= "string" then fail("vary", format("%s is not a name", show(k))) end
      list[#list + 1] = { k, v }
    end
    table.sort(list, function (a, b) return a[1] < b[1] end)
  end
  local seen = {}
  for _, e in ipairs(list) do
    local k, vals = e[1], e[2]
    if seen[k] then fail("vary", format("'%s' is varied twice", k)) end
    seen[k] = true
    if type(vals) ~= "table" or #vals == 0 then
      fail("vary." .. k, "a non-empty list of values expected")
    end
    if k == "outputs" or k == "params" or k == "id" or k == "rep" then
      fail("vary." .. k, format("'%s' cannot be varied", k))
    end
  end
  return list
end

-- The source of the jobs of a list (`list`, the spec's array part or its field jobs).
local function list_source (spec, who, list, base)
  local function fail (field, msg) error(format("%s: %s: %s", who, field, msg), 0) end
  if type(list) ~= "table" then fail("jobs", "a list of jobs expected") end
  local src = { count = check_count(who, "the list makes", #list + 0.0),
                col = function (name) return name .. ": " end }
  function src.raw (i)
    local field = list == spec and format("[%d]", i) or format("jobs[%d]", i)
    local job = clone(base, format("%s: %s", who, field))
    local t = list[i]
    if type(t) ~= "table" then fail(field, "a job (a table) expected") end
    for k, v in pairs(t) do setfield(job, k, v, field .. "." .. tostring(k), fail) end
    return job
  end
  return src
end

-- The source of the jobs of a sweep: the product of the lists of `vary`, the first
-- slowest, the last fastest, then the replicates. Job n is made from the digits of n - 1
-- in the mixed radix of the lists' lengths (the replicates the last digit).
local function sweep_source (spec, who, reps, base)
  local function fail (field, msg) error(format("%s: %s: %s", who, field, msg), 0) end
  local vary = spec.vary and vary_list(spec.vary, fail) or {}
  local seeded, varied = false, {}
  local count, dims = reps + 0.0, {}
  for _, e in ipairs(vary) do
    -- each value checked and converted once, before the product; its words in `where`
    local conv, words, param = {}, {}, CONV[e[1]] == nil
    for i = 1, #e[2] do                 -- every value up to the length: a hole is an error
      local v = e[2][i]
      if v == nil then fail(format("vary.%s[%d]", e[1], i), "a value expected, got nil") end
      local job = { params = {} }
      setfield(job, e[1], v, format("vary.%s[%d]", e[1], i), fail)
      conv[i], words[i] = param and job.params[e[1]] or job[e[1]], format("%s=%s", e[1],
        tostring(v))
    end
    e.conv, e.words, e.param = conv, words, param
    seeded = seeded or e[1] == "seed"
    varied[e[1]] = true
    count = count * #e[2]
    dims[#dims + 1] = format("%d values of %s", #e[2], e[1])
  end
  if seeded and reps > 1 then
    fail("replicates", "with vary.seed every replicate would have the same seed: vary the "
      .. "seed or give replicates, not both")
  end
  if reps > 1 then dims[#dims + 1], varied.rep = format("%d replicates", reps), true end
  local src = { count = check_count(who .. ": vary", format("the sweep (%s) makes",
                  table.concat(dims, " x ")), count),
                vary = vary, reps = reps, varied = varied,
                col = function (name) return name .. ": " end }
  function src.raw (n)
    local r = n - 1
    local rep = r % reps + 1
    r = r // reps
    local idx = {}
    for i = #vary, 1, -1 do
      local len = #vary[i][2]
      idx[i], r = r % len + 1, r // len
    end
    local parts = {}
    for i, e in ipairs(vary) do parts[i] = e.words[idx[i]] end
    if reps > 1 then parts[#parts + 1] = format("rep=%d", rep) end
    local job = clone(base, #parts > 0 and who .. ": vary " .. table.concat(parts, " ") or who)
    for i, e in ipairs(vary) do
      if e.param then job.params[e[1]] = e.conv[idx[i]] else job[e[1]] = e.conv[idx[i]] end
    end
    if reps > 1 then job.rep = rep end
    return job
  end
  -- the first job with the i-th value of the variable `k` (its digit i, the others 1)
  function src.first_with (k, i)
    local stride = reps
    for d = #vary, 1, -1 do
      if vary[d][1] == k then return 1 + (i - 1) * stride end
      stride = stride * #vary[d][2]
    end
  end
  return src
end

-- The source of the jobs of a Lua spec (a table) `spec`, named `who` in messages.
local function lua_source (spec, who)
  local function fail (field, msg) error(format("%s: %s: %s", who, field, msg), 0) end
  if type(spec) ~= "table" then
    error(format("%s: a spec is a table (a list of jobs, or { model = ..., vary = ..., "
      .. "outputs = ... }), got %s", who, type(spec)), 0)
  end
  local list = spec.jobs
  if list == nil and #spec > 0 then list = spec end
  for k in pairs(spec) do
    local item = list == spec and math.type(k) == "integer" and k >= 1 and k <= #spec
    if not item and not SPEC_FIELDS[k] then
      fail(tostring(k), "not a field of a spec (model, name, seed, steps, width, height, "
        .. "params, outputs, vary, replicates, jobs)")
    end
  end
  if list ~= nil and spec.vary ~= nil then fail("vary", "give jobs or vary, not both") end
  local reps = 1
  if spec.replicates ~= nil then
    local r, why = conv_whole(spec.replicates, 1)
    if r == nil then fail("replicates", why) end
    reps = r
    if list ~= nil then fail("replicates", "applies to a sweep (vary), not to a list of jobs") end
  end
  local base = newjob(spec, who)
  if list ~= nil then return list_source(spec, who, list, base) end
  return sweep_source(spec, who, reps, base)
end

-- {======================== no two jobs write the same file

--[[
The shape of the template `tpl` of the sweep `src`, whose first job is `job1`: the path it
gives every job, as a list of pieces -- literal text, or a token for a value that changes
from job to job ("id", "n", or "num" for any other number: the seed, a varied variable,
steps, width, height, rep; {rep} is {n} when the sweep is replicates alone) -- normalized
as `normalize` does the paths, its last segment (the file's name) as a list of pieces, and
its number of segments (depth). nil when a varied text (model, name) is in
the template: its values could hold "/" or be "..".

A number's text ("12", "-0.5", "1e+20") never holds "/", is never empty, "." or "..": a
segment with a token in it is a file or folder name for every job, and the shape's
normalization is that of every job's path.
]]
local function shape (src, job1, tpl)
  local pieces = {}
  local function lit (s)
    if type(pieces[#pieces]) == "string" then pieces[#pieces] = pieces[#pieces] .. s
    elseif s ~= "" then pieces[#pieces + 1] = s end
  end
  local pos = 1
  for a, k, b in tpl:gmatch("(){([^{}]*)}()") do
    lit(tpl:sub(pos, a - 1))
    pos = b
    if k == "id" or k == "n" then pieces[#pieces + 1] = { k }
    elseif k == "rep" and #src.vary == 0 then
      pieces[#pieces + 1] = { "n" }       -- replicates alone: job n is replicate n
    elseif k == "seed" or src.varied[k] then
      if k == "model" or k == "name" then return nil end
      pieces[#pieces + 1] = { "num" }
    else
      lit(placeholder(job1, k))           -- the same for every job (job 1 is checked)
    end
  end
  lit(tpl:sub(pos))
  -- the segments between the slashes of the literal text, normalized
  local segs, seg = {}, {}
  local function endseg ()
    local only = #seg == 0 and "" or (#seg == 1 and type(seg[1]) == "string" and seg[1])
    if only == ".." then segs[#segs] = nil
    elseif only ~= "" and only ~= "." then segs[#segs + 1] = seg end
    seg = {}
  end
  for _, p in ipairs(pieces) do
    if type(p) == "table" then
      seg[#seg + 1] = p
    else
      local from = 1
      while true do
        local s = p:find("/", from, true)
        local text = p:sub(from, (s or 0) - 1)
        if text ~= "" then
          if type(seg[#seg]) == "string" then seg[#seg] = seg[#seg] .. text
          else seg[#seg + 1] = text end
        end
        if s == nil then break end
        endseg()
        from = s + 1
      end
    end
  end
  endseg()
  local flat = {}
  for i, sg in ipairs(segs) do
    if i > 1 then flat[#flat + 1] = "/" end
    for _, p in ipairs(sg) do flat[#flat + 1] = p end
  end
  local first, last = nil, nil
  for i, p in ipairs(flat) do
    if type(p) == "table" then first, last = first or i, i end
  end
  local function text (from, to)
    local t = {}
    for i = from, to do t[#t + 1] = flat[i] end
    return table.concat(t)
  end
  if first == nil then
    return { prefix = text(1, #flat), suffix = "", name = segs[#segs], depth = #segs }
  end
  return { prefix = text(1, first - 1), suffix = text(last + 1, #flat), name = segs[#segs],
           depth = #segs }
end

-- Whether the file name `name` (a shape's last segment) gives back the job it was made for:
-- an {id} (all of one width in a sweep) with nothing but literal text on one side of it in
-- the name, or an {n} so placed whose other side is the name's end or text that does not
-- begin (end) with a digit.
local function names_job (name)
  local function literal (from, to)
    for i = from, to do if type(name[i]) == "table" then return false end end
    return true
  end
  local function nondigit (p, at)
    return type(p) == "string" and not p:sub(at, at):find("%d")
  end
  for j, p in ipairs(name) do
    if type(p) == "table" and (p[1] == "id" or p[1] == "n") then
      local before, after = literal(1, j - 1), literal(j + 1, #name)
      if p[1] == "id" and (before or after) then return true end
      if p[1] == "n" and ((before and (j == #name or nondigit(name[j + 1], 1))) or
                          (after and (j == 1 or nondigit(name[j - 1], -1)))) then
        return true
      end
    end
  end
  return false
end

local function starts (s, p) return s:sub(1, #p) == p end
local function ends (s, p) return p == "" or s:sub(-#p) == p end

-- Whether the paths of two shapes always differ: when they have not as many segments (a
-- token's text never holds "/"), or neither literal beginning is a beginning of the other,
-- or neither literal end an end of the other (two equal paths would begin, and end, with
-- both).
local function apart (a, b)
  return a.depth ~= b.depth or
         (not starts(a.prefix, b.prefix) and not starts(b.prefix, a.prefix)) or
         (not ends(a.suffix, b.suffix) and not ends(b.suffix, a.suffix))
end

--[[
Whether the templates of the sweep `src` show, by themselves, that no two of its jobs write
the same file and no job writes a file twice: every template's file name gives back its
job (names_job), so that two jobs' paths of one template differ; and any two templates (an
.obj's material file among them) are `apart`. `job1` is the sweep's first job, checked.
]]
local function proven (src, job1)
  if src.count == 1 then return true end
  local shapes = {}
  for _, t in ipairs(job1.templates) do
    local s = shape(src, job1, t.template)
    if s == nil or not names_job(s.name) then return false end
    shapes[#shapes + 1] = s
    if t.format == "obj" then          -- its material file: the same, .obj -> .mtl
      shapes[#shapes + 1] = { prefix = s.prefix, suffix = s.suffix:sub(1, -5) .. ".mtl",
                              name = s.name, depth = s.depth }
    end
  end
  for i = 1, #shapes do
    for j = i + 1, #shapes do
      if not apart(shapes[i], shapes[j]) then return false end
    end
  end
  return true
end

-- A hash of the text `s` (64 bits, 8 bytes at a time): the check of every job's paths
-- keeps a hash per file, and compares the files themselves when two hashes meet.
local function hash (s)
  local h, n = 0x2545F4914F6CDD1D ~ #s, #s
  s = s .. "\0\0\0\0\0\0\0"
  for i = 1, n, 8 do
    h = (h ~ string.unpack("<i8", s, i)) * 0x100000001B3
    h = h ~ (h >> 29)
  end
  return h
end

--[[
Checks every job of `src` (a list's, a CSV file's, or a sweep the templates of which prove
nothing): each job made and checked, ids unique (src.ids: id -> n), and no file written by
two jobs: `seen` keeps a hash of each file's path and the job that writes it (one integer
pair per file); when the hash of a path is met again, the jobs that wrote a path of that
hash are made again and their paths compared, so the check is exact.
]]
local function check_all (src)
  local seen, ids = {}, not src.vary and {} or nil    -- a sweep's ids are its numbers
  for n = 1, src.count do
    local job, claims = src.get(n)
    local prev = ids and ids[job.id]
    if prev then
      error(format("%s: %sjob id '%s' is also the id of the job at %s", job.where,
        src.col("id"), job.id, src.get(prev).where), 0)
    end
    if ids then ids[job.id] = n end
    for _, c in ipairs(claims) do
      local h = hash(c.path)
      local others = seen[h]
      if others ~= nil then
        for _, m in ipairs(type(others) == "table" and others or { others }) do
          if m ~= n then
            local other, oclaims = src.get(m)
            for _, oc in ipairs(oclaims) do
              if oc.path == c.path then
                error(format("%s: %s'%s' is also written by job %s (%s): give each job its "
                  .. "own files, with {id} for instance", job.where, src.col(c.field), c.path,
                  other.id, other.where), 0)
              end
            end
          end
        end
        if type(others) == "table" then others[#others + 1] = n
        elseif others ~= n then seen[h] = { others, n } end
      else
        seen[h] = n
      end
    end
  end
  src.ids = ids
end

-- }========================

-- Checks what is wrong with the spec of `src` before any job runs. A sweep whose templates
-- are `proven` is checked through job 1 and, for each model file it varies, the first job
-- with it (a job's paths can fail only through the text of a varied model or name, which
-- such templates do not hold); any other spec job by job (check_all).
local function check_source (src)
  if src.count == 0 then return end
  if src.vary then
    local job1 = src.raw(1)
    local templates = job1.templates
    complete(src, job1, 1)
    job1.templates = templates
    if proven(src, job1) then
      for _, e in ipairs(src.vary) do
        if e[1] == "model" then
          for i = 2, #e[2] do src.get(src.first_with("model", i)) end
        end
      end
      return
    end
  end
  check_all(src)
end

-- The source of the jobs of `spec` (as for M.jobs), checked; `who` is the public function
-- named in messages. src.count jobs; src.get(n) makes job n (and its claims, as complete);
-- src.id_to_n(id) is the number of the job of that id, or nil.
local function load_source (who, spec)
  local src, file, dir, base
  if type(spec) == "string" then
    file, dir = spec, dirname(spec)
    local ext = (spec:match("%.(%w+)$") or ""):lower()
    if ext == "csv" then
      src, base = csv_source(spec, readfile(spec)), 0
    elseif ext == "lua" then
      readfile(spec)                                  -- "cannot open" before loadfile's
      local chunk, err = loadfile(spec, "t")
      if chunk == nil then error(err, 0) end
      local ok, t = pcall(chunk)
      if not ok then error(strip_internal(t), 0) end
      if type(t) ~= "table" then
        error(format("%s returned %s, not a spec (end the file with `return { model = ..., "
          .. "vary = { ... }, outputs = { ... } }` or a list of jobs)", spec, type(t)), 0)
      end
      if t.dir ~= nil then error(format("%s: dir: a spec file's folder is its own", spec), 0) end
      src, base = lua_source(t, spec), t.seed
    else
      error(format("%s: '%s': a spec is a CSV file (.csv) or a Lua file (.lua)", who, spec), 0)
    end
  elseif type(spec) == "table" then
    dir = spec.dir or "."
    if type(dir) ~= "string" then error("spec: dir: a folder name expected", 0) end
    src, base = lua_source(spec, "spec"), spec.seed
  else
    error(format("%s: a spec (a file name or a table) expected, got %s", who, type(spec)), 0)
  end
  if base ~= nil then
    local b, why = conv_whole(base, math.mininteger)
    if b == nil then error(format("%s: seed: %s", file or "spec", why), 0) end
    base = b
  end
  src.file, src.dir, src.base, src.models = file, dir, base or 0, {}
  src.width = math.max(4, #tostring(src.count))
  src.idformat = "%0" .. src.width .. "d"
  function src.get (n) return complete(src, src.raw(n), n) end
  check_source(src)
  function src.id_to_n (id)
    if src.ids then return src.ids[id] end
    local n = #id == src.width and id:find("^%d+$") and math.tointeger(tonumber(id))
    return n and n >= 1 and n <= src.count and n or nil
  end
  return src
end

-- A list of `count` entries made when read: t[i] is get(i), a new table each time.
local function lazy_list (count, get)
  return setmetatable({}, {
    __len = function () return count end,
    __index = function (_, i)
      i = math.tointeger(i)
      if i and i >= 1 and i <= count then return (get(i)) end
      return nil
    end,
    __pairs = function (t)
      return function (_, i)
        i = i + 1
        if i <= count then return i, t[i] end
        return nil
      end, t, 0
    end,
  })
end

--- The jobs of a spec: the path of a CSV file (.csv) or a Lua file (.lua) that returns a
-- spec table, or a spec table (model paths relative to its `dir`, default the current
-- folder). Returns the list of jobs -- each made when it is read (jobs[n], ipairs, #jobs),
-- a new table each time -- each { n (its number), id, where (the spec's file and line,
-- "plants.csv:7", or the Lua field), model (as the spec names it), path (the file opened),
-- name, seed, steps, width, height, params (variable = value), outputs (a list of { format,
-- path }, paths normalized, relative to the output folder), rep }, and { file, dir, total }.
-- Raises naming the spec's file, line and column (or field) of what is wrong.
function M.jobs (spec)
  local src = load_source("lsys.batch.jobs", spec)
  return lazy_list(src.count, src.get), { file = src.file, dir = src.dir, total = src.count }
end

-- }===========================================================================================


-- {===========================================================================================
-- Manifests

-- The manifest of shard k of n in the folder `dir`.
local function manifest_name (k, n)
  return n == 1 and "manifest.jsonl" or format("manifest-%d-of-%d.jsonl", k, n)
end

-- The manifests in the folder `dir` (every run's, whatever its sharding).
local function manifests (dir)
  local p = io.popen("for f in " .. shq(dir) .. "/manifest*.jsonl; do "
    .. "[ -f \"$f\" ] && printf '%s\\n' \"$f\"; done 2>/dev/null")
  if p == nil then return {} end
  local list = {}
  for l in p:lines() do list[#list + 1] = l end
  p:close()
  table.sort(list)
  return list
end

-- What identifies a job's work: its model, seed, steps, variables, picture size and
-- outputs. A manifest line of another definition (the spec changed) is not this job's.
local function jobkey (j)
  local outs = array {}
  for i, o in ipairs(j.outputs or {}) do outs[i] = o.path end
  return json { model = j.model, name = j.name, seed = j.seed, steps = j.steps,
                params = j.params or {}, width = j.width, height = j.height, outputs = outs }
end

local OFFSET_BITS = 44                -- a record's place: file << 44 | byte offset

--[[
Where the manifests of the folder `dir` hold lines of the jobs of shard k of N of `src`:
{ files, at }, at[i] the place of the line of the shard's i-th job (file << OFFSET_BITS |
the line's byte offset), or a list of places for a job of several lines. Nothing but the
places is kept; a job's lines are read again when its status is asked for. A line of lsys
begins with its job's id ({"job":"0001",...); another line (edited, cut short by a killed
run) is decoded to find it, and passed over when it is not JSON.
]]
local function index_manifests (dir, src, k, N)
  local ok, cjson = pcall(require, "cjson.safe")
  if not ok then
    error("lsys.batch: lua-cjson is needed to read the manifests (Debian: apt-get install "
      .. "lua-cjson)", 0)
  end
  local files, at = manifests(dir), {}
  for fi, path in ipairs(files) do
    local f = io.open(path, "rb")
    if f then
      local off = 0
      for l in f:lines() do
        local id = l:match('^{"job":"([%w_.%-]+)"')
        if id == nil and not l:find('^{"run":') then
          local r = cjson.decode(l)
          id = type(r) == "table" and type(r.job) == "string" and r.job or nil
        end
        local n = id and src.id_to_n(id)
        if n and (n - 1) % N == k - 1 then
          local i, place = (n - 1) // N + 1, fi << OFFSET_BITS | off
          local e = at[i]
          if e == nil then at[i] = place
          elseif type(e) == "table" then e[#e + 1] = place
          else at[i] = { e, place } end
        end
        off = off + #l + 1
      end
      f:close()
    end
  end
  return { files = files, at = at, open = {}, cjson = cjson }
end

-- "done" when a manifest line says the job `job` ran ok with its present definition and its
-- files are there with the sizes that run wrote (not the times: folders merged by cp or
-- rsync keep their jobs done); "failed" when a line says it failed; else "todo".
local function status (job, records)
  local key, st = jobkey(job), "todo"
  for _, r in ipairs(records) do
    if type(r.outputs) == "table" and jobkey(r) == key then
      if r.status == "ok" then
        local same = true
        for _, o in ipairs(r.outputs) do
          local mtime, size
          if type(o) == "table" and type(o.path) == "string" then
            mtime, size = core.filestamp(join(job.dir, o.path))
          end
          if mtime == nil or size ~= o.bytes then same = false end
        end
        if same then return "done" end
        st = "todo"
      elseif r.status == "failed" then
        st = "failed"
      end
    end
  end
  return st
end

-- The status of the shard's i-th job `job`, from the lines `man` (index_manifests) places;
-- kept in place of them, so that a job's lines are read once.
local function job_status (man, i, job)
  local e = man.at[i]
  if e == nil then return "todo" end
  if type(e) == "string" then return e end
  local records = {}
  for _, place in ipairs(type(e) == "table" and e or { e }) do
    local fi = place >> OFFSET_BITS
    local f = man.open[fi]
    if f == nil then
      f = io.open(man.files[fi], "rb")
      man.open[fi] = f or false
    end
    if f then
      f:seek("set", place & ((1 << OFFSET_BITS) - 1))
      local r = man.cjson.decode(f:read("l") or "")
      if type(r) == "table" then records[#records + 1] = r end
    end
  end
  local st = status(job, records)
  man.at[i] = st
  return st
end

local function close_manifests (man)
  for fi, f in pairs(man.open) do
    if f then f:close() end
    man.open[fi] = nil
  end
end

-- The version of lsys (for the manifest): the library's when it is loaded (lsys.batch is
-- reached through it), else the program's, else nil.
local function version ()
  local lib = package.loaded.lsys
  return type(lib) == "table" and lib.version or host().version
end

-- This host's name (for the manifest), or nil.
local function hostname ()
  local f = io.open("/proc/sys/kernel/hostname", "r")
  local name = f and f:read("l")
  if f then f:close() end
  return name or os.getenv("HOSTNAME")
end

local function manifest_error (path, err)
  return format("cannot write the manifest '%s': %s", path, tostring(err))
end

--[[
Opens the manifest `path` for appending lines; a line a killed run left unfinished is ended
first. The manifest is the one file batch appends to rather than replaces (a shard's lines
accumulate over its runs), so it is not written through core.write_file: every write and
flush is checked (append), and the close (close_manifest); a failure raises.
]]
local function open_manifest (path)
  local last
  local r = io.open(path, "rb")
  if r then
    if r:seek("end") > 0 then
      r:seek("end", -1)
      last = r:read(1)
    end
    r:close()
  end
  local f, err = io.open(path, "ab")   -- the manifest: appended, every write checked (append)
  if f == nil then error(manifest_error(path, err), 0) end
  f:setvbuf("full", 1 << 16)
  return { f = f, path = path, cut = last ~= nil and last ~= "\n" }
end

-- Appends the record `r` as a line, written out at once (one write: a shard's lines never
-- mix, and a killed run loses at most the line being written). Raises when the system
-- refuses the bytes (a full disk, a file size limit).
local function append (m, r)
  local text = json(r) .. "\n"
  if m.cut then text, m.cut = "\n" .. text, false end
  local ok, err = m.f:write(text)
  if ok then ok, err = m.f:flush() end
  if not ok then
    m.f:close()
    error(manifest_error(m.path, err), 0)
  end
end

local function close_manifest (m)
  local ok, err = m.f:close()
  if not ok then error(manifest_error(m.path, err), 0) end
end

-- }===========================================================================================


-- {===========================================================================================
-- The output folder: links and temporaries

--[[
What the output folder `dir` holds that a run must know of, found once at its start (find
-H, which follows `dir` itself when it is a link, and nothing below it): `links`, the
symbolic links below it, by their paths relative to it (no job writes through one: core's
writer would replace the link's target); `temps`, the temporaries lsys's writer names
`.NAME.lsys-PID-N.tmp`, by the path of the file NAME they were for: { path, pid } each.
]]
local function scan_folder (dir)
  local root = dir:gsub("/+$", "")
  if root == "" then root = "/" end
  local prefix = root == "/" and "/" or root .. "/"
  local p = io.popen("find -H " .. shq(root) .. " -type l -print0 2>/dev/null; printf '\\0'; "
    .. "find -H " .. shq(root) .. " -type f -name '.*.lsys-*-*.tmp' -print0 2>/dev/null")
  local out = p and p:read("a") or ""
  if p then p:close() end
  local links, temps, second = {}, {}, false
  for path in out:gmatch("([^%z]*)%z") do
    if path == "" then
      second = true
    elseif path:sub(1, #prefix) == prefix then
      local rel = path:sub(#prefix + 1)
      if not second then
        links[rel] = true
      else
        local folder, name, pid = rel:match("^(.-)/?%.([^/]+)%.lsys%-(%d+)%-%d+%.tmp$")
        if name then
          local target = folder == "" and name or folder .. "/" .. name
          local list = temps[target] or {}
          temps[target], list[#list + 1] = list, { path = rel, pid = pid }
        end
      end
    end
  end
  return { links = links, nlinks = next(links) ~= nil, temps = temps }
end

-- Whether the process `pid` lives on this host (/proc; else `kill -0`, which a process of
-- another user also passes). When it cannot tell, it says yes.
local PROC = nil
local function alive (pid)
  if PROC == nil then
    local f = io.open("/proc/self/stat", "rb")
    PROC = f ~= nil
    if f then f:close() end
  end
  if PROC then
    local f = io.open("/proc/" .. pid .. "/stat", "rb")
    if f then f:close() end
    return f ~= nil
  end
  local p = io.popen("kill -0 " .. pid .. " 2>&1")
  local said = p and p:read("a") or ""
  local ok = p and p:close()
  return ok or not said:lower():find("no such process", 1, true)
end

-- Removes the temporaries `scan` found of the files `claims` (a job's, as complete gives
-- them) that dead processes left. Returns how many it removed.
local function clean_temps (scan, dir, claims)
  local removed = 0
  for _, c in ipairs(claims) do
    local list = scan.temps[c.path]
    if list then
      for _, t in ipairs(list) do
        if not t.gone and not alive(t.pid) and os.remove(join(dir, t.path)) then
          removed, t.gone = removed + 1, true
        end
      end
    end
  end
  return removed
end

-- The first of the folders and file of the path `path` (relative to the output folder)
-- that is a symbolic link `scan` found, or nil.
local function link_on (scan, path)
  if not scan.nlinks then return nil end
  local from = 1
  while true do
    local s = path:find("/", from, true)
    local sub = path:sub(1, (s or 0) - 1)
    if scan.links[sub] then return sub end
    if s == nil then return nil end
    from = s + 1
  end
end

-- }===========================================================================================


-- {===========================================================================================
-- Running a job

-- Makes the folder `dir` and the ones above it that are missing (`made` caches them).
local function mkdirs (dir, made)
  local ok, err = fs.mkdirs(dir, made)
  if not ok then error(err, 0) end
end

-- What a job's model file is told when it returns a single model and the job names one.
local SINGLE = "'name' picks one of a table of models"

-- The model of job `job`, made afresh (its file run again: nothing a job does to its model
-- reaches the next), with its seed, steps and variables. `chunks` caches the loaded files.
local function job_model (job, chunks)
  local v = load.run(job.path, { chunks = chunks, strip = true })
  v = load.pick(v, job.path, job.name, { single = SINGLE })
  if load.isproto(v) then
    if job.steps ~= nil or next(job.params) ~= nil then
      error(format("%s is a component graph: it has no derivation steps nor variables",
        job.path), 0)
    end
    v = load.expand(v, job.path, job.seed, { strip = true })
  end
  local m = v
  if job.steps ~= nil then m.steps = job.steps end
  m.seed = job.seed
  local env = m.env
  for k, x in pairs(job.params) do
    if env == nil or env[k] == nil then
      local names = load.variables(env)
      error(format("%s has no variable %s (%s)", job.path, k, #names == 0 and
        "its env is empty" or "its variables: " .. table.concat(names, ", ")), 0)
    end
    env[k] = x
  end
  return m
end

-- The statistics of a job's result: what the stats output holds. The same bytes wherever
-- and whenever the job runs (times go to the manifest).
local function stats (job, m, s, sc)
  local counts = {}
  for name, c in pairs(s:counts()) do counts[name] = c end
  local r = { job = job.id, model = job.model, name = job.name, seed = job.seed,
              steps = m.steps, params = job.params, modules = #s, counts = counts }
  if sc then
    r.triangles, r.vertices, r.lines, r.area = sc.ntriangles, sc.nvertices, sc.nlines,
      sc:area()
    local lo, hi = sc:bounds()
    if lo then r.bounds = { min = array(lo), max = array(hi) } end
  end
  return json(r) .. "\n"
end

--[[
Runs job `job`, writing its outputs under the folder `dir`; returns the record of the
manifest (status "ok" or "failed", with the error; the outputs with the size and time of
each file written). Each file is written whole or not at all; a job that fails leaves the
files it finished before the failure (each complete). A job that would write through a
symbolic link of the folder (`claims`, its files; ctx.scan, the folder's links) fails.
]]
local function run_job (job, claims, dir, ctx)
  local rec = { job = job.id, line = job.where, model = job.model, name = job.name,
                seed = job.seed, steps = job.steps, params = job.params, width = job.width,
                height = job.height, outputs = array {}, shard = ctx.shard, host = ctx.host }
  for i, o in ipairs(job.outputs) do rec.outputs[i] = { format = o.format, path = o.path } end
  local phases = {}
  local t0 = clock()
  local ok, err = pcall(function ()
    for _, c in ipairs(claims) do
      local link = link_on(ctx.scan, c.path)
      if link then
        error(format("cannot write '%s': '%s' is a symbolic link (lsys batch writes no file "
          .. "through a link)", join(dir, c.path), join(dir, link)), 0)
      end
    end
    local t = clock()
    local m = job_model(job, ctx.chunks)
    phases.load = clock() - t
    t = clock()
    local s <close> = m:derive()
    phases.derive = clock() - t
    local need_scene = false
    for _, o in ipairs(job.outputs) do
      if o.format ~= "lstring" then need_scene = true end
    end
    t = clock()
    local sc <close> = need_scene and m:interpret(s) or nil
    if sc then phases.interpret = clock() - t end
    for i, o in ipairs(job.outputs) do
      t = clock()
      local path = join(dir, o.path)
      mkdirs(dirname(path), ctx.made)
      if o.format == "png" then
        -- lsys.render(sc, ...) (which `require "lsys"` would bring in a cycle): the
        -- scene's view, and its supersampling
        local v = model.sceneview(sc)
        core.render(sc, { out = path, width = job.width or M.SIZE,
                          height = job.height or M.SIZE, supersample = v and v.supersample })
      elseif o.format == "lstring" then
        core.write_file(path, tostring(s) .. "\n")
      elseif o.format == "stats" then
        core.write_file(path, stats(job, m, s, sc))
      else
        sc:save(path)
      end
      rec.outputs[i].mtime, rec.outputs[i].bytes = core.filestamp(path)
      phases[o.format] = (phases[o.format] or 0) + clock() - t
    end
  end)
  rec.seconds = clock() - t0
  for k, v in pairs(phases) do phases[k] = math.floor(v * 1e6 + 0.5) / 1e6 end
  rec.seconds = math.floor(rec.seconds * 1e6 + 0.5) / 1e6
  rec.phases = phases
  rec.at = os.date("!%Y-%m-%dT%H:%M:%SZ")
  if ok then
    rec.status = "ok"
  else
    rec.status = "failed"
    rec.error = strip_internal(err)
  end
  return rec
end

-- }===========================================================================================



-- {===========================================================================================
-- Runs

local RUN_OPTS = { out = "string", shard = "any", force = "boolean", progress = "function" }

local function checkopts (who, opts)
  if opts == nil then return {} end
  if type(opts) ~= "table" then error(format("%s: an options table expected", who), 3) end
  for k, v in pairs(opts) do
    local t = RUN_OPTS[k]
    if t == nil then error(format("%s: unknown option '%s'", who, tostring(k)), 3) end
    if t ~= "any" and type(v) ~= t then
      error(format("%s: option '%s' must be a %s, got %s", who, k, t, type(v)), 3)
    end
  end
  return opts
end

-- The shard of option `shard`: nil (1 of 1), "K/N", "slurm" or { K, N }.
local function shard_opt (who, s)
  if s == nil then return 1, 1 end
  if type(s) == "table" then s = format("%s/%s", tostring(s[1]), tostring(s[2])) end
  if type(s) ~= "string" then
    error(format("%s: option 'shard' must be \"K/N\", \"slurm\" or { K, N }, got %s", who,
      type(s)), 0)
  end
  local k, n = M.parse_shard(s)
  if k == nil then error(format("%s: option 'shard' %s", who, n), 0) end
  return k, n
end

-- M.plan, for the public function `who`; p.job(i) makes the shard's i-th job (with its
-- status, and its claims), i from 1 to p.size.
local function plan (who, spec, opts)
  local k, n = shard_opt(who, opts.shard)
  local src = load_source(who, spec)
  local dir = opts.out or "."
  if dir == "" then error(format("%s: option 'out' must not be empty", who), 0) end
  local man = index_manifests(dir, src, k, n)
  local size = src.count >= k and (src.count - k) // n + 1 or 0
  local p = { total = src.count, k = k, n = n, dir = dir, file = src.file, size = size,
              manifest = join(dir, manifest_name(k, n)), man = man }
  function p.job (i)
    local job, claims = src.get(k + (i - 1) * n)
    job.dir = dir
    job.status = job_status(man, i, job)
    return job, claims
  end
  p.jobs = lazy_list(size, p.job)
  return p
end

--- What a run of `spec` with `opts` would do, without running anything: { jobs (this
-- shard's, each with `status`: "done", "failed" or "todo"; made when read, as M.jobs
-- makes them), total (the spec's jobs), k, n (shard k of n), dir (the output folder),
-- manifest (this shard's manifest), file (the spec's file) }. opts as for M.run.
function M.plan (spec, opts)
  local p = plan("lsys.batch.plan", spec, checkopts("lsys.batch.plan", opts))
  return { jobs = p.jobs, total = p.total, k = p.k, n = p.n, dir = p.dir,
           manifest = p.manifest, file = p.file }
end

local function now () return os.date("!%Y-%m-%dT%H:%M:%SZ") end

--- Runs the jobs of `spec` (as for M.jobs) in this process, those of one shard when asked.
-- opts: `out` (the folder the outputs' paths are relative to, made when missing; default
-- the current folder), `shard` ("K/N", "slurm" or { K, N }: the jobs whose number n has
-- (n - 1) % N == K - 1; default all), `force` (run jobs that are done too), `progress`
-- (called with an event table: { phase = "start" | "job" | "end", jobs, todo, done, ok,
-- failed, skipped, removed, seconds, job, record } at the start, after each job and at the
-- end). A job is skipped when a manifest line of the folder says it ran ok with the same
-- definition and its files are there with the sizes that run wrote. Temporaries that killed
-- runs left of the shard's files are removed first (`removed`: how many). Each job that
-- runs is recorded in the shard's manifest (`DIR/manifest.jsonl`, or
-- `DIR/manifest-K-of-N.jsonl`): job, seed, params, outputs (path, bytes, mtime), seconds,
-- status "ok" or "failed", error. A job that fails does not stop the others. Returns
-- { jobs, ok, failed, skipped, removed, seconds, manifest, failures = { { id, where, error }
-- }, k, n, total }. Raises for a bad spec (naming its file and line), bad options, or a
-- manifest it cannot write.
function M.run (spec, opts)
  opts = checkopts("lsys.batch.run", opts)
  local p = plan("lsys.batch.run", spec, opts)
  local k, n = p.k, p.n
  local dir, progress = p.dir, opts.progress
  local scan = scan_folder(dir)
  -- the first pass: what there is to do, and the temporaries of dead runs
  local todo, removed = 0, 0
  for i = 1, p.size do
    local job, claims = p.job(i)
    if opts.force or job.status ~= "done" then todo = todo + 1 end
    removed = removed + clean_temps(scan, dir, claims)
  end
  local r = { jobs = p.size, ok = 0, failed = 0, skipped = p.size - todo, removed = removed,
              seconds = 0, manifest = p.manifest, failures = {}, k = k, n = n,
              total = p.total }
  local ev = { phase = "start", jobs = p.size, todo = todo, done = 0, ok = 0, failed = 0,
               skipped = r.skipped, removed = removed, seconds = 0 }
  if progress then progress(ev) end
  if todo == 0 then
    close_manifests(p.man)
    if progress then ev.phase = "end" progress(ev) end
    return r
  end
  local made = {}
  mkdirs(dir, made)
  local mname = manifest_name(k, n)
  if link_on(scan, mname) then
    error(manifest_error(p.manifest, "it is a symbolic link (lsys batch writes no file "
      .. "through a link)"), 0)
  end
  local ctx = { chunks = {}, made = made, shard = format("%d/%d", k, n), host = hostname(),
                scan = scan }
  local m = open_manifest(p.manifest)
  local t0 = clock()
  append(m, { run = "start", spec = p.file, shard = ctx.shard, jobs = p.size, todo = todo,
              removed = removed, at = now(), host = ctx.host, lsys = version() })
  -- A job's model is garbage once it ran, its compiled rules with it (C memory Lua does not
  -- count); the generational collector (the lsys program's) may leave old garbage for a
  -- long time: a full collection whenever the heap has grown by half keeps a run of
  -- 100,000 jobs as small as one of 100.
  local heap = collectgarbage("count")
  local done = 0
  for i = 1, p.size do
    local job, claims = p.job(i)
    if opts.force or job.status ~= "done" then
      local rec = run_job(job, claims, dir, ctx)
      if collectgarbage("count") > 1.5 * heap + 1024 then
        collectgarbage()
        heap = collectgarbage("count")
      end
      append(m, rec)
      done = done + 1
      if rec.status == "ok" then
        r.ok = r.ok + 1
      else
        r.failed = r.failed + 1
        r.failures[#r.failures + 1] = { id = job.id, where = job.where, error = rec.error }
      end
      if progress then
        ev.phase, ev.done, ev.ok, ev.failed, ev.seconds, ev.job, ev.record =
          "job", done, r.ok, r.failed, clock() - t0, job, rec
        progress(ev)
      end
    end
  end
  close_manifests(p.man)
  r.seconds = clock() - t0
  append(m, { run = "end", shard = ctx.shard, ok = r.ok, failed = r.failed,
              skipped = r.skipped, seconds = math.floor(r.seconds * 1e3 + 0.5) / 1e3,
              at = now() })
  close_manifest(m)
  if progress then
    ev.phase, ev.job, ev.record, ev.seconds = "end", nil, nil, r.seconds
    progress(ev)
  end
  return r
end

-- }===========================================================================================

return M
