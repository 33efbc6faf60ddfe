/*
** The viewer window (viewer.h): GLFW on its own thread, drawing snapshots
** with render.c and the text and highlights over them with overlay.c.
**
** Threads. The caller's thread (Lua) and the viewer thread share only the
** fields under 'mu': the mailbox, the event queue, requests (close, keys,
** screenshots), the published state and the frames' light colours.
** Everything else -- the window, the GL context, the snapshot being shown,
** the camera -- belongs to the viewer thread. The caller wakes the viewer
** with glfwPostEmptyEvent, which GLFW allows from any thread, and only while
** the viewer is open (checked under 'mu', so never after glfwTerminate).
**
** Drawing is on demand: the loop sleeps in glfwWaitEventsTimeout until an
** input event, a post, a request or the next animation step, and redraws
** only when something changed.
**
** Camera. A snapshot arrives with the view's camera, fitted by render.c on
** the frame shown first; the viewer turns that into an explicit camera
** (target, direction, up, distance; half height for parallel projection)
** which it then changes with the mouse and keeps while stepping through
** frames, so a plant grows in place. R returns to the arrival camera; F
** fits the frame shown, keeping the direction. The camera's arithmetic and
** picking are in viewcam.c, tested without a window.
*/
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "glfwdl.h"
#include "overlay.h"
#include "pngio.h"
#include "turtle.h"
#include "viewcam.h"
#include "viewer.h"
#include "vlight.h"
#include "vpanes.h"
#include "vshot.h"
#include "xpen.h"

#define MAXEVENTS 1024          /* queued events beyond this are dropped (oldest first) */
#define CLICK_SLOP 4.0          /* a press and release closer than this (pixels) is a click */
#define PICK_TOL 6.0            /* pixels around a thin line that still pick it */
#define G lsys_glfw

/* ---------------------------------------------------------------------- */
/* one window per process (GLFW is process-wide); libglfw is glfwdl.c's */

static pthread_mutex_t glfwlock = PTHREAD_MUTEX_INITIALIZER;   /* loading; one window */
static int glfwbusy;            /* a viewer is open (GLFW is process-wide) */

/* ---------------------------------------------------------------------- */
/* the viewer */

struct lsys_viewer {
  pthread_t thread;
  pthread_mutex_t mu;
  pthread_cond_t cv;
  /* shared, under mu */
  lsys_vsnap *mail;               /* posted, not yet taken */
  const lsys_vsnap *posted;       /* the last posted (mail or snap): its frames' light */
  int started, startok, quit, open;
  char starterr[256];
  lsys_vevent *ev;                /* queue: ev[evhead .. evhead + nev) modulo MAXEVENTS */
  size_t evhead, nev;
  char shotpath[512];
  int shotreq;                    /* 1: a screenshot is asked for (path in shotpath, "" auto) */
  int keys[32];
  int nkeys;
  int serial;                     /* requests made (posts, keys) */
  int taken;                      /* (viewer thread) requests taken before drawing */
  lsys_vstate st;
  lsys_viewer_opts o;
  lsys_vlive live;                /* live frames: the stage of lsys_viewer_patch */
  /* the viewer thread's own */
  GLFWwindow *win;
  lsys_gl gl;
  lsys_vshot shot;                /* pictures read back (vshot.h) */
  lsys_vsnap *snap;
  long cur;                       /* frame shown */
  lsys_vcam cam, home;            /* current and arrival cameras (viewcam.h) */
  lsys_render_cache cache;
  int winw, winh, fbw, fbh;
  int button;                     /* 0 none, 1 orbiting, 2 panning, 3 a tool's drag */
  double px, py, lastx, lasty;    /* press position, last cursor position */
  int moved;
  int playing;
  double rate, nextt;
  int wireframe, help, dirty, light, plain;   /* light: leaves coloured by it (the L key);
                                                 plain: no sky and no ground (the G key) */
  double drawms;                  /* smoothed time to draw a frame */
  int seqreq;                     /* 1: the S key while animating: save every frame */
  char drawerr[256];              /* why the last picture could not be drawn (status line) */
  lsys_overlay text;              /* the status line and the help */
  lsys_vpanes panes;              /* image panes beside the scene (vpanes.h) */
  int sr[4];                      /* the scene's rectangle in the window (x, y, w, h) */
  int pane, pbutton;              /* the pane pressed (button 4) and the GLFW button */
  char note[64];                  /* the live frame's note on the status line */
  lsys_xpen *pen;                 /* pressure devices, opened at the first press on a pane */
};

/* Queues an event (mu held). */
static void pushevent_locked (lsys_viewer *v, const lsys_vevent *e) {
  if (v->nev == MAXEVENTS) {      /* full: the oldest goes */
    v->evhead = (v->evhead + 1) % MAXEVENTS;
    v->nev--;
  }
  v->ev[(v->evhead + v->nev) % MAXEVENTS] = *e;
  v->nev++;
  pthread_cond_broadcast(&v->cv);
}

static void pushevent (lsys_viewer *v, const lsys_vevent *e) {
  pthread_mutex_lock(&v->mu);
  pushevent_locked(v, e);
  pthread_mutex_unlock(&v->mu);
}

