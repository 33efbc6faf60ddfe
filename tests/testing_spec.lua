-- lsys.testing (docs/testing.md): each assertion passes on a match and fails with a message
-- that shows what differs; and `lsys test`, busted run by the program on a user's folder.
local H = require "tests.helper"
local lsys = require "lsys"
local core = require "lsys.core"
local testing = require "lsys.testing"

local failure = H.errof      -- the message of the assertion f(...) failing (it must fail)

-- Asserts that `text` contains each of the strings that follow (plain text).
local function has (text, ...)
  for i = 1, select("#", ...) do
    local s = select(i, ...)
    assert(text:find(s, 1, true), ("%q\ndoes not contain\n%q"):format(text, s))
  end
end

local PLANT = lsys.lsystem { axiom = "X", productions = "X --> F[+X]F[-X]+X\nF --> FF" }

describe("assert.lstring_equal", function()
  it("passes when the text matches the derived Lstring", function()
    assert.lstring_equal("F[+X]F[-X]+X", PLANT:derive(1))
    assert.lstring_equal(PLANT:derive(1), "F[+X]F[-X]+X")
    assert.lstring_equal("F(1, 2) [ +A ]", lsys.lstring("F(1,2)[+A]"))
  end)

  it("compares parameters to 1e-9 by default, or to a tolerance or significant digits", function()
    local s = lsys.lstring("A(0.3333333333333333)B(2)")
    assert.lstring_equal("A(0.33333333333333)B(2)", s)
    assert.is_not.lstring_equal("A(0.3333)B(2)", s)
    assert.lstring_equal("A(0.3333)B(2)", s, 4)           -- as s:text(1, -1, 4) prints it
    assert.lstring_equal("A(0.333)B(2.0004)", s, 1e-3)
    assert.is_not.lstring_equal("A(0.333)B(2.0004)", s, 1e-4)
    assert.lstring_equal("A(0.3333)B(2)", s, { digits = 4 })
  end)

  it("reads the expected text with the Lstring's multi-character names", function()
    local m = lsys.lsystem { axiom = "Apex", modules = "Apex Leaf",
                             productions = "Apex --> Leaf Apex" }
    assert.lstring_equal("LeafLeafApex", m:derive(2))
    local msg = failure(assert.lstring_equal, "LeafLeafLeaf", m:derive(2))
    has(msg, "L-strings differ at module 3 of 3: expected a module named Leaf, got Apex")
  end)

  it("shows the first module that differs, with its index and context", function()
    local s = PLANT:derive(3)
    local text = tostring(s)
    local i = text:find("+", 40, true)                 -- change a module past the 40th
    assert.equal(#text, #s)                            -- one character a module
    local wrong = text:sub(1, i - 1) .. "-" .. text:sub(i + 1)
    local msg = failure(assert.lstring_equal, wrong, s)
    has(msg, ("L-strings differ at module %d of %d: expected a module named -, got +")
               :format(i, #s),
        "  expected: ..." .. wrong:sub(i - 6, i + 6) .. "...\n" .. (" "):rep(21) .. "^\n",
        "  actual:   ..." .. text:sub(i - 6, i + 6) .. "...\n" .. (" "):rep(21) .. "^\n")
    assert.is_true(#msg < 400, "the message holds the context, not the whole strings")
  end)

  it("says which parameter differs and how they were compared", function()
    local msg = failure(assert.lstring_equal, "F(1)A(0.5,2)", lsys.lstring("F(1)A(0.5,2.5)"))
    has(msg, "L-strings differ at module 2 of 2: parameter 2: expected 2, got 2.5 "
        .. "(compared to 1e-9, relative)", "  expected: F(1)A(0.5,2)\n            "
        .. "    ^^^^^^^^\n", "  actual:   F(1)A(0.5,2.5)\n                ^^^^^^^^^^")
    has(failure(assert.lstring_equal, "A(0.33)", "A(0.336)", 2),
        "parameter 1: expected 0.33, got 0.336 (compared to 2 significant digits)")
    has(failure(assert.lstring_equal, "A(1)", "A(1,2)"), "expected 1 parameter, got 2")
  end)

  it("marks the end of the shorter string when the lengths differ", function()
    has(failure(assert.lstring_equal, "FFF", "FF"),
        "L-strings differ at module 3 (expected 3 modules, got 2): the actual L-string is "
        .. "shorter\n  expected: FFF\n              ^\n  actual:   FF(end)\n              ^^^^^")
    has(failure(assert.lstring_equal, "FF", "FFA(1)"), "the actual L-string is longer")
  end)

  it("raises for text that is not an L-string and for a bad tolerance", function()
    local msg = failure(assert.lstring_equal, "F(1", PLANT:derive(1))
    has(msg, "assert.lstring_equal: the expected text does not read as an L-string: "
        .. "unbalanced parentheses")
    assert.falsy(msg:find("testing.lua", 1, true), msg)
    has(failure(assert.is_not.lstring_equal, "F", "F", -1),
        "assert.lstring_equal: bad tolerance -1: an absolute tolerance (a number >= 0) or "
        .. "significant digits (an integer from 1 to 17)")
    has(failure(assert.lstring_equal, "F", {}),
        "the actual L-string must be an Lstring or a string, not a table")
    has(failure(assert.lstring_equal, "F", "F", { digit = 3 }),
        "assert.lstring_equal: unknown option 'digit' (tol, digits, names)")
  end)
end)

describe("assert.near", function()
  it("compares numbers, nested lists and keyed tables within the tolerance", function()
    assert.near(1, 1.05, 0.1)
    assert.near({ 1, { 2, 3 } }, { 1.01, { 2, 2.99 } }, 0.02)
    assert.near({ x = 1, y = { 2 } }, { y = { 2.001 }, x = 1 }, 0.01)
    assert.is_not.near(1, 1.2, 0.1)
  end)

  it("names the place that differs", function()
    has(failure(assert.near, { 1, { 2, 3 } }, { 1, { 2, 3.5 } }, 0.1),
        "at [2][2]: expected 3, got 3.5 (tolerance 0.1)")
    has(failure(assert.near, { x = 1, y = 2 }, { x = 1 }, 0.1), "at .y: expected 2, got nothing")
    has(failure(assert.near, { 1 }, { 1, 2 }, 0.1), "at [2]: got 2, expected nothing there")
    has(failure(assert.near, 0 / 0, 0, 1), "value: expected")
    has(failure(assert.near, 1, 1), "assert.near: the tolerance (argument 3) must be a number")
  end)

  it("checks a turtle position", function()
    local sc = lsys.lsystem { axiom = "F+F", view = { angle = 90 } }:interpret()
    local pos = sc:turtle(3)
    assert.near({ -1, 1, 0 }, pos, 1e-12)
  end)
end)

describe("assert.error_contains", function()
  it("passes when the message contains each text", function()
    assert.error_contains(function () lsys.lstring("F(1") end, "unbalanced", "'F'")
  end)

  it("shows the message raised when a text is missing, and fails without an error", function()
    has(failure(assert.error_contains, function () error("bad rule 'A'", 0) end, "rule 'B'"),
        "the error message\n  bad rule 'A'\ndoes not contain\n  rule 'B'")
    has(failure(assert.error_contains, function () end, "x"),
        "expected an error, but the call succeeded")
    has(failure(assert.error_contains, function () error("x") end, "x", 3),
        "assert.error_contains: the texts to look for must be strings (argument 3 is a number)")
  end)
end)

describe("testing.stats and assert.scene_stats", function()
  local m = lsys.lsystem { axiom = "F[+F]F", view = { angle = 90 } }

  it("counts what a scene holds and measures its bounds", function()
    local st = testing.stats(m:interpret())
    assert.same({ modules = 6, triangles = 0, vertices = 0, lines = 3, segments = 3,
                  records = 3, area = 0 },
                { modules = st.modules, triangles = st.triangles, vertices = st.vertices,
                  lines = st.lines, segments = st.segments, records = st.records,
                  area = st.area })
    assert.near({ { -1, 0, 0 }, { 0, 2, 0 } }, st.bounds, 1e-12)
    assert.near({ 1, 2, 0 }, st.size, 1e-12)
    assert.same(st, testing.stats(m))                 -- a Model is interpreted first
  end)

  it("passes on the given statistics and lists each that differs", function()
    assert.scene_stats(m:interpret(), { lines = 3, triangles = 0, size = { 1, 2, 0 } })
    local msg = failure(assert.scene_stats, m:interpret(),
                        { lines = 4, triangles = 0, bounds = { { -1, 0, 0 }, { 0, 3, 0 } } })
    has(msg, "scene statistics differ:\n  lines: 3, expected 4 (relative tolerance 1e-06)\n"
        .. "  bounds: {{-1, 0, 0}, {0, 2, 0}}, expected {{-1, 0, 0}, {0, 3, 0}} (relative "
        .. "tolerance 1e-06)\nthe scene: modules 6, triangles 0, vertices 0, lines 3, "
        .. "segments 3, records 3, area 0, bounds {{-1, 0, 0}, {0, 2, 0}}, size {1, 2, 0}")
    assert.falsy(msg:find("triangles: ", 1, true), msg)
  end)

  it("takes a relative tolerance, for all statistics or by statistic", function()
    local sc = m:interpret()
    assert.scene_stats(sc, { lines = 4 }, 0.5)
    assert.scene_stats(sc, { lines = 4, segments = 3 }, { lines = 0.5 })
    has(failure(assert.scene_stats, sc, { lines = 4, segments = 4 }, { lines = 0.5 }),
        "segments: 3, expected 4 (relative tolerance 1e-06)")
  end)

  it("says when nothing was drawn, and rejects an unknown statistic", function()
    has(failure(assert.scene_stats, lsys.lsystem { axiom = "f" }:interpret(),
                { bounds = { { 0, 0, 0 }, { 0, 0, 0 } } }), "bounds: none (nothing drawn)")
    has(failure(assert.scene_stats, m, { trianlges = 1 }),
        "assert.scene_stats: unknown statistic 'trianlges' (modules, triangles, vertices, "
        .. "lines, segments, records, area, bounds, size)")
    has(failure(assert.scene_stats, "F", { lines = 1 }),
        "assert.scene_stats: a Scene or a Model expected, got string")
  end)
end)

describe("testing.compare_images", function()
  local function image (w, h, f)
    local t = {}
    for y = 0, h - 1 do
      for x = 0, w - 1 do t[#t + 1] = string.char(f(x, y)) end
    end
    return table.concat(t)
  end
  local W, H0 = 20, 10
  local grey = image(W, H0, function () return 100, 100, 100, 255 end)

  it("passes pictures within the tolerance and reports the difference otherwise", function()
    local near = image(W, H0, function () return 101, 99, 100, 255 end)
    assert.is_true(testing.compare_images(grey, near, W, H0))
    local spot = image(W, H0, function (x, y)
      if x < 4 and y < 1 then return 200, 100, 100, 255 end        -- 4 pixels of 200: 2%
      return 100, 100, 100, 255
    end)
    local ok, why = testing.compare_images(grey, spot, W, H0)
    assert.is_false(ok)
    assert.equal("mean absolute difference R 2.00 G 0.00 B 0.00 A 0.00 (limit 2); 2.00% of "
                 .. "the pixels differ by more than 40 (limit 1%)", why)
    assert.is_true(testing.compare_images(grey, spot, W, H0, { mean = 3, fraction = 0.03 }))
    assert.is_false(testing.compare_images(grey, spot, W, H0, 0.03))   -- the mean still fails
    assert.equal("sizes differ: 800 and 796 bytes for 20x10",
                 select(2, testing.compare_images(grey, grey:sub(5), W, H0)))
  end)
end)

describe("assert.image_matches #gl", function()
  if not testing.can_render() then
    pending("lsys was built without OSMesa: image_matches on scenes skipped")
    return
  end
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)
  local m = lsys.lsystem { axiom = "F[+F]F[-F]F", view = { angle = 30, line_width = 4 } }

  it("writes a missing golden image, fails once saying so, then passes", function()
    local golden = dir .. "/golden/plant.png"
    has(failure(assert.image_matches, m, golden, { size = "64x48" }),
        golden .. " did not exist: this picture (64x48) is there now; look at it and run the "
        .. "test again (LSYS_UPDATE_GOLDEN=1 writes every golden image)")
    local _, w, h = core.png_read(golden)
    assert.same({ 64, 48 }, { w, h })
    assert.image_matches(m, golden, { size = { 64, 48 } })
    assert.image_matches(m:interpret(), golden, { size = "64x48" })
    assert.image_matches(golden, golden)                             -- a PNG file
    assert.image_matches({ lsys.render(m, { width = 64, height = 48 }) }, golden)
  end)

  it("keeps the picture that differs next to the golden image and names it", function()
    local golden = dir .. "/plant.png"
    local ok = pcall(assert.image_matches, m, golden, { size = 64 })
    assert.is_false(ok)                                       -- written now
    local other = lsys.lsystem { axiom = "F[-F]F[+F]F", view = { angle = 30, line_width = 4 } }
    local msg = failure(assert.image_matches, other, golden, { size = 64 })
    has(msg, golden .. ": mean absolute difference R ", "% of the pixels differ by more than 40 "
        .. "(limit 1%); this picture is " .. dir .. "/plant.actual.png (if the change is "
        .. "intended, look at it and write the golden image again with LSYS_UPDATE_GOLDEN=1)")
    assert.truthy(H.read(dir .. "/plant.actual.png"))
    assert.image_matches(other, golden, { size = 64, tolerance = { mean = 255, fraction = 1 } })
    assert.falsy(H.read(dir .. "/plant.actual.png"), "a match removes the old mismatch")
    has(failure(assert.image_matches, m, golden, { size = "64x32" }),
        "the golden image is 64x64, the picture 64x32")
  end)

  it("writes the golden image and passes with LSYS_UPDATE_GOLDEN=1", function()
    local golden = dir .. "/plant.png"
    H.write(golden, "not a PNG")
    local script = dir .. "/update.lua"
    H.write(script, ('local m = require("lsys").lsystem { axiom = "F[+F]F" }\n'
      .. 'require("luassert"); require("lsys.testing")\n'
      .. 'require("luassert").image_matches(m, %q, { size = 32 })\n'):format(golden))
    local out, code = H.sh("LSYS_UPDATE_GOLDEN=1 " .. H.ABSBIN .. " " .. script)
    assert.equal(0, code, out)
    assert.equal("lsys.testing: wrote " .. golden .. " (32x32; LSYS_UPDATE_GOLDEN=1)\n", out)
    assert.same({ 32, 32 }, { select(2, core.png_read(golden)) })
  end)

  it("rejects an unknown option and a bad size", function()
    has(failure(assert.image_matches, m, dir .. "/x.png", { tol = 1 }),
        "assert.image_matches: unknown option 'tol' (size, tolerance, render, actual)")
    has(failure(assert.image_matches, m, dir .. "/x.png", { size = "big" }),
        "assert.image_matches: bad size big: \"WxH\", {W, H} or one number of pixels")
    has(failure(assert.image_matches, dir .. "/none.png", dir .. "/x.png"),
        "assert.image_matches: cannot open '" .. dir .. "/none.png' for reading")
  end)
end)

describe("lsys test", function()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  -- `lsys test ARGS` in the folder dir; the output and exit status.
  local function lsys_test (args, env)
    return H.sh(("cd '%s' && %s %s test %s"):format(dir, env or "", H.ABSBIN, args or ""))
  end

  local GOOD = [[
local lsys = require "lsys"
require "lsys.testing"
local m = lsys.lsystem { axiom = "X", productions = "X --> F[+X]F[-X]+X\nF --> FF" }
describe("my plant", function()
  it("derives", function() assert.lstring_equal("F[+X]F[-X]+X", m:derive(1)) end)
  it("draws #lines", function() assert.scene_stats(m:interpret(m:derive(2)), { lines = 10 }) end)
end)
]]
  local BAD = [[
local lsys = require "lsys"
require "lsys.testing"
describe("wrong plant", function()
  it("derives", function()
    local m = lsys.lsystem { axiom = "X", productions = "X --> F[+X]F[-X]+X" }
    assert.lstring_equal("F[+X]F[-X]-X", m:derive(1))
  end)
end)
]]

  it("runs the *_spec.lua files of the current folder with lsys on the paths", function()
    os.execute("mkdir -p '" .. dir .. "/models'")
    H.write(dir .. "/models/plant_spec.lua", GOOD)
    H.write(dir .. "/notes.lua", "error('not a spec')")
    local out, code = lsys_test("-o plainTerminal")
    assert.equal(0, code, out)
    has(out, "2 successes / 0 failures / 0 errors / 0 pending")
  end)

  it("exits with 1 and shows the failure when a spec fails", function()
    H.write(dir .. "/good_spec.lua", GOOD)
    H.write(dir .. "/bad_spec.lua", BAD)
    local out, code = lsys_test("-o plainTerminal")
    assert.equal(1, code, out)
    has(out, "2 successes / 1 failure / 0 errors / 0 pending",
        "./bad_spec.lua:6: L-strings differ at module 11 of 12: expected a module named -, "
        .. "got +\n  expected: ...]F[-X]-X\n                     ^\n")
    out, code = lsys_test("-o plainTerminal good_spec.lua")
    assert.equal(0, code, out)
  end)

  it("takes spec/ by default when there is one, and passes busted's options on", function()
    os.execute("mkdir -p '" .. dir .. "/spec'")
    H.write(dir .. "/spec/plant_spec.lua", GOOD)
    H.write(dir .. "/bad_spec.lua", BAD)                       -- outside spec/: not run
    local out, code = lsys_test("-o plainTerminal")
    assert.equal(0, code, out)
    has(out, "2 successes / 0 failures")
    out, code = lsys_test("-o plainTerminal --exclude-tags lines")
    assert.equal(0, code, out)
    has(out, "1 success / 0 failures")
    out, code = lsys_test("-t lines -o plainTerminal spec")
    assert.equal(0, code, out)
    has(out, "1 success / 0 failures")
  end)

  it("works whatever `lua` and `busted` the PATH names (Debian's alternatives)", function()
    local bin = dir .. "/bin"
    os.execute("mkdir -p '" .. bin .. "'")
    H.write(bin .. "/lua", "#!/bin/sh\necho 'not Lua 5.4' >&2\nexit 3\n")
    H.write(bin .. "/busted", "#!/bin/sh\necho 'not busted' >&2\nexit 3\n")
    os.execute("chmod +x '" .. bin .. "/lua' '" .. bin .. "/busted'")
    H.write(dir .. "/plant_spec.lua", GOOD)
    H.write(dir .. "/.busted", 'return { default = { lua = "lua", ROOT = { "." } } }\n')
    local out, code = lsys_test("-o plainTerminal", "PATH='" .. bin .. ":'\"$PATH\"")
    assert.equal(0, code, out)
    has(out, "2 successes / 0 failures")
  end)

  it("passes the example of docs/testing.md, and fails it as the page shows", function()
    local doc = H.read("docs/testing.md")
    local model = doc:match("```lua\n(%-%- plant%.lua:.-)```")
    local spec = doc:match("```lua\n(%-%- spec/plant_spec%.lua:.-)```")
    assert.truthy(model and spec, "the page's plant.lua and spec/plant_spec.lua")
    os.execute("mkdir -p '" .. dir .. "/spec'")
    H.write(dir .. "/plant.lua", model)
    H.write(dir .. "/spec/plant_spec.lua", spec)
    local out, code = lsys_test("-o plainTerminal")
    if testing.can_render() then               -- the golden image is written, once
      assert.equal(1, code, out)
      has(out, "5 successes / 1 failure / 0 errors / 0 pending", "spec/golden/plant.png did "
          .. "not exist: this picture (200x200) is there now")
      out, code = lsys_test("-o plainTerminal")
    end
    assert.equal(0, code, out)
    has(out, "0 failures / 0 errors")
    -- section 3: R = 1.5 instead of 1.456; the page's messages, but the picture's numbers
    H.write(dir .. "/plant.lua", (model:gsub("R = 1%.456", "R = 1.5")))
    out, code = lsys_test("-o plainTerminal")
    assert.equal(1, code, out)
    local shown = doc:match("Say `R` in `plant.lua` becomes 1.5.-```\n(.-)```")
    for line in shown:gmatch("[^\n]+") do
      if not line:find("mean absolute difference", 1, true) then has(out, line) end
    end
  end)

  it("explains itself, and says how to get busted when it is missing", function()
    local out, code = H.sh(H.ABSBIN .. " test --help")
    assert.equal(0, code)
    has(out, "usage: lsys test [PATH...] [BUSTED OPTIONS]", "assert.lstring_equal")
    has(H.sh(H.ABSBIN .. " --help"), "lsys test [PATH...] [OPTS]")
    out, code = lsys_test("", "LUA_PATH='" .. dir .. "/?.lua'")
    assert.equal(1, code, out)
    assert.equal("lsys: busted is not installed for Lua 5.4: apt-get install lua-busted "
                 .. "(Debian, Ubuntu), or luarocks --lua-version 5.4 install busted\n", out)
  end)
end)
