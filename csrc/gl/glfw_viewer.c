/*
** The viewer window (viewer.h): GLFW on its own thread, drawing snapshots
** with render.c.
**
** Threads. The caller's thread (Lua) and the viewer thread share only the
** fields under 'mu': the mailbox, the event queue, requests (close, keys,
** screenshots) and the published state. Everything else -- the window, the
** GL context, the snapshot being shown, the camera -- belongs to the viewer
** thread. The caller wakes the viewer with glfwPostEmptyEvent, which GLFW
** allows from any thread, and only while the viewer is open (checked under
** 'mu', so never after glfwTerminate).
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
** fits the frame shown, keeping the direction.
*/
#define _POSIX_C_SOURCE 200809L
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/gl.h>
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "font.h"
#include "pngio.h"
#include "turtle.h"
#include "vec3.h"
#include "viewer.h"

#define PI 3.14159265358979323846

#define MAXEVENTS 1024          /* queued events beyond this are dropped (oldest first) */
#define CLICK_SLOP 4.0          /* a press and release closer than this (pixels) is a click */
#define PICK_TOL 6.0            /* pixels around a thin line that still pick it */
#define ORBIT_SPEED 0.008       /* radians per pixel dragged */

/* ---------------------------------------------------------------------- */
/* libglfw, opened at the first window */

#ifndef LSYS_GLFW_SONAME
#define LSYS_GLFW_SONAME "libglfw.so.3"
#endif

static const char *const glfwlibs[] = { LSYS_GLFW_SONAME, "libglfw.so.3", "libglfw.so", NULL };

static struct {
  void *lib;
  int (*Init) (void);
  void (*Terminate) (void);
  GLFWerrorfun (*SetErrorCallback) (GLFWerrorfun cb);
  void (*DefaultWindowHints) (void);
  void (*WindowHint) (int hint, int value);
  GLFWwindow *(*CreateWindow) (int w, int h, const char *title, GLFWmonitor *m,
                               GLFWwindow *share);
  void (*DestroyWindow) (GLFWwindow *w);
  int (*WindowShouldClose) (GLFWwindow *w);
  void (*SetWindowShouldClose) (GLFWwindow *w, int value);
  void (*SetWindowTitle) (GLFWwindow *w, const char *title);
  void (*MakeContextCurrent) (GLFWwindow *w);
  GLFWglproc (*GetProcAddress) (const char *name);
  void (*SwapBuffers) (GLFWwindow *w);
  void (*SwapInterval) (int interval);
  void (*WaitEventsTimeout) (double timeout);
  void (*PostEmptyEvent) (void);
  void (*GetFramebufferSize) (GLFWwindow *w, int *width, int *height);
  void (*GetWindowSize) (GLFWwindow *w, int *width, int *height);
  void (*SetWindowUserPointer) (GLFWwindow *w, void *p);
  void *(*GetWindowUserPointer) (GLFWwindow *w);
  GLFWkeyfun (*SetKeyCallback) (GLFWwindow *w, GLFWkeyfun cb);
  GLFWmousebuttonfun (*SetMouseButtonCallback) (GLFWwindow *w, GLFWmousebuttonfun cb);
  GLFWcursorposfun (*SetCursorPosCallback) (GLFWwindow *w, GLFWcursorposfun cb);
  GLFWscrollfun (*SetScrollCallback) (GLFWwindow *w, GLFWscrollfun cb);
  GLFWwindowrefreshfun (*SetWindowRefreshCallback) (GLFWwindow *w, GLFWwindowrefreshfun cb);
  GLFWframebuffersizefun (*SetFramebufferSizeCallback) (GLFWwindow *w,
                                                        GLFWframebuffersizefun cb);
  double (*GetTime) (void);
} G;

static pthread_mutex_t glfwlock = PTHREAD_MUTEX_INITIALIZER;   /* loading; one window */
static int glfwbusy;            /* a viewer is open (GLFW is process-wide) */
static char glfwerr[192];       /* the last GLFW error, written on the viewer thread */

static void onerror (int code, const char *msg) {
  snprintf(glfwerr, sizeof glfwerr, "%s (GLFW error 0x%x)", msg ? msg : "?", (unsigned)code);
}

