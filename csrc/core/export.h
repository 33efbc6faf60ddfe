/*
** Export writers (DESIGN.md §7): the scene geometry (mesh.h) as Wavefront
** OBJ with its MTL file (export_obj.c), binary little-endian PLY
** (export_ply.c) and glTF 2.0 binary (export_glb.c).
**
** Common conventions of the writers:
** - the material of a triangle is the colour index of its first vertex,
**   that of a segment its own colour index, both taken modulo the palette
**   size; only materials that something uses are written;
** - so is its texture (the texture index of its first vertex, when that
**   texture exists and was loaded from a file): OBJ and GLB write one
**   material per (colour, texture) pair, PLY ignores textures;
** - coordinates that are not finite are written as 0 (a JSON file cannot
**   hold NaN, and most OBJ readers choke on it);
** - outputs are atomic (outfile.h): a file is written under a temporary
**   name and renamed on success; a failure removes only the temporary file
**   (a device or a pipe is written in place and never removed).
*/
#ifndef LSYS_EXPORT_H
#define LSYS_EXPORT_H

#include "common.h"
#include "mesh.h"
#include "scene.h"
#include "texture.h"

enum { LSYS_FORMAT_OBJ = 0, LSYS_FORMAT_PLY = 1, LSYS_FORMAT_GLB = 2 };

/* The format a file name's extension names (.obj, .ply, .glb, lower case),
** or -1. */
int lsys_export_format (const char *path);

/* Writes a scene's mesh with its palette and textures in 'format'
** (LSYS_FORMAT_*): what the bindings and the program call. LSYS_OK or an
** error with e->msg naming the file. */
int lsys_scene_save (const lsys_scene *s, int format, const char *path, lsys_error *e);

/* The writers themselves, on a mesh with a palette and textures: */
/*
** 'pal' has 'npal' materials (npal may be 0: a grey default); 'tex' has
** 'ntex' textures (tex may be NULL and ntex 0), texture index k of the mesh
** being tex[k - 1]. Formats: Wavefront OBJ with a .mtl next to it (same
** base name), binary little-endian PLY with per-vertex normals and
** colours, glTF 2.0 binary (.glb) with one primitive per material and
** texture, lines as LINES primitives. A triangle is textured when its first
** vertex's texture exists and has a file ('path'): OBJ materials then name
** the file (map_Kd), GLB files embed it; PLY ignores textures. Return
** LSYS_OK or an error with e->msg naming the file.
*/
int lsys_mesh_save_obj (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e);
int lsys_mesh_save_ply (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e);
int lsys_mesh_save_glb (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e);

#endif
