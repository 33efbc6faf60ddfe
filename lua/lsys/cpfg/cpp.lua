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
local shq = require("lsys.util.text").shq
local core = require "lsys.core"
local _ENV = nil

local M = {}

-- The most bytes of one file: an L-system file is text of a few kilobytes, and an
-- #include of /dev/zero must not take the memory.
local MAXBYTES = 16 * 1024 * 1024

-- The text of a regular file, or nil and "PATH: why". Anything else (a folder, a device
-- such as /dev/zero, a FIFO that would block the open) is refused unopened.
local function readfile (path)
  local _, kind = core.realpath(path)
  if kind ~= nil and kind ~= "file" then return nil, path .. ": not a regular file" end
  local f, err = io.open(path, "rb")
  if not f then return nil, err end
  local parts, size = {}, 0
  while true do
    local s, rerr = f:read(65536)
    if s == nil then
      f:close()
      if rerr then return nil, path .. ": cannot be read" end
      return concat(parts)
    end
    size = size + #s
    if size > MAXBYTES then
      f:close()
      return nil, format("%s: larger than %d MiB", path, MAXBYTES // (1024 * 1024))
    end
    parts[#parts + 1] = s
  end
end
M.readfile = readfile

local function dirof (path)
  local d = path:match("^(.*)/[^/]*$")
  if d == nil then return "." end
  if d == "" then return "/" end
  return d
end
M.dirof = dirof

local function fail (file, line, fmt, ...)
  error({ cpfg = true, msg = format("%s:%d: " .. fmt, file, line, ...) }, 0)
end

-- Where an #include may read ---------------------------------------------

-- A model's files are the file itself and the regular files below its folder (symbolic
-- links and '..' resolved): an #include of anything else (/etc/shadow, /dev/zero, a FIFO,
-- a folder) is refused, for the built-in preprocessor and the system cpp alike, before it
-- is opened. A guard is { root = the folder resolved, files = { [resolved name] = true } }.
local function newguard (main)
  return { root = core.realpath(dirof(main)) or dirof(main), files = {} }
end

