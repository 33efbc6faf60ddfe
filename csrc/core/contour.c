/*
** Contours of generalized cylinders: the contour file parser (cpfg's
** format of Appendix B.1 and vlab's versioned "cver 1 1" .. "cver 1 3")
** and the placement of p vertices at equal arc length along the B-spline
** (cpfg guide §3.2.3 and Appendix B.1).
*/
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"

#define MAXCOORD 1e9    /* |coordinate| limit: keeps every result finite */
#define NSAMPLE 10      /* curve points computed per control point */

void lsys_contour_init (lsys_contour *c) {
  c->pt = NULL;
  c->n = 0;
  c->closed = 0;
  c->dim = 0;
}

void lsys_contour_free (lsys_contour *c) {
  LSYS_FREE(c->pt);
  lsys_contour_init(c);
}

/* Fills 'e' and returns 'code' when 'n' points are too few or too many
** for the kind of contour. */
static int checkcount (lsys_error *e, int code, size_t n, int closed) {
  size_t least = closed ? 3 : 4;
  if (n < least)
    return lsys_seterror(e, code, 0, "%s contour needs at least %zu points, got %zu",
                         closed ? "a closed" : "an open", least, n);
  if (n > LSYS_CONTOUR_MAXPOINTS)
    return lsys_seterror(e, code, 0, "too many points (limit is %d)", LSYS_CONTOUR_MAXPOINTS);
  return LSYS_OK;
}

int lsys_contour_set (lsys_contour *c, const double *pt, size_t n, int closed, int dim,
                      lsys_error *e) {
  double *np;
  size_t i;
  int k, st;
  if (dim != 2 && dim != 3)
    return lsys_seterror(e, LSYS_EARG, 0, "dimension must be 2 or 3, got %d", dim);
  if ((st = checkcount(e, LSYS_EARG, n, closed != 0)) != LSYS_OK) return st;
  for (i = 0; i < n; i++)
    for (k = 0; k < dim; k++)
      if (!(fabs(pt[3 * i + k]) <= MAXCOORD))   /* also NaN */
        return lsys_seterror(e, LSYS_EARG, i, "point %zu: coordinate %d is %s", i + 1, k + 1,
                             isfinite(pt[3 * i + k]) ? "out of range (limit is 1e9)"
                                                     : "not finite");
  np = (double *)LSYS_MALLOC(3 * n * sizeof *np);
  if (np == NULL) return lsys_seterror(e, LSYS_ENOMEM, 0, "not enough memory");
  for (i = 0; i < n; i++) {
    np[3 * i] = pt[3 * i];
    np[3 * i + 1] = pt[3 * i + 1];
    np[3 * i + 2] = dim == 3 ? pt[3 * i + 2] : 0.0;
  }
  lsys_contour_free(c);
  c->pt = np;
  c->n = n;
  c->closed = closed != 0;
  c->dim = dim;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Parser: the text is read line by line; a line is split into tokens
** separated by blanks ('#' starts a comment that runs to the end of the
** line). Lines without tokens are skipped. */

typedef struct reader {
  const char *s;          /* the text, 'len' bytes, not NUL-terminated */
  size_t len, pos;
  size_t line;            /* number of the line 'pos' is on */
  size_t at;              /* number of the line last returned by nextline */
  const char *name;
  lsys_error *e;
} reader;

typedef struct token { const char *s; size_t len; } token;

#define MAXTOK 4        /* tokens kept per line; the others are only counted */

static int isblankc (int ch) {
  return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

/* Reads the next line that has tokens, keeping the first MAXTOK in 't'.
** Returns the number of tokens on that line, or 0 at the end of the text
** (R->line is then the number of the line where the text ends). */
static size_t nextline (reader *R, token *t) {
  const char *s = R->s;
  while (R->pos < R->len) {
    size_t nt = 0;
    R->at = R->line;
    while (R->pos < R->len && s[R->pos] != '\n') {
      size_t b = R->pos;
      if (isblankc((unsigned char)s[b])) { R->pos++; continue; }
      if (s[b] == '#') {                          /* comment */
        while (R->pos < R->len && s[R->pos] != '\n') R->pos++;
        break;
      }
      while (R->pos < R->len && s[R->pos] != '\n' && s[R->pos] != '#' &&
             !isblankc((unsigned char)s[R->pos]))
        R->pos++;
      if (nt < MAXTOK) { t[nt].s = s + b; t[nt].len = R->pos - b; }
      nt++;
    }
    if (R->pos < R->len) { R->pos++; R->line++; }   /* the '\n' */
    if (nt > 0) return nt;
  }
  return 0;
}

/* A printable copy of a token for a message (lsys_common_quote: a short token). */
static const char *show (const token *t, char buf[32]) {
  return lsys_common_quote(buf, t->s, t->len);
}

/* Sets the error "name:line: message" (common.h) and returns LSYS_ESYNTAX. */
static int error (reader *R, size_t line, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 3, 4)))
#endif
  ;
