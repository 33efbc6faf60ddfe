/*
** Interpretation with a model: see interpret.h.
*/
#include "interpret.h"

/* The turtle's expansion callback: module i (parameters at 'poff') through
** the model's homomorphism. */
static int expand (void *ud, size_t i, size_t poff, lsys_lstring *out, lsys_error *e) {
  lsys_rules *m = (lsys_rules *)ud;
  int st = lsys_derive_homo_module(m, i, poff, out);
  if (st < 0) *e = m->err;
  return st;
}

/* The budget lives for the run only: when a rule function raises through
** the run (a longjmp in the bindings), the turtle and the unfinished scene
** that point to it are garbage. */
int lsys_interpret_run (lsys_rules *m, lsys_turtle *t, lsys_lstring *s, const lsys_alphabet *ab,
                        int homo) {
  lsys_meter meter;
  int st = homo ? lsys_derive_homo_begin(m, s) : 0;
  meter.limit = m->max_memory > 0 ? m->max_memory : lsys_common_memory_limit();
  meter.used = lsys_lstring_bytes(s);
  meter.hit = 0;
  meter.lock = NULL;
  t->meter = &meter;
  if (t->scene != NULL) t->scene->meter = t->scene->mesh.meter = &meter;
  if (st > 0) { t->expand = expand; t->expandud = m; st = LSYS_OK; }
  if (t->threads == 0) t->threads = m->threads > 0 ? m->threads : lsys_derive_default_threads();
  if (st == LSYS_OK) st = lsys_turtle_run(t, s, ab);
  else t->err = m->err;
  lsys_derive_homo_end(m);
  t->meter = NULL;
  if (t->scene != NULL) t->scene->meter = t->scene->mesh.meter = NULL;
  return st;
}
