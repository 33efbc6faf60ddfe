/*
** Camera and picking arithmetic, without GL (viewcam.h): the camera of a
** view fitted to a scene and the projection of a point (render.h), the
** viewer's camera moved with the mouse, and picking (viewer.h).
**
** The numbers are those the renderer and the window always computed, in
** the same order of operations: golden images and picks depend on them.
*/
#include <math.h>
#include <string.h>

#include "population.h"
#include "vec3.h"
#include "viewcam.h"
#include "viewer.h"

/* Fraction of the half-width and half-height that the fitted bounding box
** may fill: the margin is 5% of the image on each side. */
#define FIT 0.9

/* ---------------------------------------------------------------------- */
/* the camera of a view (render.h) */

/* A mesh as a scene that draws it (the arrays borrowed), for the camera
** functions, which all take scenes: a population's points are its
** instances' (lsys_scene_bounds). NULL is an empty scene. */
static const lsys_scene *asscene (const lsys_mesh *m, lsys_scene *tmp) {
  memset(tmp, 0, sizeof *tmp);
  if (m != NULL) tmp->mesh = *m;
  return tmp;
}

/* Whether scene s draws a vertex or a line end. */
static int drawsany (const lsys_scene *s) {
  size_t nv, nt, nl;
  if (s == NULL) return 0;
  lsys_population_size(s, &nv, &nt, &nl);
  return nv + nl > 0;
}

/* The 8 corners of the bounds b (lo, hi), or of s's when b is NULL; empty
** bounds (or infinite coordinates) are the cube [-1, 1]^3, a single point a
** cube of size 2 around it. Returns the length of the box's diagonal (> 0). */
static double cornersof (const lsys_scene *s, const double *b, double c[8][3],
                         double centre[3]) {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, d[3];
  int i, ok;
  if (b != NULL) {
    for (i = 0; i < 3; i++) { lo[i] = b[i]; hi[i] = b[3 + i]; }
    ok = lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2];
  } else
    ok = s != NULL && lsys_scene_bounds(s, lo, hi);
  if (!ok || !isfinite(lo[0] + lo[1] + lo[2] + hi[0] + hi[1] + hi[2])) {
    lo[0] = lo[1] = lo[2] = -1;
    hi[0] = hi[1] = hi[2] = 1;
  }
  for (i = 0; i < 3; i++) d[i] = hi[i] - lo[i];
  if (d[0] <= 0 && d[1] <= 0 && d[2] <= 0) {
    for (i = 0; i < 3; i++) { lo[i] -= 1; hi[i] += 1; d[i] = 2; }
  }
  for (i = 0; i < 8; i++) {
    c[i][0] = (i & 1) ? hi[0] : lo[0];
    c[i][1] = (i & 2) ? hi[1] : lo[1];
    c[i][2] = (i & 4) ? hi[2] : lo[2];
  }
  for (i = 0; i < 3; i++) centre[i] = 0.5 * (lo[i] + hi[i]);
  return vlen(d);
}

static double corners (const lsys_scene *s, double c[8][3], double centre[3]) {
  return cornersof(s, NULL, c, centre);
}

/* The camera frame and what fitting it accumulates over the scene's points. */
typedef struct fitstate {
  double ext;               /* parallel: half height needed */
  double D;                 /* perspective: distance from the target needed */
  int parallel;
  double aspect, ty, target[3], r[3], u[3], f[3];
} fitstate;

static void fitpointd (fitstate *fs, const double p[3]) {
  double q[3], x, y;
  q[0] = p[0] - fs->target[0];
  q[1] = p[1] - fs->target[1];
  q[2] = p[2] - fs->target[2];
  x = fabs(vdot(q, fs->r));
  y = fabs(vdot(q, fs->u));
  if (!isfinite(x + y)) return;       /* fmax would keep an infinity */
  if (fs->parallel)
    fs->ext = fmax(fs->ext, fmax(y, x / fs->aspect));
  else
    fs->D = fmax(fs->D, fmax(x / (fs->ty * fs->aspect * FIT), y / (fs->ty * FIT)) -
                        vdot(q, fs->f));
}

