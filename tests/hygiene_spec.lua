-- Rules the tree keeps about itself, so that a class of bug cannot come back:
-- specs assert behaviour, never time (a timing belongs in a benchmark under bench/: a
-- loaded machine must not fail the suite); text goes into generated Lua only through
-- lsys.codegen; the library writes files through one writer (§6), lsys.core's
-- (core.write_file, core.outfile, core.tempdir: a new temporary file, checked writes, a
-- rename); the C tests write in a private temporary folder of their own (tests/c/testdir.h).

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
    local src = readlines("lua/lsys/*.lua lua/lsys/*/*.lua lua/lsys/*/*/*.lua")
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

-- The Lua files under lua/, as { path, text }.
local function luafiles ()
  local out = {}
  local p = assert(io.popen("find lua -name '*.lua' | sort"))
  for path in p:lines() do
    local f = assert(io.open(path, "rb"))
    out[#out + 1] = { path, f:read("a") }
    f:close()
  end
  p:close()
  return out
end

-- `text` with its comments blanked out (newlines kept, so positions keep their lines).
local function uncomment (text)
  local function blank (c) return (c:gsub("[^\n]", " ")) end
  text = text:gsub("()%-%-%[(=*)%[.-%]%2%]()", function (a, _, b)
    return blank(text:sub(a, b - 1))
  end)
  return (text:gsub("%-%-[^\n]*", blank))
end

--[[
The places in `files` ({ path, text }) that write a file without lsys.core's writer, as
"path:line: code": io.open with a mode that writes or appends ("w", "a", "+"), or a mode
that is not a literal; io.open taken as a value (an alias would hide the calls);
io.output with a file; os.tmpname (a name in /tmp, whatever TMPDIR says, reopened later).
]]
local function writers (files)
  local out = {}
  for _, f in ipairs(files) do
    local path, code = f[1], uncomment(f[2])
    local function add (pos)
      local line = select(2, code:sub(1, pos):gsub("\n", "")) + 1
      local text = f[2]:match("[^\n]*", (code:sub(1, pos):find("[^\n]*$")))
      out[#out + 1] = ("%s:%d: %s"):format(path, line, (text:gsub("^%s+", "")))
    end
    for pos, args in code:gmatch("()io%.open%s*(%b())") do
      args = args:sub(2, -2)
      local mode = select(2, args:match(",%s*([\"'])(.-)%1%s*$"))
      local commas = select(2, args:gsub("%b()", ""):gsub("%b{}", ""):gsub(",", ""))
      if (commas > 0 and mode == nil) or (mode and mode:find("[wa+]")) then add(pos) end
    end
    for pos in code:gmatch("()io%.open%f[^%w_]") do
      if not code:find("^io%.open%s*%(", pos) then add(pos) end
    end
    for pos in code:gmatch("()io%.output%s*%(") do add(pos) end
    for pos in code:gmatch("()os%.tmpname") do add(pos) end
  end
  table.sort(out)
  return out
end

-- The places that may write by themselves, each with why: "path: code" (no line number).
local ALLOWED = {
  -- batch's JSON-lines manifest: lines appended, one a job, read back line by line
  ["lua/lsys/batch/manifest.lua: local f, err = io.open(path, \"ab\")   -- the manifest: " ..
   "appended, every write checked (append)"] = true,
}

describe("the library", function ()
  it("finds every way of writing a file by hand", function ()
    local sample = table.concat({
      'local a = io.open(p, "w")',
      'local b = io.open(p, "rb")   -- io.open(p, "w") in a comment',
      'local c = io.open(p)',
      'local d = io.open(p, mode)',
      'local e = io.open(name(x, y), "a+b")',
      'local open = io.open',
      '--[[ io.open(p, "w") ]] local t = os.tmpname()',
      'io.output("x")',
    }, "\n")
    assert.same({
      "x.lua:1: local a = io.open(p, \"w\")",
      "x.lua:4: local d = io.open(p, mode)",
      "x.lua:5: local e = io.open(name(x, y), \"a+b\")",
      "x.lua:6: local open = io.open",
      "x.lua:7: --[[ io.open(p, \"w\") ]] local t = os.tmpname()",
      "x.lua:8: io.output(\"x\")",
    }, writers({ { "x.lua", sample } }))
  end)

  it("writes files only through lsys.core's writer, but for the few listed", function ()
    local found, seen = {}, {}
    for _, w in ipairs(writers(luafiles())) do
      local key = w:gsub(":%d+: ", ": ", 1)
      seen[key] = true
      if not ALLOWED[key] then found[#found + 1] = w end
    end
    -- core.write_file(path, bytes), core.outfile(path) (:write, :name for a program, :commit),
    -- core.tempdir() for files that are not outputs
    assert.same({}, found)
    for key in pairs(ALLOWED) do
      assert.is_true(seen[key] ~= nil, "allowed but gone (take it off the list): " .. key)
    end
  end)
end)

--[[
The C tests (tests/c/) write their files in a folder of their own, which testdir.h makes
with mkdtemp under $TMPDIR and removes at exit: no fixed name in /tmp that two runs at
once would share, nothing left behind.
]]
describe("the C tests", function ()
  local H = require "tests.helper"
  local BUILD = os.getenv("LSYS_BUILD_DIR") or "build"

  -- The C sources' code lines (comments blanked) that name /tmp or make a temporary
  -- name themselves, as "file:line: text".
  local function own_temporaries ()
    local out = {}
    local p = assert(io.popen("ls tests/c/*.c tests/c/*.h"))
    for file in p:lines() do
      if file ~= "tests/c/testdir.h" then
        local f = assert(io.open(file, "rb"))
        local code = f:read("a"):gsub("/%*.-%*/", function (c) return (c:gsub("[^\n]", " ")) end)
        f:close()
        local n = 0
        for line in (code .. "\n"):gmatch("([^\n]*)\n") do
          n = n + 1
          if line:find('"/tmp', 1, true) or line:find("%f[%w_]mkdtemp%s*%(")
             or line:find("%f[%w_]mkstemp%s*%(") or line:find("%f[%w_]tmpnam%s*%(") then
            out[#out + 1] = ("%s:%d: %s"):format(file, n, line:gsub("^%s+", ""))
          end
        end
      end
    end
    p:close()
    return out
  end

  it("name no file in /tmp and make no temporary name but through testdir.h", function ()
    assert.same({}, own_temporaries())
  end)

  it("write into a new folder under $TMPDIR and leave nothing there", function ()
    local p = assert(io.popen("grep -l '#include \"testdir.h\"' tests/c/test_*.c"))
    local tests = {}
    for file in p:lines() do tests[#tests + 1] = file:match("tests/c/(test_[%w_]+)%.c$") end
    p:close()
    assert.is_true(#tests >= 9, table.concat(tests, " "))
    local tmp = H.tmpdir()
    for _, t in ipairs(tests) do
      -- (test_envproc takes seconds: it checks its own folder is empty at its end)
      if t ~= "test_envproc" then
        local bin = BUILD .. "/" .. t
        if not H.sh("ls " .. bin .. " 2>/dev/null"):find(t, 1, true) then
          H.rmdir(tmp)
          pending(bin .. " is not built (cmake with LSYS_BUILD_TESTS=ON builds it)")
          return
        end
        local out, code = H.sh(("TMPDIR='%s' '%s' 2>&1"):format(tmp, bin))
        assert.equal(0, code, t .. ": " .. out)
        assert.equal("", H.sh("ls -A '" .. tmp .. "'"), t .. " left files")
      end
    end
    H.rmdir(tmp)
  end)
end)
