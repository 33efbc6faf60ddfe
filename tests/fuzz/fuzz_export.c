/*
** libFuzzer target for the export writers (csrc/core/mesh.c: OBJ with its MTL,
** binary PLY, glTF binary). A mesh is built from the input (vertices with
** positions, normals, uv, colour and texture indices, triangles, line
** segments, a palette of materials, textures with and without files, and
** now and then a triangle that refers to a vertex that does not exist),
** written to a temporary directory in the three formats and read back by
** the small readers below. Crashes, leaks and sanitizer reports are
** failures, and so is a file that does not hold the mesh:
**
**   OBJ: the v, vn, vt, f and l lines count what the mesh has; every
**   number is finite and reads back as the float it stands for (non-finite
**   ones as 0); faces and segments refer to existing vertices; every
**   usemtl names a material of the MTL file, whose numbers are finite.
**   PLY: the header's element counts, the file length, the vertex, face
**   and edge records.
**   GLB: the 12-byte header, the JSON and BIN chunks (lengths, alignment,
**   the file length), JSON that is balanced and has only finite numbers,
**   the accessors' counts, the buffer length, and the binary data (finite
**   positions as written, unit normals, indices within the vertices, the
**   triangles and segment end points of the mesh).
**   A mesh with a bad triangle is refused by all three with LSYS_EARG; a
**   texture whose file is not a PNG (or is missing) fails the GLB only. A
**   failed write creates no file, and no temporary file is left behind
**   (outputs are atomic: csrc/core/outfile.h).
** FUZZ_TRACE=1 in the environment prints the mesh's counts and the sizes.
**
**   tools/fuzz.sh 600 export       (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_export
**   build-fuzz/fuzz_export -max_total_time=600 tests/fuzz/corpus_export
*/
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "export.h"
#include "mesh.h"
#include "pngio.h"

#define T(c) do { if (!(c)) __builtin_trap(); } while (0)

static int tracing = -1;       /* FUZZ_TRACE set: print the mesh and the file sizes */

/* ---------------------------------------------------------------------- */
/* The input */

typedef struct rd { const uint8_t *p; size_t n; } rd;

static unsigned byte (rd *r) {
  if (r->n == 0) return 0;
  r->n--;
  return *r->p++;
}

/* A float: the low 5 bits pick a value, the high 3 a scale; 7: 4 raw bytes. */
static float fl (rd *r) {
  static const float vals[32] = {
    0, 1, -1, 0.5f, 2, -0.0f, 1e-3f, 123.456f, 1e30f, -1e30f, FLT_MAX, -FLT_MAX, FLT_MIN,
    1e-40f, 0.1f, 3.14159265f, 1e-7f, 65504, 16777218, 0.333333343f, 0.75f, 100, -5, 1e9f,
    0.25f, 0.999999f, 1.00001f, 7, 42, -0.5f, 0, 0
  };
  static const float scale[7] = {1, 10, 0.01f, -3, 1000, 1e-20f, 7};
  unsigned b = byte(r);
  if ((b & 31) == 30) return NAN;
  if ((b & 31) == 31) return (b & 32) ? -INFINITY : INFINITY;
  if ((b >> 5) == 7) {
    uint32_t u = byte(r) | byte(r) << 8 | byte(r) << 16 | (uint32_t)byte(r) << 24;
    float f;
    memcpy(&f, &u, 4);
    return f;
  }
  return vals[b & 31] * scale[b >> 5];
}

/* ---------------------------------------------------------------------- */
/* Helpers */

static char *slurp (const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *s = NULL;
  size_t n = 0, cap = 0, k;
  if (f == NULL) return NULL;
  for (;;) {
    if (n + 1 >= cap) {
      char *t = (char *)realloc(s, cap = cap ? 2 * cap : 65536);
      T(t != NULL);
      s = t;
    }
    k = fread(s + n, 1, cap - n - 1, f);
    n += k;
    if (k == 0) break;
  }
  fclose(f);
  s[n] = '\0';
  *len = n;
  return s;
}

static float finf (float x) { return isfinite(x) ? x : 0.0f; }

