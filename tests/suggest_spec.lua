-- "Did you mean": lsys.util.suggest (the optimal string alignment distance, after Damerau
-- 1964) and the messages that use it: model options, view options, lsys.render's options,
-- the program's commands and options (--set names: friction_spec, cpfg_cli_spec, batch_spec).
local H = require "tests.helper"
local lsys = require "lsys"
local suggest = require "lsys.util.suggest"

describe("lsys.util.suggest", function ()
  it("counts insertions, deletions, substitutions and swaps of neighbours as one edit", function ()
    local d = suggest.distance
    assert.equal(0, d("axiom", "axiom"))
    assert.equal(1, d("prodcutions", "productions"))      -- a swap
    assert.equal(1, d("step", "steps"))                   -- an insertion
    assert.equal(1, d("colour", "color"))                 -- a deletion
    assert.equal(1, d("angel", "angle"))
    assert.equal(3, d("ca", "abc"))          -- no edit inside a swapped pair (Damerau's 2)
    assert.equal(3, d("kitten", "sitting"))
    assert.equal(4, d("", "abcd"))
    assert.equal(3, d("abcdefgh", "zzzzzzzz", 2))         -- past the cap: cap + 1
  end)

  it("suggests the names within a third of the name's length, ties sorted", function ()
    local names = { "productions", "decomposition", "homomorphism", "axiom", "steps", "seed" }
    assert.same({ "productions" }, suggest.nearest("prodcutions", names))
    assert.same({ "axiom" }, suggest.nearest("Axiom", names))     -- case is no edit
    assert.same({}, suggest.nearest("xyzzy", names))
    assert.same({}, suggest.nearest("s", names))          -- one letter: never all of it
    assert.same({ "steps" }, suggest.nearest("seps", names))
    assert.same({ "car", "cat" }, suggest.nearest("cax", { "cat", "dog", "car" }))
    assert.equal(" (did you mean 'car' or 'cat'?)", suggest.hint("cax", { "cat", "car" }))
    assert.equal(" (did you mean 'cab', 'car' or 'cat'?)",
                 suggest.hint("cax", { "cat", "car", "cab" }))
    assert.equal(" (did you mean 'D'?)", suggest.hint("d", { "c", "b", "D" }))  -- only its case
    assert.equal(" (did you mean '--steps'?)",
                 suggest.hint("step", names, function (n) return "'--" .. n .. "'" end))
    assert.equal("", suggest.hint("xyzzy", names))
  end)
end)

describe("messages with a suggestion", function ()
  it("name the model option meant", function ()
    assert.equal("unknown option 'prodcutions' (did you mean 'productions'?)",
                 H.errof(lsys.lsystem, { axiom = "A", prodcutions = "A --> B" }))
    assert.equal("unknown option 'xyzzy'", H.errof(lsys.lsystem, { axiom = "A", xyzzy = 1 }))
  end)

  it("name the view option meant, else list them", function ()
    assert.equal("model: unknown view option 'angel' (did you mean 'angle'?)",
                 H.errof(lsys.lsystem, { view = { angel = 30 } }))
    assert.matches("^model: unknown view option 'zoom' %(known: angle, background, ",
                   H.errof(lsys.lsystem, { view = { zoom = 3 } }))
  end)

  it("name the command and the command-line option meant", function ()
    local out, code = H.sh(H.BIN .. " rendr examples/default.lua")
    assert.equal(2, code)
    assert.equal("lsys: unknown command 'rendr' (did you mean 'render'?)\n"
                 .. "Run 'lsys --help' for the commands.\n", out)
    out, code = H.sh(H.BIN .. " render --frmaes out examples/default.lua")
    assert.equal(2, code)
    assert.equal("lsys: render: unknown option '--frmaes' (did you mean '--frames'?)\n"
                 .. "Run 'lsys render --help' for its options.\n", out)
    out, code = H.sh(H.BIN .. " derive --bogus")
    assert.equal(2, code)
    assert.equal("lsys: derive: unknown option '--bogus'\n"
                 .. "Run 'lsys derive --help' for its options.\n", out)
  end)
end)
