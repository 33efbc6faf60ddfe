--- The C preprocessor pass that cpfg runs over an L-system file: the system `cpp` when
-- present (as cpfg runs vlabcpp), else a built-in one for the common directives.
-- Both give a list of lines { file =, line =, text = }, each naming where it came from.
-- @module lsys.cpfg.cpp
local ipairs, pairs, tonumber, tostring, error, pcall, require = ipairs, pairs,
  tonumber, tostring, error, pcall, require
local math = math
local concat, insert, remove, sort = table.concat, table.insert, table.remove, table.sort
local format = string.format
local io, os = io, os
local _ENV = nil

local M = {}

local function readfile (path)
  local f, err = io.open(path, "rb")
  if not f then return nil, err end
  local s = f:read("a")
  f:close()
  if s == nil then return nil, path .. ": cannot be read" end
  return s
end
M.readfile = readfile

local function dirof (path)
  local d = path:match("^(.*)/[^/]*$")
  if d == nil then return "." end
  if d == "" then return "/" end
  return d
end
M.dirof = dirof

-- One shell word: the text in single quotes, a quote inside as '\''; nothing in it is
-- interpreted by the shell.
local function shq (s) return "'" .. s:gsub("'", "'\\''") .. "'" end

-- The directives of the preprocessor. A line whose first non-blank character is '#'
-- followed by anything else (a width module `#(0.06)` starting a continued successor,
-- `#x`) is text for vlab's preprocessor, which warns and keeps it; cpfg then reads it.
local DIRECTIVES = {}
for d in ("define undef include if ifdef ifndef elif else endif error pragma line warning"
          .. " ident"):gmatch("%a+") do
  DIRECTIVES[d] = true
end

local function isdirective (text)
  local rest = text:match("^%s*#%s*(.*)$")
  if rest == nil then return false end
  if rest == "" or rest:find("^%d") or rest:find("^/[*/]") then return true end  -- # N "f"
  local name = rest:match("^[%a_][%w_]*")
  return name ~= nil and DIRECTIVES[name] == true
end

-- A name no model uses: it stands for the '#' of a text line while the system cpp runs.
local HASH = "__lsys_cpp_hash__"

local have_cpp
local function system_cpp ()
  if have_cpp == nil then
    local ok = os.execute("command -v cpp >/dev/null 2>&1")
    have_cpp = ok == true
  end
  return have_cpp
end