static int error (reader *R, size_t line, const char *fmt, ...) {
  va_list ap;
  int code;
  va_start(ap, fmt);
  code = lsys_vseterror_line(R->e, LSYS_ESYNTAX, line, R->name, line, fmt, ap);
  va_end(ap);
  return code;
}

/* Reads a coordinate: a number that strtod takes whole, at most MAXCOORD
** in magnitude. */
static int number (reader *R, const token *t, double *x) {
  char buf[64], *end, b[32];
  if (t->len < sizeof buf) {
    memcpy(buf, t->s, t->len);
    buf[t->len] = '\0';
    *x = strtod(buf, &end);
    if (end == buf + t->len) {               /* all of it, and no NUL inside */
      if (!isfinite(*x))
        return error(R, R->at, "'%s' is not a finite number", show(t, b));
      if (fabs(*x) > MAXCOORD)
        return error(R, R->at, "%s is out of range (limit is 1e9)", show(t, b));
      return LSYS_OK;
    }
  }
  return error(R, R->at, "bad number '%s'", show(t, b));
}

/* 1 when the token is the word 'w'. */
static int tokis (const token *t, const char *w) {
  size_t n = strlen(w);
  return t->len == n && memcmp(t->s, w, n) == 0;
}

/* Reads a whole number (decimal digits only) into 'v'; values above
** LSYS_CONTOUR_MAXPOINTS all read as LSYS_CONTOUR_MAXPOINTS + 1. Returns 0
** when 't' is not such a number. */
static int whole (const token *t, size_t *v) {
  size_t i;
  *v = 0;
  for (i = 0; i < t->len; i++) {
    if (t->s[i] < '0' || t->s[i] > '9') return 0;
    if (*v <= LSYS_CONTOUR_MAXPOINTS) *v = *v * 10 + (size_t)(t->s[i] - '0');
  }
  if (*v > LSYS_CONTOUR_MAXPOINTS) *v = LSYS_CONTOUR_MAXPOINTS + 1;
  return t->len > 0;
}

/* checkcount's message, on line 'line'. */
static int counterr (reader *R, size_t line, size_t n, int closed) {
  if (checkcount(R->e, LSYS_ESYNTAX, n, closed) != LSYS_OK) {
    char msg[sizeof R->e->msg];
    memcpy(msg, R->e->msg, sizeof msg);
    return error(R, line, "%s", msg);
  }
  return LSYS_OK;
}

/* Reads the header "N dim open|closed" (the first line's 'nt' tokens are
** in 't') into 'n', 'dim' and 'closed'. */
static int header (reader *R, const token *t, size_t nt, size_t *n, int *dim, int *closed) {
  char b[32];
  if (nt != 3)
    return error(R, nt ? R->at : R->line, "expected \"N dim open|closed\"%s",
                 nt ? "" : ", got an empty file");
  if (!whole(&t[0], n)) return error(R, R->at, "bad point count '%s'", show(&t[0], b));
  if (t[1].len != 1 || (t[1].s[0] != '2' && t[1].s[0] != '3'))
    return error(R, R->at, "dimension must be 2 or 3, got '%s'", show(&t[1], b));
  *dim = t[1].s[0] - '0';
  if (tokis(&t[2], "closed")) *closed = 1;
  else if (tokis(&t[2], "open")) *closed = 0;
  else return error(R, R->at, "expected 'open' or 'closed', got '%s'", show(&t[2], b));
  return counterr(R, R->at, *n, *closed);
}

