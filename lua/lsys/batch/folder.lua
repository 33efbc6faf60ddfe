--- The output folder of an lsys.batch run: its symbolic links, which no job writes through,
-- and the temporaries that dead runs left of a job's files.
-- @module lsys.batch.folder
local shq = require("lsys.util.text").shq
local join = require("lsys.batch.fields").join

local ipairs, next = ipairs, next
local io, os = io, os
local _ENV = nil

local M = {}

--[[
What the output folder `dir` holds that a run must know of, found once at its start (find
-H, which follows `dir` itself when it is a link, and nothing below it): `links`, the
symbolic links below it, by their paths relative to it (no job writes through one: core's
writer would replace the link's target); `temps`, the temporaries lsys's writer names
`.NAME.lsys-PID-N.tmp`, by the path of the file NAME they were for: { path, pid } each.
]]
local function scan_folder (dir)
  local root = dir:gsub("/+$", "")
  if root == "" then root = "/" end
  local prefix = root == "/" and "/" or root .. "/"
  local p = io.popen("find -H " .. shq(root) .. " -type l -print0 2>/dev/null; printf '\\0'; "
    .. "find -H " .. shq(root) .. " -type f -name '.*.lsys-*-*.tmp' -print0 2>/dev/null")
  local out = p and p:read("a") or ""
  if p then p:close() end
  local links, temps, second = {}, {}, false
  for path in out:gmatch("([^%z]*)%z") do
    if path == "" then
      second = true
    elseif path:sub(1, #prefix) == prefix then
      local rel = path:sub(#prefix + 1)
      if not second then
        links[rel] = true
      else
        local folder, name, pid = rel:match("^(.-)/?%.([^/]+)%.lsys%-(%d+)%-%d+%.tmp$")
        if name then
          local target = folder == "" and name or folder .. "/" .. name
          local list = temps[target] or {}
          temps[target], list[#list + 1] = list, { path = rel, pid = pid }
        end
      end
    end
  end
  return { links = links, nlinks = next(links) ~= nil, temps = temps }
end

-- Whether the process `pid` lives on this host (/proc; else `kill -0`, which a process of
-- another user also passes). When it cannot tell, it says yes.
local PROC = nil
local function alive (pid)
  if PROC == nil then
    local f = io.open("/proc/self/stat", "rb")
    PROC = f ~= nil
    if f then f:close() end
  end
  if PROC then
    local f = io.open("/proc/" .. pid .. "/stat", "rb")
    if f then f:close() end
    return f ~= nil
  end
  local p = io.popen("kill -0 " .. pid .. " 2>&1")
  local said = p and p:read("a") or ""
  local ok = p and p:close()
  return ok or not said:lower():find("no such process", 1, true)
end

-- Removes the temporaries `scan` found of the files `claims` (a job's, as complete gives
-- them) that dead processes left. Returns how many it removed.
local function clean_temps (scan, dir, claims)
  local removed = 0
  for _, c in ipairs(claims) do
    local list = scan.temps[c.path]
    if list then
      for _, t in ipairs(list) do
        if not t.gone and not alive(t.pid) and os.remove(join(dir, t.path)) then
          removed, t.gone = removed + 1, true
        end
      end
    end
  end
  return removed
end

-- The first of the folders and file of the path `path` (relative to the output folder)
-- that is a symbolic link `scan` found, or nil.
local function link_on (scan, path)
  if not scan.nlinks then return nil end
  local from = 1
  while true do
    local s = path:find("/", from, true)
    local sub = path:sub(1, (s or 0) - 1)
    if scan.links[sub] then return sub end
    if s == nil then return nil end
    from = s + 1
  end
end

M.scan_folder, M.clean_temps, M.link_on = scan_folder, clean_temps, link_on

return M
