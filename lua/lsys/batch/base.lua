--- The table that is lsys.batch, which init.lua fills in: its limits, read from it at each
-- use by every file of the package (a user may change them), and the seeds and shards of jobs.
-- @module lsys.batch.base
local type, error, tonumber = type, error, tonumber
local os, math, string = os, math, string
local format = string.format
local _ENV = nil

local M = {}

M.MAX_SIZE = 16384                  -- the largest picture width and height
M.SIZE = 800                        -- a picture's width and height when the spec gives none
M.MAX_JOBS = 1000000000             -- the most jobs a spec may make

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

return M
