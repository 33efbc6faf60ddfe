/*
** Accessors of the geometry userdata (contours, textures, ...) for the
** other binding files. Only lua_*.c include this header.
*/
#ifndef LSYS_LUA_GEOM_H
#define LSYS_LUA_GEOM_H

#include "lua_lsys.h"
#include "contour.h"
#include "surface.h"
#include "texture.h"
#include "render.h"

/* lua_contour.c: the contour of the lsys.Contour at 'idx' (raises when it
** is not one). */
#define CONTOUR_T "lsys.Contour"
const lsys_contour *lsys_checkcontour (lua_State *L, int idx);

/* lua_surface.c: the surface of the lsys.Surface at 'idx' (raises when it
** is not one). */
#define SURFACE_T "lsys.Surface"
const lsys_surface *lsys_checksurface (lua_State *L, int idx);

/* lua_texture.c: the texture of the lsys.Texture at 'idx' (raises when it
** is not one). */
const lsys_texture *lsys_checktexture (lua_State *L, int idx);

/* lua_texture.c: the list opts.textures of the options table at 't' (0:
** none) as an array of *ntex textures, or NULL when absent or empty.
** Pushes one value that keeps the array alive (nil when NULL); raises,
** naming 'who', when the list holds anything but textures. */
const lsys_texture *const *lsys_opttextures (lua_State *L, int t, const char *who, int *ntex);

/* lua_render.c: fills 'o' from the lsys.render options table at 't' (0:
** none), checking every field (only when built with rendering). */
void lsys_readrenderopts (lua_State *L, int t, lsys_render_opts *o);

#endif
