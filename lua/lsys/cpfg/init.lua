--- cpfg's own model files as lsys Models: `lsys.cpfg.load(lfile [, vfile])` preprocesses
-- and parses an L-system file (.l) and translates it to `lsys.lsystem` options. Rules
-- that are pure expressions become rule strings (the expression machine runs them);
-- rules with statement blocks that are more than local assignments become
-- `{ pattern, function }` rules compiled with `load` in a private environment.
-- See docs/cpfg.md.
-- @module lsys.cpfg
local type, pairs, ipairs, error, pcall, load, select, setmetatable, next, tostring, tonumber =
  type, pairs, ipairs, error, pcall, load, select, setmetatable, next, tostring, tonumber
local math, string = math, string
local floor, log, exp, sqrt, min = math.floor, math.log, math.exp, math.sqrt, math.min
local concat, sort = table.concat, table.sort
local format, rep, gsub = string.format, string.rep, string.gsub
local io_write = io.write
local require = require
local cpp = require "lsys.cpfg.cpp"
local parse = require "lsys.cpfg.parse"
local model = require "lsys.model"
local func = require "lsys.func"
local viewmod = require "lsys.view"
local viewfile = require "lsys.viewfile"
local warning = require "lsys.warning"
local core = require "lsys.core"
local codegen = require "lsys.codegen"
local _ENV = nil

local M = {}

local LUA_KEYWORDS = {}
for w in ([[and break do else elseif end false for function goto if in local nil not or
  repeat return then true until while]]):gmatch("%S+") do LUA_KEYWORDS[w] = true end

