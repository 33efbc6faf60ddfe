/*
** The text of a module string (docs/manual.md §8): cpfg notation, written into
** a buffer (lsys_lstring_format*) or streamed to a sink in chunks
** (lsys_lstring_write), with the same bytes either way.
**
** Two things cost time per module: deciding whether a space must separate a
** name from the names before it, and formatting parameters.
**
** Names. A name is "plain" when no text after it can change how it reads back:
** one UTF-8 character that is not '@', '?' or '~' and starts no longer declared
** name (lsys_alphabet_scan's rules). Only the last few parameterless names can
** merge with a new one, and only the ones that are not plain need a scan, so
** the writer remembers just those; a run of plain names is copied as it is.
**
** Numbers. A parameter is written as the shortest of %.15g, %.16g and %.17g
** that reads back as the same double (whole numbers below 1e15 in full). The
** digits come from exact integer arithmetic: for 1e-6 <= |x| < 1e15 the double
** m*2^-s times 10^k fits in 128 bits, so the 17-digit value, its rounding to
** 15 or 16 digits (half to even, as glibc's printf) and whether that rounding
** reads back (it is nearer to x than half the gap to x's neighbours) are all
** decided without printf or strtod. Other values, ties and the doubles at a
** power of two (whose lower gap is half the upper) go the slow way, through
** snprintf and strtod; the output is the same.
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lstring.h"

#define CHUNK (64 * 1024)      /* bytes handed to a sink at a time */
#define NCACHE 256             /* the writer's cache of formatted numbers */

/* ---------------------------------------------------------------------- */
/* numbers */

/* The old way, and the fallback: snprintf each precision, strtod to check. */
static int fmtslow (char *buf, size_t size, double x) {
  int prec;
  for (prec = 15; prec <= 17; prec++) {
    snprintf(buf, size, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) break;
  }
  return (int)strlen(buf);
}

static const char DIG2[] =
  "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
  "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
  "8081828384858687888990919293949596979899";

/* Writes the 'n' lowest decimal digits of 'v' at 'p' (zeros in front). */
static void putn (char *p, uint64_t v, int n) {
  while (n >= 2) {
    uint64_t q = v / 100;
    unsigned r = (unsigned)(v - q * 100);
    n -= 2;
    memcpy(p + n, DIG2 + 2 * r, 2);
    v = q;
  }
  if (n > 0) p[0] = (char)('0' + v % 10);
}

/* Writes the decimal digits of 'v' at 'p'; returns their count. */
static int putdigits (char *p, uint64_t v) {
  int n = 1;
  uint64_t t = v;
  while (t >= 10) { t /= 10; n++; }
  putn(p, v, n);
  return n;
}

/* %.0f of a whole number below 1e15 in magnitude (not zero). */
static int fmtwhole (char *buf, double x) {
  int n = 0;
  if (x < 0) { buf[n++] = '-'; x = -x; }
  n += putdigits(buf + n, (uint64_t)x);
  buf[n] = '\0';
  return n;
}

/* What %.Pg prints for the P digits 'd' (10^(P-1) <= d < 10^P) of a value
** d * 10^(X-P+1): exponent style when X < -4 or X >= P, trailing zeros removed. */
static int fmtg (char *buf, int neg, uint64_t d, int P, int X) {
  char dig[24];
  int n = 0, nd = P, k;
  putn(dig, d, P);
  while (nd > 1 && dig[nd - 1] == '0') nd--;        /* significant digits left */
  if (neg) buf[n++] = '-';
  if (X < -4 || X >= P) {
    int ex = X < 0 ? -X : X;
    buf[n++] = dig[0];
    if (nd > 1) { buf[n++] = '.'; memcpy(buf + n, dig + 1, (size_t)nd - 1); n += nd - 1; }
    buf[n++] = 'e';
    buf[n++] = X < 0 ? '-' : '+';
    if (ex < 10) buf[n++] = '0';
    n += putdigits(buf + n, (uint64_t)ex);
  } else if (X >= 0) {
    for (k = 0; k <= X; k++) buf[n++] = k < nd ? dig[k] : '0';
    if (nd > X + 1) {
      buf[n++] = '.';
      memcpy(buf + n, dig + X + 1, (size_t)(nd - X - 1));
      n += nd - X - 1;
    }
  } else {
    memcpy(buf + n, "0.0000", (size_t)(1 - X));      /* "0." and -X-1 zeros */
    n += 1 - X;
    memcpy(buf + n, dig, (size_t)nd);
    n += nd;
  }
  buf[n] = '\0';
  return n;
}

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 u128;

