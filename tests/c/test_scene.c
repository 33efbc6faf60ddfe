/*
** C unit tests for the core scene (scene.h): defaults, palette copies,
** records and stiffnesses within a memory budget, parts as ranges of the
** arrays, instances, and the dirty range.
*/
#undef NDEBUG
#include <assert.h>
#include <string.h>

#include "scene.h"

static void addvertices (lsys_scene *s, int n) {
  static const double p[3] = {0, 0, 0}, nr[3] = {0, 0, 1};
  int i;
  assert(lsys_mesh_reserve(&s->mesh, (size_t)n, 0) == LSYS_OK);
  for (i = 0; i < n; i++) lsys_mesh_vertex(&s->mesh, p, nr, 0, 0, 1, 0);
}

static void addrecords (lsys_scene *s, int n) {
  int i;
  for (i = 0; i < n; i++) {
    lsys_trec r;
    memset(&r, 0, sizeof r);
    r.module = (uint32_t)i;
    assert(lsys_scene_add_record(s, &r) == LSYS_OK);
  }
}

static void defaults (void) {
  lsys_scene s;
  lsys_scene_init(&s);
  assert(s.mesh.nv == 0 && s.nrec == 0 && s.npal == 0 && s.nparts == 0 && s.ninst == 0);
  /* the view schema's defaults (lua/lsys/view.lua) */
  assert(s.cam.projection == LSYS_PARALLEL && s.cam.fov == 30 && s.cam.zoom == 1);
  assert(s.cam.up[1] == 1 && s.cam.dir[2] == -1 && !s.cam.has_eye && s.cam.twist == 0);
  assert(s.light[0] == 0.4 && s.light[1] == 0.8 && s.light[2] == 0.6);
  assert(s.background[0] == 0.93f && s.background[1] == 0.96f && s.background[2] == 1.0f);
  lsys_scene_free(&s);
}

static void palette (void) {
  lsys_scene s;
  lsys_material m[2];
  lsys_scene_init(&s);
  lsys_mesh_material_color(&m[0], 1, 0, 0);
  lsys_mesh_material_color(&m[1], 0, 1, 0);
  assert(lsys_scene_set_palette(&s, m, 2) == LSYS_OK);
  m[0].diffuse[0] = 0.5f;                     /* the scene holds a copy */
  assert(s.npal == 2 && s.pal[0].diffuse[0] == 1.0f && s.pal[1].diffuse[1] == 1.0f);
  assert(lsys_scene_set_palette(&s, NULL, 0) == LSYS_OK && s.npal == 0 && s.pal == NULL);
  lsys_scene_free(&s);
}

static void records (void) {
  lsys_scene s;
  lsys_meter mt = { 10 * sizeof(lsys_rec), 0, 0, NULL };
  const double k[3] = {1, 2, 3};
  uint32_t i0, i1;
  lsys_scene_init(&s);
  addrecords(&s, 5);
  assert(s.nrec == 5 && s.rec[4].module == 4);
  assert(lsys_scene_add_stiffness(&s, k, &i0) == LSYS_OK && i0 == 0);
  assert(lsys_scene_add_stiffness(&s, k, &i1) == LSYS_OK && i1 == 1);
  assert(s.nstiff == 2 && s.stiff[3] == 1.0f && s.stiff[5] == 3.0f);
  lsys_scene_clear(&s);
  assert(s.nrec == 0 && s.nstiff == 0 && s.reccap >= 5);
  lsys_scene_free(&s);
  /* within a budget: 10 records fit, 11 do not */
  lsys_scene_init(&s);
  s.meter = &mt;
  assert(lsys_scene_reserve_records(&s, 10) == LSYS_OK);
  s.nrec = 10;
  assert(lsys_scene_reserve_records(&s, 1) == LSYS_EMEMORY);
  s.meter = NULL;
  lsys_scene_free(&s);
}