/* Reads the n point lines and checks that nothing follows them. */
static int points (reader *R, double *pt, size_t n, int dim) {
  token t[MAXTOK];
  char b[32];
  size_t i, nt;
  int k, st;
  for (i = 0; i < n; i++) {
    if ((nt = nextline(R, t)) == 0)
      return error(R, R->line, "file ends after %zu of %zu points", i, n);
    if (nt != (size_t)dim)
      return error(R, R->at, "expected %d numbers, got %zu", dim, nt);
    for (k = 0; k < dim; k++)
      if ((st = number(R, &t[k], &pt[3 * i + k])) != LSYS_OK) return st;
    if (dim == 2) pt[3 * i + 2] = 0.0;
  }
  if (nextline(R, t) != 0)
    return error(R, R->at, "unexpected '%s' after the %zu points", show(&t[0], b), n);
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* vlab's versioned files (what cpfg's process_contour_file reads after a
** first line "cver 1 1", "cver 1 2" or "cver 1 3"; the contour editors
** write them):
**
**   cver 1 3
**   name: NAME                  ignored
**   points: LINES TOTAL         LINES point lines giving TOTAL points
**   type: or                    1.1: open|closed; 1.2, 1.3: o|c then r|e
**   samples: K                  1.3 only; read and ignored
**   x y z m                     LINES times: the point repeated m times
**
** 1.3 may have, before the points, "background: FILE" and "backgroundXY:
** X Y" (the editor's background image) and "markers: K" followed by K
** lines; they are skipped. */

/* Reads the next line, which must begin with the word 'key' and have 'nv'
** more tokens (any number when nv < 0); 'usage' is the expected line. */
static int keyline (reader *R, token *t, const char *key, int nv, const char *usage) {
  size_t nt = nextline(R, t);
  if (nt == 0) return error(R, R->line, "expected \"%s\", got the end of the file", usage);
  if (!tokis(&t[0], key) || (nv >= 0 && nt != (size_t)nv + 1))
    return error(R, R->at, "expected \"%s\"", usage);
  return LSYS_OK;
}

/* The first line "cver MAJOR MINOR" (its 'nt' tokens in 't'): 1.1, 1.2 or
** 1.3; sets 'minor'. */
static int version (reader *R, const token *t, size_t nt, int *minor) {
  char a[32], b[32];
  size_t maj, min;
  if (nt != 3 || !whole(&t[1], &maj) || !whole(&t[2], &min))
    return error(R, R->at, "expected \"cver MAJOR MINOR\"");
  if (maj != 1 || min < 1 || min > 3)
    return error(R, R->at, "unknown contour format 'cver %s %s' (lsys reads cver 1 1, 1 2 "
                 "and 1 3)", show(&t[1], a), show(&t[2], b));
  *minor = (int)min;
  return LSYS_OK;
}

/* "type:": in 1.1 'open' or 'closed'; in 1.2 and 1.3 two letters, o|c
** (open, closed) then r|e (regular, end-point interpolation). cpfg draws
** 'e' as 'r' (it says so); so does lsys. */
static int cvertype (reader *R, int minor, int *closed) {
  token t[MAXTOK];
  char b[32];
  int st = keyline(R, t, "type:", 1, minor == 1 ? "type: open|closed" : "type: o|c r|e");
  if (st != LSYS_OK) return st;
  if (minor == 1) {
    if (tokis(&t[1], "closed")) *closed = 1;
    else if (tokis(&t[1], "open")) *closed = 0;
    else return error(R, R->at, "expected 'open' or 'closed', got '%s'", show(&t[1], b));
  } else if (t[1].len == 2 && (t[1].s[0] == 'o' || t[1].s[0] == 'c') &&
             (t[1].s[1] == 'r' || t[1].s[1] == 'e')) {
    *closed = t[1].s[0] == 'c';
  } else {
    return error(R, R->at, "type must be 'or', 'oe', 'cr' or 'ce', got '%s'", show(&t[1], b));
  }
  return LSYS_OK;
}

