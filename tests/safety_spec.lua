-- Memory safety, safe outputs, bounded memory: each finding of the audit with
-- the test that fails before its fix.
local H = require "tests.helper"
local lsys = require "lsys"

local errof = H.errof

local tmpdir, rmdir, slurp, spit = H.tmpdir, H.rmdir, H.read, H.write

-- AddressSanitizer (tools/sanitize.sh) reserves terabytes of address space: a process
-- under an address-space limit (ulimit -v) cannot start there.
local SANITIZED = os.getenv("ASAN_OPTIONS") ~= nil

local function exists (path) return H.read(path) ~= nil end

describe("rule expressions", function ()
  local marker
  before_each(function () marker = os.tmpname(); os.remove(marker) end)
  after_each(function () os.remove(marker) end)

  -- each rule must fail at definition or derivation without touching the marker
  local function hostile (rule)
    local err = errof(function ()
      local m = lsys.lsystem { axiom = "A(1)", productions = { (rule:gsub("MARKER", marker)) } }
      return m:derive(1)
    end)
    assert.is_false(exists(marker), "the rule ran its command: " .. rule)
    return err
  end

  it("do not reach globals after the concatenation operator", function ()
    local err = hostile('A(x) --> A(#(""..os.execute("touch MARKER")))')
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
    err = hostile('A(x) --> A(x) B(#(""..io.open("MARKER", "w")))')
    assert.truthy(err:find("unknown name 'io'", 1, true), err)
    err = hostile('A(x) : ""..os.exit(3) --> A(x)')
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
  end)

  it("run in an environment without globals when the name scan is fooled", function ()
    -- the scan takes the comment's quote for a string and misses `os`; the compiled
    -- closure still cannot see it
    local err = hostile([[A(x) --> A(x --"
 + #os.getenv'HOME' --"
)]])
    assert.truthy(err:find("unknown name 'os'", 1, true), err)
    err = hostile([[A(x) --> A(x --"
 + #_G.os.getenv'HOME' --"
)]])
    assert.truthy(err:find("unknown name '_G'", 1, true), err)
  end)

  it("cannot end the generated closure with a line comment", function ()
    -- each expression stands on its own lines: the comment ends with the expression
    local m = lsys.lsystem { axiom = "A(1)", productions = { "A(x) --> A(x + 1 --\n) B(x * 2)" } }
    assert.equal("A(2)B(2)", tostring(m:derive(1)))
  end)

  it("still see parameters, env, ran and the builtins", function ()
    local m = lsys.lsystem { axiom = "A(1)", env = { k = 3 }, seed = 1,
      productions = 'A(x) --> A(x + k) B(floor(pi)) C(#("ab" .. x)) D(math.max(x, 2))' }
    assert.equal("A(4)B(3)C(5)D(2)", tostring(m:derive(1)))
  end)
end)

