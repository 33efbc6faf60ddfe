/*
** C unit tests for atomic output files (outfile.h): the target changes only
** at commit, an abort or a failed write leaves it as it was and no
** temporary file behind, devices are written in place and never removed.
*/
#define _XOPEN_SOURCE 700
#undef NDEBUG
#include <assert.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "outfile.h"
#include "testdir.h"

static const char *dir;     /* the test's folder (testdir.h) */

static void path (char *out, const char *name) {
  snprintf(out, 256, "%s/%s", dir, name);
}

static void spit (const char *p, const char *s) {
  FILE *f = fopen(p, "wb");
  assert(f != NULL);
  fputs(s, f);
  fclose(f);
}

static int same (const char *p, const char *s) {
  char buf[256];
  size_t n;
  FILE *f = fopen(p, "rb");
  if (f == NULL) return 0;
  n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  return strcmp(buf, s) == 0;
}

/* number of entries in the folder (without . and ..) */
static int entries (void) {
  DIR *d = opendir(dir);
  struct dirent *e;
  int n = 0;
  assert(d != NULL);
  while ((e = readdir(d)) != NULL) n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
  closedir(d);
  return n;
}

/* Temporary folders: new, private, under TMPDIR; removed with what they hold, a link
** in them removed and its target left alone. */
static void tempdirs (void) {
  char victim[256], link[256], file[256], sub[256], missing[256], msg[512];
  lsys_error e;
  struct stat st;
  char *t;
  path(victim, "victim.txt");
  spit(victim, "keep me");
  t = lsys_outfile_tempdir_make(dir, "frames", &e);
  assert(t != NULL && strncmp(t, dir, strlen(dir)) == 0);
  assert(strstr(t + strlen(dir), "/frames-") == t + strlen(dir));
  assert(stat(t, &st) == 0 && S_ISDIR(st.st_mode) && (st.st_mode & 07777) == 0700);
  snprintf(link, sizeof link, "%s/link", t);
  snprintf(file, sizeof file, "%s/frame-000001.png", t);
  snprintf(sub, sizeof sub, "%s/sub", t);
  assert(symlink(victim, link) == 0);
  spit(file, "png");
  assert(mkdir(sub, 0700) == 0);
  assert(lsys_outfile_tempdir_remove(t) == 0);
  assert(access(t, F_OK) != 0 && same(victim, "keep me"));
  assert(lsys_outfile_tempdir_remove(t) != 0);                   /* gone: says so */
  LSYS_FREE(t);
  /* $TMPDIR is the default parent; a missing one is named */
  assert(setenv("TMPDIR", dir, 1) == 0);
  t = lsys_outfile_tempdir_make(NULL, NULL, &e);
  assert(t != NULL && strncmp(t, dir, strlen(dir)) == 0 && strstr(t, "/lsys-") != NULL);
  assert(lsys_outfile_tempdir_remove(t) == 0);
  LSYS_FREE(t);
  path(missing, "none");
  assert(setenv("TMPDIR", missing, 1) == 0);
  assert(lsys_outfile_tempdir_make(NULL, "x", &e) == NULL);
  snprintf(msg, sizeof msg, "cannot make a temporary folder in '%s' (TMPDIR): No such file "
           "or directory", missing);
  assert(strcmp(e.msg, msg) == 0);
  assert(lsys_outfile_tempdir_make(dir, "a/b", &e) == NULL && strstr(e.msg, "must not hold '/'"));
  assert(unsetenv("TMPDIR") == 0);
  unlink(victim);
}

int main (void) {
  char a[256], b[256], c[256];
  lsys_outfile o, o2;
  lsys_error e;
  struct stat st;
  dir = testdir();
  path(a, "a.txt");
  path(b, "b.txt");
  path(c, "missing/c.txt");

  /* a new file appears only at commit */
  assert(lsys_outfile_open(&o, a, &e) == LSYS_OK);
  lsys_outfile_write(&o, "new", 3);
  assert(access(a, F_OK) != 0);
  assert(lsys_outfile_commit(&o, &e) == LSYS_OK);
  assert(same(a, "new") && entries() == 1);

  /* an abort leaves the old content and no temporary file */
  assert(lsys_outfile_open(&o, a, &e) == LSYS_OK);
  lsys_outfile_write(&o, "partial", 7);
  assert(entries() == 2);
  lsys_outfile_abort(&o);
  lsys_outfile_abort(&o);                                /* idempotent */
  assert(same(a, "new") && entries() == 1);

  /* two files finished, then committed: the mode of a replaced file stays */
  spit(b, "old b");
  assert(chmod(b, 0600) == 0);
  assert(lsys_outfile_open(&o, a, &e) == LSYS_OK);
  assert(lsys_outfile_open(&o2, b, &e) == LSYS_OK);
  lsys_outfile_write(&o, "A", 1);
  lsys_outfile_write(&o2, "B", 1);
  assert(lsys_outfile_finish(&o, &e) == LSYS_OK && lsys_outfile_finish(&o2, &e) == LSYS_OK);
  assert(same(a, "new") && same(b, "old b"));
  assert(lsys_outfile_commit(&o2, &e) == LSYS_OK && lsys_outfile_commit(&o, &e) == LSYS_OK);
  assert(same(a, "A") && same(b, "B") && entries() == 2);
  assert(stat(b, &st) == 0 && (st.st_mode & 07777) == 0600);

  /* another program may write the temporary file: it replaces the target at commit */
  assert(lsys_outfile_open(&o, a, &e) == LSYS_OK);
  assert(lsys_outfile_finish(&o, &e) == LSYS_OK);
  assert(strcmp(lsys_outfile_name(&o), o.tmp) == 0 && strstr(o.tmp, "/.a.txt.lsys-") != NULL);
  spit(lsys_outfile_name(&o), "by another");
  assert(same(a, "A") && lsys_outfile_commit(&o, &e) == LSYS_OK);
  assert(same(a, "by another") && entries() == 2);

  /* a device is written in place and a failed write does not remove it */
  assert(lsys_outfile_open(&o, "/dev/full", &e) == LSYS_OK);
  assert(o.tmp == NULL && strcmp(lsys_outfile_name(&o), "/dev/full") == 0);
  lsys_outfile_write(&o, "x", 1);
  assert(lsys_outfile_commit(&o, &e) == LSYS_EARG);
  assert(strstr(e.msg, "cannot write '/dev/full'") != NULL);
  assert(stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode));

  /* errors name the file */
  assert(lsys_outfile_open(&o, c, &e) == LSYS_EARG);
  assert(strstr(e.msg, "cannot open '") != NULL && strstr(e.msg, "missing/c.txt") != NULL);
  assert(lsys_outfile_open(&o, dir, &e) == LSYS_EARG && strstr(e.msg, "directory") != NULL);
  assert(lsys_outfile_open(&o, "", &e) == LSYS_EARG);

  tempdirs();
  assert(entries() == 2);
  unlink(a);
  unlink(b);
  assert(rmdir(dir) == 0);
  return 0;
}
