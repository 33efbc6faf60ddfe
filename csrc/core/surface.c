/*
** Bicubic surfaces: the cpfg surface file reader, patch evaluation in the
** three bases of the cpfg guide's Appendix A, and tessellation into the mesh.
**
** The surface file (".s", written by the vlab/L-studio surface editors and
** read by cpfg for ~X) is line oriented. Words and numbers are separated by
** blanks; a word ending in ':' is a label and may be glued to the number
** after it ("X:1.5"). Blank lines are skipped. In order:
**
**   xmin xmax ymin ymax zmin zmax         a bounding box: six numbers. The
**                                         editors write it; cpfg does not use
**                                         it and neither does lsys (checked only)
**   PRECISION S: s T: t                   optional: lines per patch along s and
**                                         t, integers 1..256 (default 5 and 5,
**                                         cpfg's middle value)
**   CONTACT POINT X: x Y: y Z: z          P_S, the point put at the turtle
**   END POINT X: x Y: y Z: z              where the turtle goes afterwards
**   HEADING X: x Y: y Z: z                H_S, turned onto the turtle's H
**   UP X: x Y: y Z: z                     U_S, turned onto the turtle's U
**   SIZE: size                            the surface's reference size,
**                                         1e-30 .. 1e30
**
** then one or more patches (at most LSYS_SURFACE_MAXPATCHES), each:
**
**   name                                  one word, at most 63 bytes
**   TOP COLOR: c DIFFUSE: d BOTTOM COLOR: c DIFFUSE: d
**                                         colour indices (integers 0..65535)
**                                         and diffuse factors of the two sides;
**                                         cpfg uses them only in its old
**                                         colour-map shading, lsys keeps them
**   AL: n A: n AR: n                      names of the neighbour patches above
**   L: n R: n                             left, on each side, and below; '~'
**   BL: n B: n BR: n                      is none
**   four lines of 12 numbers              row r = 0..3 of control points:
**                                         x y z of columns 0, 1, 2, 3
**
** The patches are Bézier patches. "Above" is the side of row 0: a patch
** named as A shares its row 3 with this patch's row 0; L shares its column
** 3 with this patch's column 0; the corners likewise. Every neighbour must
** exist and name this patch back in the opposite direction (cpfg rejects
** such files too); the shared edges get averaged normals.
**
** Numbers must be finite and within +-LSYS_SURFACE_MAXCOORD; HEADING must
** not be zero; UP must not be zero or parallel to HEADING. Both are
** normalised and UP is made orthogonal to HEADING (the files hold two
** decimals, so they are rarely exact).
**
** Placement: cpfg (and lpfg) divide the coordinates by SIZE, so the scale
** given to a surface in the view is the size it is drawn at; lsys does the
** same: x -> origin + (scale / SIZE) R (x - P_S). R turns H_S onto H, U_S
** onto U and H_S x U_S onto L. (cpfg composes the turtle's frame with the
** file frame instead of its inverse; the two agree for the usual files
** with H_S on the y axis and U_S on the z axis, and lsys follows the
** guide's words for the others.)
**
** Evaluation: P(s, t) = T M G M^T S^T (surface.h); s runs across columns,
** t across rows (as the editors' OpenGL evaluators; cpfg's own s runs
** across rows, so its per-patch texture is the transpose of ours).
*/
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"
#include "vec3.h"

/* ------------------------------------------------------------------ */
/* Evaluation                                                           */
/* ------------------------------------------------------------------ */

/* Basis matrices M: the weights of the four control points at u are
** [u^3 u^2 u 1] M. */
static const double MBEZIER[4][4] = {
  {-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}
};
static const double MBSPLINE[4][4] = {
  {-1.0 / 6, 3.0 / 6, -3.0 / 6, 1.0 / 6}, {3.0 / 6, -6.0 / 6, 3.0 / 6, 0},
  {-3.0 / 6, 0, 3.0 / 6, 0}, {1.0 / 6, 4.0 / 6, 1.0 / 6, 0}
};
/* Catmull-Rom (cardinal spline of tension 0.5): interpolates points 1 and 2. */
static const double MCARDINAL[4][4] = {
  {-0.5, 1.5, -1.5, 0.5}, {1, -2.5, 2, -0.5}, {-0.5, 0, 0.5, 0}, {0, 1, 0, 0}
};

static const double (*basismatrix (int basis))[4] {
  switch (basis) {
    case LSYS_BASIS_BSPLINE: return MBSPLINE;
    case LSYS_BASIS_CARDINAL: return MCARDINAL;
    default: return MBEZIER;
  }
}

/* Weights w and their derivatives dw of the four control points at u. */
static void weights (const double M[4][4], double u, double w[4], double dw[4]) {
  const double pw[4] = {u * u * u, u * u, u, 1}, dp[4] = {3 * u * u, 2 * u, 1, 0};
  int c, k;
  for (c = 0; c < 4; c++) {
    w[c] = dw[c] = 0;
    for (k = 0; k < 4; k++) {
      w[c] += pw[k] * M[k][c];
      dw[c] += dp[k] * M[k][c];
    }
  }
}

void lsys_surface_patch_eval (int basis, const lsys_patch *p, double s, double t, double pos[3],
                              double ds[3], double dt[3]) {
  const double (*M)[4] = basismatrix(basis);
  double ws[4], dws[4], wt[4], dwt[4], P[3] = {0, 0, 0}, S[3] = {0, 0, 0}, T[3] = {0, 0, 0};
  int r, c, k;
  weights(M, s, ws, dws);
  weights(M, t, wt, dwt);
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) {
      const double *g = p->ctrl + 3 * (4 * r + c);
      double a = wt[r] * ws[c], b = wt[r] * dws[c], d = dwt[r] * ws[c];
      for (k = 0; k < 3; k++) {
        P[k] += a * g[k];
        S[k] += b * g[k];
        T[k] += d * g[k];
      }
    }
  vcopy(pos, P);
  if (ds != NULL) vcopy(ds, S);
  if (dt != NULL) vcopy(dt, T);
}

