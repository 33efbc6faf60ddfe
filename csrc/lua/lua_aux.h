/*
** The floor of the Lua bindings, as lauxlib is Lua's: what the binding files
** share. A binding file includes this header, the core's headers and, where
** it binds them, render.h or viewer.h of csrc/gl; never another binding's.
** lua_lsys.h declares the bindings' registration functions for the entry
** point (lua_lsys.c), so the files depend on each other only as
**
**     lua_aux  <-  lua_lstring, lua_rules, lua_scene, ...  <-  lua_lsys
**
** Here: the metatable names and createmeta; the state's alphabet; core
** status codes as Lua errors; objects in use (holding and keeping them
** while Lua code runs); the userdata that more than one binding reads
** (Lstring, Rules, Scene; like lauxlib's luaL_Stream) and the checks that an
** object is alive for those and for Contour, Surface, Texture and Func; running
** a core operation with a model's rule functions bound; option readers, and
** the option tables read in more than one binding (render options, lists of
** textures). Only lua_*.c include Lua.
*/
#ifndef LSYS_LUA_AUX_H
#define LSYS_LUA_AUX_H

#include <math.h>

#include <lua.h>
#include <lauxlib.h>

#include "canvas.h"
#include "contour.h"
#include "derive.h"
#include "func.h"
#include "lstring.h"
#include "mesh.h"
#include "render.h"
#include "scene.h"
#include "surface.h"
#include "texture.h"
#include "turtle.h"

/* The metatable names of every userdata (shown in errors via __name). */
#define ALPHABET_T "lsys.Alphabet"   /* the state's alphabet (lua_aux.c) */
#define LSTRING_T  "lsys.Lstring"    /* lua_lstring.c */
#define RULES_T    "lsys.Rules"      /* lua_rules.c */
#define TEMPLATE_T "lsys.Template"   /* lua_rules.c: successor templates */
#define SCENE_T    "lsys.Scene"      /* lua_scene.c */
#define TURTLE_T   "lsys.Turtle"     /* lua_scene.c: a turtle for one call */
#define ENVQ_T     "lsys.EnvQueries" /* lua_scene.c: the ?E of one environmental pass */
#define CONTOUR_T  "lsys.Contour"    /* lua_contour.c */
#define SURFACE_T  "lsys.Surface"    /* lua_surface.c */
#define TEXTURE_T  "lsys.Texture"    /* lua_texture.c */
#define PIXELS_T   "lsys.Pixels"     /* lua_render.c: a pixel block owned by Lua until copied */
#define VIEWER_T   "lsys.Viewer"     /* lua_viewer.c */
#define IK_T       "lsys.IK"         /* lua_ik.c */
#define FUNC_T     "lsys.Func"       /* lua_func.c: positional functions */
#define CANVAS_T   "lsys.Canvas"     /* lua_canvas.c */
#define ENVPROC_T  "lsys.EnvProcess" /* lua_envproc.c: an environmental program */
#define LIGHT_T    "lsys.Light"      /* lua_light.c: the light environment */
#define HOLD_T     "lsys.Hold"       /* lua_aux.c: an object held by a running binding */

/* The registry field of the Rules deriving now (lsys.produce, lsys.ran). */
#define LSYS_PRODUCING "lsys.producing"

/*
** Registers the metatable 'tname' (liolib's createmeta): the metamethods
** 'meta', and the methods 'methods' (NULL: none) as its __index, which
** replaces a placeholder {"__index", NULL} in 'meta'. Leaves the stack as
** it was.
*/
void lsysL_createmeta (lua_State *L, const char *tname, const luaL_Reg *meta,
                       const luaL_Reg *methods);

/* The alphabet shared by all models and Lstrings of a Lua state (made at
** the first call); raises once it was finalized. */
lsys_alphabet *lsysL_getalphabet (lua_State *L);

/*
** Raises the error of a failed core call: "not enough memory" for
** LSYS_ENOMEM, else the message in 'e'. 'level' is that of Lua's error():
** 1 puts the position of the Lua code that called the binding first (as
** luaL_error does), 0 raises the message as it is (one that names a file
** and line of its own). Never returns.
*/
int lsysL_raise (lua_State *L, int code, const lsys_error *e, int level);

