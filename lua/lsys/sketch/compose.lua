--- Composing sketched plants on one stem (Anastacio et al. 2009, §7.2): the bromeliad of
-- figs. 11 and 12 and the foxglove of figs. 13 and 14 were made "by combining the grammars
-- of two parameterized L-systems", one sketch for the leaves and one for the flowers, and
-- "the distribution of the organs was edited in the L-system rules". Here the grammars of
-- Models made by sk:model are joined into one: the first plant keeps its names and draws
-- its stem; each further plant k has its modules, functions and constants renamed with the
-- suffix k (A2, internode2, ...), its organ surface under a letter of its own, its
-- sub-L-systems (a composed organ) under ids of their own, and its stem pieces moved
-- without drawing (f instead of F); its apex starts in a branch before the first plant's,
-- so that all of them place their organs along the same stem in one derivation.
--
--   local m = lsys.sketch.compose({ leaves, flowers }, { name = "foxglove" })
--
-- @module lsys.sketch.compose
local pairs, ipairs, error, tostring, next, string, table, math =
      pairs, ipairs, error, tostring, next, string, table, math
local format, concat = string.format, table.concat
local _ENV = nil

local M = {}

-- The modules of every template (lsys.sketch.templates).
M.MODULES = { "A", "S", "B", "C", "L", "R", "Organ" }

-- Letters for the organ surfaces, in the order the plants take them.
local LETTERS = "PQRSTUVWXYZJKMNOHIE"

-- `text` with the words of `names` (a set) suffixed by `suffix`. A word after '@' or '~'
-- is a command or a surface, not a module: it stays.
local function rename (text, names, suffix)
  return (text:gsub("()([%a_][%w_]*)", function (at, word)
    local before = at > 1 and text:sub(at - 1, at - 1) or ""
    if names[word] and before ~= "@" and before ~= "~" then return word .. suffix end
  end))
end
M.rename = rename

-- The surface letters the homomorphism lines `lines` draw with ~X.
local function letters (lines, used)
  for _, l in ipairs(lines) do
    for x in l:gmatch("~(%a)") do used[x] = true end
  end
end

local function copy (t)
  local out = {}
  for k, v in pairs(t or {}) do out[k] = v end
  return out
end

--- The description of the composition of `descs` (the descriptions of Models made by
-- sk:model, m.sketch.description): the form lsys.sketch's writers take, with `plants`,
-- one entry a plant ({ phyllotaxis, nodes_per_layer, suffix, file }), and `modules`, the
-- names to declare. opts: name, view (more view options).
function M.describe (descs, opts, files)
  local names, used = {}, {}
  for _, d in ipairs(descs) do
    letters(d.homomorphism, used)
    for x in pairs(d.view.surfaces or {}) do used[x] = true end
  end
  local out = { productions = {}, homomorphism = {}, env = {}, funcs = {}, surfaces = {},
                plants = {}, steps = 0 }
  local axioms, mods, sub, nsub = {}, { "Organ" }, nil, 0
  local free = LETTERS:gmatch("%a")
  for k, d in ipairs(descs) do
    local suffix = k == 1 and "" or tostring(k)
    for _, m in ipairs(M.MODULES) do names[m] = true end
    for n in pairs(d.env) do names[n] = true end
    -- this plant's sub-L-systems under the next free ids
    local ids = {}
    for id in pairs(d.sub or {}) do ids[#ids + 1] = id end
    table.sort(ids)
    local newid = {}
    for _, id in ipairs(ids) do nsub = nsub + 1; newid[id] = nsub end
    local function fix (l)
      l = k == 1 and l or rename(l, names, suffix)
      return (l:gsub("%?%((%d+),", function (id)
        return format("?(%d,", newid[math.tointeger(id + 0)] or id)
      end))
    end
    -- its organ surface (P of its own view) under a letter no other plant draws with
    local letter
    if d.surfaces and d.surfaces.P then
      if k == 1 then letter = "P" else
        for x in free do if not used[x] then letter = x break end end
        if letter == nil then error("compose: too many organ surfaces", 0) end
      end
      used[letter] = true
      out.surfaces[letter] = d.surfaces.P
    end
    for _, l in ipairs(d.productions) do
      l = fix(l)
      if k > 1 then l = l:gsub("F%(d%)", "f(d)") end   -- its stem moves, not drawn
      out.productions[#out.productions + 1] = l
    end
    for _, l in ipairs(d.homomorphism) do
      l = fix(l)
      if letter and letter ~= "P" then l = l:gsub("~P%(", "~" .. letter .. "(") end
      out.homomorphism[#out.homomorphism + 1] = l
    end
    for id, s in pairs(d.sub or {}) do
      local p = {}
      for i, l in ipairs(s.productions) do p[i] = fix(l) end
      sub = sub or {}
      sub[newid[id]] = { productions = p }
    end
    for n, v in pairs(d.env) do out.env[n .. suffix] = v end
    for n, v in pairs(d.funcs) do out.funcs[n .. suffix] = v end
    if k > 1 then
      for _, m in ipairs(M.MODULES) do mods[#mods + 1] = m .. suffix end
      axioms[#axioms + 1] = "[" .. fix(d.axiom) .. "] "
    end
    out.steps = math.max(out.steps, d.steps)
    out.plants[k] = { phyllotaxis = d.phyllotaxis, nodes_per_layer = d.nodes_per_layer,
                      suffix = suffix, file = files and files[k] }
  end
  out.axiom = concat(axioms) .. descs[1].axiom
  out.sub = sub
  out.modules = concat(mods, " ")
  -- the views' other surfaces (for "~X" organs) and the organs under their letters
  local surfaces = {}
  for _, d in ipairs(descs) do
    for x, v in pairs(d.view.surfaces or {}) do
      if x ~= "P" and surfaces[x] == nil then surfaces[x] = v end
    end
  end
  for x, v in pairs(out.surfaces) do surfaces[x] = v end
  local view = copy(descs[1].view)
  view.surfaces = next(surfaces) and surfaces or nil
  for k, v in pairs(opts.view or {}) do view[k] = v end
  out.view = view
  out.phyllotaxis = descs[1].phyllotaxis
  out.nodes_per_layer = descs[1].nodes_per_layer
  out.options = { axiom = out.axiom, productions = out.productions,
                  homomorphism = out.homomorphism, sub = sub, modules = out.modules,
                  env = out.env, steps = out.steps, view = view, name = opts.name }
  return out
end

return M