/* ------------------------------------------------------------------ */
/* The reader                                                           */
/* ------------------------------------------------------------------ */

void lsys_surface_init (lsys_surface *s) {
  *s = (lsys_surface){0};
  s->basis = LSYS_BASIS_BEZIER;
  s->size = 1;
  s->heading[1] = 1;
  s->up[2] = 1;
  s->precision_s = s->precision_t = 5;
}

void lsys_surface_free (lsys_surface *s) {
  LSYS_FREE(s->patch);
  LSYS_FREE(s->info);
  lsys_surface_init(s);
}

typedef struct reader {
  const char *text;
  const char *p, *end;     /* the unread text */
  const char *lp, *le;     /* the current line, without its newline */
  const char *tp;          /* the rest of the current line */
  size_t line;             /* the current line's number (1-based) */
  const char *name;
  lsys_error *e;
} reader;

static int isblank_ (char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* Moves to the next line that is not blank; returns 0 at the end (then
** r->line is the number of lines). */
static int nextline (reader *r) {
  while (r->p < r->end) {
    const char *nl = (const char *)memchr(r->p, '\n', (size_t)(r->end - r->p));
    r->lp = r->tp = r->p;
    r->le = nl != NULL ? nl : r->end;
    r->p = nl != NULL ? nl + 1 : r->end;
    r->line++;
    while (r->tp < r->le && isblank_(*r->tp)) r->tp++;
    if (r->tp < r->le) return 1;
  }
  r->lp = r->le = r->tp = r->end;
  return 0;
}

/* The next word of the line: blank-separated, and ending after a ':'. */
static int word (reader *r, const char **w, size_t *n) {
  const char *q = r->tp;
  while (q < r->le && isblank_(*q)) q++;
  if (q == r->le) {
    r->tp = q;
    return 0;
  }
  *w = q;
  while (q < r->le && !isblank_(*q))
    if (*q++ == ':') break;
  *n = (size_t)(q - *w);
  r->tp = q;
  return 1;
}

/* A printable copy of a word for messages (lsys_common_quote: a short token). */
static const char *quote (char buf[32], const char *w, size_t n) {
  return lsys_common_quote(buf, w, n);
}

/* The same for a patch name read from the file. */
static const char *qname (char buf[32], const char *name) {
  return lsys_common_quote(buf, name, strlen(name));
}

/* Fails with "name:LINE: message" (common.h); the error position is the
** line's byte offset. */
static int fail (reader *r, size_t line, const char *fmt, ...) {
  va_list ap;
  int code;
  va_start(ap, fmt);
  code = lsys_vseterror_line(r->e, LSYS_ESYNTAX, (size_t)(r->lp - r->text), r->name, line,
                             fmt, ap);
  va_end(ap);
  return code;
}

static int lower (char c) {
  return (c >= 'A' && c <= 'Z') ? c - 'A' + 'a' : c;
}

/* Whether w is nan or inf(inity), with an optional sign, in any case. */
static int nonfinite (const char *w, size_t n) {
  static const char *const names[] = {"nan", "inf", "infinity"};
  size_t i, k;
  if (n > 0 && (*w == '+' || *w == '-')) { w++; n--; }
  for (k = 0; k < 3; k++) {
    if (strlen(names[k]) != n) continue;
    for (i = 0; i < n && lower(w[i]) == names[k][i]; i++) {}
    if (i == n) return 1;
  }
  return 0;
}

/*
** Reads a number: [+-] digits [. digits] [e [+-] digits], with at least
** one digit before the exponent. 'what' names the line for messages.
*/
static int number (reader *r, const char *w, size_t n, const char *what, double *x) {
  char buf[64], q[32];
  char *end;
  size_t i = 0, digits = 0;
  if (n > 0 && (w[0] == '+' || w[0] == '-')) i++;
  for (; i < n && w[i] >= '0' && w[i] <= '9'; i++) digits++;
  if (i < n && w[i] == '.')
    for (i++; i < n && w[i] >= '0' && w[i] <= '9'; i++) digits++;
  if (digits > 0 && i < n && (w[i] == 'e' || w[i] == 'E')) {
    size_t ed = 0;
    i++;
    if (i < n && (w[i] == '+' || w[i] == '-')) i++;
    for (; i < n && w[i] >= '0' && w[i] <= '9'; i++) ed++;
    if (ed == 0) digits = 0;
  }
  if (nonfinite(w, n))
    return fail(r, r->line, "bad %s line: '%s' is not a finite number", what, quote(q, w, n));
  if (digits == 0 || i != n || n >= sizeof buf)
    return fail(r, r->line, "bad %s line: '%s' is not a number", what, quote(q, w, n));
  memcpy(buf, w, n);
  buf[n] = '\0';
  *x = strtod(buf, &end);
  if (end != buf + n)
    return fail(r, r->line, "bad %s line: '%s' is not a number", what, quote(q, w, n));
  if (!(fabs(*x) <= LSYS_SURFACE_MAXCOORD))
    return fail(r, r->line, "bad %s line: '%s' is out of range (limit 1e30)", what,
                quote(q, w, n));
  return LSYS_OK;
}

/* How a pattern item is shown in messages. */
static void showitem (char *out, size_t size, const char *it, size_t n) {
  if (n == 2 && it[0] == '%')
    snprintf(out, size, "%s", it[1] == 's' ? "a name" : it[1] == 'd' ? "an integer"
                                                                    : "a number");
  else snprintf(out, size, "'%.*s'", (int)n, it);
}

/* The pattern as shown in messages: %f and %d as 'n', %s as 'name'. */
static void showpattern (char *out, size_t size, const char *pat) {
  size_t k = 0;
  while (*pat && k + 5 < size) {
    if (pat[0] == '%' && pat[1] != '\0') {
      const char *sub = pat[1] == 's' ? "name" : "n";
      while (*sub && k + 1 < size) out[k++] = *sub++;
      pat += 2;
    }
    else out[k++] = *pat++;
  }
  out[k] = '\0';
}


/*
** Reads the current line against 'pat': items separated by single spaces,
** each a label to match, or %f (a number, into the next num[]), %d (an
** integer, likewise) or %s (a name: its word goes to the next nw[], its
** length to nn[]). 'what' names the line in messages.
*/
static int scan (reader *r, const char *what, const char *pat, double *num,
                 const char **nw, size_t *nn) {
  const char *it = pat, *w = NULL;
  char q[32], shown[96];
  size_t n = 0;
  int first = 1;
  while (*it) {
    const char *sp = strchr(it, ' ');
    size_t ilen = sp != NULL ? (size_t)(sp - it) : strlen(it);
    int have = word(r, &w, &n), isvar = ilen == 2 && it[0] == '%';
    if (have && isvar) {
      if (it[1] == 's') { *nw++ = w; *nn++ = n; }
      else {
        int st = number(r, w, n, what, num);
        if (st != LSYS_OK) return st;
        if (it[1] == 'd' && *num != floor(*num))
          return fail(r, r->line, "bad %s line: '%s' is not an integer", what, quote(q, w, n));
        num++;
      }
    }
    else if (!have || n != ilen || memcmp(w, it, n) != 0) {
      char exp[48];
      if (have && first) {
        showpattern(shown, sizeof shown, pat);
        return fail(r, r->line, "expected '%s', found '%s'", shown, quote(q, w, n));
      }
      showitem(exp, sizeof exp, it, ilen);
      if (!have) return fail(r, r->line, "bad %s line: expected %s, found end of line", what, exp);
      return fail(r, r->line, "bad %s line: expected %s, found '%s'", what, exp, quote(q, w, n));
    }
    first = 0;
    it += ilen;
    if (*it == ' ') it++;
  }
  if (word(r, &w, &n))
    return fail(r, r->line, "bad %s line: unexpected '%s' at the end", what, quote(q, w, n));
  return LSYS_OK;
}

/* Moves to the next line, which must exist: 'pat' is what was expected
** there, 'patch' the patch being read (NULL in the header). */
static int need (reader *r, const char *pat, const char *patch) {
  char shown[96], q[32];
  if (nextline(r)) return LSYS_OK;
  showpattern(shown, sizeof shown, pat);
  if (patch != NULL)
    return fail(r, r->line + 1, "patch '%s' ends early: expected '%s'", qname(q, patch), shown);
  return fail(r, r->line + 1, "expected '%s', found the end of the file", shown);
}

/* Reads the next line against 'pat' (numbers only) into v. */
static int vecline (reader *r, const char *what, const char *pat, double *v) {
  int st = need(r, pat, NULL);
  return st != LSYS_OK ? st : scan(r, what, pat, v, NULL, NULL);
}

/* A neighbour reference as read: a word of the text and its line. */
typedef struct nbref {
  const char *w[8];
  size_t n[8];
  size_t line[8];
} nbref;

static int growpatches (lsys_surface *s, nbref **ref, size_t *cap, size_t *rcap) {
  size_t c = *cap;
  if (lsys_common_grow((void **)&s->patch, &c, s->npatch + 1, sizeof *s->patch) != LSYS_OK)
    return LSYS_ENOMEM;
  c = *cap;
  if (lsys_common_grow((void **)&s->info, &c, s->npatch + 1, sizeof *s->info) != LSYS_OK)
    return LSYS_ENOMEM;
  c = *cap;
  if (lsys_common_grow((void **)ref, rcap, s->npatch + 1, sizeof **ref) != LSYS_OK)
    return LSYS_ENOMEM;
  *cap = c;
  return LSYS_OK;
}

/* One patch: its name is the current line. */
static int readpatch (reader *r, lsys_surface *s, nbref *ref) {
  static const char *const rows[3] = {"AL: %s A: %s AR: %s", "L: %s R: %s",
                                      "BL: %s B: %s BR: %s"};
  static const int first[3] = {LSYS_NB_AL, LSYS_NB_L, LSYS_NB_BL};
  lsys_patch *p = &s->patch[s->npatch];
  lsys_patchinfo *in = &s->info[s->npatch];
  const char *w;
  char q[32];
  size_t n, k;
  double v[12];
  int st, i, row;
  memset(in, 0, sizeof *in);
  memset(ref, 0, sizeof *ref);
  for (k = 0; k < 8; k++) in->nb[k] = -1;
  word(r, &w, &n);
  if (n >= LSYS_SURFACE_NAMELEN)
    return fail(r, r->line, "patch name '%s' is longer than %d bytes", quote(q, w, n),
                LSYS_SURFACE_NAMELEN - 1);
  for (k = 0; k < n; k++)
    if ((unsigned char)w[k] < 32 || w[k] == 127)
      return fail(r, r->line, "patch name '%s' has a control character", quote(q, w, n));
  memcpy(in->name, w, n);
  in->name[n] = '\0';
  if (word(r, &w, &n)) {
    const char *a = r->lp, *z = r->le;
    while (isblank_(*a)) a++;
    while (isblank_(z[-1])) z--;
    return fail(r, r->line, "expected a patch name (one word), found '%s'",
                quote(q, a, (size_t)(z - a)));
  }
  /* colours */
  if ((st = need(r, "TOP COLOR: %d DIFFUSE: %f BOTTOM COLOR: %d DIFFUSE: %f", in->name)) ||
      (st = scan(r, "TOP COLOR", "TOP COLOR: %d DIFFUSE: %f BOTTOM COLOR: %d DIFFUSE: %f", v,
                 NULL, NULL)))
    return st;
  for (i = 0; i < 2; i++) {
    if (v[2 * i] < 0 || v[2 * i] > 65535)
      return fail(r, r->line, "%s COLOR must be from 0 to 65535, not %g", i ? "BOTTOM" : "TOP",
                  v[2 * i]);
    in->color[i] = (int)v[2 * i];
    in->diffuse[i] = v[2 * i + 1];
  }
  /* neighbours: names for now, resolved when all patches are known */
  for (row = 0; row < 3; row++) {
    int d = first[row], cnt = row == 1 ? 2 : 3;
    if ((st = need(r, rows[row], in->name)) ||
        (st = scan(r, "neighbour", rows[row], NULL, ref->w + d, ref->n + d)))
      return st;
    for (i = 0; i < cnt; i++) ref->line[d + i] = r->line;
  }
  /* control points */
  for (row = 0; row < 4; row++) {
    char what[32], q[32];
    int cnt = 0;
    if (!nextline(r))
      return fail(r, r->line + 1, "patch '%s' ends early: expected row %d of control points",
                  qname(q, in->name), row);
    snprintf(what, sizeof what, "control point row %d", row);
    while (word(r, &w, &n)) {
      if (cnt == 12)
        return fail(r, r->line, "row %d of patch '%s' has more than 12 numbers", row,
                    qname(q, in->name));
      if ((st = number(r, w, n, what, &v[cnt])) != LSYS_OK) return st;
      cnt++;
    }
    if (cnt < 12)
      return fail(r, r->line,
                  "row %d of patch '%s' has %d numbers, expected 12 (x y z of 4 points)", row,
                  qname(q, in->name), cnt);
    memcpy(p->ctrl + 12 * row, v, sizeof v);
  }
  return LSYS_OK;
}

static uint32_t hashname (const char *w, size_t n) {
  uint32_t h = 2166136261u;
  while (n-- > 0) h = (h ^ (unsigned char)*w++) * 16777619u;
  return h;
}

static const char *const nbnames[8] = {"AL", "A", "AR", "L", "R", "BL", "B", "BR"};

/* Turns neighbour names into patch indices (the first patch of a name)
** and checks that every neighbour names the patch back. */
static int linkpatches (reader *r, lsys_surface *s, const nbref *ref) {
  size_t size = 16, mask, i, h;
  int32_t *tab;
  int d, st = LSYS_OK;
  char q[32], q2[32];
  while (size < 2 * s->npatch) size *= 2;
  mask = size - 1;
  tab = (int32_t *)LSYS_MALLOC(size * sizeof *tab);
  if (tab == NULL) return lsys_seterror(r->e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  for (i = 0; i < size; i++) tab[i] = -1;
  for (i = 0; i < s->npatch; i++) {
    const char *nm = s->info[i].name;
    for (h = hashname(nm, strlen(nm)) & mask; tab[h] >= 0; h = (h + 1) & mask)
      if (strcmp(s->info[tab[h]].name, nm) == 0) break;
    if (tab[h] < 0) tab[h] = (int32_t)i;
  }
  for (i = 0; i < s->npatch && st == LSYS_OK; i++)
    for (d = 0; d < 8 && st == LSYS_OK; d++) {
      const char *w = ref[i].w[d];
      size_t n = ref[i].n[d];
      if (n == 1 && w[0] == '~') continue;
      for (h = hashname(w, n) & mask; tab[h] >= 0; h = (h + 1) & mask) {
        const char *nm = s->info[tab[h]].name;
        if (strlen(nm) == n && memcmp(nm, w, n) == 0) break;
      }
      if (tab[h] < 0)
        st = fail(r, ref[i].line[d], "patch '%s': no patch named '%s' (its %s neighbour)",
                  qname(q2, s->info[i].name), quote(q, w, n), nbnames[d]);
      else s->info[i].nb[d] = tab[h];
    }
  for (i = 0; i < s->npatch && st == LSYS_OK; i++)
    for (d = 0; d < 8 && st == LSYS_OK; d++) {
      int j = s->info[i].nb[d], back;
      if (j < 0) continue;
      back = s->info[j].nb[7 - d];
      if (back < 0 || strcmp(s->info[back].name, s->info[i].name) != 0) {
        char a[32], b[32], c[32];
        st = fail(r, ref[i].line[d],
                  "patch '%s' has '%s' as its %s neighbour, but '%s' has %s%s%s as its %s",
                  qname(a, s->info[i].name), qname(b, s->info[j].name), nbnames[d],
                  qname(b, s->info[j].name), back < 0 ? "" : "'",
                  back < 0 ? "none" : qname(c, s->info[back].name),
                  back < 0 ? "" : "'", nbnames[7 - d]);
      }
    }
  LSYS_FREE(tab);
  return st;
}

/* Header lines: bounding box to SIZE. */
static int readheader (reader *r, lsys_surface *s) {
  double v[6];
  int st, k;
  size_t hline;
  if ((st = need(r, "%f %f %f %f %f %f", NULL)) != LSYS_OK ||
      (st = scan(r, "bounding box", "%f %f %f %f %f %f", v, NULL, NULL)) != LSYS_OK)
    return st;
  if ((st = need(r, "CONTACT POINT X: %f Y: %f Z: %f", NULL)) != LSYS_OK) return st;
  if (r->le - r->tp >= 9 && memcmp(r->tp, "PRECISION", 9) == 0) {
    const char *what[2] = {"S", "T"};
    if ((st = scan(r, "PRECISION", "PRECISION S: %d T: %d", v, NULL, NULL)) != LSYS_OK)
      return st;
    for (k = 0; k < 2; k++)
      if (v[k] < 1 || v[k] > LSYS_SURFACE_MAXDIV)
        return fail(r, r->line, "PRECISION %s must be from 1 to %d, not %g", what[k],
                    LSYS_SURFACE_MAXDIV, v[k]);
    s->precision_s = (int)v[0];
    s->precision_t = (int)v[1];
    if ((st = need(r, "CONTACT POINT X: %f Y: %f Z: %f", NULL)) != LSYS_OK) return st;
  }
  if ((st = scan(r, "CONTACT POINT", "CONTACT POINT X: %f Y: %f Z: %f", s->contact, NULL,
                 NULL)) != LSYS_OK ||
      (st = vecline(r, "END POINT", "END POINT X: %f Y: %f Z: %f", s->end)) != LSYS_OK ||
      (st = vecline(r, "HEADING", "HEADING X: %f Y: %f Z: %f", s->heading)) != LSYS_OK)
    return st;
  hline = r->line;
  if (!(vlen(s->heading) > 1e-12)) return fail(r, hline, "HEADING is the zero vector");
  vnorm(s->heading);
  if ((st = vecline(r, "UP", "UP X: %f Y: %f Z: %f", s->up)) != LSYS_OK) return st;
  {
    double l = vlen(s->up), perp;
    if (!(l > 1e-12)) return fail(r, r->line, "UP is the zero vector");
    vlin(s->up, s->up, 1, s->heading, -vdot(s->up, s->heading));
    perp = vlen(s->up);
    if (!(perp > 1e-6 * l)) return fail(r, r->line, "UP is parallel to HEADING");
    vnorm(s->up);
  }
  if ((st = vecline(r, "SIZE", "SIZE: %f", &s->size)) != LSYS_OK) return st;
  if (!(s->size >= 1e-30))
    return fail(r, r->line, "SIZE must be from 1e-30 to 1e30, not %g", s->size);
  return LSYS_OK;
}

/* The bounds of the control points into s->lo, s->hi. */
static void setbounds (lsys_surface *s) {
  size_t i;
  int k;
  for (k = 0; k < 3; k++) {
    s->lo[k] = HUGE_VAL;
    s->hi[k] = -HUGE_VAL;
  }
  for (i = 0; i < s->npatch; i++) {
    const double *c = s->patch[i].ctrl;
    int j;
    for (j = 0; j < 48; j++) {
      if (c[j] < s->lo[j % 3]) s->lo[j % 3] = c[j];
      if (c[j] > s->hi[j % 3]) s->hi[j % 3] = c[j];
    }
  }
}

int lsys_surface_parse (lsys_surface *s, const char *text, size_t len, const char *name,
                        lsys_error *e) {
  reader r;
  nbref *ref = NULL;
  size_t cap = 0, rcap = 0;
  int st;
  lsys_surface_init(s);
  r.text = r.p = r.lp = r.le = r.tp = text != NULL ? text : "";
  r.end = r.p + (text != NULL ? len : 0);
  r.line = 0;
  r.name = name != NULL ? name : "?";
  r.e = e;
  st = readheader(&r, s);
  while (st == LSYS_OK && nextline(&r)) {
    if (s->npatch == LSYS_SURFACE_MAXPATCHES) {
      st = fail(&r, r.line, "too many patches (limit is %d)", LSYS_SURFACE_MAXPATCHES);
      break;
    }
    if (growpatches(s, &ref, &cap, &rcap) != LSYS_OK) {
      st = lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
      break;
    }
    st = readpatch(&r, s, &ref[s->npatch]);
    if (st == LSYS_OK) s->npatch++;
  }
  if (st == LSYS_OK && s->npatch == 0)
    st = fail(&r, r.line + 1, "expected a patch, found the end of the file");
  if (st == LSYS_OK) st = linkpatches(&r, s, ref);
  LSYS_FREE(ref);
  if (st != LSYS_OK) {
    lsys_surface_free(s);
    return st;
  }
  setbounds(s);
  return LSYS_OK;
}

/* ------------------------------------------------------------------ */
/* Editing and writing                                                  */
/* ------------------------------------------------------------------ */

int lsys_surface_with_points (lsys_surface *dst, const lsys_surface *s, const double *pt,
                              lsys_error *e) {
  size_t i, n = s->npatch;
  lsys_patch *patch;
  lsys_patchinfo *info;
  for (i = 0; i < 48 * n; i++)
    if (!(fabs(pt[i]) <= LSYS_SURFACE_MAXCOORD))       /* also NaN */
      return lsys_seterror(e, LSYS_EARG, i, "point %zu: coordinate %d is %s", i / 3 + 1,
                           (int)(i % 3) + 1, isfinite(pt[i]) ? "out of range (limit is 1e30)"
                                                              : "not finite");
  patch = (lsys_patch *)LSYS_MALLOC((n ? n : 1) * sizeof *patch);
  info = (lsys_patchinfo *)LSYS_MALLOC((n ? n : 1) * sizeof *info);
  if (patch == NULL || info == NULL) {
    LSYS_FREE(patch);
    LSYS_FREE(info);
    return lsys_seterror(e, LSYS_ENOMEM, 0, "not enough memory");
  }
  for (i = 0; i < n; i++) {
    memcpy(patch[i].ctrl, pt + 48 * i, sizeof patch[i].ctrl);
    info[i] = s->info[i];
  }
  lsys_surface_free(dst);
  *dst = *s;
  dst->patch = patch;
  dst->info = info;
  setbounds(dst);
  return LSYS_OK;
}


size_t lsys_surface_format (const lsys_surface *s, char *buf, size_t size) {
  static const char *const vecs[4] = {"CONTACT POINT", "END POINT", "HEADING", "UP"};
  static const char *const nbs[8] = {"AL", "A", "AR", "L", "R", "BL", "B", "BR"};
  const double *v[4];
  size_t len = 0, i;
  char a[3][32];
  int w, k, d;
#define PUT(...) do { w = snprintf(len < size ? buf + len : NULL, len < size ? size - len : 0, \
                                   __VA_ARGS__); if (w > 0) len += (size_t)w; } while (0)
  v[0] = s->contact; v[1] = s->end; v[2] = s->heading; v[3] = s->up;
  for (k = 0; k < 3; k++) {
    lsys_common_shortest(a[0], s->lo[k]);
    lsys_common_shortest(a[1], s->hi[k]);
    PUT("%s%s %s", k ? "  " : "", a[0], a[1]);
  }
  PUT("\nPRECISION S: %d T: %d\n", s->precision_s, s->precision_t);
  for (k = 0; k < 4; k++) {
    for (d = 0; d < 3; d++) lsys_common_shortest(a[d], v[k][d]);
    PUT("%s X: %s Y: %s Z: %s\n", vecs[k], a[0], a[1], a[2]);
  }
  lsys_common_shortest(a[0], s->size);
  PUT("SIZE: %s\n", a[0]);
  for (i = 0; i < s->npatch; i++) {
    const lsys_patchinfo *in = &s->info[i];
    lsys_common_shortest(a[0], in->diffuse[0]);
    lsys_common_shortest(a[1], in->diffuse[1]);
    PUT("%s\nTOP COLOR: %d DIFFUSE: %s BOTTOM COLOR: %d DIFFUSE: %s\n", in->name, in->color[0],
        a[0], in->color[1], a[1]);
    for (d = 0; d < 8; d++)
      PUT("%s: %s%s", nbs[d], in->nb[d] >= 0 ? s->info[in->nb[d]].name : "~",
          d == 2 || d == 4 || d == 7 ? "\n" : " ");
    for (k = 0; k < 16; k++) {
      lsys_common_shortest(a[0], s->patch[i].ctrl[3 * k]);
      lsys_common_shortest(a[1], s->patch[i].ctrl[3 * k + 1]);
      lsys_common_shortest(a[2], s->patch[i].ctrl[3 * k + 2]);
      PUT("%s %s %s%s", a[0], a[1], a[2], k % 4 == 3 ? "\n" : "  ");
    }
  }
#undef PUT
  return len;
}

