-- Rules the tree keeps about itself (issue 34), so that a class of bug cannot come back:
-- specs assert behaviour, never time (a timing belongs in a benchmark under bench/: a
-- loaded machine must not fail the suite); text goes into generated Lua only through
-- lsys.codegen.

-- The lines of the files `ls` lists for `glob`, as { file, number, text }.
local function readlines (glob)
  local out = {}
  local p = assert(io.popen("ls " .. glob))
  for file in p:lines() do
    local n = 0
    for line in io.lines(file) do
      n = n + 1
      out[#out + 1] = { file, n, line }
    end
  end
  p:close()
  return out
end

-- The places where `pat` matches outside a comment, as "file:line: text".
local function offenders (lines, pat, except)
  local out = {}
  for _, l in ipairs(lines) do
    local code = l[3]:gsub("%-%-.*$", "")
    if code:find(pat) and not (except and except(l)) then
      out[#out + 1] = ("%s:%d: %s"):format(l[1], l[2], l[3])
    end
  end
  return out
end

describe("the suite", function ()
  local specs = readlines("tests/*_spec.lua")

  it("has specs to check", function ()
    assert.is_true(#specs > 1000)
    assert.same({ "tests/hygiene_spec.lua:1: x" },
                offenders({ { "tests/hygiene_spec.lua", 1, "x" } }, "x"))
  end)

  it("measures no CPU or wall time in a spec", function ()
    local self = "tests/hygiene_spec.lua"
    assert.same({}, offenders(specs, "os%.clock", function (l) return l[1] == self end))
    -- os.time may bound a wait (a timeout), never sit in an assertion
    assert.same({}, offenders(specs, "assert[%w_.]*%(.*os%.time"))
  end)

  it("quotes text for generated Lua only through lsys.codegen", function ()
    -- %q elsewhere only shows a value in a message or makes a key, never writes code
    local shown = { ["lua/lsys/repl.lua"] = 1, ["lua/lsys/population.lua"] = 2,
                    ["lua/lsys/components/graph.lua"] = 1, ["lua/lsys/frames.lua"] = 1 }
    local src = readlines("lua/lsys/*.lua lua/lsys/*/*.lua")
    assert.is_true(#src > 10000)
    local count = {}
    for _, o in ipairs(offenders(src, "%%q", function (l)
      return l[1] == "lua/lsys/codegen.lua"
    end)) do
      local file = o:match("^[^:]*")
      count[file] = (count[file] or 0) + 1
      if not shown[file] or count[file] > shown[file] then
        error("text quoted with %q outside lsys.codegen: " .. o)
      end
    end
  end)
end)