/* Records as the scene keeps them (scene.h): a shape shared, an end point
** read from a line until the records are detached from the lines, records
** appended to another scene with their places moved. */
static void packed (void) {
  lsys_scene s, d;
  lsys_trec r;
  lsys_rshape h;
  const double a[3] = {0, 0, 0}, b[3] = {1, 2, 3};
  memset(&h, 0, sizeof h);
  h.kind = LSYS_REC_SEGMENT; h.line = 1; h.len = 3.75f; h.H[1] = 1; h.U[2] = -1;
  h.w0 = 2; h.w1 = 1; h.color = 4; h.stiff = LSYS_NOREC; h.tri0 = 5;
  lsys_scene_init(&s);
  assert(lsys_mesh_line(&s.mesh, a, b, 2, 1, 4) == LSYS_OK);
  assert(lsys_mesh_line(&s.mesh, b, a, 2, 1, 4) == LSYS_OK);
  assert(lsys_scene_reserve_records(&s, 2) == LSYS_OK);
  assert(lsys_scene_reserve_shapes(&s, 1) == LSYS_OK);
  s.shape[s.nshape++] = h;
  s.rec[0].module = 3; s.rec[0].parent = LSYS_NOREC; s.rec[0].shape = 0; s.rec[0].at = 0;
  s.rec[1].module = 9; s.rec[1].parent = 0; s.rec[1].shape = 0; s.rec[1].at = 1;
  s.nrec = 2;
  lsys_scene_record(&s, 1, &r);
  assert(r.module == 9 && r.parent == 0 && r.kind == LSYS_REC_SEGMENT && r.color == 4);
  assert(r.p1[0] == 0 && r.p1[1] == 0 && r.p1[2] == 0 && r.len == 3.75f && r.H[1] == 1);
  assert(r.U[2] == -1 && r.w0 == 2 && r.w1 == 1 && r.tri0 == 5 && r.ntri == 0);
  lsys_scene_record(&s, 0, &r);
  assert(r.p1[0] == 1 && r.p1[1] == 2 && r.p1[2] == 3 && lsys_scene_reckind(&s, 0) == 1);
  /* appended: parents, lines and triangles moved */
  lsys_scene_init(&d);
  addrecords(&d, 1);
  assert(lsys_mesh_line(&d.mesh, b, b, 1, 1, 0) == LSYS_OK);
  assert(lsys_mesh_line(&d.mesh, a, b, 2, 1, 4) == LSYS_OK);
  assert(lsys_mesh_line(&d.mesh, b, a, 2, 1, 4) == LSYS_OK);
  assert(lsys_scene_append_records(&d, &s, 0, 10, 1) == LSYS_OK);
  assert(d.nrec == 3 && d.nshape == 2 && d.npt == 1);
  lsys_scene_record(&d, 2, &r);
  assert(r.module == 9 && r.parent == 1 && r.tri0 == 15 && r.p1[0] == 0);
  lsys_scene_record(&d, 1, &r);
  assert(r.parent == LSYS_NOREC && r.p1[2] == 3);
  /* detached: the lines may change, the records stay */
  assert(lsys_scene_detach_records(&s) == LSYS_OK);
  assert(s.npt == 2 && s.shape[0].line == 0);
  s.mesh.lpos[3] = 7;
  s.mesh.nl = 0;
  lsys_scene_record(&s, 0, &r);
  assert(r.p1[0] == 1 && r.p1[1] == 2 && r.p1[2] == 3 && r.len == 3.75f);
  /* a record whose shape is not there reads as zeros */
  s.rec[1].shape = 5;
  lsys_scene_record(&s, 1, &r);
  assert(r.kind == 0 && r.len == 0 && r.module == 9 && lsys_scene_reckind(&s, 1) == 0);
  lsys_scene_free(&s);
  lsys_scene_free(&d);
}

static void parts (void) {
  lsys_scene s;
  long a, b;
  float m[16] = {0};
  lsys_scene_init(&s);
  assert(lsys_scene_part_of_record(&s, 0) == -1);     /* no records */
  addrecords(&s, 2);
  assert(lsys_scene_part_of_record(&s, 1) == 0);      /* no parts: one part */
  a = lsys_scene_begin_part(&s);
  addvertices(&s, 4);
  addrecords(&s, 3);
  lsys_scene_end_part(&s, (size_t)a);
  b = lsys_scene_begin_part(&s);
  addvertices(&s, 2);
  addrecords(&s, 1);
  lsys_scene_end_part(&s, (size_t)b);
  assert(a == 0 && b == 1 && s.nparts == 2);
  assert(s.parts[0].v0 == 0 && s.parts[0].nv == 4 && s.parts[0].r0 == 2 && s.parts[0].nr == 3);
  assert(s.parts[1].v0 == 4 && s.parts[1].nv == 2 && s.parts[1].r0 == 5 && s.parts[1].nr == 1);
  assert(lsys_scene_part_of_record(&s, 1) == -1);     /* before the first part */
  assert(lsys_scene_part_of_record(&s, 2) == 0 && lsys_scene_part_of_record(&s, 4) == 0);
  assert(lsys_scene_part_of_record(&s, 5) == 1 && lsys_scene_part_of_record(&s, 6) == -1);
  m[0] = m[5] = m[10] = m[15] = 1; m[12] = 3;
  assert(lsys_scene_add_instance(&s, 1, m) == LSYS_OK);
  assert(lsys_scene_add_instance(&s, 2, m) == LSYS_EARG);
  assert(s.ninst == 1 && s.inst[0].part == 1 && s.inst[0].m[12] == 3);
  lsys_scene_free(&s);
}

