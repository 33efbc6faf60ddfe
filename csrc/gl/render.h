/*
** Drawing a scene with OpenGL (docs/drawing.md §6). One drawing path serves the
** offscreen renderer (osmesa.c) and the viewer window: the caller makes a
** GL context current and calls lsys_render_draw with that context's entry
** points. Camera fitting and projection are plain arithmetic and need no
** GL context (viewcam.c).
**
** Only fixed-function OpenGL 1.x calls are used (vertex arrays and
** glDrawElements), so any compatibility context will do. This header does
** not include the GL headers: a build without them still compiles the
** Lua binding against it.
*/
#ifndef LSYS_RENDER_H
#define LSYS_RENDER_H

#include "mesh.h"
#include "scene.h"
#include "texture.h"

/*
** The OpenGL entry points lsys calls, fetched through the context's own
** loader (OSMesaGetProcAddress, glfwGetProcAddress) rather than linked:
** lsys.core then does not load libOSMesa (and LLVM) until the first render,
** and an OSMesa context and a window context of another vendor can live in
** one process, each with its table. Types are the GL ABI's (GLenum =
** unsigned, GLsizei = int, GLfloat = float, GLboolean = unsigned char).
*/
#if defined(_WIN32)
#define LSYS_GLAPI __stdcall
#else
#define LSYS_GLAPI
#endif

typedef struct lsys_gl {
  unsigned (LSYS_GLAPI *GetError) (void);
  void (LSYS_GLAPI *GetFloatv) (unsigned pname, float *v);
  void (LSYS_GLAPI *GetIntegerv) (unsigned pname, int *v);
  void (LSYS_GLAPI *Viewport) (int x, int y, int w, int h);
  void (LSYS_GLAPI *ClearColor) (float r, float g, float b, float a);
  void (LSYS_GLAPI *ClearDepth) (double d);
  void (LSYS_GLAPI *Clear) (unsigned mask);
  void (LSYS_GLAPI *Finish) (void);
  void (LSYS_GLAPI *Enable) (unsigned cap);
  void (LSYS_GLAPI *Disable) (unsigned cap);
  void (LSYS_GLAPI *EnableClientState) (unsigned array);
  void (LSYS_GLAPI *DisableClientState) (unsigned array);
  void (LSYS_GLAPI *MatrixMode) (unsigned mode);
  void (LSYS_GLAPI *LoadMatrixd) (const double *m);
  void (LSYS_GLAPI *LoadIdentity) (void);
  void (LSYS_GLAPI *DepthFunc) (unsigned func);
  void (LSYS_GLAPI *DepthMask) (unsigned char flag);
  void (LSYS_GLAPI *BlendFunc) (unsigned sfactor, unsigned dfactor);
  void (LSYS_GLAPI *ShadeModel) (unsigned mode);
  void (LSYS_GLAPI *PolygonMode) (unsigned face, unsigned mode);
  void (LSYS_GLAPI *LineWidth) (float w);
  void (LSYS_GLAPI *Lightfv) (unsigned light, unsigned pname, const float *v);
  void (LSYS_GLAPI *LightModelfv) (unsigned pname, const float *v);
  void (LSYS_GLAPI *LightModeli) (unsigned pname, int v);
  void (LSYS_GLAPI *Materialfv) (unsigned face, unsigned pname, const float *v);
  void (LSYS_GLAPI *Materialf) (unsigned face, unsigned pname, float v);
  void (LSYS_GLAPI *ColorMaterial) (unsigned face, unsigned mode);
  void (LSYS_GLAPI *VertexPointer) (int size, unsigned type, int stride, const void *p);
  void (LSYS_GLAPI *NormalPointer) (unsigned type, int stride, const void *p);
  void (LSYS_GLAPI *ColorPointer) (int size, unsigned type, int stride, const void *p);
  void (LSYS_GLAPI *DrawElements) (unsigned mode, int count, unsigned type, const void *idx);
  /* textures (all OpenGL 1.1) */
  const unsigned char *(LSYS_GLAPI *GetString) (unsigned name);
  void (LSYS_GLAPI *GenTextures) (int n, unsigned *names);
  void (LSYS_GLAPI *DeleteTextures) (int n, const unsigned *names);
  void (LSYS_GLAPI *BindTexture) (unsigned target, unsigned name);
  void (LSYS_GLAPI *TexImage2D) (unsigned target, int level, int internalformat, int w, int h,
                                 int border, unsigned format, unsigned type, const void *px);
  void (LSYS_GLAPI *TexParameteri) (unsigned target, unsigned pname, int v);
  void (LSYS_GLAPI *TexEnvi) (unsigned target, unsigned pname, int v);
  void (LSYS_GLAPI *TexCoordPointer) (int size, unsigned type, int stride, const void *p);
  void (LSYS_GLAPI *PixelStorei) (unsigned pname, int v);
  void (LSYS_GLAPI *AlphaFunc) (unsigned func, float ref);
} lsys_gl;

