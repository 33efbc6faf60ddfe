--- `lsys import`: a cpfg model (a .l file with its view file, or a vlab object folder)
-- written as a readable lsys model file.
-- @module lsys.cli.commands.import
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help

local tostring, error, pcall, require = tostring, error, pcall, require
local string = string
local format = string.format
local parse, out, usage, isdir = A.parse, A.out, A.usage, A.isdir
local model_source = S.model_source
local _ENV = nil

local IMPORT_OPTS = {
  output = "value", map = "value", mat = "value", define = "list", environment = "value",
  help = "flag",
  short = { h = "help", o = "output" },
}

-- `lsys import MODEL.l [VIEW.v] -o OUT.lua`: the cpfg model as an lsys model file.
local function run (args)
  local opts, pos = parse("import", IMPORT_OPTS, args, 2)
  if opts.help then out(HELP.import) return 0 end
  local arg = pos[1]
  if arg == nil then
    usage("import", "a cpfg MODEL (a .l file or a vlab object folder) is required")
  end
  if not arg:find("%.l$") and not isdir(arg) then
    usage("import", "'%s' is not a cpfg model: MODEL is a .l file or a vlab object folder", arg)
  end
  local outpath = opts.output
  if outpath == nil then usage("import", "-o OUT.lua is required: the lsys model file to write") end
  if not outpath:find("%.lua$") then
    usage("import", "the output must be a .lua file, got '%s'", outpath)
  end
  local src = model_source("import", opts, pos)
  local cpfg = require "lsys.cpfg"
  local l, v, lopts = src.path, src.vfile, src.lopts
  local ok, err = pcall(function ()
    if src.kind == "object" then
      local pal
      l, v, pal = cpfg.object_files(src.path)
      if pal and not lopts.colormap and not lopts.materials then
        if pal:match("%.mat$") then lopts.materials = pal else lopts.colormap = pal end
      end
    end
    require("lsys.cpfg.import").write(l, v, outpath, lopts)
  end)
  if not ok then
    error((tostring(err):gsub("^lsys%.view%.load: ", ""):gsub("^lsys%.cpfg%.%a+: ", "")), 0)
  end
  out(format("wrote %s\n", outpath))
  return 0
end

return run
