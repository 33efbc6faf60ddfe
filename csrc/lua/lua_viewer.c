/*
** Lua binding of the viewer window (viewer.h) and a file-change helper.
**
**   core.has_viewer                      true when built with the viewer
**   core.viewer_open([opts]) -> Viewer   opts: width, height (800), samples (4),
**                                        visible (true), status (true)
**   v:post(frames [, opts])              frames: list of { scene = Scene, step = n,
**                                        modules = n, render = lsys.render options,
**                                        world = widths in world units, take = move
**                                        the mesh out of the scene instead of copying };
**                                        opts: first (1-based), rate, title,
**                                        keep_camera, capture, textures = { Texture... },
**                                        live, fit = {x0, y0, z0, x1, y1, z1}, frames_dir
**                                        (where S saves every frame while animating),
**                                        light (the L key on or off: true computes the
**                                        first frame's light colours before posting);
**                                        a frame's lines = { { p0 =, p1 =, color = {r, g, b
**                                        [, a]}, width = px }... } are drawn over it
**   v:patch(scene [, opts]) -> serial    a live frame (post{..., live = true}) brought to
**                                        the scene's state: the vertex ranges it marked
**                                        since the last patch and what it appended;
**                                        opts: step, count, note (the status line)
**   v:poll([timeout]) -> event or nil    { type = "pick" | "miss" | "screenshot" |
**                                        "step" | "closed" | "key" | "drag" | "frames" |
**                                        "light" (the L key: on),
**                                        frame (1-based), step, module (1-based), kind, x,
**                                        y, path, ok, msg, key, ctrl, shift, phase; frames:
**                                        count, first, last (steps) };
**                                        with a layout also "pointer" (pane, phase "down" |
**                                        "move" | "up", button, x, y in the image's pixels,
**                                        ctrl, shift, pressure: a tablet pen's, in [0, 1],
**                                        when one is pressed) and "scroll" (pane, x, y, dy)
**   v:pending() -> n                     events waiting to be polled
**   v:screenshot([path])                 S key's screenshot of the next frame
**   v:key(name) -> serial                "right" "left" "home" "end" "space" "r" ...
**                                        "redraw"; drawn when state().serial >= serial
**   v:state() -> table                   open, drawn, serial, width, height, fbwidth,
**                                        fbheight, frame, nframes, playing, wireframe, light,
**                                        drawms (the time to draw a picture, smoothed);
**                                        after the first press on a pane pen (a pressure
**                                        device is read) and pen_devices (its names or
**                                        why there is none)
**   v:project({x, y, z}) -> x, y, depth  window coordinates with the last camera drawn
**   v:layout(lay) -> serial              panes beside the scene (vpanes.h): lay = { scene =
**                                        {x0, y0, x1, y1}, panes = { {x0, y0, x1, y1, bg =
**                                        {r, g, b}}... } } in fractions of the window, y
**                                        down; nil: the scene fills the window again
**   v:image(k, pixels, w, h) -> serial   an RGBA image (w * h * 4 bytes, top row first)
**                                        shown in pane k (1-based), copied
**   v:text(status [, help]) -> serial    the status line ("" the usual) and help text
**   v:light(k [, opts]) -> info          the light colours of frame k (vlight.h), computed
**                                        on this thread unless they were: { frame, leaves,
**                                        min, max, mean, msg (why none) }; opts: threads
**                                        (0: the default), max_memory (bytes); nil, msg
**                                        once the window is closed
**   v:colour(k, t) -> r, g, b            triangle t of frame k as the window draws it now
**                                        (its first vertex's diffuse colour, in [0, 1])
**   v:close()                            (also when collected)
**   core.light_ramp(x) -> r, g, b        the colour of light x on the L key's ramp
**   core.pen_devices() -> list           the X input devices: { id, name, pressure =
**                                        { min, max, value } for a tablet }; or nil, why
**   core.filestamp(path) -> mtime, size  or nil, message
**
** A posted snapshot is a deep copy (or, with take, the scene's own mesh):
** the window never reads Lua memory, so Lua may change or collect
** everything it posted while the window draws.
*/
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <limits.h>
#include <string.h>
#include <sys/stat.h>

#include "derive.h"
#include "light.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#ifndef LSYS_NO_VIEWER
#include "viewer.h"
#include "vlight.h"
#include "xpen.h"

typedef struct lviewer { lsys_viewer *v; } lviewer;

static lsys_viewer *checkviewer (lua_State *L, int idx) {
  lviewer *lv = (lviewer *)luaL_checkudata(L, idx, VIEWER_T);
  if (lv->v == NULL) luaL_error(L, "the viewer window is closed");
  return lv->v;
}

/* The options in the table at 't' (0: none): "viewer: opts.k must be ...". */
static lsys_opts vopts (int t) {
  lsys_opts o = {0, "viewer: opts.", "", LSYS_GOT_TYPE, 0};
  o.t = t;
  return o;
}

/* The options of core.viewer_open, from the table at 't' (0: none). */
static void readopenopts (lua_State *L, int t, lsys_viewer_opts *o) {
  lsys_opts vo = vopts(t);
  lsys_viewer_defaults(o);
  o->width = lsysL_optint(L, &vo, "width", o->width, 1, 16384);
  o->height = lsysL_optint(L, &vo, "height", o->height, 1, 16384);
  o->samples = lsysL_optint(L, &vo, "samples", o->samples, 0, 32);
  o->visible = lsysL_optbool(L, &vo, "visible", o->visible);
  o->status = lsysL_optbool(L, &vo, "status", o->status);
}