/* The program {op, a, k, ...} (expr.h) of the table at 't', copied into a
** new userdata pushed on the stack; *n its length. Raises when an entry is
** not a number or it is longer than LSYS_EXPR_MAXCODE (unchecked otherwise:
** the caller runs lsys_expr_check). */
lsys_ins *lsysL_readcode (lua_State *L, int t, int *n);

/* Pushes a new list of the n <= LSYS_PUSHNUMS_MAX numbers v[0..n-1] (read
** before anything is allocated). */
#define LSYS_PUSHNUMS_MAX 16
void lsysL_pushnums (lua_State *L, const double *v, int n);

/* Reads a list of module names separated by white space or commas into 'd'.
** Returns LSYS_OK or LSYS_ENOMEM. */
int lsysL_readnames (lua_State *L, const char *s, lsys_names *d);

/* ---------------------------------------------------------------------- */
/*
** Objects in use. Lua code can run in the middle of a binding: a
** call, a metamethod of a value it reads (lua_getfield, lua_gettable,
** lua_geti, luaL_len, luaL_tolstring on the caller's values), or an
** allocation (lua_newuserdatauv, lua_createtable, lua_pushstring, ...: its
** collection step may run any finalizer, which may close or change any
** object). A binding never keeps a pointer into an object across such a
** point, unless the object is in use:
**
**   - held (a Scene, Frames): lsysL_hold marks the object busy until the
**     binding returns or raises; its close and whatever would move or free
**     its arrays refuse meanwhile (lsysL_checkidle);
**   - kept (a Contour, Surface, Texture or Func that an interpretation, a
**     Scene or a model points to): an immutable object, whose close then
**     only marks it closed; the collector frees it;
**   - or the binding takes its pointers after the last such point (checking
**     again that the object is alive), or copies what it needs before it.
** tests/misuse_spec.lua calls every method with objects closed and changed
** at such points.
*/

/*
** Holds the userdata at 'idx' whose hold count is *busy until the running C
** function returns or raises: increments *busy and pushes a to-be-closed
** value that decrements it (also when a coroutine dies with the function
** on its stack: then when the collector finalizes that value, before the
** userdata). Allocates: take the userdata's pointers after it, checking
** again that it is alive. Nothing may remove the value from the stack but
** the return (lua_settop below it ends the hold early).
*/
void lsysL_hold (lua_State *L, int idx, int *busy);

/* Raises 'msg' ("cannot close a Scene while it is in use") when 'busy' is
** not 0. */
void lsysL_checkidle (lua_State *L, int busy, const char *msg);

/* Whether the running C function was called by the collector as a finalizer
** (not by Lua code calling a __gc metamethod by hand). */
int lsysL_finalizing (lua_State *L);

/* The life of an immutable object (Contour, Surface, Texture, Func), after
** its core struct in the userdata: closed (its methods raise), and kept
** (something points to it: its memory is freed only by the collector). */
typedef struct lsys_life {
  int closed;
  int kept;
} lsys_life;

/* __close and __gc of an immutable object: marks it closed; returns whether
** its memory is to be freed now (it is not kept, or the collector finalizes
** it: nothing that points to it can run any more). */
int lsysL_life_end (lua_State *L, lsys_life *life);

/* ---------------------------------------------------------------------- */
/* lsys.Lstring */

/* An Lstring userdata: the string, whether it was closed (its memory freed by
** __close or __gc), and how many running operations read or write it (a
** derivation, an interpretation): while 'busy', it can be neither closed nor
** rewritten. User value 1: its owner, the Rules whose model made it. */
typedef struct lsys_lstr {
  lsys_lstring s;
  int closed;
  int busy;
} lsys_lstr;

/* Pushes a new empty Lstring and returns it. */
lsys_lstring *lsysL_newlstring (lua_State *L);

