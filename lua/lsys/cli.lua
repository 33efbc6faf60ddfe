--- The `lsys` command line.
-- The program (csrc/prog/lsys.c) calls `main(...)` with its arguments and exits with what it
-- returns: 0 on success, 1 when something failed, 2 for a usage error. `main` prints its
-- own messages (`lsys: ...` on stderr) and does not raise, so it can be called from Lua too:
-- `require("lsys.cli").main("derive", "examples/default.lua", "--stats")`.
--
--   lsys                      the REPL (lsys.repl)
--   lsys FILE.lua [ARGS]      run a Lua script, like `lua FILE.lua ARGS`
--   lsys derive [MODEL] ...   derive a model; print the L-string or its statistics
--   lsys render [MODEL] ...   derive, interpret and render a model to PNG (headless, OSMesa)
--   lsys render MODEL --frames DIR   one PNG per derivation step, through one camera
--   lsys animate MODEL -o OUT  the model growing, as .mp4 or .gif (ffmpeg)
--   lsys export MODEL -o OUT  derive, interpret and write the geometry (.obj .ply .glb)
--   lsys view [MODEL] ...     the viewer window on a model, reloaded when its file changes
--   lsys arrange [MODEL] ...  bend, twist and prune a derived model in the window (IK)
--   lsys sketch [FILE] ...    the sketch window; sketch plot|model|render FILE -o OUT
--   lsys components graph MODEL -o OUT   a component graph's p-graph (.png .svg .pdf .dot)
--   lsys grow FILE ...        a growing world (lsys.grow) live in the window, or --frames DIR
--   lsys import MODEL.l -o OUT.lua   a cpfg model as a readable lsys model file
--   lsys batch SPEC ...       the jobs of a CSV or Lua spec (sweeps), sharded: lsys.batch
--   lsys test [PATH...]       busted on a user's specs, with lsys and lsys.testing
--   lsys help [COMMAND]       help
-- @module lsys.cli
local host = require("lsys.program").host

local G = _G
local type, pairs, ipairs, tostring, tonumber, error, pcall, xpcall, require =
      type, pairs, ipairs, tostring, tonumber, error, pcall, xpcall, require
local loadfile, getmetatable, setmetatable, next, warn =
      loadfile, getmetatable, setmetatable, next, warn
local io, os, string, table, math, debug = io, os, string, table, math, debug
local format = string.format
local _ENV = nil

local M = {}

local USAGE = [[
usage: lsys [COMMAND] [ARGS]

  lsys                        start the REPL, with `lsys` loaded
  lsys FILE.lua [ARGS]        run a Lua script (`-` reads it from stdin), like `lua FILE.lua`
  lsys derive [MODEL] [OPTS]  derive a model; print the L-string or its statistics
  lsys render [MODEL] [OPTS]  render a model to PNG (default: the default tree to tree.png),
                              or --frames DIR: one picture per step, one camera
  lsys animate [MODEL] -o OUT.mp4|OUT.gif   an animation of the model growing (ffmpeg)
  lsys export MODEL -o OUT    write a model's geometry to OUT (.obj, .ply or .glb)
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
  -v, --version   show the version

Environment: LSYS_DEBUG=1 adds a Lua traceback to error messages; LUA_PATH and LUA_CPATH
work as in `lua`. Exit status: 0 success, 1 error, 2 usage error.
]]

local HELP = {}

