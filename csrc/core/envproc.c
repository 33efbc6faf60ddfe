/*
** Environmental programs (envproc.h): starting one, its transports (pipes,
** files, memory) and ending it, with every wait bounded.
**
** The child is made with fork and execv: the program is looked up on the
** PATH before the fork, so that the child runs only async-signal-safe calls
** (chdir, dup2, sigaction, execv); a close-on-exec pipe tells the parent why
** an exec failed. Waits are cut in slices so that a program that dies is
** seen as soon as it does (poll on pipes; semtimedop, or semop with
** IPC_NOWAIT between naps where there is no semtimedop).
*/
#if defined(__linux__)
#define _GNU_SOURCE             /* semtimedop (glibc, musl); POSIX 2008 with it */
#else
#define _XOPEN_SOURCE 700       /* SysV IPC, strnlen, clock_gettime */
#endif
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/ipc.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "envproc.h"

#define SLICE 0.05              /* seconds between two looks at the child */
#define READSIZE 65536          /* bytes read from a pipe at a time */
#define CONTROL "Control:"
#define LASTCHUNK 4
#define MAXKEYS 64              /* field indices tried for a free IPC key */

struct lsys_envproc {
  int transport;
  pid_t pid;
  int reaped, status;         /* the child was reaped (status: its wait status; -1 unknown) */
  int broken;                 /* an exchange failed: the process only closes */
  int pending;                /* the last reply lacked the last-chunk flag */
  double timeout;
  int to, from;               /* pipes: our ends of its stdin and stdout; else -1 */
  int semid, shmid, key;      /* files, memory: -1, -1, 0 when none */
  char *shm;                  /* memory: the attached area, or NULL */
  char *tofile, *fromfile;    /* files: absolute names, or NULL */
  char *name;                 /* argv[0] as given, for messages */
  char *buf;                  /* pipes: the stream read; files, memory: the reply */
  size_t cap, used;
  size_t rlen;                /* the reply handed out: buf[0..rlen), buf[rlen] = 0 */
  char saved;                 /* pipes: the byte the NUL at buf[rlen] replaced */
  size_t scan;                /* pipes: the first line not looked at yet */
  size_t limit;               /* the longest reply */
  char keyarg[16], extarg[48];
};

union envsemun {              /* semctl's fourth argument, which the caller declares */
  int val;
  struct semid_ds *buf;
  unsigned short *array;
};

static double now (void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void nap (double s) {
  struct timespec t;
  if (s <= 0) return;
  t.tv_sec = (time_t)s;
  t.tv_nsec = (long)((s - (double)t.tv_sec) * 1e9);
  while (nanosleep(&t, &t) != 0 && errno == EINTR) {}
}

static char *dupstr (const char *s) {
  size_t n = strlen(s) + 1;
  char *d = (char *)LSYS_MALLOC(n);
  if (d != NULL) memcpy(d, s, n);
  return d;
}

/* "a/b" from a and b (NULL when out of memory). */
static char *joinpath (const char *a, const char *b) {
  size_t na = strlen(a), nb = strlen(b);
  char *s = (char *)LSYS_MALLOC(na + nb + 2);
  if (s == NULL) return NULL;
  memcpy(s, a, na);
  s[na] = '/';
  memcpy(s + na + 1, b, nb + 1);
  return s;
}

/* Sets the error "environmental program 'NAME': <fmt ...>". */
static int perr (const lsys_envproc *p, lsys_error *e, int code, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 4, 5)))
#endif
  ;
