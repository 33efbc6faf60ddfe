--- cpfg's communication specification files (`.e`, vlab's environmental programs): what
-- program to start, how to talk to it, and which turtle values each query carries
-- (docs/open.md §3; vlab's EnviroManual §2). `read(path)` returns
--
--   { path =, dir =, name = (the file's name in dir), transport = "pipes" | "files" |
--     "memory", max = (queries a chunk: 100 for pipes, 1000 for files, or the number after
--     the type; nil for memory, chunked by size), argv = { program, args... },
--     formats = { position =, heading =, left =, up =, width =, scale = } (each a C format
--     of the values, as the file gives it, or nil: not sent), following = true | false,
--     verbose = true | false, interpreted = nil, or the flags of the modules whose
--     geometry follows their ?E (M.interprets tells) }
--
-- A line is `keyword: value`, the keyword compared as written (cpfg trims nothing); a blank
-- line or an unknown keyword is skipped with a warning, as cpfg does. Raises
-- "file:line: message" for what lsys cannot do: sockets, a remote host, strings-only and
-- binary modes, and for `interpreted modules:` and `when interpret:` lines it cannot read.
-- @module lsys.environment.efile
local warning = require "lsys.warning"

local io, table, tonumber, error, format, pairs = io, table, tonumber, error, string.format,
      pairs
local _ENV = nil

local M = {}

-- The keywords whose value is a C format of turtle values, by the query field they send.
local FORMATS = {
  ["turtle position"] = "position", ["turtle heading"] = "heading",
  ["turtle left"] = "left", ["turtle up"] = "up", ["turtle line width"] = "width",
  ["turtle scale factor"] = "scale",
}
M.ORDER = { "position", "heading", "left", "up", "width", "scale" }   -- as cpfg sends them

local MAX = { pipes = 100, files = 1000 }   -- queries a chunk by default (cpfg's)
local REFUSED = {
  ["remote host"] = "a program on another host",
  ["strings only"] = "cpfg's distributed mode",
  ["binary data"] = "cpfg's distributed mode",
}

-- The words of `s`, split at blanks (and at `extra` characters too).
local function words (s, extra)
  local out = {}
  for w in s:gmatch("[^%s" .. (extra or "") .. "]+") do out[#out + 1] = w end
  return out
end

-- Checks a C format of `n` values (3 for vectors, 1 for numbers) that Lua's
-- string.format can run, and returns it so: the conversions e f g E G with flags, a width
-- and a precision of at most two digits each, and %%; C's length modifiers (l, L, h) are
-- dropped, as they change nothing for a double.
local function cformat (fmt, n, fail)
  local out, i, conv = {}, 1, 0
  while true do
    local at = fmt:find("%", i, true)
    if at == nil then out[#out + 1] = fmt:sub(i); break end
    out[#out + 1] = fmt:sub(i, at - 1)
    local flags, width, dot, prec, c, stop =
      fmt:match("^([-+ #0]*)(%d*)(%.?)(%d*)[lLh]*([%%efgEG])()", at + 1)
    if c == nil or #width > 2 or #prec > 2 or (dot == "" and prec ~= "") then
      fail(format("turtle format '%s': the %% at character %d is not a conversion lsys "
                  .. "sends numbers through (%%e, %%f or %%g, with a width and a precision "
                  .. "of two digits at most)", fmt, at))
    end
    if c == "%" then
      out[#out + 1] = "%%"
    else
      out[#out + 1] = "%" .. flags .. width .. dot .. prec .. c
      conv = conv + 1
    end
    i = stop
  end
  if conv > n then
    fail(format("the format takes %d values, the turtle sends %d", conv, n))
  end
  return table.concat(out)
end

-- The flags of the modules are cpfg's: a table character -> bits, `other` the bits of every
-- character not in it; bit 0x80 any number of parameters, 0x40 >> n exactly n.

-- `interpreted modules:` sets the flags of the modules it names (cpfg's: a name alone, any
-- number of parameters; `X(n)` with n of 0 to 6, exactly n; `all`, every module, and the
-- rest of the line unread). A name replaces what earlier lines gave its character.
local function interpreted (value, t, fail)
  for w in value:gmatch("[^,; ]+") do
    if w == "all" then
      for c in pairs(t) do t[c] = nil end
      t.other = 0x80
      return
    end
    local c, n = w:match("^(.)%((%d)%)$")
    if #w == 1 then
      t[w] = 0x80
    elseif c and tonumber(n) <= 6 then
      t[c] = 0x40 >> tonumber(n)
    else
      fail(format("interpreted modules: '%s' is not a module lsys can name: one character, "
                  .. "alone (any parameters) or with its number of parameters, 0 to 6, as "
                  .. "in F(1)", w))
    end
  end
end

-- `when interpret:` adds to every module's flags: n (0 to 6) the modules of n parameters,
-- a negative number all of them (cpfg's; a number above 6 is skipped with a warning, as
-- cpfg does).
local function wheninterpret (value, t, fail, where)
  for w in value:gmatch("[^,; \t]+") do
    local n = w:match("^[-+]?%d+$") and tonumber(w)
    if n == nil then
      fail(format("when interpret: '%s' is not a number of parameters (0 to 6, or -1 for "
                  .. "all modules)", w))
    end
    if n > 6 then
      warning.warn(format("lsys: %s: when interpret: modules of %d parameters cannot be told "
                          .. "apart (6 at most, as in cpfg): skipped; name them in "
                          .. "'interpreted modules:'", where, n))
    else
      local bits = n < 0 and 0xff or 0x40 >> n
      for c, f in pairs(t) do t[c] = f | bits end
    end
  end
end

--- Whether the module `name` with `n` parameters is interpreted after a ?E (its geometry
-- follows the query), by the flags of `spec` (a read file): cpfg's test, on the flags of
-- the name's first character.
function M.interprets (spec, name, n)
  local t = spec.interpreted
  if t == nil or name == nil or name == "" then return false end
  local f = t[name:sub(1, 1)] or t.other
  return f & 0x80 ~= 0 or (n <= 6 and f & (0x40 >> n) ~= 0)
end

--- Reads the `.e` file `path`; the result as the module's header says.
function M.read (path)
  local f, err = io.open(path, "r")
  if not f then error(format("cannot open '%s': %s", path, err), 0) end
  local dir, name = path:match("^(.*)/([^/]*)$")
  local spec = { path = path, dir = dir or ".", name = name or path, transport = "pipes",
                 formats = {}, following = true, verbose = false }
  local n, max = 0, nil
  for line in f:lines() do
    n = n + 1
    local function fail (msg) f:close(); error(format("%s:%d: %s", path, n, msg), 0) end
    local key, value = line:match("^([^:\t]*)[:\t](.*)$")
    if key == nil or key == "" then
      warning.warn(format("lsys: %s:%d: not a directive of a communication file: skipped",
                          path, n))
    elseif key == "communication type" then
      local w = words(value, ":")
      local t = w[1]
      if t ~= "pipes" and t ~= "files" and t ~= "memory" then
        fail(format("communication type '%s': lsys speaks pipes, files and memory", t or ""))
      end
      spec.transport = t
      max = tonumber(w[2] or "")
    elseif key == "executable" then
      local argv = words(value)
      if argv[#argv] == "&" then argv[#argv] = nil end   -- cpfg's background marker
      if #argv == 0 then fail("executable: no program named") end
      spec.argv = argv
    elseif FORMATS[key] then
      local field = FORMATS[key]
      spec.formats[field] = cformat(value, (field == "width" or field == "scale") and 1 or 3,
                                    fail)
    elseif key == "following module" then
      local w = words(value)[1]
      if w ~= "yes" and w ~= "no" then fail("following module: yes or no expected") end
      spec.following = w == "yes"
    elseif key == "interpreted modules" then
      spec.interpreted = spec.interpreted or { other = 0 }
      interpreted(value, spec.interpreted, fail)
    elseif key == "when interpret" then
      spec.interpreted = spec.interpreted or { other = 0 }
      wheninterpret(value, spec.interpreted, fail, format("%s:%d", path, n))
    elseif key == "verbose" then
      spec.verbose = words(value)[1] == "on"
    elseif REFUSED[key] then
      fail(format("%s: lsys does not send %s", key, REFUSED[key]))
    else
      warning.warn(format("lsys: %s:%d: unknown directive '%s' in a communication file: "
                          .. "skipped", path, n, key))
    end
  end
  f:close()
  if spec.argv == nil then
    error(format("%s: no 'executable:' line: which program answers the queries?", path), 0)
  end
  if spec.transport ~= "memory" then
    spec.max = (max and max > 0) and max or MAX[spec.transport]
  end
  -- the program gets the file as cpfg gives it: -e FILE first, unless it says so itself
  local argv = spec.argv
  if not (argv[2] and argv[2]:sub(1, 2) == "-e") then
    table.insert(argv, 2, "-e")
    table.insert(argv, 3, spec.name)
  end
  return spec
end

return M
