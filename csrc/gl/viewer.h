/*
** The interactive viewer window (docs/viewer.md): a GLFW window with its own
** thread and GL context, drawing with render.c what the caller hands over.
**
** The caller (the Lua binding) builds a snapshot -- the frames to show, one
** per derivation step, with their meshes, palettes, textures and pick
** records -- and posts it; the viewer takes ownership, and from then on the
** snapshot is immutable and private to the viewer thread, but for the light
** colours the caller may give its frames (lsys_viewer_light, vlight.h). A newer post
** replaces an older one not yet taken (a mailbox of one). What happens in
** the window comes back as events (picks, screenshots written, the window
** closed) that the caller polls, so the caller's thread never waits on the
** window and the window never waits on the caller.
**
** libglfw is opened with dlopen when the first window opens, as OSMesa is
** (osmesa.c): lsys.core does not need it, nor a display, to load. GLFW
** requires its calls to come from one thread; here that is the viewer
** thread, which is fine on X11 and Wayland (not on macOS, where GLFW must
** run on the main thread).
*/
#ifndef LSYS_VIEWER_H
#define LSYS_VIEWER_H

#include "render.h"
#include "vpanes.h"

/* Something that can be picked: a segment from p0 to p1 (p0 = p1 for a
** sphere, disc, polygon or surface), with the module that drew it. */
typedef struct lsys_vpick {
  float p0[3], p1[3];
  float radius;                 /* half the width in world units (0: lines in pixels) */
  uint32_t module;              /* index in the string (0-based) */
  uint8_t kind;                 /* the turtle record's kind (LSYS_REC_*) */
} lsys_vpick;

/* A line drawn over a frame (highlights): from p0 to p1, 'width' pixels. */
typedef struct lsys_vline {
  float p0[3], p1[3];
  uint8_t rgba[4];
  float width;
  int ontop;                    /* drawn over everything (not depth-tested), after the rest */
} lsys_vline;

struct lsys_vlight;

/* One picture: a scene with what picking and highlighting it need. */
typedef struct lsys_vframe {
  lsys_scene sc;                /* owned mesh and palette (no records); camera, light and
                                   background of the view; textures: the snapshot's, set
                                   when drawn; a population's parts and instances (owned) */
  lsys_vpick *picks;            /* owned; a population's in its prototypes' coordinates */
  size_t npicks;
  size_t *partpicks;            /* owned, a population's: the picks of part p are
                                   partpicks[p] .. partpicks[p + 1] - 1 (NULL otherwise) */
  lsys_vline *lines;            /* owned: drawn over the scene (depth-tested) */
  size_t nlines;
  size_t nmodules;              /* length of the string it was drawn from */
  int step;                     /* derivation step, or -1 when unknown */
  int hasbounds;                /* the viewer's: bounds[] holds the mesh's (0: to find) */
  double bounds[6];
  uint32_t *leafr;              /* owned: the leaves' triangles, ranges [a, b) (vlight.h) */
  size_t nleafr;
  struct lsys_vlight *light;    /* owned: the light colours (vlight.h), NULL until the
                                   caller gives them (lsys_viewer_light, under the lock) */
} lsys_vframe;

/* What is shown: frames 0..nframes-1 (usually steps 0..n), textures shared
** by all frames (texture index k of a mesh is tex[k - 1]; texp[k - 1]
** points at it, the array a frame's scene borrows). */
typedef struct lsys_vsnap {
  lsys_vframe *frames;
  size_t nframes;
  size_t first;                 /* the frame shown when the snapshot arrives */
  lsys_texture *tex;            /* owned, ntex of them */
  const lsys_texture **texp;    /* owned: &tex[0] .. &tex[ntex - 1] */
  int ntex;
  double rate;                  /* animation speed in frames per second (> 0) */
  int keep_camera;              /* 1: keep the current camera (a reload), 0: fit anew */
  int capture;                  /* 1: a tool (lsys arrange) takes the keys and Ctrl-drags:
                                   every key press comes back as a KEY event, the arrows
                                   no longer step, and a left drag begun with Ctrl held
                                   comes back as DRAG events instead of orbiting */
  char title[200];              /* window title (the model's name) */
  char framesdir[512];          /* where the S key saves every frame while animating
                                   ("": lsys-frames in the current directory) */
  int live;                     /* 1: one frame, grown in place by lsys_viewer_patch (its
                                   mesh as posted is ignored: the patches fill it) */
  int light;                    /* the L key's colours by light: 1 on, 0 off, -1 (the
                                   default) as they were */
  int sky, ground;              /* 1: a 3D frame (lsys_render_solid) is drawn over the sky
                                   gradient, on a ground, as lsys render shades it (the G
                                   key turns both off) */
} lsys_vsnap;