/* ------------------------------------------------------------------ */
/* Tessellation                                                         */
/* ------------------------------------------------------------------ */

/* Evaluation space -> world: w = o + k R (x - c); identity for @PD. */
typedef struct xform {
  double R[3][3], k, c[3], o[3];
  int identity;
} xform;

/* Texture coordinates: per patch (s, t), or the evaluation-space position
** projected on the axes a1, a2 and scaled from [lo, lo + 1/inv] to [0,1]. */
typedef struct uvmap {
  int planar;
  double a1[3], a2[3], lo[2], inv[2];
} uvmap;

static void setxform (xform *x, const lsys_surface *s, const lsys_place *pl) {
  double LS[3];
  int i, j;
  vcross(LS, s->heading, s->up);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++)
      x->R[i][j] = pl->L[i] * LS[j] + pl->H[i] * s->heading[j] + pl->U[i] * s->up[j];
  x->k = pl->scale / (s->size > 0 ? s->size : 1);
  vcopy(x->c, s->contact);
  vcopy(x->o, pl->origin);
  x->identity = 0;
}

static void rotate (const xform *x, const double v[3], double out[3]) {
  double r[3];
  int i;
  for (i = 0; i < 3; i++) r[i] = x->R[i][0] * v[0] + x->R[i][1] * v[1] + x->R[i][2] * v[2];
  vcopy(out, r);
}

