-- The rock: `luarocks --lua-version 5.4 make` installs lsys into a temporary
-- tree from a copy of this source folder, offline (--deps-mode=none: the dependencies come
-- from Debian packages), and the installed lsys runs from another folder with the paths
-- `luarocks path` prints: it derives and renders a model, `require "lsys"` works in lua5.4,
-- and `lsys test` runs a spec there, with a `lua` on the PATH that is not Lua 5.4 (as after
-- Debian's alternatives switch to 5.1).
--
-- ctest's test `rock` runs it (`busted --run=rock`, about half a minute); the default run
-- leaves it out (tag #rock). Pending without luarocks (./setup.sh installs it).
local H = require "tests.helper"
local core = require "lsys.core"

local quote = require("lsys.util.text").shq

describe("the rock #rock #slow", function()
  local _, missing = H.sh("command -v luarocks")
  if missing ~= 0 then
    pending("luarocks is not installed (apt-get install luarocks; ./setup.sh does): "
      .. "the rock's install is not tested")
    return
  end

  local tmp, tree, work
  -- A shell command run in the folder `work` with the tree's paths, as a user would after
  -- eval "$(luarocks --lua-version 5.4 --tree TREE path)"; PATH starts with a folder whose
  -- `lua` is not Lua 5.4.
  local function in_work (cmd)
    return H.sh(("cd %s && eval \"$(luarocks --lua-version 5.4 --tree %s path)\" && "
                 .. "PATH=%s:\"$PATH\" && %s"):format(quote(work), quote(tree),
                                                      quote(tmp .. "/fakebin"), cmd))
  end

  setup(function()
    tmp = H.tmpdir()
    tree, work = tmp .. "/tree", tmp .. "/work"
    local src = tmp .. "/src"
    assert(os.execute(("mkdir -p %s %s %s/fakebin"):format(quote(src), quote(work), quote(tmp))))
    H.write(tmp .. "/fakebin/lua", "#!/bin/sh\necho 'this lua is not Lua 5.4' >&2\nexit 3\n")
    os.execute("chmod +x " .. quote(tmp .. "/fakebin/lua"))
    -- the source folder as it is (not only what git has), without build trees
    local out, code = H.sh(("tar -cf - --exclude=./.git --exclude='./build*' "
      .. "--exclude=./tools/node_modules --exclude=./bench/peers/node_modules . "
      .. "| tar -xf - -C %s"):format(quote(src)))
    assert.equal(0, code, out)
    out, code = H.sh(("cd %s && luarocks --lua-version 5.4 make --tree %s --deps-mode=none "
      .. "lsys-scm-1.rockspec"):format(quote(src), quote(tree)))
    assert.equal(0, code, out)
    assert.truthy(out:find("lsys scm-1 is now installed in " .. tree, 1, true), out)
  end)

  teardown(function() if tmp then H.rmdir(tmp) end end)

  it("installs the program, the modules and lsys/core.so into the tree", function()
    for _, f in ipairs { "/bin/lsys", "/share/lua/5.4/lsys/init.lua",
                         "/share/lua/5.4/lsys/testing.lua", "/share/lua/5.4/lsys/render.lua",
                         "/share/lua/5.4/lsys/util/text.lua", "/share/lua/5.4/lsys/ui/grow.lua",
                         "/share/lua/5.4/lsys/cli/init.lua", "/lib/lua/5.4/lsys/core.so" } do
      assert.truthy(H.read(tree .. f), tree .. f .. " is missing")
    end
    local out, code = in_work("command -v lsys")
    assert.equal(0, code, out)
    assert.equal(tree .. "/bin/lsys\n", out)
  end)

  it("derives and renders from another folder", function()
    local out, code = in_work("lsys derive abop/fig1_24a --steps 1")
    assert.equal(0, code, out)
    assert.equal("F[+F]F[-F]F\n", out)
    H.write(work .. "/plant.lua", 'local lsys = require "lsys"\nreturn lsys.lsystem { '
      .. 'axiom = "X", steps = 3, productions = "X --> F[+X]F[-X]+X\\nF --> FF" }\n')
    out, code = in_work("lsys derive plant.lua --steps 1")
    assert.equal(0, code, out)
    assert.equal("F[+X]F[-X]+X\n", out)
    if not core.has_render then return end
    out, code = in_work("lsys render plant.lua -o plant.png --size 64x48")
    assert.equal(0, code, out)
    local _, w, h = core.png_read(work .. "/plant.png")
    assert.same({ 64, 48 }, { w, h })
  end)

  it("gives `require \"lsys\"` to lua5.4 with the tree's paths", function()
    local out, code = in_work("lua5.4 -e 'local lsys = require \"lsys\"; "
      .. "print(lsys.lstring(\"F(1)[+A]\"), package.searchpath(\"lsys.core\", package.cpath))'")
    assert.equal(0, code, out)
    assert.equal("F(1)[+A]\t" .. tree .. "/lib/lua/5.4/lsys/core.so\n", out)
  end)

  it("runs `lsys test` on a spec in that folder, golden image included", function()
    os.execute("mkdir -p " .. quote(work .. "/spec"))
    H.write(work .. "/spec/plant_spec.lua", [[
local lsys = require "lsys"
local testing = require "lsys.testing"
local plant = dofile("plant.lua")
describe("plant.lua", function()
  it("derives", function()
    assert.lstring_equal("F[+X]F[-X]+X", plant:derive(1))
  end)
  it("draws", function()
    assert.scene_stats(plant, { lines = 38, triangles = 0, size = { 8, 10, 0 } })
    if testing.can_render() then
      assert.image_matches(plant, "spec/golden/plant.png", { size = 64 })
    end
  end)
end)
]])
    local out, code = in_work("LSYS_UPDATE_GOLDEN=1 lsys test -o plainTerminal")
    assert.equal(0, code, out)
    assert.truthy(out:find("2 successes / 0 failures / 0 errors / 0 pending", 1, true), out)
    out, code = in_work("lsys test -o plainTerminal")
    assert.equal(0, code, out)
    assert.truthy(out:find("2 successes / 0 failures / 0 errors / 0 pending", 1, true), out)
    out, code = in_work("lsys test -o plainTerminal --filter=nothing-matches && lua -v")
    assert.equal(3, code, out)                       -- the fake `lua` was first on the PATH
    assert.truthy(out:find("this lua is not Lua 5.4", 1, true), out)
  end)
end)