static int perr (const lsys_envproc *p, lsys_error *e, int code, const char *fmt, ...) {
  char msg[200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return lsys_seterror(e, code, (size_t)-1, "environmental program '%.100s': %s", p->name, msg);
}

static int nomem (lsys_error *e) {
  return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
}

/* ---------------------------------------------------------------------- */
/* The child's life */

/* Whether the child still runs; reaps it when it ended. A host that reaps
** children itself (SIGCHLD ignored) leaves the status unknown. */
static int running (lsys_envproc *p) {
  int st;
  pid_t r;
  if (p->reaped) return 0;
  do r = waitpid(p->pid, &st, WNOHANG); while (r < 0 && errno == EINTR);
  if (r == 0) return 1;
  p->reaped = 1;
  p->status = r == p->pid ? st : -1;
  return 0;
}

/* Waits until the child ended or the deadline passed; whether it ended. */
static int waitexit (lsys_envproc *p, double deadline) {
  while (running(p)) {
    double left = deadline - now();
    if (left <= 0) return 0;
    nap(left < 0.005 ? left : 0.005);
  }
  return 1;
}

/* Ends the child: SIGTERM, up to 'grace' seconds, then SIGKILL; reaps it. */
static void terminate (lsys_envproc *p, double grace) {
  if (!running(p)) return;
  kill(p->pid, SIGTERM);
  if (waitexit(p, now() + grace)) return;
  kill(p->pid, SIGKILL);
  while (!p->reaped) {
    int st;
    pid_t r = waitpid(p->pid, &st, 0);
    if (r < 0 && errno == EINTR) continue;
    p->reaped = 1;
    p->status = r == p->pid ? st : -1;
  }
}

/* The error for a child that ended: how it ended. */
static int died (lsys_envproc *p, lsys_error *e) {
  int st = p->status;
  p->broken = 1;
  if (st != -1 && WIFEXITED(st)) return perr(p, e, LSYS_EARG, "exited with status %d",
                                             WEXITSTATUS(st));
  if (st != -1 && WIFSIGNALED(st)) return perr(p, e, LSYS_EARG, "was killed by signal %d",
                                               WTERMSIG(st));
  return perr(p, e, LSYS_EARG, "has ended");
}

static int timedout (lsys_envproc *p, lsys_error *e) {
  p->broken = 1;
  return perr(p, e, LSYS_EARG, "did not answer within %g s", p->timeout);
}

/* The child closed a pipe ('what'): it is probably leaving, so its status is
** waited for (until the deadline) to name how it ended. */
static int hangup (lsys_envproc *p, double deadline, const char *what, lsys_error *e) {
  if (waitexit(p, deadline)) return died(p, e);
  p->broken = 1;
  return perr(p, e, LSYS_EARG, "%s", what);
}

static int syserr (lsys_envproc *p, lsys_error *e, const char *what, int en) {
  p->broken = 1;
  return perr(p, e, en == ENOMEM ? LSYS_ENOMEM : LSYS_EARG, "%s: %s", what, strerror(en));
}

/* ---------------------------------------------------------------------- */
/* Semaphores */

/* Semaphore 'num' += op (op < 0: waits until it can; 0: waits until it is 0),
** bounded by the deadline and the child's life. */
static int semwait (lsys_envproc *p, int num, int op, double deadline, lsys_error *e) {
  struct sembuf sb;
  sb.sem_num = (unsigned short)num;
  sb.sem_op = (short)op;
  for (;;) {
    double left = deadline - now();
    int r;
    if (left <= 0) return timedout(p, e);
#if defined(__linux__)
    {
      struct timespec ts;
      double s = left < SLICE ? left : SLICE;
      ts.tv_sec = 0;
      ts.tv_nsec = (long)(s * 1e9);
      sb.sem_flg = 0;
      r = semtimedop(p->semid, &sb, 1, &ts);
    }
#else
    sb.sem_flg = IPC_NOWAIT;
    r = semop(p->semid, &sb, 1);
    if (r != 0 && errno == EAGAIN) nap(left < 0.002 ? left : 0.002);
#endif
    if (r == 0) return LSYS_OK;
    if (errno != EAGAIN && errno != EINTR) return syserr(p, e, "semaphores", errno);
    if (!running(p)) return died(p, e);
  }
}

/* Lets the program run (sem0 += 1) and waits for its answer (sem1 -= 1). */
static int letrun (lsys_envproc *p, double deadline, lsys_error *e) {
  struct sembuf sb;
  sb.sem_num = 0;
  sb.sem_op = 1;
  sb.sem_flg = 0;
  if (semop(p->semid, &sb, 1) != 0) return syserr(p, e, "semaphores", errno);
  return semwait(p, 1, -1, deadline, e);
}

/* The semaphore set (and for memory the shared memory) at the first free
** key (pid << 2) + 4 * index, and for files the names of the two files. */
static int makeipc (lsys_envproc *p, const char *dir, lsys_error *e) {
  unsigned long pid = (unsigned long)getpid();
  int idx;
  for (idx = 0; idx < MAXKEYS; idx++) {
    int key = (unsigned short)((pid << 2) + 4u * (unsigned)idx);
    unsigned short init[2] = { 0, 1 };
    union envsemun arg;
    if (key == 0) continue;                    /* IPC_PRIVATE */
    p->semid = semget((key_t)key, 2, IPC_CREAT | IPC_EXCL | 0600);
    if (p->semid < 0) {
      if (errno == EEXIST) continue;
      return syserr(p, e, "cannot make its semaphores", errno);
    }
    p->key = key;
    if (p->transport == LSYS_ENVPROC_MEMORY) {
      p->shmid = shmget((key_t)(key - 1), LSYS_ENVPROC_TOFIELD + LSYS_ENVPROC_FROMFIELD,
                        IPC_CREAT | IPC_EXCL | 0600);
      if (p->shmid < 0) {
        int en = errno;
        semctl(p->semid, 0, IPC_RMID);
        p->semid = -1;
        p->key = 0;
        if (en == EEXIST) continue;
        return syserr(p, e, "cannot make its shared memory", en);
      }
      p->shm = (char *)shmat(p->shmid, NULL, 0);
      if (p->shm == (char *)-1) {
        p->shm = NULL;
        return syserr(p, e, "cannot attach its shared memory", errno);
      }
      memset(p->shm, 0, LSYS_ENVPROC_TOFIELD + LSYS_ENVPROC_FROMFIELD);
    }
    arg.array = init;
    if (semctl(p->semid, 0, SETALL, arg) != 0)
      return syserr(p, e, "cannot set its semaphores", errno);
    snprintf(p->keyarg, sizeof p->keyarg, "%d", key);
    snprintf(p->extarg, sizeof p->extarg, "%lu.%d", pid, idx);
    if (p->transport == LSYS_ENVPROC_FILES) {
      char name[80];
      snprintf(name, sizeof name, ".to_field%s", p->extarg);
      p->tofile = joinpath(dir, name);
      snprintf(name, sizeof name, ".from_field%s", p->extarg);
      p->fromfile = joinpath(dir, name);
      if (p->tofile == NULL || p->fromfile == NULL) return nomem(e);
    }
    return LSYS_OK;
  }
  return perr(p, e, LSYS_EARG, "no free IPC key (%d tried)", MAXKEYS);
}

/* ---------------------------------------------------------------------- */
/* Replies */

/* Makes room for READSIZE more bytes in the buffer (and its NUL). */
static int reserve (lsys_envproc *p, size_t more, lsys_error *e) {
  size_t need = p->used + more + 1, ncap;
  char *nb;
  if (need <= p->cap) return LSYS_OK;
  ncap = p->cap < 4096 ? 4096 : p->cap;
  while (ncap < need) ncap *= 2;
  nb = (char *)LSYS_REALLOC(p->buf, ncap);
  if (nb == NULL) {
    p->broken = 1;
    return nomem(e);
  }
  p->buf = nb;
  p->cap = ncap;
  return LSYS_OK;
}

/* The end (just past its '\n') of the first line of the buffer that starts
** with "Control:", or 0 while there is none yet. Lines already looked at are
** not looked at again. */
static size_t findcontrol (lsys_envproc *p) {
  while (p->scan < p->used) {
    const char *s = p->buf + p->scan;
    const char *nl = (const char *)memchr(s, '\n', p->used - p->scan);
    size_t start = p->scan;
    if (nl == NULL) return 0;
    p->scan = (size_t)(nl - p->buf) + 1;
    if (p->scan - start > 8 && memcmp(p->buf + start, CONTROL, 8) == 0) return p->scan;
  }
  return 0;
}

/* Hands out buf[0..end) as the reply; its Control flag says whether more follows
** (a flag that is not a number counts as the last chunk). */
static void finish (lsys_envproc *p, size_t end, const char **reply, size_t *rlen) {
  const char *s = p->buf, *c = NULL;
  size_t i = end - 1;
  int flag = LASTCHUNK, digits = 0;
  while (i > 0 && p->buf[i - 1] != '\n') i--;      /* the Control line starts at i */
  c = s + i + 8;
  while (*c == ' ' || *c == '\t') c++;
  if (*c >= '0' && *c <= '9') flag = 0;
  while (*c >= '0' && *c <= '9' && digits++ < 8) flag = flag * 10 + (*c++ - '0');
  p->pending = (flag & LASTCHUNK) == 0;
  p->rlen = end;
  p->saved = p->buf[end];
  p->buf[end] = '\0';
  *reply = p->buf;
  *rlen = end;
}

/* Drops the reply handed out; what followed it in the stream stays. */
static void consume (lsys_envproc *p) {
  if (p->rlen > 0) {
    p->buf[p->rlen] = p->saved;
    memmove(p->buf, p->buf + p->rlen, p->used - p->rlen);
    p->used -= p->rlen;
    p->rlen = 0;
  }
  p->scan = 0;
}

static int toolong (lsys_envproc *p, lsys_error *e) {
  char sz[32];
  p->broken = 1;
  return perr(p, e, LSYS_EARG, "answered more than %s without a Control line",
              lsys_common_fmtsize(sz, p->limit));
}

/* ---------------------------------------------------------------------- */
/* Pipes */

enum { UNTIL_CONTROL, UNTIL_BYTE, UNTIL_EOF };

/* Writes msg[0..len) to the program's stdin while reading its stdout into the
** buffer (so that a program that answers while it reads never blocks us both),
** then reads on: to the end of a Control line (*end), to a first byte, or to
** the end of its output (discarded), by 'until'. SIGPIPE is ignored meanwhile:
** a program that died gives EPIPE, not the death of this process. */
static int pipeio (lsys_envproc *p, const char *msg, size_t len, int until, double deadline,
                   size_t *end, lsys_error *e) {
  struct sigaction ign, old;
  size_t off = 0, found = 0;
  int st = LSYS_OK;
  memset(&ign, 0, sizeof ign);
  ign.sa_handler = SIG_IGN;
  sigemptyset(&ign.sa_mask);
  sigaction(SIGPIPE, &ign, &old);
  for (;;) {
    struct pollfd fd[2];
    double left;
    int r, nfd = 0, rd = -1, wr = -1, ms;
    if (until == UNTIL_CONTROL && found == 0) {
      found = findcontrol(p);
      if (found > p->limit || (found == 0 && p->used > p->limit)) { st = toolong(p, e); break; }
    }
    if (until == UNTIL_EOF) p->used = p->scan = 0;
    if (off == len && (found != 0 || (until == UNTIL_BYTE && p->used > 0))) break;
    if ((left = deadline - now()) <= 0) {
      st = until == UNTIL_EOF ? LSYS_OK : timedout(p, e);
      break;
    }
    if (found == 0) {                          /* read until the reply is whole */
      if ((st = reserve(p, READSIZE, e)) != LSYS_OK) break;
      fd[rd = nfd++] = (struct pollfd){ p->from, POLLIN, 0 };
    }
    if (off < len) fd[wr = nfd++] = (struct pollfd){ p->to, POLLOUT, 0 };
    ms = (int)ceil((left < SLICE ? left : SLICE) * 1000);
    if ((r = poll(fd, (nfds_t)nfd, ms)) < 0) {
      if (errno == EINTR) continue;
      st = syserr(p, e, "poll", errno);
      break;
    }
    if (rd >= 0 && fd[rd].revents != 0) {
      ssize_t n = read(p->from, p->buf + p->used, READSIZE);
      if (n > 0) p->used += (size_t)n;
      else if (n == 0) {
        st = until == UNTIL_EOF ? LSYS_OK : hangup(p, deadline, "closed its output", e);
        break;
      }
      else if (errno != EAGAIN && errno != EINTR) { st = syserr(p, e, "read", errno); break; }
    }
    if (wr >= 0 && fd[wr].revents != 0) {
      size_t chunk = len - off < READSIZE ? len - off : READSIZE;
      ssize_t n = write(p->to, msg + off, chunk);
      if (n > 0) off += (size_t)n;
      else if (n < 0 && errno != EAGAIN && errno != EINTR) {
        st = errno == EPIPE ? hangup(p, deadline, "stopped reading its input", e)
                            : syserr(p, e, "write", errno);
        break;
      }
    }
    if (r == 0 && !running(p)) { st = died(p, e); break; }
  }
  sigaction(SIGPIPE, &old, NULL);
  if (end != NULL) *end = found;
  return st;
}

/* ---------------------------------------------------------------------- */
/* Files and memory */

static int writeall (int fd, const char *s, size_t n) {
  while (n > 0) {
    ssize_t w = write(fd, s, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    s += w;
    n -= (size_t)w;
  }
  return 0;
}

/* The reply in buf[0..used), up to its Control line; a last line without
** '\n' is given one. */
static int takereply (lsys_envproc *p, const char **reply, size_t *rlen, lsys_error *e) {
  size_t end;
  int st;
  if (p->used > 0 && p->buf[p->used - 1] != '\n') {
    if ((st = reserve(p, 1, e)) != LSYS_OK) return st;
    p->buf[p->used++] = '\n';
  }
  if ((end = findcontrol(p)) == 0) {
    p->broken = 1;
    return perr(p, e, LSYS_EARG, "answered without a Control line");
  }
  finish(p, end, reply, rlen);
  return LSYS_OK;
}

/* Reads the reply the program wrote to .from_field... (at most the limit). */
static int readreply (lsys_envproc *p, const char **reply, size_t *rlen, lsys_error *e) {
  int fd, st = LSYS_OK;
  p->used = p->scan = p->rlen = 0;
  do fd = open(p->fromfile, O_RDONLY | O_CLOEXEC); while (fd < 0 && errno == EINTR);
  if (fd < 0) return syserr(p, e, "cannot read its answer file", errno);
  for (;;) {
    ssize_t n;
    if (p->used > p->limit) { st = toolong(p, e); break; }
    if ((st = reserve(p, READSIZE, e)) != LSYS_OK) break;
    n = read(fd, p->buf + p->used, READSIZE);
    if (n > 0) p->used += (size_t)n;
    else if (n == 0) break;
    else if (errno != EINTR) { st = syserr(p, e, "cannot read its answer file", errno); break; }
  }
  close(fd);
  if (st == LSYS_OK && p->used > p->limit) st = toolong(p, e);
  return st == LSYS_OK ? takereply(p, reply, rlen, e) : st;
}

/* Copies the reply out of the shared memory's from_field area. */
static int shmreply (lsys_envproc *p, const char **reply, size_t *rlen, lsys_error *e) {
  const char *area = p->shm + LSYS_ENVPROC_TOFIELD;
  size_t n = strnlen(area, LSYS_ENVPROC_FROMFIELD);
  int st;
  p->used = p->scan = p->rlen = 0;
  if ((st = reserve(p, n + 1, e)) != LSYS_OK) return st;
  memcpy(p->buf, area, n);
  p->used = n;
  return takereply(p, reply, rlen, e);
}

/* Gives the program the message (the file or the shared memory), lets it run
** and waits for its answer. */
static int handover (lsys_envproc *p, const char *msg, size_t len, double deadline,
                     lsys_error *e) {
  if (p->transport == LSYS_ENVPROC_FILES) {
    int fd, bad;
    do fd = open(p->tofile, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) return syserr(p, e, "cannot write its message file", errno);
    bad = writeall(fd, msg, len) != 0;
    if (close(fd) != 0) bad = 1;
    if (bad) return syserr(p, e, "cannot write its message file", errno);
  }
  else {
    memcpy(p->shm, msg, len);
    if (len < LSYS_ENVPROC_TOFIELD) p->shm[len] = '\0';
  }
  return letrun(p, deadline, e);
}

/* ---------------------------------------------------------------------- */
/* Exchanges */

static int checkmsg (lsys_envproc *p, const char *msg, size_t len, lsys_error *e) {
  size_t i;
  if (p->broken) return perr(p, e, LSYS_EARG, "not usable after an earlier error");
  if (p->pending)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the last reply is not complete: read "
                         "the rest first (more)");
  if (len == 0 || msg[len - 1] != '\n')
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the message must end with a '%s' line",
                         CONTROL);
  for (i = len - 1; i > 0 && msg[i - 1] != '\n'; i--) {}
  if (len - i < 9 || memcmp(msg + i, CONTROL, 8) != 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the message must end with a '%s' line",
                         CONTROL);
  if (p->transport == LSYS_ENVPROC_MEMORY && len > LSYS_ENVPROC_TOFIELD)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "a message of %zu bytes is longer than "
                         "the shared memory's %d", len, LSYS_ENVPROC_TOFIELD);
  return LSYS_OK;
}

