-- Hooks start, start_each, end_each, finish, and rule groups with use_group.
local lsys = require "lsys"

describe("hooks", function()
  it("are called in the order start, start_each/end_each per step, finish", function()
    local log = {}
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB",
      start = function() log[#log + 1] = "start" end,
      start_each = function(_, step) log[#log + 1] = "start_each " .. step end,
      end_each = function(_, s, step) log[#log + 1] = "end_each " .. step .. " " .. tostring(s) end,
      finish = function(_, s) log[#log + 1] = "finish " .. tostring(s) end,
    }
    m:derive(2)
    assert.same({ "start", "start_each 1", "end_each 1 AB", "start_each 2", "end_each 2 ABB",
                  "finish ABB" }, log)
  end)

  it("derive(0) calls start and finish but no per-step hook", function()
    local log = {}
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB",
      start = function() log[#log + 1] = "start" end,
      start_each = function() log[#log + 1] = "start_each" end,
      end_each = function() log[#log + 1] = "end_each" end,
      finish = function(_, s) log[#log + 1] = "finish " .. tostring(s) end,
    }
    m:derive(0)
    assert.same({ "start", "finish A" }, log)
  end)

  it("an error in a hook reaches the caller", function()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB",
                             start_each = function() error("hook failed") end }
    assert.error_contains(function() m:derive(2) end, "hook failed")
  end)

  it("receive the model as their first argument", function()
    local got = {}
    local m
    m = lsys.lsystem {
      axiom = "A", productions = "A --> AB",
      start = function(model) got.start = model end,
      start_each = function(model) got.start_each = model end,
      end_each = function(model) got.end_each = model end,
      finish = function(model) got.finish = model end,
    }
    m:derive(1)
    assert.equal(m, got.start)
    assert.equal(m, got.start_each)
    assert.equal(m, got.end_each)
    assert.equal(m, got.finish)
  end)

  it("run again on every derive", function()
    local starts = 0
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB",
                             start = function() starts = starts + 1 end }
    m:derive(1)
    m:derive(3)
    assert.equal(2, starts)
  end)

  it("end_each may return a replacement Lstring that the next step uses", function()
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB\nX --> Y",
      end_each = function(_, _, step) if step == 1 then return lsys.lstring("X") end end,
    }
    assert.equal("Y", tostring(m:derive(2)))
  end)

  it("end_each's replacement of the last step is the result", function()
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB",
      end_each = function(_, s) return s:sub(1, 1) end,
    }
    assert.equal("A", tostring(m:derive(3)))
  end)

  it("end_each returning nothing keeps the derived string", function()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB",
                             end_each = function() end }
    assert.equal("ABB", tostring(m:derive(2)))
  end)

  it("start_each can change env for the step it starts", function()
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> B(k)\nB(x) --> B(x+k)", env = { k = 0 },
      start_each = function(model, step) model.env.k = step * 10 end,
    }
    assert.equal("B(30)", tostring(m:derive(2)))
  end)

  it("finish receives the final string", function()
    local final
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB",
                             finish = function(_, s) final = tostring(s) end }
    m:derive(3)
    assert.equal("ABBB", final)
  end)
end)

describe("rule groups", function()
  local function model (extra)
    local t = { axiom = "AB", productions = "B --> D",
                groups = { [1] = "A --> C", [2] = "A --> E" } }
    for k, v in pairs(extra or {}) do t[k] = v end
    return lsys.lsystem(t)
  end

  it("only group 0 (productions) is active at first", function()
    assert.equal("AD", tostring(model():derive(1)))
  end)

  it("use_group(n) activates group n beside group 0", function()
    local m = model()
    m:use_group(1)
    assert.equal("CD", tostring(m:derive(1)))
  end)

  it("use_group(n) switches from one group to another", function()
    local m = model()
    m:use_group(1)
    m:use_group(2)
    assert.equal("ED", tostring(m:derive(1)))
  end)

  it("use_group(0) leaves only group 0", function()
    local m = model()
    m:use_group(1)
    m:use_group(0)
    assert.equal("AD", tostring(m:derive(1)))
  end)

  it("can be switched between steps from start_each", function()
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB", groups = { [1] = "B --> C" },
      start_each = function(self, step) self:use_group(step == 2 and 1 or 0) end,
    }
    -- step 1: AB; step 2 (group 1): ABC; step 3 (group 0): ABBC
    assert.equal("ABBC", tostring(m:derive(3)))
  end)
end)

describe("derive's each option", function()
  it("hands over the string of every step, to keep, after end_each and finish", function()
    local m = lsys.lsystem {
      axiom = "A", productions = "A --> AB\nB --> C",
      end_each = function(_, s, step)
        if step == 2 then return lsys.lstring("X" .. tostring(s)) end
      end,
      finish = function(_, s) return lsys.lstring(tostring(s) .. "Z") end,
    }
    local kept = {}
    local r = m:derive(4, { each = function(k, s) kept[k] = s end })
    -- kept strings stay intact: derive does not recycle their buffers
    local texts = {}
    for k = 0, 4 do texts[k + 1] = tostring(kept[k]) end
    assert.same({ "A", "AB", "XABC", "XABCC", "XABCCCZ" }, texts)
    assert.equal(r, kept[4])
    local zero = {}
    assert.equal("AZ", tostring(m:derive(0, { each = function(k, s) zero[k] = s end })))
    assert.equal("AZ", tostring(zero[0]))
    assert.is_nil(zero[1])
  end)
end)
