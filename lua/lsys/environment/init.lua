--- Open L-systems: the environment a model's ?E modules talk to (docs/open.md; Mech and
-- Prusinkiewicz 1996, "Visual models of plants interacting with their environment", §3).
--
-- Before each derivation step, the string is interpreted (the homomorphism applied, as
-- cpfg's environmental pass does) and every ?E(x1, ..., xn) met is a query: its parameters,
-- the turtle's position, heading, left and up vectors, width and scale there, and the module
-- that follows it. The environment answers each query with numbers that replace the ?E's
-- parameters in the string, and the step's rules then see them. The final string gets no
-- pass: its ?E keep what the rules gave them, as in cpfg.
--
-- `info` holds step, model, lstring (the string asked about) and scene: the plant as the
-- turtle draws that string, made when an environment first reads it (a light environment's
-- occluders) and closed after the pass.
--
-- The model option `environment` is a function `(queries, info) -> answers`, an object with
-- a method `answer(self, queries, info)` (what the built-in environments are), or a list of
-- those: then the first parameter of each ?E is the number of its environment (from 1), as
-- vlab's `multiple` program routes them, and the environment sees and answers the others.
-- `false` says the model has none on purpose: its ?E keep their values, without a warning.
-- @module lsys.environment
local warning = require "lsys.warning"
local program = require "lsys.environment.program"
local collision = require "lsys.environment.collision"
local light = require "lsys.environment.light"
local shadow = require "lsys.environment.shadow"
local vigour = require "lsys.environment.vigour"
local space = require "lsys.environment.space"
local colonize = require "lsys.environment.colonize"
local resource = require "lsys.environment.resource"

local type, ipairs, pairs, error, pcall, tostring, getmetatable, setmetatable, rawset =
      type, ipairs, pairs, error, pcall, tostring, getmetatable, setmetatable, rawset
local math, string, table = math, string, table
local format, pack, unpack = string.format, string.pack, string.unpack
local _ENV = nil

local M = {}

-- The environments of the option `environment` (one, or a list), each once.
local single
local function each (env)
  if env == nil or env == false then return {} end
  if single(env) then return { env } end
  return env
end

-- Calls the method `name` of every environment of `env` that has one.
local function call (env, name, info)
  for _, e in ipairs(each(env)) do
    if type(e) ~= "function" then
      local ok, f = pcall(function () return e[name] end)
      if ok and type(f) == "function" then f(e, info) end
    end
  end
end

--- The environments of `model` around a derivation: their `start(self, info)` methods
-- now, their `finish(self, info)` methods when the value returned is closed (a
-- to-be-closed variable of derive: however the derivation ends). An environmental program
-- starts and ends so, afresh for each derivation, as cpfg restarts it on every rewind.
function M.session (model)
  local env = model.environment
  if not env then return nil end
  local ok, err = pcall(call, env, "start", { model = model })
  if not ok then error(format("%s: environment: %s", model._where, tostring(err)), 0) end
  return setmetatable({}, { __close = function () call(env, "finish", { model = model }) end })
end

-- Is `e` one environment: a function, or an object with an `answer` method?
function single (e)
  if type(e) == "function" then return true end
  if type(e) ~= "table" and type(e) ~= "userdata" then return false end
  local ok, f = pcall(function () return e.answer end)
  return ok and type(f) == "function"
end

--- Checks the model option `environment`: nil, or the message saying what is wrong.
function M.check (e)
  if e == false or single(e) then return nil end      -- false: none, said on purpose
  if type(e) == "table" and getmetatable(e) == nil and e[1] ~= nil then
    local n = 0
    for k in pairs(e) do
      n = n + 1
      if type(k) ~= "number" or not single(e[k]) then
        return format("option 'environment': entry %s of the list is not an environment "
          .. "(a function, or an object with an answer method)", tostring(k))
      end
    end
    if n ~= #e then return "option 'environment': the list has holes" end
    return nil
  end
  return format("option 'environment' must be a function (queries, info) -> answers, an "
    .. "object with an answer method, or a list of those (got %s)", type(e))
end

-- Asks one environment; returns its answers (a table, or nil for none).
local function ask (e, queries, info, label)
  local ok, answers
  if type(e) == "function" then ok, answers = pcall(e, queries, info)
  else ok, answers = pcall(e.answer, e, queries, info) end
  if not ok then error(format("%s: %s", label, tostring(answers)), 0) end
  if answers ~= nil and type(answers) ~= "table" then
    error(format("%s: the answers must be a table (a list, one entry a query), got %s", label,
                 type(answers)), 0)
  end
  return answers
end

-- The list `queries` routed by their first parameter to the environments of the list
-- `envs`; returns the answers for `queries` (first answers nil: the number stays).
local function routed (envs, queries, info, label)
  local parts = {}
  for i, q in ipairs(queries) do
    local k = q.params[1]
    local e = math.type(k) and envs[math.tointeger(k)]
    if k == nil or e == nil then
      error(format("%s: ?E module %s: its first parameter must be the number of one of the "
        .. "%d environments, got %s", label, q.index or "(made by the homomorphism)", #envs,
        tostring(k)), 0)
    end
    local sub = {}
    for f, v in pairs(q) do sub[f] = v end
    sub.params = { table.unpack(q.params, 2) }
    local p = parts[e]
    if p == nil then p = { queries = {}, at = {} }; parts[e] = p end
    p.queries[#p.queries + 1] = sub
    p.at[#p.at + 1] = i
  end
  local answers = {}
  for n, e in ipairs(envs) do
    local p = parts[e]
    if p ~= nil then
      parts[e] = nil                      -- one environment listed twice is asked once
      local a = ask(e, p.queries, info, format("%s %d", label, n)) or {}
      for j, i in ipairs(p.at) do
        local x = a[j]
        if type(x) == "number" then x = { x } end
        if type(x) == "table" then
          local shifted = { n = (x.n or #x) + 1 }
          for f = 1, shifted.n - 1 do shifted[f + 1] = x[f] end
          answers[i] = shifted
        elseif x ~= nil and x ~= false then
          answers[i] = x                    -- reported by apply
        end
      end
    end
  end
  return answers
end

local function float32 (x) return (unpack("f", pack("f", x))) end

-- Writes the answers into the ?E modules of `s` they answer; returns how many answers had
-- more values than their ?E has parameters (those values are dropped).
local function apply (s, queries, answers, round, label)
  local over = nil
  for i, q in ipairs(queries) do
    local a = answers[i]
    if type(a) == "number" then a = { a } end
    if a ~= nil and a ~= false then
      if type(a) ~= "table" then
        error(format("%s: answer %d must be a number or a list of numbers, got %s", label, i,
                     type(a)), 0)
      end
      if q.index ~= nil then         -- one the homomorphism made has nowhere to go (cpfg)
        local p, n = q.params, a.n or #a
        for k = 1, n do
          local x = a[k]
          if x ~= nil and x ~= false then
            if type(x) ~= "number" or x ~= x or x == math.huge or x == -math.huge then
              error(format("%s: answer %d, value %d: a finite number expected, got %s", label,
                           i, k, tostring(x)), 0)
            end
            if k <= #p then p[k] = round and float32(x) or x
            elseif over == nil then over = { i = q.index, n = n, np = #p } end
          end
        end
        if #p > 0 then s:set(q.index, table.unpack(p)) end
      end
    end
  end
  return over
end

--- The environmental pass over `s` for `model` before derivation step `step` (the index
-- of the string, from 0; nil for a lone model:step): fills ?P ?H ?U ?L as the query pass
-- does, asks the environment and writes its answers. `interpret` runs core.environment
-- as the model runs its core calls. Returns the number of queries.
function M.pass (model, s, step, interpret)
  local env = model.environment
  local queries = interpret()
  if #queries == 0 then return 0 end
  -- info.scene: the plant as the turtle draws string `s` (model:interpret), made when an
  -- environment first reads it and closed after the pass (the light's occluders)
  local scene
  local info = setmetatable({ step = step, model = model, lstring = s }, {
    __index = function (t, k)
      if k ~= "scene" then return nil end
      scene = model:interpret(s)
      rawset(t, "scene", scene)
      return scene
    end })
  local label = format("%s: environment", model._where)
  local answers
  local ok, err = pcall(function ()
    if single(env) then answers = ask(env, queries, info, label) or {}
    else answers = routed(env, queries, info, label) end
  end)
  if scene then local _ <close> = scene end          -- the scene's memory goes now
  if not ok then error(err, 0) end
  local over = apply(s, queries, answers, model.numbers == "float32", label)
  if over ~= nil and not model._warnedover then       -- once a model, not at every step
    model._warnedover = true
    warning.warn(format("lsys: %s: the environment gave %d values for the ?E of %d "
      .. "parameter%s at module %d: the rest are dropped (at step %s)", model._where, over.n,
      over.np, over.np == 1 and "" or "s", over.i, tostring(step)))
  end
  return #queries
end

--- An environmental program of cpfg's (vlab's ENVIRO), from its communication file
-- (lsys.environment.program).
M.program = program.program

--- Which queries another reaches (Honda 1981's test, as vlab's honda81 answers it;
-- lsys.environment.collision).
M.collision = collision.collision

--- The light reaching each query from a sky, through the plant's own geometry
-- (lsys.environment.light).
M.light = light.light

--- The light reaching each query estimated by the shadow-propagation grid of Palubicki et
-- al. 2009 (lsys.environment.shadow).
M.shadow = shadow.shadow

--- A tree's vigour shared out among its buds by the Borchert-Honda model, from the light
-- they sense (lsys.environment.vigour).
M.vigour = vigour.vigour

--- What is within a radius of each query: how many, their density, the nearest, whether
-- none (lsys.environment.space).
M.space = space.space

--- Space colonisation: buds compete for markers and grow towards those they win
-- (lsys.environment.colonize).
M.colonize = colonize.colonize

--- Soil water or a nutrient that diffuses in a grid between passes, fed by sources and taken
-- by the plant (lsys.environment.resource).
M.resource = resource.resource

return M