static void place (const xform *x, const double v[3], double out[3]) {
  double d[3];
  int i;
  if (x->identity) { vcopy(out, v); return; }
  for (i = 0; i < 3; i++) d[i] = v[i] - x->c[i];
  rotate(x, d, d);
  for (i = 0; i < 3; i++) out[i] = x->o[i] + x->k * d[i];
}

/* A finite double within float range (mesh arrays are float). */
static double fit (double v) {
  return v > FLT_MAX ? FLT_MAX : v < -FLT_MAX ? -FLT_MAX : v == v ? v : 0;
}

/* The unit normal ds x dt at (s, t) in world space; 0 when degenerate. */
static int normalat (int basis, const lsys_patch *p, const xform *x, double s, double t,
                     double pos[3], double n[3]) {
  double ds[3], dt[3], l, a;
  lsys_surface_patch_eval(basis, p, s, t, pos, ds, dt);
  if (!x->identity) {
    rotate(x, ds, ds);
    rotate(x, dt, dt);
  }
  vcross(n, ds, dt);
  l = vlen(n);
  a = vlen(ds) * vlen(dt);
  if (!(l > 1e-9 * a) || !(l > 1e-300) || !isfinite(l)) {
    vset(n, 0, 0, 0);
    return 0;
  }
  vlin(n, n, 1 / l, n, 0);
  return 1;
}