static int loadglfw (lsys_error *e) {
#define SYM(f) {&G.f, sizeof G.f, "glfw" #f}
  const struct { void *fn; size_t size; const char *name; } syms[] = {
    SYM(Init), SYM(Terminate), SYM(SetErrorCallback), SYM(DefaultWindowHints),
    SYM(WindowHint), SYM(CreateWindow), SYM(DestroyWindow), SYM(WindowShouldClose),
    SYM(SetWindowShouldClose), SYM(SetWindowTitle), SYM(MakeContextCurrent),
    SYM(GetProcAddress), SYM(SwapBuffers), SYM(SwapInterval), SYM(WaitEventsTimeout),
    SYM(PostEmptyEvent), SYM(GetFramebufferSize), SYM(GetWindowSize),
    SYM(SetWindowUserPointer), SYM(GetWindowUserPointer), SYM(SetKeyCallback),
    SYM(SetMouseButtonCallback), SYM(SetCursorPosCallback), SYM(SetScrollCallback),
    SYM(SetWindowRefreshCallback), SYM(SetFramebufferSizeCallback), SYM(GetTime)
  };
#undef SYM
  char first[200] = "";
  size_t i;
  if (G.lib != NULL) return LSYS_OK;
  for (i = 0; glfwlibs[i] != NULL && G.lib == NULL; i++) {
    G.lib = dlopen(glfwlibs[i], RTLD_NOW | RTLD_LOCAL);
    if (G.lib == NULL && i == 0) snprintf(first, sizeof first, "%s", dlerror());
  }
  if (G.lib == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "cannot load libglfw for the viewer window (%s); install libglfw3 "
                         "(./setup.sh does)", first);
  for (i = 0; i < sizeof syms / sizeof syms[0]; i++) {
    void *p = dlsym(G.lib, syms[i].name);
    if (p == NULL) {
      dlclose(G.lib);
      G.lib = NULL;
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "libglfw has no %s (GLFW 3.2 or later "
                           "is needed)", syms[i].name);
    }
    memcpy(syms[i].fn, &p, syms[i].size);
  }
  return LSYS_OK;
}

/* glfwGetProcAddress, in the form lsys_gl_load wants. */
static lsys_glproc getproc (const char *name) {
  GLFWglproc f = G.GetProcAddress(name);
  lsys_glproc g;
  memcpy(&g, &f, sizeof g);
  return g;
}

/* ---------------------------------------------------------------------- */
/* snapshots */

lsys_vsnap *lsys_vsnap_new (size_t n) {
  lsys_vsnap *s = (lsys_vsnap *)LSYS_MALLOC(sizeof *s);
  size_t k;
  if (s == NULL) return NULL;
  memset(s, 0, sizeof *s);
  s->rate = 2;
  if (n > 0) {
    s->frames = (lsys_vframe *)LSYS_MALLOC(n * sizeof *s->frames);
    if (s->frames == NULL) { LSYS_FREE(s); return NULL; }
    memset(s->frames, 0, n * sizeof *s->frames);
    for (k = 0; k < n; k++) {
      lsys_mesh_init(&s->frames[k].mesh);
      lsys_render_defaults(&s->frames[k].ro);
      s->frames[k].step = -1;
    }
  }
  s->nframes = n;
  return s;
}

void lsys_vsnap_free (lsys_vsnap *s) {
  size_t k;
  if (s == NULL) return;
  for (k = 0; k < s->nframes; k++) {
    lsys_mesh_free(&s->frames[k].mesh);
    LSYS_FREE(s->frames[k].pal);
    LSYS_FREE(s->frames[k].picks);
    LSYS_FREE(s->frames[k].lines);
  }
  LSYS_FREE(s->frames);
  for (k = 0; k < (size_t)s->ntex; k++) lsys_texture_free(&s->tex[k]);
  LSYS_FREE(s->tex);
  LSYS_FREE(s);
}

/* ---------------------------------------------------------------------- */
/* picking */