HELP.derive = [=[
usage: lsys derive [MODEL [VIEW.v]] [--steps N] [--seed S] [--set NAME=VALUE]...
                   [--name NAME] [--map FILE | --mat FILE] [--define NAME=VALUE]...
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
  --set NAME=VALUE   sets model.env[NAME] to VALUE, a number if it reads as one, else a
                     string; may be repeated (a cpfg model's env holds the variables of
                     its Start and End blocks; a #define is not one: see `lsys import`)
  --name NAME        the model to derive when MODEL returns a table of models (default:
                     the first name in sorted order)
  --map FILE         a cpfg model's colour map (.map), relative to the .l file's folder
  --mat FILE         a cpfg model's material file (.mat), likewise
  --define NAME=VALUE  a preprocessor definition for a cpfg model, as cpp's -D (a
                     #define in the file wins); may be repeated
  --environment none  derive a cpfg model's ?E modules as cpfg does without its
                     environmental program (lsys runs none; without this option a model
                     with ?E is refused)
  --stats            print statistics instead of the string: steps, modules, the count of
                     each module name, and the derivation time
  --progress         print "step k/N: M modules" on stderr after each step (the default
                     when stderr is a terminal)
  -h, --help         show this help
]=]

HELP.render = [=[
usage: lsys render [MODEL [VIEW.v]] [-o OUT.png] [--size WxH] [--steps N] [--seed S]
                   [--set NAME=VALUE]... [--view NAME=VALUE]... [--name NAME]
                   [--map FILE | --mat FILE] [--define NAME=VALUE]... [--progress]
       lsys render [MODEL [VIEW.v]] --frames DIR [--every K] [OPTIONS as above]

Derives MODEL (a Lua file returning a model, an example name, a cpfg .l file with its
VIEW.v, or a vlab object folder, as for `lsys derive`), interprets it with the turtle and
renders it headless (OSMesa) to a PNG file. Without MODEL, renders the default example
(examples/default.lua) to tree.png. A Lua file may also return a Scene, such as a field of
plants made by lsys.population (examples/population/field.lua): it is rendered as it is.

With --frames DIR, writes one picture per derivation step into DIR instead (made when
missing): step-0000.png, step-0001.png, ... All look through one camera, fitted to the last
step, so the plant grows in place from picture to picture. `lsys animate` makes a video
of them.

Options:
  -o, --output OUT   the PNG file (default: tree.png for the default model, else the
                     model's file name with .png, in the current directory)
  --frames DIR       one picture per step into DIR (not with -o); a progress bar on a
                     terminal, else a line per frame with --progress
  --every K          with --frames: steps 0, K, 2K, ... and always the last
  --size WxH         picture size in pixels (default 800x800)
  --steps N, --seed S, --set NAME=VALUE, --name NAME, --progress   as for `lsys derive`
  --map FILE, --mat FILE, --define NAME=VALUE, --environment none   a cpfg model's, as
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
                    [--define NAME=VALUE]... [--progress]

Derives MODEL (as for `lsys render`) and writes an animation of it growing: one frame per
derivation step, all through one camera fitted to the last step, so the plant grows in
place. An .mp4 is an H.264 video (yuv420p, plays everywhere); a .gif an animated GIF that
loops, its colours from one palette made for the whole animation. The frames are drawn
headless into a temporary folder and encoded by ffmpeg (Debian package ffmpeg: apt-get
install ffmpeg); without it, `lsys render MODEL --frames DIR` writes the pictures.

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
  --steps N, --seed S, --set NAME=VALUE, --view NAME=VALUE, --name NAME, --map FILE,
  --mat FILE, --define NAME=VALUE, --environment none   as for `lsys render`
  -h, --help         show this help
]=]

HELP.export = [[
usage: lsys export MODEL [VIEW.v] -o OUT.{obj,ply,glb} [--lines tubes] [--steps N]
                   [--seed S] [--set NAME=VALUE]... [--view NAME=VALUE]... [--name NAME]
                   [--map FILE | --mat FILE] [--define NAME=VALUE]... [--progress]

Derives and interprets MODEL (as for `lsys render`: a cpfg MODEL.l takes its VIEW.v after
it) and writes its geometry: Wavefront OBJ (with a .mtl file next
to it), binary PLY, or glTF 2.0 binary (.glb), chosen by the extension of OUT. A file
returning a population (lsys.population) is written as it is: .glb with one mesh per
prototype placed by EXT_mesh_gpu_instancing, .obj and .ply with every plant written out.

Options: as for `lsys render`; -o is required.
  --lines tubes   write line-style segments as closed tubes (as thick as in an 800x800
                  render) instead of lines, which most viewers draw one pixel wide
                  (default: --lines lines)
]]

HELP.view = [=[
usage: lsys view [MODEL [VIEW.v]] [--size WxH] [--step K] [--rate R] [--no-status]
                 [--last | --history SIZE]
                 [--screenshot OUT.png] [--steps N] [--seed S] [--set NAME=VALUE]...
                 [--view NAME=VALUE]... [--name NAME] [--map FILE | --mat FILE]
                 [--define NAME=VALUE]...

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
R resets the view, F fits, W toggles wireframe, S saves a screenshot (lsys-NNN.png) --
while animating, every step through the window's camera into MODEL-frames/ --, H shows
this list.

Options:
  --size WxH           window size (default 800x800)
  --step K             the step shown first (default: the last)
  --rate R             animation speed in steps per second (default 2)
  --no-status          no status line at the bottom of the window
  --last               keep the last step only (no stepping: the least memory)
  --history SIZE       the memory the kept steps may take (default 256M; e.g. 1G): beyond
                       it the window keeps every 2nd, 4th, ... step and the last
  --screenshot OUT.png draw the first picture as the window shows it, save it to OUT.png
                       (through the same path as the S key) and exit
  --steps N, --seed S, --set NAME=VALUE, --view NAME=VALUE, --name NAME, --map FILE,
  --mat FILE, --define NAME=VALUE, --environment none   as for `lsys render`
  -h, --help           show this help

The window needs a display (X11 or Wayland through XWayland); `lsys render` draws PNG files
without one.
]=]

HELP.arrange = [[
usage: lsys arrange [MODEL] [-o OUT.txt] [--string FILE] [--size WxH] [--r0 R] [--s0u S]
                    [--s0h S] [--steps N] [--seed S] [--set NAME=VALUE]... [--view NAME=VALUE]...
                    [--name NAME]

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
  --mat FILE, --define NAME=VALUE, --environment none   as for render

The saved string keeps the arrangement as @J(h,u,l) joint modules: derive it further with
`model:step(lsys.lstring(text))`, or arrange it again with --string.
]]

HELP.sketch = [[
usage: lsys sketch [FILE] [--size WxH] [--nodes N] [--phyllotaxis P]
       lsys sketch plot FILE [-o functions.png] [--size WxH]
       lsys sketch model FILE [-o plant.lua] [--nodes N] [--phyllotaxis P]
       lsys sketch render FILE [-o plant.png] [--size WxH] [--nodes N] [--phyllotaxis P]

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
hides the plots; Ctrl+E exports the plant (FILE.glb, .obj, .png) and the model (FILE.lua).
Over the plant: drag orbits, right drag pans, the wheel zooms. H lists the keys.

  plot     draws the positional functions (six panels, seven with pitch) to a PNG
  model    writes the generated model as an editable Lua file
  render   renders the plant headless to a PNG

Options:
  -o, --output OUT    the file written (default: FILE's name with -functions.png, .lua,
                      .png, in the current directory)
  --size WxH          the window's size (default 1200x800), or the picture's (plot:
                      900x600, render: 800x800); a new sketch is 600x600 pixels
  --nodes N           nodes per layer (default: the sketch's)
  --phyllotaxis P     distichous, decussate or fibonacci (default: the sketch's)
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
usage: lsys grow FILE [--ticks N] [--seed S] [--rate R] [--size WxH] [--screenshot OUT.png]
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
wireframe, S screenshot, H help, Esc or Q quits. The status line shows the tick, the limbs,
the triangles and the frames drawn a second.

Options:
  --ticks N            how long to grow (default: the world's length, else 100)
  --seed S             the seed given to world(opts) (a file returning a World seeds it)
  --rate R             ticks a second (default: as fast as the window draws them)
  --size WxH           window or picture size (default 1000x600)
  --screenshot OUT.png grow to the end in the window, save its picture, exit; prints the
                       window's drawing rate while growing
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
  --map FILE, --mat FILE, --define NAME=VALUE, --environment none   as for `lsys derive`
  -h, --help            show this help
]]

HELP.batch = [[
usage: lsys batch SPEC [-o DIR] [--shard K/N | --shard slurm] [--list] [--force]
                  [--progress]

Runs the jobs SPEC lists -- each a model, values for its variables, a seed and the files
to write -- one after the other, and records each in a manifest (docs/batch.md). SPEC is
a CSV file with a header line -- the columns model, seed, steps, width, height, name, id,
out (file name templates separated by ;), png, glb, obj, ply, lstring, stats, and a
column per model variable it sets, as --set does -- or a Lua file that returns a list of
jobs or a sweep, expanded in the order of its names (the last one varies fastest):

  return { model = "plant.lua", seed = 1, vary = { R = { 1.2, 1.4 }, angle = { 20, 30 } },
           replicates = 5, width = 256, height = 256,
           outputs = { "png/{id}.png", "stats/{id}.json" } }

Model files are found from SPEC's folder; outputs go to DIR. In a template {id} is the
job's id (0001, 0002, ...: its number in SPEC), {seed}, {model}, {rep} and {R} (a
variable) its values. A job that gives no seed gets one made from SPEC's seed and its
number: the same in any shard, on any host. The formats, by extension: .png (width x
height, default 800x800), .glb .obj .ply (meshes), .txt (the L-string), .json (modules,
counts by name, triangles, area, bounds).

Every file appears whole or not at all. A job is skipped when the manifest says it ran
with the same values and its files are there: a run that was killed, or had failures,
goes on where it stopped. A job that fails is recorded with its message and the
others go on; the exit status is then 1.

Options:
  -o, --out DIR     the output folder (made when missing; default: the current folder)
                    and its manifest, DIR/manifest.jsonl (DIR/manifest-K-of-N.jsonl for a
                    shard): a JSON line per job run (job, seed, params, outputs, seconds,
                    status ok or failed, error)
  --shard K/N       run shard K of N only: jobs K, K+N, K+2N, ... For GNU parallel:
                    parallel lsys batch SPEC -o DIR --shard {}/4 ::: 1 2 3 4
  --shard slurm     the shard of this task of a Slurm job array (SLURM_ARRAY_TASK_ID,
                    SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT): in an sbatch script
                    with #SBATCH --array=0-9, lsys batch SPEC -o DIR --shard slurm
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
prints its values; Lstrings print abbreviated, scenes as a summary, tables one level deep.
Incomplete statements continue on `>>` lines; a `local` stays defined for the lines after
it. help() gives an overview, help "derive" or help(lsys.render) the manual's section.
With readline: Tab completes names, and the history is kept in ~/.lsys_history. Ctrl-C
clears the line at the prompt and interrupts a running evaluation; Ctrl-D quits.

lsys.show(x) opens the viewer window on a model, an Lstring or a scene (or updates it) and
returns at once; clicks on modules in the window are printed at the prompt (set
lsys.viewer.on_pick to a function to handle them yourself).
]]

HELP.help = [[
usage: lsys help [COMMAND]

Shows the list of commands, or the help of COMMAND.
]]

-- {===========================================================================================
-- Errors and output

local USAGE_ERROR = {}  -- metatable of usage errors

-- Raises a usage error (exit status 2) for command 'cmd' (nil: the program itself).
local function usage (cmd, fmt, ...)
  error(setmetatable({ cmd = cmd, msg = format(fmt, ...) }, USAGE_ERROR), 0)
end

local function out (...)
  io.stdout:write(...)
end

local function isatty (fd)
  local f = host().isatty
  return f ~= nil and f(fd) or false
end

local function clock ()
  local f = host().clock
  return f ~= nil and f() or os.clock()
end

local function isfile (path)
  local f = io.open(path, "r")
  if f == nil then return false end
  local ok, err = f:read(0)  -- nil, msg for a directory (it opens but cannot be read)
  f:close()
  return ok ~= nil or err == nil
end

local function isdir (path)
  local f = io.open(path, "r")
  if f == nil then return false end
  local ok, _, code = f:read(0)
  f:close()
  return ok == nil and code == 21     -- EISDIR
end

-- }===========================================================================================


-- {===========================================================================================
-- Option parsing

--[[
Parses args[first..] against 'spec', a table of option name -> "flag" | "value" | "list"
(short aliases: spec.short = { h = "help", o = "output" }). Accepts `--name value`,
`--name=value`, `-x value`, and `--` before positional arguments. Returns the options table
and the list of positional arguments; raises usage errors for command 'cmd'.
]]
local function parse (cmd, spec, args, first)
  local opts, pos = {}, {}
  local i = first
  while i <= args.n do
    local a = args[i]
    local name, val
    if a == "--" then
      for j = i + 1, args.n do pos[#pos + 1] = args[j] end
      break
    elseif a:sub(1, 2) == "--" then
      name, val = a:match("^%-%-([^=]+)=(.*)$")
      name = name or a:sub(3)
    elseif #a == 2 and a:sub(1, 1) == "-" and a ~= "--" then
      name = spec.short and spec.short[a:sub(2)]
      if name == nil then usage(cmd, "unknown option '%s'", a) end
    end
    if name ~= nil then
      local kind = spec[name]
      if kind == nil or name == "short" then usage(cmd, "unknown option '--%s'", name) end
      if kind == "flag" then
        if val ~= nil then usage(cmd, "option '--%s' takes no value", name) end
        opts[name] = true
      else
        if val == nil then
          i = i + 1
          val = args[i]
          if val == nil then usage(cmd, "option '--%s' needs a value", name) end
        end
        if kind == "list" then
          opts[name] = opts[name] or {}
          table.insert(opts[name], val)
        else
          opts[name] = val
        end
      end
    elseif a:sub(1, 1) == "-" and a ~= "-" then
      usage(cmd, "unknown option '%s'", a)
    else
      pos[#pos + 1] = a
    end
    i = i + 1
  end
  return opts, pos
end

-- }===========================================================================================


-- {===========================================================================================
-- Models and examples

local normalize = require("lsys.text").normpath

-- Directories that may hold the examples, most specific first.
local function example_dirs ()
  local dirs = {}
  local src = debug.getinfo(1, "S").source
  local root = src:match("^@(.*)[/\\]lsys[/\\]cli%.lua$")
  if root ~= nil then
    dirs[#dirs + 1] = normalize(root .. "/../examples")          -- source tree: lua/..
    dirs[#dirs + 1] = normalize(root .. "/../../lsys/examples")  -- share/lua/5.4/../../lsys
  end
  for _, d in ipairs(host().datadirs or {}) do
    dirs[#dirs + 1] = normalize(d .. "/examples")
  end
  return dirs
end

-- The path of the model file named by 'arg' (nil: the default example).
local function find_model (arg)
  local dirs = example_dirs()
  if arg ~= nil and isfile(arg) then return arg end
  local names = arg == nil and { "default.lua" } or { arg, arg .. ".lua" }
  if arg == nil or not arg:find("^/") then
    for _, d in ipairs(dirs) do
      for _, n in ipairs(names) do
        if isfile(d .. "/" .. n) then return d .. "/" .. n end
      end
    end
  end
  if arg == nil then
    error(format("no MODEL given and examples/default.lua was not found (looked in %s)",
      table.concat(dirs, ", ")), 0)
  end
  error(format("cannot open model '%s'", arg), 0)
end

local function is_model (v)
  if type(v) ~= "table" and type(v) ~= "userdata" then return false end
  local ok, derive = pcall(function () return v.derive end)
  return ok and type(derive) == "function"
end

-- True when 'v' is a component graph's prototype (lsys.components, issue 16).
local function is_proto (v)
  return type(v) == "table" and require("lsys.components.proto").isproto(v)
end

-- A model file's value as a model: a component graph's root prototype becomes
-- lsys.components.model(v) (expanded with 'seed'), anything else stays as it is.
local function as_model (v, path, seed)
  if not is_proto(v) then return v end
  local ok, m = pcall(require("lsys.components").model, v, { seed = seed })
  if not ok then
    local msg = tostring(m):gsub("^[^:\n]*%.lua:%d+: ", "")
    error(msg:find(path, 1, true) and msg or path .. ": " .. msg, 0)
  end
  return m
end

--[[
Runs the model file 'path' and returns the model it returns, and its name when the file
returns a table of named models ('name' picks one; default: the first in sorted order).
A component graph (the root prototype, or one in the table) is made a model here, the one
place every command loads its model through, with 'seed' for its expansion.
]]
local function load_model (path, name, seed)
  local chunk, err = loadfile(path, "t")
  if chunk == nil then error(err, 0) end
  -- runfile names the file when `return lsys.lsystem{...}` is a tail call
  local ok, v = require("lsys.model").runfile(path, chunk)
  if not ok then          -- name the model file when the message does not
    local msg = tostring(v)
    if msg:find(path, 1, true) == nil then msg = path .. ": " .. msg end
    error(msg, 0)
  end
  if is_model(v) or is_proto(v) then
    if name ~= nil then
      error(format("%s returns a single model; --name applies to a table of models", path), 0)
    end
    return as_model(v, path, seed)
  end
  if require("lsys.model").isscene(v) then return v end   -- a population: prepare checks
  if type(v) == "table" then
    local names = {}
    for k, x in pairs(v) do
      if type(k) == "string" and (is_model(x) or is_proto(x)) then names[#names + 1] = k end
    end
    table.sort(names)
    if #names > 0 then
      if name == nil then return as_model(v[names[1]], path, seed), names[1] end
      if is_model(v[name]) or is_proto(v[name]) then
        return as_model(v[name], path, seed), name
      end
      error(format("%s has no model named '%s' (models: %s)", path, name,
        table.concat(names, ", ")), 0)
    end
  end
  error(format("%s returned %s, not a model (end the file with `return lsys.lsystem { ... }`,"
    .. " a component graph's root prototype, or a table of models)", path, type(v)), 0)
end

-- The cpfg options of a command line (--map, --mat, --define) as lsys.cpfg.load options,
-- or nil when none is given.
local function cpfg_opts (cmd, opts)
  if opts.map == nil and opts.mat == nil and opts.define == nil and opts.environment == nil then
    return nil
  end
  if opts.map ~= nil and opts.mat ~= nil then usage(cmd, "give --map or --mat, not both") end
  if opts.environment ~= nil and opts.environment ~= "none" then
    usage(cmd, "--environment must be none (lsys runs no environmental program), got '%s'",
          opts.environment)
  end
  local defines
  for _, d in ipairs(opts.define or {}) do
    local k, v = d:match("^([%a_][%w_]*)=(.*)$")
    if k == nil and d:find("^[%a_][%w_]*$") then k, v = d, "1" end
    if k == nil then usage(cmd, "--define expects NAME=VALUE, got '%s'", d) end
    defines = defines or {}
    defines[k] = v
  end
  return { colormap = opts.map, materials = opts.mat, defines = defines,
           environment = opts.environment }
end

--[[
The model the positional arguments name: { path =, kind =, vfile =, lopts = }. A MODEL
ending in .l is a cpfg L-system file ("l"), and a second argument ending in .v its view
file; a folder with a `specifications` file is a vlab object ("object"); anything else is
a Lua model file or an example ("lua", find_model). lopts: the lsys.cpfg.load options of
--map, --mat and --define. Raises usage errors for arguments that do not go together.
]]
local function model_source (cmd, opts, pos)
  local arg, kind = pos[1], "lua"
  if arg ~= nil and arg:find("%.l$") then
    kind = "l"
  elseif arg ~= nil and isdir(arg) then
    if not isfile(arg .. "/specifications") then
      error(format("%s is a folder without a specifications file (a vlab object has one)",
                   arg), 0)
    end
    kind = "object"
  end
  local view = pos[2]
  if view ~= nil and kind == "lua" and view:find("%.v$") then
    usage(cmd, "a view file (%s) goes with a cpfg MODEL (.l), not with a Lua model", view)
  elseif view ~= nil and kind == "object" then
    usage(cmd, "unexpected argument '%s' (a vlab object names its view file in its "
          .. "specifications)", view)
  elseif view ~= nil and kind == "l" and not view:find("%.v$") then
    usage(cmd, "unexpected argument '%s' (after MODEL.l comes its view file, VIEW.v)", view)
  end
  if #pos > (kind == "l" and 2 or 1) then
    usage(cmd, "unexpected argument '%s' (%s)", pos[kind == "l" and 3 or 2],
          kind == "l" and "MODEL.l and VIEW.v at most" or "one MODEL at most")
  end
  local lopts = cpfg_opts(cmd, opts)
  if kind == "lua" then
    if lopts ~= nil then
      usage(cmd, "--map, --mat, --define and --environment apply to a cpfg MODEL (a .l "
            .. "file or a vlab object folder)")
    end
    return { path = find_model(arg), kind = kind }
  end
  if opts.name ~= nil then usage(cmd, "--name applies to a Lua file that returns models") end
  if kind == "l" then
    local f, err = io.open(arg, "r")
    if f == nil then error(err, 0) end
    f:close()
  end
  return { path = arg, kind = kind, vfile = view, lopts = lopts or {} }
end

-- Loads the model of model_source's `src` (`name` and `seed` as for load_model).
local function load_source (src, name, seed)
  if src.kind == "lua" then return load_model(src.path, name, seed) end
  local cpfg = require "lsys.cpfg"
  local ok, m
  if src.kind == "object" then ok, m = pcall(cpfg.load_object, src.path, src.lopts)
  else ok, m = pcall(cpfg.load, src.path, src.vfile, src.lopts) end
  if not ok then      -- the loader names the file and line; its own name is no news
    error((tostring(m):gsub("^lsys%.view%.load: ", ""):gsub("^lsys%.cpfg%.%a+: ", "")), 0)
  end
  return m
end

-- The files a model comes from, for `lsys view` to watch: the Lua file; or the .l file,
-- the files it includes, the view file and the palette.
local function source_files (src)
  if src.kind == "lua" then return { src.path } end
  local cpfg, cpp = require "lsys.cpfg", require "lsys.cpfg.cpp"
  local files, seen = {}, {}
  local function add (f) if f and not seen[f] then seen[f] = true; files[#files + 1] = f end end
  local l, v, pal = src.path, src.vfile, src.lopts.colormap or src.lopts.materials
  if src.kind == "object" then
    add(src.path .. "/specifications")
    local ok, l2, v2, p2 = pcall(cpfg.object_files, src.path)
    if not ok then return files end
    l, v, pal = l2, v2, pal or p2
  end
  -- the files it #includes, in every branch of #if (a missing one is no obstacle); only the
  -- model's own files, as its preprocessing reads (never /dev/zero or /etc/shadow)
  local function scan (file, depth)
    if seen[file] or depth > 32 then return end
    if depth > 0 and not cpp.ismodelfile(l, file) then return end
    add(file)
    local text = cpp.readfile(file)
    for inc in (text or ""):gmatch('#%s*include%s*"([^"\n]+)"') do
      scan(inc:sub(1, 1) == "/" and inc or cpp.dirof(file) .. "/" .. inc, depth + 1)
    end
  end
  scan(l, 0)
  add(v)
  if pal then add(pal:sub(1, 1) == "/" and pal or cpp.dirof(l) .. "/" .. pal) end
  return files
end

-- }===========================================================================================


-- {===========================================================================================
-- Commands

local commands = {}

-- The options of the commands that load a model (model_source, prepare) and then the
-- command's own: `extra` (false: an option the command does not take), with -h for --help
-- and, when it has --output, -o for it.
local function model_opts (extra)
  local o = { steps = "value", seed = "value", set = "list", name = "value", view = "list",
              map = "value", mat = "value", define = "list", environment = "value",
              help = "flag", short = { h = "help", o = extra.output and "output" or nil } }
  for k, v in pairs(extra) do o[k] = v or nil end
  return o
end

local DERIVE_OPTS = model_opts { stats = "flag", progress = "flag", view = false }

local RENDER_OPTS = model_opts {
  output = "value", size = "value", progress = "flag", lines = "value", frames = "value",
  every = "value",
}

-- The number of each module name in 's', as a sorted list of { name, count }.
local function module_counts (s)
  local counts = {}
  local ok, f = pcall(function () return s.counts end)
  if ok and type(f) == "function" then  -- a C-side count when the Lstring has one
    counts = f(s)
  else
    for _, name in s:modules() do counts[name] = (counts[name] or 0) + 1 end
  end
  local list = {}
  for name, n in pairs(counts) do list[#list + 1] = { name, n } end
  table.sort(list, function (a, b) return a[1] < b[1] end)
  return list
end

-- A value given on the command line: a number, a list of numbers (1,2,3), a boolean, or text.
local function value (v)
  local n = tonumber(v)
  if n ~= nil then return math.tointeger(n) or n end
  if v == "true" then return true elseif v == "false" then return false end
  if v:find("^[-+%d.eE]+,[-+%d.eE,]+$") then
    local l = {}
    for x in v:gmatch("[^,]+") do
      l[#l + 1] = tonumber(x)
      if l[#l] == nil then return v end
    end
    return l
  end
  return v
end

-- Applies --set NAME=VALUE to the model's env, warning about a name the model has no variable
-- of (a misspelt name would otherwise change nothing without a word).
local function set_env (model, sets, src)
  if model.env == nil then model.env = {} end
  local names = {}
  for k in pairs(model.env) do
    if type(k) == "string" then names[#names + 1] = k end
  end
  table.sort(names)
  for _, kv in ipairs(sets) do
    if model.env[kv[1]] == nil then
      local have = #names == 0 and "the model has no variables (its env is empty)"
        or "the model's variables: " .. table.concat(names, ", ")
      if src.kind ~= "lua" then
        have = have .. "; the preprocessor replaces a #define's name by its value, and "
          .. "`lsys import` writes a model file whose #defines of numbers are variables"
      end
      require("lsys.warning").warn(format("lsys: --set %s: the model has no variable %s (%s)",
        kv[1], kv[1], have))
    end
    model.env[kv[1]] = kv[2]
  end
end

-- Checks each --view NAME=VALUE as the model's view will, so that a wrong one is blamed on
-- the option rather than on the model file.
local function check_views (cmd, model, vlist)
  local view = require "lsys.view"
  local dir = type(model.view) == "table" and model.view.dir or nil
  for _, e in ipairs(vlist) do
    local k, s = e[1], e[2]
    local ok, err = pcall(view.normalize, { [k] = value(s:match("=(.*)$")), dir = dir }, "")
    if not ok then
      err = tostring(err):gsub("^: ", ""):gsub("'view%.", "'")
      usage(cmd, "--view %s: %s", s, err)
    end
  end
end

-- Loads the model named by the positional arguments and applies --steps --seed --set.
local function prepare (cmd, opts, pos)
  local src = model_source(cmd, opts, pos)
  local steps, seed
  if opts.steps ~= nil then
    steps = math.tointeger(tonumber(opts.steps))
    if steps == nil or steps < 0 then
      usage(cmd, "--steps expects a non-negative integer, got '%s'", opts.steps)
    end
    local limit = require("lsys.model").MAX_STEPS
    if steps > limit then
      usage(cmd, "--steps %s is more than the limit of %d steps", opts.steps, limit)
    end
  end
  if opts.seed ~= nil then
    seed = tonumber(opts.seed)
    if seed == nil then usage(cmd, "--seed expects a number, got '%s'", opts.seed) end
    seed = math.tointeger(seed) or seed
  end
  local sets = {}
  for _, s in ipairs(opts.set or {}) do
    local k, v = s:match("^([%a_][%w_]*)=(.*)$")
    if k == nil then usage(cmd, "--set expects NAME=VALUE, got '%s'", s) end
    local n = tonumber(v)
    if n == nil or n ~= n or n == math.huge or n == -math.huge then
      usage(cmd, "--set %s: the value must be a finite number, got '%s'", k, v)
    end
    sets[#sets + 1] = { k, math.tointeger(n) or n }
  end
  local views, vlist = {}, {}
  for _, s in ipairs(opts.view or {}) do
    local k, v = s:match("^([%a_][%w_]*)=(.*)$")
    if k == nil then usage(cmd, "--view expects NAME=VALUE, got '%s'", s) end
    views[k] = value(v)
    vlist[#vlist + 1] = { k, s }
  end

  local path = src.path
  local model = load_source(src, opts.name, seed)
  if require("lsys.model").isscene(model) then     -- a file returning a population
    if cmd ~= "render" and cmd ~= "export" or opts.frames ~= nil then
      error(format("%s returns a Scene (a population, lsys.population): `lsys render` and "
        .. "`lsys export` take it", path), 0)
    end
    if steps ~= nil or seed ~= nil or #sets > 0 or #vlist > 0 then
      usage(cmd, "%s returns a Scene (a population): --steps, --seed, --set and --view "
        .. "apply to a model", path)
    end
    return model, path, views, src
  end
  if model.components ~= nil and model.components.tree ~= nil and
     (steps ~= nil or #sets > 0) then
    usage(cmd, "%s is a component graph: it has no derivation steps (--steps) nor "
      .. "variables (--set)", path)
  end
  if steps ~= nil then model.steps = steps end
  if seed ~= nil then model.seed = seed end
  if #sets > 0 then set_env(model, sets, src) end
  check_views(cmd, model, vlist)
  return model, path, views, src
end

-- Derives the model, with progress on stderr when asked or when stderr is a terminal.
local function derive (model, opts)
  if opts.progress or isatty(2) then
    local function progress (step, nsteps, nmodules)
      io.stderr:write(format("step %d/%d: %d modules\n", step, nsteps, nmodules))
      io.stderr:flush()
    end
    return model:derive(model.steps, { progress = progress })
  end
  return model:derive()
end

function commands.derive (args)
  local opts, pos = parse("derive", DERIVE_OPTS, args, 2)
  if opts.help then out(HELP.derive) return 0 end
  local model = prepare("derive", opts, pos)

  local t0 = clock()
  local s = derive(model, opts)
  local elapsed = clock() - t0

  if not opts.stats then
    out(tostring(s), "\n")
    return 0
  end
  local counts = module_counts(s)
  local width = 1
  for _, c in ipairs(counts) do width = math.max(width, #c[1]) end
  out(format("steps %s\n", tostring(model.steps or 0)))
  out(format("modules %d\n", #s))
  for _, c in ipairs(counts) do out(format("  %-" .. width .. "s %d\n", c[1], c[2])) end
  out(format("time %.3f s\n", elapsed))
  return 0
end

-- Derives and interprets the model of a render or export command line.
local function scene_of (cmd, opts, pos)
  local model, path, views = prepare(cmd, opts, pos)
  local verbose = opts.progress or isatty(2)
  if require("lsys.model").isscene(model) then return model, path, views, verbose end
  local s = derive(model, opts)
  local t0 = clock()
  local scene = model:interpret(s, views)
  if verbose then
    io.stderr:write(format("interpreted %d modules: %d triangles, %d lines (%.2f s)\n", #s,
      scene.ntriangles, scene.nlines, clock() - t0))
  end
  return scene, path, views, verbose
end

-- --size WxH (nil when absent).
local function size_opt (cmd, s)
  if s == nil then return nil end
  local w, h = s:match("^(%d+)[xX](%d+)$")
  w, h = tonumber(w), tonumber(h)
  if w == nil or w < 1 or h < 1 or w > 16384 or h > 16384 then
    usage(cmd, "--size expects WxH (1 to 16384 each), got '%s'", s)
  end
  return w, h
end

-- The file a command writes without -o: the model's name (a folder's, a file's without its
-- extension) with `ext`, in the current directory; `default` without MODEL.
local function default_output (pos, ext, default)
  local name = pos[1] and pos[1]:gsub("/+$", "")
  if name == nil then return default end
  local base = name:match("([^/]*)$")
  if not isdir(name) then base = base:match("^(.+)%.[^.]*$") or base end
  return (base ~= "" and base or "model") .. ext
end

-- A whole number option (at least 'lo'; nil when absent).
local function int_opt (cmd, name, v, lo)
  if v == nil then return nil end
  local n = math.tointeger(tonumber(v))
  if n == nil or n < lo then
    usage(cmd, "--%s expects a whole number >= %d, got '%s'", name, lo, v)
  end
  return n
end

-- Minutes and seconds.
local function mmss (t)
  t = math.max(0, math.floor(t + 0.5))
  return format("%d:%02d", t // 60, t % 60)
end

--[[
The progress(phase, k, n, detail) of lsys.frames and lsys.animate for a command line: on a
terminal a line redrawn in place (the step derived; then the frame, a bar, the time taken
and the time left); elsewhere, with --progress, a plain line for each; else nil.
]]
local function frames_progress (opts)
  local tty = isatty(2)
  if not tty and not opts.progress then return nil end
  local err, t0 = io.stderr, clock()
  return function (phase, k, n, detail, step)
    if phase == "derive" then
      err:write(format(tty and "\rderiving: step %d/%d, %d modules\27[K" or
                       "step %d/%d: %d modules\n", k, n, detail))
    elseif phase == "frame" and k == 0 then
      t0 = clock()
      if tty then err:write(format("\rframe 0/%d\27[K", n)) end
    elseif phase == "frame" then
      local spent = clock() - t0
      if tty then
        local fill = math.floor(24 * k / n)
        err:write(format("\rframe %d/%d [%s%s] %s, %s left\27[K%s", k, n, ("#"):rep(fill),
          ("."):rep(24 - fill), mmss(spent), mmss(spent / k * (n - k)), k == n and "\n" or ""))
      else
        err:write(format("frame %d/%d: step %d (%.1f s)\n", k, n, step, spent))
      end
    elseif phase == "encode" then
      err:write(format("encoding %s with ffmpeg\n", detail))
    end
    err:flush()
  end
end

-- A message of lsys.frames or lsys.animate for the command line: without where in lsys it
-- was raised and the function's name.
local function frames_error (err)
  return (tostring(err):gsub("^[^:\n]*%.lua:%d+: ", ""):gsub("^lsys%.%a+: ", ""))
end

-- `lsys render MODEL --frames DIR`: one picture per step through one camera.
local function render_frames (opts, pos, w, h)
  local every = int_opt("render", "every", opts.every, 1)
  local model, _, views = prepare("render", opts, pos)
  local t0 = clock()
  local ok, files, steps = pcall(require("lsys").frames, model, {
    dir = opts.frames, every = every, width = w, height = h,
    view = next(views) and views or nil, progress = frames_progress(opts),
  })
  if not ok then error(frames_error(files), 0) end
  local function base (f) return f:match("([^/]*)$") end
  out(format("wrote %d picture%s of steps %d to %d to %s (%s%s, %dx%d, one camera) in %.1f s\n",
    #files, #files == 1 and "" or "s", steps[1], steps[#steps], opts.frames, base(files[1]),
    #files > 1 and " to " .. base(files[#files]) or "", w, h, clock() - t0))
  return 0
end

function commands.render (args)
  local opts, pos = parse("render", RENDER_OPTS, args, 2)
  if opts.help then out(HELP.render) return 0 end
  if opts.lines ~= nil then usage("render", "--lines applies to export only") end
  local w, h = size_opt("render", opts.size)
  w, h = w or 800, h or 800
  if opts.frames ~= nil then
    if opts.output ~= nil then
      usage("render", "--frames DIR writes one picture per step and -o one picture: "
        .. "give one of them")
    end
    if opts.frames == "" then usage("render", "--frames expects a folder, got ''") end
    return render_frames(opts, pos, w, h)
  end
  if opts.every ~= nil then usage("render", "--every applies to --frames") end
  local outpath = opts.output or default_output(pos, ".png", "tree.png")
  if not outpath:lower():find("%.png$") then
    usage("render", "the output must be a .png file, got '%s'", outpath)
  end
  local scene, _, _, verbose = scene_of("render", opts, pos)
  local lsys = require "lsys"
  local t0 = clock()
  lsys.render(scene, { out = outpath, width = w, height = h })
  if verbose then
    io.stderr:write(format("rendered %dx%d in %.2f s\n", w, h, clock() - t0))
  end
  out(format("wrote %s (%dx%d, %d triangles, %d lines)\n", outpath, w, h, scene.ntriangles,
    scene.nlines))
  return 0
end

local ANIMATE_OPTS = model_opts {
  output = "value", size = "value", fps = "value", every = "value", hold = "value",
  progress = "flag",
}

-- `lsys animate MODEL -o OUT.mp4|OUT.gif`: the model growing, through ffmpeg.
function commands.animate (args)
  local opts, pos = parse("animate", ANIMATE_OPTS, args, 2)
  if opts.help then out(HELP.animate) return 0 end
  local w, h = size_opt("animate", opts.size)
  local outpath = opts.output or default_output(pos, ".mp4", "tree.mp4")
  local ext = (outpath:match("%.(%w+)$") or ""):lower()
  if ext ~= "mp4" and ext ~= "gif" then
    usage("animate", "the output must be an .mp4 video or a .gif animation, got '%s' (for "
      .. "PNG pictures: lsys render MODEL --frames DIR)", outpath)
  end
  local every = int_opt("animate", "every", opts.every, 1)
  local fps = opts.fps and tonumber(opts.fps)
  if opts.fps ~= nil and not (fps and fps > 0 and fps <= 1000) then
    usage("animate", "--fps expects frames a second in (0, 1000], got '%s'", opts.fps)
  end
  local hold = opts.hold and tonumber(opts.hold)
  if opts.hold ~= nil and not (hold and hold >= 0 and hold <= 3600) then
    usage("animate", "--hold expects seconds from 0 to 3600, got '%s'", opts.hold)
  end
  local model, _, views = prepare("animate", opts, pos)
  local t0 = clock()
  local ok, r, n, fw, fh = pcall(require("lsys").animate, model, {
    out = outpath, fps = fps, hold = hold, every = every, width = w, height = h,
    view = next(views) and views or nil, progress = frames_progress(opts),
  })
  if not ok then error(frames_error(r), 0) end
  local held = hold and hold > 0 and format(", the last held %g s", hold) or ""
  out(format("wrote %s (%d frame%s, %dx%d, %g a second%s) in %.1f s\n", r, n,
    n == 1 and "" or "s", fw, fh, fps or require("lsys.frames").FPS, held, clock() - t0))
  return 0
end

function commands.export (args)
  local opts, pos = parse("export", RENDER_OPTS, args, 2)
  if opts.help then out(HELP.export) return 0 end
  if opts.size ~= nil then usage("export", "--size applies to render only") end
  if opts.frames ~= nil or opts.every ~= nil then
    usage("export", "--frames and --every apply to render only")
  end
  if #pos == 0 then usage("export", "a MODEL is required") end
  local outpath = opts.output
  if outpath == nil then usage("export", "-o OUT.obj, OUT.ply or OUT.glb is required") end
  local ext = outpath:lower():match("%.(%w+)$")
  if ext ~= "obj" and ext ~= "ply" and ext ~= "glb" then
    usage("export", "the output must end in .obj, .ply or .glb, got '%s'", outpath)
  end
  if opts.lines ~= nil and opts.lines ~= "lines" and opts.lines ~= "tubes" then
    usage("export", "--lines expects 'lines' or 'tubes', got '%s'", opts.lines)
  end
  local scene = scene_of("export", opts, pos)
  scene:save(outpath, { lines = opts.lines })
  out(format("wrote %s (%d vertices, %d triangles, %d lines%s)\n", outpath, scene.nvertices,
    scene.ntriangles, scene.nlines, opts.lines == "tubes" and " as tubes" or ""))
  return 0
end

local VIEW_OPTS = model_opts {
  size = "value", step = "value", rate = "value", screenshot = "value",
  ["no-status"] = "flag", last = "flag", history = "value",
}

-- --step, --rate and --screenshot of `lsys view`.
local function view_opts (opts)
  local step, rate
  if opts.step ~= nil then
    step = math.tointeger(tonumber(opts.step))
    if step == nil or step < 0 then
      usage("view", "--step expects a step number (0 or more), got '%s'", opts.step)
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
    local ok, r = pcall(require("lsys.model").parse_size, opts.history, "--history")
    if not ok then usage("view", "%s", (tostring(r):gsub("^[^\n]-:%d+: ", ""))) end
    history = r
  end
  if opts.last and opts.step ~= nil then usage("view", "--last and --step exclude each other") end
  return step, rate, shot, history
end

-- Handles the window's events until it is closed (or Ctrl-C); a change of one of the
-- files files() lists (its time or size, stable for 0.1 s) calls reload(), after which
-- the list is asked again. Closes the window.
local function watch (V, files, reload)
  local core = require "lsys.core"
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

function commands.view (args)
  local opts, pos = parse("view", VIEW_OPTS, args, 2)
  if opts.help then out(HELP.view) return 0 end
  local w, h = size_opt("view", opts.size)
  local step, rate, shot, history = view_opts(opts)
  local V = require "lsys.viewer"
  local print_pick = require("lsys.repl").print_pick
  local src = model_source("view", opts, pos)
  local path = src.path:gsub("/+$", "")
  local verbose = isatty(2)

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
        error(format("--step %d: the model has %d steps", first, model.steps), 0)
      end
      V.show(model, {
        width = w, height = h, step = first, rate = rate, keep_camera = keep or nil,
        steps = not opts.last, history = history,
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
    io.stderr:write("lsys: ", tostring(err), "\n")
    V.open { width = w, height = h, status = not opts["no-status"] }
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

local ARRANGE_OPTS = model_opts {
  size = "value", output = "value", string = "value", r0 = "value", s0u = "value",
  s0h = "value",
}

function commands.arrange (args)
  local opts, pos = parse("arrange", ARRANGE_OPTS, args, 2)
  if opts.help then out(HELP.arrange) return 0 end
  local w, h = size_opt("arrange", opts.size)
  local aopts = {}
  for _, k in ipairs { "r0", "s0u", "s0h" } do
    if opts[k] ~= nil then
      aopts[k] = tonumber(opts[k])
      if aopts[k] == nil or not (aopts[k] > 0) then
        usage("arrange", "--%s expects a number > 0, got '%s'", k, opts[k])
      end
    end
  end
  local model, path, views = prepare("arrange", opts, pos)
  if next(views) then aopts.view = views end
  local s
  if opts.string then
    local f, err = io.open(opts.string)
    if f == nil then error(format("cannot open '%s': %s", opts.string, tostring(err)), 0) end
    local text = f:read("a")
    f:close()
    local ok, r = pcall(model.lstring, model, (text:gsub("%s+$", "")))
    if not ok then error(format("%s: %s", opts.string, tostring(r)), 0) end
    s = r
  else
    s = derive(model, opts)
  end
  local lsys = require "lsys"
  local arr = lsys.arrange(model, s, aopts)
  local outpath = opts.output or ((path:match("([^/]-)%.?[^./]*$") or "model") .. "-arranged.txt")
  require("lsys.arrange_ui").run(arr, { out = outpath, width = w, height = h,
                                        title = "arrange " .. path:match("([^/]*)$") })
  return 0
end

local SKETCH_OPTS = {
  size = "value", nodes = "value", phyllotaxis = "value", output = "value", help = "flag",
  short = { h = "help", o = "output" },
}

-- --nodes and --phyllotaxis of `lsys sketch` as lsys.sketch.load options.
local function sketch_load_opts (opts)
  local lo = {}
  if opts.nodes ~= nil then
    lo.nodes_per_layer = math.tointeger(tonumber(opts.nodes))
    if lo.nodes_per_layer == nil or lo.nodes_per_layer < 1 or lo.nodes_per_layer > 10000 then
      usage("sketch", "--nodes expects a whole number from 1 to 10000, got '%s'", opts.nodes)
    end
  end
  if opts.phyllotaxis ~= nil then
    local p = opts.phyllotaxis
    if p ~= "distichous" and p ~= "decussate" and p ~= "fibonacci" then
      usage("sketch", "--phyllotaxis expects distichous, decussate or fibonacci, got '%s'", p)
    end
    lo.phyllotaxis = p
  end
  return lo
end

local sketch_file_write

-- `lsys sketch plot|model|render FILE -o OUT`.
local function sketch_file_command (sub, opts, pos)
  if #pos < 2 then usage("sketch", "%s: a sketch FILE is required", sub) end
  if #pos > 2 then usage("sketch", "unexpected argument '%s'", pos[3]) end
  local file = pos[2]
  local ext = sub == "model" and ".lua" or ".png"
  local outpath = opts.output or ((file:match("([^/]-)%.?[^./]*$") or "sketch") ..
                                  (sub == "plot" and "-functions" or "") .. ext)
  if not outpath:lower():find("%" .. ext .. "$") then
    usage("sketch", "%s: the output must be a %s file, got '%s'", sub, ext, outpath)
  end
  local lo = sketch_load_opts(opts)
  local w, h = size_opt("sketch", opts.size)
  if sub == "model" and w then usage("sketch", "model: --size applies to plot and render") end
  local sketch = require "lsys.sketch"
  local ok, err = pcall(function ()
    local sk = sketch.load(file, lo)
    sketch_file_write(sub, sk, outpath, w, h)
  end)
  -- the pipeline's messages name the file and the stroke; where in lsys they were raised
  -- is no news to the user
  if not ok then error((tostring(err):gsub("^[^:\n]*%.lua:%d+: ", "")), 0) end
  return 0
end

-- Writes what `lsys sketch plot|model|render` makes of the Sketch sk.
function sketch_file_write (sub, sk, outpath, w, h)
  if sub == "plot" then
    require("lsys.sketch.plot").png(sk, outpath, { width = w or 900, height = h or 600 })
    out(format("wrote %s\n", outpath))
  elseif sub == "model" then
    sk:save_model(outpath)
    out(format("wrote %s\n", outpath))
  else
    local m = sk:model {}
    local scene = m:interpret(m:derive())
    require("lsys").render(scene, { out = outpath, width = w or 800, height = h or 800 })
    out(format("wrote %s (%dx%d, %d triangles, %d lines)\n", outpath, w or 800, h or 800,
      scene.ntriangles, scene.nlines))
  end
end

function commands.sketch (args)
  local sub = args[2]
  local opts, pos = parse("sketch", SKETCH_OPTS, args, 2)
  if opts.help then out(HELP.sketch) return 0 end
  if sub == "plot" or sub == "model" or sub == "render" then
    return sketch_file_command(sub, opts, pos)
  end
  if #pos > 1 then usage("sketch", "unexpected argument '%s' (one FILE at most)", pos[2]) end
  local w, h = size_opt("sketch", opts.size)
  local lo = sketch_load_opts(opts)
  if opts.output ~= nil then usage("sketch", "-o applies to plot, model and render") end
  require("lsys.sketch.window").run {
    file = pos[1], nodes = lo.nodes_per_layer, phyllotaxis = lo.phyllotaxis,
    window = w and { w, h } or nil, out = out,
  }
  return 0
end

local COMPONENTS_OPTS = { output = "value", params = "flag", help = "flag",
                          short = { h = "help", o = "output" } }

-- `lsys components graph MODEL -o OUT`: the model file returns a component graph's root.
function commands.components (args)
  local sub = args[2]
  local opts, pos = parse("components", COMPONENTS_OPTS, args, 2)
  if opts.help then out(HELP.components) return 0 end
  if sub ~= "graph" then
    usage("components", sub == nil and "a subcommand is required (graph)" or
      "unknown subcommand '%s' (known: graph)", sub)
  end
  if #pos < 2 then usage("components", "graph: a MODEL is required") end
  if #pos > 2 then usage("components", "unexpected argument '%s'", pos[3]) end
  local outpath = opts.output or ((pos[2]:match("([^/]-)%.?[^./]*$") or "model") .. "-graph.png")
  local ext = (outpath:match("%.([^./]+)$") or ""):lower()
  if ext ~= "png" and ext ~= "svg" and ext ~= "pdf" and ext ~= "dot" and ext ~= "gv" then
    usage("components", "graph: the output must be a .png, .svg, .pdf or .dot file, got '%s'",
      outpath)
  end
  local path = find_model(pos[2])
  local chunk, err = loadfile(path, "t")
  if chunk == nil then error(err, 0) end
  local ok, root = require("lsys.model").runfile(path, chunk)
  if not ok then
    local msg = tostring(root)
    error(msg:find(path, 1, true) and msg or path .. ": " .. msg, 0)
  end
  local okp, kind, links = pcall(function () return root.kind, root.links end)
  if not okp or type(kind) ~= "string" or type(links) ~= "table" then
    error(format("%s returned %s, not a component graph (end the file with `return` and the "
      .. "root prototype, e.g. `return plant`)", path, type(root)), 0)
  end
  local graph = require "lsys.components.graph"
  local rok, rerr = pcall(graph.render, root, outpath, { params = opts.params or nil })
  if not rok then     -- the message names the item; graph.lua's line is no news to the user
    rerr = tostring(rerr):gsub("^[^:\n]*%.lua:%d+: ", ""):gsub("^graph%.render: ", "")
    error(format("%s: %s", path, rerr), 0)
  end
  out(format("wrote %s\n", outpath))
  return 0
end

local GROW_OPTS = {
  ticks = "value", seed = "value", rate = "value", size = "value", screenshot = "value",
  frames = "value", every = "value", help = "flag", short = { h = "help" },
}

-- `lsys grow FILE`: the world live in the window, or --frames DIR.
function commands.grow (args)
  local opts, pos = parse("grow", GROW_OPTS, args, 2)
  if opts.help then out(HELP.grow) return 0 end
  if #pos == 0 then usage("grow", "a FILE is required (try examples/grow/forest.lua)") end
  if #pos > 1 then usage("grow", "unexpected argument '%s' (one FILE)", pos[2]) end
  local w, h = size_opt("grow", opts.size)
  w, h = w or 1000, h or 600
  local ticks = int_opt("grow", "ticks", opts.ticks, 0)
  local seed = int_opt("grow", "seed", opts.seed, 0)
  local every = int_opt("grow", "every", opts.every, 1)
  local rate = opts.rate and tonumber(opts.rate)
  if opts.rate ~= nil and not (rate and rate > 0 and rate <= 1000) then
    usage("grow", "--rate expects ticks a second in (0, 1000], got '%s'", opts.rate)
  end
  if opts.screenshot and not opts.screenshot:lower():find("%.png$") then
    usage("grow", "the screenshot must be a .png file, got '%s'", opts.screenshot)
  end
  if opts.frames and (opts.screenshot or opts.rate) then
    usage("grow", "--frames draws no window: --screenshot and --rate do not apply")
  end
  if every and not opts.frames then usage("grow", "--every applies to --frames") end
  local path = find_model(pos[1])
  local function load ()
    local chunk, err = loadfile(path, "t")
    if chunk == nil then error(err, 0) end
    local ok, v = require("lsys.model").runfile(path, chunk)
    if not ok then
      local msg = tostring(v)
      error(msg:find(path, 1, true) and msg or path .. ": " .. msg, 0)
    end
    return v
  end
  local GV = require "lsys.growview"
  local make = GV.maker(load(), path, { seed = seed }, load)
  local t0 = clock()
  if opts.frames then
    local verbose = isatty(2)
    local n, last = GV.frames(make, opts.frames, {
      ticks = ticks, every = every, width = w, height = h,
      progress = verbose and function (k, total)
        io.stderr:write(format("\rtick %d/%d", k, total))
        if k == total then io.stderr:write("\n") end
      end or nil,
    })
    out(format("wrote %d pictures to %s (the last: %s) in %.1f s\n", n, opts.frames, last,
      clock() - t0))
    return 0
  end
  local r = GV.live(make, { ticks = ticks, rate = rate, width = w, height = h,
                            screenshot = opts.screenshot, title = pos[1] })
  if r.screenshot then
    out(format("wrote %s: %d limbs after %d ticks; the window drew %d frames in %.2f s "
      .. "(%.1f frames a second) while growing\n", r.screenshot, r.limbs, r.ticks, r.drawn,
      r.seconds, r.fps))
    if r.full then
      out(format("at %d limbs (the last %d ticks): %d frames in %.2f s, %.1f frames a second; "
        .. "a frame drawn in %.1f ms\n", r.full.limbs, r.full.ticks, r.full.drawn,
        r.full.seconds, r.full.fps, r.drawms))
    end
  end
  return 0
end

local IMPORT_OPTS = {
  output = "value", map = "value", mat = "value", define = "list", environment = "value",
  help = "flag",
  short = { h = "help", o = "output" },
}

-- `lsys import MODEL.l [VIEW.v] -o OUT.lua`: the cpfg model as an lsys model file.
function commands.import (args)
  local opts, pos = parse("import", IMPORT_OPTS, args, 2)
  if opts.help then out(HELP.import) return 0 end
  local arg = pos[1]
  if arg == nil then
    usage("import", "a cpfg MODEL (a .l file or a vlab object folder) is required")
  end
  if not arg:find("%.l$") and not isdir(arg) then
    usage("import", "'%s' is not a cpfg model: MODEL is a .l file or a vlab object folder", arg)
  end
  local outpath = opts.output
  if outpath == nil then usage("import", "-o OUT.lua is required: the lsys model file to write") end
  if not outpath:find("%.lua$") then
    usage("import", "the output must be a .lua file, got '%s'", outpath)
  end
  local src = model_source("import", opts, pos)
  local cpfg = require "lsys.cpfg"
  local l, v, lopts = src.path, src.vfile, src.lopts
  local ok, err = pcall(function ()
    if src.kind == "object" then
      local pal
      l, v, pal = cpfg.object_files(src.path)
      if pal and not lopts.colormap and not lopts.materials then
        if pal:match("%.mat$") then lopts.materials = pal else lopts.colormap = pal end
      end
    end
    require("lsys.cpfg.import").write(l, v, outpath, lopts)
  end)
  if not ok then
    error((tostring(err):gsub("^lsys%.view%.load: ", ""):gsub("^lsys%.cpfg%.%a+: ", "")), 0)
  end
  out(format("wrote %s\n", outpath))
  return 0
end

local BATCH_OPTS = {
  out = "value", shard = "value", list = "flag", force = "flag", progress = "flag",
  help = "flag", short = { h = "help", o = "out" },
}

--[[
The progress(ev) of lsys.batch.run for the command line: on a terminal a line redrawn in
place (jobs done, failures, jobs a second, the time left), at most ten times a second;
elsewhere, with --progress, a line per job. A job that fails is said in any case, with its
message.
]]
local function batch_progress (opts)
  local tty, err = isatty(2), io.stderr
  local drawn
  local function bar (ev)
    local n = ev.todo
    local fill = math.floor(24 * ev.done / n)
    local rate = ev.seconds > 0 and ev.done / ev.seconds or 0
    return format("\rbatch: %d/%d [%s%s] %d failed, %.1f jobs/s, %s left\27[K", ev.done, n,
      ("#"):rep(fill), ("."):rep(24 - fill), ev.failed, rate,
      rate > 0 and mmss((n - ev.done) / rate) or "-:--")
  end
  return function (ev)
    if ev.phase == "start" then
      if ev.skipped > 0 and (tty or opts.progress) then
        err:write(format("batch: %d of %d jobs done before, skipped (--force runs them "
          .. "again)\n", ev.skipped, ev.jobs))
      end
      if tty and ev.todo > 0 then err:write(bar(ev)) drawn = clock() end
    elseif ev.phase == "job" then
      local rec = ev.record
      if rec.status == "failed" then
        err:write(format("%slsys: batch: job %s (%s) failed: %s\n", tty and "\r\27[K" or "",
          rec.job, rec.line, rec.error))
        drawn = nil
      elseif not tty and opts.progress then
        err:write(format("job %s ok (%.2f s), %d/%d\n", rec.job, rec.seconds, ev.done,
          ev.todo))
      end
      if tty and (drawn == nil or clock() - drawn >= 0.1 or ev.done == ev.todo) then
        err:write(bar(ev))
        drawn = clock()
      end
    elseif ev.phase == "end" and tty and ev.todo > 0 then
      err:write("\n")
    end
    err:flush()
  end
end

-- `lsys batch SPEC --list`: the jobs of the shard, done or not.
local function batch_list (batch, spec, opts, shard)
  local p = batch.plan(spec, { out = opts.out, shard = shard })
  local STATUS = { done = "done", failed = "failed", todo = "to do" }
  local count = { done = 0, failed = 0, todo = 0 }
  for _, j in ipairs(p.jobs) do
    local vars = {}
    for k, v in pairs(j.params) do vars[#vars + 1] = format("%s=%s", k, tostring(v)) end
    table.sort(vars)
    if j.steps then table.insert(vars, 1, "steps=" .. j.steps) end
    if j.rep then vars[#vars + 1] = "rep=" .. j.rep end
    local outs = {}
    for i, o in ipairs(j.outputs) do outs[i] = o.path end
    out(format("%s  %-6s  seed %-10d  %s%s%s  -> %s\n", j.id, STATUS[j.status], j.seed,
      j.model, j.name and ":" .. j.name or "", #vars > 0 and "  " .. table.concat(vars, " ")
      or "", table.concat(outs, " ")))
    count[j.status] = count[j.status] + 1
  end
  out(format("%d job%s%s: %d done, %d failed, %d to do\n", #p.jobs, #p.jobs == 1 and "" or "s",
    p.n > 1 and format(" (shard %d/%d of %d)", p.k, p.n, p.total) or "", count.done,
    count.failed, count.todo))
  return 0
end

-- `lsys batch SPEC`: the jobs of a spec, or of one shard of them.
function commands.batch (args)
  local opts, pos = parse("batch", BATCH_OPTS, args, 2)
  if opts.help then out(HELP.batch) return 0 end
  if #pos == 0 then usage("batch", "a SPEC is required: a .csv or .lua file listing the jobs") end
  if #pos > 1 then usage("batch", "unexpected argument '%s' (one SPEC)", pos[2]) end
  if opts.out == "" then usage("batch", "--out expects a folder, got ''") end
  if opts.list and opts.force then usage("batch", "--list runs nothing: --force does not apply") end
  local batch = require "lsys.batch"
  local shard
  if opts.shard ~= nil then
    local k, n = batch.parse_shard(opts.shard)
    if k == nil then usage("batch", "--shard %s", n) end
    shard = { k, n }
  end
  -- the messages name the spec's file and line; the function's name is no news here
  local function unnamed (err) return (tostring(err):gsub("^lsys%.batch%.%a+: ", "")) end
  if opts.list then
    local ok, r = pcall(batch_list, batch, pos[1], opts, shard)
    if not ok then error(unnamed(r), 0) end
    return r
  end
  local ok, r = pcall(batch.run, pos[1], { out = opts.out, shard = shard,
                                           force = opts.force or nil,
                                           progress = batch_progress(opts) })
  if not ok then error(unnamed(r), 0) end
  local what = format("%s: %d job%s%s", pos[1], r.jobs, r.jobs == 1 and "" or "s",
    r.n > 1 and format(" (shard %d/%d of %d)", r.k, r.n, r.total) or "")
  local ran = r.ok + r.failed
  if ran == 0 then
    out(format("%s: %s\n", what, r.jobs == 0 and "nothing to do" or
      "all done before (--force runs them again)"))
    return 0
  end
  out(format("%s: %d ok, %d failed, %d done before; %d ran in %." .. (r.seconds < 10 and 2 or 1)
    .. "f s (%.1f jobs/s); manifest %s\n", what, r.ok, r.failed, r.skipped, ran, r.seconds,
    ran / math.max(r.seconds, 1e-9), r.manifest))
  return r.failed > 0 and 1 or 0
end

-- busted's options that take a value, so that `lsys test -t fast` does not read "fast" as a
-- path; and those that choose the specs themselves (a folder, a .busted file, a run in it).
local BUSTED_VALUE, BUSTED_ROOT = {}, {}
for o in ("o output C directory f config-file coverage-config-file t tags exclude-tags "
          .. "filter filter-out m lpath cpath r run repeat seed lang loaders helper lua p "
          .. "pattern exclude-pattern e Xoutput Xhelper"):gmatch("%S+") do
  BUSTED_VALUE[o] = true
end
for o in ("C directory f config-file r run"):gmatch("%S+") do BUSTED_ROOT[o] = true end

function commands.test (args)
  local bargs = { [0] = G.arg ~= nil and G.arg[0] or "lsys", "--ignore-lua" }
  local paths, chosen = 0, false
  local i = 2
  while i <= args.n do
    local a = args[i]
    bargs[#bargs + 1] = a
    local name, val = a:match("^%-%-?([^=]+)(=?)")
    if a == "-h" or a == "--help" then out(HELP.test) return 0 end
    if a == "--" then
      for j = i + 1, args.n do bargs[#bargs + 1] = args[j] end
      paths = paths + args.n - i
      break
    elseif name == nil or a == "-" then
      paths = paths + 1
    else
      chosen = chosen or BUSTED_ROOT[name] ~= nil
      if val == "" and BUSTED_VALUE[name] and i < args.n then      -- `-t fast`
        i = i + 1
        bargs[#bargs + 1] = args[i]
      end
    end
    i = i + 1
  end
  if paths == 0 and not chosen and not isfile(".busted") and not isdir("spec") then
    bargs[#bargs + 1] = "."
  end
  local ok, runner = pcall(require, "busted.runner")
  if not ok then
    if tostring(runner):find("module 'busted.runner' not found", 1, true) then
      error("busted is not installed for Lua 5.4: apt-get install lua-busted (Debian, "
            .. "Ubuntu), or luarocks --lua-version 5.4 install busted", 0)
    end
    error("cannot load busted: " .. tostring(runner), 0)
  end
  -- busted reads the global `arg`, and names itself after the file of the function that
  -- calls its runner: a chunk called "lsys test". It exits the program itself (os.exit)
  -- when a test fails, and returns when all passed.
  G.arg = bargs
  G.load("(...)({ standalone = false })", "@lsys test")(runner)
  return 0
end

function commands.repl (args)
  local opts = parse("repl", { help = "flag", short = { h = "help" } }, args, 2)
  if opts.help then out(HELP.repl) return 0 end
  return require("lsys.repl").run()
end

function commands.help (args)
  local cmd = args[2]
  if cmd == nil then out(USAGE) return 0 end
  if HELP[cmd] == nil then usage(nil, "no help for '%s': not a command", cmd) end
  out(HELP[cmd])
  return 0
end

-- Runs the script 'path' ("-": stdin) with args[first+1..] as `arg` and `...`, like lua.c.
local function run_script (path, args, first)
  local chunk, err = loadfile(path ~= "-" and path or nil)
  if chunk == nil then error(err, 0) end
  local sarg = { [-1] = G.arg ~= nil and G.arg[0] or "lsys", [0] = path }
  for i = first + 1, args.n do sarg[#sarg + 1] = args[i] end
  G.arg = sarg
  chunk(table.unpack(sarg, 1, #sarg))
  return 0
end

-- }===========================================================================================


local function dispatch (args)
  local a = args[1]
  if a == nil then return require("lsys.repl").run() end
  if a == "-h" or a == "--help" then out(USAGE) return 0 end
  if a == "-v" or a == "--version" then
    out(format("lsys %s (%s)\n", host().version or "scm", G._VERSION))
    return 0
  end
  if commands[a] ~= nil then return commands[a](args) end
  if a == "-" then return run_script(a, args, 1) end
  if a:sub(1, 1) == "-" then usage(nil, "unknown option '%s'", a) end
  if isfile(a) then return run_script(a, args, 1) end
  if a:find("%.lua$") or a:find("/") then error(format("cannot open '%s'", a), 0) end
  usage(nil, "unknown command '%s'", a)
end

-- The folder holding lsys's own Lua modules (the one above this file's lsys/), as it
-- appears in error positions.
local SRCDIR = (debug.getinfo(1, "S").source:match("^@(.*)lsys[/\\]cli%.lua$"))

--- 'msg' without the positions in lsys's own sources that Lua put in it ("/usr/share/lsys/
-- lua/lsys/model.lua:123: "): a user's error names the user's file or the public function,
-- not where inside lsys it was raised (LSYS_DEBUG=1 keeps them, with a traceback).
function M.strip_internal (msg)
  if SRCDIR == nil or SRCDIR == "" then return msg end
  local dir = SRCDIR:gsub("%p", "%%%0")
  return (msg:gsub(dir .. "lsys[/\\][%w_/\\]*%.lua:%d+: ", ""))
end

local function handler (e)
  if getmetatable(e) == USAGE_ERROR then return e end
  local msg = e
  if type(msg) ~= "string" then
    local mt = getmetatable(e)
    msg = (mt ~= nil and mt.__tostring ~= nil) and tostring(e)
      or format("(error object is a %s value)", type(e))
  end
  if os.getenv("LSYS_DEBUG") ~= nil then return debug.traceback(msg, 2) end
  return M.strip_internal(msg)
end

--- Runs the command line `lsys ...` given its arguments (strings).
-- @return the exit status: 0 success, 1 error, 2 usage error
function M.main (...)
  -- The library's warnings (a view file's unsupported commands, a deprecated name) go
  -- through warn(), which Lua starts with off; the program shows them, as `lua -W` does.
  -- Called from another Lua, main leaves that to its host.
  if host().exe ~= nil then warn("@on") end
  local args = table.pack(...)
  local ok, r = xpcall(dispatch, handler, args)
  io.stdout:flush()
  if ok then return math.tointeger(r) or 0 end
  if getmetatable(r) == USAGE_ERROR then
    local prefix = r.cmd and ("lsys: " .. r.cmd .. ": ") or "lsys: "
    local more = r.cmd and format("Run 'lsys %s --help' for its options.", r.cmd)
      or "Run 'lsys --help' for the commands."
    io.stderr:write(prefix, r.msg, "\n", more, "\n")
    return 2
  end
  io.stderr:write("lsys: ", r, "\n")
  return 1
end

M.usage = USAGE
M.help = HELP

return M