static const uint64_t POW10[20] = {
  1ull, 10ull, 100ull, 1000ull, 10000ull, 100000ull, 1000000ull, 10000000ull,
  100000000ull, 1000000000ull, 10000000000ull, 100000000000ull, 1000000000000ull,
  10000000000000ull, 100000000000000ull, 1000000000000000ull, 10000000000000000ull,
  100000000000000000ull, 1000000000000000000ull, 10000000000000000000ull
};

static u128 pow10x (int k) {          /* 10^k, 0 <= k <= 22 */
  return k < 20 ? (u128)POW10[k] : (u128)POW10[19] * POW10[k - 19];
}

/* %.Pg of the exact value q17 + r/2^s (times 10^-k, the 17 digits' exponent X),
** rounded half to even to P = 17 - log10(div) digits, when that reads back: it is
** nearer to |x| than half the gap 2^-s to its neighbours (in units of 10^-k, times
** 2^s: 2 dist < 10^k). Returns -1 when it does not, -2 at a tie (strtod decides). */
static inline int tryp (char *buf, int neg, uint64_t q17, u128 r, int s, int k, int X,
                        int P, const uint64_t div) {
  uint64_t d = q17 / div, rem = q17 - d * div, V;
  u128 T = ((u128)rem << s) + r, H = (u128)div << (s - 1), dist, ten = pow10x(k);
  if (T > H || (T == H && (d & 1))) d++;
  V = d * div;
  dist = V > q17 ? ((u128)(V - q17) << s) - r : ((u128)(q17 - V) << s) + r;
  if (2 * dist == ten) return -2;
  if (2 * dist > ten) return -1;
  if (d == POW10[P]) { d = POW10[P - 1]; X++; }
  return fmtg(buf, neg, d, P, X);
}

/* The shortest of %.15g/%.16g/%.17g that reads back, exactly; -1 when 'x' is
** outside the range where the arithmetic fits (or a case it leaves to the
** slow path). 'x' is finite, not zero and not whole. */
static int fmtfast (char *buf, double x) {
  uint64_t bits, m, q17, d;
  int E, s, X, k, P, neg;
  u128 N, r;
  memcpy(&bits, &x, sizeof bits);
  neg = (int)(bits >> 63);
  E = (int)((bits >> 52) & 0x7FF);
  m = bits & ((1ull << 52) - 1);
  if (E == 0 || E == 0x7FF || m == 0) return -1;     /* subnormal, not finite, 2^e */
  m |= 1ull << 52;
  s = 1075 - E;                                      /* |x| = m * 2^-s */
  if (s <= 0 || s > 80) return -1;                   /* |x| >= 2^52, or tiny */
  X = (int)floor((double)(E - 1023) * 0.30102999566398120);   /* ~ floor(log10|x|) */
  for (;;) {
    k = 16 - X;                                      /* 17 digits: q17 = |x| * 10^k */
    if (k < 0 || k > 22) return -1;
    N = (u128)m * pow10x(k);
    q17 = (uint64_t)(N >> s);
    if (q17 >= POW10[17]) X++;
    else if (q17 < POW10[16]) X--;
    else break;
  }
  r = N & (((u128)1 << s) - 1);                      /* |x|*10^k = q17 + r/2^s */
  if ((P = tryp(buf, neg, q17, r, s, k, X, 15, 100)) != -1) return P < 0 ? -1 : P;
  if ((P = tryp(buf, neg, q17, r, s, k, X, 16, 10)) != -1) return P < 0 ? -1 : P;
  d = q17;                                           /* %.17g always reads back */
  if (2 * r > ((u128)1 << s) || (2 * r == ((u128)1 << s) && (d & 1))) d++;
  if (d == POW10[17]) { d = POW10[16]; X++; }
  return fmtg(buf, neg, d, 17, X);
}

