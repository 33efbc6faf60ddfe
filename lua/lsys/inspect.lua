--- A model as text: its rules (m:rules()) and what it was made of (m:inspect()), for the
-- REPL, which prints a model this way, and for scripts (`print(m:inspect())`).
-- It reads the model's fields and the records lsys.model keeps for each rule; it requires
-- nothing of the kernel, so lsys.model can give its methods from here.
-- @module lsys.inspect
local text = require "lsys.util.text"

local type, tostring, pairs, ipairs, getmetatable, setmetatable, next =
      type, tostring, pairs, ipairs, getmetatable, setmetatable, next
local math, string, table = math, string, table
local format = string.format
local _ENV = nil

local M = {}

local ENTRIES = 20    -- entries of a table shown before "... (N more)"

-- The rule sets in the order a derivation uses them, for sorting: groups and
-- sub-L-systems by their numbers.
local function setorder (name)
  if name == "productions" then return 0 end
  local g = name:match("^group (%d+)$")
  if g then return 1 + #g / 100 end   -- by length, then text: 2 before 10
  local s = name:match("^sub%-L%-system (%d+)$")
  if s then return 2 + #s / 100 end
  return name == "decomposition" and 3 or 4
end

-- A string as Lua writes it, on one line.
local function quote (s)
  return '"' .. s:gsub('[%c"\\]', function (c)
    local esc = { ["\n"] = "\\n", ["\t"] = "\\t", ["\r"] = "\\r", ['"'] = '\\"',
                  ["\\"] = "\\\\" }
    return esc[c] or format("\\%d", c:byte())
  end) .. '"'
end

local KEYORDER = { number = 1, string = 2 }

local function keyless (a, b)
  local ta, tb = type(a), type(b)
  if ta ~= tb then return (KEYORDER[ta] or 3) < (KEYORDER[tb] or 3) end
  if ta == "number" or ta == "string" then return a < b end
  return tostring(a) < tostring(b)
end