/* A new empty snapshot with room for n frames (each frame's scene
** initialised: empty, no palette), or NULL when out of memory (vsnap.c). */
lsys_vsnap *lsys_vsnap_new (size_t n);

/* Gives 's' room for n textures (tex and texp, zeroed; ntex = n). LSYS_OK
** or LSYS_ENOMEM. */
int lsys_vsnap_textures (lsys_vsnap *s, int n);
void lsys_vsnap_free (lsys_vsnap *s);

/* The bounds of what frame f's scene draws (lo, hi; lsys_scene_bounds) into
** b, found once for each state of the mesh: whoever changes it clears
** f->hasbounds. */
void lsys_vsnap_frame_bounds (lsys_vframe *f, double b[6]);

/* The status line under frame 'cur' of 's' (which must exist) into line[n]:
** "step 3 (4/6)  1 234 modules  ...", or for a live snapshot "tick 12  300
** limbs  3 600 triangles  60 fps  <note>". */
void lsys_vsnap_status (const lsys_vsnap *s, long cur, double fps, int playing, int wireframe,
                        const char *note, char *line, size_t n);

typedef struct lsys_viewer_opts {
  int width, height;            /* window size in screen coordinates (default 800 x 800) */
  int samples;                  /* multisampling (default 4; 0 off) */
  int visible;                  /* 1 (default): show the window */
  int status;                   /* 1 (default): draw the status line */
} lsys_viewer_opts;

void lsys_viewer_defaults (lsys_viewer_opts *o);

enum {
  LSYS_VEV_NONE = 0,
  LSYS_VEV_PICK,                /* a click on a pickable thing (frame, module, kind, x, y) */
  LSYS_VEV_MISS,                /* a click on nothing (frame, x, y) */
  LSYS_VEV_SCREENSHOT,          /* a screenshot was written (path) or failed (msg) */
  LSYS_VEV_STEP,                /* the frame shown changed (frame) */
  LSYS_VEV_CLOSED,              /* the window was closed (by the user or an error: msg) */
  LSYS_VEV_KEY,                 /* capture: a key pressed (key: GLFW key code, mods) */
  LSYS_VEV_DRAG,                /* capture: a Ctrl-drag (phase 0 begin, 1 move, 2 end; x, y) */
  LSYS_VEV_POINTER,             /* panes: a button pressed (phase 0), the pointer moved with
                                   it held (1), released (2) over 'pane'; x, y in the pixels
                                   of the pane's image; button (GLFW's), mods */
  LSYS_VEV_SCROLL,              /* panes: the wheel over 'pane' (scroll: notches, up > 0) */
  LSYS_VEV_FRAMES,              /* the S key while animating: every frame saved through the
                                   current camera into the folder 'path' ('count' pictures,
                                   of steps 'first' to 'step') or not (msg says why) */
  LSYS_VEV_LIGHT                /* the L key: leaves coloured by their light (ok 1) or not
                                   (ok 0); the caller gives the frames their colours */
};

typedef struct lsys_vevent {
  int type;
  int ok;                       /* SCREENSHOT: 1 written, 0 failed (msg says why); LIGHT */
  long frame;                   /* the frame index shown (-1 when none) */
  long step;                    /* that frame's step */
  uint32_t module;              /* PICK: the module */
  int kind;                     /* PICK: the record's kind */
  long plant;                   /* PICK in a population: the instance (1-based), else 0 */
  double x, y;                  /* PICK, MISS, DRAG: window coordinates */
  int key, mods, phase;         /* KEY, DRAG, POINTER */
  int pane, button;             /* POINTER, SCROLL */
  double scroll;                /* SCROLL */
  double pressure;              /* POINTER: the pen's pressure in [0, 1] (xpen.h), -1 none */
  long count, first;            /* FRAMES: the pictures written, the first one's step */
  char path[512];               /* SCREENSHOT: the file; FRAMES: the folder */
  char msg[256];                /* SCREENSHOT, FRAMES failure, CLOSED by an error */
} lsys_vevent;

