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
** and exit 1; the exit status is otherwise what lsys.cli's main returns. SIGINT and SIGTERM
** unwind the Lua code (its writers remove their temporary files), then print "lsys:
** interrupted" or "lsys: terminated" and end the process by the signal (stopaction).
*/
#define _XOPEN_SOURCE 700  /* readlink, realpath, isatty, clock_gettime, sigaction */
#define _DEFAULT_SOURCE    /* struct winsize, TIOCGWINSZ */

#include <errno.h>
#include <limits.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
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
static volatile sig_atomic_t interrupted = 0;  /* Ctrl-C at the prompt */
static volatile sig_atomic_t stopsignal = 0;   /* the SIGINT or SIGTERM ending the program */
static int ignored[2];                         /* SIGINT, SIGTERM ignored when we started */


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

/* termsize(): the rows and columns of the terminal on stdout, or nil when it is not one. */
static int host_termsize (lua_State *L) {
  struct winsize ws;
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) != 0 || ws.ws_row == 0 || ws.ws_col == 0) {
    lua_pushnil(L);
    return 1;
  }
  lua_pushinteger(L, ws.ws_row);
  lua_pushinteger(L, ws.ws_col);
  return 2;
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
** Ending the program at SIGINT or SIGTERM: the handler sets a hook that
** raises at every Lua instruction from then on, so no pcall can swallow the interrupt
** and the program unwinds to main. What it opened is closed on the way (to-be-closed
** variables, then the finalizers at lua_close): the temporary files of an animation, a
** graph, an export or a render go, and an output being written keeps its old content.
** Only instructions count: the __close and __gc methods written in C (those of the
** writers) run whole. main then ends the process by the same signal (status 130 or 143
** as a shell shows it). A C loop that does not come back to Lua (a long step) finishes
** first; a second signal ends the process at once.
*/
static void stophook (lua_State *L, lua_Debug *ar) {
  (void)ar;
  lua_pushstring(L, stopsignal == SIGTERM ? "terminated" : "interrupted");
  lua_error(L);
}

static void stopaction (int sig) {
  stopsignal = sig;
  signal(sig, SIG_DFL);
  lua_sethook(globalL, stophook, LUA_MASKCOUNT, 1);
}

/* Installs stopaction for SIGINT and SIGTERM, except for a signal that was ignored when
** the program started (a background job's SIGINT, nohup): that one stays ignored. */
static void setstop (int which) {
  static const int sigs[2] = {SIGINT, SIGTERM};
  int k;
  for (k = 0; k < 2; k++) {
    struct sigaction sa;
    if (which != 0 && sigs[k] != which) continue;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = ignored[k] ? SIG_IGN : stopaction;
    sa.sa_flags = SA_RESTART;
    sigaction(sigs[k], &sa, NULL);
  }
}

/*
** The SIGINT handler at the prompt: notes the Ctrl-C and, inside readline, ends the line
** being edited (readline calls it after restoring the terminal; l_readline then discards
** the line). Without readline it interrupts the read, which returns with EINTR.
*/
static void promptaction (int i) {
  (void)i;
  interrupted = 1;
#ifdef LSYS_WITH_READLINE
  rl_done = 1;
#endif
}

/* SIGTERM at the prompt: the program ends (stopaction), and the line being read is
** abandoned as at Ctrl-C, so that the REPL comes back to Lua, where the hook raises. */
static void stopprompt (int i) {
  stopaction(i);
  promptaction(i);
}

/* Removes the REPL's hook, unless the program is ending (a signal may come meanwhile). */
static void clearhook (lua_State *L) {
  lua_sethook(L, NULL, 0, 0);
  if (stopsignal) lua_sethook(L, stophook, LUA_MASKCOUNT, 1);
}

/*
** interrupt(mode): true while the REPL evaluates: Ctrl-C raises "interrupted!" in the
** running Lua code instead of ending the program (C loops that do not call back into Lua
** finish first). "prompt" while it waits for a line: Ctrl-C abandons the line (see
** interrupted()), SIGTERM ends the program without waiting for the line. false or nil:
** Ctrl-C ends the program again (stopaction). Nothing changes once the program is ending.
*/
static int host_interrupt (lua_State *L) {
  static const char *const modes[] = {"prompt", NULL};
  struct sigaction sa;
  int on = lua_toboolean(L, 1);
  int prompt = lua_type(L, 1) == LUA_TSTRING && luaL_checkoption(L, 1, NULL, modes) == 0;
  if (stopsignal) return 0;
  globalL = L;
  if (!on) {
    setstop(0);
    clearhook(L);
    return 0;
  }
  memset(&sa, 0, sizeof sa);
  sigemptyset(&sa.sa_mask);
  sa.sa_handler = prompt ? promptaction : laction;
  sa.sa_flags = prompt ? 0 : SA_RESTART;  /* a read at the prompt returns on Ctrl-C */
  sigaction(SIGINT, &sa, NULL);
  if (prompt && !ignored[1]) {
    sa.sa_handler = stopprompt;
    sigaction(SIGTERM, &sa, NULL);
  }
  else setstop(SIGTERM);
  if (prompt) clearhook(L);
  return 0;
}