/* One exchange ('msg' NULL: the next part of the reply) until 'deadline'. */
static int exchange (lsys_envproc *p, const char *msg, size_t len, double deadline,
                     const char **reply, size_t *rlen, lsys_error *e) {
  int st;
  *reply = NULL;
  *rlen = 0;
  if (p->transport == LSYS_ENVPROC_PIPES) {
    size_t end;
    consume(p);
    st = pipeio(p, msg, msg != NULL ? len : 0, UNTIL_CONTROL, deadline, &end, e);
    if (st == LSYS_OK) finish(p, end, reply, rlen);
    return st;
  }
  if (msg != NULL) st = handover(p, msg, len, deadline, e);
  else st = letrun(p, deadline, e);
  if (st != LSYS_OK) return st;
  if (p->transport == LSYS_ENVPROC_FILES) return readreply(p, reply, rlen, e);
  return shmreply(p, reply, rlen, e);
}

int lsys_envproc_exchange (lsys_envproc *p, const char *msg, size_t len,
                           const char **reply, size_t *rlen, lsys_error *e) {
  int st = checkmsg(p, msg, len, e);
  *reply = NULL;
  *rlen = 0;
  if (st != LSYS_OK) return st;
  return exchange(p, msg, len, now() + p->timeout, reply, rlen, e);
}

