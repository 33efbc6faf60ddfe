--- A resource environment: soil water or a nutrient in a grid of cells, spreading by
-- diffusion between passes, fed by sources and taken by the plant (core.field, in C;
-- docs/open.md §2).
--
-- `lsys.environment.resource { lo =, hi =, cell =, diffusion =, initial =, sources =,
-- threads = }`: the box lo .. hi ({x, y, z} each) in cubic cells of side `cell` (one cell
-- across an axis where lo and hi are equal: a 2D or 1D field). The field starts with
-- `initial` in every cell (a number, or a function (x, y, z) -> amount of the cell's centre;
-- 0 by default). Before the queries of each pass, each source { x, y, z, rate } adds its
-- rate to its cell, and the field diffuses for one unit of time with the coefficient
-- `diffusion` (0 by default; units^2 a pass: explicit substeps, as many as keep the scheme
-- stable, core.field's diffuse). Then each ?E(want, ...) takes from the cell it is in:
-- `want` (its first parameter; less than 0 asks nothing) when the cell has enough for all
-- who ask there, else its share of what there is (in proportion to what each asked); the
-- answer is what it got. A ?E of four parameters or more also gets the direction (x, y, z)
-- in which the amount grows fastest there (after the takes: 0, 0, 0 where it is flat),
-- where a root is to turn. Outside the box a query gets 0. The field is made afresh at the
-- first pass of each derivation; `env:total()` is what it holds, `env:at(x, y, z)` a
-- cell's amount.
-- @module lsys.environment.resource
local core = require "lsys.core"
local check = require "lsys.environment.check"

local type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math =
      type, ipairs, pairs, error, pcall, tostring, tonumber, setmetatable, math
local format = string.format
local _ENV = nil

local M = {}

local Resource = {}
Resource.__index = Resource

local OPTIONS = { lo = true, hi = true, cell = true, diffusion = true, initial = true,
                  sources = true, threads = true }

local function bad (msg) error("lsys.environment.resource: " .. msg, 3) end

local finite = check.finite

local function vec3 (v, what)
  if not check.vec3(v) then bad(what .. " must be a list {x, y, z} of finite numbers") end
  return { v[1], v[2], v[3] }
end

--- The environment (see the module's header for the options).
function M.resource (opts)
  if type(opts) ~= "table" then bad("an options table expected") end
  for k in pairs(opts) do
    if not OPTIONS[k] then bad(format("unknown option '%s'", tostring(k))) end
  end
  local lo, hi = vec3(opts.lo, "lo"), vec3(opts.hi, "hi")
  for c = 1, 3 do
    if not (lo[c] <= hi[c]) then bad("lo must not be above hi in x, y or z") end
  end
  local h = opts.cell
  if not finite(h) or h <= 0 then bad("cell must be a number > 0") end
  local D = opts.diffusion or 0
  if not finite(D) or D < 0 then bad("diffusion must be a number >= 0") end
  local init = opts.initial or 0
  if type(init) ~= "function" and (not finite(init) or init < 0) then
    bad("initial must be a number >= 0 or a function (x, y, z) -> amount")
  end
  local src, rates = {}, {}
  for i, s in ipairs(opts.sources or {}) do
    if type(s) ~= "table" or #s ~= 4 or not (finite(s[1]) and finite(s[2]) and finite(s[3])
                                              and finite(s[4])) then
      bad(format("sources[%d] must be a list {x, y, z, rate} of finite numbers", i))
    end
    src[3 * i - 2], src[3 * i - 1], src[3 * i] = s[1], s[2], s[3]
    rates[i] = s[4]
  end
  local t = opts.threads
  if t ~= nil and (math.type(t) ~= "integer" or t < 0 or t > 64) then
    bad("threads must be an integer in [0, 64]")
  end
  return setmetatable({ lo = lo, hi = hi, cell = h, diffusion = D, initial = init,
                        src = src, rates = rates, threads = t or 0 }, Resource)
end

function Resource.__tostring () return "lsys.environment.resource" end

--- At the start of each derivation: the field is made afresh at its first pass.
function Resource:start ()
  if self.field then self.field:close() end
  self.field = nil
end

-- The field, made with its initial amounts when there is none yet.
local function field (self)
  if self.field ~= nil then return self.field end
  local F = core.field { lo = self.lo, hi = self.hi, cell = self.cell, threads = self.threads }
  local init = self.initial
  if type(init) == "function" then
    local nx, ny, nz, h = F:dims()
    local lo, v, k = self.lo, {}, 0
    for z = 0, nz - 1 do
      for y = 0, ny - 1 do
        for x = 0, nx - 1 do
          k = k + 1
          local a = init(lo[1] + (x + 0.5) * h, lo[2] + (y + 0.5) * h, lo[3] + (z + 0.5) * h)
          if not finite(a) or a < 0 then
            F:close()
            error(format("lsys.environment.resource: initial gave %s at cell %d, not a "
              .. "number >= 0", tostring(a), k), 0)
          end
          v[k] = a
        end
      end
    end
    F:set(v)
  elseif init > 0 then
    F:fill(init)
  end
  self.field = F
  return F
end

--- What the field holds now (made if it was not yet).
function Resource:total () return field(self):total() end

--- The amount of the cell of (x, y, z) (0 outside the box).
function Resource:at (x, y, z) return field(self):at({ x, y, z })[1] end

-- core.field's message about point k as one about its query.
local function blame (msg)
  msg = tostring(msg)
  local k = msg:match("^field:take: points%[(%d+)%] must be a finite number")
  if k then return format("query %d: its position is not finite", (tonumber(k) + 2) // 3) end
  return msg
end

--- Answers the queries of a pass (see the module's header).
function Resource:answer (queries)
  local F = field(self)
  if #self.rates > 0 then F:add(self.src, self.rates) end
  F:diffuse(self.diffusion, 1)
  local pts, want, dirs = {}, {}, false
  for i, q in ipairs(queries) do
    local p = q.position
    pts[3 * i - 2], pts[3 * i - 1], pts[3 * i] = p[1], p[2], p[3]
    local w = q.params[1] or 0
    want[i] = w > 0 and w or 0                       -- NaN too: asks nothing
    if #q.params >= 4 then dirs = true end
  end
  local ok, got = pcall(F.take, F, pts, want)
  if not ok then error(blame(got), 0) end
  local g = dirs and F:gradient(pts)
  local answers = {}
  for i, q in ipairs(queries) do
    if #q.params >= 4 then
      local x, y, z = g[3 * i - 2], g[3 * i - 1], g[3 * i]
      local n = math.sqrt(x * x + y * y + z * z)
      if n > 0 then x, y, z = x / n, y / n, z / n end
      answers[i] = { got[i], x, y, z }
    else
      answers[i] = got[i]
    end
  end
  return answers
end

return M
