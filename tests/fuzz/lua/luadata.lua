--- Inputs that are Lua data, for the Lua fuzz targets whose input is a table lsys takes
-- (targets/batchspec.lua, targets/components.lua): the bytes are the text of an
-- expression, a table constructor, evaluated in an empty environment.
--
-- Code of the input (functions in the table, calls in the constructor) reaches no global;
-- it reaches the string methods through the string metatable, whose rep and pattern
-- functions run in C, out of the fuzzer's hook: while `guard` is on they stop the input as
-- over budget (ctx.trip) when code of the input asks one for more than 1e7 bytes or a
-- pattern that may backtrack for long. lsys's own calls are not bounded.
local load, type, tostring, error, ipairs, pairs, pcall =
      load, type, tostring, error, ipairs, pairs, pcall
local getinfo, gethook, sethook = debug.getinfo, debug.gethook, debug.sethook
local clock, huge = os.clock, math.huge
local string_lib = string
local real = { rep = string.rep, find = string.find, match = string.match,
               gmatch = string.gmatch, gsub = string.gsub }
local sub = string.sub
local _ENV = nil

-- The results of pcall(f, ...) of a guard that tail-calls this, or the error of f raised
-- at the level of the guard's caller (the input's code, not this file: the message of a
-- bad argument to string.rep is the input's error, not one of the harness).
local function rethrow (ok, ...)
  if not ok then error((...), 2) end
  return ...
end

local M = {}

--- The value of the expression `text` in an empty environment, compiled as chunk `name`
-- ("spec": messages "spec:LINE: ..."). Raises the compiler's or the code's message; a
-- non-string error becomes "NAME: an error object (TYPE)".
function M.eval (text, name)
  local chunk, err = load("return " .. text, "=" .. name, "t", {})
  if chunk == nil then error(err, 0) end
  local ok, v = pcall(chunk)
  if not ok then
    if type(v) ~= "string" then error(name .. ": an error object (" .. type(v) .. ")", 0) end
    error(v, 0)
  end
  return v
end

--- True when the function at stack level `level` (of the caller) was compiled from a
-- string: code of the input, not a file of lsys.
local function frominput (level)
  local info = getinfo(level + 1, "S")
  return info ~= nil and info.what ~= "C" and sub(info.source, 1, 1) ~= "@"
end
M.frominput = frominput

local CTX

-- a pattern with q quantifiers can take about len^(q+1) steps on a subject of length len
local function heavy (subject, pat)
  if type(pat) ~= "string" or (type(subject) ~= "string" and type(subject) ~= "number") then
    return false
  end
  local _, q = real.gsub(pat, "[%*%-%+%?]", "")
  local _, b = real.gsub(pat, "%%[bf]", "")
  return (#tostring(subject) + 1) ^ (q + b + 1) > 1e8 and frominput(3)
end

local GUARDS = {
  rep = function (s, n, sep)
    if type(n) == "number" and n > 0 then
      local l = (type(s) == "string" or type(s) == "number") and #tostring(s) or 0
      local ls = (type(sep) == "string" or type(sep) == "number") and #tostring(sep) or 0
      if (n > 1e7 or (l + ls) * n > 1e7) and frominput(2) then
        CTX.trip("memory", "string.rep of " .. tostring(n))
      end
    end
    return rethrow(pcall(real.rep, s, n, sep))
  end,
}
for _, name in ipairs { "find", "match", "gmatch", "gsub" } do
  local f = real[name]
  GUARDS[name] = function (s, p, ...)
    if heavy(s, p) then CTX.trip("time", "pattern " .. tostring(p)) end
    return rethrow(pcall(f, s, p, ...))
  end
end

--- Bounds the string functions for the input that runs now (ctx: the fuzzer's).
function M.guard (ctx)
  CTX = ctx
  for name, g in pairs(GUARDS) do string_lib[name] = g end   -- luacheck: ignore 122
end

--- The seconds `fn(...)` takes without the fuzzer's line hook (math.huge when it runs
-- past `limit`, default 10 s: a count hook stops it), for a target's budget_clean: an
-- input that is slow only under the line hook (about 20 times slower) is no finding.
function M.bare (limit, fn, ...)
  limit = limit or 10
  local over = false
  local t0 = clock()
  local oh, om, oc = gethook()
  sethook(function ()
    if clock() - t0 > limit then over = true; error("fuzz: over the bare limit", 0) end
  end, "", 100000)
  pcall(fn, ...)
  sethook(oh, om, oc)
  return over and huge or clock() - t0
end

--- The string functions as they were.
function M.unguard ()
  for name, f in pairs(real) do string_lib[name] = f end   -- luacheck: ignore 122
end

return M
