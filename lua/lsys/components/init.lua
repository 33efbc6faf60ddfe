--- Component graphs: plants modelled as graphs of components, after Lintermann
-- and Deussen, "Interactive Modeling of Plants" (IEEE CG&A 1999), the method behind Xfrog.
-- docs/components.md is the reference.
--
--   local C = require "lsys".components        -- or require "lsys.components"
--   local leaf = C.leaf { length = 0.3, width = 0.15 }
--   local twig = C.tree { length = 1, n = 12, angle = { 60, 30 } }
--   twig:branch(leaf)
--   local tree = C.expand(twig)                  -- the i-tree
--
-- The prototypes are lsys.components.proto, the i-tree lsys.components.expand, the
-- multipliers' placements lsys.components.place; this module gathers them.
-- @module lsys.components
local proto = require "lsys.components.proto"
local expand = require "lsys.components.expand"

local pairs, require, setmetatable, error, tostring, pcall, concat =
      pairs, require, setmetatable, error, tostring, pcall, table.concat
local _ENV = nil

local M = {}
for k, v in pairs(proto) do M[k] = v end

--- Expands the p-graph at `root` into the i-tree (lsys.components.expand).
M.expand = expand.expand

--- The p-graph at `root` as Graphviz DOT text (lsys.components.graph.dot; opts as there).
function M.graph (root, opts) return require("lsys.components.graph").dot(root, opts) end

--- Draws the p-graph to `path` (.dot, or .png/.svg/.pdf with Graphviz's dot).
function M.graph_render (root, path, opts)
  return require("lsys.components.graph").render(root, path, opts)
end

--- The component graph at `root` as an lsys model (lsys.components.model).
function M.model (root, opts) return require("lsys.components.model").model(root, opts) end

--- The scene of the component graph at `root`: M.model(root, opts):interpret().
function M.scene (root, opts)
  local ok, m = pcall(M.model, root, opts)
  if not ok then
    error((tostring(m):gsub("^[^\n]-:%d+: ", ""):gsub("^lsys%.components%.model:",
          "lsys.components.scene:")), 2)
  end
  return m:interpret()
end

--- Puts component plants into an L-system: each module `P(s)` of `model`'s derived string
-- becomes the plant `plants.P` scaled by s (lsys.components.mix.place).
function M.place (model, plants, opts)
  return require("lsys.components.mix").place(model, plants, opts)
end

--- The i-tree of this prototype: lsys.components.expand(self, opts).
function proto.Proto:expand (opts) return expand.expand(self, opts) end

-- C.bush{...}: an unknown kind is an error naming the known ones, not "attempt to call nil".
setmetatable(M, { __index = function (_, k)
  error("lsys.components: unknown component kind or function '" .. tostring(k) ..
        "' (kinds: " .. concat(proto.ORDER, ", ") .. ")", 2)
end })

return M