static void fitpoint (fitstate *fs, const float p[3]) {
  double d[3] = {p[0], p[1], p[2]};
  fitpointd(fs, d);
}

/* Fits every vertex and line end scene s draws: its mesh's, or each
** instance's part under its transform. */
static void fitscene (fitstate *fs, const lsys_scene *s) {
  const lsys_mesh *m = &s->mesh;
  size_t k, i;
  if (s->ninst == 0) {
    for (k = 0; k < m->nv; k++) fitpoint(fs, m->pos + 3 * k);
    for (k = 0; k < 2 * m->nl; k++) fitpoint(fs, m->lpos + 3 * k);
    return;
  }
  for (i = 0; i < s->ninst; i++) {
    const lsys_part *p;
    double q[3];
    if (s->inst[i].part >= s->nparts) continue;
    p = &s->parts[s->inst[i].part];
    for (k = 0; k < p->nv; k++) {
      lsys_xform(s->inst[i].m, m->pos + 3 * (p->v0 + k), q);
      fitpointd(fs, q);
    }
    for (k = 0; k < 2 * p->nl; k++) {
      lsys_xform(s->inst[i].m, m->lpos + 3 * (2 * p->l0 + k), q);
      fitpointd(fs, q);
    }
  }
}

/* The frame of 'cam' aimed at fs->target: forward f, right r, up u (an up
** along f is replaced), turned by the twist. Returns LSYS_OK, or LSYS_EARG
** when the eye is on the target or 'dir' or 'up' is zero. */
static int camframe (fitstate *fs, const lsys_camera *cam) {
  double *f = fs->f, *r = fs->r, *u = fs->u, up[3], t, ct, st;
  int i;
  if (cam->has_eye) {
    for (i = 0; i < 3; i++) f[i] = fs->target[i] - cam->eye[i];
  } else
    vcopy(f, cam->dir);
  if (vnormlen(f) == 0) return LSYS_EARG;
  if (cam->has_up) vcopy(up, cam->up);
  else vset(up, 0, 1, 0);
  if (vnormlen(up) == 0) return LSYS_EARG;
  vcross(r, f, up);
  if (vnormlen(r) < 1e-6) {
    up[0] = 0; up[1] = 0; up[2] = f[1] < 0 ? -1 : 1;
    if (fabs(f[2]) > 0.9) { up[1] = 1; up[2] = 0; }
    vcross(r, f, up);
    vnormlen(r);
  }
  vcross(u, r, f);
  /* twist: turn the picture counterclockwise, i.e. the frame clockwise */
  t = cam->twist * PI / 180;
  ct = cos(t); st = sin(t);
  for (i = 0; i < 3; i++) {
    double ri = r[i], ui = u[i];
    r[i] = ct * ri - st * ui;
    u[i] = ct * ui + st * ri;
  }
  return LSYS_OK;
}

/*
** Fits the frame of 'fs' to the scene: in the camera frame around the
** target, a point is at (x, y, z), z along f. Parallel: the half height
** must cover |y| and |x| / aspect. Perspective: the eye at distance D
** behind the target sees the point within the image when
** |x| <= (D + z) ty aspect and |y| <= (D + z) ty. The points are the
** scene's vertices and line ends (the corners of the box, seen in
** perspective, would leave a wide margin), or the corners of the box 'c'
** for an empty scene. Returns the half height; sets 'eye' when the camera
** has none.
*/
static double fitview (fitstate *fs, const lsys_scene *s, const lsys_camera *cam,
                       double c[8][3], double diag, double eye[3]) {
  double halfh;
  int i, any = drawsany(s);
  if (any) fitscene(fs, s);
  if (!any || !(fs->ext > 0 || fs->D > 0))
    for (i = 0; i < 8; i++) {
      float p[3] = {(float)c[i][0], (float)c[i][1], (float)c[i][2]};
      fitpoint(fs, p);
    }
  halfh = cam->halfh > 0 ? cam->halfh : fs->ext > 0 ? fs->ext / FIT : diag / 2;
  if (!cam->has_eye) {
    double D = fs->D, back = 0;
    for (i = 0; i < 8; i++) {
      double q[3] = {c[i][0] - fs->target[0], c[i][1] - fs->target[1], c[i][2] - fs->target[2]};
      back = fmax(back, -vdot(q, fs->f));
    }
    D = fmax(D, back + 0.05 * diag);   /* the eye stays outside the box */
    for (i = 0; i < 3; i++) eye[i] = fs->target[i] - D * fs->f[i];
  }
  return halfh;
}

