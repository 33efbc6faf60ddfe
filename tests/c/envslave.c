/*
** lsys_envslave: a small environmental program (the slave side of cpfg's
** protocol, docs/open.md) for the tests of csrc/core/envproc.c and of the Lua
** side. Not a test itself.
**
**   lsys_envslave [-e EFILE] [-k KEY] [-ext EXT] SPEC
**
** The switches are those vlab's programs take (-h HOST and -C SETUP are
** taken and ignored); the transport is the .e file's "communication type:"
** (pipes, files, memory), else files with -ext, memory with -k, pipes. It says
** it runs (pipes: writes 0x01; files, memory: sets semaphore 1 to 0), then
** reads one chunk at a time (pipes: stdin lines up to a Control line; files:
** waits on semaphore 0 and reads .to_field<EXT>; memory: the shared memory's
** first area) and answers it, ending with "Control: 5" (pipes: on stdout;
** files: in .from_field<EXT>; memory: the second area; then semaphore 1 += 1).
** "Control: 8" ends it (pipes: after the goodbye byte 0x01). SPEC says how it
** answers:
**
**   echo    each item "<id> E(a,b,...)..." -> "<id> E(a+1,b+1,...)" (an empty
**           field stays empty)
**   sum     each item -> "<id> E(x)", x the sum of the numbers on the turtle
**           lines after it (not those between Dbegin and Dend)
**   chunks  as echo, but the items of all chunks are kept until the last chunk
**           (flag 4; the others get "Control: 5" alone), then answered in parts
**           of 2 items with the flags 1, 0, ..., 4 (5 for one part)
**   log=FILE  appends each chunk as it came (Control: 8 too) to FILE and answers
**           none of its items: what a master sends, byte for byte
**   hang    reads a chunk (even Control: 8) and never answers
**   die     reads a chunk and exits with status 5
**   exit    exits at once with status 3
**   silent  never says it runs
*/
#if defined(__linux__)
#define _GNU_SOURCE             /* semtimedop; POSIX 2008 with it */
#else
#define _XOPEN_SOURCE 700
#endif
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ipc.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <time.h>
#include <unistd.h>

#define TOFIELD 50000
#define FROMFIELD 10000
#define MAXWAIT 120             /* seconds on a semaphore before giving up on the master */

enum { PIPES, FILES, MEMORY };

static int transport = -1, semid = -1;
static char *shm;
static char tofile[256], fromfile[256];

union slavesemun { int val; struct semid_ds *buf; unsigned short *array; };

static void die (const char *what) {
  fprintf(stderr, "lsys_envslave: %s: %s\n", what, strerror(errno));
  exit(2);
}

/* A growing text. */
typedef struct text { char *s; size_t n, cap; } text;

static void add (text *t, const char *s, size_t n) {
  if (t->n + n + 1 > t->cap) {
    size_t cap = t->cap ? t->cap : 256;
    while (cap < t->n + n + 1) cap *= 2;
    if ((t->s = realloc(t->s, cap)) == NULL) die("realloc");
    t->cap = cap;
  }
  memcpy(t->s + t->n, s, n);
  t->n += n;
  t->s[t->n] = '\0';
}

static void adds (text *t, const char *s) { add(t, s, strlen(s)); }

/* ---------------------------------------------------------------------- */
/* Answers */

/* Whether the line is an item: digits, blanks, then 'E'. */
static int isitem (const char *l) {
  const char *c = l;
  while (*c >= '0' && *c <= '9') c++;
  if (c == l || (*c != ' ' && *c != '\t')) return 0;
  while (*c == ' ' || *c == '\t') c++;
  return *c == 'E';
}

/* "<id> E(a+1,...)\n" for the item line 'l' (nothing without parameters). */
static void echo (text *out, const char *l) {
  const char *open = strchr(l, '('), *close = open ? strchr(open, ')') : NULL, *c;
  char num[64];
  if (open == NULL || close == NULL) return;
  add(out, l, strcspn(l, " \t"));
  adds(out, " E(");
  for (c = open + 1; c < close; ) {
    const char *end = memchr(c, ',', (size_t)(close - c));
    if (end == NULL) end = close;
    if (end > c) {
      snprintf(num, sizeof num, "%g", strtod(c, NULL) + 1);
      adds(out, num);
    }
    if (end < close) adds(out, ",");
    c = end + 1;
  }
  adds(out, ")\n");
}

/* The sum of the numbers in the line. */
static double numbers (const char *l) {
  double s = 0;
  const char *c = l;
  while (*c != '\0') {
    int starts = (*c >= '0' && *c <= '9') ||
                 ((*c == '-' || *c == '+' || *c == '.') && c[1] >= '0' && c[1] <= '9') ||
                 ((*c == '-' || *c == '+') && c[1] == '.' && c[2] >= '0' && c[2] <= '9');
    char *end;
    if (starts) {
      s += strtod(c, &end);
      c = end > c ? end : c + 1;
    }
    else c++;
  }
  return s;
}

