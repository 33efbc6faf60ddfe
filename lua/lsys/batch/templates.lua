--- The templates of lsys.batch's outputs: a job's file names made from them, and the check
-- that no two jobs of a spec write the same file (proven from a sweep's templates, or job by
-- job).
-- @module lsys.batch.templates
local F = require "lsys.batch.fields"

local type, ipairs, tostring, error = type, ipairs, tostring, error
local math, string, table = math, string, table
local format = string.format
local isname = F.isname
local _ENV = nil

local M = {}

-- The extension of the file an output of a format writes beside it, by the format's name
-- (obj: its material file, mtl).
local COMPANION = {}
for _, f in ipairs(F.FORMATS) do COMPANION[f[1]] = f.companion end

-- The value of the placeholder {k} of a job's template, as text; or nil and why.
local function placeholder (job, k)
  local v
  if k == "id" or k == "n" or k == "seed" or k == "name" or k == "steps" or k == "rep" or
     k == "width" or k == "height" then
    v = job[k]
    if v == nil then return nil, format("{%s}: the job has no %s", k, k) end
  elseif k == "model" then
    v = job.model:match("([^/]*)$"):gsub("%.lua$", "")
  elseif isname(k) then
    v = job.params[k]
    if v == nil then return nil, format("{%s}: the job gives no value for %s", k, k) end
  else
    return nil, format("{%s} is not a placeholder (they are {id}, {n}, {seed}, {model}, "
      .. "{name}, {steps}, {rep} and the model's variables, as {R})", k)
  end
  if math.type(v) == "float" then v = format("%.14g", v) end
  return tostring(v)
end

