/*
** The lsys program: a Lua 5.4 host with lsys.core linked in.
**
** It opens the standard libraries, preloads "lsys.core" (so no core.so is needed),
** "lsys.host" (paths and a few POSIX helpers for the command line) and, when built with
** readline, "lsys.readline"; puts the directory of the lsys Lua files in front of
** package.path; and calls require("lsys.cli").main(...) with the command-line arguments.
** The Lua files are found without environment variables: in the source tree when the
** program runs from its build directory, else in the install tree relative to the program
** (BINDIR/../share/lua/5.4 by default), else in the compiled-in install LUADIR.
**
** Errors reaching this file print "lsys: message" (with a traceback when LSYS_DEBUG is set)
** and exit 1; the exit status is otherwise what lsys.cli's main returns.
*/
#define _XOPEN_SOURCE 700  /* readlink, realpath, isatty, clock_gettime */

#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "lua.h"
#include "lauxlib.h"
#include "lualib.h"

#ifdef LSYS_WITH_READLINE
#include <readline/history.h>
#include <readline/readline.h>
#endif

#ifndef LSYS_VERSION
#define LSYS_VERSION "scm"
#endif
#ifndef LSYS_REL_LUADIR
#define LSYS_REL_LUADIR "../share/lua/5.4"
#endif
#ifndef LSYS_REL_DATADIR
#define LSYS_REL_DATADIR "../share/lsys"
#endif

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

int luaopen_lsys_core (lua_State *L);

static lua_State *globalL = NULL;  /* for the SIGINT handler, as in lua.c */


/* {====================================================================
** lsys.host: what the command line needs beyond standard Lua
** ===================================================================== */

/* isatty(fd): whether file descriptor fd (0, 1 or 2) is a terminal. */
static int host_isatty (lua_State *L) {
  lua_Integer fd = luaL_checkinteger(L, 1);
  luaL_argcheck(L, 0 <= fd && fd <= INT_MAX, 1, "bad file descriptor");
  lua_pushboolean(L, isatty((int)fd));
  return 1;
}

/* clock(): seconds of a monotonic wall clock, for timing derivations. */
static int host_clock (lua_State *L) {
  struct timespec ts;
  if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0)
    return luaL_error(L, "clock_gettime failed");
  lua_pushnumber(L, (lua_Number)ts.tv_sec + (lua_Number)ts.tv_nsec * 1e-9);
  return 1;
}

/* Hook set by the SIGINT handler: raises at the next Lua instruction (lua.c's lstop). */
static void lstop (lua_State *L, lua_Debug *ar) {
  (void)ar;
  lua_sethook(L, NULL, 0, 0);
  luaL_error(L, "interrupted!");
}

static void laction (int i) {
  int flag = LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT;
  signal(i, SIG_DFL);  /* a second Ctrl-C kills the process */
  lua_sethook(globalL, lstop, flag, 1);
}

/*
** interrupt(on): while on, Ctrl-C raises "interrupted!" in the running Lua code instead of
** killing the process (the REPL turns it on around each evaluation). C loops that do not
** call back into Lua finish first.
*/
static int host_interrupt (lua_State *L) {
  int on = lua_toboolean(L, 1);
  globalL = L;
  signal(SIGINT, on ? laction : SIG_DFL);
  if (!on) lua_sethook(L, NULL, 0, 0);
  return 0;
}

/* host.set_idle(f): the function the REPL's line editor calls while it waits (nil: none). */
static int host_set_idle (lua_State *L) {
  if (!lua_isnoneornil(L, 1)) luaL_checktype(L, 1, LUA_TFUNCTION);
  lua_settop(L, 1);
  lua_setfield(L, LUA_REGISTRYINDEX, "lsys.idle");
  return 0;
}

#ifdef LSYS_WITH_READLINE
static int host_clear_line (lua_State *L);
#endif

static const luaL_Reg host_funcs[] = {
  {"set_idle", host_set_idle},
#ifdef LSYS_WITH_READLINE
  {"clear_line", host_clear_line},
#endif
  {"isatty", host_isatty},
  {"clock", host_clock},
  {"interrupt", host_interrupt},
  {NULL, NULL}
};

/* }==================================================================== */


