--- Testing models with busted (docs/testing.md). `require "lsys.testing"` in a spec
-- registers these assertions with luassert (busted's `assert`):
--
--   assert.lstring_equal(expected, actual [, tol])  L-strings, module by module
--   assert.near(expected, actual, tol)              numbers, or (nested) tables of numbers
--   assert.error_contains(fn, text, ...)            fn raises; the message holds each text
--   assert.scene_stats(scene, expected [, tol])     triangle, line, vertex counts, bounds...
--   assert.image_matches(x, golden [, opts])        a picture against a golden PNG file
--
-- Each has a function behind it that returns true, or false and what differs, for use
-- without busted: compare_lstrings, near, error_contains, compare_stats (with stats), and
-- compare_images and match_golden. `lsys test` runs busted with lsys on the paths.
-- @module lsys.testing
local type, pairs, ipairs, tostring, tonumber, pcall, error, select, require =
      type, pairs, ipairs, tostring, tonumber, pcall, error, select, require
local io, os, string, table, math = io, os, string, table, math
local format, abs, max, min = string.format, math.abs, math.max, math.min
local _ENV = nil

local M = {}

-- The modules are looked up at each use, not kept: busted gives each spec file its own
-- package.loaded, and this module, loaded once by a helper, must use that file's modules
-- (a Model's metatable is its file's lsys.model's).
local function kind (x) return require("lsys.kinds").type(x) end
local function core () return require "lsys.core" end

--- Whether this lsys can draw pictures (built with OSMesa): without it, image_matches on a
-- Scene or a Model raises; a spec can call pending() instead.
function M.can_render () return core().has_render == true end

-- {====================================================================
-- L-strings

local CONTEXT = 6        -- modules shown on each side of the first difference

-- The names longer than one character in the Lstring s ("Apex Leaf"), so that text compared
-- with it is read with the same modules.
local function long_names (s)
  local t = {}
  for name in pairs(s:counts()) do
    if #name > 1 then t[#t + 1] = name end
  end
  table.sort(t)
  return table.concat(t, " ")
end

local function as_lstring (x, names, what)
  if kind(x) == "lstring" then return x end
  if type(x) ~= "string" then
    error(format("the %s L-string must be an Lstring or a string, not a %s", what, type(x)), 0)
  end
  local ok, s = pcall(require("lsys.model").lstring, x, names)
  if not ok then error(format("the %s text does not read as an L-string: %s", what,
                              (tostring(s):gsub("^lsys%.lstring: ", ""))), 0) end
  return s
end

-- The test two parameters pass, and what it is called in messages, for the tolerance
-- argument of compare_lstrings.
local function number_test (tol)
  if tol == nil then
    return function (a, b) return abs(a - b) <= 1e-9 * max(1, abs(a), abs(b)) end,
           "compared to 1e-9, relative"
  elseif math.type(tol) == "integer" and tol >= 1 and tol <= 17 then
    local f = "%." .. tol .. "g"
    return function (a, b) return a == b or format(f, a) == format(f, b) end,
           format("compared to %d significant digits", tol)
  elseif type(tol) == "number" and tol >= 0 then
    return function (a, b) return abs(a - b) <= tol end, format("compared within %s", tostring(tol))
  end
  error(format("bad tolerance %s: an absolute tolerance (a number >= 0) or significant "
               .. "digits (an integer from 1 to 17)", tostring(tol)), 0)
end

-- A parameter as the L-string's text shows it: 2, not 2.0; the shortest form that reads
-- back as the same number.
local num = require("lsys.util.text").number

-- Lines showing the modules of s around module i (#s + 1: its end), carets under module i;
-- head is "expected: " or "actual:   ".
local function context (head, s, i)
  local n = #s
  local a, b = max(1, i - CONTEXT), min(n, i + CONTEXT)
  local before = (a > 1 and "..." or "") .. (i > 1 and s:text(a, i - 1) or "")
  local here = i <= n and s:text(i, i) or "(end)"
  local after = (i < n and s:text(i + 1, b) or "") .. (b < n and "..." or "")
  return format("  %s%s%s%s\n  %s%s", head, before, here, after,
                string.rep(" ", #head + #before), string.rep("^", #here))
end

--- Compares two L-strings module by module: names and parameter counts exactly, parameter
-- values within `tol`. expected, actual: Lstrings or cpfg text (text is read with the
-- multi-character names of the other side when that is an Lstring). tol: nil (relative
-- 1e-9), an integer from 1 to 17 (significant digits: equal when both print the same, as
-- s:text(i, j, digits) shows them), another number >= 0 (absolute), or a table
-- { tol = , digits = , names = "Apex Leaf" }.
-- Returns true, or false and a message showing the first module that differs.
function M.compare_lstrings (expected, actual, tol)
  local names
  if type(tol) == "table" then
    for k in pairs(tol) do
      if k ~= "tol" and k ~= "digits" and k ~= "names" then
        error(format("unknown option '%s' (tol, digits, names)", tostring(k)), 0)
      end
    end
    names = tol.names
    tol = tol.digits or tol.tol
  end
  local test, how = number_test(tol)
  if names == nil then
    local s = kind(actual) == "lstring" and actual
              or kind(expected) == "lstring" and expected
    names = s and long_names(s) or nil
  end
  local e = as_lstring(expected, names, "expected")
  local a = as_lstring(actual, names, "actual")
  if e == a then return true end                        -- the same bit for bit
  local ne, na = #e, #a
  local i, why = 1, nil
  while i <= min(ne, na) do
    local ep, ap = table.pack(e:module(i)), table.pack(a:module(i))
    if ep[1] ~= ap[1] then
      why = format("expected a module named %s, got %s", ep[1], ap[1])
      break
    end
    if ep.n ~= ap.n then
      why = format("expected %d parameter%s, got %d", ep.n - 1, ep.n == 2 and "" or "s",
                   ap.n - 1)
      break
    end
    for k = 2, ep.n do
      if not test(ep[k], ap[k]) then
        why = format("parameter %d: expected %s, got %s (%s)", k - 1, num(ep[k]),
                     num(ap[k]), how)
        break
      end
    end
    if why then break end
    i = i + 1
  end
  if why == nil then
    if ne == na then return true end
    why = ne < na and "the actual L-string is longer" or "the actual L-string is shorter"
  end
  local counts = ne == na and format("of %d", ne)
                 or format("(expected %d modules, got %d)", ne, na)
  return false, format("L-strings differ at module %d %s: %s\n%s\n%s", i, counts, why,
                       context("expected: ", e, i), context("actual:   ", a, i))
end

-- }====================================================================


-- {====================================================================
-- Numbers

-- Appends { path, value } for every value of x (a number, or a table of them, nested),
-- list entries first, then the other keys in sorted order.
local function flatten (x, out, path)
  if type(x) ~= "table" then
    out[#out + 1] = { path = path, v = x }
    return out
  end
  local n, keys = #x, {}
  for i = 1, n do flatten(x[i], out, path .. "[" .. i .. "]") end
  for k in pairs(x) do
    if not (math.type(k) == "integer" and k >= 1 and k <= n) then keys[#keys + 1] = k end
  end
  table.sort(keys, function (p, q) return tostring(p) < tostring(q) end)
  for _, k in ipairs(keys) do
    flatten(x[k], out, path .. (type(k) == "string" and "." .. k or "[" .. tostring(k) .. "]"))
  end
  return out
end

--- Whether |expected - actual| <= tol for two numbers, or for each pair of numbers at the
-- same place in two tables (lists such as positions {x, y, z}, nested, and keyed tables).
-- Returns true, or false and where they differ.
function M.near (expected, actual, tol)
  if type(tol) ~= "number" then error("the tolerance (argument 3) must be a number", 0) end
  local e, a = flatten(expected, {}, ""), flatten(actual, {}, "")
  local at = {}
  for _, p in ipairs(a) do at[p.path] = p end
  for _, p in ipairs(e) do
    local q = at[p.path]
    local where = p.path ~= "" and "at " .. p.path or "value"
    if q == nil then
      return false, format("%s: expected %s, got nothing", where, tostring(p.v))
    end
    local x, y = p.v, q.v
    if type(x) ~= "number" or type(y) ~= "number" or not (abs(x - y) <= tol) then
      return false, format("%s: expected %s, got %s (tolerance %s)", where, tostring(x),
                           tostring(y), tostring(tol))
    end
    at[p.path] = nil
  end
  for _, q in ipairs(a) do
    if at[q.path] then
      return false, format("at %s: got %s, expected nothing there", q.path, tostring(q.v))
    end
  end
  return true
end

--- Calls fn; true when it raises an error whose message contains each of the texts (plain
-- text, not patterns), else false and the message it raised.
function M.error_contains (fn, ...)
  if type(fn) ~= "function" and type(fn) ~= "table" then
    error(format("a function to call expected, got %s", type(fn)), 0)
  end
  for k = 1, select("#", ...) do
    if type((select(k, ...))) ~= "string" then
      error(format("the texts to look for must be strings (argument %d is a %s)", k + 1,
                   type((select(k, ...)))), 0)
    end
  end
  local ok, err = pcall(fn)
  if ok then return false, "expected an error, but the call succeeded" end
  err = tostring(err)
  for k = 1, select("#", ...) do
    local s = select(k, ...)
    if not err:find(s, 1, true) then
      return false, format("the error message\n  %s\ndoes not contain\n  %s", err, s)
    end
  end
  return true
end

-- }====================================================================


-- {====================================================================
-- Scenes

-- The statistics of stats(), in the order messages list them.
local STATS = { "modules", "triangles", "vertices", "lines", "segments", "records", "area",
                "bounds", "size" }
local IS_STAT = {}
for _, k in ipairs(STATS) do IS_STAT[k] = true end

local function as_scene (x)
  local k = kind(x)
  if k == "model" then return x:interpret() end
  if k == "scene" then return x end
  error(format("a Scene or a Model expected, got %s", k or type(x)), 0)
end

--- Statistics of a scene (a Model is derived and interpreted first): modules (of the
-- L-string it was drawn from), triangles, vertices, lines, segments, records, area (of
-- the triangles), bounds ({{xmin, ymin, zmin}, {xmax, ymax, zmax}}; nil when empty) and
-- size ({dx, dy, dz}).
function M.stats (x)
  local sc = as_scene(x)
  local lo, hi = sc:bounds()
  return {
    modules = sc.lstring and #sc.lstring or 0,
    triangles = sc.ntriangles, vertices = sc.nvertices, lines = sc.nlines,
    segments = sc.nsegments, records = sc.nrecords, area = sc:area(),
    bounds = lo and { lo, hi } or nil,
    size = lo and { hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3] } or { 0, 0, 0 },
  }
end

local function show (v)
  if type(v) ~= "table" then
    return math.type(v) == "float" and format("%.6g", v) or tostring(v)
  end
  local t = {}
  for i = 1, #v do t[i] = show(v[i]) end
  return "{" .. table.concat(t, ", ") .. "}"
end

-- Whether a and b (numbers or nested lists of them) agree within tol * max(1, |b|).
local function close (a, b, tol)
  if type(b) == "table" then
    if type(a) ~= "table" or #a ~= #b then return false end
    for i = 1, #b do
      if not close(a[i], b[i], tol) then return false end
    end
    return true
  end
  return type(a) == "number" and type(b) == "number" and abs(a - b) <= tol * max(1, abs(b))
end

--- Compares the statistics of x (a Scene or a Model) with `expected`, a table of some of
-- the statistics of stats(): { triangles = 1200, lines = 0, bounds = {{...}, {...}} }.
-- tol: the relative tolerance, |actual - expected| <= tol * max(1, |expected|) for every
-- number (default 1e-6: counts exactly); a table gives one per statistic, 1e-6 for the
-- others. Returns true, or false and a message listing each statistic that differs.
function M.compare_stats (x, expected, tol)
  if type(expected) ~= "table" then
    error("the expected statistics must be a table, such as { triangles = 1200 }", 0)
  end
  for k in pairs(expected) do
    if not IS_STAT[k] then
      error(format("unknown statistic '%s' (%s)", tostring(k), table.concat(STATS, ", ")), 0)
    end
  end
  if tol ~= nil and type(tol) ~= "number" and type(tol) ~= "table" then
    error("the tolerance must be a number or a table of numbers by statistic", 0)
  end
  local st = M.stats(x)
  local bad = {}
  for _, k in ipairs(STATS) do
    local want = expected[k]
    if want ~= nil then
      local t = type(tol) == "table" and tol[k] or type(tol) == "number" and tol or 1e-6
      local got = st[k]
      if got == nil or not close(got, want, t) then
        bad[#bad + 1] = format("  %s: %s, expected %s (relative tolerance %s)", k,
                               got == nil and "none (nothing drawn)" or show(got), show(want),
                               tostring(t))
      end
    end
  end
  if #bad == 0 then return true end
  local all = {}
  for _, k in ipairs(STATS) do
    if st[k] ~= nil then all[#all + 1] = k .. " " .. show(st[k]) end
  end
  return false, format("scene statistics differ:\n%s\nthe scene: %s", table.concat(bad, "\n"),
                       table.concat(all, ", "))
end

-- }====================================================================


-- {====================================================================
-- Images

--- The default image tolerance: a picture matches when the mean absolute difference of
-- every channel (R, G, B, A, of 255) is below `mean` and fewer than `fraction` of the
-- pixels differ by more than `pixel` in some channel. That absorbs rasteriser rounding
-- but not a moved, mirrored or recoloured plant.
M.TOLERANCE = { mean = 2, pixel = 40, fraction = 0.01 }

local function tolerance (tol)
  if tol == nil then return M.TOLERANCE end
  if type(tol) == "number" then
    return { mean = M.TOLERANCE.mean, pixel = M.TOLERANCE.pixel, fraction = tol }
  end
  if type(tol) ~= "table" then
    error("the image tolerance must be a number (the fraction of pixels that may differ) "
          .. "or a table { mean = , pixel = , fraction = }", 0)
  end
  local t = {}
  for k, d in pairs(M.TOLERANCE) do t[k] = d end
  for k, v in pairs(tol) do
    if M.TOLERANCE[k] == nil then
      error(format("unknown image tolerance '%s' (mean, pixel, fraction)", tostring(k)), 0)
    end
    t[k] = v
  end
  return t
end

--- Compares two RGBA pictures of w x h pixels (strings, 4 bytes a pixel) with the
-- tolerance `tol` (nil: M.TOLERANCE; a number: the fraction of pixels that may differ; a
-- table: some of M.TOLERANCE's fields). Returns true, or false and what differs.
function M.compare_images (a, b, w, h, tol)
  local t = tolerance(tol)
  if #a ~= w * h * 4 or #b ~= w * h * 4 then
    return false, format("sizes differ: %d and %d bytes for %dx%d", #a, #b, w, h)
  end
  local s1, s2, s3, s4, bad = 0, 0, 0, 0, 0
  local limit = t.pixel
  for o = 1, #a, 4 do
    local r1, g1, b1, a1 = a:byte(o, o + 3)
    local r2, g2, b2, a2 = b:byte(o, o + 3)
    local dr, dg, db, da = abs(r1 - r2), abs(g1 - g2), abs(b1 - b2), abs(a1 - a2)
    s1, s2, s3, s4 = s1 + dr, s2 + dg, s3 + db, s4 + da
    if dr > limit or dg > limit or db > limit or da > limit then bad = bad + 1 end
  end
  local n = w * h
  local m1, m2, m3, m4 = s1 / n, s2 / n, s3 / n, s4 / n
  if max(m1, m2, m3, m4) < t.mean and bad < t.fraction * n then return true end
  return false, format("mean absolute difference R %.2f G %.2f B %.2f A %.2f (limit %g); "
    .. "%.2f%% of the pixels differ by more than %d (limit %g%%)", m1, m2, m3, m4, t.mean,
    100 * bad / n, limit, 100 * t.fraction)
end

local function has_alpha (px)
  for o = 4, #px, 4 do
    if px:byte(o) ~= 255 then return true end
  end
  return false
end

local function parse_size (size)
  if size == nil then return 256, 256 end
  if math.type(size) == "integer" and size > 0 then return size, size end
  if type(size) == "table" and math.type(size[1]) == "integer" and math.type(size[2]) == "integer"
     and size[1] > 0 and size[2] > 0 then
    return size[1], size[2]
  end
  local w, h
  if type(size) == "string" then w, h = size:match("^(%d+)x(%d+)$") end
  if w and tonumber(w) > 0 and tonumber(h) > 0 then return tonumber(w), tonumber(h) end
  error(format("bad size %s: \"WxH\", {W, H} or one number of pixels", show(size)), 0)
end

local IMAGE_OPTS = { size = true, tolerance = true, render = true, actual = true }

-- The picture x stands for: RGBA pixels, width, height.
local function picture (x, opts)
  if type(x) == "string" then
    local ok, px, w, h = pcall(core().png_read, x)
    if not ok then error(px, 0) end
    return px, w, h
  end
  if type(x) == "table" and type(x[1]) == "string" and math.type(x[2]) == "integer"
     and math.type(x[3]) == "integer" then
    return x[1], x[2], x[3]                    -- { lsys.render(scene, { width =, height = }) }
  end
  local w, h = parse_size(opts.size)
  local ro = { width = w, height = h }
  for k, v in pairs(opts.render or {}) do ro[k] = v end
  local ok, px, pw, ph = pcall(require("lsys.render").render, x, ro)
  if not ok then error(px, 0) end
  return px, pw, ph
end

-- Makes the folder of `path` and the ones above it that are missing; raises naming the one
-- that cannot be made.
local function mkdir_for (path)
  local dir = path:match("^(.*)/[^/]*$")
  if dir == nil or dir == "" then return end
  local ok, err = require("lsys.util.fs").mkdirs(dir)
  if not ok then error(err, 0) end
end

local function write_png (path, px, w, h)
  mkdir_for(path)
  local ok, err = pcall(core().png_write, path, px, w, h, has_alpha(px))
  if not ok then error(err, 0) end
end

--- Compares a picture with the golden image file `golden` (a PNG). x: a PNG file, a Scene,
-- a Model (rendered at opts.size, "WxH", {W, H} or a number, default 256x256, with the
-- lsys.render options of opts.render), or { pixels, width, height } as lsys.render returns
-- them. opts.tolerance: as for compare_images. When the golden file is missing it is
-- written and the comparison fails once, saying so; with the environment variable
-- LSYS_UPDATE_GOLDEN=1 it is written and the comparison passes. On a mismatch the picture
-- is written to opts.actual (default: the golden's name with .actual.png). Returns true,
-- or false and a message.
function M.match_golden (x, golden, opts)
  opts = opts or {}
  if type(golden) ~= "string" then error("the golden image must be a file name", 0) end
  if type(opts) ~= "table" then error("the options must be a table", 0) end
  for k in pairs(opts) do
    if not IMAGE_OPTS[k] then
      error(format("unknown option '%s' (size, tolerance, render, actual)", tostring(k)), 0)
    end
  end
  local tol = tolerance(opts.tolerance)
  local px, w, h = picture(x, opts)
  if os.getenv("LSYS_UPDATE_GOLDEN") == "1" then
    write_png(golden, px, w, h)
    io.stderr:write(format("lsys.testing: wrote %s (%dx%d; LSYS_UPDATE_GOLDEN=1)\n",
                           golden, w, h))
    return true
  end
  local f = io.open(golden, "rb")
  if f == nil then
    write_png(golden, px, w, h)
    return false, format("%s did not exist: this picture (%dx%d) is there now; look at it "
                         .. "and run the test again (LSYS_UPDATE_GOLDEN=1 writes every "
                         .. "golden image)", golden, w, h)
  end
  f:close()
  local ok, gpx, gw, gh = pcall(core().png_read, golden)
  if not ok then return false, gpx end
  local why
  if gw ~= w or gh ~= h then
    ok, why = false, format("the golden image is %dx%d, the picture %dx%d", gw, gh, w, h)
  else
    ok, why = M.compare_images(px, gpx, w, h, tol)
  end
  local actual = opts.actual
    or (golden:find("%.png$") and golden:gsub("%.png$", ".actual.png") or golden .. ".actual.png")
  if ok then
    os.remove(actual)                           -- a mismatch's picture from an earlier run
    return true
  end
  write_png(actual, px, w, h)
  return false, format("%s: %s; this picture is %s (if the change is intended, look at it and "
                       .. "write the golden image again with LSYS_UPDATE_GOLDEN=1)", golden,
                       why, actual)
end

-- }====================================================================


-- {====================================================================
-- luassert: the assertions, when the module is loaded where luassert is (inside busted)

-- An assertion from a function returning true or false and a message. Misuse (an error
-- raised by fn: a bad tolerance, an unknown option) is an error, prefixed with the
-- assertion's name, whether the assertion is negated or not.
local function register (luassert, say, name, fn)
  local function check (state, args)
    local ok, r, why = pcall(fn, table.unpack(args, 1, args.n))
    if not ok then error(format("assert.%s: %s", name, tostring(r)), 0) end
    if not r then state.failure_message = why end
    return r
  end
  say:set("assertion.lsys_" .. name .. ".positive", "Expected assert." .. name .. " to pass.")
  say:set("assertion.lsys_" .. name .. ".negative", "Expected assert." .. name .. " to fail.")
  luassert:register("assertion", name, check, "assertion.lsys_" .. name .. ".positive",
                    "assertion.lsys_" .. name .. ".negative")
end

local has_luassert, luassert = pcall(require, "luassert")
local has_say, say = pcall(require, "say")
if has_luassert and has_say then
  register(luassert, say, "lstring_equal", M.compare_lstrings)
  register(luassert, say, "near", M.near)
  register(luassert, say, "error_contains", M.error_contains)
  register(luassert, say, "scene_stats", M.compare_stats)
  register(luassert, say, "image_matches", M.match_golden)
end

-- }====================================================================

return M
