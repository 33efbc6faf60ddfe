--- The model files of sketched plants: a description (what lsys.sketch makes a Model of:
-- a single sketch's, sk:model, or a composition's, lsys.sketch.compose) written as a Lua
-- model file that builds the same Model, and the organ surfaces it draws written beside
-- it. docs/sketch.md, "Models from sketches". The cpfg files are lsys.sketch.cpfg's.
-- @module lsys.sketch.write
local core = require "lsys.core"
local codegen = require "lsys.codegen"
local functions = require "lsys.sketch.functions"
local num = require("lsys.util.text").number

local type, pairs, ipairs, error, pcall, tostring, getmetatable, rawget, string, table, math =
      type, pairs, ipairs, error, pcall, tostring, getmetatable, rawget, string, table, math
local format, concat = string.format, table.concat
local quote = codegen.string
local _ENV = nil

local M = {}

-- What a written model file may reach when it loads (codegen.check).
local CHECK = { modules = { lsys = true, ["lsys.func"] = true }, globals = { pairs = pairs },
                calls = { ["lsys.lsystem"] = true, ["lsys.here"] = true,
                          ["lsys.func.new"] = true } }

local function sorted (t, keep)
  local out = {}
  for k, v in pairs(t) do if keep == nil or keep(v) then out[#out + 1] = k end end
  table.sort(out)
  return out
end
M.sorted = sorted

--- The organ surfaces of description `d` as cpfg surface files beside `path`: plant.lua
-- (or plant.l) gives plant.organ.s for surface P, plant.organ.Q.s for Q, ... Returns
-- { letter = { name = file name (no folder), path =, text = } }, nothing written yet. Only
-- organs of lsys.sketch.organ keep their source; an lsys.Surface is refused. `who`
-- begins the messages.
function M.surfaces (d, path, who)
  local out = {}
  local dir, base = path:match("^(.-)([^/]*)$")
  base = base:gsub("%.[^.]*$", "")
  for _, x in ipairs(sorted(d.surfaces or {})) do
    local org = d.surfaces[x]
    local mt = getmetatable(org)
    if type(org) ~= "table" or type(mt) ~= "table" or rawget(mt, "__name") ~= "lsys.Organ" then
      error(format("%s: an lsys.Surface organ cannot be written (it keeps no source); " ..
                   "give an organ of lsys.sketch.organ", who), 0)
    end
    local ok, text = pcall(org.text, org)
    if not ok then error(format("%s: organ: %s", who, tostring(text)), 0) end
    local name = base .. (x == "P" and ".organ.s" or ".organ." .. x .. ".s")
    out[x] = { name = name, path = dir .. name, text = text }
  end
  return out
end

--- Writes the files `files` ({ {path, text}, ... }), each atomically (a temporary beside
-- it, then a rename), in order. Raises "who: ..." at the first that fails.
function M.files (files, who)
  for _, f in ipairs(files) do
    local ok, err = pcall(core.write_file, f[1], f[2])
    if not ok then error(format("%s: %s", who, tostring(err)), 0) end
  end
end

-- The first lines of a written file, as plain text: where the plant comes from (the
-- sketches' file names are text from elsewhere: each writer escapes them for its comments).
function M.header (d)
  local L = {}
  for k, p in ipairs(d.plants) do
    local from = format("the sketch %s", p.file or "(a table)")
    if #d.plants == 1 then
      L[#L + 1] = format("A plant from %s (lsys.sketch, after Anastacio, Prusinkiewicz and Sousa",
                         from)
      L[#L + 1] = format("2009): the positional functions of §4 and the %s template of §5.",
                         p.phyllotaxis)
    else
      if k == 1 then
        L[#L + 1] = format("%d plants drawn on one stem (lsys.sketch.compose; Anastacio, " ..
                           "Prusinkiewicz and Sousa", #d.plants)
        L[#L + 1] = "2009, §7.2), each the positional functions of §4 in a template of §5:"
      end
      L[#L + 1] = format("plant %d%s: %s, %s, %d nodes per layer%s", k,
                         p.suffix ~= "" and " (names ending in " .. p.suffix .. ")" or "",
                         from, p.phyllotaxis, p.nodes_per_layer,
                         k == 1 and "" or ", its stem moved along (f)")
    end
  end
  return L
end

--- Writes the Lua model file of description `d` to `path` (docs/sketch.md, "Models from
-- sketches"): the functions inline as control points, the constants, the rules as text,
-- and the organ surfaces beside it (M.surfaces), read from the file's own folder. The
-- file is written whole or not at all. Raises "who: ...".
function M.lua (d, path, who)
  local surfiles = M.surfaces(d, path, who)
  local L = {}
  local function w (...) L[#L + 1] = format(...) end
  for _, l in ipairs(M.header(d)) do w("%s", codegen.comment(l)) end
  w("-- Edit freely: the functions are clamped cubic B-splines of x in [0, 1] (cpfg's .func")
  w("-- form).")
  w("local lsys = require \"lsys\"")
  w("local func = require \"lsys.func\"")
  w("")
  w("-- The positional functions (§4), %d nodes per layer; each interior point is written",
    d.nodes_per_layer)
  w("-- three times so that the spline is the polyline through the points.")
  w("local F = {}")
  for _, k in ipairs(sorted(d.funcs)) do
    local pts = {}
    for _, p in ipairs(functions.controls(d.funcs[k])) do
      pts[#pts + 1] = format("{ %s, %s }", num(p[1]), num(p[2]))
    end
    w("%s = func.new { name = %s, points = {", codegen.index("F", k),
      quote((k:gsub("^o1_", ""))))
    for i = 1, #pts, 4 do
      w("  %s,", concat(pts, ", ", i, math.min(i + 3, #pts)))
    end
    w("} }")
  end
  w("")
  w("-- Constants of the template: XT stops the nodes at the top inclination line, XE the")
  w("-- stem at its tip, D is the longest straight piece of stem (stem lengths).")
  w("local env = {")
  for _, k in ipairs(sorted(d.env, function (v) return type(v) == "number" end)) do
    w("  %s = %s,", codegen.key(k), num(d.env[k]))
  end
  w("}")
  w("for k, f in pairs(F) do env[k] = f end")
  w("")
  w("return lsys.lsystem {")
  if d.options.name then w("  name = %s,", quote(d.options.name)) end
  w("  modules = %s,", quote(d.modules))
  w("  axiom = %s,", quote(d.axiom))
  w("  steps = %d,", d.steps)
  w("  env = env,")
  if #d.plants == 1 then
    w("  %s", codegen.comment(format("the %s template (Anastacio et al. 2009, §5; " ..
                                     "lsys.sketch.templates)", d.phyllotaxis)))
  else
    w("  -- the templates of the plants, one after the other (lsys.sketch.templates)")
  end
  w("  productions = {")
  for _, l in ipairs(d.productions) do w("    %s,", quote(l)) end
  w("  },")
  if d.sub then
    w("  -- the organs that are plants: sub-L-systems (§7.2)")
    w("  sub = {")
    for _, id in ipairs(sorted(d.sub)) do
      w("    [%d] = { productions = {", id)
      for _, l in ipairs(d.sub[id].productions) do w("      %s,", quote(l)) end
      w("    } },")
    end
    w("  },")
  end
  w("  -- the organ drawn at each node")
  w("  homomorphism = {")
  for _, l in ipairs(d.homomorphism) do w("    %s,", quote(l)) end
  w("  },")
  w("  view = { line_style = %s, line_width = %s, color = %s,", quote(d.view.line_style),
    num(d.view.line_width), num(d.view.color))
  local letters = sorted(surfiles)
  if #letters > 0 then
    local s = {}
    for i, x in ipairs(letters) do s[i] = format("%s = %s", x, quote(surfiles[x].name)) end
    w("    -- the organs (lsys.sketch.organ), cpfg surface files beside this one")
    w("    dir = lsys.here(), surfaces = { %s },", concat(s, ", "))
  end
  w("  },")
  w("}")
  local text = concat(L, "\n") .. "\n"
  local okc, cerr = pcall(codegen.check, text, path:match("[^/]*$"), CHECK)
  if not okc then error(who .. ": " .. cerr, 0) end
  -- everything made, then written: the organs, then the model file that names them
  local out = {}
  for _, x in ipairs(letters) do out[#out + 1] = { surfiles[x].path, surfiles[x].text } end
  out[#out + 1] = { path, text }
  M.files(out, who)
  return path
end

return M
