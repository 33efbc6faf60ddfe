/*
** lsys.Rules, the compiled rules of one model (the C side of lsys.lsystem):
** parsing rule text, adding rules, configuring and running derivation steps,
** and what rule functions call while a model derives: successor templates
** with lsys.produce / lsys.nproduce, and lsys.ran / lsys.nran. Running an
** operation with the rule functions bound is lsysL_rules_run (lua_aux.c).
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "grammar.h"

/* The Rules at 'i' for a method that changes them: raises also while they
** derive. */
static lsys_lrules *checkidle (lua_State *L, int i) {
  lsys_lrules *R = lsysL_checkrules(L, i);
  if (R->m.busy) luaL_error(L, "the rules of a model cannot change while it derives");
  return R;
}

/* ---------------------------------------------------------------------- */
/* __gc and __close: idempotent; refused while the rules derive (__close from a
** rule function: the collector cannot reach rules that are deriving). */
static int rules_gc (lua_State *L) {
  lsys_lrules *R = (lsys_lrules *)luaL_checkudata(L, 1, RULES_T);
  if (R->inited && R->m.busy) return luaL_error(L, "cannot close the rules of a model while it derives");
  if (R->inited) {
    lsys_rules_free(&R->m);
    lsys_alphabet_names_free(&R->decl);
    R->inited = 0;
  }
  return 0;
}

/* core.rules([names]): a new empty rule store */
static int l_rules (lua_State *L) {
  const char *names = luaL_optstring(L, 1, "");
  lsys_alphabet *a = lsysL_getalphabet(L);
  lsys_lrules *R = (lsys_lrules *)lua_newuserdatauv(L, sizeof *R, LSYS_RULES_NUV);
  memset(R, 0, sizeof *R);
  luaL_setmetatable(L, RULES_T);
  lsys_rules_init(&R->m, a);
  R->inited = 1;
  lua_newtable(L);
  lua_setiuservalue(L, -2, LSYS_RULES_FNS);
  lua_newtable(L);
  lua_setiuservalue(L, -2, LSYS_RULES_TPL);
  if (lsysL_readnames(L, names, &R->decl) != LSYS_OK) return luaL_error(L, "not enough memory");
  return 1;
}

