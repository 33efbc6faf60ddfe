--- The agave of Lintermann and Deussen 1999 (section "Functional modeling", fig. 8): a
-- rosette of long, fleshy leaves on a Phiball whose parameters vary per instance. Each
-- leaf's length and bend are ranges over its iteration number i (the Phiball numbers its
-- children from the pole outwards, so the first leaves stand almost upright) followed by a
-- user function that adds a random offset from the seeded generator: the upright leaves are
-- less curved than the others, and no two leaves are alike. The same seed gives the same
-- plant; another seed another agave of the same kind.
--
--   build/bin/lsys render examples/components/agave.lua -o agave.png
local C = require "lsys".components
local view = require "lsys.view"

local N = 34

-- v scaled by a random factor in [1 - k, 1 + k] (ctx.random is the seeded generator)
local function jitter (k)
  return function (v, ctx) return v * (1 + k * (2 * ctx.random() - 1)) end
end

local leaf = C.leaf {
  name = "leaf", shape = "lanceolate", width = 0.42,
  length = { 1.8, 3.4, f = jitter(0.12) },            -- the outer leaves longer
  longitudinal = { 0.02, 0.55, f = function (v, ctx)     -- and more bent, each its own way
    return v + 0.15 * ctx.random()
  end },
  lateral = 0.45,                                        -- a deep, fleshy channel
  rotate = function (ctx) return { 0, 24 * ctx.random() - 12, 0 } end,   -- a random roll
  color = 13,
}

local rosette = C.phiball { name = "rosette", n = N, radius = 0.25, open = 0, close = 88 }
rosette:child(leaf)

-- a squat brown base the rosette sits on
local base = C.simple { name = "base", primitive = "sphere", size = { 0.7, 0.3, 0.7 },
                        translate = { 0, -0.15, 0 }, color = 1 }
base:child(rosette)

local palette = {}
for k, c in pairs(view.PALETTE) do palette[k] = c end
palette[13] = { 0.42, 0.58, 0.50 }                       -- agave blue-green

return C.model(base, {
  name = "agave", seed = 1,
  view = { viewpoint = { 0, 3.4, 9.5 }, target = { 0, 0.7, 0 }, up = { 0, 1, 0 },
           projection = "perspective", fov = 40, background = { 0.93, 0.96, 1 },
           palette = palette },
})
