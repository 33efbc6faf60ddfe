/*
** Pen pressure from XInput 2 (xpen.h). The few Xlib and XInput 2 types used
** are declared here (their layout is the X.Org ABI, fixed since XInput 2.0 in
** 2009), so building needs neither libx11-dev nor libxi-dev; the libraries
** are opened at run time.
*/
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dynlib.h"
#include "xpen.h"

/* {------------------------------------------------------------------------ */
/* the X.Org ABI (X11/Xlib.h, X11/extensions/XInput2.h) */

typedef unsigned long xatom;
typedef struct xdisplay xdisplay;     /* opaque */

typedef struct {
  int type, sourceid;
} xi_anyclass;

typedef struct {
  int type, sourceid, number;
  xatom label;
  double min, max, value;
  int resolution, mode;
} xi_valuatorclass;

typedef struct {
  int deviceid;
  char *name;
  int use, attachment;
  int enabled;
  int num_classes;
  xi_anyclass **classes;
} xi_deviceinfo;

enum { XI_ALLDEVICES = 0, XI_SLAVEPOINTER = 3, XI_FLOATINGSLAVE = 5, XI_VALUATORCLASS = 2 };

/* the valuator label of X.Org's input drivers (evdev, libinput, wacom) */
#define PRESSURE_LABEL "Abs Pressure"

static struct {
  void *x11, *xi;
  xdisplay *(*OpenDisplay) (const char *name);
  int (*CloseDisplay) (xdisplay *d);
  char *(*GetAtomName) (xdisplay *d, xatom a);
  int (*Free) (void *p);
  xi_deviceinfo *(*QueryDevice) (xdisplay *d, int id, int *n);
  void (*FreeDeviceInfo) (xi_deviceinfo *info);
} X;

/* Opens libX11 and libXi once (never closed: Xlib keeps extension hooks). */
static int loadx (char *why, size_t nwhy) {
  static const char *const x11libs[] = { "libX11.so.6", "libX11.so", NULL };
  static const char *const xilibs[] = { "libXi.so.6", "libXi.so", NULL };
  const lsys_dynsym x11syms[] = {
    {&X.OpenDisplay, sizeof X.OpenDisplay, "XOpenDisplay"},
    {&X.CloseDisplay, sizeof X.CloseDisplay, "XCloseDisplay"},
    {&X.GetAtomName, sizeof X.GetAtomName, "XGetAtomName"},
    {&X.Free, sizeof X.Free, "XFree"},
  };
  const lsys_dynsym xisyms[] = {
    {&X.QueryDevice, sizeof X.QueryDevice, "XIQueryDevice"},
    {&X.FreeDeviceInfo, sizeof X.FreeDeviceInfo, "XIFreeDeviceInfo"},
  };
  char err[200];
  const char *missing;
  if (X.xi != NULL) return 1;
  if (X.x11 == NULL && (X.x11 = lsys_dynlib_open(x11libs, err, sizeof err)) == NULL) {
    snprintf(why, nwhy, "no libX11 (%s)", err);
    return 0;
  }
  if ((missing = lsys_dynlib_syms(X.x11, x11syms, sizeof x11syms / sizeof x11syms[0]))) {
    snprintf(why, nwhy, "libX11 has no %s", missing);
    return 0;
  }
  if ((X.xi = lsys_dynlib_open(xilibs, err, sizeof err)) == NULL) {
    snprintf(why, nwhy, "no libXi (%s; Debian: libxi6)", err);
    return 0;
  }
  if ((missing = lsys_dynlib_syms(X.xi, xisyms, sizeof xisyms / sizeof xisyms[0]))) {
    dlclose(X.xi);
    X.xi = NULL;
    snprintf(why, nwhy, "libXi has no %s (XInput 2 is needed)", missing);
    return 0;
  }
  return 1;
}

/* }------------------------------------------------------------------------ */

struct lsys_xpen {
  xdisplay *d;
  int n;
  lsys_xpendev dev[LSYS_XPEN_MAXDEV];
  char names[256];
};

double lsys_xpen_normalize (double v, double lo, double hi) {
  double t;
  if (!(hi > lo) || !(v > lo)) return -1;
  t = (v - lo) / (hi - lo);
  return t > 1 ? 1 : t;
}

