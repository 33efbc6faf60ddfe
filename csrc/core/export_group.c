/*
** The export writers' validation of the mesh and grouping of its
** triangles and segments by material and texture (export_impl.h).
*/
#include <string.h>

#include "export_impl.h"

int lsys_export_checkmesh (const lsys_mesh *m, const char *path, lsys_error *e) {
  size_t t;
  if (m->nt > UINT32_MAX || m->nl > UINT32_MAX / 2 || m->nv > UINT32_MAX)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot write '%s': mesh too large", path);
  for (t = 0; t < 3 * m->nt; t++)
    if (m->tri[t] >= m->nv)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                           "cannot write '%s': triangle %zu refers to vertex %lu of %zu",
                           path, t / 3 + 1, (unsigned long)m->tri[t], m->nv);
  return LSYS_OK;
}

void lsys_export_freegroups (lsys_groups *g) {
  LSYS_FREE(g->tfirst); LSYS_FREE(g->lfirst);
  LSYS_FREE(g->tord); LSYS_FREE(g->lord); LSYS_FREE(g->runs);
}

/* The texture index of vertex a when its texture can be exported (it
** exists and has a file), else 0. */
static unsigned texof (const lsys_groups *g, const lsys_mesh *m, uint32_t a) {
  unsigned k = g->ntex ? m->tex[a] : 0;
  return k >= 1 && k <= g->ntex && g->tex[k - 1] != NULL && g->tex[k - 1]->path != NULL ? k : 0;
}

static int twosided (const lsys_mesh *m, const uint32_t *v) {
  return (m->twosided[v[0]] | m->twosided[v[1]] | m->twosided[v[2]]) != 0;
}

/* The triangles in 'order' by texture (a counting sort; 'tcount' has room
** for ntex + 2 counts). */
static void bytexture (const lsys_groups *g, const lsys_mesh *m, uint32_t *order,
                       size_t *tcount) {
  size_t k, t;
  memset(tcount, 0, (g->ntex + 2) * sizeof(size_t));
  for (t = 0; t < m->nt; t++) tcount[texof(g, m, m->tri[3 * t]) + 1]++;
  for (k = 0; k <= g->ntex; k++) tcount[k + 1] += tcount[k];
  for (t = 0; t < m->nt; t++) order[tcount[texof(g, m, m->tri[3 * t])]++] = (uint32_t)t;
}

/* tord and lord by material slot, and their offsets tfirst and lfirst (a
** counting sort, stable: the triangles keep the order of 'order', when
** given). */
static void bymaterial (lsys_groups *g, const lsys_mesh *m, const uint32_t *order) {
  size_t k, t, i, nmat = g->nmat;
  memset(g->tfirst, 0, (nmat + 1) * sizeof(size_t));
  memset(g->lfirst, 0, (nmat + 1) * sizeof(size_t));
  for (t = 0; t < m->nt; t++) g->tfirst[m->col[m->tri[3 * t]] % nmat + 1]++;
  for (t = 0; t < m->nl; t++) g->lfirst[m->lcol[t] % nmat + 1]++;
  for (k = 0; k < nmat; k++) {
    g->tfirst[k + 1] += g->tfirst[k];
    g->lfirst[k + 1] += g->lfirst[k];
  }
  /* fill, using tfirst[k] as the cursor of slot k, then shift back */
  for (i = 0; i < m->nt; i++) {
    t = order != NULL ? order[i] : i;
    g->tord[g->tfirst[m->col[m->tri[3 * t]] % nmat]++] = (uint32_t)t;
  }
  for (t = 0; t < m->nl; t++) g->lord[g->lfirst[m->lcol[t] % nmat]++] = (uint32_t)t;
  for (k = nmat; k > 0; k--) {
    g->tfirst[k] = g->tfirst[k - 1];
    g->lfirst[k] = g->lfirst[k - 1];
  }
  g->tfirst[0] = g->lfirst[0] = 0;
}

/* The runs of the sorted triangles: one per slot and texture. */
static int findruns (lsys_groups *g, const lsys_mesh *m) {
  size_t k, i;
  for (k = 0; k < g->nmat; k++)
    for (i = g->tfirst[k]; i < g->tfirst[k + 1];) {
      const uint32_t *v = m->tri + 3 * (size_t)g->tord[i];
      unsigned tx = texof(g, m, v[0]);
      lsys_run *r;
      if (g->nruns == g->runcap &&
          lsys_common_grow((void **)&g->runs, &g->runcap, g->nruns + 1, sizeof *g->runs) != LSYS_OK)
        return LSYS_ENOMEM;
      r = &g->runs[g->nruns++];
      r->first = i;
      r->slot = (uint32_t)k;
      r->tex = (uint16_t)tx;
      r->twosided = 0;
      for (; i < g->tfirst[k + 1]; i++) {
        v = m->tri + 3 * (size_t)g->tord[i];
        if (texof(g, m, v[0]) != tx) break;
        if (twosided(m, v)) r->twosided = 1;
      }
      r->end = i;
    }
  return LSYS_OK;
}

/* Colour indices are 16-bit, so more than 65536 slots are never needed:
** c % npal == c % 65536 == c when npal > 65536. Texture indices are
** 16-bit too. */
int lsys_export_groupmesh (lsys_groups *g, const lsys_mesh *m, size_t npal,
                           const lsys_texture *const *tex, int ntex, const char *path,
                           lsys_error *e) {
  size_t nmat = npal == 0 ? 1 : (npal < 65536 ? npal : 65536);
  uint32_t *order = NULL;      /* triangles by texture, when textured */
  size_t *tcount = NULL;
  *g = (lsys_groups){0};
  g->nmat = nmat;
  if (tex != NULL && ntex > 0 && m->tex != NULL && m->nt > 0) {
    g->tex = tex;
    g->ntex = ntex < 65535 ? (size_t)ntex : 65535;
  }
  g->tfirst = (size_t *)LSYS_MALLOC((nmat + 1) * sizeof(size_t));
  g->lfirst = (size_t *)LSYS_MALLOC((nmat + 1) * sizeof(size_t));
  g->tord = (uint32_t *)LSYS_MALLOC((m->nt ? m->nt : 1) * sizeof(uint32_t));
  g->lord = (uint32_t *)LSYS_MALLOC((m->nl ? m->nl : 1) * sizeof(uint32_t));
  if (g->ntex > 0) {
    order = (uint32_t *)LSYS_MALLOC(m->nt * sizeof(uint32_t));
    tcount = (size_t *)LSYS_MALLOC((g->ntex + 2) * sizeof(size_t));
  }
  if (!g->tfirst || !g->lfirst || !g->tord || !g->lord ||
      (g->ntex > 0 && (order == NULL || tcount == NULL))) {
    LSYS_FREE(order); LSYS_FREE(tcount);
    lsys_export_freegroups(g);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  }
  if (order != NULL) bytexture(g, m, order, tcount);   /* by texture first */
  LSYS_FREE(tcount);
  bymaterial(g, m, order);
  LSYS_FREE(order);
  if (findruns(g, m) != LSYS_OK) {
    lsys_export_freegroups(g);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  }
  return LSYS_OK;
}

/* The material used when the palette is empty. */
static const lsys_material defmaterial = {
  {0.24f, 0.24f, 0.24f, 1}, {0.8f, 0.8f, 0.8f, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}, 0
};

const lsys_material *lsys_export_slotmaterial (const lsys_material *pal, size_t npal, size_t k) {
  return npal == 0 ? &defmaterial : &pal[k];
}
