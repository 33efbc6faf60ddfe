/*
** Atomic output files (outfile.h): a temporary file next to the target,
** renamed onto it when complete.
*/
#define _XOPEN_SOURCE 700       /* realpath, lstat, fchmod, fdopen, mkdtemp, unlinkat */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "outfile.h"

static char *dupstr (const char *s) {
  size_t n = strlen(s) + 1;
  char *d = (char *)LSYS_MALLOC(n);
  if (d != NULL) memcpy(d, s, n);
  return d;
}

static void release (lsys_outfile *o) {
  LSYS_FREE(o->target);
  LSYS_FREE(o->tmp);
  o->target = o->tmp = NULL;
  o->f = NULL;
}

/* Creates the temporary file for 'o->target' (a hidden name in its folder,
** made new with O_EXCL, so an existing file is never opened). Returns the
** descriptor or -1 with errno set. */
static int maketemp (lsys_outfile *o) {
  static unsigned long counter;
  const char *slash = strrchr(o->target, '/');
  size_t dirlen = slash ? (size_t)(slash - o->target) + 1 : 0;
  const char *base = o->target + dirlen;
  size_t n = dirlen + strlen(base) + 64;
  int tries, fd = -1;
  o->tmp = (char *)LSYS_MALLOC(n);
  if (o->tmp == NULL) { errno = ENOMEM; return -1; }
  for (tries = 0; tries < 100 && fd < 0; tries++) {
    snprintf(o->tmp, n, "%.*s.%s.lsys-%ld-%lu.tmp", (int)dirlen, o->target, base,
             (long)getpid(), ++counter);
    fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);   /* the umask applies */
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    int en = errno;
    LSYS_FREE(o->tmp);
    o->tmp = NULL;
    errno = en;
  }
  return fd;
}

int lsys_outfile_open (lsys_outfile *o, const char *path, lsys_error *e) {
  struct stat st;
  int exists, fd, en;
  memset(o, 0, sizeof *o);
  o->path = path;
  if (path == NULL || path[0] == '\0')
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '' for writing: no file name");
  /* a link is followed: its target is the file to replace */
  if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
    o->target = realpath(path, NULL);        /* malloc'd by the C library */
    if (o->target != NULL) {
      char *t = dupstr(o->target);          /* keep every block on LSYS_FREE */
      free(o->target);
      o->target = t;
      if (t == NULL) goto nomem;
    }
    /* a dangling link: written through, in place, as fopen would */
  }
  else if ((o->target = dupstr(path)) == NULL) goto nomem;
  exists = o->target != NULL && stat(o->target, &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) {
    release(o);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s' for writing: %s", path,
                         strerror(EISDIR));
  }
  if (o->target != NULL && (!exists || S_ISREG(st.st_mode))) {
    fd = maketemp(o);
    if (fd >= 0) {
      if (exists) (void)fchmod(fd, st.st_mode & 07777);     /* keep the target's mode */
      if ((o->f = fdopen(fd, "wb")) != NULL) return LSYS_OK;
      en = errno;
      close(fd);
      unlink(o->tmp);
      release(o);
      return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory (%s)",
                           path, strerror(en));
    }
    /* the folder refuses new files but the file itself may be writable */
    en = errno;
    if (en == ENOMEM) goto nomem;
    if (!(exists && (en == EACCES || en == EPERM) && access(o->target, W_OK) == 0)) {
      release(o);
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s' for writing: %s", path,
                           strerror(en));
    }
  }
  /* in place: a device, a FIFO, a dangling link, a file in a closed folder */
  if ((o->f = fopen(o->target != NULL ? o->target : path, "wb")) == NULL) {
    en = errno;
    release(o);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s' for writing: %s", path,
                         strerror(en));
  }
  return LSYS_OK;
nomem:
  release(o);
  return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
}

void lsys_outfile_write (lsys_outfile *o, const void *p, size_t n) {
  if (o->f == NULL || o->err != 0 || n == 0) return;
  if (fwrite(p, 1, n, o->f) != n) o->err = errno ? errno : EIO;
}

int lsys_outfile_finish (lsys_outfile *o, lsys_error *e) {
  int err = o->err;
  if (o->f == NULL) return err ? LSYS_EARG : LSYS_OK;   /* finished before */
  errno = 0;
  if (fflush(o->f) != 0 && err == 0) err = errno ? errno : EIO;
  if (ferror(o->f) && err == 0) err = EIO;
  errno = 0;
  if (fclose(o->f) != 0 && err == 0) err = errno ? errno : EIO;
  o->f = NULL;
  o->err = err;
  if (err == 0) return LSYS_OK;
  if (o->tmp != NULL) unlink(o->tmp);
  return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': %s", o->path,
                       strerror(err));
}

int lsys_outfile_commit (lsys_outfile *o, lsys_error *e) {
  int st = lsys_outfile_finish(o, e);
  if (st == LSYS_OK && o->tmp != NULL && rename(o->tmp, o->target) != 0) {
    int en = errno;
    unlink(o->tmp);
    st = lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': %s", o->path,
                       strerror(en));
  }
  release(o);
  return st;
}

void lsys_outfile_abort (lsys_outfile *o) {
  if (o->f != NULL) fclose(o->f);
  if (o->tmp != NULL) unlink(o->tmp);
  release(o);
}

const char *lsys_outfile_name (const lsys_outfile *o) {
  if (o->tmp != NULL) return o->tmp;
  return o->target != NULL ? o->target : o->path;
}

char *lsys_outfile_tempdir_make (const char *parent, const char *prefix, lsys_error *e) {
  const char *what = "", *sep;
  size_t n;
  char *d;
  if (parent == NULL) {
    parent = getenv("TMPDIR");
    what = " (TMPDIR)";
    if (parent == NULL || parent[0] == '\0') parent = "/tmp", what = "";
  }
  if (prefix == NULL || prefix[0] == '\0') prefix = "lsys";
  if (strchr(prefix, '/') != NULL) {
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "a temporary folder's prefix must not hold '/', "
                  "got '%s'", prefix);
    return NULL;
  }
  if (parent[0] == '\0') parent = ".";
  n = strlen(parent);
  sep = parent[n - 1] == '/' ? "" : "/";
  n += strlen(prefix) + 9;
  if ((d = (char *)LSYS_MALLOC(n)) == NULL) {
    lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot make a temporary folder: out of memory");
    return NULL;
  }
  snprintf(d, n, "%s%s%s-XXXXXX", parent, sep, prefix);
  if (mkdtemp(d) == NULL) {
    int en = errno;
    LSYS_FREE(d);
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot make a temporary folder in '%s'%s: %s",
                  parent, what, strerror(en));
    return NULL;
  }
  return d;
}

int lsys_outfile_tempdir_remove (const char *dir) {
  int err = 0;
  DIR *d = opendir(dir);
  if (d != NULL) {
    int fd = dirfd(d);
    struct dirent *de;
    errno = 0;
    while ((de = readdir(d)) != NULL) {
      const char *nm = de->d_name;
      if (strcmp(nm, ".") == 0 || strcmp(nm, "..") == 0) continue;
      if (unlinkat(fd, nm, 0) != 0) {
        int en = errno;
        if ((en == EISDIR || en == EPERM) && unlinkat(fd, nm, AT_REMOVEDIR) == 0) en = 0;
        if (err == 0) err = en;
      }
      errno = 0;
    }
    if (errno != 0 && err == 0) err = errno;
    closedir(d);
  }
  if (rmdir(dir) != 0 && err == 0) err = errno;
  return err;
}
