--- The help texts of the `lsys` program: `usage`, what `lsys --help` prints, and `help`,
-- each command's text by its name (`lsys help COMMAND`, `lsys COMMAND --help`).
-- @module lsys.cli.help
local core = require "lsys.core"
local batch_formats = require "lsys.batch.formats"
local series = require("lsys.util.text").series

local ipairs, pairs, table = ipairs, pairs, table
local _ENV = nil

local M = {}

-- The lists of formats the texts show, at their $NAME: the export formats of the core
-- (core.formats()) and the outputs of lsys.batch (lsys.batch.formats).
local LISTS = {}
do
  local exts, dots, meshes = {}, {}, {}
  for _, f in ipairs(core.formats()) do
    exts[#exts + 1] = f.ext
    dots[#dots + 1] = "." .. f.ext
  end
  for _, f in ipairs(batch_formats.list) do
    if f.mesh then meshes[#meshes + 1] = "." .. f[2] end
  end
  LISTS.EXPORT_EXTS = series(dots, "or")                       -- .obj, .ply or .glb
  LISTS.EXPORT_BRACE = "{" .. table.concat(exts, ",") .. "}"   -- {obj,ply,glb}
  LISTS.BATCH_NAMES = series(batch_formats.names)              -- png, glb, ..., stats
  LISTS.BATCH_MESHES = table.concat(meshes, " ")               -- .glb .obj .ply
end

local function fill (text) return (text:gsub("%$([%u_]+)", LISTS)) end

local USAGE = [[
usage: lsys [COMMAND] [ARGS]

  lsys                        start the REPL, with `lsys` loaded
  lsys FILE.lua [ARGS]        run a Lua script (`-` reads it from stdin), like `lua FILE.lua`
  lsys derive [MODEL] [OPTS]  derive a model; print the L-string or its statistics
  lsys render [MODEL] [OPTS]  render a model to PNG (default: the default tree to tree.png),
                              or --frames DIR: one picture per step, one camera
  lsys animate [MODEL] -o OUT.mp4|OUT.gif   an animation of the model growing (ffmpeg)
  lsys animate [MODEL] --orbit              a turntable of the final plant (ffmpeg)
  lsys export MODEL -o OUT    write a model's geometry to OUT ($EXPORT_EXTS)
  lsys view [MODEL] [OPTS]    show a model in a window; reload it when its file changes
  lsys arrange [MODEL] [OPTS] bend, twist and prune a model in the window (inverse kinematics)
  lsys sketch [FILE] [OPTS]   draw a plant's construction lines; the plant follows (a window)
  lsys sketch plot|model|render FILE -o OUT   a sketch's functions, model or picture
  lsys components graph MODEL -o OUT   draw a component graph's p-graph (Graphviz)
  lsys grow FILE [OPTS]       grow plants tick by tick in the window (lsys.grow), or to PNGs
  lsys import MODEL.l [VIEW.v] -o OUT.lua   write a cpfg model as an lsys model file
  lsys batch SPEC [OPTS]      run the jobs a CSV or Lua spec lists (sweeps; --shard K/N)
  lsys test [PATH...] [OPTS]  run busted specs of models with lsys and lsys.testing
  lsys help [COMMAND]         this help, or a command's help

MODEL is a Lua file that returns a model, an example's name, a cpfg L-system file (.l,
with its view file VIEW.v after it: `lsys render plant.l plant.v`) or a vlab object folder.

Options:
  -h, --help      show this help
  -V, --version   show the version

Conventions: -o FILE names the file a command writes (a folder is -d DIR or --frames DIR);
-v is --verbose where a command has a verbose mode (lsys test: busted's); --steps N is the
number of derivation steps of every command that loads a model, and --threads N,
--max-memory SIZE and --max-modules N set its limits. The old spellings `lsys -v`, `lsys
batch -o DIR` and `lsys view --step K` still work in this release and warn.

Environment: LSYS_DEBUG=1 adds a Lua traceback to error messages; LUA_PATH and LUA_CPATH
work as in `lua`. Exit status: 0 success, 1 error, 2 usage error.
]]

local HELP = {}

HELP.derive = [=[
usage: lsys derive [MODEL [VIEW.v]] [--steps N] [--seed S] [--set NAME=VALUE]...
                   [--name NAME] [--map FILE | --mat FILE] [--define NAME=VALUE]...
                   [--threads N] [--max-memory SIZE] [--max-modules N]
                   [--stats] [--progress]

Loads MODEL, a Lua file that returns a model made by lsys.lsystem{...} (or a component
graph's root prototype, see `lsys help components`, or a table of named models), derives
it and prints the resulting L-string in cpfg notation. Without MODEL,
derives the default example (examples/default.lua). A MODEL that is not a file is looked up
in the examples directory, with or without .lua: `lsys derive abop/fig1_24a`.

A MODEL ending in .l is a cpfg L-system file, loaded as lsys.cpfg.load does (docs/cpfg.md),
with VIEW.v, when given, as its view file: `lsys derive plant.l plant.v`. A folder with a
`specifications` file is a vlab object: the specifications name its .l, .v and palette.

Options:
  --steps N          number of derivation steps (sets model.steps)
  --seed S           random seed (sets model.seed)
  --set NAME=VALUE   sets model.env[NAME] to VALUE, a finite number; may be repeated. NAME
                     must be a variable of the model (in its env; else a usage error, with
                     the names near it). A cpfg model's env holds the variables of its
                     Start and End blocks; a #define is not one: see `lsys import`
  --name NAME        the model to derive when MODEL returns a table of models (default:
                     the first name in sorted order)
  --map FILE         a cpfg model's colour map (.map): from the current folder, else
                     from the .l file's (where vlab runs cpfg)
  --mat FILE         a cpfg model's material file (.mat), likewise
  --define NAME=VALUE  a preprocessor definition for a cpfg model, as cpp's -D (a
                     #define in the file wins); may be repeated
  --environment FILE.e  the environment the model's ?E modules ask (a cpfg model's or a
                     Lua model's): the program of the communication file, started as
                     cpfg -e starts it (vlab's honda81, chiba, ...; docs/open.md)
  --environment none  derive them as cpfg does without one (without this option a model
                     with ?E is refused)
  --threads N        the threads a step (and an interpretation) may use, 1 to 64 (sets
                     model.threads; default: the model's, else LSYS_THREADS, else the
                     processors); the string is the same for any number
  --max-memory SIZE  the memory one step (or interpretation) may take: bytes, or e.g.
                     512M, 2G, unlimited (sets max_memory; default: the model's, else
                     LSYS_MAX_MEMORY, else half the physical memory)
  --max-modules N    the longest string a step may build, 1 to 1e12 (sets max_modules;
                     default: the model's, else 50000000)
  --stats            print statistics instead of the string: steps, modules, the count of
                     each module name, and the derivation time
  --progress         print "step k/N: M modules" on stderr after each step (the default
                     when stderr is a terminal)
  -h, --help         show this help
]=]

HELP.render = [=[
usage: lsys render [MODEL [VIEW.v]] [-o OUT.png|.svg|.eps|.pdf] [--size WxH] [--steps N]
                   [--seed S] [--set NAME=VALUE]... [--view NAME=VALUE]... [--name NAME]
                   [--map FILE | --mat FILE] [--define NAME=VALUE]... [--threads N]
                   [--max-memory SIZE] [--max-modules N] [--progress] [--flat] [--ao]
       lsys render [MODEL [VIEW.v]] --frames DIR [--every K] [OPTIONS as above]

Derives MODEL (a Lua file returning a model, an example name, a cpfg .l file with its
VIEW.v, or a vlab object folder, as for `lsys derive`), interprets it with the turtle and
renders it headless (OSMesa) to a PNG file. Without MODEL, renders the default example
(examples/default.lua) to tree.png. An OUT ending in .svg, .eps or .pdf gets a vector
picture instead: the lines as stroked paths with their widths and colours, polygons as
filled paths, framed as the PNG of that --size would be (docs/drawing.md §6). A Lua file
may also return a Scene, such as a field of plants made by lsys.population
(examples/population/field.lua): it is rendered as it is (to PNG only).

With --frames DIR, writes one picture per derivation step into DIR instead (made when
missing): step-0000.png, step-0001.png, ... All look through one camera, fitted to the last
step, so the plant grows in place from picture to picture. `lsys animate` makes a video
of them.

Options:
  -o, --output OUT   the picture: .png, .svg, .eps or .pdf (default: tree.png for the
                     default model, else the model's file name with .png, in the current
                     directory)
  --frames DIR       one picture per step into DIR (not with -o); a progress bar on a
                     terminal, else a line per frame with --progress
  --every K          with --frames: steps 0, K, 2K, ... and always the last
  --size WxH         picture size in pixels (default 800x800)
  --flat             no shadows, ground or sky: a 3D plant (triangles, deep in every
                     direction) gets shadows of the key light, a ground plane under it and
                     a sky gradient (unless --view background=... is given); 2D drawings never
  --ao               ambient occlusion too (darker where the plant is crowded; slower)
  --steps N, --seed S, --set NAME=VALUE, --name NAME, --progress   as for `lsys derive`
  --threads N, --max-memory SIZE, --max-modules N   the model's limits, as for `lsys
                     derive` (the interpretation's too)
  --map FILE, --mat FILE, --define NAME=VALUE, --environment FILE.e|none   a cpfg model's, as
                     for `lsys derive`
  --view NAME=VALUE  sets a view option for this picture (a number, a word, or a list
                     such as 0,1,0): line_style=cylinder, projection=perspective, fov=40,
                     viewpoint=0,10,40, background=1,1,1, supersample=2, ...
  -h, --help         show this help
]=]

HELP.animate = [=[
usage: lsys animate [MODEL [VIEW.v]] [-o OUT.mp4|OUT.gif] [--fps N] [--every K]
                    [--hold S] [--size WxH] [--steps N] [--seed S] [--set NAME=VALUE]...
                    [--view NAME=VALUE]... [--name NAME] [--map FILE | --mat FILE]
                    [--define NAME=VALUE]... [--threads N] [--max-memory SIZE]
                    [--max-modules N] [--progress]
       lsys animate [MODEL [VIEW.v]] --orbit [-o OUT.mp4|OUT.gif] [--frames N]
                    [--seconds S] [--fps N] [--axis X,Y,Z] [OPTIONS as above]

Derives MODEL (as for `lsys render`) and writes an animation of it growing: one frame per
derivation step, all through one camera fitted to the last step, so the plant grows in
place. An .mp4 is an H.264 video (yuv420p, plays everywhere); a .gif an animated GIF that
loops, its colours from one palette made for the whole animation. The frames are drawn
headless into a temporary folder and encoded by ffmpeg (Debian package ffmpeg: apt-get
install ffmpeg); without it, `lsys render MODEL --frames DIR` writes the pictures.

With --orbit, writes a turntable instead: the final plant seen by a camera that goes
once around it, about the view's up vector (+y unless the view sets `up`),
counterclockwise seen from above. The first frame looks along the view's direction, so
the elevation, the projection and the light stay the view's; the camera is fitted once,
to the plant's bounding sphere, so the whole plant stays in every frame at the same size.

Options:
  -o, --output OUT   the .mp4 or .gif file (default: the model's name with .mp4, or
                     tree.mp4 for the default model, in the current directory); it
                     appears whole or not at all
  --fps N            frames a second (default 4)
  --every K          steps 0, K, 2K, ... and always the last (default: every step)
  --hold S           the last frame stays S seconds longer (default 0)
  --size WxH         frame size in pixels (default 800x800; an .mp4's are rounded up to
                     even numbers, as H.264 needs)
  --progress         a line per step and frame on stderr (on a terminal a progress bar
                     is shown without it)
  --orbit            a turntable of the final plant (default output: the model's name
                     with -orbit.mp4, or tree-orbit.mp4); not with --every or --hold
  --frames N         with --orbit: frames in the turn (default 72: one every 5 degrees)
  --seconds S        with --orbit: the turn lasts S seconds at --fps (instead of --frames)
  --fps N            with --orbit: default 24
  --axis X,Y,Z       with --orbit: the axis the camera turns about (default the view's up)
  --steps N, --seed S, --set NAME=VALUE, --view NAME=VALUE, --name NAME, --map FILE,
  --mat FILE, --define NAME=VALUE, --environment FILE.e|none, --threads N, --max-memory SIZE,
  --max-modules N   as for `lsys render`
  -h, --help         show this help
]=]

HELP.export = [[
usage: lsys export MODEL [VIEW.v] -o OUT.$EXPORT_BRACE [--lines tubes] [--steps N]
                   [--seed S] [--set NAME=VALUE]... [--view NAME=VALUE]... [--name NAME]
                   [--map FILE | --mat FILE] [--define NAME=VALUE]... [--threads N]
                   [--max-memory SIZE] [--max-modules N] [--progress]

Derives and interprets MODEL (as for `lsys render`: a cpfg MODEL.l takes its VIEW.v after
it) and writes its geometry: Wavefront OBJ (with a .mtl file next
to it), binary PLY, or glTF 2.0 binary (.glb), chosen by the extension of OUT. A file
returning a population (lsys.population) is written as it is: .glb with one mesh per
prototype placed by EXT_mesh_gpu_instancing, .obj and .ply with every plant written out.
It prints what the file holds: its vertices, triangles and lines.

Options: as for `lsys render`; -o is required.
  --lines tubes   write line-style segments as closed tubes (as thick as in an 800x800
                  render) instead of lines, which most viewers draw one pixel wide
                  (default: --lines lines)
]]

HELP.view = [=[
usage: lsys view [MODEL [VIEW.v]] [--size WxH] [--show K] [--rate R] [--no-status]
                 [--last | --history SIZE] [--edit | --no-edit] [--flat] [--shadows] [--ao]
                 [--screenshot OUT.png] [--steps N] [--seed S] [--set NAME=VALUE]...
                 [--view NAME=VALUE]... [--name NAME] [--map FILE | --mat FILE]
                 [--define NAME=VALUE]... [--threads N] [--max-memory SIZE]
                 [--max-modules N]

Opens the viewer window on MODEL (a Lua file returning a model, an example name, a cpfg
.l file with its VIEW.v, or a vlab object folder, as for `lsys derive`; default: the
default example) with every derivation step, the last one shown. When the model file
changes on disk (for a cpfg model: the .l file, the files it #includes, the view file or
the palette) it is loaded again and the window updates,
keeping its camera; an error (a syntax error, a bad rule) is printed here and the last
good model stays on screen. A click on a module prints its index and text. The window
closes with Esc or Q, and Ctrl-C here closes it too.

In the window: drag to orbit, right-drag or shift-drag to pan, scroll to zoom; left and
right arrows step through the derivation, space animates, + and - change the speed;
R resets the view, F fits, W toggles wireframe, G the sky and ground of a 3D plant
(--flat: none), L colours the leaves by the light they
receive (and back), S saves a screenshot (lsys-NNN.png) -- while animating, every step
through the window's camera into MODEL-frames/ --, H shows this list.

A model with tunable parameters (the model option `params`), or a cpfg model with vlab
control panels (panel.l beside it, or named by its vlab object's specifications), opens
with its sliders beside the plant, and a tab for its palette: moving one makes the plant
again at once (its last step), Ctrl+S saves the values into the model file (a vlab model:
its #defines, as vlab's awkped does). See docs/viewer.md, "Editing a plant".

Options:
  --size WxH           window size (default 800x800)
  --show K             the step shown first (default: the last); --step K, its old
                       spelling, warns (--steps N is the number of steps, as everywhere)
  --rate R             animation speed in steps per second (default 2)
  --no-status          no status line at the bottom of the window
  --last               keep the last step only (no stepping: the least memory)
  --history SIZE       the memory the kept steps may take (default 256M; e.g. 1G): beyond
                       it the window keeps every 2nd, 4th, ... step and the last
  --screenshot OUT.png draw the first picture as the window shows it, save it to OUT.png
                       (through the same path as the S key) and exit
  --flat               no sky and no ground under a 3D plant (the G key turns them on)
  --shadows, --ao      a 3D plant drawn with the shadows (and ambient occlusion) that
                       lsys render gives it, baked into its colours for each step shown
                       (seconds for a large plant; each edit bakes it again)
  --edit               the editing panes for any model (its last step); --no-edit: none,
                       every step as for a model without params
  --steps N, --seed S, --set NAME=VALUE, --view NAME=VALUE, --name NAME, --map FILE,
  --mat FILE, --define NAME=VALUE, --environment FILE.e|none, --threads N, --max-memory SIZE,
  --max-modules N   as for `lsys render`
  -h, --help           show this help

The window needs a display (X11 or Wayland through XWayland); `lsys render` draws PNG files
without one.
]=]

HELP.arrange = [[
usage: lsys arrange [MODEL] [-o OUT.txt] [--string FILE] [--size WxH] [--r0 R] [--s0u S]
                    [--s0h S] [--steps N] [--seed S] [--set NAME=VALUE]... [--view NAME=VALUE]...
                    [--name NAME] [--threads N] [--max-memory SIZE] [--max-modules N]

Opens MODEL (default: the default example) derived in the viewer window for arranging by
inverse kinematics as in ilsa (Power et al. 1999; docs/arrange.md):

  click           a segment: the fixed point; the active branch above it turns red
  click again     within the red branch: the end of the branch path, which turns yellow
  Ctrl-drag       move the path's end with the tool: G or 1 sphere (default), D or 2 disc
                  (twist), A or 3 axis (in and out), P or 4 plane (in the view plane)
  arrow keys      move the fixed point: up/down along the branch, left/right to siblings
  Delete          prune the active branch (the marker @X takes its place)
  U, Ctrl-Z       undo           Ctrl-S   save the arranged L-string to OUT
  drag, scroll    orbit, zoom (as in lsys view)          Esc  quit

Options:
  -o, --output OUT   where Ctrl-S saves (default: MODEL's name with -arranged.txt)
  --string FILE      start from an L-string saved before (cpfg text) instead of deriving
  --size WxH         window size (default 800x800)
  --r0 R, --s0u S, --s0h S   trunk radius and trunk flexural and torsional stiffness for
                     the automatic joint stiffness (default 1 each)
  --steps N, --seed S, --set NAME=VALUE, --view NAME=VALUE, --name NAME, --map FILE,
  --mat FILE, --define NAME=VALUE, --environment FILE.e|none, --threads N, --max-memory SIZE,
  --max-modules N   as for render

The saved string keeps the arrangement as @J(h,u,l) joint modules: derive it further with
`model:step(lsys.lstring(text))`, or arrange it again with --string.
]]

HELP.sketch = [[
usage: lsys sketch [FILE] [--size WxH] [--nodes N] [--phyllotaxis P] [--organ ORGAN]
       lsys sketch plot FILE [-o functions.png] [--size WxH]
       lsys sketch model FILE [-o plant.lua] [--nodes N] [--phyllotaxis P] [--organ ORGAN]
       lsys sketch model FILE --cpfg [-o plant.l] [--nodes N] [--phyllotaxis P]
                          [--organ ORGAN]
       lsys sketch render FILE [-o plant.png] [--size WxH] [--nodes N] [--phyllotaxis P]
                          [--organ ORGAN]

Sketch-based parameterization of L-systems (Anastacio et al. 2009; docs/sketch.md): the
construction lines of a plant -- a stem, left and right boundaries, inclination lines --
become positional functions that parameterize a phyllotaxis template.

`lsys sketch [FILE]` opens the sketch window: the sketch on the left, the plant it makes
on the right, updated while you draw, the functions plotted under it. FILE (a .json or
.svg sketch) is read when it exists and is where Ctrl+S saves (default sketch.json; a
.svg is saved as .json next to it). In the window: left drag draws a stroke; 1 2 3 4 or
the toolbar pick its role (stem, left boundary, right boundary, inclination line); a new
stem or boundary replaces the old one; right drag (or shift drag) moves the nearest
stroke; Delete or Backspace deletes the selected (else the last) stroke; Ctrl+Z undoes;
+ and - change the nodes per layer, P the phyllotaxis; the wheel over the sketch (or [
and ]) sets the pressure of the points drawn next (darker nearer, lighter farther); Tab
hides the plots; O switches to the organ: its left and right boundaries in a top view (1,
2), its midrib in a side view (3) and its cross-section in a front view (4), and back;
Ctrl+S saves the sketch (and a changed organ: the --organ file, else FILE.organ.json);
Ctrl+E exports the plant (FILE.glb, .obj, .png) and the model (FILE.lua, and FILE.l with
its files for cpfg).
Over the plant: drag orbits, right drag pans, the wheel zooms. H lists the keys.

  plot     draws the positional functions (six panels, seven with pitch) to a PNG
  model    writes the generated model as an editable Lua file; with --cpfg as cpfg's
           files for cpfg and L-studio: plant.l, plant.v, plant.map, a plant.NAME.func
           per function and the organ's surface, which cpfg derives as lsys does
  render   renders the plant headless to a PNG

Options:
  -o, --output OUT    the file written (default: FILE's name with -functions.png, .lua,
                      .png, in the current directory)
  --size WxH          the window's size (default 1200x800), or the picture's (plot:
                      900x600, render: 800x800); a new sketch is 600x600 pixels
  --nodes N           nodes per layer (default: the sketch's)
  --phyllotaxis P     distichous, decussate or fibonacci (default: the sketch's)
  --organ ORGAN       the organ at the nodes: a leaf shape (ovate, lanceolate, elliptic,
                      obovate, linear, cordate) or an organ file (.json, drawn in three
                      views; the window draws and saves a new one there); default a
                      flat leaf
  --cpfg              model: cpfg's files instead of a Lua model file
  -h, --help          show this help

The window needs a display; a drawing tablet's pen pressure is read when X reports one (XInput2),
else the wheel sets it (docs/sketch.md, "Pressure and tablets").
]]

HELP.components = [[
usage: lsys components graph MODEL [-o OUT] [--params]

Component graphs (Lintermann and Deussen 1999; docs/components.md). MODEL is a Lua file
that returns the root prototype of a component graph (`return plant`). Every command that
takes a MODEL (derive, render, export, view, arrange) takes such a file too: the graph is
expanded (--seed seeds it) and drawn as an ordinary model; a click in `lsys view` prints
the instance's path and parameters.

  graph    draws the p-graph: a camera box at the root, child links as thin lines, branch
           links bold, leaf links dashed, the links of a recursion doubled, ending at a
           dashed copy of the component the recursion returns to; flag lists on the links

Options:
  -o, --output OUT    the file written: .png, .svg or .pdf (through Graphviz's dot, Debian
                      package graphviz) or .dot/.gv, the DOT text (default: MODEL's name
                      with -graph.png, in the current directory)
  --params            show the components' parameters in the nodes
  -h, --help          show this help
]]

HELP.grow = [[
usage: lsys grow FILE [--ticks N] [--seed S] [--rate R] [--size WxH] [--flat]
                      [--screenshot OUT.png]
       lsys grow FILE --frames DIR [--every K] [--ticks N] [--seed S] [--size WxH]

Incremental growth (Davison, "Incremental rules for growing plants"; docs/grow.md). FILE is a
Lua file that returns a world of lsys.grow, planted (`return w` after w:plant{...};
`lsys.grow.world{ticks = N}` says how long it grows), or a table with a world(opts) function
that makes one (as examples/grow/davison.lua). The plants grow tick by tick in the window:
each tick changes the limbs in place and the window receives only what changed. The camera
frames the plants' final size (the world is grown once headless first), so they grow in
place.

In the window: space pauses and resumes (at the end, grows on), right grows one tick, + and
- change the speed (1 to 60 ticks a second, or as fast as the window draws), backspace
starts again; drag orbits, right-drag pans, scroll zooms, R resets the view, F fits, W
wireframe, G sky and ground (--flat: none), S screenshot, H help, Esc or Q quits. The
status line shows the tick, the limbs, the triangles, the frames drawn a second and the
ticks a second.

Options:
  --ticks N            how long to grow (default: the world's length, else 100)
  --seed S             the seed given to world(opts) (a file returning a World seeds it)
  --rate R             ticks a second (default 10, the paper's tick of 100 ms; with
                       --screenshot, as fast as the window draws them)
  --size WxH           window or picture size (default 1000x600)
  --screenshot OUT.png grow to the end in the window, save its picture, exit; prints the
                       window's drawing rate while growing
  --flat               no sky and no ground (the G key turns them on)
  --frames DIR         no window: one PNG per tick into DIR (tick-0000.png, ...), one camera
  --every K            with --frames: every K-th tick (and the last)
  -h, --help           show this help
]]

HELP.import = [[
usage: lsys import MODEL.l [VIEW.v] -o OUT.lua [--map FILE | --mat FILE]
                   [--define NAME=VALUE]...
       lsys import FOLDER -o OUT.lua

Writes the cpfg model MODEL.l (with its view file VIEW.v and colour map or material file),
or the vlab object FOLDER, as an lsys model file to edit from there on: a Lua file that
returns lsys.lsystem{...}, with the rules in lsys's notation, the #defines of plain numbers
as env entries that the rules read by name (`--set NAME=VALUE` changes one), the view
settings, and the productions with statement blocks as Lua functions. `lsys derive OUT.lua`
gives the string `lsys derive MODEL.l` gives. The view's files (contours, surfaces,
functions, the palette) stay where they are; OUT.lua finds them from its own folder.

Options:
  -o, --output OUT.lua  the file to write (required); it appears whole or not at all
  --map FILE, --mat FILE, --define NAME=VALUE, --environment FILE.e|none   as for `lsys derive`
  -h, --help            show this help
]]

HELP.batch = [[
usage: lsys batch SPEC [-d DIR] [--shard K/N | --shard slurm] [--list] [--force]
                  [--progress]

Runs the jobs SPEC lists -- each a model, values for its variables, a seed and the files
to write -- one after the other, and records each in a manifest (docs/batch.md). SPEC is
a CSV file with a header line -- the columns model, seed, steps, width, height, name, id,
out (file name templates separated by ;), $BATCH_NAMES, and a
column per model variable it sets, as --set does -- or a Lua file that returns a list of
jobs or a sweep, expanded in the order of its names (the last one varies fastest):

  return { model = "plant.lua", seed = 1, vary = { R = { 1.2, 1.4 }, angle = { 20, 30 } },
           replicates = 5, width = 256, height = 256,
           outputs = { "png/{id}.png", "stats/{id}.json" } }

Model files are found from SPEC's folder; outputs go to DIR. In a template {id} is the
job's id (0001, 0002, ...: its number in SPEC), {seed}, {model}, {rep} and {R} (a
variable) its values. A job that gives no seed gets one made from SPEC's seed and its
number: the same in any shard, on any host. The formats, by extension: .png (width x
height, default 800x800), $BATCH_MESHES (meshes), .txt (the L-string), .json (modules,
counts by name, triangles, area, bounds).

Every file appears whole or not at all. A job is skipped when the manifest says it ran
with the same values and its files are there: a run that was killed, or had failures,
goes on where it stopped. A job that fails is recorded with its message and the
others go on; the exit status is then 1.

Options:
  -d, --dir DIR     the output folder (made when missing; default: the current folder)
                    and its manifest, DIR/manifest.jsonl (DIR/manifest-K-of-N.jsonl for a
                    shard): a JSON line per job run (job, seed, params, outputs, seconds,
                    status ok or failed, error). -o/--out DIR, its old spelling, warns
                    (everywhere else -o names a file)
  --shard K/N       run shard K of N only: jobs K, K+N, K+2N, ... For GNU parallel:
                    parallel lsys batch SPEC -d DIR --shard {}/4 ::: 1 2 3 4
  --shard slurm     the shard of this task of a Slurm job array (SLURM_ARRAY_TASK_ID,
                    SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT): in an sbatch script
                    with #SBATCH --array=0-9, lsys batch SPEC -d DIR --shard slurm
  --list            print the jobs (of the shard), each done, failed or to do; run nothing
  --force           run the jobs that are done as well
  --progress        a line per job on stderr (on a terminal a progress line shows anyway)
  -h, --help        show this help
]]

HELP.test = [[
usage: lsys test [PATH...] [BUSTED OPTIONS]

Runs busted specs (files or folders of *_spec.lua files) with this lsys, in this program:
`require "lsys"` and `require "lsys.testing"` work in any folder, with no --lpath or
LUA_PATH, and whatever `lua` or `busted` the system names. Without PATH: what a .busted
file in the current folder says, else the folder spec/ when there is one, else every
*_spec.lua file in and below the current folder.

lsys.testing adds assertions for models (docs/testing.md):
  assert.lstring_equal(expected, actual [, tol])   L-strings, module by module
  assert.near(expected, actual, tol)               numbers and tables of numbers
  assert.error_contains(fn, text, ...)             an error message holding each text
  assert.scene_stats(scene, { triangles = N, ... } [, tol])   scene statistics
  assert.image_matches(scene, "golden.png" [, opts])   a picture against a golden image;
                     LSYS_UPDATE_GOLDEN=1 writes the golden images instead

The other options are busted's (busted --help lists them), for example:
  -t, --tags=TAGS, --exclude-tags=TAGS   run only, or leave out, tests tagged #TAG
  --filter=PATTERN   only tests whose names match the Lua pattern
  -o, --output=NAME  busted's output: utfTerminal, plainTerminal, TAP, json, junit
  -v, --verbose      more output, with tracebacks
  -h, --help         show this help

The exit status is busted's: 0 when every test passed, 1 otherwise. busted itself comes
from the Debian package lua-busted, or `luarocks --lua-version 5.4 install busted`.
]]

HELP.repl = [[
usage: lsys [repl]

The interactive REPL: Lua 5.4 with `lsys` loaded as a global. An expression (or `=expr`)
prints its values, and `_` is the first of them for the lines after; Lstrings print
abbreviated, scenes as a summary, models with their options and rules (m:inspect()), tables
one level deep. Incomplete statements continue on `>>` lines; a `local` stays defined for
the lines after it. help() gives an overview, help "derive" or help(lsys.render) the
manual's section, help(m) what a model is and its methods; text longer than the terminal
goes through $PAGER (else less or more). With readline: Tab completes names, and the
history is kept in ~/.lsys_history. Ctrl-C clears the line at the prompt and interrupts a
running evaluation; Ctrl-D quits.

lsys.show(x) opens the viewer window on a model, an Lstring or a scene (or updates it) and
returns at once; clicks on modules in the window are printed at the prompt (set
lsys.viewer.on_pick to a function to handle them yourself).
]]

HELP.help = [[
usage: lsys help [COMMAND]

Shows the list of commands, or the help of COMMAND.
]]

M.usage = fill(USAGE)
for k, text in pairs(HELP) do HELP[k] = fill(text) end
M.help = HELP

return M
