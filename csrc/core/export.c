/*
** The writers' entry on a scene (export.h): the format from the file name,
** then the writer of that format with the scene's palette and textures, on
** the scene's mesh or on a copy with its lines as tubes (mesh_tube.c).
*/
#include <math.h>
#include <string.h>

#include "export.h"
#include "population.h"

#define ROW(id, name, ext, title, companion, textures, save, instanced) \
  {name, ext, title, companion, textures, save, instanced},
const lsys_format lsys_export_formats[LSYS_NFORMATS] = { LSYS_FORMATS(ROW) };
#undef ROW

int lsys_export_format (const char *path) {
  const char *ext = strrchr(path, '.');
  int k;
  if (ext == NULL) return -1;
  for (k = 0; k < LSYS_NFORMATS; k++)
    if (strcmp(ext + 1, lsys_export_formats[k].ext) == 0) return k;
  return -1;
}

double lsys_export_pixel (const lsys_mesh *m) {
  double lo[3], hi[3], ext = 0;
  int k;
  if (lsys_mesh_bounds(m, lo, hi))
    for (k = 0; k < 3; k++)
      if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
  return ext > 0 && isfinite(ext) ? ext / 720 : 1;
}

/* Fills o->sizes, when asked, with mesh 'm' and 'ninst' instances. */
static void sized (const lsys_export_opts *o, const lsys_mesh *m, size_t ninst) {
  if (o == NULL || o->sizes == NULL) return;
  o->sizes->nv = m->nv;
  o->sizes->nt = m->nt;
  o->sizes->nl = m->nl;
  o->sizes->ninst = ninst;
}

static int savemesh (const lsys_scene *s, const lsys_mesh *m, int format, const char *path,
                     const lsys_export_opts *o, lsys_error *e) {
  int st;
  if (format < 0 || format >= LSYS_NFORMATS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "unknown format of '%s'", path);
  st = lsys_export_formats[format].save(m, s->pal, s->npal, s->tex, s->ntex, path, e);
  if (st == LSYS_OK) sized(o, m, 0);
  return st;
}

/* The tube options of 'o' checked; LSYS_OK or LSYS_EARG naming 'path'. */
static int checktubes (const lsys_export_opts *o, const char *path, lsys_error *e) {
  if (o->sides < 3 || o->sides > 1024)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': tubes must have 3 to "
                         "1024 sides, got %d", path, o->sides);
  if (o->pixel != 0 && !(o->pixel > 0 && isfinite(o->pixel)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': the pixel size of tubes "
                         "must be a positive number", path);
  return LSYS_OK;
}

static int tubeserror (int st, const char *path, lsys_error *e) {
  if (st == LSYS_ELIMIT)
    return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': mesh too large with tubes "
                         "(more than 2^32 vertices)", path);
  return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': out of memory", path);
}

/* The default pixel size of a scene's tubes: lsys_export_pixel of what it
** draws. */
static double scenepixel (const lsys_scene *s) {
  double lo[3], hi[3], ext = 0;
  int k;
  if (s->ninst == 0) return lsys_export_pixel(&s->mesh);
  if (lsys_scene_bounds(s, lo, hi))
    for (k = 0; k < 3; k++)
      if (hi[k] - lo[k] > ext) ext = hi[k] - lo[k];
  return ext > 0 && isfinite(ext) ? ext / 720 : 1;
}

/* Population 's' with each prototype's lines made tubes into 'dst' (empty):
** part by part (a copy of it alone: 's' flattened through one identity
** instance), its tubes, appended as the same part; the instances borrowed. */
static int tubedparts (lsys_scene *dst, const lsys_scene *s, const lsys_export_opts *o,
                       double pixel) {
  static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  size_t p, k;
  int st = LSYS_OK;
  for (p = 0; p < s->nparts && st == LSYS_OK; p++) {
    lsys_scene one = *s, part, tubed;
    lsys_instance in;
    in.part = (uint32_t)p;
    memcpy(in.m, id, sizeof id);
    one.inst = &in;
    one.ninst = 1;
    lsys_scene_init(&part);
    lsys_scene_init(&tubed);
    st = lsys_population_flatten(&part, &one, NULL);
    if (st == LSYS_OK) st = lsys_mesh_tubes(&tubed.mesh, &part.mesh, o->sides, pixel);
    tubed.pal = s->pal;                        /* borrowed: population_add copies it */
    tubed.npal = s->npal;
    if (st == LSYS_OK) st = lsys_population_add(dst, &tubed, NULL, 0, &k);
    tubed.pal = NULL;
    lsys_scene_free(&tubed);
    lsys_scene_free(&part);
  }
  dst->tex = s->tex;
  dst->ntex = s->ntex;
  return st;
}

