--- `lsys components graph`: the p-graph of a component graph, drawn by Graphviz or written
-- as DOT text.
-- @module lsys.cli.commands.components
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help

local type, tostring, error, pcall, require = type, tostring, error, pcall, require
local string = string
local format = string.format
local parse, out, usage = A.parse, A.out, A.usage
local find_model = S.find_model
local run_file = require("lsys.load").run
local _ENV = nil

local COMPONENTS_OPTS = { output = "value", params = "flag", help = "flag",
                          short = { h = "help", o = "output" } }

-- `lsys components graph MODEL -o OUT`: the model file returns a component graph's root.
local function run (args)
  local sub = args[2]
  local opts, pos = parse("components", COMPONENTS_OPTS, args, 2)
  if opts.help then out(HELP.components) return 0 end
  if sub ~= "graph" then
    usage("components", sub == nil and "a subcommand is required (graph)" or
      "unknown subcommand '%s' (known: graph)", sub)
  end
  if #pos < 2 then usage("components", "graph: a MODEL is required") end
  if #pos > 2 then usage("components", "unexpected argument '%s'", pos[3]) end
  local outpath = opts.output or ((pos[2]:match("([^/]-)%.?[^./]*$") or "model") .. "-graph.png")
  local ext = (outpath:match("%.([^./]+)$") or ""):lower()
  if ext ~= "png" and ext ~= "svg" and ext ~= "pdf" and ext ~= "dot" and ext ~= "gv" then
    usage("components", "graph: the output must be a .png, .svg, .pdf or .dot file, got '%s'",
      outpath)
  end
  local path = find_model(pos[2])
  local root = run_file(path)
  local okp, kind, links = pcall(function () return root.kind, root.links end)
  if not okp or type(kind) ~= "string" or type(links) ~= "table" then
    error(format("%s returned %s, not a component graph (end the file with `return` and the "
      .. "root prototype, e.g. `return plant`)", path, type(root)), 0)
  end
  local graph = require "lsys.components.graph"
  local rok, rerr = pcall(graph.render, root, outpath, { params = opts.params or nil })
  if not rok then     -- the message names the item; graph.lua's line is no news to the user
    rerr = tostring(rerr):gsub("^[^:\n]*%.lua:%d+: ", ""):gsub("^graph%.render: ", "")
    error(format("%s: %s", path, rerr), 0)
  end
  out(format("wrote %s\n", outpath))
  return 0
end

return run