describe("re-entering a model from its own rules", function ()
  local REENTER = "a rule called step on the model it belongs to"

  it("is refused with a clear error (the audit's use-after-free)", function ()
    local m
    m = lsys.lsystem { axiom = "A[B][B]B[B]C", productions = {
      { "A", function () m:step(string.rep("[B]", 200000)) end },
      "B < C --> D", "B > [B] --> E" } }
    assert.error_contains(function () m:derive(1) end, REENTER, "rule 1 'A'")
    -- the refused step left the model usable
    assert.is_false(m._rules:busy())
    assert.equal("E[B]D", tostring(m:step("B[B]C")))
  end)

  it("leaves the running rule able to produce after it caught the refusal", function ()
    local m
    m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
      local ok, err = pcall(m.step, m, "A")
      assert(not ok and err:find(REENTER, 1, true), err)
      return lsys.produce("B")
    end } } }
    assert.equal("B", tostring(m:derive(1)))
  end)

  it("is refused also through the core and for expand and interpret", function ()
    local m, seen
    m = lsys.lsystem { axiom = "A[B]C", homomorphism = { { "B", function ()
        seen = select(2, pcall(m.interpret, m, "F"))
        return lsys.produce("F")
      end } },
      productions = { { "A", function ()
        seen = select(2, pcall(m._rules.step, m._rules, lsys.lstring("B C")))
        return lsys.produce("Q")
      end }, "B > C --> D" } }
    assert.equal("Q[B]C", tostring(m:derive(1)))
    assert.truthy(seen:find(REENTER, 1, true), seen)
    m:interpret("A[B]C")
    assert.truthy(seen:find("a rule called interpret on the model it belongs to", 1, true), seen)
  end)

  it("cannot change the rules or close the strings a step works on", function ()
    local m, errs = nil, {}
    local src = lsys.lstring("A B")
    m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
      errs[1] = select(2, pcall(m._rules.add, m._rules, 0, 0, 0, { pred = { 1, 0 } }))
      errs[2] = select(2, pcall(m.use_group, m, 1))
      errs[3] = select(2, pcall(getmetatable(src).__close, src))
      errs[4] = select(2, pcall(getmetatable(m._rules).__close, m._rules))
      return lsys.produce("Q")
    end } } }
    assert.equal("QB", tostring(m:step(src)))
    assert.truthy(errs[1]:find("cannot change while it derives", 1, true) or
                  errs[1]:find("cannot change", 1, true), errs[1])
    assert.truthy(errs[2]:find("a rule called use_group on the model it belongs to", 1, true),
                  errs[2])
    assert.truthy(errs[3]:find("cannot close an Lstring while", 1, true), errs[3])
    assert.truthy(errs[4]:find("cannot close the rules", 1, true), errs[4])
    assert.equal("AB", tostring(src))
  end)

  it("cannot rewrite the string another model is deriving from", function ()
    local other = lsys.lsystem { axiom = "X", productions = "X --> Y" }
    local src = lsys.lstring("A B")
    local m, err
    m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
      err = select(2, pcall(other._rules.step, other._rules, lsys.lstring("X"), src))
      return lsys.produce("Q")
    end } } }
    assert.equal("QB", tostring(m:step(src)))
    assert.truthy(err:find("the Lstring is in use", 1, true), err)
  end)
end)