typedef void (*lsys_glproc) (void);

/* Fills 'gl' with get("glClear") and so on. Returns LSYS_OK, or LSYS_EARG
** with e->msg naming the first entry point that 'get' did not find. */
int lsys_render_gl_load (lsys_gl *gl, lsys_glproc (*get) (const char *name), lsys_error *e);

/* 1 when the current context of 'gl' renders in software (llvmpipe, softpipe,
** swrast: Mesa on Xvfb, say), where every sample costs. */
int lsys_render_software (const lsys_gl *gl);

/* The camera (lsys_camera, LSYS_PERSPECTIVE, LSYS_PARALLEL) is the scene's:
** scene.h. */

/* Scratch arrays of lsys_render_draw, kept between frames so that
** drawing allocates nothing once they are large enough. */
typedef struct lsys_render_cache {
  uint32_t *idx;        /* triangle indices grouped by material */
  size_t idxcap;
  uint8_t *rgba;        /* diffuse colour per vertex, then per line end */
  size_t rgbacap;
  uint32_t *lidx;       /* thin line end indices grouped by width */
  size_t lidxcap;
  size_t *start;        /* group offsets */
  size_t startcap;
  float *wpos;          /* wide lines as triangles: clip coordinates (4 per vertex) */
  size_t wposcap;
  uint8_t *wrgba;       /* their colours */
  size_t wrgbacap;
  uint32_t *widx;       /* their triangles */
  size_t widxcap;
  uint32_t *tidx;       /* textured triangles grouped by material, before grouping by texture */
  size_t tidxcap;
  uint8_t *texok;       /* per texture index: 1 when it can be drawn */
  size_t texokcap;
  unsigned *texname;    /* per texture index: its GL texture name, 0 when not uploaded */
  size_t texnamecap;
  const lsys_texture **texkey;   /* with keep_textures: the texture each name holds */
  size_t texkeycap;
  size_t nkept;         /* with keep_textures: entries 1..nkept of texname are valid */
  uint8_t *texbuf;      /* a texture converted for uploading (grey, resampled) */
  size_t texbufcap;
} lsys_render_cache;

/* How to draw a scene: what the scene itself does not say (the camera,
** light, background, palette and textures are the scene's: scene.h). */
typedef struct lsys_render_opts {
  int width, height;        /* image size in pixels; default 800 x 800 */
  int x, y;                 /* lsys_render_draw: the viewport's lower left corner in the
                               framebuffer (a pane of a window; default 0, 0); the clear
                               still covers the whole framebuffer */
  int supersample;          /* offscreen: samples per pixel along each axis; default 3 */
  int transparent;          /* offscreen: background alpha 0 instead of 1 */
  int wireframe;            /* draw triangle edges only */
  int keep_textures;        /* with a cache: keep uploaded textures in it for the next
                               frames (a window redrawing the same scene); the caller
                               deletes them with lsys_render_cache_release */
  lsys_render_cache *cache; /* optional scratch kept by the caller; NULL: temporary */
  const lsys_gl *gl;        /* entry points of the current context (lsys_render_draw);
                               lsys_render_offscreen uses its own */
  const uint8_t *shade;     /* NULL, or one factor per mesh vertex (255: 1) scaling its
                               diffuse colour: baked shadows and occlusion (shade.h) */
  int sky;                  /* 1: a vertical gradient behind the scene (backdrop.c) */
  float sky_top[3], sky_bottom[3];   /* its colours at the top and bottom edges */
  int floor;                /* 1: a lit ground quad facing up (the window's ground; a
                               picture's is part of its mesh, to take shadows) */
  double floor_rect[5];     /* its height y, then x0, z0, x1, z1 */
  float floor_rgb[3];       /* its colour */
} lsys_render_opts;