static double clamp01 (double u) {
  return u > 0 ? (u < 1 ? u : 1) : 0;
}

static void texcoord (const uvmap *uv, const double pos[3], double s, double t, double out[2]) {
  if (!uv->planar) { out[0] = s; out[1] = t; return; }
  out[0] = uv->inv[0] > 0 ? clamp01((vdot(pos, uv->a1) - uv->lo[0]) * uv->inv[0]) : 0.5;
  out[1] = uv->inv[1] > 0 ? clamp01((vdot(pos, uv->a2) - uv->lo[1]) * uv->inv[1]) : 0.5;
}

/* Widens lo/hi (per axis of 'uv') over the grid points of a patch. */
static void uvbounds (const uvmap *uv, int basis, const lsys_patch *p, int ns, int nt,
                      double lo[2], double hi[2]) {
  int i, j;
  for (j = 0; j <= nt; j++)
    for (i = 0; i <= ns; i++) {
      double pos[3], a, b;
      lsys_surface_patch_eval(basis, p, (double)i / ns, (double)j / nt, pos, NULL, NULL);
      a = vdot(pos, uv->a1);
      b = vdot(pos, uv->a2);
      if (a < lo[0]) lo[0] = a;
      if (a > hi[0]) hi[0] = a;
      if (b < lo[1]) lo[1] = b;
      if (b > hi[1]) hi[1] = b;
    }
}

