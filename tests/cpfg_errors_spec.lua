-- lsys.cpfg.load on hostile and broken L-system files: what the cpfg fuzz target
-- (tests/fuzz/lua/targets/cpfg.lua) found in the preprocessor and the parser. Each file
-- fails with a message naming its file and line, or loads. How long the hostile inputs take
-- is measured by bench/cpp.lua, never here (a loaded machine must not fail the suite).
-- ctest: slow (runs the program on many broken cpfg files)
require "tests.helper"
local H = require "tests.helper"
local lsys = require "lsys"
local parse = require "lsys.cpfg.parse"

local dir

-- Writes the files { name = text } into the scratch folder; loads the first name given.
local function load (main, files, opts)
  for name, text in pairs(files or {}) do H.write(dir .. "/" .. name, text) end
  return lsys.cpfg.load(dir .. "/" .. main, nil, opts or { cpp = "builtin" })
end

-- The message of loading `text` as main.l.
local function err (text, files, opts)
  files = files or {}
  files["main.l"] = text
  local ok, msg = pcall(load, "main.l", files, opts)
  assert.is_false(ok, "loaded")
  return (msg:gsub(dir:gsub("%p", "%%%0") .. "/", ""))
end

local function lsystem (axiom, productions, header)
  return "Lsystem: 1\nderivation length: 1\n" .. (header or "") .. "Axiom: " .. axiom .. "\n"
         .. (productions or "") .. "endlsystem\n"
end

before_each(function () dir = H.tmpdir() end)
after_each(function () H.rmdir(dir) end)

describe("lsys.cpfg.load of an empty file", function ()
  it("names the file and line 1", function ()
    assert.equal("main.l:1: no 'Lsystem:' in the file", err(""))
    assert.equal("main.l:1: no 'Lsystem:' in the file", err("/* only a comment */\n\n\n"))
  end)

  it("names the file with the system cpp too", function ()
    if not os.execute("command -v cpp >/dev/null 2>&1") then return pending("no cpp") end
    assert.equal("main.l:1: no 'Lsystem:' in the file", err("", nil, { cpp = "system" }))
  end)
end)

describe("lsys.cpfg.load of module names", function ()
  it("refuses a control character as a module name", function ()
    assert.equal("main.l:3: module names are printable ASCII characters in cpfg, found byte "
                 .. "0x01", err(lsystem("AB\1C")))
    assert.equal("main.l:4: module names are printable ASCII characters in cpfg, found byte "
                 .. "0x1f", err(lsystem("A", "A --> B\31\n")))
  end)

  it("refuses a formal parameter named as an array of its L-system", function ()
    assert.equal("main.l:6: the formal parameter b has the name of array b",
                 err(lsystem("A(0)", "A(i) --> B(i, 1)\nB(x, b) : { k = b[x]; } * --> C(k)\n",
                             "define: { array b[3]; }\n")))
  end)

  it("names the line of a sub-L-system's rule that lsys refuses", function ()
    assert.equal("main.l:8: rule 1 'B --> [C' (entry 1 of sub-L-system 2): unbalanced "
                 .. "brackets in successor: '[' without ']' at character 7",
                 err(lsystem("A?(2,1)B$") .. lsystem("B", "B --> [C\n"):gsub("Lsystem: 1",
                                                                            "Lsystem: 2")))
  end)

  it("refuses an axiom whose branches do not close", function ()
    assert.equal("main.l:3: '[' without ']' in the axiom", err(lsystem("A[B[C]")))
    assert.equal("main.l:3: ']' without '[' in the axiom", err(lsystem("A]B[C")))
  end)
end)