static int samebits (float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

static uint32_t get32 (const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float getf (const unsigned char *p) {
  uint32_t u = get32(p);
  float f;
  memcpy(&f, &u, 4);
  return f;
}

/* An order-independent digest of triangles (a multiset). */
static uint64_t mix (uint64_t a, uint64_t b, uint64_t c) {
  uint64_t z = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
               (c + 0x7F4A7C159E3779B9ull) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return z * 0xD6E8FEB86659FD93ull;
}

static uint64_t trisum (const lsys_mesh *m) {
  uint64_t s = 0;
  size_t t;
  for (t = 0; t < m->nt; t++) s += mix(m->tri[3 * t], m->tri[3 * t + 1], m->tri[3 * t + 2]);
  return s;
}

/* The segments in the writers' order: stable by colour slot (lcol % nmat). */
static void lineorder (const lsys_mesh *m, size_t nmat, uint32_t *ord) {
  size_t k, i, n = 0;
  size_t slots = nmat < 65536 ? nmat : 65536;
  for (k = 0; k < slots && n < m->nl; k++)
    for (i = 0; i < m->nl; i++)
      if (m->lcol[i] % slots == k) ord[n++] = (uint32_t)i;
}

/* ---------------------------------------------------------------------- */
/* OBJ and MTL */

/* Reads 'n' numbers after the tag at 's'; all must be finite floats. */
static const char *numbers (const char *s, float *v, int n) {
  int k;
  for (k = 0; k < n; k++) {
    char *end;
    T(*s == ' ');
    v[k] = strtof(s + 1, &end);
    T(end > s + 1 && isfinite(v[k]));
    s = end;
  }
  T(*s == '\n');
  return s + 1;
}

static int hasname (const char *mtl, const char *name, size_t len) {
  const char *s = mtl;
  while ((s = strstr(s, "newmtl ")) != NULL) {
    s += 7;
    if (strncmp(s, name, len) == 0 && s[len] == '\n') return 1;
  }
  return 0;
}

static void checkmtl (const char *mtl) {
  const char *s = mtl;
  while (*s) {
    const char *e = strchr(s, '\n');
    float v[3];
    T(e != NULL);
    if (*s == '#' || *s == '\n') { s = e + 1; continue; }
    if (strncmp(s, "newmtl m", 8) == 0 || strncmp(s, "illum ", 6) == 0 ||
        strncmp(s, "map_Kd ", 7) == 0) { s = e + 1; continue; }
    if (strncmp(s, "Ka", 2) == 0 || strncmp(s, "Kd", 2) == 0 || strncmp(s, "Ks", 2) == 0 ||
        strncmp(s, "Ke", 2) == 0) {
      int k;
      s = numbers(s + 2, v, 3);
      for (k = 0; k < 3; k++) T(v[k] >= 0 && v[k] <= 1);
      continue;
    }
    if (strncmp(s, "Ns", 2) == 0) { s = numbers(s + 2, v, 1); continue; }
    if (strncmp(s, "d ", 2) == 0) { s = numbers(s + 1, v, 1); T(v[0] >= 0 && v[0] <= 1); continue; }
    __builtin_trap();                    /* a line the MTL writer does not write */
  }
}

static void checkobj (const lsys_mesh *m, const uint32_t *lord, const char *obj,
                      const char *mtl) {
  const char *s = obj;
  size_t nv = 0, nvn = 0, nvt = 0, nf = 0, nl = 0;
  uint64_t fsum = 0;
  while (*s) {
    const char *e = strchr(s, '\n');
    float v[3];
    T(e != NULL);
    if (*s == '#') { s = e + 1; continue; }
    if (strncmp(s, "mtllib ", 7) == 0) { T(strncmp(s + 7, "m.mtl\n", 6) == 0); s = e + 1; }
    else if (strncmp(s, "usemtl ", 7) == 0) {
      T(hasname(mtl, s + 7, (size_t)(e - s - 7)));
      s = e + 1;
    }
    else if (strncmp(s, "v ", 2) == 0) {
      s = numbers(s + 1, v, 3);
      if (nv < m->nv) {
        const float *p = m->pos + 3 * nv;
        T(v[0] == finf(p[0]) && v[1] == finf(p[1]) && v[2] == finf(p[2]));
      }
      else {
        size_t i = nv - m->nv;             /* segment end points, by material */
        T(i < 2 * m->nl);
        {
          const float *p = m->lpos + 6 * (size_t)lord[i / 2] + 3 * (i % 2);
          T(v[0] == finf(p[0]) && v[1] == finf(p[1]) && v[2] == finf(p[2]));
        }
      }
      nv++;
    }
    else if (strncmp(s, "vn ", 3) == 0) {
      s = numbers(s + 2, v, 3);
      T(nvn < m->nv);
      T(v[0] == finf(m->nrm[3 * nvn]) && v[1] == finf(m->nrm[3 * nvn + 1]) &&
        v[2] == finf(m->nrm[3 * nvn + 2]));
      nvn++;
    }
    else if (strncmp(s, "vt ", 3) == 0) {
      s = numbers(s + 2, v, 2);
      T(nvt < m->nv);
      T(v[0] == finf(m->uv[2 * nvt]) && v[1] == finf(m->uv[2 * nvt + 1]));
      nvt++;
    }
    else if (strncmp(s, "f ", 2) == 0) {
      unsigned long a[3][3];
      int k;
      T(sscanf(s, "f %lu/%lu/%lu %lu/%lu/%lu %lu/%lu/%lu", &a[0][0], &a[0][1], &a[0][2],
               &a[1][0], &a[1][1], &a[1][2], &a[2][0], &a[2][1], &a[2][2]) == 9);
      for (k = 0; k < 3; k++)
        T(a[k][0] >= 1 && a[k][0] <= m->nv && a[k][1] == a[k][0] && a[k][2] == a[k][0]);
      fsum += mix(a[0][0] - 1, a[1][0] - 1, a[2][0] - 1);
      nf++;
      s = e + 1;
    }
    else if (strncmp(s, "l ", 2) == 0) {
      unsigned long a, b;
      T(sscanf(s, "l %lu %lu", &a, &b) == 2);
      T(a > m->nv && b == a + 1 && b <= m->nv + 2 * m->nl && (a - m->nv) % 2 == 1);
      nl++;
      s = e + 1;
    }
    else __builtin_trap();               /* a line the OBJ writer does not write */
  }
  T(nv == m->nv + 2 * m->nl && nvn == m->nv && nvt == m->nv && nf == m->nt && nl == m->nl);
  T(fsum == trisum(m));
  checkmtl(mtl);
}

/* ---------------------------------------------------------------------- */
/* PLY */

static size_t element (const char *head, const char *name) {
  char key[64];
  const char *s;
  snprintf(key, sizeof key, "\nelement %s ", name);
  s = strstr(head, key);
  return s ? (size_t)strtoul(s + strlen(key), NULL, 10) : (size_t)-1;
}

static void checkply (const lsys_mesh *m, const unsigned char *f, size_t len) {
  const char *end = strstr((const char *)f, "\nend_header\n");
  const unsigned char *p;
  size_t hlen, nverts = m->nv + 2 * m->nl, i;
  T(strncmp((const char *)f, "ply\nformat binary_little_endian 1.0\n", 36) == 0 && end != NULL);
  hlen = (size_t)(end - (const char *)f) + 12;
  T(element((const char *)f, "vertex") == nverts);
  T(element((const char *)f, "face") == m->nt);
  T(element((const char *)f, "edge") == (m->nl ? m->nl : (size_t)-1));
  T(len == hlen + 35 * nverts + 13 * m->nt + 8 * m->nl);
  p = f + hlen;
  for (i = 0; i < nverts; i++, p += 35) {
    int k;
    for (k = 0; k < 8; k++) T(isfinite(getf(p + 4 * k)));
    if (i < m->nv) {
      for (k = 0; k < 3; k++) {
        T(samebits(getf(p + 4 * k), finf(m->pos[3 * i + k])));
        T(samebits(getf(p + 12 + 4 * k), finf(m->nrm[3 * i + k])));
      }
      T(samebits(getf(p + 24), finf(m->uv[2 * i])));
      T(samebits(getf(p + 28), finf(m->uv[2 * i + 1])));
    }
    else {
      const float *q = m->lpos + 3 * (i - m->nv);      /* in the mesh's order */
      for (k = 0; k < 3; k++) T(samebits(getf(p + 4 * k), finf(q[k])));
      for (k = 3; k < 8; k++) T(getf(p + 4 * k) == 0);
    }
  }
  for (i = 0; i < m->nt; i++, p += 13) {
    T(p[0] == 3);
    T(get32(p + 1) == m->tri[3 * i] && get32(p + 5) == m->tri[3 * i + 1] &&
      get32(p + 9) == m->tri[3 * i + 2]);
  }
  for (i = 0; i < m->nl; i++, p += 8)
    T(get32(p) == m->nv + 2 * i && get32(p + 4) == m->nv + 2 * i + 1);
}

/* ---------------------------------------------------------------------- */
/* GLB */

/* The length of the JSON number at 's' (RFC 8259 grammar), 0 if none. */
static size_t jsonnum (const char *s, size_t n) {
  size_t i = 0, d;
  if (i < n && s[i] == '-') i++;
  if (i < n && s[i] == '0') i++;
  else if (i < n && s[i] >= '1' && s[i] <= '9') while (i < n && s[i] >= '0' && s[i] <= '9') i++;
  else return 0;
  if (i < n && s[i] == '.') {
    for (d = ++i; i < n && s[i] >= '0' && s[i] <= '9'; i++) {}
    if (i == d) return 0;
  }
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    i++;
    if (i < n && (s[i] == '+' || s[i] == '-')) i++;
    for (d = i; i < n && s[i] >= '0' && s[i] <= '9'; i++) {}
    if (i == d) return 0;
  }
  return i < n && ((s[i] >= '0' && s[i] <= '9') || s[i] == '.') ? 0 : i;
}

/* JSON: balanced, strings closed, only true/false/null as words, finite
** numbers. */
static void checkjson (const char *j, size_t n) {
  size_t i;
  int depth = 0;
  char stack[64];
  for (i = 0; i < n; i++) {
    char c = j[i];
    T((unsigned char)c >= 0x20 && (unsigned char)c < 0x7f);
    if (c == '"') {
      for (i++; i < n && j[i] != '"'; i++) T(j[i] != '\\' && (unsigned char)j[i] >= 0x20);
      T(i < n);
    }
    else if (c == '{' || c == '[') { T(depth < 64); stack[depth++] = c; }
    else if (c == '}' || c == ']') {
      T(depth > 0 && stack[depth - 1] == (c == '}' ? '{' : '['));
      depth--;
      if (depth == 0) {                  /* only padding after the end */
        for (i++; i < n; i++) T(j[i] == ' ');
        return;
      }
    }
    else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t k = jsonnum(j + i, n - i);
      T(k > 0 && isfinite(strtod(j + i, NULL)));
      i += k - 1;
    }
    else if (c >= 'a' && c <= 'z') {
      T(strncmp(j + i, "true", 4) == 0 || strncmp(j + i, "false", 5) == 0 ||
        strncmp(j + i, "null", 4) == 0);
      while (i + 1 < n && j[i + 1] >= 'a' && j[i + 1] <= 'z') i++;
    }
    else T(c == ',' || c == ':' || c == ' ');
  }
  __builtin_trap();                      /* never closed */
}