/* The 8 corners of a camera's box (has_box) as a mesh of 8 vertices in p[24]. */
static const lsys_mesh *boxmesh (const double box[6], float p[24], lsys_mesh *bm) {
  int i;
  lsys_mesh_init(bm);
  for (i = 0; i < 8; i++) {
    p[3 * i] = (float)box[i & 1 ? 3 : 0];
    p[3 * i + 1] = (float)box[i & 2 ? 4 : 1];
    p[3 * i + 2] = (float)box[i & 4 ? 5 : 2];
  }
  bm->pos = p;
  bm->nv = 8;
  return bm;
}

int lsys_render_camera (const lsys_mesh *m, const lsys_camera *cam, int w, int h,
                        double proj[16], double view[16]) {
  lsys_scene tmp;
  return lsys_render_camera_scene(asscene(m, &tmp), cam, w, h, proj, view);
}

int lsys_render_camera_scene (const lsys_scene *s, const lsys_camera *cam, int w, int h,
                              double proj[16], double view[16]) {
  float bp[24];
  lsys_mesh bm;
  lsys_scene bs;
  double c2[8][3], centre2[3];
  const double *r, *u, *f;
  double c[8][3], centre[3], eye[3];
  double aspect, diag, dmin, dmax, pad, nearp, farp;
  double fov = cam->fov > 0 && cam->fov < 180 ? cam->fov : 30;
  double ty = tan(fov * PI / 360), halfh = 1;
  double zoom = cam->zoom > 0 ? cam->zoom : 1;
  fitstate fs;
  int i, parallel = cam->projection == LSYS_PARALLEL;
  if (w <= 0 || h <= 0) return LSYS_EARG;
  aspect = (double)w / h;
  if (cam->has_box) {         /* fit the box; the near and far planes cover the scene too */
    const lsys_scene *scene = s;
    s = asscene(boxmesh(cam->box, bp, &bm), &bs);
    diag = corners(s, c, centre);
    if (drawsany(scene)) {
      cornersof(scene, cam->has_bounds ? cam->bounds : NULL, c2, centre2);
      for (i = 0; i < 8; i++) {
        int k;
        for (k = 0; k < 3; k++) {
          double lo = fmin(c[0][k], c2[0][k]), hi = fmax(c[7][k], c2[7][k]);
          c[i][k] = (i >> k) & 1 ? hi : lo;
        }
      }
    }
  } else
    diag = cornersof(s, cam->has_bounds ? cam->bounds : NULL, c, centre);
  memset(&fs, 0, sizeof fs);
  vcopy(fs.target, cam->has_target ? cam->target : centre);
  if (camframe(&fs, cam) != LSYS_OK) return LSYS_EARG;
  r = fs.r; u = fs.u; f = fs.f;
  fs.parallel = parallel;
  fs.aspect = aspect;
  fs.ty = ty;
  if (parallel && cam->has_eye && cam->halfh > 0) halfh = cam->halfh;   /* nothing to fit */
  else if (parallel || !cam->has_eye) halfh = fitview(&fs, s, cam, c, diag, eye);
  if (cam->has_eye) vcopy(eye, cam->eye);
  /* near and far planes: the depths of the corners, padded */
  dmin = dmax = 0;
  for (i = 0; i < 8; i++) {
    double q[3] = {c[i][0] - eye[0], c[i][1] - eye[1], c[i][2] - eye[2]};
    double d = vdot(q, f);
    if (i == 0 || d < dmin) dmin = d;
    if (i == 0 || d > dmax) dmax = d;
  }
  pad = 0.02 * diag;
  nearp = dmin - pad;
  farp = dmax + pad;
  if (!parallel) {
    if (farp <= 0) farp = diag;          /* the scene is behind the eye */
    if (nearp < farp * 1e-3) nearp = farp * 1e-3;
  }
  /* view: rows r, u, -f; translation -R eye (column-major) */
  for (i = 0; i < 3; i++) {
    view[4 * i + 0] = r[i];
    view[4 * i + 1] = u[i];
    view[4 * i + 2] = -f[i];
    view[4 * i + 3] = 0;
  }
  view[12] = -vdot(r, eye);
  view[13] = -vdot(u, eye);
  view[14] = vdot(f, eye);
  view[15] = 1;
  memset(proj, 0, 16 * sizeof proj[0]);
  if (parallel) {
    proj[0] = zoom / (halfh * aspect);
    proj[5] = zoom / halfh;
    proj[10] = -2 / (farp - nearp);
    proj[14] = -(farp + nearp) / (farp - nearp);
    proj[15] = 1;
  } else {
    proj[0] = zoom / (ty * aspect);
    proj[5] = zoom / ty;
    proj[10] = (farp + nearp) / (nearp - farp);
    proj[11] = -1;
    proj[14] = 2 * farp * nearp / (nearp - farp);
  }
  return LSYS_OK;
}

