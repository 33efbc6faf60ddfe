--- `lsys batch`: the jobs of a CSV or Lua spec run through lsys.batch, or listed (--list),
-- with a progress line on a terminal.
-- @module lsys.cli.commands.batch
local A = require "lsys.cli.args"
local HELP = require("lsys.cli.help").help

local pairs, ipairs, tostring, error, pcall, require =
      pairs, ipairs, tostring, error, pcall, require
local io, string, table, math = io, string, table, math
local format = string.format
local parse, out, usage, clock, isatty, mmss, renamed =
      A.parse, A.out, A.usage, A.clock, A.isatty, A.mmss, A.renamed
local _ENV = nil

-- -d/--dir DIR is the output folder; -o/--out DIR its old spelling (everywhere else -o names
-- an output file).
local BATCH_OPTS = {
  dir = "value", out = "value", shard = "value", list = "flag", force = "flag",
  progress = "flag", help = "flag", short = { h = "help", d = "dir", o = "out" },
}

--[[
The progress(ev) of lsys.batch.run for the command line: on a terminal a line redrawn in
place (jobs done, failures, jobs a second, the time left), at most ten times a second;
elsewhere, with --progress, a line per job. A job that fails is said in any case, with its
message.
]]
local function batch_progress (opts)
  local tty, err = isatty(2), io.stderr
  local drawn
  local function bar (ev)
    local n = ev.todo
    local fill = math.floor(24 * ev.done / n)
    local rate = ev.seconds > 0 and ev.done / ev.seconds or 0
    return format("\rbatch: %d/%d [%s%s] %d failed, %.1f jobs/s, %s left\27[K", ev.done, n,
      ("#"):rep(fill), ("."):rep(24 - fill), ev.failed, rate,
      rate > 0 and mmss((n - ev.done) / rate) or "-:--")
  end
  return function (ev)
    if ev.phase == "start" then
      if ev.skipped > 0 and (tty or opts.progress) then
        err:write(format("batch: %d of %d jobs done before, skipped (--force runs them "
          .. "again)\n", ev.skipped, ev.jobs))
      end
      if tty and ev.todo > 0 then err:write(bar(ev)) drawn = clock() end
    elseif ev.phase == "job" then
      local rec = ev.record
      if rec.status == "failed" then
        err:write(format("%slsys: batch: job %s (%s) failed: %s\n", tty and "\r\27[K" or "",
          rec.job, rec.line, rec.error))
        drawn = nil
      elseif not tty and opts.progress then
        err:write(format("job %s ok (%.2f s), %d/%d\n", rec.job, rec.seconds, ev.done,
          ev.todo))
      end
      if tty and (drawn == nil or clock() - drawn >= 0.1 or ev.done == ev.todo) then
        err:write(bar(ev))
        drawn = clock()
      end
    elseif ev.phase == "end" and tty and ev.todo > 0 then
      err:write("\n")
    end
    err:flush()
  end
end

-- `lsys batch SPEC --list`: the jobs of the shard, done or not.
local function batch_list (batch, spec, opts, shard)
  local p = batch.plan(spec, { out = opts.dir, shard = shard })
  local STATUS = { done = "done", failed = "failed", todo = "to do" }
  local count = { done = 0, failed = 0, todo = 0 }
  for _, j in ipairs(p.jobs) do
    local vars = {}
    for k, v in pairs(j.params) do vars[#vars + 1] = format("%s=%s", k, tostring(v)) end
    table.sort(vars)
    if j.steps then table.insert(vars, 1, "steps=" .. j.steps) end
    if j.rep then vars[#vars + 1] = "rep=" .. j.rep end
    local outs = {}
    for i, o in ipairs(j.outputs) do outs[i] = o.path end
    out(format("%s  %-6s  seed %-10d  %s%s%s  -> %s\n", j.id, STATUS[j.status], j.seed,
      j.model, j.name and ":" .. j.name or "", #vars > 0 and "  " .. table.concat(vars, " ")
      or "", table.concat(outs, " ")))
    count[j.status] = count[j.status] + 1
  end
  out(format("%d job%s%s: %d done, %d failed, %d to do\n", #p.jobs, #p.jobs == 1 and "" or "s",
    p.n > 1 and format(" (shard %d/%d of %d)", p.k, p.n, p.total) or "", count.done,
    count.failed, count.todo))
  return 0
end

-- `lsys batch SPEC`: the jobs of a spec, or of one shard of them.
local function run (args)
  local opts, pos, given = parse("batch", BATCH_OPTS, args, 2)
  if opts.help then out(HELP.batch) return 0 end
  local flag = renamed("batch", opts, given, "out", "dir", "DIR", "d") and "--out" or "--dir"
  if #pos == 0 then usage("batch", "a SPEC is required: a .csv or .lua file listing the jobs") end
  if #pos > 1 then usage("batch", "unexpected argument '%s' (one SPEC)", pos[2]) end
  if opts.dir == "" then usage("batch", "%s expects a folder, got ''", flag) end
  if opts.list and opts.force then usage("batch", "--list runs nothing: --force does not apply") end
  local batch = require "lsys.batch"
  local shard
  if opts.shard ~= nil then
    local k, n = batch.parse_shard(opts.shard)
    if k == nil then usage("batch", "--shard %s", n) end
    shard = { k, n }
  end
  -- the messages name the spec's file and line; the function's name is no news here
  local function unnamed (err) return (tostring(err):gsub("^lsys%.batch%.%a+: ", "")) end
  if opts.list then
    local ok, r = pcall(batch_list, batch, pos[1], opts, shard)
    if not ok then error(unnamed(r), 0) end
    return r
  end
  local ok, r = pcall(batch.run, pos[1], { out = opts.dir, shard = shard,
                                           force = opts.force or nil,
                                           progress = batch_progress(opts) })
  if not ok then error(unnamed(r), 0) end
  local what = format("%s: %d job%s%s", pos[1], r.jobs, r.jobs == 1 and "" or "s",
    r.n > 1 and format(" (shard %d/%d of %d)", r.k, r.n, r.total) or "")
  local ran = r.ok + r.failed
  if ran == 0 then
    out(format("%s: %s\n", what, r.jobs == 0 and "nothing to do" or
      "all done before (--force runs them again)"))
    return 0
  end
  out(format("%s: %d ok, %d failed, %d done before; %d ran in %." .. (r.seconds < 10 and 2 or 1)
    .. "f s (%.1f jobs/s); manifest %s\n", what, r.ok, r.failed, r.skipped, ran, r.seconds,
    ran / math.max(r.seconds, 1e-9), r.manifest))
  return r.failed > 0 and 1 or 0
end

return run