static int l_viewer_open (lua_State *L) {
  int t = lua_isnoneornil(L, 1) ? 0 : 1;
  lsys_viewer_opts o;
  lsys_error e;
  lviewer *lv;
  if (t) luaL_checktype(L, 1, LUA_TTABLE);
  readopenopts(L, t, &o);
  lv = (lviewer *)lua_newuserdatauv(L, sizeof *lv, 0);
  lv->v = NULL;
  luaL_setmetatable(L, VIEWER_T);
  if ((lv->v = lsys_viewer_open(&o, &e)) == NULL)
    return luaL_error(L, "%s", e.msg);
  return 1;
}

/* The pickable records of a frame (f->picks has room for all): what the
** turtle drew, as segments; 'world': widths in world units. */
static void setpicks (lsys_vframe *f, const lsys_scene *s, int world) {
  size_t k;
  for (k = 0; k < s->nrec; k++) {
    lsys_trec rec, *r = &rec;
    lsys_vpick *p = &f->picks[f->npicks];
    int i, kind = lsys_scene_reckind(s, k);
    if (kind == LSYS_REC_LABEL || kind == LSYS_REC_SYSTEM) continue;
    lsys_scene_record(s, k, &rec);
    for (i = 0; i < 3; i++) {
      p->p1[i] = r->p1[i];
      p->p0[i] = r->p1[i] - r->len * r->H[i];
    }
    p->radius = world || r->kind == LSYS_REC_SPHERE ? 0.5f * (r->w0 > r->w1 ? r->w0 : r->w1)
                                                     : 0;
    p->module = r->module;
    p->kind = r->kind;
    f->npicks++;
  }
}

/* A frame's lines = { { p0 =, p1 =, color =, width =, ontop = }... } from
** the list at 't'. */
static void readlines (lua_State *L, int t, lsys_vframe *f) {
  lua_Integer n = luaL_len(L, t), q;
  f->lines = (lsys_vline *)LSYS_MALLOC((size_t)(n > 0 ? n : 1) * sizeof *f->lines);
  if (f->lines == NULL) luaL_error(L, "not enough memory for the viewer");
  for (q = 1; q <= n; q++) {
    lsys_vline *ln = &f->lines[f->nlines];
    double c[4] = {1, 0, 0, 1};
    int i;
    if (lua_rawgeti(L, t, q) != LUA_TTABLE) luaL_error(L, "viewer:post: line %d is not a table", (int)q);
    for (i = 0; i < 3; i++) {
      lua_getfield(L, -1, "p0");
      lua_rawgeti(L, -1, i + 1);
      ln->p0[i] = (float)luaL_checknumber(L, -1);
      lua_pop(L, 2);
      lua_getfield(L, -1, "p1");
      lua_rawgeti(L, -1, i + 1);
      ln->p1[i] = (float)luaL_checknumber(L, -1);
      lua_pop(L, 2);
    }
    if (lua_getfield(L, -1, "color") == LUA_TTABLE)
      for (i = 0; i < 4; i++) {
        if (lua_rawgeti(L, -1, i + 1) == LUA_TNUMBER) c[i] = lua_tonumber(L, -1);
        lua_pop(L, 1);
      }
    lua_pop(L, 1);
    for (i = 0; i < 4; i++) ln->rgba[i] = (uint8_t)(255 * (c[i] < 0 ? 0 : c[i] > 1 ? 1 : c[i]) + 0.5);
    lua_getfield(L, -1, "width");
    ln->width = (float)luaL_optnumber(L, -1, 3);
    lua_getfield(L, -2, "ontop");
    ln->ontop = lua_toboolean(L, -1);
    lua_pop(L, 3);
    f->nlines++;
  }
}

/* A population's parts and instances into frame f, with the range of picks
** of each part (setpicks skips labels and system calls). */
static void setinstances (lua_State *L, lsys_vframe *f, const lsys_scene *s) {
  size_t np = s->nparts, p, r, k = 0;
  f->sc.parts = (lsys_part *)LSYS_MALLOC(np * sizeof *f->sc.parts);
  f->sc.inst = (lsys_instance *)LSYS_MALLOC(s->ninst * sizeof *f->sc.inst);
  f->partpicks = (size_t *)LSYS_MALLOC((np + 1) * sizeof *f->partpicks);
  if (f->sc.parts == NULL || f->sc.inst == NULL || f->partpicks == NULL)
    luaL_error(L, "not enough memory for the viewer");
  memcpy(f->sc.parts, s->parts, np * sizeof *f->sc.parts);
  memcpy(f->sc.inst, s->inst, s->ninst * sizeof *f->sc.inst);
  f->sc.nparts = f->sc.partcap = np;
  f->sc.ninst = f->sc.instcap = s->ninst;
  for (p = 0, r = 0; p < np; p++) {
    for (; r < s->parts[p].r0 && r < s->nrec; r++) {
      int kind = lsys_scene_reckind(s, r);
      k += kind != LSYS_REC_LABEL && kind != LSYS_REC_SYSTEM;
    }
    f->partpicks[p] = k;
  }
  f->partpicks[np] = f->npicks;
}

