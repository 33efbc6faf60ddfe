--- Rule compilation (docs/manual.md §5): turns the parts of a rule parsed by the core
-- (csrc/core/grammar.c splits the rule text) into a C successor template plus, when
-- needed, one Lua closure; and its expressions into code for the C expression machine
-- when they allow it.
--
-- The closure returns `true` followed by the computed values (the weight
-- first when it is an expression, then each distinct parameter
-- expression), or `false` when the condition fails. Rules without a
-- condition and without computed values get no closure at all.
-- @module lsys.compile
local core = require "lsys.core"
local codegen = require "lsys.codegen"
local quote = require("lsys.warning").quote

local type, tostring, tonumber, pairs, ipairs, error, load, math, mathtype, setmetatable,
      getmetatable, debug_registry =
      type, tostring, tonumber, pairs, ipairs, error, load, math, math.type, setmetatable,
      getmetatable, debug.getregistry()
local format, concat, insert, remove, table_sort =
      string.format, table.concat, table.insert, table.remove, table.sort
local _ENV = nil

local M = {}

local FUNC_MT = debug_registry["lsys.Func"]
local function isfunc (x) return getmetatable(x) == FUNC_MT and FUNC_MT ~= nil end

local KEYWORDS = {}
for w in ("and break do else elseif end false for function goto if in local nil not " ..
          "or repeat return then true until while"):gmatch("%a+") do KEYWORDS[w] = true end
M.KEYWORDS = KEYWORDS

local PROD, DECOMP, HOMO = 0, 1, 2
M.PROD, M.DECOMP, M.HOMO = PROD, DECOMP, HOMO
local PS_CONST, PS_ARG, PS_VAL = 0, 1, 2