static void event (lsys_viewer *v, int type, lsys_vevent *e) {
  memset(e, 0, sizeof *e);
  e->type = type;
  e->frame = v->snap != NULL ? v->cur : -1;
  e->step = v->snap != NULL && v->cur >= 0 ? v->snap->frames[v->cur].step : -1;
}

static int capturing (const lsys_viewer *v) {
  return (v->snap != NULL && v->snap->capture) || v->panes.lay.on;
}

static const lsys_vframe *curframe (const lsys_viewer *v) {
  return v->snap != NULL && v->cur >= 0 && (size_t)v->cur < v->snap->nframes
         ? &v->snap->frames[v->cur] : NULL;
}

/* The light colours frame f is drawn with: none while the L key is off or
** until the caller gives them. */
static const lsys_vlight *lightof (lsys_viewer *v, const lsys_vframe *f) {
  const lsys_vlight *l;
  pthread_mutex_lock(&v->mu);
  l = v->light ? f->light : NULL;
  pthread_mutex_unlock(&v->mu);
  return l;
}

/* Frame f seen through the viewer's camera: its scene with the camera
** replaced (the arrays borrowed, scene.h) and the options of this window. */
static void frameview (lsys_viewer *v, const lsys_vframe *f, lsys_scene *sc,
                       lsys_render_opts *o) {
  *sc = f->sc;
  lsys_vlight_apply(lightof(v, f), sc);
  lsys_viewcam_apply(&v->cam, &sc->cam);
  sc->cam.has_box = 0;            /* near and far: from what is drawn */
  lsys_vsnap_frame_bounds((lsys_vframe *)f, sc->cam.bounds);   /* the viewer thread's frame */
  sc->cam.has_bounds = 1;
  lsys_render_defaults(o);
  o->width = v->sr[2];
  o->height = v->sr[3];
  o->wireframe = v->wireframe;
  o->gl = &v->gl;
  o->cache = &v->cache;
  o->keep_textures = 1;
  if (v->snap != NULL && !v->plain && (f->sc.mesh.nt > 0 || f->sc.ninst > 0))
    lsys_render_backdrops(o, &sc->cam, v->snap->sky, v->snap->ground);
}

/*
** Fits frame f with its view's camera (home: as the view says, its box if it
** has one; otherwise keeping the current direction and up, to what is shown)
** and sets v->cam from the result.
*/
static void fit (lsys_viewer *v, const lsys_vframe *f, int home) {
  if (lsys_viewcam_fit(&v->cam, &f->sc, &f->sc.cam, v->sr[2], v->sr[3], !home) != LSYS_OK)
    return;
  if (home) v->home = v->cam;
  v->dirty = 1;
}

/* Shows frame k (clamped) and reports the change. */
static void showframe (lsys_viewer *v, long k) {
  lsys_vevent e;
  if (v->snap == NULL || v->snap->nframes == 0) return;
  if (k < 0) k = 0;
  if ((size_t)k >= v->snap->nframes) k = (long)v->snap->nframes - 1;
  if (k == v->cur) return;
  v->cur = k;
  v->dirty = 1;
  event(v, LSYS_VEV_STEP, &e);
  pushevent(v, &e);
}

/* Takes a posted snapshot, if any, and brings a live one up to date. */
static void takemail (lsys_viewer *v) {
  lsys_vsnap *s, *old = NULL;
  size_t k;
  pthread_mutex_lock(&v->mu);
  s = v->mail;
  v->mail = NULL;
  if (s != NULL) {
    lsys_render_cache_release(&v->cache, &v->gl);    /* textures of the old snapshot */
    old = v->snap;
    v->snap = s;
    v->note[0] = '\0';
  }
  if (v->snap != NULL && v->snap->live && lsys_vlive_take(&v->live, &v->snap->frames[0], v->note)) {
    v->snap->frames[0].hasbounds = 0;
    v->dirty = 1;
  }
  pthread_mutex_unlock(&v->mu);
  if (s == NULL) return;
  lsys_vsnap_free(old);
  for (k = 0; k < s->nframes; k++) {          /* the frames share the snapshot's textures */
    s->frames[k].sc.tex = s->texp;
    s->frames[k].sc.ntex = s->texp != NULL ? s->ntex : 0;
  }
  v->rate = s->rate > 0 ? s->rate : 2;
  v->playing = 0;
  if (s->light >= 0) v->light = s->light;
  v->cur = s->nframes > 0 ? (long)(s->first < s->nframes ? s->first : s->nframes - 1) : -1;
  if (s->title[0] != '\0') G.SetWindowTitle(v->win, s->title);
  if (v->cur >= 0 && (!s->keep_camera || !v->cam.valid))
    fit(v, &s->frames[v->cur], 1);
  v->dirty = 1;
}

/* ---------------------------------------------------------------------- */
/* text: the status line, the help and the light's legend (overlay.h) */

