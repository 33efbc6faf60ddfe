--- Fuzz target: the sidecar files `lsys view` saves parameter values in (plant.params, read
-- by lsys.ui.tune.read_sidecar when a model file is loaded).
--
-- The bytes are written to a temporary .params file (removed after each input) and read.
-- Expected errors are strings naming the file and line ("PATH:LINE: ..."). Checks on what
-- reads: every key is a name the rules can read and every value a finite number, a boolean
-- or a string; the values written back as `tune.literal` lines read again equal.
local tune = require "lsys.ui.tune"

local type, pairs, pcall, error, os_remove, tmpname, open, concat, sort =
      type, pairs, pcall, error, os.remove, os.tmpname, io.open, table.concat, table.sort

local T = { maxlen = 1024 }

T.seeds = {
  "-- the values lsys view saved\nk = 4\nangle = 42.5\nleaves = true\nshape = \"spire\"\n",
  "R = 1.5e-3\n  d1 = -7  -- a note\n\n",
  "x = 0x10\n",
  "x = lots\n",
  "= 3\n",
  "a = \"unterminated\n",
  "a = 'single'\n",
  "",
}

T.dict = { "=", " = ", "\n", "--", "true", "false", "\"", "'", "1.5", "-2", "e+", "nan",
           "inf", "k", "_x9", "0x" }

local _ENV = nil

local path = tmpname() .. ".params"

function T.clean (err) return type(err) == "string" and err:find(path, 1, true) == 1 end

local last

function T.run (bytes)
  last = nil
  local f = open(path, "wb")
  f:write(bytes)
  f:close()
  local ok, r = pcall(tune.read_sidecar, path)
  os_remove(path)
  last = { ok = ok, r = r }
  if not ok then error(r, 0) end
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil or not r.ok then return nil end
  local t = r.r
  if type(t) ~= "table" then return "read gave a " .. type(t) end
  local names, lines = {}, {}
  for k, v in pairs(t) do
    if type(k) ~= "string" or not k:match("^[%a_][%w_]*$") then return "a key that is no name" end
    local tv = type(v)
    if tv == "number" and not (v == v and v - v == 0) then return "a value not finite" end
    if tv ~= "number" and tv ~= "boolean" and tv ~= "string" then return "a " .. tv .. " value" end
    names[#names + 1] = k
  end
  sort(names)
  for _, k in pairs(names) do lines[#lines + 1] = k .. " = " .. tune.side_literal(t[k]) end
  local f = open(path, "wb")
  f:write(concat(lines, "\n"))
  f:close()
  local ok, back = pcall(tune.read_sidecar, path)
  os_remove(path)
  if not ok then return "the values written back do not read: " .. back end
  for k, v in pairs(t) do
    if back[k] ~= v then return "the value of " .. k .. " read back differs" end
  end
  return nil
end

return T
