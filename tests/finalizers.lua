-- Finalizers at chosen points, for the specs of objects freed under a call:
-- lifetimes_spec.lua and misuse_spec.lua. In generational mode the collector runs a minor
-- cycle, and with it the finalizers of the garbage it finds, after the heap grew by a
-- percentage of its size (the minor multiplier); F.arm makes the next cycle fall after about
-- `slack` more bytes, so that a finalizer made just before a call runs inside the call's
-- allocations.
local F = {}

local MINOR = 1                    -- percent: the smallest minor multiplier

-- Generational mode with cycles as often as it can; F.stop goes back to the default mode.
function F.start () collectgarbage("generational", MINOR, 100) end
function F.stop () collectgarbage("incremental", 200, 100, 13) end

-- The next minor cycle after about `slack` more bytes (F.start first): a cycle now, then
-- garbage to take up the rest of the room (the string is counted once: string.rep's
-- buffer is freed as the string is made).
function F.arm (slack)
  collectgarbage("step")
  local n = math.floor(collectgarbage("count") * 1024 * MINOR / 100 - slack)
  if n > 0 then local _ = ("x"):rep(n) end
end

return F
