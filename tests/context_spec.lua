-- Context-sensitive matching (ABOP ch. 1, section 1.8; cpfg's behaviour, docs/manual.md §6.3).
local H = require "tests.helper"
local lsys = require "lsys"

local derive = H.derive

describe("left context", function()
  it("matches the module just before", function()
    assert.equal("AX", derive("AB", "A < B --> X", 1))
  end)

  it("does not match a different module", function()
    assert.equal("CB", derive("CB", "A < B --> X", 1))
  end)

  it("fails at the start of the string", function()
    assert.equal("B", derive("B", "A < B --> X", 1))
  end)

  it("skips a whole branch before the module (A < C matches A[B]C)", function()
    assert.equal("A[B]X", derive("A[B]C", "A < C --> X", 1))
  end)

  it("skips several branches before the module", function()
    assert.equal("A[B][D[E]]X", derive("A[B][D[E]]C", "A < C --> X", 1))
  end)

  it("does not see into a sibling branch (B < C fails in A[B]C)", function()
    assert.equal("A[B]C", derive("A[B]C", "B < C --> X", 1))
  end)

  it("climbs out of the current branch (A < B matches the B in A[B])", function()
    assert.equal("A[X]", derive("A[B]", "A < B --> X", 1))
  end)

  it("climbs out of several nested branch starts", function()
    assert.equal("A[[X]]", derive("A[[C]]", "A < C --> X", 1))
  end)

  it("inside a branch, sees the branch's own earlier modules and skips their sub-branches",
  function()
    assert.equal("A[B[C]X]", derive("A[B[C]D]", "B < D --> X", 1))
    assert.equal("A[B[C]D]", derive("A[B[C]D]", "C < D --> X", 1))
  end)

  it("matches a multi-module left context", function()
    assert.equal("ABX", derive("ABC", "AB < C --> X", 1))
    assert.equal("DBC", derive("DBC", "AB < C --> X", 1))
  end)

  it("matches a multi-module left context across a skipped branch", function()
    assert.equal("AB[E]X", derive("AB[E]C", "AB < C --> X", 1))
  end)

  it("matches a multi-module left context that climbs out of a branch", function()
    assert.equal("AB[X]", derive("AB[C]", "AB < C --> X", 1))
  end)

  it("uses the string before the step (parallel rewriting: a signal moves one module per step)",
  function()
    local m = H.model("BAAAA", "B < A --> B\nB --> A")
    assert.same({ "BAAAA", "ABAAA", "AABAA", "AAABA", "AAAAB" }, H.steps(m, 4))
  end)

  it("matches a context module with parameters and binds its formals", function()
    assert.equal("A(1)B(3)", derive("A(1)B(2)", "A(x) < B(y) --> B(x+y)", 1))
  end)

  it("requires the context module's parameter count to match", function()
    assert.equal("A(1,2)B(2)", derive("A(1,2)B(2)", "A(x) < B(y) --> B(x+y)", 1))
  end)
end)

describe("right context", function()
  it("matches the module just after", function()
    assert.equal("XB", derive("AB", "A > B --> X", 1))
  end)

  it("fails at the end of the string", function()
    assert.equal("A", derive("A", "A > B --> X", 1))
  end)

  it("skips a branch it does not name (A > C matches A[B]C)", function()
    assert.equal("X[B]C", derive("A[B]C", "A > C --> X", 1))
  end)

  it("skips several branches it does not name", function()
    assert.equal("X[B][D[E]]C", derive("A[B][D[E]]C", "A > C --> X", 1))
  end)

  it("does not enter a branch it does not name (A > B fails in A[B])", function()
    assert.equal("A[B]", derive("A[B]", "A > B --> X", 1))
  end)

  it("fails at the end of its branch (B > C fails in A[B]C)", function()
    assert.equal("A[B]C", derive("A[B]C", "B > C --> X", 1))
  end)

  it("names a branch (A > [B]C matches A[B]C)", function()
    assert.equal("X[B]C", derive("A[B]C", "A > [B]C --> X", 1))
  end)

  it("fails when the named branch holds something else (A > [B]C in A[D]C)", function()
    assert.equal("A[D]C", derive("A[D]C", "A > [B]C --> X", 1))
  end)

  it("matches ] literally: ABOP p. 32's S > G[H]M needs = in cpfg (S > G[H=]M)", function()
    -- ABOP fig. 1.24 reads G[H]M as matching the branch [HI[JK]L]; cpfg (and lsys) compare
    -- the pattern's ] with the I that follows H, and write the rest of the branch as =
    assert.equal("ABC[DE][SG[HI[JK]L]MNO]",
      derive("ABC[DE][SG[HI[JK]L]MNO]", "BC < S > G[H]M --> X", 1))
    assert.equal("ABC[DE][XG[HI[JK]L]MNO]",
      derive("ABC[DE][SG[HI[JK]L]MNO]", "BC < S > G[H=]M --> X", 1))
  end)

  it("leaves the current branch through an explicit ] in the pattern (C > ]D in A[BC]D)", function()
    assert.equal("A[BX]D", derive("A[BC]D", "C > ]D --> X", 1))
  end)

  it("does not skip the rest of the branch at an explicit ] (B > C]D in A[BCE]D)", function()
    assert.equal("A[XC]D", derive("A[BC]D", "B > C]D --> X", 1))
    assert.equal("A[BCE]D", derive("A[BCE]D", "B > C]D --> X", 1))
  end)

  it("matches a multi-module right context", function()
    assert.equal("XBC", derive("ABC", "A > BC --> X", 1))
    assert.equal("ABD", derive("ABD", "A > BC --> X", 1))
  end)

  it("matches a right context module with parameters and binds its formals", function()
    assert.equal("A(5)B(3)", derive("A(2)B(3)", "A(x) > B(y) --> A(x+y)", 1))
  end)
end)

-- Every case below was run through cpfg (vlab 9bf820d, built as docs/cpfg.md describes)
-- and lsys gives cpfg's string: the right context is one linear scan (cpfg's RconDiff).
describe("right context as cpfg matches it", function()
  local CASES = {
    -- a [ in the pattern matches only the next branch: no search among siblings
    { "A[B][C]D", "A > [C]D", "A[B][C]D" },
    { "A[D][B]C", "A > [B]C", "A[D][B]C" },
    { "A[B][E][C]D", "A > [B][C]D", "A[B][E][C]D" },
    { "AB[E][C]D", "A > B[C]D", "AB[E][C]D" },
    { "A[D][B]C", "A > [B][D]C", "A[D][B]C" },
    -- unnamed branches before the next named module are still skipped
    { "A[B][D]C", "A > [B]C", "X[B][D]C" },
    { "A[B][D]C", "A > [B][D]C", "X[B][D]C" },
    -- a ] matches a literal ]: it does not skip the rest of a branch
    { "A[BCE]D", "B > C]D", "A[BCE]D" },
    { "A[BE]C", "A > [B]C", "A[BE]C" },
    { "A[B[C]D]E", "C > ]]E", "A[B[C]D]E" },
    { "A[BC[E]]D", "C > ]D", "A[BX[E]]D" },       -- the unnamed [E] is skipped
    -- = moves to the ] that ends the current branch
    { "A[BCE]D", "B > =]D", "A[XCE]D" },
    { "A[BCE]D", "B > C=]D", "A[XCE]D" },
    { "F[+D][-D]", "F > [=][-D=]", "X[+D][-D]" },
    { "A[B][C]D", "A > [=][C]D", "X[B][C]D" },
    { "A[B]C", "A > [B=]C", "X[B]C" },
    { "A[B]C", "A > [B=]=C", "A[B]C" },          -- the second = goes to the string's end
    { "ABC", "A > B=C", "ABC" },
    -- an unfinished pattern branch
    { "A[B]", "A > [B", "X[B]" },
    { "A[B]C", "A > [B]", "X[B]C" },
  }
  for _, c in ipairs(CASES) do
    it(c[2] .. " on " .. c[1], function()
      assert.equal(c[3], derive(c[1], c[2] .. " --> X", 1))
    end)
  end

  it("skips ignored modules, never brackets (ignore: +)", function()
    local IGN = {
      { "A+[+B]C", "A > [B]C", "X+[+B]C" },
      { "A+[+B]+C", "A > [B]C", "X+[+B]+C" },
      { "A[B]+C", "A > [B]C", "X[B]+C" },
      { "A+B[C]D", "A > B[C]D", "X+B[C]D" },
      { "A[B+]C", "A > [B]C", "X[B+]C" },
      { "A[B+]C", "B > ]C", "A[X+]C" },
      { "A[+B][C]D", "A > [C]D", "A[+B][C]D" },
    }
    for _, c in ipairs(IGN) do
      local m = lsys.lsystem { axiom = c[1], productions = c[2] .. " --> X", ignore = "+" }
      assert.equal(c[3], tostring(m:derive(1)), c[2] .. " on " .. c[1])
    end
  end)

  it("takes = with parameters as a module like any other", function()
    assert.equal("X=(1)B", derive("A=(1)B", "A > =(x)B --> X", 1))
    assert.equal("AB=(1)", derive("AB=(1)", "A > =(x) --> X", 1))    -- not a skip
  end)
