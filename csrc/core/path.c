/*
** Resolved file names (path.h).
*/
#define _XOPEN_SOURCE 700       /* realpath */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "path.h"

char *lsys_path_real (const char *path, int *kind, lsys_error *e) {
  struct stat st;
  char *r = realpath(path, NULL), *copy;        /* malloc'd by the C library */
  size_t n;
  if (r == NULL || stat(r, &st) != 0) {
    int err = errno;
    free(r);
    lsys_seterror(e, err == ENOMEM ? LSYS_ENOMEM : LSYS_EARG, (size_t)-1, "%s: %s", path,
                  strerror(err));
    return NULL;
  }
  *kind = S_ISREG(st.st_mode) ? LSYS_PATH_FILE : S_ISDIR(st.st_mode) ? LSYS_PATH_DIR
                                                                     : LSYS_PATH_OTHER;
  n = strlen(r) + 1;
  if ((copy = (char *)LSYS_MALLOC(n)) == NULL) {
    free(r);
    lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
    return NULL;
  }
  memcpy(copy, r, n);
  free(r);
  return copy;
}