long lsys_vpick_find (const lsys_vframe *f, const double proj[16], const double view[16],
                      int w, int h, double x, double y, double tol) {
  /* the camera's right axis, for the projected radius: row 0 of 'view' */
  double right[3] = {view[0], view[4], view[8]};
  long best = -1;
  int bestdirect = 0;
  double bestd = 0, bestz = 0;
  size_t k;
  for (k = 0; k < f->npicks; k++) {
    const lsys_vpick *p = &f->picks[k];
    double a[3], b[3], pa[3], pb[3], q[3], qr[3], pq[3], pr[3];
    double dx, dy, len2, t, d, rpx = 0, z;
    int i, direct;
    for (i = 0; i < 3; i++) { a[i] = p->p0[i]; b[i] = p->p1[i]; }
    if (!lsys_render_project(proj, view, w, h, a, pa) ||
        !lsys_render_project(proj, view, w, h, b, pb))
      continue;
    dx = pb[0] - pa[0];
    dy = pb[1] - pa[1];
    len2 = dx * dx + dy * dy;
    t = len2 > 0 ? ((x - pa[0]) * dx + (y - pa[1]) * dy) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    d = hypot(pa[0] + t * dx - x, pa[1] + t * dy - y);
    z = pa[2] + t * (pb[2] - pa[2]);
    if (z < 0 || z > 1) continue;          /* clipped by the near or far plane */
    if (p->radius > 0) {        /* the drawn width, projected where the click is nearest */
      for (i = 0; i < 3; i++) {
        q[i] = a[i] + t * (b[i] - a[i]);
        qr[i] = q[i] + p->radius * right[i];
      }
      if (lsys_render_project(proj, view, w, h, q, pq) &&
          lsys_render_project(proj, view, w, h, qr, pr))
        rpx = hypot(pr[0] - pq[0], pr[1] - pq[1]);
    }
    if (d > (rpx > tol ? rpx : tol)) continue;
    /* a click inside the drawn width is a direct hit: the nearest to the eye
    ** wins; otherwise (thin lines, near misses) the nearest on screen */
    direct = rpx > 0 && d <= rpx;
    if (best < 0 || (direct && !bestdirect) ||
        (direct && bestdirect && z < bestz) ||
        (!direct && !bestdirect && (d < bestd || (d == bestd && z < bestz)))) {
      best = (long)k;
      bestdirect = direct;
      bestd = d;
      bestz = z;
    }
  }
  return best;
}

/* ---------------------------------------------------------------------- */
/* the viewer */

typedef struct vcamera {
  double target[3], f[3], u[3];   /* looks along f, up u (orthonormal) */
  double dist;                    /* perspective: eye = target - dist f */
  double halfh;                   /* parallel: half the image height */
  int valid;
} vcamera;

struct lsys_viewer {
  pthread_t thread;
  pthread_mutex_t mu;
  pthread_cond_t cv;
  /* shared, under mu */
  lsys_vsnap *mail;               /* posted, not yet taken */
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
  /* the viewer thread's own */
  GLFWwindow *win;
  lsys_gl gl;
  void (LSYS_GLAPI *ReadPixels) (int x, int y, int w, int h, unsigned fmt, unsigned type,
                                 void *px);
  void (LSYS_GLAPI *ReadBuffer) (unsigned mode);
  lsys_vsnap *snap;
  const lsys_texture **texp;      /* pointers to snap->tex, for render opts */
  long cur;                       /* frame shown */
  vcamera cam, home;              /* current and arrival cameras */
  lsys_render_cache cache;
  int winw, winh, fbw, fbh;
  int button;                     /* 0 none, 1 orbiting, 2 panning, 3 a tool's drag */
  double px, py, lastx, lasty;    /* press position, last cursor position */
  int moved;
  int playing;
  double rate, nextt;
  int wireframe, help, dirty;
  double drawms;                  /* smoothed time to draw a frame */
  int shotseq;
  uint8_t *pixels;                /* screenshot scratch */
  size_t pixcap;
  float *tv;                      /* text quads */
  uint8_t *tc;
  uint32_t *ti;
  size_t tvcap, tccap, ticap, ntq;
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
  return v->snap != NULL && v->snap->capture;
}

static const lsys_vframe *curframe (const lsys_viewer *v) {
  return v->snap != NULL && v->cur >= 0 && (size_t)v->cur < v->snap->nframes
         ? &v->snap->frames[v->cur] : NULL;
}

/* The render options of frame f seen through the viewer's camera. */
static void frameopts (const lsys_viewer *v, const lsys_vframe *f, lsys_render_opts *o) {
  *o = f->ro;
  o->width = v->winw;
  o->height = v->winh;
  o->pal = f->pal;
  o->npal = f->npal;
  o->tex = v->texp;
  o->ntex = v->snap->ntex;
  o->wireframe = v->wireframe;
  o->gl = &v->gl;
  o->transparent = 0;
  if (v->cam.valid) {
    lsys_camera *c = &o->cam;
    c->has_eye = c->has_target = c->has_up = 1;
    c->twist = 0;               /* in u already */
    vcopy(c->target, v->cam.target);
    vcopy(c->up, v->cam.u);
    if (c->projection == LSYS_PARALLEL) {
      vlin(c->eye, v->cam.target, 1, v->cam.f, -1.0);
      c->halfh = v->cam.halfh;
      c->zoom = 1;
    } else
      vlin(c->eye, v->cam.target, 1, v->cam.f, -v->cam.dist);
  }
}

