-- The files `lsys batch` writes (lua/lsys/batch/, docs/batch.md
-- §4-§6): outputs stay inside the output folder (a template that leaves it, by "..", an
-- absolute path, or a model's or name's text, is refused before any job runs), never go
-- through a symbolic link already in the folder, a resumed run removes the temporaries that
-- dead runs left of its own files (and nothing else), and a manifest the system refuses to
-- grow stops the run with a message instead of passing for written.
--
-- The jobs write L-strings and statistics only: nothing here needs OSMesa.
local H = require "tests.helper"
local batch = require "lsys.batch"

local sh, q = H.sh, require("lsys.util.text").shq

local MODEL = [[
return require("lsys").lsystem { axiom = "A", steps = 1, env = { k = 1 }, productions = "A --> F" }
]]

-- The error message of batch.jobs(spec).
local function jobs_error (spec)
  local ok, err = pcall(batch.jobs, spec)
  assert.is_false(ok, "expected an error")
  return tostring(err)
end

describe("batch outputs", function()
  local dir
  before_each(function()
    dir = H.tmpdir()
    H.write(dir .. "/m.lua", MODEL)
  end)
  after_each(function() H.rmdir(dir) end)

  -- `lsys batch ARGS` in the folder `dir` (`pre`: shell commands before it).
  local function run (args, pre)
    return sh("cd " .. q(dir) .. " && " .. (pre or "") .. " exec " .. q(H.ABSBIN) .. " batch "
      .. args)
  end

  it("refuses a template that leaves the output folder, said before any job runs", function()
    local function err (out)
      H.write(dir .. "/f.csv", "model,out\nm.lua,a{id}.txt\nm.lua," .. out .. "\n")
      local msg = jobs_error(dir .. "/f.csv")
      return (msg:gsub(dir:gsub("%p", "%%%0") .. "/", ""))
    end
    assert.equal("f.csv:3: column 'out': '../0002.txt' leaves the output folder: an output is "
      .. "a file in it", err("../{id}.txt"))
    assert.equal("f.csv:3: column 'out': 'a/./../b/../../0002.txt' leaves the output folder: "
      .. "an output is a file in it", err("a/./../b/../../{id}.txt"))
    assert.equal("f.csv:3: column 'out': '/tmp/x0002.txt' is an absolute path: an output is a "
      .. "file in the output folder, named relative to it", err("/tmp/x{id}.txt"))
    H.write(dir .. "/f.csv", "model,lstring\nm.lua,a/..\n")
    assert.equal(dir .. "/f.csv:2: column 'lstring': 'a/..' is not a file name",
      jobs_error(dir .. "/f.csv"))
    H.write(dir .. "/f.csv", "model,lstring\nm.lua,x{id}/.\n")
    assert.equal(dir .. "/f.csv:2: column 'lstring': 'x0001/.' is not a file name",
      jobs_error(dir .. "/f.csv"))
    -- through the text of a placeholder: a model named ...lua ({model} is ..), a name
    H.write(dir .. "/...lua", MODEL)
    assert.equal("spec: jobs[2]: outputs[1]: '../0002.txt' leaves the output folder: an output "
      .. "is a file in it", jobs_error { dir = dir, outputs = "{model}/{id}.txt",
        jobs = { { model = "m.lua" }, { model = "...lua" } } })
    assert.equal("spec: vary name=../../up: outputs[1]: '../../up/0002.txt' leaves the output "
      .. "folder: an output is a file in it", jobs_error { dir = dir, model = "m.lua",
        vary = { name = { "a", "../../up" } }, outputs = "{name}/{id}.txt" })
    -- and by the program, which writes nothing
    H.write(dir .. "/f.csv", "model,out\nm.lua,a{id}.txt\nm.lua,../{id}.txt\n")
    local out, code = run("f.csv -d o")
    assert.equal(1, code, out)
    assert.equal("lsys: f.csv:3: column 'out': '../0002.txt' leaves the output folder: an "
      .. "output is a file in it\n", out)
    assert.is_nil(H.read(dir .. "/0002.txt"))
    assert.is_nil(H.read(dir .. "/o/a0001.txt"))
  end)

  it("writes and records a template's normalized path", function()
    H.write(dir .. "/f.csv", "model,out\nm.lua,./sub//x/../{id}.txt\n")
    local r = batch.run(dir .. "/f.csv", { out = dir .. "/o" })
    assert.equal(1, r.ok)
    assert.equal("F\n", H.read(dir .. "/o/sub/0001.txt"))
    local line = H.read(dir .. "/o/manifest.jsonl")
    assert.truthy(line:find('"outputs":[{"format":"lstring","path":"sub/0001.txt","bytes":2,',
      1, true), line)
  end)

  it("writes no file through a symbolic link of the output folder", function()
    assert(os.execute("mkdir -p " .. q(dir .. "/o") .. " " .. q(dir .. "/elsewhere")))
    H.write(dir .. "/victim.txt", "keep\n")
    assert(os.execute("ln -s ../elsewhere " .. q(dir .. "/o/link") .. " && ln -s ../victim.txt "
      .. q(dir .. "/o/0002.txt")))
    H.write(dir .. "/f.csv", "model,out\nm.lua,link/{id}.txt\nm.lua,{id}.txt\n"
      .. "m.lua,ok/{id}.txt\nm.lua,link/../{id}.txt\n")
    local out, code = run("f.csv -d o")
    assert.equal(1, code, out)
    assert.truthy(out:find("lsys: batch: job 0001 (f.csv:2) failed: cannot write "
      .. "'o/link/0001.txt': 'o/link' is a symbolic link (lsys batch writes no file through a "
      .. "link)\n", 1, true), out)
    assert.truthy(out:find("lsys: batch: job 0002 (f.csv:3) failed: cannot write "
      .. "'o/0002.txt': 'o/0002.txt' is a symbolic link (lsys batch writes no file through a "
      .. "link)\n", 1, true), out)
    assert.truthy(out:find("f.csv: 4 jobs: 2 ok, 2 failed, 0 done before", 1, true), out)
    assert.equal("keep\n", H.read(dir .. "/victim.txt"))
    assert.equal("", (sh("ls -A " .. q(dir .. "/elsewhere"))))
    assert.equal("F\n", H.read(dir .. "/o/ok/0003.txt"))
    assert.equal("F\n", H.read(dir .. "/o/0004.txt"))          -- link/.. is the folder itself
    -- a manifest that is a link is not appended to
    H.write(dir .. "/g.csv", "model,out\nm.lua,g{id}.txt\n")
    assert(os.execute("ln -s ../victim.txt " .. q(dir .. "/o/manifest-1-of-2.jsonl")))
    out, code = run("g.csv -d o --shard 1/2")
    assert.equal(1, code, out)
    assert.equal("lsys: cannot write the manifest 'o/manifest-1-of-2.jsonl': it is a symbolic "
      .. "link (lsys batch writes no file through a link)\n", out)
    assert.equal("keep\n", H.read(dir .. "/victim.txt"))
  end)

  it("removes on resume the temporaries dead runs left of its own files, nothing else",
  function()
    local f = io.open("/proc/self/stat", "r")
    local me = f and f:read("n")
    if f then f:close() end
    if not me then
      pending("no /proc/self/stat (Linux only)")
      return
    end
    -- a process that has ended: its id is not alive (unless reused since)
    local dead
    repeat
      dead = tonumber((sh("sh -c 'echo $$'")))
      local p = io.open("/proc/" .. dead .. "/stat", "r")
      if p then p:close() dead = nil end
    until dead
    H.write(dir .. "/f.csv", "model,out\nm.lua,{id}.txt;s/{id}.json\nm.lua,{id}.txt\n"
      .. "m.lua,{id}.txt\nm.lua,{id}.txt\n")
    local r = batch.run(dir .. "/f.csv", { out = dir .. "/o", shard = "1/2" })
    assert.equal(2, r.ok)
    local files = {
      [".0001.txt.lsys-" .. dead .. "-1.tmp"] = false,      -- job 1's (done): removed
      ["s/.0001.json.lsys-" .. dead .. "-12.tmp"] = false,  -- job 1's other file
      [".0003.txt.lsys-" .. dead .. "-2.tmp"] = false,      -- job 3's
      [".0003.txt.lsys-" .. me .. "-3.tmp"] = true,         -- a live process's: kept
      [".0002.txt.lsys-" .. dead .. "-1.tmp"] = true,       -- job 2's: shard 2's, kept
      [".other.txt.lsys-" .. dead .. "-1.tmp"] = true,      -- no job's file
      [".0001.txt.lsys-x-1.tmp"] = true,                    -- not lsys's name
      [".0001.txt.lsys-" .. dead .. "-1.tmp.bak"] = true,
      ["0001.txt.lsys-" .. dead .. "-1.tmp"] = true,        -- not hidden
    }
    for name in pairs(files) do H.write(dir .. "/o/" .. name, "partial") end
    assert(os.execute("ln -s ../m.lua " .. q(dir .. "/o/.0001.txt.lsys-" .. dead .. "-9.tmp")))
    files[".0001.txt.lsys-" .. dead .. "-9.tmp"] = true     -- a link, not a file
    r = batch.run(dir .. "/f.csv", { out = dir .. "/o", shard = "1/2" })
    assert.equal(0, r.ok + r.failed)
    assert.equal(2, r.skipped)
    assert.equal(3, r.removed)
    for name, kept in pairs(files) do
      local there = sh("test -e " .. q(dir .. "/o/" .. name) .. " -o -L "
        .. q(dir .. "/o/" .. name) .. " && echo yes") == "yes\n"
      assert.equal(kept, there, name)
    end
    -- the program, resuming a job, says so in the manifest's start line
    H.write(dir .. "/o/.0003.txt.lsys-" .. dead .. "-5.tmp", "partial")
    os.remove(dir .. "/o/0003.txt")
    local out, code = run("f.csv -d o --shard 1/2")
    assert.equal(0, code, out)
    assert.truthy(out:find("f.csv: 2 jobs (shard 1/2 of 4): 1 ok, 0 failed, 1 done before", 1,
      true), out)
    assert.is_nil(H.read(dir .. "/o/.0003.txt.lsys-" .. dead .. "-5.tmp"))
    local last
    for l in io.lines(dir .. "/o/manifest-1-of-2.jsonl") do
      if l:find('^{"run":"start"') then last = l end
    end
    assert.truthy(last:find('"todo":1,"removed":1,', 1, true), last)
  end)

  it("stops with a message when the manifest cannot grow (a file size limit)", function()
    H.write(dir .. "/f.csv", "model,out\nm.lua,{id}.txt\nm.lua,{id}.txt\nm.lua,{id}.txt\n")
    -- 512 bytes: the start line and part of the first job's; SIGXFSZ ignored, so that the
    -- write fails with EFBIG instead of killing the process
    local out, code = run("f.csv", "trap '' XFSZ; ulimit -f 1;")
    assert.equal(1, code, out)
    assert.equal("lsys: cannot write the manifest 'manifest.jsonl': File too large\n", out)
    local text = H.read(dir .. "/manifest.jsonl")
    assert.equal(512, #text)
    local cut = text:match("\n([^\n]*)$")                   -- the line the limit cut short
    local id = tonumber(cut:match('^{"job":"(%d+)"'))
    assert.is_number(id, text)
    assert.equal("F\n", H.read(dir .. ("/%04d.txt"):format(id)))
    for later = id + 1, 3 do                                -- no job after the failure
      assert.is_nil(H.read(dir .. ("/%04d.txt"):format(later)))
    end
    -- the next run ends the line cut short, and runs the job whose line was lost
    out, code = run("f.csv")
    assert.equal(0, code, out)
    assert.truthy(out:find(("f.csv: 3 jobs: %d ok, 0 failed, %d done before"):format(4 - id,
      id - 1), 1, true), out)
    local lines = {}
    for l in io.lines(dir .. "/manifest.jsonl") do lines[#lines + 1] = l end
    assert.equal(text, table.concat(lines, "\n", 1, id + 1))
    assert.truthy(lines[id + 2]:find('^{"run":"start"'), lines[id + 2])
    assert.equal(id + 1 + (4 - id) + 2, #lines)
  end)
end)
