/*
** Lua binding of the writer of csrc/core/outfile.h: every file the Lua side
** of lsys writes goes through it, whole or absent.
**
**   core.outfile(path) -> Outfile      a new output (a temporary file beside it)
**     o:write(s, ...) -> o             strings or numbers; raises at a failed write
**     o:name() -> string               the file another program may write instead
**     o:commit() -> true               the temporary file replaces the target
**     o:abort()                        removes the temporary file (also __close, __gc)
**   core.tempdir([parent [, prefix]]) -> Tempdir   a new private folder (0700)
**     t:path() -> string               its path
**     t:remove() -> true               removes it and the files in it (also __close, __gc)
**
** Neither calls Lua while it holds a pointer into its userdata, so a
** finalizer cannot free what a method reads.
*/
#include <errno.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "outfile.h"

#define OUTFILE_T "lsys.Outfile"
#define TEMPDIR_T "lsys.Tempdir"

typedef struct loutfile {
  lsys_outfile o;
  int state;                  /* OPEN, HANDED (name() given away), DONE */
} loutfile;

enum { OPEN, HANDED, DONE };

static loutfile *checkopen (lua_State *L, const char *who) {
  loutfile *u = (loutfile *)luaL_checkudata(L, 1, OUTFILE_T);
  if (u->state == DONE) luaL_error(L, "%s: the output was committed or aborted", who);
  return u;
}

/* core.outfile(path): the path is kept in the user value (the core keeps the pointer). */
static int l_outfile (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  loutfile *u;
  lsys_error e;
  int st;
  lua_settop(L, 1);
  u = (loutfile *)lua_newuserdatauv(L, sizeof *u, 1);
  memset(u, 0, sizeof *u);
  u->state = DONE;                     /* nothing to abort until opened */
  luaL_setmetatable(L, OUTFILE_T);
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, -2, 1);
  st = lsys_outfile_open(&u->o, path, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  u->state = OPEN;
  return 1;
}

/* o:write(...): each argument, a string or a number; a failed write aborts and raises. */
static int outfile_write (lua_State *L) {
  loutfile *u = checkopen(L, "outfile:write");
  int i, n = lua_gettop(L);
  if (u->state != OPEN)
    return luaL_error(L, "outfile:write: the file was handed to another program (name())");
  for (i = 2; i <= n; i++) luaL_checklstring(L, i, NULL);   /* every argument, first */
  for (i = 2; i <= n; i++) {
    size_t len;
    const char *s = lua_tolstring(L, i, &len);
    lsys_outfile_write(&u->o, s, len);
  }
  if (u->o.err != 0) {
    lsys_error e;
    int en = u->o.err;
    lsys_seterror(&e, LSYS_EARG, (size_t)-1, "cannot write '%s': %s", u->o.path, strerror(en));
    lsys_outfile_abort(&u->o);
    u->state = DONE;
    return lsysL_raise(L, LSYS_EARG, &e, 1);
  }
  lua_settop(L, 1);
  return 1;
}

/* o:name(): finishes this side's stream (what was written stays) and returns the file
** another program writes; commit then renames it onto the target. */
static int outfile_name (lua_State *L) {
  loutfile *u = checkopen(L, "outfile:name");
  if (u->state == OPEN) {
    lsys_error e;
    int st = lsys_outfile_finish(&u->o, &e);
    if (st != LSYS_OK) {
      lsys_outfile_abort(&u->o);
      u->state = DONE;
      return lsysL_raise(L, st, &e, 1);
    }
    u->state = HANDED;
  }
  lua_pushstring(L, lsys_outfile_name(&u->o));
  return 1;
}

static int outfile_commit (lua_State *L) {
  loutfile *u = checkopen(L, "outfile:commit");
  lsys_error e;
  int st = lsys_outfile_commit(&u->o, &e);
  u->state = DONE;
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  lua_pushboolean(L, 1);
  return 1;
}

/* o:abort(), __close, __gc: the target stays as it was. Idempotent. */
static int outfile_abort (lua_State *L) {
  loutfile *u = (loutfile *)luaL_checkudata(L, 1, OUTFILE_T);
  if (u->state != DONE) lsys_outfile_abort(&u->o);
  u->state = DONE;
  return 0;
}