#ifdef LSYS_WITH_READLINE
/* {====================================================================
** lsys.readline
** ===================================================================== */

static lua_State *idleL = NULL;   /* the state inside l_readline, for the idle hook */

static int pushline (lua_State *L) {
  lua_pushstring(L, (const char *)lua_touserdata(L, 1));
  return 1;
}

/*
** readline([prompt]): reads a line with editing and history; returns it without the
** newline, or nil at end of input. Non-empty lines are added to the history.
*/
static int l_readline (lua_State *L) {
  const char *prompt = luaL_optstring(L, 1, "");
  char *line;
  int status;
  idleL = L;
  line = readline(prompt);
  idleL = NULL;
  if (line == NULL) {
    lua_pushnil(L);
    return 1;
  }
  if (line[0] != '\0')
    add_history(line);
  /* push in protected mode: 'line' must be freed even on a memory error */
  lua_pushcfunction(L, pushline);
  lua_pushlightuserdata(L, line);
  status = lua_pcall(L, 1, 1, 0);
  free(line);
  if (status != LUA_OK)
    return lua_error(L);
  return 1;
}

/*
** The idle function: while readline waits for a key it calls rl_event_hook
** about ten times a second; the hook calls the Lua function set with
** host.set_idle (the REPL polls the viewer window there, so a click in the
** window reaches its callback at the prompt). When the function returns
** true it has printed something, after host.clear_line: the prompt and the
** line being edited are drawn again below it.
*/
static int idlehook (void) {
  lua_State *L = idleL;
  int redraw = 0;
  if (L == NULL) return 0;
  if (lua_getfield(L, LUA_REGISTRYINDEX, "lsys.idle") != LUA_TFUNCTION) {
    lua_pop(L, 1);
    return 0;
  }
  if (lua_pcall(L, 0, 1, 0) != LUA_OK) {
    const char *msg = lua_tostring(L, -1);
    fprintf(stderr, "\n%s\n", msg != NULL ? msg : "(error in the idle function)");
    redraw = 1;
  }
  else redraw = lua_toboolean(L, -1);
  lua_pop(L, 1);
  if (redraw) rl_forced_update_display();
  return 0;
}

/* host.clear_line(): erases the prompt line being edited (before printing at the prompt). */
static int host_clear_line (lua_State *L) {
  (void)L;
  if (idleL != NULL) {
    rl_clear_visible_line();
    fflush(rl_outstream != NULL ? rl_outstream : stdout);
  }
  return 0;
}

static int luaopen_lsys_readline (lua_State *L) {
  rl_readline_name = "lsys";  /* for $if lsys in ~/.inputrc */
  rl_event_hook = idlehook;
  lua_pushcfunction(L, l_readline);
  return 1;
}

/* }==================================================================== */
#endif


/* {====================================================================
** Paths
** ===================================================================== */

static int isfile (const char *path) {
  FILE *f = fopen(path, "r");
  if (f == NULL) return 0;
  fclose(f);
  return 1;
}

/* Pushes the full path of the running program, or nil if unknown. */
static void pushexe (lua_State *L, const char *argv0) {
  char buf[PATH_MAX];
  ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) {
    buf[n] = '\0';
    lua_pushstring(L, buf);
  }
  else if (strchr(argv0, '/') != NULL && realpath(argv0, buf) != NULL)  /* no /proc */
    lua_pushstring(L, buf);
  else
    lua_pushnil(L);
}

/* Pushes the directory part of the path at 'idx' ("." if there is none or it is nil). */
static void pushdirname (lua_State *L, int idx) {
  const char *path = lua_tostring(L, idx);
  const char *slash = path != NULL ? strrchr(path, '/') : NULL;
  if (slash == NULL) lua_pushliteral(L, ".");
  else lua_pushlstring(L, path, slash == path ? 1 : (size_t)(slash - path));
}

#if defined(LSYS_SOURCE_DIR) && defined(LSYS_BUILD_BINDIR)
/* Whether the directories 'a' and 'b' are the same (after resolving links). */
static int samedir (const char *a, const char *b) {
  char ra[PATH_MAX], rb[PATH_MAX];
  return realpath(a, ra) != NULL && realpath(b, rb) != NULL && strcmp(ra, rb) == 0;
}
#endif

