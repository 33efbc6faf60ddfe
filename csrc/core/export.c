/*
** The writers' entry on a scene (export.h): the format from the file name,
** then the writer of that format with the scene's palette and textures.
*/
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

int lsys_scene_save (const lsys_scene *s, int format, const char *path, lsys_error *e) {
  switch (format) {
    case LSYS_FORMAT_OBJ:
      return lsys_mesh_save_obj(&s->mesh, s->pal, s->npal, s->tex, s->ntex, path, e);
    case LSYS_FORMAT_PLY:
      return lsys_mesh_save_ply(&s->mesh, s->pal, s->npal, s->tex, s->ntex, path, e);
    case LSYS_FORMAT_GLB:
      return lsys_mesh_save_glb(&s->mesh, s->pal, s->npal, s->tex, s->ntex, path, e);
    default:
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "unknown format of '%s'", path);
  }
}