static void sumitem (text *out, const char *item, double x) {
  char num[64];
  add(out, item, strcspn(item, " \t"));
  snprintf(num, sizeof num, " E(%g)\n", x);
  adds(out, num);
}

/* The lines of a chunk, split in place; the Control line's flag in *flag. */
static int splitlines (char *s, char **line, int max, int *flag) {
  int n = 0;
  char *c = s;
  *flag = 5;
  while (*c != '\0' && n < max) {
    char *nl = strchr(c, '\n');
    if (nl != NULL) *nl = '\0';
    if (strncmp(c, "Control:", 8) == 0) {
      *flag = atoi(c + 8);
      break;
    }
    line[n++] = c;
    if (nl == NULL) break;
    c = nl + 1;
  }
  return n;
}

/* The answer parts to one chunk (each ends with its Control line); 0 parts:
** end (Control: 8). */
static int answer (const char *spec, char *chunk, text *part, int maxparts) {
  static text kept;                    /* chunks: the items of the step so far */
  static char *line[100000];
  int flag, n = splitlines(chunk, line, 100000, &flag), i, k;
  text one = { 0 };
  if (strcmp(spec, "hang") == 0) for (;;) pause();      /* also at Control: 8 */
  if (flag == 8) return 0;
  if (strcmp(spec, "die") == 0) exit(5);
  if (strcmp(spec, "sum") == 0) {
    const char *item = NULL;
    double x = 0;
    int geometry = 0;
    for (i = 0; i <= n; i++) {
      if (i == n || isitem(line[i])) {
        if (item != NULL) sumitem(&one, item, x);
        if (i < n) item = line[i];
        x = 0;
        geometry = 0;
      }
      else if (strcmp(line[i], "Dbegin") == 0) geometry = 1;
      else if (strcmp(line[i], "Dend") == 0) geometry = 0;
      else if (!geometry) x += numbers(line[i]);
    }
  }
  else if (strcmp(spec, "chunks") == 0) {
    for (i = 0; i < n; i++)
      if (isitem(line[i])) echo(&kept, line[i]);
    if ((flag & 4) == 0) {
      adds(&part[0], "Control: 5\n");
      return 1;
    }
    for (i = 0, k = 0; i < (int)kept.n && k < maxparts; k++) {   /* 2 lines a part */
      int lines = 0;
      while (i < (int)kept.n && lines < 2) {
        char *nl = strchr(kept.s + i, '\n');
        add(&part[k], kept.s + i, (size_t)(nl - (kept.s + i)) + 1);
        i = (int)(nl - kept.s) + 1;
        lines++;
      }
    }
    if (k == 0) k = 1;
    for (i = 0; i < k; i++) {
      int f = (i == 0 ? 1 : 0) | (i == k - 1 ? 4 : 0);
      char ctl[32];
      snprintf(ctl, sizeof ctl, "Control: %d\n", f);
      adds(&part[i], ctl);
    }
    kept.n = 0;
    return k;
  }
  else if (strncmp(spec, "log=", 4) != 0)
    for (i = 0; i < n; i++)
      if (isitem(line[i])) echo(&one, line[i]);
  adds(&one, "Control: 5\n");
  part[0] = one;
  return 1;
}

/* ---------------------------------------------------------------------- */
/* Transports */

static void semadd (int num, int op) {
  struct sembuf sb;
  time_t start = time(NULL);
  sb.sem_num = (unsigned short)num;
  sb.sem_op = (short)op;
  for (;;) {
    int r;
#if defined(__linux__)
    struct timespec ts = { 1, 0 };
    sb.sem_flg = 0;
    r = semtimedop(semid, &sb, 1, &ts);
#else
    struct timespec ts = { 0, 1000000 };
    sb.sem_flg = IPC_NOWAIT;
    r = semop(semid, &sb, 1);
    if (r != 0 && errno == EAGAIN) nanosleep(&ts, NULL);
#endif
    if (r == 0) return;
    if (errno == EIDRM || errno == EINVAL) exit(0);      /* the master removed them */
    if (errno != EAGAIN && errno != EINTR) die("semop");
    if (time(NULL) - start > MAXWAIT || getppid() == 1) exit(6);
  }
}

/* The next chunk: stdin lines up to a Control line, the file, or the
** memory's first area; NULL at the end of stdin. */
static char *getchunk (void) {
  static text t;
  t.n = 0;
  if (transport == PIPES) {
    char *l = NULL;
    size_t cap = 0;
    ssize_t n;
    while ((n = getline(&l, &cap, stdin)) > 0) {
      add(&t, l, (size_t)n);
      if (strncmp(l, "Control:", 8) == 0) break;
    }
    free(l);
    return n > 0 ? t.s : NULL;
  }
  semadd(0, -1);
  if (transport == FILES) {
    char b[4096];
    size_t n;
    FILE *f = fopen(tofile, "rb");
    if (f == NULL) die(tofile);
    while ((n = fread(b, 1, sizeof b, f)) > 0) add(&t, b, n);
    fclose(f);
  }
  else add(&t, shm, strnlen(shm, TOFIELD));
  if (t.s == NULL) adds(&t, "");
  return t.s;
}

