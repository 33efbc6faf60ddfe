/*
** Shared declarations of the Lua binding files (only lua_*.c include Lua).
*/
#ifndef LSYS_LUA_LSYS_H
#define LSYS_LUA_LSYS_H

#include <lua.h>
#include <lauxlib.h>

#include "lstring.h"
#include "mesh.h"

#define LSTRING_T "lsys.Lstring"

/* An Lstring userdata: the string, whether it was closed (its memory freed by
** __close or __gc), and how many running operations read or write it (a
** derivation, an interpretation): while 'busy', it can be neither closed nor
** rewritten. */
typedef struct lsys_lstr {
  lsys_lstring s;
  int closed;
  int busy;
} lsys_lstr;

/* The Lstring at 'i'; raises when it is not one or was closed. */
lsys_lstring *lsys_checklstring (lua_State *L, int i);
#define checklstring(L, i) lsys_checklstring(L, (i))

/* The same for an Lstring that is about to be rewritten in place: raises
** also when an operation is using it. */
lsys_lstring *lsys_checkwritable (lua_State *L, int i, const char *what);

/* Marks the Lstring at 'i' used by an operation (+1) or no longer (-1). */
void lsys_lstring_busy (lua_State *L, int i, int delta);

/* The alphabet shared by all models and Lstrings of a Lua state. */
lsys_alphabet *lsys_getalphabet (lua_State *L);

/* Pushes a new empty Lstring and returns it. */
lsys_lstring *lsys_newlstring (lua_State *L);

/* The declared names of the model that made the Lstring at 'idx' (its
** owner, user value 1), or NULL. */
const lsys_names *lsys_ownernames (lua_State *L, int idx);

/* Makes the value at 'owner' the owner of the Lstring at 'idx'. */
void lsys_setowner (lua_State *L, int idx, int owner);

/* Raises the error for a core status code (message from 'e'). */
int lsys_raise (lua_State *L, int code, const lsys_error *e);

/* Reads a list of module names separated by white space into 'd'. */
int lsys_readnames (lua_State *L, const char *s, lsys_names *d);

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
struct lsys_model;
typedef int (*lsys_ruleop) (lua_State *L, struct lsys_model *m, void *ud);
int lsys_rules_run (lua_State *L, int ridx, const char *what, lsys_ruleop op, void *ud,
                    const int *lstr, int n);

#define SCENE_T "lsys.Scene"

/* The mesh and palette of the lsys.Scene at 'idx' (raises when it is not a
** scene). The palette has *npal >= 1 materials; colour c uses pal[c % npal]. */
const lsys_mesh *lsys_checkscene (lua_State *L, int idx, const lsys_material **pal,
                                  size_t *npal);

/* The turtle records of the lsys.Scene at 'idx' (*n of them). */
struct lsys_trec;
const struct lsys_trec *lsys_scenerecords (lua_State *L, int idx, size_t *n);

/* The name of a turtle record kind (LSYS_REC_*): "segment", "sphere", ... */
const char *lsys_recordkind (int kind);

/* Moves the mesh of the lsys.Scene at 'idx' into 'm' (initialised by the
** callee); the scene is left with an empty mesh. */
void lsys_scenetake (lua_State *L, int idx, lsys_mesh *m);

/* Each registers its metatables and adds its functions to the table on top. */
void lsys_open_lstring (lua_State *L);
void lsys_open_scene (lua_State *L);    /* lua_scene.c: Scene, interpret */
void lsys_open_render (lua_State *L);   /* lua_render.c: render, png */
void lsys_open_contour (lua_State *L);  /* lua_contour.c: Contour */
void lsys_open_surface (lua_State *L);  /* lua_surface.c: Surface, patches */
void lsys_open_texture (lua_State *L);  /* lua_texture.c: Texture */
void lsys_open_viewer (lua_State *L);   /* lua_viewer.c: Viewer, filestamp */
void lsys_open_ik (lua_State *L);       /* lua_ik.c: IK chains (lsys.arrange) */

#endif
