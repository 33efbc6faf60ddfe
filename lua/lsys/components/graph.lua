--- The p-graph of a component graph as Graphviz DOT (docs/components.md, "The p-graph as
-- Graphviz"), drawn as Lintermann and Deussen 1999 draw theirs (fig. 3 and section
-- "Component types and their combination"): a camera node at the root, child links as thin
-- lines, branch links bold, leaf links dashed, the links of a recursion doubled, and no
-- arrows, since every link points away from the camera.
--
-- The article keeps its p-graphs trees: it omits the link that points back to the start of a
-- recursion and appends a copy of that component to the end of the recursive part instead.
-- So does this module: a back edge (found by a depth-first search from the root, links in
-- their order) ends at a dashed copy of the prototype it returns to, and every link inside a
-- cycle of the graph (a strongly connected part, or a self link) is drawn doubled.
--
--   graph.dot(root [, opts]) -> string
--   graph.render(root, path [, opts]) -> path     .dot/.gv as text; .png/.svg/.pdf via `dot`
--   graph.nodes(root) -> the nodes and links as the drawing sees them
--   graph.quote(s) -> s quoted for a POSIX shell
-- @module lsys.components.graph
local core = require "lsys.core"
local shq = require("lsys.util.text").shq
local type, pairs, ipairs, error, tostring, pcall = type, pairs, ipairs, error, tostring, pcall
local io, math, string, table, utf8 = io, math, string, table, utf8
local format, byte, concat, sort = string.format, string.byte, table.concat, table.sort
local _ENV = nil

local M = {}

--- The link types and their DOT edge attributes (Lintermann and Deussen 1999, fig. 3).
M.LINK_STYLE = { child = nil, branch = "penwidth=3", leaf = "style=dashed" }
local LINK_TYPES = { child = true, branch = true, leaf = true }

--- A doubled line: two black strokes with a white one between them.
M.DOUBLE = 'color="black:white:black"'

--- Node shapes by kind: multipliers are hexagons, the global modelling components
-- octagons, everything else (geometry, Tree, unknown kinds) an ellipse.
M.SHAPES = { hydra = "hexagon", wreath = "hexagon", phiball = "hexagon",
             ffd = "octagon", hyperpatch = "octagon", world = "octagon" }

local OPTIONS = { params = true, max_params = true }
local MAX_LABEL = 60      -- code points of a name or string value shown
local MAX_LIST = 4        -- numbers of a list shown

