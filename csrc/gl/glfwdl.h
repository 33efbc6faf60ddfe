/*
** libglfw, opened with dlopen when the first viewer window opens
** (glfw_viewer.c), as libOSMesa is at the first render (osmesa.c):
** lsys.core then needs neither GLFW nor a display to load. The entry points
** the viewer calls are in one table, filled once.
*/
#ifndef LSYS_GLFWDL_H
#define LSYS_GLFWDL_H

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "render.h"

typedef struct lsys_glfwapi {
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
} lsys_glfwapi;

/* The table (valid after lsys_glfwdl_load) and the last GLFW error reported
** (written on the viewer thread by the error callback lsys_glfwdl_onerror). */
extern lsys_glfwapi lsys_glfw;
extern char lsys_glfwerr[192];
void lsys_glfwdl_onerror (int code, const char *msg);

/* Opens libglfw and fills the table, once; LSYS_OK or LSYS_EARG with e->msg
** saying what is missing. Callers serialise it (the viewer's lock). */
int lsys_glfwdl_load (lsys_error *e);

/* glfwGetProcAddress, in the form lsys_render_gl_load wants. */
lsys_glproc lsys_glfwdl_getproc (const char *name);

#endif
