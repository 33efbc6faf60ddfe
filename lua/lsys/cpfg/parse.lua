--- The parser of cpfg's L-system files (after preprocessing): a syntax tree of L-systems,
-- productions, C-like expressions and statements, every node with its position (`pos`)
-- that `where` turns into the file and line it came from. The grammar follows cpfg's
-- lsys_input.y and lsys_input.l (read as documentation).
-- @module lsys.cpfg.parse
local error, tonumber, setmetatable, ipairs, next, require = error, tonumber, setmetatable,
  ipairs, next, require
local concat = table.concat
local format = string.format
local _ENV = nil

local warning = require "lsys.warning"

local M = {}

local P = {}
P.__index = P

--- A parser over located lines ({ file =, line =, text = }).
function M.new (lines)
  local parts, starts, locs, pos = {}, {}, {}, 1
  for i, l in ipairs(lines) do
    parts[i] = l.text
    starts[i] = pos
    locs[i] = l
    pos = pos + #l.text + 1
  end
  return setmetatable({ src = concat(parts, "\n") .. "\n", starts = starts, locs = locs,
                        pos = 1, blocks = 0, nstrings = 0, stray = {} }, P)
end

--- The file and line of source position `pos`.
function P:where (pos)
  local s, lo, hi = self.starts, 1, #self.starts
  if hi == 0 then return "?", 0 end
  while lo < hi do
    local mid = (lo + hi + 1) // 2
    if s[mid] <= pos then lo = mid else hi = mid - 1 end
  end
  local l = self.locs[lo]
  return l.file, l.line
end

function P:fail (pos, fmt, ...)
  local file, line = self:where(pos or self.pos)
  error({ cpfg = true, msg = format("%s:%d: " .. fmt, file, line, ...) }, 0)
end

-- White space: blanks, a newline followed by a tab (a continued line, as in cpfg), and
-- inside statement blocks every newline.
function P:sp ()
  local src = self.src
  while true do
    local _, e = src:find("^[ \t\r\f\v]+", self.pos)
    if e then self.pos = e + 1 end
    if src:sub(self.pos, self.pos + 1) == "\n\t" then
      self.pos = self.pos + 1
    elseif self.blocks > 0 and src:sub(self.pos, self.pos) == "\n" then
      self.pos = self.pos + 1
    else
      return
    end
  end
end

function P:eof () return self.pos > #self.src end

-- At the end of a line (after blanks)?
function P:ateol ()
  self:sp()
  return self:eof() or self.src:sub(self.pos, self.pos) == "\n"
end

function P:eol (what)
  if not self:ateol() then
    self:fail(nil, "unexpected '%s' after %s", self:rest(), what)
  end
  self.pos = self.pos + 1
end

function P:rest ()
  local line = self.src:match("^[^\n]*", self.pos)
  if #line > 30 then line = line:sub(1, 30) .. "..." end
  return line
end

-- Skips blank lines; returns false at the end of the text.
function P:blanklines ()
  while true do
    self:sp()
    if self:eof() then return false end
    if self.src:sub(self.pos, self.pos) ~= "\n" then return true end
    self.pos = self.pos + 1
  end
end

-- Keywords, recognised at the start of a line as cpfg's lexer does.
local KEYWORDS = {
  { "lsystem", { "^[Ll]system:" } },
  { "seed", { "^[Ss]eed:" } },
  { "dlength", { "^[Dd]erivation ?[Ll]ength:" } },
  { "mdepth", { "^[Mm]aximum [Dd]epth:" } },
  { "consider", { "^[Cc]onsider:" } },
  { "ignore", { "^[Ii]gnore:" } },
  { "axiom", { "^[Aa]xiom:" } },
  { "define", { "^[Dd]efine:" } },
  { "ring", { "^[Rr]ing [Ll]system" } },
  { "starteach", { "^[Ss]tart ?[Ee]ach:" } },
  { "endeach", { "^[Ee]nd ?[Ee]ach:" } },
  { "start", { "^[Ss]tart:" } },
  { "endlsystem", { "^[Ee]nd[Ll]system" } },
  { "end", { "^[Ee]nd:" } },
  { "homomorphism", { "^[Hh]omomorphism:?" } },
  { "decomposition", { "^[Dd]ecomposition:?" } },
  { "nowarnings", { "^no warnings" } },
  { "warnings", { "^warnings" } },
}