static void putpart (const text *part) {
  if (transport == FILES) {
    FILE *f = fopen(fromfile, "wb");
    if (f == NULL) die(fromfile);
    fwrite(part->s, 1, part->n, f);
    if (fclose(f) != 0) die(fromfile);
  }
  else {
    if (part->n >= FROMFIELD) {
      fprintf(stderr, "lsys_envslave: an answer of %zu bytes\n", part->n);
      exit(4);
    }
    memcpy(shm + TOFIELD, part->s, part->n + 1);
  }
  semadd(1, 1);
}

/* The transport the .e file names, or -1. */
static int filetype (const char *efile) {
  char l[4096];
  int t = -1;
  FILE *f = efile ? fopen(efile, "r") : NULL;
  if (f == NULL) return -1;
  while (fgets(l, sizeof l, f) != NULL)
    if (strncmp(l, "communication type:", 19) == 0) {
      const char *c = l + 19;
      c += strspn(c, " \t");
      t = strncmp(c, "files", 5) == 0 ? FILES : strncmp(c, "memory", 6) == 0 ? MEMORY
                                              : PIPES;
    }
  fclose(f);
  return t;
}

/* Opens the semaphores and the memory of key 'key'. */
static void openipc (int key) {
  if ((semid = semget((key_t)key, 2, 0600)) < 0) die("semget");
  if (transport == MEMORY) {
    int id = shmget((key_t)(key - 1), TOFIELD + FROMFIELD, 0600);
    if (id < 0) die("shmget");
    if ((shm = shmat(id, NULL, 0)) == (char *)-1) die("shmat");
  }
}

int main (int argc, char **argv) {
  const char *efile = NULL, *ext = NULL, *spec = NULL;
  int key = -1, i, nparts;
  text part[64];
  char *chunk;
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-e") == 0 && i + 1 < argc) efile = argv[++i];
    else if (strcmp(argv[i], "-k") == 0 && i + 1 < argc) key = atoi(argv[++i]);
    else if (strcmp(argv[i], "-ext") == 0 && i + 1 < argc) ext = argv[++i];
    else if ((strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "-host") == 0 ||
              strcmp(argv[i], "-C") == 0) && i + 1 < argc) i++;
    else if (spec == NULL) spec = argv[i];
  }
  if (spec == NULL) spec = "echo";
  if (strcmp(spec, "exit") == 0) return 3;
  if (strcmp(spec, "silent") == 0) for (;;) pause();
  transport = filetype(efile);
  if (transport < 0) transport = ext != NULL ? FILES : key >= 0 ? MEMORY : PIPES;
  if (transport != PIPES) {
    union slavesemun arg;
    if (key < 0 || (transport == FILES && ext == NULL)) {
      fprintf(stderr, "lsys_envslave: files and memory need -k KEY (and -ext EXT)\n");
      return 2;
    }
    if (transport == FILES) {
      snprintf(tofile, sizeof tofile, ".to_field%s", ext);
      snprintf(fromfile, sizeof fromfile, ".from_field%s", ext);
    }
    openipc(key);
    arg.val = 0;
    if (semctl(semid, 1, SETVAL, arg) != 0) die("semctl");        /* it runs */
  }
  else if (write(1, "\1", 1) != 1) die("write");
  while ((chunk = getchunk()) != NULL) {
    if (strncmp(spec, "log=", 4) == 0) {              /* before answer() splits it */
      FILE *f = fopen(spec + 4, "ab");
      if (f == NULL) die(spec + 4);
      fputs(chunk, f);
      if (fclose(f) != 0) die(spec + 4);
    }
    memset(part, 0, sizeof part);
    nparts = answer(spec, chunk, part, 64);
    if (nparts == 0) {                                 /* Control: 8 */
      if (transport == PIPES) return write(1, "\1", 1) == 1 ? 0 : 2;
      part[0].n = 0;
      adds(&part[0], "Control: 5\n");
      putpart(&part[0]);
      free(part[0].s);
      return 0;
    }
    for (i = 0; i < nparts; i++) {
      if (transport == PIPES) {
        fwrite(part[i].s, 1, part[i].n, stdout);
        fflush(stdout);
      }
      else {
        if (i > 0) semadd(0, -1);                        /* the master asks for more */
        putpart(&part[i]);
      }
      free(part[i].s);
    }
  }
  return 0;
}