/*
** Fits frame f with its view's camera (home: as the view says; otherwise
** keeping the current direction and up) and sets v->cam from the result.
*/
static void fit (lsys_viewer *v, const lsys_vframe *f, int home) {
  lsys_render_opts o = f->ro;
  double proj[16], view[16], eye[3], lo[3], hi[3];
  int i;
  if (!home && v->cam.valid) {
    o.cam.has_eye = 0;
    o.cam.has_up = 1;
    o.cam.twist = 0;
    vcopy(o.cam.dir, v->cam.f);
    vcopy(o.cam.up, v->cam.u);
    o.cam.has_target = 0;
    o.cam.zoom = 1;
  }
  o.cam.halfh = 0;
  if (lsys_render_camera(&f->mesh, &o, v->winw, v->winh, proj, view) != LSYS_OK) return;
  /* rows of the view matrix: right, up, -forward; eye = -R^T t */
  for (i = 0; i < 3; i++) {
    v->cam.u[i] = view[4 * i + 1];
    v->cam.f[i] = -view[4 * i + 2];
    eye[i] = -(view[4 * i] * view[12] + view[4 * i + 1] * view[13] +
               view[4 * i + 2] * view[14]);
  }
  if (o.cam.has_target) vcopy(v->cam.target, o.cam.target);
  else if (lsys_mesh_bounds(&f->mesh, lo, hi) && isfinite(lo[0] + lo[1] + lo[2] + hi[0] +
                                                          hi[1] + hi[2]))
    for (i = 0; i < 3; i++) v->cam.target[i] = 0.5 * (lo[i] + hi[i]);
  else
    vlin(v->cam.target, eye, 1, v->cam.f, 1.0);
  {
    double d[3];
    vlin(d, eye, 1, v->cam.target, -1);
    v->cam.dist = vlen(d);
  }
  if (!(v->cam.dist > 0)) v->cam.dist = 1;
  v->cam.halfh = proj[5] > 0 ? 1 / proj[5] : 1;   /* proj[5] = zoom / halfh (parallel) */
  v->cam.valid = 1;
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

/* Takes a posted snapshot, if any. */
static void takemail (lsys_viewer *v) {
  lsys_vsnap *s;
  pthread_mutex_lock(&v->mu);
  s = v->mail;
  v->mail = NULL;
  pthread_mutex_unlock(&v->mu);
  if (s == NULL) return;
  lsys_render_cache_release(&v->cache, &v->gl);    /* textures of the old snapshot */
  if (v->snap != NULL) lsys_vsnap_free(v->snap);
  LSYS_FREE(v->texp);
  v->texp = NULL;
  v->snap = s;
  if (s->ntex > 0) {
    int k;
    v->texp = (const lsys_texture **)LSYS_MALLOC((size_t)s->ntex * sizeof *v->texp);
    if (v->texp == NULL) s->ntex = 0;
    for (k = 0; k < s->ntex; k++) v->texp[k] = &s->tex[k];
  }
  v->rate = s->rate > 0 ? s->rate : 2;
  v->playing = 0;
  v->cur = s->nframes > 0 ? (long)(s->first < s->nframes ? s->first : s->nframes - 1) : -1;
  if (s->title[0] != '\0') G.SetWindowTitle(v->win, s->title);
  if (v->cur >= 0 && (!s->keep_camera || !v->cam.valid)) fit(v, &s->frames[v->cur], 1);
  v->dirty = 1;
}

/* ---------------------------------------------------------------------- */
/* text: the status line and the help, as quads of font pixels */

static int textquad (lsys_viewer *v, float x, float y, float w, float h, const uint8_t c[4]) {
  size_t n = v->ntq, i;
  float *p;
  if (lsys_grow((void **)&v->tv, &v->tvcap, 8 * (n + 1), sizeof *v->tv) ||
      lsys_grow((void **)&v->tc, &v->tccap, 16 * (n + 1), 1) ||
      lsys_grow((void **)&v->ti, &v->ticap, 6 * (n + 1), sizeof *v->ti))
    return LSYS_ENOMEM;
  p = v->tv + 8 * n;
  p[0] = x;     p[1] = y;
  p[2] = x + w; p[3] = y;
  p[4] = x + w; p[5] = y + h;
  p[6] = x;     p[7] = y + h;
  for (i = 0; i < 4; i++) memcpy(v->tc + 16 * n + 4 * i, c, 4);
  v->ti[6 * n + 0] = (uint32_t)(4 * n);
  v->ti[6 * n + 1] = (uint32_t)(4 * n + 1);
  v->ti[6 * n + 2] = (uint32_t)(4 * n + 2);
  v->ti[6 * n + 3] = (uint32_t)(4 * n);
  v->ti[6 * n + 4] = (uint32_t)(4 * n + 2);
  v->ti[6 * n + 5] = (uint32_t)(4 * n + 3);
  v->ntq = n + 1;
  return LSYS_OK;
}

/* Lays out 's' with its top left corner at (x, y) (framebuffer pixels, y
** down), each font pixel s x s. */
static void text (lsys_viewer *v, const char *s, float x, float y, float px,
                  const uint8_t c[4]) {
  float x0 = x;
  for (; *s; s++) {
    int row, col;
    if (*s == '\n') { x = x0; y += (LSYS_FONT_H + 3) * px; continue; }
    /* letters with descenders are drawn within the 7 rows: lowered by 2,
    ** their bowls sit on the baseline with the other small letters */
    float dy = strchr("gjpqy", *s) != NULL ? 2 * px : 0;
    for (row = 0; row < LSYS_FONT_H; row++) {
      unsigned bits = lsys_font_row((unsigned char)*s, row);
      for (col = 0; col < LSYS_FONT_W; col++)
        if (bits & (1u << (LSYS_FONT_W - 1 - col)))
          textquad(v, x + col * px, y + dy + row * px, px, px, c);
    }
    x += (LSYS_FONT_W + 1) * px;
  }
}

/* Thousands separated by spaces: 1234567 -> "1 234 567". */
static void count (char *buf, size_t n, size_t x) {
  char tmp[32];
  int len = snprintf(tmp, sizeof tmp, "%zu", x), i, j = 0;
  for (i = 0; i < len && (size_t)j + 2 < n; i++) {
    if (i > 0 && (len - i) % 3 == 0) buf[j++] = ' ';
    buf[j++] = tmp[i];
  }
  buf[j] = '\0';
}

static const char helptext[] =
  "drag: orbit   right-drag / shift-drag: pan   scroll: zoom\n"
  "click: pick a module\n"
  "left / right: step back / forward   home / end: first / last\n"
  "space: animate   + / -: faster / slower\n"
  "R: reset view   F: fit   W: wireframe   S: screenshot\n"
  "H: this help   Esc / Q: quit";

/* Draws the status line (and the help) over the picture. */
static void overlay (lsys_viewer *v) {
  static const uint8_t fg[4] = {255, 255, 255, 255}, bg[4] = {0, 0, 0, 140};
  const lsys_gl *gl = &v->gl;
  const lsys_vframe *f = curframe(v);
  char line[256], a[32], b[32], c[32];
  float px = (float)(v->winh > 0 ? 2.0 * v->fbh / v->winh : 2.0);
  float lh = (LSYS_FONT_H + 4) * px;
  double m[16] = {0};
  size_t n;
  v->ntq = 0;
  if (f == NULL)
    snprintf(line, sizeof line, "waiting for a scene");
  else {
    int at = 0;
    count(a, sizeof a, f->nmodules);
    count(b, sizeof b, f->mesh.nt);
    count(c, sizeof c, f->mesh.nl);
    if (f->step >= 0 && v->snap->nframes > 1)
      at = snprintf(line, sizeof line, "step %d (%ld/%zu)  ", f->step, v->cur + 1,
                    v->snap->nframes);
    else if (f->step >= 0)
      at = snprintf(line, sizeof line, "step %d  ", f->step);
    snprintf(line + at, sizeof line - (size_t)at, "%s modules  %s triangles  %s lines  "
             "%.0f fps%s%s", a, b, c, v->drawms > 0 ? 1000 / v->drawms : 0.0,
             v->playing ? "  playing" : "", v->wireframe ? "  wireframe" : "");
  }
  n = strlen(line);
  if (v->fbw < (float)(n + 12) * (LSYS_FONT_W + 1) * px && px > 1) {   /* smaller to fit */
    px = px / 2 < 1 ? 1 : px / 2;
    lh = (LSYS_FONT_H + 4) * px;
  }
  textquad(v, 0, (float)v->fbh - lh, (float)v->fbw, lh, bg);
  text(v, line, 2 * px, (float)v->fbh - lh + 2 * px, px, fg);
  if (v->help) {
    int lines = 1;
    const char *s;
    for (s = helptext; *s; s++) lines += *s == '\n';
    textquad(v, 0, 0, (float)v->fbw, lines * (LSYS_FONT_H + 3) * px + 4 * px, bg);
    text(v, helptext, 2 * px, 2 * px, px, fg);
  }
  else if (n + 14 < (size_t)(v->fbw / ((LSYS_FONT_W + 1) * px)))
    text(v, "H: help", (float)v->fbw - 9 * (LSYS_FONT_W + 1) * px,
         (float)v->fbh - lh + 2 * px, px, fg);
  if (v->ntq == 0) return;
  /* pixels, y down: x' = 2x/w - 1, y' = 1 - 2y/h */
  m[0] = 2.0 / v->fbw;
  m[5] = -2.0 / v->fbh;
  m[10] = 1;
  m[12] = -1;
  m[13] = 1;
  m[15] = 1;
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(m);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadIdentity();
  gl->Disable(GL_DEPTH_TEST);
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_TEXTURE_2D);
  gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  gl->Enable(GL_BLEND);
  gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(2, GL_FLOAT, 0, v->tv);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, v->tc);
  gl->DrawElements(GL_TRIANGLES, (int)(6 * v->ntq), GL_UNSIGNED_INT, v->ti);
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
  gl->Disable(GL_BLEND);
}

