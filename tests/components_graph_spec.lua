-- The p-graph as Graphviz DOT (lsys.components.graph, `lsys components graph`):
-- the DOT text of Lintermann and Deussen 1999's fig. 2 graph, link styles of their fig. 3,
-- recursions doubled and ended by a dashed copy, flags on the links, escaping, errors,
-- rendering with Graphviz's dot and the command line. Prototypes are plain tables of the
-- fixed shape { kind, name, recursion, params, links = { { type, to, flags } } }.
local H = require "tests.helper"
local graph = require "lsys.components.graph"

local function proto (kind, name, recursion, params)
  return { kind = kind, name = name, recursion = recursion, params = params or {}, links = {} }
end
local function link (from, type, to, flags)
  from.links[#from.links + 1] = { type = type, to = to, flags = flags }
  return from
end

-- Fig. 2: A the root (Simple), B a stem (Horn), C a Hydra of 3, D a twig part (Horn) that
-- recurses 3 deep through a link to itself.
local function fig2 ()
  local A, B = proto("simple", "A"), proto("horn", "B")
  local C, D = proto("hydra", "C", nil, { n = 3 }), proto("horn", "D", 3, { length = { 1, 0.5 } })
  link(A, "child", B)
  link(B, "child", C)
  link(C, "child", D)
  link(D, "child", D)
  return A, B, C, D
end

local HEAD = [[
digraph "p-graph" {
  graph [rankdir=TB, ordering=out];
  node [shape=ellipse, fontname="Helvetica", fontsize=11];
  edge [dir=none, fontname="Helvetica", fontsize=10];
  camera [label="camera", shape=box];
]]

local FIG2 = HEAD .. [[
  n1 [label="A\nsimple"];
  n2 [label="B\nhorn"];
  n3 [label="C\nhydra", shape=hexagon];
  n4 [label="D\nhorn\nrecursion 3"];
  n4r1 [label="D", style=dashed];
  camera -> n1;
  n1 -> n2;
  n2 -> n3;
  n3 -> n4;
  n4 -> n4r1 [color="black:white:black"];
}
]]

local function has_dot ()
  return os.execute("command -v dot >/dev/null 2>&1") == true
end

local function files_in (dir)
  local p = io.popen("ls -A '" .. dir .. "'")
  local names = {}
  for l in p:lines() do names[#names + 1] = l end
  p:close()
  table.sort(names)
  return names
end

describe("graph.dot", function()
  it("writes fig. 2's p-graph: camera, four components, D's recursion doubled", function()
    assert.equal(FIG2, graph.dot((fig2())))
  end)

  it("shows parameters when asked: all with a short form, or the named ones", function()
    local A, _, C = fig2()
    C.params.fn = function () return 1 end
    C.params.table = { a = 1 }
    C.params.big = { 1, 2, 3, 4, 5, 6 }
    C.params.flag = true
    C.params.angle = 22.5
    C.params.what = "disc"
    local text = graph.dot(A, { params = true })
    assert.truthy(text:find('  n3 [label="C\\nhydra\\nangle = 22.5\\nbig = [1, 2, 3, 4, ...]\\n'
      .. 'flag = true\\nfn = f()\\nn = 3\\ntable = {...}\\n...", shape=hexagon];\n', 1, true), text)
    assert.truthy(text:find('  n4 [label="D\\nhorn\\nrecursion 3\\nlength = [1, 0.5]"];\n', 1,
      true))
    local text2 = graph.dot(A, { params = { "n", "what", "missing" } })
    assert.truthy(text2:find('  n3 [label="C\\nhydra\\nn = 3\\nwhat = disc", shape=hexagon];\n',
      1, true), text2)
    local text3 = graph.dot(A, { params = true, max_params = 2 })
    assert.truthy(text3:find('label="C\\nhydra\\nangle = 22.5\\nbig = [1, 2, 3, 4, ...]\\n..."',
      1, true), text3)
    -- a range with a function of the value
    C.params = { scale = { 1, 0.2, f = function (v) return v end } }
    assert.truthy(graph.dot(A, { params = true }):find('scale = [1, 0.2] f()', 1, true))
  end)

  it("draws branch links bold, leaf links dashed, flag lists on the links", function()
    -- the rhododendron twig (fig. 5c): tiny twigs at iterations 2 and 13, leaves elsewhere,
    -- and a blossom leaf once after the twig's recursion
    local twig, tiny, leaf, blossom = proto("tree", "twig"), proto("tree", "tiny"),
                                     proto("leaf"), proto("leaf", "leaf")
    link(twig, "branch", tiny, { only = { 2, 13 } })
    link(twig, "branch", leaf, { except = { 2, 13 } })
    link(twig, "leaf", blossom)
    assert.equal(HEAD .. [[
  n1 [label="twig\ntree"];
  n2 [label="tiny\ntree"];
  n3 [label="leaf#1"];
  n4 [label="leaf"];
  camera -> n1;
  n1 -> n2 [penwidth=3, label="only 2, 13"];
  n1 -> n3 [penwidth=3, label="except 2, 13"];
  n1 -> n4 [style=dashed];
}
]], graph.dot(twig))
  end)

  it("reads flags in the form lsys.components keeps them, and draws its prototypes", function()
    local twig, tiny = proto("tree", "twig"), proto("tree", "tiny")
    local set = { [3] = true, [4] = true }
    twig.links[1] = { type = "branch", to = tiny,
                      flags = { mode = "except", list = { 3, 4 }, set = set } }
    assert.truthy(graph.dot(twig):find('  n1 -> n2 [penwidth=3, label="except 3, 4"];\n', 1, true))
    -- fig. 2 made with lsys.components gives the same text as the plain tables
    local C = require "lsys.components"
    local D = C.horn { name = "D", recursion = 3 }
    D:child(D)
    local A = C.simple { name = "A" }:child(C.horn { name = "B" }:child(
      C.hydra { name = "C", n = 3 }:child(D)))
    assert.equal(FIG2, graph.dot(A))
    local t = C.tree { name = "t", n = 20 }:branch(C.leaf {}, { only = { 2, 13 } })
    assert.truthy(graph.dot(t, { params = true }):find(
      '  n1 [label="t\\ntree\\nn = 20"];\n  n2 [label="leaf#1"];\n  camera -> n1;\n'
      .. '  n1 -> n2 [penwidth=3, label="only 2, 13"];\n', 1, true))
  end)

  it("doubles every link of a recursion and ends it at a dashed copy", function()
    -- P -> Q -> R -> Q (a recursion of two components), R -> S (leaf), P -> S (shared):
    -- P -> Q is outside the cycle, Q -> R and the back link R -> Q are inside it
    local P, Q, R, S = proto("tree", "P"), proto("tree", "Q", 4), proto("horn", nil, 4),
                       proto("leaf", "S")
    link(P, "branch", Q)
    link(Q, "branch", R)
    link(R, "child", Q)
    link(R, "leaf", S)
    link(P, "child", S)
    assert.equal(HEAD .. [[
  n1 [label="P\ntree"];
  n2 [label="Q\ntree\nrecursion 4"];
  n3 [label="horn#1\nrecursion 4"];
  n2r1 [label="Q", style=dashed];
  n4 [label="S\nleaf"];
  camera -> n1;
  n1 -> n2 [penwidth=3];
  n1 -> n4;
  n2 -> n3 [penwidth=3, color="black:white:black"];
  n3 -> n2r1 [color="black:white:black"];
  n3 -> n4 [style=dashed];
}
]], graph.dot(P))
    -- two links back to the same component make two copies
    link(R, "branch", Q)
    local text = graph.dot(P)
    assert.truthy(text:find('  n2r2 [label="Q", style=dashed];\n', 1, true), text)
    assert.truthy(text:find('  n3 -> n2r2 [penwidth=3, color="black:white:black"];\n', 1, true))
  end)

  it("numbers unnamed components per kind in depth-first order, the same bytes every time",
     function()
    local root = proto("phiball")
    local a, b, c = proto("leaf"), proto("hydra"), proto("leaf")
    link(root, "child", b)
    link(root, "child", a)
    link(b, "child", c)
    local text = graph.dot(root)
    assert.truthy(text:find('n1 [label="phiball#1", shape=hexagon];\n  n2 [label="hydra#1", '
      .. 'shape=hexagon];\n  n3 [label="leaf#1"];\n  n4 [label="leaf#2"];', 1, true), text)
    assert.truthy(text:find("n1 -> n2;\n  n1 -> n4;\n  n2 -> n3;", 1, true))
    for _ = 1, 5 do assert.equal(text, graph.dot(root)) end
  end)

  it("escapes names: quotes, backslashes, newlines, control bytes, invalid UTF-8", function()
    local root = proto("simple", 'say "hi" \\N')
    link(root, "child", proto("leaf", "two\nlines\tand\0nul"))
    link(root, "child", proto("leaf", "bad \xff\xc3 byte, ok \xc3\xa9"))
    link(root, "child", proto("leaf", string.rep("x", 70)))
    local text = graph.dot(root)
    assert.truthy(text:find('  n1 [label="say \\"hi\\" \\\\N\\nsimple"];\n', 1, true), text)
    assert.truthy(text:find('  n2 [label="two\\nlines and nul\\nleaf"];\n', 1, true), text)
    assert.truthy(text:find('  n3 [label="bad ?? byte, ok \xc3\xa9\\nleaf"];\n', 1, true), text)
    assert.truthy(text:find('  n4 [label="' .. string.rep("x", 60) .. '...\\nleaf"];\n', 1,
      true), text)
    if not has_dot() then return end
    -- Graphviz reads it back: the quoted name is one label, shown as written
    local dir = H.tmpdir()
    graph.render(root, dir .. "/g.svg")
    local svg = H.read(dir .. "/g.svg")
    assert.truthy(svg:find("say &quot;hi&quot; \\N", 1, true), svg)
    H.rmdir(dir)
  end)

  it("stops with a clear error on what is not a prototype, naming the path", function()
    assert.error_contains(function () graph.dot(42) end,
      "graph.dot: the root is a number, not a prototype")
    assert.error_contains(function () graph.dot({ links = {} }) end,
      "graph.dot: the root is not a prototype (no kind")
    local A, B, C = fig2()
    C.links[2] = { type = "child", to = 7 }
    assert.error_contains(function () graph.dot(A) end,
      "graph.dot: A/B/C: links[2].to is a number, not a prototype")
    C.links[2] = { type = "child", to = { kind = "leaf", links = "none" } }
    assert.error_contains(function () graph.dot(A) end,
      "A/B/C: links[2].to is not a prototype (its links are a string, not a list)")
    C.links[2] = { type = "kid", to = B }
    assert.error_contains(function () graph.dot(A) end,
      "A/B/C: links[2]: type is 'kid', not child, branch or leaf")
    C.links[2] = "B"
    assert.error_contains(function () graph.dot(A) end, "A/B/C: links[2] is a string, not a link")
    C.links[2] = { type = "child", to = proto("leaf"), flags = { only = { 2, "x" } } }
    assert.error_contains(function () graph.dot(A) end,
      "A/B/C: links[2].flags only[2] is x, not an iteration number")
    C.links[2] = { type = "child", to = proto("leaf"), flags = { onyl = { 2 } } }
    assert.error_contains(function () graph.dot(A) end, "links[2].flags has the key 'onyl'")
    C.links[2] = { type = "child", to = proto("leaf", nil, 0) }
    assert.error_contains(function () graph.dot(A) end,
      "links[2].to has recursion 0, not a whole number of 1 or more")
    C.links[2] = { type = "child", to = proto("leaf", 5) }
    assert.error_contains(function () graph.dot(A) end,
      "links[2].to has a name that is a number, not a string")
    C.links[2] = nil
    assert.error_contains(function () graph.dot(A, { param = true }) end,
      "graph.dot: unknown option 'param'")
    assert.error_contains(function () graph.dot(A, { params = 1 }) end,
      "option 'params' must be true or a list of parameter names")
  end)
end)

