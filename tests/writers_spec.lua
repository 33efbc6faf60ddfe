-- Every file the Lua side writes is whole or absent (issue 34 §6): lsys.core's writers
-- (core.outfile, core.tempdir).
local H = require "tests.helper"
local core = require "lsys.core"
local q = require("lsys.text").shq

local sh = H.sh

-- The entries of a folder, sorted ("." and ".." left out, hidden ones in).
local function ls (dir)
  local t = {}
  for f in sh("ls -1A " .. q(dir)):gmatch("[^\n]+") do t[#t + 1] = f end
  return t
end

describe("core.outfile", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("writes beside the target and replaces it only at commit", function ()
    H.write(dir .. "/a.txt", "old")
    local o = core.outfile(dir .. "/a.txt")
    assert.equal(o, o:write("new ", 42, "\n"))
    assert.equal("old", H.read(dir .. "/a.txt"))
    assert.equal(2, #ls(dir))
    assert.is_true(o:commit())
    assert.equal("new 42\n", H.read(dir .. "/a.txt"))
    assert.same({ "a.txt" }, ls(dir))
    assert.has_error(function () o:write("x") end,
                     "outfile:write: the output was committed or aborted")
    assert.has_error(function () o:commit() end,
                     "outfile:commit: the output was committed or aborted")
    assert.equal("lsys.Outfile '" .. dir .. "/a.txt' (closed)", tostring(o))
  end)

  it("leaves the target as it was at an abort, an error or a collection", function ()
    H.write(dir .. "/a.txt", "old")
    local o = core.outfile(dir .. "/a.txt")
    o:write("partial")
    o:abort()
    o:abort()
    assert.same({ "a.txt" }, ls(dir))
    pcall(function ()
      local o2 <close> = core.outfile(dir .. "/a.txt")
      o2:write("partial")
      error("stop")
    end)
    assert.same({ "a.txt" }, ls(dir))
    core.outfile(dir .. "/a.txt"):write("lost")
    collectgarbage()
    collectgarbage()
    assert.same({ "a.txt" }, ls(dir))
    assert.equal("old", H.read(dir .. "/a.txt"))
  end)

  it("hands a new file of its own to another program", function ()
    H.write(dir .. "/a.txt", "old")
    local o = core.outfile(dir .. "/a.txt")
    local name = o:name()
    assert.equal(name, o:name())
    assert.truthy(name:find("^" .. dir:gsub("%p", "%%%0") .. "/%.a%.txt%.lsys%-%d+%-%d+%.tmp$"),
                  name)
    assert.has_error(function () o:write("x") end,
      "outfile:write: the file was handed to another program (name())")
    assert(os.execute("echo made > " .. q(name)))
    assert.equal("old", H.read(dir .. "/a.txt"))
    o:commit()
    assert.equal("made\n", H.read(dir .. "/a.txt"))
    assert.same({ "a.txt" }, ls(dir))
  end)

  it("names the file it cannot write, and checks every write", function ()
    assert.has_error(function () core.outfile(dir .. "/no/a.txt") end,
                     "cannot open '" .. dir .. "/no/a.txt' for writing: No such file or directory")
    local o = core.outfile("/dev/full")
    assert.equal("/dev/full", o:name())
    o = core.outfile("/dev/full")
    assert.has_error(function () o:write(("x"):rep(70000)) end,   -- more than the buffer
                     "cannot write '/dev/full': No space left on device")
    assert.has_error(function () o:write({}) end,
                     "outfile:write: the output was committed or aborted")
    o = core.outfile("/dev/full")
    o:write("x")
    assert.has_error(function () o:commit() end,
                     "cannot write '/dev/full': No space left on device")
    assert.has_error(function () core.outfile(dir .. "/a.txt"):write({}) end,
                     "bad argument #1 to 'write' (string expected, got table)")
  end)
end)

describe("core.tempdir", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("makes a new private folder under TMPDIR, removed with the files in it", function ()
    local t = core.tempdir(dir, "frames")
    local p = t:path()
    assert.truthy(p:find("^" .. dir:gsub("%p", "%%%0") .. "/frames%-......$"), p)
    assert.equal("drwx------\n", sh("stat -c %A " .. q(p)))
    H.write(dir .. "/victim", "keep")
    assert(os.execute(("ln -s %s %s/link && echo x > %s/f.png"):format(q(dir .. "/victim"),
                                                                         q(p), q(p))))
    assert.is_true(t:remove())
    assert.same({ "victim" }, ls(dir))
    assert.equal("keep", H.read(dir .. "/victim"))
    assert.equal("lsys.Tempdir (removed)", tostring(t))
    assert.has_error(function () t:path() end, "tempdir:path: the folder was removed")
    do local t2 <close> = core.tempdir(dir) assert.truthy(t2:path():find("/lsys%-")) end
    assert.same({ "victim" }, ls(dir))
    assert.has_error(function () core.tempdir(dir .. "/none") end,
      "cannot make a temporary folder in '" .. dir .. "/none': No such file or directory")
  end)

  it("names TMPDIR when it is missing", function ()
    local out, code = H.lsys("require('lsys.core').tempdir()", { env = "TMPDIR=" .. dir
      .. "/none" })
    assert.equal(1, code)
    assert.equal("cannot make a temporary folder in '" .. dir .. "/none' (TMPDIR): No such "
      .. "file or directory\n", out:match("^lsys: [^:]*:1: (.*)$"))
  end)
end)
