/*
** Positional functions (see func.h): the clamped cubic B-spline function of
** cpfg's function files, its exact evaluation, and the .func and .fset
** readers and writer. The facts of the format come from cpfg (vlab:
** cpfg/splinefun.cpp, funcedit/model.cpp); the code is ours.
**
** The curve's basis is evaluated here: each span is turned once into its
** four Bezier points by blossoming (de Boor's algorithm with the span's
** ends as arguments), and evaluated in Bernstein form, which gives the end
** points exactly. (csrc/core/bspline.h, which landed later, evaluates
** clamped curves too; the inversion here needs each span's polynomial, so
** the span form stays. Moving the basis there is left for a later change.)
*/
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "func.h"

#define MAXCOORD 1e9

void lsys_func_init (lsys_func *f) {
  memset(f, 0, sizeof *f);
}

void lsys_func_free (lsys_func *f) {
  LSYS_FREE(f->pt);
  LSYS_FREE(f->vals);
  LSYS_FREE(f->bez);
  lsys_func_init(f);
}

/* Knot i of the clamped cubic knot vector of n points. */
static double knot (size_t i, size_t n) {
  return i < 3 ? 0.0 : i - 3 > n - 3 ? (double)(n - 3) : (double)(i - 3);
}

/* The blossom of span j (knots [j, j+1], points j..j+3) at (u1, u2, u3), for
** coordinate c (0: x, 1: y): de Boor's triangle with one argument a level. */
static double blossom (const double *pt, size_t n, size_t j, const double u[3], int c) {
  double d[4];
  int r, i;
  for (i = 0; i < 4; i++) d[i] = pt[2 * (j + (size_t)i) + (size_t)c];
  for (r = 1; r <= 3; r++)
    for (i = 3; i >= r; i--) {
      size_t g = j + (size_t)i;                   /* global index of d[i] */
      double a = knot(g, n), b = knot(g + 4 - (size_t)r, n);   /* b - a >= 1 */
      double al = (u[r - 1] - a) / (b - a);
      d[i] = (1 - al) * d[i - 1] + al * d[i];
    }
  return d[3];
}

/* The Bezier points of every span into f->bez. */
static void spans (lsys_func *f) {
  size_t j, ns = f->n - 3;
  for (j = 0; j < ns; j++) {
    double a = (double)j, b = (double)j + 1;
    const double arg[4][3] = { {a, a, a}, {a, a, b}, {a, b, b}, {b, b, b} };
    int k;
    for (k = 0; k < 4; k++) {
      f->bez[8 * j + (size_t)k] = blossom(f->pt, f->n, j, arg[k], 0);
      f->bez[8 * j + 4 + (size_t)k] = blossom(f->pt, f->n, j, arg[k], 1);
    }
  }
}

static double bern (const double *b, double u) {
  double v = 1 - u;
  return v * v * v * b[0] + 3 * u * v * v * b[1] + 3 * u * u * v * b[2] + u * u * u * b[3];
}

static double dbern (const double *b, double u) {
  double v = 1 - u;
  return 3 * (v * v * (b[1] - b[0]) + 2 * u * v * (b[2] - b[1]) + u * u * (b[3] - b[2]));
}

/* The lowest u in [0, 1] with x(u) = x on a span whose x runs from b[0] <
** x to b[3] >= x (nondecreasing): Newton steps kept inside a bracket
** [lo, hi] with x(lo) < x <= x(hi), bisection when a step leaves it. */
static double solve (const double *b, double x) {
  double lo = 0, hi = 1, u;
  int it;
  u = (x - b[0]) / (b[3] - b[0]);                 /* the chord's guess */
  for (it = 0; it < 200; it++) {
    double g = bern(b, u) - x, d;
    if (g == 0) return u;
    if (g < 0) lo = u; else hi = u;
    d = dbern(b, u);
    u = d > 0 ? u - g / d : -1;
    if (!(u > lo && u < hi)) {
      u = lo + (hi - lo) / 2;
      if (!(u > lo && u < hi)) break;             /* the bracket is two neighbours */
    }
  }
  return hi;
}

