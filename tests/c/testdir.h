/*
** The private temporary folder of a C test, for the files it writes.
**
** testdir() makes it at its first call, with mkdtemp: $TMPDIR/lsys-test-XXXXXX
** (/tmp when TMPDIR is unset, relative or longer than TD_TMPDIR_MAX characters,
** so that every path a test builds fits its buffers). The name is new, so two
** runs at the same time never write the same file. testpath("a.glb") names a
** file in it.
**
** At a normal exit the folder goes, with whatever is left in it (files, links,
** folders; links are removed, never followed). A test that fails (assert calls
** abort) leaves it for a look at what it wrote, and says where on stderr.
**
** A test that includes this asks for POSIX 2008 first (_XOPEN_SOURCE 700 or
** _POSIX_C_SOURCE 200809L, before any header): mkdtemp, lstat, opendir.
*/
#ifndef LSYS_TESTDIR_H
#define LSYS_TESTDIR_H
#include <assert.h>
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#if defined(__GNUC__)
#define TD_UNUSED __attribute__((unused))
#else
#define TD_UNUSED
#endif

#define TD_TMPDIR_MAX 40   /* longest TMPDIR used */
#define TD_PATH 512        /* longest path of a file in the folder */
#define TD_NAMES 64        /* files a test names with testpath */

static char td_dir[TD_TMPDIR_MAX + 32];

/* Removes 'path' and, for a folder, everything in it; -1 when something stayed. */
static int td_remove (const char *path) {
  struct stat st;
  int status = 0;
  if (lstat(path, &st) != 0) return -1;
  if (S_ISDIR(st.st_mode)) {
    DIR *d = opendir(path);
    struct dirent *de;
    char sub[TD_PATH];
    if (d == NULL) return -1;
    while ((de = readdir(d)) != NULL) {
      if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
      snprintf(sub, sizeof sub, "%s/%s", path, de->d_name);
      if (td_remove(sub) != 0) status = -1;
    }
    closedir(d);
    return rmdir(path) == 0 ? status : -1;
  }
  return unlink(path);
}

static void td_atexit (void) {
  td_remove(td_dir);   /* gone already when the test removed it itself */
}

/* At an assertion's abort: where the files are (write is safe in a handler). */
static void td_abort (int sig) {
  static const char msg[] = "the test's files are left in ";
  ssize_t w = write(2, msg, sizeof msg - 1);
  w += write(2, td_dir, strlen(td_dir));
  w += write(2, "\n", 1);
  (void)w;
  signal(sig, SIG_DFL);
  raise(sig);
}

/* The test's folder, made at the first call. */
TD_UNUSED static const char *testdir (void) {
  if (td_dir[0] == '\0') {
    const char *t = getenv("TMPDIR");
    if (t == NULL || t[0] != '/' || strlen(t) > TD_TMPDIR_MAX) t = "/tmp";
    snprintf(td_dir, sizeof td_dir, "%s/lsys-test-XXXXXX", t);
    if (mkdtemp(td_dir) == NULL) {
      perror(td_dir);
      exit(1);
    }
    if (atexit(td_atexit) != 0) abort();
    signal(SIGABRT, td_abort);
  }
  return td_dir;
}

/* "DIR/name" for the test's folder DIR: the same string for the same name,
** valid until the test ends. */
TD_UNUSED static const char *testpath (const char *name) {
  static char paths[TD_NAMES][TD_PATH];
  static int n = 0;
  size_t skip;
  int i, len;
  const char *dir = testdir();
  skip = strlen(dir) + 1;
  for (i = 0; i < n; i++) {
    if (strcmp(paths[i] + skip, name) == 0) return paths[i];
  }
  assert(n < TD_NAMES);
  len = snprintf(paths[n], TD_PATH, "%s/%s", dir, name);
  assert(len > 0 && len < TD_PATH);
  (void)len;
  return paths[n++];
}

#endif