/* ---------------------------------------------------------------------- */
/* drawing and screenshots */

/* The frame's highlight lines, with the scene's camera (render_draw leaves
** its matrices loaded), unlit: first those depth-tested against the scene,
** then those drawn on top. */
static void drawlines (lsys_viewer *v, const lsys_vframe *f) {
  const lsys_gl *gl = &v->gl;
  float scale = v->winh > 0 ? (float)v->fbh / (float)v->winh : 1;
  size_t k;
  int pass;
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_TEXTURE_2D);
  gl->DepthFunc(GL_LEQUAL);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  for (pass = 0; pass < 2; pass++) {
    if (pass == 0) gl->Enable(GL_DEPTH_TEST);
    else gl->Disable(GL_DEPTH_TEST);
    for (k = 0; k < f->nlines; k++) {     /* few lines: one call each, own width */
      static const uint32_t idx[2] = {0, 1};
      const lsys_vline *l = &f->lines[k];
      float pos[6];
      uint8_t col[8];
      if ((l->ontop != 0) != pass) continue;
      memcpy(pos, l->p0, sizeof l->p0);
      memcpy(pos + 3, l->p1, sizeof l->p1);
      memcpy(col, l->rgba, 4);
      memcpy(col + 4, l->rgba, 4);
      gl->LineWidth(l->width * scale > 1 ? l->width * scale : 1);
      gl->VertexPointer(3, GL_FLOAT, 0, pos);
      gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, col);
      gl->DrawElements(GL_LINES, 2, GL_UNSIGNED_INT, idx);
    }
  }
  gl->Enable(GL_DEPTH_TEST);
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
  gl->LineWidth(1);
}

