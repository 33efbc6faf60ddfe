--- `lsys view`: the viewer window on a model, loaded again when one of its files changes.
-- @module lsys.cli.commands.view
local core = require "lsys.core"
local A = require "lsys.cli.args"
local S = require "lsys.cli.source"
local HELP = require("lsys.cli.help").help
local host = require("lsys.program").host
local parse_size = require("lsys.model").parse_size

local ipairs, pairs, tostring, tonumber, error, pcall, require, getmetatable, next =
      ipairs, pairs, tostring, tonumber, error, pcall, require, getmetatable, next
local io, string, table, math = io, string, table, math
local format = string.format
local parse, out, usage, clock, isatty = A.parse, A.out, A.usage, A.clock, A.isatty
local model_opts, size_opt, renamed, USAGE_ERROR = A.model_opts, A.size_opt, A.renamed,
      A.USAGE_ERROR
local model_source, prepare, source_files = S.model_source, S.prepare, S.source_files
local _ENV = nil

-- --step K is the old spelling of --show K (the step shown first): --steps N is the number
-- of derivation steps, as for every command.
local VIEW_OPTS = model_opts {
  size = "value", show = "value", step = "value", rate = "value", screenshot = "value",
  ["no-status"] = "flag", last = "flag", history = "value", edit = "flag",
  ["no-edit"] = "flag", flat = "flag", shadows = "flag", ao = "flag",
}

-- --show, --rate, --screenshot and --history of `lsys view`; the messages about --show
-- name the spelling given (--step, the old one, warns). Returns also that spelling.
local function view_opts (opts, given)
  local step, rate
  local flag = renamed("view", opts, given, "step", "show", "K") or "--show"
  if opts.show ~= nil then
    step = math.tointeger(tonumber(opts.show))
    if step == nil or step < 0 then
      usage("view", "%s expects a step number (0 or more), got '%s'", flag, opts.show)
    end
  end
  if opts.rate ~= nil then
    rate = tonumber(opts.rate)
    if rate == nil or not (rate > 0 and rate <= 1000) then
      usage("view", "--rate expects steps per second in (0, 1000], got '%s'", opts.rate)
    end
  end
  local shot = opts.screenshot
  if shot ~= nil and not shot:lower():find("%.png$") then
    usage("view", "the screenshot must be a .png file, got '%s'", shot)
  end
  local history
  if opts.history ~= nil then
    if opts.last then usage("view", "--last and --history exclude each other") end
    local ok, r = pcall(parse_size, opts.history, "--history")
    if not ok then usage("view", "%s", (tostring(r):gsub("^[^\n]-:%d+: ", ""))) end
    history = r
  end
  if opts.last and opts.show ~= nil then
    usage("view", "--last and %s exclude each other", flag)
  end
  return step, rate, shot, history, flag
end

-- Handles the window's events until it is closed (or Ctrl-C); a change of one of the
-- files files() lists (its time or size, stable for 0.1 s) calls reload(), after which
-- the list is asked again. Closes the window.
local function watch (V, files, reload)
  local list = files()
  local function stamp ()     -- "missing" while the model file is (being rewritten)
    local t = {}
    for i, path in ipairs(list) do
      local tm, size = core.filestamp(path)
      if not tm and i == 1 then return "missing" end
      t[i] = tm and format("%.9f/%d", tm, size) or "-"
    end
    return table.concat(t, " ")
  end
  local last = stamp()
  local interrupt = host().interrupt or function () end
  local iok, ierr = pcall(function ()
    interrupt(true)
    while V.poll(0.2) do
      local now = stamp()
      if now ~= last and now ~= "missing" then
        V.poll(0.1)
        if stamp() == now then
          last = now
          reload()
          local new = files()      -- an #include added or removed
          if table.concat(new, "\n") ~= table.concat(list, "\n") then
            list = new
            last = stamp()
          end
        end
      end
    end
    interrupt(false)
  end)
  interrupt(false)
  V.close()
  if not iok and not tostring(ierr):find("interrupted!", 1, true) then error(ierr, 0) end
end