-- Splits cpp's output at its line markers (# N "file" flags) into located lines.
-- `base`: the folder cpp ran in, for the relative names of included files.
local function marked (out, main, base)
  local lines, file, n = {}, main, 1
  for text in (out .. "\n"):gmatch("([^\n]*)\n") do
    local ln, f = text:match('^#%s*(%d+)%s+"(.-)"')
    if ln then
      n, file = tonumber(ln), f
      if file:sub(1, 1) == "<" then file = main
      elseif base and file:sub(1, 1) ~= "/" then file = base .. "/" .. file end
    else
      lines[#lines + 1] = { file = file, line = n, text = text }
      n = n + 1
    end
  end
  while #lines > 0 and lines[#lines].text == "" do remove(lines) end
  return lines
end

--- Runs the system C preprocessor on `path` with `defines` ({ NAME = value }); returns
-- the located lines, or nil and cpp's first message.
function M.system (path, defines)
  local args = { "cpp", "-x", "c", "-undef", "-nostdinc", "-w" }
  local names = {}
  for k in pairs(defines or {}) do names[#names + 1] = k end
  sort(names)
  for _, k in ipairs(names) do args[#args + 1] = shq("-D" .. k .. "=" .. tostring(defines[k])) end
  -- a name that starts with '-' (a vlab specifications file can say anything) must not
  -- reach cpp as an option such as -o FILE
  -- text lines starting with '#' (see DIRECTIVES) would be errors for cpp: the file
  -- goes through stdin with a name in their '#', cpp running in the file's folder so
  -- that #include "x" finds the same files
  local text = readfile(path)
  local protect = false
  if text then
    for line in text:gmatch("[^\n]+") do
      if line:find("^%s*#") and not isdirective(line) then protect = true; break end
    end
  end
  local cmd, tmp
  if protect then
    tmp = os.tmpname()
    local f = io.open(tmp, "wb")
    local lines = {}
    for line in (text .. "\n"):gmatch("([^\n]*)\n") do
      if line:find("^%s*#") and not isdirective(line) then
        line = line:gsub("#", HASH, 1)
      end
      lines[#lines + 1] = line
    end
    f:write(concat(lines, "\n"))
    f:close()
    args[#args + 1] = "-"
    cmd = "cd " .. shq(dirof(path)) .. " && " .. concat(args, " ") .. " <" .. shq(tmp)
  else
    args[#args + 1] = shq(path:sub(1, 1) == "-" and "./" .. path or path)
    cmd = concat(args, " ")
  end
  local errf = os.tmpname()
  local p = io.popen(cmd .. " 2>" .. shq(errf), "r")
  local out = p and p:read("a") or ""
  local ok = p and p:close()
  local msg = readfile(errf) or ""
  os.remove(errf)
  if tmp then
    os.remove(tmp)
    out = out:gsub(HASH, "#")
    msg = msg:gsub("<stdin>", function () return path end)
  end
  if not ok then
    local first = msg:match("[^\n]*error:[^\n]*") or msg:match("[^\n]+") or "cpp failed"
    first = first:gsub("^([^:]+:%d+):%d+:", "%1:"):gsub(" fatal error:", ""):gsub(" error:", "")
    return nil, first
  end
  -- cpp turns a leading tab into a space; cpfg reads a line starting with a tab as the
  -- continuation of the one before, so the tabs come back from the source lines
  local lines, sources = marked(out, path, tmp and dirof(path)), {}
  for _, l in ipairs(lines) do
    local src = sources[l.file]
    if src == nil then
      src = {}
      for s in ((readfile(l.file) or "") .. "\n"):gmatch("([^\n]*)\n") do src[#src + 1] = s end
      sources[l.file] = src
    end
    local orig = src[l.line]
    if orig and orig:sub(1, 1) == "\t" and l.text:find("^%s") then
      l.text = "\t" .. l.text:gsub("^%s+", "")
    end
  end
  return lines
end

-- The built-in preprocessor ----------------------------------------------------------

local function fail (file, line, fmt, ...)
  error({ cpfg = true, msg = format("%s:%d: " .. fmt, file, line, ...) }, 0)
end

-- cpfg's number literals (lsys.cpfg.parse's etok)
local NUMBER = { "^%d+%.%d*[eE][-+]?%d+$", "^%d*%.%d+[eE][-+]?%d+$", "^%d+%.%d*$", "^%d*%.%d+$",
                 "^%d+$" }

-- Removes /* */ comments (kept state across lines) and // comments, outside strings.
local function decomment (text, st)
  local out, i, n = {}, 1, #text
  while i <= n do
    if st.incomment then
      local e = text:find("*/", i, true)
      if not e then return concat(out) end
      st.incomment, i = false, e + 2
      out[#out + 1] = " "
    else
      local c = text:sub(i, i)
      if c == "/" and text:sub(i + 1, i + 1) == "*" then
        st.incomment, i = true, i + 2
      elseif c == "/" and text:sub(i + 1, i + 1) == "/" then
        break
      elseif c == '"' then
        local e = text:find('"', i + 1, true) or n
        out[#out + 1] = text:sub(i, e)
        i = e + 1
      else
        out[#out + 1] = c
        i = i + 1
      end
    end
  end
  return concat(out)
end

-- Splits text into identifier tokens and everything else.
local function tokens (s)
  local t, i = {}, 1
  while i <= #s do
    local a, b = s:find("^[%a_][%w_]*", i)
    if a then
      t[#t + 1] = { id = true, s = s:sub(a, b) }
      i = b + 1
    else
      local a2, b2 = s:find("^%d[%w%.]*", i)
      if a2 then
        t[#t + 1] = { s = s:sub(a2, b2) }
        i = b2 + 1
      else
        t[#t + 1] = { s = s:sub(i, i) }
        i = i + 1
      end
    end
  end
  return t
end

local expand

-- Reads a function-like macro's arguments from token list t after position i (the '(');
-- returns the argument texts and the index after ')', or nil when the call is not closed.
local function macroargs (t, i)
  local args, cur, depth = {}, {}, 0
  local j = i + 1
  while j <= #t do
    local s = t[j].s
    if s == "(" then depth = depth + 1
    elseif s == ")" then
      if depth == 0 then
        args[#args + 1] = concat(cur)
        return args, j + 1
      end
      depth = depth - 1
    elseif s == "," and depth == 0 then
      args[#args + 1] = concat(cur)
      cur = {}
      goto continue
    end
    cur[#cur + 1] = s
    ::continue::
    j = j + 1
  end
  return nil
end

expand = function (s, macros, busy, depth)
  if depth > 64 then return s end
  local t = tokens(s)
  local out, i = {}, 1
  while i <= #t do
    local tk = t[i]
    local m = tk.id and macros[tk.s]
    if m and not busy[tk.s] then
      if m.params then
        local j = i + 1
        while t[j] and t[j].s:match("^%s$") do j = j + 1 end
        local args, nexti
        if t[j] and t[j].s == "(" then args, nexti = macroargs(t, j) end
        if args then
          local bind = {}
          for k, p in ipairs(m.params) do
            bind[p] = expand(args[k] or "", macros, busy, depth + 1)
          end
          local body = {}
          for _, bt in ipairs(tokens(m.body)) do
            body[#body + 1] = bt.id and bind[bt.s] or bt.s
          end
          busy[tk.s] = true
          out[#out + 1] = expand(concat(body), macros, busy, depth + 1)
          busy[tk.s] = nil
          i = nexti
        else
          out[#out + 1] = tk.s
          i = i + 1
        end
      else
        busy[tk.s] = true
        out[#out + 1] = expand(m.body, macros, busy, depth + 1)
        busy[tk.s] = nil
        i = i + 1
      end
    else
      out[#out + 1] = tk.s
      i = i + 1
    end
  end
  return concat(out)
end

-- Evaluates a parsed #if expression with C's integer-ish semantics (comparisons give 0/1).
local function ceval (e)
  local k = e.k
  if k == "num" then return e.v end
  if k == "name" then return 0 end
  if k == "un" then
    local a = ceval(e.a)
    if e.op == "-" then return -a end
    return a == 0 and 1 or 0
  end
  if k == "cond" then return ceval(e.c) ~= 0 and ceval(e.a) or ceval(e.b) end
  if k ~= "bin" then error("unsupported") end
  local op, a = e.op, ceval(e.a)
  if op == "&&" then return (a ~= 0 and ceval(e.b) ~= 0) and 1 or 0 end
  if op == "||" then return (a ~= 0 or ceval(e.b) ~= 0) and 1 or 0 end
  local b = ceval(e.b)
  if op == "+" then return a + b elseif op == "-" then return a - b
  elseif op == "*" then return a * b
  elseif op == "/" or op == "%" then
    if b == 0 then error("division by zero") end
    if op == "/" then return a // b end
    return math.fmod(a, b)
  elseif op == "==" then return a == b and 1 or 0 elseif op == "!=" then return a ~= b and 1 or 0
  elseif op == "<" then return a < b and 1 or 0 elseif op == "<=" then return a <= b and 1 or 0
  elseif op == ">" then return a > b and 1 or 0 elseif op == ">=" then return a >= b and 1 or 0
  end
  error("unsupported")
end

-- Evaluates the expression of #if / #elif on the macro-expanded text.
local function evalif (expr, macros, file, line)
  expr = expr:gsub("defined%s*%(%s*([%a_][%w_]*)%s*%)", function (n)
    return macros[n] and " 1 " or " 0 " end)
  expr = expr:gsub("defined%s+([%a_][%w_]*)", function (n) return macros[n] and " 1 " or " 0 " end)
  expr = expand(expr, macros, {}, 0)
  local parse = require("lsys.cpfg.parse")
  local ok, v = pcall(function ()
    local P = parse.new({ { file = file, line = line, text = expr } })
    P.strict = true
    local e = P:expr()
    if not P:ateol() then error("trailing text") end
    return ceval(e)
  end)
  if not ok then fail(file, line, "#if: cannot evaluate '%s'", expr:match("^%s*(.-)%s*$")) end
  return v ~= 0
end

-- A number as cpfg's lexer reads one (lsys.cpfg.parse's etok), the whole of `s`, or nil.
local function number (s)
  for _, p in ipairs(NUMBER) do
    if s:find(p) then return tonumber(s) end
  end
  return nil
end

-- Records `#define name body` in `keep` (see M.builtin) when body is a plain number and
-- the name may be kept; true when the name is kept from here on.
local function keepdefine (keep, name, body, raw, file, line)
  local v = number(body)
  local was = keep.values[name]
  if was ~= nil and v ~= was then keep.conflict = keep.conflict or name end
  if v == nil or keep.taken[name] or not name:find("^%a") then return false end
  if was == nil then
    keep.values[name] = v + 0.0
    keep.order[#keep.order + 1] = name
    keep.where[name] = { file = file, line = line }
    keep.notes[name] = raw:match("/%*%s*(.-)%s*%*/") or raw:match("//%s*(.-)%s*$")
  end
  return true
end

--- The built-in preprocessor: #define (objects and function-like macros), #undef,
-- #include "file" (relative to the including file), #ifdef, #ifndef, #if, #elif, #else,
-- #endif, comments. Returns the located lines; raises { cpfg = true, msg = } on errors.
-- With `keep` ({ taken = set of names }, for lsys.cpfg.import), a #define of a plain
-- number (`#define RATE 1.5`, a name not in keep.taken) is not expanded in the text, only
-- in #if: keep.values[name] is its value, keep.order the names in file order,
-- keep.where[name] its file and line, keep.notes[name] the comment on its line;
-- keep.conflict names one defined again with another value or undefined (the text is then
-- not what cpp would give).
function M.builtin (path, defines, keep)
  local macros = {}
  for k, v in pairs(defines or {}) do macros[k] = { body = tostring(v) } end
  if keep then keep.values, keep.order, keep.where, keep.notes = {}, {}, {}, {} end
  local kept = {}    -- the names kept now: never expanded in the text (busy in `expand`)
  local lines = {}
  local seen = 0
  local function run (file, text, level)
    if level > 32 then fail(file, 1, "#include nested too deeply") end
    local st = { incomment = false }
    local cond = {}   -- stack of { active =, done =, parent = }
    local function active () return #cond == 0 or cond[#cond].active end
    local n, pending = 0, nil
    for raw in (text:gsub("\r\n", "\n") .. "\n"):gmatch("([^\n]*)\n") do
      n = n + 1
      seen = seen + 1
      if seen > 1e6 then fail(file, n, "too many lines") end
      local s = decomment(raw, st)
      if pending then s, pending = pending .. s, nil end
      if s:sub(-1) == "\\" then
        pending = s:sub(1, -2)
        lines[#lines + 1] = { file = file, line = n, text = "" }
        goto next
      end
      do
        local dir, rest = s:match("^%s*#%s*(%a*)(.*)$")
        if dir and not isdirective(s) then dir = nil end    -- a text line
        if dir then
          rest = rest:match("^%s*(.-)%s*$")
          if dir == "ifdef" or dir == "ifndef" then
            local name = rest:match("^[%a_][%w_]*")
            if not name then fail(file, n, "#%s without a name", dir) end
            local v = (macros[name] ~= nil) == (dir == "ifdef")
            local a = active()
            insert(cond, { active = a and v, done = v, parent = a })
          elseif dir == "if" then
            local a = active()
            local v = a and evalif(rest, macros, file, n)
            insert(cond, { active = v, done = v, parent = a })
          elseif dir == "elif" then
            local c = cond[#cond]
            if not c then fail(file, n, "#elif without #if") end
            if c.done or not c.parent then c.active = false
            else
              c.active = evalif(rest, macros, file, n)
              c.done = c.active
            end
          elseif dir == "else" then
            local c = cond[#cond]
            if not c then fail(file, n, "#else without #if") end
            c.active = c.parent and not c.done
            c.done = true
          elseif dir == "endif" then
            if not remove(cond) then fail(file, n, "#endif without #if") end
          elseif active() and dir == "define" then
            local name, params, body = rest:match("^([%a_][%w_]*)%(([^)]*)%)%s*(.*)$")
            if name then
              local ps = {}
              for p in params:gmatch("[^,%s]+") do ps[#ps + 1] = p end
              macros[name] = { params = ps, body = body }
              if kept[name] then keep.conflict, kept[name] = keep.conflict or name, nil end
            else
              name, body = rest:match("^([%a_][%w_]*)%s*(.*)$")
              if not name then fail(file, n, "#define without a name") end
              macros[name] = { body = body }
              kept[name] = keep and keepdefine(keep, name, body, raw, file, n) or nil
            end
          elseif dir == "undef" and active() then
            local name = rest:match("^[%a_][%w_]*") or ""
            if kept[name] then keep.conflict = keep.conflict or name end
            macros[name], kept[name] = nil, nil
          elseif dir == "include" and active() then
            local inc = rest:match('^"(.-)"')
            if not inc then fail(file, n, "#include needs a \"file\" name") end
            local p = inc:sub(1, 1) == "/" and inc or dirof(file) .. "/" .. inc
            local t = readfile(p)
            if not t then fail(file, n, "%s: No such file or directory", inc) end
            run(p, t, level + 1)
          elseif dir == "error" and active() then
            fail(file, n, "#error %s", rest)
          end
          lines[#lines + 1] = { file = file, line = n, text = "" }
        elseif active() then
          lines[#lines + 1] = { file = file, line = n, text = expand(s, macros, kept, 0) }
        else
          lines[#lines + 1] = { file = file, line = n, text = "" }
        end
      end
      ::next::
    end
    if #cond > 0 then fail(file, n, "unterminated #if") end
  end
  local text, err = readfile(path)
  if not text then error({ cpfg = true, msg = err }, 0) end
  run(path, text, 0)
  while #lines > 0 and lines[#lines].text == "" do remove(lines) end
  return lines
end

--- Preprocesses `path`: with `how` "system" (cpp, an error when missing), "builtin", or
-- nil (cpp when present). Returns the located lines; raises { cpfg = true, msg = }.
function M.run (path, defines, how)
  if how == "system" or (how == nil and system_cpp()) then
    local lines, err = M.system(path, defines)
    if not lines then error({ cpfg = true, msg = err }, 0) end
    return lines
  elseif how == nil or how == "builtin" then
    return M.builtin(path, defines)
  end
  error("lsys.cpfg: cpp must be \"system\" or \"builtin\"", 3)
end

return M
