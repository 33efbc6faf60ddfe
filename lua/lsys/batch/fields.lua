--- What a job of lsys.batch is made of: its output formats, the fields that are not model
-- variables, the values of its fields checked and converted, and the paths of its files.
-- @module lsys.batch.fields
local B = require "lsys.batch.base"
local formats = require "lsys.batch.formats"
local model = require "lsys.model"
local series = require("lsys.util.text").series

local type, ipairs, tostring, tonumber = type, ipairs, tostring, tonumber
local math, string = math, string
local format = string.format
local _ENV = nil

local M = {}

-- The output formats, in the order a job writes them: { name, file extension (none: any) }
-- (lsys.batch.formats).
local FORMATS = formats.list
local FORMAT_RANK, FORMAT_EXT = {}, {}
for i, f in ipairs(FORMATS) do FORMAT_RANK[f[1]], FORMAT_EXT[f[1]] = i, f[2] end
-- The format of a template in a list of outputs (the CSV column `out`), by its extension.
local BY_EXT = { json = "stats", txt = "lstring", lstring = "lstring", str = "lstring" }
for _, f in ipairs(FORMATS) do
  if f[1] == "png" or f.mesh then BY_EXT[f[2]] = f[1] end
end
-- What the message on an unknown extension lists: ".png, .glb, .obj, .ply, .json (stats) or
-- .txt (the L-string)".
local BY_EXT_LIST = {}
for i, e in ipairs(formats.exts) do BY_EXT_LIST[i] = e end
BY_EXT_LIST[#BY_EXT_LIST + 1] = ".json (stats)"
BY_EXT_LIST[#BY_EXT_LIST + 1] = ".txt (the L-string)"
BY_EXT_LIST = series(BY_EXT_LIST, "or")

-- The fields of a job that are not model variables: these and the formats' names.
local RESERVED = { id = true, model = true, name = true, seed = true, steps = true,
                   width = true, height = true, out = true, outputs = true, params = true,
                   rep = true }
for _, f in ipairs(FORMATS) do RESERVED[f[1]] = true end

-- A value in a message: text quoted, anything else as tostring gives it.
local function show (v)
  if type(v) == "string" then return "'" .. v .. "'" end
  return tostring(v)
end

local function tonum (v)
  if type(v) == "number" then return v end
  if type(v) == "string" then return tonumber(v) end
  return nil
end

-- A model variable's value: a finite number. Returns it, or nil and why.
local function conv_number (v)
  local x = tonum(v)
  if x == nil then return nil, format("%s is not a number", show(v)) end
  if x ~= x or x == math.huge or x == -math.huge then
    return nil, format("%s is not a finite number", show(v))
  end
  return math.tointeger(x) or x
end

-- A whole number from lo to hi (hi nil: any), as an integer; or nil and why.
local function conv_whole (v, lo, hi)
  local x = tonum(v)
  local n = x and x == math.floor(x) and x > -2^63 and x < 2^63 and math.tointeger(x)
  if not n then return nil, format("%s is not a whole number", show(v)) end
  if n < lo or (hi and n > hi) then
    return nil, format("%s must be %s", show(v), hi and format("from %d to %d", lo, hi)
      or format(">= %d", lo))
  end
  return n
end

local CONV = {
  seed = function (v) return conv_whole(v, math.mininteger) end,
  steps = function (v) return conv_whole(v, 0, model.MAX_STEPS) end,
  width = function (v) return conv_whole(v, 1, B.MAX_SIZE) end,
  height = function (v) return conv_whole(v, 1, B.MAX_SIZE) end,
  model = function (v)
    if type(v) ~= "string" or v == "" then return nil, "a model file name expected" end
    return v
  end,
  name = function (v)
    if type(v) ~= "string" or v == "" then return nil, "a model name expected" end
    return v
  end,
  id = function (v)
    if type(v) == "number" then v = tostring(math.tointeger(v) or v) end
    if type(v) ~= "string" or not v:find("^[%w][%w_.%-]*$") then
      return nil, format("%s is not a job id (letters, digits, '_', '.' and '-', starting "
        .. "with a letter or a digit)", show(v))
    end
    return v
  end,
}

local function isname (k)
  return type(k) == "string" and k:find("^[%a_][%w_]*$") ~= nil
end

-- The format of an output template `tpl` given under the key `key` (a format's name, or
-- "out" for one told by its extension); or nil and why.
local function output_format (key, tpl)
  if type(tpl) ~= "string" or tpl == "" then
    return nil, format("%s is not a file name template", show(tpl))
  end
  local ext = (tpl:match("%.([%w]+)$") or ""):lower()
  if key == "out" then
    local f = BY_EXT[ext]
    if f == nil then
      return nil, format("'%s': the format is told by the extension: %s", tpl, BY_EXT_LIST)
    end
    return f
  end
  local want = FORMAT_EXT[key]
  if want and ext ~= want then
    return nil, format("'%s': a %s file's name ends in .%s", tpl, key, want)
  end
  return key
end

-- `p` relative to the folder `dir` ("." for the current one); an absolute `p` as it is.
local function join (dir, p)
  if p:sub(1, 1) == "/" or dir == "." or dir == "" then return p end
  return (dir:gsub("/+$", "")) .. "/" .. p
end

local function dirname (path)
  return path:match("^(.*)/[^/]*$") or "."
end

M.FORMATS, M.FORMAT_RANK, M.FORMAT_EXT, M.BY_EXT, M.RESERVED =
  FORMATS, FORMAT_RANK, FORMAT_EXT, BY_EXT, RESERVED
M.show, M.conv_number, M.conv_whole, M.CONV, M.isname, M.output_format =
  show, conv_number, conv_whole, CONV, isname, output_format
M.join, M.dirname = join, dirname

return M
