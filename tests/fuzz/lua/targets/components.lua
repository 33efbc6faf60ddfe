--- Fuzz target: component definitions (lsys.components, lua/lsys/components/): prototypes
-- of every kind with their parameters, the links between them, the expansion into an
-- i-tree, the model and scene made from it, and the DOT text of the p-graph. Its corpus is
-- tests/fuzz/corpus_components.
--
-- The bytes are the text of a table constructor (tests/fuzz/lua/luadata.lua: evaluated in
-- an empty environment):
--   { seed = S, max = N (max_instances, at most 3000), detail = D, model = false,
--     { KIND, { PARAMS }, child = LINKS, branch = LINKS, leaf = LINKS }, ... }
-- where entry 1 is the root, KIND one of lsys.components' kinds (simple, revo, horn, leaf,
-- tree, hydra, wreath, phiball, ffd, hyperpatch, world) and LINKS an entry's number, or a
-- list of numbers and { NUMBER, only = {...} } / { NUMBER, except = {...} }. Parameters
-- may be functions (code of the input); string methods that would run long in C stop the
-- input as over budget.
-- Expected errors: the input's own ("components:LINE: ..."), and lsys's naming
-- lsys.components (a prototype, a link, an instance path and parameter, a limit) or the
-- graph.
-- Checks: the i-tree's instances (depth first) have paths of their own that it:find
-- finds, each after its parent, with the children lists their parents say; it:count of
-- every name and kind is the number of instances that have it; the same seed gives the
-- same i-tree again; the model's i-tree is the expansion's, and the turtle stands on every
-- instance's frame (position, heading and up to 1e-7 of the plant's size) after its moves;
-- the DOT text, with and without parameters, is well formed (statements one a line, every
-- string closed, escapes only of quotes, backslashes and line ends), names every prototype
-- reached once, and is the same when made again. A budget stop is the input's own when it
-- has functions or stopped while evaluating, else a finding when the input takes over 2 s
-- without the fuzzer's line hook too.
local lsys = require "lsys"
local C = lsys.components
local luadata = require "tests.fuzz.lua.luadata"

local type, pairs, ipairs, error, tostring, math_type =
      type, pairs, ipairs, error, tostring, math.type
local min, max, abs, sqrt, floor = math.min, math.max, math.abs, math.sqrt, math.floor
local format = string.format

-- 3 s: the fuzzer's line hook slows lsys's Lua about 20 times
local T = { maxlen = 4096, budget = 3 }

local KINDS = {}
for k in pairs(C.KINDS) do KINDS[k] = true end

local _ENV = nil

-- --------------------------------------------------------------------------
-- The graph of an input

local function fail (fmt, ...) error(format("components: " .. fmt, ...), 0) end

