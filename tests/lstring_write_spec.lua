-- Lstring:write: the text of a string streamed from C to a file or a path, the same bytes
-- as tostring; lsys derive writing its string that way.
local H = require "tests.helper"
local lsys = require "lsys"

describe("Lstring:write", function()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  local function message (f) return (H.errof(f):gsub("^[^:]*:%d+: ", "")) end

  local function written (s, tail)
    local path = dir .. "/s.txt"
    assert.equal(s, s:write(path, tail))
    return H.read(path)
  end

  it("writes tostring's bytes: spaces between names that would merge, parameters", function()
    local s = lsys.lstring("@ G ? P~ l F(1,0.5)[+A(0.1,-0,1e300)]B(0.30000000000000004)$%")
    assert.equal("@ G? P~ lF(1,0.5)[+A(0.1,-0,1e+300)]B(0.30000000000000004)$%", tostring(s))
    assert.equal(tostring(s), written(s))
  end)

  it("writes declared names apart from the names they begin with", function()
    local s = lsys.lstring("AB A B Apex A pex", "AB Apex")
    assert.equal("ABA BApexApe x", tostring(s))
    assert.equal(tostring(s), written(s))
  end)

  it("writes 'tail' after the text", function()
    assert.equal("F(2)[+G]\n", written(lsys.lstring("F(2)[+G]"), "\n"))
    assert.equal("", written(lsys.lstring("")))
  end)

  it("writes strings of many 64 KiB pieces as tostring does, merging names across them",
     function()
    local s = lsys.lstring(string.rep("@ G F(0.1)~ l?P(1,2)AB", 40000), "AB")
    local text = tostring(s)
    assert.equal(840000, #text)
    assert.equal(text, written(s))
    local d = lsys.lsystem { axiom = "A(1)", env = { R = 1.456 },
                             productions = "A(s) --> F(s)[+A(s/R)][-A(s/R)]" }:derive(14)
    assert.equal(131065, #d)
    assert.equal(tostring(d), written(d))
  end)

  it("writes, prints and counts a string a step made with one byte a module without "
     .. "widening it", function()
    local d = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F" }:derive(7)
    local bytes = d:bytes()
    assert.equal(195311, #d)
    assert.is_true(bytes < 2 * #d)                  -- one byte a module
    local text = written(d)
    assert.equal(bytes, d:bytes())
    assert.equal(text, tostring(d))
    assert.equal(78125, d:counts().F)
    assert.equal(bytes, d:bytes())
    assert.equal(text, tostring(lsys.lstring(text)))   -- as a wide string prints it
  end)

  it("writes to an open file and leaves it open", function()
    local path = dir .. "/f.txt"
    local f = assert(io.open(path, "wb"))
    f:write("<")
    lsys.lstring("F(1)G"):write(f, ">")
    f:write("!")
    f:close()
    assert.equal("<F(1)G>!", H.read(path))
  end)

  it("raises a clear error for a path it cannot write, and leaves the file there", function()
    local s = lsys.lstring("F")
    assert.equal("cannot open '" .. dir .. "/no/such.txt' for writing: No such file or directory",
      message(function () s:write(dir .. "/no/such.txt") end))
    H.write(dir .. "/keep.txt", "old")
    os.execute("chmod a-w '" .. dir .. "'")
    local writable = io.open(dir .. "/probe", "w")           -- root writes anyway
    if writable then writable:close() os.remove(dir .. "/probe") end
    if not writable then
      assert.matches("^cannot open '.*keep%.txt' for writing: ",
        message(function () s:write(dir .. "/keep.txt") end))
      assert.equal("old", H.read(dir .. "/keep.txt"))
    end
    os.execute("chmod u+w '" .. dir .. "'")
    if io.open("/dev/full", "w") then
      assert.equal("cannot write '/dev/full': No space left on device",
        message(function () lsys.lstring(string.rep("F", 100000)):write("/dev/full") end))
    end
  end)

  it("raises for a closed file and for a target that is neither file nor path", function()
    local s = lsys.lstring("F")
    local f = assert(io.open(dir .. "/c.txt", "w"))
    f:close()
    assert.matches("attempt to use a closed file", H.errof(function () s:write(f) end))
    assert.matches("file or path expected, got table", H.errof(function () s:write({}) end))
  end)

  it("is what lsys derive prints, with a newline", function()
    local path = dir .. "/m.lua"
    H.write(path, [[return require("lsys").lsystem { axiom = "A(1)", env = { R = 1.456 },
      steps = 9, productions = "A(s) --> F(s)[+A(s/R)][-A(s/R)]" }]])
    local out, code = H.sh(("'%s' derive '%s' > '%s/out.txt'"):format(H.BIN, path, dir))
    assert.equal("", out)
    assert.equal(0, code)
    local s = dofile(path):derive()
    assert.equal(tostring(s) .. "\n", H.read(dir .. "/out.txt"))
  end)

  it("makes lsys derive fail with the reason when its output cannot be written", function()
    if not io.open("/dev/full", "w") then return end
    local path = dir .. "/m.lua"
    H.write(path, [[return require("lsys").lsystem { axiom = "F", steps = 7,
      productions = "F --> F[+F]F[-F]F" }]])
    local out, code = H.sh(("'%s' derive '%s' > /dev/full"):format(H.BIN, path))
    assert.equal("lsys: cannot write the string: No space left on device\n", out)
    assert.equal(1, code)
  end)
end)