static void pushpmods (lua_State *L, const char *text, const lsys_prule *r,
                       size_t from, size_t n) {
  size_t k;
  uint32_t j;
  lsys_alphabet *a = lsysL_getalphabet(L);
  lua_createtable(L, (int)n, 0);
  for (k = 0; k < n; k++) {
    const lsys_pmod *pm = &r->mods[from + k];
    lua_createtable(L, 0, 4);
    lua_pushinteger(L, pm->sym);
    lua_setfield(L, -2, "sym");
    lua_pushstring(L, lsys_alphabet_name(a, pm->sym));
    lua_setfield(L, -2, "name");
    lua_pushinteger(L, (lua_Integer)pm->pos + 1);
    lua_setfield(L, -2, "pos");
    lua_createtable(L, (int)pm->np, 0);
    for (j = 0; j < pm->np; j++) {
      const lsys_span *sp = &r->params[pm->first + j];
      lua_pushlstring(L, text + sp->off, sp->len);
      lua_rawseti(L, -2, j + 1);
    }
    lua_setfield(L, -2, "params");
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
}

/*
** rules:parse(text, mode) -> table | nil, message, position
** mode: "rule" (default), "pattern" (no successor), "successor"
*/
static int rules_parse (lua_State *L) {
  static const char *const modes[] = {"rule", "pattern", "successor", NULL};
  lsys_lrules *R = lsysL_checkrules(L, 1);
  size_t len;
  const char *text = luaL_checklstring(L, 2, &len);
  int mode = luaL_checkoption(L, 3, "rule", modes);
  lsys_prule r;
  lsys_error e;
  int st;
  R = lsysL_checkrules(L, 1);                /* again: converting a number allocates */
  st = lsys_grammar_rule_parse(&r, text, len, mode, R->m.ab, &R->decl, &e);
  if (st != LSYS_OK) {
    lsys_grammar_prule_free(&r);
    lua_pushnil(L);
    lua_pushstring(L, st == LSYS_ENOMEM ? "not enough memory" : e.msg);
    lua_pushinteger(L, (lua_Integer)e.pos + 1);
    return 3;
  }
  lua_createtable(L, 0, 8);          /* may raise: r leaks only on memory errors */
  pushpmods(L, text, &r, 0, r.nlc);
  lua_setfield(L, -2, "lc");
  if (mode != 2) {                  /* pred: the first module; preds: all of them */
    pushpmods(L, text, &r, r.nlc, r.npred);
    lua_rawgeti(L, -1, 1);
    lua_setfield(L, -3, "pred");
    lua_setfield(L, -2, "preds");
  }
  pushpmods(L, text, &r, mode == 2 ? 0 : r.nlc + r.npred, r.nrc);
  lua_setfield(L, -2, "rc");
  pushpmods(L, text, &r, r.nmods - r.nsucc, r.nsucc);
  lua_setfield(L, -2, "succ");
  if (r.cond.len) {
    lua_pushlstring(L, text + r.cond.off, r.cond.len);
    lua_setfield(L, -2, "cond");
  }
  if (r.weight.len) {
    lua_pushlstring(L, text + r.weight.off, r.weight.len);
    lua_setfield(L, -2, "weight");
  }
  lua_pushboolean(L, r.empty);
  lua_setfield(L, -2, "empty");
  lsys_grammar_prule_free(&r);
  return 1;
}

static void readpats (lua_State *L, int t, const char *field, lsys_patmod *out,
                      uint32_t max, uint32_t *n) {
  lua_Integer k, len;
  lua_getfield(L, t, field);
  len = lua_istable(L, -1) ? luaL_len(L, -1) : 0;
  if (len / 2 > (lua_Integer)max) luaL_error(L, "pattern too long (limit is %d modules)", (int)max);
  for (k = 0; k < len / 2; k++) {
    lua_rawgeti(L, -1, 2 * k + 1);
    lua_rawgeti(L, -2, 2 * k + 2);
    out[k].sym = (uint32_t)luaL_checkinteger(L, -2);
    out[k].np = (uint32_t)luaL_checkinteger(L, -1);
    if (out[k].np > LSYS_MAXPARAMS) luaL_error(L, "too many parameters");
    lua_pop(L, 2);
  }
  *n = (uint32_t)(len / 2);
  lua_pop(L, 1);
}

#define MAXPAT 64

/*
** rules:add(kind, sub, group, spec) -> rule index (0-based)
** spec = { lc = {sym, np, ...}, pred = {sym, np, ...}, rc = {...},
**          succ = {sym, np, ...}, src = {kind, idx, value, ...},
**          flags = n, nvals = n, weight = w, id = n, fn = function }
** All arrays are copied before anything is allocated in the core.
*/
static int rules_add (lua_State *L) {
  lsys_lrules *R = checkidle(L, 1);
  int kind = (int)luaL_checkinteger(L, 2);
  int sub = (int)luaL_checkinteger(L, 3);
  int group = (int)luaL_checkinteger(L, 4);
  lsys_patmod lc[MAXPAT], rc[MAXPAT], pred[MAXPAT];
  lsys_rulespec sp;
  lsys_error e;
  uint32_t npred;
  lua_Integer k, n;
  long idx;
  uint16_t *succ;
  lsys_psrc *src;
  luaL_argcheck(L, kind >= LSYS_PROD && kind <= LSYS_HOMO, 2, "bad rule kind");
  luaL_checktype(L, 5, LUA_TTABLE);
  memset(&sp, 0, sizeof sp);
  readpats(L, 5, "lc", lc, MAXPAT, &sp.nlc);
  readpats(L, 5, "rc", rc, MAXPAT, &sp.nrc);
  readpats(L, 5, "pred", pred, MAXPAT, &npred);
  if (npred < 1) return luaL_error(L, "rule without predecessor");
  sp.lc = lc; sp.rc = rc; sp.pred = pred[0];
  sp.more = pred + 1; sp.nmore = npred - 1;
  lua_getfield(L, 5, "succ");
  n = lua_istable(L, -1) ? luaL_len(L, -1) / 2 : 0;
  succ = (uint16_t *)lua_newuserdatauv(L, (size_t)(n + 1) * sizeof *succ, 0);  /* scratch */
  for (k = 0; k < n; k++) {
    lua_Integer sym, np;
    lua_rawgeti(L, -2, 2 * k + 1);
    lua_rawgeti(L, -3, 2 * k + 2);
    sym = luaL_checkinteger(L, -2);
    np = luaL_checkinteger(L, -1);
    if (sym <= 0 || sym > LSYS_MAXSYM || np < 0 || np > LSYS_MAXPARAMS)
      return luaL_error(L, "bad successor module");
    succ[k] = LSYS_CODE((uint32_t)sym, (uint32_t)np);
    lua_pop(L, 2);
  }
  sp.succ = succ; sp.nsucc = (uint32_t)n;
  lua_getfield(L, 5, "src");
  n = lua_istable(L, -1) ? luaL_len(L, -1) / 3 : 0;
  src = (lsys_psrc *)lua_newuserdatauv(L, (size_t)(n + 1) * sizeof *src, 0);
  for (k = 0; k < n; k++) {
    lua_rawgeti(L, -2, 3 * k + 1);
    lua_rawgeti(L, -3, 3 * k + 2);
    lua_rawgeti(L, -4, 3 * k + 3);
    src[k].kind = (uint32_t)luaL_checkinteger(L, -3);
    src[k].idx = (uint32_t)luaL_checkinteger(L, -2);
    src[k].value = luaL_checknumber(L, -1);
    lua_pop(L, 3);
  }
  sp.src = src; sp.nsrc = (uint32_t)n;
  lua_getfield(L, 5, "flags"); sp.flags = (uint32_t)luaL_optinteger(L, -1, 0); lua_pop(L, 1);
  lua_getfield(L, 5, "nvals"); sp.nvals = (uint32_t)luaL_optinteger(L, -1, 0); lua_pop(L, 1);
  lua_getfield(L, 5, "weight"); sp.weight = luaL_optnumber(L, -1, 1); lua_pop(L, 1);
  lua_getfield(L, 5, "id"); sp.id = (int)luaL_optinteger(L, -1, 0); lua_pop(L, 1);
  R = checkidle(L, 1);                      /* again: the spec's metamethods ran Lua code */
  idx = lsys_rules_add(&R->m, kind, sub, group, &sp, &e);
  if (idx < 0) return lsysL_raise(L, (int)idx, &e, 1);
  lua_getiuservalue(L, 1, LSYS_RULES_FNS);
  lua_getfield(L, 5, "fn");
  lua_rawseti(L, -2, (lua_Integer)idx + 1);
  lua_pushinteger(L, idx);
  return 1;
}

/* rules:skiplist(sub, consider, names): ignore or consider list */
static int rules_skiplist (lua_State *L) {
  lsys_lrules *R = checkidle(L, 1);
  int sub = (int)luaL_checkinteger(L, 2);
  int consider = lua_toboolean(L, 3);
  size_t len, i = 0, n = 0;
  const char *text = luaL_checklstring(L, 4, &len);
  uint32_t *syms = (uint32_t *)lua_newuserdatauv(L, (len + 1) * sizeof *syms, 0);
  lsys_error e;
  R = checkidle(L, 1);                      /* again: a finalizer may have closed them */
  while (i < len) {
    size_t nl;
    if (text[i] == ' ' || text[i] == '\t' || text[i] == '\n') { i++; continue; }
    nl = lsys_alphabet_scan(text + i, len - i, &R->decl);
    if (nl == 0) return luaL_error(L, "bad module name at '%s'", text + i);
    syms[n] = lsys_alphabet_intern(R->m.ab, text + i, nl, &e);
    if (syms[n] == 0) return lsysL_raise(L, e.code, &e, 1);
    n++;
    i += nl;
  }
  if (lsys_rules_skiplist(&R->m, sub, consider, syms, n) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  return 0;
}

/* The generator seed of the number at 'idx': an integer as itself; a
** fractional, huge or nan number by its bits. */
static uint64_t seedof (lua_State *L, int idx) {
  lua_Number s = luaL_checknumber(L, idx);
  uint64_t seed;
  if (s >= -9.2e18 && s <= 9.2e18 && s == (double)(int64_t)s) seed = (uint64_t)(int64_t)s;
  else memcpy(&seed, &s, sizeof seed);
  return seed;
}

/* rules:config(key, value) */
static int rules_config (lua_State *L) {
  static const char *const keys[] = {"ring", "max_modules", "group", "depth_decomposition",
                                     "depth_homomorphism", "seed", "hseed", "max_memory",
                                     "float32", "threads", "max_instructions", "random",
                                     "hshare", NULL};
  lsys_lrules *R = checkidle(L, 1);
  int key = luaL_checkoption(L, 2, NULL, keys);
  lua_Number x;
  R = checkidle(L, 1);                      /* again: converting a number allocates */
  switch (key) {
    case 0: R->m.ring = lua_toboolean(L, 3); break;
    case 8: R->m.f32 = lua_toboolean(L, 3); break;
    case 9: {                          /* 0: the default (lsys_derive_default_threads) */
      lua_Integer t = luaL_checkinteger(L, 3);
      luaL_argcheck(L, t >= 0 && t <= LSYS_MAXTHREADS, 3, "bad number of threads");
      R->m.threads = (int)t;
      break;
    }
    case 1:
      x = luaL_checknumber(L, 3);
      luaL_argcheck(L, x >= 1 && x <= 1e12, 3, "max_modules must be between 1 and 1e12");
      R->m.max_modules = (size_t)x;
      break;
    case 2: {
      lua_Integer g = luaL_checkinteger(L, 3);
      luaL_argcheck(L, g >= 0 && g < 1000000, 3, "bad group number");
      R->m.group = (int)g;
      break;
    }
    case 3: case 4: {
      lua_Integer d = luaL_checkinteger(L, 3);
      luaL_argcheck(L, d >= 0 && d <= 1024, 3, "maximum depth must be between 0 and 1024");
      R->m.maxdepth[key == 3 ? LSYS_DECOMP : LSYS_HOMO] = (int)d;
      break;
    }
    case 7:                            /* bytes; 0: the process default */
      x = luaL_checknumber(L, 3);
      luaL_argcheck(L, x >= 0 && x < 1.8e19, 3, "max_memory must be a number of bytes >= 0");
      R->m.max_memory = x >= (double)((size_t)-1) ? (size_t)-1 : (size_t)x;
      break;
    case 10:                           /* per call of rule code; math.huge: none */
      x = luaL_checknumber(L, 3);
      luaL_argcheck(L, x >= 1000, 3, "max_instructions must be a number >= 1000");
      R->max_instructions = x;
      break;
    case 11: {                         /* "lsys" or "cpfg" (rng.h) */
      static const char *const kinds[] = {"lsys", "cpfg", NULL};
      int on = luaL_checkoption(L, 3, NULL, kinds);
      R->m.cpfg = R->m.rng.cpfg = R->m.hrng.cpfg = on;
      break;
    }
    case 12: R->m.hshare = lua_toboolean(L, 3); break;
    case 5: {
      uint64_t seed = seedof(L, 3);
      lsys_rng_seed(&R->m.rng, seed);
      /* cpfg's seed: statement: seed48({seed, 0, 155}) when it is not 0, else
      ** drand48's own start (glibc: state 0) */
      R->m.choice48 = seed != 0 ? (uint64_t)155 << 32 | (seed & 0xFFFFu) : 0;
      R->m.choice_ready = 0;
      break;
    }
    default: {                         /* cpfg: nrand's pair is the process's */
      uint64_t seed = seedof(L, 3);
      if (R->m.cpfg) lsys_rng_cpfg_hseed(&R->m.hrng, seed);
      else lsys_rng_seed(&R->m.hrng, seed);
      break;
    }
  }
  return 0;
}

/* rules:setvm(idx, code): code = {op, a, k, ...} (expr.h) or nil to clear.
** Returns true, or false when the program does not fit the rule. */
static int rules_setvm (lua_State *L) {
  lsys_lrules *R = checkidle(L, 1);
  lua_Integer idx = luaL_checkinteger(L, 2);
  lsys_ins *code;
  int st, n;
  luaL_argcheck(L, idx >= 0 && (size_t)idx < R->m.nrules, 2, "bad rule index");
  if (lua_isnoneornil(L, 3)) {
    lsys_rules_setvm(&R->m, (size_t)idx, NULL, 0);
    lua_pushboolean(L, 1);
    return 1;
  }
  code = lsysL_readcode(L, 3, &n);
  R = checkidle(L, 1);                      /* again: the program's reading ran Lua code */
  luaL_argcheck(L, (size_t)idx < R->m.nrules, 2, "bad rule index");
  st = lsys_rules_setvm(&R->m, (size_t)idx, code, n);
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  lua_pushboolean(L, st == LSYS_OK);
  return 1;
}

/* rules:setfuncs(list): the positional functions (Funcs) that LSYS_OP_FN
** indices 0..#list-1 call; the list is read once (lua_geti) into a copy kept
** as a user value, so the Funcs live as long as the rules, and kept
** (lsysL_keepfunc: closing one leaves the model its values). Clears every
** rule's program (setvm again). */
static int rules_setfuncs (lua_State *L) {
  lua_Integer n, k;
  const lsys_func **t;
  lsys_lrules *R;
  int st;
  checkidle(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  n = luaL_len(L, 2);
  luaL_argcheck(L, n >= 0 && n <= 65536, 2, "too many functions (limit is 65536)");
  lua_createtable(L, (int)n, 0);           /* 3: the copy */
  for (k = 1; k <= n; k++) {
    lua_geti(L, 2, k);
    lua_rawseti(L, 3, k);
  }
  t = (const lsys_func **)lua_newuserdatauv(L, (size_t)(n + 1) * sizeof *t, 0);   /* scratch */
  for (k = 0; k < n; k++) {                /* from the copy: no Lua code runs from here */
    lua_rawgeti(L, 3, k + 1);
    t[k] = lsysL_keepfunc(L, -1);
    lua_pop(L, 1);
  }
  R = checkidle(L, 1);
  st = lsys_rules_setfuncs(&R->m, t, (size_t)n);
  if (st != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_pushvalue(L, 3);
  lua_setiuservalue(L, 1, LSYS_RULES_FUNCS);
  return 0;
}

/* rules:hasvm(idx): whether rule idx runs on the expression machine */
static int rules_hasvm (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lua_Integer idx = luaL_checkinteger(L, 2);
  lua_pushboolean(L, idx >= 0 && (size_t)idx < R->m.nrules && R->m.rules[idx].vm != NULL);
  return 1;
}

/* rules:newset(kind, sub, group): an empty rule set (a sub-L-system without rules) */
static int rules_newset (lua_State *L) {
  lsys_lrules *R = checkidle(L, 1);
  int kind = (int)luaL_checkinteger(L, 2);
  luaL_argcheck(L, kind >= LSYS_PROD && kind <= LSYS_HOMO, 2, "bad rule kind");
  if (lsys_rules_newset(&R->m, kind, (int)luaL_checkinteger(L, 3),
                        (int)luaL_optinteger(L, 4, 0)) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  return 0;
}

/* rules:size(kind, sub, group): number of rules or -1 */
static int rules_size (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lua_pushinteger(L, lsys_rules_setsize(&R->m, (int)luaL_checkinteger(L, 2),
                                        (int)luaL_optinteger(L, 3, 0),
                                        (int)luaL_optinteger(L, 4, 0)));
  return 1;
}

/* rules:busy() -> whether the model is deriving (a rule function is running) */
static int rules_busy (lua_State *L) {
  lua_pushboolean(L, lsysL_checkrules(L, 1)->m.busy);
  return 1;
}

typedef struct stepop { int what; lsys_lstring *src, *dst; } stepop;

static int dostep (lua_State *L, lsys_rules *m, void *ud) {
  stepop *o = (stepop *)ud;
  (void)L;
  return o->what < 0 ? lsys_derive_step(m, o->src, o->dst)
                     : lsys_derive_expand(m, o->what, o->src, o->dst);
}

/* Runs a derivation step (what < 0) or an expansion of the Lstring at 2 into the
** one at 'dstidx'; raises on failure. */
static void run (lua_State *L, lsys_lrules *R, int what, int dstidx) {
  stepop o;
  int idx[2], st;
  idx[0] = 2; idx[1] = dstidx;
  o.what = what;
  o.src = what < 0 ? lsysL_checklstring_any(L, 2) : checklstring(L, 2);   /* a step reads */
  o.dst = lsysL_checklstring_any(L, dstidx);               /* narrow strings (lstring.h) */
  st = lsysL_rules_run(L, 1, what < 0 ? "step" : "expand", dostep, &o, idx, 2);
  if (st != LSYS_OK) lsysL_raise(L, st, &R->m.err, 1);
  /* tell the collector about the memory behind the new string */
  lua_gc(L, LUA_GCSTEP, (int)((o.dst->n * 2 + o.dst->npar * 8) >> 10));
}

/* rules:step(src [, dst]) -> dst: one derivation step */
static int rules_step (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lsysL_checklstring_any(L, 2);
  if (lua_isnoneornil(L, 3)) { lua_settop(L, 2); lsysL_newlstring(L); }
  else {
    luaL_argcheck(L, !lua_rawequal(L, 2, 3), 3, "source and destination are the same string");
    lsysL_checkwritable(L, 3, "step");
    lua_settop(L, 3);
  }
  lsysL_setowner(L, 3, 1);
  run(L, R, -1, 3);
  lua_settop(L, 3);
  return 1;
}

/* rules:advance(s) -> s: one derivation step that rewrites 's' in place (the
** caller's own string, which nothing else holds: derive's). Its memory is
** reused; on an error its contents are lost (it is left empty). */
static int rules_advance (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lsys_lstring *s = lsysL_checklstring_any(L, 2);
  luaL_argcheck(L, !((lsys_lstr *)lua_touserdata(L, 2))->busy, 2,
                "the Lstring is in use by a derivation or interpretation");
  lua_settop(L, 2);
  lsysL_setowner(L, 2, 1);
  (void)s;
  run(L, R, -1, 2);
  lua_settop(L, 2);
  return 1;
}

/* rules:expand(src, kind) -> new Lstring */
static int rules_expand (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  int kind = (int)luaL_optinteger(L, 3, LSYS_HOMO);
  checklstring(L, 2);
  luaL_argcheck(L, kind == LSYS_HOMO || kind == LSYS_DECOMP, 3, "bad rule kind");
  lua_settop(L, 3);
  lsysL_newlstring(L);
  lsysL_setowner(L, 4, 1);
  run(L, R, kind, 4);
  lua_settop(L, 4);
  return 1;
}

/* rules:current() -> rule index (0-based) or nil, module index (1-based), depth_hit */
static int rules_current (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  if (R->m.cur_rule >= 0) lua_pushinteger(L, R->m.cur_rule);
  else lua_pushnil(L);
  lua_pushinteger(L, (lua_Integer)R->m.cur_index + 1);
  lua_pushboolean(L, R->m.depth_hit);
  R->m.cur_rule = -1;
  return 3;
}

/* rules:lstring(text): parse with this model's declared names */
static int rules_lstring (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  size_t len;
  const char *text = luaL_checklstring(L, 2, &len);
  lsys_error e;
  lsys_lstring *s = lsysL_newlstring(L);
  int st;
  lsysL_setowner(L, -1, 1);
  R = lsysL_checkrules(L, 1);                /* again: a finalizer may have closed them */
  st = lsys_lstring_parse(s, text, len, R->m.ab, &R->decl, &e);
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (st != LSYS_OK) {
    lua_pushnil(L);
    lua_pushstring(L, e.msg);
    lua_pushinteger(L, (lua_Integer)e.pos + 1);
    return 3;
  }
  return 1;
}

/* rules:ran(): returns the functions ran(x) and nran(mean, sd) bound to this model */
static int ranfn (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, lua_upvalueindex(1));
  lua_Number x = luaL_optnumber(L, 1, 1);
  lua_pushnumber(L, x * lsys_rng_uniform(R->m.cur));
  return 1;
}

static int nranfn (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, lua_upvalueindex(1));
  lua_Number mu = luaL_checknumber(L, 1), sd = luaL_checknumber(L, 2);
  lua_pushnumber(L, lsys_rng_normal(R->m.cur, mu, sd));
  return 1;
}

/* rules:srand(seed): reseeds the generator in use (the derivation's, or the
** homomorphism's while it runs), as cpfg's srand; allowed during a step */
static int rules_srand (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lsys_rng_reseed(R->m.cur, seedof(L, 2));
  return 0;
}

static int rules_ran (lua_State *L) {
  lsysL_checkrules(L, 1);
  lua_pushvalue(L, 1);
  lua_pushcclosure(L, ranfn, 1);
  lua_pushvalue(L, 1);
  lua_pushcclosure(L, nranfn, 1);
  return 2;
}

/* ---------------------------------------------------------------------- */
/* Successor templates for lsys.produce / lsys.nproduce: modules whose
** parameters are numbers or '?' slots filled in order. */
typedef struct ltemplate {
  uint32_t nmod, npar, nslots;
  uint16_t *code;
  double *val;          /* constant, or the slot number when slot[k] */
  uint8_t *slot;
} ltemplate;

static int template_gc (lua_State *L) {
  ltemplate *t = (ltemplate *)luaL_checkudata(L, 1, TEMPLATE_T);
  LSYS_FREE(t->code);
  t->code = NULL;
  return 0;
}

static ltemplate *newtemplate (lua_State *L) {
  ltemplate *t = (ltemplate *)lua_newuserdatauv(L, sizeof *t, 0);
  memset(t, 0, sizeof *t);
  luaL_setmetatable(L, TEMPLATE_T);
  return t;
}

/* A parameter's text as a finite number: a numeral that strtod reads whole
** ("inf" and "nan" are names here, as in Lua). */
static int numeral (const char *x, size_t len, double *v) {
  char buf[64], *end;
  size_t i = (len > 0 && (x[0] == '+' || x[0] == '-')) ? 1 : 0;
  if (len == 0 || len >= sizeof buf || i >= len ||
      !((x[i] >= '0' && x[i] <= '9') || x[i] == '.'))
    return 0;
  memcpy(buf, x, len);
  buf[len] = '\0';
  *v = strtod(buf, &end);
  return *end == '\0' && isfinite(*v);
}

/*
** Fills 't' from the successor 'r' parsed from 'text': a parameter is a number
** or a slot. With exprs == 0 a slot is '?' (lsys.produce); otherwise every
** parameter that is not a number is an expression (the axiom), one slot per
** distinct text, listed in order in the table at 'exprs' (its keys map the
** texts to their slots). Returns NULL, or the span of a parameter that is
** neither (produce). May raise only on a memory error (then 'r' leaks).
*/
static const lsys_span *filltemplate (lua_State *L, ltemplate *t, const lsys_prule *r,
                                      const char *text, int exprs) {
  size_t k, j, n = r->nmods;
  t->code = (uint16_t *)LSYS_MALLOC(n * sizeof *t->code + r->nparams * (sizeof *t->val + 1) + 16);
  if (t->code == NULL) return NULL;      /* the caller checks t->code */
  t->val = (double *)(void *)((char *)t->code + ((n * sizeof *t->code + 7) & ~(size_t)7));
  t->slot = (uint8_t *)(t->val + r->nparams);
  for (k = 0; k < n; k++) {
    const lsys_pmod *pm = &r->mods[k];
    t->code[k] = LSYS_CODE(pm->sym, pm->np);
    for (j = 0; j < pm->np; j++) {
      const lsys_span *sp = &r->params[pm->first + j];
      const char *x = text + sp->off;
      if (numeral(x, sp->len, &t->val[t->npar])) {
        t->slot[t->npar++] = 0;
        continue;
      }
      if (exprs == 0) {
        if (sp->len != 1 || x[0] != '?') return sp;
        t->slot[t->npar] = 1;
        t->val[t->npar++] = t->nslots++;
        continue;
      }
      lua_pushlstring(L, x, sp->len);     /* the expression's slot, new or seen */
      if (lua_rawget(L, exprs) == LUA_TNUMBER) t->val[t->npar] = lua_tonumber(L, -1);
      else {
        t->val[t->npar] = t->nslots++;
        lua_pushlstring(L, x, sp->len);
        lua_rawseti(L, exprs, (lua_Integer)t->nslots);
        lua_pushlstring(L, x, sp->len);
        lua_pushinteger(L, (lua_Integer)t->nslots - 1);
        lua_rawset(L, exprs);
      }
      lua_pop(L, 1);
      t->slot[t->npar++] = 1;
    }
  }
  t->nmod = (uint32_t)n;
  return NULL;
}

static ltemplate *gettemplate (lua_State *L, lsys_lrules *R, int tidx) {
  size_t len;
  const char *text = luaL_checklstring(L, tidx, &len);
  const lsys_span *bad;
  ltemplate *t;
  lsys_prule r;
  lsys_error e;
  lua_getiuservalue(L, 1, LSYS_RULES_TPL);   /* the cache, keyed by text */
  lua_pushvalue(L, tidx);
  if (lua_rawget(L, -2) == LUA_TUSERDATA &&
      (t = (ltemplate *)lua_touserdata(L, -1))->code != NULL) {   /* not finalized */
    lua_pop(L, 2);
    return t;
  }
  lua_pop(L, 1);
  t = newtemplate(L);
  if (lsys_grammar_rule_parse(&r, text, len, 3, R->m.ab, &R->decl, &e) != LSYS_OK) {
    lsys_grammar_prule_free(&r);
    return (ltemplate *)(intptr_t)luaL_error(L, "produce: %s at character %d in '%s'",
                                              e.msg, (int)e.pos + 1, text);
  }
  bad = filltemplate(L, t, &r, text, 0);
  if (t->code == NULL) { lsys_grammar_prule_free(&r); luaL_error(L, "not enough memory"); }
  if (bad != NULL) {
    lua_pushlstring(L, text + bad->off, bad->len);   /* before the rule is freed */
    lsys_grammar_prule_free(&r);
    luaL_error(L, "produce: parameters in a template are numbers or '?' (got '%s' in '%s')",
               lua_tostring(L, -1), text);
  }
  lsys_grammar_prule_free(&r);
  lua_pushvalue(L, tidx);
  lua_pushvalue(L, -2);
  lua_rawset(L, -4);
  lua_remove(L, -2);
  return t;
}

/*
** rules:axiom(text) -> Template, {expressions} | nil, message, position
** The axiom parsed straight into a template (no table per module): its
** parameters are numbers or expressions, the distinct expression texts listed
** in order; rules:fill(template, values) makes the Lstring.
*/
static int rules_axiom (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  size_t len;
  const char *text = luaL_checklstring(L, 2, &len);
  lsys_prule r;
  lsys_error e;
  ltemplate *t;
  lua_settop(L, 2);
  R = lsysL_checkrules(L, 1);                /* again: converting a number allocates */
  if (lsys_grammar_rule_parse(&r, text, len, 2, R->m.ab, &R->decl, &e) != LSYS_OK) {
    lsys_grammar_prule_free(&r);
    lua_pushnil(L);
    lua_pushstring(L, e.msg);
    lua_pushinteger(L, (lua_Integer)e.pos + 1);
    return 3;
  }
  t = newtemplate(L);                 /* 3 */
  lua_newtable(L);                    /* 4: the expressions */
  filltemplate(L, t, &r, text, 4);
  lsys_grammar_prule_free(&r);
  if (t->code == NULL) return luaL_error(L, "not enough memory");
  return 2;
}

/* rules:kinds(template) -> { name = { np = true, ... }, ... }: the distinct
** module names of the template and their parameter counts */
static int rules_kinds (lua_State *L) {
  const lsys_alphabet *ab = lsysL_checkrules(L, 1)->m.ab;   /* the state's: it outlives R */
  ltemplate *t = (ltemplate *)luaL_checkudata(L, 2, TEMPLATE_T);
  uint8_t *seen = (uint8_t *)lua_newuserdatauv(L, 1u << 13, 0);   /* a bit per code */
  uint32_t k;
  luaL_argcheck(L, t->code != NULL, 2, "the template was finalized");
  memset(seen, 0, 1u << 13);
  lua_newtable(L);
  for (k = 0; k < t->nmod; k++) {           /* the loop allocates: the template is checked */
    uint16_t c;
    luaL_argcheck(L, t->code != NULL, 2, "the template was finalized");
    c = t->code[k];
    if (seen[c >> 3] & (1u << (c & 7))) continue;
    seen[c >> 3] |= (uint8_t)(1u << (c & 7));
    lua_pushstring(L, lsys_alphabet_name(ab, LSYS_CSYM(c)));
    if (lua_rawget(L, -2) != LUA_TTABLE) {
      lua_pop(L, 1);
      lua_newtable(L);
      lua_pushstring(L, lsys_alphabet_name(ab, LSYS_CSYM(c)));
      lua_pushvalue(L, -2);
      lua_rawset(L, -4);
    }
    lua_pushboolean(L, 1);
    lua_rawseti(L, -2, LSYS_CNP(c));
    lua_pop(L, 1);
  }
  return 1;
}

/* rules:fill(template, values) -> Lstring: the template's slots filled from
** the list 'values' (finite numbers) */
static int rules_fill (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  ltemplate *t = (ltemplate *)luaL_checkudata(L, 2, TEMPLATE_T);
  lsys_lstring *s;
  uint32_t k, m, p = 0;
  luaL_checktype(L, 3, LUA_TTABLE);
  luaL_argcheck(L, t->code != NULL, 2, "the template was finalized");
  lua_settop(L, 3);
  s = lsysL_newlstring(L);
  lsysL_setowner(L, 4, 1);
  R = lsysL_checkrules(L, 1);                /* again: a finalizer may have closed them */
  luaL_argcheck(L, t->code != NULL, 2, "the template was finalized");
  if (lsys_lstring_reserve(s, t->nmod, t->npar) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  for (k = 0; k < t->nmod; k++) {
    uint32_t np = LSYS_CNP(t->code[k]);
    s->code[s->n++] = t->code[k];
    for (m = 0; m < np; m++, p++) {
      double x = t->val[p];
      if (t->slot[p]) {
        int ok;
        lua_rawgeti(L, 3, (lua_Integer)x + 1);
        x = lua_tonumberx(L, -1, &ok);
        if (!ok || !isfinite(x))
          return luaL_error(L, "value %d is not a finite number", (int)t->val[p] + 1);
        lua_pop(L, 1);
      }
      s->par[s->npar++] = R->m.f32 ? lsys_round32(x) : x;
    }
  }
  return 1;
}

/* lsys.produce(template, ...) and lsys.nproduce(template, ...) */
static int produce (lua_State *L, int final) {
  lsys_lrules *R;
  ltemplate *t;
  uint32_t k, m, p = 0;
  int nargs = lua_gettop(L) - 1;
  if (lua_getfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING) != LUA_TUSERDATA ||
      (R = (lsys_lrules *)luaL_testudata(L, -1, RULES_T)) == NULL || !R->inited ||
      R->m.cur_rule < 0 || !(R->m.rules[R->m.cur_rule].flags & LSYS_RF_DYN))
    return luaL_error(L, "%s called outside a rule function", final ? "produce" : "nproduce");
  lua_insert(L, 1);                  /* rules at 1, template at 2, args 3.. */
  t = gettemplate(L, R, 2);
  if ((int)t->nslots != nargs)
    return luaL_error(L, "%s: the template '%s' has %d '?' but %d values were given",
                      final ? "produce" : "nproduce", lua_tostring(L, 2), (int)t->nslots, nargs);
  for (k = 0; k < t->nslots; k++) {
    lua_Number x;
    if (lua_type(L, 3 + (int)k) != LUA_TNUMBER)
      return luaL_error(L, "produce: value %d is %s, not a number", (int)k + 1,
                        luaL_typename(L, 3 + (int)k));
    x = lua_tonumber(L, 3 + (int)k);
    if (!isfinite(x)) return luaL_error(L, "produce: value %d is not a finite number", (int)k + 1);
  }
  if (R->m.dyn.n + t->nmod > R->m.max_modules)
    return luaL_error(L, "produce: the successor would exceed max_modules");
  if (lsys_lstring_reserve(&R->m.dyn, t->nmod, t->npar) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  for (k = 0; k < t->nmod; k++) {
    uint32_t np = LSYS_CNP(t->code[k]);
    R->m.dyn.code[R->m.dyn.n++] = t->code[k];
    for (m = 0; m < np; m++, p++)
      R->m.dyn.par[R->m.dyn.npar++] = t->slot[p] ? lua_tonumber(L, 3 + (int)t->val[p]) : t->val[p];
  }
  if (final) R->produced = 1;
  lua_pushboolean(L, 1);
  return 1;
}

/* lsys.ran(x) / lsys.nran(m, sd) inside rule functions: the generator of
** the model deriving now */
static lsys_lrules *deriving (lua_State *L, const char *what) {
  lsys_lrules *R = NULL;
  if (lua_getfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING) != LUA_TUSERDATA ||
      (R = (lsys_lrules *)luaL_testudata(L, -1, RULES_T)) == NULL || !R->inited)
    luaL_error(L, "%s called outside a derivation (use it in a rule function)", what);
  lua_pop(L, 1);
  return R;
}

static int l_ran (lua_State *L) {
  lsys_lrules *R = deriving(L, "ran");
  lua_pushnumber(L, luaL_optnumber(L, 1, 1) * lsys_rng_uniform(R->m.cur));
  return 1;
}

/* core.cpfg_try(): the mark of a weighted rule in Lua (lsys_derive_cpfg_mark): true
** when the rule is tried under cpfg's generator and is to return now */
static int l_cpfg_try (lua_State *L) {
  lsys_lrules *R = deriving(L, "cpfg_try");
  lua_pushboolean(L, lsys_derive_cpfg_mark(&R->m));
  return 1;
}

/* core.cpfg_resume(): lsys_derive_cpfg_resume */
static int l_cpfg_resume (lua_State *L) {
  lsys_lrules *R = deriving(L, "cpfg_resume");
  lua_pushboolean(L, lsys_derive_cpfg_resume(&R->m));
  return 1;
}

static int l_srand (lua_State *L) {
  lsys_lrules *R = deriving(L, "srand");
  lsys_rng_reseed(R->m.cur, seedof(L, 1));
  return 0;
}

/* core.names_mark() -> the number of module names in the state's alphabet;
** core.names_truncate(n): forgets the names interned since (lsys.lsystem, when
** the model it was making failed: no object refers to them) */
static int l_names_mark (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsysL_getalphabet(L)->n);
  return 1;
}

static int l_names_truncate (lua_State *L) {
  lua_Integer n = luaL_checkinteger(L, 1);
  luaL_argcheck(L, n >= LSYS_SYM_FIRSTFREE && n <= LSYS_MAXSYM + 1, 1, "bad mark");
  lsys_alphabet_truncate(lsysL_getalphabet(L), (uint32_t)n);
  return 0;
}

static int l_nran (lua_State *L) {
  lsys_lrules *R = deriving(L, "nran");
  lua_Number mu = luaL_checknumber(L, 1), sd = luaL_checknumber(L, 2);
  lua_pushnumber(L, lsys_rng_normal(R->m.cur, mu, sd));
  return 1;
}

/* core.max_memory([bytes]) -> the process-wide memory budget in bytes (with
** an argument, sets it first; 0: back to the default, half the physical
** memory), the physical memory */
static int l_max_memory (lua_State *L) {
  if (!lua_isnoneornil(L, 1)) {
    lua_Number x = luaL_checknumber(L, 1);
    luaL_argcheck(L, x >= 0 && x < 1.8e19, 1, "a number of bytes >= 0 expected");
    lsys_common_set_memory_limit(x >= (double)((size_t)-1) ? (size_t)-1 : (size_t)x);
  }
  lua_pushnumber(L, (lua_Number)lsys_common_memory_limit());
  lua_pushnumber(L, (lua_Number)lsys_common_physical_memory());
  return 2;
}

/* core.producing([v]): the rules deriving now; with an argument, sets it
** (the Lua side restores it after a step that raised) */
static int l_producing (lua_State *L) {
  lua_getfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING);
  if (lua_gettop(L) > 1) {
    lua_pushvalue(L, 1);
    lua_setfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING);
  }
  return 1;
}