/* The sky and ground colours lsys.render gives a shaded picture (docs/drawing.md). */
extern const float lsys_render_sky_top[3], lsys_render_sky_bottom[3], lsys_render_ground[3];

/*
** Whether what lies in the box lo .. hi, drawn with triangles, is a 3D plant:
** the box is deep in every direction (at least 1/20 of its largest extent), as
** lsys.render.solid decides for `lsys render`'s shading.
*/
int lsys_render_solid (const double lo[3], const double hi[3]);

/* Sets o's floor under the box lo .. hi: just under its lowest point, the
** square centred under it that a picture's ground starts from
** (lsys_shade_add_ground's, size 1.6), in the ground colour. A window's camera
** moves, so the floor is not grown to what it sees. */
void lsys_render_setfloor (lsys_render_opts *o, const double lo[3], const double hi[3]);

/* A window's sky (when 'sky') and floor (when 'ground', and the eye is above
** the plant's foot) in o for what camera 'cam' frames, its bounds (has_bounds)
** a 3D plant's (lsys_render_solid), as lsys render shades one; the bounds grow
** over the floor, so that the near and far planes reach it. */
void lsys_render_backdrops (lsys_render_opts *o, lsys_camera *cam, int sky, int ground);

/* Draws the sky gradient of o over the whole viewport, behind everything
** (without writing depth), then loads the camera's matrices proj and view
** again and leaves the depth test on. */
void lsys_render_backdrop (const lsys_gl *gl, const lsys_render_opts *o, const double proj[16],
                           const double view[16]);

/* Scales the RGB of the n colours rgba (4 bytes each) by the factors f[0 .. n)
** (255: 1), leaving alpha (backdrop.c). */
void lsys_render_shade (uint8_t *rgba, const uint8_t *f, size_t n);

/* Fills 'o' with the defaults above (no cache, no GL). */
void lsys_render_defaults (lsys_render_opts *o);

/* Frees the arrays of 'c' and leaves it empty (reusable). Textures kept
** with keep_textures must have been released first. */
void lsys_render_cache_free (lsys_render_cache *c);

/* Deletes the texture objects kept in 'c' (keep_textures) with 'gl', whose
** context must be current. A kept texture is reused while the same
** lsys_texture pointer comes back: release before freeing or changing the
** textures the cache has seen. */
void lsys_render_cache_release (lsys_render_cache *c, const lsys_gl *gl);

/*
** Computes camera 'cam' looking at mesh 'm' (its bounding box fits the
** view and gives the near and far planes) for a w x h viewport: 'proj' and 'view' are
** OpenGL matrices (column-major, ready for glLoadMatrixd). Returns LSYS_OK,
** or LSYS_EARG when w or h is not positive, the eye and the target coincide,
** or 'dir' or 'up' is the zero vector.
*/
int lsys_render_camera (const lsys_mesh *m, const lsys_camera *cam, int w, int h,
                        double proj[16], double view[16]);

/* lsys_render_camera for what scene 's' draws (NULL: nothing): its mesh,
** or with instances every instance's part under its transform. */
int lsys_render_camera_scene (const lsys_scene *s, const lsys_camera *cam, int w, int h,
                              double proj[16], double view[16]);

