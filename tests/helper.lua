--- Test helpers shared by the busted specs.
-- Loaded by busted as the `helper` (see .busted) and also `require "tests.helper"`-able
-- from a spec, so a spec runs on its own too: `busted tests/context_spec.lua`.
--
-- Registers with luassert:
--   assert.near(expected, actual, tol)      numbers, or (nested) lists of numbers elementwise
--   assert.error_contains(fn, s1, s2, ...)  fn raises; the message contains every si (plain text)
--
-- Functions (module table H):
--   H.model(axiom, productions, opts)  lsys.lsystem with axiom/productions merged into opts
--   H.derive(axiom, productions, n, opts) tostring of n derivation steps
--   H.steps(model, n)                  list of tostring for steps 0..n (via model:step)
--   H.modules(s)                       list of { name, p1, p2, ... } for every module of s
--   H.rep(text, n)                     text repeated n times
--   H.binomial_tol(n, p, k)            k standard deviations of a binomial(n, p) count
--   H.tmpdir(), H.rmdir(d), H.read(path), H.write(path, s)     temporary folders and files
--   H.sh(cmd), H.lsys(script, opts)    a shell command, a script run by the lsys program:
--                                      output and exit status
--   H.ref_derive(axiom, rules, n, ignore)  independent reference deriver (see below)
local assert = require "luassert"
local say = require "say"

local H = package.loaded["tests.helper"]
if H then return H end
H = {}
package.loaded["tests.helper"] = H

-- Make `require "lsys"` work when a spec is run without the .busted paths.
if not package.path:find("./lua/?/init.lua", 1, true) then
  package.path = package.path .. ";./lua/?.lua;./lua/?/init.lua"
end
if not package.cpath:find("./build/?.so", 1, true) then
  package.cpath = package.cpath .. ";./build/?.so"
end