/* Fills frame f from the frame table at 'idx' (the caller's snapshot box
** frees what is allocated when this raises). */
static void readframe (lua_State *L, int idx, lsys_vframe *f) {
  lsys_opts fo = vopts(idx);
  const lsys_lscene *S;
  int take, world;
  if (lua_getfield(L, idx, "scene") == LUA_TNIL)
    luaL_error(L, "viewer:post: a frame without a scene");
  lsysL_checkscene(L, -1);
  take = lsysL_optbool(L, &fo, "take", 0);
  world = lsysL_optbool(L, &fo, "world", 0);
  f->step = lsysL_optint(L, &fo, "step", -1, -1, 1 << 30);
  if (lsysL_optfield(L, &fo, "modules", LUA_TNUMBER, "an integer")) {
    f->nmodules = (size_t)lua_tointeger(L, -1);
    lua_pop(L, 1);
  }
  S = lsysL_checkscene(L, -1);               /* after the options: they ran Lua code */
  f->picks = (lsys_vpick *)LSYS_MALLOC((S->sc.nrec > 0 ? S->sc.nrec : 1) * sizeof *f->picks);
  if (f->picks == NULL || lsys_scene_set_palette(&f->sc, S->sc.pal, S->sc.npal) != LSYS_OK)
    luaL_error(L, "not enough memory for the viewer");
  f->sc.cam = S->sc.cam;                  /* how the scene is to be looked at */
  f->sc.cull = S->sc.cull;
  memcpy(f->sc.light, S->sc.light, sizeof f->sc.light);
  memcpy(f->sc.lights, S->sc.lights, sizeof f->sc.lights);
  f->sc.nlights = S->sc.nlights;
  memcpy(f->sc.background, S->sc.background, sizeof f->sc.background);
  setpicks(f, &S->sc, world);
  if (lsys_vlight_leaves(f, &S->sc) != LSYS_OK)
    luaL_error(L, "not enough memory for the viewer");
  if (S->sc.ninst > 0) setinstances(L, f, &S->sc);
  if (lsysL_optfield(L, &fo, "lines", LUA_TTABLE, "a list of lines")) {
    readlines(L, lua_gettop(L), f);
    lua_pop(L, 1);
  }
  S = lsysL_checkscene(L, -1);               /* again: the lines ran Lua code */
  if (take) {                               /* the scene's own mesh */
    lsys_lscene *T = lsysL_checkscene(L, -1);
    lsysL_changescene(L, T);
    if (lsys_scene_detach_records(&T->sc) != LSYS_OK)   /* the records keep their points */
      luaL_error(L, "not enough memory for the viewer");
    f->sc.mesh = T->sc.mesh;
    lsys_mesh_init(&T->sc.mesh);
  }
  else if (lsys_mesh_copy(&f->sc.mesh, &S->sc.mesh) != LSYS_OK)
    luaL_error(L, "not enough memory for the viewer");
  lua_pop(L, 1);
}

/* The snapshot under construction, freed if an error interrupts it. */
typedef struct snapbox { lsys_vsnap *s; } snapbox;

static int snapbox_gc (lua_State *L) {
  snapbox *b = (snapbox *)lua_touserdata(L, 1);
  lsys_vsnap_free(b->s);
  b->s = NULL;
  return 0;
}

/* The light colours of frame k of 's' (not yet posted, or the last posted:
** its meshes stay while this thread does not post again), computed with
** 'threads' (0: the default) within 'limit' bytes: a new block, for the
** frame to own. A budget exceeded becomes the frame's message. */
static lsys_vlight *computelight (lua_State *L, const lsys_vsnap *s, size_t k, int threads,
                                  size_t limit) {
  lsys_meter mt = {0, 0, 0, NULL};
  lsys_vlight *l = (lsys_vlight *)LSYS_MALLOC(sizeof *l);
  lsys_error e;
  int st;
  if (l == NULL) luaL_error(L, "not enough memory for the viewer");
  mt.limit = limit;
  st = lsys_vlight_compute(l, &s->frames[k], s->live, threads > 0 ? threads :
                           lsys_derive_default_threads(), &mt, &e);
  if (st == LSYS_ENOMEM) {
    LSYS_FREE(l);
    luaL_error(L, "not enough memory for the viewer");
  }
  if (st != LSYS_OK) snprintf(l->msg, sizeof l->msg, "%s", e.msg);
  return l;
}