int lsys_render_project (const double proj[16], const double view[16], int w, int h,
                         const double p[3], double out[3]) {
  double v[4], clip[4];
  int i;
  for (i = 0; i < 4; i++)
    v[i] = view[i] * p[0] + view[4 + i] * p[1] + view[8 + i] * p[2] + view[12 + i];
  for (i = 0; i < 4; i++)
    clip[i] = proj[i] * v[0] + proj[4 + i] * v[1] + proj[8 + i] * v[2] + proj[12 + i] * v[3];
  if (!(clip[3] > 0)) {
    out[0] = out[1] = out[2] = 0;
    return 0;
  }
  out[0] = (clip[0] / clip[3] + 1) * 0.5 * w;
  out[1] = (1 - clip[1] / clip[3]) * 0.5 * h;
  out[2] = (clip[2] / clip[3] + 1) * 0.5;
  return 1;
}

void lsys_render_unproject (const double proj[16], const double view[16], double nx,
                            double ny, double origin[3], double dir[3]) {
  /* the view's rows are r, u and -f; its translation -R eye */
  double r[3] = {view[0], view[4], view[8]}, u[3] = {view[1], view[5], view[9]};
  double f[3] = {-view[2], -view[6], -view[10]}, x = nx / proj[0], y = ny / proj[5];
  int i;
  for (i = 0; i < 3; i++) origin[i] = -view[12] * r[i] - view[13] * u[i] + view[14] * f[i];
  if (proj[15] == 1) {               /* parallel: the ray starts off the eye, along f */
    for (i = 0; i < 3; i++) {
      origin[i] += x * r[i] + y * u[i];
      dir[i] = f[i];
    }
  } else {
    for (i = 0; i < 3; i++) dir[i] = f[i] + x * r[i] + y * u[i];
    vnormlen(dir);
  }
}

/* ---------------------------------------------------------------------- */
/* the viewer's camera */