#else
static int fmtfast (char *buf, double x) { (void)buf; (void)x; return -1; }
#endif

int lsys_lstring_fmtnum_digits (char *buf, size_t size, double x, int digits) {
  int n;
  if (x == 0) return snprintf(buf, size, signbit(x) ? "-0" : "0");
  if (x == trunc(x) && fabs(x) < 1e15) {
    if (size >= 24) return fmtwhole(buf, x);
    return snprintf(buf, size, "%.0f", x);
  }
  if (digits > 0) return snprintf(buf, size, "%.*g", digits < 17 ? digits : 17, x);
  if (size >= 32 && (n = fmtfast(buf, x)) >= 0) return n;
  return fmtslow(buf, size, x);
}

int lsys_lstring_fmtnum (char *buf, size_t size, double x) {
  return lsys_lstring_fmtnum_digits(buf, size, x, 0);
}

/* ---------------------------------------------------------------------- */
/* names and the writer */

/* What the writer knows of a symbol, found when it first appears. */
enum { UNKNOWN = 0, PLAIN, SELFOK, MERGES };  /* SELFOK: reads back alone, not plain */

typedef struct writer {
  lsys_buf *b;
  lsys_lstring_sink sink;     /* NULL: everything stays in b */
  void *ud;
  const lsys_alphabet *a;
  const lsys_names *decl;
  size_t window;              /* how many names back a merge is looked for */
  size_t seq, wcount;         /* parameterless names since the last reset; in the window */
  size_t rs[16], rl[16], rq[16], nq;   /* the names not plain in the window: start, length,
                                          sequence number (oldest first) */
  uint8_t kind[LSYS_MAXSYM + 1];
  uint32_t len[LSYS_MAXSYM + 1];
  char byte[256];             /* narrow strings: 0 unknown, 1 not a plain one-byte name,
                                 else the byte the name is */
  struct { uint64_t bits; char len, txt[31]; } num[NCACHE];   /* numbers written lately:
                                 a string's parameters repeat (a depth's length, an angle) */
} writer;

/* Is 'name' (of 'len' bytes) one UTF-8 character? (it reads back alone) */
static int onechar (const char *name, size_t len) {
  unsigned char c = (unsigned char)name[0];
  return len == (c < 0x80 ? 1u : c >= 0xF0 ? 4u : c >= 0xE0 ? 3u : 2u);
}

static int classify (writer *w, uint32_t sym) {
  const char *name = lsys_alphabet_name(w->a, sym);
  size_t len = strlen(name), q;
  int k = lsys_alphabet_scan(name, len, w->decl) == len ? SELFOK : MERGES;
  if (k == SELFOK && name[0] != '@' && name[0] != '?' && name[0] != '~' &&
      onechar(name, len)) {
    k = PLAIN;
    if (w->decl != NULL)          /* a declared name other than it may start here */
      for (q = 0; q < w->decl->n; q++) {
        size_t dl = strlen(w->decl->v[q]);
        if ((dl != len || memcmp(w->decl->v[q], name, len) != 0) &&
            memcmp(w->decl->v[q], name, dl < len ? dl : len) == 0)
          k = SELFOK;
      }
  }
  w->len[sym] = (uint32_t)len;
  w->kind[sym] = (uint8_t)k;
  if (sym < 256) w->byte[sym] = (char)(k == PLAIN && len == 1 ? name[0] : 1);
  return k;
}

