/*
** The writers' entry on a scene (export.h): the format from the file name,
** then the writer of that format with the scene's palette and textures, on
** the scene's mesh or on a copy with its lines as tubes (mesh_tube.c).
*/
#include <math.h>
#include <string.h>

#include "export.h"

int lsys_export_format (const char *path) {
  const char *ext = strrchr(path, '.');
  if (ext == NULL) return -1;
  if (strcmp(ext, ".obj") == 0) return LSYS_FORMAT_OBJ;
  if (strcmp(ext, ".ply") == 0) return LSYS_FORMAT_PLY;
  if (strcmp(ext, ".glb") == 0) return LSYS_FORMAT_GLB;
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

static int savemesh (const lsys_scene *s, const lsys_mesh *m, int format, const char *path,
                     lsys_error *e) {
  switch (format) {
    case LSYS_FORMAT_OBJ:
      return lsys_mesh_save_obj(m, s->pal, s->npal, s->tex, s->ntex, path, e);
    case LSYS_FORMAT_PLY:
      return lsys_mesh_save_ply(m, s->pal, s->npal, s->tex, s->ntex, path, e);
    case LSYS_FORMAT_GLB:
      return lsys_mesh_save_glb(m, s->pal, s->npal, s->tex, s->ntex, path, e);
    default:
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "unknown format of '%s'", path);
  }
}

int lsys_scene_save (const lsys_scene *s, int format, const char *path,
                     const lsys_export_opts *o, lsys_error *e) {
  lsys_mesh tm;
  double pixel;
  int st;
  if (o == NULL || !o->tubes || s->mesh.nl == 0 || format < 0 || format > LSYS_FORMAT_GLB)
    return savemesh(s, &s->mesh, format, path, e);
  if (o->sides < 3 || o->sides > 1024)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': tubes must have 3 to "
                         "1024 sides, got %d", path, o->sides);
  if (o->pixel != 0 && !(o->pixel > 0 && isfinite(o->pixel)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': the pixel size of tubes "
                         "must be a positive number", path);
  pixel = o->pixel > 0 ? o->pixel : lsys_export_pixel(&s->mesh);
  st = lsys_mesh_tubes(&tm, &s->mesh, o->sides, pixel);
  if (st == LSYS_ELIMIT)
    return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': mesh too large with tubes "
                         "(more than 2^32 vertices)", path);
  if (st != LSYS_OK)
    return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': out of memory", path);
  st = savemesh(s, &tm, format, path, e);
  lsys_mesh_free(&tm);
  return st;
}