-- {===========================================================================================
-- Text

-- s with every byte that is not part of a valid UTF-8 sequence replaced by "?" and cut to
-- 'max' code points (with "..." then): Graphviz rejects invalid UTF-8.
local function clean (s, max)
  local out, i, n, count = {}, 1, #s, 0
  while i <= n do
    local c = byte(s, i)
    local len = c < 0x80 and 1 or (c >= 0xC2 and c <= 0xDF) and 2 or
                (c >= 0xE0 and c <= 0xEF) and 3 or (c >= 0xF0 and c <= 0xF4) and 4 or 0
    if count == max then out[#out + 1] = "..." break end
    if len > 0 and i + len - 1 <= n and utf8.len(s, i, i + len - 1) == 1 then
      out[#out + 1] = s:sub(i, i + len - 1)
      i = i + len
    else
      out[#out + 1] = "?"
      i = i + 1
    end
    count = count + 1
  end
  return concat(out)
end

-- The DOT string literal of the text lines: quotes and backslashes escaped, a line break
-- "\n" between lines, control characters as spaces (a newline in a name breaks the line).
local function dotstr (lines)
  local t = {}
  for i, l in ipairs(lines) do
    t[i] = l:gsub('[\\"]', "\\%0"):gsub("\n", "\\n"):gsub("[%c]", " ")
  end
  return '"' .. concat(t, "\\n") .. '"'
end

-- A number as a label shows it: whole numbers without a point, others with 4 digits.
local function num (x)
  if x ~= x then return "nan" end
  if x == math.huge then return "inf" elseif x == -math.huge then return "-inf" end
  if math.type(x) == "integer" or (x == math.floor(x) and math.abs(x) < 1e15) then
    return format("%d", x)
  end
  return format("%.4g", x)
end

-- A parameter's value as a label shows it, or nil when it has no short form.
local function value_text (v)
  local t = type(v)
  if t == "number" then return num(v)
  elseif t == "boolean" then return tostring(v)
  elseif t == "string" then return clean(v, 24)
  elseif t == "function" then return "f()"
  elseif t ~= "table" then return nil end
  local items = {}
  for i = 1, #v do
    if type(v[i]) ~= "number" then return "{...}" end
    if i > MAX_LIST then items[#items + 1] = "..." break end
    items[#items + 1] = num(v[i])
  end
  local fn = false
  for k, x in pairs(v) do
    if type(x) == "function" then fn = true
    elseif not (math.type(k) == "integer" and k >= 1 and k <= #v) then return "{...}" end
  end
  local s = #items > 0 and "[" .. concat(items, ", ") .. "]" or "{}"
  return fn and s .. " f()" or s
end

-- }===========================================================================================


-- {===========================================================================================
-- The graph

-- What a node of the p-graph is called: its name, else kind#k (the k-th prototype of that
-- kind in depth-first order, from 1).
local function node_title (p, seen_kind)
  if p.name ~= nil then return clean(p.name, MAX_LABEL) end
  seen_kind[p.kind] = (seen_kind[p.kind] or 0) + 1
  return p.kind .. "#" .. seen_kind[p.kind]
end

-- nil when p has the shape of a prototype, else what it lacks.
local function not_proto (p)
  if type(p) ~= "table" then return format("is a %s, not a prototype", type(p)) end
  if type(p.kind) ~= "string" or p.kind == "" then
    return "is not a prototype (no kind: a prototype is a table with kind and links)"
  end
  if type(p.links) ~= "table" then
    return format("is not a prototype (its links are a %s, not a list)", type(p.links))
  end
  if p.name ~= nil and type(p.name) ~= "string" then
    return format("has a name that is a %s, not a string", type(p.name))
  end
  local r = p.recursion
  if r ~= nil and not (type(r) == "number" and r == math.floor(r) and r >= 1) then
    return format("has recursion %s, not a whole number of 1 or more", tostring(r))
  end
  if p.params ~= nil and type(p.params) ~= "table" then
    return format("has params that are a %s, not a table", type(p.params))
  end
  return nil
end

-- The edge label of a link's flags ("only 2, 13" / "except 2, 13"), or nil, msg. Flags are
-- { only = {...} } or { except = {...} }, or as lsys.components.proto keeps them once
-- checked, { mode = "only" | "except", list = {...}, set = {...} }.
local function flags_text (flags)
  if flags == nil then return nil end
  if type(flags) ~= "table" then return nil, format("is a %s, not a table", type(flags)) end
  if (flags.mode == "only" or flags.mode == "except") and type(flags.list) == "table" then
    flags = { [flags.mode] = flags.list }
  end
  local parts = {}
  for _, key in ipairs { "only", "except" } do
    local list = flags[key]
    if list ~= nil then
      if type(list) ~= "table" then
        return nil, format("%s is a %s, not a list of iteration numbers", key, type(list))
      end
      local nums = {}
      for i, x in ipairs(list) do
        if not (type(x) == "number" and x == math.floor(x)) then
          return nil, format("%s[%d] is %s, not an iteration number", key, i, tostring(x))
        end
        nums[i] = num(x)
      end
      parts[#parts + 1] = key .. " " .. concat(nums, ", ")
    end
  end
  for k in pairs(flags) do
    if k ~= "only" and k ~= "except" then
      return nil, format("has the key '%s' (flags are { only = {...} } or { except = {...} })",
                         tostring(k))
    end
  end
  return concat(parts, "; ")
end

--[[
Walks the p-graph depth-first from root, links in order, without recursion in Lua. Returns
the nodes in preorder (each { p, id, title, path, out = { {link, to_node, back} } }), or nil
and a message naming the path of the offending item.
]]
local function walk (root)
  local why = not_proto(root)
  if why then return nil, "the root " .. why end
  local nodes, index, seen_kind = {}, {}, {}
  local function visit (p, path)
    local n = { p = p, id = "n" .. (#nodes + 1), title = node_title(p, seen_kind), out = {},
                copies = 0 }
    n.path = path and path .. "/" .. n.title or n.title
    nodes[#nodes + 1] = n
    index[p] = n
    return n
  end
  local stack = { { node = visit(root, nil), i = 0 } }
  local onstack = { [root] = true }
  while #stack > 0 do
    local top = stack[#stack]
    local n = top.node
    top.i = top.i + 1
    local link = n.p.links[top.i]
    if link == nil then
      onstack[n.p] = nil
      stack[#stack] = nil
    else
      local where = format("%s: links[%d]", n.path, top.i)
      if type(link) ~= "table" then
        return nil, format("%s is a %s, not a link", where, type(link))
      end
      if not LINK_TYPES[link.type] then
        return nil, format("%s: type is %s, not child, branch or leaf", where,
                           type(link.type) == "string" and "'" .. link.type .. "'"
                           or tostring(link.type))
      end
      local to = link.to
      why = not_proto(to)
      if why then return nil, format("%s.to %s", where, why) end
      local label, ferr = flags_text(link.flags)
      if ferr then return nil, format("%s.flags %s", where, ferr) end
      local target, back = index[to], onstack[to] == true
      if target == nil then
        target = visit(to, n.path)
        stack[#stack + 1] = { node = target, i = 0 }
        onstack[to] = true
      end
      n.out[#n.out + 1] = { type = link.type, to = target, back = back, label = label }
    end
  end
  return nodes
end

-- Marks each node with the number of its strongly connected component (Tarjan's algorithm,
-- iterative): a link is part of a recursion when both ends share one and the component
-- has a cycle (more than one node, or a self link).
local function components (nodes)
  local num_, low, comp, stack, onst, counter, ncomp = {}, {}, {}, {}, {}, 0, 0
  for _, start in ipairs(nodes) do
    if num_[start] == nil then
      local calls = { { n = start, i = 0 } }
      counter = counter + 1
      num_[start], low[start] = counter, counter
      stack[#stack + 1], onst[start] = start, true
      while #calls > 0 do
        local f = calls[#calls]
        f.i = f.i + 1
        local e = f.n.out[f.i]
        if e then
          local w = e.to
          if num_[w] == nil then
            counter = counter + 1
            num_[w], low[w] = counter, counter
            stack[#stack + 1], onst[w] = w, true
            calls[#calls + 1] = { n = w, i = 0 }
          elseif onst[w] and num_[w] < low[f.n] then
            low[f.n] = num_[w]
          end
        else
          local v = f.n
          calls[#calls] = nil
          if #calls > 0 and low[v] < low[calls[#calls].n] then low[calls[#calls].n] = low[v] end
          if low[v] == num_[v] then
            ncomp = ncomp + 1
            local w
            repeat
              w = stack[#stack]
              stack[#stack], onst[w] = nil, nil
              comp[w] = ncomp
            until w == v
          end
        end
      end
    end
  end
  local size = {}
  for _, n in ipairs(nodes) do size[comp[n]] = (size[comp[n]] or 0) + 1 end
  for _, n in ipairs(nodes) do
    n.comp = comp[n]
    n.cyclic = size[comp[n]] > 1
    for _, e in ipairs(n.out) do
      if e.to == n then n.cyclic = true end
    end
  end
end

-- The label lines of a node: its title, its kind when it has a name (other than the kind),
-- the recursion depth when > 1, and parameters as opts.params asks.
local function label_lines (n, opts)
  local p = n.p
  local lines = { n.title }
  if p.name ~= nil and p.name ~= p.kind then lines[#lines + 1] = clean(p.kind, MAX_LABEL) end
  if p.recursion ~= nil and p.recursion > 1 then
    lines[#lines + 1] = "recursion " .. num(p.recursion)
  end
  local want, params = opts.params, p.params
  if not want or params == nil then return lines end
  local keys = {}
  if want == true then
    for k in pairs(params) do
      if type(k) == "string" and value_text(params[k]) ~= nil then keys[#keys + 1] = k end
    end
    sort(keys)
  else
    for _, k in ipairs(want) do
      if params[k] ~= nil and value_text(params[k]) ~= nil then keys[#keys + 1] = k end
    end
  end
  local max = opts.max_params or 6
  for i, k in ipairs(keys) do
    if i > max then lines[#lines + 1] = "..." break end
    lines[#lines + 1] = clean(k, 24) .. " = " .. value_text(params[k])
  end
  return lines
end

-- Checks the options of graph.dot; returns them (a table) or raises blaming the caller's
-- caller.
local function check_opts (opts, fname)
  if opts == nil then return {} end
  if type(opts) ~= "table" then
    error(format("graph.%s: options must be a table, got %s", fname, type(opts)), 3)
  end
  for k in pairs(opts) do
    if not OPTIONS[k] and not (fname == "render" and k == "dot") then
      error(format("graph.%s: unknown option '%s' (options: dot (render only), max_params, "
        .. "params)", fname, tostring(k)), 3)
    end
  end
  local pr = opts.params
  if pr ~= nil and type(pr) ~= "boolean" then
    local ok = type(pr) == "table"
    if ok then for _, k in ipairs(pr) do ok = ok and type(k) == "string" end end
    if not ok then
      error(format("graph.%s: option 'params' must be true or a list of parameter names",
        fname), 3)
    end
  end
  local mp = opts.max_params
  if mp ~= nil and (math.type(mp) ~= "integer" or mp < 0) then
    error(format("graph.%s: option 'max_params' must be a whole number >= 0", fname), 3)
  end
  return opts
end

-- The DOT text of the p-graph from root, or nil and the error message.
local function build (root, opts)
  local nodes, err = walk(root)
  if nodes == nil then return nil, err end
  components(nodes)
  local out = {
    'digraph "p-graph" {',
    "  graph [rankdir=TB, ordering=out];",
    '  node [shape=ellipse, fontname="Helvetica", fontsize=11];',
    '  edge [dir=none, fontname="Helvetica", fontsize=10];',
    '  camera [label="camera", shape=box];',
  }
  local edges = { "  camera -> n1;" }
  for _, n in ipairs(nodes) do
    local shape = M.SHAPES[n.p.kind]
    out[#out + 1] = format("  %s [label=%s%s];", n.id, dotstr(label_lines(n, opts)),
                           shape and ", shape=" .. shape or "")
    for _, e in ipairs(n.out) do
      local to = e.to.id
      if e.back then     -- the recursion's end: a dashed copy of where it returns to
        e.to.copies = e.to.copies + 1
        to = format("%sr%d", e.to.id, e.to.copies)
        local cshape = M.SHAPES[e.to.p.kind]
        out[#out + 1] = format("  %s [label=%s, style=dashed%s];", to, dotstr { e.to.title },
                               cshape and ", shape=" .. cshape or "")
      end
      local attrs = {}
      attrs[#attrs + 1] = M.LINK_STYLE[e.type]
      if n.comp == e.to.comp and n.cyclic then attrs[#attrs + 1] = M.DOUBLE end
      if e.label then attrs[#attrs + 1] = "label=" .. dotstr { e.label } end
      edges[#edges + 1] = format("  %s -> %s%s;", n.id, to,
                                 #attrs > 0 and " [" .. concat(attrs, ", ") .. "]" or "")
    end
  end
  for _, e in ipairs(edges) do out[#out + 1] = e end
  out[#out + 1] = "}\n"
  return concat(out, "\n")
end

--- The nodes of the p-graph from `root` in depth-first preorder, as the drawing sees them
-- (lsys.ui.graph lays them out): each { p = the prototype, id = "n1", ..., title, path,
-- cyclic, comp, out = { { type = link type, to = node, back = true for the link that
-- returns to the start of a recursion, label = the flags' text or nil } } }. Raises as
-- M.dot on what is not a p-graph.
function M.nodes (root)
  local nodes, err = walk(root)
  if nodes == nil then error("graph.nodes: " .. err, 2) end
  components(nodes)
  return nodes
end

--- The DOT text of the p-graph whose root prototype is `root`.
-- opts.params: true shows the parameters with a short form (numbers, ranges [v0, v1],
-- strings, booleans; "f()" marks a function), sorted by name, at most opts.max_params
-- (default 6) of them; a list of names shows those. Same graph, same bytes.
function M.dot (root, opts)
  opts = check_opts(opts, "dot")
  local text, err = build(root, opts)
  if text == nil then error("graph.dot: " .. err, 2) end
  return text
end

-- }===========================================================================================


-- {===========================================================================================
-- Rendering

--- s single-quoted for a POSIX shell (a quote inside becomes '\''). Raises on control
-- characters, which have no business in a path.
function M.quote (s)
  if type(s) ~= "string" or s:find("%c") then
    error(format("graph: refusing the path %q (control characters)", tostring(s)), 2)
  end
  return shq(s)
end

local FORMATS = { dot = "dot", gv = "dot", png = "png", svg = "svg", pdf = "pdf" }

-- A path given to a program as a file: never read as an option (-x).
local function filearg (p)
  return p:sub(1, 1) == "/" and p or "./" .. p
end

-- The text dot printed and whether it succeeded ("exit", code as io.popen's close) for
-- `dot -T<fmt> -o out in` ('prog' the program).
local function run_dot (prog, fmt, outp, inp)
  local cmd = format("%s -T%s -o %s %s 2>&1", M.quote(prog), fmt, M.quote(filearg(outp)),
                     M.quote(filearg(inp)))
  local p, perr = io.popen(cmd, "r")
  if p == nil then return "cannot start it: " .. tostring(perr), "exit", -1 end
  local msg, rerr = p:read("a")
  local _, how, code = p:close()
  if msg == nil then return "cannot read what it printed: " .. tostring(rerr), how, code end
  return msg, how, code
end

-- f(...), raising its error as graph.render's (level 3: the caller of render).
local function checked (f, ...)
  local ok, r = pcall(f, ...)
  if not ok then error("graph.render: " .. tostring(r), 3) end
  return r
end

--- Writes the p-graph from `root` to `path`: the DOT text for .dot or .gv, a picture for
-- .png, .svg or .pdf through Graphviz's `dot` (opts.dot: the program, default "dot"). The
-- file appears whole or not at all (lsys.core's writer: written aside, then renamed; dot
-- writes a new file beside `path`, its input is in a private folder under TMPDIR).
-- Returns path.
function M.render (root, path, opts)
  opts = check_opts(opts, "render")
  if type(path) ~= "string" then
    error(format("graph.render: the path must be a string, got %s", type(path)), 2)
  end
  local ext = (path:match("%.([^./]+)$") or ""):lower()
  local fmt = FORMATS[ext]
  if fmt == nil then
    error(format("graph.render: cannot write '%s': the output must be .dot, .gv, .png, .svg "
      .. "or .pdf", path), 2)
  end
  local dopts = {}
  for k, v in pairs(opts) do if k ~= "dot" then dopts[k] = v end end
  local text, err = build(root, dopts)
  if text == nil then error("graph.render: " .. err, 2) end
  if fmt == "dot" then
    checked(core.write_file, path, text)
    return path
  end
  local prog = opts.dot or "dot"
  if type(prog) ~= "string" or prog == "" then
    error("graph.render: option 'dot' must be the name or path of the dot program", 2)
  end
  M.quote(path)           -- raises on a path the shell should not see
  local out <close> = checked(core.outfile, path)
  local dir <close> = checked(core.tempdir, nil, "lsys-graph")
  local src = dir:path() .. "/graph.dot"
  checked(core.write_file, src, text)
  local msg, how, code = run_dot(prog, fmt, checked(out.name, out), src)
  if how ~= "exit" or code ~= 0 then
    if how == "exit" and (code == 127 or code == 126) then
      error("graph.render: Graphviz's dot is not installed (Debian: apt-get install "
        .. "graphviz); write .dot instead", 2)
    end
    error(format("graph.render: dot failed (%s %s) writing '%s': %s", tostring(how),
      tostring(code), path, (msg:gsub("%s+$", ""))), 2)
  end
  checked(out.commit, out)
  checked(dir.remove, dir)
  return path
end

-- }===========================================================================================

return M
