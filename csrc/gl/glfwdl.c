/*
** libglfw, opened at the first window (glfwdl.h). Empty in a build without
** the viewer (no GLFW header).
*/
#ifndef LSYS_NO_VIEWER
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "dynlib.h"
#include "glfwdl.h"

#define G lsys_glfw

#ifndef LSYS_GLFW_SONAME
#define LSYS_GLFW_SONAME "libglfw.so.3"
#endif

static const char *const glfwlibs[] = { LSYS_GLFW_SONAME, "libglfw.so.3", "libglfw.so", NULL };

lsys_glfwapi lsys_glfw;
char lsys_glfwerr[192];

void lsys_glfwdl_onerror (int code, const char *msg) {
  snprintf(lsys_glfwerr, sizeof lsys_glfwerr, "%s (GLFW error 0x%x)", msg ? msg : "?",
           (unsigned)code);
}

int lsys_glfwdl_load (lsys_error *e) {
#define SYM(f) {&G.f, sizeof G.f, "glfw" #f}
  const lsys_dynsym syms[] = {
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
  char why[200];
  const char *missing;
  if (G.lib != NULL) return LSYS_OK;
  G.lib = lsys_dynlib_open(glfwlibs, why, sizeof why);
  if (G.lib == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "cannot load libglfw for the viewer window (%s); install libglfw3 "
                         "(./setup.sh does)", why);
  missing = lsys_dynlib_syms(G.lib, syms, sizeof syms / sizeof syms[0]);
  if (missing != NULL) {
    dlclose(G.lib);
    G.lib = NULL;
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "libglfw has no %s (GLFW 3.2 or later "
                         "is needed)", missing);
  }
  return LSYS_OK;
}

lsys_glproc lsys_glfwdl_getproc (const char *name) {
  GLFWglproc f = G.GetProcAddress(name);
  lsys_glproc g;
  memcpy(&g, &f, sizeof g);
  return g;
}

#else
typedef int lsys_glfwdl_empty;     /* ISO C wants something in a file */
#endif