static int outfile_tostring (lua_State *L) {
  loutfile *u = (loutfile *)luaL_checkudata(L, 1, OUTFILE_T);
  lua_getiuservalue(L, 1, 1);
  lua_pushfstring(L, "lsys.Outfile '%s'%s", lua_tostring(L, -1),
                  u->state == DONE ? " (closed)" : "");
  return 1;
}

typedef struct ltempdir {
  char *path;                 /* LSYS_MALLOC'd; NULL once removed */
} ltempdir;

/* core.tempdir([parent [, prefix]]): parent nil is $TMPDIR (else /tmp). */
static int l_tempdir (lua_State *L) {
  const char *parent = luaL_optstring(L, 1, NULL);
  const char *prefix = luaL_optstring(L, 2, "lsys");
  ltempdir *t = (ltempdir *)lua_newuserdatauv(L, sizeof *t, 0);
  lsys_error e;
  t->path = NULL;
  luaL_setmetatable(L, TEMPDIR_T);
  t->path = lsys_outfile_tempdir_make(parent, prefix, &e);
  if (t->path == NULL) return lsysL_raise(L, e.code, &e, 1);
  return 1;
}

static int tempdir_path (lua_State *L) {
  ltempdir *t = (ltempdir *)luaL_checkudata(L, 1, TEMPDIR_T);
  if (t->path == NULL) return luaL_error(L, "tempdir:path: the folder was removed");
  lua_pushstring(L, t->path);
  return 1;
}

/* t:remove(): raises naming the folder when something in it could not be removed. */
static int tempdir_remove (lua_State *L) {
  ltempdir *t = (ltempdir *)luaL_checkudata(L, 1, TEMPDIR_T);
  int en;
  if (t->path == NULL) return luaL_error(L, "tempdir:remove: the folder was removed");
  en = lsys_outfile_tempdir_remove(t->path);
  if (en != 0) {
    lua_pushfstring(L, "cannot remove the temporary folder '%s': %s", t->path, strerror(en));
    LSYS_FREE(t->path);
    t->path = NULL;
    return lua_error(L);
  }
  LSYS_FREE(t->path);
  t->path = NULL;
  lua_pushboolean(L, 1);
  return 1;
}

/* __close, __gc: removes the folder, silently. Idempotent. */
static int tempdir_gc (lua_State *L) {
  ltempdir *t = (ltempdir *)luaL_checkudata(L, 1, TEMPDIR_T);
  if (t->path != NULL) {
    (void)lsys_outfile_tempdir_remove(t->path);
    LSYS_FREE(t->path);
    t->path = NULL;
  }
  return 0;
}

static int tempdir_tostring (lua_State *L) {
  ltempdir *t = (ltempdir *)luaL_checkudata(L, 1, TEMPDIR_T);
  if (t->path == NULL) lua_pushliteral(L, "lsys.Tempdir (removed)");
  else lua_pushfstring(L, "lsys.Tempdir '%s'", t->path);
  return 1;
}

static const luaL_Reg outfile_meta[] = {
  {"__index", NULL}, {"__gc", outfile_abort}, {"__close", outfile_abort},
  {"__tostring", outfile_tostring}, {NULL, NULL}
};
static const luaL_Reg outfile_methods[] = {
  {"write", outfile_write}, {"name", outfile_name}, {"commit", outfile_commit},
  {"abort", outfile_abort}, {NULL, NULL}
};
static const luaL_Reg tempdir_meta[] = {
  {"__index", NULL}, {"__gc", tempdir_gc}, {"__close", tempdir_gc},
  {"__tostring", tempdir_tostring}, {NULL, NULL}
};
static const luaL_Reg tempdir_methods[] = {
  {"path", tempdir_path}, {"remove", tempdir_remove}, {NULL, NULL}
};
static const luaL_Reg outfile_funcs[] = {
  {"outfile", l_outfile}, {"tempdir", l_tempdir}, {NULL, NULL}
};

void lsysL_open_outfile (lua_State *L) {
  lsysL_createmeta(L, OUTFILE_T, outfile_meta, outfile_methods);
  lsysL_createmeta(L, TEMPDIR_T, tempdir_meta, tempdir_methods);
  luaL_setfuncs(L, outfile_funcs, 0);
}
