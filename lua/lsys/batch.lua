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
-- @module lsys.batch
local core = require "lsys.core"
local shortest, shq = require("lsys.text").number, require("lsys.text").shq
local model = require "lsys.model"
local host = require("lsys.program").host

local type, pairs, ipairs, next, error, pcall, tostring, tonumber, require, loadfile, select,
      setmetatable, getmetatable =
      type, pairs, ipairs, next, error, pcall, tostring, tonumber, require, loadfile, select,
      setmetatable, getmetatable
local io, os, math, string, table, debug, collectgarbage, package =
      io, os, math, string, table, debug, collectgarbage, package
local format = string.format
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
-- Helpers: the clock, messages, JSON

local function clock ()
  local f = host().clock
  return f ~= nil and f() or os.clock()
end

-- The folder holding lsys's own Lua modules, as error positions show it: a job's message
-- names the user's file, not where in lsys it was raised (as lsys.cli.strip_internal).
local SRCDIR = (debug.getinfo(1, "S").source:match("^@(.*)lsys[/\\]batch%.lua$"))

local function strip_internal (msg)
  msg = tostring(msg)
  if SRCDIR == nil or SRCDIR == "" then return msg end
  return (msg:gsub(SRCDIR:gsub("%p", "%%%0") .. "lsys[/\\][%w_/\\]*%.lua:%d+: ", ""))
