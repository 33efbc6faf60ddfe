--- Fuzz target: the cpfg palette readers, lsys.view.load_colormap (.map) and
-- lsys.view.load_materials (.mat).
--
-- The bytes are written to a temporary .map file and to a .mat file (removed after
-- each input), and each is read by its loader and, by name, by view.normalize
-- { palette = path }. Whether a loader succeeds and what it returns are checked
-- against an independent decoding of the formats as lua/lsys/viewfile.lua documents them:
-- a colour map is 768 bytes, 256 colours of 3 bytes (component / 255); a material file
-- is a non-empty sequence of 15-byte records (index, transparency, ambient, diffuse,
-- emission, specular rgb, shininess <= 128; alpha 1 - t/255 when t > 0; the last
-- record of an index wins; missing indices up to the largest get the default
-- material). A loaded palette must pass view.normalize as `palette`, and normalising
-- the path must give the same palette. Expected errors: strings that name the file.
local view = require "lsys.view"

local type, pairs, pcall, tostring, error, os_remove, tmpname, open, mathtype =
      type, pairs, pcall, tostring, error, os.remove, os.tmpname, io.open, math.type
local format, char, byte, srep = string.format, string.char, string.byte, string.rep
local concat = table.concat

local T = { maxlen = 2048 }

local function record (idx, tr, amb, dif, emi, spe, sh)
  return char(idx, tr, amb[1], amb[2], amb[3], dif[1], dif[2], dif[3], emi[1], emi[2], emi[3],
              spe[1], spe[2], spe[3], sh)
end

