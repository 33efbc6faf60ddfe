--- help() at the REPL: an overview; the section of the manual (docs/*.md) on a function, a
-- method or a topic; for a model, an Lstring or a scene, what it is and its methods. Text
-- longer than the terminal goes through a pager ($PAGER, less or more); without a
-- terminal it is printed whole.
--
-- The sections are found by their headings (`### m:derive([n [, opts]])`, `## lsys.show`,
-- `## 8. Lstrings`), by the first cell of a table row (`` | `s:count(name)` | ``) and by a
-- paragraph that starts with a call (`` `lsys.render(x, opts)` draws ... ``); else by the
-- LuaLS declarations of docs/meta.lua (`function lsys.here() end`). The docs are
-- looked up beside the Lua files (the source tree: lua/../docs) and in the program's data
-- directories (an install: share/lsys/docs, where `cmake --install` puts them).
-- @module lsys.repl.help
local core = require "lsys.core"
local inspect = require "lsys.inspect"
local S = require "lsys.repl.show"
local host = require("lsys.program").host
local normalize = require("lsys.util.text").normpath
local shq = require("lsys.util.text").shq

local G = _G
local type, tostring, pairs, ipairs, select, pcall, getmetatable, rawget =
      type, tostring, pairs, ipairs, select, pcall, getmetatable, rawget
local io, os, string, table, math, debug, package = io, os, string, table, math, debug, package
local format = string.format
local _ENV = nil

local M = {}

-- The docs in the order they are searched; others found in the folder come after.
local ORDER = { "manual.md", "drawing.md", "viewer.md", "components.md", "grow.md",
                "sketch.md", "surfaces.md", "arrange.md", "cpfg.md" }
local LAST = { ["architecture.md"] = true }   -- for developers: searched last

-- The receivers the docs write methods with, by the kind of object.
local RECEIVER = { ["lsys.Lstring"] = "s", ["lsys.Scene"] = "scene" }
-- Names whose section has no heading, row or paragraph of their own.
local ALIAS = { ["lsys.view"] = "view options" }
-- The classes of docs/meta.lua as the manual writes their methods.
local META_CLASS = { Model = "m", Lstring = "s", Scene = "scene" }
-- The section of the manual on a kind of value (help(m), help(s), help(sc)).
local KIND_TOPIC = { model = "Model methods and module functions", lstring = "Lstrings",
                     scene = "Scenes" }
local KIND_RECEIVER = { model = "m", lstring = "s", scene = "scene" }

local OVERVIEW = [[
lsys: L-systems for plant modelling, Lua 5.4 with a C core. `lsys` is loaded:

  m = lsys.lsystem { axiom = "X", steps = 4, productions = "X --> F[+X]F[-X]+X" }
  s = m:derive()        the module string, an Lstring: #s, s:count("F"), s:module(1)
  sc = m:interpret()    the turtle's Scene: sc:bounds(), sc:turtle(i), sc:save("plant.glb")
  lsys.render(m, { out = "plant.png" })   a picture; lsys.show(m) opens the window
  m = dofile("examples/abop/fig1_24d.lua") a model from a file (lsys.here() in it)

More: help "derive", help(lsys.render): the manual's section on a method or a function;
help(m), help(s), help(sc): what that model, Lstring or scene is and its methods;
help "Lstrings", help "context": a section by its title. A model prints its options and
rules (m:inspect(), m:rules()). At the prompt: `_` is the last value printed, Tab
completes names (m:de<Tab>), the arrows recall lines of this and earlier sessions,
Ctrl-C clears the line, `local` names stay for the next lines.
]]

-- {===========================================================================================
-- Finding and reading the docs


local function isfile (path)
  local f = io.open(path, "r")
  if f then f:close() end
  return f ~= nil
end

--- The folders that may hold the docs, most specific first: beside the Lua files in a
-- source tree (lua/../docs) or a luarocks tree (share/lua/5.4/../../lsys/docs), then the
-- program's data directories (share/lsys/docs when installed).
function M.dirs ()
  local dirs = {}
  local root = debug.getinfo(1, "S").source:match("^@(.*)/lsys/repl/help%.lua$")
  if root ~= nil then
    dirs[#dirs + 1] = normalize(root .. "/../docs")
    dirs[#dirs + 1] = normalize(root .. "/../../lsys/docs")
  end
  for _, d in ipairs(host().datadirs or {}) do dirs[#dirs + 1] = normalize(d .. "/docs") end
  return dirs
end

-- The .md files of 'dir', in search order.
local function docfiles (dir)
  local names, seen, last = {}, {}, {}
  for _, n in ipairs(ORDER) do
    if isfile(dir .. "/" .. n) then names[#names + 1] = n; seen[n] = true end
  end
  local ok, p = pcall(io.popen, "ls -1 -- " .. shq(dir) .. " 2>/dev/null")   -- never an option
  if ok and p ~= nil then
    local found = {}
    for n in p:lines() do
      if n:find("%.md$") and not seen[n] then found[#found + 1] = n end
    end
    p:close()
    table.sort(found)
    for _, n in ipairs(found) do
      if LAST[n] then last[#last + 1] = n else names[#names + 1] = n end
    end
  end
  for _, n in ipairs(last) do names[#names + 1] = n end
  return names
end

-- The identifiers in a piece of a heading or a table cell: "m:derive", "lsys.show".
local function idents (text, out)
  for id in text:gmatch("[%a_][%w_]*[.:][%a_][%w_.:]*") do
    id = id:gsub("[.:]+$", "")
    out[#out + 1] = id
  end
  return out
end

-- The name of an identifier without its receiver or module: "derive" for "m:derive".
local function bare (id) return id:match("([%a_][%w_]*)$") end

-- Files 'sec' under 'key' in the index: its table row 'row', or the line 'at' of the
-- paragraph that introduces the key (for one-line summaries).
local function add (index, key, prio, sec, row, at)
  local list = index[key]
  if list == nil then list = {}; index[key] = list end
  list[#list + 1] = { prio = prio, sec = sec, row = row, at = at }
end

-- Reads one doc into sections and adds its keys to 'index'.
local function read_doc (path, file, index, sections)
  local lines = {}
  for l in io.lines(path) do lines[#lines + 1] = l end
  local fence, cur = false, nil
  for i, l in ipairs(lines) do
    if l:find("^```") then fence = not fence end
    local hashes, title = l:match("^(#+)%s+(.-)%s*$")
    if not fence and hashes ~= nil then
      cur = { file = file, path = path, lines = lines, first = i, level = #hashes,
              title = title, last = #lines }
      for _, s in ipairs(sections) do   -- the open sections of this file end here
        if s.lines == lines and s.last == #lines and s.first < i and s.level >= #hashes then
          s.last = i - 1
        end
      end
      sections[#sections + 1] = cur
      cur.name = title:gsub("^[%d.]+[a-z]?%s+", ""):gsub("`", "")
      add(index, cur.name:lower(), 4, cur)
      for _, id in ipairs(idents(title, {})) do
        add(index, id, 1, cur)
        add(index, bare(id), 5, cur)
        cur.ident = cur.ident or id
      end
    elseif not fence and cur ~= nil then
      local cell = l:match("^|%s*(`[^|]*)|")
      local para, call = nil, nil
      if i == 1 or lines[i - 1]:find("^%s*$") then
        para, call = l:match("^`([%a_][%w_.:]*)([%(`])")
      end
      if cell ~= nil then
        local ids = idents(cell, {})
        local first = cell:match("^`([%a_][%w_]*)[%(`%[]")   -- `poll([timeout])` in lsys.viewer
        if first ~= nil and cur.ident ~= nil and not cur.ident:find(":") then
          ids[#ids + 1] = cur.ident .. "." .. first
        end
        for _, id in ipairs(ids) do
          add(index, id, 3, cur, i)
          add(index, bare(id), 7, cur, i)
        end
      elseif para ~= nil and para:find("[.:]") then
        -- `m:interpret([s [, view]])` introduces it; a bare `m:interpret` only mentions it
        local later = call == "(" and 0 or 0.5
        add(index, para, 2 + later, cur, nil, i)
        add(index, bare(para), 6 + later, cur, nil, i)
      end
    end
  end
end

-- Reads the declarations of docs/meta.lua: each `function NAME(...) end` with the `---`
-- comment above it is a section of its own, found by NAME (`Lstring:text` as `s:text`).
local function read_meta (path, index, sections)
  local lines = {}
  for l in io.lines(path) do lines[#lines + 1] = l end
  for i, l in ipairs(lines) do
    local name = l:match("^function ([%a_][%w_.:]*)%(.*%) end$")
    if name ~= nil then
      local first = i
      while first > 1 and lines[first - 1]:find("^%-%-%-") do first = first - 1 end
      local class, rest = name:match("^([%a_][%w_]*)(:.*)$")
      if class and META_CLASS[class] then name = META_CLASS[class] .. rest end
      local sec = { file = "meta.lua", path = path, lines = lines, first = first, last = i,
                    name = name, meta = true }
      sections[#sections + 1] = sec
      add(index, name, 8, sec)
      add(index, bare(name), 9, sec)
    end
  end
end

-- The docs of the first folder in 'dirs' that has manual.md: { dir, index, sections }, or
-- nil and a message.
local function load_docs (dirs)
  for _, d in ipairs(dirs) do
    if isfile(d .. "/manual.md") then
      local docs = { dir = d, index = {}, sections = {} }
      for _, n in ipairs(docfiles(d)) do
        pcall(read_doc, d .. "/" .. n, n, docs.index, docs.sections)
      end
      if isfile(d .. "/meta.lua") then
        pcall(read_meta, d .. "/meta.lua", docs.index, docs.sections)
      end
      return docs
    end
  end
  return nil, format("help: the lsys manual (manual.md) was not found in %s",
    #dirs > 0 and table.concat(dirs, " or ") or "any folder")
end

-- }===========================================================================================


-- {===========================================================================================
-- Names of values

local LUA_MANUAL = "https://www.lua.org/manual/5.4/manual.html#pdf-"
local STDLIBS = { "string", "table", "math", "io", "os", "utf8", "coroutine", "debug",
                  "package" }
local BASE = { "assert", "collectgarbage", "dofile", "error", "getmetatable", "ipairs", "load",
               "loadfile", "next", "pairs", "pcall", "print", "rawequal", "rawget", "rawlen",
               "rawset", "require", "select", "setmetatable", "tonumber", "tostring", "type",
               "warn", "xpcall" }

-- Lua's standard functions with their names as "lua:name", and every function and module
-- table of lsys with its name ("lsys.render", "m:derive", "s:count", "scene:bounds",
-- "lsys.viewer.poll").
local function names (lsys)
  local map = {}
  local function put (v, name) if map[v] == nil then map[v] = name end end
  local function walk (t, prefix, sep)
    for k, v in pairs(t) do
      if type(k) == "string" and (type(v) == "function" or type(v) == "table") then
        put(v, prefix .. sep .. k)
      end
    end
  end
  for _, k in ipairs(BASE) do
    if type(G[k]) == "function" then put(G[k], "lua:" .. k) end
  end
  for _, lib in ipairs(STDLIBS) do
    if type(G[lib]) == "table" then
      put(G[lib], "lua:" .. lib)
      for k, v in pairs(G[lib]) do
        if type(k) == "string" and type(v) == "function" then put(v, "lua:" .. lib .. "." .. k) end
      end
    end
  end
  if type(lsys) == "table" then
    put(lsys, "lsys")
    for _, sub in ipairs({ "viewer", "sketch", "components", "grow", "cpfg", "arrange" }) do
      local mod = package.loaded["lsys." .. sub]
      if mod ~= nil then put(mod, "lsys." .. sub) end
      if type(mod) == "table" then walk(mod, "lsys." .. sub, ".") end
    end
    walk(lsys, "lsys", ".")
    for k, v in pairs(lsys) do
      if type(k) == "string" and type(v) == "table" and getmetatable(v) == nil then
        walk(v, "lsys." .. k, ".")
      end
    end
    if type(rawget(lsys, "Model")) == "table" then walk(lsys.Model, "m", ":") end
  end
  local reg = debug.getregistry()
  for tname, recv in pairs(RECEIVER) do
    local mt = reg[tname]
    if type(mt) == "table" then
      if type(mt.__index) == "table" then walk(mt.__index, recv, ":") end
      if type(mt.__methods) == "table" then walk(mt.__methods, recv, ":") end
    end
  end
  return map
end

-- }===========================================================================================


-- {===========================================================================================
-- Finding a section and printing it

-- The best entry for 'topic' in the index: an identifier, then a title, then a name.
local function lookup (docs, topic)
  local q = topic:gsub("^%s+", ""):gsub("[%s()]+$", "")
  q = ALIAS[q] or q
  local tries = { q, q:lower() }
  if q:find("[.:]") then tries[#tries + 1] = bare(q) end
  local best
  for _, key in ipairs(tries) do
    for _, e in ipairs(docs.index[key] or {}) do
      local prio = e.prio + (key == q and 0 or 10)
      if best == nil or prio < best.p then best = { p = prio, e = e } end
    end
  end
  if best ~= nil then return best.e end
  -- a word of a title: help "context" finds "6.3 Context", help "rules" "4.2 Rules"
  local word = "%f[%w]" .. q:lower():gsub("%p", "%%%0") .. "%f[%W]"
  for _, s in ipairs(docs.sections) do
    if s.name:lower():find(word) then return { sec = s } end
  end
  return nil
end

-- The rows of the screen 'lines' take with 'cols' columns (a long line wraps).
local function height (lines, cols)
  local rows = 0
  for _, l in ipairs(lines) do rows = rows + math.max(1, (#l + cols - 1) // cols) end
  return rows
end

-- Whether the shell finds the command 'name'.
local function have (name)
  return os.execute("command -v " .. name .. " >/dev/null 2>&1") == true
end

--- The pager help uses on a terminal, as a shell command that reads the text on its
-- standard input: $PAGER when set (and not empty), else less (with LESS=FRX unless LESS is
-- set: the text stays on the screen after `q`, as git does), else more; nil without any,
-- and on a terminal that cannot run them (TERM unset or "dumb", as in Emacs's shell).
function M.pager_command ()
  local p = os.getenv("PAGER")
  if p ~= nil and p:find("%S") then return p end
  local term = os.getenv("TERM")
  if term == nil or term == "" or term == "dumb" then return nil end
  if have("less") then return os.getenv("LESS") == nil and "LESS=FRX less" or "less" end
  if have("more") then return "more" end
  return nil
end

-- Shows 'text' with the pager; false when there is none or it could not run (the text
-- is then to be printed). The text goes through a file in a private temporary folder, so
-- that a pager quit early never breaks a pipe; while the pager runs, the REPL ignores
-- Ctrl-C (os.execute is C's system()), which the pager handles.
local function run_pager (text)
  local cmd = M.pager_command()
  if cmd == nil then return false end
  local ok, dir = pcall(core.tempdir, nil, "lsys-help")
  if not ok then return false end
  local file = dir:path() .. "/help.txt"
  local done = pcall(core.write_file, file, text) and
    os.execute("exec < " .. shq(file) .. "\n" .. cmd) == true   -- any command line
  pcall(dir.remove, dir)
  return done
end

-- A doc line as it is printed: links as their text, no code fences.
local function clean (l)
  return (l:gsub("%[([^%]]+)%]%([^%)]+%)", "%1"))
end

-- The lines of section 's' (a table row 'row': the heading, the table's header, the row).
local function section_lines (s, row)
  local lines = {}
  if s.meta then   -- a declaration: its comment, then the line that declares it
    lines[1] = s.lines[s.last]:gsub(" end$", "")
    for i = s.first, s.last - 1 do
      local l = s.lines[i]:gsub("^%-%-%-%s?", "")
      lines[#lines + 1] = l:gsub("^@param ", "  "):gsub("^@return ", "  returns ")
                           :gsub("^@field ", "  ")
    end
  elseif row ~= nil then
    local top = row
    while top > s.first + 1 and s.lines[top - 1]:find("^|") do top = top - 1 end
    lines[1] = s.lines[s.first]
    lines[2] = ""
    if top < row then lines[3] = s.lines[top]; lines[4] = s.lines[top + 1] end
    lines[#lines + 1] = s.lines[row]
    lines[#lines + 1] = ""
    lines[#lines + 1] = format('(the whole section: help "%s")', s.name)
  else
    local last = s.last
    while last > s.first and s.lines[last]:find("^%s*$") do last = last - 1 end
    local code = false
    for i = s.first, last do
      local l = s.lines[i]
      if l:find("^```") then code = not code
      else lines[#lines + 1] = code and "    " .. l or l end
    end
  end
  for i, l in ipairs(lines) do lines[i] = clean(l) end
  return lines
end

-- The first sentence of a doc line, without links and code marks.
local function sentence (l)
  l = clean(l):gsub("`", "")
  return (l:match("^(.-%.)%s") or l):gsub("%s+$", "")
end

-- The signature and the one-line summary the docs give for 'key' ("m:derive"): from its
-- declaration, table row, paragraph or heading; nil when they have nothing under that
-- very name.
local function summary (docs, key)
  local best
  for _, e in ipairs(docs.index[key] or {}) do
    if best == nil or e.prio < best.prio then best = e end
  end
  if best == nil then return nil end
  local s = best.sec
  if s.meta then
    local args = s.lines[s.last]:match("%b()") or "()"
    return s.name .. args, sentence(s.lines[s.first]:gsub("^%-%-%-%s?", ""))
  end
  -- the call of 'key' in a piece of text, with its arguments
  local function call (t) return t:match(key:gsub("%p", "%%%0") .. "%b()") or key end
  if best.row then
    local cell, what = s.lines[best.row]:match("^|([^|]*)|%s*([^|]*)")
    return call(cell), sentence(what)
  elseif best.at then
    local l = s.lines[best.at]
    return call(l), sentence(l:gsub("^`[^`]*`%s*", ""))
  end
  local first = ""
  for i = s.first + 1, s.last do
    if s.lines[i]:find("%S") then first = s.lines[i] break end
  end
  return (s.title:gsub("`", "")), first:find("^```") and "" or sentence(first)
end

-- The public methods of 'x' (those of its metatable's __index and __methods tables),
-- sorted.
local function methods_of (x)
  local mt, seen, list = getmetatable(x), {}, {}
  for _, t in ipairs({ type(mt) == "table" and mt.__index, type(mt) == "table" and
                       mt.__methods }) do
    if type(t) == "table" then
      for k, v in pairs(t) do
        if type(k) == "string" and type(v) == "function" and not k:find("^_")
           and not seen[k] then
          seen[k] = true
          list[#list + 1] = k
        end
      end
    end
  end
  table.sort(list)
  return list
end

-- How help(x) names a model: what it is, and its rules by set (two lines).
local function model_line (x)
  local counts, order = {}, {}
  for _, r in ipairs(inspect.rules(x)) do
    if counts[r.set] == nil then order[#order + 1] = r.set end
    counts[r.set] = (counts[r.set] or 0) + 1
  end
  local parts, n = {}, 0
  for _, set in ipairs(order) do
    parts[#parts + 1] = format("%s %d", set, counts[set])
    n = n + counts[set]
  end
  return format("%s, a model: axiom %s, %s step%s", tostring(x),
    S.show({ x.axiom }):match("^{ (.*) }$"), tostring(x.steps), x.steps == 1 and "" or "s"),
    format("%d rule%s%s", n, n == 1 and "" or "s",
      n > 0 and ": " .. table.concat(parts, ", ") or "")
end

-- What help(x) prints for a model, an Lstring or a scene: what it is, then its methods
-- with the docs' summary of each, then where to read more.
local function about_lines (docs, x, kind, cols)
  local recv = KIND_RECEIVER[kind]
  local lines = { kind == "model" and model_line(x) or S.show(x) }
  if kind == "model" then lines[2] = select(2, model_line(x)) end
  lines[#lines + 1] = ""
  lines[#lines + 1] = format('Its methods (help "%s:NAME" prints the section on one):', recv)
  local rows, width = {}, 0
  for _, name in ipairs(methods_of(x)) do
    local sig, what
    if docs ~= nil then sig, what = summary(docs, recv .. ":" .. name) end
    rows[#rows + 1] = { sig or format("%s:%s()", recv, name), what or "" }
    width = math.max(width, math.min(#rows[#rows][1], 30))
  end
  for _, r in ipairs(rows) do
    local l = format("  %-" .. width .. "s  %s", r[1], r[2])
    if #l > cols - 1 then l = l:sub(1, cols - 4) .. "..." end
    lines[#lines + 1] = l
  end
  lines[#lines + 1] = ""
  if kind == "model" then
    lines[#lines + 1] = "m:inspect() prints its options, view and rules."
  end
  lines[#lines + 1] = format('help "%s" prints the manual\'s section.', KIND_TOPIC[kind])
  return lines
end

--- Makes the `help` function of the REPL.
-- opts: `dirs` (the folders to look for the docs in; default M.dirs()), `out` (writes a
-- string; default io.stdout), `size` (returns the rows and columns of the screen; default
-- the terminal's, else 24 by 80), `page` (shows a text that does not fit on the screen,
-- returning true, or false to have it printed; default: the pager when `out` is not given
-- and stdout is a terminal), `lsys` (the lsys module; default the global).
-- help() prints an overview; help(x) the section on x (a function, a method, or a topic as
-- a string), what x is and its methods (a model, an Lstring, a scene), or "no help for X;
-- try help()".
function M.new (opts)
  opts = opts or {}
  local out = opts.out or function (s) io.stdout:write(s) end
  local docs, why
  local function size ()
    local r, c
    if opts.size then r, c = opts.size()
    elseif host().termsize then r, c = host().termsize() end
    return r or 24, c or 80
  end
  local function get_docs ()
    if docs == nil and why == nil then docs, why = load_docs(opts.dirs or M.dirs()) end
    return docs, why
  end
  -- the pager: opts.page, else on a terminal (when help writes to stdout) the terminal's
  local pager = opts.page
  if pager == nil and opts.out == nil and host().isatty and host().isatty(1) then
    pager = run_pager
  end
  -- Prints 'lines', through the pager when they do not fit on the screen.
  local function emit (lines)
    local rows, cols = size()
    local text = table.concat(lines, "\n") .. "\n"
    if pager and height(lines, cols) > rows - 1 and pager(text) then return end
    out(text)
  end
  local function show (topic, label)
    local d, msg = get_docs()
    if d == nil then out(msg .. "\n") return end
    local e = lookup(d, topic)
    if e == nil then out(format("no help for %s; try help()\n", label or topic)) return end
    emit(section_lines(e.sec, e.row))
  end
  return function (...)
    local lsys = opts.lsys or G.lsys
    local x = ...
    if select("#", ...) == 0 or x == lsys then
      out(OVERVIEW)
      local _, msg = get_docs()
      if msg then out(msg .. "\n") end
      return
    end
    if type(x) == "string" then return show(x) end
    local name = names(lsys)[x]
    if name ~= nil and name:find("^lua:") then
      local lname = name:sub(5)
      out(format("%s is Lua's: see %s%s\n", lname, LUA_MANUAL, lname))
      return
    end
    if name ~= nil then return show(name) end
    local kind = type(lsys) == "table" and type(lsys.type) == "function" and lsys.type(x)
    if kind and KIND_TOPIC[kind] then   -- (without the docs, the methods' names alone)
      return emit(about_lines(get_docs(), x, kind, select(2, size())))
    end
    local mt = getmetatable(x)
    local label = (type(x) == "function" or type(x) == "table" and
      not (type(mt) == "table" and mt.__tostring)) and "this " .. type(x) or tostring(x)
    out(format("no help for %s; try help()\n", label))
  end
end

-- }===========================================================================================

return M
