-- The REPL (`lsys` with no arguments) driven like a user at a terminal: through a
-- pseudo-terminal with tools/ptyrun (built with the tests), which sends lines and waits
-- for what the REPL prints. With a display (#gl), a click in the viewer window opened
-- from the REPL is printed at the prompt.
local D = require "tests.display"

local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
local PTYRUN = (os.getenv("LSYS_BUILD_DIR") or "build") .. "/tools/ptyrun"
-- seconds to wait for each reply: longer under valgrind (tools/memcheck-all.sh sets
-- LSYS_TEST_SLOW, a factor for every wait of the specs that start the program)
local TIMEOUT = 20 * (tonumber(os.getenv("LSYS_TEST_SLOW")) or 1)

local function exists (path)
  local f = io.open(path)
  if f then f:close() end
  return f ~= nil
end

-- Runs the ptyrun script 'lines' against the REPL; returns the transcript, exit status.
local function drive (lines, env)
  local script = os.tmpname()
  local f = assert(io.open(script, "w"))
  f:write(table.concat(lines, "\n"), "\n")
  f:close()
  local p = io.popen((env or "") .. PTYRUN .. " -t " .. TIMEOUT .. " " .. script .. " -- " .. BIN ..
    " 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  os.remove(script)
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return (out:gsub("exit:%d+%s*$", "")), code
end

local function ptyrun ()
  if not exists(PTYRUN) then
    pending("tools/ptyrun is not built (cmake with LSYS_BUILD_TESTS=ON builds it)")
    return false
  end
  return true
end

describe("the REPL in a terminal", function()
  teardown(function() D.stop() end)

  it("prints values, abbreviates Lstrings, summarises scenes, continues statements " ..
     "and survives errors", function()
    if not ptyrun() then return end
    local out, code = drive {
      "expect `lsys` is loaded",
      "expect > ",
      "send 1 + 2, 'x'",
      "expect 3\tx",
      "expect > ",
      'send m = lsys.lsystem { axiom = "F", steps = 3, productions = "F --> F[+F]F[-F]F" }',
      "expect > ",
      "send =m:derive()",
      "expect Lstring(311 modules): " ..
        "F[+F]F[-F]F[+F[+F]F[-F]F]F[+F]F[-F]F[-F[+F]F[-F]F]F[+F]F[-F]...",
      "expect > ",
      "send =m:interpret(lsys.lstring('F[+F]F'))",
      "expect Scene(0 triangles, 3 lines, 3 turtle records; x ",
      "expect > ",
      "send for i = 1, 2 do",
      "expect >> ",
      "send   print('line ' .. i)",
      "expect >> ",
      "send end",
      "expect line 2",
      "expect > ",
      "send error('boom')",
      "expect stdin:1: boom",
      "expect > ",
      "send lsys.lsystem { productions = 'F -> G' }",
      "expect unknown operator '->'",
      "expect > ",
      -- the session goes on: m is still there; the up arrow recalls the last line
      "send #m:derive(2)",
      "expect 61",
      "expect > ",
      "sendraw \\x1b[A\\r",
      "expect 61",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }
    assert.equal(0, code, out)
  end)

  it("#gl prints a click in the window at the prompt", function()
    if not ptyrun() then return end
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return end
    local out, code = drive({
      "expect > ",
      'send m = lsys.lsystem { axiom = "F(2)[+F(1)]", view = { angle = 90 } }',
      "expect > ",
      'send lsys.show(m, { width = 300, height = 300, title = "repl pick" })',
      "expect > ",
      "send =lsys.viewer.sync()",
      "expect true",
      "expect > ",
      -- the middle of the branch F(1): from (0, 2) to (-1, 2) with + turning left
      "send r = m:interpret():record(2); x, y = lsys.viewer.project({(r.p0[1] + r.p1[1]) / 2, " ..
        "(r.p0[2] + r.p1[2]) / 2, 0})",
      "expect > ",
      "send =r.module",
      "expect 4",
      "expect > ",
      "send cmd = (\"xdotool search --name 'lsys: repl pick' mousemove --window %%1 %d %d " ..
        "click 1\"):format(x // 1, y // 1)",
      "expect > ",
      "send os.execute(cmd .. ' >/dev/null 2>&1')",
      "expect picked module 4: F(1) (segment, step 1)",
      "expect > ",
      "send =lsys.viewer.last_pick.module, lsys.viewer.last_pick.name",
      "expect 4\tF",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, D.env)
    assert.equal(0, code, out)
  end)
end)