static double exact (const lsys_func *f, double x) {
  size_t ns = f->n - 3, lo = 0, hi = ns;
  if (x <= f->bez[0]) return f->bez[4];
  while (lo < hi) {               /* the first span whose x reaches x: the lowest t */
    size_t mid = lo + (hi - lo) / 2;
    if (f->bez[8 * mid + 3] < x) lo = mid + 1; else hi = mid;
  }
  if (lo == ns) return f->bez[8 * (ns - 1) + 7];    /* beyond the last x (within XTOL) */
  return bern(f->bez + 8 * lo + 4, solve(f->bez + 8 * lo, x));
}

/* cpfg's value (GetValue/_Value of cpfg/splinefun.cpp): bisection on the
** curve parameter d in [0, 1] until |x(d) - x| <= 0.001; the y there. */
static double approx (const lsys_func *f, double x) {
  size_t ns = f->n - 3;
  double lo = 0, hi = 1, px, py = 0;
  int it;
  for (it = 0; it < 64; it++) {
    double d = (lo + hi) / 2, t = d * (double)ns, u;
    size_t j = (size_t)t;
    if (j >= ns) j = ns - 1;
    u = t - (double)j;
    px = bern(f->bez + 8 * j, u);
    py = bern(f->bez + 8 * j + 4, u);
    if (px > x) hi = d; else lo = d;
    if (fabs(px - x) <= 0.001) break;
  }
  return py;
}

double lsys_func_eval (const lsys_func *f, double x) {
  if (x != x) return x;
  if (x < 0) x = 0;
  if (x > 1) x = 1;
  if (f->samples > 2 && f->vals != NULL) {        /* cpfg's interpolation, as it computes it */
    double index = x * (f->samples - 1);
    int i = (int)floor(index);
    double w1 = 1 - index + i, w2 = index - i;
    if (i >= f->samples - 1) return f->vals[f->samples - 1];
    return w1 * f->vals[i] + w2 * f->vals[i + 1];
  }
  return f->cpfg ? approx(f, x) : exact(f, x);
}

void lsys_func_cpfg (lsys_func *f) {
  size_t i;
  if (f->n < 4 || f->cpfg) return;
  for (i = 0; i < 2 * f->n; i++) f->pt[i] = (double)(float)f->pt[i];
  spans(f);
  f->cpfg = 1;
  for (i = 0; i < (size_t)(f->samples > 2 ? f->samples : 0); i++)
    f->vals[i] = approx(f, (double)i / (f->samples - 1));
}

static int validname (const char *s) {
  size_t k, len = strlen(s);
  if (len == 0 || len > LSYS_FUNC_MAXNAME) return 0;
  for (k = 0; k < len; k++)
    if ((unsigned char)s[k] < 0x20 || s[k] == 0x7f) return 0;
  return 1;
}

/* The checks of lsys_func_set on the points. */
static int check (const double *pt, size_t n, lsys_error *e) {
  size_t i;
  if (n < 4 || n > LSYS_FUNC_MAXPOINTS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, n < 4 ?
                         "a function needs at least 4 points, got %zu" :
                         "too many points: %zu (limit is 65536)", n);
  for (i = 0; i < n; i++) {
    int c;
    for (c = 0; c < 2; c++)
      if (!isfinite(pt[2 * i + c]) || fabs(pt[2 * i + c]) > MAXCOORD)
        return lsys_seterror(e, LSYS_EARG, i, "point %zu: %c is %s", i + 1, "xy"[c],
                             isfinite(pt[2 * i + c]) ? "out of range (limit is 1e9)" :
                             "not a finite number");
    if (i > 0 && pt[2 * i] < pt[2 * i - 2])
      return lsys_seterror(e, LSYS_EARG, i, "point %zu: x is %.17g, less than the x of "
                           "point %zu (%.17g)", i + 1, pt[2 * i], i, pt[2 * i - 2]);
  }
  if (fabs(pt[0]) > LSYS_FUNC_XTOL)
    return lsys_seterror(e, LSYS_EARG, 0, "point 1: x is %.17g, not 0 (the first x must "
                         "be 0)", pt[0]);
  if (fabs(pt[2 * n - 2] - 1) > LSYS_FUNC_XTOL)
    return lsys_seterror(e, LSYS_EARG, n - 1, "point %zu: x is %.17g, not 1 (the last x "
                         "must be 1)", n, pt[2 * n - 2]);
  return LSYS_OK;
}

