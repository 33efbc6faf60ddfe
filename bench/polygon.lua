-- Polygon filling benchmark: the turtle's '{ ... }' polygons of 256,000 and
-- 512,000 vertices, combs and other shapes hostile to ear clipping, interpreted by a model
-- (the polygon's vertices placed with @M and '.', then triangulated: csrc/core/polygon.c).
--
--   build/bin/lsys bench/polygon.lua [VERTICES ...]
--
-- For each shape and size it prints the interpretation time (best of 3), triangles per
-- second, and whether the triangles are n - 2 and cover the polygon's area. The figures
-- before: a comb of 256,000 vertices took 47 s, 512,000 took 200 s; its target here
-- is under a second each. Plain Lua works too: LUA_PATH='./lua/?.lua;./lua/?/init.lua;;'
-- LUA_CPATH='./build/?.so;;' lua5.4 bench/polygon.lua

local B = dofile(((arg and arg[0] or "bench/polygon.lua"):match("^(.*)/[^/]*$") or ".")
                 .. "/common.lua")
local lsys = B.load_lsys()

local TARGET = 1.0          -- seconds for a comb

-- The shapes: each returns the list of points {x1, y1, x2, y2, ...} of about n vertices
-- and the polygon's area.
local SHAPES = {
  { "comb", true, function (n)
    local p, teeth = {}, n // 4
    for i = 0, teeth - 1 do
      for _, v in ipairs { i, 0, i + 0.5, 0, i + 0.5, -10, i + 1, -10 } do p[#p + 1] = v end
    end
    for _, v in ipairs { teeth, 1, 0, 1 } do p[#p + 1] = v end
    return p, teeth * 5 + teeth
  end },
  { "zigzag corridor", true, function (n)
    local p, walls = {}, n // 8
    local function pt (x, y) p[#p + 1] = x; p[#p + 1] = y end
    for i = 0, walls - 1 do
      local x = 2 * i
      pt(x + 0.25, 0); pt(x + 0.25, 9); pt(x + 0.75, 9); pt(x + 0.75, 0)
    end
    pt(2 * walls, 0); pt(2 * walls, 10)
    for i = walls - 1, 0, -1 do
      local x = 2 * i + 1
      pt(x + 0.75, 10); pt(x + 0.75, 1); pt(x + 0.25, 1); pt(x + 0.25, 10)
    end
    pt(0, 10); pt(0, 0)
    return p, 2 * walls * 10 - 2 * walls * 0.5 * 9
  end },
  { "spiral band", false, function (n)
    local p, inner = {}, {}
    for i = 0, n // 2 - 1 do
      local a = 0.002 * i
      local r = 1 + 0.2 * a / (2 * math.pi)
      p[#p + 1] = r * math.cos(a); p[#p + 1] = r * math.sin(a)
      inner[#inner + 1] = { (r - 0.1) * math.cos(a), (r - 0.1) * math.sin(a) }
    end
    for i = #inner, 1, -1 do p[#p + 1] = inner[i][1]; p[#p + 1] = inner[i][2] end
    return p, nil
  end },
  { "star of random radii", false, function (n)
    local p = {}
    local seed = 12345
    for i = 0, n - 1 do
      seed = (seed * 1103515245 + 12345) % 2147483648
      local a, r = 2 * math.pi * i / n, 0.1 + seed / 2147483648
      p[#p + 1] = r * math.cos(a); p[#p + 1] = r * math.sin(a)
    end
    return p, nil
  end },
}

-- The polygon's area by the shoelace formula (the shapes whose area is not given).
local function shoelace (p)
  local a, n = 0, #p // 2
  for i = 1, n do
    local j = i % n + 1
    a = a + p[2 * i - 1] * p[2 * j] - p[2 * j - 1] * p[2 * i]
  end
  return math.abs(a) / 2
end

local function lstring (m, p)
  local parts = { "{" }
  for i = 1, #p, 2 do parts[#parts + 1] = ("@M(%.17g,%.17g,0)."):format(p[i], p[i + 1]) end
  parts[#parts + 1] = "}"
  return m:lstring(table.concat(parts))
end

local sizes = {}
for i = 1, #arg do sizes[#sizes + 1] = assert(math.tointeger(tonumber(arg[i])), "a size") end
if #sizes == 0 then sizes = { 256000, 512000 } end

local m = lsys.lsystem { axiom = "", name = "polygon bench" }
print(("lsys %s, %s, best of 3; target: a comb in under %.0f s"):format(lsys.version,
      B.clock_name, TARGET))
print(("%-22s %9s %9s %12s  %s"):format("shape", "vertices", "seconds", "triangles/s", ""))
local missed = 0
for _, size in ipairs(sizes) do
  for _, shape in ipairs(SHAPES) do
    local p, area = shape[3](size)
    local n = #p // 2
    area = area or shoelace(p)
    local s = lstring(m, p)
    p = nil  -- luacheck: ignore 311 (the points go before the timing)
    local t, sc = B.best(function () return m:interpret(s, { records = false }) end, 3)
    -- the scene's positions are floats: its area is within 1e-5
    local ok = sc.ntriangles == n - 2 and math.abs(sc:area() - area) <= 1e-5 * area
    local fast = not shape[2] or t < TARGET
    if not (ok and fast) then missed = missed + 1 end
    print(("%-22s %9d %9.3f %12.0f  %s%s"):format(shape[1], n, t, sc.ntriangles / t,
          ok and "n - 2 triangles, the area" or ("%d triangles, area %.9g of %.9g"):format(
            sc.ntriangles, sc:area(), area), shape[2] and "  " .. B.verdict(fast) or ""))
    sc, s = nil, nil  -- luacheck: ignore 311
    collectgarbage()
  end
end
print(missed == 0 and "all within their targets" or missed .. " missed")