int lsys_envproc_more (lsys_envproc *p, const char **reply, size_t *rlen, lsys_error *e) {
  *reply = NULL;
  *rlen = 0;
  if (p->broken) return perr(p, e, LSYS_EARG, "not usable after an earlier error");
  if (!p->pending)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the last reply was complete: there is "
                         "nothing more to read");
  return exchange(p, NULL, 0, now() + p->timeout, reply, rlen, e);
}

/* ---------------------------------------------------------------------- */
/* Starting */

/* The absolute name of the folder 'dir' (NULL: the current one), checked to
** be one, so that the files stay found if the process changes folder. */
static char *absfolder (lsys_envproc *p, const char *dir, lsys_error *e) {
  char *cwd = NULL, *abs;
  size_t n = 256;
  struct stat st;
  if (dir != NULL && dir[0] == '/') abs = dupstr(dir);
  else {
    for (;;) {
      char *nb = (char *)LSYS_REALLOC(cwd, n);
      if (nb == NULL) { LSYS_FREE(cwd); nomem(e); return NULL; }
      cwd = nb;
      if (getcwd(cwd, n) != NULL) break;
      if (errno != ERANGE || n > 65536) {
        syserr(p, e, "cannot find the current folder", errno);
        LSYS_FREE(cwd);
        return NULL;
      }
      n *= 2;
    }
    abs = dir != NULL && dir[0] != '\0' ? joinpath(cwd, dir) : dupstr(cwd);
    LSYS_FREE(cwd);
  }
  if (abs == NULL) { nomem(e); return NULL; }
  if (stat(abs, &st) != 0 || !S_ISDIR(st.st_mode)) {
    int en = errno, found = stat(abs, &st) == 0;
    perr(p, e, LSYS_EARG, "cannot run in '%.60s': %s", dir ? dir : abs,
         found ? "not a folder" : strerror(en));
    LSYS_FREE(abs);
    return NULL;
  }
  return abs;
}

