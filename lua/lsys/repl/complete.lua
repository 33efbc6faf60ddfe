--- Tab completion at the REPL (lsys.repl.complete): the words that may replace the one
-- before the cursor. Globals and keywords; fields after `.` (`lsys.vi` -> `lsys.view`,
-- `lsys.viewer`; `m.en` -> `m.env`); methods after `:` (`m:de` -> `m:derive`); any depth
-- (`lsys.view.l`). Names come from the table itself and from the tables of its
-- metatable's `__index` chain (and `__methods`, the Scene's); names starting with `_` only
-- when `_` was typed. Nothing is called but `__index` metamethods.
-- @module lsys.repl.complete
local type, pairs, pcall, getmetatable, next =
      type, pairs, pcall, getmetatable, next
local table, package = table, package
local _ENV = nil

local M = {}

local KEYWORDS = { "and", "break", "do", "else", "elseif", "end", "false", "for", "function",
                   "goto", "if", "in", "local", "nil", "not", "or", "repeat", "return", "then",
                   "true", "until", "while" }

-- Fields of userdata computed by their __index function, by metatable name.
local FIELDS = { ["lsys.Scene"] = { "ntriangles", "nvertices", "nlines", "nsegments",
                                    "nrecords", "lstring" } }

-- Fields loaded on first use by an __index function, by module name (lsys.viewer, ...).
local LAZY = { lsys = { "viewer", "sketch", "components", "grow", "cpfg" } }

local MAX_DEPTH = 8   -- __index tables followed

-- Adds to 'names' the string keys of 'v' and of its __index chain: { name = value }.
local function collect (v, names, depth)
  if depth > MAX_DEPTH then return end
  if type(v) == "table" then
    for k, x in next, v do   -- raw: no __pairs
      if type(k) == "string" and names[k] == nil then names[k] = x end
    end
  end
  for name, keys in pairs(LAZY) do
    if v == package.loaded[name] then
      for _, k in pairs(keys) do names[k] = names[k] or true end
    end
  end
  local ok, mt = pcall(getmetatable, v)
  if not ok or type(mt) ~= "table" then return end
  local fields = type(mt.__name) == "string" and FIELDS[mt.__name]
  for _, k in pairs(fields or {}) do
    if names[k] == nil then names[k] = true end
  end
  if type(mt.__methods) == "table" then collect(mt.__methods, names, depth + 1) end
  if type(mt.__index) == "table" and mt.__index ~= v then
    collect(mt.__index, names, depth + 1)
  end
end

-- The value of the chain "a.b.c" in 'env', or nil.
local function resolve (env, chain)
  local v = env
  for part in chain:gmatch("[^.]+") do
    local ok, x = pcall(function () return v[part] end)
    if not ok or x == nil then return nil end
    v = x
  end
  return v
end

-- Whether position 'stop' of 'line' is inside a quoted string (or a comment).
local function in_string (line, stop)
  local q, i = nil, 1
  while i <= stop do
    local c = line:sub(i, i)
    if q ~= nil then
      if c == "\\" then i = i + 1 elseif c == q then q = nil end
    elseif c == '"' or c == "'" then q = c
    elseif line:sub(i, i + 1) == "--" then return true
    end
    i = i + 1
  end
  return q ~= nil
end

--- The completions of the word line:sub(start + 1, stop), names looked up in 'env'
-- (the REPL's environment: its globals and the `local`s kept from earlier lines): a sorted
-- list of whole words; nil inside a string (readline then completes a file name).
function M.complete (env, line, start, stop)
  if in_string(line, start) then return nil end
  local word = line:sub(start + 1, stop)
  local chain, sep, prefix = word:match("^([%a_][%w_.]*)([.:])([%a_]*[%w_]*)$")
  local names = {}
  if chain ~= nil then
    if chain:find("%.%.") or chain:find("%.$") then return {} end
    local v = resolve(env, chain)
    if v == nil then return {} end
    collect(v, names, 0)
  else
    prefix = word:match("^[%a_][%w_]*$") or (word == "" and "")
    if prefix == nil then return {} end
    collect(env, names, 0)
    for _, k in pairs(KEYWORDS) do names[k] = names[k] or true end
  end
  local out = {}
  local hidden = prefix:sub(1, 1) ~= "_"
  for k, x in pairs(names) do
    if k:sub(1, #prefix) == prefix and k:find("^[%a_][%w_]*$")
        and not (hidden and k:sub(1, 1) == "_")
        and (sep ~= ":" or type(x) == "function") then
      out[#out + 1] = chain and chain .. sep .. k or k
    end
  end
  table.sort(out)
  return out
end

return M
