-- Every file the Lua side writes is whole or absent: lsys.core's
-- writers (core.outfile, core.tempdir), lsys.animate and lsys components graph against
-- planted links, TMPDIR, a user path that reads as an option, and the program's Ctrl-C and
-- SIGTERM, which remove the temporaries and leave an existing output as it was.
-- ctest: slow (writes large strings and files through the program)
local H = require "tests.helper"
local core = require "lsys.core"
local q = require("lsys.util.text").shq

local sh, ABSBIN = H.sh, H.ABSBIN

-- The entries of a folder, sorted ("." and ".." left out, hidden ones in).
local function ls (dir)
  local t = {}
  for f in sh("ls -1A " .. q(dir)):gmatch("[^\n]+") do t[#t + 1] = f end
  return t
end

local function have (prog) return (sh("command -v " .. prog)) ~= "" end

-- Links named as older writers named their temporary files (NAME and a
-- time, from a second ago to a minute ahead), each pointing at `victim`.
local function plant (dir, name, form, victim)
  local now = os.time()
  for t = now - 1, now + 60 do
    assert(os.execute(("ln -s %s %s"):format(q(victim), q(dir .. "/" .. form:format(name, t)))))
  end
end

-- Links in a folder (the planted ones), as "name -> target".
local function links (dir)
  local t = {}
  for _, f in ipairs(ls(dir)) do
    local target = sh("readlink " .. q(dir .. "/" .. f)):gsub("\n$", "")
    if target ~= "" then t[#t + 1] = f end
  end
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

describe("lsys components graph", function ()
  local MODEL = [[
local A = { kind = "simple", name = "A", params = {}, links = {} }
local B = { kind = "horn", name = "B", params = {}, links = {} }
A.links[1] = { type = "child", to = B }
return A
]]
  local dir
  before_each(function ()
    dir = H.tmpdir()
    H.write(dir .. "/m.lua", MODEL)
  end)
  after_each(function () H.rmdir(dir) end)

  local function graph (args, env)
    return sh(("cd %s && %s %s components graph m.lua %s"):format(q(dir), env or "", q(ABSBIN),
                                                                   args))
  end

  it("writes no file through a link planted where it writes aside (§6)", function ()
    H.write(dir .. "/victim", "secret")
    plant(dir, "g.dot", "%s.%d-1.part", dir .. "/victim")
    plant(dir, "g.svg", "%s.%d-1.part", dir .. "/victim")
    local nlinks = #links(dir)
    local out, code = graph("-o g.dot")
    assert.equal(0, code, out)
    assert.equal("secret", H.read(dir .. "/victim"))
    assert.truthy(H.read(dir .. "/g.dot"):find("^digraph"))
    assert.equal(nlinks, #links(dir))
    if not have("dot") then pending("Graphviz's dot is not installed") return end
    out, code = graph("-o g.svg")
    assert.equal(0, code, out)
    assert.equal("secret", H.read(dir .. "/victim"))
    assert.truthy(H.read(dir .. "/g.svg"):find("<svg", 1, true))
    assert.equal(nlinks, #links(dir))
  end)

  it("gives dot an output named like an option as a file (§14)", function ()
    if not have("dot") then pending("Graphviz's dot is not installed") return end
    local out, code = graph("-o -Tx.svg")
    assert.equal(0, code, out)
    assert.equal("wrote -Tx.svg\n", out)
    assert.truthy(H.read(dir .. "/-Tx.svg"):find("<svg", 1, true))
    assert.same({ "-Tx.svg", "m.lua" }, ls(dir))
  end)

  it("keeps dot's input in a private folder under TMPDIR, removed afterwards", function ()
    if not have("dot") then pending("Graphviz's dot is not installed") return end
    assert(os.execute("mkdir " .. q(dir .. "/tmp")))
    -- a dot that shows where its input is
    H.write(dir .. "/dot", "#!/bin/sh\nfor a; do last=$a; done\nls -ld \"$last\" >&2\n" ..
      "stat -c %A \"$(dirname \"$last\")\" >&2\nexit 3\n")
    assert(os.execute("chmod +x " .. q(dir .. "/dot")))
    local out, code = graph("-o g.svg", "PATH=" .. q(dir) .. ":$PATH TMPDIR=" .. q(dir .. "/tmp"))
    assert.equal(1, code, out)
    assert.truthy(out:find(" " .. dir:gsub("%p", "%%%0") .. "/tmp/lsys%-graph%-....../"), out)
    assert.truthy(out:find("\ndrwx------\n", 1, true), out)
    assert.same({}, ls(dir .. "/tmp"))
    assert.same({ "dot", "m.lua", "tmp" }, ls(dir))
  end)
end)

describe("#gl lsys animate", function ()
  if not core.has_render then
    pending("lsys was built without OSMesa (install libosmesa6-dev and rebuild)")
    return
  end
  local MODEL = [[
local lsys = require "lsys"
return lsys.lsystem { axiom = "F", steps = 2, productions = "F --> F[+F]F" }
]]
  local dir
  before_each(function ()
    dir = H.tmpdir()
    H.write(dir .. "/m.lua", MODEL)
    assert(os.execute("mkdir " .. q(dir .. "/tmp")))
  end)
  after_each(function () H.rmdir(dir) end)

  it("writes no file through a link planted where it writes aside (§6)", function ()
    if not (have("ffmpeg")) then pending("ffmpeg is not installed") return end
    H.write(dir .. "/victim", "secret")
    plant(dir, "a.gif", "%s.lsys-%d-1.part", dir .. "/victim")
    local nlinks = #links(dir)
    local out, code = sh(("cd %s && %s animate m.lua --size 16x16 -o a.gif"):format(q(dir),
      q(ABSBIN)))
    assert.equal(0, code, out)
    assert.equal("secret", H.read(dir .. "/victim"))
    assert.equal("GIF8", H.read(dir .. "/a.gif"):sub(1, 4))
    assert.equal("", sh("readlink " .. q(dir .. "/a.gif")))
    assert.equal(nlinks, #links(dir))
  end)

  it("draws its pictures in a private folder under TMPDIR (§12)", function ()
    local fake = dir .. "/ffmpeg"      -- lists the pictures and the folder's mode
    H.write(fake, "#!/bin/sh\nwhile [ \"$1\" != -i ]; do shift; done\nd=$(dirname \"$2\")\n" ..
      "echo \"$d\"; ls \"$d\"; stat -c %A \"$d\"; exit 4\n")
    assert(os.execute("chmod +x " .. q(fake)))
    local out, code = sh(("cd %s && PATH=%s:$PATH TMPDIR=%s %s animate m.lua --size 16x16 "
      .. "-o a.gif"):format(q(dir), q(dir), q(dir .. "/tmp"), q(ABSBIN)))
    assert.equal(1, code, out)
    local folder = out:match("\n(" .. dir:gsub("%p", "%%%0") .. "/tmp/lsys%-frames%-......)\n")
    assert.truthy(folder, out)
    assert.truthy(out:find("\nframe-000001.png\nframe-000002.png\nframe-000003.png\n" ..
                           "drwx------\n", 1, true), out)
    assert.same({}, ls(dir .. "/tmp"))
    assert.same({ "ffmpeg", "m.lua", "tmp" }, ls(dir))
  end)
end)

-- Starts the shell command `cmd` in a session of its own with SIGINT and SIGTERM at their
-- defaults (a background job of a shell ignores SIGINT), waits until the file `marker`
-- exists, sends `sig` to the whole session (as a terminal sends Ctrl-C to its foreground
-- job), and returns what it printed and its exit status. Should the signal not end it, it
-- is killed (SIGKILL: status 137) after a while.
local function interrupt (cmd, marker, sig)
  local slow = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
  local function running (n)
    return ("i=0; while [ $i -lt %d ] && [ -e /proc/$pid ] && " ..
            "! grep -q '^State:.*Z' /proc/$pid/status 2>/dev/null; do sleep 0.05; " ..
            "i=$((i+1)); done; "):format(n)
  end
  return sh(("setsid env --default-signal=INT,TERM sh -c %s & pid=$!; i=0; " ..
    "while [ ! -e %s ] && [ $i -lt %d ]; do sleep 0.05; i=$((i+1)); done; kill -%s -$pid; " ..
    running(600 * slow) .. "kill -KILL -$pid 2>/dev/null; wait $pid"):format(q(cmd),
    q(marker), 600 * slow, sig))
end

describe("the lsys program, interrupted (§12)", function ()
  local dir
  before_each(function ()
    dir = H.tmpdir()
    assert(os.execute("mkdir " .. q(dir .. "/tmp")))
  end)
  after_each(function () H.rmdir(dir) end)

  it("removes the pictures and the video of lsys animate at Ctrl-C, exit status 130",
  function ()
    if not core.has_render then pending("lsys was built without OSMesa") return end
    -- the third interpretation (the second picture) stops and waits for the signal
    H.write(dir .. "/m.lua", ([[
local lsys = require "lsys"
local n = 0
return lsys.lsystem { axiom = "F", steps = 3, productions = "F --> F[+F]F",
  after_interpret = function ()
    n = n + 1
    if n == 3 then
      io.open(%q, "w"):close()
      while true do end
    end
  end }
]]):format(dir .. "/marker"))
    H.write(dir .. "/a.gif", "an older animation")
    local out, code = interrupt(("cd %s && TMPDIR=%s exec %s animate m.lua --size 16x16 -o a.gif")
      :format(q(dir), q(dir .. "/tmp"), q(ABSBIN)), dir .. "/marker", "INT")
    assert.equal("lsys: interrupted\n", out)
    assert.equal(130, code)
    assert.same({}, ls(dir .. "/tmp"))
    assert.same({ "a.gif", "m.lua", "marker", "tmp" }, ls(dir))
    assert.equal("an older animation", H.read(dir .. "/a.gif"))
  end)

  it("removes the temporaries of lsys components graph at SIGTERM, exit status 143",
  function ()
    H.write(dir .. "/m.lua", "return { kind = 'simple', name = 'A', params = {}, links = {} }\n")
    -- a dot that writes part of its output, then hangs
    H.write(dir .. "/dot", ("#!/bin/sh\nwhile [ \"$1\" != -o ]; do shift; done\n" ..
      "echo partial > \"$2\"\ntouch %s\nexec sleep 60\n"):format(q(dir .. "/marker")))
    assert(os.execute("chmod +x " .. q(dir .. "/dot")))
    H.write(dir .. "/g.png", "an older picture")
    local out, code = interrupt(("cd %s && PATH=%s:$PATH TMPDIR=%s exec %s components graph " ..
      "m.lua -o g.png"):format(q(dir), q(dir), q(dir .. "/tmp"), q(ABSBIN)), dir .. "/marker",
      "TERM")
    assert.equal("lsys: terminated\n", out)
    assert.equal(143, code)
    assert.same({}, ls(dir .. "/tmp"))
    assert.same({ "dot", "g.png", "m.lua", "marker", "tmp" }, ls(dir))
    assert.equal("an older picture", H.read(dir .. "/g.png"))
  end)

  it("ends the REPL at SIGTERM, at the prompt and while it evaluates", function ()
    local ptyrun = (os.getenv("LSYS_BUILD_DIR") or "build") .. "/tools/ptyrun"
    if not io.open(ptyrun) then pending("no " .. ptyrun .. " (built with the tests)") return end
    local slow = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1
    for _, lines in ipairs {
      -- $PPID in the shell of os.execute is the REPL
      { "expect > ", 'send os.execute("(sleep 0.3; kill -TERM $PPID) &")', "expect > " },
      { "expect > ", 'send os.execute("kill -TERM $PPID"); while true do end' },
    } do
      lines[#lines + 1] = "expect lsys: terminated"
      lines[#lines + 1] = "wait"
      H.write(dir .. "/script", table.concat(lines, "\n") .. "\n")
      local out, code = sh(("HOME=%s %s -t %d %s -- %s"):format(q(dir), q(ptyrun), 20 * slow,
        q(dir .. "/script"), q(ABSBIN)))
      assert.equal(3, code, out)      -- ptyrun: the program ended by a signal
      assert.truthy(out:find("\nlsys: terminated\nptyrun: " .. ABSBIN:gsub("%p", "%%%0") ..
                             " exited with status 143 %(killed by signal 15%)\n$"), out)
    end
  end)

  it("ends a derivation at Ctrl-C while rule code runs, within its bounds or none", function ()
    -- the rule runs under the sandbox's count hook (max_instructions) or without it: the
    -- interrupt's hook takes over either way and is not taken off when the step unwinds,
    -- so the pcall around the derivation cannot swallow the interrupt
    for _, budget in ipairs { "1e15", "math.huge" } do
      H.write(dir .. "/s.lua", ([[
local lsys = require "lsys"
local m = lsys.lsystem { axiom = "A(1)", steps = 1, max_instructions = %s,
  start = function () io.open(%q, "w"):close() end,
  productions = "A(x) --> A((function (x) while x > 0 do end return x end)(x))" }
while true do pcall(m.derive, m) end
]]):format(budget, dir .. "/marker"))
      os.remove(dir .. "/marker")
      local out, code = interrupt(("cd %s && exec %s s.lua"):format(q(dir), q(ABSBIN)),
                                  dir .. "/marker", "INT")
      assert.equal("lsys: interrupted\n", out)
      assert.equal(130, code)
    end
  end)

  it("reports a write beyond ulimit -f instead of dying of SIGXFSZ, the old file kept",
     function ()
    H.write(dir .. "/a.obj", "an older mesh")
    local out, code = sh(("cd %s && ulimit -f 2 && exec %s export %s -o a.obj"):format(q(dir),
      q(ABSBIN), q(H.absolute("examples/default.lua"))))
    assert.equal(1, code, out)
    assert.truthy(out:find("File too large", 1, true), out)
    assert.equal("an older mesh", H.read(dir .. "/a.obj"))
    assert.same({ "a.obj", "tmp" }, ls(dir))
  end)

  it("ends a script at Ctrl-C with exit status 130", function ()
    H.write(dir .. "/s.lua", ("io.open(%q, 'w'):close()\nwhile true do end\n")
      :format(dir .. "/marker"))
    local out, code = interrupt("exec " .. q(ABSBIN) .. " " .. q(dir .. "/s.lua"), dir .. "/marker",
                                "INT")
    assert.equal("lsys: interrupted\n", out)
    assert.equal(130, code)
  end)
end)

describe("lsys.testing", function ()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("makes the folders of a golden image itself, any name a file (§14)", function ()
    H.write(dir .. "/g.lua", [[
local testing = require "lsys.testing"
local px = ("\255\0\0\255"):rep(4)
print(testing.match_golden({ px, 2, 2 }, "-g/a b/p.png"))
local f = io.open("-x", "w") f:write("a file") f:close()
print(pcall(testing.match_golden, { px, 2, 2 }, "-x/p.png"))
]])
    local out, code = sh(("cd %s && %s g.lua"):format(q(dir), q(ABSBIN)))
    assert.equal(0, code, out)
    assert.equal("false\t-g/a b/p.png did not exist: this picture (2x2) is there now; look at "
      .. "it and run the test again (LSYS_UPDATE_GOLDEN=1 writes every golden image)\n"
      .. "false\tcannot make the directory -x: a file is in the way\n", out)
    assert.equal("\137PNG", H.read(dir .. "/-g/a b/p.png"):sub(1, 4))
  end)
end)
