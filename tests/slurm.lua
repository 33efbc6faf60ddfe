--- A private one-node Slurm cluster for the batch specs and bench/batch.lua: munged with a
-- key of its own, slurmctld and slurmd on this host, with ports, state, spool and logs in a
-- folder of their own, so that it touches no system Slurm or munge and a second run beside
-- it does not collide. Debian's packages slurmctld, slurmd, slurm-client and munge
-- (./setup.sh installs them); the daemons run as the user running the specs, which must be
-- root for slurmd to start jobs as themselves (otherwise `start` says so).
--
--   local S = require "tests.slurm"        (or dofile "tests/slurm.lua")
--   local ok, why = S.start()     -- ok: S.env is "SLURM_CONF=... " for sbatch, squeue, ...
--   S.stop()
local S = { env = nil }

local function sh (cmd)
  local p = io.popen(cmd .. " 2>/dev/null")
  local out = p:read("a")
  p:close()
  return out
end

local function q (s) return "'" .. s:gsub("'", "'\\''") .. "'" end

local function have (prog) return sh("command -v " .. prog) ~= "" end

local function sleep (s) os.execute("sleep " .. s) end

local function readfile (path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

-- The last lines of the daemons' logs, for a message.
local function logs (dir)
  local t = {}
  for _, f in ipairs { "munged.log", "slurmctld.log", "slurmd.log", "daemons.out" } do
    local s = readfile(dir .. "/log/" .. f)
    if s and s ~= "" then t[#t + 1] = f .. ": " .. (s:match("([^\n]*)\n?$") or "") end
  end
  return table.concat(t, "; ")
end

local CONF = [[
ClusterName=lsystest
SlurmctldHost=%s
SlurmctldPort=%d
SlurmdPort=%d
SlurmUser=%s
SlurmdUser=%s
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=%s/munge.sock
StateSaveLocation=%s/state
SlurmdSpoolDir=%s/spool
SlurmctldPidFile=%s/slurmctld.pid
SlurmdPidFile=%s/slurmd.pid
SlurmctldLogFile=%s/log/slurmctld.log
SlurmdLogFile=%s/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
SwitchType=switch/none
NodeName=%s CPUs=%d State=UNKNOWN
PartitionName=lsys Nodes=ALL Default=YES MaxTime=INFINITE State=UP
]]

--- Starts the cluster (once). Returns true (S.env, S.dir set), or nil and the reason it
-- cannot run here.
function S.start ()
  if S.env ~= nil then return true end
  for _, p in ipairs { "munged", "slurmctld", "slurmd", "sbatch", "sinfo" } do
    if not have(p) then
      return nil, p .. " is not installed (Debian packages slurmctld slurmd slurm-client "
        .. "munge; ./setup.sh installs them)"
    end
  end
  local user = sh("id -un"):gsub("%s+$", "")
  if sh("id -u"):gsub("%s+$", "") ~= "0" then
    return nil, "Slurm's slurmd runs jobs only as root here (running as " .. user .. ")"
  end
  local dir = sh("mktemp -d \"${TMPDIR:-/tmp}/lsys-slurm-XXXXXX\""):gsub("%s+$", "")
  if dir == "" then return nil, "cannot make a folder for the cluster" end
  for _, d in ipairs { "state", "spool", "log" } do
    os.execute("mkdir -p " .. q(dir .. "/" .. d))
  end
  S.dir = dir
  -- ports from this process's id, so that two runs side by side differ
  local pid = tonumber(sh("echo $PPID")) or 0
  local port = 20000 + (pid % 2000) * 2
  local host = sh("hostname"):gsub("%s+$", "")
  local cpus = tonumber(sh("nproc")) or 1
  local f = assert(io.open(dir .. "/slurm.conf", "w"))
  f:write(CONF:format(host, port, port + 1, user, user, dir, dir, dir, dir, dir, dir, dir,
                      host, cpus))
  f:close()
  local conf = dir .. "/slurm.conf"
  os.execute("dd if=/dev/urandom of=" .. q(dir .. "/munge.key") .. " bs=1024 count=1 "
    .. "2>/dev/null; chmod 600 " .. q(dir .. "/munge.key"))
  -- the daemons in the foreground under a watcher that stops them when this process ends
  -- (a spec that never calls stop, or a run that is killed, leaves nothing behind)
  os.execute(string.format("cd %s && (munged -F -f --key-file=%s/munge.key "
    .. "--socket=%s/munge.sock --pid-file=%s/munged.pid --log-file=%s/log/munged.log "
    .. "--seed-file=%s/munged.seed >>log/daemons.out 2>&1 & echo $! > munged.fg; sleep 1; "
    .. "slurmctld -D -f %s >>log/daemons.out 2>&1 & echo $! > slurmctld.fg; sleep 1; "
    .. "slurmd -D -f %s >>log/daemons.out 2>&1 & echo $! > slurmd.fg; p=%d; "
    .. "(while kill -0 $p 2>/dev/null; do sleep 1; done; kill $(cat slurmd.fg) "
    .. "$(cat slurmctld.fg) $(cat munged.fg)) >/dev/null 2>&1 &) >/dev/null 2>&1",
    q(dir), dir, dir, dir, dir, dir, q(conf), q(conf), pid))
  S.env = "SLURM_CONF=" .. q(conf) .. " "
  for _ = 1, 60 do                       -- up to 30 s for the node to be idle
    local state = sh(S.env .. "sinfo -h -o %T")
    if state:match("idle") then return true end
    sleep(0.5)
  end
  local why = "Slurm did not start: " .. logs(dir)
  S.stop()
  return nil, why
end

--- Stops the daemons this module started and removes their folder.
function S.stop ()
  if S.dir then
    for _, d in ipairs { "slurmd", "slurmctld", "munged" } do
      local pid = tonumber(readfile(S.dir .. "/" .. d .. ".fg") or "")
      if pid then os.execute("kill " .. math.tointeger(pid) .. " 2>/dev/null") end
    end
    sleep(0.5)
    os.execute("rm -rf " .. q(S.dir))
  end
  S.env, S.dir = nil, nil
end

return S
