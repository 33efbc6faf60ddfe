--- A stand: several open L-systems growing together in one environment, so that each plant
-- senses the others (their shade, their space) as well as itself (docs/open.md §2).
--
-- `lsys.stand(plants, opts)` derives every plant step by step in lockstep:
-- before each step, the ?E queries of all the plants go to the one environment
-- `opts.environment` together, in world coordinates (each plant placed by its at, rotate
-- and scale, as lsys.population places it), with `info.scene` the whole stand as drawn
-- then (every plant placed: those waiting at a pass as they stand there, those done growing
-- from their final strings), and `info.lstrings[i]` plant i's string asked about (for
-- environments that read a plant's structure: lsys.environment.vigour); the answers go back
-- to each plant. Positions and directions are in the world's frame, the answers too. A plant
-- is { model = (a Model of its own: two plants may not share one), at =, rotate =, scale =,
-- steps = (its model's steps) }. Returns the stand as a population Scene (each plant drawn
-- from its final string; opts.view as lsys.population's) and the list of final Lstrings.
--
-- Each plant runs its own derivation in a coroutine; its model's environment is, meanwhile,
-- a stand-in that hands the plant's queries to the stand and waits for the answers. A plant
-- whose string holds no ?E at a step goes on to its next pass (it is shown to the others as
-- it stands there).
-- @module lsys.stand
local model = require "lsys.model"
local population = require "lsys.population"

local type, ipairs, pairs, error, pcall, tostring, setmetatable, rawset, next, math =
      type, ipairs, pairs, error, pcall, tostring, setmetatable, rawset, next, math
local coroutine, string = coroutine, string
local format = string.format
local _ENV = nil

local M = {}

-- v (3 numbers) by the matrix of transform x (columns), plus its translation when `point`.
local function apply (x, v, point)
  local out = {}
  for i = 1, 3 do
    local s = x[i] * v[1] + x[3 + i] * v[2] + x[6 + i] * v[3]
    out[i] = point and s + x[9 + i] or s
  end
  if not point then                         -- a direction: unit again
    local n = math.sqrt(out[1] ^ 2 + out[2] ^ 2 + out[3] ^ 2)
    if n > 0 then for i = 1, 3 do out[i] = out[i] / n end end
  end
  return out
end

-- Query q of a plant placed by x, in world coordinates (a copy).
local function world (q, x, plant)
  local w = {}
  for k, v in pairs(q) do w[k] = v end
  w.position = apply(x, q.position, true)
  w.heading, w.left, w.up = apply(x, q.heading), apply(x, q.left), apply(x, q.up)
  w.plant = plant
  return w
end

-- Calls method `name` of environment e when it has one.
local function call (e, name, info)
  if type(e) ~= "function" then
    local ok, f = pcall(function () return e[name] end)
    if ok and type(f) == "function" then f(e, info) end
  end
end

local function ask (e, queries, info)
  local ok, a
  if type(e) == "function" then ok, a = pcall(e, queries, info)
  else ok, a = pcall(e.answer, e, queries, info) end
  if not ok then error(format("lsys.stand: environment: %s", tostring(a)), 0) end
  return a or {}
end

local function check (plants, opts)
  if type(plants) ~= "table" or #plants == 0 then
    error("lsys.stand: a list of plants expected", 3)
  end
  if type(opts) ~= "table" or opts.environment == nil then
    error("lsys.stand: opts.environment (the stand's environment) expected", 3)
  end
  local seen, xf = {}, {}
  for i, p in ipairs(plants) do
    if type(p) ~= "table" or not model.ismodel(p.model) then
      error(format("lsys.stand: plant %d: 'model' must be a Model", i), 3)
    end
    if seen[p.model] then
      error(format("lsys.stand: plant %d: its model is plant %d's (each plant of "
                   .. "a stand grows a model of its own)", i, seen[p.model]), 3)
    end
    seen[p.model] = i
    local ok, x = pcall(population.transform, p, format("plant %d", i))
    if not ok then error("lsys.stand: " .. tostring(x), 3) end
    xf[i] = x
  end
  return xf
end

--- Grows the plants together (see the module's header); returns the Scene and the strings.
function M.stand (plants, opts)
  local xf = check(plants, opts)
  local env = opts.environment
  local cos, saved, results, parked, answers = {}, {}, {}, {}, {}
  local function restore ()
    for i, p in ipairs(plants) do p.model.environment = saved[i] end
  end
  for i, p in ipairs(plants) do
    local m = p.model
    saved[i] = m.environment
    m.environment = { answer = function (_, qs, info)
      -- the scene: open until answered
      return coroutine.yield(qs, info.step, info.scene, info.lstring)
    end }
    cos[i] = coroutine.create(function () return m:derive(p.steps) end)
  end
  local ok, err = pcall(function ()
    call(env, "start", { plants = #plants })
    local left = #plants
    while left > 0 do
      for i = 1, #plants do                      -- each plant on to its next pass or its end
        if results[i] == nil and parked[i] == nil then
          local rok, a, step, scene, s = coroutine.resume(cos[i], answers[i])
          answers[i] = nil
          if not rok then error(format("plant %d: %s", i, tostring(a)), 0) end
          if coroutine.status(cos[i]) == "dead" then
            results[i], left = a, left - 1
          else
            parked[i] = { queries = a, step = step, scene = scene, lstring = s }
          end
        end
      end
      if next(parked) == nil then break end
      local k = math.huge                        -- the earliest pass waiting is answered
      for _, w in pairs(parked) do k = math.min(k, w.step or 0) end
      local all, who, entries, lstrings = {}, {}, {}, {}
      for i = 1, #plants do
        local w, p = parked[i], plants[i]
        if w then
          entries[#entries + 1] = { model = w.scene, at = p.at, rotate = p.rotate,
                                    scale = p.scale }
          lstrings[i] = w.lstring
        elseif results[i] ~= nil then            -- a plant done growing still stands there
          entries[#entries + 1] = { model = p.model, lstring = results[i], at = p.at,
                                    rotate = p.rotate, scale = p.scale }
        end
        if w and (w.step or 0) == k then
          for j, q in ipairs(w.queries) do
            all[#all + 1] = world(q, xf[i], i)
            who[#all] = { i, j }
          end
        end
      end
      local made
      local info = setmetatable({ step = k, plants = #plants, lstrings = lstrings },
                                { __index = function (t, key)
        if key ~= "scene" then return nil end
        made = population.population(entries, { records = false })
        rawset(t, "scene", made)
        return made
      end })
      local aok, a = pcall(ask, env, all, info)
      if made then local _ <close> = made end
      if not aok then error(a, 0) end
      for n, w in ipairs(who) do
        local i, j = w[1], w[2]
        answers[i] = answers[i] or {}
        answers[i][j] = a[n]
      end
      for i, w in pairs(parked) do
        if (w.step or 0) == k then
          answers[i] = answers[i] or {}
          parked[i] = nil
        end
      end
    end
    call(env, "finish", { plants = #plants })
  end)
  restore()
  if not ok then error("lsys.stand: " .. tostring(err), 2) end
  local entries = {}
  for i, p in ipairs(plants) do
    entries[i] = { model = p.model, lstring = results[i], at = p.at, rotate = p.rotate,
                   scale = p.scale }
  end
  local pok, scene = pcall(population.population, entries, { view = opts.view })
  if not pok then error(tostring(scene), 2) end
  return scene, results
end

return M