static int l_produce (lua_State *L) { return produce(L, 1); }
static int l_nproduce (lua_State *L) { return produce(L, 0); }

/* rules:functions() -> the table of the rules' Lua functions, which lsys.model fills
** (entry k: the function of the rules whose function index is k) and the callbacks of
** a derivation call; the table itself, not a copy. */
static int rules_functions (lua_State *L) {
  lsysL_checkrules(L, 1);
  lua_getiuservalue(L, 1, LSYS_RULES_FNS);
  return 1;
}

static const luaL_Reg rules_methods[] = {
  {"parse", rules_parse}, {"add", rules_add}, {"skiplist", rules_skiplist},
  {"config", rules_config}, {"size", rules_size}, {"step", rules_step},
  {"advance", rules_advance},
  {"expand", rules_expand}, {"current", rules_current}, {"lstring", rules_lstring},
  {"ran", rules_ran}, {"srand", rules_srand},
  {"setvm", rules_setvm}, {"newset", rules_newset}, {"hasvm", rules_hasvm},
  {"setfuncs", rules_setfuncs},
  {"busy", rules_busy}, {"axiom", rules_axiom}, {"fill", rules_fill},
  {"kinds", rules_kinds}, {"functions", rules_functions}, {NULL, NULL}
};

static const luaL_Reg rules_meta[] = {
  {"__index", NULL}, {"__gc", rules_gc}, {"__close", rules_gc}, {NULL, NULL}
};

