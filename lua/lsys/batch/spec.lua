--- The specs of lsys.batch read as sources of raw jobs: a CSV file's records, a Lua spec's
-- list of jobs, or its sweep, job n made from n alone when it is asked for.
-- @module lsys.batch.spec
local B = require "lsys.batch.base"
local CSV = require "lsys.batch.csv"
local F = require "lsys.batch.fields"
local formats = require "lsys.batch.formats"
local series = require("lsys.util.text").series

local type, pairs, ipairs, error, tostring = type, pairs, ipairs, error, tostring
local math, string, table = math, string, table
local format = string.format
local csv_record, csv_start = CSV.record, CSV.start
local FORMATS, FORMAT_RANK, RESERVED, CONV = F.FORMATS, F.FORMAT_RANK, F.RESERVED, F.CONV
local show, conv_number, conv_whole, isname, output_format =
      F.show, F.conv_number, F.conv_whole, F.isname, F.output_format
local _ENV = nil

local M = {}

-- The formats' names as the messages list them: "png, glb, obj, ply, lstring, stats" and
-- "png, glb, obj, ply, lstring and stats".
local NAMES, NAMES_AND = series(formats.names), series(formats.names, "and")

-- The number of jobs `count` (a float: a sweep's may be past 2^63) as an integer, checked
-- against lsys.batch.MAX_JOBS; `where` and `what` say where they come from.
local function check_count (where, what, count)
  if count > B.MAX_JOBS then
    error(format("%s: %s %s jobs, more than the limit of %d (lsys.batch.MAX_JOBS)", where, what,
      count < 2^53 and format("%d", math.tointeger(count)) or format("%.3e", count),
      B.MAX_JOBS), 0)
  end
  return math.tointeger(count)
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
        .. "out, %s, and a model variable per column", name, NAMES_AND))
    end
    if not RESERVED[name] and not isname(name) then
      fail(format("'%s' is not a model variable's name (letters, digits and _, not starting "
        .. "with a digit) nor one of id, model, name, seed, steps, width, height, out, %s",
        name, NAMES))
    end
    if name == "out" or FORMAT_RANK[name] then has_out = true end
    cols[c] = name
  end
  if not seen.model then
    error(format("%s:%d: no column 'model' (the model file of each job)", path, head.line), 0)
  end
  if not has_out then
    error(format("%s:%d: no output column: add 'out' (file name templates such as "
      .. "png/{id}.png, separated by ;) or %s", path, head.line, NAMES), 0)
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
      fail("outputs", format("%s is not a format (%s)", show(k), NAMES))
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

-- The error function of a spec's fields: "who: field: msg", raised without a position.
local function failer (who)
  return function (field, msg) error(format("%s: %s: %s", who, field, msg), 0) end
end

-- A raw job with the spec's defaults, from which every job of the spec is cloned.
local function newjob (spec, who)
  local job = { params = {}, templates = {}, col = function (name) return name .. ": " end }
  local fail = failer(who)
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
  local fail = failer(who)
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
  local fail = failer(who)
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
  local fail = failer(who)
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

M.csv_source, M.lua_source = csv_source, lua_source

return M