describe("graph.render", function()
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("writes .dot and .gv as text, whole, leaving no partial file", function()
    local A = fig2()
    assert.equal(dir .. "/g.dot", graph.render(A, dir .. "/g.dot"))
    assert.equal(FIG2, H.read(dir .. "/g.dot"))
    graph.render(A, dir .. "/g.GV")
    assert.equal(FIG2, H.read(dir .. "/g.GV"))
    assert.same({ "g.GV", "g.dot" }, files_in(dir))
    assert.error_contains(function () graph.render(A, dir .. "/g.jpg") end,
      "graph.render: cannot write '" .. dir .. "/g.jpg': the output must be .dot, .gv, .png, "
      .. ".svg or .pdf")
    assert.error_contains(function () graph.render(A, dir .. "/no/such/g.dot") end,
      "graph.render: ")
    assert.same({ "g.GV", "g.dot" }, files_in(dir))
  end)

  it("renders a PNG with Graphviz's dot", function()
    if not has_dot() then pending("Graphviz's dot is not installed") return end
    local A = fig2()
    graph.render(A, dir .. "/g.png", { params = true })
    local png = H.read(dir .. "/g.png")
    assert.truthy(#png > 100)
    assert.equal("\137PNG\r\n\26\n", png:sub(1, 8))
    assert.same({ "g.png" }, files_in(dir))
    graph.render(A, dir .. "/g.svg")
    assert.truthy(H.read(dir .. "/g.svg"):find("<svg", 1, true))
  end)

  it("quotes paths for the shell: quotes, spaces and $( ) stay file names", function()
    assert.equal("'a b'", graph.quote("a b"))
    assert.equal("'it'\\''s'", graph.quote("it's"))
    assert.error_contains(function () graph.quote("a\nb") end, "control characters")
    if not has_dot() then pending("Graphviz's dot is not installed") return end
    local name = "it's $(touch pwned) `x`.svg"
    graph.render((fig2()), dir .. "/" .. name)
    assert.same({ name }, files_in(dir))
    assert.is_nil(io.open("pwned"))
  end)

  it("says how to get dot when it is missing, and writes nothing", function()
    assert.error_contains(function ()
      graph.render((fig2()), dir .. "/g.png", { dot = dir .. "/no-such-dot" })
    end, "graph.render: Graphviz's dot is not installed (Debian: apt-get install graphviz); "
      .. "write .dot instead")
    assert.same({}, files_in(dir))
  end)
end)

describe("lsys components graph", function()
  local MODEL = [[
local function proto (kind, name, recursion, params)
  return { kind = kind, name = name, recursion = recursion, params = params or {}, links = {} }
end
local A, B = proto("simple", "A"), proto("horn", "B")
local C, D = proto("hydra", "C", nil, { n = 3 }), proto("horn", "D", 3, { length = { 1, 0.5 } })
A.links[1] = { type = "child", to = B }
B.links[1] = { type = "child", to = C }
C.links[1] = { type = "child", to = D }
D.links[1] = { type = "child", to = D }
return A
]]
  local dir
  before_each(function () dir = H.tmpdir() end)
  after_each(function () H.rmdir(dir) end)

  it("writes the DOT text and a PNG of a model file's graph", function()
    H.write(dir .. "/fig2.lua", MODEL)
    local out, code = H.sh(("'%s' components graph '%s/fig2.lua' -o '%s/g.dot'"):format(H.BIN,
      dir, dir))
    assert.equal(0, code, out)
    assert.equal("wrote " .. dir .. "/g.dot\n", out)
    assert.equal(FIG2, H.read(dir .. "/g.dot"))
    out, code = H.sh(("'%s' components graph '%s/fig2.lua' --params -o '%s/p.dot'"):format(H.BIN,
      dir, dir))
    assert.equal(0, code, out)
    assert.truthy(H.read(dir .. "/p.dot"):find('n3 [label="C\\nhydra\\nn = 3"', 1, true))
    if not has_dot() then pending("Graphviz's dot is not installed") return end
    -- the default output: the model's name with -graph.png, in the current directory
    out, code = H.sh(("cd '%s' && '%s' components graph fig2.lua"):format(dir,
      H.ABSBIN))
    assert.equal(0, code, out)
    assert.equal("wrote fig2-graph.png\n", out)
    assert.equal("\137PNG\r\n\26\n", H.read(dir .. "/fig2-graph.png"):sub(1, 8))
  end)

  it("names the file that does not return a graph, and the item that is wrong", function()
    H.write(dir .. "/none.lua", "return 42\n")
    local out, code = H.sh(("'%s' components graph '%s/none.lua' -o '%s/g.dot'"):format(H.BIN,
      dir, dir))
    assert.equal(1, code)
    assert.equal("lsys: " .. dir .. "/none.lua returned number, not a component graph (end the "
      .. "file with `return` and the root prototype, e.g. `return plant`)\n", out)
    H.write(dir .. "/bad.lua", MODEL:gsub("to = D }\nreturn", "to = 'D' }\nreturn"))
    out, code = H.sh(("'%s' components graph '%s/bad.lua' -o '%s/g.dot'"):format(H.BIN, dir, dir))
    assert.equal(1, code)
    assert.equal("lsys: " .. dir .. "/bad.lua: A/B/C/D: links[1].to is a string, not a "
      .. "prototype\n", out)
    assert.same({ "bad.lua", "none.lua" }, files_in(dir))
  end)

  it("reports usage errors with exit status 2, and has help", function()
    local P = "lsys: components: "
    for _, c in ipairs {
      { "components", P .. "a subcommand is required (graph)" },
      { "components draw x.lua", P .. "unknown subcommand 'draw' (known: graph)" },
      { "components graph", P .. "graph: a MODEL is required" },
      { "components graph a.lua b.lua", P .. "unexpected argument 'b.lua'" },
      { "components graph a.lua -o g.jpg",
        P .. "graph: the output must be a .png, .svg, .pdf or .dot file, got 'g.jpg'" },
      { "components graph a.lua --bogus", P .. "unknown option '--bogus'" },
    } do
      local out, code = H.sh(("'%s' %s"):format(H.BIN, c[1]))
      assert.equal(2, code, c[1] .. ": " .. out)
      assert.equal(c[2] .. "\nRun 'lsys components --help' for its options.\n", out)
    end
    local out, code = H.sh(("'%s' help components"):format(H.BIN))
    assert.equal(0, code)
    assert.truthy(out:find("usage: lsys components graph MODEL [-o OUT] [--params]", 1, true))
    assert.equal(out, (H.sh(("'%s' components --help"):format(H.BIN))))
    assert.truthy(H.sh(("'%s' --help"):format(H.BIN)):find("lsys components graph MODEL -o OUT",
      1, true))
  end)
end)