typedef struct lsys_viewer lsys_viewer;

/* Opens the window on its thread and waits until it is on screen. Returns
** NULL with e->msg set when libglfw is missing, no display can be opened
** or no GL context created. */
lsys_viewer *lsys_viewer_open (const lsys_viewer_opts *o, lsys_error *e);

/* Hands 's' over to the viewer (which frees it); never blocks on drawing. */
void lsys_viewer_post (lsys_viewer *v, lsys_vsnap *s);

/*
** Live frames (incremental growth, grow.h): after posting a snapshot with
** 'live' set, the caller sends the state of its scene 's' at each tick: the
** vertex ranges r[0 .. 2n) changed in place since the last patch
** (lsys_scene_take_ranges), while new vertices, triangles and lines are found
** by comparing sizes (they are only ever appended). The viewer copies those
** into a stage of its own at once and from there into the frame it draws,
** never the whole mesh; the palette is copied when it changed. 'step' and
** 'count' (limbs) and 'note' (or NULL) go on the status line. The first patch
** after a live post copies everything. Returns the request's serial number
** (lsys_viewer_key), LSYS_EARG (< 0) when no live snapshot was posted or the
** mesh shrank, LSYS_ENOMEM.
*/
int lsys_viewer_patch (lsys_viewer *v, const lsys_scene *s, const size_t *r, size_t n,
                       int step, size_t count, const char *note);

/*
** The stage of live frames (vlive.c): what lsys_viewer_patch copies from the
** caller's scene and the viewer takes into its frame, under the viewer's
** lock. lsys_vlive_reset starts over (on: a live snapshot was posted, so that
** the next take fills the frame from empty); lsys_vlive_patch returns LSYS_OK,
** LSYS_EARG (not on, or the mesh shrank) or LSYS_ENOMEM; lsys_vlive_take
** brings frame f (empty or taken from this stage) up to date, copies the note,
** and returns 1 when it changed f (0: nothing new, or out of memory: the
** next take tries again).
*/
typedef struct lsys_vlive {
  lsys_scene stage;             /* the caller's scene as last patched (mesh, palette) */
  size_t pend[2 * (LSYS_SCENE_NDIRTY + 1)], npend;   /* ranges the frame lacks */
  int on, chg, palchg;          /* live; changed since taken; its palette too */
  int step;                     /* the status line's tick, count and note */
  size_t count;
  char note[64];
} lsys_vlive;

void lsys_vlive_init (lsys_vlive *l);
void lsys_vlive_free (lsys_vlive *l);
void lsys_vlive_reset (lsys_vlive *l, int on);
int lsys_vlive_patch (lsys_vlive *l, const lsys_scene *s, const size_t *r, size_t n,
                      int step, size_t count, const char *note);
int lsys_vlive_take (lsys_vlive *l, lsys_vframe *f, char note[64]);

/* Takes the next event into 'ev'. Waits up to 'timeout' seconds (0: do not
** wait) for one; returns 1 with an event, 0 without. */
int lsys_viewer_poll (lsys_viewer *v, lsys_vevent *ev, double timeout);

/* The number of events waiting to be polled. */
int lsys_viewer_pending (lsys_viewer *v);

/* Asks for a screenshot of the next frame drawn, written to 'path' as a PNG
** (the S key's path; NULL: lsys-NNN.png in the current directory); the
** SCREENSHOT event tells the outcome. (The S key pressed while animating
** saves every frame instead: FRAMES.) Returns LSYS_OK, or LSYS_EARG when
** the window is closed. */
int lsys_viewer_screenshot (lsys_viewer *v, const char *path);

/* Asks the window to act as if a key was pressed (one of the keys of the
** window: 'R', 'F', 'W', 'S', ' ', and LSYS_VKEY_* below). Returns the
** request's serial number: once lsys_vstate.serial reaches it, a picture
** drawn after the key (and everything posted before it) is on screen. */
#define LSYS_VKEY_REDRAW 1      /* no key: just draw again */
#define LSYS_VKEY_RIGHT 262
#define LSYS_VKEY_LEFT  263
#define LSYS_VKEY_HOME  268
#define LSYS_VKEY_END   269
int lsys_viewer_key (lsys_viewer *v, int key);

