--- "Did you mean": the names nearest a misspelt one, for the messages about an unknown
-- model option, view option, --set variable, command or command-line option. Requires
-- nothing, so any module may use it.
--
-- Nearness is the optimal string alignment distance (Levenshtein's insertions, deletions
-- and substitutions, and a swap of two neighbouring characters counted as one edit, after
-- Damerau 1964: most typing slips are one of these four), on the names in lower case. A
-- name is suggested when at most a third of the misspelt name's characters (at least one)
-- must change and fewer than all of them: `prodcutions` gives `productions` (a swap),
-- `Q` gives nothing, whatever one-letter names there are.
-- @module lsys.util.suggest
local ipairs, type, math, string, table = ipairs, type, math, string, table
local format = string.format
local _ENV = nil

local M = {}

--- The optimal string alignment distance between strings a and b: the fewest insertions,
-- deletions, substitutions and swaps of neighbours that turn one into the other.
-- `cap`: stop counting past it (a distance above `cap` is returned as cap + 1).
function M.distance (a, b, cap)
  local la, lb = #a, #b
  cap = cap or math.huge
  if math.abs(la - lb) > cap then return cap + 1 end
  local prev2, prev, cur = {}, {}, {}
  for j = 0, lb do prev[j] = j end
  for i = 1, la do
    cur[0] = i
    local ca, best = a:byte(i), i
    for j = 1, lb do
      local cb = b:byte(j)
      local d = prev[j - 1] + (ca == cb and 0 or 1)
      if prev[j] + 1 < d then d = prev[j] + 1 end
      if cur[j - 1] + 1 < d then d = cur[j - 1] + 1 end
      if i > 1 and j > 1 and ca == b:byte(j - 1) and a:byte(i - 1) == cb
         and prev2[j - 2] + 1 < d then
        d = prev2[j - 2] + 1
      end
      cur[j] = d
      if d < best then best = d end
    end
    if best > cap then return cap + 1 end
    prev2, prev, cur = prev, cur, prev2
  end
  return prev[lb]
end

--- The names of the list `names` nearest `name` (see the module's comment), sorted; an
-- empty list when none is near enough. Names that are not strings are skipped.
function M.nearest (name, names)
  if type(name) ~= "string" or name == "" then return {} end
  local low = name:lower()
  local cap = math.min(math.max(1, #name // 3), #name - 1)
  local best, out = cap + 1, {}
  for _, n in ipairs(names) do
    if type(n) == "string" and n ~= name then
      local d = M.distance(low, n:lower(), best)
      if d < best then best, out = d, { n }
      elseif d == best and d <= cap then out[#out + 1] = n end
    end
  end
  table.sort(out)
  return out
end

--- " (did you mean 'x'?)" or " (did you mean 'x' or 'y'?)" for `name` among `names`, or ""
-- when none is near: for the end of a message. `quote` formats each name (default 'x').
function M.hint (name, names, quote)
  local near = M.nearest(name, names)
  if #near == 0 then return "" end
  local q = {}
  for i, n in ipairs(near) do q[i] = quote and quote(n) or format("'%s'", n) end
  local last = #q > 1 and " or " .. table.remove(q) or ""
  return format(" (did you mean %s%s?)", table.concat(q, ", "), last)
end

return M