/* The file to run: a name with '/' as it is (the child enters 'dir' first),
** else the first executable regular file of that name in the PATH's folders
** (an empty entry is the current folder, a relative one is relative to
** 'dir', as for execvp in the child). NULL with *en ENOENT, EACCES, ENOMEM. */
static char *findprog (const char *name, const char *dir, int *en) {
  const char *path = getenv("PATH"), *s;
  *en = ENOMEM;
  if (strchr(name, '/') != NULL) return dupstr(name);
  if (path == NULL) path = "/usr/local/bin:/usr/bin:/bin";
  *en = ENOENT;
  for (s = path;; ) {
    const char *colon = strchr(s, ':');
    size_t n = colon != NULL ? (size_t)(colon - s) : strlen(s), nn = strlen(name);
    char *cand = (char *)LSYS_MALLOC((n == 0 ? 1 : n) + nn + 2), *check;
    struct stat st;
    if (cand == NULL) { *en = ENOMEM; return NULL; }
    memcpy(cand, n == 0 ? "." : s, n == 0 ? 1 : n);
    cand[n == 0 ? 1 : n] = '/';
    memcpy(cand + (n == 0 ? 1 : n) + 1, name, nn + 1);
    check = cand[0] == '/' ? cand : joinpath(dir, cand);
    if (check == NULL) { LSYS_FREE(cand); *en = ENOMEM; return NULL; }
    if (stat(check, &st) == 0 && S_ISREG(st.st_mode)) {
      if (access(check, X_OK) == 0) {
        if (check != cand) LSYS_FREE(check);
        return cand;
      }
      *en = EACCES;
    }
    if (check != cand) LSYS_FREE(check);
    LSYS_FREE(cand);
    if (colon == NULL) return NULL;
    s = colon + 1;
  }
}

