--- Checks the built-in environments share for their options (lsys.environment.*).
-- @module lsys.environment.check
local type = type
local _ENV = nil

local M = {}

--- Is x a number, neither NaN nor infinite?
function M.finite (x) return type(x) == "number" and x == x and x - x == 0 end

--- Is v a list { x, y, z } of finite numbers?
function M.vec3 (v)
  return type(v) == "table" and #v == 3 and M.finite(v[1]) and M.finite(v[2])
         and M.finite(v[3])
end

return M