static const luaL_Reg core_funcs[] = {
  {"rules", l_rules}, {"produce", l_produce}, {"nproduce", l_nproduce},
  {"ran", l_ran}, {"nran", l_nran}, {"srand", l_srand}, {"cpfg_try", l_cpfg_try},
  {"cpfg_resume", l_cpfg_resume},
  {"producing", l_producing}, {"max_memory", l_max_memory},
  {"names_mark", l_names_mark}, {"names_truncate", l_names_truncate},
  {NULL, NULL}
};

static const luaL_Reg template_meta[] = {
  {"__gc", template_gc}, {NULL, NULL}
};

/* The rule-set constants of lsys.core (derive.h). */
static void setconstants (lua_State *L) {
  lua_pushinteger(L, LSYS_MAXPARAMS);
  lua_setfield(L, -2, "MAXPARAMS");
  lua_pushinteger(L, LSYS_MAXTHREADS);
  lua_setfield(L, -2, "MAXTHREADS");
  lua_pushinteger(L, LSYS_RF_CALL); lua_setfield(L, -2, "RF_CALL");
  lua_pushinteger(L, LSYS_RF_DYN); lua_setfield(L, -2, "RF_DYN");
  lua_pushinteger(L, LSYS_RF_STOCH); lua_setfield(L, -2, "RF_STOCH");
  lua_pushinteger(L, LSYS_RF_WEXPR); lua_setfield(L, -2, "RF_WEXPR");
}

void lsysL_open_rules (lua_State *L) {
  lsysL_createmeta(L, RULES_T, rules_meta, rules_methods);
  lsysL_createmeta(L, TEMPLATE_T, template_meta, NULL);
  luaL_setfuncs(L, core_funcs, 0);
  setconstants(L);
}