/* Draws the status line, the help and the light's legend over the picture. */
static void overlay (lsys_viewer *v) {
  const lsys_vframe *f = curframe(v);
  const char *help = v->panes.help[0] != '\0' ? v->panes.help : lsys_overlay_help;
  char line[256], note[96];
  if (v->panes.msg[0] != '\0')
    snprintf(line, sizeof line, "%s", v->panes.msg);
  else if (f == NULL)
    snprintf(line, sizeof line, "waiting for a scene");
  else if (v->drawerr[0] != '\0')
    snprintf(line, sizeof line, "cannot draw: %.240s", v->drawerr);
  else
    lsys_vsnap_status(v->snap, v->cur, v->drawms > 0 ? 1000 / v->drawms : 0.0, v->playing,
                      v->wireframe, v->note, line, sizeof line);
  if (f != NULL) lsys_vlight_note(lightof(v, f), note, sizeof note);
  lsys_overlay_screen(&v->text, &v->gl, v->fbw, v->fbh, v->winh, v->o.status ? line : NULL,
                      v->help ? help : NULL, v->light && f != NULL ? note : NULL);
}

/* ---------------------------------------------------------------------- */
/* drawing and screenshots */

static double now (void) {
  return G.GetTime();
}

/* Reads the back buffer (just drawn) and writes it to the requested file. */
static void screenshot (lsys_viewer *v, const char *path) {
  lsys_vevent ev;
  event(v, LSYS_VEV_SCREENSHOT, &ev);
  lsys_vshot_screenshot(&v->shot, path, v->fbw, v->fbh, &ev);
  pushevent(v, &ev);
}

/* Draws frame f through the current camera into the rectangle r (lsys_vpanes_fbrect);
** 'sc' is the scene as drawn. */
static int drawscene (lsys_viewer *v, const lsys_vframe *f, const int r[4], lsys_scene *sc,
                      lsys_error *e) {
  lsys_render_opts o;
  frameview(v, f, sc, &o);
  o.x = r[0];
  o.y = r[1];
  return lsys_render_draw(sc, &o, r[2], r[3], e);
}

/* Frame k of the S key's series, without the status line (lsys_vshot_series). */
static int drawframe (void *ctx, size_t k, const int r[4], lsys_error *e) {
  lsys_viewer *v = (lsys_viewer *)ctx;
  lsys_scene sc;
  return drawscene(v, &v->snap->frames[k], r, &sc, e);
}