/* The Lstring at 'i'; raises when it is not one or was closed. */
lsys_lstring *lsysL_checklstring (lua_State *L, int i);       /* made wide (lstring.h) */
lsys_lstring *lsysL_checklstring_any (lua_State *L, int i);   /* as it is: narrow or wide */
#define checklstring(L, i) lsysL_checklstring(L, (i))

/* The same for an Lstring that is about to be rewritten in place: raises
** also when an operation is using it. */
lsys_lstring *lsysL_checkwritable (lua_State *L, int i, const char *what);

/* Marks the Lstring at 'i' used by an operation (+1) or no longer (-1). */
void lsysL_lstring_busy (lua_State *L, int i, int delta);

/* Makes the value at 'owner' the owner of the Lstring at 'idx' (an Lstring
** passes on its own owner). */
void lsysL_setowner (lua_State *L, int idx, int owner);

/* The declared names of the model that made the Lstring at 'idx' (its
** owner), or NULL. */
const lsys_names *lsysL_ownernames (lua_State *L, int idx);

/* ---------------------------------------------------------------------- */
/* lsys.Rules: the compiled rules of one model (the C side of lsys.lsystem) */

/* user values of a Rules: the rule functions by rule index + 1, the
** successor templates of lsys.produce by text, and the list of positional
** functions (Funcs) the expression machine calls (rules:setfuncs) */
enum { LSYS_RULES_FNS = 1, LSYS_RULES_TPL = 2, LSYS_RULES_FUNCS = 3, LSYS_RULES_NUV = 3 };

/*
** The bounds of rule code while a model's rules run (lua_sandbox.c): the
** Lua instructions of one call (a count hook), the memory Lua may grow by
** (a wrapped allocator), and strings' methods (the sandbox's string
** library). Filled by lsysL_sandbox_enter, which pushes one value that
** lsysL_sandbox_leave removes (at 'stridx').
*/
#define LSYS_MAX_INSTRUCTIONS 1e8    /* one call's default (max_instructions) */
typedef struct lsys_sandbox {
  lua_Alloc alloc; void *aud;        /* the allocator it wraps */
  lua_Hook hook; int hmask, hcount;  /* the hook it replaced */
  long long limit, net;              /* bytes Lua may grow by; grown since entry */
  long long gcat;                    /* grown this much: collect (lsysL_sandbox_collect) */
  double budget, ran;                /* instructions of one call: the most, so far */
  int memhit, timehit;               /* a growth refused; the budget ran out */
  int strict;                        /* rule text runs (not a rule written as a function):
                                        strings' methods check their work */
  int stridx, swapped, entered;
} lsys_sandbox;

typedef struct lsys_lrules {
  lsys_rules m;
  lsys_names decl;
  lua_State *L;        /* while a step runs */
  int fnidx;           /* stack index of the closure table while a step runs */
  int produced;        /* lsys.produce was called by the running rule function */
  int inited;          /* 0 once closed (finalized) */
  lsys_sandbox *sb;    /* while a step runs: its bounds (the budget restarts per call) */
  double max_instructions;   /* per call of rule code; 0: LSYS_MAX_INSTRUCTIONS */
} lsys_lrules;

/* The Rules at 'i'; raises when they were closed. */
lsys_lrules *lsysL_checkrules (lua_State *L, int i);

/*
** Runs op(L, m, ud) on the model of the Rules at 'ridx' with its rule
** functions callable from C (for derivation and the streamed homomorphism)
** and lsys.produce / lsys.ran wired to it, and the Lstrings at the stack
** indices lstr[0..n) marked busy (they can be neither closed nor rewritten
** meanwhile). It runs in protected mode: the marks are undone and the error
** raised again, whatever op or a rule function does. Raises before anything
** when the model is running already ("a rule of this model called 'what' on
** the same model"). Returns op's status. 'op' sees a stack of its own.
*/
typedef int (*lsys_ruleop) (lua_State *L, lsys_rules *m, void *ud);
int lsysL_rules_run (lua_State *L, int ridx, const char *what, lsys_ruleop op, void *ud,
                     const int *lstr, int n);