/* 1.3: "samples: K", then the optional background and marker lines. */
static int cver13 (reader *R) {
  token t[MAXTOK];
  char b[32];
  reader save;
  size_t k, i, nt;
  int st = keyline(R, t, "samples:", 1, "samples: K");
  if (st != LSYS_OK) return st;
  if (!whole(&t[1], &k)) return error(R, R->at, "bad sample count '%s'", show(&t[1], b));
  save = *R;
  if (nextline(R, t) > 0 && tokis(&t[0], "background:")) {
    if ((st = keyline(R, t, "backgroundXY:", 2, "backgroundXY: X Y")) != LSYS_OK) return st;
  } else {
    *R = save;
  }
  save = *R;
  if ((nt = nextline(R, t)) > 0 && tokis(&t[0], "markers:")) {
    if (nt != 2 || !whole(&t[1], &k)) return error(R, R->at, "expected \"markers: K\"");
    for (i = 0; i < k; i++)
      if (nextline(R, t) == 0)
        return error(R, R->line, "file ends after %zu of %zu markers", i, k);
  } else {
    *R = save;
  }
  return LSYS_OK;
}

/* Reads the n1 point lines "x y z m" into 'pt' (n points in all, the
** TOTAL of the "points:" line 'where') and checks that nothing follows. */
static int cverpoints (reader *R, double *pt, size_t n1, size_t n, size_t where) {
  token t[MAXTOK];
  char b[32];
  double x[3];
  size_t i, j, k = 0, m, nt;
  int q, st;
  for (i = 0; i < n1; i++) {
    if ((nt = nextline(R, t)) == 0)
      return error(R, R->line, "file ends after %zu of %zu point lines", i, n1);
    if (nt != 4) return error(R, R->at, "expected 4 numbers (x y z multiplicity), got %zu", nt);
    for (q = 0; q < 3; q++)
      if ((st = number(R, &t[q], &x[q])) != LSYS_OK) return st;
    if (!whole(&t[3], &m) || m == 0)
      return error(R, R->at, "multiplicity must be a whole number >= 1, got '%s'",
                   show(&t[3], b));
    if (m > n - k)
      return error(R, R->at, "the multiplicities add up to more than the %zu points of line %zu",
                   n, where);
    for (j = 0; j < m; j++, k++) memcpy(pt + 3 * k, x, sizeof x);
  }
  if (k < n)
    return error(R, where, "the multiplicities add up to %zu points, not %zu", k, n);
  if (nextline(R, t) != 0)
    return error(R, R->at, "unexpected '%s' after the %zu point lines", show(&t[0], b), n1);
  return LSYS_OK;
}

/* A versioned file, the first line's 'nt' tokens in 't'; dimension 3. */
static int cver (reader *R, const token *t, size_t nt, lsys_contour *c) {
  token u[MAXTOK];
  char b[32];
  size_t n1, n, where;
  int minor = 0, closed = 0, st;
  double *pt;
  if ((st = version(R, t, nt, &minor)) != LSYS_OK) return st;
  if ((st = keyline(R, u, "name:", -1, "name: NAME")) != LSYS_OK) return st;
  if ((st = keyline(R, u, "points:", 2, "points: LINES TOTAL")) != LSYS_OK) return st;
  where = R->at;
  if (!whole(&u[1], &n1)) return error(R, where, "bad point line count '%s'", show(&u[1], b));
  if (!whole(&u[2], &n)) return error(R, where, "bad point count '%s'", show(&u[2], b));
  if ((st = cvertype(R, minor, &closed)) != LSYS_OK) return st;
  if ((st = counterr(R, where, n, closed)) != LSYS_OK) return st;
  if (n1 == 0 || n1 > n)
    return error(R, where, "%zu point lines cannot give %zu points", n1, n);
  if (minor == 3 && (st = cver13(R)) != LSYS_OK) return st;
  pt = (double *)LSYS_MALLOC(3 * n * sizeof *pt);
  if (pt == NULL) return lsys_seterror(R->e, LSYS_ENOMEM, 0, "not enough memory");
  if ((st = cverpoints(R, pt, n1, n, where)) != LSYS_OK) {
    LSYS_FREE(pt);
    return st;
  }
  c->pt = pt;
  c->n = n;
  c->closed = closed;
  c->dim = 3;
  return LSYS_OK;
}

