/*
** Rendering and PNG functions of lsys.core: render, project (the renderer's
** camera applied to a scene, for vector pictures), png_read, png_write, has_render.
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "outfile.h"
#include "path.h"
#include "pngio.h"
#include "population.h"
#include "shade.h"
#include "vec3.h"

#ifndef LSYS_NO_RENDER
#define SHADEPREP_T "lsys.ShadePrep"
#define GROUND_FADE 32          /* colours of the ground, from its own to what is behind */

/* What a picture with shadows, a ground or a sky holds while it is drawn: a
** population's flattened copy (its instances written out, so that each plant
** shadows the others and its own vertices), the scene's mesh with the ground
** appended, the palette with its colour, the vertices' shading factors. A
** userdata, so that an error frees them. */
typedef struct shadeprep {
  lsys_scene flat;
  lsys_mesh mesh;
  lsys_material *pal;
  uint8_t *f;
  int flattened, ground;
} shadeprep;

static int shadeprep_gc (lua_State *L) {
  shadeprep *p = (shadeprep *)luaL_checkudata(L, 1, SHADEPREP_T);
  if (p->flattened) lsys_scene_free(&p->flat);
  if (p->ground) lsys_mesh_free(&p->mesh);
  LSYS_FREE(p->pal);
  LSYS_FREE(p->f);
  memset(p, 0, sizeof *p);
  return 0;
}

static double numfield (lua_State *L, int t, const char *k, double def) {
  double x;
  lua_getfield(L, t, k);
  x = lua_isnumber(L, -1) ? lua_tonumber(L, -1) : def;
  lua_pop(L, 1);
  return x;
}

static void rgbfield (lua_State *L, int t, const char *k, float rgb[3], const float *def) {
  int c;
  lua_getfield(L, t, k);
  for (c = 0; c < 3; c++) {
    if (lua_istable(L, -1)) {
      lua_rawgeti(L, -1, c + 1);
      rgb[c] = lua_isnumber(L, -1) ? (float)lua_tonumber(L, -1) : def[c];
      lua_pop(L, 1);
    } else rgb[c] = def[c];
  }
  lua_pop(L, 1);
}

/* What opts.shade asks (lsys.render checked it): into so, g, o; the ground's
** colour into gcol. Returns 1 when a ground is asked. */
static int readshade (lua_State *L, int t, lsys_shade_opts *so, lsys_shade_ground *g,
                      float gcol[3], lsys_render_opts *o) {
  int ground, s;
  lsys_shade_defaults(so);
  memset(g, 0, sizeof *g);
  g->size = 1.6;
  g->cells = 160;
  if (t == 0 || lua_getfield(L, t, "shade") != LUA_TTABLE) {
    if (t != 0) lua_pop(L, 1);
    return 0;
  }
  s = lua_gettop(L);
  so->shadows = lua_getfield(L, s, "shadows"), lua_toboolean(L, -1);
  lua_pop(L, 1);
  so->ao = lua_getfield(L, s, "ao"), lua_toboolean(L, -1);
  lua_pop(L, 1);
  ground = lua_getfield(L, s, "ground"), lua_toboolean(L, -1);
  lua_pop(L, 1);
  o->sky = lua_getfield(L, s, "sky"), lua_toboolean(L, -1);
  lua_pop(L, 1);
  so->softness = numfield(L, s, "softness", so->softness);
  so->shadow_strength = numfield(L, s, "shadow_strength", so->shadow_strength);
  so->ao_samples = (int)numfield(L, s, "ao_samples", so->ao_samples);
  so->ao_distance = numfield(L, s, "ao_distance", so->ao_distance);
  so->ao_strength = numfield(L, s, "ao_strength", so->ao_strength);
  so->threads = (int)numfield(L, s, "threads", 2);
  g->size = numfield(L, s, "ground_size", g->size);
  g->cells = (int)numfield(L, s, "ground_cells", g->cells);
  rgbfield(L, s, "ground_color", gcol, lsys_render_ground);
  rgbfield(L, s, "sky_top", o->sky_top, lsys_render_sky_top);
  rgbfield(L, s, "sky_bottom", o->sky_bottom, lsys_render_sky_bottom);
  lua_pop(L, 1);
  return ground;
}

