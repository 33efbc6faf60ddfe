--- `lsys derive`: derives a model and prints its L-string in cpfg notation, or its
-- statistics (--stats).
-- @module lsys.cli.commands.derive
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help

local type, pairs, ipairs, tostring, pcall = type, pairs, ipairs, tostring, pcall
local string, table, math, io = string, table, math, io
local format = string.format
local parse, out, clock, model_opts = A.parse, A.out, A.clock, A.model_opts
local prepare, derive = S.prepare, S.derive
local _ENV = nil

local DERIVE_OPTS = model_opts { stats = "flag", progress = "flag", view = false }

-- The method 'name' of the Lstring 's', or nil when 's' has none.
local function method (s, name)
  local ok, f = pcall(function () return s[name] end)
  return ok and type(f) == "function" and f or nil
end

-- The number of each module name in 's', as a sorted list of { name, count }.
local function module_counts (s)
  local counts = {}
  local f = method(s, "counts")
  if f then                             -- a C-side count when the Lstring has one
    counts = f(s)
  else
    for _, name in s:modules() do counts[name] = (counts[name] or 0) + 1 end
  end
  local list = {}
  for name, n in pairs(counts) do list[#list + 1] = { name, n } end
  table.sort(list, function (a, b) return a[1] < b[1] end)
  return list
end

local function run (args)
  local opts, pos = parse("derive", DERIVE_OPTS, args, 2)
  if opts.help then out(HELP.derive) return 0 end
  local model = prepare("derive", opts, pos)

  local t0 = clock()
  local s = derive(model, opts)
  local elapsed = clock() - t0

  if not opts.stats then
    local write = method(s, "write")
    if write then write(s, io.stdout, "\n")  -- streamed from C, never one Lua string
    else out(tostring(s), "\n") end
    return 0
  end
  local counts = module_counts(s)
  local width = 1
  for _, c in ipairs(counts) do width = math.max(width, #c[1]) end
  out(format("steps %s\n", tostring(model.steps or 0)))
  out(format("modules %d\n", #s))
  for _, c in ipairs(counts) do out(format("  %-" .. width .. "s %d\n", c[1], c[2])) end
  out(format("time %.3f s\n", elapsed))
  return 0
end

return run
