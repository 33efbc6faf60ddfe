-- Memory safety, safe outputs, bounded memory: each finding of the audit (issue 13) with
-- the test that fails before its fix.
require "tests.helper"
local lsys = require "lsys"

local function errof (f, ...)
  local ok, err = pcall(f, ...)
  assert.is_false(ok, "expected an error")
  return tostring(err)
end

local function tmpdir ()
  local d = os.tmpname()
  os.remove(d)
  assert(os.execute("mkdir -p '" .. d .. "'"))
  return d
end

local function rmdir (d) os.execute("rm -rf '" .. d .. "'") end

local function exists (path)
  local f = io.open(path, "rb")
  if f then f:close() return true end
  return false
end

describe("rule expressions", function ()
  local marker
  before_each(function () marker = os.tmpname(); os.remove(marker) end)
  after_each(function () os.remove(marker) end)

  -- each rule must fail at definition or derivation without touching the marker
  local function hostile (rule)
    local err = errof(function ()
      local m = lsys.lsystem { axiom = "A(1)", productions = { (rule:gsub("MARKER", marker)) } }
      return m:derive(1)
    end)
    assert.is_false(exists(marker), "the rule ran its command: " .. rule)
    return err
  end

  it("do not reach globals after the concatenation operator", function ()
    local err = hostile('A(x) --> A(#(""..os.execute("touch MARKER")))')
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
    err = hostile('A(x) --> A(x) B(#(""..io.open("MARKER", "w")))')
    assert.truthy(err:find("unknown name 'io'", 1, true), err)
    err = hostile('A(x) : ""..os.exit(3) --> A(x)')
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
  end)

  it("run in an environment without globals when the name scan is fooled", function ()
    -- the scan takes the comment's quote for a string and misses `os`; the compiled
    -- closure still cannot see it
    local err = hostile([[A(x) --> A(x --"
 + #os.getenv'HOME' --"
)]])
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
    err = hostile([[A(x) --> A(x --"
 + #_G.os.getenv'HOME' --"
)]])
    assert.truthy(err:find("unknown name '_G'", 1, true), err)
  end)

  it("cannot end the generated closure with a line comment", function ()
    -- each expression stands on its own lines: the comment ends with the expression
    local m = lsys.lsystem { axiom = "A(1)", productions = { "A(x) --> A(x + 1 --\n) B(x * 2)" } }
    assert.equal("A(2)B(2)", tostring(m:derive(1)))
  end)

  it("still see parameters, env, ran and the builtins", function ()
    local m = lsys.lsystem { axiom = "A(1)", env = { k = 3 }, seed = 1,
      productions = 'A(x) --> A(x + k) B(floor(pi)) C(#("ab" .. x)) D(math.max(x, 2))' }
    assert.equal("A(4)B(3)C(5)D(2)", tostring(m:derive(1)))
  end)
end)