int lsys_viewcam_fit (lsys_vcam *c, const lsys_scene *s, const lsys_camera *cam, int w, int h,
                      int keep) {
  lsys_camera rc = *cam;
  double proj[16], view[16], eye[3], lo[3], hi[3], d[3];
  int i;
  if (keep && c->valid) {
    rc.has_eye = 0;
    rc.has_up = 1;
    rc.twist = 0;
    vcopy(rc.dir, c->f);
    vcopy(rc.up, c->u);
    rc.has_target = 0;
    rc.has_box = 0;             /* F fits what is shown */
    rc.zoom = 1;
  }
  rc.halfh = 0;
  if (lsys_render_camera_scene(s, &rc, w, h, proj, view) != LSYS_OK) return LSYS_EARG;
  /* rows of the view matrix: right, up, -forward; eye = -R^T t */
  for (i = 0; i < 3; i++) {
    c->u[i] = view[4 * i + 1];
    c->f[i] = -view[4 * i + 2];
    eye[i] = -(view[4 * i] * view[12] + view[4 * i + 1] * view[13] +
               view[4 * i + 2] * view[14]);
  }
  if (rc.has_target) vcopy(c->target, rc.target);
  else if (rc.has_box)
    for (i = 0; i < 3; i++) c->target[i] = 0.5 * (rc.box[i] + rc.box[3 + i]);
  else if (s != NULL && lsys_scene_bounds(s, lo, hi) &&
           isfinite(lo[0] + lo[1] + lo[2] + hi[0] + hi[1] + hi[2]))
    for (i = 0; i < 3; i++) c->target[i] = 0.5 * (lo[i] + hi[i]);
  else
    vlin(c->target, eye, 1, c->f, 1.0);
  vlin(d, eye, 1, c->target, -1);
  c->dist = vlen(d);
  if (!(c->dist > 0)) c->dist = 1;
  c->halfh = proj[5] > 0 ? 1 / proj[5] : 1;   /* proj[5] = zoom / halfh (parallel) */
  c->valid = 1;
  return LSYS_OK;
}

void lsys_viewcam_apply (const lsys_vcam *c, lsys_camera *cam) {
  if (!c->valid) return;
  cam->has_eye = cam->has_target = cam->has_up = 1;
  cam->twist = 0;               /* in u already */
  vcopy(cam->target, c->target);
  vcopy(cam->up, c->u);
  if (cam->projection == LSYS_PARALLEL) {
    vlin(cam->eye, c->target, 1, c->f, -1.0);
    cam->halfh = c->halfh;
    cam->zoom = 1;
  } else
    vlin(cam->eye, c->target, 1, c->f, -c->dist);
}

int lsys_viewcam_matrices (const lsys_vcam *c, const lsys_scene *s, const lsys_camera *cam,
                           int w, int h, double proj[16], double view[16]) {
  lsys_camera rc = *cam;
  lsys_viewcam_apply(c, &rc);
  return lsys_render_camera_scene(s, &rc, w, h, proj, view);
}

void lsys_viewcam_orbit (lsys_vcam *c, const double up[3], double dx, double dy) {
  double r[3];
  vcross(r, c->f, c->u);
  vrotate(c->f, up, -dx * LSYS_VCAM_ORBIT);       /* turntable: about the view's up */
  vrotate(c->u, up, -dx * LSYS_VCAM_ORBIT);
  vrotate(r, up, -dx * LSYS_VCAM_ORBIT);
  vrotate(c->f, r, -dy * LSYS_VCAM_ORBIT);        /* then about the camera's right */
  vrotate(c->u, r, -dy * LSYS_VCAM_ORBIT);
  vnorm(c->f);
  vcross(r, c->f, c->u);                          /* keep the frame orthonormal */
  vnorm(r);
  vcross(c->u, r, c->f);
}

double lsys_viewcam_pixelsize (const lsys_vcam *c, const lsys_camera *cam, int h) {
  double hh = h > 0 ? h : 1;
  if (cam != NULL && cam->projection == LSYS_PARALLEL) return 2 * c->halfh / hh;
  {
    double fov = cam != NULL && cam->fov > 0 ? cam->fov : 30;
    double zoom = cam != NULL && cam->zoom > 0 ? cam->zoom : 1;
    return 2 * c->dist * tan(fov * PI / 360) / zoom / hh;
  }
}

void lsys_viewcam_pan (lsys_vcam *c, const lsys_camera *cam, int h, double dx, double dy) {
  double r[3], s = lsys_viewcam_pixelsize(c, cam, h);
  vcross(r, c->f, c->u);
  vnorm(r);
  vlin(c->target, c->target, 1, r, -dx * s);
  vlin(c->target, c->target, 1, c->u, dy * s);
}

void lsys_viewcam_zoom (lsys_vcam *c, double steps) {
  double k = pow(0.88, steps);
  c->dist *= k;
  c->halfh *= k;
  if (c->dist < 1e-9) c->dist = 1e-9;
  if (c->halfh < 1e-9) c->halfh = 1e-9;
}

