--- Fuzz target: sketch files in JSON, lsys.sketch.read.json.
--
-- The bytes are read as the JSON text of a sketch named "fuzz.json". A refused file must
-- fail with a message that begins with the file's name; a read one must be a normalized
-- sketch (checked outside the hooks, in `after`: roles, one stem, at most one boundary per
-- side, two or more finite points per stroke, pressures in [0, 1], the limits) that
-- lsys.sketch.read.to_json writes and read.json reads back equal.
local read = require "lsys.sketch.read"

local check = dofile((debug.getinfo(1, "S").source:sub(2):match("^(.*/)") or "./")
                     .. "../sketch_check.lua")

local srep = string.rep

local T = { maxlen = 4096 }

local STEM = '{"role": "stem", "points": [[200, 280], [201, 180, 0.7], [200, 80, 1]]}'
T.seeds = {
  '{"width": 400, "height": 300, "strokes": [' .. STEM .. ']}',
  '{"width": 400, "height": 300, "nodes_per_layer": 13, "phyllotaxis": "fibonacci", '
    .. '"depth": {"near": -50, "far": 50}, "strokes": [' .. STEM .. ', '
    .. '{"role": "boundary_left", "points": [[110, 270], [110, 70]]}, '
    .. '{"role": "boundary_right", "id": "r", "points": [[290, 270], [290, 70]]}, '
    .. '{"role": "inclination", "points": [[100, 230], [300, 230]]}, '
    .. '{"role": "inclination", "points": [[100, 130, 0], [300, 130, 1]]}]}',
  '{"width": 1e999, "height": 300, "strokes": []}',
  '{"width": 400, "height": 300, "strokes": [{"role": "stem2", "points": []}]}',
  '{"width": 400, "height": 300, "strokes": [' .. STEM .. ', ' .. STEM .. ']}',
  '{"width": 400, "height": 300, "phyllotaxis": "decussate", "strokes": [{"role": '
    .. '"inclination", "points": [[1, 2, 1.5], [3, 4]]}]}',
  '[' .. srep('[1, 2], ', 20) .. '[3, 4]]',
  '{"width": 400,}',
  "",
}

T.dict = { '"role"', '"points"', '"stem"', '"boundary_left"', '"boundary_right"',
           '"inclination"', '"width"', '"height"', '"nodes_per_layer"', '"phyllotaxis"',
           '"fibonacci"', '"decussate"', '"distichous"', '"depth"', '"near"', '"far"',
           '"strokes"', '"id"', "null", "true", "[", "]", "{", "}", ",", ":", "[0, 0]",
           "[1, 1, 0.5]", "1e999", "-1e999", "1e308", "0.5", "-0", '"\\u0000"', '"' }

T.mutators = {
  function (rnd, s)                                      -- repeat a point
    local a, b = s:find("%[%-?[%d%.]+, %-?[%d%.]+[^%]]*%]")
    if not a then return s end
    local pt = s:sub(a, b)
    return s:sub(1, b) .. srep(", " .. pt, rnd(8)) .. s:sub(b + 1)
  end,
}

local _ENV = nil

local last

function T.clean (err) return err:find("fuzz.json: ", 1, true) == 1 end

function T.run (bytes)
  last = nil
  last = read.json(bytes, "fuzz.json")
end

function T.after (tripped)
  local sk = last
  last = nil
  if tripped or sk == nil then return nil end
  return check(sk, "fuzz.json", read, function (text) return read.json(text, "fuzz.json") end)
end

return T