-- each plant the editing panes build again, on stderr (a terminal's line overwritten)
local function report (session, verbose)
  local st = session.stats
  if st == nil then return end
  local vals = session.form:status()
  io.stderr:write(format("%sbuilt %s%s%d triangles (%.0f ms)%s", verbose and "\r" or "",
    vals ~= "" and vals .. ": " or "", st.modules and format("%d modules, ", st.modules) or "",
    st.triangles, st.ms, verbose and "   " or "\n"))
end

-- the panes that edit a cpfg model: its vlab panels (unless --no-edit)
local function edit_subject (s, model, editing, title)
  if editing == false or s.kind == "lua" then return nil end
  local cpfg = require "lsys.cpfg"
  local panel = require "lsys.cpfg.panel"
  local l, v, pal = s.path, s.vfile, nil
  local dir = s.path
  if s.kind == "object" then l, v, pal = cpfg.object_files(s.path)
  else dir = s.path:match("^(.*)/[^/]*$") or "." end
  local found = panel.find(dir)
  if #found == 0 then return nil end
  local panels = {}             -- each with the file its messages edit (the .l file: awkped)
  for _, f in ipairs(found) do
    panels[#panels + 1] = { panel = panel.read(f.panel), target = f.target or l,
                            editor = f.editor }
  end
  local lo = {}
  for k, x in pairs(s.lopts or {}) do lo[k] = x end
  if pal and not lo.colormap and not lo.materials then     -- (relative to the .l file)
    if pal:match("%.mat$") then lo.materials = pal else lo.colormap = pal end
  end
  return require("lsys.ui.tune").panels({ l = l, v = v }, panels,
    { title = title, load = lo, model = model })
end

local function run (args)
  local opts, pos, given = parse("view", VIEW_OPTS, args, 2)
  if opts.help then out(HELP.view) return 0 end
  local w, h = size_opt("view", opts.size)
  local step, rate, shot, history, flag = view_opts(opts, given)
  local V = require "lsys.viewer"
  local print_pick = require("lsys.repl").print_pick
  local src = model_source("view", opts, pos)
  local path = src.path:gsub("/+$", "")
  local verbose = isatty(2)
  if opts.edit and opts["no-edit"] then usage("view", "--edit and --no-edit exclude each other") end
  local editing = opts.edit and true or opts["no-edit"] and false or nil
  if editing and opts.show ~= nil then
    usage("view", "--edit shows the last step: --show does not go with it")
  end

  -- Loads and shows the model; returns true, or false and the message.
  local shown = false
  local function show (keep)
    local ok, err = pcall(function ()
      local model, _, views = prepare("view", opts, pos)
      local t0 = clock()
      local st = shown and V.state()
      local first = step
      -- a reload keeps a step stepped back to; from the last step it goes to the new last
      if keep and st and st.step ~= nil and st.frame < st.nframes and
         st.step <= model.steps then
        first = st.step
      end
      if first ~= nil and first > model.steps then
        error(format("%s %d: the model has %d steps", flag, first, model.steps), 0)
      end
      local subject = edit_subject(src, model, editing, path:match("([^/]*)$"))
      if subject ~= nil then
        local session = V.edit(subject, {
          width = w, height = h, keep_camera = keep or nil, title = path:match("([^/]*)$"),
          status = not opts["no-status"],
          on_pick = V.on_pick == nil and print_pick or nil,
          on_build = function (se) report(se, verbose) end,
          out = function (msg) io.stderr:write("lsys: ", msg) end,
        })
        if session.error then error(session.error, 0) end
        io.stderr:write(format("%s %s: %d panel items (%.2f s)\n", keep and "reloaded" or
          "editing", path, #session.form.items, clock() - t0))
        return V.state()
      end
      V.show(model, {
        edit = editing, file = src.kind == "lua" and src.path or nil,
        on_build = function (se) report(se, verbose) end,
        out = function (msg) io.stderr:write("lsys: ", msg) end,
        width = w, height = h, step = first, rate = rate, keep_camera = keep or nil,
        steps = not opts.last, history = history, flat = opts.flat or nil,
        shadows = opts.shadows or nil, ao = opts.ao or nil,
        title = path:match("([^/]*)$"), status = not opts["no-status"],
        view = next(views) and views or nil,
        -- a click prints the module, unless lsys.viewer.on_pick (set by the model) takes it
        on_pick = V.on_pick == nil and print_pick or nil,
        progress = verbose and function (k, n)
          io.stderr:write(format("\rinterpreting step %d/%d", k, n))
          if k == n then io.stderr:write("\n") end
        end or nil,
      })
      local st2 = V.state()
      if verbose or keep then
        io.stderr:write(format("%s %s: %d steps (%.2f s)\n", keep and "reloaded" or "showing",
          path, model.steps, clock() - t0))
      end
      return st2
    end)
    if not ok and getmetatable(err) == USAGE_ERROR then error(err, 0) end
    if ok then shown = true end
    return ok, err
  end

  local ok, err = show(false)
  if shot ~= nil then
    if not ok then error(err, 0) end
    if not V.sync(30) then error("the window did not draw its first picture", 0) end
    local written = V.screenshot(shot, 30)
    local st = V.state()
    V.close()
    out(format("wrote %s (%dx%d)\n", written, st.fbwidth, st.fbheight))
    return 0
  end
  if not ok then             -- an empty window waits for the file to be fixed
    local wok, werr = pcall(V.open, { width = w, height = h, status = not opts["no-status"] })
    if not wok then          -- no window at all (no display): said once, not by both calls
      local why = werr:gsub("^lsys%.viewer%.open: ", "")
      if tostring(err):gsub("^lsys%.show: ", "") ~= why then
        io.stderr:write("lsys: ", tostring(err), "\n")       -- the model's own error
      end
      error(why, 0)
    end
    io.stderr:write("lsys: ", tostring(err), "\n")
    io.stderr:write(format("lsys: waiting for %s to change\n", path))
  end

  watch(V, function () return source_files(src) end, function ()
    local rok, rerr = show(true)
    if not rok then
      io.stderr:write("lsys: ", tostring(rerr), "\n",
        shown and "lsys: (the last good model stays on screen)\n" or "")
    end
  end)
  return 0
end

return run
