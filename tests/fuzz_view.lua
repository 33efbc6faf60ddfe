--- Mutation fuzzer for the cpfg view file reader (lsys.view.parse / load).
--
--   lua5.4 tests/fuzz_view.lua [iterations [seed]]     (from the source directory)
--
-- Starts from the view files in tests/data/views and a few built-in lines, and makes
-- `iterations` variants (20000 by default) with a seeded generator of its own, so a run
-- is the same on every machine: bytes replaced, lines inserted (known commands with
-- random values, unknown commands, comment markers, binary junk), lines deleted or
-- repeated, text truncated. Each variant must either load to a table that
-- lsys.view.normalize accepts (with the file-based options left out: their files do not
-- exist), or fail with a string "fuzz.v:LINE: ...": never a Lua runtime error, a
-- non-string error, or a message without the file and line. Every 97th variant also
-- goes through view.load from a temporary file.
--
-- tests/viewfuzz_spec.lua runs 2000 iterations under busted; require-ing this file
-- returns the function run(iterations, seed) -> counts, or raises on the first failure.
if not package.path:find("./lua/?.lua", 1, true) then
  package.path = "./lua/?.lua;./lua/?/init.lua;" .. package.path
end
local view = require "lsys.view"

-- xorshift64*: the same sequence for a seed on every platform (Lua 5.4 integers wrap).
local function generator (seed)
  local x = seed ~ 0x2545F4914F6CDD1D
  if x == 0 then x = 1 end
  return function (n)                 -- an integer in 1..n
    x = x ~ (x >> 12); x = x ~ (x << 25); x = x ~ (x >> 27)
    local r = (x * 0x2545F4914F6CDD1D) >> 11   -- 53 bits, non-negative
    return r % n + 1
  end
end

local function readfile (path)
  local f = assert(io.open(path, "rb"))
  local s = f:read("a")
  f:close()
  return s
end

local SEEDS = {
  readfile("tests/data/views/plant.v"),
  readfile("tests/data/views/legacy.v"),
  "angle factor: 8\ninitial color: 1\nviewpoint: 0,0,1\nview reference point: 0,0,0\n",
  "texture: F: a.png H: l L: m E: b S: R: 2\nsurface: A a.s 1 4 4 1\nsurface: B b.s 2 1\n",
  "tropism: T: 0 1 0 I: 0.5 A: 10\ntorque: T: 1 0 0 A: 5 E: 1 S: 2\n" ..
    "light: O: 1 2 3 P: 0 0 1 10 45 T: 1 0 0\nlight: A: 1 1 1\n",
}