local ramp = {}
for i = 0, 255 do ramp[#ramp + 1] = char(i, 255 - i, (i * 7) % 256) end

T.seeds = {
  concat(ramp),                                                -- a valid colour map
  srep("\0", 768), srep("\255", 768), srep("\1", 767), srep("\2", 769),
  record(1, 0, {0, 0, 0}, {255, 255, 255}, {0, 0, 0}, {0, 0, 0}, 0),
  record(0, 0, {10, 20, 30}, {200, 100, 50}, {0, 0, 0}, {255, 255, 255}, 128) ..
    record(2, 128, {0, 0, 0}, {40, 220, 40}, {5, 5, 5}, {90, 90, 90}, 64),
  record(3, 255, {1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}, 1) ..
    record(3, 1, {1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}, 2) ..
    record(255, 0, {255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}, 100),
  record(7, 0, {0, 0, 0}, {255, 0, 0}, {0, 0, 0}, {0, 0, 0}, 129),   -- shininess too high
  record(7, 0, {0, 0, 0}, {255, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0):sub(1, 14),
  "",
}

T.dict = { "\0", "\255", "\128", "\129", srep("\0", 15), srep("\255", 3), srep("\0", 3) }

-- the target's own mutations: whole records and map entries
T.mutators = {
  function (rnd, s)                                       -- insert or append a record
    local r = {}
    for i = 1, 15 do r[i] = char(rnd(256) - 1) end
    if rnd(2) == 1 then r[15] = char(rnd(130) - 1) end
    local at = 15 * (rnd(#s // 15 + 1) - 1) + 1
    return s:sub(1, at - 1) .. concat(r) .. s:sub(at)
  end,
  function (rnd, s)                                       -- pad or cut to a size that loads
    local n = rnd(2) == 1 and 768 or 15 * rnd(20)
    if #s >= n then return s:sub(1, n) end
    return s .. srep(char(rnd(256) - 1), n - #s)
  end,
}

local _ENV = nil

local base = tmpname()
local MAP, MAT = base .. ".map", base .. ".mat"

local function writefile (path, s)
  local f = open(path, "wb")
  f:write(s)
  f:close()
end

local function same (a, b)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  for k, x in pairs(a) do if not same(x, b[k]) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

-- the palettes the documentation describes, or nil when the file must be refused
local function expect_map (s)
  if #s ~= 768 then return nil end
  local p = {}
  for i = 0, 255 do
    local r, g, b = byte(s, 3 * i + 1, 3 * i + 3)
    p[i] = { r / 255, g / 255, b / 255 }
  end
  return p
end

local function expect_mat (s)
  if #s == 0 or #s % 15 ~= 0 then return nil end
  local p, top = {}, 0
  for o = 0, #s - 15, 15 do
    local idx, tr = byte(s, o + 1, o + 2)
    local sh = byte(s, o + 15)
    if sh > 128 then return nil end
    local function rgb (at)
      local c = { byte(s, o + at, o + at + 2) }
      for i = 1, 3 do c[i] = c[i] / 255 end
      if tr > 0 then c[4] = 1 - tr / 255 end
      return c
    end
    p[idx] = { ambient = rgb(3), diffuse = rgb(6), emission = rgb(9), specular = rgb(12),
               shininess = sh }
    if idx > top then top = idx end
  end
  for i = 0, top do
    p[i] = p[i] or { ambient = { 0, 0, 0 }, diffuse = { 1, 1, 1 }, emission = { 0, 0, 0 },
                     specular = { 0, 0, 0 }, shininess = 0 }
  end
  return p
end

-- what view.normalize makes of a palette: every entry a material with a diffuse colour
local function normalised (p)
  local out = {}
  for i, c in pairs(p) do
    if c.diffuse then out[i] = c else out[i] = { diffuse = c } end
  end
  return out
end

local function clean_for (path, err)
  return type(err) == "string" and err:find(path, 1, true) ~= nil
end

function T.clean (err) return err:find(base, 1, true) ~= nil end

-- The loaders and normalize run under the fuzzer's hooks (run); the checks against the
-- decoding do not (after).
local last

local function load (path, bytes, loader)
  writefile(path, bytes)
  local r = {}
  r.ok, r.p = pcall(loader, path)
  r.nok, r.n = pcall(view.normalize, { palette = path }, "fuzz")
  os_remove(path)
  if r.ok and type(r.p) == "table" then
    r.pok, r.pn = pcall(view.normalize, { palette = r.p }, "fuzz")
  end
  return r
end

function T.run (bytes)
  last = nil
  local m = load(MAP, bytes, view.load_colormap)
  local t = load(MAT, bytes, view.load_materials)
  last = { bytes = bytes, map = m, mat = t }
  if not m.ok and not t.ok then error(t.p, 0) end
end

local function check (r, bytes, path, expect, what)
  local want = expect(bytes)
  if r.ok ~= (want ~= nil) then
    return format("%s: %d bytes %s, but the format says it %s (%s)", what, #bytes,
                  r.ok and "loaded" or "were refused", want and "loads" or "does not",
                  tostring(r.p))
  end
  if r.ok ~= r.nok then
    return format("%s: the loader and view.normalize disagree: %s / %s", what, tostring(r.p),
                  tostring(r.n))
  end
  if not r.ok then
    if not clean_for(path, r.p) then
      return what .. ": an error without the file: " .. tostring(r.p)
    end
    if not clean_for(path, r.n) then
      return what .. ": normalize's error without the file: " .. tostring(r.n)
    end
    return nil
  end
  if type(r.p) ~= "table" then return what .. " returned a " .. type(r.p) end
  for i in pairs(r.p) do
    if mathtype(i) ~= "integer" or i < 0 or i > 255 then
      return what .. ": a palette key " .. tostring(i)
    end
  end
  if not same(r.p, want) then return what .. ": the palette differs from the format's decoding" end
  if not r.pok then
    return what .. ": view.normalize rejected the loaded palette: " .. tostring(r.pn)
  end
  if not same(r.pn.palette, normalised(want)) then
    return what .. ": view.normalize changed the palette"
  end
  if not same(r.n.palette, r.pn.palette) then
    return what .. ": normalize by name and by table differ"
  end
  return nil
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  return check(r.map, r.bytes, MAP, expect_map, "load_colormap")
      or check(r.mat, r.bytes, MAT, expect_mat, "load_materials")
end

function T.finish ()
  os_remove(MAP); os_remove(MAT); os_remove(base)
end

function T.describe (bytes)
  local hex = {}
  for i = 1, #bytes do hex[i] = format("%02x", byte(bytes, i)) end
  return #bytes .. " bytes: " .. concat(hex, " ")
end

return T