static void dirty (void) {
  lsys_scene s;
  size_t v0, v1;
  lsys_scene_init(&s);
  assert(!lsys_scene_take_dirty(&s, &v0, &v1));
  lsys_scene_touch(&s, 10, 0);                         /* nothing */
  assert(!lsys_scene_take_dirty(&s, &v0, &v1));
  lsys_scene_touch(&s, 10, 5);
  lsys_scene_touch(&s, 3, 2);
  lsys_scene_touch(&s, 12, 10);
  assert(lsys_scene_take_dirty(&s, &v0, &v1) && v0 == 3 && v1 == 22);
  assert(!lsys_scene_take_dirty(&s, &v0, &v1));        /* taken: empty again */
  lsys_scene_touch(&s, 10, 5);
  lsys_scene_touch(&s, 30, 5);
  lsys_scene_touch(&s, 15, 2);                         /* touches [10, 15): one range */
  {
    size_t r[2 * LSYS_SCENE_NDIRTY];
    assert(lsys_scene_take_ranges(&s, r) == 2);
    assert(r[0] == 10 && r[1] == 17 && r[2] == 30 && r[3] == 35);
    assert(lsys_scene_take_ranges(&s, r) == 0);
  }
  lsys_scene_free(&s);
}

/* Random ranges against a bitmap: every vertex touched stays covered, the
** list stays sorted and apart, within its size, and exact while it fits. */
static void ranges (void) {
  enum { NV = 2000, MAX = 8 };
  static unsigned char bit[NV];
  size_t r[2 * (MAX + 1)], n = 0, k, v;
  unsigned x = 12345;
  int t;
  for (t = 0; t < 3000; t++) {
    size_t a, len;
    if (t % 100 == 0) { n = 0; memset(bit, 0, sizeof bit); }
    x = x * 1103515245u + 12345u; a = (x >> 8) % (NV - 50);
    x = x * 1103515245u + 12345u; len = (x >> 8) % 40;
    lsys_scene_ranges_add(r, &n, MAX, a, a + len);
    for (v = a; v < a + len; v++) bit[v] = 1;
    assert(n <= MAX);
    for (k = 0; k < n; k++) {
      assert(r[2 * k] < r[2 * k + 1]);
      if (k > 0) assert(r[2 * k] > r[2 * k - 1]);      /* apart: a gap between */
    }
    for (v = 0, k = 0; v < NV; v++) {
      int in;
      while (k < n && r[2 * k + 1] <= v) k++;
      in = k < n && r[2 * k] <= v;
      if (bit[v]) assert(in);
    }
  }
  n = 0;                                               /* MAX apart ranges: exact */
  for (k = 0; k < MAX; k++)
    lsys_scene_ranges_add(r, &n, MAX, 100 * (MAX - k), 100 * (MAX - k) + 10);
  assert(n == MAX && r[0] == 100 && r[1] == 110 && r[2 * MAX - 1] == 100 * MAX + 10);
  lsys_scene_ranges_add(r, &n, MAX, 5, 6);                   /* one more: the nearest two merge */
  assert(n == MAX && r[0] == 5 && r[1] == 6 && r[2] == 100 && r[3] == 210);
  lsys_scene_ranges_add(r, &n, MAX, 0, 10000);               /* covers all: one */
  assert(n == 1 && r[0] == 0 && r[1] == 10000);
}

int main (void) {
  defaults();
  palette();
  records();
  packed();
  parts();
  dirty();
  ranges();
  return 0;
}
