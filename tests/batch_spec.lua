-- Batch runs: lsys.batch and `lsys batch SPEC`. CSV specs (RFC 4180 quoting,
-- CRLF, errors that name the file, line and column), Lua specs (job lists, sweeps expanded
-- in a stated order), seeds made from the spec, shards (K/N and Slurm's variables); runs:
-- the files and the manifest, a failing job recorded while the others run, jobs done
-- skipped on the next run, a run killed by SIGKILL going on where it stopped, and the same
-- bytes from one process and from 2 shards under GNU parallel.
--
-- The runs write PNG pictures and are tagged #gl (OSMesa). The GNU parallel spec is
-- pending when parallel is not installed (Debian package parallel; ./setup.sh installs it).
local H = require "tests.helper"
local batch = require "lsys.batch"
local core = require "lsys.core"
local cjson = require "cjson"

local sh, ABSBIN = H.sh, H.ABSBIN

-- One word for the shell.
local q = require("lsys.util.text").shq

-- A small plant: R and angle are its variables; K is a job's number, and the start hook
-- kills the lsys process (SIGKILL, as `kill -9` from outside) at job KILL_AT when the
-- environment variable BATCH_KILL_AT says so.
local PLANT = [[
local lsys = require "lsys"
return lsys.lsystem {
  axiom = "A(1)", steps = 4, env = { R = 1.4, angle = 30, K = 0 },
  productions = "A(s) --> F(s)[+(angle)A(s/R)][-(angle)A(s/R)] : 2\nA(s) --> F(s)A(s/R) : 1",
  view = { background = { 1, 1, 1 } },
  start = function (m)
    if tostring(m.env.K) == os.getenv("BATCH_KILL_AT") then os.execute("kill -9 $PPID") end
  end,
}
]]

-- A model whose derivation fails when its variable k is 0.
local BAD = [[
local lsys = require "lsys"
return lsys.lsystem { axiom = "A", env = { k = 1 }, productions = "A --> B(1/k)",
  start = function (m) if m.env.k == 0 then error("k must not be 0") end end }
]]

-- The error message of batch.jobs(spec).
local function jobs_error (spec)
  local ok, err = pcall(batch.jobs, spec)
  assert.is_false(ok, "expected an error")
  return tostring(err)
end

-- The files under `dir` (relative paths, sorted), the manifests left out.
local function files (dir)
  local out = sh("cd " .. q(dir) .. " && find . -type f ! -name 'manifest*' | sort")
  local t = {}
  for f in out:gmatch("[^\n]+") do t[#t + 1] = f:gsub("^%./", "") end
  return t
end

-- The lines of a manifest, decoded.
local function manifest (path)
  local t = {}
  for l in io.lines(path) do t[#t + 1] = cjson.decode(l) end
  return t
end

-- The job lines of a manifest: job id -> status.
local function statuses (path)
  local t = {}
  for _, r in ipairs(manifest(path)) do
    if r.job then t[r.job] = r.status end
  end
  return t
end

describe("batch specs", function()
  local dir
  before_each(function()
    dir = H.tmpdir()
    assert(os.execute("mkdir -p " .. q(dir .. "/specs/models")))
    H.write(dir .. "/specs/models/plant.lua", PLANT)
  end)
  after_each(function() H.rmdir(dir) end)

  describe("CSV", function()
    it("reads quoted fields with commas, doubled quotes and line breaks, CRLF and blank lines",
    function()
      local rows = batch.csv('\239\187\191a, b ,c\r\n"x, y","say ""hi""",3\r\n\r\n'
        .. '"two\r\nlines", z ,""\n\n', "t.csv")
      assert.equal(3, #rows)
      assert.same({ "a", "b", "c", line = 1 }, rows[1])
      assert.same({ "x, y", 'say "hi"', "3", line = 2 }, rows[2])
      assert.same({ "two\r\nlines", "z", "", line = 4 }, rows[3])
      assert.same({ { "1", "", line = 1 } }, batch.csv("1,", "t.csv"))     -- no line break
    end)

    it("names the file and line of broken quoting", function()
      assert.error_contains(function () batch.csv('a,b\n1,"open\n\n2,3\n', "t.csv") end,
        "t.csv:2: field 2: the quote that opens it is not closed")
      assert.error_contains(function () batch.csv('a,b\n"x"y,1\n', "t.csv") end,
        "t.csv:2: field 1: text after the closing quote")
      assert.error_contains(function () batch.csv('a,b\n"l1\nl2",x"y\n', "t.csv") end,
        "t.csv:3: field 2: a quote inside an unquoted field")
    end)

    it("makes a job per record: the model found from the spec's folder, a variable per column",
    function()
      H.write(dir .. "/specs/plants.csv", "model,R,seed,steps,out,stats\r\n"
        .. 'models/plant.lua,1.2,,,"png/{id}.png; lstring/{id}-R{R}.txt",s/{model}-{id}.json\r\n'
        .. "models/plant.lua,,7,3,png/{id}.png,\r\n")
      local jobs, info = batch.jobs(dir .. "/specs/plants.csv")
      assert.equal(2, #jobs)
      assert.equal(2, info.total)
      local a, b = jobs[1], jobs[2]
      assert.equal("0001", a.id)
      assert.equal(dir .. "/specs/plants.csv:2", a.where)
      assert.equal("models/plant.lua", a.model)
      assert.equal(dir .. "/specs/models/plant.lua", a.path)
      assert.same({ R = 1.2 }, a.params)
      assert.is_nil(a.steps)
      assert.same({ { format = "png", path = "png/0001.png" },
                    { format = "lstring", path = "lstring/0001-R1.2.txt" },
                    { format = "stats", path = "s/plant-0001.json" } }, a.outputs)
      assert.equal("0002", b.id)
      assert.equal(7, b.seed)
      assert.equal(3, b.steps)
      assert.same({}, b.params)                          -- an empty cell sets nothing
      assert.same({ { format = "png", path = "png/0002.png" } }, b.outputs)
    end)

    it("names the file, line and column of a bad value", function()
      local spec = dir .. "/specs/bad.csv"
      local function err (text)         -- the message, without the folder of the spec
        H.write(spec, text)
        local msg, prefix = jobs_error(spec), dir .. "/specs/"
        while msg:find(prefix, 1, true) do
          local i = msg:find(prefix, 1, true)
          msg = msg:sub(1, i - 1) .. msg:sub(i + #prefix)
        end
        return msg
      end
      local head = "model,R,out\n"
      local ok = "models/plant.lua,1,x{id}.png\n"
      assert.equal("bad.csv:3: column 'R': 'abc' is not a number",
        err(head .. ok .. "models/plant.lua,abc,y.png\n"))
      assert.equal("bad.csv:2: column 'R': '1e999' is not a finite number",
        err(head .. "models/plant.lua,1e999,y.png\n"))
      assert.equal("bad.csv:4: column 'seed': '1.5' is not a whole number",
        err("model,seed,out\nmodels/plant.lua,1,a.png\n\nmodels/plant.lua,1.5,b.png\n"))
      assert.equal("bad.csv:2: column 'steps': '-1' must be from 0 to 10000000",
        err("model,steps,out\nmodels/plant.lua,-1,a.png\n"))
      assert.equal("bad.csv:3: 2 fields, the header (line 1) has 3",
        err(head .. ok .. "models/plant.lua,1\n"))
      assert.equal("bad.csv:2: column 'model': cannot open 'plant.lua' (a model's path is "
        .. "relative to the spec's folder)", err(head .. "plant.lua,1,a.png\n"))
      assert.equal("bad.csv:3: column 'out': {a b} is not a placeholder (they are {id}, {n}, "
        .. "{seed}, {model}, {name}, {steps}, {rep} and the model's variables, as {R})",
        err(head .. ok .. "models/plant.lua,1,{a b}.png\n"))
      assert.equal("bad.csv:2: column 'out': {R}: the job gives no value for R",
        err(head .. "models/plant.lua,,{R}.png\n"))
      assert.equal("bad.csv:3: column 'out': 'x0001.png' is also written by job 0001 "
        .. "(bad.csv:2): give each job its own files, with {id} for instance",
        err(head .. ok .. "models/plant.lua,2,x0001.png\n"))
      assert.equal("bad.csv:2: column 'out': 'a.gif': the format is told by the extension: "
        .. ".png, .glb, .obj, .ply, .json (stats) or .txt (the L-string)",
        err(head .. "models/plant.lua,1,a.gif\n"))
      assert.equal("bad.csv:2: column 'png': 'a.jpg': a png file's name ends in .png",
        err("model,png\nmodels/plant.lua,a.jpg\n"))
      assert.equal("bad.csv:2: no outputs: give file name templates such as png/{id}.png",
        err(head .. "models/plant.lua,1,\n"))
      assert.equal("bad.csv:1: column 3: 'leaf size' is not a model variable's name (letters, "
        .. "digits and _, not starting with a digit) nor one of id, model, name, seed, steps, "
        .. "width, height, out, png, glb, obj, ply, lstring, stats",
        err("model,out,leaf size\n"))
      assert.equal("bad.csv:1: no column 'model' (the model file of each job)",
        err("R,out\n1,a.png\n"))
      assert.equal("bad.csv:1: no output column: add 'out' (file name templates such as "
        .. "png/{id}.png, separated by ;) or png, glb, obj, ply, lstring, stats",
        err("model,R\n"))
      assert.equal("bad.csv:3: column 'id': job id 'a' is also the id of the job at bad.csv:2",
        err("model,id,out\nmodels/plant.lua,a,{id}.png\nmodels/plant.lua,a,b.png\n"))
      assert.equal("cannot open '" .. dir .. "/specs/none.csv': No such file or directory",
        jobs_error(dir .. "/specs/none.csv"))
    end)
  end)

  describe("Lua", function()
    it("expands a sweep in the byte order of its names, the last fastest, replicates innermost",
    function()
      local jobs = batch.jobs { dir = dir .. "/specs", model = "models/plant.lua", seed = 5,
        vary = { angle = { 20, 30 }, R = { 1.2, 1.4, 1.6 } }, replicates = 2, width = 64,
        outputs = { "{id}_R{R}_a{angle}_{rep}.png", stats = "{id}.json" } }
      assert.equal(12, #jobs)
      local got = {}
      for i, j in ipairs(jobs) do
        got[i] = j.outputs[1].path
        assert.equal(64, j.width)
        assert.equal(j.id .. ".json", j.outputs[2].path)
      end
      assert.same({ "0001_R1.2_a20_1.png", "0002_R1.2_a20_2.png", "0003_R1.2_a30_1.png",
                    "0004_R1.2_a30_2.png", "0005_R1.4_a20_1.png", "0006_R1.4_a20_2.png",
                    "0007_R1.4_a30_1.png", "0008_R1.4_a30_2.png", "0009_R1.6_a20_1.png",
                    "0010_R1.6_a20_2.png", "0011_R1.6_a30_1.png", "0012_R1.6_a30_2.png" }, got)
      assert.equal("spec: vary R=1.4 angle=30 rep=2", jobs[8].where)
    end)

    it("expands a sweep in the order a list of pairs gives, seeds and steps among them",
    function()
      local jobs = batch.jobs { dir = dir .. "/specs", model = "models/plant.lua",
        vary = { { "seed", { 3, 1 } }, { "steps", { 2, 4 } } }, outputs = { "{seed}-{steps}.txt" } }
      local got = {}
      for i, j in ipairs(jobs) do got[i] = j.outputs[1].path end
      assert.same({ "3-2.txt", "3-4.txt", "1-2.txt", "1-4.txt" }, got)
      assert.equal(4, jobs[2].steps)
      assert.equal(1, jobs[4].seed)
    end)

    it("gives a list's jobs the spec's defaults, reads a spec file, pads ids to the count",
    function()
      local list = {}
      for i = 1, 10001 do list[i] = { R = i } end
      local jobs = batch.jobs { dir = dir .. "/specs", model = "models/plant.lua", steps = 2,
        params = { angle = 10 }, outputs = { "{R}.txt" }, jobs = list }
      assert.equal("00001", jobs[1].id)
      assert.equal("10001", jobs[10001].id)
      assert.same({ R = 3, angle = 10 }, jobs[3].params)
      assert.equal(2, jobs[3].steps)
      H.write(dir .. "/specs/s.lua", 'return { { model = "models/plant.lua", out = "a.png" },\n'
        .. '  { model = "models/plant.lua", out = { png = "b.png" }, id = "tall", steps = 5 } }')
      jobs = batch.jobs(dir .. "/specs/s.lua")
      assert.equal("0001", jobs[1].id)
      assert.equal("tall", jobs[2].id)
      assert.equal(dir .. "/specs/s.lua: [2]", jobs[2].where)
    end)

    it("names the field of a bad value", function()
      local base = { dir = dir .. "/specs", model = "models/plant.lua", outputs = "{id}.txt" }
      local function err (t)
        for k, v in pairs(base) do if t[k] == nil then t[k] = v end end
        return jobs_error(t)
      end
      assert.equal("spec: vary.R[2]: 'abc' is not a number", err { vary = { R = { 1, "abc" } } })
      assert.equal("spec: vary.steps[1]: -1 must be from 0 to 10000000",
        err { vary = { steps = { -1 } } })
      -- a hole in a list of values (the batchspec fuzz target: concat of a nil word)
      assert.equal("spec: vary.seed[1]: a value expected, got nil",
        err { vary = { seed = { nil, 0 } } })
      assert.equal("spec: jobs[2].seed: 0.5 is not a whole number",
        err { jobs = { {}, { seed = 0.5 } } })
      assert.equal("spec: jobs[1]: model: cannot open 'models/none.lua'",
        jobs_error { dir = ".", model = "models/none.lua", outputs = "a.txt", jobs = { {} } })
      assert.equal("spec: vray: not a field of a spec (model, name, seed, steps, width, height, "
        .. "params, outputs, vary, replicates, jobs)", err { vray = {} })
      assert.equal("spec: replicates: with vary.seed every replicate would have the same seed: "
        .. "vary the seed or give replicates, not both",
        err { vary = { seed = { 1, 2 } }, replicates = 3 })
      assert.equal("spec: outputs[1]: 'a.gif': the format is told by the extension: .png, "
        .. ".glb, .obj, .ply, .json (stats) or .txt (the L-string)", err { outputs = "a.gif" })
      assert.equal("spec: vary: give jobs or vary, not both",
        err { jobs = { {} }, vary = { R = { 1 } } })
      H.write(dir .. "/specs/n.lua", "return 42")
      assert.equal(dir .. "/specs/n.lua returned number, not a spec (end the file with "
        .. "`return { model = ..., vary = { ... }, outputs = { ... } }` or a list of jobs)",
        jobs_error(dir .. "/specs/n.lua"))
      assert.equal("lsys.batch.jobs: 'x.txt': a spec is a CSV file (.csv) or a Lua file (.lua)",
        jobs_error("x.txt"))
      assert.equal("lsys.batch.jobs: a spec (a file name or a table) expected, got number",
        jobs_error(5))
    end)
  end)

  describe("seeds and shards", function()
    it("derives a job's seed from the spec's seed and its number: splitmix64's, top 31 bits",
    function()
      assert.equal(0xE220A8397B1DCDAF >> 33, batch.seed(0, 1))   -- splitmix64(0)'s first
      assert.equal(0x6E789E6AA1B965F4 >> 33, batch.seed(0, 2))
      local spec = { dir = dir .. "/specs", model = "models/plant.lua", seed = 42,
                     vary = { R = { 1, 2, 3 } }, outputs = { "{id}.txt" } }
      local jobs = batch.jobs(spec)
      for n, j in ipairs(jobs) do
        assert.equal(batch.seed(42, n), j.seed)
        assert.is_true(j.seed >= 0 and j.seed < 2^31)
      end
      assert.are_not.equal(jobs[1].seed, jobs[2].seed)
      spec.seed = 43
      assert.are_not.equal(jobs[1].seed, batch.jobs(spec)[1].seed)
    end)

    it("deals the jobs round to the shards", function()
      local got = {}
      for n = 1, 7 do got[n] = batch.shard_of(n, 3) end
      assert.same({ 1, 2, 3, 1, 2, 3, 1 }, got)
    end)

    it("reads K/N, and a Slurm array's task id, first id, step and count", function()
      assert.same({ 2, 5 }, { batch.parse_shard("2/5") })
      local function slurm (env)
        return { batch.parse_shard("slurm", function (k) return env[k] end) }
      end
      assert.same({ 1, 10 }, slurm { SLURM_ARRAY_TASK_ID = "0", SLURM_ARRAY_TASK_MIN = "0",
                                     SLURM_ARRAY_TASK_COUNT = "10" })
      assert.same({ 3, 4 }, slurm { SLURM_ARRAY_TASK_ID = "7", SLURM_ARRAY_TASK_MIN = "3",
                                    SLURM_ARRAY_TASK_STEP = "2", SLURM_ARRAY_TASK_COUNT = "4" })
      assert.same({ nil, "expects K/N (shard K of N, 1 <= K <= N) or slurm, got '3/2'" },
                  { batch.parse_shard("3/2") })
      assert.same({ nil, "slurm: SLURM_ARRAY_TASK_ID is not set (run it in a Slurm job array: "
        .. "sbatch --array=0-9 ...)" }, slurm {})
      assert.same({ nil, "slurm: SLURM_ARRAY_TASK_COUNT is not set (Slurm sets it in a job "
        .. "array: sbatch --array=0-9 ...)" }, slurm { SLURM_ARRAY_TASK_ID = "3" })
      assert.same({ nil, "slurm: task 12 is not one of 10 tasks from 0 by 1: give the array as "
        .. "a range (sbatch --array=0-9)" },
        slurm { SLURM_ARRAY_TASK_ID = "12", SLURM_ARRAY_TASK_COUNT = "10" })
    end)
  end)
end)

describe("#gl batch runs", function()
  if not core.has_render then
    pending("lsys was built without OSMesa (install libosmesa6-dev and rebuild)")
    return
  end
  local dir
  before_each(function()
    dir = H.tmpdir()
    H.write(dir .. "/plant.lua", PLANT)
    H.write(dir .. "/bad.lua", BAD)
  end)
  after_each(function() H.rmdir(dir) end)

  -- `lsys batch ARGS` in the folder `dir`: its output and exit status. (The shell that
  -- runs it stays to the end, so that what it says of a killed lsys is in the output.)
  local function run (args, env)
    return sh("cd " .. q(dir) .. " && " .. (env or "") .. " " .. q(ABSBIN) .. " batch " .. args
      .. "; exit $?")
  end

  -- The sweep: K = 1..6, two values of R, every format.
  local SWEEP = [[
return { model = "plant.lua", seed = 11, width = 64, height = 64,
         vary = { K = { 1, 2, 3 }, R = { 1.3, 1.6 } },
         outputs = { "png/{id}.png", "stats/{id}.json", "str/{id}.txt", "mesh/{id}.glb",
                     "mesh/{id}.obj", "mesh/{id}.ply" } }
]]

  it("writes each job's files and a manifest line; stats count the modules", function()
    H.write(dir .. "/sweep.lua", SWEEP)
    local out, code = run("sweep.lua -d out")
    assert.equal(0, code, out)
    assert.truthy(out:find("sweep.lua: 6 jobs: 6 ok, 0 failed, 0 done before; 6 ran in ", 1,
      true), out)
    assert.truthy(out:find("manifest out/manifest.jsonl", 1, true), out)
    local got = files(dir .. "/out")
    assert.equal(6 * 7, #got)                       -- .obj with its .mtl
    assert.equal("mesh/0001.glb", got[1])
    for i = 1, 6 do
      local id = ("%04d"):format(i)
      local _, w, h = core.png_read(dir .. "/out/png/" .. id .. ".png")
      assert.same({ 64, 64 }, { w, h })
      local st = cjson.decode(H.read(dir .. "/out/stats/" .. id .. ".json"))
      local text = H.read(dir .. "/out/str/" .. id .. ".txt")
      local m = dofile(dir .. "/plant.lua")
      m.seed, m.env.K, m.env.R = st.seed, st.params.K, st.params.R
      local s = m:derive()
      assert.equal(tostring(s) .. "\n", text)       -- the job's seed and variables
      if i == 1 then                                -- the picture lsys.render makes
        require("lsys").render(m:interpret(s), { out = dir .. "/x.png", width = 64,
                                                 height = 64 })
        assert.equal(H.read(dir .. "/x.png"), H.read(dir .. "/out/png/0001.png"))
      end
      assert.equal(#s, st.modules)
      assert.equal(s:count("F"), st.counts.F)
      assert.equal(batch.seed(11, i), st.seed)
      assert.equal(4, st.steps)
      assert.is_true(st.lines > 0)
      assert.equal(3, #st.bounds.max)
    end
    local lines = manifest(dir .. "/out/manifest.jsonl")
    assert.equal(8, #lines)
    assert.equal("start", lines[1].run)
    assert.equal("end", lines[8].run)
    local rec = lines[2]
    assert.equal("0001", rec.job)
    assert.equal("ok", rec.status)
    assert.equal("sweep.lua: vary K=1 R=1.3", rec.line)
    assert.equal(batch.seed(11, 1), rec.seed)
    assert.same({ K = 1, R = 1.3 }, rec.params)
    assert.equal(6, #rec.outputs)
    assert.equal("png/0001.png", rec.outputs[1].path)
    assert.equal(#H.read(dir .. "/out/png/0001.png"), rec.outputs[1].bytes)
    assert.is_number(rec.seconds)
  end)

  it("records a failing job with its message, runs the others, exits with status 1", function()
    H.write(dir .. "/f.csv", "model,k,out\nbad.lua,1,{id}.txt\nbad.lua,0,{id}.txt\n"
      .. "plant.lua,,{id}.png\n\"bad.lua\",2,{id}.txt\nplant.lua,3,{id}.txt\n")
    local out, code = run("f.csv")
    assert.equal(1, code, out)
    assert.truthy(out:find("lsys: batch: job 0002 (f.csv:3) failed: bad.lua:3: k must not be "
      .. "0\n", 1, true), out)
    assert.truthy(out:find("lsys: batch: job 0005 (f.csv:6) failed: plant.lua has no "
      .. "variable k (did you mean 'K'?)\n", 1, true), out)
    assert.truthy(out:find("f.csv: 5 jobs: 3 ok, 2 failed, 0 done before", 1, true), out)
    assert.same({ "0001.txt", "0003.png", "0004.txt", "bad.lua", "f.csv", "plant.lua" },
                files(dir))
    local st = statuses(dir .. "/manifest.jsonl")
    assert.same({ ["0001"] = "ok", ["0002"] = "failed", ["0003"] = "ok", ["0004"] = "ok",
                  ["0005"] = "failed" }, st)
    local rec = manifest(dir .. "/manifest.jsonl")[3]
    assert.equal("bad.lua:3: k must not be 0", rec.error)
    -- the failed jobs, and only they, run again
    out, code = run("f.csv --list")
    assert.equal(0, code, out)
    assert.truthy(out:find("0002  failed  seed ", 1, true), out)
    assert.truthy(out:find("5 jobs: 3 done, 2 failed, 0 to do", 1, true), out)
    out, code = run("f.csv")
    assert.equal(1, code, out)
    assert.truthy(out:find("f.csv: 5 jobs: 0 ok, 2 failed, 3 done before", 1, true), out)
  end)

  it("skips the jobs that are done; runs those whose line or files changed, or all with --force",
  function()
    local csv = "model,R,out\nplant.lua,1.2,{id}.txt\nplant.lua,1.3,{id}.txt\n"
      .. "plant.lua,1.4,{id}.txt\n"
    H.write(dir .. "/p.csv", csv)
    local out, code = run("p.csv -d o")
    assert.equal(0, code, out)
    out = run("p.csv -d o")
    assert.truthy(out:find("p.csv: 3 jobs: all done before (--force runs them again)", 1, true),
      out)
    H.write(dir .. "/p.csv", (csv:gsub("1%.3", "1.35")))     -- job 0002 changed
    os.remove(dir .. "/o/0003.txt")                           -- job 0003's file is gone
    H.write(dir .. "/o/0001.txt", "edited\n")                 -- job 0001's file was replaced
    out, code = run("p.csv -d o")
    assert.equal(0, code, out)
    assert.truthy(out:find("p.csv: 3 jobs: 3 ok, 0 failed, 0 done before", 1, true), out)
    out = run("p.csv -d o --force")
    assert.truthy(out:find("p.csv: 3 jobs: 3 ok, 0 failed, 0 done before", 1, true), out)
    assert.equal(3 * 5, #manifest(dir .. "/o/manifest.jsonl"))    -- 3 runs that ran jobs
  end)

  it("goes on where a killed run stopped, with the files a whole run makes", function()
    H.write(dir .. "/sweep.lua", SWEEP)
    -- job 5 is K = 3, R = 1.3: the process dies (SIGKILL) as that job starts
    local out, code = run("sweep.lua -d a", "BATCH_KILL_AT=3")
    assert.equal(137, code, out)
    local st = statuses(dir .. "/a/manifest.jsonl")
    assert.same({ ["0001"] = "ok", ["0002"] = "ok", ["0003"] = "ok", ["0004"] = "ok" }, st)
    local before = files(dir .. "/a")
    assert.equal(4 * 7, #before)                 -- no file of job 5, whole or in part
    for _, f in ipairs(before) do assert.falsy(f:find("0005", 1, true), f) end
    for _, f in ipairs(before) do
      if f:find("%.png$") then assert.truthy(core.png_read(dir .. "/a/" .. f)) end
    end
    local stamp = core.filestamp(dir .. "/a/png/0001.png")
    out, code = run("sweep.lua -d a")
    assert.equal(0, code, out)
    assert.truthy(out:find("sweep.lua: 6 jobs: 2 ok, 0 failed, 4 done before", 1, true), out)
    assert.equal(stamp, (core.filestamp(dir .. "/a/png/0001.png")))      -- not written again
    out, code = run("sweep.lua -d b")
    assert.equal(0, code, out)
    local all = files(dir .. "/b")
    assert.same(all, files(dir .. "/a"))
    for _, f in ipairs(all) do
      assert.equal(H.read(dir .. "/b/" .. f), H.read(dir .. "/a/" .. f), f)
    end
  end)

  it("gives the same bytes in one process and in 2 shards under GNU parallel", function()
    if (sh("command -v parallel")) == "" then
      pending("GNU parallel is not installed (Debian package parallel)")
      return
    end
    H.write(dir .. "/sweep.lua", SWEEP)
    local out, code = run("sweep.lua -d one")
    assert.equal(0, code, out)
    out, code = sh("cd " .. q(dir) .. " && parallel -j2 " .. q(ABSBIN)
      .. " batch sweep.lua -d two --shard {}/2 ::: 1 2")
    assert.equal(0, code, out)
    assert.truthy(out:find("sweep.lua: 3 jobs (shard 1/2 of 6): 3 ok", 1, true), out)
    assert.truthy(out:find("sweep.lua: 3 jobs (shard 2/2 of 6): 3 ok", 1, true), out)
    assert.same({ ["0001"] = "ok", ["0003"] = "ok", ["0005"] = "ok" },
                statuses(dir .. "/two/manifest-1-of-2.jsonl"))
    assert.same({ ["0002"] = "ok", ["0004"] = "ok", ["0006"] = "ok" },
                statuses(dir .. "/two/manifest-2-of-2.jsonl"))
    local all = files(dir .. "/one")
    assert.equal(6 * 7, #all)
    assert.same(all, files(dir .. "/two"))
    for _, f in ipairs(all) do
      assert.equal(H.read(dir .. "/one/" .. f), H.read(dir .. "/two/" .. f), f)
    end
    -- the shards' manifests count for an unsharded run, and the other way round
    out = run("sweep.lua -d two")
    assert.truthy(out:find("sweep.lua: 6 jobs: all done before", 1, true), out)
    out = run("sweep.lua -d one --shard 2/2 --list")
    assert.truthy(out:find("3 jobs (shard 2/2 of 6): 3 done, 0 failed, 0 to do", 1, true), out)
    -- a copy of the folder (its files' times new) keeps its jobs done
    assert.equal(0, select(2, sh("cp -r " .. q(dir .. "/two") .. " " .. q(dir .. "/copy"))))
    out = run("sweep.lua -d copy")
    assert.truthy(out:find("sweep.lua: 6 jobs: all done before", 1, true), out)
  end)

  it("gives the same bytes in one process and in a Slurm job array of 4 shards", function()
    -- docs/batch.md §7's job array, end to end on a one-node cluster of this host's own
    -- (tests/slurm.lua: munged, slurmctld and slurmd in a private folder)
    local S = require "tests.slurm"
    local ok, why = S.start()
    if not ok then
      pending(why)
      return
    end
    finally(S.stop)
    H.write(dir .. "/sweep.lua", SWEEP)
    local out, code = run("sweep.lua -d solo")
    assert.equal(0, code, out)
    H.write(dir .. "/array.sh", "#!/bin/bash\n#SBATCH --job-name=sweep\n#SBATCH --array=0-3\n"
      .. "#SBATCH --cpus-per-task=1\n#SBATCH --output=logs/sweep-%A_%a.log\n"
      .. "cd \"$SLURM_SUBMIT_DIR\"\n" .. q(ABSBIN) .. " batch sweep.lua -d arr --shard slurm\n")
    out, code = sh("cd " .. q(dir) .. " && mkdir -p logs && " .. S.env
      .. "sbatch --wait array.sh; exit $?")
    assert.equal(0, code, out)
    local logs = sh("cat " .. q(dir) .. "/logs/sweep-*.log")
    for k = 1, 4 do
      assert.truthy(logs:find("(shard " .. k .. "/4 of 6)", 1, true), logs)
    end
    local done = {}
    for k = 1, 4 do
      for job, st in pairs(statuses(dir .. "/arr/manifest-" .. k .. "-of-4.jsonl")) do
        assert.equal("ok", st)
        assert.is_nil(done[job], job .. " ran twice")
        done[job] = k
      end
    end
    assert.same({ ["0001"] = 1, ["0002"] = 2, ["0003"] = 3, ["0004"] = 4, ["0005"] = 1,
                  ["0006"] = 2 }, done)
    local all = files(dir .. "/solo")
    assert.equal(6 * 7, #all)
    assert.same(all, files(dir .. "/arr"))
    for _, f in ipairs(all) do
      assert.equal(H.read(dir .. "/solo/" .. f), H.read(dir .. "/arr/" .. f), f)
    end
  end)

  it("takes its shard from Slurm's variables, says what is wrong with the command line",
  function()
    H.write(dir .. "/p.csv", "model,R,out\nplant.lua,1.2,{id}.txt\nplant.lua,1.3,{id}.txt\n")
    local out, code = run("p.csv --shard slurm",
      "SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_MIN=3 SLURM_ARRAY_TASK_COUNT=2")
    assert.equal(0, code, out)
    assert.truthy(out:find("p.csv: 1 job (shard 2/2 of 2): 1 ok", 1, true), out)
    assert.same({ ["0002"] = "ok" }, statuses(dir .. "/manifest-2-of-2.jsonl"))
    local function usage (args, msg)
      local o, c = run(args)
      assert.equal(2, c, o)
      assert.truthy(o:find("lsys: batch: " .. msg, 1, true), o)
      assert.truthy(o:find("Run 'lsys batch --help' for its options.", 1, true), o)
    end
    usage("p.csv --shard slurm", "--shard slurm: SLURM_ARRAY_TASK_ID is not set")
    usage("p.csv --shard 3/2", "--shard expects K/N (shard K of N, 1 <= K <= N) or slurm, "
      .. "got '3/2'")
    usage("", "a SPEC is required: a .csv or .lua file listing the jobs")
    usage("p.csv q.csv", "unexpected argument 'q.csv' (one SPEC)")
    usage("p.csv --list --force", "--list runs nothing: --force does not apply")
    out, code = run("nope.csv")
    assert.equal(1, code, out)
    assert.equal("lsys: cannot open 'nope.csv': No such file or directory\n", out)
    H.write(dir .. "/e.csv", "model,R,out\nplant.lua,x,{id}.txt\n")
    out, code = run("e.csv")
    assert.equal(1, code, out)
    assert.equal("lsys: e.csv:2: column 'R': 'x' is not a number\n", out)
  end)

  it("writes into -d DIR (--dir DIR); -o DIR and --out DIR, the old spellings, warn", function()
    H.write(dir .. "/p.csv", "model,R,out\nplant.lua,1.2,{id}.txt\n")
    local function warning (old)
      return "Lua warning: lsys: 'lsys batch " .. old .. " DIR' is deprecated; use "
        .. "'lsys batch --dir DIR' (-d DIR)\n"
    end
    for _, c in ipairs { { "-d a", "a" }, { "--dir=b", "b" }, { "-o c", "c", "-o" },
                         { "--out d", "d", "--out" }, { "--out=e", "e", "--out" } } do
      local out, code = run("p.csv " .. c[1])
      assert.equal(0, code, out)
      assert.truthy(out:find("manifest " .. c[2] .. "/manifest.jsonl\n", 1, true), out)
      assert.equal(H.read(dir .. "/a/0001.txt"), H.read(dir .. "/" .. c[2] .. "/0001.txt"))
      if c[3] then
        assert.equal(warning(c[3]), out:match("^[^\n]*\n"))
      else
        assert.falsy(out:find("warning", 1, true), out)
      end
    end
    local function usage (args, msg)
      local o, c = run(args)
      assert.equal(2, c, o)
      assert.truthy(o:find("lsys: batch: " .. msg .. "\nRun 'lsys batch --help' for its options.",
        1, true), o)
    end
    usage("p.csv -d a -o b", "-o is the old spelling of -d: give one of them")
    usage("p.csv --dir=", "--dir expects a folder, got ''")
    usage("p.csv --out=", "--out expects a folder, got ''")
    local out = run("--help")
    assert.truthy(out:find("\n  -d, --dir DIR     the output folder", 1, true), out)
  end)
end)