end)

describe("both contexts", function()
  it("match together (AB < C > DE)", function()
    assert.equal("ABXDE", derive("ABCDE", "AB < C > DE --> X", 1))
  end)

  it("fail when one side fails", function()
    assert.equal("ABCDF", derive("ABCDF", "AB < C > DE --> X", 1))
    assert.equal("FBCDE", derive("FBCDE", "AB < C > DE --> X", 1))
  end)

  it("bind formals left to right: left context, predecessor, right context", function()
    assert.equal("A(1)B(123)C(3)",
      derive("A(1)B(2)C(3)", "A(a) < B(b) > C(c) --> B(a*100+b*10+c)", 1))
  end)

  it("a context-free rule after a failing context-sensitive one still applies", function()
    assert.equal("Y[B]", derive("A[B]", "A > B --> X\nA --> Y", 1))
  end)
end)

describe("ignore list", function()
  it("left context skips symbols on the ignore list", function()
    local m = lsys.lsystem { axiom = "A+B", ignore = "+", productions = "A < B --> C" }
    assert.equal("A+C", tostring(m:derive(1)))
  end)

  it("without an ignore list the same rule does not match", function()
    assert.equal("A+B", derive("A+B", "A < B --> C", 1))
  end)

  it("right context skips symbols on the ignore list", function()
    assert.equal("X+-&B", derive("A+-&B", "A > B --> X", 1, { ignore = "+-&" }))
  end)

  it("ignores the symbols also inside a multi-module context", function()
    assert.equal("A+B-X", derive("A+B-C", "AB < C --> X", 1, { ignore = "+-" }))
  end)

  it("does not stop ignored symbols from being rewritten", function()
    assert.equal("AGX", derive("AFB", "A < B --> X\nF --> G", 1, { ignore = "F" }))
  end)

  it("steps over listed brackets in a right context, as cpfg; a left context keeps them",
     function()
    -- cpfg (its RconDiff tests the ignore table before it skips a branch)
    assert.equal("X[B]C", derive("A[B]C", "A > B --> X", 1, { ignore = "[]" }))
    assert.equal("[X]B", derive("[A]B", "A > B --> X", 1, { ignore = "]" }))
    assert.equal("A[B]C", derive("A[B]C", "A > C --> X", 1, { ignore = "[" }))
    assert.equal("A[B]C", derive("A[B]C", "B < C --> X", 1, { ignore = "[" }))
  end)

  it("cannot match a context module that is on the ignore list: it is skipped", function()
    -- with F ignored, the left context of B is A, so F < B cannot match
    assert.equal("AFB", derive("AFB", "F < B --> X", 1, { ignore = "F" }))
    assert.equal("AFX", derive("AFB", "A < B --> X", 1, { ignore = "F" }))
  end)
end)

