-- Shared by the cpfg oracle tools (cpfg-compare.lua, cpfg-stats.lua): shell quoting and
-- whole-file reads and writes. Loaded with dofile from the tool's own folder.
local T = {}

--- 's' quoted for the shell
function T.q (s) return "'" .. s:gsub("'", "'\\''") .. "'" end

--- the bytes of a file, or nil
function T.read (path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

--- writes the bytes 's' to a file
function T.write (path, s)
  local f = assert(io.open(path, "wb"))
  f:write(s)
  f:close()
end

return T
