--- Running one job of lsys.batch: its model made afresh from its file, derived,
-- interpreted, and written to its files, with the record of the manifest that says so.
-- @module lsys.batch.job
local core = require "lsys.core"
local load = require "lsys.load"
local draw = require("lsys.render").draw
local B = require "lsys.batch.base"
local F = require "lsys.batch.fields"
local J = require "lsys.batch.json"
local link_on = require("lsys.batch.folder").link_on
local clock = require("lsys.program").clock
local strip_internal = require("lsys.util.errors").strip_internal
local fs = require "lsys.util.fs"
local hint = require("lsys.util.suggest").hint

local pairs, ipairs, next, error, pcall = pairs, ipairs, next, error, pcall
local os, math, string, table = os, math, string, table
local format = string.format
local join, dirname = F.join, F.dirname
local json, array = J.json, J.array
local _ENV = nil

local M = {}

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
      local near = hint(k, names)
      error(format("%s has no variable %s%s", job.path, k, near ~= "" and near or #names == 0
        and " (its env is empty)" or " (its variables: " .. table.concat(names, ", ") .. ")"), 0)
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
        draw(sc, { out = path, width = job.width or B.SIZE, height = job.height or B.SIZE })
      elseif o.format == "lstring" then
        s:write(path, "\n")             -- streamed from C, atomically
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

M.run_job, M.mkdirs = run_job, mkdirs

return M
