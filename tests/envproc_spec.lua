-- Environmental programs from Lua (csrc/lua/lua_envproc.c): core.envproc's options and
-- errors, and lsys.EnvProcess's exchange, more and close over the three transports, against
-- the test program tests/c/envslave.c (LSYS_ENVSLAVE; the C side is tests/c/test_envproc.c).
local H = require "tests.helper"
local core = require "lsys.core"

local ENVSLAVE = os.getenv("LSYS_ENVSLAVE")
  or H.absolute((os.getenv("LSYS_BUILD_DIR") or "build") .. "/lsys_envslave")

describe("core.envproc", function ()
  local dir

  setup(function () dir = H.tmpdir() end)
  teardown(function () H.rmdir(dir) end)

  -- the message of an error without the position of the Lua code that called the binding
  local function errof (f, ...) return (H.errof(f, ...):gsub("^[^:]+:%d+: ", "")) end

  local function start (transport, spec, timeout)
    H.write(dir .. "/x.e", "communication type: " .. transport .. "\n")
    return core.envproc { transport = transport, dir = dir, timeout = timeout or 5,
                          argv = { ENVSLAVE, "-e", "x.e", spec } }
  end

  for _, t in ipairs { "pipes", "files", "memory" } do
    it("exchanges messages and replies over " .. t, function ()
      local p = start(t, "echo")
      assert.matches("^lsys%.EnvProcess '.*' %(" .. t .. ", pid %d+%)$", tostring(p))
      assert.equal("0 E(2,3)\n12 E(6)\nControl: 5\n",
                   p:exchange("0 E(1,2)F\n 1 2 3\n12 E(5)]\nControl: 5 1\n"))
      assert.equal("7 E(,5)\nControl: 5\n", p:exchange("7 E(,4)\nControl: 5 2\n"))
      p:close()
      p:close()                                   -- closing twice is fine
      assert.equal("lsys.EnvProcess (closed)", tostring(p))
      assert.equal("EnvProcess:exchange: the process was closed",
                   H.errof(p.exchange, p, "Control: 5 1\n"))
      assert.equal("EnvProcess:more: the process was closed", H.errof(p.more, p))
      assert.equal("x.e\n", H.sh("ls -A '" .. dir .. "'"))   -- the files are gone
    end)

    it("reads a reply sent in several Control chunks over " .. t, function ()
      local p <close> = start(t, "chunks")
      assert.equal("Control: 5\n", p:exchange("0 E(1)\nControl: 1 0\n"))
      assert.equal("0 E(2)\n5 E(3)\nControl: 1\n", p:exchange("5 E(2)\n9 E(3)\nControl: 4 1\n"))
      assert.equal("the last reply is not complete: read the rest first (more)",
                   H.errof(p.exchange, p, "1 E(1)\nControl: 5 2\n"))
      assert.equal("9 E(4)\nControl: 4\n", p:more())
      assert.equal("the last reply was complete: there is nothing more to read",
                   H.errof(p.more, p))
    end)
  end

  it("refuses a message without its Control line, and the process stays usable", function ()
    local p <close> = start("pipes", "echo")
    assert.equal("the message must end with a 'Control:' line", H.errof(p.exchange, p, "0 E(1)"))
    assert.equal("0 E(2)\nControl: 5\n", p:exchange("0 E(1)\nControl: 5 1\n"))
  end)

  it("names the program and what went wrong", function ()
    assert.equal("environmental program 'lsys-no-such-program': not found on the PATH",
                 H.errof(core.envproc, { argv = { "lsys-no-such-program" } }))
    assert.equal("environmental program '" .. ENVSLAVE .. "': exited with status 3",
                 errof(start, "files", "exit"))
    assert.equal("environmental program '" .. ENVSLAVE .. "': did not answer within 0.3 s",
                 errof(start, "pipes", "silent", 0.3))
    local p <close> = start("memory", "hang", 0.3)
    assert.equal("environmental program '" .. ENVSLAVE .. "': did not answer within 0.3 s",
                 H.errof(p.exchange, p, "0 E(1)\nControl: 5 1\n"))
    assert.equal("environmental program '" .. ENVSLAVE .. "': not usable after an earlier error",
                 H.errof(p.exchange, p, "0 E(1)\nControl: 5 1\n"))
  end)

  it("checks its options", function ()
    local cases = {
      { {}, "envproc: opts.argv is missing (the program and its arguments)" },
      { { argv = {} }, "envproc: opts.argv must hold 1 to 1000 strings, got 0" },
      { { argv = { "a", 2 } }, "envproc: opts.argv[2] must be a string, got number" },
      { { argv = { "a\0b" } }, "envproc: opts.argv[1] has a zero byte" },
      { { argv = { "a" }, transport = "sockets" },
        "envproc: opts.transport must be 'pipes', 'files' or 'memory', got 'sockets'" },
      { { argv = { "a" }, timeout = 0 },
        "envproc: opts.timeout must be a number of seconds in (0, 1e6), got 0" },
      { { argv = { "a" }, dir = 1 }, "envproc: opts.dir must be a string, got number" },
      { { argv = { "a" }, folder = "x" }, "envproc: unknown option 'folder'" },
    }
    for _, c in ipairs(cases) do assert.equal(c[2], H.errof(core.envproc, c[1])) end
    assert.matches("bad argument #1 to '[%w.]*envproc' %(table expected",
                   H.errof(core.envproc, "x"))
  end)
end)
