/*
** C unit tests of the viewer's camera without a window (viewcam.h): orbit,
** pan and zoom move the eye and the target where they should, fitting
** reproduces the view's camera, and a ray through a pixel goes where the
** projection put it. Positions and matrices are compared with tolerances.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mesh.h"
#include "vec3.h"

#ifndef LSYS_NO_RENDER
#include "viewcam.h"
#include "viewer.h"

#define W 200
#define H 200

static int near3 (const double a[3], double x, double y, double z, double tol) {
  return fabs(a[0] - x) <= tol && fabs(a[1] - y) <= tol && fabs(a[2] - z) <= tol;
}

/* The eye of a view matrix: -R^T t. */
static void eyeof (const double view[16], double eye[3]) {
  int i;
  for (i = 0; i < 3; i++)
    eye[i] = -(view[4 * i] * view[12] + view[4 * i + 1] * view[13] +
               view[4 * i + 2] * view[14]);
}

/* A camera at 'target' looking down -z, 'dist' away (eye at target + dist z). */
static lsys_vcam front (double x, double y, double z, double dist) {
  lsys_vcam c;
  memset(&c, 0, sizeof c);
  vset(c.target, x, y, z);
  vset(c.f, 0, 0, -1);
  vset(c.u, 0, 1, 0);
  c.dist = dist;
  c.halfh = 2;
  c.valid = 1;
  return c;
}

static void project (const double proj[16], const double view[16], const double p[3],
                     double out[3]) {
  assert(lsys_render_project(proj, view, W, H, p, out) == 1);
}

/* A vertical segment from the origin to (0, 2, 0): its middle is the target. */
static void stick (lsys_mesh *m) {
  double a[3] = {0, 0, 0}, b[3] = {0, 2, 0};
  lsys_mesh_init(m);
  assert(lsys_mesh_line(m, a, b, 1, 1, 0) == LSYS_OK);
}

static void test_orbit (void) {
  lsys_camera cam;
  lsys_vcam c = front(1, 2, 3, 10);
  double up[3] = {0, 1, 0}, proj[16], view[16], eye[3], out[3], r[3];
  lsys_scene_camera_defaults(&cam);
  cam.projection = LSYS_PERSPECTIVE;
  /* a drag of 90 degrees to the right: the eye goes round to the left (-x) */
  lsys_viewcam_orbit(&c, up, (PI / 2) / LSYS_VCAM_ORBIT, 0);
  assert(near3(c.f, 1, 0, 0, 1e-12) && near3(c.u, 0, 1, 0, 1e-12));
  assert(near3(c.target, 1, 2, 3, 0) && c.dist == 10);
  assert(lsys_viewcam_matrices(&c, NULL, &cam, W, H, proj, view) == LSYS_OK);
  eyeof(view, eye);
  assert(near3(eye, -9, 2, 3, 1e-9));
  project(proj, view, c.target, out);              /* the target stays in the middle */
  assert(fabs(out[0] - W / 2) < 1e-9 && fabs(out[1] - H / 2) < 1e-9);
  /* back, then a drag down by 45 degrees lifts the eye */
  lsys_viewcam_orbit(&c, up, -(PI / 2) / LSYS_VCAM_ORBIT, 0);
  assert(near3(c.f, 0, 0, -1, 1e-12));
  lsys_viewcam_orbit(&c, up, 0, (PI / 4) / LSYS_VCAM_ORBIT);
  assert(near3(c.f, 0, -sqrt(0.5), -sqrt(0.5), 1e-12));
  assert(near3(c.u, 0, sqrt(0.5), -sqrt(0.5), 1e-12));
  assert(lsys_viewcam_matrices(&c, NULL, &cam, W, H, proj, view) == LSYS_OK);
  eyeof(view, eye);
  assert(near3(eye, 1, 2 + 10 * sqrt(0.5), 3 + 10 * sqrt(0.5), 1e-9));
  /* a turntable turn after that keeps the horizon: right stays horizontal,
  ** the frame orthonormal */
  lsys_viewcam_orbit(&c, up, 37, 0);
  vcross(r, c.f, c.u);
  assert(fabs(r[1]) < 1e-12);
  assert(fabs(vdot(c.f, c.u)) < 1e-12 && fabs(vlen(c.f) - 1) < 1e-12 &&
         fabs(vlen(c.u) - 1) < 1e-12);
  assert(fabs(c.f[1] + sqrt(0.5)) < 1e-12);        /* still looking down by 45 degrees */
  printf("orbit: ok\n");
}

