/*
** Runs a libFuzzer target without libFuzzer: calls LLVMFuzzerTestOneInput
** on every file named on the command line and on every regular file of
** every directory named (in sorted order), then prints how many inputs
** ran. Linked with a target's source, it replays the checked-in corpus as
** a ctest with any compiler (fuzz_corpus_<name> in CMakeLists.txt):
**
**   build/replay_fuzz_derive tests/fuzz/corpus_derive
**   build/replay_fuzz_derive tests/fuzz/findings/derive/some-crash
**
** A failing input stops the run (the targets trap); the name of the input
** was printed before it ran, with -v, or is the last one a debugger shows.
*/
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size);

static int verbose;

/* Reads 'path' and runs it; returns 0, or 1 when it cannot be read. */
static int runfile (const char *path) {
  FILE *f = fopen(path, "rb");
  uint8_t *buf = NULL;
  size_t n = 0, cap = 0;
  if (f == NULL) {
    fprintf(stderr, "replay: cannot open '%s': %s\n", path, strerror(errno));
    return 1;
  }
  for (;;) {
    size_t k;
    if (n == cap) {
      uint8_t *b = (uint8_t *)realloc(buf, cap = cap ? 2 * cap : 4096);
      if (b == NULL) { fclose(f); free(buf); fprintf(stderr, "replay: out of memory\n"); return 1; }
      buf = b;
    }
    k = fread(buf + n, 1, cap - n, f);
    n += k;
    if (k == 0) break;
  }
  if (ferror(f)) {
    fprintf(stderr, "replay: cannot read '%s'\n", path);
    fclose(f);
    free(buf);
    return 1;
  }
  fclose(f);
  if (verbose) { fprintf(stderr, "replay: %s\n", path); fflush(stderr); }
  /* a copy of exactly n bytes, so that reading past the input is caught */
  {
    uint8_t *data = (uint8_t *)malloc(n ? n : 1);
    if (data == NULL) { free(buf); fprintf(stderr, "replay: out of memory\n"); return 1; }
    if (n) memcpy(data, buf, n);
    free(buf);
    LLVMFuzzerTestOneInput(data, n);
    free(data);
  }
  return 0;
}

static int cmpname (const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Runs the regular files of directory 'dir' in sorted order; counts them. */
static int rundir (const char *dir, long *count) {
  DIR *d = opendir(dir);
  struct dirent *de;
  char **names = NULL;
  size_t n = 0, cap = 0, i;
  int bad = 0;
  if (d == NULL) {
    fprintf(stderr, "replay: cannot open directory '%s': %s\n", dir, strerror(errno));
    return 1;
  }
  while ((de = readdir(d)) != NULL) {
    size_t len = strlen(dir) + strlen(de->d_name) + 2;
    char *path;
    struct stat st;
    if (de->d_name[0] == '.') continue;
    path = (char *)malloc(len);
    if (path == NULL) { bad = 1; break; }
    snprintf(path, len, "%s/%s", dir, de->d_name);
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) { free(path); continue; }
    if (n == cap) {
      char **v = (char **)realloc(names, (cap = cap ? 2 * cap : 64) * sizeof *names);
      if (v == NULL) { free(path); bad = 1; break; }
      names = v;
    }
    names[n++] = path;
  }
  closedir(d);
  if (n > 0) qsort(names, n, sizeof *names, cmpname);
  for (i = 0; i < n; i++) {
    if (!bad) {
      bad = runfile(names[i]);
      if (!bad) (*count)++;
    }
    free(names[i]);
  }
  free(names);
  return bad;
}

int main (int argc, char **argv) {
  long count = 0;
  int i, bad = 0;
  for (i = 1; i < argc && !bad; i++) {
    struct stat st;
    if (strcmp(argv[i], "-v") == 0) { verbose = 1; continue; }
    if (stat(argv[i], &st) != 0) {
      fprintf(stderr, "replay: cannot open '%s': %s\n", argv[i], strerror(errno));
      bad = 1;
    }
    else if (S_ISDIR(st.st_mode)) bad = rundir(argv[i], &count);
    else {
      bad = runfile(argv[i]);
      if (!bad) count++;
    }
  }
  printf("replay: %ld input%s ran\n", count, count == 1 ? "" : "s");
  return bad;
}