describe("consider list", function()
  it("left context sees only symbols on the consider list", function()
    assert.equal("ACDX", derive("ACDB", "A < B --> X", 1, { consider = "AB" }))
  end)

  it("right context sees only symbols on the consider list", function()
    assert.equal("XCDB", derive("ACDB", "A > B --> X", 1, { consider = "AB" }))
  end)

  it("makes the right context step over brackets it does not name, as cpfg", function()
    -- cpfg: its consider list ignores every other module, brackets included
    assert.equal("X[B]", derive("A[B]", "A > B --> X", 1, { consider = "AB" }))
    assert.equal("A[B]", derive("A[B]", "A > B --> X", 1, { consider = "AB[]" }))
    assert.equal("A[B]", derive("A[B]", "A > [B] --> X", 1, { consider = "AB" }))
    assert.equal("X[B]C[B]", derive("A[B]C[B]", "A > BB --> X", 1, { consider = "AB" }))
    assert.equal("A[X]C", derive("A[B]C", "B > C --> X", 1, { consider = "BC" }))
    assert.equal("[A]B", derive("[A]B", "B > A --> X", 1, { consider = "AB" }))
  end)

  it("still lets the left context climb out of a branch", function()
    assert.equal("A[C+X]", derive("A[C+B]", "A < B --> X", 1, { consider = "AB" }))
  end)
end)

