--- The translator of cpfg's L-system files: the parsed L-systems (lsys.cpfg.parse, after
-- the preprocessor of lsys.cpfg.cpp) become `lsys.lsystem` options, one step a section of
-- the file. Rules that are pure expressions become rule strings (the expression machine
-- runs them); rules with statement blocks that are more than local assignments become
-- `{ pattern, function }` rules compiled with `load` in a private environment; the
-- Start:, StartEach:, EndEach: and End: blocks and the arrays become the model's hooks.
-- The Lua text of expressions and statements comes from lsys.cpfg.emit, and what it calls
-- at run time from lsys.cpfg.helpers. lsys.cpfg loads models through it; see docs/cpfg.md.
-- @module lsys.cpfg.translate
local type, pairs, ipairs, error, pcall, load, select, setmetatable, next =
  type, pairs, ipairs, error, pcall, load, select, setmetatable, next
local floor = math.floor
local concat, sort = table.concat, table.sort
local format, rep = string.format, string.rep
local parse = require "lsys.cpfg.parse"
local luatext = require "lsys.cpfg.emit"
local H = require "lsys.cpfg.helpers"
local model = require "lsys.model"
local warning = require "lsys.warning"
local core = require "lsys.core"
local codegen = require "lsys.codegen"
local _ENV = nil

local NOSTRING, fail, numlit = luatext.NOSTRING, luatext.fail, luatext.numlit
local emit, N, B, statements = luatext.emit, luatext.N, luatext.B, luatext.statements

local M = {}

local LUA_KEYWORDS = {}
for w in ([[and break do else elseif end false for function goto if in local nil not or
  repeat return then true until while]]):gmatch("%S+") do LUA_KEYWORDS[w] = true end

