/*
** Offscreen rendering with OSMesa (render.h): the scene is drawn by
** lsys_render_draw into a supersampled buffer, then box-filtered down.
**
** libOSMesa is opened with dlopen at the first render rather than linked:
** it pulls in LLVM, which would cost every start of lsys (and every test
** run under valgrind) tens of megabytes and milliseconds for a feature
** most runs do not use. Only its header is needed to build.
**
** Creating a context starts llvmpipe's threads and takes tens of
** milliseconds, so one context (and the drawing scratch) is kept for the
** process, behind a mutex: renders from several threads take turns.
*/
#define _POSIX_C_SOURCE 200809L
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "dynlib.h"
#include "render.h"

/* Names tried in turn (dynlib.h): the library found when lsys was
** configured, then the usual sonames, then the development symlink. */
#ifndef LSYS_OSMESA_SONAME
#define LSYS_OSMESA_SONAME "libOSMesa.so.8"
#endif

static const char *const libnames[] = {
  LSYS_OSMESA_SONAME, "libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so", NULL
};

typedef OSMesaContext (GLAPIENTRY *createfn) (GLenum, GLint, GLint, GLint, OSMesaContext);
typedef GLboolean (GLAPIENTRY *makecurrentfn) (OSMesaContext, void *, GLenum, GLsizei,
                                               GLsizei);
typedef void (GLAPIENTRY *pixelstorefn) (GLint, GLint);
typedef void (GLAPIENTRY *getintegervfn) (GLint, GLint *);
typedef void (GLAPIENTRY *destroyfn) (OSMesaContext);
typedef OSMESAproc (GLAPIENTRY *getprocfn) (const char *);

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

static struct {
  void *lib;                  /* never closed: Mesa does not support unloading */
  createfn create;
  makecurrentfn makecurrent;
  pixelstorefn pixelstore;
  getintegervfn getintegerv;
  destroyfn destroy;
  getprocfn getproc;
  lsys_gl gl;
  OSMesaContext ctx;
  int maxw, maxh;
  lsys_render_cache cache;
} S;

/* OSMesaGetProcAddress, in the form lsys_render_gl_load wants. */
static lsys_glproc getproc (const char *name) {
  OSMESAproc f = S.getproc(name);
  lsys_glproc g;
  memcpy(&g, &f, sizeof g);
  return g;
}

static int loadlib (lsys_error *e) {
  const lsys_dynsym syms[] = {
    {&S.create, sizeof S.create, "OSMesaCreateContextExt"},
    {&S.makecurrent, sizeof S.makecurrent, "OSMesaMakeCurrent"},
    {&S.pixelstore, sizeof S.pixelstore, "OSMesaPixelStore"},
    {&S.getintegerv, sizeof S.getintegerv, "OSMesaGetIntegerv"},
    {&S.destroy, sizeof S.destroy, "OSMesaDestroyContext"},
    {&S.getproc, sizeof S.getproc, "OSMesaGetProcAddress"}
  };
  char why[200];
  const char *missing;
  if (S.lib != NULL) return LSYS_OK;
  S.lib = lsys_dynlib_open(libnames, why, sizeof why);
  if (S.lib == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "cannot load OSMesa (%s): install libosmesa6 (./setup.sh does)", why);
  missing = lsys_dynlib_syms(S.lib, syms, sizeof syms / sizeof syms[0]);
  if (missing != NULL) {
    dlclose(S.lib);
    S.lib = NULL;
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the OSMesa library lacks %s", missing);
  }
  return LSYS_OK;
}

/* Loads the library and creates the context, asking its limits once. */
static int setup (lsys_error *e) {
  GLint mw = 0, mh = 0, vp[2] = {0, 0};
  uint32_t pixel;
  int st;
  if (S.ctx != NULL) return LSYS_OK;
  if ((st = loadlib(e)) != LSYS_OK) return st;
  S.ctx = S.create(OSMESA_RGBA, 24, 0, 0, NULL);
  if (S.ctx == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "OSMesa context creation failed");
  /* entry points and limits can only be asked with a current context */
  if (!S.makecurrent(S.ctx, &pixel, GL_UNSIGNED_BYTE, 1, 1)) {
    st = lsys_seterror(e, LSYS_EARG, (size_t)-1, "OSMesa cannot make its context current");
  } else if ((st = lsys_render_gl_load(&S.gl, getproc, e)) == LSYS_OK) {
    S.getintegerv(OSMESA_MAX_WIDTH, &mw);
    S.getintegerv(OSMESA_MAX_HEIGHT, &mh);
    S.gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    S.maxw = vp[0] > 0 && vp[0] < mw ? vp[0] : mw > 0 ? mw : 4096;
    S.maxh = vp[1] > 0 && vp[1] < mh ? vp[1] : mh > 0 ? mh : 4096;
  }
  S.makecurrent(NULL, NULL, 0, 0, 0);
  if (st != LSYS_OK) {
    S.destroy(S.ctx);
    S.ctx = NULL;
  }
  return st;
}

