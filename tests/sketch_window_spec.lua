-- The sketch window: the state machine of lsys.sketch.window fed events as the
-- window sends them (strokes drawn, moved, deleted, undone; the wheel's pressure; keys;
-- the toolbar; saving), the session's handling of a sketch that makes no plant yet, and
-- (#gl) the real window under a private Xvfb, drawn with xdotool, saved and read back.
-- ctest: slow (drives the window under Xvfb with waits)
local H = require "tests.helper"
local core = require "lsys.core"
local W = require "lsys.sketch.window"
local read = require "lsys.sketch.read"
local D = require "tests.display"
local SLOW = tonumber(os.getenv("LSYS_TEST_SLOW")) or 1   -- under valgrind: longer waits

local tmpdir = H.tmpdir

-- Drags from (x0, y0) to (x1, y1) in n straight steps of the pointer.
local function drag (st, x0, y0, x1, y1, n, button)
  button = button or "left"
  st:pointer("down", x0, y0, button)
  for i = 1, n do
    st:pointer("move", x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n, button)
  end
  st:pointer("up", x1, y1, button)
end

-- A sketch a plant can be made of: stem, boundaries and three inclination lines.
local function plant_sketch (st)
  st:key("1") drag(st, 300, 550, 300, 50, 10)
  st:key("2") drag(st, 200, 550, 200, 50, 10)
  st:key("3") drag(st, 400, 550, 400, 50, 10)
  st:key("4")
  for _, y in ipairs { 450, 300, 150 } do drag(st, 150, y, 450, y, 6) end
end

describe("the sketch window's state machine", function()
  it("draws a stroke of the current role from pointer events, in sketch pixels", function()
    local st = W.new { width = 400, height = 300, file = "a.json" }
    assert.equal("stem", st.role)
    drag(st, 100, 250, 100, 50, 4)
    local sk = st:sketch()
    assert.equal("a.json", sk.file)                -- the pipeline's messages name it
    assert.equal(400, sk.width)
    assert.equal(300, sk.height)
    assert.equal(1, #sk.strokes)
    assert.equal("stem", sk.strokes[1].role)
    -- the press and the four moves; the release at the last point adds none
    assert.same({ {100, 250, 0.5}, {100, 200, 0.5}, {100, 150, 0.5}, {100, 100, 0.5},
                  {100, 50, 0.5} }, sk.strokes[1].points)
    assert.equal(1, st.selected)
  end)

  it("shows the stroke being drawn in the sketch once it has two points", function()
    local st = W.new {}
    st:pointer("down", 10, 10, "left")
    assert.equal(0, #st:sketch().strokes)
    st:pointer("move", 10.5, 10.5, "left")      -- under a pixel away: no new point
    assert.equal(0, #st:sketch().strokes)
    assert.is_true(st:pointer("move", 10, 20, "left"))
    assert.same({ {10, 10, 0.5}, {10, 20, 0.5} }, st:sketch().strokes[1].points)
    assert.equal(0, #st.strokes)                  -- not kept before the release
  end)

  it("picks roles with 1-4 and the toolbar; a new stem or boundary replaces the old", function()
    local st = W.new {}
    drag(st, 10, 100, 10, 0, 2)
    st:pointer("down", 20, 100, "left")
    st:pointer("move", 20, 50, "left")            -- while drawn, it stands for the old one
    local sk = st:sketch()
    assert.equal(1, #sk.strokes)
    assert.same({ {20, 100, 0.5}, {20, 50, 0.5} }, sk.strokes[1].points)
    st:pointer("move", 20, 0, "left")
    st:pointer("up", 20, 0, "left")               -- a second stem replaces the first
    assert.equal(1, #st.strokes)
    assert.equal(20, st.strokes[1].points[1][1])
    st:key("2") drag(st, 0, 100, 0, 0, 2)
    st:key("4") drag(st, 0, 50, 30, 50, 2)
    drag(st, 0, 60, 30, 60, 2)                    -- inclination lines add up
    assert.equal("inclination", st.role)
    local roles = {}
    for i, s in ipairs(st.strokes) do roles[i] = s.role end
    assert.same({ "stem", "boundary_left", "inclination", "inclination" }, roles)
    assert.is_true(st:toolbar(3 * W.BUTTON_W + 5))   -- the fourth button... is inclination
    assert.is_true(st:toolbar(2 * W.BUTTON_W + 5))
    assert.equal("boundary_right", st.role)
    assert.equal(1, W.toolbar_hit(0))
    assert.equal("nodes-", W.toolbar_hit(4 * W.BUTTON_W + 10))
    assert.equal("nodes+", W.toolbar_hit(4 * W.BUTTON_W + 60))
    assert.equal("phyllotaxis", W.toolbar_hit(4 * W.BUTTON_W + 200))
  end)

  it("sets the pressure of the points drawn next with the wheel and [ ]", function()
    local st = W.new {}
    st:pointer("down", 0, 0, "left")
    st:pointer("move", 0, 10, "left")
    assert.equal(0.6, st:scroll(2))               -- two notches up: 0.5 + 2 * 0.05, nearer
    st:pointer("move", 0, 20, "left")
    st:scroll(-5)                                 -- 0.35: farther than the drawing plane
    st:pointer("move", 0, 30, "left")
    st:pointer("up", 0, 30, "left")
    local p = {}
    for i, q in ipairs(st.strokes[1].points) do p[i] = q[3] end
    assert.same({ 0.5, 0.5, 0.6, 0.35 }, p)
    st:key("]")
    assert.equal(0.45, st.pressure)
    for _ = 1, 20 do st:key("[") end
    assert.equal(0, st.pressure)                  -- clamped to [0, 1]
    assert.truthy(st.status:find("farther", 1, true))
  end)

  it("colours the stem by pressure: nearer darker, farther lighter (§7.3)", function()
    assert.same({ 0.75, 0.9, 0.75 }, W.stem_rgb(0))
    assert.near({ 0.05, 0.25, 0.05 }, W.stem_rgb(1), 1e-12)
    assert.near({ 0.4, 0.575, 0.4 }, W.stem_rgb(0.5), 1e-12)
  end)

  it("takes a tablet pen's pressure for the point and the points after it", function()
    local st = W.new {}
    st:pointer("down", 10, 100, "left", false, 0.8)
    st:pointer("move", 10, 80, "left", false, 0.9)
    st:pointer("move", 10, 60, "left", false, nil)         -- no reading: the last one
    st:pointer("move", 10, 40, "left", false, 1.7)         -- clamped
    st:pointer("up", 10, 40, "left")
    local pts = st.strokes[1].points
    assert.same({ 0.8, 0.9, 0.9, 1 }, { pts[1][3], pts[2][3], pts[3][3], pts[4][3] })
    assert.equal(1, st.pressure)                           -- shown on the toolbar
    st:scroll(-4)                                          -- the wheel still works
    assert.equal(0.8, st.pressure)
    st:pointer("move", 50, 50, "left", false, 0.1)         -- not drawing: ignored
    assert.equal(0.8, st.pressure)
  end)

  it("redraws a stroke in place with Ctrl + drag: the selected one, else the nearest", function()
    local st = W.new {}
    plant_sketch(st)
    assert.equal(6, #st.strokes)
    assert.equal(6, st.selected)                           -- the last inclination line
    st:pointer("down", 150, 200, "left", false, nil, true)
    st:pointer("move", 300, 210, "left")
    -- while drawn, it stands in the old one's place
    local sk = st:sketch()
    assert.equal(6, #sk.strokes)
    assert.same({ 150, 200, 0.5 }, sk.strokes[6].points[1])
    st:pointer("up", 450, 200, "left")
    assert.equal(6, #st.strokes)
    assert.equal("inclination", st.strokes[6].role)
    assert.same({ {150, 200, 0.5}, {300, 210, 0.5}, {450, 200, 0.5} }, st.strokes[6].points)
    assert.equal("redrew stroke 6 (inclination, 3 points)", st.status)
    -- nothing selected: the nearest stroke, whatever the current role (here the stem)
    st.selected = nil
    st:key("4")
    drag(st, 0, 0, 0, 0, 0)                                -- a click: no stroke, no change
    st:pointer("down", 305, 400, "left", false, nil, true)
    st:pointer("move", 310, 300, "left")
    st:pointer("up", 310, 100, "left")
    assert.equal(6, #st.strokes)
    assert.equal("stem", st.strokes[1].role)
    assert.same({ 305, 400, 0.5 }, st.strokes[1].points[1])
    assert.equal(1, st.selected)
    assert.is_true(st:undo_last())                         -- undone like any change
    assert.same({ 300, 550, 0.5 }, st.strokes[1].points[1])
    -- nothing near and nothing selected
    local e = W.new {}
    e:pointer("down", 5, 5, "left", false, nil, true)
    assert.is_nil(e.drawing)
    assert.equal("no stroke to redraw: select one (right click) first", e.status)
  end)

  it("draws the analysis' nodes and rays over the sketch, A hides them", function()
    local st = W.new {}
    plant_sketch(st)
    local r = W.pipeline(st:sketch())
    local an = r.sketch:analysis()
    local c = core.canvas(st.width, st.height)
    local function reds ()
      local px, n = c:pixels(), 0
      for i = 0, #px - 4, 4 do
        local rr, g, b = px:byte(i + 1, i + 3)
        if rr > 150 and g < 80 and b < 100 then n = n + 1 end
      end
      return n
    end
    W.draw_sketch(st, c)
    assert.equal(0, reds())                                -- no analysis given
    W.draw_sketch(st, c, an)
    local n = #an.nodes
    assert.is_true(n >= 9)
    -- each node a dot of radius 2.5: about 20 pixels of the node colour each
    assert.is_true(reds() >= 10 * n, reds() .. " red pixels for " .. n .. " nodes")
    -- the first node's dot is where the analysis puts it
    local px = c:pixels()
    local x, y = math.floor(an.nodes[1].px[1] + 0.5), math.floor(an.nodes[1].px[2] + 0.5)
    local i = 4 * (y * st.width + x)
    assert.same({ 0xc0, 0x20, 0x3a }, { px:byte(i + 1, i + 3) })
    st:key("a")
    assert.is_false(st.overlay)
    W.draw_sketch(st, c, an)
    assert.equal(0, reds())
  end)

  it("hides the old stem while a new one is drawn, as the plant does", function()
    local st = W.new {}
    plant_sketch(st)
    local c = core.canvas(st.width, st.height)
    local function white (x, y)
      local px = c:pixels()
      local i = 4 * (y * st.width + x)
      return px:byte(i + 1) == 255 and px:byte(i + 2) == 255 and px:byte(i + 3) == 255
    end
    W.draw_sketch(st, c)
    assert.is_false(white(300, 500))                -- the stem at x = 300
    st:key("1")
    st:pointer("down", 100, 550, "left")
    st:pointer("move", 100, 380, "left")
    W.draw_sketch(st, c)
    assert.is_true(white(300, 500))                 -- the old stem is gone from the pane
    assert.is_false(white(100, 450))                -- the new one is there
    local stems = 0
    for _, t in ipairs(st:sketch().strokes) do
      if t.role == "stem" then stems = stems + 1 assert.equal(100, t.points[1][1]) end
    end
    assert.equal(1, stems)                          -- as the plant sees it
    st:pointer("up", 100, 380, "left")
    W.draw_sketch(st, c)
    assert.is_true(white(300, 500))
    -- a redrawn boundary hides the old one too; an inclination line adds to the others
    st:key("2")
    st:pointer("down", 150, 550, "left")
    st:pointer("move", 150, 380, "left")
    W.draw_sketch(st, c)
    assert.is_true(white(200, 500))
    st:pointer("up", 150, 380, "left")
    st:key("4")
    st:pointer("down", 150, 520, "left")
    st:pointer("move", 450, 520, "left")
    W.draw_sketch(st, c)
    assert.is_false(white(250, 450))               -- the line at y = 450 stays
  end)

  it("moves the nearest stroke with a right drag, and undoes it", function()
    local st = W.new {}
    plant_sketch(st)
    local before = st.strokes[2].points[1][1]
    -- press 5 pixels right of the left boundary (x = 200), drag by (+10, -5)
    drag(st, 205, 380, 215, 375, 2, "right")
    assert.equal(2, st.selected)
    assert.same({ before + 10, 545, 0.5 }, st.strokes[2].points[1])
    assert.equal(300, st.strokes[1].points[1][1])   -- the stem did not move
    assert.is_true(st:key("z", true) == nil)
    assert.same({ before, 550, 0.5 }, st.strokes[2].points[1])
    -- nothing within reach: no move
    st:pointer("down", 590, 590, "right")
    assert.is_nil(st.moving)
    assert.truthy(st.status:find("no stroke near", 1, true))
  end)

  it("deletes the selected stroke, else the last, and undoes strokes and settings", function()
    local st = W.new {}
    plant_sketch(st)
    assert.equal(6, #st.strokes)
    st.selected = 2
    st:key("delete")
    assert.equal(5, #st.strokes)
    assert.equal("boundary_right", st.strokes[2].role)
    st:key("backspace")                           -- nothing selected now: the last
    assert.equal(4, #st.strokes)
    st:key("=") st:key("=") st:key("-")
    assert.equal(6, st.nodes)
    st:key("p")
    assert.equal("decussate", st.phyllotaxis)
    st:key("z", true)
    assert.equal("distichous", st.phyllotaxis)
    st:key("z", true) st:key("z", true) st:key("z", true)
    assert.equal(5, st.nodes)
    st:key("z", true) st:key("z", true)
    assert.equal(6, #st.strokes)
    assert.equal("boundary_left", st.strokes[2].role)
  end)

  it("keeps the nodes per layer at 1 or more", function()
    local st = W.new { nodes = 1 }
    st:key("-")
    assert.equal(1, st.nodes)
  end)

  it("saves the sketch and reads it back equal", function()
    local dir = tmpdir()
    local st = W.new { file = dir .. "/x.json", nodes = 4, phyllotaxis = "fibonacci" }
    plant_sketch(st)
    st:scroll(3)
    drag(st, 160, 100, 440, 100, 3)
    assert.equal("save", st:key("s", true))
    assert.equal(dir .. "/x.json", st:save())
    local back = read.file(dir .. "/x.json")
    assert.equal(600, back.width)
    assert.equal(4, back.nodes_per_layer)
    assert.equal("fibonacci", back.phyllotaxis)
    assert.equal(#st.strokes, #back.strokes)
    for i, s in ipairs(st.strokes) do
      assert.equal(s.role, back.strokes[i].role)
      assert.same(s.points, back.strokes[i].points)
    end
    assert.same({ 160, 100, 0.65 }, back.strokes[7].points[1])
    -- a new session on the file has the same sketch
    local st2 = W.new { sketch = back, file = dir .. "/x.json" }
    assert.same(st:sketch().strokes, st2:sketch().strokes)
    os.execute("rm -rf " .. dir)
  end)

  it("saves a sketch without a stem yet as it is, and a .svg file's as .json", function()
    local dir = tmpdir()
    local st = W.new { file = dir .. "/y.svg" }
    st:key("2") drag(st, 0, 100, 0, 0, 2)
    assert.equal(dir .. "/y.json", st:save())
    local t = require("cjson").decode((assert(core.read_file(dir .. "/y.json", 1e6))))
    assert.equal("boundary_left", t.strokes[1].role)
    assert.same({ 0, 50, 0.5 }, t.strokes[1].points[2])
    os.execute("rm -rf " .. dir)
  end)

  it("maps sketch pixels to the window as the panes place the sketch", function()
    local st = W.new { width = 600, height = 600 }
    -- 1200 x 800: the sketch pane is x 0..600, y 40..800 (600 x 760); scale 1, centred
    local x, y = W.to_window(st, 1200, 800, 300, 300)
    assert.equal(300, x)
    assert.equal(420, y)
    -- 800 x 600: the pane is 400 x 570 from y 30: scale 2/3, the image 400 x 400 from y 115
    x, y = W.to_window(st, 800, 600, 600, 0)
    assert.near(400, x, 1e-9)
    assert.near(115, y, 1e-9)
  end)
end)

-- A stand-in for the core Viewer: records what the session sends.
local function fake_viewer ()
  local v = { posts = {}, images = {}, texts = {} }
  function v:layout (lay) self.lay = lay end
  function v:post (frames, opts) self.posts[#self.posts + 1] = { frames = frames, opts = opts } end
  v.pixels, v.nimages = {}, {}
  function v:image (k, px, w, h)
    self.images[k] = { w = w, h = h, n = #px }
    self.pixels[k], self.nimages[k] = px, (self.nimages[k] or 0) + 1
  end
  function v:text (s) self.texts[#self.texts + 1] = s end
  return v
end

describe("the sketch window's session", function()
  it("shows the pipeline's error on the status line instead of the plant", function()
    local v = fake_viewer()
    local st = W.new {}
    local s = W.session(v, st, {})
    assert.equal(1, #v.posts)
    assert.equal(0, v.posts[1].frames[1].scene.ntriangles)       -- an empty scene
    assert.truthy(v.texts[#v.texts]:find("no stem stroke", 1, true), v.texts[#v.texts])
    assert.same({ w = 600, h = 600, n = 600 * 600 * 4 }, v.images[2])
    assert.same({ w = W.TOOLBAR_W, h = W.TOOLBAR_H, n = W.TOOLBAR_W * W.TOOLBAR_H * 4 },
                v.images[1])
    assert.equal(3, #v.lay.panes)
    -- Tab hides the plots: the scene takes the right half
    s:event { type = "key", key = "tab" }
    assert.equal(2, #v.lay.panes)
    assert.same({ 0.5, 0, 1, 1 }, v.lay.scene)
  end)

  it("posts the plant of the pipeline, keeping the camera after the first", function()
    local v = fake_viewer()
    local lsys = require "lsys"
    local m = lsys.lsystem { axiom = "F", view = { line_style = "cylinder", line_width = 0.1 } }
    local calls = {}
    local function pipeline (t)
      calls[#calls + 1] = #t.strokes
      if #t.strokes < 1 then error("x.json: no stem stroke", 0) end
      local s = m:derive()
      return { lstring = s, scene = m:interpret(s), sketch = {} }
    end
    local st = W.new {}
    local s = W.session(v, st, { pipeline = pipeline })
    s:event { type = "pointer", pane = 2, phase = "down", x = 5, y = 90, button = "left" }
    s:event { type = "pointer", pane = 2, phase = "move", x = 5, y = 50, button = "left" }
    assert.is_true(st.changed)
    s:compute(false)                              -- while drawing: the stroke so far
    assert.same({ 0, 1 }, calls)
    assert.is_true(v.posts[2].frames[1].scene.ntriangles > 0)
    assert.is_nil(v.posts[2].opts.keep_camera)   -- the first plant is fitted
    s:event { type = "pointer", pane = 2, phase = "up", x = 5, y = 10, button = "left" }
    s:compute(true)
    assert.is_true(v.posts[3].opts.keep_camera)
    assert.truthy(s:status():find("1 modules", 1, true), s:status())
    -- the wheel over the sketch pane sets the pressure
    s:event { type = "scroll", pane = 2, dy = 1, x = 0, y = 0 }
    assert.equal(0.55, st.pressure)
    -- a click on the toolbar picks a role
    s:event { type = "pointer", pane = 1, phase = "down", x = W.BUTTON_W + 3, y = 5 }
    assert.equal("boundary_left", st.role)
  end)
end)

describe("the sketch window's plots", function()
  it("follow the plant: no stale message once the sketch makes one", function()
    local v = fake_viewer()
    local st = W.new {}
    st:key("1") drag(st, 300, 550, 300, 50, 10)
    st:key("2") drag(st, 200, 550, 200, 50, 10)
    st:key("3") drag(st, 400, 550, 400, 50, 10)
    st:key("4") drag(st, 150, 450, 450, 450, 6)
    local s = W.session(v, st, {})
    assert.truthy(s.error:find("at least two inclination lines", 1, true), s.error)
    local message = v.pixels[3]
    assert.equal(1, v.nimages[3])
    -- the second line, still being drawn: the plant is posted, and the plots with it
    st:pointer("down", 150, 300, "left")
    st:pointer("move", 300, 300, "left")
    st:pointer("move", 450, 300, "left")
    s:compute()
    assert.is_nil(s.error, s.error)
    assert.is_true(v.posts[#v.posts].frames[1].scene.ntriangles > 0)
    assert.equal(2, v.nimages[3])
    assert.are_not.equal(message, v.pixels[3])
    local live = v.pixels[3]
    st:pointer("up", 450, 300, "left")
    s:compute()
    assert.equal(live, v.pixels[3])
    -- and they go back to the message when the sketch makes no plant again
    st:delete()
    s:compute()
    assert.truthy(s.error:find("at least two inclination lines", 1, true), s.error)
    assert.equal(message, v.pixels[3])
  end)
end)

describe("the sketch window's organ (§6: four strokes in three views)", function()
  local organ = require "lsys.sketch.organ"
  local LEAF = "examples/sketch/organ_leaf.json"

  -- a stroke through the points pts, four pointer moves a segment
  local function path (st, pts)
    st:pointer("down", pts[1][1], pts[1][2], "left")
    for i = 2, #pts do
      for k = 1, 4 do
        st:pointer("move", pts[i - 1][1] + (pts[i][1] - pts[i - 1][1]) * k / 4,
                   pts[i - 1][2] + (pts[i][2] - pts[i - 1][2]) * k / 4, "left")
      end
    end
    st:pointer("up", pts[#pts][1], pts[#pts][2], "left")
  end

  -- a leaf drawn in the pane's three views: the top view is the left half, the side view
  -- the upper right quarter, the front view the lower right one (600 x 600)
  local function draw_leaf (st)
    st:key("1") path(st, { { 150, 500 }, { 100, 300 }, { 120, 200 }, { 150, 100 } })
    st:key("2") path(st, { { 150, 500 }, { 200, 300 }, { 180, 200 }, { 150, 100 } })
    st:key("3") path(st, { { 450, 280 }, { 470, 60 } })
    st:key("4") path(st, { { 350, 420 }, { 450, 450 } })
    path(st, { { 350, 420 }, { 450, 450 }, { 550, 420 } })
  end

  it("switches to the organ with O; its strokes are the organ's, not the plant's", function()
    local st = W.new {}
    plant_sketch(st)
    assert.equal("organ", st:toggle_organ())
    assert.is_nil(st:organ_table())
    draw_leaf(st)
    assert.equal(6, #st.strokes)                   -- the plant's are untouched
    local roles = {}
    for i, x in ipairs(st.organ_strokes) do roles[i] = x.role end
    assert.same({ "top_left", "top_right", "side", "front" }, roles)   -- one of each
    local t = st:organ_table().organ
    assert.same({ 150, 500 }, t.top.left[1])
    assert.same({ 150, 100 }, t.top.left[#t.top.left])
    assert.same({ 550, 420 }, t.front[#t.front])  -- the second front stroke replaced the first
    assert.equal(9, #t.front)
    local org = organ.load(st:organ_table())
    assert.truthy(tostring(org):find("^lsys%.Organ"))
    -- the toolbar's buttons pick the organ's roles now
    assert.is_true(st:toolbar(2 * W.BUTTON_W + 5))
    assert.equal("side", st.organ_role)
    assert.equal("inclination", st.role)          -- the plant's role stays
    -- the pane shows the views and the organ's strokes, not the plant's
    local c = core.canvas(st.width, st.height)
    W.draw_sketch(st, c)
    local px = c:pixels()
    local function rgb (x, y) local i = 4 * (y * st.width + x) return { px:byte(i + 1, i + 3) } end
    assert.same({ 255, 255, 255 }, rgb(300, 500))  -- the stem is not drawn
    assert.are_not.same({ 255, 255, 255 }, rgb(460, 170))   -- the midrib is
    -- back to the plant; undo takes back organ strokes as any other
    st:key("o")
    assert.equal("plant", st.mode)
    assert.is_true(st:undo_last())
    assert.equal(5, #st.organ_strokes[4].points)   -- the first front stroke again
    assert.equal(6, #st.strokes)
  end)

  it("shows an organ file's strokes in their views and keeps their own pixels", function()
    local org = organ.load(LEAF)
    local st = W.new { organ = org }
    -- unchanged, the strokes make the same organ
    assert.equal(org:text(), organ.load(st:organ_table()):text())
    -- shown inside their regions: the top view in the left half, the side view top right
    local regions = require("lsys.ui.sketch_organ").regions(st.width, st.height)
    for _, s in ipairs(st.organ_strokes) do
      local r = regions[require("lsys.ui.sketch_organ").VIEW[s.role]]
      for _, p in ipairs(st:pane_points(s)) do
        assert.is_true(p[1] >= r[1] and p[1] <= r[1] + r[3] and p[2] >= r[2] and
                       p[2] <= r[2] + r[4], s.role)
      end
    end
    -- a move in the pane moves the stroke in its own pixels, by the pane's scale
    st:key("o")
    local side = st.organ_strokes[3]
    assert.equal("side", side.role)
    local x0 = side.points[1][1]
    local q = st:pane_points(side)[20]
    st:pointer("down", q[1], q[2], "right")
    st:pointer("move", q[1] + 10, q[2], "right")
    st:pointer("up", q[1] + 10, q[2], "right")
    local sc = st.views.side.s
    assert.near(x0 + 10 / sc, side.points[1][1], 1e-9)
  end)

  it("draws the plant with the organ, and says why a half-drawn organ makes none", function()
    local v = fake_viewer()
    local st = W.new { organ = organ.load(LEAF) }
    plant_sketch(st)
    local s = W.session(v, st, {})
    assert.is_nil(s.error, s.error)
    local with = s.result.scene.ntriangles
    local plain = W.pipeline(st:sketch()).scene.ntriangles      -- the default leaf
    assert.equal(W.pipeline(st:sketch(), organ.load(LEAF)).scene.ntriangles, with)
    assert.is_true(with > plain + 1000, with .. " against " .. plain)
    -- an organ of a front stroke alone: no top view, so the default leaf, and the reason
    local st2 = W.new {}
    plant_sketch(st2)
    st2:key("o")
    st2:key("4") drag(st2, 350, 420, 550, 420, 4)
    local s2 = W.session(fake_viewer(), st2, {})
    assert.equal(plain, s2.result.scene.ntriangles)
    assert.truthy(s2:status():find("organ: ", 1, true), s2:status())
    assert.truthy(s2:status():find("(the plant shows the default leaf)", 1, true), s2:status())
  end)

  it("saves the organ beside the sketch when it changed, as organ.load reads it", function()
    local dir = tmpdir()
    local st = W.new { file = dir .. "/herb.json" }
    plant_sketch(st)
    assert.equal(dir .. "/herb.json", st:save())   -- no organ yet: the sketch alone
    assert.is_nil(io.open(dir .. "/herb.organ.json"))
    st:key("o")
    draw_leaf(st)
    local spath, opath = st:save()
    assert.equal(dir .. "/herb.json", spath)
    assert.equal(dir .. "/herb.organ.json", opath)
    local back = organ.load(opath)
    assert.equal(organ.load(st:organ_table()):text(), back:text())
    assert.equal(1, select("#", st:save()))        -- unchanged since: not written again
    -- an organ file given is where it goes
    local st2 = W.new { organ = back, organ_file = dir .. "/leaf.json" }
    st2:key("o")
    st2:key("3") drag(st2, 450, 280, 480, 60, 4)
    assert.equal(dir .. "/leaf.json", select(2, st2:save(dir .. "/x.json")))
    os.execute("rm -rf " .. dir)
  end)
end)

describe("the sketch window's export", function()
  it("writes the plant as .glb, .obj and .png and the model as .lua beside the sketch", function()
    local dir = tmpdir()
    local v = fake_viewer()
    local st = W.new { file = dir .. "/herb.json" }
    plant_sketch(st)
    local s = W.session(v, st, {})
    s:compute(true)
    assert.is_nil(s.error, s.error)
    s:export()
    for _, ext in ipairs { ".glb", ".obj", ".mtl", ".png", ".lua", ".l", ".v", ".map",
                           ".internode.func" } do
      assert.truthy(io.open(dir .. "/herb" .. ext), ext)
    end
    local back = require("lsys").cpfg.load(dir .. "/herb.l", dir .. "/herb.v")
    assert.equal(#s.result.lstring, #back:derive())
    assert.truthy(st.status:find("herb.obj", 1, true), st.status)
    local m = dofile(dir .. "/herb.lua")                -- the model file is a model
    assert.equal(tostring(s.result.lstring), tostring(m:derive()))
  end)
end)

describe("#gl the sketch window under Xvfb", function()
  teardown(function() D.stop() end)

  it("draws a sketch with the mouse, shows the plant, saves it and reads it back", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not D.have("xdotool") then pending("xdotool is not installed (./setup.sh does)") return end
    local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
    if BIN:sub(1, 1) ~= "/" then BIN = io.popen("pwd"):read("l") .. "/" .. BIN end
    local dir = tmpdir()
    local outf = dir .. "/out.txt"
    os.execute(("cd %s && %s%s sketch %s/x.json --size 1200x800 --nodes 3 >%s 2>&1 &"):format(
      dir, D.env, BIN, dir, outf))
    local xd = D.env .. "xdotool "
    local p = io.popen(D.env .. "timeout " .. 20 * SLOW ..
                       " xdotool search --sync --name 'lsys sketch' 2>/dev/null")
    local wid = p:read("l")
    p:close()
    assert.truthy(wid, "the window did not open: " .. tostring(io.open(outf):read("a")))
    D.sleep(1 * SLOW)          -- its panes laid out before the first stroke
    local st = W.new { width = 600, height = 600 }
    local function at (x, y)
      local wx, wy = W.to_window(st, 1200, 800, x, y)
      return ("mousemove --window %s %d %d"):format(wid, math.floor(wx + 0.5), math.floor(wy + 0.5))
    end
    local function stroke (key, pts)
      local cmd = { "key --window " .. wid .. " " .. key, at(pts[1][1], pts[1][2]), "mousedown 1" }
      for i = 2, #pts do
        local a, b = pts[i - 1], pts[i]
        for k = 1, 4 do
          cmd[#cmd + 1] = at(a[1] + (b[1] - a[1]) * k / 4, a[2] + (b[2] - a[2]) * k / 4)
        end
      end
      cmd[#cmd + 1] = "mouseup 1"
      assert(os.execute(xd .. table.concat(cmd, " ") .. " >/dev/null 2>&1"))
      D.sleep(0.3 * SLOW)
    end
    stroke("1", { {300, 560}, {300, 300}, {310, 60} })
    stroke("2", { {250, 560}, {150, 300}, {260, 60} })
    stroke("3", { {350, 560}, {450, 300}, {360, 60} })
    stroke("4", { {100, 480}, {300, 440}, {500, 480} })
    stroke("4", { {100, 320}, {300, 280}, {500, 320} })
    stroke("4", { {100, 160}, {300, 120}, {500, 160} })
    -- Ctrl + drag redraws the selected stroke (the last inclination) in place
    stroke("ctrl+a ctrl+a keydown ctrl", { {100, 200}, {300, 200}, {500, 200} })
    os.execute(xd .. "keyup ctrl >/dev/null 2>&1")
    D.sleep(2 * SLOW)
    os.execute(xd .. "key --window " .. wid .. " s >/dev/null 2>&1")     -- a screenshot
    os.execute(xd .. "key --window " .. wid .. " ctrl+s >/dev/null 2>&1")
    D.sleep(2 * SLOW)
    os.execute(xd .. "key --window " .. wid .. " Escape >/dev/null 2>&1")
    D.sleep(1 * SLOW)
    local out = io.open(outf):read("a")
    assert.truthy(out:find("saved " .. dir .. "/x.json", 1, true), out)
    local back = read.file(dir .. "/x.json")
    local roles = {}
    for i, s in ipairs(back.strokes) do roles[i] = s.role end
    assert.same({ "stem", "boundary_left", "boundary_right", "inclination", "inclination",
                  "inclination" }, roles)
    assert.equal(3, back.nodes_per_layer)
    local last = back.strokes[6].points                    -- redrawn in place
    assert.near(200, last[1][2], 1.01)
    assert.near(200, last[#last][2], 1.01)
    -- Xvfb's pointers report no pressure: the window says so and the wheel stays in charge
    assert.truthy(out:find("no tablet pressure (none of the", 1, true), out)
    assert.equal(0.5, back.strokes[1].points[1][3])
    -- the points are where the mouse went, within a pixel of the window's rounding
    local stem = back.strokes[1].points
    assert.near({ 300, 560 }, { stem[1][1], stem[1][2] }, 1.01)
    assert.near({ 310, 60 }, { stem[#stem][1], stem[#stem][2] }, 1.01)
    assert.is_true(#stem >= 8, "stem points: " .. #stem)
    -- the screenshot: the sketch drawn on the left; the plant on the right, when the
    -- pipeline's curves are built (lsys.core's stroke_curve)
    assert.truthy(out:find("wrote lsys%-001%.png"), out)
    local px, w, h = core.png_read(dir .. "/lsys-001.png")
    assert.equal(1200, w)
    assert.equal(800, h)
    local function count (x0, y0, x1, y1)
      local br, bg, bb = px:byte(4 * (y0 * w + x0) + 1, 4 * (y0 * w + x0) + 3)
      local n = 0
      for y = y0, y1 - 1 do
        for x = x0, x1 - 1 do
          local i = 4 * (y * w + x)
          local r, g, b = px:byte(i + 1, i + 3)
          if math.abs(r - br) + math.abs(g - bg) + math.abs(b - bb) > 60 then n = n + 1 end
        end
      end
      return n
    end
    assert.is_true(count(10, 130, 590, 700) > 2000, "the sketch pane is empty")
    local red = 0                          -- the nodes of the analysis (plot's node colour)
    for y = 60, 790 do
      for x = 0, 599 do
        local i = 4 * (y * w + x)
        local r, g, b = px:byte(i + 1, i + 3)
        if r > 150 and g < 80 and b < 100 then red = red + 1 end
      end
    end
    if core.stroke_curve then assert.is_true(red > 20, "no nodes drawn: " .. red) end
    if core.stroke_curve then
      assert.is_true(count(610, 10, 1190, 530) > 500, "the plant pane is empty: " .. out)
    end
    os.execute("rm -rf " .. dir)
  end)

  it("lists the X input devices and which report pressure (core.pen_devices)", function()
    local ok, why = D.start()
    if not ok then pending(why) return end
    if not core.pen_devices then pending("built without the viewer") return end
    local BIN = os.getenv("LSYS_BIN") or "build/bin/lsys"
    local f = os.tmpname()
    local h = io.open(f, "w")
    h:write([[
      local d, why = require("lsys.core").pen_devices()
      if not d then print("ERR " .. why) return end
      for _, x in ipairs(d) do print(x.id, x.name, x.pressure and "pressure" or "none") end]])
    h:close()
    local p = io.popen(D.env .. BIN .. " " .. f .. " 2>&1")
    local out = p:read("a")
    p:close()
    os.remove(f)
    -- Xvfb has its mouse and XTEST's pointer, neither with a pressure valuator
    assert.truthy(out:find("Xvfb mouse\tnone", 1, true), out)
    assert.truthy(out:find("XTEST pointer\tnone", 1, true), out)
    assert.falsy(out:find("\tpressure", 1, true), out)
    -- without a display: nil and why
    p = io.popen("echo 'print(require(\"lsys.core\").pen_devices())' | DISPLAY= " .. BIN ..
                 " - 2>&1")
    out = p:read("a")
    p:close()
    assert.truthy(out:find("nil\tcannot open the X display (DISPLAY is not set)", 1, true), out)
  end)
end)
