-- The view file reader under tests/fuzz_view.lua's mutations, 2000 variants (the
-- standalone run does 20000): every variant loads or fails with "file:LINE: ...".
require "tests.helper"
local run = dofile "tests/fuzz_view.lua"

describe("view file fuzzing", function ()
  it("loads or rejects with file and line 2000 mutated view files", function ()
    local counts = run(2000, 7)
    assert.equal(2000, counts.ok + counts.error)
    -- both outcomes occur: the mutations neither break every file nor none of them
    assert.is_true(counts.ok > 100, "only " .. counts.ok .. " variants loaded")
    assert.is_true(counts.error > 100, "only " .. counts.error .. " variants were rejected")
  end)
end)