describe("ring = true", function()
  it("wraps the left context from the first module to the last", function()
    assert.equal("XBC", derive("ABC", "C < A --> X", 1, { ring = true }))
  end)

  it("wraps the right context from the last module to the first", function()
    assert.equal("ABY", derive("ABC", "C > A --> Y", 1, { ring = true }))
  end)

  it("wraps both ways in the same step", function()
    assert.equal("XBY", derive("ABC", "C < A --> X\nC > A --> Y", 1, { ring = true }))
  end)

  it("does not wrap without ring", function()
    assert.equal("ABC", derive("ABC", "C < A --> X\nC > A --> Y", 1))
  end)

  it("a signal travels around the ring", function()
    local m = H.model("AAB", "B < A --> B\nB --> A", { ring = true })
    assert.same({ "AAB", "BAA", "ABA", "AAB" }, H.steps(m, 3))
  end)
end)

-- ABOP fig. 1.31 (a): #ignore +-F, axiom F1F1F1, n = 30, delta = 22.5.
-- `* < + > * -> -` is written `+ --> -` (no context).
local FIG_1_31A = {
  { lc = "0", pred = "0", rc = "0", succ = "0" },
  { lc = "0", pred = "0", rc = "1", succ = "1[+F1F1]" },
  { lc = "0", pred = "1", rc = "0", succ = "1" },
  { lc = "0", pred = "1", rc = "1", succ = "1" },
  { lc = "1", pred = "0", rc = "0", succ = "0" },
  { lc = "1", pred = "0", rc = "1", succ = "1F1" },
  { lc = "1", pred = "1", rc = "0", succ = "0" },
  { lc = "1", pred = "1", rc = "1", succ = "0" },
  { pred = "+", succ = "-" },
  { pred = "-", succ = "+" },
}
-- ABOP fig. 1.31 (b).
local FIG_1_31B = {
  { lc = "0", pred = "0", rc = "0", succ = "1" },
  { lc = "0", pred = "0", rc = "1", succ = "1[-F1F1]" },
  { lc = "0", pred = "1", rc = "0", succ = "1" },
  { lc = "0", pred = "1", rc = "1", succ = "1" },
  { lc = "1", pred = "0", rc = "0", succ = "0" },
  { lc = "1", pred = "0", rc = "1", succ = "1F1" },
  { lc = "1", pred = "1", rc = "0", succ = "1" },
  { lc = "1", pred = "1", rc = "1", succ = "0" },
  { pred = "+", succ = "-" },
  { pred = "-", succ = "+" },
}

local function fig_model (rules)
  local text = {}
  for i, r in ipairs(rules) do text[i] = H.rule_text(r) end
  return lsys.lsystem { axiom = "F1F1F1", ignore = "+-F", productions = table.concat(text, "\n") }