/* The number after "key": inside [s, e), or -1. */
static long long field (const char *s, const char *e, const char *key) {
  size_t kl = strlen(key);
  for (; s + kl < e; s++)
    if (memcmp(s, key, kl) == 0) return strtoll(s + kl, NULL, 10);
  return -1;
}

static void checkglb (const lsys_mesh *m, const uint32_t *lord, const unsigned char *f,
                      size_t len) {
  uint32_t jlen, blen = 0;
  const char *j, *acc;
  const unsigned char *bin = NULL, *p;
  size_t i, vbytes, ibytes, lbytes, nacc = 0;
  long long sumidx = 0, sumline = 0;
  uint64_t isum = 0;
  T(len >= 20 && len % 4 == 0);
  T(get32(f) == 0x46546C67u && get32(f + 4) == 2 && get32(f + 8) == len);
  jlen = get32(f + 12);
  T(get32(f + 16) == 0x4E4F534Au && jlen % 4 == 0 && jlen <= len - 20);
  j = (const char *)f + 20;
  if (20 + (size_t)jlen < len) {
    T(len - 20 - jlen >= 8);
    blen = get32(f + 20 + jlen);
    T(get32(f + 24 + jlen) == 0x004E4942u && blen % 4 == 0);
    T((size_t)28 + jlen + blen == len);
    bin = f + 28 + jlen;
  }
  checkjson(j, jlen);
  if (m->nt == 0 && m->nl == 0) {
    T(strstr(j, "\"scenes\":[{}]") != NULL && blen == 0);
    return;
  }
  T(bin != NULL);
  T(field(j, j + jlen, "\"buffers\":[{\"byteLength\":") == (long long)blen);
  acc = strstr(j, "\"accessors\":[");
  T(acc != NULL);
  for (acc += 13; *acc == '{' || *acc == ',';) {      /* one accessor object at a time */
    const char *b = *acc == ',' ? acc + 1 : acc, *e = strchr(b, '}');
    long long count, ct;
    /* "min"/"max" arrays hold no braces: the object ends at the first '}' */
    T(*b == '{' && e != NULL);
    count = field(b, e, "\"count\":");
    ct = field(b, e, "\"componentType\":");
    T(count > 0);
    if (m->nt > 0 && nacc < 3) T(count == (long long)m->nv && ct == 5126);
    else if (ct == 5125) sumidx += count;
    else { T(ct == 5126); sumline += count; }
    nacc++;
    acc = e + 1;
  }
  T(*acc == ']');
  T(sumidx == 3 * (long long)m->nt && sumline == 2 * (long long)m->nl);
  /* the binary data */
  vbytes = m->nt ? 32 * m->nv : 0;
  ibytes = 12 * m->nt;
  lbytes = 24 * m->nl;
  T(blen >= vbytes + ibytes + lbytes);
  for (i = 0, p = bin; i < (m->nt ? m->nv : 0); i++, p += 32) {
    int k;
    double l = 0;
    for (k = 0; k < 8; k++) T(isfinite(getf(p + 4 * k)));
    for (k = 0; k < 3; k++) T(samebits(getf(p + 4 * k), finf(m->pos[3 * i + k])));
    for (k = 0; k < 3; k++) l += (double)getf(p + 12 + 4 * k) * getf(p + 12 + 4 * k);
    T(fabs(l - 1) < 1e-5);
    T(samebits(getf(p + 24), finf(m->uv[2 * i])));
    T(samebits(getf(p + 28), finf(1.0f - finf(m->uv[2 * i + 1]))));
  }
  for (i = 0; i < m->nt; i++, p += 12) {
    T(get32(p) < m->nv && get32(p + 4) < m->nv && get32(p + 8) < m->nv);
    isum += mix(get32(p), get32(p + 4), get32(p + 8));
  }
  T(isum == trisum(m));
  for (i = 0; i < m->nl; i++, p += 24) {
    int k;
    for (k = 0; k < 6; k++) T(samebits(getf(p + 4 * k), finf(m->lpos[6 * (size_t)lord[i] + k])));
  }
  if (p < bin + blen) T(memcmp(p, "\x89PNG\r\n\x1a\n", 8) == 0);   /* the images */
}

