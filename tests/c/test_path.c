/*
** C unit tests for resolved file names (path.h): symbolic links and '..'
** resolved, the kinds of file told apart, a FIFO resolved without blocking,
** a missing file reported by name (what the cpfg preprocessor
** checks before it includes a file).
*/
#define _XOPEN_SOURCE 700
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "path.h"
#include "testdir.h"

int main (void) {
  const char *dir = testdir();
  char p[320], q[256], *real, *rdir;
  lsys_error e;
  int kind;
  FILE *f;
  rdir = lsys_path_real(dir, &kind, &e);        /* /tmp may be a link itself */
  assert(rdir != NULL && kind == LSYS_PATH_DIR);
  snprintf(p, sizeof p, "%s/a.l", dir);
  assert((f = fopen(p, "w")) != NULL);
  fclose(f);
  snprintf(q, sizeof q, "%s/sub", dir);
  assert(mkdir(q, 0700) == 0);
  snprintf(q, sizeof q, "%s/sub/../a.l", dir);
  real = lsys_path_real(q, &kind, &e);
  snprintf(p, sizeof p, "%s/a.l", rdir);
  assert(real != NULL && kind == LSYS_PATH_FILE && strcmp(real, p) == 0);
  free(real);
  snprintf(q, sizeof q, "%s/link", dir);        /* a link out of the folder */
  assert(symlink("/dev/null", q) == 0);
  real = lsys_path_real(q, &kind, &e);
  assert(real != NULL && kind == LSYS_PATH_OTHER && strcmp(real, "/dev/null") == 0);
  free(real);
  snprintf(q, sizeof q, "%s/fifo", dir);        /* resolved, not opened: no wait */
  assert(mkfifo(q, 0600) == 0);
  real = lsys_path_real(q, &kind, &e);
  assert(real != NULL && kind == LSYS_PATH_OTHER);
  free(real);
  snprintf(q, sizeof q, "%s/none", dir);
  assert(lsys_path_real(q, &kind, &e) == NULL && e.code == LSYS_EARG);
  snprintf(p, sizeof p, "%s: No such file or directory", q);
  assert(strcmp(e.msg, p) == 0);
  free(rdir);                                   /* the folder goes at exit */
  printf("test_path: ok\n");
  return 0;
}
