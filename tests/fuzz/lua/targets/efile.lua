--- Fuzz target: cpfg's communication files (.e), lsys.environment.efile.read.
--
-- The bytes are written to a temporary .e file (removed after each input) and read. Expected
-- errors are strings naming the file ("PATH: ..." or "PATH:LINE: ..."). Checks on what
-- loads: the transport is pipes, files or memory, with a chunk size > 0 except in memory;
-- the program's argv is a non-empty list of non-empty words with "-e" and the file's name
-- (or the file's own -e switch) after the program; every turtle format runs through
-- string.format with its values (3 for vectors, 1 for the width and the scale); and
-- reading the file again gives the same table.
local efile = require "lsys.environment.efile"
local warning = require "lsys.warning"

local type, pairs, ipairs, pcall, tostring, error, os_remove, tmpname, open, mathtype =
      type, pairs, ipairs, pcall, tostring, error, os.remove, os.tmpname, io.open, math.type
local format = string.format

local T = { maxlen = 2048 }

T.seeds = {
  "executable: honda81 density.spec\ncommunication type: files\n"
    .. "turtle position:P:%.4f %.4f %.0f\nverbose: off\n",
  "communication type: pipes 50\nexecutable: chiba chiba.spec\nturtle position: %g %g %g\n"
    .. "turtle heading: %g %g %g\nturtle up: %f %f %f\nturtle line width: %g\n"
    .. "turtle scale factor: %g\nfollowing module: no\n",
  "communication type: memory\nexecutable: clover -e x.e clover.spec &\n"
    .. "turtle position:P:%.4f %.4f\n",
  "communication type: sockets\nexecutable: a\n",
  "executable: a\ninterpreted modules: F, P(2)\n",
  "executable: a\nturtle position: %d %d %d\n",
  "executable: a\nturtle position: %g %g %g %g\n",
  "executable: a\nturtle line width: %5.2lf\nturtle scale factor: %%%e\n",
  "executable:\n",
  "turtle position: %g %g %g\n",
  "executable: a\n\nbogus: 1\nfollowing module: maybe\n",
  "",
}

T.dict = { "executable:", "communication type:", "pipes", "files", "memory", "sockets",
           "turtle position:", "turtle heading:", "turtle left:", "turtle up:",
           "turtle line width:", "turtle scale factor:", "following module:", "yes", "no",
           "verbose:", "on", "interpreted modules:", "when interpret:", "remote host:",
           "%g", "%f", "%.4f", "%e", "%%", "%lf", "%d", "%s", "\t", ":", "\n", " ", "&",
           "-e" }

local _ENV = nil

local path = tmpname() .. ".e"

function T.clean (err) return type(err) == "string" and err:find(path, 1, true) == 1 end

local last

local function read ()
  local saved = warning.warn
  warning.warn = function () end            -- skipped lines warn: no output while fuzzing
  local ok, r = pcall(efile.read, path)
  warning.warn = saved
  return ok, r
end

function T.run (bytes)
  last = nil
  local f = open(path, "wb")
  f:write(bytes)
  f:close()
  local ok, r = read()
  local ok2, r2 = read()
  os_remove(path)
  last = { ok = ok, r = r, ok2 = ok2, r2 = r2 }
  if not ok then error(r, 0) end
end

local function same (a, b)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  for k, x in pairs(a) do if not same(x, b[k]) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

local function check (s)
  if type(s) ~= "table" then return "read returned a " .. type(s) end
  local t = s.transport
  if t ~= "pipes" and t ~= "files" and t ~= "memory" then
    return "a transport " .. tostring(t)
  end
  if (t == "memory") ~= (s.max == nil) or s.max and not (mathtype(s.max) or s.max > 0) then
    return "a chunk size " .. tostring(s.max) .. " for " .. t
  end
  if s.max and not (s.max > 0) then return "a chunk size " .. tostring(s.max) end
  if type(s.argv) ~= "table" or #s.argv < 2 then return "an argv without -e" end
  for _, w in ipairs(s.argv) do
    if type(w) ~= "string" or w == "" or w:find("%s") then
      return "an argv word " .. format("%q", tostring(w))
    end
  end
  if s.argv[2]:sub(1, 2) ~= "-e" then return "argv[2] is " .. s.argv[2] end
  for field, fmt in pairs(s.formats) do
    local n = (field == "width" or field == "scale") and 1 or 3
    local ok, err = pcall(format, fmt, 1.5, -2.25, 3e10)
    if n == 1 then ok, err = pcall(format, fmt, 1.5) end
    if not ok then return "the " .. field .. " format fails: " .. tostring(err) end
  end
  return nil
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  if r.ok ~= r.ok2 or (r.ok and not same(r.r, r.r2)) or (not r.ok and r.r ~= r.r2) then
    return "two reads of one file differ"
  end
  if not r.ok then return nil end
  return check(r.r)
end

return T
