--- The manifests of lsys.batch: a JSON line for each job that ran, appended to its shard's
-- file, read back to tell the jobs that are done from those to do.
-- @module lsys.batch.manifest
local core = require "lsys.core"
local J = require "lsys.batch.json"
local shq = require("lsys.util.text").shq
local join = require("lsys.batch.fields").join
local host = require("lsys.program").host

local type, pairs, ipairs, error, pcall, tostring, require =
      type, pairs, ipairs, error, pcall, tostring, require
local io, os, string, table, package = io, os, string, table, package
local format = string.format
local json, array = J.json, J.array
local _ENV = nil

local M = {}

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

M.manifest_name, M.index_manifests, M.job_status, M.close_manifests = manifest_name,
  index_manifests, job_status, close_manifests
M.version, M.hostname, M.manifest_error = version, hostname, manifest_error
M.open_manifest, M.append, M.close_manifest = open_manifest, append, close_manifest

return M
