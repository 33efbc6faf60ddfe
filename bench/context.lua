-- Context-sensitive derivation benchmark: modules produced per second by lsys on
-- context-sensitive models, side by side with the npm package lindenmayer (bench/peers/).
--
--   build/bin/lsys bench/context.lua
--
-- Models: (s) a signal: the axiom b followed by 5,000 a, the rule b < a --> b, 5,000 steps
-- (the signal walks to the end; each step rewrites all 5,001 modules); (h) ABOP fig. 1.31a-e,
-- Hogeweg and Hesper's plants, context across branches with F, + and - ignored
-- (examples/abop/fig1_31?.lua, 26 to 30 steps). Modules/s = sum of the string lengths over
-- all steps / derivation time, best of 3, in this process. The peer runs the same rules in
-- node (lindenmayer's classic context syntax, ignoredSymbols, branchSymbols "[]"); its final
-- string is compared with lsys's by a hash: lsys's strings are cpfg's (checked with cpfg
-- built from vlab), and a peer whose context matching differs is reported as "differs".
-- Plain Lua works too: LUA_PATH='./lua/?.lua;./lua/?/init.lua;;' LUA_CPATH='./build/?.so;;'
-- lua5.4 bench/context.lua
--
-- With cpfg (`--cpfg PATH`, or CPFG=PATH: a cpfg built for batch use, docs/cpfg.md), both
-- programs also derive fig. 1.31a-e grown to millions of modules (55 steps, b 50) and (p), a
-- parametric model whose signal crosses branches with its parameters, as whole processes:
-- wall clock, best of 5, the same process at 0 steps subtracted, cpfg with `-g -strb` and
-- CPFG_SKIP_VV=1, peak memory from GNU time. Target (issue 41): at least 3x cpfg's speed,
-- peak memory at most cpfg's. The strings agree with cpfg's (fig. 1.31 exactly; (p) module
-- for module, its numbers in cpfg's single precision).

local script = arg and arg[0] or "bench/context.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local root = B.root
local lsys = B.load_lsys()
local RUNS = 3
local PEER_TIMEOUT = 600          -- seconds per peer run
local BIG = { a = 55, b = 50, c = 55, d = 55, e = 55 }   -- steps of fig. 1.31 against cpfg
                                  -- (b passes 50 M modules, max_modules, at 53)

-- (p): a signal from the base through the branches, with parameters (both contexts)
local PARAM = {
  name = "(p) parametric signal across branches", steps = 12, ignore = "+-/",
  axiom = "I(1,0)A(0)",
  rules = {
    "A(n) : n < 30 --> I(0,n)/(137)[+A(n+1)][-A(n+1)]I(0,n)A(n+1)",
    "I(a,d) < I(b,e) > A(n) --> I(b + a * 0.25 + n, e)",
    "I(a,d) < I(b,e) --> I(b + a * 0.5, e)",
  },
}

-- The signal model, and a Hogeweg plant read from its example file.
local function signal ()
  return { name = "(s) signal b < a --> b, b + 5000 a", steps = 5000,
           axiom = "b" .. string.rep("a", 5000), ignore = "", rules = { { "b<a", "b" } } }
end

local function hogeweg (letter)
  local path = string.format("%s/examples/abop/fig1_31%s.lua", root, letter)
  local text = assert(B.read_file(path), "cannot read " .. path)
  local m = { name = "(h) ABOP fig. 1.31" .. letter, file = path, rules = {} }
  m.axiom = text:match('axiom = "([^"]+)"')
  m.steps = tonumber(text:match("steps = (%d+)"))
  m.ignore = text:match('ignore = "([^"]*)"') or ""
  for line in text:match("productions = %[%[(.-)%]%]"):gmatch("[^\n]+") do
    local lhs, rhs = line:match("^%s*(.-)%s*%-%->%s*(.-)%s*$")
    if lhs then m.rules[#m.rules + 1] = { (lhs:gsub("%s", "")), (rhs:gsub("%s", "")) } end
  end
  return m
end

-- 32-bit FNV-1a of a string (as the peer computes it).
local function fnv1a (s)
  local h = 0x811c9dc5
  for i = 1, #s do h = ((h ~ s:byte(i)) * 0x01000193) & 0xffffffff end
  return h
end

local function measure_lsys (m)
  local model
  if m.file then
    model = dofile(m.file)
  else
    local rules = {}
    for i, r in ipairs(m.rules) do rules[i] = r[1]:gsub("<", " < ") .. " --> " .. r[2] end
    model = lsys.lsystem { axiom = m.axiom, steps = m.steps, productions = rules,
                           ignore = m.ignore ~= "" and m.ignore or nil }
  end
  local modules = 0
  model:derive(m.steps, { each = function (k, s) if k > 0 then modules = modules + #s end end })
  local t, s = B.best(function () return model:derive(m.steps) end, RUNS)
  return { seconds = t, modules = modules, length = #s, hash = fnv1a(tostring(s)) }
end

-- A JSON object for the peer (strings only need quotes and backslashes escaped here).
local function json (m)
  local function q (s) return '"' .. s:gsub('[\\"]', "\\%0") .. '"' end
  local prods = {}
  for _, r in ipairs(m.rules) do prods[#prods + 1] = q(r[1]) .. ":" .. q(r[2]) end
  return string.format('{"axiom":%s,"productions":{%s},"ignore":%s,"steps":%d}', q(m.axiom),
    table.concat(prods, ","), q(m.ignore), m.steps)
end

local function measure_peer (node, m)
  local js = root .. "/bench/peers/context_lindenmayer.js"
  local out, ok = B.capture(string.format("timeout %d %s %s %s", PEER_TIMEOUT,
    B.shell_quote(node), B.shell_quote(js), B.shell_quote(json(m))))
  local line = out:match("(%b{})")
  if not ok or not line then return nil, (out:match("[^\n]+") or "no output"):sub(1, 100) end
  local r = {}
  for k, v in line:gmatch('"([%w_]+)":"?([^,"}]*)"?') do r[k] = tonumber(v) or v end
  return r
end

-- The lsys model of fig. 1.31`letter` ("p": PARAM) for `steps` steps.
local function big_model (letter, steps)
  if letter == "p" then
    return lsys.lsystem { axiom = PARAM.axiom, ignore = PARAM.ignore, steps = steps,
                          productions = PARAM.rules }
  end
  local model = dofile(string.format("%s/examples/abop/fig1_31%s.lua", root, letter))
  return model
end

-- The same as a cpfg .l file.
local function cpfg_text (letter, steps)
  local m = letter == "p" and PARAM or hogeweg(letter)
  local rules = {}
  for i, r in ipairs(m.rules) do
    rules[i] = type(r) == "string" and r
      or (r[1]:gsub("<", " < "):gsub(">", " > ") .. " --> " .. r[2])
  end
  return string.format("Lsystem: 1\nderivation length: %d\nignore: %s\nAxiom: %s\n%s\nendlsystem\n",
    steps, m.ignore, m.axiom, table.concat(rules, "\n"))
end

-- lsys and cpfg on fig. 1.31`letter` (or "p"), whole processes, start-up subtracted.
local function versus_cpfg (cpfg, dir, letter)
  local steps = letter == "p" and PARAM.steps or BIG[letter]
  local R = 5
  local function lfile (n)
    local path = string.format("%s/%s%d.l", dir, letter, n)
    B.write_file(path, cpfg_text(letter, n))
    return path
  end
  local function ccmd (n)
    return string.format("env CPFG_SKIP_VV=1 %s -g -m %s/e.map -strb /dev/null %s %s/e.v",
      B.shell_quote(cpfg), dir, B.shell_quote(lfile(n)), dir)
  end
  local function lcmd (n)
    return B.self_command() .. " whole " .. letter .. " " .. n .. " >/dev/null"
  end
  local modules = B.measure("count " .. letter .. " " .. steps).modules
  local ct, lt, cpeak, lpeak, c0, l0 = B.versus(ccmd(0), ccmd(steps), lcmd(0), lcmd(steps), R)
  return { steps = steps, modules = modules, cpfg = modules / ct,
           lsys = modules / lt, cpeak = cpeak, lpeak = lpeak,
           cstart = c0, lstart = l0 }
end

local function cpfg_table (cpfg)
  local dir = B.cpfg_folder()
  print()
  print("cpfg: " .. cpfg .. " (-g -strb, CPFG_SKIP_VV=1); whole process, wall clock, best of 5, "
        .. "start-up subtracted" .. (B.has_time and "" or "; no /usr/bin/time: no peak memory"))
  print(string.format("%-40s %5s %10s %9s %9s %7s %-10s %8s %8s %6s %s", "model", "steps",
    "modules", "lsys M/s", "cpfg M/s", "ratio", "target", "lsys MiB", "cpfg MiB", "ratio",
    "target"))
  for _, letter in ipairs { "a", "b", "c", "d", "e", "p" } do
    local name = letter == "p" and PARAM.name or "(h) ABOP fig. 1.31" .. letter
    local ok, r = pcall(versus_cpfg, cpfg, dir, letter)
    if not ok then
      print(string.format("%-40s failed: %s", name, tostring(r)))
    else
      local ratio, mratio = r.lsys / r.cpfg, r.lpeak and r.cpeak and r.lpeak / r.cpeak
      print(string.format("%-40s %5d %10d %9.1f %9.1f %6.2fx %-10s %8s %8s %6s %s", name,
        r.steps, r.modules, r.lsys / 1e6, r.cpfg / 1e6, ratio, ">=3x " .. B.verdict(ratio >= 3),
        r.lpeak and string.format("%.1f", r.lpeak / 1024) or "?",
        r.cpeak and string.format("%.1f", r.cpeak / 1024) or "?",
        mratio and string.format("%.2fx", mratio) or "?",
        mratio and ("<=1x " .. B.verdict(mratio <= 1)) or ""))
      print(string.format("  (start-up: lsys %.1f ms, cpfg %.1f ms)", r.lstart * 1e3,
        r.cstart * 1e3))
    end
  end
  B.rmdir(dir)
end

local function main (cpfg)
  print(string.format("lsys %s context-sensitive derivation benchmark (%s; best of %d, %s)",
    lsys.version or "?", _VERSION, RUNS, B.clock_name))
  local models = { signal() }
  for _, l in ipairs { "a", "b", "c", "d", "e" } do models[#models + 1] = hogeweg(l) end

  local node = B.node_path()
  local installed = B.read_file(root .. "/bench/peers/node_modules/lindenmayer/package.json")
  local peer = node and installed
  if not node then
    print("peer: skipped, node is not installed")
  elseif not installed then
    print("peer: skipped, lindenmayer is not installed: npm ci --prefix " .. root
          .. "/bench/peers")
  else
    print(string.format("peer: lindenmayer %s (node %s); ratio = lsys / lindenmayer",
      installed:match('"version"%s*:%s*"([^"]+)"') or "?",
      B.capture(B.shell_quote(node) .. " --version"):match("%S+") or "?"))
  end
  print()
  print(string.format("%-36s %5s %10s %8s %9s  %10s %9s %7s  %s", "model", "steps",
    "modules", "length", "lsys M/s", "peer M/s", "peer MiB", "ratio", "same string"))
  for _, m in ipairs(models) do
    local l = measure_lsys(m)
    local rate = l.modules / l.seconds / 1e6
    local cols = ""
    if peer then
      local p, why = measure_peer(node, m)
      if p then
        local prate = p.modules / p.seconds / 1e6
        cols = string.format("%10.2f %9.1f %6.1fx  %s", prate, p.peak_kib / 1024,
          rate / prate, (p.hash == l.hash and p.length == l.length) and "yes"
          or string.format("differs (peer: %d modules)", p.length))
      else
        cols = "peer failed: " .. why
      end
    end
    print(string.format("%-36s %5d %10d %8d %9.1f  %s", m.name, m.steps, l.modules, l.length,
      rate, cols))
  end
  print()
  print(string.format("lsys peak memory: %.1f MiB (this process, all models)", B.peak_mib()
    or -1))
  if cpfg then cpfg_table(cpfg)
  else print("\ncpfg: not given (--cpfg PATH or CPFG=PATH; docs/cpfg.md says how to build it)") end
end

local mode = arg and arg[1]
if mode == "whole" or mode == "count" then       -- a child: one model in this process
  local letter, steps = arg[2], tonumber(arg[3])
  local model = big_model(letter, steps)
  if mode == "whole" then
    io.write(#model:derive(steps), "\n")
  else
    local modules = 0
    model:derive(steps, { each = function (k, s) if k > 0 then modules = modules + #s end end })
    io.write(string.format("RESULT modules=%d\n", modules))
  end
elseif mode == nil or (mode == "--cpfg" and arg[2]) then
  local cpfg = mode == "--cpfg" and arg[2] or os.getenv("CPFG")
  main(cpfg ~= "" and cpfg or nil)
else
  io.stderr:write("usage: context.lua [--cpfg PATH]\n")
  os.exit(2)
end