static void draw (lsys_viewer *v) {
  const lsys_vframe *f = curframe(v);
  lsys_scene sc;
  lsys_error e;
  char shot[512];
  int wantshot, r[4];
  double t0 = now(), ms;
  G.GetFramebufferSize(v->win, &v->fbw, &v->fbh);
  G.GetWindowSize(v->win, &v->winw, &v->winh);
  if (v->fbw <= 0 || v->fbh <= 0 || v->winw <= 0 || v->winh <= 0) return;   /* iconified */
  lsys_vpanes_scene(&v->panes, v->winw, v->winh, v->sr);
  if (v->seqreq && v->snap != NULL) {   /* the S key while animating; drawn over next */
    lsys_vevent ev;
    lsys_vpanes_fbrect(v->sr, v->winh, v->fbh, r);
    event(v, LSYS_VEV_FRAMES, &ev);
    lsys_vshot_series(&v->shot, v->snap, r, drawframe, v, &ev);
    pushevent(v, &ev);
  }
  v->seqreq = 0;
  if (f != NULL) {
    lsys_vpanes_fbrect(v->sr, v->winh, v->fbh, r);
    v->drawerr[0] = '\0';
    if (drawscene(v, f, r, &sc, &e) != LSYS_OK) {
      snprintf(v->drawerr, sizeof v->drawerr, "%s", e.msg);   /* on the status line */
      v->gl.ClearColor(0.3f, 0, 0, 1);
      v->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
  } else {
    v->gl.Viewport(0, 0, v->fbw, v->fbh);
    v->gl.ClearColor(1, 1, 1, 1);
    v->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  if (f != NULL && f->nlines > 0)       /* over the scene, with its camera */
    lsys_overlay_lines(&v->gl, f->lines, f->nlines,
                       v->winh > 0 ? (float)v->fbh / (float)v->winh : 1);
  lsys_vpanes_draw(&v->panes, &v->gl, v->winw, v->winh, v->fbw, v->fbh);
  if (v->o.status || v->light) overlay(v);
  pthread_mutex_lock(&v->mu);
  wantshot = v->shotreq && (f != NULL || v->mail == NULL);
  if (wantshot) {
    memcpy(shot, v->shotpath, sizeof shot);
    v->shotreq = 0;
  }
  pthread_mutex_unlock(&v->mu);
  if (wantshot) screenshot(v, shot);
  G.SwapBuffers(v->win);
  ms = 1000 * (now() - t0);
  v->drawms = v->drawms > 0 ? 0.8 * v->drawms + 0.2 * ms : ms;
  v->dirty = 0;
  /* publish what was drawn */
  pthread_mutex_lock(&v->mu);
  v->st.drawn++;
  v->st.drawms = v->drawms;
  v->st.serial = v->taken;
  v->st.width = v->winw;
  v->st.height = v->winh;
  v->st.fbwidth = v->fbw;
  v->st.fbheight = v->fbh;
  v->st.frame = v->cur;
  v->st.nframes = v->snap ? (long)v->snap->nframes : 0;
  v->st.playing = v->playing;
  v->st.wireframe = v->wireframe;
  v->st.light = v->light;
  v->st.capture = capturing(v);
  memcpy(v->st.scene, v->sr, sizeof v->sr);
  if (f != NULL)
    lsys_render_camera_scene(&sc, &sc.cam, v->sr[2], v->sr[3], v->st.proj, v->st.view);
  pthread_cond_broadcast(&v->cv);
  pthread_mutex_unlock(&v->mu);
}

/* ---------------------------------------------------------------------- */
/* input */

/* The mouse moves the camera (viewcam.h); the arrival camera's up stays up. */
static void orbit (lsys_viewer *v, double dx, double dy) {
  lsys_viewcam_orbit(&v->cam, v->home.valid ? v->home.u : v->cam.u, dx, dy);
  v->dirty = 1;
}

static void pan (lsys_viewer *v, double dx, double dy) {
  const lsys_vframe *f = curframe(v);
  lsys_viewcam_pan(&v->cam, f != NULL ? &f->sc.cam : NULL, v->sr[3], dx, dy);
  v->dirty = 1;
}

static void zoom (lsys_viewer *v, double steps) {
  lsys_viewcam_zoom(&v->cam, steps);
  v->dirty = 1;
}

static void pick (lsys_viewer *v, double x, double y) {
  const lsys_vframe *f = curframe(v);
  lsys_vevent ev;
  double proj[16], view[16];
  if (f == NULL) return;
  event(v, LSYS_VEV_MISS, &ev);
  if (lsys_viewcam_matrices(&v->cam, &f->sc, &f->sc.cam, v->sr[2], v->sr[3], proj, view) ==
      LSYS_OK &&
      lsys_viewcam_pick_event(f, proj, view, v->sr[2], v->sr[3], x - v->sr[0], y - v->sr[1],
                              PICK_TOL, &ev))
    ev.type = LSYS_VEV_PICK;
  ev.x = x;
  ev.y = y;
  pushevent(v, &ev);
}

static void play (lsys_viewer *v) {
  if (v->snap == NULL || v->snap->nframes < 2) return;
  v->playing = !v->playing;
  if (v->playing) {
    if ((size_t)v->cur + 1 >= v->snap->nframes) showframe(v, 0);
    v->nextt = now() + 1 / v->rate;
  }
  v->dirty = 1;
}

/* One key press (a real one, or one asked for with lsys_viewer_key). */
static void key (lsys_viewer *v, int k, int mods) {
  (void)mods;
  switch (k) {
    case GLFW_KEY_ESCAPE: case GLFW_KEY_Q:
      G.SetWindowShouldClose(v->win, 1);
      break;
    case GLFW_KEY_R:
      if (v->home.valid) { v->cam = v->home; v->dirty = 1; }
      break;
    case GLFW_KEY_F:
      if (curframe(v) != NULL) fit(v, curframe(v), 0);
      break;
    case GLFW_KEY_W:
      v->wireframe = !v->wireframe;
      v->dirty = 1;
      break;
    case GLFW_KEY_G:              /* the sky and the ground off and on again */
      v->plain = !v->plain, v->dirty = 1;
      break;
    case GLFW_KEY_L: {            /* the caller gives the frames their colours */
      lsys_vevent e;
      v->light = !v->light;
      v->dirty = 1;
      event(v, LSYS_VEV_LIGHT, &e);
      e.ok = v->light;
      pushevent(v, &e);
      break;
    }
    case GLFW_KEY_H: case GLFW_KEY_SLASH:
      v->help = !v->help;
      v->dirty = 1;
      break;
    case GLFW_KEY_S:              /* while animating: every frame, drawn by draw */
      v->seqreq = v->playing;     /* (play: 2 frames or more, never live) */
      pthread_mutex_lock(&v->mu);
      if (!v->seqreq) { v->shotreq = 1; v->shotpath[0] = '\0'; }
      pthread_mutex_unlock(&v->mu);
      v->dirty = 1;
      break;
    case GLFW_KEY_SPACE:
      play(v);
      break;
    case GLFW_KEY_RIGHT:
      v->playing = 0;
      showframe(v, v->cur + 1);
      v->dirty = 1;
      break;
    case GLFW_KEY_LEFT:
      v->playing = 0;
      showframe(v, v->cur - 1);
      v->dirty = 1;
      break;
    case GLFW_KEY_HOME:
      v->playing = 0;
      showframe(v, 0);
      break;
    case GLFW_KEY_END:
      v->playing = 0;
      if (v->snap != NULL) showframe(v, (long)v->snap->nframes - 1);
      break;
    case LSYS_VKEY_REDRAW:
      v->dirty = 1;
      break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD:
      v->rate = fmin(v->rate * 1.5, 120);
      v->dirty = 1;
      break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT:
      v->rate = fmax(v->rate / 1.5, 0.05);
      v->dirty = 1;
      break;
    default:
      break;
  }
}

static lsys_viewer *self (GLFWwindow *w) {
  return (lsys_viewer *)G.GetWindowUserPointer(w);
}

static void onkey (GLFWwindow *w, int k, int scancode, int action, int mods) {
  lsys_viewer *v = self(w);
  (void)scancode;
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (capturing(v)) {             /* the tool hears every key; the arrows are its own */
    lsys_vevent ev;
    event(v, LSYS_VEV_KEY, &ev);
    ev.key = k;
    ev.mods = mods;
    pushevent(v, &ev);
    if (k == GLFW_KEY_LEFT || k == GLFW_KEY_RIGHT || k == GLFW_KEY_UP || k == GLFW_KEY_DOWN ||
        k == GLFW_KEY_HOME || k == GLFW_KEY_END || (mods & GLFW_MOD_CONTROL) ||
        action == GLFW_REPEAT)
      return;
  }
  if (action == GLFW_PRESS || k == GLFW_KEY_LEFT || k == GLFW_KEY_RIGHT) key(v, k, mods);
}

static void dragevent (lsys_viewer *v, int phase, double x, double y) {
  lsys_vevent ev;
  event(v, LSYS_VEV_DRAG, &ev);
  ev.phase = phase;
  ev.x = x;
  ev.y = y;
  pushevent(v, &ev);
}

/* Looks for pressure devices (a tablet) once, at the first press on a pane:
** a window without panes never opens a second X connection. */
static void openpen (lsys_viewer *v) {
  char why[256];
  lsys_xpen *p = lsys_xpen_open(why, sizeof why);
  pthread_mutex_lock(&v->mu);
  v->pen = p;
  v->st.pen = p != NULL;
  snprintf(v->st.pendesc, sizeof v->st.pendesc, "%s", p ? lsys_xpen_names(p) : why);
  pthread_mutex_unlock(&v->mu);
}

/* A pointer (type POINTER) or wheel (SCROLL) event of pane k at window point
** (x, y), reported in the pixels of the pane's image. */
static void paneevent (lsys_viewer *v, int type, int k, int phase, int mods, double x, double y,
                       double scroll) {
  lsys_vevent ev;
  event(v, type, &ev);
  ev.pane = k;
  ev.phase = phase;
  ev.button = v->pbutton;
  ev.mods = mods;
  ev.scroll = scroll;
  ev.pressure = -1;
  if (type == LSYS_VEV_POINTER && phase != 2) {
    if (v->st.pen < 0) openpen(v);
    ev.pressure = lsys_xpen_pressure(v->pen);
  }
  lsys_vpanes_map(&v->panes, k, v->winw, v->winh, x, y, &ev.x, &ev.y);
  pushevent(v, &ev);
}

/* What the window point (x, y) is over: a pane (>= 0), the scene or nothing. */
static int over (const lsys_viewer *v, double x, double y) {
  double px, py;
  return lsys_vpanes_hit(&v->panes, v->winw, v->winh, x, y, &px, &py);
}

static void onbutton (GLFWwindow *w, int button, int action, int mods) {
  lsys_viewer *v = self(w);
  if (action == GLFW_PRESS) {
    int k = over(v, v->lastx, v->lasty);
    if (v->button != 0 || k == LSYS_VPANE_NONE) return;
    if (k >= 0) {                 /* a pane: the caller draws with it */
      v->button = 4;
      v->pane = k;
      v->pbutton = button;
      paneevent(v, LSYS_VEV_POINTER, k, 0, mods, v->lastx, v->lasty, 0);
      return;
    }
    v->button = (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE ||
                 (mods & GLFW_MOD_SHIFT)) ? 2 : 1;
    if (v->button == 1 && (mods & GLFW_MOD_CONTROL) && capturing(v)) v->button = 3;
    v->px = v->lastx;
    v->py = v->lasty;
    v->moved = 0;
  } else if (action == GLFW_RELEASE && v->button == 4) {
    if (button != v->pbutton) return;
    paneevent(v, LSYS_VEV_POINTER, v->pane, 2, mods, v->lastx, v->lasty, 0);
    v->button = 0;
  } else if (action == GLFW_RELEASE && v->button != 0) {
    if (v->button == 3 && v->moved) dragevent(v, 2, v->lastx, v->lasty);
    else if (!v->moved && button == GLFW_MOUSE_BUTTON_LEFT) pick(v, v->lastx, v->lasty);
    v->button = 0;
  }
}

static void oncursor (GLFWwindow *w, double x, double y) {
  lsys_viewer *v = self(w);
  double dx = x - v->lastx, dy = y - v->lasty;
  v->lastx = x;
  v->lasty = y;
  if (v->button == 0) return;
  if (v->button == 4) {
    paneevent(v, LSYS_VEV_POINTER, v->pane, 1, 0, x, y, 0);
    return;
  }
  if (!v->moved && hypot(x - v->px, y - v->py) < CLICK_SLOP) return;
  if (!v->moved) {
    dx = x - v->px;
    dy = y - v->py;
    if (v->button == 3) dragevent(v, 0, v->px, v->py);
  }
  v->moved = 1;
  if (v->button == 3) dragevent(v, 1, x, y);
  else if (v->button == 1) orbit(v, dx, dy);
  else pan(v, dx, dy);
}

static void onscroll (GLFWwindow *w, double dx, double dy) {
  lsys_viewer *v = self(w);
  int k = over(v, v->lastx, v->lasty);
  (void)dx;
  if (k >= 0) paneevent(v, LSYS_VEV_SCROLL, k, 0, 0, v->lastx, v->lasty, dy);
  else if (k == LSYS_VPANE_SCENE) zoom(v, dy);
}

static void onrefresh (GLFWwindow *w) {
  self(w)->dirty = 1;
}

static void onresize (GLFWwindow *w, int width, int height) {
  (void)width; (void)height;
  self(w)->dirty = 1;
}

/* ---------------------------------------------------------------------- */
/* the thread */

static void started (lsys_viewer *v, int ok, const char *msg) {
  pthread_mutex_lock(&v->mu);
  v->started = 1;
  v->startok = ok;
  v->open = ok;
  v->st.open = ok;
  if (!ok) snprintf(v->starterr, sizeof v->starterr, "%s", msg);
  pthread_cond_broadcast(&v->cv);
  pthread_mutex_unlock(&v->mu);
}

/* Creates the window with 'samples' and makes its context current with
** the GL entry points loaded; 0 (window destroyed, message in err) when
** that fails. */
static int mkwindow (lsys_viewer *v, int samples, char *err, size_t nerr) {
  lsys_error e;
  G.WindowHint(GLFW_SAMPLES, samples);
  v->win = G.CreateWindow(v->o.width, v->o.height, "lsys", NULL, NULL);
  if (v->win == NULL) {
    snprintf(err, nerr, "cannot open a window with an OpenGL context: %s",
             lsys_glfwerr[0] ? lsys_glfwerr : "unknown error");
    return 0;
  }
  G.MakeContextCurrent(v->win);
  if (lsys_render_gl_load(&v->gl, lsys_glfwdl_getproc, &e) != LSYS_OK) {
    snprintf(err, nerr, "%s", e.msg);
    G.MakeContextCurrent(NULL);
    G.DestroyWindow(v->win);
    v->win = NULL;
    return 0;
  }
  return 1;
}

static int openwindow (lsys_viewer *v, char *err, size_t nerr) {
  lsys_glfwerr[0] = '\0';
  G.SetErrorCallback(lsys_glfwdl_onerror);
  if (!G.Init()) {
    snprintf(err, nerr, "cannot start GLFW: %s",
             lsys_glfwerr[0] ? lsys_glfwerr : "unknown error");
    return 0;
  }
  G.DefaultWindowHints();
  G.WindowHint(GLFW_VISIBLE, v->o.visible ? GLFW_TRUE : GLFW_FALSE);
  G.WindowHint(GLFW_DEPTH_BITS, 24);
  if (!mkwindow(v, v->o.samples, err, nerr) &&
      (v->o.samples == 0 || !mkwindow(v, 0, err, nerr))) {   /* no multisampling here? */
    G.Terminate();
    return 0;
  }
  /* A software renderer (llvmpipe under Xvfb, say) pays for every sample,
  ** and Mesa 22's llvmpipe leaves gaps in thin multisampled lines: no
  ** multisampling there. */
  if (v->o.samples > 0 && lsys_render_software(&v->gl)) {
    G.MakeContextCurrent(NULL);
    G.DestroyWindow(v->win);
    if (!mkwindow(v, 0, err, nerr)) {
      G.Terminate();
      return 0;
    }
  }
  G.SwapInterval(1);
  {
    lsys_glproc rp = lsys_glfwdl_getproc("glReadPixels"), rb = lsys_glfwdl_getproc("glReadBuffer");
    if (rp == NULL || rb == NULL) {
      snprintf(err, nerr, "the OpenGL context has no glReadPixels");
      G.DestroyWindow(v->win);
      G.Terminate();
      return 0;
    }
    memcpy(&v->shot.ReadPixels, &rp, sizeof rp);
    memcpy(&v->shot.ReadBuffer, &rb, sizeof rb);
    v->shot.PixelStorei = v->gl.PixelStorei;
  }
  G.SetWindowUserPointer(v->win, v);
  G.SetKeyCallback(v->win, onkey);
  G.SetMouseButtonCallback(v->win, onbutton);
  G.SetCursorPosCallback(v->win, oncursor);
  G.SetScrollCallback(v->win, onscroll);
  G.SetWindowRefreshCallback(v->win, onrefresh);
  G.SetFramebufferSizeCallback(v->win, onresize);
  G.GetWindowSize(v->win, &v->winw, &v->winh);
  return 1;
}

static void *run (void *arg) {
  lsys_viewer *v = (lsys_viewer *)arg;
  char err[256];
  lsys_vevent ev;
  if (!openwindow(v, err, sizeof err)) {
    started(v, 0, err);
    return NULL;
  }
  v->dirty = 1;
  started(v, 1, NULL);
  for (;;) {
    int keys[32], nkeys, quit, i;
    double wait = 0.5;
    pthread_mutex_lock(&v->mu);
    quit = v->quit;
    nkeys = v->nkeys;
    memcpy(keys, v->keys, sizeof keys);
    v->nkeys = 0;
    if (v->taken != v->serial) v->dirty = 1;
    v->taken = v->serial;
    if (v->shotreq) v->dirty = 1;
    pthread_mutex_unlock(&v->mu);
    if (quit || G.WindowShouldClose(v->win)) break;
    if (lsys_vpanes_take(&v->panes)) v->dirty = 1;
    G.GetWindowSize(v->win, &v->winw, &v->winh);
    lsys_vpanes_scene(&v->panes, v->winw, v->winh, v->sr);   /* before a fit */
    takemail(v);
    for (i = 0; i < nkeys; i++) key(v, keys[i], 0);
    if (v->playing) {
      double t = now();
      if (t >= v->nextt) {
        showframe(v, v->cur + 1);
        if (v->snap == NULL || (size_t)v->cur + 1 >= v->snap->nframes) v->playing = 0;
        v->nextt = fmax(v->nextt + 1 / v->rate, t);   /* no burst after a stall */
        v->dirty = 1;
      }
      if (v->playing) wait = fmax(v->nextt - now(), 0);
    }
    if (v->dirty) draw(v);
    G.WaitEventsTimeout(wait);
  }
  /* closing: say so first, so that nobody posts empty events to a dead GLFW */
  pthread_mutex_lock(&v->mu);
  v->open = 0;
  v->st.open = 0;
  event(v, LSYS_VEV_CLOSED, &ev);
  pushevent_locked(v, &ev);
  pthread_mutex_unlock(&v->mu);
  lsys_render_cache_release(&v->cache, &v->gl);
  lsys_vpanes_release(&v->panes, &v->gl);
  lsys_xpen_close(v->pen);
  v->pen = NULL;
  G.DestroyWindow(v->win);
  G.Terminate();
  v->win = NULL;
  return NULL;
}

/* ---------------------------------------------------------------------- */
/* the caller's side */

void lsys_viewer_defaults (lsys_viewer_opts *o) {
  memset(o, 0, sizeof *o);
  o->width = o->height = 800;
  o->samples = 4;
  o->visible = 1;
  o->status = 1;
}

static void freeviewer (lsys_viewer *v) {
  lsys_vlive_free(&v->live);
  lsys_vsnap_free(v->mail);
  lsys_vsnap_free(v->snap);
  lsys_render_cache_free(&v->cache);
  LSYS_FREE(v->ev);
  lsys_vshot_free(&v->shot);
  lsys_overlay_free(&v->text);
  lsys_vpanes_free(&v->panes);
  pthread_cond_destroy(&v->cv);
  pthread_mutex_destroy(&v->mu);
  LSYS_FREE(v);
}

lsys_viewer *lsys_viewer_open (const lsys_viewer_opts *o, lsys_error *e) {
  lsys_viewer *v;
  int ok;
  pthread_mutex_lock(&glfwlock);
  if (glfwbusy) {
    pthread_mutex_unlock(&glfwlock);
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "a viewer window is already open");
    return NULL;
  }
  if (lsys_glfwdl_load(e) != LSYS_OK) {
    pthread_mutex_unlock(&glfwlock);
    return NULL;
  }
  glfwbusy = 1;
  pthread_mutex_unlock(&glfwlock);
  v = (lsys_viewer *)LSYS_MALLOC(sizeof *v);
  if (v == NULL) goto nomem;
  memset(v, 0, sizeof *v);
  v->ev = (lsys_vevent *)LSYS_MALLOC(MAXEVENTS * sizeof *v->ev);
  if (v->ev == NULL) { LSYS_FREE(v); goto nomem; }
  pthread_mutex_init(&v->mu, NULL);
  pthread_cond_init(&v->cv, NULL);
  lsys_vpanes_init(&v->panes);
  lsys_vlive_init(&v->live);
  v->o = *o;
  if (v->o.width <= 0) v->o.width = 800;
  if (v->o.height <= 0) v->o.height = 800;
  if (v->o.samples < 0) v->o.samples = 0;
  v->cur = -1;
  v->rate = 2;
  v->st.frame = -1;
  v->st.pen = -1;
  if (pthread_create(&v->thread, NULL, run, v) != 0) {
    freeviewer(v);
    pthread_mutex_lock(&glfwlock);
    glfwbusy = 0;
    pthread_mutex_unlock(&glfwlock);
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot start the viewer thread");
    return NULL;
  }
  pthread_mutex_lock(&v->mu);
  while (!v->started) pthread_cond_wait(&v->cv, &v->mu);
  ok = v->startok;
  pthread_mutex_unlock(&v->mu);
  if (!ok) {
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "%s", v->starterr);
    pthread_join(v->thread, NULL);
    freeviewer(v);
    pthread_mutex_lock(&glfwlock);
    glfwbusy = 0;
    pthread_mutex_unlock(&glfwlock);
    return NULL;
  }
  return v;
nomem:
  pthread_mutex_lock(&glfwlock);
  glfwbusy = 0;
  pthread_mutex_unlock(&glfwlock);
  lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory for the viewer");
  return NULL;
}