describe("closed objects", function ()
  local function close (x) getmetatable(x).__close(x) end

  it("a closed scene raises in every method (the audit's use-after-free)", function ()
    local m = lsys.lsystem { axiom = "F[+F]F", view = { angle = 30 } }
    local scene = m:interpret()
    assert.equal(3, scene.nrecords)
    close(scene)
    close(scene)                                   -- idempotent
    assert.equal("lsys.Scene (closed)", tostring(scene))
    local d = tmpdir()
    for name, f in pairs {
      records = function () for _ in scene:records() do end end,
      record = function () return scene:record(1) end,
      find = function () return scene:find(1) end,
      edges = function () return scene:edges(1) end,
      bounds = function () return scene:bounds() end,
      area = function () return scene:area() end,
      turtle = function () return scene:turtle(1) end,
      save = function () return scene:save(d .. "/x.obj") end,
      nrecords = function () return scene.nrecords end,
      ntriangles = function () return scene.ntriangles end,
      render = function () return lsys.render(scene, { width = 8, height = 8 }) end,
    } do
      local err = errof(f)
      assert.truthy(err:find("the scene was closed", 1, true), name .. ": " .. err)
    end
    assert.is_false(exists(d .. "/x.obj"))
    rmdir(d)
  end)

  it("a scene's records iterator stops with an error when the scene closes", function ()
    local scene = lsys.lsystem { axiom = "FFF" }:interpret()
    assert.error_contains(function ()
      for k in scene:records() do if k == 1 then close(scene) end end
    end, "the scene was closed")
  end)

  it("closed rules raise instead of crashing (the audit's segfault)", function ()
    local m = lsys.lsystem { axiom = "A", productions = "A --> AB" }
    close(m._rules)
    for name, f in pairs {
      derive = function () return m:derive(1) end,
      step = function () return m:step("A") end,
      interpret = function () return m:interpret("F") end,
      lstring = function () return m:lstring("A") end,
      expand = function () return m:expand("A") end,
    } do
      local err = errof(f)
      assert.truthy(err:find("the model's rules were closed", 1, true), name .. ": " .. err)
    end
  end)

  it("a model resurrected by a finalizer raises instead of crashing", function ()
    -- the guard is created first, so its finalizer runs after the rules' at exit
    local out, code = H.lsys([[
local lsys = require "lsys"
local guard = setmetatable({}, { __gc = function (g)
  local ok, err = pcall(g.m.derive, g.m, 2)
  io.stdout:write("resurrected: ", tostring(ok), " ", tostring(err), "\n")
end })
guard.m = lsys.lsystem { axiom = "A", productions = "A --> AB" }
_G.keep = guard
]])
    assert.equal(0, code, out)
    assert.truthy(out:find("resurrected: false", 1, true), out)
    assert.truthy(out:find("were closed", 1, true), out)
  end)

  it("closed Lstrings, contours, surfaces, textures and IK chains raise", function ()
    local core = require "lsys.core"
    local s = lsys.lstring("F(1)[+A]")
    close(s)
    assert.equal("lsys.Lstring (closed)", tostring(s))
    for _, f in ipairs {
      function () return #s end, function () return s:module(1) end,
      function () return s:sub(1, 2) end, function () return s:count("F") end,
      function () return s == lsys.lstring("F") end,
      function () return lsys.lsystem { axiom = "F" }:interpret(s) end,
    } do
      assert.truthy(errof(f):find("the Lstring was closed", 1, true))
    end
    local c = core.contour({ { 1, 0 }, { 0, 1 }, { -1, 0 } })
    close(c)
    assert.equal("lsys.Contour (closed)", tostring(c))
    assert.truthy(errof(c.sample, c, 4):find("the contour was closed", 1, true))
    assert.truthy(errof(function ()
      lsys.lsystem { axiom = "@#(1)F", view = { line_style = "cylinder", contours = { c } } }
        :interpret()
    end):find("the contour was closed", 1, true))
    local sf = core.surface_parse(H.read("tests/data/surfaces/leaf.s"), "leaf.s")
    close(sf)
    assert.equal("lsys.Surface (closed)", tostring(sf))
    assert.truthy(errof(sf.info, sf):find("the surface was closed", 1, true))
    local ik = core.ik_chain { base = { H = { 0, 1, 0 }, U = { 0, 0, 1 }, p = { 0, 0, 0 } },
      joints = { { p0 = { 0, 0, 0 }, p1 = { 0, 1, 0 }, H = { 0, 1, 0 }, U = { 0, 0, 1 } } } }
    assert.equal(1, #ik)
    close(ik)
    assert.truthy(errof(ik.angles, ik):find("the chain was closed", 1, true))
  end)
end)

describe("outputs", function ()
  local core = require "lsys.core"
  local d
  before_each(function () d = tmpdir() end)
  after_each(function () rmdir(d) end)

  local function listing (dir) return (H.sh("ls -A '" .. dir .. "'")) end
  local function scene ()
    return lsys.lsystem { axiom = "F[+F]F[-F]F", view = { angle = 30, line_style = "cylinder",
                                                          line_width = 0.1 } }:interpret()
  end

  it("a failed write to a device leaves the device alone (the audit's deleted /dev/full)",
  function ()
    -- as root, a copy of /dev/full in the temporary folder, so that a regression removes
    -- only the copy; otherwise /dev/full itself, which a user cannot remove
    local full = d .. "/full"
    if not os.execute("mknod -m 666 '" .. full .. "' c 1 7 2>/dev/null") then full = "/dev/full" end
    local function kind (path, follow)
      return (H.sh("stat " .. (follow and "-L " or "") .. "-c %F '" .. path .. "'"))
    end
    local function isdevice (path) return kind(path, true) == "character special file\n" end
    assert.is_true(isdevice(full))
    assert.error_contains(function ()
      lsys.render(scene(), { out = full, width = 32, height = 32 })
    end, "cannot write '" .. full .. "'", "No space left on device")
    assert.error_contains(function ()
      core.png_write(full, string.rep("\0\0\0\255", 4), 2, 2)
    end, "cannot write '" .. full .. "'")
    assert.is_true(isdevice(full), full .. " was removed or replaced")
    -- a link to the device: the link stays too
    os.execute("ln -s '" .. full .. "' '" .. d .. "/out.png'")
    assert.error_contains(function ()
      lsys.render(scene(), { out = d .. "/out.png", width = 32, height = 32 })
    end, "No space left on device")
    assert.equal("symbolic link\n", kind(d .. "/out.png"))
    assert.is_true(isdevice(d .. "/out.png"))
    assert.is_true(isdevice(full))
  end)

  -- runs `lsys SCRIPT` with the file size limited to 'kib' KiB, so a write fails
  -- half-way as on a full disk; returns the output
  local function limited (script, kib)
    return (H.lsys(script, { prefix = ("trap \"\" XFSZ; ulimit -f %d;"):format(kib) }))
  end

  it("a failed write keeps the old file and leaves no partial file", function ()
    for _, name in ipairs { "old.png", "old.obj", "old.ply", "old.glb" } do
      spit(d .. "/" .. name, "previous content")
    end
    spit(d .. "/old.mtl", "previous materials")
    local out = limited(([[
local lsys = require "lsys"
local s = lsys.lsystem { axiom = "F", productions = "F --> F[+F]F[-F]F", steps = 4,
                         view = { angle = 25, line_style = "cylinder", line_width = 0.1 } }
local scene = s:interpret()
for _, ext in ipairs { "obj", "ply", "glb" } do
  print(ext, pcall(scene.save, scene, "%s/old." .. ext))
end
print("png", pcall(lsys.render, scene, { out = "%s/old.png", width = 600, height = 600 }))
]]):format(d, d), 8)
    for _, ext in ipairs { "obj", "ply", "glb", "png" } do
      local want = ext .. "\tfalse\t[^\n]*cannot write '[^']*old%." .. ext .. "': File too large"
      assert.truthy(out:find(want), out)
      assert.equal("previous content", slurp(d .. "/old." .. ext))
    end
    assert.equal("previous materials", slurp(d .. "/old.mtl"))
    assert.equal("old.glb\nold.mtl\nold.obj\nold.ply\nold.png\n", listing(d))
  end)

  it("a successful write replaces the file, keeps its mode and follows links", function ()
    spit(d .. "/a.obj", "old")
    os.execute("chmod 600 '" .. d .. "/a.obj'")
    os.execute("mkdir '" .. d .. "/real' && ln -s real/b.ply '" .. d .. "/b.ply' && " ..
               "echo old > '" .. d .. "/real/b.ply'")
    local sc = scene()
    assert.truthy(sc:save(d .. "/a.obj"))
    assert.truthy(sc:save(d .. "/b.ply"))
    assert.truthy(slurp(d .. "/a.obj"):find("^# lsys: "))
    assert.truthy(slurp(d .. "/real/b.ply"):find("^ply\n"))
    local modes = H.sh("stat -c '%a %F' '" .. d .. "/a.obj' '" .. d .. "/b.ply'")
    assert.equal("600 regular file\n777 symbolic link\n", modes)
    assert.equal("a.mtl\na.obj\nb.ply\nreal\n", listing(d))
    assert.is_true(core.write_file(d .. "/c.txt", "hello"))
    assert.equal("hello", slurp(d .. "/c.txt"))
    assert.error_contains(function () core.write_file(d .. "/none/c.txt", "x") end,
                          "cannot open '" .. d .. "/none/c.txt' for writing")
    assert.error_contains(function () core.write_file(d, "x") end, "Is a directory")
  end)
end)

describe("the memory budget", function ()
  local core = require "lsys.core"
  local saved
  before_each(function () saved = lsys.max_memory() end)
  after_each(function () lsys.max_memory(saved == math.huge and "unlimited" or saved) end)

  -- runs `lsys SCRIPT` with the environment `env`, under a virtual memory limit of `kib`
  local function run (script, env, kib)
    local limit = SANITIZED and "" or ("ulimit -v %d;"):format(kib or 4000000)
    local out, code = H.lsys(script, { env = env, prefix = limit })
    return out .. "exit:" .. tostring(code)
  end

  it("reads sizes in bytes and binary units", function ()
    assert.equal(512 * 2 ^ 20, lsys.parse_size("512M"))
    assert.equal(2 * 2 ^ 30, lsys.parse_size("2G"))
    assert.equal(1.5 * 2 ^ 30, lsys.parse_size("1.5GiB"))
    assert.equal(800 * 2 ^ 20, lsys.parse_size("800 MB"))
    assert.equal(4096, lsys.parse_size(4096))
    assert.equal(math.huge, lsys.parse_size("unlimited"))
    assert.error_contains(function () lsys.parse_size("lots", "max_memory") end,
                          "max_memory: 'lots' is not a size")
    assert.error_contains(function () lsys.lsystem { max_memory = 0 } end,
                          "option 'max_memory' must be at least 1 byte")
    local limit, phys = lsys.max_memory()
    assert.is_true(phys > 0 and (saved ~= limit or limit <= phys))
    assert.equal(2 ^ 30, (lsys.max_memory("1G")))
  end)

  it("stops a derivation whose parameters outgrow max_memory (31 doubles a module)", function ()
    local names = {}
    for i = 1, 31 do names[i] = "p" .. i end
    local P = table.concat(names, ",")
    -- each step doubles the string; at 50 M modules it would need 12 GB
    local out = run(([[
local lsys = require "lsys"
local m = lsys.lsystem { axiom = "A(%s)", max_memory = "64M",
                         productions = "A(%s) --> A(%s) A(%s)" }
print(pcall(m.derive, m, 26))
]]):format(string.rep("1,", 30) .. "1", P, P, P), nil, 1000000)
    assert.truthy(out:find("false\t[^\n]*the derivation would need more than " ..
                           "max_memory %(64 MiB%)"), out)
    assert.truthy(out:find("exit:0", 1, true), out)
    -- the process default, from LSYS_MAX_MEMORY
    out = run(([[
local lsys = require "lsys"
print(lsys.max_memory())
local m = lsys.lsystem { axiom = "A(%s)", productions = "A(%s) --> A(%s) A(%s)" }
print(pcall(m.derive, m, 26))
]]):format(string.rep("1,", 30) .. "1", P, P, P), "LSYS_MAX_MEMORY=32M", 1000000)
    assert.truthy(out:find("^33554432\t"), out)
    assert.truthy(out:find("max_memory %(32 MiB%)"), out)
    out = run("require 'lsys'", "LSYS_MAX_MEMORY=3X")
    assert.truthy(out:find("LSYS_MAX_MEMORY: '3X' is not a size", 1, true), out)
  end)

  it("stops an interpretation whose mesh outgrows max_memory", function ()
    local m = lsys.lsystem { axiom = "F", max_memory = "8M", productions = "F --> F[+F]F",
                             view = { line_style = "cylinder", contour_sides = 16 } }
    local s = m:derive(9)
    assert.error_contains(function () m:interpret(s) end,
                          "the interpretation would need more than max_memory (8 MiB)")
    m.view.line_style = "line"
    assert.truthy(m:interpret(m:derive(4)).nlines > 0)  -- smaller ones still draw
  end)

  it("takes max_memory = \"unlimited\" as a model option (no limit of its own)", function ()
    local m = lsys.lsystem { axiom = "F", max_memory = "unlimited", productions = "F --> FF" }
    assert.equal(math.huge, m.max_memory)
    assert.equal(256, #m:derive(8))
  end)

  -- a PNG whose header declares w x h pixels (CRCs computed), its data a few bytes
  local function crc32 (s)
    local c = 0xffffffff
    for i = 1, #s do
      c = c ~ s:byte(i)
      for _ = 1, 8 do c = (c >> 1) ~ (0xedb88320 & -(c & 1)) end
    end
    return c ~ 0xffffffff
  end
  local function chunk (kind, data)
    return string.pack(">I4", #data) .. kind .. data .. string.pack(">I4", crc32(kind .. data))
  end
  local function bigpng (path, w, h)
    spit(path, "\137PNG\r\n\26\n" .. chunk("IHDR", string.pack(">I4I4BBBBB", w, h, 8, 6, 0, 0, 0))
               .. chunk("IDAT", "\120\156\3\0\0\0\0\1") .. chunk("IEND", ""))
  end

  it("refuses a texture whose pixels outgrow max_memory before decoding it", function ()
    local path = os.tmpname()
    bigpng(path, 32768, 32768)                   -- a few bytes declaring 4 GiB of pixels
    lsys.max_memory("1G")
    assert.error_contains(function () core.texture_load(path) end,
      "32768x32768 pixels need 4.0 GiB, more than max_memory (1.0 GiB)")
    assert.error_contains(function () core.png_read(path) end, "more than max_memory")
    os.remove(path)
  end)

  it("refuses a picture whose buffers outgrow max_memory", function ()
    if not core.has_render then return pending("built without rendering") end
    local scene = lsys.lsystem { axiom = "F" }:interpret()
    lsys.max_memory("16M")
    assert.error_contains(function () lsys.render(scene, { width = 4096, height = 4096 }) end,
                          "a 4096x4096 picture needs 192 MiB, more than max_memory (16 MiB)")
    assert.equal(64 * 64 * 4, #lsys.render(scene, { width = 64, height = 64 }))
  end)

  it("reads only regular files of bounded size (a view naming /dev/zero)", function ()
    local view = require "lsys.view"
    for what, f in pairs {
      contour = function () return core.contour_load("/dev/zero") end,
      surface = function () return core.surface_load("/dev/zero") end,
      texture = function () return core.texture_load("/dev/zero") end,
      viewfile = function () return view.load("/dev/zero") end,
      colormap = function () return view.load_colormap("/dev/zero") end,
      materials = function () return view.load_materials("/dev/zero") end,
      model = function ()
        return lsys.lsystem { axiom = "F", view = { contours = { "/dev/zero" } } }:interpret()
      end,
    } do
      local err = errof(f)
      assert.truthy(err:find("cannot read '/dev/zero': not a regular file", 1, true),
                    what .. ": " .. err)
    end
  end)
end)

describe("parse errors about files a view names", function ()
  local core = require "lsys.core"
  local view = require "lsys.view"
  local SECRET = "Zq8xFvLwT2pKsMnBhJ3k9Qe7rUvYzA1bC5dEfG"     -- say, a token in a private file

  -- the longest run of the secret that the message repeats
  local function leaked (msg)
    local best = 0
    for i = 1, #SECRET do
      for j = i + best, #SECRET do
        if not msg:find(SECRET:sub(i, j), 1, true) then break end
        best = j - i + 1
      end
    end
    return best
  end

  it("quote at most a short token of the file", function ()
    local path = os.tmpname()
    local function file (text) spit(path, text) end
    for what, case in pairs {
      contour = { SECRET .. " 2 closed\n", function () return core.contour_load(path) end },
      surface = { SECRET .. "\n", function () return core.surface_load(path) end },
      viewfile = { SECRET .. " " .. SECRET .. "\n", function () return view.load(path) end },
      command = { SECRET .. ": 1\n", function () return view.load(path) end },
      model = { SECRET .. " 2 closed\n", function ()
        return lsys.lsystem { axiom = "F", view = { contours = { path } } }:interpret()
      end },
    } do
      file(case[1])
      local err = errof(case[2])
      assert.truthy(err:find(path, 1, true), what .. ": " .. err)     -- names the file
      assert.is_true(leaked(err) <= 12, what .. " quotes too much: " .. err)
    end
    os.remove(path)
  end)
end)

describe("a long axiom", function ()
  it("is parsed straight into an Lstring, without a Lua table per module", function ()
    local ax = string.rep("F(1)[+A(2)]", 200000)          -- 1 M modules
    collectgarbage(); collectgarbage()
    local before = collectgarbage("count")
    local m = lsys.lsystem { axiom = ax, productions = "A(x) --> A(x*2)" }
    local s = m:derive(0)
    collectgarbage(); collectgarbage()
    local grown = (collectgarbage("count") - before) / 1024
    assert.equal(1000000, #s)
    assert.equal(200000, s:count("A"))
    assert.is_true(grown < 16, ("the model took %.1f MB of Lua heap"):format(grown))
    assert.equal("F(1)[+A(4)]", tostring(m:derive(1):sub(1, 5)))
  end)

  it("keeps its expressions, evaluated in env at each derivation", function ()
    local m = lsys.lsystem { axiom = "A(k*2) B(k+1) A(k*2) C(-.5,1e1,0x10)", env = { k = 2 } }
    assert.equal("A(4)B(3)A(4)C(-0.5,10,16)", tostring(m:derive(0)))
    m.env.k = 5
    assert.equal("A(10)B(6)A(10)C(-0.5,10,16)", tostring(m:derive(0)))
    m.axiom = "X(inf)"
    assert.error_contains(function () m:derive(0) end, "axiom: expression 'inf' is nil")
    assert.error_contains(function () lsys.lsystem { axiom = string.rep("F", 1000) .. "(" } end,
                          "axiom 'FFFFFFFFFF", "...FFFFFFFF", "F(': ", "at character 1000")
  end)
end)

describe("fuzzing findings", function ()
  it("a constant parameter that overflows is an error, not an infinite parameter", function ()
    assert.error_contains(function ()
      lsys.lsystem { axiom = "A", productions = "A --> F(1e999)" }
    end, "parameter 1 of 'F' is '1e999', not a finite number")
  end)

  it("expanding a stochastic homomorphism leaves the derivation generator alone", function ()
    local function model ()
      return lsys.lsystem { axiom = "AAAA", seed = 3,
        productions = "A --> A : 1\nA --> B : 1", homomorphism = "A --> X : 1\nA --> Y : 1" }
    end
    local a, b = model(), model()
    local s = a:lstring("AAAAAAAAAAAAAAAA")
    b:expand(s)                                  -- draws from the homomorphism's generator
    assert.equal(tostring(a:step(s)), tostring(b:step(s)))
  end)

  it("the expression machine computes as Lua does (%, ceil, min with nan)", function ()
    for _, e in ipairs { "x % -3", "-x % -3", "-x % 3", "ceil(-x / 10)", "floor(-x / 10)",
                         "min(x, asin(x), exp(1))", "max(x, acos(x), 0.5)", "min(x, 0/0, 2)" } do
      local rule = ("A(x) --> B(%s)"):format(e)
      local got = {}
      for k, lx in ipairs { false, true } do
        local m = lsys.lsystem { axiom = "A(5)A(3)A(0.5)", productions = rule }
        m.lua_expressions = lx
        got[k] = tostring(m:derive(1))
      end
      assert.equal(got[2], got[1], e)
    end
    local m = lsys.lsystem { axiom = "A(5)", productions = "A(x) --> B(-x % -3, ceil(-x / 10))" }
    assert.equal("B(-2,0)", tostring(m:derive(1)))
    -- a bad value is reported where the condition held (seed 5: first at module 3)
    local errs = {}
    for k, lx in ipairs { false, true } do
      local r = lsys.lsystem { axiom = "A(1)A(1)A(1)A(1)A(1)A(1)", seed = 5,
                               productions = "A(x) : nran(1, 2^63) > 2 --> B(1/0 + 1)" }
      r.lua_expressions = lx
      errs[k] = select(2, pcall(r.derive, r, 1))
    end
    assert.truthy(errs[1]:find("module 3: value 1 is infinite", 1, true), errs[1])
    assert.equal(errs[2], errs[1])
  end)

  it("a PNG text chunk declaring 1.9 GB is skipped, not allocated", function ()
    local core = require "lsys.core"
    local path = os.tmpname()                      -- IHDR 1x1 RGB, then tEXt of 0x74455874 bytes
    spit(path, "\137PNG\r\n\26\n\0\0\0\13IHDR\0\0\0\1\0\0\0\1\8\2\0\0\0\144\119\83\222" ..
               "\116\69\88\116tEXtComment\0lsys")
    assert.error_contains(function () core.png_read(path) end, "unexpected end of file")
    -- under a 300 MB address-space limit the 1.9 GB allocation would fail instead
    local out = H.lsys(("print(pcall(require('lsys.core').png_read, %q))"):format(path),
                       { prefix = SANITIZED and "" or "ulimit -v 300000;" })
    os.remove(path)
    assert.truthy(out:find("false\t[^\n]*unexpected end of file"), out)
  end)
end)