--- The parameter counts each module name has in a parsed successor (or axiom): { name =
-- { [n] = true } } (kept instead of the successor's modules, which a generated successor
-- has millions of).
function M.kinds (mods)
  local made = {}
  for _, m in ipairs(mods or {}) do
    local k = made[m.name]
    if k == nil then k = {}; made[m.name] = k end
    k[#m.params] = true
  end
  return made
end

-- Brackets, cuts and sub-L-system modules: never a reason a rule cannot apply.
local STRUCTURE = { ["["] = true, ["]"] = true, ["%"] = true, ["?"] = true, ["$"] = true }

--[[
The rules that can never apply because a module of their pattern never appears with the
rule's parameter count (`A(x,y) --> ...` where every A made is `A(1)`), as a list of
{ info =, name =, count =, have = { the counts that do appear, sorted } } in the order of
the rules. `infos`: the model's rules, each with its kind, its pattern (lists of modules)
and `made` (M.kinds of its successor; nil for a rule function, which may make anything:
then nothing is said); `made`: the axiom's M.kinds. A module of the string counts when the
axiom has it or a production or decomposition rule that can apply makes it; the
homomorphism sees those and what its own rules that can apply make. A rule can apply once
every module of its pattern can appear, and then what it makes can appear too: a fixed
point, reached with a work list (a rule is tried again only when a name of its pattern
gains a count). `open`: the string may get modules from elsewhere too (end_each returns
strings): every successor counts then. A name that never appears at all says nothing (a
rule kept for a module only another version of the model makes).
]]
function M.unreachable (infos, made, open)
  local str, homo, byname, fired, pending = {}, {}, {}, {}, {}
  local function add (reach, kinds)
    for name, counts in pairs(kinds) do
      local c = reach[name]
      if c == nil then c = {}; reach[name] = c end
      for n in pairs(counts) do
        if not c[n] then c[n] = true; pending[#pending + 1] = name end
      end
    end
  end
  local function addmade (info)      -- what the string holds, the homomorphism sees too
    if info.kind ~= HOMO then add(str, info.made) end
    add(homo, info.made)
  end
  local function seen (info) return info.kind == HOMO and homo or str end
  local function applies (info)
    local reach = seen(info)
    for _, part in ipairs(info.pattern) do
      for _, m in ipairs(part) do
        local c = reach[m.name]
        if not STRUCTURE[m.name] and not (c and c[#m.params]) then return false end
      end
    end
    return true
  end
  local function try (i)
    if not fired[i] and applies(infos[i]) then fired[i] = true; addmade(infos[i]) end
  end
  add(str, made)
  add(homo, made)
  for _, info in pairs(infos) do
    if not info.made then return {} end           -- a rule function
    if open then addmade(info) end
  end
  for i, info in pairs(infos) do
    for _, part in ipairs(info.pattern) do
      for _, m in ipairs(part) do
        local l = byname[m.name]
        if l == nil then l = {}; byname[m.name] = l end
        l[#l + 1] = i
      end
    end
  end
  pending = {}
  for i in pairs(infos) do try(i) end
  while #pending > 0 do
    local name = remove(pending)
    for _, i in ipairs(byname[name] or {}) do try(i) end
  end
  -- the first module of each rule that cannot apply whose name appears with other counts
  local function why (info)
    local reach = seen(info)
    for _, part in ipairs(info.pattern) do
      for _, m in ipairs(part) do
        local c, np = reach[m.name], #m.params
        if c and not c[np] and not STRUCTURE[m.name] then
          local have = {}
          for k in pairs(c) do have[#have + 1] = k end
          table_sort(have)
          return { info = info, name = m.name, count = np, have = have }
        end
      end
    end
  end
  local idx, out = {}, {}
  for i in pairs(infos) do
    if not fired[i] then idx[#idx + 1] = i end
  end
  table_sort(idx)
  for _, i in ipairs(idx) do out[#out + 1] = why(infos[i]) end
  return out
end

--- The free names of a Lua expression: identifiers that are not keywords,
-- not fields (after `.` or `:`), not inside strings, and not in `bound`.
function M.freenames (expr, bound, out)
  out = out or {}
  local i, n = 1, #expr
  while i <= n do
    local c = expr:sub(i, i)
    if c == '"' or c == "'" then
      local j = i + 1
      while j <= n and expr:sub(j, j) ~= c do
        if expr:sub(j, j) == "\\" then j = j + 1 end
        j = j + 1
      end
      i = j + 1
    elseif c:match("[%a_]") then
      local s, e = expr:find("^[%a_][%w_]*", i)
      local name = expr:sub(s, e)
      -- a field follows one '.' or a ':'; after '..' (concatenation) a name is free
      local before = expr:sub(1, s - 1):match("(%S%S?)%s*$") or ""
      local field = before:sub(-1) == ":" or (before:sub(-1) == "." and before ~= "..")
      if not KEYWORDS[name] and not field and not bound[name] then
        out[name] = true
      end
      i = e + 1
    elseif c:match("%d") then
      local _, e = expr:find("^[%w%.]*", i)       -- numbers like 1e5, 0x1F, 1.5
      if expr:sub(e, e):match("[eE]") and expr:sub(e + 1, e + 1):match("[%+%-]") then
        _, e = expr:find("^[%+%-][%w%.]*", e + 1)
      end
      i = e + 1
    else
      i = i + 1
    end
  end
  return out
end

local function isnumber (s)
  return s:match("^%s*[%+%-]?[%d%.]") ~= nil and tonumber(s) ~= nil
end

--- Checks that `expr` is a valid Lua expression; returns nil or a message.
local function checkexpr (expr)
  local f, msg = load("return " .. expr, "=expression", "t", {})
  if f then return nil end
  return (msg:gsub("^expression:1: ", ""))
end

-- Builds the source of the closure factory: `function(E) local x = E.x ...
-- return function(formals) ... end end`. Each expression stands on lines of its
-- own inside parentheses: an expression is checked on its own (checkexpr), and a
-- line comment at its end cannot swallow the code that follows it.
local function factorysource (formals, cond, exprs, frees, weighted)
  local ups = {}
  for name in pairs(frees) do ups[#ups + 1] = name end
  table_sort(ups)
  local head = {}
  for _, name in ipairs(ups) do
    head[#head + 1] = format("local %s = E[%s];", name, codegen.string(name))
  end
  local body = {}
  if cond then
    body[#body + 1] = format("local c_ = (\n%s\n); if c_ ~= true then if not c_ or c_ == 0 " ..
      "then return false end; if type_(c_) ~= 'number' then error_('condition is ' .. " ..
      "type_(c_) .. ', not a boolean or number', 0) end end;", cond)
  end
  local vals = {}
  for k, e in ipairs(exprs) do vals[k] = "(\n" .. e .. "\n)" end
  if weighted then
    -- the mark of cpfg's generator (lsys_derive_cpfg_mark): a rule being tried stops after its
    -- condition and weight; the chosen one's values are drawn after every try
    local w = weighted == "expr" and remove(vals, 1)
    body[#body + 1] = (w and "local w_ = " .. w .. "; " or "") ..
      "if try_() then return true" .. (w and ", w_" or "") .. " end;"
    if w then insert(vals, 1, "w_") end
  end
  body[#body + 1] = "return true" .. (#vals > 0 and ", " .. concat(vals, ", ") or "")
  return "local E, type_, error_, try_ = ...; " .. concat(head, " ") ..
         " return function(" .. concat(formals, ", ") .. ") " .. concat(body, " ") .. " end"
end

-- The environment rule code is compiled in: nothing. Every name a rule uses is a
-- parameter or a local bound from the model's lookup table (parameters, ran/nran,
-- env, lsys.BUILTIN); a name the scan above missed fails here instead of reaching
-- a global.
local SEALED = setmetatable({}, {
  __index = function (_, k)
    error(format("unknown name '%s' (not a parameter, not in env)", tostring(k)), 2)
  end,
  __newindex = function (_, k)
    error(format("cannot assign to '%s' in a rule expression", tostring(k)), 2)
  end,
  __metatable = false,
})
M.SEALED = SEALED

-- Whether the text of expression e calls nothing (a name, `)` or `]` followed by `(`, a
-- string or a table): only such an expression gives the same value twice, so only they
-- are listed once. `B(ran(10)) C(ran(10))` draws twice, and a user's function with
-- effects runs at each use.
local function callsnothing (e)
  return not (e:find("[%w_%]%)]%s*%(") or e:find("[%w_%]%)]%s*[\"'{]") or e:find("%[=*%["))
end

-- The successor's modules into spec.succ, and where each of their parameters comes from
-- into spec.src: a constant, a formal parameter (an index in `seen`), or a computed value
-- (an index in `exprs`; an expression that calls nothing is listed once).
local function successor (r, spec, seen, exprs, fail)
  local exprindex = {}
  for _, m in ipairs(r.succ) do
    insert(spec.succ, m.sym); insert(spec.succ, #m.params)
    for pi, e in ipairs(m.params) do
      if isnumber(e) then
        local x = tonumber(e)
        if x ~= x or x == 1 / 0 or x == -1 / 0 then
          fail("parameter %d of '%s' is '%s', not a finite number", pi, m.name, quote(e))
        end
        insert(spec.src, PS_CONST); insert(spec.src, 0); insert(spec.src, x)
      elseif seen[e] then
        insert(spec.src, PS_ARG); insert(spec.src, seen[e]); insert(spec.src, 0)
      else
        local msg = checkexpr(e)
        if msg then
          fail("bad expression '%s' in parameter %d of '%s': %s", quote(e), pi, m.name, msg)
        end
        local k = exprindex[e]
        if not k then
          exprs[#exprs + 1] = e
          k = #exprs - 1
          if callsnothing(e) then exprindex[e] = k end
        end
        insert(spec.src, PS_VAL); insert(spec.src, k); insert(spec.src, 0)
      end
    end
  end
end

-- The trees of the condition and the values for the C machine (M.machine), or nil when
-- one of them does not parse (M.parseexpr): the rule then keeps its closure.
local function parsetrees (cond, exprs, seen)
  local trees = { formals = seen, exprs = {} }
  if cond then
    trees.cond = M.parseexpr(cond)
    if not trees.cond then return nil end
  end
  for k, e in ipairs(exprs) do
    trees.exprs[k] = M.parseexpr(e)
    if not trees.exprs[k] then return nil end
  end
  return trees
end

--- Compiles one rule.
-- `r` is the table from rules:parse; `info` = { label = ..., kind = ...,
-- sub = ..., group = ..., fn = function or nil }.
-- Returns the spec for rules:add and the factory (or nil): factory(E)
-- returns the closure bound to the environment lookup E; with a factory, also the free
-- names of its expressions and their trees for `machine` (nil when they do not parse).
function M.rule (r, info)
  local label = info.label
  local function fail (msg, ...) error(label .. ": " .. format(msg, ...), 0) end
  local formals, seen = {}, {}
  local function addformals (mods)
    for _, m in ipairs(mods) do
      for _, p in ipairs(m.params) do
        if KEYWORDS[p] then fail("'%s' cannot be a parameter name", p) end
        if seen[p] then fail("parameter name '%s' is used twice", p) end
        seen[p] = #formals
        formals[#formals + 1] = p
      end
    end
  end
  local preds = r.preds or { r.pred }     -- several modules: cpfg's strict predecessor
  addformals(r.lc); addformals(preds); addformals(r.rc)
  local spec = { lc = {}, rc = {}, pred = {}, succ = {}, src = {},
                 flags = 0, nvals = 0, id = info.id }
  for _, m in ipairs(preds) do insert(spec.pred, m.sym); insert(spec.pred, #m.params) end
  for _, m in ipairs(r.lc) do insert(spec.lc, m.sym); insert(spec.lc, #m.params) end
  for _, m in ipairs(r.rc) do insert(spec.rc, m.sym); insert(spec.rc, #m.params) end
  if info.fn then
    if r.cond then fail("a rule with a function has no condition (test it in the function)") end
    spec.flags = core.RF_DYN
    spec.fn = info.fn
    if info.weight then         -- weighted: among the applicable rules, chosen by weight
      spec.flags = spec.flags | core.RF_STOCH
      spec.weight = info.weight
    end
    return spec, nil
  end
  local exprs = {}
  if r.weight then
    local w = r.weight
    if isnumber(w) then
      local x = tonumber(w)
      if not (x >= 0) or x == 1 / 0 then fail("bad weight '%s' (a number >= 0 expected)", w) end
      spec.weight = x
    else
      local msg = checkexpr(w)
      if msg then fail("bad weight '%s': %s", quote(w), msg) end
      exprs[1] = w
      spec.flags = spec.flags | core.RF_WEXPR
    end
    spec.flags = spec.flags | core.RF_STOCH
  end
  successor(r, spec, seen, exprs, fail)
  if r.cond then
    local msg = checkexpr(r.cond)
    if msg then fail("bad condition '%s': %s", quote(r.cond), msg) end
  end
  if not r.cond and #exprs == 0 then return spec, nil end
  spec.flags = spec.flags | core.RF_CALL
  spec.nvals = #exprs
  local frees = {}
  if r.cond then M.freenames(r.cond, seen, frees) end
  for _, e in ipairs(exprs) do M.freenames(e, seen, frees) end
  local weighted = r.weight and (spec.flags & core.RF_WEXPR ~= 0 and "expr" or "const")
  local src = factorysource(formals, r.cond, exprs, frees, weighted)
  local factory, msg = load(src, "=rule", "t", SEALED)   -- messages say 'rule:N:'
  if not factory then fail("%s", msg) end
  return spec, factory, frees, parsetrees(r.cond, exprs, seen)
end

-- ---------------------------------------------------------------------------
-- Expressions that run in C (csrc/core/expr.h). An expression is parsed once into
-- a tree; when a model is bound to its env, the tree becomes stack-machine
-- code if every name is a parameter, a number in env, a math function or
-- ran/nran, and every operation means in C what it means in Lua. Otherwise
-- the rule keeps its Lua closure.

local OP = { K = 0, ARG = 1, ["+"] = 2, ["-"] = 3, ["*"] = 4, ["/"] = 5, ["%"] = 6, ["^"] = 7,
             ["//"] = 8, UNM = 9, ["<"] = 10, ["<="] = 11, [">"] = 12, [">="] = 13,
             ["=="] = 14, ["~="] = 15, NOT = 16, JF = 17, JT = 18, F1 = 19, F2 = 20,
             RAN = 21, NRAN = 22, RET = 23, COND = 24, FN = 25 }
M.OP = OP

-- lparser.c priorities: {left, right}
local PRIO = { ["or"] = {1, 1}, ["and"] = {2, 2}, ["<"] = {3, 3}, [">"] = {3, 3},
  ["<="] = {3, 3}, [">="] = {3, 3}, ["~="] = {3, 3}, ["=="] = {3, 3}, ["+"] = {10, 10},
  ["-"] = {10, 10}, ["*"] = {11, 11}, ["/"] = {11, 11}, ["//"] = {11, 11}, ["%"] = {11, 11},
  ["^"] = {14, 13} }
local UNARY = 12

local function tokenize (s)
  local toks, i, n = {}, 1, #s
  while i <= n do
    local c = s:sub(i, i)
    if c:match("%s") then i = i + 1
    else
      local tok
      tok = s:match("^0[xX][%x%.pP]+", i) or s:match("^%d*%.?%d+[eE][%+%-]?%d+", i) or
            s:match("^%d+%.?%d*[eE][%+%-]?%d+", i) or s:match("^%d+%.?%d*", i) or
            s:match("^%.%d+", i)
      local str = not tok and (s:match("^\"[^\"\\\n]*\"", i) or s:match("^'[^'\\\n]*'", i))
      if tok then
        local v = tonumber(tok)
        if not v then return nil end
        toks[#toks + 1] = { "num", v }
      elseif str then             -- a string without escapes: only func's first argument
        tok = str
        toks[#toks + 1] = { "str", str:sub(2, -2) }
      else
        tok = s:match("^[%a_][%w_]*", i)
        if tok then
          if tok == "and" or tok == "or" or tok == "not" then toks[#toks + 1] = { "op", tok }
          elseif tok == "true" or tok == "false" then toks[#toks + 1] = { "bool", tok == "true" }
          elseif KEYWORDS[tok] then return nil
          else toks[#toks + 1] = { "name", tok } end
        else
          if s:match("^%-%-", i) then return nil end   -- a comment: Lua's business
          tok = s:match("^//", i) or s:match("^[<>=~]=", i) or s:match("^[%+%-%*/%%%^<>%(%),%.]", i)
          if not tok or tok == "=" then return nil end
          toks[#toks + 1] = { "op", tok }
        end
      end
      i = i + #tok
    end
  end
  return toks
end

--- Parses a Lua expression into a tree, or returns nil when it uses
-- anything outside arithmetic, comparisons, logic, names and calls.
function M.parseexpr (s)
  local toks = tokenize(s)
  if not toks then return nil end
  local pos = 1
  local function peek () return toks[pos] end
  local function isop (t, v) return t and t[1] == "op" and t[2] == v end
  local subexpr
  local function primary ()
    local t = toks[pos]
    if not t then return nil end
    pos = pos + 1
    if t[1] == "num" then return { "num", t[2] }
    elseif t[1] == "bool" then return { "bool", t[2] }
    elseif isop(t, "(") then
      local e = subexpr(0)
      if not e or not isop(peek(), ")") then return nil end
      pos = pos + 1
      return { "paren", e }
    elseif t[1] == "name" then
      local node = { "name", t[2] }
      if isop(peek(), ".") then
        pos = pos + 1
        local f = toks[pos]
        if not f or f[1] ~= "name" then return nil end
        pos = pos + 1
        node = { "field", t[2], f[2] }
      end
      if isop(peek(), "(") then
        pos = pos + 1
        local args = {}
        local first = toks[pos]      -- func("name", x): a string, and only there
        if node[1] == "name" and node[2] == "func" and first and first[1] == "str" and
           isop(toks[pos + 1], ",") then
          args[1] = { "str", first[2] }
          pos = pos + 2
        end
        if #args == 0 and isop(peek(), ")") then pos = pos + 1
        else
          while true do
            local a = subexpr(0)
            if not a then return nil end
            args[#args + 1] = a
            local sep = peek()
            pos = pos + 1
            if isop(sep, ")") then break end
            if not isop(sep, ",") then return nil end
          end
        end
        return { "call", node, args }
      end
      return node
    end
    return nil
  end
  function subexpr (limit)
    local left
    local t = peek()
    if isop(t, "-") or isop(t, "not") then
      pos = pos + 1
      local e = subexpr(UNARY)
      if not e then return nil end
      if t[2] == "-" and e[1] == "num" then left = { "num", -e[2] }   -- folded, as Lua does
      else left = { "un", t[2], e } end
    else
      left = primary()
      if not left then return nil end
    end
    while true do
      t = peek()
      local p = t and t[1] == "op" and PRIO[t[2]]
      if not p or p[1] <= limit then break end
      pos = pos + 1
      local right = subexpr(p[2])
      if not right then return nil end
      left = { "bin", t[2], left, right }
    end
    return left
  end
  local e = subexpr(0)
  if not e or pos <= #toks then return nil end
  return e
end

local F1 = { abs = 0, floor = 1, ceil = 2, sqrt = 3, exp = 4, log = 5, sin = 6, cos = 7,
             tan = 8, asin = 9, acos = 10, atan = 11 }
local F2 = { min = 12, max = 13, fmod = 14, atan = 15 }

-- Machine code for a tree (M.gen) -------------------------------------------------------
-- The generator's state `g`: `out` (the code, flat {op, a, k}), `formals` (names to
-- argument indices), `E` (the other names) and `lib` (what calls are known by, M.library).
-- Each function below generates one node and returns its type as M.gen does, or nil.

local gen      -- the code of any node: one case a node kind (GEN, below)

local function emit (g, op, a, k)
  local out = g.out
  out[#out + 1] = op; out[#out + 1] = a or 0; out[#out + 1] = k or 0
  return #out // 3 - 1
end

local function isnum (t) return t == "n" or t == "i" end

-- which function a call names
local function fnof (g, node)
  local formals, E, lib = g.formals, g.E, g.lib
  local f
  if node[1] == "name" then
    if formals[node[2]] then return nil end
    f = E[node[2]]
  elseif node[1] == "field" then
    if formals[node[2]] then return nil end
    local base = E[node[2]]
    if type(base) ~= "table" then return nil end
    f = base[node[3]]
  end
  if f == nil then return nil end
  if f == lib.ran then return "ran" elseif f == lib.nran then return "nran" end
  if lib.func ~= nil and f == lib.func then return "func" end
  if lib.isfunc ~= nil and lib.isfunc(f) then return "fn", f end
  for name, v in pairs(lib.math) do
    if v == f and (F1[name] or F2[name]) then return name end
  end
  return nil
end

-- a number: "i" for an integer (none beyond 2^53, which a double cannot hold), else "n"
local function number (g, v)
  if mathtype(v) == "integer" then
    if v > 2 ^ 53 or v < -2 ^ 53 then return nil end
    emit(g, OP.K, 0, v)
    return "i"
  end
  emit(g, OP.K, 0, v)
  return "n"
end

-- a positional function (an lsys.Func) applied to the value of tree `a`
local function applyfn (g, f, a)
  if f == nil or not isnum(gen(g, a)) then return nil end
  emit(g, OP.FN, g.lib.index(f))
  return "n"
end

-- func(ID, x) and func("name", x): ID a number in the text or in env
local function funcall (g, args)
  if #args ~= 2 then return nil end
  local id, f = args[1], nil
  if id[1] == "str" then f = g.lib.byname[id[2]]
  else
    local v = id[1] == "num" and id[2] or id[1] == "name" and not g.formals[id[2]] and
              g.E[id[2]]
    if type(v) == "number" then f = g.lib.list[v] end
  end
  return applyfn(g, f, args[2])
end

-- ran, nran and the math functions that the machine has, their arguments generated
local function mathcall (g, name, args)
  local fold = (name == "min" or name == "max") and #args >= 2
  local types = {}
  for k, a in ipairs(args) do
    types[k] = gen(g, a)
    if not isnum(types[k]) then return nil end
    -- min and max fold from the left as Lua's do (it matters with nan: min(3, nan, 2)
    -- is 2 in Lua, min(3, min(nan, 2)) would be 3)
    if fold and k >= 2 then emit(g, OP.F2, F2[name]) end
  end
  -- the result's type as Lua has it ("i": may be an integer, so the integer checks
  -- of `bin` keep arithmetic between two of them in Lua): floor and ceil give integers,
  -- min and max return one of their arguments as it is, abs keeps an integer, and
  -- fmod of two integers is an integer fmod that raises on 0: not on the machine
  local anyint, allint = false, #args > 0
  for _, a in ipairs(types) do
    if a == "i" then anyint = true else allint = false end
  end
  if name == "ran" then
    if #args == 0 then emit(g, OP.K, 0, 1) elseif #args ~= 1 then return nil end
    emit(g, OP.RAN); return "n"
  elseif name == "nran" then
    if #args ~= 2 then return nil end
    emit(g, OP.NRAN); return "n"
  elseif fold then
    return anyint and "i" or "n"
  elseif name == "atan" and #args == 2 then emit(g, OP.F2, F2.atan); return "n"
  elseif name == "fmod" and #args == 2 then
    if allint then return nil end
    emit(g, OP.F2, F2.fmod); return "n"
  elseif F1[name] and #args == 1 then
    emit(g, OP.F1, F1[name])
    if name == "floor" or name == "ceil" or (name == "abs" and anyint) then return "i" end
    return "n"
  end
  return nil
end

-- One function a node kind of the tree (M.parseexpr's nodes).
local GEN = {}

function GEN.num (g, n) return number(g, n[2]) end

function GEN.bool (g, n) emit(g, OP.K, 0, n[2] and 1 or 0); return "b" end

function GEN.paren (g, n) return gen(g, n[2]) end

-- a formal parameter, or a number or boolean in env
function GEN.name (g, n)
  local a = g.formals[n[2]]
  if a then emit(g, OP.ARG, a); return "n" end
  local v = g.E[n[2]]
  if type(v) == "number" then return number(g, v) end
  if type(v) == "boolean" then emit(g, OP.K, 0, v and 1 or 0); return "b" end
  return nil
end

-- t.x: a number in a table of env
function GEN.field (g, n)
  if g.formals[n[2]] then return nil end
  local base = g.E[n[2]]
  local v = type(base) == "table" and base[n[3]]
  if type(v) == "number" then return number(g, v) end
  return nil
end

function GEN.un (g, n)
  local t = gen(g, n[3])
  if n[2] == "-" and t == "n" then emit(g, OP.UNM); return "n" end   -- not integers: they wrap
  if n[2] == "not" and t == "b" then emit(g, OP.NOT); return "b" end
  return nil
end

-- and, or (a jump over the right side), ==, ~=, arithmetic and order comparisons
function GEN.bin (g, n)
  local op = n[2]
  if op == "and" or op == "or" then
    if gen(g, n[3]) ~= "b" then return nil end
    local j = emit(g, op == "and" and OP.JF or OP.JT, 0)
    if gen(g, n[4]) ~= "b" then return nil end
    g.out[3 * j + 2] = #g.out // 3
    return "b"
  end
  local ta = gen(g, n[3])
  local tb = ta and gen(g, n[4])
  if not tb then return nil end
  if op == "==" or op == "~=" then
    if (ta == "b") ~= (tb == "b") then return nil end
    emit(g, OP[op]); return "b"
  end
  if not isnum(ta) or not isnum(tb) then return nil end
  if ta == "i" and tb == "i" and op ~= "/" and op ~= "^" and op ~= "<" and op ~= "<=" and
     op ~= ">" and op ~= ">=" then
    return nil                   -- integer arithmetic: Lua's own rules
  end
  emit(g, OP[op])
  return (op == "<" or op == "<=" or op == ">" or op == ">=") and "b" or "n"
end

-- a call of ran, nran, a math function that the machine has, or a positional function
function GEN.call (g, n)
  local name, fobj = fnof(g, n[2])
  local args = n[3]
  if not name then return nil end
  if name == "func" then return funcall(g, args) end
  if name == "fn" then
    if #args ~= 1 then return nil end
    return applyfn(g, fobj, args[1])
  end
  return mathcall(g, name, args)
end

gen = function (g, n)
  local f = GEN[n[1]]
  if f then return f(g, n) end
  return nil
end

--- Generates machine code for tree `e` into `out` (flat {op, a, k}).
-- `formals` maps names to argument indices; `E` resolves other names;
-- `lib` holds Lua's math table (math) and the model's functions (ran, nran).
-- Returns the type ("n" float, "i" integer constant, "b" boolean) or nil when
-- the expression is not compilable. Lua computes integer op integer in
-- integers (wrapping, raising on // 0): such expressions stay in Lua, as do
-- integers beyond 2^53 that a double cannot hold.
function M.gen (e, out, formals, E, lib)
  return gen({ out = out, formals = formals, E = E, lib = lib }, e)
end

--- What `gen` calls by identity, for one binding of a model's rules: Lua's math table,
-- the model's ran and nran and its func (from `E`), and its positional functions: `list`
-- (func(ID, x)) and `byname` (func("name", x)). lib.fns collects the Funcs the code
-- calls, in the order of their LSYS_OP_FN indices (rules:setfuncs).
function M.library (E, list, byname)
  local lib = { math = math, ran = E.ran, nran = E.nran, func = E.func, isfunc = isfunc,
                list = list, byname = byname, fns = {}, fnidx = {} }
  function lib.index (f)
    local k = lib.fnidx[f]
    if k == nil then
      k = #lib.fns
      lib.fns[k + 1] = f
      lib.fnidx[f] = k
    end
    return k
  end
  return lib
end

--- The functions a rule's text calls with a constant first argument, for the check when
-- derivation starts: { {"name", "internode"}, {"id", 2}, ... }.
function M.funcrefs (text)
  local refs = {}
  for q, name in text:gmatch("%f[%w_]func%s*%(%s*([\"'])(.-)%1") do
    if q then refs[#refs + 1] = { "name", name } end
  end
  for id in text:gmatch("%f[%w_]func%s*%(%s*(%d+%.?%d*)%s*,") do
    refs[#refs + 1] = { "id", tonumber(id) }
  end
  return refs
end

--- The code of a rule's expressions for the C machine (rules:setvm), or nil when one of
-- them stays in Lua. `trees` is what `rule` returned (nil: an expression did not parse);
-- `E` is the lookup table of the model's env (lsys.model), read now: the code is made
-- again each time the model binds its rules. The condition comes first and ends in COND
-- (a number is true unless it is 0, as in the closure); each value then ends in RET.
function M.machine (trees, E, lib)
  local t = trees
  local code, ok = {}, t ~= nil
  if ok then
    lib = lib or M.library(E, {}, {})
    if t.cond then
      local ty = M.gen(t.cond, code, t.formals, E, lib)
      if ty == "n" or ty == "i" then
        code[#code + 1] = OP.K; code[#code + 1] = 0; code[#code + 1] = 0
        code[#code + 1] = OP["~="]; code[#code + 1] = 0; code[#code + 1] = 0
      elseif ty ~= "b" then ok = false end
      code[#code + 1] = OP.COND; code[#code + 1] = 0; code[#code + 1] = 0
    end
    for _, e in ipairs(t.exprs) do
      local ty = ok and M.gen(e, code, t.formals, E, lib)
      if ty ~= "n" and ty ~= "i" then ok = false end
      code[#code + 1] = OP.RET; code[#code + 1] = 0; code[#code + 1] = 0
    end
  end
  return ok and code or nil
end

return M