describe("lsys.cpfg.load of deep nesting", function ()
  local MAX = parse.MAXHEIGHT

  it("takes expressions of the highest tree, in rules, conditions and blocks", function ()
    local forms = {
      ("-"):rep(MAX - 1) .. "x", "x" .. (" + 1"):rep(MAX - 1), "x" .. (" ^ 1"):rep(MAX - 1),
      ("1 ? "):rep(MAX - 1) .. "x" .. (" : 0"):rep(MAX - 1),
      ("sin("):rep(MAX - 1) .. "x" .. (")"):rep(MAX - 1),
    }
    for _, e in ipairs(forms) do
      local nest = ("if (1) { "):rep(parse.MAXBLOCKS - 1) .. "y = " .. e .. ";"
                   .. (" }"):rep(parse.MAXBLOCKS - 1)
      local m = load("main.l", { ["main.l"] = lsystem("A(1)",
        "A(x) --> B(" .. e .. ")\nB(x) : { " .. nest .. " } * --> C(y)\n" ..
        "C(x) : " .. e .. " --> D\n", "Start: { x = 1; " .. nest .. " }\n") })
      assert.truthy(tostring(m:derive(3)):find("^[CD]"))   -- C(y) when the condition fails
    end
  end)

  it("refuses an expression one level higher, naming its line", function ()
    local msg = "main.l:4: expression nested too deeply (more than " .. MAX .. " levels of "
                .. "operators and calls)"
    assert.equal(msg, err(lsystem("A(1)", "A(x) --> B(" .. ("-"):rep(MAX) .. "x)\n")))
    assert.equal(msg, err(lsystem("A(1)", "A(x) --> B(x" .. (" + 1"):rep(MAX) .. ")\n")))
    assert.equal(msg, err(lsystem("A(1)", "A(x) --> B(" .. ("1 ? "):rep(MAX) .. "x"
                                  .. (" : 0"):rep(MAX) .. ")\n")))
    assert.equal(msg, err(lsystem("A(1)", "A(x) : x" .. (" && 1"):rep(MAX) .. " --> B\n")))
    -- a sum of macros (vlab models write them) grows as fast as the text
    local defs = "#define A0 x\n"
    for i = 1, 7 do defs = defs .. ("#define A%d A%d+A%d\n"):format(i, i - 1, i - 1) end
    assert.equal("main.l:11: expression nested too deeply (more than " .. MAX .. " levels of "
                 .. "operators and calls)", err(defs .. lsystem("X(A7)")))
  end)

  it("refuses parentheses nested hundreds deep", function ()
    assert.equal("main.l:3: expression nested too deeply (parentheses)",
                 err(lsystem("X(" .. ("("):rep(400) .. "1" .. (")"):rep(400) .. ")")))
    local m = load("main.l", { ["main.l"] = lsystem("X(" .. ("("):rep(300) .. "1"
                                                    .. (")"):rep(300) .. ")") })
    assert.equal("X(1)", tostring(m:derive(0)))
  end)

  it("refuses statement blocks nested too deeply", function ()
    local nest = ("if (1) { "):rep(parse.MAXBLOCKS) .. "y = 1;" .. (" }"):rep(parse.MAXBLOCKS)
    assert.equal("main.l:4: statement blocks nested too deeply (more than "
                 .. parse.MAXBLOCKS .. ")", err(lsystem("A", "A : { " .. nest .. " } * --> B\n")))
  end)
end)