/*
** Pushes the first directory that holds lsys/cli.lua, or nil: the source tree when running
** from the build directory, then the install tree relative to the program (BINDIR to
** LUADIR, and the usual ../share/lua/5.4 where luarocks deploys), then the compiled-in
** install directory, then ../../lua (a build tree moved with its sources).
*/
static void pushluadir (lua_State *L, const char *exedir) {
  int top = lua_gettop(L);
#if defined(LSYS_SOURCE_DIR) && defined(LSYS_BUILD_BINDIR)
  if (samedir(exedir, LSYS_BUILD_BINDIR))  /* running from the build tree */
    lua_pushliteral(L, LSYS_SOURCE_DIR "/lua");
#endif
  lua_pushfstring(L, "%s/" LSYS_REL_LUADIR, exedir);
  lua_pushfstring(L, "%s/../share/lua/5.4", exedir);  /* where luarocks deploys them */
#ifdef LSYS_INSTALL_LUADIR
  lua_pushliteral(L, LSYS_INSTALL_LUADIR);
#endif
  lua_pushfstring(L, "%s/../../lua", exedir);  /* SRC/build/bin/lsys in a moved tree */
  for (int i = top + 1; i <= lua_gettop(L); i++) {
    lua_pushfstring(L, "%s/lsys/cli.lua", lua_tostring(L, i));
    if (isfile(lua_tostring(L, -1))) {
      char real[PATH_MAX];  /* without "bin/.." for readable messages */
      if (realpath(lua_tostring(L, i), real) != NULL)
        lua_pushstring(L, real);
      else
        lua_pushvalue(L, i);
      lua_copy(L, -1, top + 1);
      lua_settop(L, top + 1);
      return;
    }
    lua_pop(L, 1);
  }
  lua_settop(L, top);
  lua_pushnil(L);
}

/* package.path = "<luadir>/?.lua;<luadir>/?/init.lua;" .. package.path */
static void prependpath (lua_State *L, const char *luadir) {
  lua_getglobal(L, "package");
  lua_pushfstring(L, "%s/?.lua;%s/?/init.lua;", luadir, luadir);
  lua_getfield(L, -2, "path");
  lua_concat(L, 2);
  lua_setfield(L, -2, "path");
  lua_pop(L, 1);
}

/* }==================================================================== */


static void preload (lua_State *L, const char *name, lua_CFunction f) {
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
  lua_pushcfunction(L, f);
  lua_setfield(L, -2, name);
  lua_pop(L, 1);
}

/* package.loaded["lsys.host"] = { exe, exedir, luadir, datadirs, version, readline, ... } */
static void sethost (lua_State *L, int exe, int exedir, int luadir) {
  luaL_newlib(L, host_funcs);
  lua_pushvalue(L, exe);
  lua_setfield(L, -2, "exe");
  lua_pushvalue(L, exedir);
  lua_setfield(L, -2, "exedir");
  lua_pushvalue(L, luadir);
  lua_setfield(L, -2, "luadir");
  /* examples and other data, in the order to try */
  lua_createtable(L, 3, 0);
  lua_pushfstring(L, "%s/" LSYS_REL_DATADIR, lua_tostring(L, exedir));
  lua_rawseti(L, -2, 1);
#ifdef LSYS_INSTALL_DATADIR
  lua_pushliteral(L, LSYS_INSTALL_DATADIR);
  lua_rawseti(L, -2, 2);
#endif
  lua_setfield(L, -2, "datadirs");
#ifdef LSYS_SOURCE_DIR
  lua_pushliteral(L, LSYS_SOURCE_DIR);
  lua_setfield(L, -2, "source_dir");
#endif
  lua_pushliteral(L, LSYS_VERSION);
  lua_setfield(L, -2, "version");
#ifdef LSYS_WITH_READLINE
  lua_pushboolean(L, 1);
#else
  lua_pushboolean(L, 0);
#endif
  lua_setfield(L, -2, "readline");
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_insert(L, -2);
  lua_setfield(L, -2, "lsys.host");
  lua_pop(L, 1);
}

