--- Fuzz target: sketch files in SVG, lsys.sketch.read.svg, with the SVG path
-- data parser lsys.sketch.svgpath, transforms, lengths and the XML around them.
--
-- The bytes are read as an SVG file named "fuzz.svg". A refused file must fail with a
-- message that begins with the file's name; a read one must be a normalized sketch
-- (checked in `after`, as for the sketch target) that writes to JSON and reads back
-- equal. While an input runs, the limits of points are smaller (4000 per stroke, 16000 in
-- all): a few bytes of path data can ask for 100,000 points, and under the coverage hook
-- reading them would take longer than the time budget; the limits themselves are reached
-- sooner that way.
local read = require "lsys.sketch.read"

local check = dofile((debug.getinfo(1, "S").source:sub(2):match("^(.*/)") or "./")
                     .. "../sketch_check.lua")

local T = { maxlen = 4096 }

local HEAD = '<svg xmlns="http://www.w3.org/2000/svg" '
             .. 'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
local function svg (attrs, body) return HEAD .. attrs .. ">" .. body .. "</svg>" end
local S = '<path id="stem" d="m 200,280 c 0,-30 5,-60 0,-90 s -5,-60 0,-90"/>'

T.seeds = {
  svg('width="400" height="300"', S),
  svg('viewBox="0 0 400 300" width="210mm" height="297mm"',
      '<g inkscape:label="Layer 1" transform="translate(10,-20)">' .. S
      .. '<path inkscape:label="boundary-left" d="M 100,290 Q 120,190 100,90"/>'
      .. '<polyline id="boundary_right" points="290,270 295,170 290,70"/>'
      .. '<path id="inclination-1" d="m 90,250 h 200 m -200,-100 h 200 M 90 50 H 290 Z"/>'
      .. '<line id="inclination-2" x1="90" y1="110" x2="290" y2="100"/></g>'),
  svg('width="1in" height="10cm" data-nodes-per-layer="13" data-phyllotaxis="fibonacci" '
      .. 'data-depth-near="-5" data-depth-far="5"',
      '<path id="stem" d="M0 0 L 10 0 20 0" data-pressure="0 1 0.5" '
      .. 'transform="rotate(30 5 5) skewX(10) scale(2,3) matrix(1 0 0 1 4 5)"/>'),
  svg('width="40" height="40"', '<path id="stem" d="M0 0a5 5 0 01 10 0A 5 3 45 1 0 20 0 '
      .. 'q 1 2 3 4t 5 6T 7 8 v 1 V 2 h 3 H 4 l .5.5-1-2 1e-3 1E+2 z m 1 1 C 1 2 3 4 5 6 z"/>'),
  svg('width="40" height="40"', '<defs><path id="stem" d="M0 0 1 1"/></defs>'
      .. '<path id="stem-old" d="M0 0 1 1"/><svg><path id="stem" d="M0 0 1 1"/></svg>'),
  '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY a "b">]>\n<svg width="1" height="1"/>',
  '<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "x.dtd">' .. svg('width="1" height="1"', S),
  svg('width="100%" height="1"', S),
  svg('width="4" height="4"', '<path id="stem" d="M 0 0 L 10"/>'),
  "<html/>",
  "",
}

T.dict = { "<path ", "<polyline ", "<line ", "<g ", "</g>", "/>", ">", 'id="stem"',
           'id="inclination-2"', 'id="boundary-left"', 'inkscape:label="boundary right"',
           'd="', 'points="', 'transform="', 'viewBox="', 'width="', 'data-pressure="',
           "translate(", "scale(", "rotate(", "matrix(", "skewX(", "skewY(", ")", '"',
           "M", "m", "L", "l", "H", "h", "V", "v", "C", "c", "S", "s", "Q", "q", "T", "t",
           "A", "a", "Z", "z", " 0 0", ",", ".5", "-1", "1e-3", "1e308", "1e999", " 0 1 ",
           "mm", "px", "in", "%", "<![CDATA[", "]]>", "<!--", "-->", "&amp;", "&#x41;",
           "<defs>", "</defs>", "<!ENTITY", "<!DOCTYPE" }

-- the target's own mutation: a random command with random numbers into some path data
T.mutators = {
  function (rnd, s)
    local a = s:find('d="', 1, true)
    if not a then return s end
    local cmds = "MmLlHhVvCcSsQqTtAaZz"
    local k = rnd(#cmds)
    local parts = { cmds:sub(k, k) }
    for i = 1, rnd(8) - 1 do
      local v = ({ "0", "1", "-1", ".5", "10", "1e3", "-2.5e-1", "7" })[rnd(8)]
      parts[#parts + 1] = (i > 1 and rnd(3) == 1) and "," .. v or " " .. v
    end
    local at = a + 2 + rnd(8)
    return s:sub(1, at) .. table.concat(parts) .. " " .. s:sub(at + 1)
  end,
}

local _ENV = nil

local last
local saved

function T.clean (err) return err:find("fuzz.svg:", 1, true) == 1 end

function T.before ()
  saved = { read.MAX_POINTS, read.MAX_TOTAL }
  read.MAX_POINTS, read.MAX_TOTAL = 4000, 16000
end

function T.run (bytes)
  last = nil
  last = read.svg(bytes, "fuzz.svg")
end

function T.after (tripped)
  read.MAX_POINTS, read.MAX_TOTAL = saved[1], saved[2]
  local sk = last
  last = nil
  if tripped or sk == nil then return nil end
  return check(sk, "fuzz.svg", read, function (text) return read.json(text, "fuzz.svg") end)
end

return T
