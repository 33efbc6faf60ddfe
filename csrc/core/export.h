/*
** Export writers (docs/drawing.md §5): the scene geometry (mesh.h) as Wavefront
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
** - colours: the palette holds display (sRGB) values, as the renderer
**   shows them. glTF's colour factors are linear (glTF 2.0, 3.9.2), so GLB
**   converts them with the sRGB transfer function (export_impl.h); so
**   does MTL, for Blender's importer reads Kd as linear (export_obj.c);
**   PLY vertex colours stay 8-bit sRGB, as PLY readers take them; textures
**   are embedded or named as they are (glTF reads base colour images as
**   sRGB);
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

/*
** The export formats, in one table: X(id, name, ext, title, companion, textures, save,
** instanced), one row per format, in the order they are listed (messages, help,
** core.formats()). A new format is a row here and its writer.
**   id          LSYS_FORMAT_<id>, the row's index
**   name        its name (lsys.batch's output field, core.formats())
**   ext         its file name's extension, lower case, without the dot
**   title       what it is, in words
**   companion   the extension of a file written beside it (OBJ's material file), or NULL
**   textures    1: a textured triangle names or embeds its image
**   save        the writer, on a mesh with a palette and textures (below)
**   instanced   the writer of a population with instancing (unless it is flattened), or
**               NULL: a population is always written flattened
*/
#define LSYS_FORMATS(X) \
  X(OBJ, "obj", "obj", "Wavefront OBJ", "mtl", 1, lsys_export_obj, NULL) \
  X(PLY, "ply", "ply", "binary PLY", NULL, 0, lsys_export_ply, NULL) \
  X(GLB, "glb", "glb", "glTF 2.0 binary", NULL, 1, lsys_export_glb, \
    lsys_export_glb_instanced)

#define LSYS_FORMAT_ENUM(id, name, ext, title, companion, textures, save, instanced) \
  LSYS_FORMAT_##id,
enum { LSYS_FORMATS(LSYS_FORMAT_ENUM) LSYS_NFORMATS };
#undef LSYS_FORMAT_ENUM

/* One row of the table. */
typedef struct lsys_format {
  const char *name, *ext, *title;
  const char *companion;      /* NULL: none */
  int textures;
  int (*save) (const lsys_mesh *m, const lsys_material *pal, size_t npal,
               const lsys_texture *const *tex, int ntex, const char *path, lsys_error *e);
  int (*instanced) (const lsys_scene *s, const char *path, lsys_error *e);   /* or NULL */
} lsys_format;

/* The rows, lsys_export_formats[LSYS_FORMAT_<id>] (export.c). */
extern const lsys_format lsys_export_formats[LSYS_NFORMATS];

/* The format a file name's extension names (one of the table's, lower case),
** or -1. */
int lsys_export_format (const char *path);

/*
** How a scene is written. Line segments (line style) are GL lines by
** default: glTF LINES primitives, OBJ 'l' elements, a PLY 'edge' element,
** none of which keeps a width, so most viewers draw them one pixel wide.
** With 'tubes' they become closed tubes of 'sides' sides instead
** (lsys_mesh_tubes), whose diameter is the line width (in line style,
** pixels of the rendered picture) times 'pixel' scene units; 'pixel' 0
** means lsys_export_pixel's. The triangles of a scene are written as they
** are either way.
*/
/* What a file lsys_export_scene wrote holds: the vertices, triangles and line
** segments of the mesh written (with tubes, the copy with them; a population
** flattened, its copy; with instancing, its prototypes once each, and 'ninst'
** instances of them; 0 otherwise). */
typedef struct lsys_export_sizes {
  size_t nv, nt, nl, ninst;
} lsys_export_sizes;

typedef struct lsys_export_opts {
  int tubes;               /* 1: line segments as tubes; 0: as lines */
  int sides;               /* sides of a tube, 3 .. 1024 */
  double pixel;            /* scene units per unit of line width; 0: the default */
  int flatten;             /* a population: 1 writes every instance out in every format;
                              0 keeps glb's instancing (OBJ and PLY are always flattened) */
  size_t max_memory;       /* the bytes a flattened copy may take; 0: lsys_common_memory_limit() */
  lsys_export_sizes *sizes; /* when not NULL, filled with what the file holds */
} lsys_export_opts;

/* The default size of a pixel of line width, in scene units: the largest
** side of the mesh's bounds over 720, so that a tube is as thick, next to
** the plant, as the line in an 800 x 800 picture of `lsys render`, which
** fits the plant into 90% of the picture (a flat plant seen face on: the
** view's default). 1 for a mesh without extent. */
double lsys_export_pixel (const lsys_mesh *m);

/* Writes a scene's mesh with its palette and textures in 'format'
** (LSYS_FORMAT_*), as 'o' says (NULL: lines as lines): what the bindings
** call. LSYS_OK or an error with e->msg naming the file (LSYS_EARG for bad
** options). With tubes, the mesh is copied once with its tubes added.
** A population (a scene with instances, population.h) is written as GLB
** with instancing (lsys_export_glb_instanced; with tubes, each
** prototype gets its own) unless o->flatten; otherwise, and always as OBJ
** or PLY, a flattened copy (lsys_population_flatten) is made first,
** LSYS_EMEMORY when it would take more than o->max_memory. */
int lsys_export_scene (const lsys_scene *s, int format, const char *path,
                       const lsys_export_opts *o, lsys_error *e);

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
int lsys_export_obj (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e);
int lsys_export_ply (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e);
int lsys_export_glb (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e);

/*
** A population (a scene with parts and instances: population.h) as glTF
** binary with EXT_mesh_gpu_instancing: one mesh per part that has
** instances and draws something, one node per such mesh whose extension
** gives its instances' translations, rotations and scales (the extension
** is listed in extensionsUsed and extensionsRequired). Materials and
** textures as lsys_export_glb. LSYS_EARG (naming the instance) when an
** instance is not a translation, rotation and positive scale
** (lsys_population_trs): such a population must be flattened.
*/
int lsys_export_glb_instanced (const lsys_scene *s, const char *path, lsys_error *e);

#endif