/* The options of v:post for the snapshot 's' of n frames, from the table
** at 't' (0: none). */
static void readpostopts (lua_State *L, int t, lsys_vsnap *s, int n) {
  lsys_opts po = vopts(t);
  const lsys_texture *const *tex;
  int ntex = 0, i;
  s->first = (size_t)lsysL_optint(L, &po, "first", n, 1, n) - 1;
  if (lsysL_optfield(L, &po, "rate", LUA_TNUMBER, "a number of frames per second")) {
    double r = lua_tonumber(L, -1);
    if (!(r > 0 && r <= 1000)) lsysL_opterror(L, &po, "rate", "in (0, 1000]");
    s->rate = r;
    lua_pop(L, 1);
  }
  if (lsysL_optfield(L, &po, "title", LUA_TSTRING, "a string")) {
    snprintf(s->title, sizeof s->title, "%s", lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  if (lsysL_optfield(L, &po, "frames_dir", LUA_TSTRING, "a folder's path")) {
    size_t len;
    const char *d = lua_tolstring(L, -1, &len);
    if (len == 0 || len >= sizeof s->framesdir) lsysL_opterror(L, &po, "frames_dir",
                                                               "a path of 1 to 511 bytes");
    memcpy(s->framesdir, d, len + 1);
    lua_pop(L, 1);
  }
  if (lsysL_optfield(L, &po, "light", LUA_TBOOLEAN, "a boolean")) {
    s->light = lua_toboolean(L, -1);
    lua_pop(L, 1);
  }
  s->sky = lsysL_optbool(L, &po, "sky", 0);
  s->ground = lsysL_optbool(L, &po, "ground", 0);
  s->keep_camera = lsysL_optbool(L, &po, "keep_camera", 0);
  s->capture = lsysL_optbool(L, &po, "capture", 0);
  s->live = lsysL_optbool(L, &po, "live", 0);
  if (s->live && n != 1) lsysL_opterror(L, &po, "live", "for one frame");
  if (lsysL_optfield(L, &po, "fit", LUA_TTABLE, "a box {x0, y0, z0, x1, y1, z1}")) {
    double box[6];
    size_t k;
    lsysL_readbox(L, lua_gettop(L), "viewer: opts.fit", box);
    for (k = 0; k < s->nframes; k++) {
      s->frames[k].sc.cam.has_box = 1;
      memcpy(s->frames[k].sc.cam.box, box, sizeof box);
    }
    lua_pop(L, 1);
  }
  tex = lsysL_opttextures(L, t, "viewer:post", &ntex);
  if (lsys_vsnap_textures(s, ntex) != LSYS_OK)
    luaL_error(L, "not enough memory for the viewer");
  for (i = 0; i < ntex; i++)
    if (lsys_texture_copy(&s->tex[i], tex[i]) != LSYS_OK)
      luaL_error(L, "not enough memory for the viewer");
  lua_pop(L, 1);
}

static int viewer_post (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  int t = lua_isnoneornil(L, 3) ? 0 : 3;
  lua_Integer n, k;
  snapbox *box;
  lsys_vsnap *s;
  luaL_checktype(L, 2, LUA_TTABLE);
  if (t) luaL_checktype(L, 3, LUA_TTABLE);
  n = luaL_len(L, 2);
  luaL_argcheck(L, n >= 1 && n <= (1 << 20), 2, "a list of 1 or more frames expected");
  box = (snapbox *)lua_newuserdatauv(L, sizeof *box, 0);   /* frees on errors below */
  box->s = NULL;
  lua_newtable(L);
  lua_pushcfunction(L, snapbox_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  if ((box->s = s = lsys_vsnap_new((size_t)n)) == NULL)
    return luaL_error(L, "not enough memory for the viewer");
  for (k = 1; k <= n; k++) {
    if (lua_rawgeti(L, 2, k) != LUA_TTABLE)
      return luaL_error(L, "viewer:post: frame %d is not a table", (int)k);
    readframe(L, lua_gettop(L), &s->frames[k - 1]);
    lua_pop(L, 1);
  }
  readpostopts(L, t, s, (int)n);
  if (s->light == 1)                        /* drawn with its colours from the first picture */
    s->frames[s->first].light = computelight(L, s, s->first, 0, lsys_common_memory_limit());
  v = checkviewer(L, 1);                    /* again: the frames and options ran Lua code */
  box->s = NULL;
  lsys_viewer_post(v, s);
  return 0;
}

/* v:patch(scene, {step =, count =, note =}): a live frame's changes (viewer.h);
** returns the request's serial number. */
static int viewer_patch (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  lsys_lscene *S = lsysL_checkscene(L, 2);
  int t = lua_isnoneornil(L, 3) ? 0 : 3, step, rc;
  lsys_opts po = vopts(t);
  size_t r[2 * LSYS_SCENE_NDIRTY], n, count;
  const char *note = NULL;
  if (t) luaL_checktype(L, 3, LUA_TTABLE);
  step = lsysL_optint(L, &po, "step", 0, 0, INT_MAX);
  count = (size_t)lsysL_optint(L, &po, "count", 0, 0, INT_MAX);
  if (lsysL_optfield(L, &po, "note", LUA_TSTRING, "a string"))
    note = lua_tostring(L, -1);   /* left on the stack: an __index may have made it */
  S = lsysL_checkscene(L, 2);                /* again: the options ran Lua code */
  v = checkviewer(L, 1);
  n = lsys_scene_take_ranges(&S->sc, r);
  rc = lsys_viewer_patch(v, &S->sc, r, n, step, count, note);
  if (rc < 0) {                             /* the ranges stay to be sent */
    size_t k;
    for (k = 0; k < n; k++) lsys_scene_touch(&S->sc, r[2 * k], r[2 * k + 1] - r[2 * k]);
  }
  if (rc == LSYS_ENOMEM) return luaL_error(L, "not enough memory for the viewer");
  if (rc < 0)
    return luaL_error(L, "viewer:patch: no live frame to patch (post one with live = true) "
                      "or its scene shrank");
  lua_pushinteger(L, rc);
  return 1;
}

static const char *const evnames[] = {
  "none", "pick", "miss", "screenshot", "step", "closed", "key", "drag", "pointer", "scroll",
  "frames", "light"
};

static void setnum (lua_State *L, const char *k, double x) {
  lua_pushnumber(L, x);
  lua_setfield(L, -2, k);
}

static void setbool (lua_State *L, const char *k, int b) {
  lua_pushboolean(L, b);
  lua_setfield(L, -2, k);
}

/* The fields of a POINTER or SCROLL event (panes). */
static void paneevent (lua_State *L, const lsys_vevent *ev) {
  static const char *const phases[] = {"down", "move", "up"};
  static const char *const buttons[] = {"left", "right", "middle"};
  lua_pushinteger(L, ev->pane + 1);
  lua_setfield(L, -2, "pane");
  setnum(L, "x", ev->x);
  setnum(L, "y", ev->y);
  if (ev->type == LSYS_VEV_SCROLL) {
    setnum(L, "dy", ev->scroll);
    return;
  }
  lua_pushstring(L, phases[ev->phase >= 0 && ev->phase <= 2 ? ev->phase : 1]);
  lua_setfield(L, -2, "phase");
  lua_pushstring(L, ev->button >= 0 && ev->button <= 2 ? buttons[ev->button] : "other");
  lua_setfield(L, -2, "button");
  setbool(L, "ctrl", (ev->mods & 0x2) != 0);
  setbool(L, "shift", (ev->mods & 0x1) != 0);
  if (ev->pressure >= 0) setnum(L, "pressure", ev->pressure);
}

/* A name for a GLFW key code: "a".."z", "0".."9", punctuation, or a word. */
static const char *keyname (int k, char buf[2]) {
  static const struct { int code; const char *name; } named[] = {
    {256, "escape"}, {257, "enter"}, {258, "tab"}, {259, "backspace"}, {260, "insert"},
    {261, "delete"}, {262, "right"}, {263, "left"}, {264, "down"}, {265, "up"},
    {266, "pageup"}, {267, "pagedown"}, {268, "home"}, {269, "end"}, {32, "space"},
    {334, "+"}, {333, "-"}, {335, "enter"}, {0, NULL}
  };
  int i;
  for (i = 0; named[i].name; i++) if (named[i].code == k) return named[i].name;
  if (k > 32 && k < 127) {
    buf[0] = (char)(k >= 'A' && k <= 'Z' ? k - 'A' + 'a' : k);
    buf[1] = '\0';
    return buf;
  }
  return "?";
}

static int viewer_poll (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  double timeout = luaL_optnumber(L, 2, 0);
  lsys_vevent ev;
  if (!lsys_viewer_poll(v, &ev, timeout)) return 0;
  lua_createtable(L, 0, 8);
  lua_pushstring(L, evnames[ev.type]);
  lua_setfield(L, -2, "type");
  if (ev.frame >= 0) {
    lua_pushinteger(L, ev.frame + 1);
    lua_setfield(L, -2, "frame");
  }
  if (ev.step >= 0) {
    lua_pushinteger(L, ev.step);
    lua_setfield(L, -2, "step");
  }
  switch (ev.type) {
    case LSYS_VEV_PICK:
      lua_pushinteger(L, (lua_Integer)ev.module + 1);
      lua_setfield(L, -2, "module");
      lua_pushstring(L, lsysL_recordkind(ev.kind));
      lua_setfield(L, -2, "kind");
      if (ev.plant > 0) {
        lua_pushinteger(L, ev.plant);
        lua_setfield(L, -2, "plant");
      }
      /* fall through */
    case LSYS_VEV_MISS:
      lua_pushnumber(L, ev.x);
      lua_setfield(L, -2, "x");
      lua_pushnumber(L, ev.y);
      lua_setfield(L, -2, "y");
      break;
    case LSYS_VEV_KEY: {
      char buf[2];
      lua_pushstring(L, keyname(ev.key, buf));
      lua_setfield(L, -2, "key");
      lua_pushboolean(L, (ev.mods & 0x2) != 0);
      lua_setfield(L, -2, "ctrl");
      lua_pushboolean(L, (ev.mods & 0x1) != 0);
      lua_setfield(L, -2, "shift");
      break;
    }
    case LSYS_VEV_DRAG:
      lua_pushstring(L, ev.phase == 0 ? "begin" : ev.phase == 1 ? "move" : "end");
      lua_setfield(L, -2, "phase");
      lua_pushnumber(L, ev.x);
      lua_setfield(L, -2, "x");
      lua_pushnumber(L, ev.y);
      lua_setfield(L, -2, "y");
      break;
    case LSYS_VEV_POINTER: case LSYS_VEV_SCROLL:
      paneevent(L, &ev);
      break;
    case LSYS_VEV_LIGHT:
      setbool(L, "on", ev.ok);
      break;
    case LSYS_VEV_FRAMES:
      lua_pushinteger(L, ev.count);
      lua_setfield(L, -2, "count");
      if (ev.count > 0) {
        lua_pushinteger(L, ev.first);
        lua_setfield(L, -2, "first");
        lua_pushinteger(L, ev.step);
        lua_setfield(L, -2, "last");
      }
      /* fall through */
    case LSYS_VEV_SCREENSHOT:
      lua_pushstring(L, ev.path);
      lua_setfield(L, -2, "path");
      lua_pushboolean(L, ev.ok);
      lua_setfield(L, -2, "ok");
      if (!ev.ok) {
        lua_pushstring(L, ev.msg);
        lua_setfield(L, -2, "msg");
      }
      break;
    default:
      break;
  }
  return 1;
}

static int viewer_pending (lua_State *L) {
  lviewer *lv = (lviewer *)luaL_checkudata(L, 1, VIEWER_T);
  lua_pushinteger(L, lv->v != NULL ? lsys_viewer_pending(lv->v) : 0);
  return 1;
}

static int viewer_screenshot (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  const char *path = luaL_optstring(L, 2, NULL);
  v = checkviewer(L, 1);                    /* again: converting a number allocates */
  lua_pushboolean(L, lsys_viewer_screenshot(v, path) == LSYS_OK);
  return 1;
}

static int viewer_key (lua_State *L) {
  static const char *const names[] = {
    "right", "left", "home", "end", "space", "r", "f", "w", "s", "h", "q", "escape", "+", "-",
    "redraw", "l", NULL
  };
  static const int keys[] = {
    LSYS_VKEY_RIGHT, LSYS_VKEY_LEFT, LSYS_VKEY_HOME, LSYS_VKEY_END, ' ', 'R', 'F', 'W', 'S',
    'H', 'Q', 256, '=', '-', LSYS_VKEY_REDRAW, 'L'
  };
  lsys_viewer *v = checkviewer(L, 1);
  int i = luaL_checkoption(L, 2, NULL, names);
  v = checkviewer(L, 1);                    /* again: converting a number allocates */
  lua_pushinteger(L, lsys_viewer_key(v, keys[i]));
  return 1;
}

static void setint (lua_State *L, const char *k, lua_Integer x) {
  lua_pushinteger(L, x);
  lua_setfield(L, -2, k);
}

static void pushv3 (lua_State *L, const double v[3]) {
  int i;
  lua_createtable(L, 3, 0);
  for (i = 0; i < 3; i++) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

static int viewer_state (lua_State *L) {
  lviewer *lv = (lviewer *)luaL_checkudata(L, 1, VIEWER_T);
  lsys_vstate st;
  lua_createtable(L, 0, 9);
  if (lv->v == NULL) {
    lua_pushboolean(L, 0);
    lua_setfield(L, -2, "open");
    return 1;
  }
  lsys_viewer_state(lv->v, &st);
  lua_pushboolean(L, st.open);
  lua_setfield(L, -2, "open");
  setint(L, "drawn", st.drawn);
  setnum(L, "drawms", st.drawms);
  setint(L, "serial", st.serial);
  setint(L, "width", st.width);
  setint(L, "height", st.height);
  setint(L, "fbwidth", st.fbwidth);
  setint(L, "fbheight", st.fbheight);
  setint(L, "frame", st.frame + 1);
  setint(L, "nframes", st.nframes);
  lua_pushboolean(L, st.playing);
  lua_setfield(L, -2, "playing");
  lua_pushboolean(L, st.wireframe);
  lua_setfield(L, -2, "wireframe");
  lua_pushboolean(L, st.light);
  lua_setfield(L, -2, "light");
  lua_createtable(L, 4, 0);             /* the scene's rectangle: x, y, w, h */
  for (int i = 0; i < 4; i++) {
    lua_pushinteger(L, st.scene[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "scene");
  if (st.pen >= 0) {                    /* looked for at the first press on a pane */
    lua_pushboolean(L, st.pen);
    lua_setfield(L, -2, "pen");
    lua_pushstring(L, st.pendesc);
    lua_setfield(L, -2, "pen_devices");
  }
  if (st.drawn > 0 && st.frame >= 0) {   /* the camera's axes in the world, rows of 'view' */
    double r[3] = {st.view[0], st.view[4], st.view[8]}, u[3] = {st.view[1], st.view[5], st.view[9]},
           f[3] = {-st.view[2], -st.view[6], -st.view[10]};
    pushv3(L, r);
    lua_setfield(L, -2, "right");
    pushv3(L, u);
    lua_setfield(L, -2, "up");
    pushv3(L, f);
    lua_setfield(L, -2, "forward");
  }
  return 1;
}

static int viewer_project (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  lsys_vstate st;
  double p[3], out[3];
  int i;
  luaL_checktype(L, 2, LUA_TTABLE);
  for (i = 0; i < 3; i++) {
    lua_rawgeti(L, 2, i + 1);
    p[i] = luaL_checknumber(L, -1);
    lua_pop(L, 1);
  }
  lsys_viewer_state(v, &st);
  if (st.drawn == 0 || st.frame < 0 ||
      !lsys_render_project(st.proj, st.view, st.scene[2], st.scene[3], p, out))
    return 0;
  lua_pushnumber(L, out[0] + st.scene[0]);    /* window coordinates, panes or not */
  lua_pushnumber(L, out[1] + st.scene[1]);
  lua_pushnumber(L, out[2]);
  return 3;
}

/* Four fractions of the window from the list at 't' ("viewer:layout: <what> ..."). */
static void readrect (lua_State *L, int t, const char *what, float r[4]) {
  int i;
  if (!lua_istable(L, t))
    luaL_error(L, "viewer:layout: %s must be a table {x0, y0, x1, y1}", what);
  for (i = 0; i < 4; i++) {
    double x;
    lua_rawgeti(L, t, i + 1);
    x = lua_tonumber(L, -1);
    if (!lua_isnumber(L, -1) || !(x >= 0 && x <= 1))
      luaL_error(L, "viewer:layout: %s[%d] must be a number in [0, 1]", what, i + 1);
    r[i] = (float)x;
    lua_pop(L, 1);
  }
  if (!(r[0] < r[2] && r[1] < r[3]))
    luaL_error(L, "viewer:layout: %s must have x0 < x1 and y0 < y1", what);
}

static int viewer_layout (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  lsys_vlayout lay;
  memset(&lay, 0, sizeof lay);
  if (!lua_isnoneornil(L, 2)) {
    lua_Integer n, k;
    char what[32];
    luaL_checktype(L, 2, LUA_TTABLE);
    lay.on = 1;
    lua_getfield(L, 2, "scene");
    readrect(L, lua_gettop(L), "scene", lay.scene);
    lua_pop(L, 1);
    if (lua_getfield(L, 2, "panes") != LUA_TTABLE)
      luaL_error(L, "viewer:layout: panes must be a list");
    n = luaL_len(L, -1);
    luaL_argcheck(L, n <= LSYS_VPANES_MAX, 2, "too many panes (limit is 4)");
    for (k = 1; k <= n; k++) {
      int i;
      lua_rawgeti(L, -1, k);
      snprintf(what, sizeof what, "pane %d", (int)k);
      readrect(L, lua_gettop(L), what, lay.pane[k - 1]);
      lay.bg[k - 1][3] = 255;
      for (i = 0; i < 3; i++) lay.bg[k - 1][i] = 255;
      if (lua_getfield(L, -1, "bg") == LUA_TTABLE)
        for (i = 0; i < 3; i++) {
          double c;
          lua_rawgeti(L, -1, i + 1);
          c = luaL_optnumber(L, -1, 1);
          lay.bg[k - 1][i] = (uint8_t)(255 * (c < 0 ? 0 : c > 1 ? 1 : c) + 0.5);
          lua_pop(L, 1);
        }
      lua_pop(L, 2);
    }
    lay.npanes = (int)n;
    lua_pop(L, 1);
  }
  v = checkviewer(L, 1);                    /* again: the layout's metamethods ran */
  lua_pushinteger(L, lsys_viewer_layout(v, &lay));
  return 1;
}

static int viewer_image (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2), w = luaL_checkinteger(L, 4),
              h = luaL_checkinteger(L, 5);
  size_t len;
  const char *px = luaL_checklstring(L, 3, &len);
  int r;
  luaL_argcheck(L, k >= 1 && k <= LSYS_VPANES_MAX, 2, "a pane from 1 to 4 expected");
  luaL_argcheck(L, w >= 1 && w <= 16384, 4, "a width from 1 to 16384 expected");
  luaL_argcheck(L, h >= 1 && h <= 16384, 5, "a height from 1 to 16384 expected");
  if ((lua_Integer)len != w * h * 4)
    return luaL_error(L, "viewer:image: %d bytes of pixels for %dx%d (%d expected)", (int)len,
                      (int)w, (int)h, (int)(w * h * 4));
  v = checkviewer(L, 1);                    /* again: converting a number allocates */
  r = lsys_viewer_image(v, (int)k - 1, (const uint8_t *)px, (int)w, (int)h);
  if (r < 0) return luaL_error(L, "not enough memory for the viewer");
  lua_pushinteger(L, r);
  return 1;
}

static int viewer_text (lua_State *L) {
  lsys_viewer *v = checkviewer(L, 1);
  const char *status = luaL_optstring(L, 2, NULL), *help = luaL_optstring(L, 3, NULL);
  v = checkviewer(L, 1);                    /* again: converting a number allocates */
  lua_pushinteger(L, lsys_viewer_text(v, status, help));
  return 1;
}

static int viewer_close (lua_State *L) {
  lviewer *lv = (lviewer *)luaL_checkudata(L, 1, VIEWER_T);
  lsys_viewer_close(lv->v);
  lv->v = NULL;
  return 0;
}

/* v:light(k [, {threads =, max_memory =}]): frame k's light colours, computed
** here unless they were (only this thread gives them), and what they show. */
static int viewer_light (lua_State *L) {
  static const char *const names[] = {"threads", "max_memory", NULL};
  lsys_viewer *v = checkviewer(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  int t = lua_isnoneornil(L, 3) ? 0 : 3, threads;
  lsys_opts lo = {t, "viewer:light: opts.", "", LSYS_GOT_VALUE, 0};
  const lsys_vsnap *s;
  const lsys_vlight *l;
  size_t limit;
  if (t) luaL_checktype(L, 3, LUA_TTABLE);
  if (lsysL_optunknown(L, &lo, names))
    return luaL_error(L, "viewer:light: unknown option '%s' (known: threads, max_memory)",
                      luaL_tolstring(L, -1, NULL));
  threads = lsysL_optint(L, &lo, "threads", 0, 0, LSYS_LIGHT_MAXTHREADS);
  limit = (size_t)lsysL_optnum(L, &lo, "max_memory", (double)lsys_common_memory_limit(), 0,
                               1.8e19, "a positive number of bytes");
  v = checkviewer(L, 1);                    /* again: the options ran Lua code */
  if ((s = lsys_viewer_posted(v)) == NULL) {     /* closed meanwhile, or nothing shown */
    lua_pushnil(L);
    lua_pushliteral(L, "no window open");
    return 2;
  }
  if (k < 1 || (size_t)k > s->nframes)
    return luaL_error(L, "viewer:light: no frame %I (the window shows frames 1 to %I)", k,
                      (lua_Integer)s->nframes);
  if (s->frames[k - 1].light == NULL) {
    lsys_vlight *nl = computelight(L, s, (size_t)k - 1, threads, limit);
    if (lsys_viewer_light(v, s, (size_t)k - 1, nl) < 0) {   /* cannot happen: we post */
      lsys_vlight_free(nl);
      LSYS_FREE(nl);
      return luaL_error(L, "viewer:light: the frame is gone");
    }
  }
  l = s->frames[k - 1].light;
  lua_createtable(L, 0, 6);
  lua_pushinteger(L, k);
  lua_setfield(L, -2, "frame");
  lua_pushinteger(L, (lua_Integer)l->nleaves);
  lua_setfield(L, -2, "leaves");
  setnum(L, "min", l->min);
  setnum(L, "max", l->max);
  setnum(L, "mean", l->mean);
  if (l->msg[0] != '\0') {
    lua_pushstring(L, l->msg);
    lua_setfield(L, -2, "msg");
  }
  return 1;
}

/* v:colour(k, t) -> r, g, b: triangle t of frame k as the window draws it now,
** with the light colours while the L key is on. */
static int viewer_colour (lua_State *L) {
  static const lsys_material grey = {{0}, {0.8f, 0.8f, 0.8f, 1}, {0}, {0}, 0};
  lsys_viewer *v = checkviewer(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2), t = luaL_checkinteger(L, 3);
  const lsys_vsnap *s = lsys_viewer_posted(v);
  const lsys_vframe *f;
  const lsys_material *mt = &grey;
  const uint16_t *col;
  lsys_vstate st;
  int i;
  if (s == NULL) return luaL_error(L, "viewer:colour: nothing shown");
  if (s->live)                              /* its mesh is the window's to grow */
    return luaL_error(L, "viewer:colour: not for a growing scene (lsys.viewer.live)");
  if (k < 1 || (size_t)k > s->nframes)
    return luaL_error(L, "viewer:colour: no frame %I (the window shows frames 1 to %I)", k,
                      (lua_Integer)s->nframes);
  f = &s->frames[k - 1];
  if (t < 1 || (size_t)t > f->sc.mesh.nt)
    return luaL_error(L, "viewer:colour: no triangle %I in frame %I (it has %I)", t, k,
                      (lua_Integer)f->sc.mesh.nt);
  lsys_viewer_state(v, &st);
  col = f->sc.mesh.col;
  if (st.light && f->light != NULL && f->light->col != NULL) {
    col = f->light->col;
    mt = &f->light->pal[col[f->sc.mesh.tri[3 * (t - 1)]] % f->light->npal];
  } else if (f->sc.npal > 0)
    mt = &f->sc.pal[col[f->sc.mesh.tri[3 * (t - 1)]] % f->sc.npal];
  for (i = 0; i < 3; i++) lua_pushnumber(L, mt->diffuse[i]);
  return 3;
}

static const luaL_Reg viewer_meta[] = {
  {"__index", NULL},  /* placeholder: the method table */
  {"__gc", viewer_close}, {NULL, NULL}
};

static const luaL_Reg viewer_methods[] = {
  {"post", viewer_post}, {"patch", viewer_patch}, {"poll", viewer_poll},
  {"pending", viewer_pending},
  {"screenshot", viewer_screenshot},
  {"key", viewer_key}, {"state", viewer_state}, {"project", viewer_project},
  {"layout", viewer_layout}, {"image", viewer_image}, {"text", viewer_text},
  {"light", viewer_light}, {"colour", viewer_colour},
  {"close", viewer_close}, {NULL, NULL}
};
#endif

/* core.filestamp(path) -> modification time (seconds, with fraction), size; or nil, msg */
static int l_filestamp (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  struct stat sb;
  if (stat(path, &sb) != 0) {
    lua_pushnil(L);
    lua_pushfstring(L, "%s: %s", path, strerror(errno));
    return 2;
  }
  lua_pushnumber(L, (lua_Number)sb.st_mtim.tv_sec + (lua_Number)sb.st_mtim.tv_nsec * 1e-9);
  lua_pushinteger(L, (lua_Integer)sb.st_size);
  return 2;
}

#ifndef LSYS_NO_VIEWER
/* core.light_ramp(x) -> r, g, b: the colour of light x (clamped to [0, 1]) on the
** ramp of the window's L key (vlight.h). */
static int l_light_ramp (lua_State *L) {
  float rgb[3];
  int i;
  lsys_vlight_ramp(luaL_checknumber(L, 1), rgb);
  for (i = 0; i < 3; i++) lua_pushnumber(L, rgb[i]);
  return 3;
}

/* core.pen_devices() -> { { id, name, pressure = { min, max, value } or nil }... }
** the X input devices and which report pressure (xpen.h); or nil, why. */
static int l_pen_devices (lua_State *L) {
  lsys_xpendev dev[LSYS_XPEN_MAXDEV];
  char why[256];
  int i, n = lsys_xpen_list(dev, LSYS_XPEN_MAXDEV, why, sizeof why);
  if (n < 0) {
    lua_pushnil(L);
    lua_pushstring(L, why);
    return 2;
  }
  lua_createtable(L, n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, 0, 3);
    setint(L, "id", dev[i].id);
    lua_pushstring(L, dev[i].name);
    lua_setfield(L, -2, "name");
    if (dev[i].valuator >= 0) {
      lua_createtable(L, 0, 3);
      setnum(L, "min", dev[i].min);
      setnum(L, "max", dev[i].max);
      setnum(L, "value", dev[i].value);
      lua_setfield(L, -2, "pressure");
    }
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}
#endif

/* core.mkdir(path) -> true (made, or a directory already); or nil, msg */
static int l_mkdir (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  struct stat sb;
  int err = mkdir(path, 0777) == 0 ? 0 : errno;
  if (err != 0 && !(err == EEXIST && stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))) {
    lua_pushnil(L);
    lua_pushfstring(L, "cannot make the directory %s: %s", path,
                    err == EEXIST ? "a file is in the way" : strerror(err));
    return 2;
  }
  lua_pushboolean(L, 1);
  return 1;
}

void lsysL_open_viewer (lua_State *L) {
#ifndef LSYS_NO_VIEWER
  lua_pushcfunction(L, l_pen_devices);
  lua_setfield(L, -2, "pen_devices");
  lua_pushcfunction(L, l_light_ramp);
  lua_setfield(L, -2, "light_ramp");
  lsysL_createmeta(L, VIEWER_T, viewer_meta, viewer_methods);
  lua_pushcfunction(L, l_viewer_open);
  lua_setfield(L, -2, "viewer_open");
  lua_pushboolean(L, 1);
#else
  lua_pushboolean(L, 0);
#endif
  lua_setfield(L, -2, "has_viewer");
  lua_pushcfunction(L, l_filestamp);
  lua_setfield(L, -2, "filestamp");
  lua_pushcfunction(L, l_mkdir);
  lua_setfield(L, -2, "mkdir");
}