/* argv with "-k KEY" (and "-ext EXT" for files) after its "-e EFILE". */
static char **buildargv (const lsys_envproc *p, const char *const *argv) {
  size_t n = 0, pos, i, k = 0, extra;
  char **a;
  while (argv[n] != NULL) n++;
  extra = p->transport == LSYS_ENVPROC_PIPES ? 0 : p->transport == LSYS_ENVPROC_FILES ? 4 : 2;
  if (n >= 3 && strcmp(argv[1], "-e") == 0) pos = 3;         /* after "-e EFILE" */
  else if (n >= 2 && strncmp(argv[1], "-e", 2) == 0) pos = 2;
  else pos = 1;
  if ((a = (char **)LSYS_MALLOC((n + extra + 1) * sizeof *a)) == NULL) return NULL;
  for (i = 0; i <= n; i++) {
    if (i == pos && extra > 0) {
      a[k++] = (char *)"-k";
      a[k++] = (char *)p->keyarg;
      if (extra == 4) {
        a[k++] = (char *)"-ext";
        a[k++] = (char *)p->extarg;
      }
    }
    if (i < n) a[k++] = (char *)argv[i];
  }
  a[k] = NULL;
  return a;
}

/* What the child does between fork and exec: async-signal-safe calls only.
** A failure is written to 'ep' as {stage, errno}. */
static void child (const char *path, char *const *argv, const char *dir, int in, int out,
                   int ep) {
  struct sigaction dfl;
  sigset_t none;
  int v[2] = { 0, 0 };
  if (chdir(dir) != 0) v[0] = 1;
  else if (dup2(in, 0) < 0 || (out >= 0 && dup2(out, 1) < 0)) v[0] = 2;
  else {
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(SIGPIPE, &dfl, NULL);          /* the program's own, whatever ours is */
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    execv(path, argv);
    v[0] = 3;
  }
  v[1] = errno;
  if (write(ep, v, sizeof v) < 0) v[0] = 0;
  _exit(127);
}