-- The entries a LINKS value names: a list of { index, flags }.
local function links (v)
  if v == nil then return {} end
  if type(v) ~= "table" then v = { v } end
  local out = {}
  for _, l in ipairs(v) do
    if type(l) == "table" then
      local flags
      for k, x in pairs(l) do
        if k ~= 1 then flags = flags or {}; flags[k] = x end
      end
      out[#out + 1] = { l[1], flags }
    else
      out[#out + 1] = { l }
    end
  end
  return out
end

local hasfn

-- The prototypes of input `t`, linked; the root first.
local function graph (t)
  if type(t) ~= "table" then fail("a table expected, got %s", type(t)) end
  local protos = {}
  for i, e in ipairs(t) do
    if type(e) ~= "table" or not KINDS[e[1]] then
      fail("entry %d: { KIND, { PARAMS }, ... } expected", i)
    end
    if type(e[2]) == "table" then
      for _, v in pairs(e[2]) do if type(v) == "function" then hasfn = true end end
    end
    protos[i] = C[e[1]](e[2])
  end
  if #protos == 0 then fail("no prototype") end
  for i, e in ipairs(t) do
    for _, how in ipairs { "child", "branch", "leaf" } do
      for _, l in ipairs(links(e[how])) do
        local target = protos[l[1]]
        if target == nil then
          fail("entry %d: %s link to %s: no such entry", i, how, tostring(l[1]))
        end
        protos[i][how](protos[i], target, l[2])
      end
    end
  end
  return protos
end

-- --------------------------------------------------------------------------
-- Checks

local function dist (a, b)
  return sqrt((a[1] - b[1]) ^ 2 + (a[2] - b[2]) ^ 2 + (a[3] - b[3]) ^ 2)
end

-- The i-tree `it`: paths, find, parents, children, counts. Returns the list of paths.
local function checktree (it)
  local list = it:instances()
  local seen, paths, counts, nchildren = {}, {}, {}, {}
  for i, inst in ipairs(list) do
    local p = inst.path
    if type(p) ~= "string" then return nil, format("instance %d has no path", i) end
    if seen[p] then return nil, format("instances %d and %d have the path %s", seen[p], i, p) end
    seen[p] = i
    paths[i] = p
    local found = it:find(p)
    if found == nil or found.path ~= p then
      return nil, format("it:find('%s') gives %s", p, found and found.path or "nil")
    end
    if inst.parent ~= nil then
      local parent = list[inst.parent]
      if parent == nil or inst.parent >= i then
        return nil, format("%s comes before its parent (instance %s)", p, tostring(inst.parent))
      end
      nchildren[inst.parent] = (nchildren[inst.parent] or 0) + 1
    elseif i ~= 1 then
      return nil, format("%s has no parent and is not the first instance", p)
    end
    local proto = inst.proto
    if proto then
      counts[proto.kind] = (counts[proto.kind] or 0) + 1
      if proto.name and proto.name ~= proto.kind then
        counts[proto.name] = (counts[proto.name] or 0) + 1
      end
    end
  end
  for i, inst in ipairs(list) do
    local n = inst.children and #inst.children or 0
    if n ~= (nchildren[i] or 0) then
      return nil, format("%s has %d children, %d instances name it their parent", inst.path, n,
                         nchildren[i] or 0)
    end
    for _, c in ipairs(inst.children or {}) do
      if list[c] == nil or list[c].parent ~= i then
        return nil, format("%s lists child %s, whose parent is another", inst.path, tostring(c))
      end
    end
  end
  for name, n in pairs(counts) do
    local c = it:count(name)
    -- a name that is also a kind counts both
    if KINDS[name] then n = c end
    if c ~= n then return nil, format("it:count('%s') is %s, %d instances have it", name, c, n) end
  end
  return paths
end

-- The turtle after each instance's moves stands on its frame.
local function checkframes (m, scene)
  local size = 1
  local list = m.components.tree:instances()
  for _, inst in ipairs(list) do
    for k = 1, 3 do size = max(size, abs(inst.frame.p[k])) end
  end
  if not (size < 1e12) then return nil end      -- beyond what the comparison can say
  local tol = 1e-7 * size
  for _, inst in ipairs(list) do
    local p, H, _, U = scene:turtle(inst.at)
    local f = inst.frame
    if not (dist(p, f.p) <= tol) then
      return format("%s: the turtle is at (%g, %g, %g), the frame at (%g, %g, %g)", inst.path,
                    p[1], p[2], p[3], f.p[1], f.p[2], f.p[3])
    end
    if not (dist(H, f.H) <= 1e-7) or not (dist(U, f.U) <= 1e-7) then
      return format("%s: the turtle's heading or up is not the frame's", inst.path)
    end
  end
  return nil
end

-- The tokens of a line of DOT text: names, strings (checked: closed, escapes of quotes,
-- backslashes and line ends only, no control character) and punctuation; nil and why.
local function dottokens (line)
  local toks, i, len = {}, 1, #line
  while i <= len do
    local c = line:sub(i, i)
    if c == '"' then
      local j = i + 1
      while true do
        local d = line:sub(j, j)
        if d == "" then return nil, "a string is not closed" end
        if d == "\\" then
          local e = line:sub(j + 1, j + 1)
          if e ~= '"' and e ~= "\\" and e ~= "n" then return nil, "the escape \\" .. e end
          j = j + 2
        elseif d == '"' then break
        elseif d:find("%c") then return nil, "a control character in a string"
        else j = j + 1 end
      end
      toks[#toks + 1] = { "str", line:sub(i, j) }
      i = j + 1
    elseif c == " " then
      i = i + 1
    elseif line:sub(i, i + 1) == "->" then
      toks[#toks + 1] = { "->" }
      i = i + 2
    elseif c:find("[%[%]=,;{}]") then
      toks[#toks + 1] = { c }
      i = i + 1
    else
      local s, e = line:find("^[%w_%.%-]+", i)
      if s == nil then return nil, format("'%s' outside a string", c) end
      toks[#toks + 1] = { "id", line:sub(s, e) }
      i = e + 1
    end
  end
  return toks
end

-- One statement of the graph's body: ID [attrs]; or ID -> ID [attrs]; where attrs are
-- ID = (ID | STRING) separated by commas. Returns "node", "edge" or nil and why.
local function dotstatement (toks)
  local k = 1
  local function want (kind)
    local t = toks[k]
    if t == nil or t[1] ~= kind then return false end
    k = k + 1
    return t
  end
  if not want("id") then return nil, "a statement that does not start with a name" end
  local what = "node"
  if want("->") then
    if not want("id") then return nil, "an edge without its end" end
    what = "edge"
  end
  if want("[") then
    repeat
      if not want("id") or not want("=") then return nil, "an attribute without name =" end
      if not (want("id") or want("str")) then return nil, "an attribute without its value" end
    until not want(",")
    if not want("]") then
      return nil, format("an attribute's value followed by %s", toks[k] and
                         (toks[k][2] or toks[k][1]) or "nothing")
    end
  end
  if not want(";") or toks[k] ~= nil then return nil, "a statement that does not end in ';'" end
  return what
end

-- The DOT text: a digraph of one statement a line; its nodes name every prototype reached.
local function checkdot (text, want)
  if text:sub(1, 20) ~= 'digraph "p-graph" {\n' or not text:find("\n}\n+$") then
    return "the DOT text does not start and end as a digraph"
  end
  local nodes, n = 0, 0
  for line in text:gmatch("([^\n]*)\n") do
    n = n + 1
    if n > 1 and line ~= "}" and line ~= "" then
      local toks, why = dottokens(line)
      local what
      if toks then what, why = dotstatement(toks) end
      if not what then return format("DOT line %d: %s: %s", n, why, line) end
      if what == "node" and toks[1][2]:find("^n%d+$") then nodes = nodes + 1 end
    end
  end
  if nodes ~= want then
    return format("the DOT text has %d nodes, the graph reaches %d prototypes", nodes, want)
  end
  return nil
end

-- The prototypes reached from `root` by links.
local function reached (root)
  local seen, stack, n = { [root] = true }, { root }, 1
  while #stack > 0 do
    local p = stack[#stack]
    stack[#stack] = nil
    for _, l in ipairs(p.links) do
      if not seen[l.to] then seen[l.to] = true; n = n + 1; stack[#stack + 1] = l.to end
    end
  end
  return n
end

-- --------------------------------------------------------------------------
-- The target

local phase, last

function T.clean (err)
  if phase == "eval" or phase == "graph" then
    if err:find("^components:") then return true end
  end
  -- lsys's messages, perhaps after the file and line of the call here
  local body = err:match("^[^\n]-%.lua:%d+: (.*)$") or err
  return body:find("^lsys%.components") ~= nil or body:find("^graph%.dot: ") ~= nil or
         body:find("^phiball: ") ~= nil or body:find("^hydra: ") ~= nil or
         body:find("^wreath: ") ~= nil
end

function T.run (bytes, ctx)
  last, hasfn = nil, false
  luadata.guard(ctx)
  phase = "eval"
  local t = luadata.eval(bytes, "components")
  phase = "graph"
  local protos = graph(t)
  local root = protos[1]
  local seed = t.seed
  if seed ~= nil and type(seed) ~= "number" then seed = 1 end
  local limit = t.max
  limit = math_type(limit) and limit >= 1 and min(floor(limit), 3000) or 3000
  local opts = { seed = seed, max_instances = limit }
  local r = { root = root, protos = protos }
  last = r
  phase = "dot"
  r.dot = C.graph(root)
  r.dotp = C.graph(root, { params = true })
  r.reached = reached(root)
  r.dot2 = C.graph(root)
  phase = "expand"
  r.it = C.expand(root, opts)
  r.it2 = C.expand(root, opts)
  if t.model ~= false then
    phase = "model"
    local detail = t.detail
    detail = math_type(detail) == "integer" and detail >= 1 and detail <= 16 and detail or 1
    r.m = C.model(root, { seed = seed, max_instances = limit, detail = min(detail, 2) })
    r.scene = r.m:interpret()
  end
  phase = "done"
end

local function check (r)
  local why = checkdot(r.dot, r.reached) or checkdot(r.dotp, r.reached)
  if why then return why end
  if r.dot2 ~= r.dot then return "the DOT text differs when made again" end
  if r.it == nil then return nil end
  local paths, err = checktree(r.it)
  if paths == nil then return err end
  local again = r.it2:instances()
  if #again ~= #paths then
    return format("the same seed gives %d instances, then %d", #paths, #again)
  end
  for i, inst in ipairs(again) do
    if inst.path ~= paths[i] then
      return format("the same seed gives instance %d as %s, then %s", i, paths[i], inst.path)
    end
  end
  if r.m == nil or r.scene == nil then return nil end
  local mine = r.m.components.tree:instances()
  if #mine ~= #paths then
    return format("the model's i-tree has %d instances, the expansion %d", #mine, #paths)
  end
  for i, inst in ipairs(mine) do
    if inst.path ~= paths[i] then
      return format("the model's instance %d is %s, the expansion's %s", i, inst.path, paths[i])
    end
  end
  return checkframes(r.m, r.scene)
end

function T.after (tripped)
  luadata.unguard()
  local r = last
  last = nil
  if tripped or r == nil then return nil end
  -- a check that stopped on the way is incomplete: only what ran is checked
  if phase ~= "done" then
    if r.dot and r.dotp and r.dot2 then
      local why = checkdot(r.dot, r.reached) or checkdot(r.dotp, r.reached)
      if why then return why end
    end
    return nil
  end
  return check(r)
end

local lastbytes
function T.before (bytes) lastbytes = bytes end
local NOCTX = { trip = function () error("fuzz: over budget", 0) end }
function T.budget_clean ()
  if phase == "eval" or hasfn then return true end
  local secs = luadata.bare(3, T.run, lastbytes, NOCTX)
  luadata.unguard()
  return secs <= 2
end

function T.describe (bytes) return bytes end

-- --------------------------------------------------------------------------
-- Seeds, dictionary

T.seeds = {
  -- examples/components/sunflower.lua (fewer seeds)
  '{ seed = 1, { "tree", { name = "stalk", length = 9, radius = 0.16, tip = 0.55, n = 11,\n'
    .. '  first = 0.08, last = 0.8, angle = { 65, 40 }, branch_scale = { 1.2, 0.6 },\n'
    .. '  curvature = 10, color = 3 }, branch = 2, child = 4 },\n'
    .. '  { "horn", { name = "petiole", length = 0.9, radius = 0.05, tip = 0.7, curvature = -30,\n'
    .. '  color = 3 }, child = 3 },\n'
    .. '  { "leaf", { name = "leaf", shape = "cordate", length = 2.2, width = 1.8,\n'
    .. '  lateral = 0.25, longitudinal = 0.3, color = 2 } },\n'
    .. '  { "simple", { name = "head", primitive = "none", rotate = { 35, 0, 0 } },\n'
    .. '  child = { 5, 7, 9 } },\n'
    .. '  { "phiball", { name = "seeds", n = 50, radius = 3, open = 0, close = 25,\n'
    .. '  child_size = 0.13, translate = { 0, -2.72, 0 } }, child = 6 },\n'
    .. '  { "simple", { name = "seed", primitive = "sphere", size = { 1, 1, 1 }, color = 1 } },\n'
    .. '  { "phiball", { name = "petals", n = 34, radius = 1.3, open = 80, close = 100 },\n'
    .. '  child = 8 },\n'
    .. '  { "leaf", { name = "petal", shape = "lanceolate", length = 1.8, width = 0.45,\n'
    .. '  longitudinal = -0.2, lateral = 0.2, color = 4 } },\n'
    .. '  { "phiball", { name = "bracts", n = 21, radius = 1.1, open = 100, close = 150 },\n'
    .. '  child = 10 },\n'
    .. '  { "leaf", { name = "bract", shape = "ovate", length = 0.8, width = 0.45,\n'
    .. '  longitudinal = 0.3, color = 2 } } }',
  -- docs/components.md, "Components"
  '{ { "tree", { length = 10, n = 20, angle = { 70, 40 } }, branch = 2 },\n'
    .. '  { "tree", { name = "twig", length = 1, n = 12, angle = { 60, 30 } }, branch = 3 },\n'
    .. '  { "leaf", { length = 0.3, width = 0.15, shape = "ovate" } } }',
  -- fig. 2: C multiplies three D, D of recursion 3 linked to itself
  '{ { "simple", { name = "A", primitive = "disc" }, child = 2 },\n'
    .. '  { "hydra", { name = "C", n = 3, radius = 0.5 }, child = 3 },\n'
    .. '  { "horn", { name = "D", length = 0.4, recursion = 3, rotate = { 25, 40, 0 } }, '
    .. 'child = 3 } }',
  -- the rhododendron twig: flags pick iterations
  '{ seed = 4, { "tree", { name = "tw", n = 16, angle = { 50, 30 }, gnarl = 10 },\n'
    .. '  branch = { { 2, only = { 2, 13 } }, { 3, except = { 2, 13 } } } },\n'
    .. '  { "tree", { name = "small", length = 0.3, n = 3 } },\n'
    .. '  { "leaf", { length = 0.2, shape = "lanceolate", lateral = 0.3 } } }',
  '{ { "phiball", { n = 13, close = 120, influence = 0.5 }, child = 2 },\n'
    .. '  { "simple", { name = "seed", primitive = "sphere", size = { 0.1, 0.1, 0.1 } } } }',
  '{ { "wreath", { n = 6, radius = 0.5, open = 10, close = 200 }, child = 2 },\n'
    .. '  { "revo", { profile = { { 0.3, 0 }, { 0.5, 0.5 }, { 0.1, 1 } }, scale = 0.2 } } }',
  '{ { "world", { gravity = { 0, -1, 0 }, light = { 0, 1, 0 } }, child = 2 },\n'
    .. '  { "tree", { n = 8, gravitropism = 0.4, phototropism = 0.2, deviation = 5, '
    .. 'curvature = 30 }, branch = 3 },\n'
    .. '  { "leaf", { shape = "cordate", phototropism = 0.5, longitudinal = 0.4 } } }',
  '{ { "ffd", { fx = 2, mode = "skeleton" }, child = 2 },\n'
    .. '  { "horn", { length = 2, segments = 12, curvature = 90, twist = 30, tip = 0.2 } } }',
  '{ { "hyperpatch", { degree = { 1, 2, 1 } }, child = 2 },\n'
    .. '  { "tree", { n = 4, segments = 6 } } }',
  '{ { "tree", { n = 5, angle = { 0, 40, f = function (v, ctx) return v + ctx.i end },\n'
    .. '  branch_scale = function (ctx) return 1 - ctx.u / 2 end }, branch = 2 },\n'
    .. '  { "leaf", { width = function (ctx) return 0.1 + 0.1 * ctx.random() end } } }',
  '{ model = false, { "simple", { primitive = "cube", size = { 1, 2, 3 }, color = 2, '
    .. 'translate = { 1, 0, 0 } } } }',
  '{ { "hydra", { n = 3 }, child = { { 2, only = { 4 } } } }, { "leaf", {} } }',
  '{ { "horn", { name = "x" }, child = 1 } }',
  '{ { "tree", { n = 1e9 } } }',
  '{ { "tree", { bogus = 1 } } }',
  '{ { "leaf", { width = 0/0 } } }',
  '{ { "leaf", { width = function () return "x" end } } }',
  '{ { "leaf", { width = function () error({}) end } } }',
  '{ { "tree", { name = "a\\"b\\\\c\\nd" }, child = 2 }, { "leaf", { name = "\\0" } } }',
  '{ max = 10, { "hydra", { n = 100 }, child = 2 }, { "leaf", {} } }',
  '{ { "nothing", {} } }',
}

T.dict = { '"simple"', '"revo"', '"horn"', '"leaf"', '"tree"', '"hydra"', '"wreath"',
           '"phiball"', '"ffd"', '"hyperpatch"', '"world"', "child", "branch", "leaf", "only",
           "except", "name", "recursion", "translate", "rotate", "scale", "primitive", "size",
           "color", "texture", "profile", "length", "radius", "tip", "segments", "curvature",
           "twist", "thickness", "width", "shape", "outline", "lateral", "longitudinal",
           "phototropism", "gravitropism", "n", "first", "last", "density", "angle",
           "divergence", "deviation", "gnarl", "branch_scale", "open", "close", "child_size",
           "influence", "fx", "fy", "fz", "mode", "isolate", "degree", "moves", "box",
           "gravity", "light", "cylinder", "wind", '"cube"', '"sphere"', '"cylinder"',
           '"cone"', '"disc"', '"area"', '"tube"', '"none"', '"ovate"', '"lanceolate"',
           '"cordate"', '"linear"', '"all"', '"skeleton"', "seed", "max", "detail", "model",
           "{", "}", ",", " = ", "{ 0, 1 }", "{ 0, 0, 1 }", "{ { 0, 0 }, { 1, 1 } }",
           "function (ctx) return ctx.i end", "function (v, ctx) return v end", "ctx.random()",
           "ctx.u", "ctx.n", "ctx.depth", "0", "1", "2", "3", "-1", "0.5", "90", "180", "360",
           "1e308", "0/0", "1/0", "1e-300", "true", "false", '"\\n"', '"\\""' }

return T