/* Enters the bounds of the Rules R (pushes one value); leaves them (removes
** it), rewording the error object on top when 'err' is a memory error the
** bound caused. Runs nest. */
void lsysL_sandbox_enter (lua_State *L, lsys_sandbox *sb, const lsys_lrules *R);
void lsysL_sandbox_leave (lua_State *L, lsys_sandbox *sb, int err);
/* At a safe point of the run (between calls of rule code, in the count hook):
** collects garbage when Lua has grown halfway to the bound, so that garbage is not
** what reaches it. */
void lsysL_sandbox_collect (lua_State *L, lsys_sandbox *sb);

/* ---------------------------------------------------------------------- */
/* lsys.Scene: what an interpretation drew (docs/drawing.md §5) */

/* user values of a Scene: what made it, for scene:turtle() and the
** textures of scene:save() */
enum { LSYS_SCENE_RULES = 1, LSYS_SCENE_LSTRING = 2, LSYS_SCENE_OPTS = 3, LSYS_SCENE_TEX = 4,
       LSYS_SCENE_NUV = 4 };

/* The palette has npal >= 1 materials; colour c uses pal[c % npal]. */
typedef struct lsys_lscene {
  lsys_scene sc;       /* mesh, palette, records and stiffnesses (scene.h) */
  int inited;          /* 0 once closed */
  int busy;            /* holds (lsysL_hold): it can be neither closed nor changed */
} lsys_lscene;

/* Pushes a new, empty Scene. */
lsys_lscene *lsysL_newscene (lua_State *L);
/* The Scene at 'i'; raises when it is not one or was closed. */
lsys_lscene *lsysL_checkscene (lua_State *L, int i);
/* The same, held for the rest of the running C function (lsysL_hold). */
lsys_lscene *lsysL_holdscene (lua_State *L, int i);
/* Raises "cannot change a Scene while it is in use" when S is held: before
** anything that moves or frees its arrays (growth, a stolen mesh). */
void lsysL_changescene (lua_State *L, const lsys_lscene *S);

/* The name of a turtle record kind (LSYS_REC_*): "segment", "sphere", ... */
const char *lsysL_recordkind (int kind);

/* ---------------------------------------------------------------------- */
/* Contour, Surface, Texture, Func: core objects, immutable once made, each
** the first member of its userdata and followed by its life. Each check
** raises when the value at 'i' is not one or was closed; the keep functions
** check and mark it kept, for a caller that points to it beyond the running
** C function or across Lua code (and keeps a reference to it). */

typedef struct lsys_lcontour { lsys_contour c; lsys_life life; } lsys_lcontour;
typedef struct lsys_lsurface { lsys_surface s; lsys_life life; } lsys_lsurface;
typedef struct lsys_ltexture { lsys_texture t; lsys_life life; } lsys_ltexture;
typedef struct lsys_lfunc { lsys_func f; lsys_life life; } lsys_lfunc;

const lsys_contour *lsysL_checkcontour (lua_State *L, int i);
const lsys_surface *lsysL_checksurface (lua_State *L, int i);
const lsys_texture *lsysL_checktexture (lua_State *L, int i);
const lsys_func *lsysL_checkfunc (lua_State *L, int i);
const lsys_contour *lsysL_keepcontour (lua_State *L, int i);
const lsys_surface *lsysL_keepsurface (lua_State *L, int i);
const lsys_texture *lsysL_keeptexture (lua_State *L, int i);
const lsys_func *lsysL_keepfunc (lua_State *L, int i);

/* The Canvas at 'i' (lua_canvas.c), for a binding that draws into one or
** shows its pixels; raises when it is not one or was closed. */
lsys_canvas *lsysL_checkcanvas (lua_State *L, int i);

