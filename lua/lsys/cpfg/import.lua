--- A cpfg model as a readable lsys model file (`lsys import`): a Lua file that returns
-- `lsys.lsystem { ... }` with the rules in lsys's syntax, the #defines of plain numbers as
-- env entries that the rules read by name, the view and palette settings, and the rules
-- with statement blocks as Lua functions. `lsys derive` of the written file gives the
-- string `lsys derive` of the .l file gives. See docs/cpfg.md.
-- @module lsys.cpfg.import
local type, pairs, ipairs, error, pcall, load, tostring, tonumber, next =
  type, pairs, ipairs, error, pcall, load, tostring, tonumber, next
local math, string, table, os, io = math, string, table, os, io
local concat, sort, unpack, pack = table.concat, table.sort, table.unpack, table.pack
local format, rep = string.format, string.rep
local cpfg = require "lsys.cpfg"
local cpp = require "lsys.cpfg.cpp"
local model = require "lsys.model"
local warning = require "lsys.warning"
local core = require "lsys.core"
local codegen = require "lsys.codegen"
local sandbox = require "lsys.sandbox"
local _ENV = nil

local M = {}

-- Numbers ---------------------------------------------------------------------------------

-- The shortest text that reads back as the float `v`, with a point or an exponent.
local function float (v)
  if v ~= v then return "(0.0/0.0)" end
  if v == math.huge then return "math.huge" elseif v == -math.huge then return "-math.huge" end
  if v == math.floor(v) and math.abs(v) < 1e15 then return format("%.1f", v) end
  local s
  for p = 1, 17 do
    s = format("%." .. p .. "g", v)
    if tonumber(s) == v then break end
  end
  if not s:find("[%.eE]") then s = s .. ".0" end
  return s
end

-- A number as lsys.cpfg writes it in the rules it translates.
local numlit = cpfg.numlit

-- Code text -------------------------------------------------------------------------------

