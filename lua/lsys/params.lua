--- A model's tunable parameters (docs/manual.md, "Tunable parameters"): the model option
-- `params` declares them with their ranges, and `m.params` reads and sets their values.
--
--   params = { R = { 1.456, min = 1, max = 2, step = 0.01, label = "contraction" },
--              leaf = { true }, shape = { "round", choices = { "round", "flat" } } }
--
-- A number has `min` and `max` (its range, both needed) and an optional `step` (the value is
-- rounded to min + k step when set); a boolean is a toggle; a string needs `choices`. Each
-- parameter is a name the rules read, as one of `env`: its value is written into the model's
-- env (a name may not be in both). `m.params.R = 1.5` checks the value (a number outside its
-- range, or not one of the choices, is an error naming the parameter) and sets it for the
-- next derivation; `m.params.R` reads it; `pairs(m.params)` walks the names in order with
-- their values; `m:param(name)` gives the declaration (kind, default, min, max, step, choices,
-- label). `m:on_param(fn)` calls fn(name, value) after each change (a window's sliders and a
-- script's reactions).
-- @module lsys.params
local type, pairs, ipairs, error, tostring, setmetatable, math =
      type, pairs, ipairs, error, tostring, setmetatable, math
local format, sort = string.format, table.sort
local _ENV = nil

local M = {}

local KEYS = { [1] = true, min = true, max = true, step = true, label = true, choices = true }

local function finite (x) return type(x) == "number" and x == x and x - x == 0 end

-- The declaration of parameter `name` from its entry `d`, checked (`fail` raises).
local function declare (name, d, fail)
  if type(name) ~= "string" or not name:match("^[%a_][%w_]*$") then
    fail(format("params: '%s' is not a name the rules can read", tostring(name)))
  end
  local function bad (msg) fail(format("params: %s: %s", name, msg)) end
  if type(d) ~= "table" then bad("a table { default, ... } expected") end
  for k in pairs(d) do
    if not KEYS[k] then bad(format("unknown field '%s'", tostring(k))) end
  end
  local v = d[1]
  local p = { name = name, default = v, label = d.label }
  if d.label ~= nil and type(d.label) ~= "string" then bad("label must be a string") end
  if type(v) == "number" then
    p.kind = "number"
    if not finite(v) then bad("the default must be a finite number") end
    if not finite(d.min) or not finite(d.max) or d.min >= d.max then
      bad("a number needs min and max, finite, min below max")
    end
    if d.step ~= nil and not (finite(d.step) and d.step > 0) then
      bad("step must be a number > 0")
    end
    if v < d.min or v > d.max then
      bad(format("the default %g is outside min %g .. max %g", v, d.min, d.max))
    end
    p.min, p.max, p.step = d.min, d.max, d.step
  elseif type(v) == "boolean" then
    p.kind = "boolean"
    if d.min or d.max or d.step or d.choices then bad("a toggle has no range or choices") end
  elseif type(v) == "string" then
    p.kind = "choice"
    local c = d.choices
    if type(c) ~= "table" or #c == 0 then bad("a string needs a list of choices") end
    local ok = false
    p.choices = {}
    for i, x in ipairs(c) do
      if type(x) ~= "string" then bad(format("choice %d is not a string", i)) end
      p.choices[i] = x
      if x == v then ok = true end
    end
    if not ok then bad(format("the default '%s' is not one of the choices", v)) end
  else
    bad("the default (the first entry) must be a number, a boolean or a string")
  end
  return p
end

-- Value v for parameter p, checked and (for a step) rounded; raises naming it.
local function checked (p, v, level)
  if p.kind == "number" then
    if not finite(v) then
      error(format("params.%s: a number expected, got %s", p.name, tostring(v)), level)
    end
    if v < p.min or v > p.max then
      error(format("params.%s: %g is outside %g .. %g", p.name, v, p.min, p.max), level)
    end
    if p.step then
      local r = p.min + math.floor((v - p.min) / p.step + 0.5) * p.step
      if r > p.max then r = p.max end
      if r ~= v then v = r end                 -- (a value on the step keeps its type)
    end
  elseif p.kind == "boolean" then
    if type(v) ~= "boolean" then
      error(format("params.%s: true or false expected, got %s", p.name, tostring(v)), level)
    end
  else
    local ok = false
    for _, c in ipairs(p.choices) do if c == v then ok = true end end
    if not ok then
      error(format("params.%s: '%s' is not one of its choices", p.name, tostring(v)), level)
    end
  end
  return v
end

--- The parameters of `spec` (the option) over the model's `env`: returns the proxy that is
-- `m.params`, the declarations by name, and the list of names in order. `fail` raises
-- naming the model.
function M.make (spec, env, fail, notify)
  local decl, names = {}, {}
  for name, d in pairs(spec) do
    decl[name] = declare(name, d, fail)
    if env[name] ~= nil then
      fail(format("params: %s is in env too: give it in one of them", tostring(name)))
    end
    names[#names + 1] = name
  end
  sort(names)
  for _, name in ipairs(names) do env[name] = decl[name].default end
  local proxy = setmetatable({}, {
    __index = function (_, k)
      if decl[k] == nil then return nil end
      return env[k]
    end,
    __newindex = function (_, k, v)
      local p = decl[k]
      if p == nil then
        error(format("params: the model has no parameter '%s'", tostring(k)), 2)
      end
      v = checked(p, v, 3)
      env[k] = v
      if notify then notify(k, v) end
    end,
    __pairs = function ()
      local i = 0
      return function ()
        i = i + 1
        local k = names[i]
        if k ~= nil then return k, env[k] end
      end
    end,
    __len = function () return #names end,
  })
  return proxy, decl, names
end


return M