/* ---------------------------------------------------------------------- */
/*
** Option readers, lauxlib's luaL_opt* for the fields of an options table.
** An lsys_opts says where the table is and how messages name its fields:
** option k is pre..k..post ("lsys.render: opts." "width"; "view option '"
** "angle" "'"). A reader reads o[k]: an absent option (nil, or no table at
** all) gives the default; a bad one raises "<option> must be <what is
** expected>", followed by ", got ..." as 'got' says. One argument order:
** L, the options, the key, the default, the bounds.
*/
enum {
  LSYS_GOT_NONE,       /* the message ends there */
  LSYS_GOT_TYPE,       /* a value of the wrong type is named by its type (or as "a
                          non-finite number"); a bad value of the right type is not */
  LSYS_GOT_VALUE       /* every bad value is shown: a number or 'string' as it is,
                          anything else by its type */
};

typedef struct lsys_opts {
  int t;               /* absolute stack index of the table; 0: none */
  const char *pre, *post;
  int got;             /* LSYS_GOT_* */
  int numerals;        /* numbers may be numerals (strings), as lua_tonumberx reads them */
} lsys_opts;

/* Pushes o[k] and returns 1, or returns 0 when it is absent. With a 'type'
** (not LUA_TNONE), a value of another type raises ("must be <expect>"). */
int lsysL_optfield (lua_State *L, const lsys_opts *o, const char *k, int type,
                    const char *expect);

/* Raises "<option k> must be <expect>" for the bad value of o[k] on top of
** the stack (shown with LSYS_GOT_VALUE). */
int lsysL_opterror (lua_State *L, const lsys_opts *o, const char *k, const char *expect);

/* A boolean ("must be a boolean"). */
int lsysL_optbool (lua_State *L, const lsys_opts *o, const char *k, int def);

/* An integer in [lo, hi]: a number, or a numeral with o->numerals ("must be
** an integer"), whose value is an integer in range ("must be an integer in
** [lo, hi]"). */
int lsysL_optint (lua_State *L, const lsys_opts *o, const char *k, int def, int lo, int hi);

/* A finite number in the open interval (lo, hi) (-HUGE_VAL, HUGE_VAL: no
** bound); "must be <expect>" (NULL: "a finite number") for anything else. */
double lsysL_optnum (lua_State *L, const lsys_opts *o, const char *k, double def, double lo,
                     double hi, const char *expect);
#define lsysL_optfinite(L, o, k, def) lsysL_optnum(L, o, k, def, -HUGE_VAL, HUGE_VAL, NULL)

/* A string out of the NULL-terminated list 'names': returns its index.
** Anything else raises "must be <expect>"; a string is always shown. */
int lsysL_optchoice (lua_State *L, const lsys_opts *o, const char *k, int def,
                     const char *const names[], const char *expect);

/* Whether the table has a key that is not a string in the NULL-terminated
** list 'names' (the caller's message names it): then pushes the first such
** key in lua_next order and returns 1. */
int lsysL_optunknown (lua_State *L, const lsys_opts *o, const char *const names[]);

/*
** The list opts.textures of the options table at 't' (0: none) as an array
** of *ntex textures, or NULL when absent or empty. The list is read once;
** its textures are kept (lsysL_keeptexture). Pushes one value that keeps the
** array and its textures alive (nil when NULL); raises, naming 'who', when
** the list holds anything but live textures.
*/
const lsys_texture *const *lsysL_opttextures (lua_State *L, int t, const char *who, int *ntex);

/* A box {x0, y0, z0, x1, y1, z1} of finite numbers (low corner first) from the
** table at t, or an error naming 'what'. */
void lsysL_readbox (lua_State *L, int t, const char *what, double box[6]);

/* How to look at scene 'sc' (scene.h: camera, light, background) from the
** fields of the options o->t that are present: background, light,
** viewpoint, target, up, direction, projection, fov, twist, zoom. Each field
** given replaces the scene's; the messages begin with o->pre. */
void lsysL_readlook (lua_State *L, const lsys_opts *o, lsys_scene *sc);

/* Fills 'o' from the lsys.render options table at 't' (0: none), checking
** every field, and the look fields into 'sc' (a copy of the scene for this
** picture: lsysL_readlook). Only when built with rendering. */
void lsysL_readrenderopts (lua_State *L, int t, lsys_render_opts *o, lsys_scene *sc);

#endif
