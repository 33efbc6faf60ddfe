-- Batch specs read as streams (lua/lsys/batch/, docs/batch.md §2): a sweep of
-- 10^6 jobs is listed, sharded and checked without making every job (job n computed from
-- n), a spec making more jobs than lsys.batch.MAX_JOBS is refused with the count, and the
-- check that no two jobs write the same file stays exact: proved from the templates when
-- they name each job's file by its id, else made job by job (with the files' paths
-- normalized before they are compared).
local H = require "tests.helper"
local batch = require "lsys.batch"

local q = require("lsys.util.text").shq

-- A model with three variables; its jobs are never run here.
local MODEL = [[
return require("lsys").lsystem { axiom = "A", steps = 1, env = { a = 1, b = 1, c = 1 },
                                 productions = "A --> F" }
]]

-- A Lua sweep of 100 x 100 x 100 = 10^6 jobs, with the outputs `outs` (Lua text).
local function big_sweep (outs)
  return [[
local v, w = {}, {}
for i = 1, 100 do v[i], w[i] = i, i / 4 end
return { model = "m.lua", seed = 9, vary = { a = v, b = v, c = w }, outputs = ]] .. outs
    .. " }\n"
end

-- The message of a failing call.
local function err_of (f, ...)
  local ok, e = pcall(f, ...)
  assert.is_false(ok, "expected an error")
  return tostring(e)
end

describe("batch specs as streams", function()
  local dir
  before_each(function()
    dir = H.tmpdir()
    H.write(dir .. "/m.lua", MODEL)
  end)
  after_each(function() H.rmdir(dir) end)

  it("makes any job of a sweep of 10^6 from its number, with the fields a full expansion "
     .. "gives it", function()
    H.write(dir .. "/big.lua", big_sweep('{ "s/{id}.txt", stats = "st/{a}/{id}.json" }'))
    local jobs, info = batch.jobs(dir .. "/big.lua")
    assert.equal(1000000, #jobs)
    assert.equal(1000000, info.total)
    -- job n - 1 = (a - 1) * 10^4 + (b - 1) * 100 + (c - 1): 999,998 is a = 100, b = 100, c = 99
    local j = jobs[999999]
    assert.equal(999999, j.n)
    assert.equal("0999999", j.id)
    assert.equal(batch.seed(9, 999999), j.seed)
    assert.same({ a = 100, b = 100, c = 24.75 }, j.params)
    assert.equal(dir .. "/big.lua: vary a=100 b=100 c=24.75", j.where)
    assert.same({ { format = "lstring", path = "s/0999999.txt" },
                  { format = "stats", path = "st/100/0999999.json" } }, j.outputs)
    assert.same({ a = 1, b = 1, c = 0.25 }, jobs[1].params)
    assert.same({ a = 1, b = 2, c = 0.25 }, jobs[101].params)
    assert.is_nil(jobs[1000001])
    local n = 0
    for i, job in ipairs(jobs) do
      if i > 3 then break end
      n = n + 1
      assert.equal(i, job.n)
    end
    assert.equal(3, n)
  end)

  it("gives a shard of a sweep of 10^6 its every N-th job", function()
    H.write(dir .. "/big.lua", big_sweep('{ "s/{id}.txt" }'))
    local p = batch.plan(dir .. "/big.lua", { out = dir .. "/out", shard = "1000/1000" })
    assert.equal(1000, #p.jobs)
    assert.equal(1000000, p.total)
    assert.equal(1000, p.jobs[1].n)
    assert.equal("1000000", p.jobs[1000].id)
    assert.equal("todo", p.jobs[1000].status)
    assert.same({ a = 100, b = 100, c = 25 }, p.jobs[1000].params)
  end)

  it("lists a shard of a sweep of 10^6 in a few megabytes: no job made but the shard's",
  function()
    local f = io.open("/proc/self/status", "r")
    local status = f and f:read("a")
    if f then f:close() end
    if not (status and status:find("VmHWM:")) then
      pending("no VmHWM in /proc/self/status (Linux only)")
      return
    end
    H.write(dir .. "/big.lua", big_sweep('{ "s/{id}.txt", "{a}-{b}/{id}.png" }'))
    -- the program lists the shard, then reports its own peak resident size
    H.write(dir .. "/list.lua", [[
local n = require("lsys.cli").main("batch", "big.lua", "-d", "out", "--list", "--shard",
                                  "999/1000")
local f = io.open("/proc/self/status", "r")
io.stderr:write("exit ", n, " peak ", f:read("a"):match("VmHWM:%s*(%d+)"), " kB\n")
f:close()
]])
    local out, code = H.sh("cd " .. q(dir) .. " && " .. q(H.ABSBIN) .. " list.lua")
    assert.equal(0, code, out)
    assert.truthy(out:find("0999999  to do   seed " .. batch.seed(9, 999999)
      .. "  m.lua  a=100 b=100 c=24.75  -> 100-100/0999999.png s/0999999.txt\n", 1, true), out)
    assert.truthy(out:find("\n1000 jobs (shard 999/1000 of 1000000): 0 done, 0 failed, 1000 to "
      .. "do\n", 1, true), out)
    local kb = tonumber(out:match("exit 0 peak (%d+) kB"))
    assert.is_number(kb, out)
    -- the whole expansion took 2.2 KiB a job: 2.2 GB; the program alone takes about 5 MB
    assert.is_true(kb < 64 * 1024, ("peak %d kB"):format(kb))
  end)

  it("refuses a spec of more jobs than lsys.batch.MAX_JOBS, with the count", function()
    local v = {}
    for i = 1, 1000 do v[i] = i end
    assert.equal(1000000000, batch.MAX_JOBS)
    assert.equal("spec: vary: the sweep (1000 values of a x 1000 values of b x 1000 values of c "
      .. "x 2 replicates) makes 2000000000 jobs, more than the limit of 1000000000 "
      .. "(lsys.batch.MAX_JOBS)", err_of(batch.jobs, { dir = dir, model = "m.lua",
        vary = { a = v, b = v, c = v }, replicates = 2, outputs = "{id}.txt" }))
    local huge = {}
    for i = 1, 8 do huge[i] = { "v" .. i, v } end       -- 10^24: past 2^63
    assert.equal("spec: vary: the sweep (" .. ("1000 values of v1 x 1000 values of v2 x 1000 "
      .. "values of v3 x 1000 values of v4 x 1000 values of v5 x 1000 values of v6 x 1000 "
      .. "values of v7 x 1000 values of v8") .. ") makes 1.000e+24 jobs, more than the limit of "
      .. "1000000000 (lsys.batch.MAX_JOBS)", err_of(batch.jobs, { dir = dir, model = "m.lua",
        vary = huge, outputs = "{id}.txt" }))
    local max = batch.MAX_JOBS
    batch.MAX_JOBS = 3
    local ok, e = pcall(batch.jobs, { dir = dir, model = "m.lua", outputs = "{id}.txt",
                                      jobs = { {}, {}, {}, {} } })
    local ok2, e2 = pcall(batch.jobs, { dir = dir, model = "m.lua", outputs = "{id}.txt",
                                        jobs = { {}, {}, {} } })
    H.write(dir .. "/f.csv", "model,out\nm.lua,a{id}.txt\nm.lua,b{id}.txt\nm.lua,c{id}.txt\n"
      .. "m.lua,d{id}.txt\n")
    local ok3, e3 = pcall(batch.jobs, dir .. "/f.csv")
    batch.MAX_JOBS = max
    assert.is_false(ok)
    assert.equal("spec: the list makes 4 jobs, more than the limit of 3 (lsys.batch.MAX_JOBS)", e)
    assert.is_true(ok2, e2)
    assert.is_false(ok3)
    assert.equal(dir .. "/f.csv: the file makes 4 jobs, more than the limit of 3 "
      .. "(lsys.batch.MAX_JOBS)", e3)
  end)

  describe("no two jobs write the same file", function()
    local function spec (t)
      t.dir, t.model = dir, t.model or "m.lua"
      return t
    end

    it("finds two jobs of a sweep that write one file, where a template proves nothing",
    function()
      -- "{a}{b}": a = 1, b = 11 and a = 11, b = 1 both give 111.txt
      assert.equal("spec: vary a=11 b=1: outputs[1]: '111.txt' is also written by job 0001 "
        .. "(spec: vary a=1 b=11): give each job its own files, with {id} for instance",
        err_of(batch.jobs, spec { vary = { { "a", { 1, 11 } }, { "b", { 11, 1 } } },
                                  outputs = "{a}{b}.txt" }))
      -- the same value twice in a list
      assert.equal("spec: vary a=1: outputs.stats: 's/1.json' is also written by job 0001 "
        .. "(spec: vary a=1): give each job its own files, with {id} for instance",
        err_of(batch.jobs, spec { vary = { a = { 1, 2, 1 } }, outputs = { stats = "s/{a}.json" } }))
      -- a file of one template that is another's of another job
      assert.equal("spec: vary a=1: outputs[2]: 'x1.txt' is written twice by this job",
        err_of(batch.jobs, spec { vary = { a = { 1, 2, 3 } },
                                  outputs = { "x{a}.txt", "x{a}.txt" } }))
    end)

    -- The proof from the templates checks job 1 alone; job by job, 10^8 or 10^9 jobs take
    -- minutes (the batchspec fuzz target's findings: {rep} alone and a file in a folder
    -- beside one at the top were checked job by job). A count hook stops the check when it
    -- runs 10^7 Lua instructions: job by job it would run thousands a job.
    it("proves from the templates that replicates in {rep} and files at two depths differ",
    function()
      local function bounded (f, ...)
        debug.sethook(function () error("over 10^7 instructions: checked job by job", 0) end,
                      "", 1e7)
        local r = table.pack(pcall(f, ...))
        debug.sethook()
        return table.unpack(r, 1, r.n)
      end
      local ok, jobs = bounded(batch.jobs, spec { replicates = 129 ^ 3, outputs = "r{rep}.png" })
      assert.is_true(ok, jobs)
      assert.equal(2146689, #jobs)
      assert.same({ { format = "png", path = "r2146689.png" } }, jobs[#jobs].outputs)
      ok, jobs = bounded(batch.jobs, spec { vary = { angle = { 7, 1 } }, replicates = 10265536,
                                            outputs = { "x//{id}.png", "{id}.png" } })
      assert.is_true(ok, jobs)
      assert.equal(20531072, #jobs)
      assert.same({ { format = "png", path = "x/00000003.png" },
                    { format = "png", path = "00000003.png" } }, jobs[3].outputs)
      -- with a sweep of values, {rep} is not the job: checked job by job, which finds it
      assert.equal("spec: vary a=2 rep=1: outputs[1]: 'r1.png' is also written by job 0001 "
        .. "(spec: vary a=1 rep=1): give each job its own files, with {id} for instance",
        err_of(batch.jobs, spec { vary = { a = { 1, 2 } }, replicates = 2,
                                  outputs = "r{rep}.png" }))
    end)

    it("finds, job by job, the file of the first of 10^5 jobs written again by job 90,001",
    function()
      -- a = 1 again at the 10th value: job 90,001 (a = 1, b = 1, c = 1) writes 1/1/1.txt
      H.write(dir .. "/big.lua", [[
local v, w = {}, {}
for i = 1, 100 do v[i] = i end
for i = 1, 10 do w[i] = i end
w[10] = 1
return { model = "m.lua", vary = { { "a", w }, { "b", v }, { "c", v } },
         outputs = { "{a}/{b}/{c}.txt" } }
]])
      assert.equal(dir .. "/big.lua: vary a=1 b=1 c=1: outputs[1]: '1/1/1.txt' is also written "
        .. "by job 000001 (" .. dir .. "/big.lua: vary a=1 b=1 c=1): give each job its own "
        .. "files, with {id} for instance", err_of(batch.jobs, dir .. "/big.lua"))
      H.write(dir .. "/big.lua", (H.read(dir .. "/big.lua"):gsub("w%[10%] = 1", "")))
      assert.equal(100000, #batch.jobs(dir .. "/big.lua"))
    end)

    it("compares the files' normalized paths: sub/./x, sub//x and sub/y/../x are sub/x",
    function()
      H.write(dir .. "/f.csv", "model,out\nm.lua,sub/x.txt\nm.lua,sub/./x.txt\n")
      assert.equal(dir .. "/f.csv:3: column 'out': 'sub/x.txt' is also written by job 0001 ("
        .. dir .. "/f.csv:2): give each job its own files, with {id} for instance",
        err_of(batch.jobs, dir .. "/f.csv"))
      H.write(dir .. "/f.csv", "model,out\nm.lua,sub//x.txt\nm.lua,a.txt;sub/y/../x.txt\n")
      assert.equal(dir .. "/f.csv:3: column 'out': 'sub/x.txt' is also written by job 0001 ("
        .. dir .. "/f.csv:2): give each job its own files, with {id} for instance",
        err_of(batch.jobs, dir .. "/f.csv"))
      assert.equal("spec: vary a=1: outputs[2]: 'p/1.txt' is written twice by this job",
        err_of(batch.jobs, spec { vary = { a = { 1, 2 } },
                                  outputs = { "p/{a}.txt", "./p/q/../{a}.txt" } }))
      local jobs = batch.jobs(spec { vary = { a = { 1, 2 } },
                                     outputs = { "./sub//{id}/./x.txt", "a/../b/{id}.json" } })
      assert.same({ { format = "lstring", path = "sub/0002/x.txt" },
                    { format = "stats", path = "b/0002.json" } }, jobs[2].outputs)
    end)

    it("counts an .obj's material file among the files a job writes", function()
      assert.equal("spec: vary a=1: outputs.lstring: 'm/0001.mtl' is written twice by this "
        .. "job (the material file of 'm/0001.obj')", err_of(batch.jobs,
          spec { vary = { a = { 1, 2 } }, outputs = { "m/{id}.obj", lstring = "m/{id}.mtl" } }))
      assert.equal("spec: jobs[2]: outputs.lstring: 'p.mtl' is also written by job 0001 "
        .. "(spec: jobs[1]): give each job its own files, with {id} for instance",
        err_of(batch.jobs, spec { jobs = { { outputs = "p.obj" },
                                           { outputs = { lstring = "q/../p.mtl" } } } }))
    end)

    -- Every template of a list, over a small sweep whose values run into each other (1 and
    -- 11, 1 and 0.1): batch.jobs accepts it exactly when no two of its files are the same
    -- (its paths made here by hand) -- by the proof from the templates, or job by job.
    it("accepts a sweep's templates exactly when the jobs' files are all different", function()
      local TEMPLATES = {
        "{id}.txt", "{n}.txt", "{a}{id}.txt", "{id}{a}.txt", "{a}{id}{b}.txt", "x{n}{a}.txt",
        "{n}_{a}.txt", "{a}_{n}.txt", "{a}{n}.txt", "{n}{a}.txt", "{a}.txt", "{a}{b}.txt",
        "{a}-{b}.txt", "{a}/{b}.txt", "{a}/{id}.txt", "d/{id}/../x.txt", "{id}/x.txt",
        "{b}{n}1.txt", "{n}1{b}.txt", "{rep}{n}.txt", "{seed}.txt", "s{steps}/{id}.txt",
        "{a}-{b}-{rep}.txt", "{a}/./{b}//{rep}.txt", "{a}/../{b}-{rep}.txt",
      }
      local PAIRS = { { "{id}.txt", "{id}.json" }, { "a/{id}.txt", "b/{id}.txt" },
                      { "{id}.txt", "x{id}.txt" }, { "{id}.txt", "{id}x.txt" },
                      { "{id}.obj", "{id}.mtl" }, { "{id}/x.obj", "{id}/y.mtl" },
                      { "a{id}.txt", "{id}.txt" }, { "{id}.txt", "./{id}.txt" },
                      { "x//{id}.txt", "{id}.txt" }, { "x/{id}.txt", "x{id}.txt" } }
      -- the sweep's 12 jobs: a (1, 11, 0.1) slowest, then b (1, 11), then rep (1, 2)
      local function paths_by_hand (outs)
        local seen, shared, n = {}, false, 0
        for _, a in ipairs { 1, 11, 0.1 } do
          for _, b in ipairs { 1, 11 } do
            for rep = 1, 2 do
              n = n + 1
              local v = { id = ("%04d"):format(n), n = n, a = a, b = b, rep = rep, steps = 2,
                          seed = batch.seed(0, n) }
              local files = {}
              for _, t in ipairs(outs) do
                local path = t:gsub("{(%w+)}", function (k)
                  return math.type(v[k]) == "float" and ("%.14g"):format(v[k]) or tostring(v[k])
                end)
                local segs = {}
                for seg in path:gmatch("[^/]+") do
                  if seg == ".." then segs[#segs] = nil
                  elseif seg ~= "." then segs[#segs + 1] = seg end
                end
                path = table.concat(segs, "/")
                files[#files + 1] = path
                if path:find("%.obj$") then files[#files + 1] = path:gsub("%.obj$", ".mtl") end
              end
              for _, f in ipairs(files) do
                shared = shared or seen[f] ~= nil
                seen[f] = true
              end
            end
          end
        end
        return shared
      end
      local cases = {}
      for _, t in ipairs(TEMPLATES) do cases[#cases + 1] = { t } end
      for _, p in ipairs(PAIRS) do cases[#cases + 1] = p end
      local accepted, refused = 0, 0
      for _, outs in ipairs(cases) do
        local list = {}
        for i, t in ipairs(outs) do
          if t:find("%.mtl$") then list.lstring = t else list[i] = t end
        end
        local ok, e = pcall(batch.jobs, spec { vary = { { "a", { 1, 11, 0.1 } },
          { "b", { 1, 11 } }, { "steps", { 2 } } }, replicates = 2, outputs = list })
        local what = table.concat(outs, " ") .. ": " .. tostring(ok and "accepted" or e)
        if ok then
          accepted = accepted + 1
          assert.is_false(paths_by_hand(outs), what)
        else
          refused = refused + 1
          assert.truthy(e:find("is also written by job") or e:find("is written twice"), what)
          assert.is_true(paths_by_hand(outs), what)
        end
      end
      assert.is_true(accepted >= 15 and refused >= 5, accepted .. " accepted, " .. refused
        .. " refused")
    end)
  end)
end)
