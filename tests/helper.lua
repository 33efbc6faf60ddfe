--- Test helpers shared by the busted specs.
-- Loaded by busted as the `helper` (see .busted) and also `require "tests.helper"`-able
-- from a spec, so a spec runs on its own too: `busted tests/context_spec.lua`.
--
-- Registers with luassert, through lsys.testing (docs/testing.md):
--   assert.near(expected, actual, tol)      numbers, or (nested) tables of numbers elementwise
--   assert.error_contains(fn, s1, s2, ...)  fn raises; the message contains every si (plain text)
--   assert.lstring_equal, assert.scene_stats, assert.image_matches
--
-- Functions (module table H):
--   H.model(axiom, productions, opts)  lsys.lsystem with axiom/productions merged into opts
--   H.derive(axiom, productions, n, opts) tostring of n derivation steps
--   H.steps(model, n)                  list of tostring for steps 0..n (via model:step)
--   H.modules(s)                       list of { name, p1, p2, ... } for every module of s
--   H.rep(text, n)                     text repeated n times
--   H.errof(f, ...)                    the message of the error f(...) raises (fails without)
--   H.binomial_tol(n, p, k)            k standard deviations of a binomial(n, p) count
--   H.tmpdir(), H.rmdir(d), H.read(path), H.write(path, s)     temporary folders and files
--   H.sh(cmd), H.lsys(script, opts)    a shell command, a script run by the lsys program:
--                                      output and exit status
--   H.ref_derive(axiom, rules, n, ignore)  independent reference deriver (see below)
local assert = require "luassert"

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

-- The assertions of lsys.testing (lstring_equal, near, error_contains, scene_stats,
-- image_matches), registered with luassert. It requires lsys only when an assertion runs, so
-- each spec file still loads its own lsys (busted restores package.loaded after a file).
local testing = require "lsys.testing"

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

--- The message of the error f(...) raises, as a string; fails the test when it raises none.
function H.errof (f, ...)
  local ok, msg = pcall(f, ...)
  assert.is_false(ok, "expected an error")
  return tostring(msg)
end

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
-- Images: two renders compared with a tolerance, and golden images in tests/golden/, with
-- lsys.testing's comparison: the mean absolute difference of every channel below 2 and
-- fewer than 1% of the pixels differing by more than 40 in some channel (testing.TOLERANCE;
-- tests/render_spec.lua says why these values).
H.GOLDEN_DIR = "tests/golden"

--- Compares two RGBA images of w x h pixels: true, or false and what differs.
function H.compare_images (a, b, w, h) return testing.compare_images(a, b, w, h) end

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
-- LSYS_UPDATE_GOLDEN=1 writes it instead, and a missing one is written and fails once; on a
-- mismatch the render is kept in $TMPDIR.
function H.golden (name, px, w, h)
  local actual = (os.getenv("TMPDIR") or "/tmp") .. "/lsys-" .. name .. ".actual.png"
  assert.image_matches({ px, w, h }, H.GOLDEN_DIR .. "/" .. name .. ".png", { actual = actual })
end
-- }====================================================================

--- A sketch stroke: n + 1 points evenly from (x0, y0) to (x1, y1), each with pressure p.
function H.line (x0, y0, x1, y1, n, p)
  local t = {}
  for i = 0, n do
    local f = i / n
    t[#t + 1] = { x0 + f * (x1 - x0), y0 + f * (y1 - y0), p }
  end
  return t
end

return H
