/*
** Reading what the C tests wrote: whole files, little-endian words, glb
** chunks, and counts of substrings and lines. Static functions for tests
** that include it; a test that does not call one of them gets no warning
** (they are marked unused where the compiler knows the attribute).
*/
#ifndef LSYS_TESTFILE_H
#define LSYS_TESTFILE_H
#include <assert.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#define TF_UNUSED __attribute__((unused))
#else
#define TF_UNUSED
#endif

/* The bytes of 'path' and a terminating NUL (free them); *len the size. */
TF_UNUSED static char *slurp (const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *s;
  long n;
  assert(f != NULL);
  assert(fseek(f, 0, SEEK_END) == 0);
  n = ftell(f);
  assert(n >= 0);
  rewind(f);
  s = malloc((size_t)n + 1);
  assert(s != NULL);
  assert(fread(s, 1, (size_t)n, f) == (size_t)n);
  s[n] = '\0';
  fclose(f);
  *len = (size_t)n;
  return s;
}

TF_UNUSED static uint32_t rd32 (const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The JSON chunk of the .glb 'path' as a string (free it); the whole file in
** *file (free it) of *len bytes, its BIN chunk at *bin, *blen bytes. */
TF_UNUSED static char *glbjson (const char *path, unsigned char **file, size_t *len,
                                unsigned char **bin, size_t *blen) {
  unsigned char *s = (unsigned char *)slurp(path, len);
  size_t jlen;
  char *json;
  assert(*len >= 20 && rd32(s) == 0x46546C67u && rd32(s + 8) == *len);
  jlen = rd32(s + 12);
  json = malloc(jlen + 1);
  assert(json != NULL);
  memcpy(json, s + 20, jlen);
  json[jlen] = '\0';
  *blen = 20 + jlen < *len ? rd32(s + 20 + jlen) : 0;
  *bin = s + 28 + jlen;
  assert(*blen == 0 || (28 + jlen + *blen == *len && *blen % 4 == 0));
  *file = s;
  return json;
}

/* Occurrences of 'needle' in 's'. */
TF_UNUSED static int count (const char *s, const char *needle) {
  int n = 0;
  while ((s = strstr(s, needle)) != NULL) { n++; s++; }
  return n;
}

/* Number of lines of 's' that start with 'prefix'. */
TF_UNUSED static int countlines (const char *s, const char *prefix) {
  size_t k = strlen(prefix);
  int n = 0;
  while (*s) {
    if (strncmp(s, prefix, k) == 0) n++;
    s = strchr(s, '\n');
    if (s == NULL) break;
    s++;
  }
  return n;
}

#endif
