--- `lsys sketch`: the sketch window, or with plot, model or render a sketch file's
-- positional functions, generated model (a Lua model file, or with --cpfg cpfg's files) or
-- picture written to a file; --organ gives the organ drawn at the nodes.
-- @module lsys.cli.commands.sketch
local A = require "lsys.cli.args"
local HELP = require("lsys.cli.help").help
local render = require("lsys.render").render

local tostring, tonumber, error, pcall, require, ipairs =
      tostring, tonumber, error, pcall, require, ipairs
local string, math, table = string, math, table
local format = string.format
local parse, out, usage, size_opt, isfile = A.parse, A.out, A.usage, A.size_opt, A.isfile
local warn = require("lsys.warning").warn
local _ENV = nil

local SKETCH_OPTS = {
  size = "value", nodes = "value", phyllotaxis = "value", output = "value", help = "flag",
  organ = "value", cpfg = "flag",
  short = { h = "help", o = "output" },
}

-- The leaf shapes of lsys.sketch.organ.leaf that --organ takes by name.
local SHAPES = { ovate = true, lanceolate = true, elliptic = true, obovate = true,
                 linear = true, cordate = true }

-- A usage error unless --organ's value is a leaf shape or an organ file (.json).
local function organ_usage (v)
  if v ~= nil and not SHAPES[v] and not v:lower():find("%.json$") then
    usage("sketch", "--organ expects a leaf shape (ovate, lanceolate, elliptic, obovate, " ..
          "linear, cordate) or an organ file (.json), got '%s'", v)
  end
end

-- --organ ORGAN: a leaf shape or an organ file (lsys.sketch.organ.load). Returns the Organ
-- (nil for a file that is not there yet, in the window: the organ drawn is saved there)
-- and the file.
local function organ_opt (v, window)
  if v == nil then return nil, nil end
  if SHAPES[v] then return require("lsys.sketch.organ").leaf { shape = v }, nil end
  if window and not isfile(v) then return nil, v end
  return require("lsys.sketch.organ").load(v), v
end

-- --nodes and --phyllotaxis of `lsys sketch` as lsys.sketch.load options.
local function sketch_load_opts (opts)
  local lo = {}
  if opts.nodes ~= nil then
    lo.nodes_per_layer = math.tointeger(tonumber(opts.nodes))
    if lo.nodes_per_layer == nil or lo.nodes_per_layer < 1 or lo.nodes_per_layer > 10000 then
      usage("sketch", "--nodes expects a whole number from 1 to 10000, got '%s'", opts.nodes)
    end
  end
  if opts.phyllotaxis ~= nil then
    local p = opts.phyllotaxis
    if p ~= "distichous" and p ~= "decussate" and p ~= "fibonacci" then
      usage("sketch", "--phyllotaxis expects distichous, decussate or fibonacci, got '%s'", p)
    end
    lo.phyllotaxis = p
  end
  return lo
end

local sketch_file_write

-- `lsys sketch plot|model|render FILE -o OUT`.
local function sketch_file_command (sub, opts, pos)
  if #pos < 2 then usage("sketch", "%s: a sketch FILE is required", sub) end
  if #pos > 2 then usage("sketch", "unexpected argument '%s'", pos[3]) end
  local file = pos[2]
  if opts.cpfg and sub ~= "model" then usage("sketch", "%s: --cpfg applies to model", sub) end
  if opts.organ and sub == "plot" then
    usage("sketch", "plot: --organ applies to the window, model and render")
  end
  organ_usage(opts.organ)
  local ext = sub == "model" and (opts.cpfg and ".l" or ".lua") or ".png"
  local outpath = opts.output or ((file:match("([^/]-)%.?[^./]*$") or "sketch") ..
                                  (sub == "plot" and "-functions" or "") .. ext)
  if not outpath:lower():find("%" .. ext .. "$") then
    usage("sketch", "%s: the output must be a %s file, got '%s'", sub, ext, outpath)
  end
  local lo = sketch_load_opts(opts)
  local w, h = size_opt("sketch", opts.size)
  if sub == "model" and w then usage("sketch", "model: --size applies to plot and render") end
  local sketch = require "lsys.sketch"
  local ok, err = pcall(function ()
    local org = organ_opt(opts.organ)
    local sk = sketch.load(file, lo)
    sketch_file_write(sub, sk, outpath, w, h, org, opts.cpfg)
  end)
  -- the pipeline's messages name the file and the stroke; where in lsys they were raised
  -- is no news to the user
  if not ok then error((tostring(err):gsub("^[^:\n]*%.lua:%d+: ", "")), 0) end
  return 0
end

-- Writes what `lsys sketch plot|model|render` makes of the Sketch sk (with the Organ org).
function sketch_file_write (sub, sk, outpath, w, h, org, cpfg)
  if sub == "plot" then
    require("lsys.sketch.plot").png(sk, outpath, { width = w or 900, height = h or 600 })
    out(format("wrote %s\n", outpath))
  elseif sub == "model" and cpfg then
    local files, inexact = sk:save_cpfg(outpath, { organ = org })
    table.sort(files)
    for _, f in ipairs(files) do out(format("wrote %s\n", f)) end
    local base = outpath:match("([^/]*)%.l$")
    out(format("cpfg -m %s.map %s.l %s.v (in %s) derives the plant as lsys does\n", base,
               base, base, outpath:match("^(.*)/") or "."))
    if inexact > 0 then
      warn(format("lsys: sketch: %d readings of the functions lie closer together than " ..
                  "cpfg tells apart (0.002 of the stem): cpfg's plant differs there", inexact))
    end
  elseif sub == "model" then
    sk:save_model(outpath, { organ = org })
    out(format("wrote %s\n", outpath))
  else
    local m = sk:model { organ = org }
    local scene = m:interpret(m:derive())
    render(scene, { out = outpath, width = w or 800, height = h or 800 })
    out(format("wrote %s (%dx%d, %d triangles, %d lines)\n", outpath, w or 800, h or 800,
      scene.ntriangles, scene.nlines))
  end
end

local function run (args)
  local sub = args[2]
  local opts, pos = parse("sketch", SKETCH_OPTS, args, 2)
  if opts.help then out(HELP.sketch) return 0 end
  if sub == "plot" or sub == "model" or sub == "render" then
    return sketch_file_command(sub, opts, pos)
  end
  if #pos > 1 then usage("sketch", "unexpected argument '%s' (one FILE at most)", pos[2]) end
  local w, h = size_opt("sketch", opts.size)
  local lo = sketch_load_opts(opts)
  if opts.output ~= nil then usage("sketch", "-o applies to plot, model and render") end
  if opts.cpfg then usage("sketch", "--cpfg applies to model") end
  organ_usage(opts.organ)
  local ok, org, ofile = pcall(organ_opt, opts.organ, true)
  if not ok then error((tostring(org):gsub("^[^:\n]*%.lua:%d+: ", "")), 0) end
  require("lsys.ui.sketch").run {
    file = pos[1], nodes = lo.nodes_per_layer, phyllotaxis = lo.phyllotaxis,
    window = w and { w, h } or nil, out = out, organ = org, organ_file = ofile,
  }
  return 0
end

return run