function P:keyword ()
  self:sp()
  for _, k in ipairs(KEYWORDS) do
    local _, e = self.src:find(k[2][1], self.pos)
    if e then return k[1], e + 1 end
  end
end

function P:take (kw)
  local k, e = self:keyword()
  if k == kw then self.pos = e; return true end
  return false
end

-- Expressions ------------------------------------------------------------------------

local OPS = { "-->", "-o>", "<>", "!=", "==", "<=", ">=", "&&", "||",
              "=", "&", "+", "-", "*", "/", "%", "^", ";", ",", "?", ":", "(", ")", "[",
              "]", "<", ">", "!", "{", "}" }

-- The text of a string literal as cpfg's lexer makes it (lsys_input.l ProcessString):
-- \n, \t and \r are control characters, a backslash before any other character is
-- dropped.
local ESCAPES = { n = "\n", t = "\t", r = "\r" }
local function unescape (s)
  return (s:gsub("\\(.?)", function (c) return ESCAPES[c] or c end))
end

-- A character that no rule of cpfg's expression lexer matches: flex's default rule
-- echoes it and goes on, so it is skipped here too, with a warning (vlab's fern-leaf
-- model has `dx = \ (0.33 * ...)`, a macro continued with "\\"). A parser made with
-- `strict` (the #if of the built-in preprocessor) fails instead.
function P:skipstray (i)
  local c = self.src:sub(i, i)
  if self.strict then self:fail(i, "unexpected character '%s' in an expression", c) end
  if not self.stray[i] then
    self.stray[i] = true
    local file, line = self:where(i)
    local shown = c:find("^[%g ]$") and c or format("\\%d", c:byte())
    warning.warn(format("%s:%d: stray '%s' in an expression ignored (as cpfg does)", file,
                        line, shown))
  end
  self.pos = i + 1
end

-- The next token of an expression: kind ("num", "name", "str", "op", "eol"), value, and
-- its start and end positions. A string's value is its text.
function P:etok ()
  while true do
    self:sp()
    local src, i = self.src, self.pos
    if i > #src or src:sub(i, i) == "\n" then return "eol", nil, i, i end
    local a, e = src:find("^%d+%.%d*[eE][-+]?%d+", i)
    if not a then a, e = src:find("^%d*%.%d+[eE][-+]?%d+", i) end
    if not a then a, e = src:find("^%d+%.%d*", i) end
    if not a then a, e = src:find("^%d*%.%d+", i) end
    if not a then a, e = src:find("^%d+", i) end
    if a then return "num", tonumber(src:sub(a, e)), i, e + 1 end
    a, e = src:find("^%a[%w_]*", i)
    if a then return "name", src:sub(a, e), i, e + 1 end
    if src:sub(i, i) == '"' then
      local q = src:find('["\n]', i + 1)
      if not q or src:sub(q, q) ~= '"' then self:fail(i, "unterminated string") end
      return "str", unescape(src:sub(i + 1, q - 1)), i, q + 1
    end
    for _, op in ipairs(OPS) do
      if src:sub(i, i + #op - 1) == op then return "op", op, i, i + #op end
    end
    self:skipstray(i)
  end
end

function P:isop (op)
  local k, v = self:etok()
  return k == "op" and v == op
end

function P:accept (op)
  local k, v, _, e = self:etok()
  if k == "op" and v == op then self.pos = e; return true end
  return false
end

function P:expect (op, what)
  if not self:accept(op) then
    local k, v = self:etok()
    self:fail(nil, "'%s' expected %s, found %s", op, what,
              k == "eol" and "the end of the line" or "'" .. (v or "") .. "'")
  end
end

-- cpfg's reserved names (lsys_input.l CheckReserved).
local RESERVED = {}
for n in ([[if while do else array tan sin atan2 cos atan asin acos ran nran bran biran srand
  exp log floor ceil sign sqrt trunc fabs inblob stop printf fprintf fopen fclose fflush
  fscanf func play curveX curveY curveZ curveGAL SetDerivationLength GetDerivationLength
  vvXmin vvXmax vvYmin vvYmax vvZmin vvZmax vvScale Display]]):gmatch("%S+") do
  RESERVED[n] = true
end
M.RESERVED = RESERVED

local BINARY = {
  ["||"] = 1, ["&&"] = 2, ["=="] = 3, ["!="] = 3, ["<>"] = 3,
  ["<"] = 4, ["<="] = 4, [">="] = 4, [">"] = 4,
  ["+"] = 5, ["-"] = 5, ["*"] = 6, ["/"] = 6, ["%"] = 6, ["^"] = 7,
}

-- The recursion of the parser: parentheses, which leave no node, nest up to about 300
-- levels (MAXHEIGHT below limits the rest).
function P:depth (d)
  if d > 1000 then self:fail(nil, "expression nested too deeply (parentheses)") end
end

-- The highest expression tree and the deepest nest of statement blocks the parser takes:
-- the Lua source and the lsys rule strings they become nest as deeply, and Lua's parser
-- and lsys's expression compiler stop at about 200 levels (a C stack overflow).
local MAXHEIGHT, MAXBLOCKS = 64, 16
M.MAXHEIGHT, M.MAXBLOCKS = MAXHEIGHT, MAXBLOCKS

-- Node `n` over the expressions `kids`: one level higher than the highest of them.
function P:node (n, kids)
  local h = 0
  for _, x in ipairs(kids) do if x.h > h then h = x.h end end
  n.h = h + 1
  if n.h > MAXHEIGHT then
    self:fail(n.pos, "expression nested too deeply (more than %d levels of operators and "
              .. "calls)", MAXHEIGHT)
  end
  return n
end

function P:primary (d)
  self:depth(d)
  local k, v, s, e = self:etok()
  if k == "num" then
    self.pos = e
    return { k = "num", v = v, pos = s, h = 1 }
  elseif k == "str" then
    -- cpfg numbers the strings of the file in order (GlobalStringIndex): a string used
    -- as a value is its number
    self.pos = e
    self.nstrings = self.nstrings + 1
    return { k = "str", v = v, index = self.nstrings - 1, pos = s, h = 1 }
  elseif k == "name" then
    self.pos = e
    if RESERVED[v] then
      if v == "if" or v == "while" or v == "do" or v == "else" or v == "array" then
        self:fail(s, "'%s' cannot start an expression", v)
      end
      self:expect("(", "after " .. v)
      local args = {}
      if not self:isop(")") then
        repeat args[#args + 1] = self:expr(d + 1) until not self:accept(",")
      end
      self:expect(")", "after the arguments of " .. v)
      return self:node({ k = "call", f = v, args = args, pos = s }, args)
    end
    local node = { k = "name", n = v, pos = s, h = 1 }
    if self:isop("[") then
      local idx = {}
      while self:accept("[") do
        idx[#idx + 1] = self:expr(d + 1)
        self:expect("]", "after an array index")
      end
      node = self:node({ k = "index", n = v, idx = idx, pos = s }, idx)
    end
    return node
  elseif k == "op" and v == "(" then
    self.pos = e
    local x = self:expr(d + 1)
    self:expect(")", "to close '('")
    return x
  elseif k == "op" and (v == "-" or v == "!") then
    self.pos = e
    local a = self:primary(d + 1)
    return self:node({ k = "un", op = v, a = a, pos = s }, { a })
  elseif k == "op" and v == "&" then
    self:fail(s, "'&' (the address of a variable, for fscanf) is not supported")
  end
  self:fail(s, "an expression expected, found %s",
            k == "eol" and "the end of the line" or "'" .. (v or "") .. "'")
end

function P:binary (minp, d)
  self:depth(d)
  local left = self:primary(d + 1)
  while true do
    local k, v, s, e = self:etok()
    local p = k == "op" and BINARY[v]
    if not p or p < minp then return left end
    self.pos = e
    local right = self:binary(p + 1, d + 1)
    left = self:node({ k = "bin", op = v == "<>" and "!=" or v, a = left, b = right, pos = s },
                     { left, right })
  end
end

--- An expression (cpfg's precedence: ?: < || < && < == != < relations < + - < * / % < ^
-- < unary - and !; all binary operators left-associative).
function P:expr (d)
  d = d or 0
  self:depth(d)
  local c = self:binary(1, d + 1)
  local _, _, s = self:etok()
  if self:accept("?") then
    local a = self:expr(d + 1)
    self:expect(":", "in '? :'")
    local b = self:expr(d + 1)
    return self:node({ k = "cond", c = c, a = a, b = b, pos = s }, { c, a, b })
  end
  return c
end

-- Statements -------------------------------------------------------------------------

function P:block (d)
  d = d or 0
  self:depth(d)
  self:sp()
  local s = self.pos
  self:expect("{", "to start a block")
  self.blocks = self.blocks + 1
  if self.blocks > MAXBLOCKS then
    self:fail(s, "statement blocks nested too deeply (more than %d)", MAXBLOCKS)
  end
  local list = {}
  while not self:accept("}") do
    if self:eof() then self:fail(s, "block not closed with '}'") end
    list[#list + 1] = self:statement(d + 1)
  end
  self.blocks = self.blocks - 1
  return list
end

function P:statement (d)
  local k, v, s, e = self:etok()
  if k == "name" and v == "if" then
    self.pos = e
    self:expect("(", "after if")
    local c = self:expr(d)
    self:expect(")", "after the condition of if")
    local body = self:block(d + 1)
    local k2, v2, _, e2 = self:etok()
    local other
    if k2 == "name" and v2 == "else" then
      self.pos = e2
      other = self:block(d + 1)
    end
    return { k = "if", c = c, body = body, other = other, pos = s }
  elseif k == "name" and v == "while" then
    self.pos = e
    self:expect("(", "after while")
    local c = self:expr(d)
    self:expect(")", "after the condition of while")
    return { k = "while", c = c, body = self:block(d + 1), pos = s }
  elseif k == "name" and v == "do" then
    self.pos = e
    local body = self:block(d + 1)
    local k2, v2, _, e2 = self:etok()
    if k2 ~= "name" or v2 ~= "while" then self:fail(nil, "'while' expected after do { }") end
    self.pos = e2
    self:expect("(", "after while")
    local c = self:expr(d)
    self:expect(")", "after the condition of do-while")
    self:expect(";", "after do-while")
    return { k = "do", c = c, body = body, pos = s }
  elseif k == "name" and v == "array" then
    self:fail(s, "'array' is allowed only in define: blocks")
  end
  local x = self:expr(d)
  if self:accept("=") then
    if x.k ~= "name" and x.k ~= "index" then
      self:fail(s, "the left side of '=' must be a variable or an array element")
    end
    local rhs = self:expr(d)
    self:expect(";", "after an assignment")
    return { k = "assign", lhs = x, e = rhs, pos = s }
  end
  self:expect(";", "after a statement")
  return { k = "expr", e = x, pos = s }
end

-- define: { array a[3] = { 1, 2, 3 }, b[2][2]; }
function P:defineblock ()
  self:sp()
  local s = self.pos
  self:expect("{", "after define:")
  self.blocks = self.blocks + 1
  local arrays = {}
  while not self:accept("}") do
    if self:eof() then self:fail(s, "define: block not closed with '}'") end
    local k, v, s2, e = self:etok()
    if k ~= "name" or v ~= "array" then
      self:fail(s2, "only 'array' definitions are supported in define: blocks")
    end
    self.pos = e
    repeat
      local k3, name, s3, e3 = self:etok()
      if k3 ~= "name" or RESERVED[name] then self:fail(s3, "an array name expected") end
      self.pos = e3
      local dims = {}
      while self:accept("[") do
        dims[#dims + 1] = self:expr()
        self:expect("]", "after an array dimension")
      end
      if #dims == 0 then self:fail(s3, "array %s needs a dimension", name) end
      local init
      if self:accept("=") then
        self:expect("{", "to start the values of array " .. name)
        init = {}
        if not self:isop("}") then
          repeat init[#init + 1] = self:expr() until not self:accept(",")
        end
        self:expect("}", "after the values of array " .. name)
      end
      arrays[#arrays + 1] = { name = name, dims = dims, init = init, pos = s3 }
    until not self:accept(",")
    self:expect(";", "after an array definition")
  end
  self.blocks = self.blocks - 1
  return arrays
end

-- Modules ----------------------------------------------------------------------------

-- cpfg module symbols: one character, not < > : * or white space.
function P:symbol ()
  self:sp()
  local c = self.src:sub(self.pos, self.pos)
  if c == "" or c:find("^[<>:%*%s%(%)]") then return nil end
  local b = self.src:byte(self.pos)
  if b >= 0x7f or b < 0x20 then
    self:fail(nil, "module names are printable ASCII characters in cpfg, found byte 0x%02x", b)
  end
  self.pos = self.pos + 1
  return c
end

-- A list of modules; `formal` reads formal parameter names instead of expressions.
-- Stops at < > : --> * or the end of the line.
function P:modules (formal)
  local list = {}
  while true do
    self:sp()
    if self.src:sub(self.pos, self.pos + 2) == "-->" or
       self.src:sub(self.pos, self.pos + 2) == "-o>" then
      return list
    end
    local s = self.pos
    local c = self:symbol()
    if not c then return list end
    local m = { sym = c, pos = s }
    local prev = list[#list]
    if c == "E" and prev and prev.sym == "?" and not prev.params then
      self.envq = self.envq or prev.pos      -- the first ?E: cpfg's environment module
    end
    -- cpfg's lexer reads a '(' after a symbol as its parameters with blanks between
    -- (lsys_input.l, state SYMBOL): vlab's Lychnis writes `+ (90)`.
    local _, b = self.src:find("^[ \t]*%(", self.pos)
    if b then
      self.pos = b + 1
      m.params = {}
      if formal then
        repeat
          local k, v, s2, e = self:etok()
          if k ~= "name" or RESERVED[v] then
            self:fail(s2, "a formal parameter name expected in %s(...)", c)
          end
          self.pos = e
          m.params[#m.params + 1] = v
        until not self:accept(",")
      else
        repeat m.params[#m.params + 1] = self:expr() until not self:accept(",")
      end
      self:expect(")", "to close the parameters of " .. c)
    end
    list[#list + 1] = m
  end
end

-- Branches in the axiom (`mods`, at `pos`) must close: lsys refuses an axiom that does not
-- balance them, with a message that could not name the line.
function P:brackets (mods, pos)
  local open = 0
  for _, m in ipairs(mods) do
    if m.sym == "[" then open = open + 1
    elseif m.sym == "]" then
      open = open - 1
      if open < 0 then self:fail(m.pos, "']' without '[' in the axiom") end
    end
  end
  if open > 0 then self:fail(pos, "'[' without ']' in the axiom") end
end

-- L-system files ---------------------------------------------------------------------

-- The text of the production that starts at `pos`, continued lines (a newline and a
-- tab) included.
function P:logicalline (pos)
  local src, e = self.src, pos
  while true do
    e = src:find("\n", e, true) or #src + 1
    if src:sub(e + 1, e + 1) ~= "\t" then return src:sub(pos, e - 1) end
    e = e + 1
  end
end

function P:production ()
  local pos = self.pos
  local prod = { pos = pos }
  -- '->' where '-->' is meant reads as a module '-' and a right context '>': say so
  local text = self:logicalline(pos)
  local arrow = text:find("%->")
  if arrow and not text:find("%-%->") and not text:find("%-o>") then
    self:fail(pos + arrow - 1, "'->' is not a production arrow in cpfg; write '-->'")
  end
  local function part ()
    self:sp()
    if self.src:sub(self.pos, self.pos) == "*" then
      self.pos = self.pos + 1
      return {}, true
    end
    return self:modules(true), false
  end
  local a, astar = part()
  self:sp()
  local c = self.src:sub(self.pos, self.pos)
  if c == "<" then
    self.pos = self.pos + 1
    prod.lc = a
    a, astar = part()
    self:sp()
    c = self.src:sub(self.pos, self.pos)
  end
  if astar or #a == 0 then self:fail(pos, "a production needs a predecessor") end
  prod.pred = a
  if c == ">" then
    self.pos = self.pos + 1
    prod.rc = part()
    self:sp()
    c = self.src:sub(self.pos, self.pos)
  end
  if c == ":" then
    self.pos = self.pos + 1
    if self:isop("{") then prod.pre = self:block() end
    self:sp()
    if self.src:sub(self.pos, self.pos) == "*" then   -- no condition: true
      self.pos = self.pos + 1
    else
      prod.cond = self:expr()
    end
    if self:isop("{") then prod.post = self:block() end
  end
  self:sp()
  if self.src:sub(self.pos, self.pos + 2) == "-o>" then
    self:fail(nil, "'-o>' (object productions) is not supported")
  end
  if self.src:sub(self.pos, self.pos + 2) ~= "-->" then
    local r = self:rest()
    self:fail(nil, "'-->' expected in a production, found %s",
              r == "" and "the end of the line" or "'" .. r .. "'")
  end
  self.pos = self.pos + 3
  self:sp()
  if self.src:sub(self.pos, self.pos) == "*" then
    self.pos = self.pos + 1
    prod.succ = {}
  else
    prod.succ = self:modules(false)
  end
  self:sp()
  if self.src:sub(self.pos, self.pos) == ":" then
    self.pos = self.pos + 1
    prod.prob = self:expr()
  end
  self:eol("the production")
  return prod
end

local ENDS = { decomposition = true, homomorphism = true, endlsystem = true }

function P:productions (list)
  while self:blanklines() do
    local k = self:keyword()
    if ENDS[k] then return k end
    if k then self:fail(nil, "'%s' is not allowed among productions", self:rest()) end
    list[#list + 1] = self:production()
  end
  return nil
end

function P:warnings (sect)
  if self:take("nowarnings") then sect.warnings = false
  elseif self:take("warnings") then sect.warnings = true end
  self:eol(sect.name)
end

function P:lsystem ()
  local ls = { pos = self.pos, productions = {} }
  self:sp()
  local label = self.src:match("^[^\n]*", self.pos)
  self.pos = self.pos + #label
  label = label:gsub("%s", "")
  ls.label = label
  ls.id = tonumber(label:match("^[-+]?%d+%.?%d*")) or 0
  self:eol("the L-system label")
  while true do
    if not self:blanklines() then self:fail(nil, "the L-system has no 'Axiom:'") end
    local k, e = self:keyword()
    if k then self.pos = e end
    local s = self.pos
    if k == "ring" then
      ls.ring = true
      self:eol("ring lsystem")
    elseif k == "seed" or k == "dlength" then
      ls[k] = self:expr()
      ls[k .. "pos"] = s
      self:eol(k == "seed" and "the seed" or "the derivation length")
    elseif k == "ignore" or k == "consider" then
      local chars = {}
      while true do
        local c = self:symbol()
        if not c then break end
        chars[#chars + 1] = c
      end
      if ls.ignore or ls.consider then
        self:fail(s, "ignore: and consider: given twice")
      end
      ls[k] = concat(chars)
      self:eol(k)
    elseif k == "define" then
      local arrays = self:defineblock()
      ls.arrays = ls.arrays or {}
      for _, a in ipairs(arrays) do ls.arrays[#ls.arrays + 1] = a end
      self:eol("define:")
    elseif k == "start" or k == "end" or k == "starteach" or k == "endeach" then
      ls[k] = self:block()
      self:eol(k)
    elseif k == "axiom" then
      self:sp()
      if self.src:sub(self.pos, self.pos) == "*" then
        self.pos = self.pos + 1
        ls.axiom = {}
      else
        ls.axiom = self:modules(false)
      end
      ls.axiompos = s
      self:eol("the axiom")
      self:brackets(ls.axiom, s)
      break
    elseif k == "mdepth" then
      self:fail(s, "'maximum depth:' belongs in a decomposition or homomorphism section")
    else
      self:fail(s, "an L-system item or 'Axiom:' expected, found '%s'", self:rest())
    end
  end
  local k = self:productions(ls.productions)
  if k == "decomposition" then
    self:take("decomposition")
    ls.decomposition = { name = "decomposition", productions = {}, pos = self.pos }
    self:warnings(ls.decomposition)
    if self:blanklines() and self:take("mdepth") then
      ls.decomposition.depth = self:expr()
      self:eol("maximum depth")
    end
    k = self:productions(ls.decomposition.productions)
  end
  if k == "homomorphism" then
    self:take("homomorphism")
    ls.homomorphism = { name = "homomorphism", productions = {}, pos = self.pos }
    self:warnings(ls.homomorphism)
    while self:blanklines() do
      if self:take("mdepth") then
        ls.homomorphism.depth = self:expr()
        self:eol("maximum depth")
      elseif self:take("seed") then
        ls.homomorphism.seed = self:expr()
        self:eol("seed")
      else
        break
      end
    end
    k = self:productions(ls.homomorphism.productions)
  end
  if k == "decomposition" or k == "homomorphism" then
    self:fail(nil, "'%s' out of place (decomposition comes before homomorphism, once each)",
              k)
  end
  if k ~= "endlsystem" then self:fail(nil, "'endlsystem' expected") end
  self:take("endlsystem")
  self:eol("endlsystem")
  self:formals(ls)
  return ls
end

-- A formal parameter may not take the name of an array of its L-system: `b[i]` in the
-- production would index the number.
function P:formals (ls)
  local arrays = {}
  for _, a in ipairs(ls.arrays or {}) do arrays[a.name] = true end
  if next(arrays) == nil then return end
  for _, list in ipairs({ ls.productions, ls.decomposition and ls.decomposition.productions,
                          ls.homomorphism and ls.homomorphism.productions }) do
    for _, p in ipairs(list or {}) do
      for _, part in ipairs({ p.lc or {}, p.pred, p.rc or {} }) do
        for _, m in ipairs(part) do
          for _, n in ipairs(m.params or {}) do
            if arrays[n] then
              self:fail(m.pos, "the formal parameter %s has the name of array %s", n, n)
            end
          end
        end
      end
    end
  end
end

--- Parses the whole file: a list of L-systems.
function P:file ()
  local list = {}
  while self:blanklines() do
    if not self:take("lsystem") then
      self:fail(nil, "'Lsystem:' expected, found '%s'", self:rest())
    end
    list[#list + 1] = self:lsystem()
  end
  if #list == 0 then self:fail(1, "no 'Lsystem:' in the file") end
  return list
end

return M
