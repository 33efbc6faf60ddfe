--- Fuzz target: the cpfg view file reader (lsys.view.parse and load).
--
-- The bytes are parsed as "fuzz.v". A parsed view must be a table with a list of
-- warnings "fuzz.v:LINE: ...", and lsys.view.normalize must accept it with the
-- file-based options (contours, surfaces, textures) left out, as the view specs do
-- does: their files do not exist. The normalised view must give turtle and renderer
-- options. The same bytes through view.load from a temporary file must give the same
-- view (but `dir`) or the same error (but the file name). Expected errors: strings
-- "fuzz.v:LINE: ...".
local view = require "lsys.view"

local type, pairs, ipairs, pcall, tostring, error, os_remove, tmpname, open =
      type, pairs, ipairs, pcall, tostring, error, os.remove, os.tmpname, io.open
local format, concat = string.format, table.concat

local function readfile (path)
  local f = open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

local T = { maxlen = 4096 }

-- seeds: the view files of the tests, a few hand-made texts, and one line
-- of every command
T.seeds = {}
for _, name in ipairs { "plant.v", "legacy.v" } do
  local s = readfile("tests/data/views/" .. name)
  if s then T.seeds[#T.seeds + 1] = s end
end
for _, s in ipairs {
  "angle factor: 8\ninitial color: 1\nviewpoint: 0,0,1\nview reference point: 0,0,0\n",
  "texture: F: a.png H: l L: m E: b S: R: 2\nsurface: A a.s 1 4 4 1\nsurface: B b.s 2 1\n",
  "tropism: T: 0 1 0 I: 0.5 A: 10\ntorque: T: 1 0 0 A: 5 E: 1 S: 2\n" ..
    "light: O: 1 2 3 P: 0 0 1 10 45 T: 1 0 0\nlight: A: 1 1 1\n",
  "angle increment: 22.5\ncolor increment: -2 1\ninitial colour: 7 2\n" ..
    "line width increment: 0.25\nline style: 2\nprojection: parallel\ntwist: -900\n",
  "initial line width: 3\ncontour sides: 3\npolygonization level: 0\n" ..
    "twist of cylinders: on\nbackground colour: 1,1,1\nlight direction: 0 0 1\n",
  "viewing angle: 179.5\nbackground color: 2,0,0\ncontour: 65535 c.con\n" ..
    "tropism direction: 1,0,0\nelasticity increment: 0.1\n",
  "/* a comment\n over lines */ angle factor: 4 // and one to the end\n" ..
    "Angle   Factor : 6\nfront distance: 1\nscale factor: 2\n",
  "initial elasticity: 0.5\n",
} do
  T.seeds[#T.seeds + 1] = s
end

-- labels and values of every command
local LABELS = {
  "angle factor", "angle increment", "initial color", "initial colour", "color increment",
  "colour increment", "initial line width", "line width increment", "line style",
  "viewpoint", "view reference point", "twist", "projection", "viewing angle",
  "light direction", "light", "background color", "background colour", "contour",
  "contour sides", "polygonization level", "twist of cylinders", "texture", "tropism",
  "torque", "tropism direction", "initial elasticity", "elasticity increment", "surface",
  "z buffer", "front distance", "render mode", "shadow map", "interpretation past %",
  "bogus", "", "Angle  Factor",
}
local ATOMS = {
  "0", "1", "-1", "2.5", "1e999", "-1e999", "nan", "inf", "0x10", "1e-320", "3", "64", "65",
  "1024", "1025", "65536", "-0", "9", "10", ",", ",,", "x", "on", "off", "pixels", "polygons",
  "p", "parallel", "perspective", "cylinder", "pixel", "polygon", "4", "T:", "A:", "E:",
  "S:", "F:", "H:", "L:", "R:", "I:", "V:", "D:", "O:", "P:", "l", "n", "m", "d", "b",
  "a.png", "sub/a.con", "/*", "*/", "//", "#", ":", "\0", "\255", "é", "~", "0,0,0",
  "1,2,3", "1 2 3", "0,-1,0", "-1,-1,-1", "0x1p4", "1e308", "179.9", "180",
}
T.dict = { "\n", ": ", "/*", "*/", "//", "#define X 1\n", ",", " ", "\r\n" }
for _, l in ipairs(LABELS) do T.dict[#T.dict + 1] = l .. ":" end
for _, a in ipairs(ATOMS) do T.dict[#T.dict + 1] = a end

-- a command line with random values
local function randomline (rnd)
  local parts = { LABELS[rnd(#LABELS)], ":" }
  for _ = 1, rnd(7) - 1 do
    parts[#parts + 1] = rnd(4) == 1 and " " or ""
    parts[#parts + 1] = " " .. ATOMS[rnd(#ATOMS)]
  end
  if rnd(8) == 1 then parts[1] = ATOMS[rnd(#ATOMS)] end
  return concat(parts)
end

T.mutators = {
  function (rnd, s)
    local i = rnd(#s + 1)
    return s:sub(1, i - 1) .. "\n" .. randomline(rnd) .. "\n" .. s:sub(i)
  end,
}

local _ENV = nil

-- The options whose files are read by normalize are dropped; the rest must pass.
local function strip (v)
  local out = {}
  for k, x in pairs(v) do
    if k ~= "contours" and k ~= "surfaces" and k ~= "textures" and k ~= "dir" then out[k] = x end
  end
  return out
end

local function same (a, b)
  if type(a) ~= "table" or type(b) ~= "table" then
    return a == b or (a ~= a and b ~= b)
  end
  for k, x in pairs(a) do if not same(x, b[k]) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

local TMP = tmpname()
local TMPPAT = TMP:gsub("%p", "%%%0")

function T.clean (err)
  return err:find("^fuzz%.v:%d+: ") ~= nil
end

-- The lsys calls run under the fuzzer's hooks (run); the comparisons after them do not
-- (after), which keeps the hooks on lsys's code.
local last

function T.run (bytes)
  last = nil
  local r = {}
  r.ok, r.v, r.w = pcall(view.parse, bytes, "fuzz.v", { quiet = true })
  local f = open(TMP, "wb")       -- the same through a file
  f:write(bytes)
  f:close()
  r.lok, r.lv, r.lw = pcall(view.load, TMP, { quiet = true })
  os_remove(TMP)
  last = r
  if not r.ok then error(r.v, 0) end
  if type(r.v) == "table" then
    r.nok, r.n = pcall(view.normalize, strip(r.v), "fuzz")
    if r.nok then
      r.tok, r.t = pcall(view.turtle_options, r.n, false)
      r.rok, r.r = pcall(view.render_options, r.n)
      r.n2ok, r.n2 = pcall(view.normalize, r.n, "fuzz")   -- normalising twice changes nothing
    end
  end
  r.done = true
end

local function check (r)
  if r.ok ~= r.lok then
    return format("view.parse and view.load disagree: %s / %s", tostring(r.v), tostring(r.lv))
  end
  if not r.ok then
    if type(r.v) == "string" and type(r.lv) == "string" and r.lv:gsub(TMPPAT, "fuzz.v") ~= r.v then
      return format("view.parse and view.load fail differently: %s / %s", r.v, r.lv)
    end
    return nil                                 -- the error itself is classified by clean
  end
  if type(r.v) ~= "table" then return "view.parse returned a " .. type(r.v) end
  if type(r.w) ~= "table" then return "view.parse returned no list of warnings" end
  for _, w in ipairs(r.w) do
    if type(w) ~= "string" or not w:find("^fuzz%.v:%d+: ") then
      return "a warning without file and line: " .. tostring(w)
    end
  end
  if type(r.lv) ~= "table" or r.lv.dir == nil or not same(strip(r.v), strip(r.lv)) then
    return "view.parse and view.load read different views"
  end
  if #r.lw ~= #r.w then return "view.parse and view.load warn differently" end
  if not r.nok then return "normalize rejected the parsed view: " .. tostring(r.n) end
  if not r.tok then return "view.turtle_options failed on a normalised view: " .. tostring(r.t) end
  if not r.rok then return "view.render_options failed on a normalised view: " .. tostring(r.r) end
  if not r.n2ok then return "normalize rejected its own output: " .. tostring(r.n2) end
  if not same(r.n, r.n2) then return "normalize is not idempotent" end
  return nil
end

function T.after (tripped)
  local r = last
  last = nil
  if tripped or r == nil or (r.ok and not r.done) then return nil end
  return check(r)
end

function T.finish () os_remove(TMP) end

function T.describe (bytes) return bytes end

return T