/* ---------------------------------------------------------------------- */

/* What the directory holds: 1 for each of 'names' that is there; any other
** file (a temporary file left behind) is a failure. Then it is emptied and
** removed when 'rm'. */
static const char *const names[] = {"m.obj", "m.mtl", "m.ply", "m.glb", "t1.png", "t2.png",
                                    "t3.png", "bad.png", NULL};

static void listdir (const char *dir, int *there, int rm) {
  DIR *d = opendir(dir);
  struct dirent *de;
  char path[600];
  int k;
  if (d == NULL) return;
  for (k = 0; names[k] != NULL; k++) there[k] = 0;
  while ((de = readdir(d)) != NULL) {
    if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
    for (k = 0; names[k] != NULL && strcmp(names[k], de->d_name) != 0; k++) {}
    if (names[k] != NULL) there[k] = 1;
    snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
    if (rm) remove(path);
    else T(names[k] != NULL);
  }
  closedir(d);
  if (rm) rmdir(dir);
}

static const char *tempdir (char *dir, size_t size) {
  struct stat st;
  const char *base = getenv("TMPDIR");
  if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0)
    base = "/dev/shm";
  else if (base == NULL)
    base = "/tmp";
  snprintf(dir, size, "%s/lsys_fuzz_export_XXXXXX", base);
  return mkdtemp(dir);
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  rd r = {data, size};
  lsys_mesh m;
  lsys_material pal[5];
  lsys_texture tx[3];
  const lsys_texture *tp[3];
  uint8_t px[3][16];
  uint32_t lord[32];
  char dir[256], path[300];
  lsys_error e;
  size_t nv, nt, nl, npal, i;
  int ntex, flags, k, bad = 0, badtex = 0, st, filebad[3] = {0, 0, 0};
  nv = byte(&r) % 65;
  nt = nv ? byte(&r) % 129 : 0;
  nl = byte(&r) % 33;
  npal = byte(&r) % 6;
  flags = (int)byte(&r);
  ntex = flags & 3;
  if (tempdir(dir, sizeof dir) == NULL) return 0;
  lsys_mesh_init(&m);
  /* the palette */
  for (i = 0; i < npal; i++) {
    float *f = &pal[i].ambient[0];
    if (byte(&r) & 1) {
      double c[3];
      for (k = 0; k < 3; k++) c[k] = fl(&r);
      lsys_mesh_material_color(&pal[i], c[0], c[1], c[2]);
    }
    else {
      for (k = 0; k < 16; k++) f[k] = fl(&r);
      pal[i].shininess = fl(&r);
    }
  }
  /* the textures: 2 x 2 pixels; a file (PNG, not PNG, missing) or none */
  for (k = 0; k < ntex; k++) {
    unsigned kind = byte(&r), j;
    lsys_texture_init(&tx[k]);
    for (j = 0; j < 16; j++) px[k][j] = (uint8_t)(j % 4 == 3 && !(kind & 16) ? 255 : byte(&r));
    tx[k].rgba = px[k];
    tx[k].w = tx[k].h = 2;
    tx[k].mode = kind & 32 ? LSYS_TEX_DECAL : LSYS_TEX_MODULATE;
    tx[k].mag_linear = (kind >> 6) & 1;
    tx[k].min_linear = kind >> 7;
    tp[k] = &tx[k];
    switch (kind % 8) {
      case 5: tp[k] = NULL; break;
      case 6: tx[k].path = NULL; break;
      case 7:                                  /* not a PNG file, or missing */
        snprintf(path, sizeof path, "%s/%s", dir, kind & 8 ? "bad.png" : "missing.png");
        if (kind & 8) {
          FILE *f = fopen(path, "wb");
          if (f != NULL) { fputs("not a png", f); fclose(f); }
        }
        tx[k].path = strdup(path);
        filebad[k] = 1;
        break;
      default:
        snprintf(path, sizeof path, "%s/t%d.png", dir, k + 1);
        T(lsys_pngio_write(path, px[k], 2, 2, 1, &e) == LSYS_OK);
        tx[k].path = strdup(path);
        break;
    }
  }
  /* vertices, triangles, segments */
  T(lsys_mesh_reserve(&m, nv, nt) == LSYS_OK);
  for (i = 0; i < nv; i++) {
    double p[3], n[3], u, v;
    unsigned col, b;
    p[0] = fl(&r); p[1] = fl(&r); p[2] = fl(&r);
    n[0] = fl(&r); n[1] = fl(&r); n[2] = fl(&r);
    u = fl(&r); v = fl(&r);
    b = byte(&r);
    col = b == 0xff ? 65535 : b % 8;
    m.curtex = (unsigned)byte(&r) % (unsigned)(ntex + 2);
    lsys_mesh_vertex(&m, p, n, u, v, col, (int)(b >> 7));
  }
  for (i = 0; i < nt; i++) {
    uint32_t a[3];
    for (k = 0; k < 3; k++) {
      unsigned b = byte(&r);
      a[k] = (uint32_t)(b % nv);
      if ((flags & 4) && b == 0xff) { a[k] = (uint32_t)nv + (b & 1); bad = 1; }
    }
    lsys_mesh_tri(&m, a[0], a[1], a[2]);
  }
  for (i = 0; i < nl; i++) {
    double a[3], b[3], w0, w1;
    unsigned c;
    for (k = 0; k < 3; k++) a[k] = fl(&r);
    for (k = 0; k < 3; k++) b[k] = fl(&r);
    if (flags & 8) a[0] *= 1e300;            /* beyond float: saturated */
    c = byte(&r);
    w0 = fl(&r);
    w1 = fl(&r);
    T(lsys_mesh_line(&m, a, b, w0, w1, c == 0xff ? 65535 : c % 8) == LSYS_OK);
  }
  lineorder(&m, npal ? npal : 1, lord);
  if (tracing < 0) tracing = getenv("FUZZ_TRACE") != NULL;
  /* would a textured triangle use a texture whose file is not a PNG? */
  for (i = 0; i < nt && !bad; i++) {
    unsigned t = m.tex[m.tri[3 * i]];
    if (t >= 1 && t <= (unsigned)ntex && tp[t - 1] != NULL && filebad[t - 1]) badtex = 1;
  }
  if (tracing)
    fprintf(stderr, "%zu vertices, %zu triangles%s, %zu segments, %zu materials, %d textures%s\n",
            nv, nt, bad ? " (one bad)" : "", nl, npal, ntex, badtex ? " (a bad file)" : "");
  /* write and read back */
  {
    size_t len, mlen;
    char *obj, *mtl;
    snprintf(path, sizeof path, "%s/m.obj", dir);
    st = lsys_export_obj(&m, pal, npal, tp, ntex, path, &e);
    if (bad) T(st == LSYS_EARG && strstr(e.msg, "m.obj") != NULL);
    else {
      T(st == LSYS_OK);
      snprintf(path, sizeof path, "%s/m.mtl", dir);
      mtl = slurp(path, &mlen);
      snprintf(path, sizeof path, "%s/m.obj", dir);
      obj = slurp(path, &len);
      T(obj != NULL && mtl != NULL && strlen(obj) == len && strlen(mtl) == mlen);
      if (tracing) fprintf(stderr, "obj %zu bytes, mtl %zu bytes\n", len, mlen);
      checkobj(&m, lord, obj, mtl);
      free(obj);
      free(mtl);
    }
    snprintf(path, sizeof path, "%s/m.ply", dir);
    st = lsys_export_ply(&m, pal, npal, tp, ntex, path, &e);
    if (bad) T(st == LSYS_EARG && strstr(e.msg, "m.ply") != NULL);
    else {
      T(st == LSYS_OK);
      obj = slurp(path, &len);
      T(obj != NULL);
      if (tracing) fprintf(stderr, "ply %zu bytes\n", len);
      checkply(&m, (const unsigned char *)obj, len);
      free(obj);
    }
    snprintf(path, sizeof path, "%s/m.glb", dir);
    st = lsys_export_glb(&m, pal, npal, tp, ntex, path, &e);
    if (bad || badtex) T((st == LSYS_EARG || st == LSYS_ESYNTAX) && strstr(e.msg, "m.glb") != NULL);
    else {
      T(st == LSYS_OK);
      obj = slurp(path, &len);
      T(obj != NULL);
      if (tracing) fprintf(stderr, "glb %zu bytes\n", len);
      checkglb(&m, lord, (const unsigned char *)obj, len);
      free(obj);
    }
  }
  {   /* no temporary file is left; a failed write creates no file */
    int there[9];
    listdir(dir, there, 0);
    T(there[0] == !bad && there[1] == !bad && there[2] == !bad && there[3] == !(bad || badtex));
    listdir(dir, there, 1);
  }
  for (k = 0; k < ntex; k++) {
    tx[k].rgba = NULL;                       /* the pixels are on the stack */
    lsys_texture_free(&tx[k]);
  }
  lsys_mesh_free(&m);
  return 0;
}