local function flatten (x, out, path)
  if type(x) == "table" then
    for i = 1, #x do flatten(x[i], out, path .. "[" .. i .. "]") end
  else
    out[#out + 1] = { path = path, v = x }
  end
  return out
end

-- assert.near(expected, actual, tol): |expected - actual| <= tol, elementwise for lists.
local function near (state, args)
  local expected, actual, tol = args[1], args[2], args[3]
  if type(tol) ~= "number" then
    state.failure_message = "assert.near: tolerance (argument 3) must be a number"
    return false
  end
  local e, a = flatten(expected, {}, ""), flatten(actual, {}, "")
  if #e ~= #a then
    state.failure_message = ("assert.near: expected %d numbers, got %d"):format(#e, #a)
    return false
  end
  for i = 1, #e do
    local x, y = e[i].v, a[i].v
    if type(x) ~= "number" or type(y) ~= "number" or not (math.abs(x - y) <= tol) then
      state.failure_message = ("assert.near: at %s expected %s, got %s (tolerance %s)")
        :format(e[i].path ~= "" and e[i].path or "value", tostring(x), tostring(y), tostring(tol))
      return false
    end
  end
  return true
end
say:set("assertion.lsys_near.positive", "Expected values to be near.")
say:set("assertion.lsys_near.negative", "Expected values not to be near.")
assert:register("assertion", "near", near, "assertion.lsys_near.positive",
  "assertion.lsys_near.negative")

-- assert.error_contains(fn, "text", ...): fn raises and its message contains each text.
local function error_contains (state, args)
  local fn = args[1]
  local ok, err = pcall(fn)
  if ok then
    state.failure_message = "expected an error, but the call succeeded"
    return false
  end
  err = tostring(err)
  for i = 2, args.n do
    if not err:find(args[i], 1, true) then
      state.failure_message = ("error message %q does not contain %q"):format(err, args[i])
      return false
    end
  end
  return true
end
say:set("assertion.error_contains.positive", "Expected an error containing the given texts.")
say:set("assertion.error_contains.negative", "Expected no error containing the given texts.")
assert:register("assertion", "error_contains", error_contains,
  "assertion.error_contains.positive", "assertion.error_contains.negative")

local function lsys () return require "lsys" end

function H.model (axiom, productions, opts)
  local t = {}
  for k, v in pairs(opts or {}) do t[k] = v end
  t.axiom = axiom
  t.productions = productions
  return lsys().lsystem(t)
end

function H.derive (axiom, productions, n, opts)
  return tostring(H.model(axiom, productions, opts):derive(n or 1))
end

function H.steps (m, n)
  local s = m:derive(0)
  local out = { tostring(s) }
  for _ = 1, n do
    s = m:step(s)
    out[#out + 1] = tostring(s)
  end
  return out
end

function H.modules (s)
  local out = {}
  for i = 1, #s do out[i] = table.pack(s:module(i)) ; out[i].n = nil end
  return out
end

function H.rep (text, n) return string.rep(text, n) end

-- Files and processes ----------------------------------------------------------------------

--- A new empty temporary folder.
function H.tmpdir ()
  local d = os.tmpname()
  os.remove(d)
  assert(os.execute("mkdir -p '" .. d .. "'"))
  return d
end

--- Removes a folder and everything in it.
function H.rmdir (d) os.execute("rm -rf '" .. d .. "'") end

--- The bytes of a file, or nil when it cannot be read.
function H.read (path)
  local f = io.open(path, "rb")
  if f == nil then return nil end
  local s = f:read("a")
  f:close()
  return s
end

--- Writes the bytes `s` to a file.
function H.write (path, s)
  local f = assert(io.open(path, "wb"))
  f:write(s)
  f:close()
end

--- Runs a shell command; returns what it printed (stdout and stderr) and its exit status.
function H.sh (cmd)
  local p = io.popen("(" .. cmd .. ") 2>&1; echo \"exit:$?\"")
  local out = p:read("a")
  p:close()
  local code = tonumber(out:match("exit:(%d+)%s*$"))
  return (out:gsub("exit:%d+%s*$", "")), code
end

--- The lsys program: LSYS_BIN (ctest sets it) or build/bin/lsys.
H.BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"

-- The program as an absolute path, for commands run from another folder (the current
-- folder asked of the system: $PWD is the shell's that started busted, ctest's or ours).
function H.absolute (path)
  if path:sub(1, 1) == "/" then return path end
  local p = io.popen("pwd")
  local cwd = p:read("l")
  p:close()
  return cwd .. "/" .. path
end
H.ABSBIN = H.absolute(H.BIN)

--- Runs the Lua text `script` with the lsys program. opts: env ("NAME=value ..."),
-- prefix (shell commands before it, e.g. a ulimit). Returns the output and exit status.
function H.lsys (script, opts)
  opts = opts or {}
  local path = os.tmpname()
  H.write(path, script)
  local out, code = H.sh(("sh -c '%s %s exec \"%s\" \"%s\"'"):format(opts.prefix or "",
                                                                    opts.env or "", H.BIN, path))
  os.remove(path)
  return out, code
end

function H.binomial_tol (n, p, k)
  return (k or 5) * math.sqrt(n * p * (1 - p))
end

--[[
Reference deriver, written independently of the core, for bracketed context-sensitive
L-systems with one-character modules and no parameters (ABOP ch. 1, section 1.8):
  rules: list of { lc = "..", pred = "X", rc = "..", succ = ".." } (lc/rc without brackets)
  ignore: string of symbols skipped when matching contexts
Left context skips whole branches and climbs out of the current branch; right context skips
branches and fails at the end of its branch. First matching rule wins. Returns the string.
]]
function H.ref_derive (axiom, rules, n, ignore)
  local ign = {}
  for c in (ignore or ""):gmatch(".") do ign[c] = true end
  local function left_ok (s, i, lc)
    local k = #lc
    local j = i - 1
    while k >= 1 do
      if j < 1 then return false end
      local c = s:sub(j, j)
      if c == "]" then          -- skip the whole branch backwards
        local depth = 1
        j = j - 1
        while depth > 0 do
          local d = s:sub(j, j)
          if d == "]" then depth = depth + 1 elseif d == "[" then depth = depth - 1 end
          j = j - 1
        end
      elseif c == "[" or ign[c] then  -- climb out of the branch / skip ignored
        j = j - 1
      else
        if c ~= lc:sub(k, k) then return false end
        k = k - 1
        j = j - 1
      end
    end
    return true
  end
  local function right_ok (s, i, rc)
    local k = 1
    local j = i + 1
    while k <= #rc do
      if j > #s then return false end
      local c = s:sub(j, j)
      if c == "[" then          -- skip the whole branch forwards
        local depth = 1
        j = j + 1
        while depth > 0 do
          local d = s:sub(j, j)
          if d == "[" then depth = depth + 1 elseif d == "]" then depth = depth - 1 end
          j = j + 1
        end
      elseif c == "]" then
        return false            -- end of the branch
      elseif ign[c] then
        j = j + 1
      else
        if c ~= rc:sub(k, k) then return false end
        k = k + 1
        j = j + 1
      end
    end
    return true
  end
  local s = axiom
  for _ = 1, n do
    local out = {}
    for i = 1, #s do
      local c = s:sub(i, i)
      local succ = c
      for _, r in ipairs(rules) do
        if r.pred == c and left_ok(s, i, r.lc or "") and right_ok(s, i, r.rc or "") then
          succ = r.succ
          break
        end
      end
      out[#out + 1] = succ
    end
    s = table.concat(out)
  end
  return s
end

-- Rule text "lc < p > rc --> succ" for ref_derive rules (same text the specs give lsys).
function H.rule_text (r)
  local t = {}
  if r.lc and r.lc ~= "" then t[#t + 1] = r.lc .. " < " end
  t[#t + 1] = r.pred
  if r.rc and r.rc ~= "" then t[#t + 1] = " > " .. r.rc end
  t[#t + 1] = " --> " .. (r.succ == "" and "*" or r.succ)
  return table.concat(t)
end

-- {====================================================================
-- Images: two renders compared with a tolerance, and golden images in tests/golden/.
-- A render matches when the mean absolute difference of every channel is below
-- H.MEAN_TOL and fewer than H.PIXEL_FRACTION of the pixels differ by more than
-- H.PIXEL_TOL in some channel (tests/render_spec.lua says why these values).
H.MEAN_TOL, H.PIXEL_TOL, H.PIXEL_FRACTION = 2, 40, 0.01
H.GOLDEN_DIR = "tests/golden"

--- Compares two RGBA images of w x h pixels: true, or false and what differs.
function H.compare_images (a, b, w, h)
  if #a ~= w * h * 4 or #b ~= w * h * 4 then
    return false, string.format("sizes differ: %d and %d bytes for %dx%d", #a, #b, w, h)
  end
  local sum, bad = { 0, 0, 0, 0 }, 0
  for o = 1, #a, 4 do
    local worst = 0
    for c = 0, 3 do
      local d = math.abs(a:byte(o + c) - b:byte(o + c))
      sum[c + 1] = sum[c + 1] + d
      if d > worst then worst = d end
    end
    if worst > H.PIXEL_TOL then bad = bad + 1 end
  end
  local n, ok = w * h, true
  local means = {}
  for c = 1, 4 do
    means[c] = sum[c] / n
    if means[c] >= H.MEAN_TOL then ok = false end
  end
  if bad >= H.PIXEL_FRACTION * n then ok = false end
  if ok then return true end
  return false, string.format("mean absolute difference R %.2f G %.2f B %.2f A %.2f (limit %g); "
    .. "%.2f%% of the pixels differ by more than %d (limit %g%%)", means[1], means[2], means[3],
    means[4], H.MEAN_TOL, 100 * bad / n, H.PIXEL_TOL, 100 * H.PIXEL_FRACTION)
end

--- The pixels of a PNG that differ from its top left corner (the background) by more than 40
-- in the sum of R, G and B, over its first `rows` rows (all): { mask (mask[y * w + x + 1] =
-- true), n (their count), box = { x0, y0, x1, y1 } around them, w, h }.
function H.ink (path, rows)
  local px, w, h = require("lsys.core").png_read(path)
  local br, bg, bb = px:byte(1, 3)
  local mask, n = {}, 0
  local x0, y0, x1, y1 = w, h, -1, -1
  for y = 0, (rows or h) - 1 do
    for x = 0, w - 1 do
      local i = 4 * (y * w + x)
      local r, g, b = px:byte(i + 1, i + 3)
      if math.abs(r - br) + math.abs(g - bg) + math.abs(b - bb) > 40 then
        mask[y * w + x + 1] = true
        n = n + 1
        if x < x0 then x0 = x end
        if x > x1 then x1 = x end
        if y < y0 then y0 = y end
        if y > y1 then y1 = y end
      end
    end
  end
  return { mask = mask, n = n, w = w, h = h, box = { x0, y0, x1, y1 } }
end

--- Asserts that the render px (w x h) matches the golden image tests/golden/NAME.png.
-- LSYS_UPDATE_GOLDEN=1 writes it instead; on a mismatch the render is kept in $TMPDIR.
function H.golden (name, px, w, h)
  local core = require "lsys.core"
  local path = H.GOLDEN_DIR .. "/" .. name .. ".png"
  if os.getenv("LSYS_UPDATE_GOLDEN") == "1" then
    core.png_write(path, px, w, h, false)
    print("wrote " .. path)
  end
  local f = io.open(path, "rb")
  assert.truthy(f, path .. " is missing: write it with LSYS_UPDATE_GOLDEN=1 (see the top "
    .. "of tests/render_spec.lua)")
  f:close()
  local gpx, gw, gh = core.png_read(path)
  assert.equal(gw, w, "golden width")
  assert.equal(gh, h, "golden height")
  local ok, why = H.compare_images(px, gpx, w, h)
  if not ok then
    local actual = (os.getenv("TMPDIR") or "/tmp") .. "/lsys-" .. name .. ".actual.png"
    core.png_write(actual, px, w, h, false)
    why = ("%s: %s; this render is %s (if the change is intended, look at it and "
      .. "regenerate with LSYS_UPDATE_GOLDEN=1)"):format(path, why, actual)
  end
  assert.is_true(ok, why)
end
-- }====================================================================

return H