-- names an env variable may not take (they would hide lsys's own)
local TAKEN = { ran = true, nran = true, func = true }
for k in pairs(model.BUILTIN) do TAKEN[k] = true end

-- Names a #define kept as a name may not have (lsys.cpfg.import): lsys's own, cpfg's
-- reserved words, Lua's keywords, the derivation length's Q and Z.
local function untakable ()
  local t = { Q = true, Z = true }
  for k in pairs(TAKEN) do t[k] = true end
  for k in pairs(LUA_KEYWORDS) do t[k] = true end
  for k in pairs(parse.RESERVED) do t[k] = true end
  return t
end

-- What statements assign, read and do ---------------------------------------------------

-- Names assigned in statements (for scopes), and every name read.
local function walknames (list, assigned, read)
  local function expr (e)
    if e == nil then return end
    if e.k == "name" or e.k == "index" then read[e.n] = read[e.n] or e.pos end
    for _, f in ipairs({ "a", "b", "c" }) do expr(e[f]) end
    for _, x in ipairs(e.args or e.idx or {}) do expr(x) end
  end
  local function stmts (l)
    for _, s in ipairs(l or {}) do
      if s.k == "assign" then
        if s.lhs.k == "name" then assigned[#assigned + 1] = s.lhs.n end
        expr(s.lhs)
        if s.lhs.k == "name" then read[s.lhs.n] = nil end
        for _, x in ipairs(s.lhs.idx or {}) do expr(x) end
      end
      expr(s.e)
      expr(s.c)
      stmts(s.body)
      stmts(s.other)
    end
  end
  stmts(list)
  return expr
end

-- The first statement of 'list' that acts beyond the production's own variables (an
-- assignment to a global or an array, a call of printf or srand): its position and what
-- it does, or nil.
local function sideeffect (list, own)
  local found
  local function expr (e)
    if e == nil or found then return end
    if e.k == "call" and (e.f == "printf" or e.f == "srand") then
      found = { e.pos, "calls " .. e.f }
    end
    for _, f in ipairs({ "a", "b", "c" }) do expr(e[f]) end
    for _, x in ipairs(e.args or e.idx or {}) do expr(x) end
  end
  local function stmts (l)
    for _, st in ipairs(l or {}) do
      if found then return end
      if st.k == "assign" and not (st.lhs.k == "name" and own[st.lhs.n]) then
        found = { st.pos, "assigns " .. st.lhs.n }
        return
      end
      expr(st.e); expr(st.c)
      stmts(st.body); stmts(st.other)
    end
  end
  stmts(list)
  return found
end

-- Whether expression e draws a random number: a block local set from one is evaluated once
-- (cpfg's `{a=floor(n*ran(1)); b=n-a;}` keeps a+b = n), so the rule takes the function form
-- rather than substituting the expression's text at each use.
local RANDOM = { ran = true, nran = true, bran = true, biran = true }
local function draws (e)
  if e == nil then return false end
  if e.k == "call" and RANDOM[e.f] then return true end
  for _, f in ipairs({ "a", "b", "c" }) do if draws(e[f]) then return true end end
  for _, x in ipairs(e.args or e.idx or {}) do if draws(x) then return true end end
  return false
end

local function compile (T, src, pos)
  local file, line = T.P:where(pos)
  local chunk, err = load(src, "=" .. file .. ":" .. line, "t", {})
  if not chunk then
    error({ cpfg = true, msg = format("%s:%d: internal error compiling the translation: %s",
                                      file, line, err) }, 0)
  end
  if T.keep then        -- the function it makes, by its source and its locals L (import)
    return function (...)
      local f = chunk(...)
      T.keep.rules[f] = { src = src, L = (select(3, ...)) }
      return f
    end
  end
  return chunk
end

-- Modules --------------------------------------------------------------------------------

-- A parameter's Lua name: with a prefix when it is a Lua keyword, a name the translation
-- calls in rule strings (pi, abs: TAKEN) or a table of the function form (E, H, L).
local function mangle (name)
  if LUA_KEYWORDS[name] or TAKEN[name] or name == "E" or name == "H" or name == "L" then
    return "_p_" .. name
  end
  return name
end

-- The lsys text of a pattern (formal parameters) and the parameters it binds.
local function pattern (mods, params)
  local t = {}
  for _, m in ipairs(mods or {}) do
    local s = m.sym
    if m.params then
      local ps = {}
      for i, p in ipairs(m.params) do
        ps[i] = mangle(p)
        params[p] = mangle(p)
      end
      s = s .. "(" .. concat(ps, ",") .. ")"
    end
    t[#t + 1] = s
  end
  return concat(t)
end

-- The lsys text of a successor.
local function successor (T, ctx, mods)
  if #mods == 0 then return "*" end
  local t = {}
  for _, m in ipairs(mods) do
    local s = m.sym
    if m.params then
      local ps = {}
      for i, x in ipairs(m.params) do
        ps[i] = N(T, ctx, x)
      end
      s = s .. "(" .. concat(ps, ", ") .. ")"
    end
    t[#t + 1] = s
  end
  return concat(t)
end

local function template (T, ctx, mods)
  local t, vals = {}, {}
  for _, m in ipairs(mods) do
    local s = m.sym
    if m.params then
      for _, x in ipairs(m.params) do vals[#vals + 1] = N(T, ctx, x) end
      s = s .. "(" .. rep("?", #m.params, ",") .. ")"
    end
    t[#t + 1] = s
  end
  return concat(t), vals
end

-- How many lsys modules the text of a pattern is.
local function count (T, mods)
  local t = {}
  for _, m in ipairs(mods) do
    t[#t + 1] = m.sym .. (m.params and "(" .. rep("0", #m.params, ",") .. ")" or "")
  end
  local ok, s = pcall(core.lstring, concat(t), T.modnames)
  if not ok then return 0 end
  return #s
end

-- Productions ------------------------------------------------------------------------------

local consteval     -- the value of a constant expression (below)

-- Translates one production to a rule string or a { pattern, function } rule.
local function production (T, ls, p, section, stochastic)
  local params = {}
  local lc = p.lc and #p.lc > 0 and pattern(p.lc, params)
  local pred = pattern(p.pred, params)
  local rc = p.rc and #p.rc > 0 and pattern(p.rc, params)
  local pat = (lc and lc .. " < " or "") .. pred .. (rc and " > " .. rc or "")
  if p.prob and not stochastic then
    local file, line = T.P:where(p.pos)
    warning.warn(format("%s:%d: probability given for a deterministic production (ignored)",
                        file, line))
  end
  local weighted = stochastic and section == "productions"
  -- locals: names assigned in the blocks that are not the L-system's variables
  local assigned, read = {}, {}
  walknames(p.pre, assigned, read)
  walknames(p.post, assigned, read)
  local locals = {}
  for _, n in ipairs(assigned) do
    if not params[n] and not T.vars[ls.scope][n] and not T.glob[n] then
      if T.arrays[ls.scope][n] then fail(T, p.pos, "cannot assign to array %s", n) end
      locals[n] = mangle(n)
    end
  end
  -- the rule-string form: blocks of assignments only, every local set before it is read
  local ok, rule = pcall(function ()
    -- a local read before it is set (cpfg keeps its last value) gives up the string form
    local ctx = { mode = "s", scope = ls.scope, params = params, subst = {}, locals = locals }
    local function block (list)
      for _, s in ipairs(list or {}) do
        if s.k ~= "assign" or s.lhs.k ~= "name" or
           not (locals[s.lhs.n] or params[s.lhs.n]) or draws(s.e) then
          error(NOSTRING, 0)
        end
        local code = N(T, ctx, s.e)
        if #code > 2000 then error(NOSTRING, 0) end
        ctx.subst[s.lhs.n] = "(" .. code .. ")"
      end
    end
    block(p.pre)
    local cond = p.cond and emit(T, ctx, p.cond)
    block(p.post)
    local succ = successor(T, ctx, p.succ)
    local weight = weighted and (p.prob and N(T, ctx, p.prob) or "1")
    local r = pat .. (cond and " : (" .. cond .. ")" or "") .. " --> " .. succ ..
              (weight and " : " .. weight or "")
    if #r > 20000 then error(NOSTRING, 0) end
    return r
  end)
  if ok then return rule end
  if rule ~= NOSTRING then error(rule, 0) end
  local weight
  if weighted then         -- a weighted function rule: every one that applies runs
    local own = {}
    for n in pairs(locals) do own[n] = true end
    for n in pairs(params) do own[n] = true end
    -- with cpfg's generator the chosen production's post-condition block runs alone (its
    -- mark, below); lsys's runs the blocks of every production that applies
    local se = T.random == "lsys" and sideeffect(p.post, own)
    if se then
      fail(T, se[1], "in a stochastic L-system, a post-condition block that %s is not "
           .. "supported (lsys runs the blocks of every production that applies, cpfg only "
           .. "the chosen one's)", se[2])
    end
    weight = p.prob and consteval(T, p.prob, ls.scope,
                                  "the probability of a production with statement blocks") or 1
    if weight < 0 then fail(T, p.prob.pos, "the probability is %g, not >= 0", weight) end
  end
  -- the function form
  local ctx = { mode = "f", scope = ls.scope, params = params, locals = locals }
  local args = {}
  local seen = {}
  for _, part in ipairs({ p.lc or {}, p.pred, p.rc or {} }) do
    for _, m in ipairs(part) do
      for _, n in ipairs(m.params or {}) do
        if seen[n] then fail(T, m.pos, "formal parameter %s appears twice", n) end
        seen[n] = true
        args[#args + 1] = mangle(n)
      end
    end
  end
  local out = { "local E, H, L = ...", "return function (" .. concat(args, ", ") .. ")",
                "  local _n = 0" }
  -- cpfg's generator: a weighted production being tried stops after its condition
  -- (lsys_derive_cpfg_mark); the chosen one then goes on from there (its locals are in L), so
  -- that its post-condition block and successor draw after every production was tried,
  -- and its pre-condition block runs once
  -- (a formal parameter the pre-condition block assigns is kept in L[-k] meanwhile)
  local ind = weighted and "    " or "  "
  local keep, back = {}, {}
  if weighted then
    local pre = {}
    walknames(p.pre, pre, {})
    for _, n in ipairs(pre) do
      if params[n] and not back[n] then
        keep[#keep + 1] = format("L[%d] = %s", -#keep - 1, mangle(n))
        back[n] = format("%s = L[%d]", mangle(n), -#keep)
        back[#back + 1] = back[n]
      end
    end
    out[#out + 1] = "  if H._resume() then " .. concat(back, "; ") .. " else"
  end
  statements(T, ctx, p.pre, out, ind)
  if p.cond then out[#out + 1] = ind .. "if not " .. B(T, ctx, p.cond) .. " then return end" end
  if weighted then
    out[#out + 1] = "    if H._try() then " .. concat(keep, "; ") .. " return end\n  end"
  end
  statements(T, ctx, p.post, out, "  ")
  local tmpl, vals = template(T, ctx, p.succ)
  local v = #vals > 0 and ", " .. concat(vals, ", ") or ""
  out[#out + 1] = "  return H.produce(" .. codegen.string(tmpl) .. v .. ")"
  out[#out + 1] = "end"
  local L = {}
  T.localtables[#T.localtables + 1] = L
  local f = compile(T, concat(out, "\n"), p.pos)(T.env, T.H, L)
  return { pat, f, weight = weight }
end

-- Passes over the L-systems: constants, scopes, blocks, rules -------------------------

consteval = function (T, e, scope, what)
  local ctx = { mode = "s", scope = scope }
  local ok, code = pcall(N, T, ctx, e)
  if not ok then
    if code == NOSTRING then fail(T, e.pos, "%s must be a constant", what) end
    error(code, 0)
  end
  local env = setmetatable({}, { __index = function (_, k)
    return T.env[k] ~= nil and T.env[k] or model.BUILTIN[k] end })
  local chunk = load("return " .. code, "=" .. what, "t", env)
  local ok2, v = pcall(chunk)
  if not ok2 or type(v) ~= "number" or v ~= v then
    fail(T, e.pos, "%s must be a constant number", what)
  end
  return v
end

-- Declares the variables of every L-system: those of its define:, Start:, End:,
-- StartEach: and EndEach: blocks (cpfg's L-system symbol table).
local function variables (T, lsystems)
  for i, ls in ipairs(lsystems) do
    ls.scope = i
    local prefix = i == 1 and "" or "_l" .. i .. "_"
    local vars, arrays = {}, {}
    T.vars[i], T.arrays[i] = vars, arrays
    for _, a in ipairs(ls.arrays or {}) do
      if arrays[a.name] then fail(T, a.pos, "array %s defined twice", a.name) end
      local key = prefix .. ((TAKEN[a.name] or LUA_KEYWORDS[a.name]) and "_v_" or "") .. a.name
      arrays[a.name] = key
      T.arraykeys[key] = true
    end
    local names, order = {}, {}
    for _, b in ipairs({ "start", "starteach", "endeach", "end" }) do
      local assigned, read = {}, {}
      walknames(ls[b], assigned, read)
      for _, n in ipairs(assigned) do
        if not names[n] then names[n] = true; order[#order + 1] = n end
      end
      for n, pos in pairs(read) do
        if not names[n] and not arrays[n] then
          names[n] = pos
          order[#order + 1] = n
        end
      end
    end
    sort(order)
    for _, n in ipairs(order) do
      if not arrays[n] and not T.glob[n] then
        vars[n] = prefix .. ((TAKEN[n] or LUA_KEYWORDS[n] or n:sub(1, 1) == "_") and "_v_" or "")
                  .. n
        T.env[vars[n]] = 0.0
      end
    end
  end
end

-- Variables that productions assign (their rules read them live, as functions).
local function dynamic (T, lsystems)
  for _, ls in ipairs(lsystems) do
    for _, sect in ipairs({ ls.productions, ls.decomposition and ls.decomposition.productions,
                            ls.homomorphism and ls.homomorphism.productions }) do
      for _, p in ipairs(sect or {}) do
        local assigned = {}
        walknames(p.pre, assigned, {})
        walknames(p.post, assigned, {})
        for _, n in ipairs(assigned) do
          local key = T.vars[ls.scope][n] or T.glob[n]
          if key then T.dyn[key] = true end
        end
      end
    end
  end
end

-- A hook running one kind of block of every L-system (cpfg runs them in file order).
local function hook (T, lsystems, kind)
  local fns = {}
  for _, ls in ipairs(lsystems) do
    if ls[kind] then
      local ctx = { mode = "f", scope = ls.scope, locals = {} }
      local out = { "local E, H = ...", "return function ()", "  local _n = 0" }
      statements(T, ctx, ls[kind], out, "  ")
      out[#out + 1] = "end"
      local src = concat(out, "\n")
      local pos = ls[kind][1] and ls[kind][1].pos or ls.pos
      fns[#fns + 1] = compile(T, src, pos)(T.env, T.H)
      fns.where = fns.where or format("%s:%d: block", T.P:where(pos))
      if T.keep then T.keep.hooks[#T.keep.hooks + 1] = { kind = kind, src = src } end
    end
  end
  return fns
end

local function arrayinit (T, ls)
  local inits = {}
  for _, a in ipairs(ls.arrays or {}) do
    local dims, size = {}, 1
    for d, x in ipairs(a.dims) do
      dims[d] = floor(consteval(T, x, ls.scope, "an array dimension"))
      if dims[d] < 1 or dims[d] > 1e6 then
        fail(T, a.pos, "array %s: dimension %d is %d, not 1 to 1000000", a.name, d, dims[d])
      end
      size = size * dims[d]
    end
    if size > 1e7 then fail(T, a.pos, "array %s has more than 1e7 elements", a.name) end
    T.arraysize = (T.arraysize or 0) + size     -- 1e7 numbers are 160 MB
    if T.arraysize > 1e7 then
      fail(T, a.pos, "array %s: the arrays have more than 1e7 elements in all", a.name)
    end
    if a.init and #a.init > size then
      fail(T, a.pos, "array %s: %d values for %d elements", a.name, #a.init, size)
    end
    local vals, parts
    if a.init then
      local ctx = { mode = "f", scope = ls.scope, locals = {} }
      parts = {}
      for i, x in ipairs(a.init) do parts[i] = N(T, ctx, x) end
      vals = compile(T, "local E, H = ... return function () return " .. concat(parts, ", ")
                     .. " end", a.pos)(T.env, T.H)
    end
    if T.keep then
      T.keep.arrays[#T.keep.arrays + 1] = { key = T.arrays[ls.scope][a.name], name = a.name,
                                            dims = dims, values = parts }
    end
    local afile, aline = T.P:where(a.pos)
    local where = format("%s:%d: ", afile, aline)        -- where the array is defined
    inits[#inits + 1] = function ()
      local t = { name = a.name, dims = dims, v = {}, where = where }
      for i = 0, size - 1 do t.v[i] = 0.0 end
      if vals then
        local v = { vals() }
        for i = 1, #v do t.v[i - 1] = v[i] end
      end
      T.env[T.arrays[ls.scope][a.name]] = t
    end
  end
  return inits
end

local function rules (T, ls, list, section, stochastic)
  local out = {}
  for _, p in ipairs(list) do
    for _, m in ipairs(p.pred) do
      if m.sym == "[" or m.sym == "]" then
        -- cpfg matches '[' and ']' there as modules (`[f(y)P(r)?E(x)] --> *` removes a
        -- whole branch); lsys's brackets are the string's structure, which its rule
        -- matching, contexts and parallel steps rely on, never a module a rule rewrites
        fail(T, m.pos, "a bracket in a predecessor is not supported: lsys rewrites modules, "
             .. "never the branch structure; remove a branch with %% (a cut) from a module "
             .. "in it (docs/cpfg.md)")
      end
    end
    out[#out + 1] = production(T, ls, p, section, stochastic)
    T.origin[section][#out] = p.pos
  end
  return out
end

-- A strict predecessor of several modules (`leaf(a)` is l, e, a, f(a) in cpfg) is one in
-- productions and in the homomorphism, as in cpfg. When it is letters with parameters on the
-- last one only, a decomposition's or homomorphism's becomes a declared lsys module name
-- (every string then reads it as one module); any other is kept as several modules in the
-- homomorphism (vlab's 12-two-trees: `F(vig,n)#(w)`), and refused in a decomposition (lsys
-- decomposes one module at a time).
local function declare (T, lsystems)
  local names, list = {}, {}
  for _, ls in ipairs(lsystems) do
    for _, part in ipairs({ ls.decomposition or false, ls.homomorphism or false }) do
      for _, p in ipairs(part and part.productions or {}) do
        if count(T, p.pred) ~= 1 then
          local text, ok = {}, true
          for i, m in ipairs(p.pred) do
            if not m.sym:find("^[%a%d_]$") or (m.params and i < #p.pred) then ok = false end
            text[#text + 1] = m.sym
          end
          if (not ok or not text[1]:find("^%a")) and part == ls.homomorphism then
            goto several
          end
          if not ok or not text[1]:find("^%a") then
            fail(T, p.pos, "a strict predecessor of several modules ('%s') in a decomposition "
                 .. "is supported only as letters and digits with parameters on the last "
                 .. "one", concat(text))
          end
          local name = concat(text)
          if not names[name] then names[name] = true; list[#list + 1] = name end
          local last = p.pred[#p.pred]
          p.pred = { { sym = name, params = last.params, pos = p.pred[1].pos } }
        end
        ::several::
      end
    end
  end
  return list
end

-- cpfg's string is characters: its sphere `@o(0.2)` is '@' then 'o(0.2)', so a production
-- for `o` also rewrites the o of every @o (vlab's mycelis: `o(r) --> o(r+0.03)` grows the
-- spheres). lsys reads @o as one module: such a production gets a twin for @X placed right
-- after it, when the L-system has @X modules, the successor starts with a letter Y (cpfg's
-- string then reads @Y, as lsys's does) and no left context would see the '@' (or '@' is
-- ignored).
local function atrules (T, lsystems)
  for _, ls in ipairs(lsystems) do
    local used = {}
    local function scan (mods)          -- cpfg's characters: '@' then the letter
      for i, m in ipairs(mods or {}) do
        local nx = mods[i + 1]
        if m.sym == "@" and not m.params and nx and nx.sym:find("^%a$") then
          used["@" .. nx.sym] = true
        end
      end
    end
    scan(ls.axiom)
    for _, p in ipairs(ls.productions) do scan(p.succ) end
    local ignored = ls.ignore and ls.ignore:find("@", 1, true)
    local out = {}
    for _, p in ipairs(ls.productions) do
      out[#out + 1] = p
      local x = #p.pred == 1 and p.pred[1].sym
      local at = { sym = "@", pos = p.pred[1].pos }
      local first = p.succ[1] and p.succ[1].sym
      if x and x:find("^%a$") and used["@" .. x] and first and first:find("^%a$") and
         (not p.lc or #p.lc == 0 or ignored) and count(T, { at, p.pred[1] }) == 1 then
        local twin = {}
        for k, v in pairs(p) do twin[k] = v end
        twin.pred = { at, p.pred[1] }          -- the text @X(...): one lsys module
        twin.succ = { at }
        for i = 1, #p.succ do twin.succ[i + 1] = p.succ[i] end
        out[#out + 1] = twin
      end
    end
    ls.productions = out
  end
end

local function float32 ()
  return pcall(model.lsystem, { numbers = "float32" })
end

--- Translates parsed L-systems (`parse.new(lines):file()`) into lsys.lsystem options.
-- The translation, one step a section of the L-system file -----------------------------
-- The steps share the translation's state T (made by `state`): P, the parser (positions);
-- vars, arrays and arraykeys, each L-system's variables and arrays by scope; glob, the
-- file's globals (#defines kept as names, Q and Z); dyn, the variables productions assign;
-- env, the model's; localtables, the locals of the function rules; origin, where each rule
-- came from; modnames, the declared module names; H, the helpers as the rules call them;
-- random, the model's generator; undefined, the warning for a name not defined; keep, what
-- lsys.cpfg.import asked to keep. A rule calling func sets usesfunc; the model, model.

local function state (P, main, opts)
  local T = { P = P, vars = {}, arrays = {}, arraykeys = {}, glob = {}, dyn = {}, env = {},
              localtables = {}, origin = { productions = {}, decomposition = {},
                                           homomorphism = {} }, modnames = nil }
  T.H = setmetatable({}, { __index = H })
  T.random = opts.random or "cpfg"        -- the generator the model will have
  local warned = {}
  T.undefined = function (n, pos)
    local file, line = P:where(pos)
    local key = file .. n
    if not warned[key] then
      warned[key] = true
      warning.warn(format("%s:%d: identifier %s not previously defined (taken as 0)",
                          file, line, n))
    end
  end
  for k, v in pairs(H) do if k:sub(1, 1) == "_" then T.env[k] = v end end
  -- opts.keep: the Lua source of function rules, hooks and arrays, for lsys.cpfg.import;
  -- opts.globals: numbers by name (#defines kept as names), read as the model's variables
  if opts.keep then T.keep = { rules = {}, hooks = {}, arrays = {} } end
  for k, v in pairs(opts.globals or {}) do T.glob[k], T.env[k] = k, v end
  if main.dlength then
    T.glob.Q, T.glob.Z = "Q", "Z"
    T.env.Q = 0.0
  end
  return T
end

-- Derivation length: the number of steps (1 without one), and Z, which rules read.
local function dlength (T, main)
  if not main.dlength then return 1 end
  local steps = consteval(T, main.dlength, 1, "the derivation length")
  if steps < 0 or steps > model.MAX_STEPS then         -- lsys's limit
    fail(T, main.dlengthpos, "the derivation length is %g, not 0 to %d", steps,
         model.MAX_STEPS)
  end
  steps = floor(steps)
  T.env.Z = steps + 0.0
  return steps
end

-- The main L-system's settings: seed, ring, ignore and consider (and lsys's numbers,
-- float32 when this build has them).
local function settings (T, main, o)
  if float32() then o.numbers = "float32" end
  if main.seed then o.seed = floor(consteval(T, main.seed, 1, "the seed")) end
  o.ring = main.ring or nil
  o.ignore, o.consider = main.ignore, main.consider
end

-- Axiom: the text of its modules (evaluated after the start hook, the Start: blocks, as in
-- cpfg).
local function axiom (T, main)
  local actx = { mode = "s", scope = 1 }
  local ok, ax = pcall(successor, T, actx, main.axiom)
  if not ok then
    if ax == NOSTRING then fail(T, main.axiompos, "the axiom reads a variable set by a "
                                .. "production") end
    error(ax, 0)
  end
  return ax
end

-- Decomposition and homomorphism: their rules, maximum depth, seed and warnings.
local function decomphomo (T, main, o)
  local depth = {}
  for _, s in ipairs({ "decomposition", "homomorphism" }) do
    local sect = main[s]
    if sect then
      o[s] = rules(T, main, sect.productions, s, false)
      if sect.depth then
        local d = consteval(T, sect.depth, 1, "the maximum depth")
        if d < 0 then fail(T, sect.depth.pos, "the maximum depth is %g, not 0 or more", d) end
        if d > 1024 then     -- cpfg takes any depth; lsys's limit is 1024
          local file, line = T.P:where(sect.depth.pos)
          warning.warn(format("%s:%d: maximum depth %g taken as 1024, lsys's limit", file, line,
                              d))
          d = 1024
        end
        depth[s] = floor(d)
      end
      if sect.seed then o.homomorphism_seed = floor(consteval(T, sect.seed, 1, "the seed")) end
      if sect.warnings == false then          -- `no warnings`: no depth-limit warning
        o.depth_warnings = o.depth_warnings or {}
        o.depth_warnings[s] = false
      end
    end
  end
  if next(depth) ~= nil then o.max_depth = depth end
end

-- Sub-L-systems: their productions by label, with the main L-system's under its own.
local function sublsystems (T, lsystems, o)
  local main = lsystems[1]
  local sub = {}
  for i = 2, #lsystems do
    local ls = lsystems[i]
    local id = ls.id
    if id < 1 or id ~= floor(id) then
      fail(T, ls.pos, "a sub-L-system needs a whole number >= 1 as its label, not '%s'", ls.label)
    end
    if sub[id] or id == main.id then fail(T, ls.pos, "L-system %d defined twice", id) end
    for _, s in ipairs({ "decomposition", "homomorphism" }) do
      if ls[s] and #ls[s].productions > 0 then
        fail(T, ls[s].pos, "%s in a sub-L-system is not supported (lsys applies the main "
             .. "L-system's)", s)
      end
    end
    local rs, origin = {}, {}
    T.origin["sub-L-system " .. id] = origin    -- as lsys names it in its messages
    for _, p in ipairs(ls.productions) do
      rs[#rs + 1] = production(T, ls, p, "sub", ls.seed ~= nil)
      origin[#rs] = p.pos
    end
    if #rs > 0 then sub[id] = { productions = rs, ignore = ls.ignore, consider = ls.consider } end
  end
  if main.id >= 1 and main.id == floor(main.id) and #o.productions > 0 then
    sub[main.id] = { productions = o.productions, ignore = o.ignore, consider = o.consider }
  end
  if next(sub) ~= nil then o.sub = sub end
end

-- A hook running the blocks `fs` within the model's bounds, as its rules run (the blocks
-- are the file's code: max_instructions for each block, max_memory; docs/manual.md §4).
local function bounded (fs, name)
  local function run () for _, f in ipairs(fs) do f() end end
  return function (m)
    local done, e = pcall(m._rules.sandboxed, m._rules, run)
    if done then return end
    if type(e) == "string" and (e:find("^ran more than") or e:find("^needs more than")) then
      e = format("%s: %s", (fs.where or "?"):gsub("block$", name .. " block"), e)
    end
    error(e, 0)
  end
end

-- The arrays of define: and the Start:, StartEach:, EndEach: and End: blocks, as the
-- model's hooks: its start resets the variables, the blocks' locals and the arrays, then
-- runs the Start: blocks.
local function blocks (T, lsystems, o)
  local inits = {}
  for _, ls in ipairs(lsystems) do
    for _, f in ipairs(arrayinit(T, ls)) do inits[#inits + 1] = f end
  end
  local starts, each, ends, finish = hook(T, lsystems, "start"), hook(T, lsystems, "starteach"),
    hook(T, lsystems, "endeach"), hook(T, lsystems, "end")
  local env, vars, locals = T.env, {}, T.localtables
  for _, ls in ipairs(lsystems) do
    for _, k in pairs(T.vars[ls.scope]) do vars[#vars + 1] = k end
  end
  if T.keep then T.keep.vars, T.keep.locals = vars, locals end
  local function reset ()
    for _, k in ipairs(vars) do env[k] = 0.0 end
    if env.Q then env.Q = 0.0 end
    for _, L in ipairs(locals) do for k in pairs(L) do L[k] = nil end end
    for _, f in ipairs(inits) do f() end
  end
  reset()
  -- srand reseeds the generator of the model deriving: from a rule, the one producing now
  T.H._srand = function (x)
    if core.producing() then core.srand(x) else T.model:srand(x) end
    return 0.0
  end
  local startblocks = bounded(starts, "Start")
  o.start = function (m)
    T.model = m
    reset()
    startblocks(m)
  end
  if #each > 0 then o.start_each = bounded(each, "StartEach") end
  if #ends > 0 then o.end_each = bounded(ends, "EndEach") end
  if #finish > 0 then o.finish = bounded(finish, "End") end
end

--- Translates parsed L-systems (`parse.new(lines):file()`, the main one first) into
-- lsys.lsystem options, and returns them with the translation's state T: the loader
-- reads T.origin and T.P (where each rule came from), T.usesfunc and T.H (func, bound
-- to the model), and sets T.model; T.keep is what lsys.cpfg.import asked to keep.
-- opts: name (the model's), random ("cpfg" or "lsys", the model's generator), keep,
-- globals (numbers by name, for #defines kept as names). Raises { cpfg = true, msg = ... }
-- for the file's errors.
function M.translate (P, lsystems, opts)
  local main = lsystems[1]
  local T = state(P, main, opts)
  variables(T, lsystems)
  local steps = dlength(T, main)
  dynamic(T, lsystems)
  atrules(T, lsystems)
  local declared = declare(T, lsystems)
  T.modnames = #declared > 0 and concat(declared, " ") or nil
  local o = { steps = steps, env = T.env, name = opts.name, modules = T.modnames }
  settings(T, main, o)
  o.axiom = axiom(T, main)
  o.productions = rules(T, main, main.productions, "productions", main.seed ~= nil)
  decomphomo(T, main, o)
  sublsystems(T, lsystems, o)
  blocks(T, lsystems, o)
  return o, T
end

--- The names a #define kept as a name may not have (lsys.cpfg.import): lsys's own,
-- cpfg's reserved words, Lua's keywords, the derivation length's Q and Z.
M.untakable = untakable

-- For lsys.cpfg.import, which writes the same Lua: a number literal as the translated rules
-- hold it, and Lua's reserved words (no variable may take one as its name).
M.numlit = numlit
M.LUA_KEYWORDS = LUA_KEYWORDS

return M
