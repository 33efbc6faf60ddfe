/*
** Error record, growable arrays, the memory budget and whole-file reading
** shared by the core.
*/
#define _XOPEN_SOURCE 700       /* fileno, fstat, sysconf */
#if defined(__linux__) && !defined(_DEFAULT_SOURCE)
#define _DEFAULT_SOURCE         /* madvise */
#endif
#include <errno.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common.h"

int lsys_seterror (lsys_error *e, int code, size_t pos, const char *fmt, ...) {
  if (e != NULL) {
    va_list ap;
    e->code = code;
    e->pos = pos;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
  }
  return code;
}

int lsys_vseterror_at (lsys_error *e, int code, size_t pos, const char *where,
                       const char *fmt, va_list ap) {
  char msg[200];
  vsnprintf(msg, sizeof msg, fmt, ap);
  return lsys_seterror(e, code, pos, "%s: %s", where, msg);
}

int lsys_vseterror_line (lsys_error *e, int code, size_t pos, const char *name, size_t line,
                         const char *fmt, va_list ap) {
  char where[sizeof e->msg];    /* a longer place would be cut from the message anyway */
  snprintf(where, sizeof where, "%s:%zu", name, line);
  return lsys_vseterror_at(e, code, pos, where, fmt, ap);
}

/* (common.h) Linux's transparent huge pages, on request: a big block's
** first touch then costs a fault every 2 MiB, not every 4 KiB. The whole
** block is marked, its pages included where it starts and ends, so that the
** mapping stays one piece (realloc can then move it with mremap, which does
** not span mappings of different kinds); what it grows into later stays
** marked. Blocks under 4 MiB are left alone. */
void lsys_common_hugepages (void *p, size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const uintptr_t page = 4096;
  uintptr_t a = (uintptr_t)p & ~(page - 1), b = ((uintptr_t)p + n + page - 1) & ~(page - 1);
  if (n >= ((size_t)4 << 20)) madvise((void *)a, b - a, MADV_HUGEPAGE);
#else
  (void)p; (void)n;
#endif
}

int lsys_common_grow (void **p, size_t *cap, size_t need, size_t elem) {
  size_t ncap = *cap ? *cap : 16;
  void *np;
  if (need <= *cap) return LSYS_OK;
  while (ncap < need) {
    if (ncap > ((size_t)-1 / 2) / elem) return LSYS_ENOMEM;
    ncap *= 2;
  }
  np = LSYS_REALLOC(*p, ncap * elem);
  if (np == NULL) return LSYS_ENOMEM;
  lsys_common_hugepages(np, ncap * elem);
  *p = np;
  *cap = ncap;
  return LSYS_OK;
}

static int take (lsys_meter *mt, size_t cap, size_t need, size_t elem, size_t *ncap) {
  size_t n = cap ? cap : 16, old = cap * elem, base, maxcap;
  base = mt->used > old ? mt->used - old : 0;          /* all but this block */
  maxcap = mt->limit > base ? (mt->limit - base) / elem : 0;
  if (need > maxcap) {
    mt->hit = 1;
    return LSYS_EMEMORY;
  }
  while (n < need) {
    if (n > ((size_t)-1 / 2) / elem) return LSYS_ENOMEM;
    n *= 2;
  }
  if (n > maxcap) n = maxcap;                           /* as much as the budget leaves */
  mt->used = base + n * elem;
  *ncap = n;
  return LSYS_OK;
}

int lsys_common_meter_take (lsys_meter *mt, size_t cap, size_t need, size_t elem, size_t *ncap) {
  int st;
  if (mt->lock == NULL) return take(mt, cap, need, elem, ncap);
  pthread_mutex_lock((pthread_mutex_t *)mt->lock);
  st = take(mt, cap, need, elem, ncap);
  pthread_mutex_unlock((pthread_mutex_t *)mt->lock);
  return st;
}

int lsys_common_grow_metered (void **p, size_t *cap, size_t need, size_t elem, lsys_meter *mt) {
  size_t ncap;
  void *np;
  int st;
  if (need <= *cap) return LSYS_OK;
  if (mt == NULL) return lsys_common_grow(p, cap, need, elem);
  if ((st = lsys_common_meter_take(mt, *cap, need, elem, &ncap)) != LSYS_OK) return st;
  np = LSYS_REALLOC(*p, ncap * elem);
  if (np == NULL) return LSYS_ENOMEM;
  lsys_common_hugepages(np, ncap * elem);
  *p = np;
  *cap = ncap;
  return LSYS_OK;
}