static void test_zoom (void) {
  lsys_camera cam;
  lsys_vcam c = front(0, 0, 0, 10);
  double proj[16], view[16], eye[3];
  lsys_scene_camera_defaults(&cam);
  cam.projection = LSYS_PERSPECTIVE;
  lsys_viewcam_zoom(&c, 1);                           /* one step in: 12% closer */
  assert(fabs(c.dist - 8.8) < 1e-12 && fabs(c.halfh - 1.76) < 1e-12);
  assert(lsys_viewcam_matrices(&c, NULL, &cam, W, H, proj, view) == LSYS_OK);
  eyeof(view, eye);
  assert(near3(eye, 0, 0, 8.8, 1e-9));
  lsys_viewcam_zoom(&c, -2);                          /* two steps out */
  assert(fabs(c.dist - 10 / 0.88) < 1e-9 && fabs(c.halfh - 2 / 0.88) < 1e-9);
  lsys_viewcam_zoom(&c, 1e4);                         /* never down to nothing */
  assert(c.dist == 1e-9 && c.halfh == 1e-9);
  /* parallel: the half height is the scale; the picture shows 2 halfh */
  c = front(0, 0, 0, 10);
  cam.projection = LSYS_PARALLEL;
  lsys_viewcam_zoom(&c, 1);
  assert(lsys_viewcam_matrices(&c, NULL, &cam, W, H, proj, view) == LSYS_OK);
  assert(fabs(proj[5] - 1 / 1.76) < 1e-12 && fabs(proj[0] - 1 / 1.76) < 1e-12);
  printf("zoom: ok\n");
}

/* After a pan by (dx, dy) pixels, the old target is seen (dx, dy) away
** from the middle: the scene follows the cursor. */
static void checkpan (lsys_camera *cam, double dx, double dy) {
  lsys_vcam c = front(1, 1, 1, 10);
  double proj[16], view[16], old[3] = {1, 1, 1}, out[3];
  lsys_viewcam_pan(&c, cam, H, dx, dy);
  assert(lsys_viewcam_matrices(&c, NULL, cam, W, H, proj, view) == LSYS_OK);
  project(proj, view, old, out);
  assert(fabs(out[0] - (W / 2 + dx)) < 1e-9 && fabs(out[1] - (H / 2 + dy)) < 1e-9);
}

static void test_pan (void) {
  lsys_camera cam;
  lsys_vcam c = front(0, 0, 0, 10);
  lsys_scene_camera_defaults(&cam);
  cam.projection = LSYS_PERSPECTIVE;
  /* perspective, 30 degrees: 2 dist tan(15 degrees) / h world units a pixel */
  assert(fabs(lsys_viewcam_pixelsize(&c, &cam, H) - 20 * tan(PI / 12) / H) < 1e-15);
  assert(lsys_viewcam_pixelsize(&c, NULL, H) == lsys_viewcam_pixelsize(&c, &cam, H));
  checkpan(&cam, 20, -10);
  cam.fov = 60;
  checkpan(&cam, -35, 5);
  cam.projection = LSYS_PARALLEL;                /* 2 halfh / h */
  assert(fabs(lsys_viewcam_pixelsize(&c, &cam, H) - 4.0 / H) < 1e-15);
  checkpan(&cam, 20, -10);
  printf("pan: ok\n");
}

/* Fitting takes the view's camera over: seen through the result, the
** scene is where the view put it. */
/* A scene that draws mesh m (its arrays borrowed), for the camera functions. */
static const lsys_scene *sceneof (const lsys_mesh *m) {
  static lsys_scene s;
  memset(&s, 0, sizeof s);
  s.mesh = *m;
  return &s;
}

