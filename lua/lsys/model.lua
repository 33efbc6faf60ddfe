--- Models (docs/manual.md §2-6): lsys.lsystem and the methods of the models it makes; rules
-- compiled into the core's rule set, derivation, the homomorphism, interpretation; and
-- the memory budget. `require "lsys"` gives all of this (init.lua). The modules that work
-- on models (lsys.viewer, lsys.cli) require this one, not "lsys": init.lua loads lsys.viewer
-- for lsys.show, and no module requires one that requires it back.
-- @module lsys.model
local core = require "lsys.core"
local compile = require "lsys.compile"
local func = require "lsys.func"
local view = require "lsys.view"
local warning = require "lsys.warning"
local sandbox = require "lsys.sandbox"
local environment = require "lsys.environment"
local params = require "lsys.params"
local inspect = require "lsys.inspect"
local suggest = require "lsys.util.suggest"

local type, pairs, ipairs, error, setmetatable, getmetatable, tostring, tonumber, pcall,
      math, string, table, debug, _G, os =
      type, pairs, ipairs, error, setmetatable, getmetatable, tostring, tonumber, pcall,
      math, string, table, debug, _G, os
local format = string.format
local _ENV = nil

local M = {}

-- The query modules (?P ?H ?U ?L), from the turtle's symbol table.
local QUERIES = {}
for _, row in ipairs(core.symbols()) do
  if row.query then QUERIES[#QUERIES + 1] = row.name end
end

-- Does `s` hold a query module?
local function hasquery (s)
  for _, name in ipairs(QUERIES) do
    if s:count(name) > 0 then return true end
  end
  return false
end

-- --------------------------------------------------------------------------
-- The memory budget (max_memory): the most memory one derivation step or one
-- interpretation may take for its strings, tables, mesh and records.

local UNITS = { [""] = 1, k = 2 ^ 10, m = 2 ^ 20, g = 2 ^ 30, t = 2 ^ 40 }

--- A memory size in bytes from a number of bytes or a string: "512M", "2G",
-- "1.5GiB", "800MB" (binary units: K = 1024), "unlimited". Raises naming `what` (by
-- default the public name, lsys.parse_size).
function M.parse_size (x, what)
  what = what or "lsys.parse_size"
  if type(x) == "number" then
    if x ~= x or x < 1 then error(format("%s must be at least 1 byte, got %s", what, x), 2) end
    return math.floor(x)
  end
  if type(x) ~= "string" then
    error(format("%s must be a number of bytes or a string such as \"2G\", got %s", what,
                 type(x)), 2)
  end
  local s = x:lower():gsub("%s", "")
  if s == "unlimited" or s == "none" then return math.huge end
  local num, unit = s:match("^([%d%.]+)([kmgt]?)i?b?$")
  local n = tonumber(num or "")
  if not n or n <= 0 then
    error(format("%s: '%s' is not a size (use a number of bytes, or e.g. \"512M\", \"2G\", " ..
                 "\"unlimited\")", what, x), 2)
  end
  return math.floor(n * UNITS[unit])
end

--- The process-wide memory budget in bytes (math.huge: none); with an argument (bytes or
-- a string such as "2G"; nil leaves it), sets it first. The default is half the physical
-- memory, or LSYS_MAX_MEMORY. A model's own `max_memory` option takes precedence. Also
-- returns the physical memory.
function M.max_memory (x)
  local bytes
  if x ~= nil then
    local ok, r = pcall(M.parse_size, x, "lsys.max_memory")
    if not ok then error(r, 2) end
    bytes = r
  end
  local limit, phys = core.max_memory(bytes)
  return limit >= 2 ^ 63 and math.huge or math.tointeger(limit) or limit,
         math.tointeger(phys) or phys
end

do
  local env = os.getenv("LSYS_MAX_MEMORY")
  if env ~= nil and env ~= "" then
    local ok, r = pcall(M.parse_size, env, "LSYS_MAX_MEMORY")
    if not ok then error(r, 0) end
    core.max_memory(r)
  end
end

local PROD, DECOMP, HOMO = compile.PROD, compile.DECOMP, compile.HOMO
local LSTRING_MT = getmetatable(core.lstring(""))

--- True when `x` is an Lstring.
local function islstring (x) return getmetatable(x) == LSTRING_MT end
M.islstring = islstring

--- lsys.lstring: parses cpfg text notation into an Lstring; `names` declares
-- multi-character module names ("Apex Leaf").
function M.lstring (text, names)
  if (names == nil or names == "") and type(text) ~= "string" then
    error(format("lsys.lstring: the text must be a string, got %s", type(text)), 2)
  end
  if names == nil or names == "" then
    local ok, s = pcall(core.lstring, text)
    if not ok then error((tostring(s):gsub("^lstring: ", "lsys.lstring: ")), 2) end
    return s
  end
  if type(text) ~= "string" then
    error(format("lsys.lstring: the text must be a string, got %s", type(text)), 2)
  end
  if type(names) ~= "string" then
    error(format("lsys.lstring: the names must be a string (\"Apex Leaf\"), got %s",
                 type(names)), 2)
  end
  local s, msg, pos = core.rules(names):lstring(text)
  if not s then error(format("lsys.lstring: %s at character %d", msg, pos), 2) end
  return s
end


-- Names usable in rule expressions besides `env` (lsys.sandbox: no library table of the
-- process is among them).
local BUILTIN = sandbox.BUILTIN
M.BUILTIN = BUILTIN

local OPTIONS = {
  axiom = "string", steps = "number", seed = "number", env = "table", modules = "string",
  ignore = "string", consider = "string", productions = "rules", decomposition = "rules",
  homomorphism = "rules", max_depth = "table", ring = "boolean", sub = "table",
  groups = "table", start = "function", start_each = "function", end_each = "function",
  finish = "function", max_modules = "number", view = "table", name = "string",
  max_memory = "size",
  homomorphism_seed = "number", allow_system_calls = "boolean", system_call = "function",
  functions = "table", after_interpret = "function", numbers = "string",
  depth_warnings = "any", threads = "number", max_instructions = "number",
  random = "string", environment = "any", params = "table",
}
local OPTION_NAMES = {}           -- for "did you mean" (lsys.util.suggest)
for k in pairs(OPTIONS) do OPTION_NAMES[#OPTION_NAMES + 1] = k end
table.sort(OPTION_NAMES)

local Model = {}
local rules_models = setmetatable({}, { __mode = "k" })   -- Rules userdata -> its model
Model.__index = Model
M.Model = Model

-- Splits a rules value (string or list) into entries { text=, fn=, line= }.
local function entries (rules, what, fail)
  local out = {}
  if type(rules) == "string" then
    local line = 0
    for l in (rules .. "\n"):gmatch("([^\n]*)\n") do
      line = line + 1
      if l:match("%S") then out[#out + 1] = { text = l:match("^%s*(.-)%s*$"), line = line } end
    end
  elseif type(rules) == "table" then
    for i, e in ipairs(rules) do
      if type(e) == "string" then
        out[#out + 1] = { text = e:match("^%s*(.-)%s*$"), line = i, item = true }
      elseif type(e) == "table" and type(e[1]) == "string" and type(e[2]) == "function" then
        local w = e.weight
        for k in pairs(e) do
          if k ~= 1 and k ~= 2 and k ~= "weight" then
            fail(format("%s: entry %d: unknown key '%s' in {pattern, function, weight = w}",
                        what, i, tostring(k)))
          end
        end
        if w ~= nil and (type(w) ~= "number" or not (w >= 0) or w == math.huge) then
          fail(format("%s: entry %d: weight must be a number >= 0", what, i))
        end
        out[#out + 1] = { text = e[1], fn = e[2], weight = w, line = i, item = true }
      else
        fail(format("%s: entry %d must be a rule string or {pattern, function}", what, i))
      end
    end
  else
    fail(format("%s must be a string or a list of rules", what))
  end
  return out
end

-- Compiles a rules value into the set (kind, sub, group).
function Model:_addrules (rules, what, kind, sub, group, fail)
  for _, e in ipairs(entries(rules, what, fail)) do
    local n = #self._info + 1
    local function labelled (pos)
      return format("rule %d '%s' (%s %d of %s)", n, warning.quote(e.text, pos),
                    e.item and "entry" or "line", e.line, what)
    end
    local label = labelled()
    local r, msg, pos = self._rules:parse(e.text, e.fn and "pattern" or "rule")
    if not r then fail(format("%s: %s at character %d", labelled(pos), msg, pos)) end
    local ok, spec, factory, frees, trees = pcall(compile.rule, r,
      { label = label, fn = e.fn, weight = e.weight, id = n })
    if not ok then fail(spec) end
    local added, idx = pcall(self._rules.add, self._rules, kind, sub, group, spec)
    if not added then fail(format("%s: %s", label, tostring(idx):gsub("^.-:%d+: ", ""))) end
    self._info[idx + 1] = { label = label, factory = factory, frees = frees, text = e.text,
                            set = what, line = e.line, n = n, fn = e.fn, weight = e.weight,
                            kind = kind,
                            trees = trees, funcrefs = factory and compile.funcrefs(e.text),
                            pattern = { r.lc, r.preds or { r.pred }, r.rc },
                            made = not e.fn and compile.kinds(r.succ) or nil }
    if spec.fn then self._fns[idx + 1] = spec.fn end
    -- (cpfg interprets the string between steps when it has query modules, ?E included:
    -- its environment step, which runs the homomorphism's random numbers too)
    if kind == PROD and e.text:find("?[PHULE]") then self._queries = true end
    if e.text:find("?E", 1, true) then self._hasE = true end
  end
end

-- Warns about each rule that can never apply because a module of its pattern never
-- appears with the rule's parameter count (compile.unreachable: made by the axiom or by a
-- rule that can apply); once a process (the jobs of lsys batch make their model again).
local countwarned = {}
function Model:_checkcounts (open)
  for _, u in ipairs(compile.unreachable(self._info, self._rules:kinds(self._axiom), open)) do
    local msg = format("lsys: %s: %s: no '%s' with %d parameter%s in the axiom or a "
      .. "successor of a rule that can apply (every '%s' there has %s): the rule never applies",
      self._where, u.info.label, u.name, u.count, u.count == 1 and "" or "s", u.name,
      table.concat(u.have, " or "))
    if not countwarned[msg] then
      countwarned[msg] = true
      warning.warn(msg)
    end
  end
end

--- lsys.here: the directory of the Lua file that calls this ("." when it is not a file):
-- for a model's contour, surface and texture files next to it, as
-- `view = { dir = lsys.here() }`.
function M.here ()
  local src = debug.getinfo(2, "S").source
  return src:match("^@(.*)/[^/]*$") or "."
end

-- The model file being run (see runfile), or nil.
local loading

-- The name of a model made by the model file `path` without one: the file's name without
-- its folder and .lua (nil without a file).
local function filename (path)
  return path and (path:match("([^/]*)$"):gsub("%.lua$", ""))
end

--- Runs `chunk`, the model file `path` (loaded by lsys.load, or the program's dofile), in
-- protected mode; returns what pcall returns. A model it makes without a name is named
-- after the file (`plant` for dir/plant.lua), and its messages name the file when the
-- line of the lsys.lsystem call is unknown (`return lsys.lsystem{...}` is a tail call:
-- the caller's frame is gone).
function M.runfile (path, chunk)
  local outer = loading
  loading = path
  local r = table.pack(pcall(chunk))
  loading = outer
  return table.unpack(r, 1, r.n)
end

-- Checks the option names and their types; `fail` raises naming the model.
local function checkoptions (opts, fail)
  for k, v in pairs(opts) do
    local t = OPTIONS[k]
    if t == nil then
      fail(format("unknown option '%s'%s", tostring(k), suggest.hint(k, OPTION_NAMES)))
    end
    if t == "rules" then
      if type(v) ~= "string" and type(v) ~= "table" then
        fail(format("option '%s' must be a string or a list of rules", k))
      end
    elseif t == "size" then
      local ok, r = pcall(M.parse_size, v, "option '" .. k .. "'")
      if not ok then fail(r) end
    elseif t ~= "any" and type(v) ~= t then
      fail(format("option '%s' must be a %s (got %s)", k, t, type(v)))
    end
  end
  if opts.ignore and opts.consider then fail("give either 'ignore' or 'consider', not both") end
end

-- Compiles the rule sets of the options: productions, groups, sub-L-systems,
-- decomposition and homomorphism.
function Model:_addsets (opts, fail)
  local rules = self._rules
  if opts.productions then self:_addrules(opts.productions, "productions", PROD, 0, 0, fail) end
  for g, rs in pairs(opts.groups or {}) do
    if type(g) ~= "number" or g < 1 or g ~= math.floor(g) then
      fail("groups: keys must be group numbers >= 1")
    end
    self:_addrules(rs, format("group %d", g), PROD, 0, g, fail)
    self._groups = self._groups or {}
    self._groups[g] = true
  end
  for id, s in pairs(opts.sub or {}) do
    if type(id) ~= "number" or id < 1 or id ~= math.floor(id) then
      fail("sub: keys must be sub-L-system numbers >= 1")
    end
    if type(s) ~= "table" then fail(format("sub[%d] must be a table", id)) end
    for k in pairs(s) do
      if k ~= "productions" and k ~= "ignore" and k ~= "consider" then
        fail(format("sub[%d]: unknown option '%s'", id, tostring(k)))
      end
    end
    self:_addrules(s.productions or "", format("sub-L-system %d", id), PROD, id, 0, fail)
    rules:newset(PROD, id, 0)
    if s.ignore or s.consider then
      rules:skiplist(id, s.consider ~= nil, s.consider or s.ignore)
    end
  end
  if opts.decomposition then
    self:_addrules(opts.decomposition, "decomposition", DECOMP, 0, 0, fail)
  end
  if opts.homomorphism then
    self:_addrules(opts.homomorphism, "homomorphism", HOMO, 0, 0, fail)
  end
end

-- Gives the core the options that configure the derivation: the symbols context skips,
-- ring, and the limits (max_modules, max_memory, max_depth).
function Model:_configure (opts, fail)
  local rules = self._rules
  self._options = opts          -- for m:inspect(): what the core keeps (ignore, ring...)
  if opts.ignore or opts.consider then
    local ok, msg = pcall(rules.skiplist, rules, 0, opts.consider ~= nil,
                          opts.consider or opts.ignore)
    if not ok then fail(format("%s: %s", opts.consider and "consider" or "ignore", msg)) end
  end
  if opts.ring then rules:config("ring", true) end
  if opts.numbers ~= nil and opts.numbers ~= "double" then
    if opts.numbers ~= "float32" then
      fail(format("option 'numbers' must be \"double\" or \"float32\", got \"%s\"",
                  opts.numbers))
    end
    rules:config("float32", true)      -- parameters stored as cpfg stores them
  end
  self.numbers = opts.numbers or "double"
  if opts.max_modules then
    local ok = pcall(rules.config, rules, "max_modules", opts.max_modules)
    if not ok then fail("max_modules must be between 1 and 1e12") end
    self.max_modules = opts.max_modules
  end
  if opts.max_memory then self:_limits { max_memory = M.parse_size(opts.max_memory) } end
  if opts.max_instructions then
    local n = opts.max_instructions
    if not (n >= 1000) then fail("max_instructions must be a number >= 1000 (or math.huge)") end
    rules:config("max_instructions", n)
    self.max_instructions = n
  end
  local dw = opts.depth_warnings     -- false, or { decomposition = b, homomorphism = b }
  self._depthwarn = { decomposition = dw ~= false, homomorphism = dw ~= false }
  if type(dw) == "table" then
    for k, b in pairs(dw) do
      if (k ~= "decomposition" and k ~= "homomorphism") or type(b) ~= "boolean" then
        fail(format("depth_warnings: bad entry '%s' (decomposition = or homomorphism = "
                    .. "true or false)", tostring(k)))
      end
      self._depthwarn[k] = b
    end
  elseif dw ~= nil and type(dw) ~= "boolean" then
    fail("option 'depth_warnings' must be a boolean or a table (decomposition, homomorphism)")
  end
  for k, d in pairs(opts.max_depth or {}) do
    if k ~= "decomposition" and k ~= "homomorphism" then
      fail(format("max_depth: unknown key '%s' (decomposition or homomorphism)", tostring(k)))
    end
    local ok = pcall(rules.config, rules, "depth_" .. k, d)
    if not ok then fail(format("max_depth.%s must be a whole number from 0 to 1024", k)) end
  end
end

local make

--- Creates a model from its description (docs/manual.md §2).
-- Raises an error naming the rule and its line for malformed rules.
function M.lsystem (opts)
  if type(opts) ~= "table" then error("lsys.lsystem: a table of options expected", 2) end
  -- where the model is defined; unknown when `return lsys.lsystem{...}`
  -- was a tail call (the caller's frame is gone: the loader names the file)
  local info = not debug.getinfo(1, "t").istailcall and debug.getinfo(2, "Sl")
  local where = info and info.currentline > 0 and
                format("%s:%d", info.short_src, info.currentline) or loading
  local function fail (msg) error(where and where .. ": " .. msg or msg, 0) end
  -- the folder of the file that makes the model: its view's files are read from there
  local file = info and info.source:match("^@(.*)$") or loading
  local dir = file and (file:match("^(.*)/[^/]*$") or ".")
  -- a model that fails leaves no module names behind (they count against the state's
  -- 2047, and nothing refers to them)
  local mark = core.names_mark()
  local ok, m = pcall(make, opts, where, fail, dir)
  if not ok then
    core.names_truncate(mark)
    error(m, 0)
  end
  return m
end

-- The model of M.lsystem (which undoes its module names when this raises).
make = function (opts, where, fail, dir)
  checkoptions(opts, fail)
  local rules = core.rules(opts.modules)
  local v = opts.view or {}
  if dir and type(v) == "table" and v.dir == nil then v = view.merge(v, { dir = dir }) end
  local self = setmetatable({
    axiom = opts.axiom or "", steps = opts.steps or 1, seed = opts.seed or 0,
    env = opts.env or {}, view = v, name = opts.name or filename(loading),
    homomorphism_seed = opts.homomorphism_seed,
    start = opts.start, start_each = opts.start_each, end_each = opts.end_each,
    finish = opts.finish, allow_system_calls = opts.allow_system_calls or false,
    system_call = opts.system_call, after_interpret = opts.after_interpret,
    threads = opts.threads, random = opts.random or "lsys", environment = opts.environment,
    _rules = rules, _info = {}, _where = where or "model", _group = 0,
  }, Model)
  if opts.environment ~= nil then
    local bad = environment.check(opts.environment)
    if bad then fail(bad) end
  end
  if opts.params ~= nil then                  -- tunable parameters: names in a copy of env
    local e = {}
    for k, x in pairs(self.env) do e[k] = x end
    self.env, self._onparam = e, {}
    self.params, self._params = params.make(opts.params, e, fail, function (k, x)
      for _, f in ipairs(self._onparam) do f(k, x) end
    end)
  end
  self._fns = rules:functions()
  rules_models[rules] = self
  if self.steps < 0 or self.steps ~= math.floor(self.steps) then
    fail("option 'steps' must be a whole number >= 0")
  end
  if self.steps > M.MAX_STEPS then
    fail(format("option 'steps' is %.14g, more than the limit of %d", self.steps, M.MAX_STEPS))
  end
  if not M.checkthreads(self.threads) then
    fail(format("option 'threads' must be a whole number from 1 to %d", M.MAX_THREADS))
  end
  self:_addsets(opts, fail)
  self:_configure(opts, fail)
  local nv = view.normalize(v, where or "model")   -- a bad view fails at definition
  self:_functions(opts.functions or nv.functions, nv.dir, fail)
  if self.axiom:find("?[PHULE]") then self._queries = true end
  if self.axiom:find("?E", 1, true) then self._hasE = true end
  -- the axiom: parsed now (errors at definition), its expressions evaluated per derivation
  local ok, msg = pcall(self._parseaxiom, self)
  if not ok then fail(msg) end
  self:_checkcounts(opts.end_each ~= nil)      -- end_each may return any string
  if self.random ~= "lsys" and self.random ~= "cpfg" then
    fail(format("option 'random' must be \"lsys\" or \"cpfg\", not \"%s\"",
                tostring(self.random)))
  end
  self:_seed()                   -- step() before any derive() uses the seed too
  return self
end

-- Seeds the generators from model.seed and model.homomorphism_seed, with the generator
-- model.random names (docs/manual.md §10): "lsys", counter-based, or "cpfg", cpfg's
-- erand48 and drand48 in the order cpfg draws. With "cpfg" and no homomorphism_seed,
-- the homomorphism draws from the derivation's numbers, as in cpfg.
function Model:_seed (homoonly)
  local rules, r = self._rules, self.random
  if r ~= "lsys" and r ~= "cpfg" then
    error(format("model.random must be \"lsys\" or \"cpfg\", not \"%s\"", tostring(r)), 0)
  end
  rules:config("random", r)
  if not homoonly then rules:config("seed", self.seed) end
  local share = r == "cpfg" and self.homomorphism_seed == nil
  rules:config("hshare", share)
  if not share then rules:config("hseed", self.homomorphism_seed or self.seed) end
end

-- The positional functions of the model (option `functions`, else its view's): the list
-- that func(ID, x) indexes, the table by name of func("name", x), and `func` itself.
function Model:_functions (spec, dir, fail)
  local list, byname, files = {}, {}, {}
  if spec ~= nil then
    local ok, l, b, fl = pcall(func.collect, spec, dir, "option 'functions'")
    if not ok then fail(l) end
    list, byname, files = l, b, fl
  end
  self._funclist, self._funcnames, self._funcfiles = list, byname, files
  self._func = function (id, x)
    local f = type(id) == "string" and byname[id] or type(id) == "number" and list[id]
    if not f then
      error(format("unknown function %s (functions: %s)",
                   type(id) == "string" and "'" .. id .. "'" or tostring(id),
                   func.names(byname)), 2)
    end
    return f(x)
  end
end

--- The value of the model's positional function `id` (its position from 1, or its name)
-- at `x`: what func(id, x) gives in a rule.
function Model:func (id, x)
  if type(x) ~= "number" then
    error(format("func: x must be a number, got %s", type(x)), 2)
  end
  return self._func(id, x)
end

--- Replaces the positional function `id` (position or name) by the lsys.Func `f`
-- wherever the old one was, from the next step on (lsys.func.replace).
function Model:set_func (id, f)
  self:_idle("set_func")
  local err = func.replace(self._funclist, self._funcnames, self._funcfiles, id, f)
  if err then error("set_func: " .. err, 2) end
end

--- The model's positional functions, { id =, name =, func =, file = } (lsys.func.entries).
function Model:functions ()
  return func.entries(self._funclist, self._funcnames, self._funcfiles)
end

-- Raises when a rule calls func(ID, x) or func("name", x) with a function the model
-- does not have (when derivation starts, as for unknown names).
function Model:_checkfuncs (info)
  for _, r in ipairs(info.funcrefs) do
    local ok = r[1] == "name" and self._funcnames[r[2]] or r[1] == "id" and self._funclist[r[2]]
    if not ok then
      error(format("%s: %s: unknown function %s (functions: %s)%s", info.where or self._where,
                   info.label,
                   r[1] == "name" and "'" .. r[2] .. "'" or tostring(math.tointeger(r[2]) or r[2]),
                   func.names(self._funcnames), self._funchint or ""), 0)
    end
  end
end

--- The declaration of tunable parameter `name` (lsys.params): a copy, or nil.
function Model:param (name)
  local d = self._params and self._params[name]
  if d == nil then return nil end
  local c = {}
  for k, x in pairs(d) do c[k] = x end
  return c
end

--- Calls fn(name, value) after each change of a tunable parameter (m.params.R = 1.5).
function Model:on_param (fn)
  if type(fn) ~= "function" then error("on_param: a function expected", 2) end
  if self._onparam == nil then error("on_param: the model has no params", 2) end
  self._onparam[#self._onparam + 1] = fn
end

-- The lookup table rule closures bind their free names from.
function Model:_env ()
  local ran, nran = self._rules:ran()
  local env, fn = self.env, self._func
  return setmetatable({}, { __index = function (_, k)
    if k == "ran" then return ran elseif k == "nran" then return nran
    elseif k == "func" then return fn end
    local v = env[k]
    if v == nil then v = BUILTIN[k] end
    return v
  end })
end

-- Raises when a rule function of this model calls `what` on the model itself: the
-- running step owns its rules and scratch (binding them again would change the rules
-- under it).
function Model:_idle (what)
  if self._rules:busy() then
    error(format("a rule called %s on the model it belongs to", what), 0)
  end
end

-- Binds every compiled rule to the current env (called before each step).
function Model:_bind ()
  local E = self:_env()
  local lib = compile.library(E, self._funclist, self._funcnames)
  local codes = {}
  for i, info in pairs(self._info) do
    if info.factory then
      for name in pairs(info.frees) do
        if E[name] == nil then
          error(format("%s: %s: unknown name '%s' (not a parameter, not in env)",
                       info.where or self._where, info.label, name), 0)
        end
      end
      self:_checkfuncs(info)
      self._fns[i] = info.factory(E, type, error, core.cpfg_try)
      -- the C expression machine when the expressions allow it, else the closure
      codes[i] = not self.lua_expressions and compile.machine(info.trees, E, lib) or false
    end
  end
  -- the functions the code calls, then the code (setfuncs cleared every program)
  self._rules:setfuncs(lib.fns)
  for i, code in pairs(codes) do
    if code and not self._rules:setvm(i - 1, code) then self._rules:setvm(i - 1, nil) end
  end
  return E
end

-- The axiom text for messages: a long one shortened.
local function axiomtext (a, pos)
  return warning.quote(a, pos)
end

-- Parses model.axiom into a template (in C: no table per module, docs/architecture.md) and the
-- list of its distinct parameter expressions; raises "axiom '...': ...".
function Model:_parseaxiom ()
  local tpl, exprs, pos = self._rules:axiom(self.axiom)
  if not tpl then
    error(format("axiom '%s': %s at character %d", axiomtext(self.axiom, pos), exprs, pos), 0)
  end
  self._axiom, self._axiomexprs, self._axiomsrc = tpl, exprs, self.axiom
end

-- The axiom as an Lstring, its expressions evaluated in env.
function Model:_axiomlstring (E)
  if self.axiom ~= self._axiomsrc then           -- the axiom field was changed
    local ok, msg = pcall(self._parseaxiom, self)
    if not ok then error(self._where .. ": " .. msg, 0) end
  end
  local vals = {}
  for k, e in ipairs(self._axiomexprs) do
    local f, msg = _G.load("return " .. e, "=axiom", "t", E)
    if not f then
      error(format("%s: axiom: bad expression '%s': %s", self._where, warning.quote(e), msg), 0)
    end
    local ok, x = pcall(self._rules.sandboxed, self._rules, f)    -- axiom text is rule text
    if not ok then
      error(format("%s: axiom: expression '%s': %s", self._where, e,
                   tostring(x):gsub("^axiom:%d+: ", "")), 0)
    end
    if type(x) ~= "number" or x ~= x or x == 1 / 0 or x == -1 / 0 then
      error(format("%s: axiom: expression '%s' is %s, not a finite number",
                   self._where, e, tostring(x)), 0)
    end
    vals[k] = x
  end
  return self._rules:fill(self._axiom, vals)
end

--- Parses text with this model's declared module names.
function Model:lstring (text)
  if type(text) ~= "string" then
    error(format("lstring: the text must be a string, got %s", type(text)), 2)
  end
  local s, msg, pos = self._rules:lstring(text)
  if not s then error(format("lstring: %s at character %d", msg, pos), 2) end
  return s
end

--- The most threads a derivation step may use (`threads`).
M.MAX_THREADS = core.MAXTHREADS

-- Whether `n` is a valid `threads` (nil: the default).
function M.checkthreads (n)
  return n == nil or type(n) == "number" and n >= 1 and n <= M.MAX_THREADS and n == math.floor(n)
end

-- Gives the core the threads of the next steps (model.threads, read by every derive and step).
function Model:_threads (what)
  if not M.checkthreads(self.threads) then
    error(format("%s: threads must be a whole number from 1 to %d (got %s)", what,
                 M.MAX_THREADS, tostring(self.threads)), 3)
  end
  self._rules:config("threads", self.threads or 0)
end

-- Runs a core call; turns a failure into a message naming rule and module.
function Model:_core (what, ...)
  return self:_call(self._rules[what], what, self._rules, ...)
end

-- How deep derivations may nest (a rule function that derives a model, whose rules
-- derive another, ...): far below the C stack's limit, so a rule that derives a fresh copy
-- of its own model gets one clear message instead of a C stack overflow.
local MAXNEST, nesting = 32, 0
local NESTED = "derivations nested"

-- Runs fn(...), which may call rule functions; errors as for _core.
function Model:_call (fn, what, ...)
  local rules = self._rules
  local producing = core.producing()
  if nesting >= MAXNEST then
    error(format("%s: %s %d deep: a rule function derives a model whose rules derive again "
                 .. "(does a rule make and derive its own model?)", self._where, NESTED,
                 MAXNEST), 0)
  end
  nesting = nesting + 1
  local ok, res = pcall(fn, ...)
  nesting = nesting - 1
  if not ok then core.producing(producing) end   -- a raising step left it set
  if ok then
    local _, _, deep = rules:current()
    local kind = (what == "step" or what == "advance") and "decomposition" or "homomorphism"
    if deep and not self._warned and self._depthwarn[kind] then
      self._warned = true
      warning.warn(format("lsys: %s: the %s depth limit stopped at modules that have " ..
                          "rules (raise max_depth if they should apply)", self._where, kind))
    end
    return res
  end
  local idx, mod = rules:current()
  local msg = type(res) == "string" and res or tostring(res)
  local step = self._atstep
  self._atstep = nil
  if msg:find(NESTED, 1, true) then error(msg, 0) end      -- said once, at the innermost
  if idx then
    local info = self._info[idx + 1]
    local label = info and info.label or format("rule %d", idx + 1)
    msg = msg:gsub("^rule:%d+: ", "")
    error(format("%s: %s, module %d: %s", info and info.where or self._where, label, mod, msg),
          0)
  end
  -- not a rule's: a limit of the step (max_modules, max_memory), named with the step of
  -- derive it stopped at, so that the user sees how far the model got
  if step ~= nil then
    error(format("%s: step %d of %d: %s", self._where, step, self._atsteps, msg), 0)
  end
  error(format("%s: %s", self._where, msg), 0)
end

-- The most steps one derivation may take (a guard against math.huge and typos: a step
-- costs at least a few microseconds, so this is hours of work at the least).
M.MAX_STEPS = 10000000

local function checksteps (n, what)
  if type(n) ~= "number" or n < 0 or n ~= math.floor(n) then
    error(format("%s: the number of steps must be a whole number >= 0", what), 3)
  end
  if n > M.MAX_STEPS then
    error(format("%s: %s steps is more than the limit of %d", what,
                 n == math.huge and "infinitely many" or format("%.14g", n), M.MAX_STEPS), 3)
  end
end

-- The model whose hook (start, start_each, end_each, finish) runs now: lsys.srand there
-- reseeds it.
local hooked

--- The model whose hook runs now, or nil.
function M.hooked () return hooked end

--- lsys.srand(seed), cpfg's: in a rule function, reseeds the generator of the model
-- deriving; in a model's hook (start, start_each, end_each, finish), that model's (m:srand).
function M.srand (seed)
  local m = not core.producing() and hooked
  if m then return m:srand(seed) end
  local ok, err = pcall(core.srand, seed)
  if not ok then error("lsys." .. tostring(err):gsub("^[^:]*:%d+: ", ""), 2) end
end

-- Runs the hook `f` of model `m` (f(m, ...)) with `hooked` set to m for its duration.
local function runhook (m, f, ...)
  local prev = hooked
  hooked = m
  local ok, r = pcall(f, m, ...)
  hooked = prev
  if not ok then error(r, 0) end
  return r
end

--- Derives `n` steps (default `model.steps`) from the axiom and returns the
-- Lstring. Reseeds the generator from `model.seed` first, so the result is
-- reproducible. `opts.progress(step, n, nmodules)` is called after each step;
-- `opts.each(k, s)` receives the string of every step k = 0..n (it may keep them).
function Model:derive (n, opts)
  self:_idle("derive")
  if opts ~= nil and type(opts) ~= "table" then
    error(format("derive: the options must be a table ({progress = f, each = f}), got %s",
                 type(opts)), 2)
  end
  n = n or self.steps
  checksteps(n, "derive")
  self:_threads("derive")
  self:_seed()
  self._warned = false
  local E = self:_bind()
  if self.start then             -- first: the axiom may read what start sets (as in cpfg)
    runhook(self, self.start)
    E = self:_bind()
  end
  local s = self:_axiomlstring(E)
  local progress = opts and opts.progress
  local each = opts and opts.each
  -- the strings of the steps are the derivation's own unless `each` or end_each may keep
  -- them: then each step rewrites its string in place (its memory is reused, the string
  -- before the step is not kept)
  local own = not each and not self.end_each
  local _ <close> = environment.session(self)  -- the environments' start and finish
  if each and n > 0 then each(0, s) end   -- (n = 0: the axiom after finish, below)
  for k = 1, n do
    if self.start_each then
      runhook(self, self.start_each, k)
      self:_bind()
    end
    self:_pass(s, k - 1)
    local t
    self._atstep, self._atsteps = k, n  -- for a limit's message (_call): the step it stopped
    if own then t = self:_core("advance", s) else t = self:_core("step", s) end
    self._atstep = nil
    if self.end_each then
      local r = runhook(self, self.end_each, t, k)
      if r ~= nil then
        if not islstring(r) then error("end_each must return an Lstring or nil", 0) end
        t = r
      end
      if k < n and not self.start_each then self:_bind() end   -- end_each may change env
    end
    if progress then progress(k, n, #t) end
    if each and k < n then each(k, t) end
    s = t
  end
  if self._queries then self:_query(s) end       -- the final string gets its pass too
  if self.finish then
    local r = runhook(self, self.finish, s)
    if r ~= nil then
      if not islstring(r) then error("finish must return an Lstring or nil", 0) end
      s = r
    end
  end
  if each then each(n, s) end
  return s
end

--- One derivation step from `s` (an Lstring or text); returns a new Lstring.
-- The generator continues from where it was (no reseeding).
function Model:step (s)
  if type(s) == "string" then s = self:lstring(s) end
  if not islstring(s) then error("step: an Lstring expected", 2) end
  self:_idle("step")
  self:_threads("step")
  self:_bind()
  self:_pass(s, nil, true)
  return self:_core("step", s)
end

--- Reseeds the generator of the derivation now, as cpfg's srand: called from a `start`
-- hook, the derivation follows `seed` instead of `model.seed`; from `start_each` or
-- `end_each`, the steps after. (`lsys.srand(seed)` does it from inside a rule function.)
function Model:srand (seed)
  if type(seed) ~= "number" then
    error(format("srand: a number expected, got %s", type(seed)), 2)
  end
  self._rules:srand(seed)
end

--- Applies the homomorphism to `s` (what the turtle sees); a new Lstring.
function Model:expand (s)
  if type(s) == "string" then s = self:lstring(s) end
  if not islstring(s) then error("expand: an Lstring expected", 2) end
  self:_idle("expand")
  self:_bind()
  self:_seed(true)
  return self:_core("expand", s, HOMO)
end

-- The view of the model with `over` merged in, checked, defaults filled.
function Model:_view (over)
  return view.normalize(over and view.merge(self.view, over) or self.view, self._where)
end

-- The pass before a derivation step from `s` (string `step`): with an environment and ?E
-- modules in `s`, the environmental pass (lsys.environment), which fills the query modules
-- too; else the query pass when the rules make query modules (or `any`: `s` has some).
function Model:_pass (s, step, any)
  if (self._hasE or self.environment) and self.environment ~= false then
    if s:count("?E") > 0 then
      if self.environment then
        return environment.pass(self, s, step, function ()
          local opts = view.turtle_options(self:_view(), self.allow_system_calls)
          self:_seed(true)
          return self:_call(core.environment, "interpret", self._rules, s, opts)
        end)
      elseif not self._warnedE then
        self._warnedE = true
        warning.warn(format("lsys: %s: the string has ?E modules but the model has no "
          .. "environment: they keep the parameters the rules give them (option "
          .. "'environment', docs/open.md)", self._where))
      end
    end
  end
  if self._queries or (any and hasquery(s)) then self:_query(s) end
end

-- Fills the query modules ?P ?H ?U ?L of `s` in place from an interpretation
-- (cpfg: productions at step n see the values of string n-1).
function Model:_query (s)
  local opts = view.turtle_options(self:_view(), self.allow_system_calls)
  self:_seed(true)
  return self:_call(core.query, "interpret", self._rules, s, opts)
end

local scene_views = setmetatable({}, { __mode = "k" })   -- scene -> its normalised view

--- Interprets `s` (an Lstring or text; default: `self:derive()`) with the turtle and
-- returns an lsys.Scene. `over` replaces fields of the model's view for this call;
-- `over.records = false` leaves out the turtle records (less memory for big exports).
function Model:interpret (s, over)
  self:_idle("interpret")          -- before deriving: the message names what was called
  if s == nil then s = self:derive()
  elseif type(s) == "string" then s = self:lstring(s) end
  if not islstring(s) then error("interpret: an Lstring expected", 2) end
  if over ~= nil and type(over) ~= "table" then error("interpret: a view table expected", 2) end
  local records = true
  if over ~= nil and over.records ~= nil then
    records = over.records
    over = view.merge(over, nil)
    over.records = nil
  end
  self:_threads("interpret")
  local v = self:_view(over)
  self:_bind()
  self:_seed(true)
  local topts = view.turtle_options(v, self.allow_system_calls)
  topts.records = records and true or false
  local scene = self:_call(core.interpret, "interpret", self._rules, s, topts)
  scene_views[scene] = v
  if self.allow_system_calls and self.system_call then
    for _, r in scene:records() do
      if r.kind == "system" then self.system_call(r.module, s:module(r.module)) end
    end
  end
  if self.after_interpret then self.after_interpret(self, scene, s) end
  return scene
end

local SCENE_MT = debug.getregistry()["lsys.Scene"]

--- True when `x` is an lsys.Scene.
function M.isscene (x) return getmetatable(x) == SCENE_MT end

--- True when `x` is a model made by lsys.lsystem.
function M.ismodel (x) return getmetatable(x) == Model end

--- The normalised view a scene was interpreted with (nil for scenes made elsewhere): for
-- the renderer's options (lsys.render, lsys.viewer). A population (lsys.population) and its
-- flattened copies keep theirs with their options.
function M.sceneview (scene)
  local v = scene_views[scene]
  if v == nil and getmetatable(scene) == SCENE_MT then
    local o = core.scene_options(scene)
    if type(o) == "table" and o.population then v = o.view end
  end
  return v
end

--- Where model `m` was defined, for messages and titles: "file:line", the model file
-- lsys.cli ran, or "model".
function M.where (m) return m._where end

--- The model whose rules made the Lstring `s`, or nil (also for anything but an Lstring).
function M.owner (s)
  local r = islstring(s) and core.lstring_rules(s)
  return r and rules_models[r] or nil
end

-- Sets the model's limits over its own options, as lsys.lsystem would have set them:
-- `lim` holds any of threads, max_modules (checked by the caller) and max_memory (bytes;
-- math.huge for none). The command line's --threads, --max-modules and --max-memory.
function Model:_limits (lim)
  if lim.threads ~= nil then self.threads = lim.threads end
  if lim.max_modules ~= nil then
    self.max_modules = lim.max_modules
    self._rules:config("max_modules", lim.max_modules)
  end
  if lim.max_memory ~= nil then
    self.max_memory = lim.max_memory
    -- "unlimited" (math.huge): the most the core takes, 2^63 bytes, as good as none
    self._rules:config("max_memory", math.min(lim.max_memory, 2 ^ 63))
  end
end

--- Selects the rule group `n` (0 = only the productions, always active).
function Model:use_group (n)
  if type(n) ~= "number" or n < 0 or n ~= math.floor(n) then
    error("use_group: a group number >= 0 expected", 2)
  end
  self:_idle("use_group")
  if n ~= 0 and not (self._groups and self._groups[n]) then
    local have = {}
    for g in pairs(self._groups or {}) do have[#have + 1] = g end
    table.sort(have)
    error(format("use_group: the model has no group %.14g (groups: %s)", n,
                 #have > 0 and table.concat(have, ", ") or "none"), 2)
  end
  self._group = n
  self._rules:config("group", n)
end

Model.rules, Model.inspect = inspect.rules, inspect.text   -- m:rules(), m:inspect()

function Model:__tostring ()
  return format("lsys.Model(%s)", self.name or self._where)
end

return M