int lsys_common_meter_fits (const lsys_meter *mt, size_t bytes) {
  return mt == NULL || (mt->used <= mt->limit && bytes <= mt->limit - mt->used);
}

static size_t memlimit;       /* set by lsys_common_set_memory_limit; 0: the default */

/* A cgroup's memory limit (v2, then v1), or 0 when there is none. */
static size_t cgrouplimit (void) {
  static const char *const files[] = {"/sys/fs/cgroup/memory.max",
                                      "/sys/fs/cgroup/memory/memory.limit_in_bytes"};
  size_t k;
  for (k = 0; k < 2; k++) {
    FILE *f = fopen(files[k], "r");
    unsigned long long v;
    int n;
    if (f == NULL) continue;
    n = fscanf(f, "%llu", &v);
    fclose(f);
    if (n == 1 && v > 0 && v < (unsigned long long)((size_t)-1 / 2)) return (size_t)v;
  }
  return 0;
}

size_t lsys_common_physical_memory (void) {
  long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  size_t phys = pages > 0 && size > 0 ? (size_t)pages * (size_t)size : 0, cg = cgrouplimit();
  if (cg > 0 && (phys == 0 || cg < phys)) phys = cg;
  return phys;
}

size_t lsys_common_memory_limit (void) {
  static size_t def;
  if (memlimit > 0) return memlimit;
  if (def == 0) {
    size_t phys = lsys_common_physical_memory();
    def = phys > 0 ? phys / 2 : (size_t)1 << 32;       /* unknown: 4 GiB */
  }
  return def;
}

void lsys_common_set_memory_limit (size_t bytes) {
  memlimit = bytes;
}

const char *lsys_common_quote (char buf[LSYS_QUOTE + 1], const char *s, size_t n) {
  size_t i, k = n > LSYS_QUOTE ? LSYS_QUOTE - 4 : n;
  for (i = 0; i < k; i++) {
    unsigned char c = (unsigned char)s[i];
    buf[i] = c >= 0x20 && c < 0x7f ? (char)c : '?';
  }
  if (n > k) { memcpy(buf + k, "...", 3); k += 3; }
  buf[k] = '\0';
  return buf;
}

void lsys_common_shortest (char buf[32], double x) {
  int p;
  for (p = 1; p <= 17; p++) {
    snprintf(buf, 32, "%.*g", p, x);
    if (strtod(buf, NULL) == x) return;
  }
}

const char *lsys_common_fmtsize (char buf[32], size_t bytes) {
  double x = (double)bytes;
  if (bytes == (size_t)-1) snprintf(buf, 32, "no limit");
  else if (x >= 1024.0 * 1024 * 1024) snprintf(buf, 32, "%.1f GiB", x / (1024.0 * 1024 * 1024));
  else if (x >= 1024.0 * 1024) snprintf(buf, 32, "%.0f MiB", x / (1024.0 * 1024));
  else if (x >= 1024.0) snprintf(buf, 32, "%.0f KiB", x / 1024.0);
  else snprintf(buf, 32, "%zu bytes", bytes);
  return buf;
}

char *lsys_common_readfile (const char *path, size_t max, size_t *len, lsys_error *e) {
  FILE *f = fopen(path, "rb");
  char *buf = NULL, *nb;
  size_t cap = 0, n = 0;
  struct stat st;
  if (f == NULL) {
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s': %s", path, strerror(errno));
    return NULL;
  }
  if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
    fclose(f);
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path,
                  S_ISDIR(st.st_mode) ? strerror(EISDIR) : "not a regular file");
    return NULL;
  }
  if ((size_t)st.st_size > max) {
    char b[32];
    fclose(f);
    lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot read '%s': larger than %s", path,
                  lsys_common_fmtsize(b, max));
    return NULL;
  }
  for (;;) {
    if (n == cap) {             /* capacity up to max + 1, to see a larger file */
      cap = cap == 0 ? 4096 : 2 * cap > max ? max + 1 : 2 * cap;
      if ((nb = (char *)LSYS_REALLOC(buf, cap)) == NULL) {
        lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
        break;
      }
      buf = nb;
    }
    n += fread(buf + n, 1, cap - n, f);
    if (n > max) {            /* it grew while we read it */
      char b[32];
      lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot read '%s': larger than %s", path,
                    lsys_common_fmtsize(b, max));
      break;
    }
    if (ferror(f)) {
      lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path, strerror(errno));
      break;
    }
    if (feof(f)) {
      fclose(f);
      *len = n;
      return buf;
    }
  }
  fclose(f);
  LSYS_FREE(buf);
  return NULL;
}