/* Wakes the viewer thread (mu held). */
static void wake_locked (lsys_viewer *v) {
  if (v->open) G.PostEmptyEvent();
}

void lsys_viewer_post (lsys_viewer *v, lsys_vsnap *s) {
  lsys_vsnap *old;
  if (s->live && s->nframes > 0) {    /* the patches fill the one frame from empty */
    lsys_mesh_free(&s->frames[0].sc.mesh);
    lsys_mesh_init(&s->frames[0].sc.mesh);
  }
  pthread_mutex_lock(&v->mu);
  lsys_vlive_reset(&v->live, s->live && s->nframes == 1);
  old = v->mail;
  v->mail = s;
  v->posted = s;
  v->serial++;
  wake_locked(v);
  pthread_mutex_unlock(&v->mu);
  lsys_vsnap_free(old);          /* never taken: replaced by a newer one */
}

int lsys_viewer_patch (lsys_viewer *v, const lsys_scene *s, const size_t *r, size_t n,
                       int step, size_t count, const char *note) {
  int rc;
  pthread_mutex_lock(&v->mu);
  if ((rc = lsys_vlive_patch(&v->live, s, r, n, step, count, note)) == LSYS_OK) {
    rc = ++v->serial;
    wake_locked(v);
  }
  pthread_mutex_unlock(&v->mu);
  return rc;
}

