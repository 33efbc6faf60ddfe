/*
** C unit tests of dynlib.h: the error of a library that cannot be opened
** says why the first name failed and lists the other names tried, once
** each; a library that opens gives its functions.
*/
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <string.h>

#ifndef LSYS_NO_RENDER
#include <dlfcn.h>

#include "dynlib.h"

static void test_missing (void) {
  static const char *const names[] = {
    "liblsys-none.so.8", "liblsys-none.so.8", "liblsys-none.so.6", "liblsys-none.so", NULL
  };
  static const char *const none[] = {NULL};
  char err[200], small[20];
  assert(lsys_dynlib_open(names, err, sizeof err) == NULL);
  assert(strncmp(err, "liblsys-none.so.8: ", 19) == 0);        /* dlerror's reason */
  assert(strstr(err, "; also tried liblsys-none.so.6, liblsys-none.so") != NULL);
  assert(strstr(err, "tried liblsys-none.so.8") == NULL);       /* a repeat is not tried */
  assert(lsys_dynlib_open(names, small, sizeof small) == NULL);
  assert(strlen(small) == sizeof small - 1);                    /* cut, terminated */
  assert(lsys_dynlib_open(none, err, sizeof err) == NULL && err[0] == '\0');
  printf("missing: ok\n");
}

#ifdef __linux__
static void test_found (void) {
  static const char *const names[] = {"liblsys-none.so", "libm.so.6", NULL};
  double (*cosine) (double) = NULL, (*sine) (double) = NULL;
  const lsys_dynsym syms[] = {
    {&cosine, sizeof cosine, "cos"}, {&sine, sizeof sine, "sin"}
  };
  const lsys_dynsym bad[] = {{&sine, sizeof sine, "sin"}, {&cosine, sizeof cosine, "nocos"}};
  char err[200];
  void *lib = lsys_dynlib_open(names, err, sizeof err);
  assert(lib != NULL);
  assert(lsys_dynlib_syms(lib, syms, 2) == NULL);
  assert(cosine(0) == 1 && sine(0) == 0);
  assert(strcmp(lsys_dynlib_syms(lib, bad, 2), "nocos") == 0);
  dlclose(lib);
  printf("found: ok\n");
}
#endif
#endif

int main (void) {
#ifdef LSYS_NO_RENDER
  printf("built without rendering: nothing to test\n");
#else
  test_missing();
#ifdef __linux__
  test_found();
#endif
#endif
  return 0;
}
