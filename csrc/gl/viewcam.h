/*
** The viewer's camera and picking as plain arithmetic (docs/viewer.md): no
** window, no GL context, unit-tested on their own (tests/c/test_viewcam.c).
** The window (glfw_viewer.c) turns mouse drags and keys into these calls.
**
** viewcam.c also holds the camera of a view fitted to a scene and the
** projection of a point (lsys_render_camera, lsys_render_project: render.h),
** and the picking of viewer.h (lsys_viewcam_pick_find), which all need no GL.
*/
#ifndef LSYS_VIEWCAM_H
#define LSYS_VIEWCAM_H

#include "render.h"

/*
** An explicit camera: it looks along f with up u (orthonormal) at the
** target, from 'dist' away in perspective; a parallel projection shows
** 'halfh' world units above and below the target. A snapshot's view
** camera, fitted, becomes one (lsys_viewcam_fit); the mouse then moves it.
*/
typedef struct lsys_vcam {
  double target[3], f[3], u[3];
  double dist;                  /* perspective: eye = target - dist f */
  double halfh;                 /* parallel: half the image height */
  int valid;                    /* 0 until fitted */
} lsys_vcam;

/* Radians the camera turns per pixel dragged (lsys_viewcam_orbit). */
#define LSYS_VCAM_ORBIT 0.008

/*
** Sets 'c' from camera 'cam' (a view's) fitted to scene 's' (NULL: empty)
** in a w x h window (lsys_render_camera_scene, with a fitted rather than a
** kept parallel scale): as the view says, or with 'keep' (and a valid 'c')
** looking along c's direction and up at the fitted target. The target is
** the view's, else the centre of s's bounds. Returns LSYS_OK, or LSYS_EARG
** (and 'c' is left alone) when the view's camera is bad.
*/
int lsys_viewcam_fit (lsys_vcam *c, const lsys_scene *s, const lsys_camera *cam, int w, int h,
                      int keep);

/* Writes 'c' into the view camera 'cam' as an explicit eye, target and up
** (no twist; for a parallel projection, its scale with zoom 1). Leaves
** 'cam' alone when 'c' is not valid. */
void lsys_viewcam_apply (const lsys_vcam *c, lsys_camera *cam);

/* The matrices of lsys_render_camera_scene for camera 'cam' of 's' as 'c'
** moved it (lsys_viewcam_apply) in a w x h window; same returns. */
int lsys_viewcam_matrices (const lsys_vcam *c, const lsys_scene *s, const lsys_camera *cam,
                           int w, int h, double proj[16], double view[16]);

/*
** Turns the camera about its target for a drag of (dx, dy) window pixels,
** LSYS_VCAM_ORBIT radians a pixel: a turntable turn about 'up' (the arrival
** camera's up, so the horizon stays; it may be c->u), then a turn about the
** camera's right. Dragging right turns the scene to the right, i.e. the eye
** to the left; dragging down lifts the eye.
*/
void lsys_viewcam_orbit (lsys_vcam *c, const double up[3], double dx, double dy);

/* World units per window pixel at the target, for a window h pixels high
** and the projection, fov (default 30) and zoom of 'cam' (NULL: perspective,
** the defaults). */
double lsys_viewcam_pixelsize (const lsys_vcam *c, const lsys_camera *cam, int h);

/* Moves the target for a drag of (dx, dy) window pixels (y down) so that
** the scene at the target's depth follows the cursor ('cam', h: as for
** lsys_viewcam_pixelsize). */
void lsys_viewcam_pan (lsys_vcam *c, const lsys_camera *cam, int h, double dx, double dy);

/* Zooms by 'steps' scroll steps: distance and half height times 0.88^steps
** (a step in brings the eye 12% closer), neither below 1e-9. */
void lsys_viewcam_zoom (lsys_vcam *c, double steps);

/*
** The ray through the window point (x, y) (pixels, y down, as
** lsys_render_project gives them) of a camera proj/view in a w x h window:
** 'origin' on the near plane, 'dir' a unit vector away from the eye.
** Returns 1, or 0 when the matrices cannot be inverted.
*/
int lsys_viewcam_ray (const double proj[16], const double view[16], int w, int h, double x,
                      double y, double origin[3], double dir[3]);

#endif
