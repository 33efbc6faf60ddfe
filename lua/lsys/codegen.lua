--- Writing Lua source that other text goes into: `lsys import` (a cpfg model's
-- comments, file names and strings), `sketch:save_model` (a sketch's names). Every piece of
-- text from elsewhere goes through one of these, so that no byte of it can end a comment or
-- a string and become code; `check` then runs the written source in an environment of
-- stand-ins, where it can reach only what the generator meant it to.
-- @module lsys.codegen
local string = string
local type, tostring, error, setmetatable, load, pcall = type, tostring, error,
      setmetatable, load, pcall
local format, byte, gsub, find = string.format, string.byte, string.gsub, string.find
local _ENV = nil

local M = {}

local KEYWORDS = {}
for w in ([[and break do else elseif end false for function goto if in local nil not or
            repeat return then true until while]]):gmatch("%a+") do KEYWORDS[w] = true end
M.KEYWORDS = KEYWORDS

--- `s` as a Lua string literal on one line (control characters and quotes escaped).
function M.string (s)
  return (gsub(format("%q", tostring(s)), "\n", "n"))   -- %q writes a newline as \ + newline
end

--- `s` as the text of a line comment: `-- ` then `s` with every control character (a
-- carriage return ends a Lua comment as a newline does) written as \ and its code, so
-- the comment ends where the line does. An empty `s` gives `--`.
function M.comment (s)
  s = tostring(s)
  if s == "" then return "--" end
  return "-- " .. gsub(s, "%c", function (c)
    return c == "\t" and "  " or format("\\%d", byte(c))
  end)
end

--- Whether `s` is a Lua name (not a keyword).
function M.isname (s)
  return type(s) == "string" and find(s, "^[%a_][%w_]*$") ~= nil and not KEYWORDS[s]
end

--- The key `k` in a table constructor: `k` when it is a name, else `[literal]`.
function M.key (k)
  if M.isname(k) then return k end
  return "[" .. (type(k) == "string" and M.string(k) or tostring(k)) .. "]"
end

--- `t` indexed by `k`: `t.k` when k is a name, else `t[literal]`.
function M.index (t, k)
  if M.isname(k) then return t .. "." .. k end
  return t .. "[" .. (type(k) == "string" and M.string(k) or tostring(k)) .. "]"
end

-- A stand-in for a module value: any field is another stand-in; calling one is allowed
-- only for the paths in `calls`, and gives a stand-in; changing one is refused.
local function standin (path, calls)
  return setmetatable({}, {
    __index = function (_, k) return standin(path .. "." .. tostring(k), calls) end,
    __newindex = function (_, k)
      error({ reach = format("changes %s.%s", path, tostring(k)) }, 0)
    end,
    __call = function ()
      if not calls[path] then error({ reach = format("calls %s", path) }, 0) end
      return standin(path .. "()", calls)
    end,
    __concat = function () return standin(path .. "..", calls) end,
  })
end

--- Runs the Lua source `src` (named `name` in messages) in an environment of stand-ins:
-- `require` gives a stand-in for the modules listed in `allow.modules` (a set), the
-- globals `allow.globals` (a table of name = value) are given, and calling a module's
-- function is allowed only for the paths in `allow.calls` (a set of "lsys.lsystem", ...).
-- Anything else the source reaches at load (a global such as `os`, a module, a call)
-- raises "NAME reaches ... when loaded"; another error, "NAME fails when loaded among
-- stand-ins". Returns true.
function M.check (src, name, allow)
  local mods, calls, globals = allow.modules or {}, allow.calls or {}, allow.globals or {}
  local env = setmetatable({}, {
    __index = function (_, k)
      if k == "require" then
        return function (mod)
          if not mods[mod] then error({ reach = format("requires %s", tostring(mod)) }, 0) end
          return standin(mod, calls)
        end
      end
      if globals[k] ~= nil then return globals[k] end
      error({ reach = format("the global '%s'", tostring(k)) }, 0)
    end,
    __newindex = function (_, k)
      error({ reach = format("sets the global '%s'", tostring(k)) }, 0)
    end,
  })
  local chunk, err = load(src, "=" .. name, "t", env)
  if not chunk then error(format("%s does not compile: %s", name, err), 0) end
  local ok, what = pcall(chunk)
  if ok then return true end
  if type(what) == "table" and what.reach then
    error(format("%s reaches %s when loaded (it may reach only what it was written to)",
                 name, what.reach), 0)
  end
  error(format("%s fails when loaded among stand-ins: %s", name, tostring(what)), 0)
end

return M