/* Sets the scaling of 'uv' from bounds; a range with no extent maps to 0.5. */
static void uvscale (uvmap *uv, const double lo[2], const double hi[2]) {
  int k;
  for (k = 0; k < 2; k++) {
    double d = hi[k] - lo[k], m = fabs(lo[k]) > fabs(hi[k]) ? fabs(lo[k]) : fabs(hi[k]);
    uv->lo[k] = lo[k];
    uv->inv[k] = (d > 1e-12 * m && d > 1e-300 && isfinite(d)) ? 1 / d : 0;
  }
}

/*
** Appends the (ns + 1) x (nt + 1) vertices (vertex (i, j) at s = i/ns,
** t = j/nt, index j (ns + 1) + i) and 2 ns nt triangles of one patch; room
** must be reserved. A degenerate normal is taken from a point a little
** further inside the patch (moving t, then s, then both, by 1e-4 up to
** 0.1), else from the patch's average normal, else 'dflt'.
*/
static void meshpatch (lsys_mesh *m, int basis, const lsys_patch *p, const xform *x,
                       const uvmap *uv, unsigned col, int ns, int nt, const double dflt[3]) {
  static const double shift[4] = {1e-4, 1e-3, 1e-2, 0.1};
  uint32_t base = (uint32_t)m->nv, w = (uint32_t)ns + 1;
  double sum[3] = {0, 0, 0};
  int i, j, bad = 0;
  for (j = 0; j <= nt; j++)
    for (i = 0; i <= ns; i++) {
      double s = (double)i / ns, t = (double)j / nt, pos[3], wp[3], n[3], tc[2];
      if (normalat(basis, p, x, s, t, pos, n)) vlin(sum, sum, 1, n, 1);
      else bad++;
      texcoord(uv, pos, s, t, tc);
      place(x, pos, wp);
      vset(wp, fit(wp[0]), fit(wp[1]), fit(wp[2]));
      lsys_mesh_vertex(m, wp, n, tc[0], tc[1], col, 1);
    }
  if (!vnorm(sum)) vcopy(sum, dflt);
  for (j = 0; j <= nt && bad > 0; j++)
    for (i = 0; i <= ns; i++) {
      float *f = m->nrm + 3 * (size_t)(base + (uint32_t)j * w + (uint32_t)i);
      double s = (double)i / ns, t = (double)j / nt, pos[3], n[3];
      int k, ok = 0;
      if (f[0] != 0 || f[1] != 0 || f[2] != 0) continue;
      for (k = 0; k < 12 && !ok; k++) {   /* along t, along s, then both */
        double ds = s < 0.5 ? shift[k / 3] : -shift[k / 3];
        double dt = t < 0.5 ? shift[k / 3] : -shift[k / 3];
        ok = normalat(basis, p, x, k % 3 == 0 ? s : s + ds, k % 3 == 1 ? t : t + dt, pos, n);
      }
      if (!ok) vcopy(n, sum);
      f[0] = (float)n[0]; f[1] = (float)n[1]; f[2] = (float)n[2];
      bad--;
    }
  for (j = 0; j < nt; j++)
    for (i = 0; i < ns; i++) {
      uint32_t a = base + (uint32_t)j * w + (uint32_t)i, b = a + 1, c = a + w + 1, d = a + w;
      lsys_mesh_tri(m, a, b, c);
      lsys_mesh_tri(m, a, c, d);
    }
}