/* A population: with instancing (glb; its tubes per prototype) when the format
** has an instanced writer, or flattened. */
static int savepopulation (const lsys_scene *s, int format, const char *path,
                           const lsys_export_opts *o, lsys_error *e) {
  int (*instanced) (const lsys_scene *, const char *, lsys_error *) =
    lsys_export_formats[format].instanced;
  int tubes = o != NULL && o->tubes, st;
  lsys_meter mt = {0, 0, 0, NULL};
  lsys_scene f;
  if (tubes && (st = checktubes(o, path, e)) != LSYS_OK) return st;
  if (instanced != NULL && (o == NULL || !o->flatten)) {
    lsys_scene t;
    if (!tubes) {
      if ((st = instanced(s, path, e)) == LSYS_OK) sized(o, &s->mesh, s->ninst);
      return st;
    }
    lsys_scene_init(&t);
    st = tubedparts(&t, s, o, o->pixel > 0 ? o->pixel : scenepixel(s));
    t.inst = s->inst;                          /* borrowed for the call */
    t.ninst = s->ninst;
    if (st == LSYS_OK && (st = instanced(&t, path, e)) == LSYS_OK) sized(o, &t.mesh, t.ninst);
    else if (st != LSYS_OK) tubeserror(st, path, e);
    t.inst = NULL;
    t.ninst = 0;
    lsys_scene_free(&t);
    return st;
  }
  mt.limit = o != NULL && o->max_memory > 0 ? o->max_memory : lsys_common_memory_limit();
  lsys_scene_init(&f);
  st = lsys_population_flatten(&f, s, &mt);
  if (st == LSYS_EMEMORY) {
    char b1[32], b2[32];
    return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': the population written out "
                         "needs %s, more than max_memory (%s)", path,
                         lsys_common_fmtsize(b1, lsys_population_flatbytes(s)),
                         lsys_common_fmtsize(b2, mt.limit));
  }
  if (st == LSYS_ELIMIT)
    return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': the population written out "
                         "has more than 2^32 vertices", path);
  if (st != LSYS_OK) return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': out of memory",
                                          path);
  if (tubes && o->pixel == 0) {                /* the scale of the population as drawn */
    lsys_export_opts to = *o;
    to.pixel = scenepixel(s);
    st = lsys_export_scene(&f, format, path, &to, e);
  } else
    st = lsys_export_scene(&f, format, path, o, e);
  lsys_scene_free(&f);
  return st;
}

int lsys_export_scene (const lsys_scene *s, int format, const char *path,
                       const lsys_export_opts *o, lsys_error *e) {
  lsys_mesh tm;
  double pixel;
  int st;
  if (format < 0 || format >= LSYS_NFORMATS)
    return savemesh(s, &s->mesh, format, path, o, e);
  if (s->ninst > 0) return savepopulation(s, format, path, o, e);
  if (o == NULL || !o->tubes || s->mesh.nl == 0)
    return savemesh(s, &s->mesh, format, path, o, e);
  if ((st = checktubes(o, path, e)) != LSYS_OK) return st;
  pixel = o->pixel > 0 ? o->pixel : lsys_export_pixel(&s->mesh);
  st = lsys_mesh_tubes(&tm, &s->mesh, o->sides, pixel);
  if (st != LSYS_OK) return tubeserror(st, path, e);
  st = savemesh(s, &tm, format, path, o, e);
  lsys_mesh_free(&tm);
  return st;
}
