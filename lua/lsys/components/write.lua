--- A component graph written as a Lua model file: the prototypes, their parameters and
-- links, and the model's options, as a script that lsys.load, `lsys render` and
-- `lsys view` take and that gives the same scene (lsys.ui.graph saves its edits with it).
--
--   write.save(root, path [, opts]) -> path      opts: seed, view, detail, name
--   write.tofunc(p, key) -> lsys.Func | nil, why  a range or function as a curve
-- @module lsys.components.write
local core = require "lsys.core"
local proto = require "lsys.components.proto"
local G = require "lsys.components.graph"
local X = require "lsys.components.expand"
local lfunc = require "lsys.func"
local codegen = require "lsys.codegen"

local type, pairs, ipairs, error, tostring, pcall = type, pairs, ipairs, error, tostring, pcall
local math, string, table = math, string, table
local format, concat, sort = string.format, table.concat, table.sort
local _ENV = nil

local M = {}

-- {=========================================================================================
-- Ranges and functions as curves

-- A function of ctx (or a range's f) sampled at K points of the position u, as the control
-- points of an lsys.Func: the curve editor's picture of it, and what M.save writes.
local SAMPLES = 7
M.SAMPLES = SAMPLES

local function sampled (p, key, v)
  local gen = X.generator(1)
  local pts = {}
  for k = 0, SAMPLES - 1 do
    local u = k / (SAMPLES - 1)
    local ctx = { i = k + 1, n = SAMPLES, depth = 1, random = gen, u = u }
    local ok, y
    if type(v) == "function" then ok, y = pcall(v, ctx)
    else
      local x = v[1] + u * (v[2] - v[1])
      ctx.v = x
      ok, y = pcall(v.f, x, ctx)
    end
    if not ok or not proto.isnum(y) then
      return nil, format("%s: '%s': its function %s", proto.who(p), key,
                         ok and "gave " .. tostring(y) .. ", not a finite number"
                            or "failed: " .. tostring(y))
    end
    pts[k + 1] = { u, y }
  end
  return lfunc.new { points = pts, name = key }
end

--- The range or function of a number parameter as an lsys.Func of the position u (from 0
-- at the first instance to 1 at the last): a range {v0, v1} exactly (four control points
-- on its line); a function (or a range's function) through its values at M.SAMPLES
-- positions, which the B-spline approximates. nil and why for anything else.
function M.tofunc (p, key)
  local v = p:param(key)
  if proto.isfunc(v) then return v end
  if type(v) == "function" or type(v) == "table" and v.f ~= nil then
    return sampled(p, key, v)
  end
  if type(v) == "table" and #v == 2 and type(v[1]) == "number" then
    local pts = {}
    for k = 0, 3 do pts[k + 1] = { k / 3, v[1] + k / 3 * (v[2] - v[1]) } end
    return lfunc.new { points = pts, name = key }
  end
  return nil, format("%s: '%s' is not a range", proto.who(p), key)
end

-- }=========================================================================================

-- {=========================================================================================
-- Writing the graph as a Lua model file

-- Lua source of a plain value (numbers, strings, booleans, lists and records of them,
-- lsys.Func); nil and what cannot be written (its place in `where`).
local function lua (v, where)
  local t = type(v)
  if t == "number" then
    if v ~= v or v == math.huge or v == -math.huge then return nil, where .. " (not finite)" end
    if math.type(v) == "integer" then return format("%d", v) end
    return format("%.17g", v)
  elseif t == "string" then return codegen.string(v)
  elseif t == "boolean" then return tostring(v)
  elseif proto.isfunc(v) then
    local pts = {}
    for i, q in ipairs(v:points()) do pts[i] = format("{ %.17g, %.17g }", q[1], q[2]) end
    return format("lsys.func.new { points = { %s }, name = %s, samples = %d, approx = %s }",
                  concat(pts, ", "), codegen.string(v:name()), v:samples(),
                  codegen.string(v:approx()))
  elseif t == "table" then
    local parts, keys = {}, {}
    local n = #v
    for i = 1, n do
      local s, err = lua(v[i], where .. "[" .. i .. "]")
      if not s then return nil, err end
      parts[#parts + 1] = s
    end
    for k in pairs(v) do
      if not (math.type(k) == "integer" and k >= 1 and k <= n) then keys[#keys + 1] = k end
    end
    sort(keys, function (a, b) return tostring(a) < tostring(b) end)
    for _, k in ipairs(keys) do
      if type(k) ~= "string" and type(k) ~= "number" then return nil, where end
      local s, err = lua(v[k], where .. "." .. tostring(k))
      if not s then return nil, err end
      parts[#parts + 1] = codegen.key(k) .. " = " .. s
    end
    return "{ " .. concat(parts, ", ") .. " }"
  end
  return nil, where .. " (a " .. t .. ")"
end

local function savefail (fmt, ...)
  error(format("lsys.components.write.save: " .. fmt, ...), 3)
end

--- Writes the p-graph from `root` to `path` as a Lua model file that lsys.load and
-- `lsys render` take: one constructor per prototype, its links, and
-- `return C.model(root, { seed, view, detail, name })` (opts as lsys.components.model; a
-- view of plain values). A Lua function in a number parameter cannot be written: it is
-- written as the lsys.Func through its values at M.SAMPLES positions (M.tofunc), and a
-- comment in the file says so; any other function or object (an FFD's fx, a World's
-- field, a `geometry` model) is an error naming the component and the parameter. The
-- file is replaced atomically. Returns path.
function M.save (root, path, opts)
  if not proto.isproto(root) then savefail("a component prototype expected, got %s", type(root)) end
  if type(path) ~= "string" or path == "" then savefail("a file name expected") end
  opts = opts or {}
  local nodes = G.nodes(root)
  local var = {}
  for i, n in ipairs(nodes) do var[n.p] = format("c[%d]", i) end
  local out = {
    "-- A component graph written by lsys.components.write (the component-graph pane's save): one",
    "-- prototype per line, then the links in their order.",
    'local lsys = require "lsys"',
    "local C = lsys.components",
    "local c = {}",
  }
  local notes = {}
  for _, n in ipairs(nodes) do
    local p = n.p
    local keys = {}
    for k in pairs(p.params) do keys[#keys + 1] = k end
    sort(keys)
    local parts = {}
    if p.name then parts[1] = "name = " .. codegen.string(p.name) end
    for _, k in ipairs(keys) do
      local v = p.params[k]
      local sch = proto.schema(p.kind, k)
      local where = format("%s: '%s'", proto.who(p), k)
      if sch[1] == "number" and (type(v) == "function" or type(v) == "table" and v.f) then
        local f, err = M.tofunc(p, k)
        if not f then savefail("%s", err) end
        notes[#notes + 1] = codegen.comment(format("%s was a Lua function: written as the " ..
                                                   "curve through its values at %d positions",
                                                   where, SAMPLES))
        v = f
      end
      local s, err = lua(v, where)
      if not s then
        savefail("%s cannot be written to a file (%s): give it a value, a range or an " ..
                 "lsys.Func", where, err)
      end
      parts[#parts + 1] = codegen.key(k) .. " = " .. s
    end
    if p.recursive then parts[#parts + 1] = "recursion = " .. p.recursion end
    out[#out + 1] = format("%s = C.%s { %s }", var[n.p], p.kind, concat(parts, ", "))
  end
  for _, n in ipairs(nodes) do
    for _, l in ipairs(n.p.links) do
      local flags = ""
      if l.flags then
        local s = lua(l.flags.list, "flags")
        flags = format(", { %s = %s }", l.flags.mode, s)
      end
      out[#out + 1] = format("%s:%s(%s%s)", var[n.p], l.type, var[l.to], flags)
    end
  end
  local mo = {}
  for _, k in ipairs { "seed", "detail", "name" } do
    if opts[k] ~= nil then
      local s, err = lua(opts[k], k)
      if not s then savefail("option %s cannot be written", err) end
      mo[#mo + 1] = k .. " = " .. s
    end
  end
  if opts.view ~= nil then
    local s, err = lua(opts.view, "view")
    if not s then savefail("the view's %s cannot be written", err) end
    mo[#mo + 1] = "view = " .. s
  end
  for _, l in ipairs(notes) do out[#out + 1] = l end
  out[#out + 1] = format("return C.model(c[1], { %s })", concat(mo, ", "))
  local ok, err = pcall(core.write_file, path, concat(out, "\n") .. "\n")
  if not ok then savefail("%s", tostring(err)) end
  return path
end

-- }=========================================================================================

return M