/* Message handler: the message, plus a traceback when LSYS_DEBUG is set. */
static int msghandler (lua_State *L) {
  const char *msg = lua_tostring(L, 1);
  if (msg == NULL) {  /* error object is not a string */
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
      return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  if (getenv("LSYS_DEBUG") != NULL)
    luaL_traceback(L, L, msg, 1);
  return 1;
}

/*
** Runs in protected mode: sets up the state, then returns the exit status of
** require("lsys.cli").main(argv[1], ..., argv[argc-1]).
*/
static int pmain (lua_State *L) {
  int argc = (int)lua_tointeger(L, 1);
  char **argv = (char **)lua_touserdata(L, 2);
  const char *argv0 = (argc > 0 && argv[0] != NULL) ? argv[0] : "lsys";
  int exe, exedir, luadir, base, isnum;
  lua_Integer code;
  luaL_checkversion(L);
  luaL_openlibs(L);
  lua_gc(L, LUA_GCRESTART);
  lua_gc(L, LUA_GCGEN, 0, 0);
  preload(L, "lsys.core", luaopen_lsys_core);
#ifdef LSYS_WITH_READLINE
  preload(L, "lsys.readline", luaopen_lsys_readline);
#endif
  pushexe(L, argv0);
  exe = lua_gettop(L);
  pushdirname(L, exe);
  exedir = lua_gettop(L);
  pushluadir(L, lua_tostring(L, exedir));
  luadir = lua_gettop(L);
  if (!lua_isnil(L, luadir))
    prependpath(L, lua_tostring(L, luadir));
  sethost(L, exe, exedir, luadir);
  /* arg = { [0] = argv[0], argv[1], ... } like lua.c; lsys.cli rebuilds it for scripts */
  lua_createtable(L, argc, 1);
  for (int i = 0; i < argc; i++) {
    lua_pushstring(L, argv[i]);
    lua_rawseti(L, -2, i);
  }
  lua_setglobal(L, "arg");
  lua_pushcfunction(L, msghandler);
  base = lua_gettop(L);
  lua_getglobal(L, "require");
  lua_pushliteral(L, "lsys.cli");
  if (lua_pcall(L, 1, 1, base) != LUA_OK) {
    const char *msg = lua_tostring(L, -1);
    if (lua_isnil(L, luadir) && msg != NULL && strstr(msg, "'lsys.cli' not found") != NULL)
      return luaL_error(L, "cannot find the lsys Lua files (lsys/cli.lua) beside the program "
                           "(%s) nor in its install directory; LUA_PATH may name them",
                           lua_tostring(L, exedir));
    return lua_error(L);
  }
  if (lua_getfield(L, -1, "main") != LUA_TFUNCTION)
    return luaL_error(L, "lsys.cli has no function 'main'");
  luaL_checkstack(L, argc, "too many arguments");
  for (int i = 1; i < argc; i++)
    lua_pushstring(L, argv[i]);
  if (lua_pcall(L, argc > 0 ? argc - 1 : 0, 1, base) != LUA_OK)
    return lua_error(L);
  code = lua_tointegerx(L, -1, &isnum);  /* nil or true: 0; false: 1 */
  if (!isnum) code = (lua_isnil(L, -1) || lua_toboolean(L, -1)) ? 0 : 1;
  lua_pushinteger(L, code);
  return 1;
}

int main (int argc, char **argv) {
  lua_State *L = luaL_newstate();
  int status, code;
  if (L == NULL) {
    fputs("lsys: cannot create the Lua state: not enough memory\n", stderr);
    return EXIT_FAILURE;
  }
  lua_gc(L, LUA_GCSTOP);  /* stop the collector while building the state */
  lua_pushcfunction(L, pmain);
  lua_pushinteger(L, argc);
  lua_pushlightuserdata(L, argv);
  status = lua_pcall(L, 2, 1, 0);
  if (status == LUA_OK) {
    code = (int)lua_tointeger(L, -1);
  }
  else {
    const char *msg = lua_tostring(L, -1);
    fprintf(stderr, "lsys: %s\n", msg != NULL ? msg : "(error object is not a string)");
    fflush(stderr);
    code = EXIT_FAILURE;
  }
  lua_close(L);
  return code;
}