static int reserve (lsys_buf *b, size_t more) {
  if (b->n + more + 1 <= b->cap) return LSYS_OK;
  return lsys_common_grow((void **)&b->p, &b->cap, b->n + more + 1, 1);
}

/* Hands the text before the oldest name that may still merge to the sink. */
static int flush (writer *w, int all) {
  lsys_buf *b = w->b;
  size_t keep = (!all && w->nq > 0) ? w->rs[0] : b->n, q;
  int st;
  if (w->sink == NULL || keep == 0) return LSYS_OK;
  st = w->sink(w->ud, b->p, keep);
  if (st != LSYS_OK) return st;
  memmove(b->p, b->p + keep, b->n - keep);
  b->n -= keep;
  for (q = 0; q < w->nq; q++) w->rs[q] -= keep;
  return LSYS_OK;
}

static void reset (writer *w) { w->wcount = 0; w->nq = 0; }

/* Appends module k (code c, parameters at s->par + off). */
static int module (writer *w, const lsys_lstring *s, uint32_t c, size_t off, int digits) {
  lsys_buf *b = w->b;
  uint32_t sym = LSYS_CSYM(c), np = LSYS_CNP(c), m;
  const char *name = lsys_alphabet_name(w->a, sym);
  int kind = sym <= LSYS_MAXSYM ? (w->kind[sym] ? w->kind[sym] : classify(w, sym)) : MERGES;
  size_t len = sym <= LSYS_MAXSYM ? w->len[sym] : strlen(name), start = b->n, q;
  int split = 0;
  if (reserve(b, len + 8 + (size_t)np * 40) != LSYS_OK) return LSYS_ENOMEM;
  memcpy(b->p + b->n, name, len);
  b->n += len;
  for (q = 0; q < w->nq; q++)
    if (lsys_alphabet_scan(b->p + w->rs[q], b->n - w->rs[q], w->decl) != w->rl[q]) break;
  if (q < w->nq) split = 1;
  else if (w->wcount > 0 && np == 0 && kind == MERGES) split = 1;   /* it would not read back */
  if (split) {                           /* separate with a space */
    memmove(b->p + start + 1, b->p + start, len);
    b->p[start] = ' ';
    b->n++;
    start++;
    reset(w);
  }
  if (np > 0) {
    reset(w);
    for (m = 0; m < np; m++) {
      double x = s->par[off + m];
      uint64_t bits;
      unsigned h;
      b->p[b->n++] = m == 0 ? '(' : ',';
      memcpy(&bits, &x, sizeof bits);
      h = (unsigned)((bits * 0x9E3779B97F4A7C15ull) >> 56) % NCACHE;
      if (w->num[h].len == 0 || w->num[h].bits != bits) {
        int n = lsys_lstring_fmtnum_digits(b->p + b->n, 40, x, digits);
        if (n < (int)sizeof w->num[h].txt) {
          w->num[h].bits = bits;
          w->num[h].len = (char)n;
          memcpy(w->num[h].txt, b->p + b->n, (size_t)n);
        }
        b->n += (size_t)n;
      } else {
        memcpy(b->p + b->n, w->num[h].txt, sizeof w->num[h].txt);   /* the reserve allows it */
        b->n += (size_t)w->num[h].len;
      }
    }
    b->p[b->n++] = ')';
  } else {
    w->seq++;
    if (w->wcount < w->window) w->wcount++;
    if (w->nq > 0 && w->seq - w->rq[0] >= w->window) {   /* the oldest leaves the window */
      memmove(w->rs, w->rs + 1, (w->nq - 1) * sizeof *w->rs);
      memmove(w->rl, w->rl + 1, (w->nq - 1) * sizeof *w->rl);
      memmove(w->rq, w->rq + 1, (w->nq - 1) * sizeof *w->rq);
      w->nq--;
    }
    if (kind != PLAIN) {
      w->rs[w->nq] = start; w->rl[w->nq] = len; w->rq[w->nq] = w->seq; w->nq++;
    }
  }
  return LSYS_OK;
}