int lsys_func_set (lsys_func *f, const double *pt, size_t n, const char *name, int samples,
                   lsys_error *e) {
  lsys_func g;
  size_t i;
  int st;
  if ((st = check(pt, n, e)) != LSYS_OK) return st;
  if (name == NULL || !validname(name))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "a function's name must be 1 to %d "
                         "bytes without control characters", LSYS_FUNC_MAXNAME);
  if (samples < 0 || samples > LSYS_FUNC_MAXSAMPLES)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "samples must be from 0 to %d, got %d",
                         LSYS_FUNC_MAXSAMPLES, samples);
  lsys_func_init(&g);
  g.n = n;
  g.pt = (double *)LSYS_MALLOC(2 * n * sizeof *g.pt);
  g.bez = (double *)LSYS_MALLOC(8 * (n - 3) * sizeof *g.bez);
  g.vals = samples > 2 ? (double *)LSYS_MALLOC((size_t)samples * sizeof *g.vals) : NULL;
  if (g.pt == NULL || g.bez == NULL || (samples > 2 && g.vals == NULL)) {
    lsys_func_free(&g);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  }
  for (i = 0; i < 2 * n; i++) g.pt[i] = pt[i] == 0 ? 0.0 : pt[i];   /* no -0: "-0 0 1"
                                   ** and "0 0 1" would be one point written twice */
  strcpy(g.name, name);
  spans(&g);
  if (samples > 2) {
    for (i = 0; i < (size_t)samples; i++) g.vals[i] = exact(&g, (double)i / (samples - 1));
    g.samples = samples;
  }
  lsys_func_free(f);
  *f = g;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Reading. Line by line; a line is trimmed of blanks (and the CR of CRLF)
** and blank lines are skipped. */

typedef struct reader {
  const char *s; size_t len, pos;
  size_t line, at;          /* the next line's number; the current one's */
  const char *l; size_t ll; /* the current line, trimmed */
  const char *name;
  lsys_error *e;
} reader;

static int isblankc (int c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/* The next non-blank line into R->l / R->ll; 0 at the end of the text. */
static int nextline (reader *R) {
  while (R->pos < R->len) {
    size_t b = R->pos, e;
    while (R->pos < R->len && R->s[R->pos] != '\n') R->pos++;
    e = R->pos;
    R->at = R->line;
    if (R->pos < R->len) { R->pos++; R->line++; }
    while (b < e && isblankc((unsigned char)R->s[b])) b++;
    while (e > b && isblankc((unsigned char)R->s[e - 1])) e--;
    if (e > b) { R->l = R->s + b; R->ll = e - b; return 1; }
  }
  R->at = R->line;
  R->l = R->s + R->len; R->ll = 0;
  return 0;
}

static int error (reader *R, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 2, 3)))
#endif
  ;
static int error (reader *R, const char *fmt, ...) {
  va_list ap;
  int code;
  va_start(ap, fmt);
  code = lsys_vseterror_line(R->e, LSYS_ESYNTAX, R->at, R->name, R->at, fmt, ap);
  va_end(ap);
  return code;
}

/* The current line, quoted for a message. */
static const char *shown (const reader *R, char buf[LSYS_QUOTE + 1]) {
  return lsys_common_quote(buf, R->l, R->ll);
}

/* When the current line is "word: value" (blanks allowed before the colon),
** points *v at the value (trimmed) and returns 1. */
static int keyword (const reader *R, const char *word, const char **v, size_t *vl) {
  size_t k = strlen(word), i;
  if (R->ll < k || memcmp(R->l, word, k) != 0) return 0;
  for (i = k; i < R->ll && isblankc((unsigned char)R->l[i]); i++) {}
  if (i >= R->ll || R->l[i] != ':') return 0;
  for (i++; i < R->ll && isblankc((unsigned char)R->l[i]); i++) {}
  *v = R->l + i; *vl = R->ll - i;
  return 1;
}

/* Splits s[0..len) at blanks into at most 'max' tokens; returns how many
** there are (possibly more than max). */
static size_t split (const char *s, size_t len, const char **tok, size_t *tl, size_t max) {
  size_t i = 0, n = 0;
  while (i < len) {
    size_t b;
    while (i < len && isblankc((unsigned char)s[i])) i++;
    if (i >= len) break;
    b = i;
    while (i < len && !isblankc((unsigned char)s[i])) i++;
    if (n < max) { tok[n] = s + b; tl[n] = i - b; }
    n++;
  }
  return n;
}

