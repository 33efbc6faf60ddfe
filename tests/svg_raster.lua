-- A small rasteriser of the SVG subset lsys.vector writes (a background rect, paths of M, L
-- and Z with a stroke and stroke-width, or a fill), for tests and for looking at a picture on
-- a machine without an SVG renderer. Strokes are covered by their distance to the segments
-- (round caps and joins), fills by the pixel centres inside their triangles; painted in
-- order. Returns the RGBA pixels (top row first), width and height.
local floor, min, max, sqrt = math.floor, math.min, math.max, math.sqrt

local function colour (s)
  local r, g, b = s:match("#(%x%x)(%x%x)(%x%x)")
  return tonumber(r, 16), tonumber(g, 16), tonumber(b, 16)
end

local function subpaths (d)
  local out, cur = {}, nil
  for op, args in d:gmatch("([MLZ])([^MLZ]*)") do
    if op == "M" then cur = { closed = false }; out[#out + 1] = cur end
    if op == "Z" then cur.closed = true end
    for n in args:gmatch("%-?[%d%.]+") do cur[#cur + 1] = tonumber(n) end
  end
  return out
end

return function (text)
  local w = tonumber(text:match('<svg[^>]- width="([%d%.]+)"'))
  local h = tonumber(text:match('<svg[^>]- height="([%d%.]+)"'))
  local R, G, B = {}, {}, {}
  local br, bg, bb = 255, 255, 255
  local rect = text:match("<rect [^>]*>")
  if rect then br, bg, bb = colour(rect:match('fill="([^"]+)"')) end
  for i = 1, w * h do R[i], G[i], B[i] = br, bg, bb end
  local function paint (x, y, c, r, g, b)
    local i = y * w + x + 1
    R[i] = R[i] + (r - R[i]) * c
    G[i] = G[i] + (g - G[i]) * c
    B[i] = B[i] + (b - B[i]) * c
  end
  for el in text:gmatch("<path [^>]*>") do
    local d = el:match(' d="([^"]*)"')
    local stroke, fill = el:match(' stroke="(#%x+)"'), el:match(' fill="(#%x+)"')
    local sw = tonumber(el:match(' stroke%-width="([%d%.]+)"') or "1")
    for _, sp in ipairs(subpaths(d)) do
      if stroke then
        local r, g, b = colour(stroke)
        local hw = sw / 2
        local n = #sp / 2
        local cov = {}
        local last = sp.closed and n or n - 1
        for k = 1, last do
          local x0, y0 = sp[2 * k - 1], sp[2 * k]
          local j = k % n + 1
          local x1, y1 = sp[2 * j - 1], sp[2 * j]
          local dx, dy = x1 - x0, y1 - y0
          local ll = dx * dx + dy * dy
          for y = max(0, floor(min(y0, y1) - hw - 1)), min(h - 1, floor(max(y0, y1) + hw + 1)) do
            for x = max(0, floor(min(x0, x1) - hw - 1)), min(w - 1, floor(max(x0, x1) + hw + 1)) do
              local px, py = x + 0.5, y + 0.5
              local t = ll > 0 and ((px - x0) * dx + (py - y0) * dy) / ll or 0
              t = t < 0 and 0 or t > 1 and 1 or t
              local ex, ey = px - x0 - t * dx, py - y0 - t * dy
              local c = hw + 0.5 - sqrt(ex * ex + ey * ey)
              c = c < 0 and 0 or c > 1 and 1 or c
              local i = y * w + x
              if c > (cov[i] or 0) then cov[i] = c end
            end
          end
        end
        for i, c in pairs(cov) do paint(i % w, i // w, c, r, g, b) end
      elseif fill then
        local r, g, b = colour(fill)
        local ax, ay, bx, by, cx, cy = table.unpack(sp, 1, 6)
        local function side (x0, y0, x1, y1, px, py)
          return (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)
        end
        for y = max(0, floor(min(ay, by, cy))), min(h - 1, floor(max(ay, by, cy))) do
          for x = max(0, floor(min(ax, bx, cx))), min(w - 1, floor(max(ax, bx, cx))) do
            local px, py = x + 0.5, y + 0.5
            local s1 = side(ax, ay, bx, by, px, py)
            local s2 = side(bx, by, cx, cy, px, py)
            local s3 = side(cx, cy, ax, ay, px, py)
            if (s1 >= 0 and s2 >= 0 and s3 >= 0) or (s1 <= 0 and s2 <= 0 and s3 <= 0) then
              paint(x, y, 1, r, g, b)
            end
          end
        end
      end
    end
  end
  local out = {}
  for i = 1, w * h do
    out[i] = string.char(floor(R[i] + 0.5), floor(G[i] + 0.5), floor(B[i] + 0.5), 255)
  end
  return table.concat(out), w, h
end
