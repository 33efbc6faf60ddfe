/*
** Inverse kinematics of a branch path (Power et al. 1999, ilsa: §3.1 and
** the appendix): a chain of rigid segments joined by 3-joints, posed by
** minimising equation (1) over the joint angles with the conjugate-gradient
** minimiser of cg.h.
**
** Frames are 3 x 3 matrices, column-major, with the columns H, L, U (the
** turtle's heading, left and up in world coordinates), L = U x H so that
** (H, L, U) is right-handed. A 3-joint is three 1-joints (§3.1): right-handed
** rotations by alpha[0] about the local H, then alpha[1] about the (new)
** local U, then alpha[2] about the (new) local L -- the @J(h, u, l) module's
** order (turtle.c). Joint i sits at the start of segment i:
**
**   M_i = M_{i-1} . pre_i . Rh(a0) . Ru(a1) . Rl(a2)      (M_0 = base)
**   x_i = e_{i-1} + M_{i-1} . off_i                      (start of segment i)
**   e_i = x_i + len_i M_i H                              (its end; e_0 = root)
**
** pre_i is the fixed turn between the segments that the string has anyway
** (its + - & ^ / \ modules), off_i a move without drawing between them (f,
** usually zero). The end effector is p = e_n with the twist vectors
** s = M_n L and t = M_n U.
**
** Objective (1), with squared norms throughout (the printed equation mixes
** norms and squared norms; its gradient, eqs. 8-11, is the one of the
** squared form), per axis k of every joint, delta = alpha - rest:
**
**   f = wp |p - p^|^2 + wt (|s - s^|^2 + |t - t^|^2)
**     + we sum_i sum_k stiff_ik delta_ik^2
**     + ws sum_{i<n} sum_k (delta_{i+1,k} - delta_ik)^2
**
** and its gradient (eqs. 7-11): for a 1-joint with world axis w through
** the joint position x, dp/da = w x (p - x), ds/da = w x s, dt/da = w x t.
*/
#ifndef LSYS_IK_H
#define LSYS_IK_H

#include "cg.h"
#include "common.h"

typedef struct lsys_ikjoint {
  double pre[9];          /* fixed rotation before the joint (local to the previous frame) */
  double off[3];          /* start of the segment from the previous end, previous frame */
  double len;             /* length of the segment after the joint */
  double alpha[3];        /* joint angles in radians: about H, U, L */
  double rest[3];         /* rest angles (delta = alpha - rest) */
  double stiff[3];        /* stiffness s^h, s^u, s^l (§3.3) */
  unsigned free;          /* axes that may move: bit 0 H, bit 1 U, bit 2 L (7: all) */
} lsys_ikjoint;

typedef struct lsys_ikchain {
  int n;                  /* joints (and segments) */
  lsys_ikjoint *j;
  double base[9];         /* frame M_0 before joint 1 */
  double root[3];         /* e_0: where segment 1's offset starts */
} lsys_ikchain;

typedef struct lsys_ikgoal {
  double p[3], s[3], t[3];      /* targets p^, s^, t^ */
  double wp, wt, we, ws;        /* weights of the four terms */
} lsys_ikgoal;

/*
** Sets up joint i of 'c' from where the string currently draws it: 'prev'
** is the frame of the segment before (M_{i-1}, or the base for i = 0),
** 'prevend' its end point, 'frame' and 'start' the frame and start point of
** segment i, whose joint angles are already alpha[] (the @J module before
** it; zeros when none). Fills pre, off and len ('end' is the segment's end).
*/
void lsys_ik_setjoint (lsys_ikjoint *j, const double prev[9], const double prevend[3],
                       const double frame[9], const double start[3], const double end[3]);

/* A frame (columns H, L = U x H, U) from H and U (normalised; U made
** orthogonal to H). */
void lsys_ik_frame (double M[9], const double H[3], const double U[3]);

/*
** Forward kinematics with the angles 'a' (3 per joint; NULL: the joints'
** alpha): the end p and twist vectors s, t; optionally every frame
** (frames: 9 per joint) and every segment start and end (pts: 3 * (2n)).
*/
void lsys_ik_forward (const lsys_ikchain *c, const double *a, double p[3], double s[3],
                      double t[3], double *frames, double *pts);

/* Objective (1) at the angles 'a' (3n), and its gradient into 'g' (3n; NULL:
** none). Fixed axes (free bit clear) get a zero gradient. 'work' is scratch
** of lsys_ik_work_size(n) bytes, or NULL: then a gradient for more than 64
** joints allocates (and returns NaN when that fails). */
double lsys_ik_objective (const lsys_ikchain *c, const lsys_ikgoal *goal, const double *a,
                          double *g, void *work);

typedef struct lsys_ik_result {
  lsys_cg_result cg;
  double f0, f;           /* objective before and after */
  double dist;            /* |p - p^| after */
} lsys_ik_result;

/* Scratch memory for a chain of n joints (bytes), so that a solve allocates
** nothing; lsys_ik_solve accepts NULL and allocates itself. */
size_t lsys_ik_work_size (int n);

/*
** Minimises (1) from the joints' current angles and stores the result in
** their alpha, by conjugate gradients preconditioned with the diagonal of
** the Gauss-Newton Hessian of (1) (unless o->precond is set). 'o' NULL: the
** cg defaults, except that the solve stops once two iterations in a row
** gain less than 1e-6 of the starting objective (what dragging needs: the
** pose no longer changes visibly). Returns LSYS_OK (res->cg.status says
** why it stopped), LSYS_ENOMEM, or LSYS_EARG with e->msg set.
*/
int lsys_ik_solve (lsys_ikchain *c, const lsys_ikgoal *goal, const lsys_cg_opts *o,
                   void *work, lsys_ik_result *res, lsys_error *e);

#endif
