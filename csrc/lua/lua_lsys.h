/*
** The registration functions of the binding files, for the entry point
** (lua_lsys.c). Each registers its metatables and adds its functions to the
** table on top of the stack. Nothing else of a binding file is visible to
** another: what they share is in lua_aux.h.
*/
#ifndef LSYS_LUA_LSYS_H
#define LSYS_LUA_LSYS_H

#include <lua.h>

void lsysL_open_rules (lua_State *L);    /* lua_rules.c: Rules, Template, rules, produce, ran */
void lsysL_open_lstring (lua_State *L);  /* lua_lstring.c: Lstring, lstring */
void lsysL_open_scene (lua_State *L);    /* lua_scene.c: Scene, interpret, query */
void lsysL_open_export (lua_State *L);   /* lua_export.c: scene:save, formats */
void lsysL_open_render (lua_State *L);   /* lua_render.c: render, png, files */
void lsysL_open_contour (lua_State *L);  /* lua_contour.c: Contour */
void lsysL_open_surface (lua_State *L);  /* lua_surface.c: Surface, patches */
void lsysL_open_texture (lua_State *L);  /* lua_texture.c: Texture */
void lsysL_open_viewer (lua_State *L);   /* lua_viewer.c: Viewer, filestamp */
void lsysL_open_ik (lua_State *L);       /* lua_ik.c: IK chains (lsys.arrange) */
void lsysL_open_bspline (lua_State *L); /* lua_bspline.c: BSpline, chaikin, stroke_curve */
void lsysL_open_func (lua_State *L);     /* lua_func.c: Func, func, func_parse */
void lsysL_open_canvas (lua_State *L);   /* lua_canvas.c: Canvas, canvas */
void lsysL_open_ffd (lua_State *L);      /* lua_ffd.c: Hyperpatch, hyperpatch; scene:deform, ... */
void lsysL_open_compgeo (lua_State *L); /* lua_compgeo.c: Frames, Cwriter (lsys.components) */
void lsysL_open_grow (lua_State *L);     /* lua_grow.c: Limbs, limbs (lsys.grow) */
void lsysL_open_population (lua_State *L); /* lua_population.c: population; scene:instance */
void lsysL_open_sandbox (lua_State *L);  /* lua_sandbox.c: sandbox_strings; rules:sandboxed */
void lsysL_open_outfile (lua_State *L);  /* lua_outfile.c: Outfile, Tempdir (atomic writers) */
void lsysL_open_envproc (lua_State *L);  /* lua_envproc.c: EnvProcess, envproc */
void lsysL_open_light (lua_State *L);    /* lua_light.c: Light, light */
void lsysL_open_shadow (lua_State *L);   /* lua_shadow.c: Shadow, shadow */
void lsysL_open_space (lua_State *L);    /* lua_space.c: Space, Markers, Field */

/* require "lsys.core" */
int luaopen_lsys_core (lua_State *L);

#endif