int lsys_viewer_poll (lsys_viewer *v, lsys_vevent *ev, double timeout) {
  int got = 0;
  pthread_mutex_lock(&v->mu);
  if (v->nev == 0 && timeout > 0 && v->open) {
    struct timespec ts;
    double whole;
    clock_gettime(CLOCK_REALTIME, &ts);
    timeout += ts.tv_nsec * 1e-9;
    timeout = modf(timeout, &whole) ;
    ts.tv_sec += (time_t)whole;
    ts.tv_nsec = (long)(timeout * 1e9);
    while (v->nev == 0 && v->open)
      if (pthread_cond_timedwait(&v->cv, &v->mu, &ts) == ETIMEDOUT) break;
  }
  if (v->nev > 0) {
    *ev = v->ev[v->evhead];
    v->evhead = (v->evhead + 1) % MAXEVENTS;
    v->nev--;
    got = 1;
  }
  pthread_mutex_unlock(&v->mu);
  return got;
}

int lsys_viewer_pending (lsys_viewer *v) {
  int n;
  pthread_mutex_lock(&v->mu);
  n = (int)v->nev;
  pthread_mutex_unlock(&v->mu);
  return n;
}

int lsys_viewer_screenshot (lsys_viewer *v, const char *path) {
  int ok;
  pthread_mutex_lock(&v->mu);
  ok = v->open;
  if (ok) {
    snprintf(v->shotpath, sizeof v->shotpath, "%s", path != NULL ? path : "");
    v->shotreq = 1;
    wake_locked(v);
  }
  pthread_mutex_unlock(&v->mu);
  return ok ? LSYS_OK : LSYS_EARG;
}