/* Room for 'np' patches; LSYS_EARG for bad divisions. */
static int reserve (lsys_mesh *m, size_t np, int ns, int nt) {
  size_t nv, ntri;
  if (ns < 1 || nt < 1 || ns > LSYS_SURFACE_MAXDIV || nt > LSYS_SURFACE_MAXDIV) return LSYS_EARG;
  nv = (size_t)(ns + 1) * (size_t)(nt + 1);
  ntri = 2 * (size_t)ns * (size_t)nt;
  if (np > ((size_t)-1 / 4) / nv) return LSYS_ELIMIT;
  return lsys_mesh_reserve(m, np * nv, np * ntri);
}

/* Averages the normals of two vertices that lie on a shared edge. */
static void sharenormal (lsys_mesh *m, size_t a, size_t b) {
  float *na = m->nrm + 3 * a, *nb = m->nrm + 3 * b;
  double v[3] = {(double)na[0] + nb[0], (double)na[1] + nb[1], (double)na[2] + nb[2]};
  if (vlen(v) < 1e-6) return;   /* opposite sides: leave both */
  vnorm(v);
  na[0] = nb[0] = (float)v[0];
  na[1] = nb[1] = (float)v[1];
  na[2] = nb[2] = (float)v[2];
}

/* Normals along the edges and corners shared with neighbours. Each pair is
** visited once: from the patch that has the other above or to its left. */
static void shareedges (lsys_mesh *m, const lsys_surface *s, size_t first, int ns, int nt) {
  size_t w = (size_t)ns + 1, per = w * ((size_t)nt + 1), p;
  int i;
  for (p = 0; p < s->npatch; p++) {
    const int *nb = s->info[p].nb;
    size_t bp = first + p * per;
    if (nb[LSYS_NB_A] >= 0) {
      size_t bq = first + (size_t)nb[LSYS_NB_A] * per;
      for (i = 0; i <= ns; i++) sharenormal(m, bp + (size_t)i, bq + (size_t)nt * w + (size_t)i);
    }
    if (nb[LSYS_NB_L] >= 0) {
      size_t bq = first + (size_t)nb[LSYS_NB_L] * per;
      for (i = 0; i <= nt; i++) sharenormal(m, bp + (size_t)i * w, bq + (size_t)i * w + (size_t)ns);
    }
    if (nb[LSYS_NB_AL] >= 0)
      sharenormal(m, bp, first + (size_t)nb[LSYS_NB_AL] * per + per - 1);
    if (nb[LSYS_NB_AR] >= 0)
      sharenormal(m, bp + (size_t)ns, first + (size_t)nb[LSYS_NB_AR] * per + (size_t)nt * w);
  }
}

