--- `lsys arrange`: a derived model in the window, to bend, twist and prune by inverse
-- kinematics (lsys.arrange_ui); Ctrl-S saves the arranged L-string.
-- @module lsys.cli.commands.arrange
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help
local arrange = require "lsys.arrange"

local ipairs, tostring, tonumber, error, pcall, require, next =
      ipairs, tostring, tonumber, error, pcall, require, next
local io, string = io, string
local format = string.format
local parse, out, usage, model_opts, size_opt = A.parse, A.out, A.usage, A.model_opts, A.size_opt
local prepare, derive = S.prepare, S.derive
local _ENV = nil

local ARRANGE_OPTS = model_opts {
  size = "value", output = "value", string = "value", r0 = "value", s0u = "value",
  s0h = "value",
}

local function run (args)
  local opts, pos = parse("arrange", ARRANGE_OPTS, args, 2)
  if opts.help then out(HELP.arrange) return 0 end
  local w, h = size_opt("arrange", opts.size)
  local aopts = {}
  for _, k in ipairs { "r0", "s0u", "s0h" } do
    if opts[k] ~= nil then
      aopts[k] = tonumber(opts[k])
      if aopts[k] == nil or not (aopts[k] > 0) then
        usage("arrange", "--%s expects a number > 0, got '%s'", k, opts[k])
      end
    end
  end
  local model, path, views = prepare("arrange", opts, pos)
  if next(views) then aopts.view = views end
  local s
  if opts.string then
    local f, err = io.open(opts.string)
    if f == nil then error(format("cannot open '%s': %s", opts.string, tostring(err)), 0) end
    local text = f:read("a")
    f:close()
    local ok, r = pcall(model.lstring, model, (text:gsub("%s+$", "")))
    if not ok then error(format("%s: %s", opts.string, tostring(r)), 0) end
    s = r
  else
    s = derive(model, opts)
  end
  local arr = arrange(model, s, aopts)
  local outpath = opts.output or ((path:match("([^/]-)%.?[^./]*$") or "model") .. "-arranged.txt")
  require("lsys.ui.arrange").run(arr, { out = outpath, width = w, height = h,
                                        title = "arrange " .. path:match("([^/]*)$") })
  return 0
end

return run
