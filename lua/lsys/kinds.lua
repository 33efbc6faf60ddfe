--- What kind of lsys object a value is: lsys.type, as io.type, math.type and lpeg.type.
-- @module lsys.kinds
local model = require "lsys.model"

local type, ipairs, getmetatable, rawget, package, debug =
      type, ipairs, getmetatable, rawget, package, debug
local _ENV = nil

local M = {}

-- What lsys.type calls the userdata of lsys.core, by metatable name; the arrangement and
-- the model are Lua tables, told apart by their metatables.
local KINDS = {
  ["lsys.Lstring"] = "lstring", ["lsys.Scene"] = "scene", ["lsys.Contour"] = "contour",
  ["lsys.Surface"] = "surface", ["lsys.Texture"] = "texture", ["lsys.IK"] = "ik",
  ["lsys.Viewer"] = "viewer", ["lsys.Rules"] = "rules", ["lsys.Func"] = "func",
  ["lsys.Canvas"] = "canvas", ["lsys.BSpline"] = "bspline",
}
-- Lua objects of modules loaded on demand: { module, its metatable's field, kind }
local TABLE_KINDS = { { "lsys.arrange", "Arrangement", "arrangement" },
                      { "lsys.sketch", "Sketch", "sketch" },
                      { "lsys.sketch.organ", "Organ", "organ" } }
local REGISTRY = debug.getregistry()

--- The kind of lsys object `x` is: "lstring", "scene", "model", "arrangement", "contour",
-- "surface", "texture", "ik", "viewer", "rules", "func", "canvas", "bspline", "sketch" or
-- "organ"; nil for any other value (as io.type, math.type and lpeg.type). Closed objects
-- keep their kind.
function M.type (x)
  local mt = getmetatable(x)
  if mt == nil then return nil end
  if mt == model.Model then return "model" end
  if type(x) == "userdata" then
    local name = type(mt) == "table" and rawget(mt, "__name")
    -- the registry check: another library's userdata may call itself "lsys.Scene" too
    return name and REGISTRY[name] == mt and KINDS[name] or nil
  end
  for _, k in ipairs(TABLE_KINDS) do                 -- none before its module is loaded
    local mod = package.loaded[k[1]]
    if type(mod) == "table" and mt == rawget(mod, k[2]) then return k[3] end
  end
  return nil
end

return M
