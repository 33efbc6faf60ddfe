-- lsys's turtle against cpfg's: the cases of tests/data/cpfg_probes.lua, made by
-- tools/cpfg-probes.lua with cpfg as the oracle, are turtle sequences with query modules
-- (?P position, ?H ?L ?U frame) that cpfg filled in batch mode. lsys loads the same .l and
-- .v texts with lsys.cpfg.load; every query must report what cpfg's did, positions to 1e-4
-- of the step (cpfg prints six digits) and frames to 1e-5.
local H = require "tests.helper"
local cpfg = require "lsys.cpfg"

local CASES = dofile "tests/data/cpfg_probes.lua"

-- The query modules of a string's text, in order: { name, x, y, z }.
local function queries (text)
  local out = {}
  for name, args in text:gmatch("%?([PHLU])(%b())") do
    local v = {}
    for x in args:sub(2, -2):gmatch("[^,]+") do v[#v + 1] = tonumber(x) end
    out[#out + 1] = { name, v[1], v[2], v[3] }
  end
  return out
end

describe("the turtle as cpfg's (tests/data/cpfg_probes.lua)", function ()
  local dir
  setup(function () dir = H.tmpdir() end)
  teardown(function () H.rmdir(dir) end)

  it("has the oracle's cases", function ()
    assert.is_true(#CASES >= 20)
    local n = 0
    for _, c in ipairs(CASES) do n = n + #queries(c.cpfg) end
    assert.is_true(n >= 200, n)
  end)

  for _, c in ipairs(CASES) do
    it(c.name, function ()
      H.write(dir .. "/p.l", c.l)
      H.write(dir .. "/p.v", c.v)
      local m = cpfg.load(dir .. "/p.l", dir .. "/p.v")
      local got, want = queries(tostring(m:derive())), queries(c.cpfg)
      assert.equal(#want, #got)
      for k, w in ipairs(want) do
        local g = got[k]
        local tol = w[1] == "P" and 1e-4 * math.max(1, math.abs(w[2]), math.abs(w[3]),
                                                    math.abs(w[4])) or 1e-5
        local ok = g[1] == w[1]
        for i = 2, 4 do ok = ok and math.abs(g[i] - w[i]) <= tol end
        if not ok then
          error(string.format("query %d: lsys ?%s(%.6g,%.6g,%.6g), cpfg ?%s(%g,%g,%g)", k,
                              g[1], g[2], g[3], g[4], w[1], w[2], w[3], w[4]), 0)
        end
      end
    end)
  end
end)