/* Fills dev[0..max) from display d's pointer devices; device 'only' (or all
** when 0). Returns the count. */
static int query (xdisplay *d, int only, lsys_xpendev *dev, int max) {
  int i, k, n = 0, count = 0;
  xi_deviceinfo *info = X.QueryDevice(d, only ? only : XI_ALLDEVICES, &n);
  if (info == NULL) return 0;
  for (i = 0; i < n && count < max; i++) {
    xi_deviceinfo *di = &info[i];
    lsys_xpendev *o = &dev[count];
    if (!only && di->use != XI_SLAVEPOINTER && di->use != XI_FLOATINGSLAVE) continue;
    memset(o, 0, sizeof *o);
    o->id = di->deviceid;
    snprintf(o->name, sizeof o->name, "%s", di->name ? di->name : "?");
    o->valuator = -1;
    for (k = 0; k < di->num_classes; k++) {
      const xi_valuatorclass *vc = (const xi_valuatorclass *)di->classes[k];
      char *label;
      if (di->classes[k]->type != XI_VALUATORCLASS || vc->label == 0) continue;
      label = X.GetAtomName(d, vc->label);
      if (label != NULL && strcmp(label, PRESSURE_LABEL) == 0) {
        o->valuator = vc->number;
        o->min = vc->min;
        o->max = vc->max;
        o->value = vc->value;
      }
      if (label != NULL) X.Free(label);
      if (o->valuator >= 0) break;
    }
    count++;
  }
  X.FreeDeviceInfo(info);
  return count;
}

int lsys_xpen_list (lsys_xpendev *dev, int max, char *why, size_t nwhy) {
  xdisplay *d;
  int n;
  if (!loadx(why, nwhy)) return -1;
  if ((d = X.OpenDisplay(NULL)) == NULL) {
    const char *name = getenv("DISPLAY");
    snprintf(why, nwhy, "cannot open the X display %s", name && *name ? name
             : "(DISPLAY is not set)");
    return -1;
  }
  n = query(d, 0, dev, max);
  X.CloseDisplay(d);
  return n;
}

lsys_xpen *lsys_xpen_open (char *why, size_t nwhy) {
  lsys_xpendev all[LSYS_XPEN_MAXDEV];
  lsys_xpen *p;
  xdisplay *d;
  int i, n;
  size_t at = 0;
  if (!loadx(why, nwhy)) return NULL;
  if ((d = X.OpenDisplay(NULL)) == NULL) {
    snprintf(why, nwhy, "cannot open the X display");
    return NULL;
  }
  n = query(d, 0, all, LSYS_XPEN_MAXDEV);
  if ((p = (lsys_xpen *)calloc(1, sizeof *p)) == NULL) {
    X.CloseDisplay(d);
    snprintf(why, nwhy, "out of memory");
    return NULL;
  }
  p->d = d;
  for (i = 0; i < n; i++) {
    int w;
    if (all[i].valuator < 0) continue;
    p->dev[p->n++] = all[i];
    w = snprintf(p->names + at, sizeof p->names - at, "%s%s", at ? ", " : "", all[i].name);
    if (w > 0 && at + (size_t)w < sizeof p->names) at += (size_t)w;
  }
  if (p->n == 0) {
    snprintf(why, nwhy, "none of the %d X input devices reports pressure", n);
    lsys_xpen_close(p);
    return NULL;
  }
  return p;
}

double lsys_xpen_pressure (lsys_xpen *p) {
  double best = -1;
  int i;
  if (p == NULL) return -1;
  for (i = 0; i < p->n; i++) {
    lsys_xpendev *dv = &p->dev[i], now;
    double t;
    if (query(p->d, dv->id, &now, 1) != 1 || now.valuator < 0) continue;  /* unplugged */
    dv->value = now.value;
    t = lsys_xpen_normalize(now.value, dv->min, dv->max);
    if (t > best) best = t;
  }
  return best;
}

const char *lsys_xpen_names (const lsys_xpen *p) {
  return p ? p->names : "";
}

void lsys_xpen_close (lsys_xpen *p) {
  if (p == NULL) return;
  if (p->d) X.CloseDisplay(p->d);
  free(p);
}
