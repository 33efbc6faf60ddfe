-- What a new user trips over: each such mistake that is a behaviour of the library has
-- its spec here.
local H = require "tests.helper"
local lsys = require "lsys"
local format = string.format

local errof = H.errof

describe("the number of steps is bounded", function ()
  local m = lsys.lsystem { axiom = "A", productions = "A --> B" }

  it("refuses math.huge and 1e300 steps with a clear error, at once", function ()
    assert.matches("derive: infinitely many steps is more than the limit of 10000000",
                   errof(m.derive, m, math.huge), 1, true)
    assert.matches("derive: 1e+300 steps is more than the limit of 10000000",
                   errof(m.derive, m, 1e300), 1, true)
    assert.matches("option 'steps' is inf, more than the limit of 10000000",
                   errof(lsys.lsystem, { axiom = "A", steps = math.huge }), 1, true)
    m.steps = 1e8
    assert.matches("derive: 100000000 steps is more than the limit of 10000000",
                   errof(m.derive, m), 1, true)
    m.steps = 1
    assert.equal("B", tostring(m:derive()))
  end)

  it("says so on the command line, naming --steps", function ()
    local out, code = H.sh(H.BIN .. " derive --steps 1e8 examples/default.lua")
    assert.equal(2, code)
    assert.matches("lsys: derive: --steps 1e8 is more than the limit of 10000000 steps", out, 1,
                   true)
  end)
end)

