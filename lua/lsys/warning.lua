--- The library's warnings (issue 14 §5): they go through Lua 5.4's warn(), never straight
-- to stderr, so the host decides. Warnings are off in a plain `lua` unless it runs with -W
-- (or a script calls warn("@on")), as Lua intends; the lsys program turns them on.
--
-- Also the deprecated names: an old name works for one release, and its first use warns
-- once ("lsys: X is deprecated; use Y").
-- @module lsys.warning
local warn = warn
local _ENV = nil

local M = {}

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
