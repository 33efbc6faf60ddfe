--- Files and folders as several modules test and make them: whether a path is a file or a
-- folder, and a folder made with the ones above it.
-- @module lsys.util.fs
local require = require
local io = io
local _ENV = nil

local M = {}

--- Whether `path` opens as a file that can be read (a folder opens but cannot be read).
function M.isfile (path)
  local f = io.open(path, "r")
  if f == nil then return false end
  local ok, err = f:read(0)  -- nil, msg for a directory (it opens but cannot be read)
  f:close()
  return ok ~= nil or err == nil
end

--- Whether `path` is a folder.
function M.isdir (path)
  local f = io.open(path, "r")
  if f == nil then return false end
  local ok, _, code = f:read(0)
  f:close()
  return ok == nil and code == 21     -- EISDIR
end

--- Makes the folder `dir` and the ones above it that are missing; `made` (optional) caches
-- the folders made or found, for a caller that makes many in one tree. Returns true, or nil
-- and the message of the folder that cannot be made. lsys.core is looked up at each call,
-- as lsys.testing needs (busted gives each spec file its own package.loaded).
function M.mkdirs (dir, made)
  if made and made[dir] then return true end
  local mkdir = require("lsys.core").mkdir
  local path = dir:sub(1, 1) == "/" and "/" or ""
  for seg in dir:gmatch("[^/]+") do
    path = path .. seg
    if not (made and made[path]) then
      local ok, err = mkdir(path)
      if not ok then return nil, err end
      if made then made[path] = true end
    end
    path = path .. "/"
  end
  if made then made[dir] = true end
  return true
end

return M
