/*
** Pen pressure from an X input device (a drawing tablet), for the sketch
** window (Anastacio et al. 2009 §3.5: pressure sets the stem's
** depth). GLFW 3.3 reports no pressure, so this opens its own connection to
** the X server and reads the "Abs Pressure" valuator of every XInput 2
** device that has one. libX11 and libXi are opened with dlopen, like
** libglfw: without them, without a display, or without such a device,
** lsys_xpen_open says why and the window falls back to the wheel.
**
** The connection belongs to the thread that opened it (Xlib is not asked to
** be thread-safe); the viewer opens it on its own thread.
*/
#ifndef LSYS_XPEN_H
#define LSYS_XPEN_H

#include <stddef.h>

#define LSYS_XPEN_MAXDEV 16

typedef struct lsys_xpendev {
  int id;                       /* the XInput 2 device id */
  char name[96];
  int valuator;                 /* the pressure valuator's number, -1 when none */
  double min, max, value;       /* its range and its value when last read */
} lsys_xpendev;

typedef struct lsys_xpen lsys_xpen;

/* Lists the X input devices (pointer and floating slaves) into dev[0..max)
** and returns how many there are (at most max), or -1 with 'why' (nwhy
** bytes) saying why none could be listed (no libXi, no display). */
int lsys_xpen_list (lsys_xpendev *dev, int max, char *why, size_t nwhy);

/* Opens the devices that report pressure. NULL, with 'why', when there are
** none or they cannot be read. */
lsys_xpen *lsys_xpen_open (char *why, size_t nwhy);

/* The pressure in [0, 1] of the device pressed hardest now, or -1 when no
** pressure device is pressed (its valuator at its minimum): a pen lifted, or
** the mouse is the one drawing. */
double lsys_xpen_pressure (lsys_xpen *p);

/* The device names, for a status line ("" when p is NULL). */
const char *lsys_xpen_names (const lsys_xpen *p);

void lsys_xpen_close (lsys_xpen *p);

/* (v - lo) / (hi - lo) clamped to [0, 1]; -1 when v <= lo or the range is
** empty. Exposed for the unit test. */
double lsys_xpen_normalize (double v, double lo, double hi);

#endif