/*
** Projects the world point 'p' into a w x h window: out[0] is x in pixels
** from the left edge, out[1] is y in pixels from the TOP edge (image rows,
** and GLFW's cursor coordinates), out[2] the depth in [0, 1] between the
** near and far planes. Returns 1 when the point is in front of the eye, 0
** when it is behind it (out[] is then meaningless).
*/
int lsys_render_project (const double proj[16], const double view[16], int w, int h,
                         const double p[3], double out[3]);

/*
** The ray through the point (nx, ny) of the picture of lsys_render_camera's
** matrices, in normalised coordinates (-1 .. 1 from the left and the bottom
** edge): its origin (on the eye's plane in a parallel view, the eye in a
** perspective one) and its unit direction, in world space.
*/
void lsys_render_unproject (const double proj[16], const double view[16], double nx,
                            double ny, double origin[3], double dir[3]);

/*
** Draws scene 's' into the current GL context's framebuffer of fbw x fbh
** pixels, through the scene's camera, with its palette (a grey default
** when it has none): clears to the scene's background, lights with its key
** light, a fill opposite it, a sky and a ground light and ambient (render.c),
** lights two-sided vertices on both faces, and draws lines with their widths
** scaled by fbh / o->height (the supersampling factor offscreen, the content
** scale in a window). Lines narrower than LSYS_RENDER_WIDE pixels are GL
** lines; wider ones are flat bands facing the eye, tapered from one end's
** width to the other's, with round ends so that polylines join smoothly.
**
** Textures: a triangle whose first vertex has texture index k in
** 1..s->ntex, with s->tex[k - 1] non-NULL and holding pixels, is textured
** with it (other indices draw untextured). Each texture in use is uploaded
** once per call and deleted before returning, unless o->keep_textures. Modulate multiplies the lit
** colour by the texel (by its intensity alone for an 'intensity' texture);
** decal replaces the lit colour by the texel where the texel is opaque
** (OpenGL's GL_DECAL: lighting does not reach those texels), blending by
** its alpha elsewhere. In modulate mode on opaque materials, texels with
** alpha below 1/2 are cut out (leaf silhouettes). Wireframe drawing ignores
** textures. The texture matrix is set to flip v (texture.h).
**
** Leaves the GL state it changed set for the next frame.
** Returns LSYS_OK, LSYS_ENOMEM, or LSYS_EARG (no o->gl, a bad camera or a GL
** error), with e->msg set.
*/
#define LSYS_RENDER_WIDE 3

int lsys_render_draw (const lsys_scene *s, const lsys_render_opts *o, int fbw, int fbh,
                      lsys_error *e);

/* osmesa.c ------------------------------------------------------------- */

/* Largest number of samples (supersampled pixels) of one offscreen render;
** the supersampling factor is lowered to stay within it. */
#define LSYS_RENDER_MAX_SAMPLES (64 * 1024 * 1024)

/*
** Renders scene 's' offscreen into 'rgba' (o->width * o->height * 4 bytes, top
** row first, straight alpha). Draws at o->supersample times the size along
** each axis, lowered to fit OSMesa's maximum size and
** LSYS_RENDER_MAX_SAMPLES, and box-filters down. libOSMesa is loaded at the
** first call and one context is kept for the process; calls from several
** threads take turns. Returns LSYS_OK or an error with e->msg set (e.g.
** libOSMesa missing, an image larger than OSMesa allows).
*/
int lsys_render_offscreen (const lsys_scene *s, const lsys_render_opts *o, uint8_t *rgba,
                           lsys_error *e);

/* The largest image OSMesa can draw, asked once; returns LSYS_OK, or an
** error when libOSMesa cannot be loaded or no context can be created. */
int lsys_render_maxsize (int *maxw, int *maxh, lsys_error *e);

/* Destroys the kept OSMesa context and its scratch (at exit, for leak
** checkers); the next render creates them again. */
void lsys_render_shutdown (void);

#endif