int lsys_surface_mesh (lsys_mesh *m, const lsys_surface *s, const lsys_place *pl, int ns,
                       int nt) {
  xform x;
  uvmap uv = {0};
  double dflt[3];
  size_t first = m->nv, p;
  int st = reserve(m, s->npatch, ns, nt);
  if (st != LSYS_OK) return st;
  setxform(&x, s, pl);
  rotate(&x, s->up, dflt);
  if (!vnorm(dflt)) vset(dflt, 0, 0, 1);
  if (pl->uv_surface) {
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    uv.planar = 1;
    vset(uv.a1, 1, 0, 0);
    vset(uv.a2, 0, 1, 0);
    for (p = 0; p < s->npatch; p++) uvbounds(&uv, s->basis, &s->patch[p], ns, nt, lo, hi);
    uvscale(&uv, lo, hi);
  }
  for (p = 0; p < s->npatch; p++)
    meshpatch(m, s->basis, &s->patch[p], &x, &uv, pl->color, ns, nt, dflt);
  if (s->info != NULL) shareedges(m, s, first, ns, nt);
  return LSYS_OK;
}

void lsys_surface_endpoint (const lsys_surface *s, const lsys_place *pl, double out[3]) {
  xform x;
  setxform(&x, s, pl);
  place(&x, s->end, out);
}

int lsys_surface_patch_mesh (lsys_mesh *m, int basis, const lsys_patch *p, const lsys_place *pl,
                             int ns, int nt) {
  static const double dflt[3] = {0, 0, 1};
  xform x = {0};
  uvmap uv = {0};
  int st = reserve(m, 1, ns, nt);
  if (st != LSYS_OK) return st;
  x.identity = 1;
  if (pl->uv_surface) {
    /* axes: the patch's mean s direction, and its mean t direction made
    ** orthogonal to it; (s, t) when either is degenerate */
    double c00[3], c10[3], c01[3], c11[3], a1[3], a2[3];
    lsys_surface_patch_eval(basis, p, 0, 0, c00, NULL, NULL);
    lsys_surface_patch_eval(basis, p, 1, 0, c10, NULL, NULL);
    lsys_surface_patch_eval(basis, p, 0, 1, c01, NULL, NULL);
    lsys_surface_patch_eval(basis, p, 1, 1, c11, NULL, NULL);
    vlin(a1, c10, 1, c00, -1);
    vlin(a1, a1, 1, c11, 1);
    vlin(a1, a1, 1, c01, -1);
    vlin(a2, c01, 1, c00, -1);
    vlin(a2, a2, 1, c11, 1);
    vlin(a2, a2, 1, c10, -1);
    if (vnorm(a1) && isfinite(a1[0] + a1[1] + a1[2])) {
      vlin(a2, a2, 1, a1, -vdot(a2, a1));
      if (vlen(a2) > 1e-9 * (vlen(c10) + vlen(c01) + 1e-300) && vnorm(a2) &&
          isfinite(a2[0] + a2[1] + a2[2])) {
        double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
        uv.planar = 1;
        vcopy(uv.a1, a1);
        vcopy(uv.a2, a2);
        uvbounds(&uv, basis, p, ns, nt, lo, hi);
        uvscale(&uv, lo, hi);
      }
    }
  }
  meshpatch(m, basis, p, &x, &uv, pl->color, ns, nt, dflt);
  return LSYS_OK;
}