/* Copies a run of narrow modules whose names are plain single bytes, from k;
** returns where the run ends. */
static size_t narrowrun (writer *w, const lsys_lstring *s, size_t k, size_t j) {
  lsys_buf *b = w->b;
  size_t room = b->cap - b->n - 1, end = j - k < room ? j : k + room, k0 = k;
  char *p = b->p + b->n;
  const uint8_t *sym = s->sym8;
  while (k < end) {
    char ch = w->byte[sym[k]];
    if (ch == 0) {
      if (sym[k] >= w->a->n) break;
      classify(w, sym[k]);
      continue;
    }
    if (ch == 1) break;
    *p++ = ch;
    k++;
  }
  b->n += k - k0;
  w->seq += k - k0;
  w->wcount = k - k0 >= w->window ? w->window
            : (w->wcount + (k - k0) < w->window ? w->wcount + (k - k0) : w->window);
  return k;
}

static int run (writer *w, lsys_lstring *s, size_t i, size_t j, int digits) {
  size_t k, off = lsys_lstring_poff(s, i), q;
  int st;
  w->window = 4;
  if (w->decl != NULL)
    for (q = 0; q < w->decl->n; q++)
      if (strlen(w->decl->v[q]) + 1 > w->window) w->window = strlen(w->decl->v[q]) + 1;
  if (w->window > 16) w->window = 16;
  w->seq = 0;
  reset(w);
  memset(w->kind, 0, sizeof w->kind);
  memset(w->byte, 0, sizeof w->byte);
  for (q = 0; q < NCACHE; q++) w->num[q].len = 0;
  for (k = i; k < j;) {
    uint32_t c;
    if (s->sym8 != NULL && w->nq == 0) {
      if (reserve(w->b, CHUNK) != LSYS_OK) return LSYS_ENOMEM;
      k = narrowrun(w, s, k, j);
      if (w->b->n >= CHUNK && (st = flush(w, 0)) != LSYS_OK) return st;
      if (k >= j) break;
      if (w->byte[s->sym8[k]] > 1) continue;  /* the buffer was full */
    }
    c = lsys_lstring_code(s, k);
    if ((st = module(w, s, c, off, digits)) != LSYS_OK) return st;
    off += LSYS_CNP(c);
    k++;
    if (w->b->n >= CHUNK && (st = flush(w, 0)) != LSYS_OK) return st;
  }
  return flush(w, 1);
}

int lsys_lstring_format (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a,
                         const lsys_names *decl, size_t i, size_t j) {
  return lsys_lstring_format_digits(b, s, a, decl, i, j, 0);
}

static int go (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a, const lsys_names *decl,
               size_t i, size_t j, int digits, lsys_lstring_sink sink, void *ud) {
  writer *w = (writer *)LSYS_MALLOC(sizeof *w);
  int st;
  if (w == NULL) return LSYS_ENOMEM;
  w->b = b; w->sink = sink; w->ud = ud; w->a = a; w->decl = decl;
  st = reserve(b, 0);
  if (st == LSYS_OK) st = run(w, s, i, j, digits);
  if (b->p != NULL) b->p[b->n] = '\0';
  LSYS_FREE(w);
  return st;
}

int lsys_lstring_format_digits (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a,
                                const lsys_names *decl, size_t i, size_t j, int digits) {
  return go(b, s, a, decl, i, j, digits, NULL, NULL);
}

int lsys_lstring_write (lsys_lstring *s, const lsys_alphabet *a, const lsys_names *decl,
                        size_t i, size_t j, int digits, lsys_lstring_sink sink, void *ud) {
  lsys_buf b = {0};
  int st = go(&b, s, a, decl, i, j, digits, sink, ud);
  lsys_lstring_buf_free(&b);
  return st;
}
