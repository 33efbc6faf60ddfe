--- The output formats of an lsys.batch job, in the order a job writes them: the picture,
-- the export formats of the core (core.formats(), by name: glb, obj, ply), the L-string and
-- the statistics. The batch's checks and messages and the `lsys batch` help take their
-- lists from here.
-- @module lsys.batch.formats
local core = require "lsys.core"

local ipairs, table = ipairs, table
local _ENV = nil

local M = {}

local meshes = core.formats()
table.sort(meshes, function (a, b) return a.name < b.name end)

--- The formats: { name, ext (nil: any extension), companion = the extension of a file
-- written beside it (an .obj's material file), mesh = true for the core's }.
M.list = { { "png", "png" } }
for _, f in ipairs(meshes) do
  M.list[#M.list + 1] = { f.name, f.ext, companion = f.companion, mesh = true }
end
M.list[#M.list + 1] = { "lstring" }
M.list[#M.list + 1] = { "stats", "json" }

--- Their names, in that order; and the extensions of the picture and the meshes
-- (".png", ".glb", ...).
M.names, M.exts = {}, {}
for _, f in ipairs(M.list) do
  M.names[#M.names + 1] = f[1]
  if f[1] == "png" or f.mesh then M.exts[#M.exts + 1] = "." .. f[2] end
end

return M