/* Counts a request and wakes the viewer: drawn when state().serial reaches it. */
static int request (lsys_viewer *v) {
  int serial;
  pthread_mutex_lock(&v->mu);
  serial = ++v->serial;
  wake_locked(v);
  pthread_mutex_unlock(&v->mu);
  return serial;
}

int lsys_viewer_layout (lsys_viewer *v, const lsys_vlayout *lay) {
  lsys_vpanes_set_layout(&v->panes, lay);
  return request(v);
}

int lsys_viewer_image (lsys_viewer *v, int pane, const uint8_t *rgba, int w, int h) {
  int r = lsys_vpanes_set_image(&v->panes, pane, rgba, w, h);
  return r == LSYS_OK ? request(v) : r;
}

int lsys_viewer_text (lsys_viewer *v, const char *status, const char *help) {
  lsys_vpanes_set_text(&v->panes, status, help);
  return request(v);
}

int lsys_viewer_key (lsys_viewer *v, int k) {
  int serial;
  pthread_mutex_lock(&v->mu);
  if (v->nkeys < (int)(sizeof v->keys / sizeof v->keys[0])) v->keys[v->nkeys++] = k;
  serial = ++v->serial;
  wake_locked(v);
  pthread_mutex_unlock(&v->mu);
  return serial;
}

