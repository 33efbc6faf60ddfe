--- The Lua text of cpfg's expressions and statements (trees of lsys.cpfg.parse), for the
-- translator, lsys.cpfg.translate. A context `ctx` says how: its mode, "s" for a rule
-- string (env's names and the helpers' bare; NOSTRING is raised where only a function
-- can do: a statement, a variable that productions assign) or "f" for the source of a
-- function rule or hook (E.x for env, H.x for lsys.cpfg.helpers, L.x for its locals);
-- scope (the L-system whose variables and arrays it sees), params, locals and subst (in
-- mode "s", the expression of a local, in its place). The translation's state T gives
-- the variables and arrays (vars, arrays, arraykeys, glob, dyn), P for positions and
-- undefined (the warning for a name not defined), and learns usesfunc.
-- @module lsys.cpfg.emit
local ipairs, error, tonumber = ipairs, error, tonumber
local math, string = math, string
local concat = table.concat
local format = string.format
local codegen = require "lsys.codegen"
local _ENV = nil

local M = {}

local NOSTRING = {}   -- raised to give up the rule-string form of a rule

-- Raises an error of the file, "file:line: message" for the position `pos`, as the table
-- { cpfg = true, msg = ... } that lsys.cpfg turns into its message.
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

-- For the translator: NOSTRING, fail and numlit, which it shares; the text of an
-- expression (emit: the text and its kind, "n" number or "b" boolean; N as a number, B as
-- a condition) and of a list of statements (appended to `out`, each line indented `ind`).
M.NOSTRING, M.fail, M.numlit = NOSTRING, fail, numlit
M.emit, M.N, M.B, M.statements = emit, N, B, statements

return M