static void test_fit (void) {
  lsys_camera cam;
  lsys_mesh m;
  lsys_vcam c;
  double proj[16], view[16], p2[16], v2[16], eye[3], d[3];
  int i, parallel;
  stick(&m);
  for (parallel = 0; parallel < 2; parallel++) {
    lsys_scene_camera_defaults(&cam);
    cam.projection = LSYS_PERSPECTIVE;
    cam.projection = parallel ? LSYS_PARALLEL : LSYS_PERSPECTIVE;
    memset(&c, 0, sizeof c);
    assert(lsys_viewcam_fit(&c, sceneof(&m), &cam, W, H, 0) == LSYS_OK && c.valid);
    assert(near3(c.target, 0, 1, 0, 1e-12));       /* the middle of the bounds */
    assert(near3(c.f, 0, 0, -1, 1e-12) && near3(c.u, 0, 1, 0, 1e-12));
    assert(lsys_render_camera(&m, &cam, W, H, proj, view) == LSYS_OK);
    eyeof(view, eye);
    vlin(d, eye, 1, c.target, -1);
    if (!parallel) assert(fabs(c.dist - vlen(d)) < 1e-12);
    else assert(fabs(c.halfh - 1 / proj[5]) < 1e-12);
    /* the same picture (near and far planes, and a parallel eye, may differ) */
    assert(lsys_viewcam_matrices(&c, sceneof(&m), &cam, W, H, p2, v2) == LSYS_OK);
    for (i = 0; i < 12; i++) assert(fabs(v2[i] - view[i]) < 1e-12);
    for (i = 0; i < 3; i++) {
      double p[3] = {0.3 * i, 2.0 - i, 0.5 * i - 0.5}, a[3], b[3];
      project(proj, view, p, a);
      project(p2, v2, p, b);
      assert(fabs(a[0] - b[0]) < 1e-9 && fabs(a[1] - b[1]) < 1e-9);
    }
  }
  /* keeping the direction: after an orbit, F fits again looking the same way */
  {
    double up[3] = {0, 1, 0}, f[3];
    lsys_scene_camera_defaults(&cam);
    cam.projection = LSYS_PERSPECTIVE;
    assert(lsys_viewcam_fit(&c, sceneof(&m), &cam, W, H, 0) == LSYS_OK);
    lsys_viewcam_orbit(&c, up, 100, 40);
    lsys_viewcam_zoom(&c, 5);
    vcopy(f, c.f);
    assert(lsys_viewcam_fit(&c, sceneof(&m), &cam, W, H, 1) == LSYS_OK);
    assert(near3(c.f, f[0], f[1], f[2], 1e-12) && near3(c.target, 0, 1, 0, 1e-12));
  }
  /* a bad view camera leaves 'c' alone */
  cam.dir[0] = cam.dir[1] = cam.dir[2] = 0;
  cam.has_eye = 0;
  memset(&c, 0, sizeof c);
  assert(lsys_viewcam_fit(&c, sceneof(&m), &cam, W, H, 0) == LSYS_EARG && !c.valid);
  lsys_mesh_free(&m);
  printf("fit: ok\n");
}

static void test_ray (void) {
  lsys_camera cam;
  lsys_mesh m;
  lsys_vcam c;
  lsys_vframe f;
  lsys_vpick pick;
  double proj[16], view[16], org[3], dir[3], q[3], p[3], out[3], t;
  int parallel;
  stick(&m);
  memset(&f, 0, sizeof f);
  memset(&pick, 0, sizeof pick);
  pick.p1[1] = 2;                                  /* the stick, as a pick */
  pick.module = 7;
  f.picks = &pick;
  f.npicks = 1;
  for (parallel = 0; parallel < 2; parallel++) {
    lsys_scene_camera_defaults(&cam);
    cam.projection = LSYS_PERSPECTIVE;
    cam.projection = parallel ? LSYS_PARALLEL : LSYS_PERSPECTIVE;
    assert(lsys_viewcam_fit(&c, sceneof(&m), &cam, W, H, 0) == LSYS_OK);
    lsys_viewcam_orbit(&c, c.u, 30, -20);             /* not along an axis */
    assert(lsys_viewcam_matrices(&c, sceneof(&m), &cam, W, H, proj, view) == LSYS_OK);
    /* through the middle of the image: along the view, through the target,
    ** which is on the stick; a click there picks it */
    assert(lsys_viewcam_ray(proj, view, W, H, W / 2, H / 2, org, dir) == 1);
    assert(near3(dir, c.f[0], c.f[1], c.f[2], 1e-9));
    vlin(q, c.target, 1, org, -1);
    t = vdot(q, dir);
    assert(t > 0);
    vlin(p, org, 1, dir, t);
    assert(near3(p, 0, 1, 0, 1e-9));
    assert(lsys_viewcam_pick_find(&f, proj, view, W, H, W / 2, H / 2, 6, NULL) == 0);
    assert(lsys_viewcam_pick_find(&f, proj, view, W, H, 5, 5, 6, NULL) == -1);
    /* elsewhere: every point of the ray projects back to the pixel */
    assert(lsys_viewcam_ray(proj, view, W, H, 30, 170, org, dir) == 1);
    assert(fabs(vlen(dir) - 1) < 1e-12);
    for (t = 0; t < 3; t += 1) {
      vlin(p, org, 1, dir, t);
      project(proj, view, p, out);
      assert(fabs(out[0] - 30) < 1e-6 && fabs(out[1] - 170) < 1e-6);
    }
    project(proj, view, org, out);
    assert(fabs(out[2]) < 1e-9);                   /* it starts on the near plane */
    if (parallel) assert(near3(dir, c.f[0], c.f[1], c.f[2], 1e-9));
  }
  memset(proj, 0, sizeof proj);                    /* nothing to invert */
  assert(lsys_viewcam_ray(proj, view, W, H, 1, 1, org, dir) == 0);
  lsys_mesh_free(&m);
  printf("ray: ok\n");
}
#endif

int main (void) {
#ifdef LSYS_NO_RENDER
  printf("built without rendering: nothing to test\n");
#else
  test_orbit();
  test_zoom();
  test_pan();
  test_fit();
  test_ray();
#endif
  return 0;
}
