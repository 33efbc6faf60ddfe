--- A display for the viewer specs: a private Xvfb server when Xvfb is installed (so the
-- tests never draw on a user's screen and always have the same screen), else the
-- DISPLAY of the environment. Specs run the lsys program with `D.env` in front of the
-- command, so this process itself needs no display.
--
--   local D = require "tests.display"
--   local ok, why = D.start()     -- ok: D.env is "DISPLAY=:N " ; else why says what is missing
--   D.stop()
local D = { env = nil }

local function sh (cmd)
  local p = io.popen(cmd .. " 2>/dev/null")
  local out = p:read("a")
  p:close()
  return out
end

local function have (prog)
  return sh("command -v " .. prog) ~= ""
end

local function sleep (s) os.execute("sleep " .. s) end

local started = false

--- Starts (once) the display. Returns true, or nil and the reason there is none.
function D.start ()
  if D.env ~= nil then return true end
  if have("Xvfb") then
    local dfile, pfile = os.tmpname(), os.tmpname()
    -- -displayfd: Xvfb picks a free display number and writes it when it is ready
    -- a watcher stops the server when this process ends, so a spec that never calls
    -- D.stop (or a run that is killed) leaves no Xvfb behind; $PPID is this Lua process
    os.execute(string.format("Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp " ..
      "3>%s >/dev/null 2>&1 & x=$!; echo $x > %s; p=$PPID; " ..
      "(while kill -0 $p 2>/dev/null; do sleep 1; done; kill $x) >/dev/null 2>&1 &",
      dfile, pfile))
    local n
    for _ = 1, 100 do
      local f = io.open(dfile)
      n = f and f:read("n")
      if f then f:close() end
      if n then break end
      sleep(0.1)
    end
    local f = io.open(pfile)
    D.pid = f and f:read("n")
    if f then f:close() end
    os.remove(dfile)
    os.remove(pfile)
    if n == nil then
      D.stop()
      return nil, "Xvfb did not start (no display number within 10 s)"
    end
    D.env = string.format("DISPLAY=:%d ", math.tointeger(n))
    started = true
    return true
  end
  local d = os.getenv("DISPLAY")
  if d ~= nil and d ~= "" then
    D.env = "DISPLAY=" .. d .. " "
    return true
  end
  return nil, "no display: install Xvfb (Debian package xvfb; ./setup.sh does) or set DISPLAY"
end

--- Stops the Xvfb this module started.
function D.stop ()
  if started and D.pid then os.execute("kill " .. math.tointeger(D.pid) .. " 2>/dev/null") end
  started, D.pid, D.env = false, nil, nil
end

--- Whether `prog` is on PATH.
D.have = have
D.sleep = sleep

--- Waits up to `seconds` (10) for the file `path` to hold `text` (plain); returns what it
-- holds then ("" when it cannot be read): what a program running in the background wrote.
function D.wait_for (path, text, seconds)
  local read = require("tests.helper").read
  for _ = 1, 10 * (seconds or 10) do
    local s = read(path)
    if s and s:find(text, 1, true) then return s end
    sleep(0.1)
  end
  return read(path) or ""
end

return D