-- A value as an option shows it: numbers in their shortest exact text, strings quoted,
-- tables two levels deep (`{ a = 1, t = { 1, 2 } }`, deeper ones as {...}), functions and
-- userdata by their kind, never by an address.
local function value (v, depth)
  local tv = type(v)
  if tv == "number" then
    if v ~= v or v == math.huge or v == -math.huge then return tostring(v) end
    return text.number(v)
  end
  if tv == "string" then return quote(v) end
  if tv == "function" then return "function" end
  local mt = getmetatable(v)
  if tv == "userdata" then
    return type(mt) == "table" and type(mt.__name) == "string" and mt.__name or "userdata"
  end
  if tv ~= "table" then return tostring(v) end
  if type(mt) == "table" and mt.__tostring ~= nil then return tostring(v) end
  if next(v) == nil then return "{}" end
  if depth >= 2 then return "{...}" end
  local n, keys = #v, {}
  for k in pairs(v) do
    if not (math.type(k) == "integer" and k >= 1 and k <= n) then keys[#keys + 1] = k end
  end
  table.sort(keys, keyless)
  local parts, total = {}, n + #keys
  for i = 1, math.min(total, ENTRIES) do
    if i <= n then parts[i] = value(v[i], depth + 1)
    else
      local k = keys[i - n]
      local name = type(k) == "string" and k:find("^[%a_][%w_]*$") and k
        or "[" .. value(k, 2) .. "]"
      parts[i] = name .. " = " .. value(v[k], depth + 1)
    end
  end
  if total > ENTRIES then parts[#parts + 1] = format("... (%d more)", total - ENTRIES) end
  return "{ " .. table.concat(parts, ", ") .. " }"
end

-- The text of a list of rules (m:rules()): each set under its name, a rule a line after
-- its line (or entry) number in the text or list that gave it, or its file and line.
local function rules_text (list)
  local out, set = {}, nil
  for _, r in ipairs(list) do
    if r.set ~= set then
      set = r.set
      out[#out + 1] = set .. ":"
    end
    local body = r.text
    if r.fn then body = body .. " --> (a Lua function)" end
    if r.weight then body = body .. format(", weight %s", value(r.weight, 2)) end
    out[#out + 1] = format("  %-4s %s", r.where or tostring(r.line), body)
  end
  return table.concat(out, "\n")
end

local RULES = { __name = "lsys.Rule list", __tostring = rules_text }

--- The model's rules, set by set (productions, groups, sub-L-systems, decomposition,
-- homomorphism), each set's as written. Each is a table { text = the rule
-- (for a rule function: its pattern), set = "productions", "group 2", "sub-L-system 1",
-- "decomposition" or "homomorphism", line = its line in the set's text or its entry in the
-- set's list, fn = the rule function or nil, weight = its weight or nil, where = the file
-- and line it was read from (a cpfg model) or nil }. `tostring` of the list gives them a
-- line each, under the name of their set.
function M.rules (m)
  local list = {}
  for _, info in pairs(m._info) do
    list[#list + 1] = { text = info.text, set = info.set, line = info.line, fn = info.fn,
                        weight = info.weight, where = info.where, n = info.n }
  end
  table.sort(list, function (a, b)
    local oa, ob = setorder(a.set), setorder(b.set)
    if oa ~= ob then return oa < ob end
    if a.set ~= b.set then return a.set < b.set end
    return a.n < b.n
  end)
  for _, r in ipairs(list) do r.n = nil end
  return setmetatable(list, RULES)
end

-- The options shown after the axiom, steps and seed, when given (and not the default).
local SHOWN = { "homomorphism_seed", "random", "numbers", "threads", "max_modules",
                "max_memory", "max_instructions", "allow_system_calls", "environment" }
local DEFAULT = { random = "lsys", numbers = "double", allow_system_calls = false }
-- Options the model keeps only in the core, read from the table it was made from.
local GIVEN = { "modules", "ignore", "consider", "ring", "max_depth", "depth_warnings" }
local HOOKS = { "start", "start_each", "end_each", "finish", "after_interpret",
                "system_call" }

--- The model as text: its name (and where it was defined), the options it has (axiom,
-- steps, seed, then those given: env, params, view, the limits, the hooks...), then its
-- rules as m:rules() gives them. What the REPL prints for a model.
function M.text (m)
  local where = m._where
  local lines = { tostring(m) .. (m.name ~= nil and where ~= "model" and where ~= m.name
    and "  -- " .. where or "") }
  local function opt (k, v) lines[#lines + 1] = "  " .. k .. " = " .. value(v, 0) end
  opt("axiom", m.axiom)
  opt("steps", m.steps)
  opt("seed", m.seed)
  for _, k in ipairs(SHOWN) do
    if m[k] ~= nil and m[k] ~= DEFAULT[k] then opt(k, m[k]) end
  end
  local given = m._options or {}
  for _, k in ipairs(GIVEN) do
    if given[k] ~= nil then opt(k, given[k]) end
  end
  local env, declared = {}, m._params or {}
  for k, v in pairs(m.env or {}) do   -- names with a leading _ are lsys's (cpfg's helpers)
    if declared[k] == nil and not (type(k) == "string" and k:find("^_")) then env[k] = v end
  end
  if next(env) ~= nil then opt("env", env) end
  if m.params ~= nil then
    local p = {}
    for k, v in pairs(m.params) do p[k] = v end
    opt("params", p)
  end
  local v = m.view
  local gv = given.view
  if type(v) == "table" and v.dir ~= nil and m._options ~= nil
     and (type(gv) ~= "table" or gv.dir == nil) then   -- the folder lsys.lsystem adds
    v = {}
    for k, x in pairs(m.view) do
      if k ~= "dir" then v[k] = x end
    end
  end
  if type(v) ~= "table" or next(v) ~= nil then opt("view", v) end
  local hooks = {}
  for _, k in ipairs(HOOKS) do
    if m[k] ~= nil then hooks[#hooks + 1] = k end
  end
  if #hooks > 0 then lines[#lines + 1] = "  hooks: " .. table.concat(hooks, ", ") end
  local rules = M.rules(m)
  lines[#lines + 1] = #rules > 0 and tostring(rules) or "no rules"
  return table.concat(lines, "\n")
end

return M