describe("lsys.cpfg.load's built-in preprocessor", function ()
  it("stops a macro that doubles its text at every level", function ()
    local defs = "#define A0 x\n"
    for i = 1, 30 do defs = defs .. ("#define A%d A%d A%d\n"):format(i, i - 1, i - 1) end
    assert.equal("main.l:34: macro expansion longer than 100000 characters",
                 err(defs .. lsystem("X(A30)")))
  end)

  it("refuses a #define whose parameters are not names", function ()
    assert.equal("main.l:1: #define F: '' is not a parameter name",
                 err("#define F(a,,b) a\n" .. lsystem("A")))
    assert.equal("main.l:2: #define sqrt: 'sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(...' is not a "
                 .. "parameter name", err("#define G() 1\n#define sqrt(" .. ("sqrt("):rep(9)
                                          .. "x) 1\n" .. lsystem("A")))
  end)

  it("refuses macro calls nested more than 64 deep", function ()
    local m = load("main.l", { ["main.l"] = "#define f(x) x\n"
      .. lsystem("A(" .. ("f("):rep(64) .. "1" .. (")"):rep(64) .. ")") })
    assert.equal("A(1)", tostring(m:derive(0)))
    assert.equal("main.l:4: macros nested more than 64 deep", err("#define f(x) x\n"
      .. lsystem("A(" .. ("f("):rep(65) .. "1" .. (")"):rep(65) .. ")")))
  end)

  it("reads a long line of unclosed macro calls", function ()
    assert.equal("main.l:4: ')' expected to close the parameters of A, found '('",
                 err("#define G(x) x\n" .. lsystem("A(" .. ("G(x "):rep(20000))))
  end)

  it("leaves self-referential macros as C does", function ()
    local m = load("main.l", { ["main.l"] = "#define R R + 1\n#define A B\n#define B A\n"
      .. "#define sqrt(x) sqrt(x + 1)\n#define floor(x) ceil(x)\n#define ceil(x) floor(x)\n"
      .. lsystem("X(R)", "X(x) --> X(A) X(sqrt(8)) X(floor(1.5)) X(x)\n") })
    assert.equal("X(0)X(3)X(1)X(1)", tostring(m:derive(1)))
  end)

  it("expands no macro inside a string", function ()
    local out = dir .. "/out.txt"
    local m = load("main.l", { ["main.l"] = "#define N 3\n"
      .. lsystem("A", 'A : { printf("N is %d\\n", N); } * --> B\n') })
    local old = io.output()
    io.output(out)
    local ok, e = pcall(m.derive, m, 1)
    io.output():close()
    io.output(old)
    assert(ok, e)
    assert.equal("N is 3\n", H.read(out))
  end)

  it("refuses to include an endless file or a folder", function ()
    assert.equal("main.l:1: /dev/zero: not a regular file",
                 err('#include "/dev/zero"\n' .. lsystem("A")))
    os.execute("mkdir '" .. dir .. "/sub'")
    assert.equal("main.l:2: sub: not a regular file", err('\n#include "sub"\n' .. lsystem("A")))
  end)

  it("stops a file that includes itself", function ()
    assert.equal("self.l:1: #include nested too deeply",
                 err('#include "self.l"\n' .. lsystem("A"), { ["self.l"] = '#include "self.l"\n' }))
  end)

  it("stops files that include each other twice", function ()
    local files = {}
    for i = 1, 22 do
      files["f" .. i .. ".l"] = ('#include "f%d.l"\n'):rep(2):format(i + 1, i + 1)
    end
    files["f23.l"] = "\n"
    assert.equal("f23.l:1: more than 100000 lines with the #include files",
                 err('#include "f1.l"\n' .. lsystem("A"), files))
  end)

  it("stops files that include each other twice and expand long lines",
     function ()
    local files = {}
    for i = 1, 12 do
      files["f" .. i .. ".l"] = ('#include "f%d.l"\n'):rep(2):format(i + 1, i + 1)
    end
    files["f13.l"] = "#define X x\n" .. ("X + "):rep(500) .. "\n"
    assert.equal("f13.l:2: more than 4 MiB of text with the #include files and macros",
                 err('#include "f1.l"\n' .. lsystem("A"), files))
  end)

  it("takes a header included many times", function ()
    local m = load("main.l", { ["k.h"] = "#define K 2\n",
                               ["main.l"] = ('#include "k.h"\n'):rep(50) .. lsystem("A(K)") })
    assert.equal("A(2)", tostring(m:derive(0)))
  end)
end)

