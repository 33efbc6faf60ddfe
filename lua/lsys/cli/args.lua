--- What the commands of the `lsys` program share: usage errors, output, the terminal and
-- files, the option parser, the option readers and the progress lines of several commands.
-- @module lsys.cli.args
local program = require "lsys.program"
local fs = require "lsys.util.fs"
local warning = require "lsys.warning"
local suggest = require "lsys.util.suggest"

local pairs, tonumber, tostring, error, setmetatable, type =
      pairs, tonumber, tostring, error, setmetatable, type
local io, string, table, math = io, string, table, math
local format = string.format
local host, clock = program.host, program.clock
local isfile, isdir = fs.isfile, fs.isdir
local _ENV = nil

local M = {}

-- {===========================================================================================
-- Errors and output

local USAGE_ERROR = {}  -- metatable of usage errors

-- Raises a usage error (exit status 2) for command 'cmd' (nil: the program itself).
local function usage (cmd, fmt, ...)
  error(setmetatable({ cmd = cmd, msg = format(fmt, ...) }, USAGE_ERROR), 0)
end

local function out (...)
  io.stdout:write(...)
end

local function isatty (fd)
  local f = host().isatty
  return f ~= nil and f(fd) or false
end

-- }===========================================================================================


-- {===========================================================================================
-- Option parsing

--[[
Parses args[first..] against 'spec', a table of option name -> "flag" | "value" | "list"
(short aliases: spec.short = { h = "help", o = "output" }). Accepts `--name value`,
`--name=value`, `-x value`, and `--` before positional arguments. Returns the options table,
the list of positional arguments and how each option was spelt ({ out = "-o" }: what a
message about it quotes); raises usage errors for command 'cmd'.
]]
local function parse (cmd, spec, args, first)
  local opts, pos, given = {}, {}, {}
  local i = first
  while i <= args.n do
    local a = args[i]
    local name, val
    if a == "--" then
      for j = i + 1, args.n do pos[#pos + 1] = args[j] end
      break
    elseif a:sub(1, 2) == "--" then
      name, val = a:match("^%-%-([^=]+)=(.*)$")
      name = name or a:sub(3)
    elseif #a == 2 and a:sub(1, 1) == "-" and a ~= "--" then
      name = spec.short and spec.short[a:sub(2)]
      if name == nil then usage(cmd, "unknown option '%s'", a) end
    end
    if name ~= nil then
      local kind = spec[name]
      if kind == nil or name == "short" then
        local names = {}
        for k in pairs(spec) do
          if k ~= "short" then names[#names + 1] = k end
        end
        usage(cmd, "unknown option '--%s'%s", name,
              suggest.hint(name, names, function (n) return "'--" .. n .. "'" end))
      end
      given[name] = a:match("^[^=]*")
      if kind == "flag" then
        if val ~= nil then usage(cmd, "option '--%s' takes no value", name) end
        opts[name] = true
      else
        if val == nil then
          i = i + 1
          val = args[i]
          if val == nil then usage(cmd, "option '--%s' needs a value", name) end
        end
        if kind == "list" then
          opts[name] = opts[name] or {}
          table.insert(opts[name], val)
        else
          opts[name] = val
        end
      end
    elseif a:sub(1, 1) == "-" and a ~= "-" then
      usage(cmd, "unknown option '%s'", a)
    else
      pos[#pos + 1] = a
    end
    i = i + 1
  end
  return opts, pos, given
end

--[[
An option under its old spelling: `old` (an option name of the spec) is now `new`. When
given, the first use warns as deprecated names do (lsys.warning: "lsys: 'lsys batch -o DIR'
is deprecated; use 'lsys batch --dir DIR' (-d DIR)"), and its value moves to opts[new].
`arg` names the value in the messages ("DIR"), `short` the new short spelling (nil: none).
Returns the spelling given (`given` from parse), for the messages about the value; nil when
the old one was not given. Both spellings at once are a usage error.
]]
local function renamed (cmd, opts, given, old, new, arg, short)
  if opts[old] == nil then return nil end
  local was = given[old]
  if opts[new] ~= nil then
    usage(cmd, "%s is the old spelling of %s: give one of them", was, given[new])
  end
  warning.deprecated(format("'lsys %s %s %s'", cmd, was, arg),
    format("'lsys %s --%s %s'%s", cmd, new, arg, short and format(" (-%s %s)", short, arg) or ""))
  opts[new], opts[old] = opts[old], nil
  return was
end

-- The options of the commands that load a model (model_source, prepare) and then the
-- command's own: `extra` (false: an option the command does not take), with -h for --help
-- and, when it has --output, -o for it. --threads, --max-memory and --max-modules set the
-- model options threads, max_memory and max_modules.
local function model_opts (extra)
  local o = { steps = "value", seed = "value", set = "list", name = "value", view = "list",
              map = "value", mat = "value", define = "list", environment = "value",
              threads = "value", ["max-memory"] = "value", ["max-modules"] = "value",
              help = "flag", short = { h = "help", o = extra.output and "output" or nil } }
  for k, v in pairs(extra) do o[k] = v or nil end
  return o
end

-- The options of render and export (export refuses --size, --frames and --every).
local RENDER_OPTS = model_opts {
  output = "value", size = "value", progress = "flag", lines = "value", frames = "value",
  every = "value", flat = "flag", ao = "flag",
}

-- --size WxH (nil when absent).
local function size_opt (cmd, s)
  if s == nil then return nil end
  local w, h = s:match("^(%d+)[xX](%d+)$")
  w, h = tonumber(w), tonumber(h)
  if w == nil or w < 1 or h < 1 or w > 16384 or h > 16384 then
    usage(cmd, "--size expects WxH (1 to 16384 each), got '%s'", s)
  end
  return w, h
end

-- The file a command writes without -o: the model's name (a folder's, a file's without its
-- extension) with `ext`, in the current directory; `default` without MODEL.
local function default_output (pos, ext, default)
  local name = pos[1] and pos[1]:gsub("/+$", "")
  if name == nil then return default end
  local base = name:match("([^/]*)$")
  if not isdir(name) then base = base:match("^(.+)%.[^.]*$") or base end
  return (base ~= "" and base or "model") .. ext
end

-- A whole number option (at least 'lo'; nil when absent).
local function int_opt (cmd, name, v, lo)
  if v == nil then return nil end
  local n = math.tointeger(tonumber(v))
  if n == nil or n < lo then
    usage(cmd, "--%s expects a whole number >= %d, got '%s'", name, lo, v)
  end
  return n
end

-- }===========================================================================================


-- {===========================================================================================
-- Progress

-- Minutes and seconds.
local function mmss (t)
  t = math.max(0, math.floor(t + 0.5))
  return format("%d:%02d", t // 60, t % 60)
end

--[[
The progress(phase, k, n, detail) of lsys.frames and lsys.animate for a command line: on a
terminal a line redrawn in place (the step derived; then the frame, a bar, the time taken
and the time left); elsewhere, with --progress, a plain line for each; else nil.
]]
local function frames_progress (opts)
  local tty = isatty(2)
  if not tty and not opts.progress then return nil end
  local err, t0 = io.stderr, clock()
  return function (phase, k, n, detail, step)
    if phase == "derive" then
      err:write(format(tty and "\rderiving: step %d/%d, %d modules\27[K" or
                       "step %d/%d: %d modules\n", k, n, detail))
    elseif phase == "frame" and k == 0 then
      t0 = clock()
      if tty then err:write(format("\rframe 0/%d\27[K", n)) end
    elseif phase == "frame" then
      local spent = clock() - t0
      if tty then
        local fill = math.floor(24 * k / n)
        err:write(format("\rframe %d/%d [%s%s] %s, %s left\27[K%s", k, n, ("#"):rep(fill),
          ("."):rep(24 - fill), mmss(spent), mmss(spent / k * (n - k)), k == n and "\n" or ""))
      else
        err:write(format("frame %d/%d: %s (%.1f s)\n", k, n, type(step) == "string" and step
          or format("step %d", step), spent))
      end
    elseif phase == "encode" then
      err:write(format("encoding %s with ffmpeg\n", detail))
    end
    err:flush()
  end
end

-- A message of lsys.frames or lsys.animate for the command line: without where in lsys it
-- was raised and the function's name.
local function frames_error (err)
  return (tostring(err):gsub("^[^:\n]*%.lua:%d+: ", ""):gsub("^lsys%.%a+: ", ""))
end

-- }===========================================================================================

M.USAGE_ERROR = USAGE_ERROR
M.usage = usage
M.out = out
M.isatty = isatty
M.clock = clock
M.isfile = isfile
M.isdir = isdir
M.parse = parse
M.renamed = renamed
M.model_opts = model_opts
M.RENDER_OPTS = RENDER_OPTS
M.size_opt = size_opt
M.default_output = default_output
M.int_opt = int_opt
M.mmss = mmss
M.frames_progress = frames_progress
M.frames_error = frames_error

return M
