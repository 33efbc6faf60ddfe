/*
** C unit tests for environmental programs (envproc.h) against the test
** program tests/c/envslave.c (LSYS_ENVSLAVE): start, exchange, more and close
** over pipes, files and shared memory; programs that are missing, exit at
** once, never start, never answer or die; replies in several Control chunks;
** and after every failure and close no child, no IPC object and no file left.
*/
#if defined(__linux__)
#define _GNU_SOURCE
#else
#define _XOPEN_SOURCE 700
#endif
#undef NDEBUG
#include <assert.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ipc.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "envproc.h"
#include "testdir.h"

#ifndef LSYS_ENVSLAVE
#define LSYS_ENVSLAVE "build/lsys_envslave"
#endif

static const char *dir;     /* the test's folder (testdir.h) */
static const char *const TYPES[] = { "pipes", "files", "memory" };

static double now (void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* x.e in the folder, naming the transport as vlab's .e files do. */
static void efile (int transport) {
  char p[128];
  FILE *f;
  snprintf(p, sizeof p, "%s/x.e", dir);
  f = fopen(p, "w");
  assert(f != NULL);
  fprintf(f, "communication type: %s\nturtle position: %%g %%g %%g\n", TYPES[transport]);
  fclose(f);
}

/* The number of entries in the folder (x.e is one). */
static int entries (void) {
  DIR *d = opendir(dir);
  struct dirent *de;
  int n = 0;
  assert(d != NULL);
  while ((de = readdir(d)) != NULL)
    n += strcmp(de->d_name, ".") != 0 && strcmp(de->d_name, "..") != 0;
  closedir(d);
  return n;
}

/* No child left, zombie or not. */
static void nochild (void) {
  errno = 0;
  assert(waitpid(-1, NULL, WNOHANG) == -1 && errno == ECHILD);
}

/* The semaphore set and shared memory at 'key' (-1: none), to compare before and after:
** another process running at the same time (ctest -j) may hold a key of its own that
** equals one of ours, so the checks are about our objects, not about the keys. */
typedef struct ipcs { int sem, shm; } ipcs;
static ipcs ipcat (int key) {
  ipcs r;
  r.sem = semget((key_t)key, 0, 0);
  r.shm = shmget((key_t)(key - 1), 0, 0);
  return r;
}

/* What was at 'key' before is all that is there: nothing of ours is left. */
static void noipc (int key, ipcs before) {
  ipcs now = ipcat(key);
  assert(now.sem == -1 || now.sem == before.sem);
  assert(now.shm == -1 || now.shm == before.shm);
}

/* Our objects at 'key' (made by a program of ours that is running) are gone. */
static void gone (int key, ipcs ours) {
  ipcs now = ipcat(key);
  assert(now.sem == -1 || now.sem != ours.sem);
  assert(now.shm == -1 || now.shm != ours.shm);
}

/* The key a first program of this process gets. */
static int firstkey (void) { return (unsigned short)((unsigned long)getpid() << 2); }

static int start (lsys_envproc **p, int transport, const char *prog, const char *spec,
                  double timeout, lsys_error *e) {
  const char *argv[] = { prog, "-e", "x.e", spec, NULL };
  efile(transport);
  return lsys_envproc_start(p, transport, dir, argv, timeout, e);
}

static lsys_envproc *started (int transport, const char *spec) {
  lsys_envproc *p = NULL;
  lsys_error e;
  int st = start(&p, transport, LSYS_ENVSLAVE, spec, 5, &e);
  if (st != LSYS_OK) fprintf(stderr, "%s %s: %s\n", TYPES[transport], spec, e.msg);
  assert(st == LSYS_OK && p != NULL);
  assert(lsys_envproc_pid(p) > 0 && lsys_envproc_transport(p) == transport);
  assert((lsys_envproc_key(p) != 0) == (transport != LSYS_ENVPROC_PIPES));
  return p;
}

/* Sends 'msg' and checks the reply is 'want'. */
static void ask (lsys_envproc *p, const char *msg, const char *want) {
  const char *r;
  size_t n;
  lsys_error e;
  int st = lsys_envproc_exchange(p, msg, strlen(msg), &r, &n, &e);
  if (st != LSYS_OK) fprintf(stderr, "exchange: %s\n", e.msg);
  assert(st == LSYS_OK);
  if (strcmp(r, want) != 0) fprintf(stderr, "got [%s] want [%s]\n", r, want);
  assert(n == strlen(want) && strcmp(r, want) == 0);
}

static void more (lsys_envproc *p, const char *want) {
  const char *r;
  size_t n;
  lsys_error e;
  int st = lsys_envproc_more(p, &r, &n, &e);
  if (st != LSYS_OK) fprintf(stderr, "more: %s\n", e.msg);
  assert(st == LSYS_OK && strcmp(r, want) == 0 && n == strlen(want));
}

/* An exchange that fails with a message containing 'msg'. */
static void refused (lsys_envproc *p, const char *msg, const char *want) {
  const char *r = "x";
  size_t n = 1;
  lsys_error e;
  int st = msg != NULL ? lsys_envproc_exchange(p, msg, strlen(msg), &r, &n, &e)
                       : lsys_envproc_more(p, &r, &n, &e);
  if (st == LSYS_OK || strstr(e.msg, want) == NULL)
    fprintf(stderr, "want an error with [%s], got %d [%s]\n", want, st, st ? e.msg : r);
  assert(st != LSYS_OK && strstr(e.msg, want) != NULL && r == NULL && n == 0);
}

/* Closes and checks that nothing is left; the close took less than 'most' s. */
static void closed (lsys_envproc *p, double most) {
  int key = lsys_envproc_key(p);
  ipcs ours = ipcat(key);
  double t0 = now();
  if (lsys_envproc_transport(p) != LSYS_ENVPROC_MEMORY) ours.shm = -2;   /* none of ours */
  lsys_envproc_close(p);
  assert(now() - t0 < most);
  nochild();
  if (key != 0) gone(key, ours);
  assert(entries() == 1);
}

/* echo and sum: items answered, a position format's numbers added, empty fields kept. */
static void answers (int t) {
  lsys_envproc *p = started(t, "echo");
  const char *r;
  size_t n;
  lsys_error e;
  ask(p, "0 E(1,2)F(3)\n 1 2 3\n12 E(5)]\n20 E\nControl: 5 1\n",
      "0 E(2,3)\n12 E(6)\nControl: 5\n");
  ask(p, "7 E(,4)\nControl: 5 2\n", "7 E(,5)\nControl: 5\n");
  ask(p, "Control: 5 3\n", "Control: 5\n");
  /* the caller's mistakes leave the program usable */
  refused(p, "0 E(1)\n", "must end with a 'Control:' line");
  refused(p, "0 E(1)\nControl: 5 1", "must end with a 'Control:' line");
  refused(p, NULL, "nothing more to read");
  assert(lsys_envproc_exchange(p, "", 0, &r, &n, &e) == LSYS_EARG);
  ask(p, "1 E(1)\nControl: 5 4\n", "1 E(2)\nControl: 5\n");
  if (t == LSYS_ENVPROC_MEMORY) {
    char *big = malloc(LSYS_ENVPROC_TOFIELD + 20);
    assert(big != NULL);
    memset(big, 'x', LSYS_ENVPROC_TOFIELD + 20);
    memcpy(big + LSYS_ENVPROC_TOFIELD + 20 - 14, "\nControl: 5 1\n", 14);
    assert(lsys_envproc_exchange(p, big, LSYS_ENVPROC_TOFIELD + 20, &r, &n, &e) == LSYS_EARG);
    assert(strstr(e.msg, "longer than the shared memory's 50000") != NULL);
    free(big);
  }
  ask(p, "2 E(2)\nControl: 5 5\n", "2 E(3)\nControl: 5\n");
  closed(p, 1.5);                      /* it left when asked: no SIGTERM after 4 s */

  p = started(t, "sum");
  ask(p, "0 E(1)F\nP:-1.0000 1.0000 0\n H: 0 1 0\n12 E(2)\nP: 2 3 4\nDbegin\n9 9\nDend\n"
         "Control: 5 1\n", "0 E(1)\n12 E(9)\nControl: 5\n");
  closed(p, 1.5);
}

/* A reply in several Control chunks, after a master chunk without the last flag. */
static void chunks (int t) {
  lsys_envproc *p = started(t, "chunks");
  ask(p, "0 E(1)\n5 E(2)\nControl: 1 0\n", "Control: 5\n");
  ask(p, "10 E(3)\n15 E(4)\n20 E(5)\nControl: 4 1\n", "0 E(2)\n5 E(3)\nControl: 1\n");
  refused(p, "1 E(1)\nControl: 5 2\n", "not complete");
  more(p, "10 E(4)\n15 E(5)\nControl: 0\n");
  more(p, "20 E(6)\nControl: 4\n");
  refused(p, NULL, "nothing more to read");
  ask(p, "3 E(1)\nControl: 5 2\n", "3 E(2)\nControl: 5\n");
  /* closed in the middle of a reply: the rest is read, then the program leaves */
  ask(p, "1 E(1)\n2 E(2)\n3 E(3)\nControl: 5 3\n", "1 E(2)\n2 E(3)\nControl: 1\n");
  closed(p, 1.5);
}

/* A long message and reply (pipes and files; memory holds 50000 bytes). */
static void large (int t) {
  lsys_envproc *p = started(t, "echo");
  size_t i, cap = 4000 * 40;
  char *msg = malloc(cap), *want = malloc(cap), *m = msg, *w = want;
  assert(msg != NULL && want != NULL);
  for (i = 0; i < 4000; i++) {
    m += sprintf(m, "%zu E(%zu)F(1)\n 1 2 3\n", i * 12, i);
    w += sprintf(w, "%zu E(%zu)\n", i * 12, i + 1);
  }
  strcpy(m, "Control: 5 1\n");
  strcpy(w, "Control: 5\n");
  ask(p, msg, want);
  ask(p, msg, want);
  lsys_envproc_set_limit(p, 100);                      /* a reply longer than the limit */
  refused(p, msg, "answered more than 100 bytes without a Control line");
  refused(p, "0 E(1)\nControl: 5 1\n", "not usable after an earlier error");
  closed(p, 1.5);
  free(msg);
  free(want);
}

/* Two programs at once: the second gets the next key and its own files. */
static void two (int t) {
  lsys_envproc *a = started(t, "echo"), *b = started(t, "sum");
  int kb = lsys_envproc_key(b);
  ipcs bs;
  /* the next free key: key + 4 unless another process holds that one */
  assert(t == LSYS_ENVPROC_PIPES || (kb > lsys_envproc_key(a) && kb % 4 == 0));
  ask(a, "0 E(1)\n 1 1 1\nControl: 5 1\n", "0 E(2)\nControl: 5\n");
  ask(b, "0 E(1)\n 1 1 1\nControl: 5 1\n", "0 E(3)\nControl: 5\n");
  bs = ipcat(kb);
  if (t != LSYS_ENVPROC_MEMORY) bs.shm = -2;
  lsys_envproc_close(b);
  ask(a, "0 E(7)\nControl: 5 2\n", "0 E(8)\nControl: 5\n");
  closed(a, 1.5);
  if (t != LSYS_ENVPROC_PIPES) gone(kb, bs);
}

/* A start that fails: the message, and nothing left behind. */
static void nostart (int t, const char *prog, const char *spec, double timeout,
                     const char *want) {
  lsys_envproc *p = (lsys_envproc *)&p;
  lsys_error e;
  ipcs before = ipcat(firstkey());
  double t0 = now();
  int st = start(&p, t, prog, spec, timeout, &e);
  if (st == LSYS_OK || strcmp(e.msg, want) != 0)
    fprintf(stderr, "%s: want [%s], got %d [%s]\n", TYPES[t], want, st, e.msg);
  assert(st == LSYS_EARG && p == NULL && strcmp(e.msg, want) == 0);
  assert(now() - t0 < timeout + 2);
  nochild();
  noipc(firstkey(), before);
  assert(entries() == 1);
}

static void failures (int t) {
  lsys_envproc *p;
  lsys_error e;
  double t0;
  char want[300];
  nostart(t, "lsys-no-such-program", "echo", 5,
          "environmental program 'lsys-no-such-program': not found on the PATH");
  nostart(t, "./no-such-program", "echo", 5,
          "environmental program './no-such-program': not found");
  snprintf(want, sizeof want, "environmental program '%s': exited with status 3",
           LSYS_ENVSLAVE);
  nostart(t, LSYS_ENVSLAVE, "exit", 5, want);
  snprintf(want, sizeof want, "environmental program '%s': did not answer within 0.5 s",
           LSYS_ENVSLAVE);
  nostart(t, LSYS_ENVSLAVE, "silent", 0.5, want);

  /* a program that runs but never answers: the error in time, then only closing */
  assert(start(&p, t, LSYS_ENVSLAVE, "hang", 0.5, &e) == LSYS_OK);
  t0 = now();
  refused(p, "0 E(1)\nControl: 5 1\n", "did not answer within 0.5 s");
  assert(now() - t0 < 2);
  refused(p, "0 E(1)\nControl: 5 1\n", "not usable after an earlier error");
  refused(p, NULL, "not usable after an earlier error");
  closed(p, 1);

  /* a program that dies while it should answer */
  p = started(t, "die");
  snprintf(want, sizeof want, "environmental program '%s': exited with status 5",
           LSYS_ENVSLAVE);
  refused(p, "0 E(1)\nControl: 5 1\n", want);
  closed(p, 1);

  /* a program that does not leave when asked: terminated within its timeout */
  assert(start(&p, t, LSYS_ENVSLAVE, "hang", 1, &e) == LSYS_OK);
  t0 = now();
  closed(p, 1.5);
  assert(now() - t0 > 0.5);
}

static void arguments (void) {
  lsys_envproc *p = NULL;
  lsys_error e;
  const char *none[] = { NULL }, *argv[] = { LSYS_ENVSLAVE, "-e", "x.e", "echo", NULL };
  char missing[128];
  assert(lsys_envproc_start(&p, 0, dir, NULL, 1, &e) == LSYS_EARG && p == NULL);
  assert(lsys_envproc_start(&p, 0, dir, none, 1, &e) == LSYS_EARG);
  assert(lsys_envproc_start(&p, 3, dir, argv, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "unknown transport 3") == 0);
  assert(lsys_envproc_start(&p, 0, dir, argv, 0, &e) == LSYS_EARG);
  assert(lsys_envproc_start(&p, 0, dir, argv, 0.0 / 0.0, &e) == LSYS_EARG);
  assert(strstr(e.msg, "the timeout must be") != NULL);
  snprintf(missing, sizeof missing, "%s/missing", dir);
  assert(lsys_envproc_start(&p, 1, missing, argv, 1, &e) == LSYS_EARG && p == NULL);
  assert(strstr(e.msg, "cannot run in") != NULL);
  lsys_envproc_close(NULL);
  nochild();
}

int main (void) {
  int t;
  char x[128];
  dir = testdir();
  efile(0);
  arguments();
  for (t = LSYS_ENVPROC_PIPES; t <= LSYS_ENVPROC_MEMORY; t++) {
    answers(t);
    chunks(t);
    if (t != LSYS_ENVPROC_MEMORY) large(t);
    two(t);
    failures(t);
  }
  snprintf(x, sizeof x, "%s/x.e", dir);
  assert(remove(x) == 0);
  assert(rmdir(dir) == 0);
  printf("test_envproc: ok\n");
  return 0;
}
