/*
** Small vector helpers on double[3], and PI: the one copy, shared by the
** turtle, the geometry builders, inverse kinematics, the renderer and the
** viewer.
*/
#ifndef LSYS_VEC3_H
#define LSYS_VEC3_H

#include <math.h>

#define PI 3.14159265358979323846

static inline void vset (double *a, double x, double y, double z) { a[0] = x; a[1] = y; a[2] = z; }
static inline void vcopy (double *a, const double *b) { a[0] = b[0]; a[1] = b[1]; a[2] = b[2]; }
static inline double vdot (const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/* r = a x b (r may alias a or b) */
static inline void vcross (double *r, const double *a, const double *b) {
  double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
         z = a[0] * b[1] - a[1] * b[0];
  r[0] = x; r[1] = y; r[2] = z;
}
static inline double vlen (const double *a) { return sqrt(vdot(a, a)); }
/* Normalises 'a'; returns 0 (and leaves 'a') when it is (nearly) zero. */
static inline int vnorm (double *a) {
  double l = vlen(a);
  if (!(l > 1e-300)) return 0;
  a[0] /= l; a[1] /= l; a[2] /= l;
  return 1;
}
/* Normalises 'a' unless it is exactly zero; returns its length before.
** Where the caller tests the length itself (the camera frame, IK frames):
** unlike vnorm, a tiny vector is still scaled up. */
static inline double vnormlen (double *a) {
  double l = vlen(a);
  if (l > 0) { a[0] /= l; a[1] /= l; a[2] /= l; }
  return l;
}
/* r = a*ca + b*cb (r may alias a or b) */
static inline void vlin (double *r, const double *a, double ca, const double *b, double cb) {
  double x = a[0] * ca + b[0] * cb, y = a[1] * ca + b[1] * cb, z = a[2] * ca + b[2] * cb;
  r[0] = x; r[1] = y; r[2] = z;
}
/* Rotates 'v' about the unit axis 'k' by the angle whose cosine and sine
** are c and s (Rodrigues). */
static inline void vrotcs (double *v, const double *k, double c, double s) {
  double kv[3], d = vdot(k, v);
  vcross(kv, k, v);
  v[0] = v[0] * c + kv[0] * s + k[0] * d * (1 - c);
  v[1] = v[1] * c + kv[1] * s + k[1] * d * (1 - c);
  v[2] = v[2] * c + kv[2] * s + k[2] * d * (1 - c);
}
static inline void vrotate (double *v, const double *k, double a) { vrotcs(v, k, cos(a), sin(a)); }

#endif
