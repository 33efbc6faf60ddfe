--- What rule code sees of Lua's libraries (docs/manual.md §4, "What rule code can
-- reach"). Rule text may come from someone else (a cpfg file, a service
-- building models from text), so:
--
-- * it is given no library table of the process: `math`, `string` and `table` are
--   read-only proxies of private copies, whose `pairs` walks the copy without handing it
--   out, so `select(2, pairs(math))` reaches nothing that changes the process;
-- * the string functions that can run long inside C without allocating (repetition of
--   an empty string, backtracking patterns) and `table.move` refuse work beyond fixed
--   bounds while rule text runs. The strings' methods (`("x"):rep(n)`) are this copy
--   too while a model's rules run (csrc/lua/lua_sandbox.c swaps the string metatable's
--   __index): Lua's count hook, which bounds the instructions of each call, cannot stop a
--   C function, and the allocator bound (max_memory) cannot stop one that allocates
--   nothing.
--
-- A rule written as a Lua function is the model author's own code: it keeps its own
-- globals, and the string functions check nothing for it (core.sandbox_strict).
-- @module lsys.sandbox
local core = require "lsys.core"

local type, pairs, error, setmetatable, tostring, next, select, math, string, table, _G =
      type, pairs, error, setmetatable, tostring, next, select, math, string, table, _G
local format, sub, find, len = string.format, string.sub, string.find, string.len
local _ENV = nil

local M = {}

--- The most backtracking steps a pattern may need, by its worst case, in rule text.
M.PATTERN_WORK = 1e8
--- The most elements one table.move may copy in rule text.
M.MOVE_MAX = 1e7

local function copy (t, except)
  local c = {}
  for k, v in pairs(t) do if not (except and except[k]) then c[k] = v end end
  return c
end

-- A read-only view of the table `t` (a private copy), named `name` in messages.
local function frozen (t, name)
  return setmetatable({}, {
    __index = t,
    __newindex = function (_, k)
      error(format("cannot change %s.%s in a rule expression", name, tostring(k)), 2)
    end,
    __pairs = function (p) return function (_, k) return next(t, k) end, p, nil end,
    __metatable = false,
  })
end

-- The end of the set that starts at p[i] ('['), or len(p) when it is not closed.
local function setend (p, i)
  i = i + 1
  if sub(p, i, i) == "^" then i = i + 1 end
  repeat                                    -- a ']' first is part of the set
    local c = sub(p, i, i)
    if c == "%" then i = i + 1 end
    i = i + 1
  until i > len(p) or sub(p, i, i) == "]"
  return i
end

--- The most steps Lua's matcher may take for the pattern `p` on a subject of `n`
-- characters: each start position (one when anchored) times the alternatives of the
-- quantified items (n + 1 for `*`, `+`, `-`, a back reference or `%b`; 2 for `?`), an
-- item at the end of the pattern being taken once (nothing after it can fail).
function M.pattern_work (p, n, anchors)
  local k = n + 1.0                        -- a float: the product may be huge
  local i, np, starts = 1, len(p), k
  if anchors and sub(p, 1, 1) == "^" then starts, i = 1, 2 end
  local work, lastfactor, lastend = 1, 1, 0
  while i <= np do
    local c, f = sub(p, i, i), 1
    if c == "(" or c == ")" or (c == "$" and i == np) then
      i = i + 1
    elseif c == "%" and sub(p, i + 1, i + 1) == "b" then
      f, i = k, i + 4
    elseif c == "%" and sub(p, i + 1, i + 1) == "f" then
      i = setend(p, i + 2) + 1
    elseif c == "%" and find(sub(p, i + 1, i + 1), "%d") then
      f, i = k, i + 2
    else
      local j = c == "%" and i + 1 or c == "[" and setend(p, i) or i
      local q = sub(p, j + 1, j + 1)
      if q == "*" or q == "+" or q == "-" then f, i = k, j + 2
      elseif q == "?" then f, i = 2, j + 2
      else i = j + 1 end
    end
    if f > 1 then work, lastfactor, lastend = work * f, f, i end
  end
  if lastend > 0 and find(sub(p, lastend), "^%)*$") then
    work = work / lastfactor                 -- nothing after it: the last item never backtracks
  end
  return starts * work + n
end

local S = copy(string)
local real = { rep = string.rep, find = string.find, match = string.match,
               gmatch = string.gmatch, gsub = string.gsub }
local strict = core.sandbox_strict

local function checkpattern (what, s, p, anchors)
  if type(p) ~= "string" or (type(s) ~= "string" and type(s) ~= "number") then return end
  local w = M.pattern_work(p, #tostring(s), anchors)
  if w > M.PATTERN_WORK then
    local shown = len(p) > 40 and sub(p, 1, 37) .. "..." or p
    error(format("string.%s: the pattern '%s' could take %.3g steps on %d characters " ..
                 "(rule text may take at most %.0f)", what, shown, w, #tostring(s),
                 M.PATTERN_WORK), 3)
  end
end

function S.rep (s, n, sep, ...)
  if strict() and (type(s) == "string" or type(s) == "number") and type(n) == "number"
     and n > 0 and #tostring(s) == 0 and (sep == nil or #tostring(sep) == 0) then
    return ""                                 -- Lua would copy nothing n times
  end
  return real.rep(s, n, sep, ...)
end
function S.find (s, p, init, plain, ...)
  if strict() and not plain then checkpattern("find", s, p, true) end
  return real.find(s, p, init, plain, ...)
end
function S.match (s, p, ...)
  if strict() then checkpattern("match", s, p, true) end
  return real.match(s, p, ...)
end
function S.gmatch (s, p, ...)
  if strict() then checkpattern("gmatch", s, p, false) end
  return real.gmatch(s, p, ...)
end
function S.gsub (s, p, ...)
  if strict() then checkpattern("gsub", s, p, true) end
  return real.gsub(s, p, ...)
end
core.sandbox_strings(S)

local T = copy(table)
local move = table.move
function T.move (a, f, e, t, ...)
  if type(f) == "number" and type(e) == "number" and e - f + 1 > M.MOVE_MAX then
    error(format("table.move: %.0f elements is more than rule text may move (%.0f)",
                 e - f + 1, M.MOVE_MAX), 2)
  end
  return move(a, f, e, t, ...)
end

--- Names usable in rule expressions besides `env` (lsys.BUILTIN): Lua's math functions
-- (radians, as in Lua), `pi`, the library views, and a few base functions. No
-- `math.randomseed` (rule code draws from the model's seeded ran and nran).
M.BUILTIN = {
  math = frozen(copy(math, { randomseed = true }), "math"),
  string = frozen(S, "string"), table = frozen(T, "table"),
  pi = math.pi, huge = math.huge,
  abs = math.abs, floor = math.floor, ceil = math.ceil, sqrt = math.sqrt, exp = math.exp,
  log = math.log, sin = math.sin, cos = math.cos, tan = math.tan, asin = math.asin,
  acos = math.acos, atan = math.atan, min = math.min, max = math.max, fmod = math.fmod,
  deg = math.deg, rad = math.rad,
  type = type, tostring = tostring, tonumber = _G.tonumber, print = _G.print,
  select = select, error = error, assert = _G.assert, pairs = pairs, ipairs = _G.ipairs,
}

return M
