--- Fuzz target: batch specs in Lua (lsys.batch.jobs on a table and on a spec file,
-- lua/lsys/batch/). Its corpus is tests/fuzz/corpus_batchspec (the CSV specs are
-- targets/batch.lua's).
--
-- The bytes are the text of a table constructor (tests/fuzz/lua/luadata.lua: evaluated in
-- an empty environment). The table goes to lsys.batch.jobs with dir = a scratch folder
-- (unless it gives its own dir) holding the model files m.lua, n.lua and sub/m.lua; the
-- same text, as a spec file `local _ENV = {} return TEXT` in that folder, goes to
-- lsys.batch.jobs too (not when the table gives a dir: a spec file may not).
-- Expected errors: the input's own ("spec:LINE: ..." from Lua), and lsys's, naming the
-- spec ("spec: FIELD: ...", "DIR/spec.lua: ...").
-- Checks: the table and the file both give jobs, the same ones, or both fail (when the
-- table has no holes); a list of jobs makes one job per entry, a sweep the product of its
-- lists' lengths times the replicates; every job has an id of its own, a whole seed, a
-- `where` naming the spec, and outputs; every output path is relative, stays in the output
-- folder (no `..` above it), has no control character, and no two outputs are the same
-- file (`a/./b` is `a/b`). A string is not passed on (it would be a spec file's path). A
-- budget stop is the input's own while its code runs, and the spec's size up to 10^6 jobs;
-- a spec of more that lsys neither refuses nor lists within 1 s (without the fuzzer's line
-- hook) is a finding.
local batch = require "lsys.batch"
local luadata = require "tests.fuzz.lua.luadata"

local type, pairs, ipairs, pcall, error, tostring =
      type, pairs, ipairs, pcall, error, tostring
local os_remove, open, mathtype, execute, tmpname = os.remove, io.open, math.type, os.execute,
      os.tmpname
local format, concat = string.format, table.concat
local shq = require("lsys.util.text").shq

-- 3 s: the fuzzer's line hook slows lsys's Lua about 20 times
local T = { maxlen = 4096, budget = 3 }

local DIR = tmpname()
os_remove(DIR)
local SPEC = DIR .. "/spec.lua"
local MODELS = { "m.lua", "n.lua", "sub/m.lua" }

local _ENV = nil

local function setup ()
  if open(DIR .. "/m.lua", "rb") then return end
  execute("mkdir -p " .. shq(DIR .. "/sub"))
  for _, name in ipairs(MODELS) do
    local f = open(DIR .. "/" .. name, "wb")
    f:write("return require('lsys').lsystem { axiom = 'F', steps = 1 }\n")
    f:close()
  end
end

local phase          -- "eval", "jobs" or "file": where the input is
local last, lastbytes, lastspec

-- the input's own errors, or lsys's naming the spec
function T.clean (err)
  if phase == "eval" then return err:find("^spec:") ~= nil end
  return err:find("^spec: ") ~= nil or err:sub(1, #SPEC) == SPEC or
         err:find("^lsys%.batch%.jobs: a spec %(a file name or a table%) expected, got ") ~= nil
end

-- a message with the spec's name made "SPEC"
local function norm (msg, who)
  return (tostring(msg):gsub(who:gsub("%p", "%%%0"), "SPEC"))
end

function T.run (bytes, ctx)
  last = nil
  setup()
  luadata.guard(ctx)
  phase = "eval"
  local spec = luadata.eval(bytes, "spec")
  lastspec = spec
  -- a string is a spec file's path: not one of the input's
  if type(spec) == "string" then error("spec: a string, not a spec table", 0) end
  local r = { spec = spec, bytes = bytes }
  last = r
  local given = type(spec) == "table" and spec.dir ~= nil
  if type(spec) == "table" and not given then spec.dir = DIR end
  phase = "jobs"
  r.ok, r.jobs = pcall(batch.jobs, spec)
  if type(spec) == "table" and not given then spec.dir = nil end
  if not given then
    phase = "file"
    local f = open(SPEC, "wb")
    f:write("local _ENV = {} return ", bytes)
    f:close()
    r.fok, r.fjobs = pcall(batch.jobs, SPEC)
    r.file = true
  end
  phase = "jobs"
  if not r.ok then error(r.jobs, 0) end
  if r.file and not r.fok then phase = "file"; error(r.fjobs, 0) end
  phase = "done"
end

-- The number of jobs the spec table `t` makes, by its own fields; nil when it is not
-- plain enough to tell.
local function expected (t)
  if type(t) ~= "table" then return nil end
  local list = t.jobs
  if list == nil and #t > 0 then list = t end
  if list ~= nil then return type(list) == "table" and #list or nil end
  local reps = t.replicates or 1
  if mathtype(reps) ~= "integer" and not (type(reps) == "number" and reps == reps // 1) then
    return nil
  end
  local n = reps
  if t.vary == nil then return n end
  if type(t.vary) ~= "table" then return nil end
  if #t.vary > 0 then
    for _, e in ipairs(t.vary) do
      if type(e) ~= "table" or type(e[2]) ~= "table" then return nil end
      n = n * #e[2]
    end
  else
    for _, v in pairs(t.vary) do
      if type(v) ~= "table" then return nil end
      n = n * #v
    end
  end
  return n
end

-- `p` with "." and empty components removed; nil when it leaves its folder or is absolute
local function normal (p)
  if p:sub(1, 1) == "/" then return nil end
  local parts = {}
  for c in p:gmatch("[^/]+") do
    if c == ".." then
      if #parts == 0 then return nil end
      parts[#parts] = nil
    elseif c ~= "." then
      parts[#parts + 1] = c
    end
  end
  return concat(parts, "/")
end

local FIELDS = { "n", "id", "seed", "model", "path", "name", "steps", "width", "height", "rep" }

-- the first difference between two job lists (the table's `a`, the file's `b`), or nil
local function differ (a, b)
  if #a ~= #b then return format("%d jobs from the table, %d from the file", #a, #b) end
  for i = 1, #a do
    local x, y = a[i], b[i]
    for _, k in ipairs(FIELDS) do
      if x[k] ~= y[k] then
        return format("job %d: %s is %s from the table, %s from the file", i, k,
                      tostring(x[k]), tostring(y[k]))
      end
    end
    if norm(x.where, "spec") ~= norm(y.where, SPEC) then
      return format("job %d: where is '%s' from the table, '%s' from the file", i, x.where,
                    y.where)
    end
    for k, v in pairs(x.params) do
      if y.params[k] ~= v then return format("job %d: params.%s differ", i, tostring(k)) end
    end
    for k in pairs(y.params) do
      if x.params[k] == nil then return format("job %d: params.%s differ", i, tostring(k)) end
    end
    if #x.outputs ~= #y.outputs then return format("job %d: the outputs differ", i) end
    for k, o in ipairs(x.outputs) do
      if o.path ~= y.outputs[k].path or o.format ~= y.outputs[k].format then
        return format("job %d: output %d differs", i, k)
      end
    end
  end
  return nil
end

-- True when the positive integer keys of `t` are 1 .. #t: a table with holes has no one
-- length, and the table given dir (one key more) may see another than the file.
local function sequence (t)
  local n, count = #t, 0
  for k in pairs(t) do
    if mathtype(k) == "integer" and k > 0 then
      if k > n then return false end
      count = count + 1
    end
  end
  return count == n
end

local MANY = 1e6        -- jobs: the size of spec checked job by job (see T.budget_clean)

local function check (r)
  -- both fail or neither (the first of several errors may differ: the table given dir
  -- orders its keys otherwise)
  local compare = r.file and type(r.spec) == "table" and sequence(r.spec)
  if not r.ok then
    if compare and r.fok then
      return "the file gives jobs, the table fails: " .. tostring(r.jobs)
    end
    return nil
  end
  if compare and not r.fok then
    return "the table gives jobs, the file fails: " .. tostring(r.fjobs)
  end
  local jobs = r.jobs
  local want = type(r.spec) == "table" and sequence(r.spec) and expected(r.spec)
  if want and #jobs ~= want then
    return format("the spec makes %d jobs, lsys.batch.jobs gave %d", want, #jobs)
  end
  -- every job of a spec of up to MANY; of more (made when read), the first and last 1000
  local count, picks = #jobs, {}
  for i = 1, count do
    if count <= MANY or i <= 1000 then picks[#picks + 1] = i
    else for j = count - 999, count do picks[#picks + 1] = j end; break end
  end
  local ids, paths = {}, {}
  for _, i in ipairs(picks) do
    local job = jobs[i]
    local name = "job " .. tostring(job.id)
    if job.n ~= i then return format("job %d has n = %s", i, tostring(job.n)) end
    if type(job.id) ~= "string" or job.id == "" then return format("job %d has no id", i) end
    if ids[job.id] then return format("jobs %d and %d have the id '%s'", ids[job.id], i, job.id) end
    ids[job.id] = i
    if mathtype(job.seed) ~= "integer" then return name .. ": seed not whole" end
    if type(job.where) ~= "string" or job.where:sub(1, 6) ~= "spec: " and job.where ~= "spec"
    then
      return name .. ": where is " .. tostring(job.where)
    end
    if type(job.outputs) ~= "table" or #job.outputs == 0 then return name .. ": no outputs" end
    for _, o in ipairs(job.outputs) do
      if type(o.path) ~= "string" or o.path:find("%c") then
        return name .. ": output path " .. tostring(o.path)
      end
      local p = normal(o.path)
      if p == nil then
        return format("%s: output '%s' is outside the output folder", name, o.path)
      end
      if paths[p] and paths[p].id == job.id then
        return format("job %s writes '%s' twice ('%s', '%s')", job.id, p, paths[p].path, o.path)
      elseif paths[p] then
        return format("jobs %s and %s both write '%s' ('%s', '%s')", paths[p].id, job.id, p,
                      paths[p].path, o.path)
      end
      paths[p] = { id = job.id, path = o.path }
    end
  end
  if compare and count <= MANY then return differ(jobs, r.fjobs) end
  if compare and #r.fjobs ~= count then
    return format("%d jobs from the table, %d from the file", count, #r.fjobs)
  end
  return nil
end

function T.after (tripped)
  luadata.unguard()
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  return check(r)
end

-- A budget stop while the input's own code runs is the input's. In lsys it is the spec's
-- size when it makes up to 10^6 jobs (65,536 take 1.1 s without the fuzzer's line hook,
-- 20 s with it); a spec of more (2^53 replicates) must be refused, or listed, within 1 s
-- without the hook: else a finding. Unknown counts go by that second.
function T.before (bytes) lastbytes, lastspec = bytes, nil end
local NOCTX = { trip = function () error("fuzz: over budget", 0) end }
function T.budget_clean ()
  if phase == "eval" then return true end
  local n = type(lastspec) == "table" and sequence(lastspec) and expected(lastspec)
  if n and n <= MANY then return true end
  local secs = luadata.bare(2, T.run, lastbytes, NOCTX)
  luadata.unguard()
  return secs <= 1
end

function T.finish ()
  os_remove(SPEC)
  for _, name in ipairs(MODELS) do os_remove(DIR .. "/" .. name) end
  os_remove(DIR .. "/sub")
  os_remove(DIR)
end

function T.describe (bytes) return bytes end

T.seeds = {
  '{ model = "m.lua", seed = 2024, width = 256, height = 256,\n'
    .. '  vary = { angle = { 20, 25, 30 }, R = { 0.6, 0.7 } }, replicates = 4,\n'
    .. '  outputs = { "png/{id}.png", "stats/{id}.json" } }',
  '{ model = "m.lua", outputs = { "png/{id}.png" }, width = 256, height = 256,\n'
    .. '  { angle = 20 }, { angle = 35, R = 0.5 }, { model = "n.lua", id = "control", seed = 1 } }',
  '{ model = "m.lua", vary = { { "angle", { 20, 30 } }, { "R", { 0.6, 0.7 } } },\n'
    .. '  outputs = { png = "{id}-{angle}-{R}.png", lstring = "s/{n}.txt" } }',
  '{ jobs = { { model = "sub/m.lua", steps = 3, outputs = "a/{model}-{seed}.glb" },\n'
    .. '  { model = "m.lua", name = "x", params = { k = 2 }, outputs = { "b/{name}.obj" } } } }',
  '{ model = "m.lua", vary = { seed = { 1, 2, 3 }, steps = { 0, 1 } },\n'
    .. '  outputs = "{seed}/{steps}.ply" }',
  '{ model = "m.lua", replicates = 3, outputs = { "r{rep}.png" } }',
  '{ model = "m.lua", vary = { R = { 1, "x" } }, outputs = { "{id}.png" } }',
  '{ model = "m.lua", seed = 0.5, outputs = { "{id}.png" } }',
  '{ model = "m.lua", vray = {}, outputs = { "{id}.png" } }',
  '{ model = "none.lua", outputs = { "{id}.png" } }',
  '{ model = "m.lua", vary = { seed = { 1, 2 } }, replicates = 2, outputs = { "{id}.png" } }',
  '{ model = "m.lua", outputs = { "same.png" }, {}, {} }',
  '{ model = "m.lua", outputs = { "{id}.avi" } }',
  '{ model = "m.lua", outputs = { png = "x.txt" } }',
  '{ model = "m.lua", dir = "/nonexistent", outputs = { "{id}.png" } }',
  '{ model = "m.lua", outputs = { "{id}.png" }, jobs = { 1 } }',
  '{ model = "m.lua", outputs = { "{R}.png" }, vary = { R = { 0.1, 1e300, -0 } } }',
  '{ model = "m.lua", outputs = { "{id}.png" }, vary = {} }',
  '{ model = "m.lua", outputs = { "{bad key}.png" } }',
  '{ model = "m.lua", outputs = { "{id}.png" }, [1.5] = 1 }',
  '(function () local t = { model = "m.lua", outputs = { "{id}.png" } } '
    .. 'for i = 1, 5 do t[i] = { angle = i } end return t end)()',
  '"not a table"',
  "{ model = ",
}

T.dict = { "model", "name", "seed", "steps", "width", "height", "params", "outputs", "vary",
           "replicates", "jobs", "dir", "id", "rep", "out", "png", "glb", "obj", "ply",
           "lstring", "stats", '"m.lua"', '"n.lua"', '"sub/m.lua"', '"../m.lua"', '"/m.lua"',
           '"{id}.png"', '"{seed}"', '"{n}"', '"{model}"', '"{name}"', '"{rep}"', '"{R}"',
           '"{steps}"', '"{width}"', '"a/./"', '"../"', '"/"', '"//"', ".png", ".glb", ".json",
           ".txt", ".obj", ".ply", "{", "}", "{}", ",", " = ", ";", "[1]", "[2]", '"R"',
           '"angle"', "R", "angle", "-1", "0", "1", "2", "0.5", "1e308", "1/0", "0/0",
           "2^53", "2^63", "math", "nil", "true", "false", '"\\n"', '"\\0"', '"\\r"',
           "(function () return 1 end)()", "function () end", "..", '("x"):rep(3)' }

-- a spec made of random parts: mostly one that gives jobs
local MODELS_T = { '"m.lua"', '"n.lua"', '"sub/m.lua"', '"./m.lua"', '"none.lua"' }
local OUTS = { '"{id}.png"', '"a/{id}.glb"', '"{model}/{n}.obj"', '"{seed}.ply"', '"s/{id}.txt"',
               '"{R}-{angle}.json"', '"r{rep}/{id}.png"', '"x/./{id}.png"', '"x//{id}.png"',
               '"../{id}.png"', '"/tmp/{id}.png"', '"{name}.png"', '"{steps}.png"', '"o.png"' }
local VALUES = { "1", "2", "0.5", "-3", "1e3", "20", '"x"', "2^31", "0", "7" }
local function list (rnd, from, n)
  local t = {}
  for i = 1, n do t[i] = from[rnd(#from)] end
  return "{ " .. concat(t, ", ") .. " }"
end
local function generate (rnd)
  local f = { "model = " .. MODELS_T[rnd(#MODELS_T)], "outputs = " .. list(rnd, OUTS, rnd(3)) }
  if rnd(3) == 1 then f[#f + 1] = "seed = " .. VALUES[rnd(#VALUES)] end
  if rnd(4) == 1 then f[#f + 1] = "steps = " .. VALUES[rnd(#VALUES)] end
  if rnd(4) == 1 then f[#f + 1] = "name = \"x\"" end
  if rnd(4) == 1 then f[#f + 1] = "params = { k = " .. VALUES[rnd(#VALUES)] .. " }" end
  local k = rnd(3)
  if k == 1 then
    local v = {}
    for i = 1, rnd(3) do
      local name = ({ "R", "angle", "seed", "steps", "width" })[rnd(5)]
      v[i] = name .. " = " .. list(rnd, VALUES, rnd(4))
    end
    f[#f + 1] = "vary = { " .. concat(v, ", ") .. " }"
    if rnd(2) == 1 then f[#f + 1] = "replicates = " .. rnd(4) end
  elseif k == 2 then
    for _ = 1, rnd(4) do
      f[#f + 1] = rnd(2) == 1 and "{ R = " .. VALUES[rnd(#VALUES)] .. " }" or
                  "{ id = \"j" .. rnd(9) .. "\", model = " .. MODELS_T[rnd(#MODELS_T)] .. " }"
    end
  end
  return "{ " .. concat(f, ", ") .. " }"
end

-- the target's own mutations: a generated spec, a field = value from the dictionary
T.mutators = {
  function (rnd) return generate(rnd) end,
  function (rnd, s)
    local keys = { "model", "seed", "steps", "width", "height", "outputs", "vary",
                   "replicates", "jobs", "name", "params", "id", "angle", "R" }
    local vals = { '"m.lua"', "1", "0", "-1", "2.5", '{ "{id}.png" }', '{ R = { 1, 2 } }',
                   "3", '{ {}, {} }', '"x"', "{ k = 1 }", '"a"', "{ 1, 2, 3 }", "true" }
    local at = s:find("{", 1, true)
    if at == nil then return s end
    return s:sub(1, at) .. " " .. keys[rnd(#keys)] .. " = " .. vals[rnd(#vals)] .. ","
      .. s:sub(at + 1)
  end,
}

return T
