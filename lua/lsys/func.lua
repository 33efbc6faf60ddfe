--- Positional functions (Anastacio et al. 2009, §4; Prusinkiewicz et al. 2001): functions
-- y = f(x) of the relative position x in [0, 1], cpfg's B-spline functions and their
-- .func / .fset files. A function is an lsys.Func (csrc/lua/lua_func.c): `f(x)`,
-- `f:points()`, `f:name()`, `f:samples()`, `f:approx()`, `f:format()`. Models call them from rule
-- expressions (lsys.model, option `functions`) on the C expression machine.
-- @module lsys.func
local core = require "lsys.core"
local view = require "lsys.view"

local type, pairs, ipairs, error, tostring, pcall, getmetatable, math, string, table, next =
      type, pairs, ipairs, error, tostring, pcall, getmetatable, math, string, table, next
local format = string.format
local _ENV = nil

local M = {}

local MAXFILE = 16 * 2 ^ 20
local FUNC_MT = getmetatable(core.func({ { 0, 0 }, { 0, 0 }, { 1, 0 }, { 1, 0 } }))

--- True when `x` is an lsys.Func.
function M.isfunc (x) return getmetatable(x) == FUNC_MT end
local isfunc = M.isfunc

--- A function from its control points: opts = { points = { {x, y}, ... }, name = "f",
-- samples = 0, approx = "exact" }. At least 4 points, x nondecreasing from 0 to 1 (within
-- 1e-6); samples 0 (exact values) or > 2 (cpfg's table of that many values, interpolated
-- linearly); approx "cpfg" computes values as cpfg approximates them (float32 points,
-- bisection to 0.001 in x), for models that must give cpfg's numbers.
function M.new (opts)
  if type(opts) ~= "table" then error("lsys.func.new: a table of options expected", 2) end
  for k in pairs(opts) do
    if k ~= "points" and k ~= "name" and k ~= "samples" and k ~= "approx" then
      error(format("lsys.func.new: unknown option '%s'", tostring(k)), 2)
    end
  end
  if type(opts.points) ~= "table" then error("lsys.func.new: 'points' must be a list", 2) end
  local ok, f = pcall(core.func, opts.points, { name = opts.name, samples = opts.samples,
                                                approx = opts.approx })
  if not ok then
    local msg = tostring(f):gsub("^bad argument #1 to '.-'%s*%((.*)%)$", "%1")
    error("lsys.func.new: " .. msg:gsub("^core%.func: opts%.", ""), 2)
  end
  return f
end

-- Reads the functions of the file `path`; `samples` as a view file's "function:" line
-- gives it (it applies to the old "range:" form only). Raises "path:LINE: ...".
local function readall (path, samples)
  local text, err = core.read_file(path, MAXFILE)
  if text == nil then error(err, 0) end
  return core.func_parse(text, path, samples or 0)
end
M.readall = readall

--- Reads a .func file (one function, an lsys.Func) or a .fset file (a function set: a
-- list of Funcs in file order that is also a table by name, `set.internode`). Raises
-- "lsys.func.load: file:LINE: what is wrong".
function M.load (path)
  if type(path) ~= "string" then error("lsys.func.load: a file name expected", 2) end
  local ok, fs = pcall(readall, path)
  if not ok then error("lsys.func.load: " .. tostring(fs), 0) end
  if #fs == 1 and not path:match("%.fset$") then return fs[1] end
  for _, f in ipairs(fs) do
    if fs[f:name()] == nil then fs[f:name()] = f end
  end
  return fs
end

--- Writes `f` (an lsys.Func) as a cpfg .func file (fver 1 1), atomically: the file is
-- replaced only once everything was written.
function M.save (f, path)
  if not isfunc(f) then error("lsys.func.save: an lsys.Func expected", 2) end
  if type(path) ~= "string" then error("lsys.func.save: a file name expected", 2) end
  local ok, err = pcall(core.write_file, path, f:format())
  if not ok then error("lsys.func.save: " .. tostring(err), 0) end
end

-- The Funcs one entry of a functions list stands for: a Func, a file name (a .fset gives
-- all of its functions) or { file = NAME, samples = N, approx = "exact" | "cpfg" }.
-- Also returns the path read (nil for a Func).
local function entry (x, dir, what)
  if isfunc(x) then return { x } end
  local file, samples, approx = x, 0, nil
  if type(x) == "table" then
    for k in pairs(x) do
      if k ~= "file" and k ~= "samples" and k ~= "approx" then
        error(format("%s: unknown key '%s' (file, samples, approx)", what, tostring(k)), 0)
      end
    end
    file, samples, approx = x.file, x.samples or 0, x.approx
    if math.type(samples) == nil or samples ~= math.floor(samples) or samples < -1 then
      error(format("%s: 'samples' must be a whole number", what), 0)
    end
    if approx ~= nil and approx ~= "exact" and approx ~= "cpfg" then
      error(format("%s: 'approx' must be \"exact\" or \"cpfg\"", what), 0)
    end
  end
  if type(file) ~= "string" or file == "" then
    error(format("%s: an lsys.Func or a file name expected, got %s", what, type(x)), 0)
  end
  -- relative to `dir` as the view's files are read
  local path = view.resolve(dir, file)
  local ok, fs = pcall(readall, path, math.tointeger(samples))
  if not ok and path ~= file and file:sub(1, 1) ~= "/" then   -- then the current folder
    local ok2, fs2 = pcall(readall, file, math.tointeger(samples))
    if ok2 then ok, fs, path = ok2, fs2, file end
  end
  if not ok then error(format("%s: %s", what, tostring(fs)), 0) end
  if approx == "cpfg" then       -- computed as cpfg approximates them
    for i, f in ipairs(fs) do
      fs[i] = M.new { points = f:points(), name = f:name(), samples = f:samples(),
                      approx = "cpfg" }
    end
  end
  return fs, path
