--- Model files, loaded one way by the commands of the program and by lsys.batch: the file
-- run, a failure naming it, a model picked from a table of named models, a component
-- graph's prototype made a Model. Whatever takes a model or a component graph's root
-- prototype (lsys.render, lsys.frames, the viewer, lsys.batch, the commands) tells and
-- converts a prototype here: isproto, tomodel.
-- @module lsys.load
local model = require "lsys.model"
local strip_internal = require("lsys.util.errors").strip_internal

local type, pairs, tostring, error, pcall, require, loadfile, package =
      type, pairs, tostring, error, pcall, require, loadfile, package
local string, table = string, table
local format = string.format
local _ENV = nil

local M = {}

--- Whether `v` is a model: a table or userdata whose `derive` is a function (read in
-- protected mode, so that a table whose __index raises is simply not one).
function M.ismodel (v)
  if type(v) ~= "table" and type(v) ~= "userdata" then return false end
  local ok, derive = pcall(function () return v.derive end)
  return ok and type(derive) == "function"
end

--- Whether `v` is a component graph's prototype (lsys.components). There is none before
-- lsys.components.proto is loaded, and this does not load it: a script without component
-- graphs never does.
function M.isproto (v)
  local proto = type(v) == "table" and package.loaded["lsys.components.proto"]
  return type(proto) == "table" and proto.isproto(v)
end

--- `v` as a Model: a component graph's prototype made one by lsys.components.model (`opts`,
-- its options: seed, detail, ...); anything else as it is. Raises lsys.components.model's
-- errors.
function M.tomodel (v, opts)
  if not M.isproto(v) then return v end
  return require("lsys.components").model(v, opts)
end

local function either (v) return M.ismodel(v) or M.isproto(v) end

--[[
Runs the model file `path` and returns what it returns: the file loaded as text and run
with no arguments in the global environment, through lsys.model.runfile, which names a
model the file makes without a name after the file. A failure is raised
with the file's name in front when the message does not hold it. opts (optional):
`chunks`, a table that keeps each file's chunk (or the message of its load) by its path,
for a caller that runs one file many times; `strip`, lsys's own positions taken out of the
message (lsys.batch records its messages; the program's error handler strips those of the
commands, but for LSYS_DEBUG).
]]
function M.run (path, opts)
  local chunks = opts and opts.chunks
  local chunk = chunks and chunks[path]
  if chunk == nil then
    local c, err = loadfile(path, "t")
    chunk = c or err
    if chunks then chunks[path] = chunk end
  end
  if type(chunk) ~= "function" then error(chunk, 0) end
  local ok, v = model.runfile(path, chunk)
  if not ok then
    local msg = opts and opts.strip and strip_internal(v) or tostring(v)
    error(msg:find(path, 1, true) and msg or path .. ": " .. msg, 0)
  end
  return v
end

--[[
The model in `v`, what the model file `path` returned, and its name: `v` itself when it is
a model or a prototype (`name` must then be nil), or the entry `name` of a table of named
models (nil: the first name in sorted order). opts (optional): `scene`, a Scene (a
population) taken as it is (the commands render and export take one); `single`, what the
message for a name given with a single model says after its ';' (default: the program's
option). Raises naming the file.
]]
function M.pick (v, path, name, opts)
  if either(v) then
    if name ~= nil then
      error(format("%s returns a single model; %s", path,
        opts and opts.single or "--name applies to a table of models"), 0)
    end
    return v
  end
  if opts and opts.scene and model.isscene(v) then return v end
  local names = {}
  if type(v) == "table" then
    for k, x in pairs(v) do
      if type(k) == "string" and either(x) then names[#names + 1] = k end
    end
    table.sort(names)
  end
  if #names == 0 then
    error(format("%s returned %s, not a model (end the file with `return lsys.lsystem "
      .. "{ ... }`, a component graph's root prototype, or a table of models)", path,
      type(v)), 0)
  end
  name = name or names[1]
  if not either(v[name]) then
    error(format("%s has no model named '%s' (models: %s)", path, name,
      table.concat(names, ", ")), 0)
  end
  return v[name], name
end

--[[
`v` as a Model: a component graph's prototype (of the file `path`) made one by M.tomodel,
expanded with `seed`; anything else as it is. A failure is raised
naming the file: its message without its first position (the component module's line),
the file's name in front when the message does not hold it; with opts.strip (as lsys.batch
records it), without lsys's own positions and the file's name always in front.
]]
function M.expand (v, path, seed, opts)
  if not M.isproto(v) then return v end
  local ok, m = pcall(M.tomodel, v, { seed = seed })
  if ok then return m end
  if opts and opts.strip then error(format("%s: %s", path, strip_internal(m)), 0) end
  local msg = tostring(m):gsub("^[^:\n]*%.lua:%d+: ", "")
  error(msg:find(path, 1, true) and msg or path .. ": " .. msg, 0)
end

--- Runs the model file `path` and returns its model (M.pick, a Scene as it is) made a Model
-- (M.expand with `seed`), and its name when the file returns a table of named models.
function M.model (path, name, seed)
  local v, n = M.pick(M.run(path), path, name, { scene = true })
  return M.expand(v, path, seed), n
end

--- The names of the variables of the env `env` (a model's; nil: none), sorted: what a
-- message about a variable the model has not lists.
function M.variables (env, cpfg)
  local names = {}
  for k in pairs(env or {}) do
    if type(k) == "string" and not M.hidden(k, cpfg) then names[#names + 1] = k end
  end
  table.sort(names)
  return names
end

--- Whether env name `k` of a model read from a cpfg file (`cpfg` true) is one of the
-- translator's (its helpers `_aget`, `_try` ..., the derivation length's Q and Z;
-- lsys.cpfg.translate): not the model's variable, not to be set from outside.
function M.hidden (k, cpfg)
  return cpfg and type(k) == "string" and (k:sub(1, 1) == "_" or k == "Q" or k == "Z") or false
end

return M
