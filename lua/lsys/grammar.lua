--- Rule compilation: turns the parts of a parsed rule into a C successor
-- template plus, when needed, one Lua closure (DESIGN.md §3-5).
--
-- The closure returns `true` followed by the computed values (the weight
-- first when it is an expression, then each distinct parameter
-- expression), or `false` when the condition fails. Rules without a
-- condition and without computed values get no closure at all.
-- @module lsys.grammar
local core = require "lsys.core"

local type, tostring, tonumber, pairs, ipairs, error, load, select =
      type, tostring, tonumber, pairs, ipairs, error, load, select
local format, concat, insert, table_sort = string.format, table.concat, table.insert, table.sort
local _ENV = nil

local M = {}

local KEYWORDS = {}
for w in ("and break do else elseif end false for function goto if in local nil not " ..
          "or repeat return then true until while"):gmatch("%a+") do KEYWORDS[w] = true end
M.KEYWORDS = KEYWORDS

local PROD, DECOMP, HOMO = 0, 1, 2
M.PROD, M.DECOMP, M.HOMO = PROD, DECOMP, HOMO
local PS_CONST, PS_ARG, PS_VAL = 0, 1, 2

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
      local before = expr:sub(1, s - 1):match("(%S)%s*$")
      if not KEYWORDS[name] and before ~= "." and before ~= ":" and not bound[name] then
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
-- return function(formals) ... end end`, all on one line so that runtime
-- messages say ':1:'.
local function factorysource (formals, cond, exprs, frees)
  local ups = {}
  for name in pairs(frees) do ups[#ups + 1] = name end
  table_sort(ups)
  local head = {}
  for _, name in ipairs(ups) do head[#head + 1] = format("local %s = E[%q];", name, name) end
  local body = {}
  if cond then
    body[#body + 1] = format("local c_ = (%s); if c_ ~= true then if not c_ or c_ == 0 then " ..
      "return false end; if type_(c_) ~= 'number' then error_('condition is ' .. type_(c_) .. " ..
      "', not a boolean or number', 0) end end;", cond)
  end
  local vals = {}
  for k, e in ipairs(exprs) do vals[k] = "(" .. e .. ")" end
  body[#body + 1] = "return true" .. (#vals > 0 and ", " .. concat(vals, ", ") or "")
  return "local E, type_, error_ = ...; " .. concat(head, " ") ..
         " return function(" .. concat(formals, ", ") .. ") " .. concat(body, " ") .. " end"
end

--- Compiles one rule.
-- `r` is the table from rules:parse; `info` = { label = ..., kind = ...,
-- sub = ..., group = ..., fn = function or nil }.
-- Returns the spec for rules:add and the factory (or nil): factory(E)
-- returns the closure bound to the environment lookup E.
function M.compile (r, info)
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
  addformals(r.lc); addformals({r.pred}); addformals(r.rc)
  local spec = { lc = {}, rc = {}, pred = { r.pred.sym, #r.pred.params }, succ = {}, src = {},
                 flags = 0, nvals = 0, id = info.id }
  for _, m in ipairs(r.lc) do insert(spec.lc, m.sym); insert(spec.lc, #m.params) end
  for _, m in ipairs(r.rc) do insert(spec.rc, m.sym); insert(spec.rc, #m.params) end
  if info.fn then
    if r.cond then fail("a rule with a function has no condition (test it in the function)") end
    spec.flags = core.RF_DYN
    spec.fn = info.fn
    return spec, nil
  end
  local exprs, exprindex = {}, {}
  local weightexpr
  if r.weight then
    local w = r.weight
    if isnumber(w) then
      local x = tonumber(w)
      if not (x >= 0) or x == 1 / 0 then fail("bad weight '%s' (a number >= 0 expected)", w) end
      spec.weight = x
    else
      local msg = checkexpr(w)
      if msg then fail("bad weight '%s': %s", w, msg) end
      weightexpr = w
      exprs[1] = w
      spec.flags = spec.flags | core.RF_WEXPR
    end
    spec.flags = spec.flags | core.RF_STOCH
  end
  for _, m in ipairs(r.succ) do
    insert(spec.succ, m.sym); insert(spec.succ, #m.params)
    for pi, e in ipairs(m.params) do
      if isnumber(e) then
        insert(spec.src, PS_CONST); insert(spec.src, 0); insert(spec.src, tonumber(e))
      elseif seen[e] then
        insert(spec.src, PS_ARG); insert(spec.src, seen[e]); insert(spec.src, 0)
      else
        local msg = checkexpr(e)
        if msg then fail("bad expression '%s' in parameter %d of '%s': %s", e, pi, m.name, msg) end
        local k = exprindex[e]
        if not k then
          exprs[#exprs + 1] = e
          k = #exprs - 1
          exprindex[e] = k
        end
        insert(spec.src, PS_VAL); insert(spec.src, k); insert(spec.src, 0)
      end
    end
  end
  if r.cond then
    local msg = checkexpr(r.cond)
    if msg then fail("bad condition '%s': %s", r.cond, msg) end
  end
  if not r.cond and #exprs == 0 then return spec, nil end
  spec.flags = spec.flags | core.RF_CALL
  spec.nvals = #exprs
  local frees = {}
  if r.cond then M.freenames(r.cond, seen, frees) end
  for _, e in ipairs(exprs) do M.freenames(e, seen, frees) end
  local src = factorysource(formals, r.cond, exprs, frees)
  local factory, msg = load(src, "=" .. label, "t")
  if not factory then fail("%s", msg) end
  return spec, factory, frees
end

return M