local LABELS = {}
for _, l in ipairs {
  "angle factor", "angle increment", "initial color", "initial colour", "color increment",
  "initial line width", "line width increment", "line style", "viewpoint",
  "view reference point", "twist", "projection", "viewing angle", "light direction", "light",
  "background color", "contour", "contour sides", "polygonization level",
  "twist of cylinders", "texture", "tropism", "torque", "tropism direction",
  "initial elasticity", "elasticity increment", "surface", "z buffer", "front distance",
  "render mode", "shadow map", "interpretation past %", "bogus", "", "Angle  Factor",
} do LABELS[#LABELS + 1] = l end

local ATOMS = {
  "0", "1", "-1", "2.5", "1e999", "-1e999", "nan", "inf", "0x10", "1e-320", "3", "64", "65",
  "1024", "1025", "65536", "-0", "9", "10", ",", ",,", "x", "on", "off", "pixels", "polygons",
  "p", "parallel", "perspective", "cylinder", "pixel", "polygon", "4", "T:", "A:", "E:",
  "S:", "F:", "H:", "L:", "R:", "I:", "V:", "D:", "O:", "P:", "l", "n", "m", "d", "b",
  "a.png", "sub/a.con", "/*", "*/", "//", "#", ":", "\0", "\255", "é", "~", "0,0,0",
  "1,2,3", "1 2 3", "0,-1,0",
}

local function randomline (rnd)
  local parts = { LABELS[rnd(#LABELS)], ":" }
  for _ = 1, rnd(7) - 1 do
    parts[#parts + 1] = rnd(4) == 1 and " " or ""
    parts[#parts + 1] = " " .. ATOMS[rnd(#ATOMS)]
  end
  if rnd(8) == 1 then parts[1] = ATOMS[rnd(#ATOMS)] end
  return table.concat(parts)
end

local function mutate (rnd, s)
  for _ = 1, rnd(4) do
    local op = rnd(7)
    local n = #s
    if op == 1 and n > 0 then                          -- replace a byte
      local i = rnd(n)
      s = s:sub(1, i - 1) .. string.char(rnd(256) - 1) .. s:sub(i + 1)
    elseif op == 2 then                                -- insert a command line
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. "\n" .. randomline(rnd) .. "\n" .. s:sub(i)
    elseif op == 3 then                                -- insert an atom anywhere
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. ATOMS[rnd(#ATOMS)] .. s:sub(i)
    elseif op == 4 then                                -- truncate
      s = s:sub(1, rnd(n + 1) - 1)
    elseif op == 5 and n > 0 then                      -- delete a range
      local i = rnd(n)
      s = s:sub(1, i - 1) .. s:sub(i + rnd(20))
    elseif op == 6 then                                -- repeat a line
      local lines = {}
      for l in (s .. "\n"):gmatch("([^\n]*)\n") do lines[#lines + 1] = l end
      local k = rnd(#lines)
      table.insert(lines, k, lines[k])
      s = table.concat(lines, "\n")
    else                                               -- a line of random bytes
      local b = {}
      for j = 1, rnd(30) do b[j] = string.char(rnd(256) - 1) end
      local i = rnd(n + 1)
      s = s:sub(1, i - 1) .. table.concat(b) .. s:sub(i)
    end
  end
  return s
end

-- The options whose files are read by normalize are dropped; the rest must pass.
local function strip (v)
  local out = {}
  for k, x in pairs(v) do
    if k ~= "contours" and k ~= "surfaces" and k ~= "textures" then out[k] = x end
  end
  return out
end

local function check (ok, r, text, name)
  local function failure (what)
    error(("fuzz_view: %s\n--- input (%d bytes) ---\n%s\n--- end ---"):format(what, #text,
          text:gsub("[%z\1-\8\11-\31\127-\255]", function (c)
            return ("\\%d"):format(c:byte())
          end)), 0)
  end
  if ok then
    if type(r) ~= "table" then failure("parse returned a " .. type(r)) end
    local nok, nr = pcall(view.normalize, strip(r), "fuzz")
    if not nok then failure("normalize rejected the parsed view: " .. tostring(nr)) end
    return "ok"
  end
  if type(r) ~= "string" then failure("a " .. type(r) .. " error") end
  local pat = "^" .. name:gsub("%p", "%%%0") .. ":%d+: "
  if not r:find(pat) then failure("error without file and line: " .. r) end
  if r:find("attempt to", 1, true) or r:find("view.lua", 1, true) then
    failure("runtime error: " .. r)
  end
  return "error"
end

local function run (iterations, seed)
  iterations = iterations or 20000
  local rnd = generator(seed or 20240611)
  local counts = { ok = 0, error = 0 }
  local tmp = os.tmpname()
  for it = 1, iterations do
    local text = mutate(rnd, SEEDS[rnd(#SEEDS)])
    local ok, r = pcall(view.parse, text, "fuzz.v", { quiet = true })
    local kind = check(ok, r, text, "fuzz.v")
    counts[kind] = counts[kind] + 1
    if it % 97 == 0 then                               -- the same through a file
      local f = assert(io.open(tmp, "wb"))
      f:write(text)
      f:close()
      local lok, lr = pcall(view.load, tmp, { quiet = true })
      check(lok, lr, text, tmp)
      if lok ~= ok then error("fuzz_view: load and parse disagree on a variant", 0) end
    end
  end
  os.remove(tmp)
  return counts
end

if arg and arg[0] and arg[0]:match("fuzz_view%.lua$") then
  local n = tonumber(arg[1]) or 20000
  local counts = run(n, tonumber(arg[2]))
  print(("fuzz_view: %d variants: %d loaded, %d rejected with file:line"):format(n, counts.ok,
        counts.error))
end

return run
