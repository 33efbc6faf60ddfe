/*
** C unit tests of the tablet pressure reader (xpen.h) without a tablet: the
** normalization of a valuator's value (a lifted pen reads its minimum), and
** the clear answer without a display. The Xvfb spec (sketch_window_spec.lua)
** lists a real server's devices, none of which report pressure.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef LSYS_NO_RENDER
#include "xpen.h"

static void normalize (void) {
  /* a Wacom pen reports 0 .. 2047, libinput's devices 0 .. 65535 */
  assert(lsys_xpen_normalize(1023.5, 0, 2047) == 0.5);
  assert(lsys_xpen_normalize(2047, 0, 2047) == 1);
  assert(lsys_xpen_normalize(5000, 0, 2047) == 1);          /* clamped */
  assert(fabs(lsys_xpen_normalize(16384, 0, 65535) - 0.25000381) < 1e-7);
  assert(lsys_xpen_normalize(-3, -10, 10) == 0.35);
  assert(lsys_xpen_normalize(0, 0, 2047) == -1);            /* lifted: none */
  assert(lsys_xpen_normalize(-1, 0, 2047) == -1);
  assert(lsys_xpen_normalize(5, 3, 3) == -1);               /* an empty range */
  assert(lsys_xpen_normalize(5, 7, 3) == -1);
  assert(lsys_xpen_normalize(NAN, 0, 1) == -1);
}

static void nodisplay (void) {
  lsys_xpendev dev[4];
  char why[256];
  int n;
  setenv("DISPLAY", "", 1);
  n = lsys_xpen_list(dev, 4, why, sizeof why);
  if (strstr(why, "libX") != NULL) {        /* no libX11 or libXi: said so */
    assert(n == -1);
    return;
  }
  assert(n == -1);
  assert(strcmp(why, "cannot open the X display (DISPLAY is not set)") == 0);
  assert(lsys_xpen_open(why, sizeof why) == NULL);
  assert(strcmp(why, "cannot open the X display") == 0);
  assert(lsys_xpen_pressure(NULL) == -1);
  assert(strcmp(lsys_xpen_names(NULL), "") == 0);
  lsys_xpen_close(NULL);
}

int main (void) {
  normalize();
  nodisplay();
  printf("test_xpen: ok\n");
  return 0;
}
#else
int main (void) {
  printf("test_xpen: skipped (built without rendering)\n");
  return 0;
}
#endif
