-- Rules the test suite keeps about itself (issue 34): specs assert behaviour, never time.
-- A timing belongs in a benchmark under bench/ (a loaded machine must not fail the suite).

-- The lines of every spec, as { file, number, text }.
local function speclines ()
  local out = {}
  local p = assert(io.popen("ls tests/*_spec.lua"))
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
  local lines = speclines()

  it("has specs to check", function ()
    assert.is_true(#lines > 1000)
    assert.same({ "tests/hygiene_spec.lua:1: x" },
                offenders({ { "tests/hygiene_spec.lua", 1, "x" } }, "x"))
  end)

  it("measures no CPU or wall time in a spec", function ()
    local self = "tests/hygiene_spec.lua"
    assert.same({}, offenders(lines, "os%.clock", function (l) return l[1] == self end))
    -- os.time may bound a wait (a timeout), never sit in an assertion
    assert.same({}, offenders(lines, "assert[%w_.]*%(.*os%.time"))
  end)
end)
