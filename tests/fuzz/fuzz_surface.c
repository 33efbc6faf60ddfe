/*
** libFuzzer target for the surface file reader (csrc/core/surface.c) and the
** tessellation of what it accepts. Crashes, leaks and sanitizer reports are
** failures; syntax errors are expected results. A parsed surface is meshed
** at 3 x 3 with per-patch and per-surface texture coordinates, and its first
** patches as @PD patches in the three bases: every position, normal and uv
** must be finite, normals of unit length, uv in [0,1], triangles within the
** vertices, and the counts (ns + 1)(nt + 1) and 2 ns nt per patch.
**
**   tools/fuzz.sh 600 surface      (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_surface
**   build-fuzz/fuzz_surface -max_total_time=300 -dict=tests/fuzz/surface.dict \
**                           tests/fuzz/corpus_surface
*/
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "surface.h"

static void check (const lsys_mesh *m, size_t v0, size_t t0, size_t nv, size_t nt) {
  size_t i;
  if (m->nv - v0 != nv || m->nt - t0 != nt) __builtin_trap();
  for (i = v0; i < m->nv; i++) {
    const float *p = m->pos + 3 * i, *n = m->nrm + 3 * i, *uv = m->uv + 2 * i;
    double l;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) __builtin_trap();
    if (!isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2])) __builtin_trap();
    l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    if (fabs(l - 1) > 1e-4) __builtin_trap();
    if (!(uv[0] >= 0 && uv[0] <= 1 && uv[1] >= 0 && uv[1] <= 1)) __builtin_trap();
    if (m->twosided[i] != 1 || m->col[i] != 5) __builtin_trap();
  }
  for (i = 3 * t0; i < 3 * m->nt; i++)
    if (m->tri[i] < v0 || m->tri[i] >= m->nv) __builtin_trap();
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  lsys_surface s;
  lsys_error e;
  if (lsys_surface_parse(&s, (const char *)data, size, "fuzz.s", &e) == LSYS_OK) {
    lsys_mesh m;
    lsys_place pl;
    double end[3];
    size_t i;
    int uvs, basis;
    if (s.npatch == 0 || s.npatch > LSYS_SURFACE_MAXPATCHES) __builtin_trap();
    if (!(s.size > 0) || fabs(sqrt(s.heading[0] * s.heading[0] + s.heading[1] * s.heading[1] +
                                   s.heading[2] * s.heading[2]) - 1) > 1e-12)
      __builtin_trap();
    for (i = 0; i < s.npatch; i++) {
      int d;
      for (d = 0; d < 8; d++) {
        int q = s.info[i].nb[d];
        if (q >= (int)s.npatch || q < -1) __builtin_trap();
        if (q >= 0 && strcmp(s.info[s.info[q].nb[7 - d]].name, s.info[i].name) != 0)
          __builtin_trap();
      }
    }
    memset(&pl, 0, sizeof pl);
    pl.origin[0] = 1; pl.origin[1] = 2; pl.origin[2] = 3;
    pl.H[1] = 1; pl.L[0] = -1; pl.U[2] = -1;
    pl.scale = 1.5;
    pl.color = 5;
    lsys_mesh_init(&m);
    for (uvs = 0; uvs < 2; uvs++) {
      size_t v0 = m.nv, t0 = m.nt;
      pl.uv_surface = uvs;
      if (lsys_surface_mesh(&m, &s, &pl, 3, 3) != LSYS_OK) __builtin_trap();
      check(&m, v0, t0, 16 * s.npatch, 18 * s.npatch);
    }
    for (i = 0; i < s.npatch && i < 4; i++)
      for (basis = 1; basis <= 3; basis++) {
        size_t v0 = m.nv, t0 = m.nt;
        pl.uv_surface = basis != 2;
        if (lsys_surface_patch_mesh(&m, basis, &s.patch[i], &pl, 3, 2) != LSYS_OK) __builtin_trap();
        check(&m, v0, t0, 12, 12);
      }
    lsys_surface_endpoint(&s, &pl, end);
    if (!isfinite(end[0]) || !isfinite(end[1]) || !isfinite(end[2])) __builtin_trap();
    lsys_mesh_free(&m);
  }
  else if (e.msg[0] == '\0' || strncmp(e.msg, "fuzz.s:", 7) != 0) {
    if (e.code != LSYS_ENOMEM) __builtin_trap();
  }
  lsys_surface_free(&s);
  return 0;
}