local function below (root, real)
  return root == "/" or real:sub(1, #root + 1) == root .. "/"
end

--- Whether `path` is one of the files of the model `main` (a regular file below its folder,
-- links and '..' resolved): what its preprocessing may read, and what `lsys view` watches.
function M.ismodelfile (main, path)
  local real, kind = core.realpath(path)
  return real ~= nil and kind == "file" and below(newguard(main).root, real)
end

-- The file that `#include "inc"` on line n of `file` names (relative to the including
-- file's folder, as cpp finds it) and its resolved name, nil when it does not exist (the
-- preprocessor says so, or skips it in a branch not taken); raises when it may not be read.
local function included (guard, file, n, inc)
  local p = inc:sub(1, 1) == "/" and inc or dirof(file) .. "/" .. inc
  local real, kind = core.realpath(p)
  if real == nil then return p, nil end
  if kind ~= "file" then fail(file, n, "%s: not a regular file", inc) end
  if not below(guard.root, real) then fail(file, n, "%s: outside the model's folder", inc) end
  guard.files[real] = true
  return p, real
end

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
  while #lines > 1 and lines[#lines].text == "" do remove(lines) end
  -- an empty file is one empty line, so that a message about it names the file
  if #lines == 0 then lines[1] = { file = main, line = 1, text = "" } end
  return lines
end

-- The limits of the system cpp, besides what the scan below refuses: the text and lines it
-- may give (those of the built-in preprocessor, MAXTEXT and MAXLINES), the CPU seconds and
-- memory of its process (ulimit), and its wall clock (timeout(1) where there is one: an
-- open that waits, which no scan of the text can rule out entirely).
local MAXLINES, MAXTEXT = 100000, 4 * 1024 * 1024
local MAXARG = 120 * 1024          -- the longest argument Linux passes (MAX_ARG_STRLEN 128 KiB)
local CPP_SECONDS, CPP_KIB = 60, 1024 * 1024

local have_timeout

-- The shell words that run the command `words` (shell words already) under those limits:
-- a shell of its own (a fresh one, so that the limits hold for it alone), started without
-- a preloaded library (a sanitizer's runtime, tools/sanitize.sh, reserves terabytes of
-- address space and would fail under the memory limit).
local function limited (words)
  if have_timeout == nil then
    have_timeout = os.execute("command -v timeout >/dev/null 2>&1") == true
  end
  return "LD_PRELOAD= sh -c " .. shq(("ulimit -t %d 2>/dev/null; ulimit -v %d 2>/dev/null; "
    .. "exec %s%s"):format(CPP_SECONDS, CPP_KIB,
                           have_timeout and ("timeout -s KILL %d "):format(CPP_SECONDS) or "",
                           words))
end

-- The directives through which cpp reads a file.
local READS = { include = true, include_next = true, import = true, embed = true }

-- Skips blanks and /* */ comments of `line` from i.
local function blanks (line, i)
  while true do
    i = line:match("^[ \t\f\v]*()", i)
    if line:sub(i, i + 1) ~= "/*" then return i end
    local e = line:find("*/", i + 2, true)
    if not e then return #line + 1 end
    i = e + 2
  end
end

local decomment

-- Calls f(n, name, rest, maybe) for each directive of `text` that cpp could see, and more:
-- lines joined at a backslash before the newline (blanks between too), '#' or '%:' looked
-- for at the start of every line and after every "*/" on it, blanks and comments before
-- and after it; n is its line. `maybe` is true on a line that starts in a /* */ comment
-- as far as this scan can tell (which a quote can fool: it sees every directive anyway).
local function directives (text, f)
  local n, pending, pn, st = 0, nil, nil, { incomment = false }
  for raw in (text:gsub("\r\n?", "\n") .. "\n"):gmatch("([^\n]*)\n") do
    n = n + 1
    local line, ln = (pending or "") .. raw, pn or n
    if line:find("\\[ \t\f\v]*$") then
      pending, pn = line:gsub("\\[ \t\f\v]*$", ""), ln
    else
      local maybe, i = st.incomment, 1
      pending, pn = nil, nil
      decomment(line, st)
      while i do
        local j = blanks(line, i)
        local h = line:match("^#()", j) or line:match("^%%:()", j)
        if h then
          local name, rest = line:match("^([%a_][%w_]*)(.*)$", blanks(line, h))
          if name then f(ln, name, rest, maybe) end
        end
        local e = line:find("*/", i, true)
        i = e and e + 2
      end
    end
  end
end

-- The line of byte `at` of `text`.
local function lineof (text, at)
  local _, k = text:sub(1, at):gsub("\n", "")
  return k + 1
end

-- Checks every file the system cpp could read for `file` (its text `text`) as the built-in
-- preprocessor would include it (see included), recursively: each #include, #include_next,
-- #import, #embed of a "file" (a <file> only when it names an absolute path: with
-- -nostdinc cpp looks nowhere else), in every branch and comment, each file read once and
-- MAXBYTES in all. A directive that names its file otherwise (a macro), `__has_include`
-- (cpp opens the file to answer it), and `_Pragma` or #pragma ... dependency (which also
-- open files) are refused.
local function prescan (guard, file, text, depth, seen)
  if depth > 200 then fail(file, 1, "#include nested too deeply") end   -- cpp's own limit
  seen.bytes = (seen.bytes or 0) + #text
  if seen.bytes > MAXBYTES then
    fail(file, 1, "the model's files are larger than %d MiB in all", MAXBYTES // (1024 * 1024))
  end
  directives(text, function (n, name, rest, maybe)
    if READS[name] then
      rest = rest:sub(blanks(rest, 1))
      local inc = rest:match('^"(.-)"') or rest:match("^<(/.-)>")
      if inc == nil and not rest:find("^<") and not maybe then   -- (prose in a comment)
        fail(file, n, "#%s needs a \"file\" name", name)
      end
      local p, real
      if inc then p, real = included(guard, file, n, inc) end
      if real and not seen[real] then
        seen[real] = true
        local t, why = readfile(p)
        if not t then fail(file, n, "%s: %s", inc, why:match("^.*: (.-)$") or why) end
        prescan(guard, p, t, depth + 1, seen)
      end
    elseif name == "pragma" and rest:find("dependency", 1, true) then
      fail(file, n, "#pragma ... dependency is not supported")
    end
  end)
  for _, w in ipairs { "__has_include", "_Pragma" } do
    local at = text:find(w, 1, true)
    if at then fail(file, lineof(text, at), "%s is not supported", w) end
  end
end

-- The sed program that gives a text line whose '#' starts no directive (isdirective) the
-- name HASH for its '#', for cpp to read it from stdin.
local function sedprogram ()
  local names = {}
  for d in pairs(DIRECTIVES) do names[#names + 1] = d end
  sort(names)
  return ("\\%%^[[:space:]]*#[[:space:]]*($|[0-9]|/[*/]|(%s)([^[:alnum:]_]|$))%%!"
          .. "s/^([[:space:]]*)#/\\1%s/"):format(concat(names, "|"), HASH)
end

-- Runs the shell command `cmd`, whose output is cpp's output, then a line `sep`, cpp's
-- messages and a line "`sep` STATUS"; reads at most twice MAXTEXT bytes and a little (the
-- pipe is then closed: cpp ends on its next write). Returns the output, the messages, cpp's
-- status (nil when unknown) and whether it was stopped at the limit.
local function runcpp (cmd, sep)
  local p = io.popen(cmd, "r")
  if not p then return "", "cannot run the shell", nil, false end
  local parts, size, over = {}, 0, false
  while true do
    local chunk = p:read(65536)
    if not chunk then break end
    size = size + #chunk
    parts[#parts + 1] = chunk
    if size > 2 * MAXTEXT + 65536 then over = true; break end
  end
  p:close()
  local all = concat(parts)
  local at = all:find("\n" .. sep .. "\n", 1, true)
  if not at then return all, "", nil, over end
  local rest = all:sub(at + #sep + 2)
  local msgs, st = rest:match("^(.-)\n?" .. sep .. " (%d+)\n?$")
  return all:sub(1, at), msgs or rest, tonumber(st), over
end

--- Runs the system C preprocessor on `path` with `defines` ({ NAME = value }); returns
-- the located lines, or nil and cpp's first message. Raises { cpfg = true, msg = } for an
-- #include that may not be read, or at a limit. `text`, when given, is read in place of
-- the file's own bytes (a panel's edited #defines); its #includes are the file's.
function M.system (path, defines, text)
  local args = { "cpp", "-x", "c", "-undef", "-nostdinc", "-w", "-fmax-errors=20" }
  local names = {}
  for k in pairs(defines or {}) do names[#names + 1] = k end
  sort(names)
  for _, k in ipairs(names) do args[#args + 1] = shq("-D" .. k .. "=" .. tostring(defines[k])) end
  -- everything cpp could read is checked first; then cpp runs on no other input
  local given = text ~= nil
  if not given then
    local t, err = readfile(path)
    if not t then return nil, err end
    text = t
  elseif #text > MAXARG then         -- (it goes to cpp as one shell word)
    return nil, format("%s: an edited text of over %d bytes is for the built-in "
                       .. "preprocessor (cpp = \"builtin\")", path, MAXARG)
  end
  local guard = newguard(path)
  local mainreal = core.realpath(path)
  prescan(guard, path, text, 0, { [mainreal or path] = true })
  -- text lines starting with '#' (see DIRECTIVES) would be errors for cpp: then the file
  -- goes through sed, which gives their '#' a name, and cpp reads stdin in the file's
  -- folder, so that #include "x" finds the same files; a name that starts with '-' (a
  -- vlab specifications file can say anything) must not reach cpp as an option such as
  -- -o FILE. Its output and then its messages come back on one pipe: no file is written.
  local protect = given
  for line in text:gmatch("[^\n]+") do
    if line:find("^%s*#") and not isdirective(line) then protect = true; break end
  end
  local run
  if protect then
    local base = path:match("[^/]*$")
    local from = given and "printf '%s' " .. shq(text) .. " | LC_ALL=C sed -E "
                             .. shq(sedprogram())
                 or "LC_ALL=C sed -E " .. shq(sedprogram()) .. " < " .. shq("./" .. base)
    run = "cd " .. shq(dirof(path)) .. " && " .. from .. " | "
          .. limited(concat(args, " ") .. " -")
  else
    run = limited(concat(args, " ") .. " " .. shq(path:sub(1, 1) == "-" and "./" .. path or path))
  end
  -- cpp's output goes straight to the pipe (fd 4), its messages wait in a variable
  local sep = ("__lsys_cpp_%08x%08x__"):format(math.random(0, 0x7fffffff),
                                               math.random(0, 0x7fffffff))
  local cmd = "{ e=$( { { " .. run .. "; } 2>&1 >&4; echo \"" .. sep .. " $?\"; } ); "
              .. "printf '\\n%s\\n%s\\n' " .. sep .. " \"$e\"; } 4>&1"
  local out, msg, status, over = runcpp(cmd, sep)
  if protect then
    out = out:gsub(HASH, "#")
    msg = msg:gsub("<stdin>", function () return path end)
  end
  local lines, size = marked(out, path, protect and dirof(path)), #out
  -- every file cpp says it read is the model's (the scan saw them all, unless a #line
  -- names another); the first that is not is refused, its lines never shown
  local prev = { file = path, line = 1 }
  for _, l in ipairs(lines) do
    if l.file ~= prev.file and l.file ~= path then
      local real, kind = core.realpath(l.file)
      if real and real ~= mainreal and not guard.files[real] and
         (kind ~= "file" or not below(guard.root, real)) then
        fail(prev.file, prev.line, "%s: outside the model's folder", l.file)
      end
    end
    prev = l
  end
  if over or size > MAXTEXT then
    fail(prev.file, prev.line, "more than %d MiB of text with the #include files and macros",
         MAXTEXT // (1024 * 1024))
  elseif #lines > MAXLINES then
    fail(lines[MAXLINES + 1].file, lines[MAXLINES + 1].line,
         "more than %d lines with the #include files", MAXLINES)
  end
  if status ~= 0 then
    local first = msg:match("[^\n]*error:[^\n]*") or msg:match("[^\n]+") or ""
    first = first:gsub("^([^:]+:%d+):%d+:", "%1:"):gsub(" fatal error:", ""):gsub(" error:", "")
    -- a message about a line quotes it: only a model file's (cpp's own, "cc1: out of
    -- memory ...", names none)
    local f = first:match("^([^:]+):%d+:")
    local real = f and core.realpath(protect and f:sub(1, 1) ~= "/" and f ~= path
                                     and dirof(path) .. "/" .. f or f)
    if first == "" or f and not (f == path or real == mainreal or (real and guard.files[real]))
    then
      first = status == nil and "cpp failed" or
              status >= 128 and ("cpp was stopped (more than %d s or %d MiB)"):format(
                CPP_SECONDS, CPP_KIB // 1024) or ("cpp failed (status %d)"):format(status)
    end
    return nil, first
  end
  -- cpp turns a leading tab into a space; cpfg reads a line starting with a tab as the
  -- continuation of the one before, so the tabs come back from the source lines
  local sources = {}
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

-- cpfg's number literals (lsys.cpfg.parse's etok)
local NUMBER = { "^%d+%.%d*[eE][-+]?%d+$", "^%d*%.%d+[eE][-+]?%d+$", "^%d+%.%d*$", "^%d*%.%d+$",
                 "^%d+$" }

-- Removes /* */ comments (kept state across lines) and // comments, outside strings.
decomment = function (text, st)
  local out, i, n = {}, 1, #text
  while i <= n do
    if st.incomment then
      local e = text:find("*/", i, true)
      if not e then return concat(out) end
      st.incomment, i = false, e + 2
      out[#out + 1] = " "
    else
      local a = text:find('[/"]', i)
      if not a then
        out[#out + 1] = text:sub(i)
        break
      end
      out[#out + 1] = text:sub(i, a - 1)
      local c2 = text:sub(a + 1, a + 1)
      if text:sub(a, a) == '"' then
        local e = text:find('"', a + 1, true) or n
        out[#out + 1] = text:sub(a, e)
        i = e + 1
      elseif c2 == "*" then
        st.incomment, i = true, a + 2
      elseif c2 == "/" then
        break
      else
        out[#out + 1] = "/"
        i = a + 1
      end
    end
  end
  return concat(out)
end

-- Splits text into identifier tokens, numbers, strings and single characters.
local function tokens (s)
  local t, i = {}, 1
  while i <= #s do
    local a, b = s:find("^[%a_][%w_]*", i)
    if a then
      t[#t + 1] = { id = true, s = s:sub(a, b) }
      i = b + 1
    else
      local a2, b2 = s:find("^%d[%w%.]*", i)
      if not a2 and s:sub(i, i) == '"' then     -- a string: no macros inside, as in C
        a2, b2 = i, s:find('"', i + 1, true) or #s
      end
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

-- The index of the ')' that closes each '(' of token list t (none for an unclosed one):
-- one pass, so that a line of many unclosed calls is not scanned once per call.
local function matching (t)
  local close, stack = {}, {}
  for j, tk in ipairs(t) do
    if tk.s == "(" then stack[#stack + 1] = j
    elseif tk.s == ")" and #stack > 0 then close[remove(stack)] = j end
  end
  return close
end

-- Reads a function-like macro's arguments from token list t after position i (the '(',
-- closed at close[i]); returns the argument texts and the index after ')', or nil when
-- the call is not closed.
local function macroargs (t, i, close)
  local e = close[i]
  if not e then return nil end
  local args, cur, depth = {}, {}, 0
  for j = i + 1, e - 1 do
    local s = t[j].s
    if s == "(" then depth = depth + 1
    elseif s == ")" then depth = depth - 1 end
    if s == "," and depth == 0 then
      args[#args + 1] = concat(cur)
      cur = {}
    else
      cur[#cur + 1] = s
    end
  end
  args[#args + 1] = concat(cur)
  return args, e + 1
end

-- The longest text that the macros of one line may expand to.
local MAXEXPAND = 100000

-- Expands the macros in `s`. `st` is { file =, line =, left = } for the line: `left`
-- counts down the characters the expansion may still produce, as they are produced (a
-- macro that doubles its text at each of 30 levels must fail, not take the memory).
expand = function (s, macros, busy, depth, st)
  if depth > 64 then fail(st.file, st.line, "macros nested more than 64 deep") end
  local t = tokens(s)
  local out, i, close = {}, 1, nil
  while i <= #t do
    local tk = t[i]
    local m = tk.id and macros[tk.s]
    local x
    if m and not busy[tk.s] then
      if m.params then
        local j = i + 1
        while t[j] and t[j].s:match("^%s$") do j = j + 1 end
        local args, nexti
        if t[j] and t[j].s == "(" then
          close = close or matching(t)
          args, nexti = macroargs(t, j, close)
        end
        if args then
          local bind = {}
          for k, p in ipairs(m.params) do
            bind[p] = expand(args[k] or "", macros, busy, depth + 1, st)
          end
          local body = {}
          for _, bt in ipairs(tokens(m.body)) do
            body[#body + 1] = bt.id and bind[bt.s] or bt.s
          end
          busy[tk.s] = true
          x = expand(concat(body), macros, busy, depth + 1, st)
          busy[tk.s] = nil
          i = nexti
        end
      else
        busy[tk.s] = true
        x = expand(m.body, macros, busy, depth + 1, st)
        busy[tk.s] = nil
        i = i + 1
      end
    end
    if not x then          -- a token of the final text (arguments: once per expansion)
      x = tk.s
      i = i + 1
      st.left = st.left - #x
      if st.left < 0 then
        fail(st.file, st.line, "macro expansion longer than %d characters", MAXEXPAND)
      end
    end
    out[#out + 1] = x
  end
  return concat(out)
end

-- Expands the macros of one line (`file`, `line`); a line without a macro name is as is.
local function expandline (s, macros, file, line, kept)
  for id in s:gmatch("[%a_][%w_]*") do
    if macros[id] and not (kept and kept[id]) then
      return expand(s, macros, kept or {}, 0, { file = file, line = line, left = MAXEXPAND })
    end
  end
  return s
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
  expr = expandline(expr, macros, file, line)
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

-- #define: `rest` is the text after the directive, on `line` of `file`; returns the name.
local function define (rest, macros, file, line)
  local name, params, body = rest:match("^([%a_][%w_]*)%(([^)]*)%)%s*(.*)$")
  if name then
    local ps = {}
    if params:find("%S") then
      for p in (params .. ","):gmatch("([^,]*),") do
        local q = p:match("^%s*([%a_][%w_]*)%s*$")
        if not q then
          p = p:match("^%s*(.-)%s*$")
          fail(file, line, "#define %s: '%s' is not a parameter name", name,
               #p > 30 and p:sub(1, 30) .. "..." or p)
        end
        ps[#ps + 1] = q
      end
    end
    macros[name] = { params = ps, body = body }
  else
    name, body = rest:match("^([%a_][%w_]*)%s*(.*)$")
    if not name then fail(file, line, "#define without a name") end
    macros[name] = { body = body }
  end
  return name
end

-- MAXLINES: the most lines the built-in preprocessor reads, counting each #include of a
-- file anew (files that include each other twice would otherwise run for hours), and
-- MAXTEXT the most text, as read and as the macros expand it (the system cpp's limits).

--- The built-in preprocessor: #define (objects and function-like macros), #undef,
-- #include "file" (relative to the including file), #ifdef, #ifndef, #if, #elif, #else,
-- #endif, comments. Returns the located lines; raises { cpfg = true, msg = } on errors.
-- With `keep` ({ taken = set of names }, for lsys.cpfg.import), a #define of a plain
-- number (`#define RATE 1.5`, a name not in keep.taken) is not expanded in the text, only
-- in #if: keep.values[name] is its value, keep.order the names in file order,
-- keep.where[name] its file and line, keep.notes[name] the comment on its line;
-- keep.conflict names one defined again with another value or undefined (the text is then
-- not what cpp would give).
function M.builtin (path, defines, keep, given)
  local macros = {}
  for k, v in pairs(defines or {}) do macros[k] = { body = tostring(v) } end
  if keep then keep.values, keep.order, keep.where, keep.notes = {}, {}, {}, {} end
  local kept = {}    -- the names kept now: never expanded in the text (busy in `expand`)
  local lines = {}
  local seen, size = 0, 0
  local texts = {}      -- path -> text: a file included many times is read once
  local guard = newguard(path)
  local function run (file, text, level)
    if level > 32 then fail(file, 1, "#include nested too deeply") end
    local st = { incomment = false }
    local cond = {}   -- stack of { active =, done =, parent = }
    local function active () return #cond == 0 or cond[#cond].active end
    local n, pending = 0, nil
    for raw in (text:gsub("\r\n", "\n") .. "\n"):gmatch("([^\n]*)\n") do
      n = n + 1
      seen, size = seen + 1, size + #raw
      if seen > MAXLINES then
        fail(file, n, "more than %d lines with the #include files", MAXLINES)
      end
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
            local name = define(rest, macros, file, n)
            local m = macros[name]
            if m.params then
              if kept[name] then keep.conflict, kept[name] = keep.conflict or name, nil end
            else
              kept[name] = keep and keepdefine(keep, name, m.body, raw, file, n) or nil
            end
          elseif dir == "undef" and active() then
            local name = rest:match("^[%a_][%w_]*") or ""
            if kept[name] then keep.conflict = keep.conflict or name end
            macros[name], kept[name] = nil, nil
          elseif dir == "include" and active() then
            local inc = rest:match('^"(.-)"')
            if not inc then fail(file, n, "#include needs a \"file\" name") end
            local p = included(guard, file, n, inc)
            local t, why = texts[p], nil
            if not t then t, why = readfile(p) end
            if not t then fail(file, n, "%s: %s", inc, why:match("^.*: (.-)$") or why) end
            texts[p] = t
            run(p, t, level + 1)
          elseif dir == "error" and active() then
            fail(file, n, "#error %s", rest)
          end
          lines[#lines + 1] = { file = file, line = n, text = "" }
        elseif active() then
          local x = expandline(s, macros, file, n, kept)
          size = size + #x
          if size > MAXTEXT then
            fail(file, n, "more than %d MiB of text with the #include files and macros",
                 MAXTEXT // (1024 * 1024))
          end
          lines[#lines + 1] = { file = file, line = n, text = x }
        else
          lines[#lines + 1] = { file = file, line = n, text = "" }
        end
      end
      ::next::
    end
    if #cond > 0 then fail(file, n, "unterminated #if") end
  end
  local text = given
  if text == nil then
    local err
    text, err = readfile(path)
    if not text then error({ cpfg = true, msg = err }, 0) end
  end
  run(path, text, 0)
  while #lines > 1 and lines[#lines].text == "" do remove(lines) end
  return lines
end

--- Preprocesses `path`: with `how` "system" (cpp, an error when missing), "builtin", or
-- nil (cpp when present); `text` in place of the file's bytes. Returns the located lines;
-- raises { cpfg = true, msg = }.
function M.run (path, defines, how, text)
  if how == "system" or (how == nil and system_cpp()) then
    local lines, err = M.system(path, defines, text)
    if not lines then error({ cpfg = true, msg = err }, 0) end
    return lines
  elseif how == nil or how == "builtin" then
    return M.builtin(path, defines, nil, text)
  end
  error("lsys.cpfg: cpp must be \"system\" or \"builtin\"", 3)
end

return M
