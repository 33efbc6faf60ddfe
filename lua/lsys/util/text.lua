--- Small text helpers shared by lsys's modules (no dependencies, so anything may require it).
-- @module lsys.util.text
local math, string, table = math, string, table
local format = string.format
local tonumber = tonumber
local _ENV = nil

local M = {}

--- The shortest text of the finite number x that reads back as the same double: whole
-- numbers below 2^53 without a decimal point (2, not 2.0), else 15, 16 or 17 digits.
function M.number (x)
  if x == math.floor(x) and math.abs(x) < 2 ^ 53 then return format("%d", x) end
  for digits = 15, 16 do
    local s = format("%." .. digits .. "g", x)
    if tonumber(s) == x then return s end
  end
  return format("%.17g", x)
end

--- 'path' without "." segments and with "dir/.." removed ("." when nothing is left), for
-- messages and search lists.
function M.normpath (path)
  local segs = {}
  for seg in path:gmatch("[^/]+") do
    if seg == ".." and #segs > 0 and segs[#segs] ~= ".." then segs[#segs] = nil
    elseif seg ~= "." then segs[#segs + 1] = seg end
  end
  local r = table.concat(segs, "/")
  if path:sub(1, 1) == "/" then return "/" .. r end
  return r ~= "" and r or "."
end

--- s single-quoted for a POSIX shell (a quote inside becomes '\'').
function M.shq (s) return "'" .. s:gsub("'", "'\\''") .. "'" end

--- The strings of the list `items` as a message lists them: "a, b or c" with `last` "or",
-- "a, b and c" with "and", "a, b, c" without.
function M.series (items, last)
  if last == nil or #items < 2 then return table.concat(items, ", ") end
  return table.concat(items, ", ", 1, #items - 1) .. " " .. last .. " " .. items[#items]
end

return M