-- What an #include may read, for both preprocessors. A model's files are
-- the file and the regular files below its folder; nothing else is opened, and no line of
-- another file is ever quoted.
describe("lsys.cpfg.load's #include", function ()
  local hascpp = os.execute("command -v cpp >/dev/null 2>&1")
  local shq = require("lsys.util.text").shq

  -- The message of loading `text` as sub/main.l (the model's folder is sub), or nil.
  local function suberr (text, how)
    os.execute("mkdir -p " .. shq(dir .. "/sub"))
    H.write(dir .. "/sub/main.l", text)
    local ok, msg = pcall(lsys.cpfg.load, dir .. "/sub/main.l", nil, { cpp = how })
    if ok then return nil end
    return (msg:gsub(dir:gsub("%p", "%%%0") .. "/", ""))
  end

  local function each (f)
    f("builtin")
    if hascpp then f("system") end
  end

  it("refuses a file outside the model's folder, and never quotes it", function ()
    H.write(dir .. "/up.h", "secret line\n")
    os.execute("ln -s /etc/passwd " .. shq(dir .. "/sub-link.h"))
    each(function (how)
      assert.equal('sub/main.l:1: /etc/passwd: outside the model\'s folder',
                   suberr('#include "/etc/passwd"\n' .. lsystem("A"), how))
      assert.equal("sub/main.l:2: ../up.h: outside the model's folder",
                   suberr('\n#include "../up.h"\n' .. lsystem("A"), how))
      assert.equal("sub/main.l:1: ./../sub/../up.h: outside the model's folder",
                   suberr('#include "./../sub/../up.h"\n' .. lsystem("A"), how))
      os.execute("ln -sf ../sub-link.h " .. shq(dir .. "/sub/link.h"))
      assert.equal("sub/main.l:1: link.h: outside the model's folder",   -- a link out
                   suberr('#include "link.h"\n' .. lsystem("A"), how))
    end)
  end)

  it("tells the model's own files from others (what lsys view watches)", function ()
    local cpp = require "lsys.cpfg.cpp"
    os.execute("mkdir -p " .. shq(dir .. "/sub/inc"))
    H.write(dir .. "/sub/main.l", "x\n")
    H.write(dir .. "/sub/inc/k.h", "y\n")
    H.write(dir .. "/up.h", "z\n")
    local main = dir .. "/sub/main.l"
    assert.is_true(cpp.ismodelfile(main, dir .. "/sub/inc/k.h"))
    assert.is_true(cpp.ismodelfile(main, dir .. "/sub/../sub/inc/k.h"))
    assert.is_false(cpp.ismodelfile(main, dir .. "/sub/../up.h"))
    assert.is_false(cpp.ismodelfile(main, "/etc/passwd"))
    assert.is_false(cpp.ismodelfile(main, "/dev/zero"))
    assert.is_false(cpp.ismodelfile(main, dir .. "/sub/inc"))
    assert.is_false(cpp.ismodelfile(main, dir .. "/sub/missing.h"))
  end)

  it("refuses devices, folders and FIFOs without opening them", function ()
    os.execute("mkfifo " .. shq(dir .. "/fifo"))
    each(function (how)
      assert.equal("main.l:1: fifo: not a regular file",
                   err('#include "fifo"\n' .. lsystem("A"), nil, { cpp = how }))
      assert.equal("main.l:1: /dev/zero: not a regular file",
                   err('#include "/dev/zero"\n' .. lsystem("A"), nil, { cpp = how }))
    end)
  end)

  it("takes the files below the folder, through links that stay in it", function ()
    each(function (how)
      os.execute("mkdir -p " .. shq(dir .. "/sub/inc"))
      H.write(dir .. "/sub/inc/k.h", "#define K 4\n")
      os.execute("ln -sf inc/k.h " .. shq(dir .. "/sub/k2.h"))
      assert.is_nil(suberr('#include "inc/k.h"\n#include "k2.h"\n' .. lsystem("A(K)"), how))
    end)
  end)

  it("refuses what the system cpp could read past the scan", function ()
    if not hascpp then return pending("no cpp") end
    local opts = { cpp = "system" }
    assert.equal('main.l:2: #include needs a "file" name',
                 err('#define F "/etc/passwd"\n#include F\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: /etc/passwd: outside the model's folder",      -- a digraph
                 err('%:include "/etc/passwd"\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: /etc/passwd: outside the model's folder",      -- a continuation
                 err('#inc\\\nlude "/etc/passwd"\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:2: /etc/passwd: outside the model's folder",      -- '/*' in quotes
                 err("A '/*'\n#include \"/etc/passwd\"\n" .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: /etc/passwd: outside the model's folder",
                 err('#include </etc/passwd>\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: /etc/passwd: outside the model's folder",
                 err('#embed "/etc/passwd"\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: __has_include is not supported",
                 err('#if __has_include("/etc/passwd")\n#endif\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: _Pragma is not supported",
                 err('_Pragma("GCC dependency \\"x\\"")\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: #pragma ... dependency is not supported",
                 err('#pragma GCC dependency "main.l"\n' .. lsystem("A"), nil, opts))
    assert.equal("main.l:1: /etc/passwd: outside the model's folder",      -- a #line's name
                 err('#line 1 "/etc/passwd"\n' .. lsystem("A"), nil, opts))
    -- prose in a comment is not a directive that needs a file
    assert.truthy(load("main.l", { ["main.l"] = "/* a comment\n  #include files */\n"
                                   .. lsystem("A") }, opts))
  end)

  it("bounds the system cpp's output as the built-in preprocessor's", function ()
    if not hascpp then return pending("no cpp") end
    local files = {}
    for i = 1, 22 do
      files["f" .. i .. ".l"] = ('#include "f%d.l"\n'):rep(2):format(i + 1, i + 1)
    end
    files["f23.l"] = "\n"
    assert.equal("f23.l:1: more than 4 MiB of text with the #include files and macros",
                 err('#include "f1.l"\n' .. lsystem("A"), files, { cpp = "system" }))
    local defs = "#define A0 x\n"
    for i = 1, 30 do defs = defs .. ("#define A%d A%d A%d\n"):format(i, i - 1, i - 1) end
    assert.equal("main.l:34: more than 4 MiB of text with the #include files and macros",
                 err(defs .. lsystem("X(A30)"), nil, { cpp = "system" }))
    -- arguments expanded before they are used: 2^29 tokens in cc1's memory, within 1 GiB
    local bomb = err("#define D(x) x x\n" .. lsystem("X(" .. ("D("):rep(30) .. "1"
                                                     .. (")"):rep(30) .. ")"), nil,
                     { cpp = "system" })
    assert.truthy(bomb:find("^cc1: out of memory") or bomb:find("^cpp was stopped"), bomb)
  end)

  it("writes no file: cpp reads the model through a pipe", function ()
    if not hascpp then return pending("no cpp") end
    -- luacheck: push ignore 122 (os.tmpname and io.open watched for the call)
    local tmpname, open = os.tmpname, io.open
    local wrote = {}
    os.tmpname = function () wrote[#wrote + 1] = "os.tmpname" return tmpname() end
    io.open = function (path, mode)
      if mode and mode:find("[wa+]") then wrote[#wrote + 1] = path end
      return open(path, mode)
    end
    local ok, m = pcall(load, "main.l", { ["main.l"] = "#define N 2\n"    -- '#' on a text line
                        .. lsystem("A(N)", "A(x) --> F(x)\n\t#(N) F\n") }, { cpp = "system" })
    os.tmpname, io.open = tmpname, open
    -- luacheck: pop
    assert(ok, m)
    assert.equal("F(2)#(2)F", tostring(m:derive(1)))
    assert.same({ dir .. "/main.l" }, wrote)          -- the spec's own file, nothing else
  end)
end)

describe("lsys.cpfg.load's translated statements", function ()
  local function derive (body)
    local m = load("main.l", { ["main.l"] = lsystem("A(1)", "A(x) : { " .. body
                                                    .. " } * --> B(y)\n",
                                                    "define: { array a[3]; }\n") })
    local ok, msg = pcall(m.derive, m, 1)
    return ok and tostring(msg) or msg
  end

  it("keep parameters named as the translation's own names apart from them", function ()
    local function run (prod)
      local m = load("main.l", { ["main.l"] = lsystem("A(2)", prod .. "\n",
                                                      "Start: { glob = 1; }\n") })
      return tostring(m:derive(1))
    end
    -- the function form: E, H and L are its tables
    assert.equal("B(3)", run("A(E) : { y = 0; while (y < 1) { y = y + E + glob; } } * --> B(y)"))
    assert.equal("B(2)", run("A(H) : { y = 0; while (y < 1) { y = y + H; } } * --> B(y)"))
    assert.equal("B(2)", run("A(L) : { y = 0; while (y < 1) { y = y + L; } } * --> B(y)"))
    -- rule strings: sin(x) is sin(x * pi / 180), fabs is abs
    assert.equal("B(1,2)", run("A(pi) --> B(sin(90), pi)"))
    assert.equal("B(2,2)", run("A(abs) --> B(fabs(-2), abs)"))
  end)

  it("print with conversions Lua's format refuses, as C's without them", function ()
    local out = dir .. "/out.txt"
    local old = io.output()
    io.output(out)
    local ok, s = pcall(derive, 'printf("%100d|%#d|%.2c|%+x|%5.300f|%c\\n", 1, 2, 65, 255, '
                                .. "1.5, 66); y = 1;")
    io.output():close()
    io.output(old)
    assert(ok, s)
    assert.equal("B(1)", s)
    assert.equal("1|2|A|ff|1.500000|B\n", H.read(out))
  end)

  it("refuse a derivation length over lsys's limit, naming its line", function ()
    assert.equal("main.l:3: the derivation length is 4.29497e+08, not 0 to 10000000",
                 err("#define N 429496720.5\n" .. lsystem("A"):gsub("length: 1", "length: N")))
  end)

  it("refuse arrays of more than 1e7 elements in all", function ()
    assert.equal("main.l:4: array c: the arrays have more than 1e7 elements in all",
                 err(lsystem("A", nil, "define: { array a[1000][5000], b[1000][5000]; }\n"
                             .. "define: { array c[2]; }\n")))
    assert.equal("main.l:3: array a has more than 1e7 elements",
                 err(lsystem("A", nil, "define: { array a[10000][1001]; }\n")))
  end)

  it("take the nearest element for an index out of range, as cpfg; refuse NaN", function ()
    local warning = require "lsys.warning"
    local saved, got = warning.warn, {}
    warning.warn = function (msg)
      if msg:find("array a", 1, true) then
        got[#got + 1] = msg:gsub(dir:gsub("%p", "%%%0") .. "/", "")
      end
    end
    local r = {}
    for i, body in ipairs { "a[2] = 5; y = a[7];", "a[0] = 4; y = a[-3];",
                            "a[2] = 6; y = a[3];", "y = a[-0.5];", "a[0/0] = 1;",
                            "y = a[0/0];" } do
      r[i] = derive(body)
    end
    warning.warn = saved
    assert.same({ "B(5)", "B(4)", "B(6)", "B(0)" }, { r[1], r[2], r[3], r[4] })   -- cpfg
    assert.equal("index", r[5]:match("cpfg: (index) %S+ out of range 0..2 of array a$"))
    assert.equal("index", r[6]:match("cpfg: (index) %S+ out of range 0..2 of array a$"))
    assert.same({
      "main.l:3: array a: index 7 out of range 0..2; 2 used, as cpfg does (said once per "
        .. "array and derivation)",
      "main.l:3: array a: index -3 out of range 0..2; 0 used, as cpfg does (said once per "
        .. "array and derivation)",
      "main.l:3: array a: index 3 out of range 0..2; 2 used, as cpfg does (said once per "
        .. "array and derivation)",
    }, got)
  end)
end)

describe("lsys.cpfg.load's messages", function ()
  it("hint at '-->' for a production written with '->'", function ()
    assert.equal("main.l:4: '->' is not a production arrow in cpfg; write '-->'",
                 err(lsystem("A(1)", "A(x) -> A(x+1)\n")))
    assert.equal("main.l:4: '-->' expected in a production, found the end of the line",
                 err(lsystem("A(1)", "A(x) B\n")))
    -- a '-' module before a right context is not an arrow
    local m = load("main.l", { ["main.l"] = lsystem("-B", "-<B --> C\n") })
    assert.equal("-C", tostring(m:derive(1)))
  end)

  it("name the .l file and the production's line when a rule fails as it derives",
     function ()
    local m = load("main.l", { ["main.l"] = lsystem("A(1)", "A(x) --> B(x)\n\nB(x) --> C(x/0)\n") })
    local ok, msg = pcall(m.derive, m, 2)
    assert.is_false(ok)
    assert.equal("main.l:6: rule 2 'B(x) --> C((x / 0.0))', module 1: value 1 is "
                 .. "infinite, not a finite number", (msg:gsub(dir:gsub("%p", "%%%0") .. "/", "")))
  end)

  it("refuse a bracket in a predecessor, saying why", function ()
    assert.equal("main.l:4: a bracket in a predecessor is not supported: lsys rewrites "
                 .. "modules, never the branch structure; remove a branch with % (a cut) "
                 .. "from a module in it (docs/cpfg.md)",
                 err(lsystem("A[BC]D", "[BC] --> X\n")))
    assert.equal("main.l:4: a bracket in a predecessor is not supported: lsys rewrites "
                 .. "modules, never the branch structure; remove a branch with % (a cut) "
                 .. "from a module in it (docs/cpfg.md)",
                 err(lsystem("A[BC]D", "A < B C] --> X\n")))
  end)

  it("say that a model without its view file has no functions", function ()
    local m = load("main.l", { ["main.l"] = lsystem("A(1)", "A(x) --> A(func(1, x))\n") })
    local ok, msg = pcall(m.derive, m, 1)
    assert.is_false(ok)
    assert.equal("main.l:4: rule 1 'A(x) --> A(func(1.0, x))': unknown function 1 (functions: "
                 .. "none); a cpfg model's functions come from its view file (.v), and none "
                 .. "was given", (msg:gsub(dir:gsub("%p", "%%%0") .. "/", "")))
  end)
end)