/* Makes *fd close-on-exec and at least 3, so that the child's dup2 onto 0
** and 1 never overwrites another of its descriptors. */
static int highfd (int *fd) {
  if (*fd >= 0 && *fd < 3) {
    int n = fcntl(*fd, F_DUPFD_CLOEXEC, 3), en = errno;
    close(*fd);
    *fd = n;
    errno = en;
    return n < 0 ? -1 : 0;
  }
  return fcntl(*fd, F_SETFD, FD_CLOEXEC);
}

static void closeall (int *fd, int n) {
  int i;
  for (i = 0; i < n; i++)
    if (fd[i] >= 0) { close(fd[i]); fd[i] = -1; }
}

/* Waits for the child's exec: the report pipe closes (it ran) or holds why
** it failed. */
static int execreport (lsys_envproc *p, int ep, double deadline, lsys_error *e) {
  int v[2];
  size_t got = 0;
  for (;;) {
    struct pollfd fd;
    double left = deadline - now();
    ssize_t n;
    if (left <= 0) return timedout(p, e);
    fd.fd = ep;
    fd.events = POLLIN;
    if (poll(&fd, 1, (int)ceil((left < SLICE ? left : SLICE) * 1000)) <= 0) continue;
    n = read(ep, (char *)v + got, sizeof v - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    if ((got += (size_t)n) == sizeof v) break;
  }
  if (got == 0) return LSYS_OK;
  p->broken = 1;
  if (got < sizeof v) return hangup(p, deadline, "failed to start", e);
  if (v[0] == 1) return perr(p, e, LSYS_EARG, "cannot enter its folder: %s", strerror(v[1]));
  if (v[1] == ENOENT) return perr(p, e, LSYS_EARG, "not found");
  return perr(p, e, LSYS_EARG, "cannot start: %s", strerror(v[1]));
}

/* Forks and runs the program: pipes as its stdin and stdout, or /dev/null as
** its stdin (files, memory); its stderr is ours. */
static int spawn (lsys_envproc *p, const char *path, char *const *argv, const char *dir,
                  double deadline, lsys_error *e) {
  int fd[6] = { -1, -1, -1, -1, -1, -1 };     /* stdin r/w, stdout r/w, report r/w */
  int i, ok = 1;
  pid_t pid;
  if (p->transport == LSYS_ENVPROC_PIPES) ok = pipe(fd) == 0 && pipe(fd + 2) == 0;
  else ok = (fd[0] = open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;
  ok = ok && pipe(fd + 4) == 0;
  for (i = 0; ok && i < 6; i++) ok = fd[i] < 0 || highfd(&fd[i]) == 0;
  if (!ok) {
    int en = errno;
    closeall(fd, 6);
    return syserr(p, e, "cannot start", en);
  }
  if ((pid = fork()) == 0) child(path, argv, dir, fd[0], fd[3], fd[5]);
  if (pid < 0) {
    int en = errno;
    closeall(fd, 6);
    return syserr(p, e, "cannot start", en);
  }
  p->pid = pid;
  p->reaped = 0;
  close(fd[0]);
  if (fd[3] >= 0) close(fd[3]);
  close(fd[5]);
  p->to = fd[1];
  p->from = fd[2];
  if (p->to >= 0) fcntl(p->to, F_SETFL, fcntl(p->to, F_GETFL) | O_NONBLOCK);
  if (p->from >= 0) fcntl(p->from, F_SETFL, fcntl(p->from, F_GETFL) | O_NONBLOCK);
  i = execreport(p, fd[4], deadline, e);
  close(fd[4]);
  return i;
}

/* Waits for the program to say it runs: its byte 0x01 (pipes), sem1 at 0 (files,
** memory). */
static int waitalive (lsys_envproc *p, double deadline, lsys_error *e) {
  int st;
  if (p->transport != LSYS_ENVPROC_PIPES) return semwait(p, 1, 0, deadline, e);
  if ((st = pipeio(p, NULL, 0, UNTIL_BYTE, deadline, NULL, e)) != LSYS_OK) return st;
  if ((unsigned char)p->buf[0] != 1) {
    p->broken = 1;
    return perr(p, e, LSYS_EARG, "wrote 0x%02x instead of its start byte 0x01",
                (unsigned char)p->buf[0]);
  }
  memmove(p->buf, p->buf + 1, --p->used);
  return LSYS_OK;
}

/* Frees 'p' and what it made, but for the child (terminate first). */
static void release (lsys_envproc *p) {
  if (p->to >= 0) close(p->to);
  if (p->from >= 0) close(p->from);
  if (p->shm != NULL) shmdt(p->shm);
  if (p->shmid >= 0) shmctl(p->shmid, IPC_RMID, NULL);
  if (p->semid >= 0) semctl(p->semid, 0, IPC_RMID);
  if (p->tofile != NULL) unlink(p->tofile);
  if (p->fromfile != NULL) unlink(p->fromfile);
  LSYS_FREE(p->tofile);
  LSYS_FREE(p->fromfile);
  LSYS_FREE(p->name);
  LSYS_FREE(p->buf);
  LSYS_FREE(p);
}

static double gracetime (const lsys_envproc *p) {
  return p->timeout / 4 < 1 ? p->timeout / 4 : 1;
}

int lsys_envproc_start (lsys_envproc **pp, int transport, const char *dir,
                        const char *const *argv, double timeout, lsys_error *e) {
  lsys_envproc *p;
  char *folder = NULL, *path = NULL, **args = NULL;
  double deadline = now() + timeout;
  int st = LSYS_OK, en;
  *pp = NULL;
  if (argv == NULL || argv[0] == NULL || argv[0][0] == '\0')
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "no environmental program to run");
  if (transport < LSYS_ENVPROC_PIPES || transport > LSYS_ENVPROC_MEMORY)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "unknown transport %d", transport);
  if (!(timeout > 0 && timeout <= 1e6))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the timeout must be a number of seconds "
                         "in (0, 1e6], got %g", timeout);
  if ((p = (lsys_envproc *)LSYS_MALLOC(sizeof *p)) == NULL) return nomem(e);
  memset(p, 0, sizeof *p);
  p->transport = transport;
  p->reaped = 1;
  p->status = -1;
  p->timeout = timeout;
  p->to = p->from = p->semid = p->shmid = -1;
  p->limit = LSYS_ENVPROC_MAXREPLY;
  if ((p->name = dupstr(argv[0])) == NULL) st = nomem(e);
  if (st == LSYS_OK && (folder = absfolder(p, dir, e)) == NULL) st = e->code;
  if (st == LSYS_OK && (path = findprog(argv[0], folder, &en)) == NULL)
    st = en == ENOMEM ? nomem(e) : en == ENOENT ? perr(p, e, LSYS_EARG, "not found on the PATH")
                                                : perr(p, e, LSYS_EARG, "cannot start: %s",
                                                       strerror(en));
  if (st == LSYS_OK && transport != LSYS_ENVPROC_PIPES) st = makeipc(p, folder, e);
  if (st == LSYS_OK && (args = buildargv(p, argv)) == NULL) st = nomem(e);
  if (st == LSYS_OK) st = spawn(p, path, args, folder, deadline, e);
  if (st == LSYS_OK) st = waitalive(p, deadline, e);
  LSYS_FREE(folder);
  LSYS_FREE(path);
  LSYS_FREE(args);
  if (st != LSYS_OK) {
    terminate(p, gracetime(p));
    release(p);
    return st;
  }
  *pp = p;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Ending */