end

--- The function table of a model: `spec` is a list of Funcs, file names (relative to
-- `dir`) or { file =, samples = } (a .fset gives all of its functions, in order), and/or
-- a table by name { internode = f | file }. Returns the list (func(ID, x): ID is the
-- position, from 1), the table by name (func("name", x): the keyed entries, then the
-- listed functions by their own names) and the file each Func was read from (a table
-- keyed by the Func; none for a Func given). `what` starts messages.
function M.collect (spec, dir, what)
  what = what or "functions"
  if type(spec) ~= "table" then error(format("%s must be a table", what), 0) end
  local list, byname, files, n, m = {}, {}, {}, 0, 0
  for i, x in ipairs(spec) do
    m = i
    local fs, path = entry(x, dir, format("%s[%d]", what, i))
    for _, f in ipairs(fs) do
      n = n + 1
      list[n] = f
      files[f] = path
    end
  end
  for k, x in pairs(spec) do
    if type(k) == "string" then
      local fs, path = entry(x, dir, format("%s.%s", what, k))
      if #fs ~= 1 then
        error(format("%s.%s: a function set has %d functions, not one", what, k, #fs), 0)
      end
      byname[k] = fs[1]
      files[fs[1]] = path
    elseif math.type(k) ~= "integer" or k < 1 or k > m then
      error(format("%s: keys must be positions 1, 2, ... without holes, or names; got %s",
                   what, tostring(k)), 0)
    end
  end
  for _, f in ipairs(list) do
    if byname[f:name()] == nil then byname[f:name()] = f end
  end
  return list, byname, files
end

--- Replaces the function `id` (a position in `list` from 1, or a name in `byname`) of a
-- function table (as `collect` returns) by the Func `f`: every entry of `list` and
-- `byname` that held the old function takes `f`, which keeps the old one's file. Returns
-- nil, or a message for a bad `f` or an unknown id.
function M.replace (list, byname, files, id, f)
  if not isfunc(f) then return format("an lsys.Func expected, got %s", type(f)) end
  local old = type(id) == "string" and byname[id] or type(id) == "number" and list[id]
  if not old then
    return format("unknown function %s (functions: %s)",
                  type(id) == "string" and "'" .. id .. "'" or tostring(id), M.names(byname))
  end
  for i, g in ipairs(list) do if g == old then list[i] = f end end
  for k, g in pairs(byname) do if g == old then byname[k] = f end end
  if files[f] == nil then files[f] = files[old] end
  return nil
end

--- The functions of a function table (as `collect` returns) for editors: a list of
-- { id =, name =, func =, file = (the path read, or nil) }, first the listed ones by
-- position (id 1, 2, ...), then those given only by name (id the name, sorted).
function M.entries (list, byname, files)
  local out, seen, keys = {}, {}, {}
  for i, f in ipairs(list) do
    out[#out + 1] = { id = i, name = f:name(), func = f, file = files[f] }
    seen[f] = true
  end
  for k, f in pairs(byname) do
    if not seen[f] then keys[#keys + 1] = k end
  end
  table.sort(keys)
  for _, k in ipairs(keys) do
    out[#out + 1] = { id = k, name = k, func = byname[k], file = files[byname[k]] }
  end
  return out
end

--- Writes the list of Funcs `fs` as a cpfg function set (.fset: "funcgalleryver 1 1",
-- "items: N", then each function as `save` writes it), atomically.
function M.save_set (fs, path)
  if type(fs) ~= "table" or #fs == 0 then
    error("lsys.func.save_set: a list of at least one lsys.Func expected", 2)
  end
  if type(path) ~= "string" then error("lsys.func.save_set: a file name expected", 2) end
  local parts = { format("funcgalleryver 1 1\nitems: %d\n", #fs) }
  for i, f in ipairs(fs) do
    if not isfunc(f) then
      error(format("lsys.func.save_set: item %d is a %s, not an lsys.Func", i, type(f)), 2)
    end
    parts[i + 1] = f:format()
  end
  local ok, err = pcall(core.write_file, path, table.concat(parts))
  if not ok then error("lsys.func.save_set: " .. tostring(err), 0) end
end

--- The names of a function table for messages: "internode, angle" (sorted), or "none".
function M.names (byname)
  local t = {}
  for k in pairs(byname) do t[#t + 1] = k end
  if next(t) == nil then return "none" end
  table.sort(t)
  return table.concat(t, ", ")
end

return M