/* A number strtod takes whole. */
static int tonum (const char *s, size_t len, double *x) {
  char buf[64], *end;
  if (len == 0 || len >= sizeof buf) return 0;
  memcpy(buf, s, len);
  buf[len] = '\0';
  *x = strtod(buf, &end);
  return end == buf + len;
}

/* A whole number from 0 to max. */
static int toint (const char *s, size_t len, long max, long *v) {
  size_t i;
  if (len == 0) return 0;
  for (*v = 0, i = 0; i < len; i++) {
    if (s[i] < '0' || s[i] > '9') return 0;
    *v = *v * 10 + (s[i] - '0');
    if (*v > max) return 0;
  }
  return 1;
}

/* "word: N" with 0 <= N <= max on the next line. */
static int count (reader *R, const char *word, long max, long *v) {
  const char *s;
  size_t sl;
  char b[LSYS_QUOTE + 1];
  if (!nextline(R)) return error(R, "expected '%s: N', got the end of the file", word);
  if (!keyword(R, word, &s, &sl))
    return error(R, "expected '%s: N', got '%s'", word, shown(R, b));
  if (!toint(s, sl, max, v))
    return error(R, "'%s' must be a whole number from 0 to %ld", word, max);
  return LSYS_OK;
}

/* The point lines: n of them, "x y" or (fver) "x y multiplicity"; appended
** to *pt (capacity *cap, count *np). */
static int points (reader *R, long n, int fver, double **pt, size_t *cap, size_t *np) {
  long i, m;
  for (i = 0; i < n; i++) {
    const char *tok[3];
    size_t tl[3], nt;
    double xy[2];
    char b[LSYS_QUOTE + 1];
    int c;
    if (!nextline(R)) return error(R, "the file ends after %ld of %ld points", i, n);
    nt = split(R->l, R->ll, tok, tl, 3);
    if (nt < 2 || nt > (fver ? 3u : 2u))
      return error(R, "expected 'x y%s', got '%s'", fver ? " [multiplicity]" : "",
                   shown(R, b));
    for (c = 0; c < 2; c++) {
      if (!tonum(tok[c], tl[c], &xy[c]))
        return error(R, "bad number '%s'", lsys_common_quote(b, tok[c], tl[c]));
      if (!isfinite(xy[c]) || fabs(xy[c]) > MAXCOORD)
        return error(R, "%c is %s", "xy"[c], isfinite(xy[c]) ?
                     "out of range (limit is 1e9)" : "not a finite number");
    }
    m = 1;
    if (nt == 3 && (!toint(tok[2], tl[2], LSYS_FUNC_MAXPOINTS, &m) || m < 1))
      return error(R, "the multiplicity must be a whole number from 1 to %d, got '%s'",
                   LSYS_FUNC_MAXPOINTS, lsys_common_quote(b, tok[2], tl[2]));
    if (*np > 0 && xy[0] < (*pt)[2 * *np - 2])
      return error(R, "x is %.17g, less than the x before it (%.17g)", xy[0],
                   (*pt)[2 * *np - 2]);
    if (*np + (size_t)m > LSYS_FUNC_MAXPOINTS)
      return error(R, "too many points (limit is %d)", LSYS_FUNC_MAXPOINTS);
    if (lsys_common_grow((void **)pt, cap, *np + (size_t)m, 2 * sizeof **pt) != LSYS_OK)
      return lsys_seterror(R->e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
    for (; m > 0; m--, (*np)++) { (*pt)[2 * *np] = xy[0]; (*pt)[2 * *np + 1] = xy[1]; }
  }
  return LSYS_OK;
}

/* The header lines of the fver 1 1 form after "fver 1 1": name, samples,
** background (skipped), markers (skipped), flip (ignored, as cpfg does). */
static int fverhead (reader *R, char *name, long *samples) {
  const char *v;
  size_t vl;
  long k, i;
  int st;
  char b[LSYS_QUOTE + 1];
  if (!nextline(R) || !keyword(R, "name", &v, &vl))
    return error(R, "expected 'name: NAME'%s", R->ll ? "" : ", got the end of the file");
  if (vl == 0 || vl > LSYS_FUNC_MAXNAME)
    return error(R, "the name must be 1 to %d bytes", LSYS_FUNC_MAXNAME);
  for (i = 0; i < (long)vl; i++)
    if ((unsigned char)v[i] < 0x20 || v[i] == 0x7f)
      return error(R, "the name has a control character");
  memcpy(name, v, vl);
  name[vl] = '\0';
  if ((st = count(R, "samples", LSYS_FUNC_MAXSAMPLES, samples)) != LSYS_OK) return st;
  for (;;) {
    size_t save = R->pos, line = R->line;
    if (!nextline(R)) return error(R, "expected 'points: N', got the end of the file");
    if (R->ll >= 10 && memcmp(R->l, "background", 10) == 0) continue;  /* editor's image */
    if (keyword(R, "markers", &v, &vl)) {
      if (!toint(v, vl, LSYS_FUNC_MAXPOINTS, &k))
        return error(R, "'markers' must be a whole number from 0 to %d", LSYS_FUNC_MAXPOINTS);
      for (i = 0; i < k; i++) {
        if (!nextline(R)) return error(R, "the file ends after %ld of %ld markers", i, k);
        if (R->l[0] != 'm') return error(R, "expected a marker 'mI x y', got '%s'", shown(R, b));
      }
      continue;
    }
    if (keyword(R, "flip", &v, &vl)) {
      if (!(vl == 2 && memcmp(v, "on", 2) == 0) && !(vl == 3 && memcmp(v, "off", 3) == 0))
        return error(R, "'flip' must be 'on' or 'off', got '%s'", lsys_common_quote(b, v, vl));
      continue;
    }
    R->pos = save; R->line = line;                /* the points line: read it again */
    return LSYS_OK;
  }
}

/* One function from the current position: its first line (the format line)
** is the current line. */
static int one (reader *R, lsys_func *f, int vsamples, const char *dflname) {
  char fname[LSYS_FUNC_MAXNAME + 1], b[LSYS_QUOTE + 1];
  const char *v;
  size_t vl, cap = 0, np = 0;
  long samples = vsamples > 0 ? vsamples : 0, n;
  double *pt = NULL, r[2];
  int fver, st;
  size_t headline = R->at;
  if (keyword(R, "range", &v, &vl)) {
    const char *tok[2];
    size_t tl[2];
    if (split(v, vl, tok, tl, 2) != 2 || !tonum(tok[0], tl[0], &r[0]) ||
        !tonum(tok[1], tl[1], &r[1]))
      return error(R, "expected 'range: 0.0 1.0', got '%s'", shown(R, b));
    fver = 0;
    snprintf(fname, sizeof fname, "%s", dflname);
  }
  else if (R->ll == 8 && memcmp(R->l, "fver 1 1", 8) == 0) {
    fver = 1;
    if ((st = fverhead(R, fname, &samples)) != LSYS_OK) return st;
  }
  else if (R->ll >= 4 && memcmp(R->l, "fver", 4) == 0)
    return error(R, "unsupported function version '%s' (only 'fver 1 1')", shown(R, b));
  else return error(R, "expected 'fver 1 1' or 'range: 0.0 1.0', got '%s'", shown(R, b));
  if ((st = count(R, "points", LSYS_FUNC_MAXPOINTS, &n)) != LSYS_OK) return st;
  if ((st = points(R, n, fver, &pt, &cap, &np)) != LSYS_OK) goto done;
  if ((st = lsys_func_set(f, pt, np, fname, (int)samples, R->e)) != LSYS_OK) {
    char msg[sizeof R->e->msg];
    if (st == LSYS_ENOMEM) goto done;
    memcpy(msg, R->e->msg, sizeof msg);         /* "point 3: ..." at the function's line */
    R->at = headline;
    st = error(R, "function '%s': %s", fname, msg);
  }
done:
  LSYS_FREE(pt);
  return st;
}

/* The name of the old form's function: the file name without folder and
** extension. */
static void basename_of (const char *path, char *out) {
  const char *b = strrchr(path, '/'), *dot;
  size_t len;
  b = b ? b + 1 : path;
  dot = strrchr(b, '.');
  len = dot && dot > b ? (size_t)(dot - b) : strlen(b);
  if (len == 0) { b = "function"; len = 8; }
  if (len > LSYS_FUNC_MAXNAME) len = LSYS_FUNC_MAXNAME;
  memcpy(out, b, len);
  out[len] = '\0';
  for (; *out; out++) if ((unsigned char)*out < 0x20 || *out == 0x7f) *out = '_';
}

int lsys_func_parse (lsys_func **out, size_t *nout, const char *text, size_t len,
                     const char *name, int samples, lsys_error *e) {
  reader R;
  lsys_func *fs = NULL;
  size_t nf = 0, want = 1, k;
  char dfl[LSYS_FUNC_MAXNAME + 1], b[LSYS_QUOTE + 1];
  int st = LSYS_OK;
  *out = NULL; *nout = 0;
  memset(&R, 0, sizeof R);
  R.s = text; R.len = text ? len : 0; R.line = 1; R.at = 1; R.name = name; R.e = e;
  basename_of(name, dfl);
  if (!nextline(&R)) return error(&R, "empty file (expected 'fver 1 1')");
  if (R.ll >= 14 && memcmp(R.l, "funcgalleryver", 14) == 0) {
    long items;
    if (!(R.ll == 18 && memcmp(R.l, "funcgalleryver 1 1", 18) == 0))
      return error(&R, "unsupported function set version '%s' (only 'funcgalleryver 1 1')",
                   shown(&R, b));
    if ((st = count(&R, "items", LSYS_FUNC_MAXITEMS, &items)) != LSYS_OK) return st;
    if (items == 0) return error(&R, "a function set needs at least 1 item");
    want = (size_t)items;
    if (!nextline(&R)) return error(&R, "the file ends before its first function");
  }
  fs = (lsys_func *)LSYS_MALLOC(want * sizeof *fs);
  if (fs == NULL) return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  for (k = 0; k < want; k++) lsys_func_init(&fs[k]);
  for (nf = 0; nf < want; nf++) {
    if (nf > 0 && !nextline(&R)) {
      st = error(&R, "the file ends after %zu of %zu functions", nf, want);
      break;
    }
    if (want > 1 && !(R.ll == 8 && memcmp(R.l, "fver 1 1", 8) == 0)) {
      st = error(&R, "expected 'fver 1 1' (function %zu of %zu), got '%s'", nf + 1, want,
                 shown(&R, b));
      break;
    }
    if ((st = one(&R, &fs[nf], samples, dfl)) != LSYS_OK) break;
  }
  if (st == LSYS_OK && nextline(&R))
    st = error(&R, "unexpected '%s' after the %s", shown(&R, b),
               want > 1 ? "last function" : "points");
  if (st != LSYS_OK) {
    for (k = 0; k < want; k++) lsys_func_free(&fs[k]);
    LSYS_FREE(fs);
    return st;
  }
  *out = fs; *nout = want;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Writing. */


size_t lsys_func_format (const lsys_func *f, char *buf, size_t size) {
  size_t len = 0, i, runs = 0;
  char a[32], c[32];
  int w;
#define PUT(...) do { w = snprintf(len < size ? buf + len : NULL, len < size ? size - len : 0, \
                                   __VA_ARGS__); if (w > 0) len += (size_t)w; } while (0)
  for (i = 0; i < f->n; i++)
    if (i == 0 || f->pt[2 * i] != f->pt[2 * i - 2] || f->pt[2 * i + 1] != f->pt[2 * i - 1]) runs++;
  PUT("fver 1 1\nname: %s\nsamples: %d\nflip: off\npoints: %zu\n", f->name, f->samples, runs);
  for (i = 0; i < f->n;) {
    size_t m = 1;
    while (i + m < f->n && f->pt[2 * (i + m)] == f->pt[2 * i] &&
           f->pt[2 * (i + m) + 1] == f->pt[2 * i + 1]) m++;
    lsys_common_shortest(a, f->pt[2 * i]);
    lsys_common_shortest(c, f->pt[2 * i + 1]);
    PUT("%s %s %zu\n", a, c, m);
    i += m;
  }
#undef PUT
  return len;
}