void lsys_envproc_close (lsys_envproc *p) {
  static const char bye[] = "Control: 8 0\n";
  double grace, end;
  if (p == NULL) return;
  grace = gracetime(p);
  end = now() + p->timeout - grace;
  if (!p->broken && running(p)) {
    lsys_error e;
    const char *r;
    size_t n;
    while (p->pending && !p->broken) exchange(p, NULL, 0, end, &r, &n, &e);  /* the rest */
    if (!p->broken && p->transport == LSYS_ENVPROC_PIPES) {
      p->used = p->scan = p->rlen = 0;
      if (pipeio(p, bye, sizeof bye - 1, UNTIL_BYTE, end, NULL, &e) == LSYS_OK) {
        close(p->to);                          /* its goodbye byte came: then its end */
        p->to = -1;
        pipeio(p, NULL, 0, UNTIL_EOF, end, NULL, &e);
      }
    }
    else if (!p->broken) handover(p, bye, sizeof bye - 1, end, &e);
    if (p->to >= 0) { close(p->to); p->to = -1; }
    if (!p->broken) waitexit(p, end);
  }
  terminate(p, grace);
  release(p);
}

void lsys_envproc_set_limit (lsys_envproc *p, size_t max_reply) {
  p->limit = max_reply < 64 ? 64 : max_reply;
}

long lsys_envproc_pid (const lsys_envproc *p) { return (long)p->pid; }
int lsys_envproc_key (const lsys_envproc *p) { return p->key; }
const char *lsys_envproc_name (const lsys_envproc *p) { return p->name; }
int lsys_envproc_transport (const lsys_envproc *p) { return p->transport; }
