-- The documentation against the repository: every relative link of
-- the Markdown pages points at a file that exists (and at a heading that exists, for
-- `page.md#anchor`); no page, and no comment in the sources, points outside the repository
-- (the project's working notes and source texts are not part of it: the pages cite the
-- published works, docs/manual.md §12); every `lsys COMMAND` a page shows is a command of
-- the program; every JSON example reads, and the sketch files among them make a plant; the
-- examples index names every file and folder of examples/, and the README every example
-- folder and every package setup.sh installs.
local H = require "tests.helper"

-- The pages checked: every Markdown file of the repository but the changelog, which
-- records history (old names and links stay as they were).
local PAGES = {
  "README.md", "CONTRIBUTING.md", "bench/README.md", "examples/README.md",
  "examples/cpfg/README.md", "examples/gallery/README.md",
  "tests/fuzz/findings/README.md", "tests/fuzz/lua/findings/README.md",
}
do
  local p = io.popen("ls docs/*.md")
  for f in p:lines() do PAGES[#PAGES + 1] = f end
  p:close()
end

local read = H.read

local function exists (path)
  local f = io.open(path, "rb")
  if f then f:close() return true end
  return false
end

local function dirname (path)
  return path:match("^(.*)/[^/]*$") or "."
end

-- a/b/../c -> a/c; nil when the path climbs above the repository
local function normalize (path)
  local out = {}
  for part in path:gmatch("[^/]+") do
    if part == ".." then
      if #out == 0 then return nil end
      out[#out] = nil
    elseif part ~= "." then
      out[#out + 1] = part
    end
  end
  return table.concat(out, "/")
end

-- The lines a shell command prints.
local function output_lines (cmd)
  local p, l = io.popen(cmd), {}
  for line in p:lines() do l[#l + 1] = line end
  p:close()
  return l
end

-- A page split into its prose (without fenced code blocks and inline code spans: links
-- there are code, the blocks' lines left empty) and its code (the lines of fenced blocks
-- and the inline spans, as a list).
local function split (text)
  local lines, code, fence = {}, {}, nil
  for line in (text .. "\n"):gmatch("(.-)\n") do
    local f = line:match("^%s*(```+)") or line:match("^%s*(~~~+)")
    if fence then
      if f and f:sub(1, 1) == fence:sub(1, 1) and #f >= #fence then fence = nil
      else code[#code + 1] = line end
      lines[#lines + 1] = ""
    elseif f then
      fence = f
      lines[#lines + 1] = ""
    else
      for span in line:gmatch("`+(.-)`+") do code[#code + 1] = span end
      lines[#lines + 1] = (line:gsub("(`+).-%1", ""))
    end
  end
  return table.concat(lines, "\n"), code
end

-- Non-ASCII punctuation that GitHub drops from heading anchors (letters stay).
local DROP = {}
for _, c in ipairs { "§", "—", "–", "×", "→", "←", "…", "·", "’", "‘", "“", "”", "≥", "≤",
                     "−", "°", "²", "³", "±", "✓" } do
  DROP[c] = true
end

-- GitHub's anchor for a heading: lower case, links reduced to their text, punctuation
-- dropped, spaces to hyphens.
local function slug (heading)
  local h = heading:gsub("%[(.-)%]%b()", "%1"):gsub("`", ""):lower()
  local out = {}
  for _, c in utf8.codes(h) do
    local ch = utf8.char(c)
    if c < 128 then
      if ch:match("[%w_%-]") then out[#out + 1] = ch
      elseif ch == " " then out[#out + 1] = "-" end
    elseif not DROP[ch] then
      out[#out + 1] = ch
    end
  end
  return table.concat(out)
end

local anchors_of = {}
local function anchors (path)
  if anchors_of[path] then return anchors_of[path] end
  local set, seen = {}, {}
  local text = read(path) or ""
  local fence = nil
  for line in (text .. "\n"):gmatch("(.-)\n") do
    local f = line:match("^%s*(```+)")
    if fence then
      if f then fence = nil end
    elseif f then
      fence = f
    else
      local h = line:match("^#+%s+(.-)%s*#*%s*$")
      if h then
        local s = slug(h)
        if seen[s] then
          seen[s] = seen[s] + 1
          s = s .. "-" .. seen[s]
        else
          seen[s] = 0
        end
        set[s] = true
      end
    end
  end
  anchors_of[path] = set
  return set
end

local function links (text)
  local out = {}
  for target in (split(text)):gmatch("%]%(([^)%s]+)[^)]*%)") do
    out[#out + 1] = target
  end
  return out
end

describe("the documentation", function ()
  it("has relative links that resolve to files and headings of the repository", function ()
    local bad = {}
    for _, page in ipairs(PAGES) do
      local text = assert(read(page), page)
      for _, target in ipairs(links(text)) do
        if not target:match("^%a[%w+.-]*:") then          -- not http:, https:, mailto:
          local file, anchor = target:match("^([^#]*)#?(.*)$")
          local path = file == "" and page or normalize(dirname(page) .. "/" .. file)
          if path == nil then
            bad[#bad + 1] = page .. ": " .. target .. " (outside the repository)"
          elseif not exists(path) then
            bad[#bad + 1] = page .. ": " .. target .. " (no such file)"
          elseif anchor ~= "" and path:match("%.md$") and not anchors(path)[anchor] then
            bad[#bad + 1] = page .. ": " .. target .. " (no such heading)"
          end
        end
      end
    end
    assert.same({}, bad)
  end)

  it("cites published works, not paths outside the repository", function ()
    local bad = {}
    for _, page in ipairs(PAGES) do
      local text = read(page)
      for _, pat in ipairs { "%.%./shared", "/work/", "CPFG%-NOTES", "seeds/",
                             "source document", "seed 00%d", "document 00%d" } do
        local ln = 0
        for line in (text .. "\n"):gmatch("(.-)\n") do
          ln = ln + 1
          if line:find(pat) then bad[#bad + 1] = ("%s:%d: %s"):format(page, ln, line) end
        end
      end
    end
    assert.same({}, bad)
  end)

  it("leaves no source file pointing at notes outside the repository", function ()
    local files = {}
    local p = io.popen("find lua csrc docs examples tests tools bench cmake -type f "
      .. "\\( -name '*.lua' -o -name '*.c' -o -name '*.h' -o -name '*.md' -o -name '*.sh' "
      .. "-o -name '*.cmake' \\) -not -path '*/node_modules/*' -not -path 'tests/fuzz/corpus_*'")
    for f in p:lines() do files[#files + 1] = f end
    p:close()
    for _, f in ipairs { "README.md", "CONTRIBUTING.md", "CMakeLists.txt", "setup.sh", "test.sh",
                         ".luacheckrc", ".busted" } do
      files[#files + 1] = f
    end
    assert.is_true(#files > 100)
    local bad = {}
    for _, f in ipairs(files) do
      if f ~= "tests/docs_spec.lua" then
        local ln = 0
        for line in ((read(f) or "") .. "\n"):gmatch("(.-)\n") do
          ln = ln + 1
          for _, pat in ipairs { "%.%./shared", "[%s\"'`(]/work/", "CPFG%-NOTES", "DESIGN%.md",
                                 "STYLE%.md", "seeds/" } do
            if line:find(pat) then bad[#bad + 1] = ("%s:%d: %s"):format(f, ln, line) end
          end
        end
      end
    end
    assert.same({}, bad)
  end)

  it("shows only commands that the lsys program has", function ()
    local commands = require("lsys.cli").help
    assert.is_string(commands.derive)
    local bad = {}
    for _, page in ipairs(PAGES) do
      for _, c in ipairs(select(2, split(read(page)))) do
        -- a command line: `lsys CMD ...`, `build/bin/lsys CMD`, `$ lsys CMD`, `X=1 lsys CMD`
        local line = c:gsub("^%s*%$%s+", ""):gsub("^%s+", "")
        repeat local n; line, n = line:gsub("^[%u_][%u%d_]*=%S*%s+", "") until n == 0
        local prefix, cmd, rest = line:match("^([%w._/-]*)lsys (%l[%l_-]*)(.*)$")
        if cmd and (prefix == "" or prefix:sub(-1) == "/") and not rest:match("^[%w./:]") then
          if commands[cmd] == nil then
            bad[#bad + 1] = page .. ": lsys " .. cmd
          elseif cmd == "components" and not rest:match("^%s+graph%f[%W]") then
            bad[#bad + 1] = page .. ": lsys components" .. rest
          end
        end
      end
    end
    assert.same({}, bad)
  end)

  it("has JSON examples that read as JSON, and sketches that make a plant", function ()
    local cjson = require "cjson"
    local sketch = require "lsys.sketch"
    local blocks, sketches = 0, 0
    for _, page in ipairs(PAGES) do
      local text = read(page)
      for code in text:gmatch("\n```json\n(.-)```") do
        blocks = blocks + 1
        local ok, t = pcall(cjson.decode, code)
        assert(ok, page .. ": a JSON example does not read: " .. tostring(t))
        if type(t) == "table" and t.strokes ~= nil then   -- a sketch file (docs/sketch.md)
          sketches = sketches + 1
          local dir = H.tmpdir()
          H.write(dir .. "/plant.json", code)
          local made, m = pcall(function ()
            return sketch.load(dir .. "/plant.json"):model()
          end)
          H.rmdir(dir)
          assert(made, page .. ": its sketch example: " .. tostring(m))
          local scene = m:interpret()
          assert.is_true(scene.ntriangles > 0, page)
        end
      end
    end
    assert.is_true(blocks >= 3)
    assert.equal(1, sketches)
  end)

  it("lists in the README every package setup.sh installs, and no other", function ()
    local installs = output_lines("./setup.sh --packages")
    assert.is_true(#installs > 10)
    local listed = read("README.md"):match("installs the missing ones of these packages.-:%s*`"
      .. "([^`]+)`")
    assert.is_string(listed, "the README's list of packages")
    local readme = {}
    for p in listed:gmatch("%S+") do readme[#readme + 1] = p end
    table.sort(installs)
    table.sort(readme)
    assert.same(installs, readme)
  end)

  it("indexes every folder and file of examples/ in examples/README.md", function ()
    local index = read("examples/README.md")
    local missing = {}
    for _, name in ipairs(output_lines("ls examples")) do
      if name ~= "README.md" and not index:find(name, 1, true) then
        missing[#missing + 1] = name
      end
    end
    assert.same({}, missing)
  end)

  it("names every example folder in the README", function ()
    local readme = read("README.md")
    local missing = {}
    for _, dir in ipairs(output_lines("ls -d examples/*/")) do
      local name = dir:match("examples/([^/]+)/")
      if name ~= "gallery" and not readme:find("examples/" .. name, 1, true) then
        missing[#missing + 1] = name
      end
    end
    assert.same({}, missing)
  end)
end)