end

describe("ABOP fig. 1.31 (a)", function()
  it("gives the hand-computed strings for its first six steps", function()
    assert.same({
      "F1F1F1",
      "F1F0F1",
      "F1F1F1F1",
      "F1F0F0F1",
      "F1F0F1[+F1F1]F1",
      "F1F1F1F1[-F0F1]F1",
      "F1F0F0F0[+F1F1F1]F1",
    }, H.steps(fig_model(FIG_1_31A), 6))
  end)

  it("agrees with the reference deriver after 30 and 38 steps", function()
    local s = fig_model(FIG_1_31A):derive(30)
    local ref = H.ref_derive("F1F1F1", FIG_1_31A, 30, "+-F")
    assert.equal(ref, tostring(s))
    -- past 8192 modules: the worker threads' step, by the symbols' context tables
    s = fig_model(FIG_1_31A):derive(38)
    ref = H.ref_derive("F1F1F1", FIG_1_31A, 38, "+-F")
    assert.is_true(#ref > 40000)
    assert.equal(#ref, #s)
    assert.equal(ref, tostring(s))
  end)
end)

describe("ABOP fig. 1.31 (b)", function()
  it("gives the hand-computed strings for its first five steps", function()
    assert.same({
      "F1F1F1",
      "F1F0F1",
      "F1F1F1F1",
      "F1F0F0F1",
      "F1F0F1[-F1F1]F1",
      "F1F1F1F1[+F0F1]F1",
    }, H.steps(fig_model(FIG_1_31B), 5))
  end)

  it("agrees with the reference deriver after 30 and 34 steps", function()
    for _, n in ipairs { 30, 34 } do
      local s = fig_model(FIG_1_31B):derive(n)
      assert.equal(H.ref_derive("F1F1F1", FIG_1_31B, n, "+-F"), tostring(s))
    end
  end)
end)

describe("contexts on long strings (the worker threads' step)", function()
  -- random bracketed strings of some 20,000 modules, with runs nested 300 deep, across the
  -- 64-module words of the bracket table
  local function lcg (seed)                  -- a small LCG: the same strings everywhere
    local x = seed
    return function (k)
      x = (x * 1103515245 + 12345) % 2147483648
      return x % k + 1
    end
  end
  -- a random bracketed string of about n modules of `syms` (each written by mod), extra
  -- adding runs after a module and giving the brackets it leaves open
  local function bracketed (seed, n, syms, mod, extra)
    local rnd, out, depth = lcg(seed), {}, 0
    while #out < n do
      local c = syms[rnd(#syms)]
      if c == "]" and depth == 0 then c = "A" end
      if c == "[" then depth = depth + 1 elseif c == "]" then depth = depth - 1 end
      out[#out + 1] = mod(c, rnd)
      depth = depth + extra(out, rnd, mod)
    end
    return table.concat(out) .. string.rep("]", depth)
  end
  local function random_string (seed, n)
    return bracketed(seed, n, { "A", "B", "C", "+", "-", "[", "]", "[", "]" },
      function (c) return c end,
      function (out, rnd)
        if rnd(400) == 1 then out[#out + 1] = string.rep("[A", 300) .. string.rep("B]", 300) end
        return 0
      end)
  end
  local RULES = {
    { lc = "A", pred = "B", rc = "C", succ = "C" },
    { lc = "BA", pred = "C", succ = "A" },
    { pred = "A", rc = "CB", succ = "B" },
    { lc = "C", pred = "A", succ = "[B]" },
    { pred = "B", rc = "A", succ = "A" },
  }
  local function model (axiom, threads)
    local text = {}
    for i, r in ipairs(RULES) do text[i] = H.rule_text(r) end
    return lsys.lsystem { axiom = axiom, ignore = "+-", threads = threads,
                          productions = table.concat(text, "\n") }
  end
  for _, seed in ipairs { 1, 2 } do
    it("give the reference deriver's string, seed " .. seed, function()
      local axiom = random_string(seed, 12000)
      for _, threads in ipairs { 1, 2 } do
        local s = tostring(model(axiom, threads):derive(3))
        assert.is_true(#s > 12000, "a short string: " .. #s)
        assert.is_true(s == H.ref_derive(axiom, RULES, 3, "+-"),
          ("threads = %d: not the reference deriver's string"):format(threads))
      end
    end)
  end

  -- The context tables keep a window of brackets per thread; a bracket whose partner is
  -- more than 1,024 modules away is found in the string's list of far ones, a nearer one
  -- outside the window by a scan. These strings have branches of every span from a few
  -- modules to most of the string, nested 2,000 deep, across every chunk and window edge.
  local function far_string (seed, n, param)
    return bracketed(seed, n, { "A", "B", "C", "+", "[", "]" },
      function (c, rnd)
        if param and (c == "A" or c == "B" or c == "C") then return c .. "(" .. rnd(9) .. ")" end
        return c
      end,
      function (out, rnd, mod)
        local r = rnd(3000)
        if r == 1 then                            -- deep: spans up to 8,000 modules
          out[#out + 1] = string.rep("[" .. mod("A", rnd), 2000) ..
                          string.rep(mod("B", rnd) .. "]", 2000)
        elseif r == 2 then                        -- a long branch opens here
          out[#out + 1] = "["
          return 1
        end
        return 0
      end)
  end

  it("give the reference deriver's string across far brackets on 1 and 2 threads", function()
    local axiom = far_string(7, 40000)
    local ref = H.ref_derive(axiom, RULES, 2, "+-")
    assert.is_true(#ref > 60000, "a short string: " .. #ref)
    for _, threads in ipairs { 1, 2 } do
      local s = tostring(model(axiom, threads):derive(2))
      assert.is_true(s == ref, ("threads = %d: not the reference deriver's string"):format(threads))
    end
  end)

  it("bind the same parameters on the worker threads as on the calling thread", function()
    -- 150,000 modules: several of the calling thread's windows of 65,536; a rule that runs
    -- in Lua (Z is in the string) makes the step run there
    local axiom = far_string(11, 150000, true) .. "Z"
    local prods = {
      "A(a) < B(b) > C(c) --> C(a + 10 * b + 100 * c)",
      "B(a) A(b) < C(c) --> A(a - b + c)",
      "A(a) > C(b) B(c) --> B(a * b - c)",
      "C(a) < A(b) --> [B(a + b)]",
      "B(a) > A(b) --> A(b - a)",
    }
    local function derived (threads, seq)
      local p = { table.unpack(prods) }
      if seq then p[#p + 1] = { "Z", function () return lsys.produce("Z") end } end
      return tostring(lsys.lsystem { axiom = axiom, ignore = "+", threads = threads,
                                     productions = p }:derive(2))
    end
    local seq = derived(1, true)
    assert.is_true(#seq > 150000, "a short string: " .. #seq)
    assert.truthy(seq:find("C(21", 1, true))   -- some contexts bound their parameters
    for _, threads in ipairs { 1, 2 } do
      assert.is_true(derived(threads) == seq,
        ("threads = %d: not the calling thread's string"):format(threads))
    end
  end)
end)

describe("a symbol with several rules and no context", function()
  -- its modules are rewritten by the table of neighbours' symbols on the worker threads; a
  -- model without contexts has no context tables, so the rules without a context apply
  -- (the first one), as the calling thread chooses: the step once read the tables it had not
  it("takes its first rule on a long bracketed string, in place too", function()
    local axiom = H.rep("A[B]A[[A]B]", 2000)
    for _, threads in ipairs { 1, 2 } do    -- (more rules than the short programs' four)
      local m = lsys.lsystem { axiom = axiom, threads = threads, productions =
        "A --> C[A]\nA --> D\nA --> E\nA --> F\nA --> G\nB --> B" }
      local s = tostring(m:derive(2))
      assert.equal(H.rep("C[C[A]][B]C[C[A]][[C[C[A]]]B]", 2000), s)
    end
  end)
end)