static double now (void) {
  return G.GetTime();
}

/* A file name lsys-NNN.png that does not exist yet in the current directory. */
static void autoname (lsys_viewer *v, char *buf, size_t n) {
  int k;
  for (k = 0; k < 1000; k++) {
    snprintf(buf, n, "lsys-%03d.png", (v->shotseq + k) % 1000 + 1);
    if (access(buf, F_OK) != 0) break;
  }
  v->shotseq = (v->shotseq + k + 1) % 1000;
}

/* Reads the back buffer (just drawn) and writes it to the requested file. */
static void screenshot (lsys_viewer *v, const char *path) {
  lsys_vevent ev;
  lsys_error e;
  size_t row = 4 * (size_t)v->fbw, y;
  event(v, LSYS_VEV_SCREENSHOT, &ev);
  if (path[0] == '\0') autoname(v, ev.path, sizeof ev.path);
  else snprintf(ev.path, sizeof ev.path, "%s", path);
  if (lsys_grow((void **)&v->pixels, &v->pixcap, row * (size_t)v->fbh + row, 1) != LSYS_OK) {
    snprintf(ev.msg, sizeof ev.msg, "not enough memory for a %dx%d screenshot", v->fbw, v->fbh);
    pushevent(v, &ev);
    return;
  }
  v->ReadBuffer(GL_BACK);
  v->gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  v->ReadPixels(0, 0, v->fbw, v->fbh, GL_RGBA, GL_UNSIGNED_BYTE, v->pixels);
  for (y = 0; y < (size_t)v->fbh / 2; y++) {          /* GL rows go up; PNG rows go down */
    uint8_t *a = v->pixels + y * row, *b = v->pixels + ((size_t)v->fbh - 1 - y) * row;
    uint8_t *t = v->pixels + (size_t)v->fbh * row;
    memcpy(t, a, row);
    memcpy(a, b, row);
    memcpy(b, t, row);
  }
  if (lsys_png_write(ev.path, v->pixels, v->fbw, v->fbh, 0, &e) == LSYS_OK) ev.ok = 1;
  else snprintf(ev.msg, sizeof ev.msg, "%s", e.msg);
  pushevent(v, &ev);
}

