--- cpfg's semantics where Lua's differ, as functions the translated rules call when they
-- run: C's % on integer parts, cpfg's bran and biran, arrays with cpfg's index clamping,
-- printf and the loop bound; with them lsys's built-ins, ran, nran and produce. They are
-- the H of the rules' Lua source (lsys.cpfg.translate writes the calls); those named with
-- a '_' reach rule strings through env. The same table is lsys.cpfg.helpers, which the
-- model files that lsys.cpfg.import writes call.
-- @module lsys.cpfg.helpers
local pairs, error, pcall, select = pairs, error, pcall, select
local math = math
local floor, log, exp, sqrt, min = math.floor, math.log, math.exp, math.sqrt, math.min
local format, gsub = string.format, string.gsub
local io_write = io.write
local model = require "lsys.model"
local warning = require "lsys.warning"
local core = require "lsys.core"
local _ENV = nil

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

return H