end

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
                     "todo", "ok", "failed", "skipped", "spec", "at", "host", "lsys" } do
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
  local rows = {}
  local i, len, line = 1, #text, 1
  if text:sub(1, 3) == "\239\187\191" then i = 4 end
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
    if not blank then rows[#rows + 1] = row end
  end
  return rows
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

local function readfile (path)
  local f, err = io.open(path, "rb")
  if f == nil then error(format("cannot open '%s': %s", path, tostring(err):match(": ([^:]*)$")
    or tostring(err)), 0) end
  local text, rerr = f:read("a")
  f:close()
  if text == nil then error(format("cannot read '%s': %s", path, tostring(rerr)), 0) end
  return text
end

local function isfile (path)
  local f = io.open(path, "r")
  if f == nil then return false end
  local ok, err = f:read(0)
  f:close()
  return ok ~= nil or err == nil
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

-- The job's template `tpl` with its placeholders replaced; or nil and why.
local function expand (job, tpl)
  local why
  local path = tpl:gsub("{([^{}]*)}", function (k)
    local v, err = placeholder(job, k)
    if v == nil then why = why or err end
    return v
  end)
  if why then return nil, why end
  if path:find("[{}]") then return nil, format("'%s': an unmatched { or }", tpl) end
  if path:find("%c") or path:find("/$") then
    return nil, format("'%s' is not a file name", path)
  end
  return path
end

--[[
The jobs of a spec as lists of raw fields, made complete: ids (given, or the job's number
padded with zeros to 4 digits, more when there are 10,000 jobs or more), seeds (given, or
M.seed(base, n)), the outputs' paths (templates expanded), each checked; raises naming
where the job comes from (`job.where`, "plants.csv:7") and the field (`job.col[field]`).
]]
local function complete (jobs, base, dir)
  local width = math.max(4, #tostring(#jobs))
  local ids, paths, models = {}, {}, {}
  for n, job in ipairs(jobs) do
    local function fail (field, msg)
      local col = field and job.col(field) or ""
      error(format("%s: %s%s", job.where, col, msg), 0)
    end
    job.n = n
    job.id = job.id or format("%0" .. width .. "d", n)
    if ids[job.id] then
      fail("id", format("job id '%s' is also the id of the job at %s", job.id,
        ids[job.id].where))
    end
    ids[job.id] = job
    if job.seed == nil then job.seed = M.seed(base, n) end
    if job.model == nil then fail("model", "no model file given") end
    job.path = join(dir, job.model)
    if models[job.path] == nil then models[job.path] = isfile(job.path) end
    if not models[job.path] then
      fail("model", format("cannot open '%s'%s", job.path, dir ~= "." and
        " (a model's path is relative to the spec's folder)" or ""))
    end
    if #job.templates == 0 then
      fail(nil, "no outputs: give file name templates such as png/{id}.png")
    end
    local outs, mine = {}, {}
    for _, t in ipairs(job.templates) do
      local path, why = expand(job, t.template)
      if path == nil then fail(t.field, why) end
      if mine[path] then fail(t.field, format("'%s' is written twice by this job", path)) end
      local other = paths[path]
      if other then
        fail(t.field, format("'%s' is also written by job %s (%s): give each job its own "
          .. "files, with {id} for instance", path, other.id, other.where))
      end
      mine[path], paths[path] = true, job
      outs[#outs + 1] = { format = t.format, path = path, i = #outs + 1 }
    end
    table.sort(outs, function (a, b)       -- a job writes its formats in one order
      if a.format ~= b.format then return FORMAT_RANK[a.format] < FORMAT_RANK[b.format] end
      return a.i < b.i
    end)
    for _, o in ipairs(outs) do o.i = nil end
    job.outputs, job.templates, job.col = outs, nil, nil
  end
  return jobs
end

-- The jobs of the CSV file `path` (text `text`): one job per record after the header.
local function csv_jobs (path, text)
  local rows = M.csv(text, path)
  local head = rows[1]
  if head == nil then error(format("%s: no header line and no jobs", path), 0) end
  local cols, seen = {}, {}
  local has_out = false
  for i, name in ipairs(head) do
    local function fail (msg) error(format("%s:%d: column %d: %s", path, head.line, i, msg), 0) end
    if name == "" then fail("a column without a name") end
    if seen[name] then fail(format("'%s' is also column %d", name, seen[name])) end
    seen[name] = i
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
    cols[i] = name
  end
  if not seen.model then
    error(format("%s:%d: no column 'model' (the model file of each job)", path, head.line), 0)
  end
  if not has_out then
    error(format("%s:%d: no output column: add 'out' (file name templates such as "
      .. "png/{id}.png, separated by ;) or png, glb, obj, ply, lstring, stats", path,
      head.line), 0)
  end
  local jobs = {}
  for r = 2, #rows do
    local row = rows[r]
    local where = format("%s:%d", path, row.line)
    if #row ~= #head then
      error(format("%s: %d field%s, the header (line %d) has %d", where, #row,
        #row == 1 and "" or "s", head.line, #head), 0)
    end
    local job = { where = where, params = {}, templates = {},
                  col = function (name) return format("column '%s': ", name) end }
    for i, name in ipairs(cols) do
      local v = row[i]
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
    jobs[#jobs + 1] = job
  end
  return jobs
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

-- A new job with the spec's defaults.
local function newjob (spec, who, where)
  local job = { where = where, params = {}, templates = {},
                col = function (name) return name .. ": " end }
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

-- The jobs of a Lua spec (a table) `spec`, named `who` in messages.
local function lua_jobs (spec, who)
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
  local jobs = {}
  if list ~= nil then
    if type(list) ~= "table" then fail("jobs", "a list of jobs expected") end
    for i, t in ipairs(list) do
      local field = list == spec and format("[%d]", i) or format("jobs[%d]", i)
      local job = newjob(spec, who, format("%s: %s", who, field))
      if type(t) ~= "table" then fail(field, "a job (a table) expected") end
      for k, v in pairs(t) do setfield(job, k, v, field .. "." .. tostring(k), fail) end
      jobs[i] = job
    end
    return jobs
  end
  local vary = spec.vary and vary_list(spec.vary, fail) or {}
  local seeded = false
  for _, e in ipairs(vary) do
    for i, v in ipairs(e[2]) do          -- each value checked once, before the product
      setfield({ params = {} }, e[1], v, format("vary.%s[%d]", e[1], i), fail)
    end
    seeded = seeded or e[1] == "seed"
  end
  if seeded and reps > 1 then
    fail("replicates", "with vary.seed every replicate would have the same seed: vary the "
      .. "seed or give replicates, not both")
  end
  -- the product: the first variable slowest, the last fastest, then the replicates
  local idx = {}
  for i = 1, #vary do idx[i] = 1 end
  while true do
    for rep = 1, reps do
      local parts = {}
      for i, e in ipairs(vary) do
        parts[i] = format("%s=%s", e[1], tostring(e[2][idx[i]]))
      end
      if reps > 1 then parts[#parts + 1] = format("rep=%d", rep) end
      local job = newjob(spec, who, #parts > 0 and format("%s: vary %s", who,
        table.concat(parts, " ")) or who)
      for i, e in ipairs(vary) do setfield(job, e[1], e[2][idx[i]], "vary." .. e[1], fail) end
      if reps > 1 then job.rep = rep end
      jobs[#jobs + 1] = job
    end
    local i = #vary
    while i >= 1 do
      idx[i] = idx[i] + 1
      if idx[i] <= #vary[i][2] then break end
      idx[i] = 1
      i = i - 1
    end
    if i < 1 then break end
  end
  return jobs
end

-- The jobs of `spec` (as for M.jobs); `who` is the public function named in messages.
local function load_jobs (who, spec)
  local jobs, file, dir, base
  if type(spec) == "string" then
    file, dir = spec, dirname(spec)
    local ext = (spec:match("%.(%w+)$") or ""):lower()
    if ext == "csv" then
      jobs, base = csv_jobs(spec, readfile(spec)), 0
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
      jobs = lua_jobs(t, spec)
      base = t.seed
    else
      error(format("%s: '%s': a spec is a CSV file (.csv) or a Lua file (.lua)", who, spec), 0)
    end
  elseif type(spec) == "table" then
    dir = spec.dir or "."
    if type(dir) ~= "string" then error("spec: dir: a folder name expected", 0) end
    jobs, base = lua_jobs(spec, "spec"), spec.seed
  else
    error(format("%s: a spec (a file name or a table) expected, got %s", who, type(spec)), 0)
  end
  if base ~= nil then
    local b, why = conv_whole(base, math.mininteger)
    if b == nil then error(format("%s: seed: %s", file or "spec", why), 0) end
    base = b
  end
  complete(jobs, base or 0, dir)
  return jobs, { file = file, dir = dir, total = #jobs }
end

--- The jobs of a spec: the path of a CSV file (.csv) or a Lua file (.lua) that returns a
-- spec table, or a spec table (model paths relative to its `dir`, default the current
-- folder). Returns the list of jobs, each { n (its number), id, where (the spec's file and
-- line, "plants.csv:7", or the Lua field), model (as the spec names it), path (the file
-- opened), name, seed, steps, width, height, params (variable = value), outputs (a list of
-- { format, path }, paths relative to the output folder), rep }, and { file, dir, total }.
-- Raises naming the spec's file, line and column (or field) of what is wrong.
function M.jobs (spec) return load_jobs("lsys.batch.jobs", spec) end

-- }===========================================================================================


-- {===========================================================================================
-- Manifests

-- The manifest of shard k of n in the folder `dir`.
local function manifest_name (k, n)
  return n == 1 and "manifest.jsonl" or format("manifest-%d-of-%d.jsonl", k, n)
end

-- One word for a POSIX shell.

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

-- The job lines of the manifests in `dir`: job id -> list of records (decoded). A line cut
-- short by a killed run, or not JSON, is passed over.
local function read_manifests (dir)
  local ok, cjson = pcall(require, "cjson.safe")
  if not ok then
    error("lsys.batch: lua-cjson is needed to read the manifests (Debian: apt-get install "
      .. "lua-cjson)", 0)
  end
  local byjob = {}
  for _, path in ipairs(manifests(dir)) do
    local f = io.open(path, "rb")
    if f then
      for l in f:lines() do
        local r = cjson.decode(l)
        if type(r) == "table" and type(r.job) == "string" then
          local t = byjob[r.job] or {}
          byjob[r.job], t[#t + 1] = t, r
        end
      end
      f:close()
    end
  end
  return byjob
end

-- "done" when a manifest line says the job `job` ran ok with its present definition and its
-- files are there with the sizes that run wrote (not the times: folders merged by cp or
-- rsync keep their jobs done); "failed" when a line says it failed; else "todo".
local function status (job, records)
  local key, st = jobkey(job), "todo"
  for _, r in ipairs(records or {}) do
    if type(r.outputs) == "table" and jobkey(r) == key then
      if r.status == "ok" then
        local same = true
        for _, o in ipairs(r.outputs) do
          local mtime, size = core.filestamp(join(job.dir, o.path))
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

-- Opens the manifest `path` for appending lines; a line a killed run left unfinished is
-- ended first.
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
  local f, err = io.open(path, "ab")
  if f == nil then error(format("cannot write the manifest '%s': %s", path, tostring(err)), 0) end
  f:setvbuf("full", 1 << 16)
  if last and last ~= "\n" then f:write("\n") end
  return f
end

-- Appends the record `r` as a line, written out at once (one write: a shard's lines never
-- mix, and a killed run loses at most the line being written).
local function append (f, r)
  f:write(json(r), "\n")
  f:flush()
end

-- }===========================================================================================


-- {===========================================================================================
-- Running a job

-- Makes the folder `dir` and the ones above it that are missing (`made` caches them).
local function mkdirs (dir, made)
  if made[dir] then return end
  local path = dir:sub(1, 1) == "/" and "/" or ""
  for seg in dir:gmatch("[^/]+") do
    path = path .. seg
    if not made[path] then
      local ok, err = core.mkdir(path)
      if not ok then error(err, 0) end
      made[path] = true
    end
    path = path .. "/"
  end
  made[dir] = true
end

local function is_model (v)
  return model.ismodel(v)
end

local function is_proto (v)
  return type(v) == "table" and v.links ~= nil and require("lsys.components.proto").isproto(v)
end

-- The model of job `job`, made afresh (its file run again: nothing a job does to its model
-- reaches the next), with its seed, steps and variables. `chunks` caches the loaded files.
local function job_model (job, chunks)
  local chunk = chunks[job.path]
  if chunk == nil then
    local c, err = loadfile(job.path, "t")
    chunk = c or err
    chunks[job.path] = chunk
  end
  if type(chunk) ~= "function" then error(chunk, 0) end
  local ok, v = model.runfile(job.path, chunk)
  if not ok then
    local msg = strip_internal(v)
    error(msg:find(job.path, 1, true) and msg or job.path .. ": " .. msg, 0)
  end
  if not is_model(v) and not is_proto(v) then
    local names = {}
    if type(v) == "table" then
      for k, x in pairs(v) do
        if type(k) == "string" and (is_model(x) or is_proto(x)) then names[#names + 1] = k end
      end
      table.sort(names)
    end
    if #names == 0 then
      error(format("%s returned %s, not a model (end the file with `return lsys.lsystem "
        .. "{ ... }`, a component graph's root prototype, or a table of models)", job.path,
        type(v)), 0)
    end
    local name = job.name or names[1]
    if v[name] == nil or not (is_model(v[name]) or is_proto(v[name])) then
      error(format("%s has no model named '%s' (models: %s)", job.path, name,
        table.concat(names, ", ")), 0)
    end
    v = v[name]
  elseif job.name ~= nil then
    error(format("%s returns a single model; 'name' picks one of a table of models",
      job.path), 0)
  end
  if is_proto(v) then
    if job.steps ~= nil or next(job.params) ~= nil then
      error(format("%s is a component graph: it has no derivation steps nor variables",
        job.path), 0)
    end
    local cok, m = pcall(require("lsys.components").model, v, { seed = job.seed })
    if not cok then error(format("%s: %s", job.path, strip_internal(m)), 0) end
    v = m
  end
  local m = v
  if job.steps ~= nil then m.steps = job.steps end
  m.seed = job.seed
  local env = m.env
  for k, x in pairs(job.params) do
    if env == nil or env[k] == nil then
      local names = {}
      for name in pairs(env or {}) do
        if type(name) == "string" then names[#names + 1] = name end
      end
      table.sort(names)
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
files it finished before the failure (each complete).
]]
local function run_job (job, dir, ctx)
  local rec = { job = job.id, line = job.where, model = job.model, name = job.name,
                seed = job.seed, steps = job.steps, params = job.params, width = job.width,
                height = job.height, outputs = array {}, shard = ctx.shard, host = ctx.host }
  for i, o in ipairs(job.outputs) do rec.outputs[i] = { format = o.format, path = o.path } end
  local phases = {}
  local t0 = clock()
  local ok, err = pcall(function ()
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

-- M.plan, for the public function `who`.
local function plan (who, spec, opts)
  local k, n = shard_opt(who, opts.shard)
  local all, info = load_jobs(who, spec)
  local dir = opts.out or "."
  if dir == "" then error(format("%s: option 'out' must not be empty", who), 0) end
  local records = read_manifests(dir)
  local jobs = {}
  for _, job in ipairs(all) do
    if M.shard_of(job.n, n) == k then
      job.dir = dir
      job.status = status(job, records[job.id])
      jobs[#jobs + 1] = job
    end
  end
  return { jobs = jobs, total = #all, k = k, n = n, dir = dir, file = info.file,
           manifest = join(dir, manifest_name(k, n)) }
end

--- What a run of `spec` with `opts` would do, without running anything: { jobs (this
-- shard's, each with `status`: "done", "failed" or "todo"), total (the spec's jobs), k, n
-- (shard k of n), dir (the output folder), manifest (this shard's manifest), file (the
-- spec's file) }. opts as for M.run.
function M.plan (spec, opts)
  return plan("lsys.batch.plan", spec, checkopts("lsys.batch.plan", opts))
end

--- Runs the jobs of `spec` (as for M.jobs) in this process, those of one shard when asked.
-- opts: `out` (the folder the outputs' paths are relative to, made when missing; default
-- the current folder), `shard` ("K/N", "slurm" or { K, N }: the jobs whose number n has
-- (n - 1) % N == K - 1; default all), `force` (run jobs that are done too), `progress`
-- (called with an event table: { phase = "start" | "job" | "end", jobs, todo, done, ok,
-- failed, skipped, seconds, job, record } at the start, after each job and at the end).
-- A job is skipped when a manifest line of the folder says it ran ok with the same
-- definition and its files are there with the sizes that run wrote. Each job that runs is
-- recorded in the shard's manifest (`DIR/manifest.jsonl`, or `DIR/manifest-K-of-N.jsonl`):
-- job, seed, params, outputs (path, bytes, mtime), seconds, status "ok" or "failed", error.
-- A job that fails does not stop the others. Returns { jobs, ok, failed, skipped, seconds,
-- manifest, failures = { { id, where, error } }, k, n, total }. Raises for a bad spec
-- (naming its file and line) or bad options.
function M.run (spec, opts)
  opts = checkopts("lsys.batch.run", opts)
  local p = plan("lsys.batch.run", spec, opts)
  local k, n = p.k, p.n
  local dir, progress = p.dir, opts.progress
  local made = {}
  local todo = {}
  for _, job in ipairs(p.jobs) do
    if opts.force or job.status ~= "done" then todo[#todo + 1] = job end
  end
  local r = { jobs = #p.jobs, ok = 0, failed = 0, skipped = #p.jobs - #todo, seconds = 0,
              manifest = p.manifest, failures = {}, k = k, n = n, total = p.total }
  local ev = { phase = "start", jobs = #p.jobs, todo = #todo, done = 0, ok = 0, failed = 0,
               skipped = r.skipped, seconds = 0 }
  if progress then progress(ev) end
  if #todo == 0 then
    if progress then ev.phase = "end" progress(ev) end
    return r
  end
  mkdirs(dir, made)
  local ctx = { chunks = {}, made = made, shard = format("%d/%d", k, n), host = hostname() }
  local f = open_manifest(p.manifest)
  local t0 = clock()
  append(f, { run = "start", spec = p.file, shard = ctx.shard, jobs = #p.jobs,
              todo = #todo, at = os.date("!%Y-%m-%dT%H:%M:%SZ"), host = ctx.host,
              lsys = version() })
  -- A job's model is garbage once it ran, its compiled rules with it (C memory Lua does not
  -- count); the generational collector (the lsys program's) may leave old garbage for a
  -- long time: a full collection whenever the heap has grown by half keeps a run of
  -- 100,000 jobs as small as one of 100.
  local heap = collectgarbage("count")
  for i, job in ipairs(todo) do
    local rec = run_job(job, dir, ctx)
    if collectgarbage("count") > 1.5 * heap + 1024 then
      collectgarbage()
      heap = collectgarbage("count")
    end
    append(f, rec)
    if rec.status == "ok" then
      r.ok = r.ok + 1
    else
      r.failed = r.failed + 1
      r.failures[#r.failures + 1] = { id = job.id, where = job.where, error = rec.error }
    end
    if progress then
      ev.phase, ev.done, ev.ok, ev.failed, ev.seconds, ev.job, ev.record =
        "job", i, r.ok, r.failed, clock() - t0, job, rec
      progress(ev)
    end
  end
  r.seconds = clock() - t0
  append(f, { run = "end", shard = ctx.shard, ok = r.ok, failed = r.failed,
              skipped = r.skipped, seconds = math.floor(r.seconds * 1e3 + 0.5) / 1e3,
              at = os.date("!%Y-%m-%dT%H:%M:%SZ") })
  f:close()
  if progress then
    ev.phase, ev.job, ev.record, ev.seconds = "end", nil, nil, r.seconds
    progress(ev)
  end
  return r
end

-- }===========================================================================================

return M
