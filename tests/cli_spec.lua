-- The lsys program: derive, errors that name the model file.
local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"

local function run (args)
  local p = io.popen(BIN .. " " .. args .. " 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return out:gsub("exit:%d+%s*$", ""), code
end

local function tmpmodel (text)
  local path = os.tmpname()
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
  return path
end

describe("lsys derive", function()
  it("prints the derived string of a model file", function()
    local path = tmpmodel('local lsys = require "lsys"\n' ..
      'return lsys.lsystem { axiom = "F", steps = 2, productions = "F --> F+F" }\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(0, code)
    assert.equal("F+F+F+F\n", out)
  end)

  it("prints counts with --stats and honours --steps and --set", function()
    local path = tmpmodel('local lsys = require "lsys"\n' ..
      'return lsys.lsystem { axiom = "A(1)", env = { K = 2 }, productions = "A(x) --> A(x*K)B" }\n')
    local out, code = run("derive " .. path .. " --steps 3 --set K=3 --stats")
    local out2 = run("derive " .. path .. " --steps 3 --set K=3")
    os.remove(path)
    assert.equal(0, code)
    assert.truthy(out:find("modules 4", 1, true))
    assert.truthy(out:find("B 3", 1, true))
    assert.equal("A(27)BBB\n", out2)
  end)

  it("names the model file when `return lsys.lsystem{...}` has a bad rule", function()
    local path = tmpmodel('local lsys = require "lsys"\n\nreturn lsys.lsystem {\n' ..
      '  axiom = "A",\n  productions = "A(s --> B",\n}\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(1, code)
    assert.truthy(out:find("lsys: " .. path .. ": rule 1 'A(s --> B' (line 1 of productions): " ..
                           "unbalanced parentheses: '(' without ')' at character 2", 1, true))
  end)

  it("names file and line when the model is returned through a local", function()
    local path = tmpmodel('local lsys = require "lsys"\nlocal m = lsys.lsystem {\n' ..
      '  productions = "A --> B\\nA(s) --> B(s*)",\n}\nreturn m\n')
    local out, code = run("derive " .. path)
    os.remove(path)
    assert.equal(1, code)
    assert.truthy(out:find(path .. ":2: rule 2 'A(s) --> B(s*)' (line 2 of productions): " ..
                           "bad expression 's*' in parameter 1 of 'B'", 1, true))
  end)

  it("exits with 2 and a hint on an unknown option", function()
    local out, code = run("derive --bogus")
    assert.equal(2, code)
    assert.truthy(out:find("unknown option '--bogus'", 1, true))
  end)
end)
