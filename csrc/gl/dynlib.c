/*
** Opening a shared library by one of several names (dynlib.h).
*/
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "dynlib.h"

/* Whether names[i] already came earlier in the list. */
static int seen (const char *const *names, size_t i) {
  size_t j;
  for (j = 0; j < i; j++)
    if (strcmp(names[j], names[i]) == 0) return 1;
  return 0;
}

void *lsys_dynlib_open (const char *const *names, char *err, size_t nerr) {
  const char *sep = "; also tried ";
  size_t i, at;
  if (nerr > 0) err[0] = '\0';
  for (i = 0; names[i] != NULL; i++) {
    void *lib;
    if (seen(names, i)) continue;
    lib = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
    if (lib != NULL) return lib;
    /* dlerror names the file and says why; the first name is the library
    ** found when lsys was configured, so its reason is the telling one */
    if (i == 0 && nerr > 0) snprintf(err, nerr, "%s", dlerror());
  }
  for (i = 1, at = nerr > 0 ? strlen(err) : 0; names[0] != NULL && names[i] != NULL; i++) {
    int n;
    if (seen(names, i)) continue;
    if (at >= nerr || (n = snprintf(err + at, nerr - at, "%s%s", sep, names[i])) < 0) break;
    at += (size_t)n;
    sep = ", ";
  }
  return NULL;
}

/* Each pointer is stored through memcpy, as in lsys_render_gl_load (render.c):
** dlsym returns an object pointer, and all function pointers share its
** representation on the platforms that have dlsym. */
const char *lsys_dynlib_syms (void *lib, const lsys_dynsym *syms, size_t n) {
  size_t i;
  for (i = 0; i < n; i++) {
    void *p = dlsym(lib, syms[i].name);
    if (p == NULL) return syms[i].name;
    memcpy(syms[i].fn, &p, syms[i].size);
  }
  return NULL;
}