/* The state of the window as last drawn. */
typedef struct lsys_vstate {
  int open;                     /* 0 once closed */
  int drawn;                    /* frames drawn so far */
  double drawms;                /* the time to draw one, smoothed (ms, swap included) */
  int serial;                   /* requests (posts, keys) handled before the last picture */
  int width, height;            /* window size in screen coordinates */
  int fbwidth, fbheight;        /* framebuffer size in pixels */
  long frame, nframes;          /* the frame shown (-1: none yet) and how many there are */
  int playing;                  /* animating through the frames */
  int wireframe;
  int light;                    /* leaves coloured by their light (the L key) */
  double proj[16], view[16];    /* the camera of the last picture drawn */
  int capture;                  /* the snapshot shown captures keys and drags */
  int scene[4];                 /* the scene's rectangle in the window (x, y, w, h): the
                                   whole window unless a layout gives panes */
  int pen;                      /* 1: a pressure device is read (after the first press
                                   on a pane), 0: none, -1: not looked for yet */
  char pendesc[256];            /* its names, or why there is none */
} lsys_vstate;

void lsys_viewer_state (lsys_viewer *v, lsys_vstate *st);

/*
** Panes (vpanes.h): splits the window into the scene and image panes
** (lay->on 0: the scene fills the window again); posts an RGBA image
** (w * h * 4 bytes, top row first, copied) for pane k; sets the status line
** ('status', "" for the usual one) and the help text ('help', "" for the
** usual; NULL leaves either as it is). While a layout is on, every key
** press comes back as a KEY event (as with capture) and the mouse over a
** pane as POINTER and SCROLL events. Each returns the request's serial
** number (lsys_viewer_key); the image LSYS_EARG or LSYS_ENOMEM (< 0) when
** it cannot be taken.
*/
int lsys_viewer_layout (lsys_viewer *v, const lsys_vlayout *lay);
int lsys_viewer_image (lsys_viewer *v, int pane, const uint8_t *rgba, int w, int h);
int lsys_viewer_text (lsys_viewer *v, const char *status, const char *help);

/*
** Light colours (vlight.h), computed by the caller on its own thread.
** lsys_viewer_posted returns the snapshot last posted (NULL once the window
** is closed): the caller may read its frames' meshes and leaves, which the
** window never changes (but a live frame's), until it posts again or closes
** the window, and the light of its frames, which only the caller gives.
** lsys_viewer_light gives frame k of 's' the colours *l, which the window
** then owns and draws while the L key is on: it returns the request's
** serial number (lsys_viewer_key), or LSYS_EARG when 's' is no longer the
** snapshot last posted or the frame has its colours already (*l is then
** left to the caller).
*/
const lsys_vsnap *lsys_viewer_posted (lsys_viewer *v);
int lsys_viewer_light (lsys_viewer *v, const lsys_vsnap *s, size_t k, struct lsys_vlight *l);

/* Closes the window (if open), ends the thread and frees 'v'. */
void lsys_viewer_close (lsys_viewer *v);

/*
** Finds what a click at (x, y) (window coordinates, y down) hits in frame
** 'f' seen through proj/view in a w x h window: the pick whose projected
** segment passes within max(tol, its projected radius) pixels, nearest to
** the eye where several do; points clipped by the near or far plane do not
** count. Returns its index, or -1. In a population (f->partpicks) each
** instance's picks are tried under its transform, and *plant (when not
** NULL) is set to the instance hit (0-based; -1 otherwise). Plain
** arithmetic (viewcam.c): tested without a window.
*/
long lsys_viewcam_pick_find (const lsys_vframe *f, const double proj[16], const double view[16],
                             int w, int h, double x, double y, double tol, long *plant);

/* lsys_viewcam_pick_find into event 'ev': its module, kind and plant when
** something is hit (then returns 1; 0 leaves ev alone). */
int lsys_viewcam_pick_event (const lsys_vframe *f, const double proj[16], const double view[16],
                             int w, int h, double x, double y, double tol, lsys_vevent *ev);

#endif
