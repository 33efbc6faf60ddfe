--- The jobs of an lsys.batch spec as a stream: the spec read and checked before any job runs,
-- then job n made complete from n when it is asked for (its id, seed, model file and
-- outputs), in a list made as it is read.
-- @module lsys.batch.jobs
local B = require "lsys.batch.base"
local F = require "lsys.batch.fields"
local S = require "lsys.batch.spec"
local T = require "lsys.batch.templates"
local isfile = require("lsys.util.fs").isfile
local strip_internal = require("lsys.util.errors").strip_internal

local type, ipairs, error, pcall, tostring, tonumber, loadfile, setmetatable =
      type, ipairs, error, pcall, tostring, tonumber, loadfile, setmetatable
local io, math, string, table = io, math, string, table
local format = string.format
local FORMAT_RANK, conv_whole, join, dirname = F.FORMAT_RANK, F.conv_whole, F.join, F.dirname
local expand, companion, proven, check_all = T.expand, T.companion, T.proven, T.check_all
local csv_source, lua_source = S.csv_source, S.lua_source
local _ENV = nil

local M = {}

-- A spec is read as a source of jobs: its number of jobs, and job n made from n alone when
-- it is asked for (a sweep's from n's digits in the mixed radix of its lists, a CSV
-- record's from the record, a list's from its entry), so that nothing holds every job: a
-- shard, a listing and a resumed run make only the jobs they touch. What is wrong with a
-- spec is said before any job runs (check_source below).

local function readfile (path)
  local f, err = io.open(path, "rb")
  if f == nil then error(format("cannot open '%s': %s", path, tostring(err):match(": ([^:]*)$")
    or tostring(err)), 0) end
  local text, rerr = f:read("a")
  f:close()
  if text == nil then error(format("cannot read '%s': %s", path, tostring(rerr)), 0) end
  return text
end

local function outputs_order (a, b)
  if a.format ~= b.format then return FORMAT_RANK[a.format] < FORMAT_RANK[b.format] end
  return a.i < b.i
end

--[[
Makes the job `job` (a table of raw fields: where, col, params, templates, and what the spec
gives of id, seed, model, name, steps, width, height, rep) complete as job number `n` of
the source `src`: its id (given, or n padded with zeros to src.width digits), seed (given,
or lsys.batch.seed(src.base, n)), model file (found from src.dir, checked once per file), outputs
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
  if job.seed == nil then job.seed = B.seed(src.base, n) end
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
    local beside = companion(path, t.format)
    if beside ~= nil then claim(beside, t.field, path) end
    outs[#outs + 1] = { format = t.format, path = path, i = #outs + 1 }
  end
  if #outs > 1 then table.sort(outs, outputs_order) end    -- a job writes its formats in one order
  for _, o in ipairs(outs) do o.i = nil end
  job.outputs, job.templates, job.col = outs, nil, nil
  return job, claims
end

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

-- The source of the jobs of `spec` (as for lsys.batch.jobs), checked; `who` is the public function
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

M.source, M.lazy_list = load_source, lazy_list

return M
