--- `lsys export`: a model's geometry written to an .obj, .ply or .glb file.
-- @module lsys.cli.commands.export
local core = require "lsys.core"
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help
local series = require("lsys.util.text").series

local ipairs, string = ipairs, string
local format = string.format
local parse, out, usage, RENDER_OPTS = A.parse, A.out, A.usage, A.RENDER_OPTS
local scene_of = S.scene_of
local _ENV = nil

-- The export formats of the core by their extension, and the two lists the messages give:
-- "OUT.obj, OUT.ply or OUT.glb", ".obj, .ply or .glb".
local BY_EXT, OUTS, EXTS = {}, {}, {}
for _, f in ipairs(core.formats()) do
  BY_EXT[f.ext] = f
  OUTS[#OUTS + 1] = "OUT." .. f.ext
  EXTS[#EXTS + 1] = "." .. f.ext
end
OUTS, EXTS = series(OUTS, "or"), series(EXTS, "or")

local function run (args)
  local opts, pos = parse("export", RENDER_OPTS, args, 2)
  if opts.help then out(HELP.export) return 0 end
  if opts.size ~= nil then usage("export", "--size applies to render only") end
  if opts.frames ~= nil or opts.every ~= nil then
    usage("export", "--frames and --every apply to render only")
  end
  if #pos == 0 then usage("export", "a MODEL is required") end
  local outpath = opts.output
  if outpath == nil then usage("export", "-o %s is required", OUTS) end
  local ext = outpath:lower():match("%.(%w+)$")
  if ext == nil or BY_EXT[ext] == nil then
    usage("export", "the output must end in %s, got '%s'", EXTS, outpath)
  end
  if opts.lines ~= nil and opts.lines ~= "lines" and opts.lines ~= "tubes" then
    usage("export", "--lines expects 'lines' or 'tubes', got '%s'", opts.lines)
  end
  local scene = scene_of("export", opts, pos)
  local n = scene:save(outpath, { lines = opts.lines })    -- what the file holds
  local tubes = opts.lines == "tubes" and scene.nlines > 0
  out(format("wrote %s (%d vertices, %d triangles, %d lines%s)\n", outpath, n.vertices,
    n.triangles, n.lines, tubes and format("; %d lines as tubes", scene.nlines) or ""))
  return 0
end

return run
