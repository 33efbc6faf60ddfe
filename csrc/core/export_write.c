/*
** The export writers' buffered output and number formatting
** (export_impl.h).
*/
#include <float.h>
#include <math.h>
#include <string.h>

#include "export_impl.h"

/* ------------------------------------------------------------------ */
/* Buffered output                                                      */
/* ------------------------------------------------------------------ */

void lsys_export_wflush (lsys_writer *w) {
  lsys_outfile_write(&w->out, w->b, w->n);
  w->n = 0;
}

void lsys_export_wbytes (lsys_writer *w, const void *s, size_t n) {
  const unsigned char *p = (const unsigned char *)s;
  while (n > 0) {
    size_t k = n < WBUFSIZE ? n : WBUFSIZE;
    unsigned char *d = wroom(w, k);
    memcpy(d, p, k);
    wdone(w, d + k);
    p += k; n -= k;
  }
}

void lsys_export_wstr (lsys_writer *w, const char *s) {
  lsys_export_wbytes(w, s, strlen(s));
}

int lsys_export_wopen (lsys_writer **wp, const char *path, lsys_error *e) {
  lsys_writer *w = (lsys_writer *)LSYS_MALLOC(sizeof *w);
  int st;
  if (w == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if ((st = lsys_outfile_open(&w->out, path, e)) != LSYS_OK) {
    LSYS_FREE(w);
    return st;
  }
  w->n = 0;
  *wp = w;
  return LSYS_OK;
}

int lsys_export_wfinish (lsys_writer *w, lsys_error *e) {
  lsys_export_wflush(w);
  return lsys_outfile_finish(&w->out, e);
}

int lsys_export_wcommit (lsys_writer *w, lsys_error *e) {
  int st;
  lsys_export_wflush(w);
  st = lsys_outfile_commit(&w->out, e);
  LSYS_FREE(w);
  return st;
}

void lsys_export_wabort (lsys_writer *w) {
  if (w == NULL) return;
  lsys_outfile_abort(&w->out);
  LSYS_FREE(w);
}

/* ------------------------------------------------------------------ */
/* Number formatting                                                    */
/* ------------------------------------------------------------------ */

static const double P10[64] = {
  1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
  1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31,
  1e32, 1e33, 1e34, 1e35, 1e36, 1e37, 1e38, 1e39, 1e40, 1e41, 1e42, 1e43, 1e44, 1e45, 1e46,
  1e47, 1e48, 1e49, 1e50, 1e51, 1e52, 1e53, 1e54, 1e55, 1e56, 1e57, 1e58, 1e59, 1e60, 1e61,
  1e62, 1e63
};

/* x * 10^e for |e| < 64, with a single rounding. */
static double scale10 (double x, int e) {
  return e >= 0 ? x * P10[e] : x / P10[-e];
}

/*
** The fewest significant digits between 6 and 9 that read back as the same
** float: 9 always do, and 6 cover every shorter form.
**
** The digits come from a double scaled into [1e8, 1e9): a double carries 53
** bits where 9 decimal digits need 30, so they are exact except next to a
** tie, where being one unit off still stays within half a float ulp.
*/
char *lsys_export_putfloat (char *s, float f) {
  double a = f, m, v;
  uint64_t M = 0;
  int e2, k, kk = 0, p, i, nd;
  char dig[9];
  if (!isfinite(a) || a == 0) { *s++ = '0'; return s; }
  if (a < 0) { *s++ = '-'; a = -a; }
  (void)frexp(a, &e2);                         /* 2^(e2-1) <= a < 2^e2 */
  k = (int)floor((e2 - 1) * 0.30102999566398120);  /* floor(log10 a), or one less */
  m = scale10(a, 8 - k);
  if (m >= 1e9) { k++; m = scale10(a, 8 - k); }
  else if (m < 1e8) { k--; m = scale10(a, 8 - k); }
  for (p = 6; p <= 9; p++) {
    kk = k;
    M = (uint64_t)(m / P10[9 - p] + 0.5);
    if (M >= (uint64_t)P10[p]) { M /= 10; kk++; }   /* rounded up to 10^p */
    if (p == 9) break;
    v = scale10((double)M, kk - p + 1);
    if (v <= FLT_MAX && (float)v == (float)a) break;     /* (float) of more is undefined */
  }
  for (i = p - 1; i >= 0; i--) { dig[i] = (char)('0' + M % 10); M /= 10; }
  for (nd = p; nd > 1 && dig[nd - 1] == '0'; nd--) {}
  k = kk;                                      /* the value is 0.d1d2... * 10^(k+1) */
  if (k >= -4 && k < 9) {
    if (k >= 0) {
      for (i = 0; i <= k; i++) *s++ = i < nd ? dig[i] : '0';
      if (nd > k + 1) {
        *s++ = '.';
        for (i = k + 1; i < nd; i++) *s++ = dig[i];
      }
    }
    else {
      *s++ = '0'; *s++ = '.';
      for (i = -1; i > k; i--) *s++ = '0';
      for (i = 0; i < nd; i++) *s++ = dig[i];
    }
  }
  else {
    *s++ = dig[0];
    if (nd > 1) {
      *s++ = '.';
      for (i = 1; i < nd; i++) *s++ = dig[i];
    }
    *s++ = 'e';
    if (k < 0) { *s++ = '-'; k = -k; } else *s++ = '+';
    if (k < 10) *s++ = '0';
    s = putuint(s, (uint64_t)k);
  }
  return s;
}

void lsys_export_putvec (lsys_writer *w, const char *tag, const float *v, int n) {
  char *s = (char *)wroom(w, 64);
  int k;
  while (*tag) *s++ = *tag++;
  for (k = 0; k < n; k++) {
    *s++ = ' ';
    s = lsys_export_putfloat(s, fin(v[k]));
  }
  *s++ = '\n';
  wdone(w, s);
}