/* ---------------------------------------------------------------------- */
/* picking */

/* Inverts the 4 x 4 matrix 'a' (column-major) into 'inv' by Gauss-Jordan
** elimination with partial pivoting; 0 when it is singular. */
static int invert4 (const double a[16], double inv[16]) {
  double m[4][8];
  int r, c, k;
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) {
      m[r][c] = a[4 * c + r];
      m[r][4 + c] = r == c;
    }
  for (c = 0; c < 4; c++) {
    int p = c;
    for (r = c + 1; r < 4; r++)
      if (fabs(m[r][c]) > fabs(m[p][c])) p = r;
    if (!(fabs(m[p][c]) > 1e-300)) return 0;
    if (p != c)
      for (k = 0; k < 8; k++) { double t = m[c][k]; m[c][k] = m[p][k]; m[p][k] = t; }
    for (k = 7; k >= c; k--) m[c][k] /= m[c][c];
    for (r = 0; r < 4; r++) {
      double x = m[r][c];
      if (r == c || x == 0) continue;
      for (k = c; k < 8; k++) m[r][k] -= x * m[c][k];
    }
  }
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) inv[4 * c + r] = m[r][4 + c];
  return 1;
}

/* The world point of normalised device coordinates (x, y, z) under the
** inverse 'inv' of proj view; 0 when it is at infinity. */
static int unproject (const double inv[16], double x, double y, double z, double p[3]) {
  double q[4];
  int i;
  for (i = 0; i < 4; i++) q[i] = inv[i] * x + inv[4 + i] * y + inv[8 + i] * z + inv[12 + i];
  if (!(fabs(q[3]) > 1e-300)) return 0;
  for (i = 0; i < 3; i++) p[i] = q[i] / q[3];
  return 1;
}

int lsys_viewcam_ray (const double proj[16], const double view[16], int w, int h, double x,
                      double y, double origin[3], double dir[3]) {
  double pv[16], inv[16], back[3], nx, ny;
  int i, j;
  if (w <= 0 || h <= 0) return 0;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++)
      pv[4 * j + i] = proj[i] * view[4 * j] + proj[4 + i] * view[4 * j + 1] +
                      proj[8 + i] * view[4 * j + 2] + proj[12 + i] * view[4 * j + 3];
  nx = 2 * x / w - 1;           /* lsys_render_project, backwards */
  ny = 1 - 2 * y / h;
  if (!invert4(pv, inv) || !unproject(inv, nx, ny, -1, origin) ||
      !unproject(inv, nx, ny, 1, back))
    return 0;
  vlin(dir, back, 1, origin, -1);
  return vnorm(dir);
}

/*
** How a click at (x, y) meets pick p: its distance *d in pixels from the
** projected segment, the depth *z there, and the segment's drawn radius
** *rpx in pixels there (0 for lines drawn in pixels). Returns 0 when an
** end is behind the eye or the nearest point is clipped by the near or
** far plane.
*/
static int pickhit (const lsys_vpick *p, const double proj[16], const double view[16], int w,
                    int h, const double right[3], double x, double y, double *d, double *z,
                    double *rpx) {
  double a[3], b[3], pa[3], pb[3], q[3], qr[3], pq[3], pr[3], dx, dy, len2, t;
  int i;
  for (i = 0; i < 3; i++) { a[i] = p->p0[i]; b[i] = p->p1[i]; }
  if (!lsys_render_project(proj, view, w, h, a, pa) ||
      !lsys_render_project(proj, view, w, h, b, pb))
    return 0;
  dx = pb[0] - pa[0];
  dy = pb[1] - pa[1];
  len2 = dx * dx + dy * dy;
  t = len2 > 0 ? ((x - pa[0]) * dx + (y - pa[1]) * dy) / len2 : 0;
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  *d = hypot(pa[0] + t * dx - x, pa[1] + t * dy - y);
  *z = pa[2] + t * (pb[2] - pa[2]);
  if (*z < 0 || *z > 1) return 0;          /* clipped by the near or far plane */
  *rpx = 0;
  if (p->radius > 0) {        /* the drawn width, projected where the click is nearest */
    for (i = 0; i < 3; i++) {
      q[i] = a[i] + t * (b[i] - a[i]);
      qr[i] = q[i] + p->radius * right[i];
    }
    if (lsys_render_project(proj, view, w, h, q, pq) &&
        lsys_render_project(proj, view, w, h, qr, pr))
      *rpx = hypot(pr[0] - pq[0], pr[1] - pq[1]);
  }
  return 1;
}

