/*
** File names resolved, for checks of where a file lies (the cpfg
** preprocessor's #include, docs/cpfg.md): symbolic links, '.' and '..'
** resolved, and what kind of file the name is.
*/
#ifndef LSYS_PATH_H
#define LSYS_PATH_H

#include "common.h"

#define LSYS_PATH_FILE  1     /* a regular file */
#define LSYS_PATH_DIR   2     /* a folder */
#define LSYS_PATH_OTHER 3     /* a device, a FIFO, a socket */

/*
** The absolute name of 'path' with no symbolic link, '.' or '..' in it
** (realpath(3)), allocated with LSYS_MALLOC (the caller frees it), and in
** *kind what it names (LSYS_PATH_*). NULL when it does not exist or cannot
** be resolved: e->msg is then "PATH: why" (strerror), e->code LSYS_EARG, or
** LSYS_ENOMEM. Opens nothing, so a FIFO does not block it.
*/
char *lsys_path_real (const char *path, int *kind, lsys_error *e);

#endif
