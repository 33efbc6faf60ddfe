-- Shared by the benchmark scripts: finding lsys, the clock, peak memory.
--   local B = dofile((arg[0]:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local B = {}

local script = arg and arg[0] or "bench/x.lua"
B.root = script:match("^(.*)/bench/[^/]*$") or (script:match("^bench/") and ".") or ".."

--- require "lsys", falling back to the build tree next to the bench folder
function B.load_lsys ()
  local ok, mod = pcall(require, "lsys")
  if ok then return mod end
  package.path = B.root .. "/lua/?.lua;" .. B.root .. "/lua/?/init.lua;" .. package.path
  package.cpath = B.root .. "/build/?.so;" .. package.cpath
  return require "lsys"
end

-- seconds: the lsys program's monotonic wall clock when there is one, else CPU time
local host = package.loaded["lsys.host"]
B.clock = type(host) == "table" and host.clock or os.clock
B.clock_name = B.clock == os.clock and "CPU time (os.clock)" or "wall clock"

--- VmHWM of this process in MiB, or nil
function B.peak_mib ()
  local f = io.open("/proc/self/status", "r")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  local kb = s:match("VmHWM:%s*(%d+)")
  return kb and tonumber(kb) / 1024
end

--- the shortest of 'runs' timed calls of f (after a full collection each), and f's last result
function B.best (f, runs)
  local t, r = math.huge
  for _ = 1, runs or 3 do
    r = nil  -- luacheck: ignore 311 (the last result goes before the next run: peak memory)
    collectgarbage()
    local t0 = B.clock()
    r = f()
    t = math.min(t, B.clock() - t0)
  end
  return t, r
end

function B.verdict (ok) return ok and "PASS" or "MISS" end

--- 's' quoted for the shell
function B.shell_quote (s)
  B.load_lsys()              -- lsys's modules on the path
  return require("lsys.util.text").shq(tostring(s))
end

--- the command that runs this script again (the interpreter and its options, then the
-- script): for a benchmark that measures each case in a fresh process
function B.self_command ()
  local lo = 0
  while arg and arg[lo - 1] do lo = lo - 1 end
  local parts = {}
  for i = lo, -1 do parts[#parts + 1] = B.shell_quote(arg[i]) end
  if #parts == 0 then parts[1] = "lua5.4" end
  parts[#parts + 1] = B.shell_quote(arg[0])
  return table.concat(parts, " ")
end

--- the contents of a file, or nil
function B.read_file (path)
  local f = io.open(path, "r")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

--- writes 'text' to a file
function B.write_file (path, text)
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
end

--- runs a shell command: its output (stdout and stderr) and io.popen's close results
function B.capture (cmd)
  local p = io.popen(cmd .. " 2>&1")
  local out = p:read("a")
  local ok, how, code = p:close()
  return out, ok, how, code
end

--- The fields of the RESULT line a benchmark run of this script prints (`args` after the
-- script), as a table of numbers and words; raises with the run's output when it has none.
function B.measure (args)
  local out = B.capture(B.self_command() .. " " .. args)
  local line = out:match("RESULT ([^\n]*)")
  if not line then error("the run '" .. args .. "' failed:\n" .. out, 0) end
  local r = {}
  for k, v in line:gmatch("([%w_]+)=(%S+)") do r[k] = tonumber(v) or v end
  return r
end

local TIME = io.open("/usr/bin/time", "r") and (io.close(io.open("/usr/bin/time")) and
  "/usr/bin/time") or nil
B.has_time = TIME ~= nil

--- The best wall-clock time of the shell command 'cmd' over 'runs' (its standard error
-- discarded, no input) and its largest resident size in KiB as GNU time reports it (nil
-- without /usr/bin/time); raises when a run fails. For the whole-process figures against
-- cpfg: the same command on the model at 0 steps is timed too, and subtracted.
function B.whole (cmd, runs)
  local best, peak = math.huge, nil
  local tmp = os.tmpname()
  for _ = 1, runs do
    local t0 = B.clock()
    local ok = os.execute((TIME and (TIME .. " -f %M -o " .. tmp .. " ") or "") .. cmd
                          .. " 2>/dev/null </dev/null")
    local t = B.clock() - t0
    if not ok then os.remove(tmp) error("failed: " .. cmd, 0) end
    best = math.min(best, t)
    local kib = TIME and tonumber((B.read_file(tmp) or ""):match("(%d+)%s*$"))
    if kib then peak = math.max(peak or 0, kib) end
  end
  os.remove(tmp)
  return best, peak
end

--- B.whole for several commands at once, their runs interleaved (one of each in turn, `runs`
-- rounds), so that a machine that slows down or speeds up for a while (a virtual machine
-- does) moves every figure alike and their ratios stay: a list of { best, peak } in the
-- order of `cmds`.
function B.wholes (cmds, runs)
  local out = {}
  for k = 1, #cmds do out[k] = { math.huge, nil } end
  for _ = 1, runs do
    for k, cmd in ipairs(cmds) do
      local t, kib = B.whole(cmd, 1)
      out[k][1] = math.min(out[k][1], t)
      if kib then out[k][2] = math.max(out[k][2] or 0, kib) end
    end
  end
  return out
end

--- The times of a program against cpfg from B.wholes on four commands: cpfg at 0 steps and
-- at n, lsys at 0 and at n. Returns cpfg's and lsys's seconds, start-up subtracted, their
-- peaks at n (KiB) and their start-up seconds.
function B.versus (c0, c1, l0, l1, runs)
  local r = B.wholes({ c0, c1, l0, l1 }, runs)
  return math.max(r[2][1] - r[1][1], 1e-9), math.max(r[4][1] - r[3][1], 1e-9), r[2][2], r[4][2],
         r[1][1], r[3][1]
end

--- A fresh temporary folder for running cpfg: an empty colour map e.map and the view
-- file e.v holding 'view' (empty by default). Its path; remove it with B.rmdir.
function B.cpfg_folder (view)
  local dir = os.tmpname()
  os.remove(dir)
  assert(os.execute("mkdir -p " .. B.shell_quote(dir)))
  B.write_file(dir .. "/e.map", "")
  B.write_file(dir .. "/e.v", view or "")
  return dir
end

function B.rmdir (dir) os.execute("rm -rf " .. B.shell_quote(dir)) end

--- the path of node, or nil
function B.node_path ()
  local p = io.popen("command -v node 2>/dev/null")
  local path = p:read("l")
  p:close()
  return path
end

return B
