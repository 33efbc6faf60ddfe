-- luacheck configuration (issue 14): `luacheck lua tests examples bench` in the source dir
-- (Debian package lua-check). ctest runs it as the test `luacheck`; any warning fails it.
std = "lua54"
max_line_length = 100         -- as the C sources (CONTRIBUTING.md, Habits)

ignore = {
  -- `local _ENV = nil` after a module's local copies of the globals is never read on
  -- purpose: it makes any later global access an error (CONTRIBUTING.md, where things live; LPeg's re.lua).
  "211/_ENV",
  -- `not (x > 0)` is how the code rejects NaN along with the rest: the rewrite luacheck
  -- suggests (x <= 0) is false for NaN and would let it through.
  "581",
}

-- Installed by npm for the glTF validator and the peer benchmarks; not ours.
exclude_files = { "tools/node_modules/**", "bench/peers/node_modules/**" }

-- The specs run under busted.
files["tests/*_spec.lua"] = { std = "+busted" }

-- The readers' if-chains read as tables of line kinds: a kind that is skipped has an empty
-- branch with a comment.
files["tests/export_reader.lua"] = { ignore = { "542" } }