-- names an env variable may not take (they would hide lsys's own)
local TAKEN = { ran = true, nran = true, func = true }
for k in pairs(model.BUILTIN) do TAKEN[k] = true end

local NOSTRING = {}   -- raised to give up the rule-string form of a rule

-- Names a #define kept as a name may not have (lsys.cpfg.import): lsys's own, cpfg's
-- reserved words, Lua's keywords, the derivation length's Q and Z.
local function untakable ()
  local t = { Q = true, Z = true }
  for k in pairs(TAKEN) do t[k] = true end
  for k in pairs(LUA_KEYWORDS) do t[k] = true end
  for k in pairs(parse.RESERVED) do t[k] = true end
  return t
end

local function fail (T, pos, fmt, ...)
  local file, line = T.P:where(pos)
  error({ cpfg = true, msg = format("%s:%d: " .. fmt, file, line, ...) }, 0)
end

-- A number as source text for rule strings and for Lua alike (a block's closure has no
-- `math`): 2.21e308 in a file is infinite.
local function numlit (v)
  if v ~= v then return "(0.0/0.0)" end
  if v == math.huge then return "(1.0/0.0)" end
  if v == -math.huge then return "(-1.0/0.0)" end
  local s = format("%.17g", v)
  if not s:find("[%.eEn]") then s = s .. ".0" end
  return s
end

-- Helpers (cpfg's semantics where Lua's differ) ---------------------------------------

local function trunc (x) return x >= 0 and floor(x) or -floor(-x) end

local H = {}
-- % on the integer parts, as C's (int)a % (int)b
function H._rem (a, b)
  local ia, ib = trunc(a), trunc(b)
  if ib == 0 then error("cpfg: % by zero (integer part of the right operand is 0)", 0) end
  return math.fmod(ia, ib) + 0.0
end
function H._sign (x) return x == 0 and 0.0 or x > 0 and 1.0 or -1.0 end
-- beta distribution (Cheng's algorithm BA), as cpfg's bran
function H._bran (a, b)
  local s = a + b
  local lambda = min(a, b) <= 1 and min(a, b) or sqrt((2 * a * b - s) / (s - 2))
  local u = a + lambda
  local ym, n
  n = 0
  repeat
    local u1, u2
    repeat u1 = core.ran(1) until u1 ~= 0
    repeat u2 = core.ran(1) until u2 ~= 0
    local v = (1 / lambda) * log(u1 / (1 - u1))
    ym = a * exp(v)
    n = n + 1
    if n > 1e6 then error("cpfg: bran(" .. a .. ", " .. b .. ") does not converge", 0) end
  until not (s * log(s / (b + ym)) + u * v - log(4) < log(u1 * u1 * u2))
  return ym / (b + ym)
end
-- binomial: n coin flips with probability p, as cpfg's biran
function H._biran (n, p)
  n = trunc(n)
  if n > 1e7 then error("cpfg: biran: n is " .. n .. ", more than 1e7", 0) end
  local j = 0
  for _ = 1, n do if core.ran(1) <= p then j = j + 1 end end
  return j + 0.0
end
local function aindex (a, ...)
  local n = select("#", ...)
  if n ~= #a.dims then
    error(format("cpfg: array %s has %d dimensions, not %d", a.name, #a.dims, n), 0)
  end
  local k = 0
  for d = 1, n do
    local x = select(d, ...)
    local i = trunc(x)
    if not (i >= 0 and i < a.dims[d]) then
      if x ~= x then                            -- cpfg's own result is undefined
        error(format("cpfg: index %g out of range 0..%d of array %s", x, a.dims[d] - 1,
                     a.name), 0)
      end
      -- cpfg takes the nearest element, with a warning (generate.c, tARRAYREF)
      i = x < 0 and 0 or a.dims[d] - 1
      if not a.warned then
        a.warned = true
        warning.warn(format("%sarray %s: index %g out of range 0..%d; %d used, as cpfg does "
                            .. "(said once per array and derivation)", a.where or "cpfg: ",
                            a.name, x, a.dims[d] - 1, i))
      end
    end
    k = k * a.dims[d] + i
  end
  return k
end
function H._aget (a, ...) return a.v[aindex(a, ...)] end
function H._aset (a, x, ...) a.v[aindex(a, ...)] = x end
function H._stop () return 0.0 end
-- One conversion of printf; without its flags, width and precision when Lua's format
-- refuses them (a width over 99, '#' with %d: C's printf takes them).
local function cformat (spec, c, x)
  local ok, s = pcall(format, "%" .. spec .. c, x)
  if ok then return s end
  return format("%" .. c, x)
end
-- printf: C's format on numbers; %d and the other integer conversions take the integer
-- part; length modifiers (%lf, %ld) are accepted and mean nothing, as for C's printf of
-- a double
-- (string.gsub itself, not the rules' guarded view of it: the pattern is the loader's,
-- linear in the format's length, which the guard's bound for any pattern overstates)
function H._printf (fmt, ...)
  local args, i = { ... }, 0
  local out = gsub(fmt, "%%([-+ #0]*%d*%.?%d*)[hlLqjzt]*([diouxXcfFeEgGs%%])", function (flags, c)
    if c == "%" then return "%" end
    i = i + 1
    local x = args[i] or 0
    if c:find("[diouxXc]") then
      x = trunc(x)
      if c == "i" or c == "u" then c = "d" end
      return cformat(flags, c, math.tointeger(x) or 0)
    end
    if c == "s" then return "" end
    return cformat(flags, c, x)
  end)
  io_write(out)
  return 0.0
end
function H._loop () error("cpfg: a loop ran 100000000 times", 0) end
for k, v in pairs(model.BUILTIN) do H[k] = v end
H.ran, H.nran, H.produce = core.ran, core.nran, core.produce
H._try, H._resume = core.cpfg_try, core.cpfg_resume

-- Expressions --------------------------------------------------------------------------

local emit

local function num (code, kind) if kind == "b" then return "(" .. code .. " and 1.0 or 0.0)" end
  return code end
local function bool (code, kind) if kind == "n" then return "(" .. code .. " ~= 0)" end
  return code end

local function N (T, ctx, e) return num(emit(T, ctx, e)) end
local function B (T, ctx, e) return bool(emit(T, ctx, e)) end

-- a function or constant of H, by its name in the rule string's environment
local function fn (ctx, name) return ctx.mode == "f" and "H." .. name or name end

local function nostring (ctx) if ctx.mode == "s" then error(NOSTRING, 0) end end

-- The Lua text of variable `name` in `ctx`, or nil when it is not a variable here.
local function var (T, ctx, name, write)
  if ctx.subst and ctx.subst[name] and not write then return ctx.subst[name] end
  if ctx.params and ctx.params[name] then return ctx.params[name] end
  if ctx.locals and ctx.locals[name] then
    nostring(ctx)              -- read before it is ever set: 0, as cpfg's variables start
    return write and "L." .. ctx.locals[name] or "(L." .. ctx.locals[name] .. " or 0.0)"
  end
  local key = T.vars[ctx.scope][name] or T.glob[name]
  if key then
    if T.arraykeys[key] then return nil end
    if ctx.mode == "s" and T.dyn[key] then nostring(ctx) end
    return ctx.mode == "f" and "E." .. key or key
  end
end

-- C's escape sequences in a string literal (printf's format): \n \t \\ \" and the others.
local CESC = { n = "\n", t = "\t", r = "\r", a = "\a", b = "\b", f = "\f", v = "\v",
               ["\\"] = "\\", ['"'] = '"', ["'"] = "'", ["?"] = "?" }
local function cescapes (s)
  local out, i = {}, 1
  while i <= #s do
    local c = s:sub(i, i)
    if c == "\\" and i < #s then
      local o = s:match("^[0-7][0-7]?[0-7]?", i + 1)
      if o then
        out[#out + 1] = string.char(tonumber(o, 8) % 256)
        i = i + 1 + #o
      else
        local e = s:sub(i + 1, i + 1)
        out[#out + 1] = CESC[e] or "\\" .. e
        i = i + 2
      end
    else
      out[#out + 1] = c
      i = i + 1
    end
  end
  return concat(out)
end

local ARGS = { sin = 1, cos = 1, tan = 1, asin = 1, acos = 1, atan = 1, exp = 1,
               log = 1, floor = 1, ceil = 1, sqrt = 1, fabs = 1, trunc = 1, sign = 1, ran = 1,
               nran = 2, bran = 2, biran = 2, func = 2, stop = 1, atan2 = 2 }

local function call (T, ctx, e)
  local f, a = e.f, e.args
  if f == "printf" then
    if #a == 0 or a[1].k ~= "str" then fail(T, e.pos, "printf needs a format string first") end
    local parts = { codegen.string(cescapes(a[1].v)) }
    for i = 2, #a do parts[i] = N(T, ctx, a[i]) end
    return fn(ctx, "_printf") .. "(" .. concat(parts, ", ") .. ")", "n"
  end
  if f == "srand" then         -- a statement: only in the function form
    nostring(ctx)
    if #a ~= 1 then fail(T, e.pos, "srand takes 1 argument, not %d", #a) end
    return "H._srand(" .. N(T, ctx, a[1]) .. ")", "n"
  end
  local n = ARGS[f]
  if not n then fail(T, e.pos, "the function %s is not supported", f) end
  if #a ~= n then
    fail(T, e.pos, "%s takes %d argument%s, not %d", f, n, n == 1 and "" or "s", #a)
  end
  local x = N(T, ctx, a[1])
  local y = a[2] and N(T, ctx, a[2])
  local p = fn(ctx, "pi")
  if f == "sin" or f == "cos" or f == "tan" then
    return fn(ctx, f) .. "(" .. x .. " * " .. p .. " / 180.0)", "n"
  elseif f == "asin" or f == "acos" or f == "atan" then
    return "(" .. fn(ctx, f) .. "(" .. x .. ") * 180.0 / " .. p .. ")", "n"
  elseif f == "atan2" then     -- C's atan2(y, x), in degrees (cpfg's grammar rejects it)
    return "(" .. fn(ctx, "atan") .. "(" .. x .. ", " .. y .. ") * 180.0 / " .. p .. ")", "n"
  elseif f == "fabs" then return fn(ctx, "abs") .. "(" .. x .. ")", "n"
  elseif f == "trunc" then return fn(ctx, "floor") .. "(" .. x .. " + 0.5)", "n"
  elseif f == "sign" then return fn(ctx, "_sign") .. "(" .. x .. ")", "n"
  elseif f == "bran" or f == "biran" then
    return fn(ctx, "_" .. f) .. "(" .. x .. ", " .. y .. ")", "n"
  elseif f == "stop" then return fn(ctx, "_stop") .. "(" .. x .. ")", "n"
  elseif f == "func" then
    if ctx.mode == "f" then T.usesfunc = true end
    return fn(ctx, "func") .. "(" .. x .. ", " .. y .. ")", "n"
  end
  return fn(ctx, f) .. "(" .. x .. (y and ", " .. y or "") .. ")", "n"
end

local CMP = { ["=="] = "==", ["!="] = "~=", ["<"] = "<", ["<="] = "<=", [">"] = ">",
              [">="] = ">=" }

emit = function (T, ctx, e)
  local k = e.k
  if k == "num" then return numlit(e.v), "n"
  elseif k == "name" then
    local v = var(T, ctx, e.n)
    if v then return v, "n" end
    if T.arrays[ctx.scope][e.n] then fail(T, e.pos, "array %s used without an index", e.n) end
    T.undefined(e.n, e.pos)
    return "0.0", "n"
  elseif k == "index" then
    local key = T.arrays[ctx.scope][e.n]
    if not key then fail(T, e.pos, "%s is not an array (define: { array %s[N]; })", e.n, e.n) end
    local parts = { ctx.mode == "f" and "E." .. key or key }
    for i, x in ipairs(e.idx) do parts[i + 1] = N(T, ctx, x) end
    return fn(ctx, "_aget") .. "(" .. concat(parts, ", ") .. ")", "n"
  elseif k == "str" then   -- its number among the file's strings, as cpfg (@L("%.f", x))
    return numlit(e.index), "n"
  elseif k == "call" then return call(T, ctx, e)
  elseif k == "un" then
    if e.op == "-" then return "(-" .. N(T, ctx, e.a) .. ")", "n" end
    return "(not " .. B(T, ctx, e.a) .. ")", "b"
  elseif k == "cond" then
    return "(" .. B(T, ctx, e.c) .. " and " .. N(T, ctx, e.a) .. " or " .. N(T, ctx, e.b) .. ")",
           "n"
  end
  local op = e.op
  if op == "&&" or op == "||" then
    return "(" .. B(T, ctx, e.a) .. (op == "&&" and " and " or " or ") .. B(T, ctx, e.b) .. ")",
           "b"
  elseif CMP[op] then
    return "(" .. N(T, ctx, e.a) .. " " .. CMP[op] .. " " .. N(T, ctx, e.b) .. ")", "b"
  elseif op == "%" then
    return fn(ctx, "_rem") .. "(" .. N(T, ctx, e.a) .. ", " .. N(T, ctx, e.b) .. ")", "n"
  end
  return "(" .. N(T, ctx, e.a) .. " " .. op .. " " .. N(T, ctx, e.b) .. ")", "n"
end

-- Statements (function form) ------------------------------------------------------------

local statements

local function assign (T, ctx, s, out, ind)
  local lhs = s.lhs
  local value = N(T, ctx, s.e)
  if lhs.k == "index" then
    local key = T.arrays[ctx.scope][lhs.n]
    if not key then fail(T, lhs.pos, "%s is not an array", lhs.n) end
    local parts = { "E." .. key, value }
    for i, x in ipairs(lhs.idx) do parts[i + 2] = N(T, ctx, x) end
    out[#out + 1] = ind .. "H._aset(" .. concat(parts, ", ") .. ")"
    return
  end
  local target = var(T, ctx, lhs.n, true)
  if not target then
    if T.arrays[ctx.scope][lhs.n] then fail(T, lhs.pos, "cannot assign to array %s", lhs.n) end
    fail(T, lhs.pos, "cannot assign to %s", lhs.n)
  end
  out[#out + 1] = ind .. target .. " = " .. value
end

statements = function (T, ctx, list, out, ind)
  for _, s in ipairs(list or {}) do
    if s.k == "assign" then assign(T, ctx, s, out, ind)
    elseif s.k == "expr" then out[#out + 1] = ind .. "local _ = " .. emit(T, ctx, s.e)
    elseif s.k == "if" then
      out[#out + 1] = ind .. "if " .. B(T, ctx, s.c) .. " then"
      statements(T, ctx, s.body, out, ind .. "  ")
      if s.other then
        out[#out + 1] = ind .. "else"
        statements(T, ctx, s.other, out, ind .. "  ")
      end
      out[#out + 1] = ind .. "end"
    elseif s.k == "while" then
      out[#out + 1] = ind .. "while " .. B(T, ctx, s.c) .. " do"
      out[#out + 1] = ind .. "  _n = _n + 1; if _n > 1e8 then H._loop() end"
      statements(T, ctx, s.body, out, ind .. "  ")
      out[#out + 1] = ind .. "end"
    elseif s.k == "do" then
      out[#out + 1] = ind .. "repeat"
      out[#out + 1] = ind .. "  _n = _n + 1; if _n > 1e8 then H._loop() end"
      statements(T, ctx, s.body, out, ind .. "  ")
      out[#out + 1] = ind .. "until not " .. B(T, ctx, s.c)
    end
  end
end

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

-- The translation ----------------------------------------------------------------------------

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
-- productions, as in cpfg. In a decomposition or homomorphism (lsys rewrites one module
-- there) it becomes a declared lsys module name when it is letters with parameters on the
-- last one only; every string then reads it as one module.
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
          if not ok or not text[1]:find("^%a") then
            fail(T, p.pos, "a strict predecessor of several modules ('%s') in a decomposition or "
                 .. "homomorphism is supported only as letters and digits with parameters on "
                 .. "the last one", concat(text))
          end
          local name = concat(text)
          if not names[name] then names[name] = true; list[#list + 1] = name end
          local last = p.pred[#p.pred]
          p.pred = { { sym = name, params = last.params, pos = p.pred[1].pos } }
        end
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
local function translate (P, lsystems, opts)
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
  local main = lsystems[1]
  if main.dlength then
    T.glob.Q, T.glob.Z = "Q", "Z"
    T.env.Q = 0.0
  end
  variables(T, lsystems)
  local steps = 1
  if main.dlength then
    steps = consteval(T, main.dlength, 1, "the derivation length")
    if steps < 0 or steps > model.MAX_STEPS then         -- lsys's limit
      fail(T, main.dlengthpos, "the derivation length is %g, not 0 to %d", steps,
           model.MAX_STEPS)
    end
    steps = floor(steps)
    T.env.Z = steps + 0.0
  end
  dynamic(T, lsystems)
  atrules(T, lsystems)
  local declared = declare(T, lsystems)
  T.modnames = #declared > 0 and concat(declared, " ") or nil
  local o = { steps = steps, env = T.env, name = opts.name, modules = T.modnames }
  if float32() then o.numbers = "float32" end
  local stoch = main.seed ~= nil
  if main.seed then o.seed = floor(consteval(T, main.seed, 1, "the seed")) end
  o.ring = main.ring or nil
  o.ignore, o.consider = main.ignore, main.consider
  local actx = { mode = "s", scope = 1 }
  -- the axiom is evaluated after the start hook (the Start: blocks), as in cpfg
  local ok, ax = pcall(successor, T, actx, main.axiom)
  if not ok then
    if ax == NOSTRING then fail(T, main.axiompos, "the axiom reads a variable set by a "
                                .. "production") end
    error(ax, 0)
  end
  o.axiom = ax
  o.productions = rules(T, main, main.productions, "productions", stoch)
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
  -- sub-L-systems
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
  -- hooks
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
  -- the blocks are the file's code: they run within the model's bounds, as its rules do
  -- (max_instructions for each block, max_memory; docs/manual.md §4)
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
  local startblocks = bounded(starts, "Start")
  o.start = function (m)
    T.model = m
    reset()
    startblocks(m)
  end
  if #each > 0 then o.start_each = bounded(each, "StartEach") end
  if #ends > 0 then o.end_each = bounded(ends, "EndEach") end
  if #finish > 0 then o.finish = bounded(finish, "End") end
  return o, T
end

-- Loading -------------------------------------------------------------------------------------

local function cpfgerror (e)
  if type(e) == "table" and e.cpfg then return e.msg end
  return e
end

-- #define NAME i for the functions of a function set, as cpfg does for func(NAME, x)
local function funcdefines (v)
  local defs = {}
  local fs = v and v.functions
  if type(fs) ~= "table" then return defs end
  local fromset = false
  for _, x in ipairs(fs) do
    local file = type(x) == "table" and x.file or x
    if type(file) == "string" and file:match("%.fset$") then fromset = true end
  end
  if not fromset then return defs end
  local ok, list = pcall(func.collect, fs, v.dir, "functions")
  if not ok then return defs end
  for i, f in ipairs(list) do
    local name = f:name():gsub("%.[^.]*$", "")
    if name:find("^[%a_][%w_]*$") then defs[name] = i end
  end
  return defs
end

local function checkopts (opts, fname)
  if opts == nil then return {} end
  if type(opts) ~= "table" then error(fname .. ": opts must be a table", 3) end
  for k in pairs(opts) do
    if k ~= "cpp" and k ~= "colormap" and k ~= "materials" and k ~= "defines" and
       k ~= "functions" and k ~= "random" and k ~= "environment" then
      error(format("%s: unknown option '%s'", fname, tostring(k)), 3)
    end
  end
  if opts.functions ~= nil and opts.functions ~= "cpfg" and opts.functions ~= "exact" then
    error(format("%s: option 'functions' must be \"cpfg\" or \"exact\"", fname), 3)
  end
  if opts.random ~= nil and opts.random ~= "cpfg" and opts.random ~= "lsys" then
    error(format("%s: option 'random' must be \"cpfg\" or \"lsys\"", fname), 3)
  end
  if opts.environment ~= nil and opts.environment ~= "none" then
    error(format("%s: option 'environment' must be \"none\" (lsys runs no environmental "
                 .. "program)", fname), 3)
  end
  return opts
end

-- An open L-system's ?E modules exchange values with an environmental program that cpfg
-- runs beside the model (cpfg -e; Mech and Prusinkiewicz 1996). lsys runs none, and a
-- model that relies on one would silently draw another plant, so ?E is refused unless
-- the caller asks for cpfg's behaviour without a program (environment = "none": the
-- modules keep the values the rules give them, as `cpfg -g` without -e does).
local function envcheck (P, opts)
  if P.envq and opts.environment ~= "none" then
    P:fail(P.envq, "?E (an environmental program's query module) is not supported: lsys "
           .. "runs no environmental program; environment = \"none\" (--environment none) "
           .. "derives the model as cpfg does without one")
  end
end

-- The view's positional functions as cpfg computes them (lsys.func approx "cpfg"), or
-- nil when the view has none.
local function cpfgfuncs (v)
  if not (v and type(v.functions) == "table") then return nil end
  local list = func.collect(v.functions, v.dir, "view functions")
  local out = {}
  for i, f in ipairs(list) do
    out[i] = f:approx() == "cpfg" and f or
             func.new { points = f:points(), name = f:name(), samples = f:samples(),
                        approx = "cpfg" }
  end
  return out
end

--- A view's `functions` entries marked to be computed as cpfg approximates them
-- ({ file = NAME, samples = N, approx = "cpfg" }), as `lsys import` writes them.
function M.cpfg_functions (list)
  local out = {}
  for i, x in ipairs(list) do
    if type(x) == "table" and x.file then
      out[i] = { file = x.file, samples = x.samples, approx = "cpfg" }
    elseif type(x) == "string" then
      out[i] = { file = x, approx = "cpfg" }
    else
      out[i] = x
    end
  end
  return out
end

--- The lsys.lsystem options of a cpfg L-system file, and the translation's details.
-- opts: cpp ("system", "builtin"; default the system cpp when present), defines
-- ({ NAME = value } for the preprocessor), view (a view table: its function set
-- defines the functions' names, as in cpfg). For lsys.cpfg.import: keep (true: a second
-- result with the Lua source of the function rules, hooks and arrays), names (true: the
-- built-in preprocessor keeps the #defines of plain numbers as names, which the rules
-- read from env; the second result's `defines` lists them, see cpp.builtin).
function M.options (lfile, opts)
  if type(lfile) ~= "string" then error("lsys.cpfg.options: a file name expected", 2) end
  opts = opts or {}
  local ok, o, keep = pcall(function ()
    local defs = funcdefines(opts.view)
    for k, v in pairs(opts.defines or {}) do defs[k] = v end
    local kept = opts.names and { taken = untakable() } or nil
    local lines = kept and cpp.builtin(lfile, defs, kept) or cpp.run(lfile, defs, opts.cpp)
    local P = parse.new(lines)
    local lsystems = P:file()
    envcheck(P, opts)
    local o, T = translate(P, lsystems, { name = lfile, keep = opts.keep, random = opts.random,
                                          globals = kept and kept.values })
    if T.keep then T.keep.defines = kept end
    return o, T.keep
  end)
  if not ok then error(cpfgerror(o), 0) end
  return o, keep
end

--- Loads a cpfg model: the L-system file `lfile` and optionally its view file `vfile`
-- (read with lsys.view.load; contours, surfaces and functions are relative to its
-- folder). opts: colormap or materials (a .map or .mat file, the palette), cpp and
-- defines as for `options`, functions ("cpfg", the default: the view's functions
-- approximated as cpfg does; "exact": lsys's exact values), random ("cpfg", the default:
-- cpfg's random numbers in cpfg's order, on one thread; "lsys": lsys's generator, which
-- does not depend on the order nor on the threads), environment ("none": a model with ?E
-- modules derives as cpfg does without an environmental program; without it such a
-- model is refused). Returns an lsys Model; raises
-- "file:line: message".
function M.load (lfile, vfile, opts)
  if type(lfile) ~= "string" then error("lsys.cpfg.load: a file name expected", 2) end
  if vfile ~= nil and type(vfile) ~= "string" then
    error("lsys.cpfg.load: the view file must be a file name", 2)
  end
  opts = checkopts(opts, "lsys.cpfg.load")
  local v = vfile and viewmod.load(vfile, { missing = "warn" }) or { dir = cpp.dirof(lfile) }
  -- what the view leaves unset (or sets to '?') is cpfg's default, not lsys.view's
  for k, x in pairs(viewfile.CPFG_DEFAULTS) do
    if v[k] == nil then v[k] = x end
  end
  local pal = opts.colormap or opts.materials
  if pal then
    local ldir = cpp.dirof(lfile)
    v = v or { dir = ldir }
    v.palette = (pal:sub(1, 1) == "/" or v.dir == ldir) and pal or ldir .. "/" .. pal
  end
  local o, T
  local ok, err = pcall(function ()
    local defs = funcdefines(v)
    for k, x in pairs(opts.defines or {}) do defs[k] = x end
    local lines = cpp.run(lfile, defs, opts.cpp)
    local P = parse.new(lines)
    local lsystems = P:file()
    envcheck(P, opts)
    o, T = translate(P, lsystems, { name = lfile, random = opts.random })
  end)
  if not ok then error(cpfgerror(err), 0) end
  o.view = v
  if opts.functions ~= "exact" then o.functions = cpfgfuncs(v) end
  o.random = opts.random or "cpfg"      -- cpfg's numbers in cpfg's order (docs/cpfg.md)
  local ok2, m = pcall(model.lsystem, o)
  if not ok2 then
    -- name the cpfg line of a rule lsys refused
    local msg = tostring(m)
    local n, sect = msg:match("entry (%d+) of ([^)]+)%)")
    local pos = sect and T.origin[sect] and T.origin[sect][tonumber(n)]
    if pos then
      local file, line = T.P:where(pos)
      msg = format("%s:%d: %s", file, line, msg)
    end
    error(msg, 0)
  end
  -- messages name the .l file and the production's line, not lsys's list of rules
  m._where = lfile
  for _, info in pairs(m._info) do
    local n, sect = info.label:match("%(entry (%d+) of ([^)]+)%)$")
    local pos = sect and T.origin[sect] and T.origin[sect][tonumber(n)]
    if pos then
      local file, line = T.P:where(pos)
      info.where, info.label = format("%s:%d", file, line), info.label:gsub(" %(entry.*$", "")
    end
  end
  if not vfile then
    m._funchint = "; a cpfg model's functions come from its view file (.v), and none was given"
  end
  T.model = m         -- (srand in Start: blocks run by the axiom, before the start hook)
  if T.usesfunc then T.H.func = function (id, x) return m:func(id, x) end end
  return m
end

--- The files of a vlab object folder, as `load_object` picks them: the L-system file, the
-- view file (or nil) and the palette (a .map or .mat file relative to the folder, or nil),
-- each but the palette with the folder's path in front.
function M.object_files (dir)
  if type(dir) ~= "string" then error("lsys.cpfg.object_files: a folder name expected", 2) end
  local spec = dir .. "/specifications"
  local text, err = cpp.readfile(spec)
  if not text then error("lsys.cpfg.load_object: " .. tostring(err), 0) end
  local files, l, v, pal = {}, nil, nil, nil
  for line in text:gmatch("[^\n]+") do
    local cmd = line:match("^%s*cpfg%s(.*)$")
    if cmd and not l then
      local words = {}
      for w in cmd:gmatch("%S+") do words[#words + 1] = w end
      local i = 1
      while i <= #words do
        local w = words[i]
        if w:match("^%-[mM]1?$") then          -- -m2, -M2: colour map 2, not the palette
          pal = pal or words[i + 1]
          i = i + 1
        elseif w:match("^%-[mM]%d+$") then
          i = i + 1
        elseif w:match("%.l$") then l = l or w
        elseif w:match("%.v$") then v = v or w end
        i = i + 1
      end
    end
  end
  for line in text:gmatch("[^\n]+") do
    if line:match("^ignore:") then break end
    local f = line:match("^(%S+)%s*$")
    if f then files[#files + 1] = f end
  end
  for _, f in ipairs(files) do
    if not l and f:match("%.l$") then l = f end
    if not v and f:match("%.v$") then v = f end
    if not pal and (f:match("%.map$") or f:match("%.mat$")) then pal = f end
  end
  if not l then error(format("%s: no L-system file (.l) named", spec), 0) end
  return dir .. "/" .. l, v and dir .. "/" .. v or nil, pal
end

--- Loads a vlab object folder: its `specifications` file names the files; the first
-- `cpfg` command in it (as in `generate: cpfg -m leaf.map leaf.l leaf.v`) picks the
-- L-system, view and colour map or material file, else the first .l, .v, .map or .mat
-- listed. Returns the Model.
function M.load_object (dir, opts)
  if type(dir) ~= "string" then error("lsys.cpfg.load_object: a folder name expected", 2) end
  opts = checkopts(opts, "lsys.cpfg.load_object")
  local l, v, pal = M.object_files(dir)
  local o2 = {}
  for k, x in pairs(opts) do o2[k] = x end
  if pal and not o2.colormap and not o2.materials then
    if pal:match("%.mat$") then o2.materials = pal else o2.colormap = pal end
  end
  return M.load(l, v, o2)
end

--- cpfg's helper functions as the translated rules call them (H in their Lua source):
-- lsys.cpfg.import's model files use them.
M.helpers = H

-- For lsys.cpfg.import, which writes the same Lua: a number literal as the translated rules
-- hold it, and Lua's reserved words (no variable may take one as its name).
M.numlit = numlit
M.LUA_KEYWORDS = LUA_KEYWORDS

return M