/* The best pick so far: a click inside the drawn width is a direct hit,
** the nearest to the eye winning; otherwise (thin lines, near misses) the
** nearest on screen. */
typedef struct pickbest {
  long k, plant;
  int direct;
  double d, z;
} pickbest;

static void tryhit (pickbest *b, const lsys_vpick *p, long k, long plant, const double proj[16],
                    const double view[16], int w, int h, const double right[3], double x,
                    double y, double tol) {
  double d, z, rpx;
  int direct;
  if (!pickhit(p, proj, view, w, h, right, x, y, &d, &z, &rpx)) return;
  if (d > (rpx > tol ? rpx : tol)) return;
  direct = rpx > 0 && d <= rpx;
  if (b->k < 0 || (direct && !b->direct) || (direct && b->direct && z < b->z) ||
      (!direct && !b->direct && (d < b->d || (d == b->d && z < b->z)))) {
    b->k = k;
    b->plant = plant;
    b->direct = direct;
    b->d = d;
    b->z = z;
  }
}

/* Pick p under the instance transform m: its ends moved, its width (in
** world units) scaled by the largest of m's scales. */
static void xpick (const lsys_vpick *p, const float m[16], lsys_vpick *q) {
  double a[3], b[3], s = 0;
  int i, j;
  lsys_xform(m, p->p0, a);
  lsys_xform(m, p->p1, b);
  for (i = 0; i < 3; i++) {
    q->p0[i] = (float)a[i];
    q->p1[i] = (float)b[i];
  }
  for (j = 0; j < 3; j++)
    s = fmax(s, sqrt((double)m[4 * j] * m[4 * j] + (double)m[4 * j + 1] * m[4 * j + 1] +
                     (double)m[4 * j + 2] * m[4 * j + 2]));
  q->radius = (float)(p->radius * s);
  q->module = p->module;
  q->kind = p->kind;
}

long lsys_viewcam_pick_find (const lsys_vframe *f, const double proj[16], const double view[16],
                             int w, int h, double x, double y, double tol, long *plant) {
  /* the camera's right axis, for the projected radius: row 0 of 'view' */
  double right[3] = {view[0], view[4], view[8]};
  const lsys_scene *s = &f->sc;
  pickbest b = {-1, -1, 0, 0, 0};
  size_t k, i;
  if (s->ninst == 0 || f->partpicks == NULL)
    for (k = 0; k < f->npicks; k++)
      tryhit(&b, &f->picks[k], (long)k, -1, proj, view, w, h, right, x, y, tol);
  else
    for (i = 0; i < s->ninst; i++) {
      size_t p = s->inst[i].part;
      if (p >= s->nparts) continue;
      for (k = f->partpicks[p]; k < f->partpicks[p + 1] && k < f->npicks; k++) {
        lsys_vpick q;
        xpick(&f->picks[k], s->inst[i].m, &q);
        tryhit(&b, &q, (long)k, (long)i, proj, view, w, h, right, x, y, tol);
      }
    }
  if (plant != NULL) *plant = b.plant;
  return b.k;
}

int lsys_viewcam_pick_event (const lsys_vframe *f, const double proj[16], const double view[16],
                             int w, int h, double x, double y, double tol, lsys_vevent *ev) {
  long plant, k = lsys_viewcam_pick_find(f, proj, view, w, h, x, y, tol, &plant);
  if (k < 0) return 0;
  ev->module = f->picks[k].module;
  ev->kind = f->picks[k].kind;
  ev->plant = plant + 1;
  return 1;
}