describe("long quoted text is elided in messages", function ()
  local big = H.rep("F(1)", 200000)

  it("keeps a message about a 800 kB axiom short and shows where it is wrong", function ()
    local e = errof(lsys.lsystem, { axiom = big .. "F(" .. H.rep("F(1)", 100) })
    assert.is_true(#e < 400, #e .. " characters")
    assert.matches("^axiom 'F%(1%)F%(1%)", e)
    assert.matches("F%(F%(1%)", e)                          -- the unclosed F( is shown
    assert.matches("unbalanced parentheses after 'F' at character 800001", e, 1, true)
  end)

  it("keeps a message about a long rule short, at definition and in a step", function ()
    local e = errof(lsys.lsystem, { axiom = "A", productions = "A --> " .. big .. "F(" })
    assert.is_true(#e < 400, #e .. " characters")
    assert.matches("F%(1%)F%(' %(line 1 of productions%): unbalanced parentheses: '%(' "
                   .. "without '%)' at character 800008", e)
    local m = lsys.lsystem { axiom = "A", productions = "A --> " .. big .. "F(x)" }
    e = errof(m.derive, m, 1)
    assert.is_true(#e < 500, #e .. " characters")
    assert.matches("unknown name 'x'", e, 1, true)
  end)

  it("quotes short text whole", function ()
    local q = require("lsys.warning").quote
    assert.equal("A --> B", q("A --> B", 3))
    local s = H.rep("a", 1000) .. "X" .. H.rep("b", 1000)
    local shown = q(s, 1001)
    assert.truthy(shown:find("aaaXbbb", 1, true), shown)
    assert.matches("^a+%.%.%.a+Xb+%.%.%.b+$", shown)
    assert.is_true(#shown < 240)
  end)
end)

describe("a model that fails leaves no module names behind", function ()
  it("lets later models use names after one failed with too many", function ()
    local names = {}
    for i = 1, 2100 do names[#names + 1] = "m" .. i end
    local list = table.concat(names, " ")
    for _ = 1, 3 do       -- each attempt fails the same way; none poisons the state
      local e = errof(lsys.lsystem, { modules = list, axiom = list })
      assert.matches("too many module names (limit is 2047)", e, 1, true)
      local m = lsys.lsystem { axiom = "Q", productions = "Q --> R[S]T" }
      assert.equal("R[S]T", tostring(m:derive(1)))
    end
    -- names of a model that was made stay: its strings still read them
    local ok = lsys.lsystem { modules = "leaf stem", axiom = "leaf stem" }
    local s = ok:derive(0)
    errof(lsys.lsystem, { modules = list, axiom = list })
    assert.equal("leaf", (s:module(1)))
    assert.equal("stem", (s:module(2)))
    assert.equal(2, #ok:derive(0))
  end)
end)

describe("a rule that derives its own model", function ()
  it("gets one clear message for its own model", function ()
    local m
    m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
      m:derive(1)
      return lsys.produce("B")
    end } } }
    local e = errof(m.derive, m, 1)
    assert.matches("rule 1 'A' %(entry 1 of productions%), module 1: .*a rule called derive on "
                   .. "the model it belongs to$", e)
    assert.equal(1, select(2, e:gsub("rule 1 'A'", "")))
  end)

  it("gets one clear message, not a C stack overflow, for fresh copies of itself", function ()
    local function make ()
      local m = lsys.lsystem { axiom = "A", productions = { { "A", function ()
        make():derive(1)
        return lsys.produce("B")
      end } } }
      return m
    end
    local e = errof(function () return make():derive(1) end)
    assert.matches("derivations nested 32 deep: a rule function derives a model whose rules "
                   .. "derive again", e, 1, true)
    assert.is_nil(e:find("rule 1 'A'", 1, true))      -- said once, not 32 times
    assert.is_nil(e:find("stack overflow", 1, true))
    -- and the state is fine afterwards
    assert.equal("B", tostring(lsys.lsystem { axiom = "A", productions = "A --> B" }:derive(1)))
  end)
end)

describe("mistakes that used to pass in silence", function ()
  local function warnings (f)
    local warning = require "lsys.warning"
    local saved, got = warning.warn, {}
    warning.warn = function (msg) got[#got + 1] = msg end
    local ok, err = pcall(f)
    warning.warn = saved
    assert(ok, err)
    return got
  end

  it("warns about a rule whose parameter count no module has", function ()
    local got = warnings(function ()
      lsys.lsystem { axiom = "A(1)B", productions = "A(x) --> A(x+1)B\nB(x,y) --> C\n"
                     .. "A(x) < B(y) --> D\nB --> E" }
    end)
    assert.equal(2, #got)
    assert.matches("rule 2 'B(x,y) --> C' (line 2 of productions): no 'B' with 2 parameters in "
                   .. "the axiom or a successor of a rule that can apply (every 'B' there has "
                   .. "0): the rule never applies", got[1], 1, true)
    assert.matches("rule 3 'A(x) < B(y) --> D'", got[2], 1, true)
    -- a rule whose own successor is the only one to make its count: it never starts; said
    -- once (lsys batch makes a job's model again for each job)
    got = warnings(function ()
      for _ = 1, 3 do lsys.lsystem { axiom = "A(1)", productions = "A(x,y) --> F A(x+1,y)" } end
    end)
    assert.equal(1, #got)
    assert.equal("rule 1 'A(x,y) --> F A(x+1,y)' (line 1 of productions): no 'A' with 2 "
                 .. "parameters in the axiom or a successor of a rule that can apply (every 'A' "
                 .. "there has 1): the rule never applies",
                 (got[1]:gsub("^lsys: tests/friction_spec%.lua:%d+: ", "")))
    -- nor when the rule that makes it never applies; a chain of rules that apply is fine
    got = warnings(function ()
      lsys.lsystem { axiom = "B", productions = "B --> A(1)\nX --> A(1,2)\nA(x,y) --> C\n"
                     .. "A(x) --> D(x,x)\nD(x,y) --> E(x)\nE(x) --> E(x+1)" }
    end)
    assert.equal(1, #got)
    assert.matches("rule 3 'A(x,y) --> C'", got[1], 1, true)
    -- the homomorphism's successors are not in the string: a production for a module only
    -- the homomorphism makes is quiet (vlab's Shedding has `+(a) --> +(a+DANG)` beside a
    -- homomorphism drawing `+`); a homomorphism rule sees the string and what it makes
    got = warnings(function ()
      lsys.lsystem { axiom = "K(1)", productions = "+(a) --> +(a+1)\nK(t) --> K(t+1)",
                     homomorphism = "K(t) --> [+f(t)]\nf(x,y) --> F" }
    end)
    assert.equal(1, #got)
    assert.matches("rule 4 'f(x,y) --> F' (line 2 of homomorphism): no 'f' with 2 parameters",
                   got[1], 1, true)
    -- end_each may return any string: then every successor counts, as it may be there
    got = warnings(function ()
      lsys.lsystem { axiom = "B", productions = "B --> A(1)\nX --> A(1,2)\nA(x,y) --> C\n"
                     .. "A(x,y,z) --> C", end_each = function () end }
    end)
    assert.equal(1, #got)
    assert.matches("rule 4 'A(x,y,z) --> C'", got[1], 1, true)
    assert.matches("(every 'A' there has 1 or 2)", got[1], 1, true)
    -- a rule function may produce anything: nothing is said
    assert.equal(0, #warnings(function ()
      lsys.lsystem { axiom = "A", productions = { "B(x) --> C",
                     { "A", function () return lsys.produce("B(1)") end } } }
    end))
  end)

  it("refuses use_group for a group the model does not have", function ()
    local m = lsys.lsystem { axiom = "A", productions = "A --> B",
                             groups = { [1] = "A --> C", [3] = "A --> D" } }
    assert.matches("use_group: the model has no group 7 (groups: 1, 3)", errof(m.use_group, m, 7),
                   1, true)
    m:use_group(3)
    assert.equal("D", tostring(m:derive(1)))
  end)

  it("refuses a negative line width and a tropism without a direction", function ()
    assert.matches("'view.line_width' must be >= 0, got -3",
                   errof(lsys.lsystem, { axiom = "F", view = { line_width = -3 } }), 1, true)
    local m = lsys.lsystem { axiom = "F" }
    assert.matches("'view.line_width' must be >= 0, got -3",
                   errof(lsys.render, m, { line_width = -3 }), 1, true)
    assert.matches("'view.tropisms[1].vector' is {0, 0, 0}: a tropism needs a direction",
                   errof(lsys.lsystem, { axiom = "F", view = { tropisms = {
                     { vector = { 0, 0, 0 }, elasticity = 0.2 } } } }), 1, true)
  end)

  it("refuses a negative contour; an undefined texture warns and draws untextured (cpfg)",
     function ()
    local m = lsys.lsystem { axiom = "F@#(-1)F" }
    assert.matches("module 2 '@#': contour -1 is not defined", errof(m.interpret, m), 1, true)
    local dir = H.tmpdir()
    H.write(dir .. "/w.lua", 'local lsys = require "lsys"\n'
      .. 'local sc = lsys.lsystem { axiom = "F@Tx(-2)F@Tx(3)F" }:interpret()\n'
      .. 'print(sc.nlines)\n')
    local out, code = H.sh(H.BIN .. " " .. dir .. "/w.lua")
    H.rmdir(dir)
    assert.equal(0, code, out)
    assert.equal("Lua warning: lsys: module 2 '@Tx': texture -2 is not defined (the view has "
                 .. "0; view.textures); untextured from there, as in cpfg\n3\n", out)
  end)

  it("refuses positions that overflow instead of drawing nothing", function ()
    local m = lsys.lsystem { axiom = "F(1e308)F(1e308)" }
    assert.matches("module 2 'F': the position is no longer finite after a move of 1e+308",
                   errof(m.interpret, m), 1, true)
  end)

  it("writes PNG only under a PNG name", function ()
    local dir = H.tmpdir()
    local m = lsys.lsystem { axiom = "F" }
    assert.matches("lsys.render: '" .. dir .. "/x.jpg': unknown picture format '.jpg': lsys "
                   .. "writes .png, .svg, .eps or .pdf", errof(lsys.render, m,
                   { out = dir .. "/x.jpg" }), 1, true)
    assert.is_nil(io.open(dir .. "/x.jpg"))
    lsys.render(m, { out = dir .. "/x.PNG", width = 16, height = 16 })
    assert.truthy(io.open(dir .. "/x.PNG"))
    H.rmdir(dir)
  end)

  it("warns about a polygon that is never closed", function ()
    local dir = H.tmpdir()
    H.write(dir .. "/open.lua", 'local lsys = require "lsys"\n'
      .. 'lsys.lsystem { axiom = "F{.f.+f.F" }:interpret()\n')
    local out, code = H.sh(H.BIN .. " " .. dir .. "/open.lua")
    H.rmdir(dir)
    assert.equal(0, code, out)
    assert.matches("lsys: the polygon '{' of module 2 is never closed with '}': it is not drawn",
                   out, 1, true)
  end)
end)

describe("changing a colour", function ()
  local m = lsys.lsystem { axiom = ";(1)F;(2)F", view = { line_width = 5 } }
  local function px (x, o)
    o = o or {}
    o.width, o.height = 32, 32
    return lsys.render(x, o)
  end

  it("renders with the palette given to lsys.render", function ()
    local plain, blue = px(m), px(m, { palette = { [2] = "#3050ff" } })
    assert.not_equal(plain, blue)
    assert.equal(blue, px(m, { view = { palette = { [2] = "#3050ff" } } }))
    assert.equal(blue, px(m:interpret(nil, { palette = { [2] = "#3050ff" } })))
    local m2 = lsys.lsystem { axiom = ";(1)F;(2)F",
                              view = { line_width = 5, palette = { [2] = "#3050ff" } } }
    assert.equal(blue, px(m2))
    assert.equal(plain, px(m))                         -- the model's own view is unchanged
  end)

  it("changes only the entries a partial palette names", function ()
    local full = {}
    for i = 0, #require("lsys.view").PALETTE do full[i] = require("lsys.view").PALETTE[i] end
    full[2] = "#3050ff"
    assert.equal(px(m, { palette = full }), px(m, { palette = { [2] = "#3050ff" } }))
    -- over a model's own palette: its entries stay, the named one changes
    local own = lsys.lsystem { axiom = ";(1)F;(2)F", view = { line_width = 5,
                               palette = { [1] = "#ff0000", [2] = "#00ff00" } } }
    assert.equal(px(own, { palette = { [2] = "#3050ff" } }),
                 px(lsys.lsystem { axiom = ";(1)F;(2)F", view = { line_width = 5,
                    palette = { [1] = "#ff0000", [2] = "#3050ff" } } }))
  end)

  it("says why a palette cannot change a scene already drawn", function ()
    assert.matches("lsys.render: 'palette' changes how the turtle draws: render the model, or "
                   .. "interpret it with the option", errof(lsys.render, m:interpret(),
                   { palette = { [2] = "#ff0000" } }), 1, true)
    assert.matches("'view.palette': entry 13 is missing (the default palette has 0 to 12)",
                   errof(lsys.render, m, { palette = { [20] = "#ff0000" } }), 1, true)
  end)
end)

describe("a palette of one colour", function ()
  it("draws every colour index in it, entry 0 included (regression: fig27's petals)", function ()
    local m = lsys.lsystem { axiom = ";(100) F ;(0) F ;(3) F",
      view = { palette = { "#e08cb2" }, line_style = "cylinder", line_width = 0.3,
               background = { 1, 1, 1 } } }
    local px, w, h = lsys.render(m, { width = 64, height = 64, supersample = 1 })
    local pink, black = 0, 0          -- pink even in shade (red > 60); entry 0 was near black
    for i = 0, w * h - 1 do
      local r, g, b = px:byte(4 * i + 1, 4 * i + 3)
      if r > 60 and r > g + 15 and b > g then pink = pink + 1 end
      if r < 50 and g < 50 and b < 50 then black = black + 1 end
    end
    assert.is_true(pink > 50, pink .. " pink pixels")
    assert.equal(0, black)
  end)
end)

describe("files next to the model", function ()
  it("are found from the model file's folder, from anywhere", function ()
    local dir = H.tmpdir()
    os.execute("mkdir -p '" .. dir .. "/plants' '" .. dir .. "/elsewhere'")
    H.write(dir .. "/plants/leaf.con", "4 2 closed\n0 0\n1 0\n1 1\n0 1\n")
    H.write(dir .. "/plants/leafy.lua", 'local lsys = require "lsys"\n'
      .. 'return lsys.lsystem { axiom = "@#(1)F", view = { line_style = "cylinder",\n'
      .. '  contours = { [1] = "leaf.con" } } }\n')
    local bin = H.ABSBIN
    local out, code = H.sh("cd '" .. dir .. "/elsewhere' && " .. bin
                           .. " render ../plants/leafy.lua -o leafy.png --size 32x32")
    assert.equal(0, code, out)
    assert.truthy(io.open(dir .. "/elsewhere/leafy.png"))
    os.remove(dir .. "/plants/leaf.con")
    out, code = H.sh("cd '" .. dir .. "/elsewhere' && " .. bin
                     .. " derive ../plants/leafy.lua")
    assert.equal(1, code)
    assert.matches("view.contours[1]: cannot open '../plants/leaf.con': No such file or "
                   .. "directory (looked for in '../plants' (view.dir: the model's folder unless "
                   .. "set), then in the current folder)", out, 1, true)
    H.rmdir(dir)
  end)
end)

describe("lsys export --lines tubes", function ()
  it("writes line-style segments as tubes, no GL lines", function ()
    local glb = require "tests.glb"
    local dir = H.tmpdir()
    local function counts (extra)
      local out, code = H.sh(H.BIN .. " export examples/abop/fig1_24c.lua --steps 3 -o "
                             .. dir .. "/x.glb" .. extra)
      assert.equal(0, code, out)
      local doc, bin = glb.read(dir .. "/x.glb")
      local tris, lines = 0, 0
      for _, pr in ipairs(glb.primitives(doc, bin)) do
        if pr.mode == 4 then tris = tris + pr.triangles
        elseif pr.mode == 1 then lines = lines + pr.segments end
      end
      return tris, lines, out
    end
    local t0, l0 = counts("")
    assert.equal(0, t0)
    assert.equal(512, l0)
    local t1, l1, out = counts(" --lines tubes")
    assert.equal(0, l1)
    assert.is_true(t1 >= 512 * 2 * 8, tostring(t1))      -- at least a band of 8 sides each
    -- the message gives what the file holds, not the scene's 0 triangles
    assert.equal(string.format("wrote %s/x.glb (9792 vertices, %d triangles, 0 lines; 512 "
                               .. "lines as tubes)\n", dir, t1), out)
    assert.equal(11264, t1)
    local msg, code = H.sh(H.BIN .. " export examples/abop/fig1_24c.lua -o " .. dir
                           .. "/x.glb --lines pipes")
    assert.equal(2, code)
    assert.matches("--lines expects 'lines' or 'tubes', got 'pipes'", msg, 1, true)
    H.rmdir(dir)
  end)
end)

describe("--set and --view say what is wrong with them", function ()
  it("refuses a --set name the model has no variable of, as lsys batch does", function ()
    local out, code = H.sh(H.BIN .. " derive --steps 1 --stats --set Q=3 examples/default.lua")
    assert.equal(2, code)
    assert.equal("lsys: derive: --set Q: the model has no variable Q (the model's variables: "
                 .. "a, d1, d2, lr, vr)\nRun 'lsys derive --help' for its options.\n", out)
    -- a near name is suggested instead of the list
    local dir = H.tmpdir()
    out, code = H.sh(H.BIN .. " render --steps 1 --set Lr=3 -o " .. dir .. "/x.png "
                     .. "examples/default.lua")
    assert.is_nil(io.open(dir .. "/x.png"))            -- no picture
    H.rmdir(dir)
    assert.equal(2, code)
    assert.equal("lsys: render: --set Lr: the model has no variable Lr (did you mean 'lr'?)\n"
                 .. "Run 'lsys render --help' for its options.\n", out)
    out, code = H.sh(H.BIN .. " derive --steps 1 --stats --set a=30 examples/default.lua")
    assert.equal(0, code)
    assert.not_matches("no variable", out, 1, true)
  end)

  it("refuses a --set value that is not a finite number, naming --set", function ()
    for _, v in ipairs { "abc", "nan", "inf", "-inf", "" } do
      local out, code = H.sh(H.BIN .. " derive --set a=" .. v .. " examples/default.lua")
      assert.equal(2, code)
      assert.matches("lsys: derive: --set a: the value must be a finite number, got '" .. v
                     .. "'", out, 1, true)
    end
  end)

  it("blames a wrong --view on the option, not on the model file", function ()
    local cases = {
      { "zoom=3", "--view zoom=3: unknown view option 'zoom' (known: angle, " },
      { "angel=30", "--view angel=30: unknown view option 'angel' (did you mean 'angle'?)\n" },
      { "line_width=abc", "--view line_width=abc: 'line_width' must be a finite number" },
      { "line_width=-3", "--view line_width=-3: 'line_width' must be >= 0, got -3" },
      { "line_style=tube", "--view line_style=tube: 'line_style' must be \"line\", " },
    }
    for _, c in ipairs(cases) do
      local out, code = H.sh(H.BIN .. " render -o " .. os.tmpname() .. ".png --view " .. c[1]
                             .. " examples/default.lua")
      assert.equal(2, code)
      assert.matches("lsys: render: " .. c[2], out, 1, true)
      assert.not_matches("default.lua", out, 1, true)
    end
  end)
end)

describe("messages name the user's file or the public function", function ()
  -- what must never show in a message: lsys's own sources, its core's names, Lua's own
  -- complaints about lsys's variables, or a function Lua cannot name
  local INTERNAL = { "lua/lsys/", "lsys%.core", "'%?'", "%.c:%d", "attempt to", "for iterator" }
  local function internal (msg, user_code)
    for i = 1, user_code and 4 or #INTERNAL do    -- a user's code may attempt to index nil
      if msg:find(INTERNAL[i]) then return INTERNAL[i] end
    end
  end

  it("holds for every public function and method given bad arguments", function ()
    local function new ()
      local m = lsys.lsystem { axiom = "F(1)+F(2)", steps = 1, productions = "F(x) --> F(x+1)" }
      local s = m:derive()
      return m, s, m:interpret(s)
    end
    local m, s, sc = new()
    local targets = {}
    local function add (name, call, k)
      targets[#targets + 1] = { name, load("local new, lsys = ... return function (...) "
                                .. call .. k .. "(...) end", "=" .. name, "t")(new, lsys) }
    end
    -- not here: the window (show, wait, arrange), the global memory budget, deprecated names
    local skip = { show = true, wait = true, arrange = true, max_memory = true,
                   islstring = true, ismodel = true, isscene = true }
    for k, v in pairs(lsys) do
      if type(v) == "function" and not skip[k] then add("lsys." .. k, "return lsys.", k) end
    end
    -- and every function of the modules that the reference (docs/meta.lua) documents, but
    -- the window's (lsys.viewer, lsys.repl) and the deprecated names
    for line in io.lines("docs/meta.lua") do
      local mod, k = line:match("^function (lsys%.[%w_.]+)%.([%w_]+)%(")
      if mod and not mod:find("^lsys%.viewer") and not mod:find("^lsys%.repl")
         and k ~= "turtle" and k ~= "render" then
        add(mod .. "." .. k, "return " .. mod .. ".", k)
      end
    end
    add("lsys.grow.from_lstring", "return require('lsys.grow').", "from_lstring")
    for k in pairs(getmetatable(m).__index) do
      if not k:find("^_") then add("model:" .. k, "local o = new() return o:", k) end
    end
    for k in pairs(getmetatable(s).__index) do    -- (write: a path it is given, "x" or 5,
      if k ~= "write" then                        -- is a file: lstring_write_spec's errors)
        add("lstring:" .. k, "local _, o = new() return o:", k)
      end
    end
    for k in pairs(getmetatable(sc).__methods) do
      add("scene:" .. k, "local _, _, o = new() return o:", k)
    end
    table.sort(targets, function (a, b) return a[1] < b[1] end)
    local BAD = { true, 5, -1, 0.5, 1e300, math.huge, 0 / 0, "x", {}, { 1, 2 }, { x = 1 } }
    local bad, calls = {}, 0
    for _, t in ipairs(targets) do
      for pos = 1, 3 do
        for i = 0, #BAD do
          local args = {}
          for j = 1, pos - 1 do args[j] = 1 end
          args[pos] = BAD[i]                       -- i = 0: nil
          local ok, e = pcall(t[2], table.unpack(args, 1, pos))
          calls = calls + 1
          local p = not ok and internal(tostring(e))
          if p then bad[#bad + 1] = format("%s #%d %s: %s", t[1], pos, tostring(BAD[i]), e) end
        end
      end
    end
    assert.is_true(#targets > 40 and calls > 1000)
    assert.same({}, bad)
  end)

  it("names the public method for a module index out of range", function ()
    local sc = lsys.lsystem { axiom = "F+F" }:interpret()
    assert.matches("scene:turtle: no module 5 (the scene's Lstring has 3; 0 is the start)",
                   errof(sc.turtle, sc, 5), 1, true)
    assert.matches("derive: the options must be a table", errof(function ()
      lsys.lsystem { axiom = "F" }:derive(1, true) end), 1, true)
  end)

  it("holds for the command line, with the traceback kept for LSYS_DEBUG=1", function ()
    local dir = H.tmpdir()
    H.write(dir .. "/bad.lua", "local lsys = require 'lsys'\nreturn lsys.lsystem { axiom = "
            .. "'A', productions = { { 'A', function () return 1 + nil end } } }\n")
    H.write(dir .. "/none.lua", "return 42\n")
    H.write(dir .. "/syntax.lua", "return lsys.lsystem {\n")
    local runs = {
      { "derive --steps 1e8", "--steps 1e8 is more than" },
      { "render -o x.jpg", "the output must be a .png, .svg, .eps or .pdf file" },
      { "derive no/such/model.lua", "no/such/model.lua" },
      { "render --size 0x0", "--size expects WxH" },
      { "derive --steps 1 " .. dir .. "/bad.lua", "bad.lua:2:" },
      { "derive " .. dir .. "/none.lua", "none.lua" },
      { "derive " .. dir .. "/syntax.lua", "syntax.lua:2:" },
      { "export " .. dir .. "/bad.lua", "-o OUT.obj" },
    }
    for _, r in ipairs(runs) do
      local out, code = H.sh("cd " .. dir .. " && " .. H.ABSBIN .. " " .. r[1])
      assert.is_true(code == 1 or code == 2, r[1])
      assert.matches(r[2], out, 1, true)
      assert.is_nil(internal(out, true), r[1] .. ": " .. out)
      assert.not_matches("traceback", out, 1, true)
    end
    local out = H.sh("cd " .. dir .. " && LSYS_DEBUG=1 " .. H.ABSBIN .. " derive --steps 1 "
                     .. dir .. "/bad.lua")
    assert.matches("stack traceback:", out, 1, true)
    H.rmdir(dir)
  end)
end)

describe("memory a user did not ask for", function ()
  it("holds a long axiom once, as its text, until it derives", function ()
    -- 400 000 modules, 2 MB of text: the model keeps the text and the C template, no table
    -- a module (the expressions are kept once each: 'x' and 'x*x+1')
    local text = string.rep("F(x)G(x*x+1)+", 100000) .. "A"
    collectgarbage()
    local before = collectgarbage("count")
    local m = lsys.lsystem { axiom = text, env = { x = 2 }, productions = "A --> B" }
    collectgarbage()
    local kept = collectgarbage("count") - before
    assert.is_true(kept < 64, kept .. " kB")
    local s = m:derive(1)
    assert.equal(300001, #s)
    assert.equal("F(2)G(5)+B", tostring(s:sub(299998, 300001)))
  end)

  it("keeps no copy of a long successor's modules once the model is made", function ()
    collectgarbage()
    local before = collectgarbage("count")
    local m = lsys.lsystem { axiom = "A", productions = "A --> " .. string.rep("F+", 50000) }
    collectgarbage()
    local kept = collectgarbage("count") - before
    assert.equal(100000, #m:derive(1))
    assert.is_true(kept < 2 * 1024, kept .. " kB")      -- was 11 MB: a table a module
  end)

  it("lsys view takes --last and --history, and checks them before opening a window", function ()
    local out, code = H.sh(H.BIN .. " view --history lots examples/default.lua")
    assert.equal(2, code)
    assert.matches("lsys: view: --history: 'lots' is not a size", out, 1, true)
    out, code = H.sh(H.BIN .. " view --last --step 2 examples/default.lua")
    assert.equal(2, code)
    assert.matches("--last and --step exclude each other", out, 1, true)
    out = H.sh(H.BIN .. " view --help")
    assert.matches("--history SIZE       the memory the kept steps may take (default 256M",
                   out, 1, true)
  end)

  it("refuses a picture larger than the memory budget before drawing it", function ()
    local out, code = H.sh("LSYS_MAX_MEMORY=100M " .. H.BIN .. " render --size 16384x16384 -o "
                           .. os.tmpname() .. ".png examples/abop/fig1_24a.lua")
    assert.equal(1, code)
    assert.matches("lsys: a 16384x16384 picture needs 3.0 GiB, more than max_memory "
                   .. "(100 MiB)", out, 1, true)
  end)
end)
