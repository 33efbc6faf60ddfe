--- The checks the sketch and svg fuzz targets make of a sketch that was read: the
-- normalized form documented in lua/lsys/sketch/read.lua, and a JSON round trip.
-- Returns a function (sk, name, read, reread) -> nil, or the finding's message.
local type, pairs, ipairs, pcall, tostring, mathtype = type, pairs, ipairs, pcall, tostring,
                                                       math.type
local huge = math.huge
local _ENV = nil

local ROLES = { stem = true, boundary_left = true, boundary_right = true, inclination = true }
local PHYLLO = { distichous = true, decussate = true, fibonacci = true }

local function finite (x) return type(x) == "number" and x == x and x ~= huge and x ~= -huge end

local function same (a, b)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  for k, x in pairs(a) do if not same(x, b[k]) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

local function shape (sk, name, read)
  if type(sk) ~= "table" then return "read returned a " .. type(sk) end
  if sk.file ~= name then return "file is " .. tostring(sk.file) end
  if not (finite(sk.width) and sk.width > 0 and finite(sk.height) and sk.height > 0) then
    return "bad size " .. tostring(sk.width) .. " x " .. tostring(sk.height)
  end
  local n = sk.nodes_per_layer
  if mathtype(n) ~= "integer" or n < 1 or n > read.MAX_NODES then
    return "bad nodes_per_layer " .. tostring(n)
  end
  if not PHYLLO[sk.phyllotaxis] then return "bad phyllotaxis " .. tostring(sk.phyllotaxis) end
  if sk.depth ~= nil and not (finite(sk.depth.near) and finite(sk.depth.far)) then
    return "bad depth"
  end
  local count, total = {}, 0
  if #sk.strokes > read.MAX_STROKES then return "too many strokes" end
  for k, s in ipairs(sk.strokes) do
    if s.index ~= k then return "stroke " .. k .. " has index " .. tostring(s.index) end
    if not ROLES[s.role] then return "stroke " .. k .. " has role " .. tostring(s.role) end
    if s.id ~= nil and type(s.id) ~= "string" then return "stroke " .. k .. ": bad id" end
    count[s.role] = (count[s.role] or 0) + 1
    local pts = s.points
    if #pts < 2 or #pts > read.MAX_POINTS then
      return "stroke " .. k .. ": " .. #pts .. " points"
    end
    total = total + #pts
    for j, p in ipairs(pts) do
      if #p ~= 3 or not (finite(p[1]) and finite(p[2]) and finite(p[3])) or p[3] < 0
         or p[3] > 1 then
        return "stroke " .. k .. ": bad point " .. j
      end
    end
  end
  if total > read.MAX_TOTAL then return "too many points" end
  if count.stem ~= 1 then return tostring(count.stem) .. " stems" end
  if (count.boundary_left or 0) > 1 or (count.boundary_right or 0) > 1 then
    return "two boundaries on a side"
  end
  return nil
end

return function (sk, name, read, reread)
  local bad = shape(sk, name, read)
  if bad then return "the sketch read is not normalized: " .. bad end
  local ok, text = pcall(read.to_json, sk)
  if not ok then return "to_json refused a sketch that was read: " .. tostring(text) end
  local ok2, back = pcall(reread, text)
  if not ok2 then return "the JSON of a sketch does not read back: " .. tostring(back) end
  local w = sk.warnings
  sk.warnings = nil
  local eq = same(sk, back)
  sk.warnings = w
  if not eq then return "the JSON of a sketch reads back different" end
  return nil
end
