--- Batch runs (docs/batch.md): many jobs -- a model, values for its variables, a seed,
-- the files to write -- listed by a spec (a CSV file, or a Lua file or table that lists jobs
-- or describes a sweep), run one after the other in this process, or split into shards that
-- GNU parallel or a Slurm job array run on any number of hosts. What `lsys batch SPEC` runs.
--
-- Each job's seed comes from the spec alone (M.seed), and a job is in the same shard
-- wherever it runs (M.shard_of), so a sweep gives the same files in one process and in N.
-- Every file is written whole or not at all (core's atomic writer); a manifest of JSON lines
-- records each job that ran; a job whose files and manifest line say it was done is skipped
-- on the next run, so a run that was killed goes on where it stopped. A job that fails is
-- recorded with its message and the others go on.
--
-- Nothing holds every job: a spec is a source whose job n is made from n when it is needed,
-- so a listing, a shard and a resumed run take memory that does not grow with the spec's
-- jobs and time in proportion to the jobs they touch. Outputs are paths inside the output
-- folder, normalized before they are compared, written through no symbolic link of the
-- folder; a run removes the temporaries dead runs left of its files.
--
-- The package: base.lua (this table, its limits, seeds and shards), csv.lua, fields.lua (a
-- job's formats and values), spec.lua (CSV and Lua specs read as sources of raw jobs),
-- templates.lua (file names, and no two jobs writing one file), jobs.lua (the stream of
-- complete jobs), manifest.lua, folder.lua (links and temporaries), job.lua (running a job)
-- and this file, the runs.
-- @module lsys.batch
local M = require "lsys.batch.base"
local CSV = require "lsys.batch.csv"
local JOBS = require "lsys.batch.jobs"
local MAN = require "lsys.batch.manifest"
local FOLDER = require "lsys.batch.folder"
local JOB = require "lsys.batch.job"
local join = require("lsys.batch.fields").join
local clock = require("lsys.program").clock

local type, pairs, error, tostring = type, pairs, error, tostring
local os, math, string, collectgarbage = os, math, string, collectgarbage
local format = string.format
local load_source, lazy_list = JOBS.source, JOBS.lazy_list
local manifest_name, index_manifests, job_status, close_manifests =
      MAN.manifest_name, MAN.index_manifests, MAN.job_status, MAN.close_manifests
local version, hostname, manifest_error = MAN.version, MAN.hostname, MAN.manifest_error
local open_manifest, append, close_manifest = MAN.open_manifest, MAN.append, MAN.close_manifest
local scan_folder, clean_temps, link_on = FOLDER.scan_folder, FOLDER.clean_temps, FOLDER.link_on
local run_job, mkdirs = JOB.run_job, JOB.mkdirs
local _ENV = nil

M.csv = CSV.csv                     -- lsys.batch.csv(text, name): the records of CSV text

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