const lsys_vsnap *lsys_viewer_posted (lsys_viewer *v) {
  const lsys_vsnap *s;
  pthread_mutex_lock(&v->mu);
  s = v->open ? v->posted : NULL;
  pthread_mutex_unlock(&v->mu);
  return s;
}

int lsys_viewer_light (lsys_viewer *v, const lsys_vsnap *s, size_t k, lsys_vlight *l) {
  int serial = LSYS_EARG;
  pthread_mutex_lock(&v->mu);
  if (s != NULL && s == v->posted && k < s->nframes && s->frames[k].light == NULL) {
    s->frames[k].light = l;
    serial = ++v->serial;
    wake_locked(v);
  }
  pthread_mutex_unlock(&v->mu);
  return serial;
}

void lsys_viewer_state (lsys_viewer *v, lsys_vstate *st) {
  pthread_mutex_lock(&v->mu);
  *st = v->st;
  pthread_mutex_unlock(&v->mu);
}

void lsys_viewer_close (lsys_viewer *v) {
  if (v == NULL) return;
  pthread_mutex_lock(&v->mu);
  v->quit = 1;
  wake_locked(v);
  pthread_mutex_unlock(&v->mu);
  pthread_join(v->thread, NULL);
  freeviewer(v);
  pthread_mutex_lock(&glfwlock);
  glfwbusy = 0;
  pthread_mutex_unlock(&glfwlock);
}