-- `s` split into code and "strings" (Lua's %q form): a list of { text, code = bool }.
local function segments (s)
  local out, i, n = {}, 1, #s
  while i <= n do
    local q = s:find('"', i, true)
    if not q then out[#out + 1] = { s:sub(i), code = true } break end
    if q > i then out[#out + 1] = { s:sub(i, q - 1), code = true } end
    local j = q + 1
    while j <= n and s:sub(j, j) ~= '"' do j = j + (s:sub(j, j) == "\\" and 2 or 1) end
    out[#out + 1] = { s:sub(q, j), code = false }
    i = j + 1
  end
  return out
end

-- `s` with the characters inside its strings replaced by x (same length).
local function mask (s)
  local t = {}
  for i, seg in ipairs(segments(s)) do
    t[i] = seg.code and seg[1] or '"' .. rep("x", #seg[1] - 2) .. seg[1]:sub(-1)
  end
  return concat(t)
end

-- `s` with gsub(pattern, repl) applied to its code only.
local function codegsub (s, pattern, repl)
  local t = {}
  for i, seg in ipairs(segments(s)) do
    t[i] = seg.code and seg[1]:gsub(pattern, repl) or seg[1]
  end
  return concat(t)
end

-- The parentheses of `m` that group a whole expression where none are needed: around an
-- argument, a condition, the right side of an assignment (lua: `s` is Lua code, not a
-- rule string, where `,` at depth 0 is a module). Marks both of each pair in `drop`.
local function redundant (m, lua, drop)
  local n, stack, depth = #m, {}, {}
  local level = 0
  for i = 1, n do
    local c = m:sub(i, i)
    depth[i] = level
    if c == "(" then stack[#stack + 1] = i; level = level + 1
    elseif c == ")" and #stack > 0 then
      level = level - 1
      local o = stack[#stack]
      stack[#stack] = nil
      local a = o - 1
      while a >= 1 and m:sub(a, a):find("%s") do a = a - 1 end
      local b = i + 1
      while b <= n and m:sub(b, b):find("[ \t]") do b = b + 1 end
      local pc, nc = a >= 1 and m:sub(a, a) or "", b <= n and m:sub(b, b) or ""
      local word = function (w)
        return m:sub(a - #w + 1, a) == w and not m:sub(a - #w, a - #w):find("[%w_]")
      end
      local ok
      if pc == "(" or (pc == "," and depth[a] > 0) then ok = nc == ")" or nc == ","
      elseif lua and pc == "=" then ok = nc == "" and not m:sub(a - 1, a - 1):find("[=~<>]")
      elseif lua and word("if") then ok = m:sub(b, b + 4) == "then" or m:sub(b, b + 4) == "then "
      elseif lua and word("while") then ok = m:sub(b, b + 1) == "do"
      elseif not lua and pc == ":" then ok = nc == "" or m:sub(b, b + 2) == "-->"
      end
      if ok then drop[o], drop[i] = true, true end
    end
  end
end

-- `s` easier to read and the same: numbers in their shortest form (1.456, not
-- 1.4559999999999999), parentheses that group nothing left out.
local function tidy (s, lua)
  local m = mask(s)
  local n = #m
  local drop, edits = {}, {}
  redundant(m, lua, drop)
  local i = 1
  while true do
    local a, b = m:find("%d[%d%.]*", i)
    if not a then break end
    local _, e = m:find("^[eE][-+]?%d+", b + 1)
    b = e or b
    if a == 1 or not m:sub(a - 1, a - 1):find("[%w_%.]") then
      local tok = m:sub(a, b)
      local v = tonumber(tok)
      if v and math.type(v) == "float" then
        local short = float(v)
        if #short < #tok and tonumber(short) == v then edits[a] = { b, short } end
      end
    end
    i = b + 1
  end
  local out = {}
  i = 1
  while i <= n do
    local e = edits[i]
    if e then out[#out + 1] = e[2]; i = e[1] + 1
    else
      if not drop[i] then out[#out + 1] = s:sub(i, i) end
      i = i + 1
    end
  end
  return concat(out)
end

M.tidy = tidy     -- (s [, lua]): what the writer makes of a rule string or a line of Lua

-- The translations ------------------------------------------------------------------------

-- f(...) with lsys's warnings left out (they were given once when the model was loaded).
local function quietly (f, ...)
  local w = warning.warn
  warning.warn = function () end
  local r = pack(pcall(f, ...))
  warning.warn = w
  if not r[1] then error(r[2], 0) end
  return unpack(r, 2, r.n)
end

-- Everything a translation makes, as a list of texts; `sub` rewrites each.
local function describe (o, keep, sub)
  local t = {}
  local function add (...) t[#t + 1] = sub(concat({ ... }, " ")) end
  for _, k in ipairs { "axiom", "steps", "seed", "ring", "ignore", "consider", "modules",
                       "numbers", "homomorphism_seed", "start", "start_each", "end_each",
                       "finish" } do
    add(k, type(o[k]) == "function" and "function" or tostring(o[k]))
  end
  for k, d in pairs(o.max_depth or {}) do add("depth", k, tostring(d)) end
  local function rules (what, list)
    for i, r in ipairs(list or {}) do
      if type(r) == "string" then add(what, tostring(i), r)
      else
        local more = {}
        for k, x in pairs(r) do
          if k ~= 1 and k ~= 2 then more[#more + 1] = tostring(k) .. "=" .. tostring(x) end
        end
        sort(more)
        add(what, tostring(i), r[1], keep.rules[r[2]].src, concat(more, " "))
      end
    end
  end
  rules("productions", o.productions)
  rules("decomposition", o.decomposition)
  rules("homomorphism", o.homomorphism)
  local ids = {}
  for id in pairs(o.sub or {}) do ids[#ids + 1] = id end
  sort(ids)
  for _, id in ipairs(ids) do
    local s = o.sub[id]
    add("sub", tostring(id), tostring(s.ignore), tostring(s.consider),
        tostring(s.productions == o.productions))
    rules("sub" .. id, s.productions)
  end
  for _, h in ipairs(keep.hooks) do add("hook", h.kind, h.src) end
  for _, a in ipairs(keep.arrays) do
    add("array", a.key, a.name, concat(a.dims, "x"), concat(a.values or {}, ", "))
  end
  local vars = { unpack(keep.vars) }
  sort(vars)
  add("vars", concat(vars, " "), tostring(#keep.locals))
  local keys = {}
  for k, v in pairs(o.env) do
    if type(v) == "number" and not (keep.defines and keep.defines.values[k]) then
      keys[#keys + 1] = k
    end
  end
  sort(keys)
  for _, k in ipairs(keys) do add("env", k, numlit(o.env[k])) end
  return t
end

-- The translation with the #defines of numbers kept as names when it is the same as the
-- one with them expanded (the names replaced by their numbers give the same text): then
-- o, keep, true; else the expanded one, and why the names could not be kept.
local function translations (lfile, v, lopts)
  local o, keep = quietly(cpfg.options, lfile, { view = v, defines = lopts.defines,
                                                   cpp = lopts.cpp, keep = true,
                                                   environment = lopts.environment })
  local ok, o2, keep2 = pcall(quietly, cpfg.options, lfile,
                              { view = v, defines = lopts.defines, keep = true, names = true,
                                environment = lopts.environment })
  if not ok then        -- (no reason to give when there is no #define to keep)
    local text = cpp.readfile(lfile) or ""
    return o, keep, false, text:find("#%s*[di][en][fc]") and
                           "the built-in preprocessor reads the file otherwise" or nil
  end
  local d = keep2.defines
  if not next(d.values) then return o, keep, false end
  if d.conflict then
    return o, keep, false, format("%s is defined again with another value", d.conflict)
  end
  local function id (s) return s end
  local function numbers (s)
    for _, n in ipairs(d.order) do
      local lit = numlit(d.values[n])
      s = s:gsub("E%." .. n .. "%f[^%w_]", lit):gsub("%f[%w_]" .. n .. "%f[^%w_]", lit)
    end
    return s
  end
  local a, b = describe(o, keep, id), describe(o2, keep2, numbers)
  local same = #a == #b
  for i = 1, #a do if a[i] ~= b[i] then same = false break end end
  if not same then return o, keep, false, "a name is used where cpfg reads no number" end
  return o2, keep2, true
end

-- Paths -----------------------------------------------------------------------------------

local function cwd ()
  local d = os.getenv("PWD")
  if d and d:sub(1, 1) == "/" then return d end
  local p = io.popen("pwd")
  d = p and p:read("l")
  if p then p:close() end
  return d or "/"
end

-- The segments of the absolute path of `p`, without . and dir/.. (as the words read).
local function absolute (p)
  if p:sub(1, 1) ~= "/" then p = cwd() .. "/" .. p end
  local segs = {}
  for seg in p:gmatch("[^/]+") do
    if seg == ".." then segs[#segs] = nil
    elseif seg ~= "." then segs[#segs + 1] = seg end
  end
  return segs
end

-- The folder `to` relative to the folder `from`: "" when the same, nil when they share
-- nothing but the root.
local function relative (from, to)
  local a, b = absolute(from), absolute(to)
  local k = 0
  while k < #a and k < #b and a[k + 1] == b[k + 1] do k = k + 1 end
  if k == 0 and (#a > 0 or #b > 0) then return nil end
  local parts = {}
  for _ = k + 1, #a do parts[#parts + 1] = ".." end
  for i = k + 1, #b do parts[#parts + 1] = b[i] end
  return concat(parts, "/")
end

local function base (p) return p:match("([^/]*)$") end

-- Writing ---------------------------------------------------------------------------------

local LIB = { produce = "lsys.produce", nproduce = "lsys.nproduce", ran = "lsys.ran",
              nran = "lsys.nran", func = "func", _srand = "lsys.srand" }

-- A line of a translated function with the written file's names: env for E, cpfg for
-- the helpers H, lsys.produce, math.floor, ..., the rule's own table for L.
local function rename (C, line, L)
  line = codegsub(line, "%f[%w_]H%.([%a_][%w_]*)", function (name)
    if LIB[name] then
      if name == "func" then C.usesfunc = true end
      return LIB[name]
    end
    if name:sub(1, 1) == "_" and cpfg.helpers[name] ~= nil then
      C.usescpfg = true
      return "cpfg." .. name
    end
    local b = model.BUILTIN[name]
    if b ~= nil and math[name] == b then return "math." .. name end
    error(format("%s: cannot import: a statement block calls %s, which lsys import does not "
                 .. "write yet", C.lfile, name), 0)
  end)
  line = codegsub(line, "%f[%w_]E%.", function () C.usesenv = true return "env." end)
  if L and C.lname[L] then line = codegsub(line, "%f[%w_]L%.", C.lname[L] .. ".") end
  return line
end

-- The parameters and the body lines of a translated function's source (lsys.cpfg.options
-- keep), indented by `ind`.
local function body (C, src, ind, L)
  -- a newline in a string (%q writes it as \ and a newline) as \n: one statement a line
  local t = {}
  for i, seg in ipairs(segments(src)) do
    t[i] = seg.code and seg[1] or seg[1]:gsub("\\\n", "\\n")
  end
  src = concat(t)
  local lines = {}
  for l in (src .. "\n"):gmatch("([^\n]*)\n") do lines[#lines + 1] = l end
  local args = lines[2]:match("^return function %((.*)%)$")
  local loops = false
  for i = 4, #lines - 1 do
    if lines[i]:find("%f[%w_]_n%f[^%w_]") then loops = true end
  end
  local out = {}
  for i = 3, #lines - 1 do        -- lines[3] is `local _n = 0`, the count of loop rounds
    if i > 3 or loops then out[#out + 1] = ind .. tidy(rename(C, lines[i]:sub(3), L), true) end
  end
  for p in args:gmatch("[^,%s]+") do
    if C.taken[p] then
      error(format("%s: cannot import: a rule's parameter is named %s, a name the written "
                   .. "file uses", C.lfile, p), 0)
    end
  end
  return args, out
end

local quote = codegen.string      -- every string of the written file, on one line

-- A value of the view as Lua text on one line, or nil when it is long or nested deeply.
local function inline (x, depth)
  local t = type(x)
  if t == "number" then return math.type(x) == "integer" and tostring(x) or float(x) end
  if t == "string" then return quote(x) end
  if t == "boolean" then return tostring(x) end
  if t ~= "table" or depth > 2 then return nil end
  local keys, n = {}, #x
  for k in pairs(x) do keys[#keys + 1] = k end
  if #keys == 0 then return "{}" end
  local parts = {}
  if #keys == n then
    for i = 1, n do parts[i] = inline(x[i], depth + 1) if not parts[i] then return nil end end
  else
    sort(keys, function (a, b)
      if type(a) == type(b) then return a < b end
      return type(a) == "number"
    end)
    for i, k in ipairs(keys) do
      local v = inline(x[k], depth + 1)
      if not v then return nil end
      parts[i] = codegen.key(k) .. " = " .. v
    end
  end
  local s = "{ " .. concat(parts, ", ") .. " }"
  return #s <= 80 and s or nil
end

local viewkey = codegen.key

-- A list of rules: rule strings and { pattern, function } pairs; `head` is what comes
-- before the table ("productions ="), `close` what ends it ("},").
local function rulelist (C, W, head, list, ind, close)
  W("%s%s {", ind, head)
  for _, r in ipairs(list) do
    if type(r) == "string" then
      W("%s  %s,", ind, quote(tidy(r)))
    else
      local kept = C.keep.rules[r[2]]
      local args, lines = body(C, kept.src, ind .. "    ", kept.L)
      W("%s  { %s, function (%s)", ind, quote(r[1]), args)
      for _, l in ipairs(lines) do W("%s", l) end
      local more = {}          -- other fields of the rule (none yet), as they are
      for k, x in pairs(r) do
        if k ~= 1 and k ~= 2 then
          local v = inline(x, 0)
          if not v then error(format("cannot import: a rule's field %s", tostring(k)), 0) end
          more[#more + 1] = format("%s = %s", viewkey(k), v)
        end
      end
      sort(more)
      W("%s  end%s },", ind, #more > 0 and ", " .. concat(more, ", ") or "")
    end
  end
  W("%s%s", ind, close or "},")
end

-- One entry of the view table (multi-line when it does not fit on one).
local function viewentry (W, ind, k, x)
  local s = inline(x, 0)
  if s then W("%s%s = %s,", ind, viewkey(k), s) return end
  if type(x) ~= "table" then
    error(format("cannot import: the view's %s is a %s", tostring(k), type(x)), 0)
  end
  W("%s%s = {", ind, viewkey(k))
  local keys = {}
  for kk in pairs(x) do keys[#keys + 1] = kk end
  sort(keys, function (a, b)
    if type(a) == type(b) then return a < b end
    return type(a) == "number"
  end)
  local list = #keys == #x
  for _, kk in ipairs(keys) do
    if list then
      local v = inline(x[kk], 1)
      if v then W("%s  %s,", ind, v) else viewentry(W, ind .. "  ", kk, x[kk]) end
    else
      viewentry(W, ind .. "  ", kk, x[kk])
    end
  end
  W("%s},", ind)
end

-- The view: its files (contours, surfaces, functions, palette) found from where the
-- written file is, through lsys.here().
local function viewtable (C, W)
  local v = C.view
  if not v then return end
  W("  view = {")
  local files = false
  for _, k in ipairs { "contours", "surfaces", "textures", "functions", "palette" } do
    if v[k] ~= nil then files = true end
  end
  if files and v.dir then
    local rel = relative(C.outdir, v.dir)
    if rel == "" then W("    dir = lsys.here(),    -- the files below are read from here")
    elseif rel then W("    dir = lsys.here() .. %s,", quote("/" .. rel))
    else W("    dir = %s,", quote(v.dir)) end
  end
  local keys = {}
  for k in pairs(v) do if k ~= "dir" then keys[#keys + 1] = k end end
  sort(keys)
  for _, k in ipairs(keys) do
    local x = v[k]
    if k == "palette" and C.palette then x = C.palette end
    if k == "functions" and type(x) == "table" and not C.exactfuncs then
      x = cpfg.cpfg_functions(x)      -- as the loaded model computes them
    end
    viewentry(W, "    ", k, x)
  end
  W("  },")
end

-- The first /* comment */ of the .l file, as comment lines (at most 12).
local function leadcomment (lfile)
  local text = cpp.readfile(lfile)
  local c = text and text:match("^%s*/%*(.-)%*/")
  local out = {}
  if not c then return out end
  for l in (c .. "\n"):gmatch("([^\n]*)\n") do
    l = l:gsub("^%s*%*?%s?", ""):gsub("%s+$", "")
    if l ~= "" or #out > 0 then out[#out + 1] = l end
  end
  while #out > 0 and out[#out] == "" do out[#out] = nil end
  while #out > 12 do out[#out] = nil end
  return out
end

-- Whether `name` appears in the texts `list` (C.texts: the rules and the functions of the
-- translation; C.strings: the rule strings and the axiom).
local function used (list, name)
  local pat = "%f[%w_]" .. name .. "%f[^%w_]"
  for _, s in ipairs(list) do if s:find(pat) then return true end end
  return false
end

-- The comment at the top of the written file.
local function header (C, W)
  local from = { }
  if C.vfile then from[#from + 1] = "view " .. base(C.vfile) end
  if C.palfile then
    from[#from + 1] = (C.palfile:match("%.mat$") and "materials " or "colour map ")
                      .. base(C.palfile)
  end
  -- file names and the .l file's comment are text from elsewhere: codegen.comment keeps
  -- each on its line (a carriage return in one would end the comment and start code)
  local what = format("%s: the cpfg model %s%s,", base(C.out), base(C.lfile),
                      #from > 0 and " (" .. concat(from, ", ") .. ")" or "")
  if #what > 69 then
    W("%s", codegen.comment(what:match("^(.-) %(") or what))
    what = what:match("^.- (%(.*)$") or ""
  end
  W("%s", codegen.comment((what ~= "" and what .. " " or "") .. "imported by `lsys import`."))
  W("%s", codegen.comment(format("`lsys derive %s` gives the string `lsys derive %s` gives.",
                                 base(C.out), base(C.lfile))))
  for _, l in ipairs(C.comment) do W("%s", codegen.comment(l)) end
  if C.named and C.defines > 0 then
    W("-- The #defines of numbers are env entries, read by name (--set NAME=VALUE changes one).")
  elseif C.why then
    W("-- The #defines are written as their numbers: %s.", C.why)
  end
  if C.nfuncs > 0 then
    W("-- Rules with statement blocks are Lua functions (cpfg's helpers are lsys.cpfg.helpers);")
    W("-- cpfg's variables are in env.")
  end
  W("local lsys = require \"lsys\"")
  if C.usescpfg then W("local cpfg = require(\"lsys.cpfg\").helpers") end
  W("")
end

-- env: the #defines kept as names, cpfg's variables, the helpers rule strings call.
local function envtable (C, W)
  local o, d = C.o, C.named and C.keep.defines
  local vars = {}
  for _, k in ipairs(C.keep.vars) do vars[k] = true end
  local lines = {}
  local function E (fmt, ...) lines[#lines + 1] = format(fmt, ...) end
  C.defines = 0
  if d then        -- those the rules read (the others gave the steps, seed or depths)
    for _, n in ipairs(d.order) do
      local note = d.notes[n]
      if used(C.texts, n) then
        C.defines = C.defines + 1
        E("  %s = %s,%s", codegen.key(n), float(d.values[n]),
          note and note ~= "" and "  " .. codegen.comment(note) or "")
      end
    end
  end
  local keys, helpers = {}, {}
  for k, v in pairs(o.env) do
    if type(v) == "number" and not (d and d.values[k]) and not vars[k] then
      if (k ~= "Q" and k ~= "Z") or used(C.texts, k) then keys[#keys + 1] = k end
    elseif type(v) == "function" and used(C.strings, k) then
      helpers[#helpers + 1] = k
    end
  end
  sort(keys)
  for _, k in ipairs(keys) do
    E("  %s = %s,%s", k, float(o.env[k]), k == "Z" and "  -- cpfg's derivation length" or "")
  end
  local vs = { unpack(C.keep.vars) }
  sort(vs)
  if #vs > 0 then
    E("  -- the variables of the Start, StartEach, EndEach and End blocks")
    for _, k in ipairs(vs) do E("  %s = 0.0,", k) end
  end
  sort(helpers)
  if #helpers > 0 then C.usescpfg = true end
  for _, k in ipairs(helpers) do E("  %s = cpfg.%s,", k, k) end
  C.env = #lines > 0 or C.usesenv
  if not C.env then return end
  W("local env = {")
  for _, l in ipairs(lines) do W("%s", l) end
  W("}")
  W("")
end

-- The tables of the rule functions' own variables, and `reset`, which starts a derivation
-- as cpfg does: the variables at 0, the arrays at their first values.
local function resetfn (C, W)
  local tables = {}
  for _, L in ipairs(C.keep.locals) do
    if C.lname[L] then tables[#tables + 1] = C.lname[L] end
  end
  if #tables > 0 then
    W("-- the variables each rule function keeps between uses (as in cpfg)")
    W("local %s = %s", concat(tables, ", "), rep("{}", #tables, ", "))
    W("")
  end
  local arrays = C.keep.arrays
  if #arrays > 0 then
    W("-- a cpfg array: its values from v[0], its dimensions in dims (cpfg._aget, cpfg._aset)")
    W("local function array (name, dims, values)")
    W("  local a, size = { name = name, dims = dims, v = {} }, 1")
    W("  for _, d in ipairs(dims) do size = size * d end")
    W("  for i = 0, size - 1 do a.v[i] = values[i + 1] or 0.0 end")
    W("  return a")
    W("end")
    W("")
  end
  local vars = { unpack(C.keep.vars) }
  sort(vars)
  if #vars + #tables + #arrays == 0 and not C.resetQ then return false end
  if #vars + #arrays > 0 or C.resetQ then C.usesenv = true end
  W("-- every derivation starts afresh: variables at 0, arrays at their first values")
  W("local function reset ()")
  if #vars > 0 then
    local q = {}
    for i, k in ipairs(vars) do q[i] = quote(k) end
    W("  for _, k in ipairs { %s } do env[k] = 0.0 end", concat(q, ", "))
  end
  if C.resetQ then W("  env.Q = 0.0") end
  if #tables > 0 then
    W("  for _, t in ipairs { %s } do for k in pairs(t) do t[k] = nil end end",
      concat(tables, ", "))
  end
  for _, a in ipairs(arrays) do
    local vals = {}
    for i, x in ipairs(a.values or {}) do vals[i] = tidy(rename(C, x), true) end
    W("  env.%s = array(%s, { %s }, { %s })", a.key, quote(a.name), concat(a.dims, ", "),
      concat(vals, ", "))
  end
  W("end")
  W("reset()")
  W("")
  return true
end

-- The hooks of one kind (start, start_each, end_each, finish) as one function.
local function hookfn (C, W, key, kind, reset)
  local srcs = {}
  for _, h in ipairs(C.keep.hooks) do if h.kind == kind then srcs[#srcs + 1] = h.src end end
  if #srcs == 0 and not reset then return end
  W("  %s = function ()", key)
  if reset then W("    reset()") end
  for _, src in ipairs(srcs) do
    local _, lines = body(C, src, #srcs > 1 and "      " or "    ")
    if #srcs > 1 then W("    do") end
    for _, l in ipairs(lines) do W("%s", l) end
    if #srcs > 1 then W("    end") end
  end
  W("  end,")
end

-- The names of the rule functions' own tables (L1, L2, ... in the order written).
local function lnames (C)
  local n = 0
  local function visit (list)
    for _, r in ipairs(list or {}) do
      local k = type(r) == "table" and C.keep.rules[r[2]]
      if k and not C.lname[k.L] then
        local uses = false
        for _, seg in ipairs(segments(k.src)) do
          if seg.code and seg[1]:find("%f[%w_]L%.") then uses = true end
        end
        if uses then
          n = n + 1
          C.lname[k.L] = "L" .. n
          C.taken["L" .. n] = true
        end
      end
    end
  end
  local o = C.o
  visit(o.productions)
  visit(o.decomposition)
  visit(o.homomorphism)
  local ids = {}
  for id in pairs(o.sub or {}) do ids[#ids + 1] = id end
  sort(ids)
  for _, id in ipairs(ids) do visit(o.sub[id].productions) end
end

-- Every text of the translation (for `used`), and the rule strings and axiom alone.
local function texts (o, keep)
  local t, strings = { o.axiom }, { o.axiom }
  local function add (list)
    for _, r in ipairs(list or {}) do
      if type(r) == "string" then strings[#strings + 1] = r end
      t[#t + 1] = type(r) == "string" and r or keep.rules[r[2]].src
    end
  end
  add(o.productions)
  add(o.decomposition)
  add(o.homomorphism)
  for _, s in pairs(o.sub or {}) do add(s.productions) end
  for _, h in ipairs(keep.hooks) do t[#t + 1] = h.src end
  for _, a in ipairs(keep.arrays) do t[#t + 1] = concat(a.values or {}, ", ") end
  return t, strings
end

-- The sub-L-systems (the main one among them only when a rule calls one: `?(`).
local function subtable (C, W)
  local o = C.o
  if not C.subs then return end
  local ids = {}
  for id in pairs(o.sub or {}) do ids[#ids + 1] = id end
  sort(ids)
  W("  sub = {")
  for _, id in ipairs(ids) do
    local s = o.sub[id]
    local skip = s.ignore and format(", ignore = %s", quote(s.ignore)) or
                 s.consider and format(", consider = %s", quote(s.consider)) or ""
    if s.productions == o.productions then
      W("    [%d] = { productions = productions%s },   -- the main L-system", id, skip)
    else
      rulelist(C, W, format("[%d] = { productions =", id), s.productions, "    ",
               "}" .. skip .. " },")
    end
  end
  W("  },")
end

-- The options modeltable writes by name (`name` is the .l file's: left out).
local WRITTEN = {}
for k in ([[axiom steps seed numbers ring ignore consider modules env name start start_each
  end_each finish productions decomposition homomorphism max_depth homomorphism_seed sub
  view]]):gmatch("%S+") do WRITTEN[k] = true end

-- The lsys.lsystem { ... } call.
local function modeltable (C, W, reset)
  local o = C.o
  local selfsub = false
  for _, s in pairs(o.sub or {}) do
    if s.productions == o.productions then selfsub = true end
  end
  local localprods = selfsub and C.subs
  if localprods then
    rulelist(C, W, "local productions =", o.productions, "", "}")
    W("")
  end
  W("%s lsys.lsystem {", C.usesfunc and "m =" or "return")
  if o.modules then
    W("  modules = %s,   -- cpfg's predecessors of several letters, one module each",
      quote(o.modules))
  end
  W("  axiom = %s,", quote(tidy(o.axiom)))
  W("  steps = %s,", tostring(math.tointeger(o.steps) or o.steps))
  if o.seed then W("  seed = %s,", tostring(math.tointeger(o.seed) or o.seed)) end
  W("  random = \"cpfg\",   -- cpfg's random numbers in cpfg's order, as lsys.cpfg.load")
  if C.envnone then
    W("  environment = false,   -- no environment: ?E keep their values, as cpfg without -e")
  end
  if o.numbers then
    W("  numbers = %s,   -- parameters stored as cpfg stores them", quote(o.numbers))
  end
  if o.ring then W("  ring = true,") end
  if o.ignore then W("  ignore = %s,", quote(o.ignore)) end
  if o.consider then W("  consider = %s,", quote(o.consider)) end
  W("  env = env,%s", "\0")   -- dropped when env is empty (envtable decides, after)
  hookfn(C, W, "start", "start", reset)
  hookfn(C, W, "start_each", "starteach")
  hookfn(C, W, "end_each", "endeach")
  hookfn(C, W, "finish", "end")
  if localprods then W("  productions = productions,")
  else rulelist(C, W, "productions =", o.productions, "  ") end
  if o.decomposition then rulelist(C, W, "decomposition =", o.decomposition, "  ") end
  if o.homomorphism then rulelist(C, W, "homomorphism =", o.homomorphism, "  ") end
  if o.max_depth then
    local t = {}
    for _, k in ipairs { "decomposition", "homomorphism" } do
      if o.max_depth[k] then t[#t + 1] = format("%s = %d", k, o.max_depth[k]) end
    end
    W("  max_depth = { %s },", concat(t, ", "))
  end
  if o.homomorphism_seed then W("  homomorphism_seed = %d,", o.homomorphism_seed) end
  subtable(C, W)
  viewtable(C, W)
  local more = {}              -- other options of the translation (none yet), as they are
  for k, x in pairs(o) do
    if not WRITTEN[k] then
      local v = inline(x, 0)
      if not v then error(format("cannot import: the option %s", tostring(k)), 0) end
      more[#more + 1] = format("  %s = %s,", viewkey(k), v)
    end
  end
  sort(more)
  for _, l in ipairs(more) do W("%s", l) end
  W("}")
  if C.usesfunc then W("return m") end
end

--- The text of the lsys model file for the cpfg model `lfile` (and view file `vfile`).
-- opts: colormap or materials, defines, cpp, environment (as for lsys.cpfg.load), out
-- (the path the text will be written to: the view's files are found from there; default
-- lfile with .lua). Raises the loader's "file:line: message" errors, and "cannot import: ..." for
-- what the writer does not handle.
-- What a written file may reach when it loads (codegen.check): lsys.lsystem and
-- lsys.here, the helpers' table, and the base functions of its top-level code.
local CHECK = {
  modules = { lsys = true, ["lsys.cpfg"] = true },
  calls = { ["lsys.lsystem"] = true, ["lsys.here"] = true },
  globals = { ipairs = ipairs, pairs = pairs, type = type, tostring = tostring,
              tonumber = tonumber, error = error, math = sandbox.BUILTIN.math,
              string = sandbox.BUILTIN.string, table = sandbox.BUILTIN.table },
}

function M.source (lfile, vfile, opts)
  if type(lfile) ~= "string" then error("lsys.cpfg.import: a file name expected", 2) end
  opts = opts or {}
  if opts.environment ~= nil and opts.environment ~= "none" then
    error("cannot import: an environment (the file would not run the program); load the model "
          .. "with lsys.cpfg.load and its environment option instead", 0)
  end
  local lopts = { colormap = opts.colormap, materials = opts.materials,
                  defines = opts.defines, cpp = opts.cpp, environment = opts.environment }
  local m = cpfg.load(lfile, vfile, lopts)           -- its errors, its warnings (once)
  local pal = opts.colormap or opts.materials
  local out = opts.out or (lfile:gsub("%.l$", "") .. ".lua")
  local v = m.view            -- the view file's, or cpfg's defaults the loader fills in
  local o, keep, named, why = translations(lfile, v, lopts)
  local C = { lfile = lfile, vfile = vfile, out = out, outdir = cpp.dirof(out), o = o,
              keep = keep, named = named, why = why, view = v, lname = {},
              taken = { env = true, cpfg = true, lsys = true, math = true, func = true,
                        m = true, array = true, reset = true, productions = true },
              comment = leadcomment(lfile), envnone = opts.environment == "none" }
  if pal then
    C.palfile = pal:sub(1, 1) == "/" and pal or cpp.dirof(lfile) .. "/" .. pal
    local rel = relative(v.dir, cpp.dirof(C.palfile))
    C.palette = rel == "" and base(C.palfile) or rel and rel .. "/" .. base(C.palfile)
                or "/" .. concat(absolute(C.palfile), "/")
  end
  C.texts, C.strings = texts(o, keep)
  -- the sub-L-systems are written when there is one besides the main L-system, or when a
  -- rule calls one (`?(`)
  for _, s in pairs(o.sub or {}) do if s.productions ~= o.productions then C.subs = true end end
  for _, t in ipairs(C.texts) do if t:find("?(", 1, true) then C.subs = true end end
  -- func(id, x) in a statement block calls the model's functions: `m` is the model
  for _, t in ipairs(C.texts) do if t:find("%f[%w_]H%.func%(") then C.usesfunc = true end end
  lnames(C)
  C.nfuncs = 0
  for _, t in ipairs(C.texts) do if t:find("^local E, H, L = ") then C.nfuncs = C.nfuncs + 1 end end
  for _, h in ipairs(keep.hooks) do if h.src:find("E%.Q%s*=[^=]") then C.resetQ = true end end
  for _, t in ipairs(C.texts) do if t:find("E%.Q%s*=[^=]") then C.resetQ = true end end
  -- the body first (it finds what the head must declare), then the head
  local lines = {}
  local function W (fmt, ...) lines[#lines + 1] = format(fmt, ...) end
  local reset = resetfn(C, W)
  if C.usesfunc then
    W("local m")
    W("local function func (id, x) return m._func(id, x) end   -- the view's functions")
    W("")
  end
  modeltable(C, W, reset)
  local top = {}
  local function T (fmt, ...) top[#top + 1] = format(fmt, ...) end
  envtable(C, T)
  for i = #lines, 1, -1 do
    if lines[i]:find("\0", 1, true) then
      if C.env then lines[i] = lines[i]:gsub("%z", "") else table.remove(lines, i) end
    end
  end
  local head = {}
  header(C, function (fmt, ...) head[#head + 1] = format(fmt, ...) end)
  for _, l in ipairs(top) do head[#head + 1] = l end
  for _, l in ipairs(lines) do head[#head + 1] = l end
  local text = concat(head, "\n") .. "\n"
  -- the file reaches only what it was written to reach (no text of the .l file became
  -- code), then it must load: a model made from it, here
  local ok0, cerr = pcall(codegen.check, text, base(out), CHECK)
  if not ok0 then error("cannot import: " .. cerr, 0) end
  local chunk, err = load(text, "@" .. out, "t")
  if not chunk then error("cannot import: the written file does not compile: " .. err, 0) end
  local ok, r = pcall(chunk)
  if not ok then error("cannot import: the written file does not load: " .. tostring(r), 0) end
  -- the positional functions the file's view gives must be the loaded model's
  for i = 1, #(m._funclist or {}) do
    for k = 0, 20 do
      local a, b = m._func(i, k / 20), r._func(i, k / 20)
      if a ~= b then
        error(format("cannot import: the written file's positional function %d gives %.17g "
                     .. "at %g, the loaded model's %.17g", i, b, k / 20, a), 0)
      end
    end
  end
  return text
end

--- Writes the lsys model file for the cpfg model `lfile` (with `vfile`) to `out`,
-- atomically (written aside, then renamed); opts as for `source`. Returns `out`.
function M.write (lfile, vfile, out, opts)
  if type(out) ~= "string" then error("lsys.cpfg.import: an output file name expected", 2) end
  local o = {}
  for k, v in pairs(opts or {}) do o[k] = v end
  o.out = out
  local text = M.source(lfile, vfile, o)
  local ok, err = pcall(core.write_file, out, text)
  if not ok then error(format("cannot write '%s': %s", out, tostring(err)), 0) end
  return out
end

return M