/* Whether camera c sees a ground (horizontal, under mesh m: +y is the world's up, as the
** turtle's heading starts) from above: the eye over the mesh's lowest point, or looking
** down or level when it has no eye. A shell seen from below gets none. */
static int above (const lsys_camera *c, const lsys_mesh *m) {
  double lo[3], hi[3];
  if (c->has_eye) {
    if (!lsys_mesh_bounds(m, lo, hi)) return 0;
    return c->eye[1] > lo[1];
  } else {
    double n = sqrt(c->dir[0] * c->dir[0] + c->dir[1] * c->dir[1] + c->dir[2] * c->dir[2]);
    return c->dir[1] <= 0.05 * n;
  }
}

/* Pushes an empty shadeprep (freed by its __gc). */
static shadeprep *newprep (lua_State *L) {
  shadeprep *p = (shadeprep *)lua_newuserdatauv(L, sizeof *p, 0);
  memset(p, 0, sizeof *p);
  if (luaL_newmetatable(L, SHADEPREP_T)) {
    lua_pushcfunction(L, shadeprep_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  return p;
}

/* Scene v (a copy of the scene drawn, its arrays borrowed) with the camera, lights and
** background of 'look' (what the options gave). */
static void lookof (lsys_scene *v, const lsys_scene *look) {
  v->cam = look->cam;
  memcpy(v->light, look->light, sizeof v->light);
  memcpy(v->lights, look->lights, sizeof v->lights);
  v->nlights = look->nlights;
  memcpy(v->background, look->background, sizeof v->background);
}

/* Where the picture o of scene v (its camera framing a box: has_box) sees the
** plane under its lowest point: the hits of rays through the picture's edges
** into g->rect, so that the ground reaches the picture's bottom and sides. In a
** parallel view that looks down less than 30 degrees the hits are brought
** no farther from the camera than the default square's far edge: every ray of
** such a view meets the plane, and the ground ends behind the plant (a
** horizon) rather than at the picture's top; a steeper view is ground
** wherever it reaches. */
static void groundrect (const lsys_scene *v, const lsys_render_opts *o, lsys_shade_ground *g) {
  enum { N = 16 };
  double proj[16], view[16], lo[3], hi[3], c[3], fh[3], far;
  int k, side, shallow;
  if (!lsys_mesh_bounds(&v->mesh, lo, hi)) return;
  if (lsys_render_camera_scene(v, &v->cam, o->width, o->height, proj, view) != LSYS_OK) return;
  shallow = proj[15] == 1 && -view[6] > -0.5;       /* parallel, f[1] = -view[6] */
  for (k = 0; k < 3; k++) c[k] = (lo[k] + hi[k]) / 2;
  fh[0] = -view[2]; fh[1] = 0; fh[2] = -view[10];      /* the camera's forward, level */
  if (!(vnormlen(fh) > 0)) shallow = 0;
  far = lsys_shade_ground_half(&v->mesh, g);
  for (side = 0; side < 4; side++)
    for (k = 0; k <= N; k++) {
      double s = -1 + 2.0 * k / N, org[3], d[3], t, px, pz;
      lsys_render_unproject(proj, view, side < 2 ? s : side == 2 ? -1 : 1,
                            side < 2 ? (side == 0 ? -1 : 1) : s, org, d);
      if (!(d[1] < -1e-9)) continue;                    /* never meets the plane */
      t = (lo[1] - org[1]) / d[1];
      if (!(t > 0) && proj[15] != 1) continue;      /* (a parallel view's line is whole) */
      px = org[0] + t * d[0];
      pz = org[2] + t * d[2];
      if (shallow) {                /* no farther than the default square's far edge */
        double beyond = (px - c[0]) * fh[0] + (pz - c[2]) * fh[2] - far;
        if (beyond > 0) { px -= beyond * fh[0]; pz -= beyond * fh[2]; }
      }
      if (!g->has_rect) {
        g->has_rect = 1;
        g->rect[0] = g->rect[2] = px;
        g->rect[1] = g->rect[3] = pz;
      }
      g->rect[0] = fmin(g->rect[0], px); g->rect[2] = fmax(g->rect[2], px);
      g->rect[1] = fmin(g->rect[1], pz); g->rect[3] = fmax(g->rect[3], pz);
    }
}

/* Makes scene v the one drawn with a ground (its mesh and palette in p) and
** the shading factors of o. Raises on failure (p is freed by its __gc). */
static void prepare (lua_State *L, shadeprep *p, lsys_scene *v, lsys_render_opts *o,
                     const lsys_shade_opts *so, lsys_shade_ground *g, const float gcol[3],
                     int ground) {
  lsys_error e;
  int st;
  if ((ground || so->shadows || so->ao) && v->ninst > 0) {
    lsys_meter mt = {0};
    mt.limit = lsys_common_memory_limit();
    lsys_scene_init(&p->flat);
    st = lsys_population_flatten(&p->flat, v, &mt);
    if (st == LSYS_EMEMORY) {
      char b1[32], b2[32];
      luaL_error(L, "lsys.render: shadows, ambient occlusion or a ground draw the %zu "
                 "instances one by one, which needs %s, more than max_memory (%s): render "
                 "without them", v->ninst, lsys_common_fmtsize(b1, lsys_population_flatbytes(v)),
                 lsys_common_fmtsize(b2, mt.limit));
    }
    if (st == LSYS_ELIMIT) luaL_error(L, "lsys.render: more than 2^32 vertices to shade");
    if (st != LSYS_OK) luaL_error(L, "not enough memory");
    p->flattened = 1;
    v->mesh = p->flat.mesh;
    v->pal = p->flat.pal;
    v->npal = p->flat.npal;
    v->parts = NULL; v->nparts = 0;
    v->inst = NULL; v->ninst = 0;
    v->rec = NULL; v->nrec = 0;
    v->shape = NULL; v->nshape = 0;
    v->recpt = NULL; v->npt = 0;
  }
  if (ground && v->ninst == 0 && v->mesh.nt + v->mesh.nl > 0 && above(&v->cam, &v->mesh)) {
    size_t npal = v->npal > 0 ? v->npal : 1, k;
    const float *behind = o->sky ? o->sky_bottom : v->background;   /* what it fades into */
    if (npal + GROUND_FADE > LSYS_MESH_NCOLORS)
      luaL_error(L, "lsys.render: ground: the palette is full");
    if (lsys_mesh_copy(&p->mesh, &v->mesh) != LSYS_OK) luaL_error(L, "not enough memory");
    p->ground = 1;
    /* colour c is pal[c % npal]: the same entry once the palette grows */
    for (k = 0; k < p->mesh.nv; k++) p->mesh.col[k] = (uint16_t)(p->mesh.col[k] % npal);
    for (k = 0; k < p->mesh.nl; k++) p->mesh.lcol[k] = (uint16_t)(p->mesh.lcol[k] % npal);
    if ((p->pal = (lsys_material *)LSYS_MALLOC((npal + GROUND_FADE) * sizeof *p->pal)) == NULL)
      luaL_error(L, "not enough memory");
    if (v->npal > 0) memcpy(p->pal, v->pal, npal * sizeof *p->pal);
    else {
      static const lsys_material grey = {{0.24f, 0.24f, 0.24f, 1}, {0.8f, 0.8f, 0.8f, 1},
                                         {0, 0, 0, 1}, {0, 0, 0, 1}, 0};
      p->pal[0] = grey;
    }
    for (k = 0; k < GROUND_FADE; k++) {
      double t = (double)k / (GROUND_FADE - 1);
      lsys_mesh_material_color(&p->pal[npal + k], gcol[0] + t * (behind[0] - gcol[0]),
                               gcol[1] + t * (behind[1] - gcol[1]),
                               gcol[2] + t * (behind[2] - gcol[2]));
    }
    g->col = (unsigned)npal;
    g->nfade = GROUND_FADE;
    if (!v->cam.has_box) {                  /* the camera frames the plant, not its ground */
      double lo[3], hi[3];
      if (lsys_mesh_bounds(&v->mesh, lo, hi)) {
        v->cam.has_box = 1;
        memcpy(v->cam.box, lo, sizeof lo);
        memcpy(v->cam.box + 3, hi, sizeof hi);
      }
    }
    groundrect(v, o, g);
    if ((st = lsys_shade_add_ground(&p->mesh, g, &e)) != LSYS_OK)
      luaL_error(L, "lsys.render: %s", st == LSYS_ENOMEM ? "not enough memory" : e.msg);
    v->mesh = p->mesh;
    v->pal = p->pal;
    v->npal = npal + GROUND_FADE;
  }
  if ((so->shadows || so->ao) && v->mesh.nv > 0) {
    lsys_shade_opts oo = *so;
    lsys_meter mt = {0};
    mt.limit = lsys_common_memory_limit();
    oo.meter = &mt;
    if ((p->f = (uint8_t *)LSYS_MALLOC(v->mesh.nv)) == NULL) luaL_error(L, "not enough memory");
    if ((st = lsys_shade_compute(p->f, v, &oo, &e)) != LSYS_OK)
      luaL_error(L, "lsys.render: %s", st == LSYS_ENOMEM ? "not enough memory" : e.msg);
    o->shade = p->f;
  }
}
#endif

/*
** core.render(scene [, opts]): draws the scene offscreen. With opts.out,
** writes that PNG file (RGB, or RGBA with opts.transparent) and returns
** true; otherwise returns the RGBA pixels (a string, top row first), the
** width and the height. The scene's camera, light, background and textures
** are used, except where opts gives them (lsysL_readlook; opts.textures: a
** list of lsys.Texture, read last: lsysL_opttextures). The scene is taken
** after everything that runs Lua code (the options' metamethods, finalizers
** run by the allocation of the pixels).
** The supersampling factor is lowered when the supersampled image would
** exceed OSMesa's maximum size or LSYS_RENDER_MAX_SAMPLES; width and height
** themselves must fit OSMesa.
*/
static int l_render (lua_State *L) {
#ifdef LSYS_NO_RENDER
  return luaL_error(L, "lsys was built without OSMesa: install libosmesa6-dev and rebuild "
                       "(./setup.sh does)");
#else
  const lsys_lscene *S = lsysL_checkscene(L, 1);
  const char *out = NULL;
  const lsys_texture *const *tex;
  lsys_scene look = S->sc, v;         /* look: the camera, light, background opts give */
  lsys_render_opts o;
  lsys_opts ro = {0, "lsys.render: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_error e;
  luaL_Buffer b;
  uint8_t *px;
  size_t n;
  int maxw, maxh, ntex, ground;
  lsys_shade_opts so;
  lsys_shade_ground g;
  float gcol[3];
  shadeprep *prep;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    ro.t = 2;
  }
  lsysL_readrenderopts(L, ro.t, &o, &look);
  ground = readshade(L, ro.t, &so, &g, gcol, &o);
  prep = newprep(L);
  if (lsysL_optfield(L, &ro, "out", LUA_TSTRING, "a file name"))
    out = lua_tostring(L, -1);        /* stays on the stack */
  if (lsys_render_maxsize(&maxw, &maxh, &e) != LSYS_OK)
    return luaL_error(L, "lsys.render: %s", e.msg);
  if (o.width > maxw || o.height > maxh)
    return luaL_error(L, "lsys.render: %dx%d is larger than OSMesa's limit of %dx%d",
                      o.width, o.height, maxw, maxh);
  n = (size_t)o.width * (size_t)o.height * 4;
  if ((double)n * 3 > (double)lsys_common_memory_limit()) {   /* the picture, colour and depth */
    char b1[32], b2[32];
    return luaL_error(L, "lsys.render: a %dx%d picture needs %s, more than max_memory (%s)",
                      o.width, o.height, lsys_common_fmtsize(b1, n * 3),
                      lsys_common_fmtsize(b2, lsys_common_memory_limit()));
  }
  /* the pixels live in Lua memory, so an error cannot leak them */
  px = out ? (uint8_t *)lua_newuserdatauv(L, n, 0) : (uint8_t *)luaL_buffinitsize(L, &b, n);
  tex = lsysL_opttextures(L, ro.t, "lsys.render", &ntex);   /* pushes one value; kept */
  S = lsysL_checkscene(L, 1);          /* after the last Lua code (metamethods, finalizers) */
  v = S->sc;                          /* the scene as this picture sees it (scene.h) */
  lookof(&v, &look);
  if (tex != NULL) { v.tex = tex; v.ntex = ntex; }
  prepare(L, prep, &v, &o, &so, &g, gcol, ground);
  if (lsys_render_offscreen(&v, &o, px, &e) != LSYS_OK)
    return luaL_error(L, "lsys.render: %s", e.msg);
  if (out) {
    if (lsys_pngio_write(out, px, o.width, o.height, o.transparent, &e) != LSYS_OK)
      return luaL_error(L, "lsys.render: %s", e.msg);
    lua_pushboolean(L, 1);
    return 1;
  }
  lua_pop(L, 1);                      /* the textures' value: the buffer is on top again */
  luaL_pushresultsize(&b, n);
  lua_pushinteger(L, o.width);
  lua_pushinteger(L, o.height);
  return 3;
#endif
}

#ifndef LSYS_NO_RENDER
#define BAKE_LEVELS 16          /* steps of a palette entry's diffuse colour */

/* Bakes the factors f of the vertices of B's mesh (prepare's) into their colours: pal0
** (npal entries) grows to 'levels' steps of each entry's diffuse colour, the first the
** entry itself, the last 1/levels of it; a vertex takes the step of its factor. */
static void bakecolours (lua_State *L, lsys_scene *B, const lsys_material *pal0, size_t npal,
                         const uint8_t *f) {
  size_t levels = BAKE_LEVELS, j, c, k;
  lsys_material *pal;
  int st;
  while (npal * levels > LSYS_MESH_NCOLORS && levels > 1) levels /= 2;
  if (f == NULL || levels < 2) {
    if (lsys_scene_set_palette(B, pal0, npal) != LSYS_OK) luaL_error(L, "not enough memory");
    return;
  }
  if ((pal = (lsys_material *)LSYS_MALLOC(npal * levels * sizeof *pal)) == NULL)
    luaL_error(L, "not enough memory");
  for (j = 0; j < levels; j++)
    for (c = 0; c < npal; c++) {
      lsys_material *m = &pal[j * npal + c];
      float x = 1 - (float)j / (float)levels;
      int i;
      *m = pal0[c];
      for (i = 0; i < 3; i++) m->diffuse[i] *= x;
    }
  st = lsys_scene_set_palette(B, pal, npal * levels);
  LSYS_FREE(pal);
  if (st != LSYS_OK) luaL_error(L, "not enough memory");
  for (k = 0; k < B->mesh.nv; k++) {
    size_t step = (size_t)((255 - f[k]) * (double)levels / 256.0);
    B->mesh.col[k] = (uint16_t)(B->mesh.col[k] % npal + npal * step);
  }
}

/*
** core.bake(scene [, opts]) -> Scene: the scene as core.render draws it with
** opts.shade (lsys.render.bake: shadows, ao, ground), for a window, which draws
** no shadows of its own: a population's instances written out, the ground
** appended, and each vertex's shading factor baked into its colour
** (bakecolours). opts as core.render's (width and height: the picture whose
** ground grows to what its camera sees). The camera (framing the plant), the
** light and background are the picture's, the textures the scene's; its
** records are kept unless it had instances.
*/
static int l_bake (lua_State *L) {
  static const lsys_material grey = {{0.24f, 0.24f, 0.24f, 1}, {0.8f, 0.8f, 0.8f, 1},
                                     {0, 0, 0, 1}, {0, 0, 0, 1}, 0};
  const lsys_lscene *S = lsysL_checkscene(L, 1);
  lsys_scene look = S->sc, v;
  lsys_render_opts o;
  lsys_opts ro = {0, "lsys.render.bake: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_shade_opts so;
  lsys_shade_ground g;
  float gcol[3];
  shadeprep *prep;
  lsys_lscene *B;
  int ground;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    ro.t = 2;
  }
  lsysL_readrenderopts(L, ro.t, &o, &look);
  ground = readshade(L, ro.t, &so, &g, gcol, &o);
  prep = newprep(L);
  B = lsysL_newscene(L);
  S = lsysL_checkscene(L, 1);         /* after the last Lua code */
  v = S->sc;
  lookof(&v, &look);
  prepare(L, prep, &v, &o, &so, &g, gcol, ground);
  if (lsys_mesh_copy(&B->sc.mesh, &v.mesh) != LSYS_OK) return luaL_error(L, "not enough memory");
  bakecolours(L, &B->sc, v.npal > 0 ? v.pal : &grey, v.npal > 0 ? v.npal : 1, prep->f);
  if (!prep->flattened && v.nrec > 0) {       /* the mesh copy has the same lines */
    if (lsys_scene_append_records(&B->sc, &v, 0, 0, 0) != LSYS_OK)
      return luaL_error(L, "not enough memory");
    if (v.nstiff > 0) {               /* the records' stiffnesses, 3 floats each */
      if ((B->sc.stiff = (float *)LSYS_MALLOC(3 * v.nstiff * sizeof *v.stiff)) == NULL)
        return luaL_error(L, "not enough memory");
      memcpy(B->sc.stiff, v.stiff, 3 * v.nstiff * sizeof *v.stiff);
      B->sc.nstiff = v.nstiff;
      B->sc.stiffcap = 3 * v.nstiff;
    }
  }
  lookof(&B->sc, &v);
  B->sc.tex = S->sc.tex;
  B->sc.ntex = S->sc.ntex;
  B->sc.cull = v.cull;
  lua_getiuservalue(L, 1, LSYS_SCENE_TEX);        /* the textures stay alive with it */
  lua_setiuservalue(L, -2, LSYS_SCENE_TEX);
  return 1;
}

/* Sets t[k] = x for the flat arrays of l_project. */
static void seti (lua_State *L, lua_Integer *k, double x) {
  lua_pushnumber(L, x);
  lua_rawseti(L, -2, ++*k);
}
#endif

/*
** core.project(scene [, opts]) -> { width =, height =, background = {r, g, b},
** lines = {...}, triangles = {...}, palette = {{r, g, b, a}, ...} }: what the
** scene draws, projected through the camera of core.render with the same options
** (lsysL_readrenderopts: the view fields, width, height, zoom, fit) into a window
** of width x height pixels (x from the left, y from the top, depth in [0, 1]).
** 'lines' holds 9 numbers per segment: x0, y0, depth0, x1, y1, depth1, the widths
** at both ends in pixels (as the renderer reads them) and the palette entry
** (1-based); 'triangles' 10 per triangle: three corners (x, y, depth) and the
** palette entry of its first vertex. A segment or triangle with a point behind
** the eye is left out. 'palette': the diffuse colours the renderer draws with.
** A population (instances) is not projected: raises.
*/
static int l_project (lua_State *L) {
#ifdef LSYS_NO_RENDER
  return luaL_error(L, "lsys was built without OSMesa: install libosmesa6-dev and rebuild "
                       "(./setup.sh does)");
#else
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lsys_scene look = S->sc, v;
  lsys_render_opts o;
  double proj[16], view[16];
  lua_Integer k;
  size_t i, j, npal;
  int t = 0;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    t = 2;
  }
  lsysL_readrenderopts(L, t, &o, &look);
  lua_settop(L, 1);
  S = lsysL_holdscene(L, 1);           /* after the last Lua code; kept while tables grow */
  lua_createtable(L, 0, 6);
  lua_pushinteger(L, o.width); lua_setfield(L, -2, "width");
  lua_pushinteger(L, o.height); lua_setfield(L, -2, "height");
  lua_createtable(L, 3, 0);
  for (k = 0; k < 3; k++) { lua_pushnumber(L, look.background[k]); lua_rawseti(L, -2, k + 1); }
  lua_setfield(L, -2, "background");
  if (S->sc.ninst > 0)
    return luaL_error(L, "lsys.render: vector output draws one plant, not a population of %d "
                      "(render it to .png)", (int)S->sc.ninst);
  {                                    /* the tables: a Lua number per value, ~16 bytes */
    double need = 16.0 * (9.0 * (double)S->sc.mesh.nl + 10.0 * (double)S->sc.mesh.nt);
    if (need > (double)lsys_common_memory_limit()) {
      char b1[32], b2[32];
      return luaL_error(L, "lsys.render: a vector picture of %d lines and %d triangles needs "
                        "%s, more than max_memory (%s)", (int)S->sc.mesh.nl, (int)S->sc.mesh.nt,
                        lsys_common_fmtsize(b1, (size_t)need),
                        lsys_common_fmtsize(b2, lsys_common_memory_limit()));
    }
  }
  v = S->sc;
  v.cam = look.cam;
  if (lsys_render_camera_scene(&v, &v.cam, o.width, o.height, proj, view) != LSYS_OK)
    return luaL_error(L, "lsys.render: bad camera: the viewpoint and the target coincide, a "
                      "zero direction or up vector");
  npal = v.pal != NULL && v.npal > 0 ? (v.npal > 65536 ? 65536 : v.npal) : 0;
  lua_createtable(L, (int)(npal > 0 ? npal : 1), 0);
  for (i = 0; i < (npal > 0 ? npal : 1); i++) {
    static const float grey[4] = {0.8f, 0.8f, 0.8f, 1};
    const float *d = npal > 0 ? v.pal[i].diffuse : grey;
    lua_createtable(L, 4, 0);
    for (k = 0; k < 4; k++) {
      lua_pushnumber(L, d[k] <= 0 ? 0 : d[k] >= 1 ? 1 : d[k]);
      lua_rawseti(L, -2, k + 1);
    }
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  lua_setfield(L, -2, "palette");
  if (npal == 0) npal = 1;
  lua_createtable(L, (int)(9 * v.mesh.nl), 0);
  for (i = 0, k = 0; i < v.mesh.nl; i++) {
    double p[3], w[2][3];
    int in = 1;
    for (j = 0; j < 2; j++) {
      const float *q = v.mesh.lpos + 6 * i + 3 * j;
      p[0] = q[0]; p[1] = q[1]; p[2] = q[2];
      in &= lsys_render_project(proj, view, o.width, o.height, p, w[j]);
    }
    if (!in) continue;
    for (j = 0; j < 6; j++) seti(L, &k, w[j / 3][j % 3]);
    seti(L, &k, v.mesh.lwidth[2 * i]);
    seti(L, &k, v.mesh.lwidth[2 * i + 1]);
    seti(L, &k, (double)(v.mesh.lcol[i] % npal + 1));
  }
  lua_setfield(L, -2, "lines");
  lua_createtable(L, (int)(10 * v.mesh.nt), 0);
  for (i = 0, k = 0; i < v.mesh.nt; i++) {
    double p[3], w[3][3];
    int in = 1;
    for (j = 0; j < 3; j++) {
      const float *q = v.mesh.pos + 3 * (size_t)v.mesh.tri[3 * i + j];
      p[0] = q[0]; p[1] = q[1]; p[2] = q[2];
      in &= lsys_render_project(proj, view, o.width, o.height, p, w[j]);
    }
    if (!in) continue;
    for (j = 0; j < 9; j++) seti(L, &k, w[j / 3][j % 3]);
    seti(L, &k, (double)(v.mesh.col[v.mesh.tri[3 * i]] % npal + 1));
  }
  lua_setfield(L, -2, "triangles");
  return 1;
#endif
}

static int pixels_gc (lua_State *L) {
  uint8_t **p = (uint8_t **)luaL_checkudata(L, 1, PIXELS_T);
  LSYS_FREE(*p);
  *p = NULL;
  return 0;
}

/* core.png_read(path): the RGBA pixels (a string, top row first), width, height. */
static int l_png_read (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  uint8_t **box = (uint8_t **)lua_newuserdatauv(L, sizeof *box, 0);
  int w, h;
  lsys_error e;
  *box = NULL;
  luaL_setmetatable(L, PIXELS_T);
  if (lsys_pngio_read(path, box, &w, &h, &e) != LSYS_OK) return lsysL_raise(L, e.code, &e, 1);
  lua_pushlstring(L, (const char *)*box, (size_t)w * h * 4);
  LSYS_FREE(*box);
  *box = NULL;
  lua_pushinteger(L, w);
  lua_pushinteger(L, h);
  return 3;
}

/*
** core.png_write(path, pixels, w, h [, alpha]): writes RGBA pixels (top row
** first) as a PNG; RGBA when 'alpha' is true, RGB when false, and when it
** is absent RGBA only if some pixel is not opaque. Returns true.
*/
static int l_png_write (lua_State *L) {
  size_t len, i;
  const char *path = luaL_checkstring(L, 1);
  const uint8_t *px = (const uint8_t *)luaL_checklstring(L, 2, &len);
  lua_Integer w = luaL_checkinteger(L, 3), h = luaL_checkinteger(L, 4);
  int alpha = 0;
  lsys_error e;
  luaL_argcheck(L, w > 0 && w <= LSYS_PNG_MAXSIZE, 3, "width out of range");
  luaL_argcheck(L, h > 0 && h <= LSYS_PNG_MAXSIZE, 4, "height out of range");
  if (len != (size_t)w * (size_t)h * 4)
    return luaL_error(L, "lsys.png_write: %I x %I RGBA pixels need %I bytes, got %I", w, h,
                      (lua_Integer)(w * h * 4), (lua_Integer)len);
  if (lua_isnoneornil(L, 5)) {
    for (i = 3; i < len && !alpha; i += 4) alpha = px[i] != 255;
  } else {
    luaL_checktype(L, 5, LUA_TBOOLEAN);
    alpha = lua_toboolean(L, 5);
  }
  if (lsys_pngio_write(path, px, (int)w, (int)h, alpha, &e) != LSYS_OK)
    return lsysL_raise(L, e.code, &e, 1);
  lua_pushboolean(L, 1);
  return 1;
}

/* core.write_file(path, bytes): writes the string atomically (outfile.h). */
static int l_write_file (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  size_t len;
  const char *bytes = luaL_checklstring(L, 2, &len);
  lsys_outfile out;
  lsys_error e;
  int st = lsys_outfile_open(&out, path, &e);
  if (st == LSYS_OK) {
    lsys_outfile_write(&out, bytes, len);
    st = lsys_outfile_commit(&out, &e);
  }
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  lua_pushboolean(L, 1);
  return 1;
}

/* core.read_file(path, max) -> the bytes of a regular file of at most 'max'
** bytes, or nil and a message naming the file (lsys_common_readfile) */
static int l_read_file (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  lua_Number max = luaL_checknumber(L, 2);
  lsys_error e;
  size_t len;
  char *text;
  luaL_argcheck(L, max >= 0 && max < 1e15, 2, "a number of bytes expected");
  text = lsys_common_readfile(path, (size_t)max, &len, &e);
  if (text == NULL) {
    lua_pushnil(L);
    lua_pushstring(L, e.msg);
    return 2;
  }
  lua_pushlstring(L, text, len);     /* may raise: a leak only on a memory error */
  LSYS_FREE(text);
  return 1;
}

/* core.realpath(path) -> the absolute name without symbolic links, '.' or '..', and
** "file", "directory" or "other" (opening nothing); nil and "PATH: why" when it does not
** exist (path.h) */
static int l_realpath (lua_State *L) {
  static const char *const kinds[] = {"file", "directory", "other"};
  const char *path = luaL_checkstring(L, 1);
  lsys_error e;
  int kind;
  char *real = lsys_path_real(path, &kind, &e);
  if (real == NULL) {
    if (e.code == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
    lua_pushnil(L);
    lua_pushstring(L, e.msg);
    return 2;
  }
  lua_pushstring(L, real);           /* may raise: a leak only on a memory error */
  LSYS_FREE(real);
  lua_pushstring(L, kinds[kind - 1]);
  return 2;
}

static const luaL_Reg pixels_meta[] = {
  {"__gc", pixels_gc}, {NULL, NULL}
};

static const luaL_Reg render_funcs[] = {
  {"render", l_render}, {"bake", l_bake}, {"project", l_project}, {"png_read", l_png_read},
  {"png_write", l_png_write}, {"write_file", l_write_file}, {"read_file", l_read_file}, {"realpath", l_realpath},
  {NULL, NULL}
};

#ifndef LSYS_NO_RENDER
/* At lua_close: the offscreen context and its scratch are freed before the C
** library is unloaded (they would show as leaks). */
static int renderstate_gc (lua_State *L) {
  (void)L;
  lsys_render_shutdown();
  return 0;
}
#endif

void lsysL_open_render (lua_State *L) {
  lsysL_createmeta(L, PIXELS_T, pixels_meta, NULL);
#ifndef LSYS_NO_RENDER
  if (lua_getfield(L, LUA_REGISTRYINDEX, "lsys.renderstate") == LUA_TNIL) {
    lua_newuserdatauv(L, 0, 0);
    lua_newtable(L);
    lua_pushcfunction(L, renderstate_gc);
    lua_setfield(L, -2, "__gc");
    lua_setmetatable(L, -2);
    lua_setfield(L, LUA_REGISTRYINDEX, "lsys.renderstate");
  }
  lua_pop(L, 1);
#endif
  luaL_setfuncs(L, render_funcs, 0);
#ifdef LSYS_NO_RENDER
  lua_pushboolean(L, 0);
#else
  lua_pushboolean(L, 1);
#endif
  lua_setfield(L, -2, "has_render");
}