static void draw (lsys_viewer *v) {
  const lsys_vframe *f = curframe(v);
  lsys_render_opts o;
  lsys_error e;
  char shot[512];
  int wantshot;
  double t0 = now(), ms;
  G.GetFramebufferSize(v->win, &v->fbw, &v->fbh);
  G.GetWindowSize(v->win, &v->winw, &v->winh);
  if (v->fbw <= 0 || v->fbh <= 0 || v->winw <= 0 || v->winh <= 0) return;   /* iconified */
  if (f != NULL) {
    frameopts(v, f, &o);
    o.cache = &v->cache;
    o.keep_textures = 1;
    if (lsys_render_draw(&f->mesh, &o, v->fbw, v->fbh, &e) != LSYS_OK) {
      fprintf(stderr, "lsys viewer: %s\n", e.msg);
      v->gl.ClearColor(0.3f, 0, 0, 1);
      v->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
  } else {
    v->gl.Viewport(0, 0, v->fbw, v->fbh);
    v->gl.ClearColor(1, 1, 1, 1);
    v->gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  if (f != NULL && f->nlines > 0) drawlines(v, f);
  if (v->o.status) overlay(v);
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
  v->st.serial = v->taken;
  v->st.width = v->winw;
  v->st.height = v->winh;
  v->st.fbwidth = v->fbw;
  v->st.fbheight = v->fbh;
  v->st.frame = v->cur;
  v->st.nframes = v->snap ? (long)v->snap->nframes : 0;
  v->st.playing = v->playing;
  v->st.wireframe = v->wireframe;
  v->st.capture = capturing(v);
  if (f != NULL) lsys_render_camera(&f->mesh, &o, v->winw, v->winh, v->st.proj, v->st.view);
  pthread_cond_broadcast(&v->cv);
  pthread_mutex_unlock(&v->mu);
}

/* ---------------------------------------------------------------------- */
/* input */

static void rotate (double v[3], const double axis[3], double angle) {
  vrotate(v, axis, angle);
}

static void orbit (lsys_viewer *v, double dx, double dy) {
  double r[3], *up = v->home.valid ? v->home.u : v->cam.u;
  vcross(r, v->cam.f, v->cam.u);
  rotate(v->cam.f, up, -dx * ORBIT_SPEED);        /* turntable: about the view's up */
  rotate(v->cam.u, up, -dx * ORBIT_SPEED);
  rotate(r, up, -dx * ORBIT_SPEED);
  rotate(v->cam.f, r, -dy * ORBIT_SPEED);         /* then about the camera's right */
  rotate(v->cam.u, r, -dy * ORBIT_SPEED);
  vnorm(v->cam.f);
  vcross(r, v->cam.f, v->cam.u);                  /* keep the frame orthonormal */
  vnorm(r);
  vcross(v->cam.u, r, v->cam.f);
  v->dirty = 1;
}

/* World units per window pixel at the target. */
static double pixelsize (const lsys_viewer *v) {
  const lsys_vframe *f = curframe(v);
  double h = v->winh > 0 ? v->winh : 1;
  if (f != NULL && f->ro.cam.projection == LSYS_PARALLEL) return 2 * v->cam.halfh / h;
  {
    double fov = f != NULL && f->ro.cam.fov > 0 ? f->ro.cam.fov : 30;
    double zoom = f != NULL && f->ro.cam.zoom > 0 ? f->ro.cam.zoom : 1;
    return 2 * v->cam.dist * tan(fov * PI / 360) / zoom / h;
  }
}

static void pan (lsys_viewer *v, double dx, double dy) {
  double r[3], s = pixelsize(v);
  vcross(r, v->cam.f, v->cam.u);
  vnorm(r);
  vlin(v->cam.target, v->cam.target, 1, r, -dx * s);
  vlin(v->cam.target, v->cam.target, 1, v->cam.u, dy * s);
  v->dirty = 1;
}

static void zoom (lsys_viewer *v, double steps) {
  double k = pow(0.88, steps);
  v->cam.dist *= k;
  v->cam.halfh *= k;
  if (v->cam.dist < 1e-9) v->cam.dist = 1e-9;
  if (v->cam.halfh < 1e-9) v->cam.halfh = 1e-9;
  v->dirty = 1;
}

static void pick (lsys_viewer *v, double x, double y) {
  const lsys_vframe *f = curframe(v);
  lsys_render_opts o;
  lsys_vevent ev;
  double proj[16], view[16];
  long k = -1;
  if (f == NULL) return;
  frameopts(v, f, &o);
  if (lsys_render_camera(&f->mesh, &o, v->winw, v->winh, proj, view) == LSYS_OK)
    k = lsys_vpick_find(f, proj, view, v->winw, v->winh, x, y, PICK_TOL);
  event(v, k >= 0 ? LSYS_VEV_PICK : LSYS_VEV_MISS, &ev);
  ev.x = x;
  ev.y = y;
  if (k >= 0) {
    ev.module = f->picks[k].module;
    ev.kind = f->picks[k].kind;
  }
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
    case GLFW_KEY_H: case GLFW_KEY_SLASH:
      v->help = !v->help;
      v->dirty = 1;
      break;
    case GLFW_KEY_S:
      pthread_mutex_lock(&v->mu);
      v->shotreq = 1;
      v->shotpath[0] = '\0';
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

static void onbutton (GLFWwindow *w, int button, int action, int mods) {
  lsys_viewer *v = self(w);
  if (action == GLFW_PRESS) {
    if (v->button != 0) return;
    v->button = (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE ||
                 (mods & GLFW_MOD_SHIFT)) ? 2 : 1;
    if (v->button == 1 && (mods & GLFW_MOD_CONTROL) && capturing(v)) v->button = 3;
    v->px = v->lastx;
    v->py = v->lasty;
    v->moved = 0;
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
  (void)dx;
  zoom(self(w), dy);
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

static int softrenderer (const lsys_gl *gl) {
  const char *r = (const char *)gl->GetString(GL_RENDERER);
  return r != NULL && (strstr(r, "llvmpipe") != NULL || strstr(r, "softpipe") != NULL ||
                       strstr(r, "swrast") != NULL);
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
             glfwerr[0] ? glfwerr : "unknown error");
    return 0;
  }
  G.MakeContextCurrent(v->win);
  if (lsys_gl_load(&v->gl, getproc, &e) != LSYS_OK) {
    snprintf(err, nerr, "%s", e.msg);
    G.MakeContextCurrent(NULL);
    G.DestroyWindow(v->win);
    v->win = NULL;
    return 0;
  }
  return 1;
}

static int openwindow (lsys_viewer *v, char *err, size_t nerr) {
  glfwerr[0] = '\0';
  G.SetErrorCallback(onerror);
  if (!G.Init()) {
    snprintf(err, nerr, "cannot start GLFW: %s", glfwerr[0] ? glfwerr : "unknown error");
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
  if (v->o.samples > 0 && softrenderer(&v->gl)) {
    G.MakeContextCurrent(NULL);
    G.DestroyWindow(v->win);
    if (!mkwindow(v, 0, err, nerr)) {
      G.Terminate();
      return 0;
    }
  }
  G.SwapInterval(1);
  {
    lsys_glproc rp = getproc("glReadPixels"), rb = getproc("glReadBuffer");
    if (rp == NULL || rb == NULL) {
      snprintf(err, nerr, "the OpenGL context has no glReadPixels");
      G.DestroyWindow(v->win);
      G.Terminate();
      return 0;
    }
    memcpy(&v->ReadPixels, &rp, sizeof rp);
    memcpy(&v->ReadBuffer, &rb, sizeof rb);
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
  lsys_vsnap_free(v->mail);
  lsys_vsnap_free(v->snap);
  LSYS_FREE(v->texp);
  lsys_render_cache_free(&v->cache);
  LSYS_FREE(v->ev);
  LSYS_FREE(v->pixels);
  LSYS_FREE(v->tv);
  LSYS_FREE(v->tc);
  LSYS_FREE(v->ti);
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
  if (loadglfw(e) != LSYS_OK) {
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
  v->o = *o;
  if (v->o.width <= 0) v->o.width = 800;
  if (v->o.height <= 0) v->o.height = 800;
  if (v->o.samples < 0) v->o.samples = 0;
  v->cur = -1;
  v->rate = 2;
  v->st.frame = -1;
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
  pthread_mutex_lock(&v->mu);
  old = v->mail;
  v->mail = s;
  v->serial++;
  wake_locked(v);
  pthread_mutex_unlock(&v->mu);
  lsys_vsnap_free(old);          /* never taken: replaced by a newer one */
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

int lsys_viewer_key (lsys_viewer *v, int k) {
  int serial;
  pthread_mutex_lock(&v->mu);
  if (v->nkeys < (int)(sizeof v->keys / sizeof v->keys[0])) v->keys[v->nkeys++] = k;
  serial = ++v->serial;
  wake_locked(v);
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
