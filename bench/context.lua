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

local script = arg and arg[0] or "bench/context.lua"
local B = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/common.lua")
local root = B.root
local lsys = B.load_lsys()
local RUNS = 3
local PEER_TIMEOUT = 600          -- seconds per peer run

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

local function main ()
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
end

main()
