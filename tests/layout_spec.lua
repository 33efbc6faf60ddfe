-- The shape of the source tree, checked so that it stays that way:
--   * layers: csrc/core includes only the core, csrc/gl the core and itself, csrc/lua the
--     three; a forbidden system header is a compile error (cmake/forbid/);
--   * the Lua modules' layers (LUA_LAYERS): a module requires only its own layer and those
--     below; nothing but init.lua requires "lsys", and init.lua only gathers; a require
--     inside a function only loads an optional dependency (LUA_LAZY);
--   * no include cycle among the C modules and no require cycle among the Lua modules;
--   * no Lua module reads the user values of the bindings' objects (debug.getuservalue):
--     the bindings give what the Lua side needs as functions and methods;
--   * no file in csrc/ over 1000 lines and no C function over 120 lines, except the
--     dispatch switches listed in DISPATCH; the same budget for lua/, except what
--     LUA_LONG_FILES and LUA_LONG_FUNCTIONS list (lists that only shrink).
local H = require "tests.helper"
local format = string.format

-- Functions allowed past 120 lines: a switch that reads as a table, one case per command.
local DISPATCH = {
}

local function lines (path)
  local n = 0
  for _ in io.lines(path) do n = n + 1 end
  return n
end

local function ls (pattern)
  local out = {}
  local p = io.popen("ls " .. pattern .. " 2>/dev/null")
  for f in p:lines() do out[#out + 1] = f end
  p:close()
  table.sort(out)
  return out
end

local function layer (path) return path:match("^csrc/(%w+)/") end

-- Comments, strings and character literals blanked out (newlines kept).
local function strip (src)
  local out, i, n = {}, 1, #src
  while i <= n do
    local c, d = src:sub(i, i), src:sub(i, i + 1)
    if d == "/*" then
      local j = src:find("*/", i + 2, true) or n
      out[#out + 1] = (src:sub(i, j + 1):gsub("[^\n]", " ")); i = j + 2
    elseif d == "//" then
      i = src:find("\n", i, true) or n + 1
    elseif c == '"' or c == "'" then
      local j = i + 1
      while j <= n and src:sub(j, j) ~= c do
        if src:sub(j, j) == "\\" then j = j + 1 end
        j = j + 1
      end
      out[#out + 1] = c .. c; i = j + 1
    else
      out[#out + 1] = c; i = i + 1
    end
  end
  return table.concat(out)
end

-- The functions of a C file longer than 'max' lines: { {name, lines}, ... }.
local function long_functions (path, max)
  local src = strip(io.open(path):read("a"))
  local found, depth, line, head, start, name = {}, 0, 1, {}, nil, nil
  for i = 1, #src do
    local c = src:sub(i, i)
    if c == "\n" then line = line + 1 end
    if c == "{" then
      local h = table.concat(head)
      if depth == 0 and h:find("%)%s*$") and not h:find("=%s*$") then
        start, name = line, h:match("([%w_]+)%s*%b()%s*$") or "?"
      end
      depth, head = depth + 1, {}
    elseif c == "}" then
      depth = depth - 1
      if depth == 0 then
        if start and line - start + 1 > max then found[#found + 1] = { name, line - start + 1 } end
        start, head = nil, {}
      end
    elseif depth == 0 then
      if c == ";" then head = {} else head[#head + 1] = c end
    end
  end
  return found
end

-- A cycle in 'graph' (node -> list of nodes) as "a -> b -> a", or nil.
local function cycle (graph)
  local state, stack = {}, {}
  local function visit (n)
    state[n] = 1; stack[#stack + 1] = n
    for _, m in ipairs(graph[n] or {}) do
      if state[m] == 1 then
        local i = #stack
        while stack[i] ~= m do i = i - 1 end
        local path = { table.unpack(stack, i) }
        path[#path + 1] = m
        return table.concat(path, " -> ")
      elseif state[m] == nil then
        local c = visit(m)
        if c then return c end
      end
    end
    state[n] = 2; stack[#stack] = nil
  end
  local nodes = {}
  for n in pairs(graph) do nodes[#nodes + 1] = n end
  table.sort(nodes)
  for _, n in ipairs(nodes) do
    if state[n] == nil then
      local c = visit(n)
      if c then return c end
    end
  end
end

-- The functions a header declares that are not static: { name, ... } (prototypes at the top
-- level; preprocessor lines, bodies and attributes left out).
local function declared (path)
  local src = strip(io.open(path):read("a"))
  local text = {}
  for line in (src .. "\n"):gmatch("([^\n]*)\n") do        -- #lines, with their \ continuations
    if text.cont or line:match("^%s*#") then
      text.cont = line:match("\\%s*$") ~= nil
    else
      text[#text + 1] = line
    end
  end
  local flat, depth = {}, 0
  for c in table.concat(text, "\n"):gmatch(".") do         -- the top level: bodies become ';'
    if c == "{" then
      if depth == 0 then flat[#flat + 1] = ";" end
      depth = depth + 1
    elseif c == "}" then depth = depth - 1
    elseif depth == 0 then flat[#flat + 1] = c end
  end
  local names = {}
  for stmt in table.concat(flat):gmatch("[^;]+") do
    stmt = stmt:gsub("__attribute__%s*%b()", ""):gsub("%s+", " "):gsub("^ ", ""):gsub(" $", "")
    local pre, name = stmt:match("^([^()]-)%f[%w_]([%w_]+) ?%b()$")
    if pre and pre ~= "" and not pre:find("%f[%w_]static%f[^%w_]") and
       not pre:find("%f[%w_]typedef%f[^%w_]") then
      names[#names + 1] = name
    end
  end
  return names
end

-- The functions a C file defines at the top level: { name = true }.
local function defined (path)
  local src = "\n" .. strip(io.open(path):read("a"))
  local names = {}
  for name in src:gmatch("\n[%a_][^\n;{}()]-%f[%w_]([%w_]+)%s*%b()%s*{") do names[name] = true end
  return names
end

-- The module of a C file: its name up to the first '_' (turtle_cyl.c is module turtle,
-- export_obj.c export, derive_impl.h derive).
local function module_of (path) return path:match("([^/_]+)[^/]*%.[ch]$") end

-- Public names of the core and the GL layer that start with neither lsys_<module>_ of the
-- file that defines them nor that of the header that declares them, each with the reason:
-- only where the name is a concept of several files. A key ending in '_' is a prefix.
local NAME_EXCEPTIONS = {
  lsys_seterror = "the error record (lsys_error, common.h) that every module of the core "
    .. "fills, in the one form of its messages",
  lsys_vseterror_at = "the error record, as lsys_seterror (with a place)",
  lsys_vseterror_line = "the error record, as lsys_seterror (with a file and line)",
  lsys_rules_ = "the rule set (lsys_rules, derive.h; derive_rules.c): what Lua calls "
    .. "lsys.Rules, used by the derivation, the contexts, the homomorphism and the bindings",
}

local function excepted (name)
  if NAME_EXCEPTIONS[name] then return true end
  for k in pairs(NAME_EXCEPTIONS) do
    if k:sub(-1) == "_" and name:sub(1, #k) == k then return true end
  end
  return false
end

local C = ls("csrc/*/*.c csrc/*/*.h")
local where = {}                       -- file name -> path
for _, f in ipairs(C) do where[f:match("[^/]+$")] = f end

describe("the C tree", function ()
  it("has its four layers and nothing else at the top", function ()
    assert.same({ "csrc/core", "csrc/gl", "csrc/lua", "csrc/prog" }, ls("-d csrc/*"))
    assert.is_true(#C > 40)
  end)

  it("has no file over 1000 lines", function ()
    local over = {}
    for _, f in ipairs(C) do
      local n = lines(f)
      if n > 1000 then over[#over + 1] = f .. " " .. n end
    end
    assert.same({}, over)
  end)

  it("has no function over 120 lines but the dispatch switches", function ()
    local over = {}
    for _, f in ipairs(C) do
      if f:match("%.c$") then
        for _, fn in ipairs(long_functions(f, 120)) do
          if not DISPATCH[fn[1]] then over[#over + 1] = f .. ": " .. fn[1] .. " " .. fn[2] end
        end
      end
    end
    assert.same({}, over)
  end)

  it("includes only downwards: core <- gl <- lua <- prog", function ()
    local allowed = {
      core = { core = true }, gl = { core = true, gl = true },
      lua = { core = true, gl = true, lua = true }, prog = {},
    }
    local bad = {}
    for _, f in ipairs(C) do
      for inc in io.open(f):read("a"):gmatch('#%s*include%s*"([^"]+)"') do
        local to = where[inc]
        if to and not allowed[layer(f)][layer(to)] then bad[#bad + 1] = f .. " includes " .. to end
      end
    end
    assert.same({}, bad)
  end)

  it("has no include cycle among its modules (x.c with x.h and x_impl.h)", function ()
    -- x_impl.h is the internal header that the files of module x share
    local function module (path) return (path:gsub("_impl%.h$", ".h"):gsub("%.[ch]$", "")) end
    local graph = {}
    for _, f in ipairs(C) do
      local from = module(f)
      graph[from] = graph[from] or {}
      for inc in io.open(f):read("a"):gmatch('#%s*include%s*"([^"]+)"') do
        local to = where[inc] and module(where[inc])
        if to and to ~= from then table.insert(graph[from], to) end
      end
    end
    assert.is_nil(cycle(graph))
  end)

  it("names the public functions of the core and the GL layer lsys_<module>_<verb>", function ()
    -- the module of the file that defines a function, or of the header that declares it
    -- (render.h's lsys_render_offscreen lives in osmesa.c), but for NAME_EXCEPTIONS
    local function core_or_gl (f) return layer(f) == "core" or layer(f) == "gl" end
    local function of (name, f)
      local prefix = "lsys_" .. module_of(f) .. "_"
      return name:sub(1, #prefix) == prefix
    end
    local def = {}
    for _, f in ipairs(C) do
      if core_or_gl(f) and f:match("%.c$") then
        for name in pairs(defined(f)) do def[name] = def[name] or f end
      end
    end
    local bad, used, n = {}, {}, 0
    for _, h in ipairs(C) do
      if core_or_gl(h) and h:match("%.h$") then
        for _, name in ipairs(declared(h)) do
          n = n + 1
          local f = def[name]
          if not (of(name, h) or f and of(name, f)) then
            if excepted(name) then used[name] = true
            else bad[#bad + 1] = h .. ": " .. name .. (f and " (" .. f .. ")" or "") end
          end
        end
      end
    end
    assert.is_true(n > 300)
    assert.same({}, bad)
    for k in pairs(NAME_EXCEPTIONS) do            -- an exception nothing needs must go
      local any = used[k]
      for name in pairs(used) do any = any or (k:sub(-1) == "_" and name:sub(1, #k) == k) end
      assert.is_true(any, k)
    end
  end)

  it("names the bindings' shared functions lsysL_ (and the entry luaopen_lsys_core)", function ()
    local bad = {}
    for _, h in ipairs(C) do
      if layer(h) == "lua" and h:match("%.h$") then
        for _, name in ipairs(declared(h)) do
          if not name:match("^lsysL_") and name ~= "luaopen_lsys_core" then
            bad[#bad + 1] = h .. ": " .. name
          end
        end
      end
    end
    assert.same({}, bad)
  end)

  it("makes a forbidden header a compile error in the core and the GL layer", function ()
    local cc = os.getenv("CC") or "cc"
    local _, have = H.sh("command -v " .. cc)
    if have ~= 0 then return pending("no C compiler") end
    local dir = H.tmpdir()
    local cases = {
      { "core", "lua.h", "the core (csrc/core) must not include Lua headers" },
      { "core", "GL/gl.h", "the core (csrc/core) must not include GL headers" },
      { "gl", "lauxlib.h", "the GL layer (csrc/gl) must not include Lua headers" },
      { "lua", "GLFW/glfw3.h", "the bindings (csrc/lua) must not include GL headers" },
    }
    for _, k in ipairs(cases) do
      H.write(dir .. "/t.c", "#include <" .. k[2] .. ">\nint x;\n")
      local out, code = H.sh(("%s -fsyntax-only -Icmake/forbid/%s %s/t.c"):format(cc, k[1], dir))
      assert.are_not.equal(0, code)
      assert.truthy(out:find(k[3], 1, true), out)
    end
    H.rmdir(dir)
  end)
end)

-- Every Lua file of the library, at any depth.
local function luafiles ()
  local files = {}
  for _, depth in ipairs { "*", "*/*", "*/*/*", "*/*/*/*" } do
    for _, f in ipairs(ls("lua/lsys/" .. depth .. ".lua")) do files[#files + 1] = f end
  end
  return files
end

-- Lua files and top-level functions still over the budget, each with what is to become of
-- it; the lists only shrink (one that fits the budget again must leave its list).
local LUA_LONG_FILES = {
}
local LUA_LONG_FUNCTIONS = {
}

-- The top-level functions of a Lua file (`function f`, `local function f`, `f = function`
-- at the start of a line, ended by `end` at the start of a line): { name, lines } each.
local function luafunctions (path)
  local out, n, start, name = {}, 0, nil, nil
  for line in io.lines(path) do
    n = n + 1
    local nm = line:match("^local function ([%w_.:]+)") or line:match("^function ([%w_.:]+)")
               or (line:match("^[%w_.]+%s*=%s*function") and line:match("^([%w_.]+)"))
    if nm and not line:find("end%s*$") then
      start, name = n, nm
    elseif start and line:match("^end") then
      out[#out + 1] = { name, n - start + 1 }
      start = nil
    end
  end
  return out
end

-- The module name of a file: lua/lsys/a/b.lua is lsys.a.b, lua/lsys/a/init.lua is lsys.a.
local function modname (f)
  return (f:gsub("^lua/", ""):gsub("%.lua$", ""):gsub("/init$", ""):gsub("/", "."))
end

-- The tokens of Lua source: { kind = "name" | "string" | "op", text =, line = } each;
-- comments, numbers and white space are dropped.
local function luatokens (src)
  local out, i, n, line = {}, 1, #src, 1
  local function add (kind, text) out[#out + 1] = { kind = kind, text = text, line = line } end
  local function skip (j)              -- to j + 1, counting the newlines passed
    local _, nl = src:sub(i, j):gsub("\n", "")
    line, i = line + nl, j + 1
  end
  while i <= n do
    local c = src:sub(i, i)
    local long = src:match("^%[(=*)%[", src:sub(i, i + 1) == "--" and i + 2 or i)
    if src:sub(i, i + 1) == "--" and not long then
      i = src:find("\n", i, true) or n + 1
    elseif long then
      local open = src:find("[", i, true) + #long + 2
      local close, j = src:find("]" .. long .. "]", open, true)
      if src:sub(i, i + 1) ~= "--" then add("string", src:sub(open, (close or n + 1) - 1)) end
      skip(j or n)
    elseif c == '"' or c == "'" then
      local j, buf = i + 1, {}
      while j <= n and src:sub(j, j) ~= c do
        if src:sub(j, j) == "\\" then j = j + 1 end
        buf[#buf + 1] = src:sub(j, j)
        j = j + 1
      end
      add("string", table.concat(buf))
      skip(j)
    elseif c:match("[%a_]") then
      local w = src:match("^[%w_]+", i)
      add("name", w); i = i + #w
    elseif c:match("%d") then
      i = i + #src:match("^[%w_.]+", i)
    else
      if c == "\n" then line = line + 1 elseif not c:match("%s") then add("op", c) end
      i = i + 1
    end
  end
  return out
end

-- Walks the tokens of the Lua file `path` keeping the blocks open (function, if, do,
-- repeat: the keywords with an `end` or `until` of their own; `while` and `for` open theirs
-- with `do`): visit(k, token, functions) for each token, `functions` the number of
-- functions it is inside; close(kind, first line, last line) for each block closed.
local function luawalk (path, visit, close)
  local t = luatokens(io.open(path):read("a"))
  local stack, nfun = {}, 0
  for k, tok in ipairs(t) do
    visit(k, tok, nfun, t)
    if tok.kind == "name" then
      local w = tok.text
      if w == "function" or w == "if" or w == "do" or w == "repeat" then
        stack[#stack + 1] = { w, tok.line }
        if w == "function" then nfun = nfun + 1 end
      elseif (w == "end" or w == "until") and #stack > 0 then
        local b = table.remove(stack)
        if b[1] == "function" then nfun = nfun - 1 end
        if close then close(b[1], b[2], tok.line) end
      end
    end
  end
end

-- The requires of the Lua file `path` whose module name is written out: `require "m"`,
-- `require("m")`, `pcall(require, "m")` (also as `_G.require`): { module =, line =, lazy =
-- (inside a function) } each. A name built at run time ends where its text does
-- ("lsys.cli.commands.").
local function luarequires (path)
  local out = {}
  luawalk(path, function (k, tok, nfun, t)
    if tok.kind ~= "name" or tok.text ~= "require" then return end
    local a, b, before = t[k + 1], t[k + 2], t[k - 1]
    local name
    if a and a.kind == "string" then name = a.text
    elseif a and a.text == "(" and b and b.kind == "string" then name = b.text
    elseif a and a.text == "," and b and b.kind == "string" and before and before.text == "("
    then name = b.text end
    if name then out[#out + 1] = { module = name, line = tok.line, lazy = nfun > 0 } end
  end)
  return out
end

-- The functions of the Lua file `path`: { first =, last = } (lines) each.
local function luafunctionspans (path)
  local out = {}
  luawalk(path, function () end, function (kind, first, last)
    if kind == "function" then out[#out + 1] = { first = first, last = last } end
  end)
  return out
end

-- The layers of the Lua modules, lowest first, each { name, module, ... }: a module may
-- require modules of its own layer and of those below, never above. "lsys.x*" is lsys.x
-- and every lsys.x.NAME; an exact name wins over such a prefix.
local LUA_LAYERS = {
  { "the C module", "lsys.core" },
  { "util", "lsys.util*", "lsys.program" },         -- helpers that know nothing of models
  { "the kernel", "lsys.model", "lsys.compile", "lsys.codegen", "lsys.view", "lsys.viewfile",
    "lsys.func", "lsys.population", "lsys.warning", "lsys.sandbox", "lsys.kinds",
    "lsys.environment*", "lsys.params", "lsys.inspect" },
  -- what builds models and plants on the kernel: other notations (component graphs,
  -- sketches, cpfg's files), incremental growth, the arrangement
  { "the front ends", "lsys.components*", "lsys.sketch*", "lsys.cpfg*", "lsys.grow",
    "lsys.arrange", "lsys.stand" },
  -- pictures and model files: both take a component graph's prototype for a Model
  { "render and load", "lsys.render", "lsys.vector", "lsys.load" },
  { "the tools", "lsys.frames", "lsys.testing", "lsys.batch*" },
  -- the window: lsys.viewer and the sessions in it (lua/lsys/ui/; their documented names
  -- lsys.growview, lsys.arrange_ui and lsys.sketch.window give them)
  { "the window", "lsys.viewer", "lsys.ui*", "lsys.growview", "lsys.arrange_ui",
    "lsys.sketch.window",
    "lsys.ui.curve" },                                -- the curve editor pane
  { "the library", "lsys" },                        -- init.lua: `require "lsys"`
  { "the program", "lsys.cli*", "lsys.repl*" },     -- the command line and the REPL
}

-- The layer (index in LUA_LAYERS) of module `name`, or nil.
local function layerof (name)
  local best, blen
  for i, l in ipairs(LUA_LAYERS) do
    for j = 2, #l do
      local base = l[j]:match("^(.-)%*$")
      if l[j] == name then return i end
      if base and (name == base or name:sub(1, #base + 1) == base .. ".")
         and (blen == nil or #base > blen) then
        best, blen = i, #base
      end
    end
  end
  return best
end

-- Modules a function may require when it first needs them, each with why it is loaded
-- late; "lsys.x*" as in LUA_LAYERS. Every other require is at the top of its file.
local LUA_LAZY = {
  ["cjson"] = "lua-cjson, an optional library: JSON sketches, organs and the sketch window",
  ["cjson.safe"] = "lua-cjson, as cjson",
  ["lxp"] = "lua-expat, an optional library: SVG sketches only",
  ["lsys.viewer"] = "the window (libglfw, a display): what never opens one does not load it",
  ["lsys.ui*"] = "the window sessions, loaded by the command that opens their window",
  ["lsys.repl"] = "the REPL, loaded when it runs (lsys with no command, lsys view)",
  ["lsys.cli.commands*"] = "the program loads only the command that runs",
  ["lsys.components*"] = "component graphs, loaded by the scripts that make them",
  ["lsys.sketch*"] = "sketches, loaded by the scripts and commands that read them",
  ["lsys.cpfg*"] = "cpfg's model files, loaded by the commands given one",
  ["lsys.batch"] = "batch runs, loaded by lsys.batch and `lsys batch`",
  ["lsys.arrange"] = "the arrangement, loaded by lsys.arrange",
  ["lsys"] = "the library, which the REPL loads for its user as it starts (LIBRARY_USERS)",
  ["lsys.readline"] = "the program's line editor, there when it was built with readline",
  ["busted.runner"] = "busted, an optional program: only `lsys test` runs it",
}

-- Files that look modules up at each use instead of keeping them, and why.
local LUA_LOOKED_UP = {
  ["lua/lsys/testing.lua"] = "busted gives each spec file its own package.loaded, and this "
    .. "module, loaded once by a helper, must use that file's modules",
  ["lua/lsys/util/fs.lua"] = "lsys.core, for lsys.testing's reason",
}

-- Files besides init.lua that require "lsys", and why.
local LIBRARY_USERS = {
  ["lua/lsys/repl.lua"] = "the REPL hands its user the library as the global lsys",
}

-- The LUA_LAZY entry that covers module `name`, or nil.
local function lazyentry (name)
  if LUA_LAZY[name] then return name end
  local best
  for k in pairs(LUA_LAZY) do
    local base = k:match("^(.-)%*$")
    if base and (name == base or name:sub(1, #base + 1) == base .. ".")
       and (best == nil or #k > #best) then
      best = k
    end
  end
  return best
end

describe("the Lua tree", function ()
  it("keeps to the size budget: 1000 lines a file, 120 a top-level function", function ()
    local over, fits = {}, {}
    local seen = {}
    for _, f in ipairs(luafiles()) do
      local n = lines(f)
      if n > 1000 and not LUA_LONG_FILES[f] then over[#over + 1] = f .. ": " .. n .. " lines" end
      if LUA_LONG_FILES[f] then
        seen[f] = true
        if n <= 1000 then fits[#fits + 1] = f end
      end
      for _, fn in ipairs(luafunctions(f)) do
        local key = f .. " " .. fn[1]
        if fn[2] > 120 and not LUA_LONG_FUNCTIONS[key] then
          over[#over + 1] = key .. ": " .. fn[2] .. " lines"
        end
        if LUA_LONG_FUNCTIONS[key] then
          seen[key] = true
          if fn[2] <= 120 then fits[#fits + 1] = key end
        end
      end
    end
    for k in pairs(LUA_LONG_FILES) do if not seen[k] then fits[#fits + 1] = k end end
    for k in pairs(LUA_LONG_FUNCTIONS) do if not seen[k] then fits[#fits + 1] = k end end
    table.sort(over)
    table.sort(fits)
    assert.same({}, over)
    assert.same({}, fits)          -- listed, but within the budget (or gone): unlist it
  end)

  it("has no require cycle among the lsys modules", function ()
    local graph = {}
    for _, f in ipairs(luafiles()) do
      local name = modname(f)
      graph[name] = {}
      for _, r in ipairs(luarequires(f)) do
        if r.module == "lsys" or r.module:match("^lsys%.") and r.module ~= "lsys.core" then
          table.insert(graph[name], r.module)
        end
      end
    end
    assert.is_nil(cycle(graph))
  end)

  it("gives every module a layer", function ()
    local none = {}
    for _, f in ipairs(luafiles()) do
      if layerof(modname(f)) == nil then none[#none + 1] = f .. " (" .. modname(f) .. ")" end
    end
    assert.same({}, none)
  end)

  it("requires only downwards: a module requires its own layer or those below", function ()
    local bad = {}
    for _, f in ipairs(luafiles()) do
      local from = layerof(modname(f))
      for _, r in ipairs(luarequires(f)) do
        local to = r.module:match("^lsys") and layerof(r.module)
        if from and to and to > from then
          bad[#bad + 1] = format("%s:%d -> %s (%s requires %s)", f, r.line, r.module,
                                 LUA_LAYERS[from][1], LUA_LAYERS[to][1])
        end
      end
    end
    assert.same({}, bad)
  end)

  it("has no file but init.lua that requires \"lsys\" (the REPL hands it to its user)",
     function ()
    local bad = {}
    for _, f in ipairs(luafiles()) do
      for _, r in ipairs(luarequires(f)) do
        if r.module == "lsys" and f ~= "lua/lsys/init.lua" and not LIBRARY_USERS[f] then
          bad[#bad + 1] = format("%s:%d -> lsys", f, r.line)
        end
      end
    end
    assert.same({}, bad)
    for f in pairs(LIBRARY_USERS) do
      local uses = false
      for _, r in ipairs(luarequires(f)) do uses = uses or r.module == "lsys" end
      assert(uses, f .. " is listed in LIBRARY_USERS but does not require \"lsys\": unlist it")
    end
  end)

  it("has an init.lua that only gathers: no function body longer than two lines", function ()
    local long = {}
    for _, fn in ipairs(luafunctionspans("lua/lsys/init.lua")) do
      if fn.last - fn.first + 1 > 2 then
        long[#long + 1] = format("lua/lsys/init.lua:%d: a function of %d lines", fn.first,
                                 fn.last - fn.first + 1)
      end
    end
    assert.same({}, long)
  end)

  it("requires inside functions only what LUA_LAZY lists (optional dependencies)", function ()
    local bad, used = {}, {}
    for _, f in ipairs(luafiles()) do
      if not LUA_LOOKED_UP[f] then
        for _, r in ipairs(luarequires(f)) do
          if r.lazy then
            local entry = lazyentry(r.module)
            if entry then used[entry] = true
            else bad[#bad + 1] = format("%s:%d -> %s", f, r.line, r.module) end
          end
        end
      end
    end
    table.sort(bad)
    assert.same({}, bad)
    local unused = {}
    for k in pairs(LUA_LAZY) do if not used[k] then unused[#unused + 1] = k end end
    table.sort(unused)
    assert.same({}, unused)        -- listed, but no function requires it: unlist it
  end)

  it("reads no binding's internals: no debug.getuservalue or debug.setuservalue", function ()
    local bad = {}
    for _, f in ipairs(luafiles()) do
      local n = 0
      for line in io.lines(f) do
        n = n + 1
        if line:find("debug%.[gs]etuservalue") then bad[#bad + 1] = f .. ":" .. n end
      end
    end
    assert.same({}, bad)
  end)
end)