int lsys_render_maxsize (int *maxw, int *maxh, lsys_error *e) {
  int st;
  pthread_mutex_lock(&lock);
  st = setup(e);
  *maxw = S.maxw;
  *maxh = S.maxh;
  pthread_mutex_unlock(&lock);
  return st;
}

void lsys_render_shutdown (void) {
  pthread_mutex_lock(&lock);
  if (S.ctx != NULL) S.destroy(S.ctx);
  S.ctx = NULL;
  lsys_render_cache_free(&S.cache);
  pthread_mutex_unlock(&lock);
}

/* Averages each ss x ss block of 'src' (W = w ss wide, top row first) into
** one pixel of 'dst'. With 'alpha', colours are weighted by their alpha so
** that the transparent background does not tint the edges. */
static void boxfilter (uint8_t *dst, const uint8_t *src, int w, int h, int ss, int alpha) {
  size_t W = (size_t)w * ss, n = (size_t)ss * ss;
  int x, y, i, j;
  for (y = 0; y < h; y++) {
    for (x = 0; x < w; x++) {
      const uint8_t *block = src + 4 * ((size_t)y * ss * W + (size_t)x * ss);
      uint32_t r = 0, g = 0, b = 0, a = 0;
      uint8_t *d = dst + 4 * ((size_t)y * w + x);
      for (j = 0; j < ss; j++) {
        const uint8_t *p = block + 4 * j * W;
        for (i = 0; i < ss; i++, p += 4) {
          uint32_t k = alpha ? p[3] : 1;
          r += p[0] * k; g += p[1] * k; b += p[2] * k; a += p[3];
        }
      }
      if (!alpha) {
        d[0] = (uint8_t)((r + n / 2) / n);
        d[1] = (uint8_t)((g + n / 2) / n);
        d[2] = (uint8_t)((b + n / 2) / n);
      } else if (a == 0) {                /* all background: keep its colour */
        memcpy(d, block, 3);
      } else {
        d[0] = (uint8_t)((r + a / 2) / a);
        d[1] = (uint8_t)((g + a / 2) / a);
        d[2] = (uint8_t)((b + a / 2) / a);
      }
      d[3] = (uint8_t)((a + n / 2) / n);
    }
  }
}

/* The body of lsys_render_offscreen, with the lock held. */
static int render (const lsys_scene *sc, const lsys_render_opts *o, uint8_t *rgba,
                   lsys_error *e) {
  lsys_render_opts oo = *o;
  int w = o->width, h = o->height, ss = o->supersample < 1 ? 1 : o->supersample, st;
  uint8_t *buf;
  if ((st = setup(e)) != LSYS_OK) return st;
  if (w > S.maxw || h > S.maxh)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "image size %dx%d exceeds OSMesa's limit of %dx%d", w, h, S.maxw,
                         S.maxh);
  /* the supersampled colour and depth buffers (8 bytes a sample) within OSMesa's
  ** limits, LSYS_RENDER_MAX_SAMPLES and the memory budget */
  while (ss > 1 && ((long long)w * ss > S.maxw || (long long)h * ss > S.maxh ||
                    (long long)w * h * ss * ss > LSYS_RENDER_MAX_SAMPLES ||
                    (double)w * h * ss * ss * 8 > (double)lsys_common_memory_limit()))
    ss--;
  /* without supersampling, draw straight into the caller's buffer */
  buf = ss == 1 ? rgba : (uint8_t *)LSYS_MALLOC((size_t)w * ss * h * ss * 4);
  if (buf == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory for a %dx%d image",
                         w * ss, h * ss);
  if (!S.makecurrent(S.ctx, buf, GL_UNSIGNED_BYTE, w * ss, h * ss)) {
    st = lsys_seterror(e, LSYS_EARG, (size_t)-1, "OSMesa cannot draw a %dx%d image", w * ss,
                       h * ss);
  } else {
    S.pixelstore(OSMESA_Y_UP, 0);               /* row 0 is the top row */
    if (oo.cache == NULL) oo.cache = &S.cache;
    oo.gl = &S.gl;
    st = lsys_render_draw(sc, &oo, w * ss, h * ss, e);
    S.gl.Finish();
    S.makecurrent(NULL, NULL, 0, 0, 0);         /* the context forgets 'buf' */
    if (st == LSYS_OK && ss > 1) boxfilter(rgba, buf, w, h, ss, o->transparent);
  }
  if (buf != rgba) LSYS_FREE(buf);
  return st;
}

int lsys_render_offscreen (const lsys_scene *sc, const lsys_render_opts *o, uint8_t *rgba,
                           lsys_error *e) {
  int st;
  if (o->width <= 0 || o->height <= 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "bad image size %dx%d", o->width,
                         o->height);
  pthread_mutex_lock(&lock);
  st = render(sc, o, rgba, e);
  pthread_mutex_unlock(&lock);
  return st;
}
