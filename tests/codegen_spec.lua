-- lsys.codegen: text from elsewhere stays text in the Lua source lsys writes
-- (lsys import, sketch:save_model), and a written source reaches only what it was meant to.
local codegen = require "lsys.codegen"

-- Every byte: the text a hostile file name or comment could hold.
local ALL = {}
for b = 0, 255 do ALL[#ALL + 1] = string.char(b) end
ALL = table.concat(ALL)

describe("lsys.codegen", function ()
  it("writes any string as a one-line literal that reads back as itself", function ()
    for _, s in ipairs { ALL, "a\nb", "\r", "x\\\n", "]]", "\"'", "" } do
      local lit = codegen.string(s)
      assert.is_nil(lit:find("[\n\r]"), lit)
      assert.equal(s, load("return " .. lit)())
    end
  end)

  it("writes any text as one comment line that ends where the line does", function ()
    for _, s in ipairs { ALL, "x\ros.exit(3) --\r", "[[ long", "\n" } do
      local c = codegen.comment(s)
      assert.is_nil(c:find("%c"), c)
      assert.equal("-- ", c:sub(1, 3))
      -- the line is all comment: a statement after it on the next line is the only code
      assert.equal(7, load(c .. "\nreturn 7")())
    end
    assert.equal("--", codegen.comment(""))
    assert.equal("-- a\\13b\\10c  d", codegen.comment("a\rb\nc\td"))
  end)

  it("writes names as fields and other keys in brackets", function ()
    assert.equal("abc", codegen.key("abc"))
    assert.equal('["end"]', codegen.key("end"))
    assert.equal('["a b"]', codegen.key("a b"))
    assert.equal("[3]", codegen.key(3))
    assert.equal("F.x_1", codegen.index("F", "x_1"))
    assert.equal('F["x = os.exit() --"]', codegen.index("F", "x = os.exit() --"))
  end)

  it("checks a written source among stand-ins", function ()
    local allow = { modules = { lsys = true }, calls = { ["lsys.lsystem"] = true },
                    globals = { pairs = pairs, error = error } }
    assert.is_true(codegen.check('local lsys = require "lsys"\nfor _ in pairs({}) do end\n' ..
                                 "return lsys.lsystem { dir = lsys.here .. 'x' }", "m.lua", allow))
    local function refused (src)
      local ok, e = pcall(codegen.check, src, "m.lua", allow)
      assert.is_false(ok)
      return e
    end
    assert.equal("m.lua reaches the global 'os' when loaded (it may reach only what it was " ..
                 "written to)", refused("os.execute('x')"))
    assert.equal("m.lua reaches requires io when loaded (it may reach only what it was " ..
                 "written to)", refused("require('io')"))
    assert.equal("m.lua reaches calls lsys.render when loaded (it may reach only what it was " ..
                 "written to)", refused("require('lsys').render()"))
    assert.equal("m.lua reaches sets the global 'x' when loaded (it may reach only what it was " ..
                 "written to)", refused("x = 1"))
    assert.equal("m.lua reaches changes lsys.x when loaded (it may reach only what it was " ..
                 "written to)", refused("require('lsys').x = 1"))
    assert.equal("m.lua fails when loaded among stand-ins: boom", refused("error('boom', 0)"))
    assert.truthy(refused("return ("):find("^m.lua does not compile: "))
  end)
end)
