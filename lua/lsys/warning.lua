--- The library's warnings: they go through Lua 5.4's warn(), never straight
-- to stderr, so the host decides. Warnings are off in a plain `lua` unless it runs with -W
-- (or a script calls warn("@on")), as Lua intends; the lsys program turns them on.
--
-- Also the deprecated names: an old name works for one release, and its first use warns
-- once ("lsys: X is deprecated; use Y").
-- @module lsys.warning
local warn, math = warn, math
local _ENV = nil

local M = {}

--- Text quoted in a message (a rule, an axiom, an expression): whole when it is short;
-- else its start, the part around `pos` (the 1-based character a message points at, when
-- there is one) and its end, with "..." where characters are left out, so a generated
-- 5 MB axiom gives a message of a few hundred characters that still shows what is wrong.
function M.quote (text, pos)
  if #text <= 240 then return text end
  if pos and pos > 100 then
    local a, b = math.max(pos - 90, 61), math.min(pos + 50, #text)
    local tail = #text - b <= 20 and text:sub(b + 1) or "..." .. text:sub(-20)
    return text:sub(1, 60) .. (a > 61 and "..." or "") .. text:sub(a, b) .. tail
  end
  return text:sub(1, 180) .. "..." .. text:sub(-40)
end

--- Sends the warning `msg` to warn(). In two pieces: a message of one piece that begins
-- with '@' would be taken as a control message ("@on"), and a view file's name begins
-- the warnings about it.
function M.warn (msg)
  warn("", msg)
end

local warned = {}             -- old name -> true once its use was reported

--- Reports the first use of the deprecated `old` (later ones are quiet).
function M.deprecated (old, new)
  if warned[old] then return end
  warned[old] = true
  M.warn("lsys: " .. old .. " is deprecated; use " .. new)
end

--- The function `fn` under its old name `old`: the first call warns (see `deprecated`),
-- every call forwards to `fn`. A tail call, so `fn`'s error(msg, 2) still blames the
-- caller.
function M.alias (old, new, fn)
  return function (...)
    M.deprecated(old, new)
    return fn(...)
  end
end

return M