int lsys_contour_parse (lsys_contour *c, const char *text, size_t len, const char *name,
                        lsys_error *e) {
  reader R;
  token t[MAXTOK];
  size_t n = 0, nt;
  int dim = 0, closed = 0, st;
  double *pt;
  R.s = text; R.len = text ? len : 0; R.pos = 0; R.line = 1; R.at = 1; R.name = name; R.e = e;
  lsys_contour_free(c);
  nt = nextline(&R, t);
  if (nt > 0 && tokis(&t[0], "cver")) return cver(&R, t, nt, c);
  if ((st = header(&R, t, nt, &n, &dim, &closed)) != LSYS_OK) return st;
  pt = (double *)LSYS_MALLOC(3 * n * sizeof *pt);
  if (pt == NULL) return lsys_seterror(e, LSYS_ENOMEM, 0, "not enough memory");
  if ((st = points(&R, pt, n, dim)) != LSYS_OK) {
    LSYS_FREE(pt);
    return st;
  }
  c->pt = pt;
  c->n = n;
  c->closed = closed;
  c->dim = dim;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Sampling. The curve is followed through m = 10n points S_k at equal
** steps of the parameter; a closed curve has m + 1 of them (S_m = S_0).
** Nothing is stored: the points are recomputed as the polyline is walked
** twice, once for its length and once to place the vertices. */

typedef struct curve {
  const lsys_contour *c;
  size_t m;               /* distinct points */
  size_t nseg;            /* polyline segments: m closed, m - 1 open */
} curve;

/* S_k; k may run from -1 to nseg + 1: closed curves wrap, open ones stop
** at their ends. */
static void point (const curve *C, long k, double s[3]) {
  const lsys_contour *c = C->c;
  const double *p[4];
  double t, u, w[4];
  size_t seg, q;
  int i;
  if (c->closed) {
    k = (k + (long)C->m) % (long)C->m;
    seg = (size_t)k / NSAMPLE;
    t = (double)((size_t)k % NSAMPLE) / NSAMPLE;
    for (q = 0; q < 4; q++) p[q] = c->pt + 3 * ((seg + q) % c->n);
  } else {
    if (k < 0) k = 0;
    if (k > (long)C->m - 1) k = (long)C->m - 1;
    u = (double)k * (double)(c->n - 3) / (double)(C->m - 1);
    seg = (size_t)u;
    if (seg > c->n - 4) seg = c->n - 4;
    t = u - (double)seg;
    for (q = 0; q < 4; q++) p[q] = c->pt + 3 * (seg + q);
  }
  u = 1 - t;      /* uniform cubic B-spline basis; the weights add up to 1 */
  w[0] = u * u * u / 6;
  w[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
  w[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
  w[3] = t * t * t / 6;
  for (i = 0; i < 3; i++)
    s[i] = w[0] * p[0][i] + w[1] * p[1][i] + w[2] * p[2][i] + w[3] * p[3][i];
}

static double dist (const double *a, const double *b) {
  double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Unit normal in the xy plane at position 'v' for the tangent 'tan'
** (left of it when side > 0, right when side < 0); falls back on the
** chord 'ch', then on the direction of 'v', then on +x, when a vector is
** no longer than 'eps' (rounding noise at the contour's scale). */
static void normal (double side, const double *tan, const double *ch, const double *v,
                    double eps, double *n) {
  double l = hypot(tan[0], tan[1]);
  if (!(l > eps)) { tan = ch; l = hypot(ch[0], ch[1]); }
  if (l > eps) {
    n[0] = -side * tan[1] / l;
    n[1] = side * tan[0] / l;
  } else if ((l = hypot(v[0], v[1])) > eps) {
    n[0] = v[0] / l;
    n[1] = v[1] / l;
  } else {
    n[0] = 1;
    n[1] = 0;
  }
  n[2] = 0;
}

int lsys_contour_sample (const lsys_contour *c, int p, double *out, double *nrm) {
  curve C;
  double total = 0, area = 0, eps = 0, side, l0, w[4][3], tan[3], ch[3], r;
  double *v0 = out, *vp = out + 3 * (size_t)p;
  size_t j;
  long i;
  int k;
  if (p < 3 || c->pt == NULL || c->n < (c->closed ? 3u : 4u)) return LSYS_EARG;
  for (j = 0; j < c->n; j++)
    for (k = 0; k < 2; k++)
      if (fabs(c->pt[3 * j + k]) > eps) eps = fabs(c->pt[3 * j + k]);
  eps *= 1e-12;
  C.c = c;
  C.m = NSAMPLE * c->n;
  C.nseg = c->closed ? C.m : C.m - 1;
  point(&C, 0, w[1]);
  for (j = 0; j < C.nseg; j++) {           /* length and signed area */
    point(&C, (long)j + 1, w[2]);
    total += dist(w[1], w[2]);
    area += w[1][0] * w[2][1] - w[2][0] * w[1][1];
    memcpy(w[1], w[2], sizeof w[1]);
  }
  side = c->closed && area > 0 ? -1 : 1;   /* outward: right of a CCW curve */
  /* Walk again with the window w = S_(j-1) .. S_(j+2); vertex i lies at
  ** length total i / p on segment S_j S_(j+1) (fraction f). */
  point(&C, -1, w[0]);
  point(&C, 0, w[1]);
  point(&C, 1, w[2]);
  l0 = 0;
  i = 0;
  for (j = 0; j < C.nseg && i < p; j++) {
    double len = dist(w[1], w[2]), l1 = l0 + len;
    point(&C, (long)j + 2, w[3]);
    if (j + 1 == C.nseg) l1 = total;
    for (; i < p; i++) {
      double s = total * (double)i / p, f;
      double *v = out + 3 * i;
      if (s > l1) break;
      f = len > 0 ? (s - l0) / len : 0;
      f = f < 0 ? 0 : f > 1 ? 1 : f;
      for (k = 0; k < 3; k++) {
        v[k] = w[1][k] + f * (w[2][k] - w[1][k]);
        tan[k] = (1 - f) * (w[2][k] - w[0][k]) + f * (w[3][k] - w[1][k]);
        ch[k] = w[2][k] - w[1][k];
      }
      if (nrm) normal(side, tan, ch, v, eps, nrm + 3 * i);
    }
    l0 = l1;
    memmove(w[0], w[1], 3 * sizeof w[0]);
  }
  if (!c->closed) {                        /* the end of the curve */
    point(&C, (long)C.m - 2, w[0]);
    point(&C, (long)C.m - 1, vp);
    for (k = 0; k < 3; k++) tan[k] = ch[k] = vp[k] - w[0][k];
    if (nrm) normal(side, tan, ch, vp, eps, nrm + 3 * (size_t)p);
  }
  r = hypot(v0[0], v0[1]);                 /* rotate V_0 onto +x */
  if (r > 0) {
    double cs = v0[0] / r, sn = v0[1] / r;
    for (i = 0; i <= p - c->closed; i++) {
      double *v = out + 3 * i, x = v[0];
      v[0] = cs * x + sn * v[1];
      v[1] = cs * v[1] - sn * x;
      if (nrm) {
        v = nrm + 3 * i;
        x = v[0];
        v[0] = cs * x + sn * v[1];
        v[1] = cs * v[1] - sn * x;
      }
    }
    v0[0] = r;
    v0[1] = 0;
  }
  if (c->closed) {
    memcpy(vp, v0, 3 * sizeof *vp);
    if (nrm) memcpy(nrm + 3 * (size_t)p, nrm, 3 * sizeof *nrm);
  }
  return LSYS_OK;
}

void lsys_contour_circle (int p, double *out, double *nrm) {
  const double twopi = 6.283185307179586476925286766559;
  int i;
  if (p < 3) return;
  for (i = 0; i <= p; i++) {
    double a = twopi * (double)(i % p) / p;
    double *v = out + 3 * i;
    v[0] = i % p ? cos(a) : 1;
    v[1] = i % p ? sin(a) : 0;
    v[2] = 0;
    if (nrm) memcpy(nrm + 3 * i, v, 3 * sizeof *v);
  }
}
