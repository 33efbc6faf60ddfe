--- Vigour: a tree's resource shared out among its buds by the Borchert-Honda model, from
-- the light each bud receives (Palubicki et al. 2009, "Self-organizing tree models for
-- image synthesis", §4.3, after Borchert and Honda 1984; docs/open.md §2).
--
-- `lsys.environment.vigour { sense = env, alpha =, lambda =, xi =, tropism = }` wraps an
-- environment that senses (lsys.environment.light or .shadow, or a function of one's own)
-- and reads the tree's structure from the string's brackets. Each ?E says what it is by its
-- first parameter:
--
--   ?E(0, Q, v, x, y, z)  a bud (a lateral bud, waiting)
--   ?E(1, Q, v, x, y, z)  an apex (the bud ending a shoot; a tip of the pipe model)
--   ?E(2, Q, v, t, n)     an internode
--
-- A pass asks `sense` about the buds and apices (as ?E of four parameters: their light Q
-- and, when it gives one, the direction V it comes from most), then, over the tree as the
-- brackets make it (an internode bears what follows it up to the end of its branch;
-- a `[` starts a lateral branch):
--
-- 1. basipetally, every internode's Q: the sum of the Q of the buds it bears (eq. 1 of
--    §4.3, Q = Qm + Ql at every branching);
-- 2. acropetally, the vigour: the base gets v = alpha Q (alpha: `alpha`, 2); at a branching
--    with the main axis's light Qm and the lateral's Ql, the lateral gets
--    v (1 - lambda) Ql / (lambda Qm + (1 - lambda) Ql) and the main axis the rest (eq. 2;
--    lambda: `lambda`, 0.5, above 1/2 favours the main axis, the apical control).
--
-- A bud's answer is its role, Q, its vigour v and the direction its shoot is to grow,
-- H + xi V + T made unit (H: the bud's heading; V: the sense's direction, or none; xi:
-- `xi`, 0.3; T: the vector `tropism`, { 0, 0, 0 }: §4.4's weighted sum of the default,
-- optimal and tropism directions); a shoot grows floor(v) metamers of length v / floor(v)
-- (§4.4), which the model's rules say. An internode's answer is its role, the Q it bears,
-- the vigour that enters it, t the apices it bears (its width by the pipe model, w0 t^(1/p))
-- and n the internodes it bears, itself included (Q / n: its branch's light-use, by which
-- §4.5 sheds branches). examples/open/selforg.lua grows a tree so.
--
-- The object's fields sense, alpha, lambda, xi and tropism are its options, and may be
-- changed between derivations (examples/open/wall.lua gives the tree another sense).
--
-- In a stand (lsys.stand), the queries of each plant are shared out within that plant (by
-- the query's `plant` and the stand's `info.lstrings`); directions are in the world's frame.
-- @module lsys.environment.vigour
local type, ipairs, pairs, error, pcall, tostring, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Vigour = {}
Vigour.__index = Vigour

local BUD, APEX, INTERNODE = 0, 1, 2

local function number (opts, k, dflt, lo, hi)
  local v = opts[k]
  if v == nil then return dflt end
  if type(v) ~= "number" or not (v >= lo and v <= hi) then
    error(format("lsys.environment.vigour: %s must be a number from %g to %g", k, lo, hi), 3)
  end
  return v
end

local OPTIONS = { sense = true, alpha = true, lambda = true, xi = true, tropism = true }

--- The environment (see the module's header for the options).
function M.vigour (opts)
  if type(opts) ~= "table" then error("lsys.environment.vigour: an options table expected", 2) end
  for k in pairs(opts) do
    if not OPTIONS[k] then
      error(format("lsys.environment.vigour: unknown option '%s'", tostring(k)), 2)
    end
  end
  local s = opts.sense
  local ok, f = pcall(function () return s.answer end)
  if type(s) ~= "function" and not (ok and type(f) == "function") then
    error("lsys.environment.vigour: sense must be an environment (a function, or an object "
          .. "with an answer method) giving each bud its light", 2)
  end
  local t = opts.tropism or { 0, 0, 0 }
  if type(t) ~= "table" or type(t[1]) ~= "number" or type(t[2]) ~= "number"
     or type(t[3]) ~= "number" then
    error("lsys.environment.vigour: tropism must be a vector { x, y, z }", 2)
  end
  return setmetatable({
    sense = s,
    alpha = number(opts, "alpha", 2, 0, 1e12),
    lambda = number(opts, "lambda", 0.5, 0, 1),
    xi = number(opts, "xi", 0.3, 0, 1e6),
    tropism = { t[1], t[2], t[3] },
  }, Vigour)
end

function Vigour.__tostring () return "lsys.environment.vigour" end

local function forward (self, name, info)
  local s = self.sense
  if type(s) ~= "function" then
    local ok, f = pcall(function () return s[name] end)
    if ok and type(f) == "function" then f(s, info) end
  end
end

function Vigour:start (info) forward(self, "start", info) end
function Vigour:finish (info) forward(self, "finish", info) end

-- The light of the buds: `sense` asked about them as ?E of four parameters. Returns the
-- list of Q and the list of directions (a vector, or false), one each a bud.
local function sensed (self, queries, buds, info)
  local asked = {}
  for j, i in ipairs(buds) do
    local c = {}
    for k, v in pairs(queries[i]) do c[k] = v end
    c.params = { 0, 0, 0, 0 }
    asked[j] = c
  end
  local s, ok, a = self.sense
  if type(s) == "function" then ok, a = pcall(s, asked, info)
  else ok, a = pcall(s.answer, s, asked, info) end
  if not ok then error("sense: " .. tostring(a), 0) end
  if type(a) ~= "table" then error("sense: the answers must be a list", 0) end
  local Q, V = {}, {}
  for j = 1, #buds do
    local x = a[j]
    local q, d = x, false
    if type(x) == "table" then
      q = x[1]
      if type(x[2]) == "number" and type(x[3]) == "number" and type(x[4]) == "number" then
        d = { x[2], x[3], x[4] }
      end
    end
    if type(q) ~= "number" or q ~= q or q < 0 or q == math.huge then
      error(format("sense: answer %d: a light (a finite number >= 0) expected, got %s", j,
                   tostring(q)), 0)
    end
    Q[j], V[j] = q, d
  end
  return Q, V
end

-- The positions of the brackets of Lstring s: a list of string indices, and a list saying
-- which each is (true: '[').
local function brackets (s)
  local at, open = {}, {}
  for i, name in s:modules() do
    if name == "[" then at[#at + 1], open[#at + 1] = i, true
    elseif name == "]" then at[#at + 1], open[#at + 1] = i, false end
  end
  return at, open
end

-- Shares out the vigour among the queries `list` of one plant (indices into `queries`, in
-- string order) whose string is `s`; writes into `out[i]` the answer of each.
local function allocate (self, s, queries, list, Qof, out)
  local at, open = brackets(s)
  -- the events in string order: brackets (b > 0: the b-th) and queries (-i)
  local ev, nb, nq = {}, 1, 1
  while nb <= #at or nq <= #list do
    local qi = list[nq]
    if qi == nil or (nb <= #at and at[nb] < queries[qi].index) then
      ev[#ev + 1] = nb; nb = nb + 1
    else
      ev[#ev + 1] = -qi; nq = nq + 1
    end
  end
  -- basipetal: what each internode bears, and for each '[' the light inside and after
  local qin, qafter, rest, bears = {}, {}, {}, {}
  local acc, tips, cnt = 0, 0, 0
  local stack, top = {}, 0
  for e = #ev, 1, -1 do
    local x = ev[e]
    if x > 0 and not open[x] then                  -- ']': a branch, seen from its end
      stack[top + 1], stack[top + 2], stack[top + 3] = acc, tips, cnt
      top = top + 3
      acc, tips, cnt = 0, 0, 0
    elseif x > 0 then                              -- '[': the branch ends here
      local oa, ot, oc = 0, 0, 0
      if top > 0 then
        oa, ot, oc = stack[top - 2], stack[top - 1], stack[top]
        top = top - 3
      end
      qin[x], qafter[x] = acc, oa
      acc, tips, cnt = acc + oa, tips + ot, cnt + oc
    else
      local i = -x
      local role = queries[i].params[1]
      if role == INTERNODE then
        cnt = cnt + 1
        bears[i] = { acc, tips, cnt }
      else
        rest[i] = acc
        acc = acc + Qof[i]
        if role == APEX then tips = tips + 1 end
      end
    end
  end
  -- acropetal: the vigour, from v = alpha Q at the base
  local lam = self.lambda
  local v = self.alpha * acc
  top = 0
  for e = 1, #ev do
    local x = ev[e]
    if x > 0 and open[x] then
      local qi, qa = qin[x], qafter[x]
      local den = lam * qa + (1 - lam) * qi
      local vin = den > 0 and v * (1 - lam) * qi / den or 0
      stack[top + 1] = v - vin
      top = top + 1
      v = vin
    elseif x > 0 then
      if top > 0 then v = stack[top]; top = top - 1 end
    else
      local i = -x
      local b = bears[i]
      if b then
        out[i] = { INTERNODE, b[1], v, b[2], b[3] }
      else
        local q, r = Qof[i], rest[i]
        local vb = q + r > 0 and v * q / (q + r) or 0
        v = v - vb
        out[i] = vb
      end
    end
  end
end

-- The unit direction H + xi V + T of a bud's shoot.
local function direction (self, q, V)
  local h, t, xi = q.heading, self.tropism, self.xi
  local d = { h[1] + t[1], h[2] + t[2], h[3] + t[3] }
  if V then for c = 1, 3 do d[c] = d[c] + xi * V[c] end end
  local n = math.sqrt(d[1] * d[1] + d[2] * d[2] + d[3] * d[3])
  if n < 1e-12 then return h[1], h[2], h[3] end
  return d[1] / n, d[2] / n, d[3] / n
end

--- Answers a pass (see the module's header).
function Vigour:answer (queries, info)
  local buds, plants, order = {}, {}, {}
  for i, q in ipairs(queries) do
    local role = q.params[1]
    if role ~= BUD and role ~= APEX and role ~= INTERNODE then
      error(format("?E module %s: its first parameter says what it is: 0 a bud, 1 an apex, "
        .. "2 an internode (got %s)", tostring(q.index or "(made by the homomorphism)"),
        math.type(role) and format("%g", role) or tostring(role)), 0)
    end
    if role ~= INTERNODE then buds[#buds + 1] = i end
    if q.index ~= nil then                         -- those the homomorphism made: no place
      local p = q.plant or 0
      local l = plants[p]
      if l == nil then l = {}; plants[p] = l; order[#order + 1] = p end
      l[#l + 1] = i
    end
  end
  local Qof, Vof = {}, {}
  if #buds > 0 then
    local Q, V = sensed(self, queries, buds, info)
    for j, i in ipairs(buds) do Qof[i], Vof[i] = Q[j], V[j] end
  end
  local vig = {}
  for _, p in ipairs(order) do
    local s = p == 0 and info.lstring or (info.lstrings or {})[p]
    if s == nil then
      error(format("no string for plant %s (a stand gives info.lstrings)", tostring(p)), 0)
    end
    allocate(self, s, queries, plants[p], Qof, vig)
  end
  local answers = {}
  for i, q in ipairs(queries) do
    local a = vig[i]
    if q.params[1] == INTERNODE then
      answers[i] = a
    else
      answers[i] = { q.params[1], Qof[i], a or 0, direction(self, q, Vof[i]) }
    end
  end
  return answers
end

return M
