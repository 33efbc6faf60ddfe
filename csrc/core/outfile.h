/*
** Output files written atomically (docs/manual.md §9): the bytes go to a new
** temporary file in the target's folder, which replaces the target by
** rename(2) only when everything was written. A failure (a full disk, an
** error while rendering, an interrupt) leaves the target as it was and
** removes only the temporary file, never the target.
**
** A symbolic link is followed: the file it points to is replaced and the
** link stays. A target that exists and is not a regular file (a terminal,
** /dev/null, /dev/full, a FIFO) is written in place, as the user asked,
** and is never removed or replaced. A replaced file keeps its permission
** bits; a new one gets 0666 less the umask, as fopen would give it.
*/
#ifndef LSYS_OUTFILE_H
#define LSYS_OUTFILE_H

#include <stdio.h>

#include "common.h"

typedef struct lsys_outfile {
  FILE *f;              /* write here (NULL once finished or aborted) */
  const char *path;     /* the target, as the caller named it (messages) */
  char *target;         /* the file the rename replaces (a link resolved) */
  char *tmp;            /* the temporary file; NULL when writing in place */
  int err;              /* errno of the first failed write, or 0 */
} lsys_outfile;

/* Opens an output for 'path' (kept, not copied: it must outlive 'o').
** Returns LSYS_OK, or LSYS_EARG / LSYS_ENOMEM with e->msg naming the file
** ("cannot open 'x' for writing: ..."). */
int lsys_outfile_open (lsys_outfile *o, const char *path, lsys_error *e);

/* Writes n bytes; a failure is remembered and reported by finish. */
void lsys_outfile_write (lsys_outfile *o, const void *p, size_t n);

/* Flushes and closes the temporary file without replacing the target yet
** (for outputs made of several files: finish them all, then commit them).
** On failure the temporary file is removed and e->msg names the target. */
int lsys_outfile_finish (lsys_outfile *o, lsys_error *e);

/* Finishes (when not done yet) and renames the temporary file onto the
** target. On failure the temporary file is removed and the target is left
** as it was. Frees what 'o' holds in every case. */
int lsys_outfile_commit (lsys_outfile *o, lsys_error *e);

/* Closes and removes the temporary file; the target is not touched.
** Idempotent; frees what 'o' holds. */
void lsys_outfile_abort (lsys_outfile *o);

/* The file the bytes go to while 'o' is open: the temporary file, or the
** target itself when it is written in place. For an output another program
** writes (Graphviz, ffmpeg): finish 'o' (no bytes of its own), let the
** program write this file, then commit or abort. The temporary file was
** made new with O_EXCL in the target's folder, so that name is the
** program's alone. */
const char *lsys_outfile_name (const lsys_outfile *o);

/*
** Temporary folders: made new (mkdtemp: a fresh name, mode 0700, never an
** existing folder or a planted link) for files that are not outputs (the
** pictures of an animation, the input of a program).
*/

/* Makes the folder "PARENT/PREFIX-XXXXXX", PARENT being 'parent' or, when
** it is NULL, $TMPDIR (/tmp when TMPDIR is unset or empty). Returns its
** path (LSYS_MALLOC'd, the caller frees it), or NULL with e->msg ("cannot
** make a temporary folder in '/x' (TMPDIR): No such file or directory"). */
char *lsys_outfile_tempdir_make (const char *parent, const char *prefix, lsys_error *e);

/* Removes the folder 'dir' and the entries in it (files and links, which
** are removed, never followed; empty folders); nothing below one level.
** Returns 0, or the errno of the first entry or of the folder that could
** not be removed (ENOTEMPTY for a folder left with something in it). */
int lsys_outfile_tempdir_remove (const char *dir);

#endif