/* interrupted(): whether Ctrl-C was pressed at the prompt since the last call. */
static int host_interrupted (lua_State *L) {
  lua_pushboolean(L, interrupted);
  interrupted = 0;
  return 1;
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
  {"termsize", host_termsize},
  {"clock", host_clock},
  {"interrupt", host_interrupt},
  {"interrupted", host_interrupted},
  {NULL, NULL}
};

/* }==================================================================== */


#ifdef LSYS_WITH_READLINE
/* {====================================================================
** lsys.readline
** ===================================================================== */

static lua_State *idleL = NULL;   /* the state inside l_readline, for the hooks */
static char *histfile = NULL;     /* where lines are appended, or NULL */
static lua_Integer candidate = 0; /* the next completion candidate to hand to readline */

static int pushline (lua_State *L) {
  lua_pushstring(L, (const char *)lua_touserdata(L, 1));
  return 1;
}

/* Adds 'line' to the history unless it is empty or repeats the last entry, and appends it
** to the history file. append_history does not create the file: write_history does.
** Failures to write are silent. */
static void remember (const char *line) {
  HIST_ENTRY *last = history_length > 0 ? history_get(history_base + history_length - 1)
                                        : NULL;
  if (line[0] == '\0' || (last != NULL && strcmp(last->line, line) == 0)) return;
  add_history(line);
  if (histfile != NULL && append_history(1, histfile) != 0) write_history(histfile);
}

#if RL_READLINE_VERSION >= 0x0800
/*
** Reads a key for readline (its rl_getc_function): as rl_getc, except that after a Ctrl-C
** at the prompt it returns EOF at once instead of waiting for another key, so that
** readline ends the line (l_readline then discards it). The Ctrl-C may arrive while
** readline waits in select (it then ends the line itself, promptaction having set
** rl_done) or here in read.
*/
static int getkey (FILE *f) {
  unsigned char c;
  for (;;) {
    ssize_t n;
    if (interrupted) return EOF;
    n = read(fileno(f), &c, 1);
    if (n == 1) return c;
    if (n == 0 || errno != EINTR) return EOF;
    rl_check_signals();  /* readline's handler: the terminal, then promptaction */
  }
}
#endif