-- The path `path` (a template's expansion) as the file it names in the output folder:
-- empty and "." segments dropped, ".." taking away the segment before it -- the path lsys
-- writes, compares and records. Returns it, or nil and why: an absolute path, a path that
-- leaves the output folder.
local function normalize (path)
  if not path:find("//", 1, true) and not path:find("%.%.?/") and not path:find("/%.%.?$")
     and path:sub(1, 1) ~= "/" then
    return path                              -- nothing to normalize (the usual path)
  end
  if path:sub(1, 1) == "/" then
    return nil, format("'%s' is an absolute path: an output is a file in the output folder, "
      .. "named relative to it", path)
  end
  local segs = {}
  for seg in path:gmatch("[^/]+") do
    if seg == ".." then
      if #segs == 0 then
        return nil, format("'%s' leaves the output folder: an output is a file in it", path)
      end
      segs[#segs] = nil
    elseif seg ~= "." then
      segs[#segs + 1] = seg
    end
  end
  if #segs == 0 then return nil, format("'%s' is not a file name", path) end
  return table.concat(segs, "/")
end

-- The job's template `tpl` with its placeholders replaced, normalized; or nil and why.
local function expand (job, tpl)
  local why
  local path = tpl:gsub("{([^{}]*)}", function (k)
    local v, err = placeholder(job, k)
    if v == nil then why = why or err end
    return v
  end)
  if why then return nil, why end
  if path:find("[{}]") then return nil, format("'%s': an unmatched { or }", tpl) end
  local last = path:match("[^/]*$")
  if path:find("%c") or last == "" or last == "." or last == ".." then
    return nil, format("'%s' is not a file name", path)
  end
  return normalize(path)
end

-- The file an output of format `fmt` writes beside its file `path` (an .obj's material
-- file), or nil: the file name's extension becomes the companion's, as export_obj.c's
-- mtlpath does (".obj" alone stays whole).
local function companion (path, fmt)
  local ext = COMPANION[fmt]
  if ext == nil then return nil end
  if path:match("[^/]*$"):find("^%.[^.]*$") then return path .. "." .. ext end
  return (path:gsub("%.[^./]*$", "." .. ext))
end

--[[
The shape of the template `tpl` of the sweep `src`, whose first job is `job1`: the path it
gives every job, as a list of pieces -- literal text, or a token for a value that changes
from job to job ("id", "n", or "num" for any other number: the seed, a varied variable,
steps, width, height, rep; {rep} is {n} when the sweep is replicates alone) -- normalized
as `normalize` does the paths, its last segment (the file's name) as a list of pieces, and
its number of segments (depth). nil when a varied text (model, name) is in
the template: its values could hold "/" or be "..".

A number's text ("12", "-0.5", "1e+20") never holds "/", is never empty, "." or "..": a
segment with a token in it is a file or folder name for every job, and the shape's
normalization is that of every job's path.
]]
local function shape (src, job1, tpl)
  local pieces = {}
  local function lit (s)
    if type(pieces[#pieces]) == "string" then pieces[#pieces] = pieces[#pieces] .. s
    elseif s ~= "" then pieces[#pieces + 1] = s end
  end
  local pos = 1
  for a, k, b in tpl:gmatch("(){([^{}]*)}()") do
    lit(tpl:sub(pos, a - 1))
    pos = b
    if k == "id" or k == "n" then pieces[#pieces + 1] = { k }
    elseif k == "rep" and #src.vary == 0 then
      pieces[#pieces + 1] = { "n" }       -- replicates alone: job n is replicate n
    elseif k == "seed" or src.varied[k] then
      if k == "model" or k == "name" then return nil end
      pieces[#pieces + 1] = { "num" }
    else
      lit(placeholder(job1, k))           -- the same for every job (job 1 is checked)
    end
  end
  lit(tpl:sub(pos))
  -- the segments between the slashes of the literal text, normalized
  local segs, seg = {}, {}
  local function endseg ()
    local only = #seg == 0 and "" or (#seg == 1 and type(seg[1]) == "string" and seg[1])
    if only == ".." then segs[#segs] = nil
    elseif only ~= "" and only ~= "." then segs[#segs + 1] = seg end
    seg = {}
  end
  for _, p in ipairs(pieces) do
    if type(p) == "table" then
      seg[#seg + 1] = p
    else
      local from = 1
      while true do
        local s = p:find("/", from, true)
        local text = p:sub(from, (s or 0) - 1)
        if text ~= "" then
          if type(seg[#seg]) == "string" then seg[#seg] = seg[#seg] .. text
          else seg[#seg + 1] = text end
        end
        if s == nil then break end
        endseg()
        from = s + 1
      end
    end
  end
  endseg()
  local flat = {}
  for i, sg in ipairs(segs) do
    if i > 1 then flat[#flat + 1] = "/" end
    for _, p in ipairs(sg) do flat[#flat + 1] = p end
  end
  local first, last = nil, nil
  for i, p in ipairs(flat) do
    if type(p) == "table" then first, last = first or i, i end
  end
  local function text (from, to)
    local t = {}
    for i = from, to do t[#t + 1] = flat[i] end
    return table.concat(t)
  end
  if first == nil then
    return { prefix = text(1, #flat), suffix = "", name = segs[#segs], depth = #segs }
  end
  return { prefix = text(1, first - 1), suffix = text(last + 1, #flat), name = segs[#segs],
           depth = #segs }
end

-- Whether the file name `name` (a shape's last segment) gives back the job it was made for:
-- an {id} (all of one width in a sweep) with nothing but literal text on one side of it in
-- the name, or an {n} so placed whose other side is the name's end or text that does not
-- begin (end) with a digit.
local function names_job (name)
  local function literal (from, to)
    for i = from, to do if type(name[i]) == "table" then return false end end
    return true
  end
  local function nondigit (p, at)
    return type(p) == "string" and not p:sub(at, at):find("%d")
  end
  for j, p in ipairs(name) do
    if type(p) == "table" and (p[1] == "id" or p[1] == "n") then
      local before, after = literal(1, j - 1), literal(j + 1, #name)
      if p[1] == "id" and (before or after) then return true end
      if p[1] == "n" and ((before and (j == #name or nondigit(name[j + 1], 1))) or
                          (after and (j == 1 or nondigit(name[j - 1], -1)))) then
        return true
      end
    end
  end
  return false
end

local function starts (s, p) return s:sub(1, #p) == p end
local function ends (s, p) return p == "" or s:sub(-#p) == p end

-- Whether the paths of two shapes always differ: when they have not as many segments (a
-- token's text never holds "/"), or neither literal beginning is a beginning of the other,
-- or neither literal end an end of the other (two equal paths would begin, and end, with
-- both).
local function apart (a, b)
  return a.depth ~= b.depth or
         (not starts(a.prefix, b.prefix) and not starts(b.prefix, a.prefix)) or
         (not ends(a.suffix, b.suffix) and not ends(b.suffix, a.suffix))
end

--[[
Whether the templates of the sweep `src` show, by themselves, that no two of its jobs write
the same file and no job writes a file twice: every template's file name gives back its
job (names_job), so that two jobs' paths of one template differ; and any two templates (an
.obj's material file among them) are `apart`. `job1` is the sweep's first job, checked.
]]
local function proven (src, job1)
  if src.count == 1 then return true end
  local shapes = {}
  for _, t in ipairs(job1.templates) do
    local s = shape(src, job1, t.template)
    if s == nil or not names_job(s.name) then return false end
    shapes[#shapes + 1] = s
    local ext = COMPANION[t.format]
    if ext ~= nil then                 -- its material file: the same, .obj -> .mtl
      shapes[#shapes + 1] = { prefix = s.prefix,
                              suffix = s.suffix:sub(1, -#F.FORMAT_EXT[t.format] - 2) ..
                                "." .. ext,
                              name = s.name, depth = s.depth }
    end
  end
  for i = 1, #shapes do
    for j = i + 1, #shapes do
      if not apart(shapes[i], shapes[j]) then return false end
    end
  end
  return true
end

-- A hash of the text `s` (64 bits, 8 bytes at a time): the check of every job's paths
-- keeps a hash per file, and compares the files themselves when two hashes meet.
local function hash (s)
  local h, n = 0x2545F4914F6CDD1D ~ #s, #s
  s = s .. "\0\0\0\0\0\0\0"
  for i = 1, n, 8 do
    h = (h ~ string.unpack("<i8", s, i)) * 0x100000001B3
    h = h ~ (h >> 29)
  end
  return h
end

--[[
Checks every job of `src` (a list's, a CSV file's, or a sweep the templates of which prove
nothing): each job made and checked, ids unique (src.ids: id -> n), and no file written by
two jobs: `seen` keeps a hash of each file's path and the job that writes it (one integer
pair per file); when the hash of a path is met again, the jobs that wrote a path of that
hash are made again and their paths compared, so the check is exact.
]]
local function check_all (src)
  local seen, ids = {}, not src.vary and {} or nil    -- a sweep's ids are its numbers
  for n = 1, src.count do
    local job, claims = src.get(n)
    local prev = ids and ids[job.id]
    if prev then
      error(format("%s: %sjob id '%s' is also the id of the job at %s", job.where,
        src.col("id"), job.id, src.get(prev).where), 0)
    end
    if ids then ids[job.id] = n end
    for _, c in ipairs(claims) do
      local h = hash(c.path)
      local others = seen[h]
      if others ~= nil then
        for _, m in ipairs(type(others) == "table" and others or { others }) do
          if m ~= n then
            local other, oclaims = src.get(m)
            for _, oc in ipairs(oclaims) do
              if oc.path == c.path then
                error(format("%s: %s'%s' is also written by job %s (%s): give each job its "
                  .. "own files, with {id} for instance", job.where, src.col(c.field), c.path,
                  other.id, other.where), 0)
              end
            end
          end
        end
        if type(others) == "table" then others[#others + 1] = n
        elseif others ~= n then seen[h] = { others, n } end
      else
        seen[h] = n
      end
    end
  end
  src.ids = ids
end

M.expand, M.companion, M.proven, M.check_all = expand, companion, proven, check_all

return M
