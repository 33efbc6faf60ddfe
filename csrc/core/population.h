/*
** Populations (docs/population.md): many plants in one scene, the plants
** that are alike sharing their geometry. A population is an lsys_scene
** (scene.h) whose parts are its prototypes -- the mesh, records and
** stiffnesses of one plant each, in the plant's own coordinates -- and whose
** instances place them: instance k draws part inst[k].part under the
** transform inst[k].m. A field of 10,000 plants of 20 kinds holds the
** geometry of 20 plants and 10,000 transforms of 68 bytes.
**
** Instance transforms are M = T R S, as glTF composes a node's: a positive
** scale along the plant's own axes, then a rotation, then a translation.
** That is what EXT_mesh_gpu_instancing stores (lsys_population_trs), and
** what keeps normals right under any of them (a renderer transforms them
** by the inverse transpose, which for T R S is R S^-1).
*/
#ifndef LSYS_POPULATION_H
#define LSYS_POPULATION_H

#include "common.h"
#include "scene.h"

/*
** Appends scene 'src' (a plant, without instances) to 'dst' as a new part
** and sets *part to its index. Its colour indices are moved to a copy of its
** palette in dst's (c becomes off + c % npal, where dst's palette holds
** src's at 'off': the first place it is found, else appended), its texture
** indices k in 1 .. src->ntex become texmap[k] (NULL: unchanged; indices
** past src->ntex become 0, as they draw untextured), and its records (when
** 'records') keep their modules, with parents, stiffnesses and triangles
** moved to where they now are. dst's palette then has every entry the part
** needs; its textures are the caller's to set (tex, ntex).
** Returns LSYS_OK; LSYS_ELIMIT (more than UINT32_MAX vertices or segments,
** or 65,536 materials); LSYS_ENOMEM; LSYS_EMEMORY (dst's meter, attached to
** its mesh and records). On failure dst's geometry and parts are unchanged.
*/
int lsys_population_add (lsys_scene *dst, const lsys_scene *src, const uint16_t *texmap,
                         int records, size_t *part);

/*
** Makes room in 'dst' for 'n' instances in all, exactly (no doubling: a
** population knows its plants before it places them), within the meter 'mt'
** (NULL: none; 'mt->used' must count dst's arrays). Returns LSYS_OK;
** LSYS_EMEMORY (mt->hit set), LSYS_ENOMEM. dst is unchanged on failure.
*/
int lsys_population_reserve (lsys_scene *dst, size_t n, lsys_meter *mt);

/* The vertices, triangles and line segments scene 's' draws: its mesh's
** sizes without instances, else the sum over its instances of their parts'
** (a flattened copy's sizes). */
void lsys_population_size (const lsys_scene *s, size_t *nv, size_t *nt, size_t *nl);

/* The total area of the triangles scene 's' draws (under their instances'
** transforms when it has instances). */
double lsys_population_area (const lsys_scene *s);

/* The bytes of the mesh arrays of a flattened copy of 's' (as
** lsys_scene_bytes counts them, without records). */
size_t lsys_population_flatbytes (const lsys_scene *s);

/*
** Makes 'dst' (initialised, empty) a copy of 's' with every instance's
** geometry written out under its transform, in instance order: positions
** and line ends transformed, normals by the inverse transpose and
** normalised. No parts, instances or records. The palette is copied; the
** camera, light, background, textures (borrowed) and cull flag are s's.
** A scene without instances is copied as it is. The arrays are checked
** against the meter 'mt' (NULL: none) before anything is allocated.
** Returns LSYS_OK; LSYS_EMEMORY (the copy would not fit 'mt'); LSYS_ELIMIT
** (more than UINT32_MAX vertices); LSYS_ENOMEM. On failure dst is empty.
*/
int lsys_population_flatten (lsys_scene *dst, const lsys_scene *s, lsys_meter *mt);

/*
** Splits the affine transform 'm' into a translation t, a unit rotation
** quaternion q (x, y, z, w; w >= 0) and scales s along the rotated axes,
** m = T R S. Returns 1, or 0 when m is not of that form: not affine, a
** scale that is not positive and finite, or columns that are not
** orthogonal (a shear) within a relative 1e-4.
*/
int lsys_population_trs (const float m[16], float t[3], float q[4], float s[3]);

#endif