/*
** readline([prompt]): reads a line with editing and history; returns it without the
** newline, nil at end of input, or false when Ctrl-C abandoned it (with host.interrupt
** "prompt" on). Lines are added to the history unless empty or a repetition.
*/
static int l_readline (lua_State *L) {
  const char *prompt = luaL_optstring(L, 1, "");
  char *line;
  int status;
  idleL = L;
  interrupted = 0;
  line = readline(prompt);
  idleL = NULL;
  if (interrupted) {
    interrupted = 0;
    free(line);
    lua_pushboolean(L, 0);
    return 1;
  }
  if (line == NULL) {
    lua_pushnil(L);
    return 1;
  }
  remember(line);
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
** history(path [, max]): keeps at most 'max' lines of history (default 1000), reads them
** from the file 'path', cuts the file to 'max' lines and appends each new line to it.
** Returns whether the file could be read; a missing file is made at the first line.
*/
static int l_history (lua_State *L) {
  size_t len;
  const char *path = luaL_checklstring(L, 1, &len);
  lua_Integer max = luaL_optinteger(L, 2, 1000);
  char *copy;
  luaL_argcheck(L, 0 < max && max <= 1000000, 2, "out of range (1 to 1000000)");
  copy = (char *)malloc(len + 1);
  if (copy == NULL) return luaL_error(L, "not enough memory");
  memcpy(copy, path, len + 1);
  free(histfile);
  histfile = copy;
  stifle_history((int)max);
  lua_pushboolean(L, read_history(path) == 0);
  history_truncate_file(path, (int)max);
  return 1;
}

/*
** The generator of rl_completion_matches: the next string of the list that complete()
** left in the registry, as a malloc'ed copy (readline frees it), or NULL after the last.
*/
static char *nextcandidate (const char *text, int state) {
  lua_State *L = idleL;
  char *r = NULL;
  int top;
  (void)text;
  if (state == 0) candidate = 0;
  if (L == NULL) return NULL;
  top = lua_gettop(L);
  if (lua_getfield(L, LUA_REGISTRYINDEX, "lsys.candidates") == LUA_TTABLE &&
      lua_rawgeti(L, -1, ++candidate) == LUA_TSTRING) {
    size_t n;
    const char *s = lua_tolstring(L, -1, &n);
    r = (char *)malloc(n + 1);
    if (r != NULL) memcpy(r, s, n + 1);
  }
  lua_settop(L, top);
  return r;
}

/*
** readline's completion hook: calls the function set with set_complete as f(line, start,
** stop), the word being line:sub(start + 1, stop). A list of strings are the words that
** may replace it; nil lets readline complete a file name (in a quoted string). Nothing
** is appended after a completed word.
*/
static char **complete (const char *text, int start, int end) {
  lua_State *L = idleL;
  int top;
  rl_attempted_completion_over = 1;  /* no file names unless the function says so */
  rl_completion_append_character = '\0';
  if (L == NULL) return NULL;
  top = lua_gettop(L);
  if (lua_getfield(L, LUA_REGISTRYINDEX, "lsys.complete") != LUA_TFUNCTION) {
    lua_settop(L, top);
    return NULL;
  }
  lua_pushstring(L, rl_line_buffer);
  lua_pushinteger(L, start);
  lua_pushinteger(L, end);
  if (lua_pcall(L, 3, 1, 0) == LUA_OK && lua_isnil(L, -1)) {
    rl_attempted_completion_over = 0;
    lua_settop(L, top);
    return NULL;
  }
  lua_setfield(L, LUA_REGISTRYINDEX, "lsys.candidates");  /* an error message: no list */
  lua_settop(L, top);
  return rl_completion_matches(text, nextcandidate);
}

/* set_complete(f): the Lua function that completes words at the Tab key (nil: none). */
static int l_set_complete (lua_State *L) {
  if (!lua_isnoneornil(L, 1)) luaL_checktype(L, 1, LUA_TFUNCTION);
  lua_settop(L, 1);
  lua_setfield(L, LUA_REGISTRYINDEX, "lsys.complete");
  return 0;
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
  if (L == NULL || stopsignal) return 0;   /* ending: the line is being abandoned */
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

static const luaL_Reg readline_funcs[] = {
  {"readline", l_readline},
  {"history", l_history},
  {"set_complete", l_set_complete},
  {NULL, NULL}
};

/*
** require "lsys.readline" -> { readline, history, set_complete }. A word to complete
** runs back to a blank, a quote or an operator: "lsys.view.l" and "m:de" are one word.
*/
static int luaopen_lsys_readline (lua_State *L) {
  static char breaks[] = " \t\n\"'`@$><=;|&{([,+-*/%^#~)}]";
  static char quotes[] = "\"'";
  rl_readline_name = "lsys";  /* for $if lsys in ~/.inputrc */
  rl_event_hook = idlehook;
#if RL_READLINE_VERSION >= 0x0800
  rl_getc_function = getkey;
#endif
  rl_attempted_completion_function = complete;
  rl_completer_word_break_characters = breaks;
  rl_completer_quote_characters = quotes;
  luaL_newlib(L, readline_funcs);
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
** Pushes the first directory that holds lsys/cli/init.lua, or nil: the source tree when
** running from the build directory, then the install tree relative to the program (BINDIR
** to LUADIR, and the usual ../share/lua/5.4 where luarocks deploys), then the compiled-in
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
    lua_pushfstring(L, "%s/lsys/cli/init.lua", lua_tostring(L, i));
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
      return luaL_error(L, "cannot find the lsys Lua files (lsys/cli/init.lua) beside the "
                           "program (%s) nor in its install directory; LUA_PATH may name them",
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

/* The end of a program stopped by SIGINT or SIGTERM: the finalizers run (with no hook:
** they are cleaning up), the message is printed, then the process ends by the signal,
** as a shell expects of a program that was interrupted. */
static int stopped (lua_State *L) {
  int sig = stopsignal;
  lua_sethook(L, NULL, 0, 0);
  lua_close(L);
  fflush(stdout);
  fprintf(stderr, "lsys: %s\n", sig == SIGTERM ? "terminated" : "interrupted");
  fflush(stderr);
  signal(sig, SIG_DFL);
  raise(sig);
  return 128 + sig;
}

int main (int argc, char **argv) {
  lua_State *L;
  int status, code;
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD)
  /* Blocks under 32 MiB come from the heap, and up to 64 MiB freed at its top stay
  ** there: a plant made again (an edit, an animation frame, a regeneration) reuses the
  ** memory of the one before instead of faulting fresh pages, which costs more than the
  ** work on them. A string's arrays map blocks of 1 MiB and more themselves
  ** (lstring.c), so a derivation still grows its string in place by moving pages. */
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
  L = luaL_newstate();
  if (L == NULL) {
    fputs("lsys: cannot create the Lua state: not enough memory\n", stderr);
    return EXIT_FAILURE;
  }
  globalL = L;
  {
    struct sigaction old;
    ignored[0] = sigaction(SIGINT, NULL, &old) == 0 && old.sa_handler == SIG_IGN;
    ignored[1] = sigaction(SIGTERM, NULL, &old) == 0 && old.sa_handler == SIG_IGN;
  }
  setstop(0);
#ifdef SIGXFSZ
  /* a write beyond `ulimit -f` fails (EFBIG) instead of killing the program: the writers
  ** report it and remove their temporary, and the old file stays */
  signal(SIGXFSZ, SIG_IGN);
#endif
  lua_gc(L, LUA_GCSTOP);  /* stop the collector while building the state */
  lua_pushcfunction(L, pmain);
  lua_pushinteger(L, argc);
  lua_pushlightuserdata(L, argv);
  status = lua_pcall(L, 2, 1, 0);
  if (stopsignal) return stopped(L);
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
