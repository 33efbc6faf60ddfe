-- A rule function that calls a method of its own model: the message names the
-- method called, also when that method would derive first (interpret with no string).
local lsys = require "lsys"
local H = require "tests.helper"

describe("a rule calling its own model", function ()
  it("is told which method it called", function ()
    local calls = {
      derive = function (m) m:derive(1) end,
      step = function (m) m:step("A") end,
      expand = function (m) m:expand("A") end,
      interpret = function (m) m:interpret("A") end,
      ["interpret (no string: it would derive)"] = function (m) m:interpret() end,
      use_group = function (m) m:use_group(0) end,
    }
    for name, call in pairs(calls) do
      local m
      m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
        call(m)
        return lsys.produce("B")
      end } } }
      local e = H.errof(m.derive, m, 1)
      local method = name:match("^%S+")
      assert.equal("rule 1 'A' (entry 1 of productions), module 1: a rule called " .. method
        .. " on the model it belongs to", e:match("rule 1 .*$"), name)
    end
  end)
end)
