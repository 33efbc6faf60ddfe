-- The REPL (`lsys` with no arguments) driven like a user at a terminal: through a
-- pseudo-terminal with tools/ptyrun (built with the tests), which sends lines and waits
-- for what the REPL prints. With a display (#gl), a click in the viewer window opened
-- from the REPL is printed at the prompt. What it prints (tables, numbers, Lstrings, help)
-- is checked with stdin a file, where it prints no prompts; lsys.repl.show,
-- lsys.repl.help and lsys.repl.complete are also checked in this Lua state. Completion and
-- history need readline: without it (cmake -DLSYS_WITH_READLINE=OFF) those are pending.
local H = require "tests.helper"
local D = require "tests.display"

local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
local BUILD = os.getenv("LSYS_BUILD_DIR") or "build"
local PTYRUN = BUILD .. "/tools/ptyrun"
-- seconds to wait for each reply: longer under valgrind (tools/memcheck-all.sh sets
-- LSYS_TEST_SLOW, a factor for every wait of the specs that start the program)
local TIMEOUT = 20 * (tonumber(os.getenv("LSYS_TEST_SLOW")) or 1)

local function exists (path)
  local f = io.open(path)
  if f then f:close() end
  return f ~= nil
end

-- A HOME for the sessions of one test, so that ~/.lsys_history is its own.
local homes = {}
local function tmphome ()
  local d = H.tmpdir()
  homes[#homes + 1] = d
  return d
end

-- Runs the ptyrun script 'lines' against the REPL; returns the transcript, exit status.
-- 'env' is put before the command ("NAME=value ..."); HOME is a fresh folder unless given.
local function drive (lines, env)
  local script = os.tmpname()
  local f = assert(io.open(script, "w"))
  f:write(table.concat(lines, "\n"), "\n")
  f:close()
  env = env or ""
  if not env:find("HOME=") then env = env .. " HOME=" .. tmphome() .. " " end
  local p = io.popen(env .. PTYRUN .. " -t " .. TIMEOUT .. " " .. script .. " -- " .. BIN ..
    " 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  os.remove(script)
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return (out:gsub("exit:%d+%s*$", "")), code
end

-- Runs the REPL with 'lines' as its input (a file: no prompts, no line editing); returns
-- what it printed (stdout and stderr) and its exit status.
local function pipe (lines, cwd)
  local script = os.tmpname()
  H.write(script, table.concat(lines, "\n") .. "\n")
  local bin = BIN:sub(1, 1) == "/" and BIN or os.getenv("PWD") .. "/" .. BIN
  local out, code = H.sh(("cd '%s' && HOME='%s' '%s' < '%s'"):format(cwd or ".", tmphome(),
    bin, script))
  os.remove(script)
  return out, code
end

local function ptyrun ()
  if not exists(PTYRUN) then
    pending("tools/ptyrun is not built (cmake with LSYS_BUILD_TESTS=ON builds it)")
    return false
  end
  return true
end

-- Whether the program was built with readline (completion and history need it).
local has_readline
local function readline ()
  if has_readline == nil then
    has_readline = pipe { "print((require 'lsys.program').host().readline)" } == "true\n"
  end
  if not has_readline then
    pending("the lsys program was built without readline (cmake says 'without readline')")
  end
  return has_readline
end

describe("the REPL in a terminal", function()
  teardown(function()
    D.stop()
    for _, d in ipairs(homes) do H.rmdir(d) end
  end)

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
      -- the session goes on: m is still there
      "send #m:derive(2)",
      "expect 61",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }
    assert.equal(0, code, out)
  end)

  it("recalls the last line with the up arrow", function()
    if not ptyrun() or not readline() then return end
    local out, code = drive {
      "expect > ",
      'send m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F" }',
      "expect > ",
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

  it("completes globals, fields, methods and nested fields with Tab", function()
    if not ptyrun() or not readline() then return end
    local out, code = drive {
      "expect > ",
      'send m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F" }',
      "expect > ",
      -- a method after ':' (without completion, m:de(1) is an error)
      "sendraw x = m:de\\t",
      "expect m:derive",
      "sendraw (1)\\r",
      "expect > ",
      "send =x",
      "expect Lstring(6 modules): F[+F]F",
      "expect > ",
      -- a key after '.', a nested field, a global
      "sendraw =m.en\\t",
      "expect m.env",
      "sendraw \\r",
      "expect {}",
      "expect > ",
      "sendraw =type(lsys.view.load_c\\t",
      "expect lsys.view.load_colormap",
      "sendraw )\\r",
      "expect function",
      "expect > ",
      "sendraw =tostr\\t",
      "expect tostring",
      "sendraw (1.5)\\r",
      "expect 1.5",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }
    assert.equal(0, code, out)
  end)

  it("keeps the history in ~/.lsys_history: the up arrow recalls a line of the last " ..
     "session", function()
    if not ptyrun() or not readline() then return end
    local home = tmphome()
    local env = "HOME=" .. home .. " "
    local out, code = drive({
      "expect > ",
      "send 6 * 7",
      "expect 42",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, env)
    assert.equal(0, code, out)
    assert.equal("6 * 7\n", H.read(home .. "/.lsys_history"))
    out, code = drive({
      "expect > ",
      "sendraw \\x1b[A\\r",
      "expect 6 * 7",
      "expect 42",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, env)
    assert.equal(0, code, out)
    -- a HOME that cannot be written to: the session goes on, silently
    out, code = drive({
      "expect > ",
      "send 6 * 7",
      "expect 42",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, "HOME=" .. home .. "/none ")
    assert.equal(0, code, out)
    assert.not_matches("history", out)
  end)

  it("clears the line at Ctrl-C and goes on; Ctrl-C still interrupts an evaluation",
     function()
    if not ptyrun() then return end
    local out, code = drive {
      "expect > ",
      "sendraw abc def",
      "sleep 0.2",
      "sendraw \\x03",
      "expect > ",
      "send 1 + 41",
      "expect 42",
      "expect > ",
      -- in a statement continued on '>>' lines: back to '>'
      "send for i = 1, 2 do",
      "expect >> ",
      "sleep 0.2",
      "sendraw \\x03",
      "expect > ",
      "send 'still here'",
      "expect still here",
      "expect > ",
      "send while true do end",
      "sleep 0.3",
      "sendraw \\x03",
      "expect interrupted!",
      "expect > ",
      "send 2 + 2",
      "expect 4",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }
    assert.equal(0, code, out)
    assert.not_matches("near 'def'", out)   -- the abandoned line is not run
  end)

  it("says help() in its greeting and prints a section of the manual for help, whole " ..
     "on a terminal that runs no pager", function()
    if not ptyrun() then return end
    -- ptyrun's terminal is TERM=dumb: without $PAGER, no pager runs
    local out, code = drive({
      "expect help() for help",
      "expect > ",
      'send help "derive"',
      "expect ### m:derive([n [, opts]])",
      "expect print(#kept[0], #kept[1], #kept[3])   --> 1  6  66",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, "PAGER= ")
    assert.equal(0, code, out)
    assert.not_matches("more lines", out)
  end)

  it("pages help longer than the screen through $PAGER, and prints shorter help", function()
    if not ptyrun() then return end
    local out, code = drive({
      "expect > ",
      'send help "Model options"',
      "expect P:## 2. Model options",
      "expect P:",
      "expect > ",
      "send help(lsys.lstring('F').count)",
      "expect | `s:count(name)` |",
      "expect > ",
      "send 6 * 7",
      "expect 42",
      "expect > ",
      "sendraw \\x04",
      "wait",
    }, "PAGER='head -n 2 | sed s/^/P:/' ")
    assert.equal(0, code, out)
    -- the pager had the section (the first two lines of it), the REPL printed none of it
    assert.not_matches("| `axiom` |", out, 1, true)
    assert.not_matches("P:| `s:count", out, 1, true)
  end)

  it("pages help with less on a terminal without $PAGER (tmux); q goes back to the prompt",
     function()
    for _, tool in ipairs { "tmux", "less" } do
      if not D.have(tool) then pending(tool .. " is not installed (./setup.sh does)") return end
    end
    local home = tmphome()
    local sock = "lsys-repl-" .. H.absolute(home):gsub("%W", "")
    local function tmux (args)
      return H.sh("tmux -L " .. sock .. " " .. args .. " 2>&1")
    end
    local function screen () return (tmux("capture-pane -p")) end
    -- waits for 'text' on the screen; the screen
    local function await (text)
      local deadline = os.time() + TIMEOUT
      repeat
        local s = screen()
        if s:find(text, 1, true) then return s end
        os.execute("sleep 0.1")
      until os.time() > deadline
      error(("timed out waiting for %q; the screen:\n%s"):format(text, screen()))
    end
    local _, started = tmux(("-f /dev/null new-session -d -x 80 -y 24 " ..
      "\"env -u PAGER -u LESS HOME='%s' '%s'\""):format(home, H.ABSBIN))
    assert.equal(0, started)
    local ok, err = pcall(function ()
      await("\n>")     -- (capture-pane leaves out the blanks that end a line)
      tmux("send-keys 'help \"Model options\"' Enter")
      local s = await("| `seed` |")
      -- less's prompt on the last line; the end of the section not yet shown
      assert.matches("\n:%s*$", s)
      assert.not_matches("### Tunable parameters", s, 1, true)
      tmux("send-keys C-c")   -- less's; the REPL, in system(), ignores it
      -- less drops the keys typed before it has handled ^C: q again until the prompt is back
      local back
      for _ = 1, 50 do
        tmux("send-keys q")
        os.execute("sleep 0.2")
        local sc = screen()
        local typed = sc:match("\n> (q+)%s*$")     -- less had quit: the q went to the prompt
        if typed then tmux("send-keys" .. string.rep(" BSpace", #typed)) end
        back = typed or sc:match("\n>%s*$")
        if back then break end
      end
      assert.is_truthy(back, "less did not quit: " .. screen())
      tmux("send-keys '6 * 7' Enter")
      s = await("\n42\n")
      assert.matches("\n> 6 %* 7\n42\n", s)
      assert.not_matches("interrupted", s, 1, true)
    end)
    tmux("kill-server")
    assert(ok, err)
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

describe("what the REPL prints", function()
  teardown(function() for _, d in ipairs(homes) do H.rmdir(d) end end)

  it("prints numbers as lua5.4 does", function()
    local out = pipe { "0.1 + 0.2", "1.0", "2^53", "1/3", "7 // 2", "-0.0" }
    assert.equal(table.concat({ tostring(0.1 + 0.2), tostring(1.0), tostring(2^53),
      tostring(1/3), tostring(7 // 2), tostring(-0.0) }, "\n") .. "\n", out)
  end)

  it("prints a table one level deep, short vectors of numbers in full", function()
    local out = pipe {
      '{ 1, 2.5, a = "x\\ny", t = { 1, 2 }, u = { a = 1 }, [10] = true, f = print }',
      "{}",
      "t = {} for i = 1, 100 do t[i] = i end",
      "t",
      "setmetatable({}, { __tostring = function () return 'custom' end })",
    }
    assert.equal('{ 1, 2.5, [10] = true, a = "x\\ny", f = function, t = { 1, 2 }, ' ..
      "u = {...} }\n{}\n" ..
      "{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, " ..
      "... (80 more) }\ncustom\n", out)
  end)

  it("shows the numbers of sc:bounds(), sc:turtle(i) and sc:record(k)", function()
    local out = pipe {
      'sc = lsys.lsystem { axiom = "F(2)[+F(1)]" }:interpret()',
      "sc:bounds()",
      "sc:turtle(2)",
      "sc:record(1).p1, sc:record(1).length",
    }
    assert.equal("{ -1.0, 0.0, 0.0 }\t{ 0.0, 2.0, 0.0 }\n" ..
      "{ 0.0, 2.0, 0.0 }\t{ 0.0, 1.0, 0.0 }\t{ -1.0, 0.0, 0.0 }\t{ 0.0, 0.0, -1.0 }\t1.0\t1\n" ..
      "{ 0.0, 2.0, 0.0 }\t2.0\n", out)
  end)

  it("rounds the numbers of an Lstring to 15 digits; lsys.repl.digits(17) shows them all",
     function()
    local out = pipe {
      's = lsys.lstring("F(0.48999999999999994,2)G(1e300)")',
      "s",
      "print(s)",
      "lsys.repl.digits(17)",
      "s",
      "lsys.repl.digits(3)",
      "s, { 2 / 3 }",
      "lsys.repl.digits()",
      "s, { 2 / 3 }",
      "lsys.repl.digits(0)",
    }
    assert.equal("Lstring(2 modules): F(0.49,2)G(1e+300)\n" ..
      "F(0.48999999999999994,2)G(1e+300)\n" ..
      "Lstring(2 modules): F(0.48999999999999994,2)G(1e+300)\n" ..
      "Lstring(2 modules): F(0.49,2)G(1e+300)\t{ 0.667 }\n" ..
      "Lstring(2 modules): F(0.49,2)G(1e+300)\t{ 0.666667 }\n" ..
      "stdin:1: digits: give a whole number from 1 to 17, or nothing for the defaults\n", out)
  end)

  it("prints nothing for several results that are all nil but a leading true", function()
    local out = pipe {
      "(function () return true, nil, nil end)()",
      "(function () return nil, nil end)()",
      "(function () end)()",
      "true",
      "nil",
      "(function () return true, 1 end)()",
      "(function () return false, nil end)()",
    }
    assert.equal("nil\tnil\ntrue\nnil\ntrue\t1\nfalse\tnil\n", out)
  end)

  it("keeps the first value of the last printed line in `_`", function()
    local out = pipe {
      'm = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F" }',
      "m:derive(2)",
      '_:count("F")',
      "_ * 2",
      "x = 1",            -- prints nothing: `_` stays
      "print('p')",
      "_",
      "'a', 'b'",
      "_",
      "error('e')",
      "_",
      "_ = 5",
      "_, rawget(_G, '_')",
      "for _, v in ipairs({ 7 }) do y = v end",
      "_, y",
    }
    assert.equal("Lstring(21 modules): F[+F]F[+F[+F]F]F[+F]F\n9\n18\np\n18\na\tb\na\n" ..
      "stdin:1: e\na\n5\tnil\n5\t7\n", out)
  end)

  it("prints a model with its options, view and rules", function()
    local out = pipe {
      'm = lsys.lsystem { axiom = "X", steps = 2, env = { R = 2 }, view = { angle = 20 },' ..
        ' productions = "X --> F[+X]F[-X]+X\\nF --> FF" }',
      "m",
      "print(m)",
    }
    assert.equal('lsys.Model(stdin:1)\n  axiom = "X"\n  steps = 2\n  seed = 0\n' ..
      "  env = { R = 2 }\n  view = { angle = 20 }\nproductions:\n" ..
      "  1    X --> F[+X]F[-X]+X\n  2    F --> FF\nlsys.Model(stdin:1)\n", out)
  end)

  it("keeps a `local` of one line for the lines after it, without making a global",
     function()
    local out = pipe {
      "local x = 41",
      "x + 1",
      "local function sq (a) return a * a end",
      "sq(x)",
      "rawget(_G, 'x'), rawget(_G, 'sq')",
      "function getx () return x end",
      "x = 7",
      "getx(), rawget(_G, 'x')",
      "local string = 5",
      "string, type(_G.string), ('ab'):upper()",
      "do local y = 1 end",
      "y",
      "local a, b = 1",
      "a, b",
      "for i = 1, 2 do local z = i end return 'last'",
    }
    assert.equal("42\n1681\nnil\tnil\n7\tnil\n5\ttable\tAB\nnil\n1\tnil\nlast\n", out)
  end)

  it("prints the manual's section on a function, a method or a topic, whole", function()
    local out = pipe { 'help "derive"' }
    assert.matches("^### m:derive%(%[n %[, opts%]%]%)\n", out)
    -- no pager without a terminal: the section to its last line
    assert.matches("\n    print%(#kept%[0%], #kept%[1%], #kept%[3%]%)   %-%-> 1  6  66\n$", out)
    out = pipe { "help(lsys.lsystem)" }
    assert.matches("^## 2%. Model options\n", out)
    assert.matches("\n### Tunable parameters\n", out)
    out = pipe { 'm = lsys.lsystem { axiom = "F" }', "help(m.derive)" }
    assert.matches("^### m:derive", out)
    out = pipe { "help(lsys.lstring('F').count)" }
    assert.matches("^## 8%. Lstrings\n\n| operation | result |\n|%-%-%-|%-%-%-|\n" ..
      "| `s:count%(name%)` |[^\n]*\n\n%(the whole section: help \"Lstrings\"%)\n$", out)
    out = pipe { 'help "lsys.show"' }
    assert.matches("^## lsys%.show\n", out)
    out = pipe { "help(lsys.repl.digits)" }   -- from the declarations of docs/meta.lua
    assert.matches("^function lsys%.repl%.digits%(n%)\nHow many significant digits", out)
    out = pipe { 'help "nosuch"', "help(42)", "help({})", "help(print)" }
    assert.equal("no help for nosuch; try help()\nno help for 42; try help()\n" ..
      "no help for this table; try help()\n" ..
      "print is Lua's: see https://www.lua.org/manual/5.4/manual.html#pdf-print\n", out)
  end)

  it("tells what a model, an Lstring or a scene is and its methods for help(x)", function()
    local out = pipe { 'm = lsys.lsystem { axiom = "X", steps = 2, productions = ' ..
      '"X --> F[+X]F[-X]+X\\nF --> FF", homomorphism = "X --> F" }', "help(m)" }
    local lines = {}
    for l in out:gmatch("([^\n]*)\n") do lines[#lines + 1] = l end
    assert.equal('lsys.Model(stdin:1), a model: axiom "X", 2 steps', lines[1])
    assert.equal("3 rules: productions 2, homomorphism 1", lines[2])
    assert.equal('Its methods (help "m:NAME" prints the section on one):', lines[4])
    -- each method with the first sentence of its section, cut to the 80 columns
    assert.equal("  m:derive([n [, opts]])     Derives n steps from the axiom (default " ..
      "m.steps...", lines[5])
    assert.equal("  m:step(s)                  One derivation step (productions, cut, " ..
      "decompos...", lines[#lines - 4])
    assert.equal("  m:use_group(n)             Makes rule group n active beside group 0 " ..
      "(the p...", lines[#lines - 3])
    assert.equal("m:inspect() prints its options, view and rules.", lines[#lines - 1])
    assert.equal('help "Model methods and module functions" prints the manual\'s section.',
                 lines[#lines])
    assert.matches("\n  m:rules%(%) +The model's rules, set by set", out)
    for _, l in ipairs(lines) do assert.is_true(#l < 80, l) end
    out = pipe { 's = lsys.lstring("F[+F]")', "help(s)" }
    assert.matches('^Lstring%(5 modules%): F%[%+F%]\n\nIts methods %(help "s:NAME"', out)
    assert.matches("\n  s:count%(name%) +number of modules named name", out)
    assert.matches('\nhelp "Lstrings" prints the manual\'s section%.\n$', out)
    out = pipe { 'sc = lsys.lsystem { axiom = "F" }:interpret()', "help(sc)" }
    assert.matches("^Scene%(0 triangles, 1 lines, 1 turtle records; ", out)
    assert.matches("\n  scene:records%(%) +turtle record k", out)
    assert.matches('\nhelp "Scenes" prints the manual\'s section%.\n$', out)
  end)

  it("gives an overview for help(), from any folder", function()
    local out = pipe({ "help()" }, "/")
    assert.matches("^lsys: L%-systems for plant modelling", out)
    assert.matches('help "derive"', out)
    assert.not_matches("not found", out)
  end)

  it("finds the docs in an install (cmake --install)", function()
    if not H.sh("command -v cmake"):find("cmake") then
      pending("cmake is not installed") return
    end
    local prefix = H.tmpdir()
    local out, code = H.sh(("cmake --install '%s' --prefix '%s'"):format(BUILD, prefix))
    assert.equal(0, code, out)
    local home = tmphome()
    local function run (line)
      return H.sh(("cd / && echo '%s' | HOME='%s' '%s/bin/lsys'"):format(line, home, prefix))
    end
    out = run('help "derive"')
    assert.matches("^### m:derive", out)
    -- the installed copy is the one read
    H.write(prefix .. "/share/lsys/docs/manual.md", "# m\n\n### m:derive(n)\n\nInstalled.\n")
    assert.equal("### m:derive(n)\n\nInstalled.\n", run('help "derive"'))
    H.rmdir(prefix .. "/share/lsys/docs")
    out = run('help "derive"')
    H.rmdir(prefix)
    assert.matches("^help: the lsys manual %(manual.md%) was not found in [^\n]*\n$", out)
  end)
end)

describe("lsys.repl's parts", function()
  local lsys = require "lsys"
  local C = require "lsys.repl.complete"
  local Help = require "lsys.repl.help"
  local S = require "lsys.repl.show"

  -- The completions of the word before the end of 'line' in 'env'.
  local function complete (env, line)
    local start = line:find("[%w_.:]*$") - 1
    return C.complete(env, line, start, #line)
  end

  it("completes globals, keys after '.', methods after ':' and nested fields", function()
    local m = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F" }
    local env = setmetatable({ m = m, s = m:derive(1), sc = m:interpret(), str = "ab",
                               lsys = lsys },
                             { __index = _G })
    assert.same({ "m:derive" }, complete(env, "x = m:de"))
    assert.same({ "m:inspect", "m:interpret" }, complete(env, "m:in"))
    assert.same({ "m.env" }, complete(env, "m.en"))
    assert.same({ "lsys.view.load_colormap" }, complete(env, "lsys.view.load_c"))
    assert.same({ "lsys.view", "lsys.viewer" }, complete(env, "lsys.vi"))
    assert.same({ "s:copy", "s:count", "s:counts" }, complete(env, "print(s:co"))
    assert.same({ "sc:bounds" }, complete(env, "sc:bo"))
    assert.same({ "sc.nlines", "sc.nrecords", "sc.nsegments", "sc.ntriangles",
                  "sc.nvertices" }, complete(env, "sc.n"))
    assert.same({ "str:upper" }, complete(env, "str:up"))
    assert.same({ "function" }, complete(env, "fun"))
    assert.same({ "tostring" }, complete(env, "tostr"))
    assert.same({}, complete(env, "nosuch.x"))
    assert.same({}, complete(env, "m:nosuch"))
    -- names starting with '_' only when '_' is typed
    local all = table.concat(complete(env, "m:"), " ")
    assert.matches("m:derive", all)
    assert.not_matches("m:_", all)
    assert.same({ "m:_call", "m:_checkcounts", "m:_checkfuncs", "m:_configure", "m:_core" },
                complete(env, "m:_c"))
    -- in a string: nil, for readline's file names
    assert.is_nil(C.complete(env, 'dofile("exa', 8, 11))
  end)

  it("finds a section by heading, paragraph, table row, title or declaration", function()
    local dir = H.tmpdir()
    H.write(dir .. "/manual.md", table.concat({
      "# The manual", "", "## 1. Things", "",
      "`lsys.thing(x)` makes a thing.", "",
      "| method | does |", "|---|---|", "| `t:poke(n)` | pokes n times |",
      "| `t:prod()` | prods |", "",
      "```lua", "## not a heading: code", "```", "",
      "### t:spin([turns])", "", "Spins.", "",
      "## 2. Other things", "", "Other.", "" }, "\n"))
    H.write(dir .. "/meta.lua", table.concat({
      "local lsys = {}", "--- Waits for the thing.", "---@param secs number Seconds.",
      "function lsys.wait_thing(secs) end", "" }, "\n"))
    local out = {}
    local help = Help.new { dirs = { dir }, size = function () return 24, 80 end,
                            out = function (x) out[#out + 1] = x end }
    local function run (...)
      out = {}
      help(...)
      return table.concat(out)
    end
    assert.equal("### t:spin([turns])\n\nSpins.\n", run("spin"))
    assert.equal(run("spin"), run("t:spin"))
    assert.matches("^## 1%. Things\n\n`lsys.thing%(x%)` makes", run("lsys.thing"))
    assert.matches("^## 1%. Things\n\n`lsys.thing", run("thing"))
    assert.matches("    ## not a heading: code\n", run("things"))
    assert.equal("## 1. Things\n\n| method | does |\n|---|---|\n| `t:poke(n)` | pokes n " ..
      "times |\n\n(the whole section: help \"Things\")\n", run("poke"))
    assert.equal("## 2. Other things\n\nOther.\n", run("Other things"))
    assert.equal("function lsys.wait_thing(secs)\nWaits for the thing.\n" ..
      "  secs number Seconds.\n", run("lsys.wait_thing"))
    assert.equal("no help for nosuch; try help()\n", run("nosuch"))
    H.rmdir(dir)
  end)

  it("says in one line that the manual is missing", function()
    local out = {}
    local help = Help.new { dirs = { "/nonexistent/docs" },
                            out = function (s) out[#out + 1] = s end }
    help("derive")
    assert.equal("help: the lsys manual (manual.md) was not found in /nonexistent/docs\n",
                 table.concat(out))
  end)

  it("gives the pager what does not fit on the screen, and prints the rest", function()
    local dir = H.tmpdir()
    H.write(dir .. "/manual.md", "# M\n\n## Short\n\nOne line.\n\n## Long\n\n" ..
      ("x"):rep(100) .. "\n" .. ("line\n"):rep(6))
    local out, paged = {}, {}
    local answer = true
    local help = Help.new { dirs = { dir }, size = function () return 10, 50 end,
                            out = function (s) out[#out + 1] = s end,
                            page = function (t) paged[#paged + 1] = t return answer end }
    help("Short")                 -- 3 rows: printed
    assert.same({ "## Short\n\nOne line.\n" }, out)
    assert.same({}, paged)
    out = {}
    help("Long")                  -- 2 + 3 rows for the wrapped line + 6: the pager's
    local long = "## Long\n\n" .. ("x"):rep(100) .. "\n" .. ("line\n"):rep(6)
    assert.same({ long }, paged)
    assert.same({}, out)
    answer = false                -- no pager could run: printed whole
    help("Long")
    assert.same({ long }, out)
    H.rmdir(dir)
  end)

  it("picks $PAGER, else less or more on a terminal that can run them", function()
    local function pager (env)
      local script = H.tmpdir()
      H.write(script .. "/p.lua",
        "print(require('lsys.repl.help').pager_command() or 'none')")
      local out = H.sh(("env -u PAGER -u LESS %s '%s' '%s/p.lua'"):format(env, H.ABSBIN, script))
      H.rmdir(script)
      return (out:gsub("\n$", ""))
    end
    assert.equal("most -s", pager("PAGER='most -s' TERM=dumb"))
    assert.equal("none", pager("PAGER= TERM=dumb"))
    assert.equal("none", pager("PAGER=' ' TERM="))
    if H.sh("command -v less") ~= "" then
      assert.equal("LESS=FRX less", pager("TERM=xterm"))
      assert.equal("less", pager("TERM=xterm LESS=-S"))
    else
      pending("less is not installed")
    end
  end)

  it("shows floats in tables with 6 digits and integers in full", function()
    assert.equal("{ 0.333333, 1.0, 100000000000, 1.23457e+20, inf }",
                 S.show({ 1 / 3, 1.0, 100000000000, 1.23456789e20, math.huge }))
    assert.equal("Lstring(1 module): F(0.1)", S.show(lsys.lstring("F(0.1)")))
  end)
end)
