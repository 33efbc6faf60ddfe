/*
** ptyrun: drive an interactive program through a pseudo-terminal, as a user
** at a terminal would, for the tests of the REPL.
**
**   ptyrun [-t SECONDS] SCRIPT -- PROGRAM [ARGS...]
**
** PROGRAM runs in a new 80x24 pseudo-terminal with TERM=dumb (so readline
** emits few escape sequences). SCRIPT holds one command a line:
**
**   expect TEXT     read output until TEXT (a plain substring) has appeared
**                   since the end of the previous match; fails after the
**                   timeout (-t, default 10 s) or when the output ends
**   send TEXT       type TEXT and press Enter (TEXT then "\r")
**   sendraw TEXT    write TEXT with \r \n \t \\ \xHH decoded, nothing added
**                   (sendraw \x04 is Ctrl-D, sendraw \x1b[A the up arrow)
**   sleep SECONDS   wait (fractions allowed), still reading the output
**   wait            wait (within the timeout) for PROGRAM to exit
**
** TEXT is the rest of the line after the single space following the command,
** trailing blanks included. Empty lines and lines starting with '#' are
** ignored. The program's output is copied to stdout as it arrives, without
** "\r" and without ANSI escape sequences; expect matches that same text.
**
** Expect the prompt before each send: what is typed before readline has set
** up the terminal is typeahead in the kernel's line mode, where a Ctrl-D
** (sendraw \x04) does not reach readline as Ctrl-D.
**
** Exit status: 0 when every command succeeded (and, after a `wait`, PROGRAM
** exited with status 0); 1 when a command failed (the message and the end of
** the unmatched output go to stderr); 2 for a usage error or a bad SCRIPT;
** 3 when `wait` saw PROGRAM exit with a non-zero status or by a signal.
*/
#define _DEFAULT_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#if defined(__APPLE__) || defined(__NetBSD__) || defined(__OpenBSD__)
#include <util.h>
#elif defined(__FreeBSD__) || defined(__DragonFly__)
#include <libutil.h>
#else
#include <pty.h>
#endif

#define EXIT_FAILED 1     /* a command of the script failed */
#define EXIT_USAGE 2      /* bad arguments or script */
#define EXIT_STATUS 3     /* `wait` saw a non-zero exit status */

#define TAIL_CHARS 500    /* output shown when an expect fails */
#define KILL_GRACE 0.5    /* seconds between SIGTERM and SIGKILL */

enum { C_EXPECT, C_SEND, C_SENDRAW, C_SLEEP, C_WAIT };

typedef struct Cmd {
  int kind;
  int line;               /* in SCRIPT, for messages */
  char *text;             /* expect, send, sendraw (decoded); NUL-terminated */
  size_t len;             /* of text, which may hold NULs after sendraw */
  double secs;            /* sleep */
} Cmd;

typedef struct Buf {
  char *p;
  size_t n, cap;
} Buf;

static const char *script_name;
static const char *prog_name;
static double timeout = 10;

static int master = -1;           /* our side of the pseudo-terminal */
static pid_t child = -1;
static int child_done = 0;        /* reaped; child_status is valid */
static int child_status = 0;
static int out_eof = 0;           /* the terminal's output has ended */
static int chld_pipe[2] = {-1, -1};  /* SIGCHLD handler -> poll (self-pipe) */
static Buf pending;               /* stripped output since the last match */


/* ---------------------------------------------------------------- helpers */

static void usage (FILE *f) {
  fprintf(f, "usage: ptyrun [-t SECONDS] SCRIPT -- PROGRAM [ARGS...]\n"
             "SCRIPT commands, one a line: expect TEXT | send TEXT | sendraw TEXT |\n"
             "sleep SECONDS | wait   (-t: timeout of expect, send and wait; default 10)\n");
}

static void *xrealloc (void *p, size_t n) {
  p = realloc(p, n);
  if (p == NULL) {
    fprintf(stderr, "ptyrun: out of memory\n");
    exit(EXIT_USAGE);
  }
  return p;
}

static void buf_add (Buf *b, const char *s, size_t n) {
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->n + n) cap *= 2;
    b->p = (char *)xrealloc(b->p, cap);
    b->cap = cap;
  }
  memcpy(b->p + b->n, s, n);
  b->n += n;
}

static double now (void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Milliseconds for poll() until 'deadline', rounded up so that we do not
** wake up just before it and spin. */
static int poll_ms (double deadline) {
  double rem = deadline - now();
  if (rem <= 0) return 0;
  if (rem > 1e6) return 1000000000;
  return (int)(rem * 1000) + 1;
}

/* Position of 'pat' (length m >= 1) in s[from..n), or -1. */
static long find (const char *s, size_t n, size_t from, const char *pat, size_t m) {
  size_t i;
  if (m > n) return -1;
  for (i = from; i + m <= n; i++)
    if (s[i] == pat[0] && memcmp(s + i, pat, m) == 0) return (long)i;
  return -1;
}


/* ------------------------------------------------------ escape stripping */

/* States of the stripper, kept between reads so that a sequence split over
** two reads is still removed. */
enum { S_TEXT, S_ESC, S_NF, S_CSI, S_STR, S_STR_ESC };
static int strip_state = S_TEXT;

/* Whether byte c of the output is kept (1) or is part of "\r" or of an
** escape sequence (0). */
static int keep_byte (int c) {
  for (;;) {
    switch (strip_state) {
      case S_TEXT:
        if (c == 0x1b) { strip_state = S_ESC; return 0; }
        return c != '\r';
      case S_ESC:
        if (c == '[') strip_state = S_CSI;
        /* OSC, DCS, SOS, PM, APC: strings ended by BEL or ESC \ */
        else if (c == ']' || c == 'P' || c == 'X' || c == '^' || c == '_') strip_state = S_STR;
        else if (c >= 0x20 && c <= 0x2f) strip_state = S_NF;  /* ESC ( B and the like */
        else if (c != 0x1b) strip_state = S_TEXT;             /* two-byte ESC x */
        return 0;
      case S_NF:    /* intermediate bytes, then one final byte */
        if (c == 0x1b) strip_state = S_ESC;
        else if (c < 0x20 || c > 0x2f) strip_state = S_TEXT;
        return 0;
      case S_CSI:   /* parameters and intermediates up to a final byte 0x40..0x7e */
        if (c == 0x1b) strip_state = S_ESC;
        else if (c >= 0x40 && c <= 0x7e) strip_state = S_TEXT;
        return 0;
      case S_STR:
        if (c == 0x07) strip_state = S_TEXT;
        else if (c == 0x1b) strip_state = S_STR_ESC;
        return 0;
      default:      /* S_STR_ESC: ESC \ ends the string; ESC x starts a new sequence */
        if (c == '\\') { strip_state = S_TEXT; return 0; }
        strip_state = S_ESC;
        continue;   /* look at c again as the byte after ESC */
    }
  }
}

/* Strips n bytes of output, appends them to 'pending' and to the transcript. */
static void take_output (const unsigned char *in, size_t n) {
  char out[4096];
  size_t i, k = 0;
  for (i = 0; i < n; i++) {
    if (keep_byte(in[i])) out[k++] = (char)in[i];
    if (k == sizeof out || (i + 1 == n && k > 0)) {
      buf_add(&pending, out, k);
      fwrite(out, 1, k, stdout);
      k = 0;
    }
  }
  fflush(stdout);
}


/* -------------------------------------------------------- the event loop */

static void on_sigchld (int sig) {
  int saved = errno;
  ssize_t r = write(chld_pipe[1], "c", 1);   /* full pipe: a byte is there already */
  (void)r; (void)sig;
  errno = saved;
}

/* Empties the self-pipe and reaps the child if it has exited. */
static void reap (void) {
  char tmp[64];
  int st;
  while (read(chld_pipe[0], tmp, sizeof tmp) > 0) {}
  if (!child_done && waitpid(child, &st, WNOHANG) == child) {
    child_done = 1;
    child_status = st;
  }
}

/* Reads one chunk from the terminal, if there is one. Linux returns EIO
** once the slave side is closed by everyone: that is the end of output. */
static int read_master (void) {
  unsigned char in[4096];
  ssize_t r = read(master, in, sizeof in);
  if (r > 0) {
    take_output(in, (size_t)r);
    return 1;
  }
  if (r == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR))
    out_eof = 1;
  return 0;
}

#define P_READ 1      /* output was read */
#define P_WRITABLE 2  /* the terminal accepts input */

/* Waits until 'deadline' or until something happens: output (read and
** handled), the child's exit (reaped) or, with 'want_write', room to
** write. Returns a mask of P_READ and P_WRITABLE. */
static int pump (double deadline, int want_write) {
  struct pollfd fds[2];
  int nfds = 1, res = 0;
  fds[0].fd = chld_pipe[0];
  fds[0].events = POLLIN;
  if (!out_eof) {
    fds[1].fd = master;
    fds[1].events = (short)(POLLIN | (want_write ? POLLOUT : 0));
    nfds = 2;
  }
  if (poll(fds, (nfds_t)nfds, poll_ms(deadline)) <= 0) return 0;  /* timeout or EINTR */
  if (fds[0].revents) reap();
  if (nfds == 2) {
    if (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) {
      if (read_master()) res |= P_READ;
    }
    if (fds[1].revents & POLLOUT) res |= P_WRITABLE;
  }
  return res;
}

/* Waits, without reading the terminal, until the child is reaped or 'deadline'. */
static void wait_child (double deadline) {
  struct pollfd fd;
  reap();
  while (!child_done && now() < deadline) {
    fd.fd = chld_pipe[0];
    fd.events = POLLIN;
    poll(&fd, 1, poll_ms(deadline));
    reap();
  }
}

/* Signals the child's process group (forkpty made it a session leader, so
** that group is its own), or the child alone if the group is gone. */
static void signal_child (int sig) {
  if (kill(-child, sig) != 0) kill(child, sig);
}

/* Ends the child: each signal in turn, KILL_GRACE seconds apart, then SIGKILL. */
static void end_child (int first, int second) {
  if (child_done) return;
  signal_child(first);
  wait_child(now() + KILL_GRACE);
  if (second != 0 && !child_done) {
    signal_child(second);
    wait_child(now() + KILL_GRACE);
  }
  if (!child_done) {
    signal_child(SIGKILL);
    if (waitpid(child, &child_status, 0) == child) child_done = 1;
  }
}


/* ---------------------------------------------------------------- failure */

/* Reports a failed command with the end of the unmatched output, ends the
** child and exits. */
static _Noreturn void fail (const Cmd *c, const char *fmt, ...) {
  va_list ap;
  size_t start = 0;
  fflush(stdout);
  fprintf(stderr, "ptyrun: %s:%d: ", script_name, c->line);
  va_start(ap, fmt);
  vfprintf(stderr, fmt, ap);
  va_end(ap);
  fputc('\n', stderr);
  if (pending.n > TAIL_CHARS) {
    start = pending.n - TAIL_CHARS;
    while (start < pending.n && ((unsigned char)pending.p[start] & 0xc0) == 0x80)
      start++;   /* do not begin inside a UTF-8 sequence */
  }
  fprintf(stderr, "ptyrun: output since the previous match%s:\n",
          start > 0 ? " (last 500 characters)" : "");
  fprintf(stderr, "--------\n");
  if (pending.n > 0) fwrite(pending.p + start, 1, pending.n - start, stderr);
  if (pending.n == 0 || pending.p[pending.n - 1] != '\n') fputc('\n', stderr);
  fprintf(stderr, "--------\n");
  end_child(SIGTERM, 0);
  exit(EXIT_FAILED);
}


/* --------------------------------------------------------------- commands */

static void do_expect (const Cmd *c) {
  double deadline = now() + timeout;
  size_t from = 0;
  for (;;) {
    long at = find(pending.p, pending.n, from, c->text, c->len);
    if (at >= 0) {   /* drop everything up to the end of the match */
      size_t end = (size_t)at + c->len;
      memmove(pending.p, pending.p + end, pending.n - end);
      pending.n -= end;
      return;
    }
    /* a match may still end in output that has not arrived */
    from = pending.n >= c->len ? pending.n - c->len + 1 : 0;
    if (out_eof) fail(c, "program exited before \"%s\"", c->text);
    if (now() >= deadline) fail(c, "timed out waiting for \"%s\"", c->text);
    pump(deadline, 0);
  }
}

static void do_send (const Cmd *c, const char *s, size_t n) {
  double deadline = now() + timeout;
  size_t off = 0;
  while (off < n) {
    ssize_t w;
    if (out_eof) fail(c, "cannot send: the program has exited");
    w = write(master, s + off, n - off);
    if (w > 0)
      off += (size_t)w;
    else if (w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      /* the terminal's input queue is full: read output while it drains */
      if (now() >= deadline) fail(c, "timed out sending (the program reads no input)");
      pump(deadline, 1);
    }
    else if (w < 0 && errno == EIO)
      fail(c, "cannot send: the program has exited");
    else if (w < 0 && errno != EINTR)
      fail(c, "cannot send: %s", strerror(errno));
  }
}

static void do_sleep (double secs) {
  double deadline = now() + secs;
  while (now() < deadline) pump(deadline, 0);
}

static void do_wait (const Cmd *c) {
  double deadline = now() + timeout, drain;
  reap();
  while (!child_done) {
    if (now() >= deadline) fail(c, "timed out waiting for %s to exit", prog_name);
    pump(deadline, 0);
  }
  /* Read what it wrote last. The output ends at once unless a process it
  ** started still holds the terminal: do not wait long for that one. */
  drain = now() + KILL_GRACE;
  while (!out_eof && now() < drain) pump(drain, 0);
}


/* ----------------------------------------------------------------- script */

static _Noreturn void script_error (int line, const char *msg, const char *arg) {
  fprintf(stderr, "ptyrun: %s:%d: %s%s\n", script_name, line, msg, arg);
  exit(EXIT_USAGE);
}

static int hexval (int c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/* Decodes the escapes of sendraw in place; returns the decoded length. */
static size_t unescape (char *s, int line) {
  char *r = s, *w = s;
  while (*r != '\0') {
    if (*r != '\\') { *w++ = *r++; continue; }
    r++;
    switch (*r) {
      case 'r': *w++ = '\r'; r++; break;
      case 'n': *w++ = '\n'; r++; break;
      case 't': *w++ = '\t'; r++; break;
      case '\\': *w++ = '\\'; r++; break;
      case 'x': {
        int hi = hexval((unsigned char)r[1]), lo = hi < 0 ? -1 : hexval((unsigned char)r[2]);
        if (lo < 0) script_error(line, "\\x needs two hex digits", "");
        *w++ = (char)(hi * 16 + lo);
        r += 3;
        break;
      }
      default:
        script_error(line, "unknown escape (use \\r \\n \\t \\\\ \\xHH)", "");
    }
  }
  *w = '\0';
  return (size_t)(w - s);
}

/* Reads and checks the whole script before PROGRAM starts. */
static Cmd *read_script (const char *path, int *ncmds) {
  FILE *f = fopen(path, "r");
  Cmd *cmds = NULL;
  int n = 0, cap = 0, line = 0;
  char *ln = NULL;
  size_t lncap = 0;
  ssize_t len;
  if (f == NULL) {
    fprintf(stderr, "ptyrun: cannot open %s: %s\n", path, strerror(errno));
    exit(EXIT_USAGE);
  }
  while ((len = getline(&ln, &lncap, f)) >= 0) {
    char *p = ln, *word, *arg;
    Cmd c;
    line++;
    if (len > 0 && ln[len - 1] == '\n') ln[--len] = '\0';
    if (len > 0 && ln[len - 1] == '\r') ln[--len] = '\0';   /* CRLF scripts */
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '\0' || *p == '#') continue;
    word = p;
    while (*p != '\0' && *p != ' ' && *p != '\t') p++;
    arg = *p != '\0' ? p + 1 : p;   /* TEXT: everything after one blank */
    *p = '\0';
    memset(&c, 0, sizeof c);
    c.line = line;
    if (strcmp(word, "expect") == 0) {
      c.kind = C_EXPECT;
      if (*arg == '\0') script_error(line, "expect needs a TEXT", "");
    }
    else if (strcmp(word, "send") == 0) c.kind = C_SEND;
    else if (strcmp(word, "sendraw") == 0) {
      c.kind = C_SENDRAW;
      if (*arg == '\0') script_error(line, "sendraw needs a TEXT", "");
    }
    else if (strcmp(word, "sleep") == 0) {
      char *end;
      c.kind = C_SLEEP;
      c.secs = strtod(arg, &end);
      if (end == arg || *end != '\0' || !(c.secs >= 0 && c.secs < 1e6))
        script_error(line, "sleep needs a number of seconds, not: ", arg);
    }
    else if (strcmp(word, "wait") == 0) {
      c.kind = C_WAIT;
      if (*arg != '\0') script_error(line, "wait takes no argument", "");
    }
    else
      script_error(line, "unknown command: ", word);
    if (c.kind != C_SLEEP && c.kind != C_WAIT) {
      c.len = strlen(arg);
      c.text = (char *)xrealloc(NULL, c.len + 1);
      memcpy(c.text, arg, c.len + 1);
      if (c.kind == C_SENDRAW) c.len = unescape(c.text, line);
    }
    if (n == cap) {
      cap = cap ? 2 * cap : 16;
      cmds = (Cmd *)xrealloc(cmds, (size_t)cap * sizeof *cmds);
    }
    cmds[n++] = c;
  }
  if (ferror(f)) {
    fprintf(stderr, "ptyrun: cannot read %s: %s\n", path, strerror(errno));
    exit(EXIT_USAGE);
  }
  free(ln);
  fclose(f);
  *ncmds = n;
  return cmds;
}


/* ------------------------------------------------------------------- main */

/* In the child, on the slave side of the terminal: run PROGRAM. */
static _Noreturn void exec_program (char **argv) {
  static const int sigs[] = {SIGINT, SIGQUIT, SIGTERM, SIGHUP, SIGPIPE, SIGCHLD, SIGTSTP};
  sigset_t none;
  size_t i;
  /* an interactive program expects default signals, even if we were
  ** started with some ignored (as background jobs of a script are) */
  for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++) signal(sigs[i], SIG_DFL);
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, NULL);
  setenv("TERM", "dumb", 1);
  execvp(argv[0], argv);
  /* stderr is the terminal: the message is in the output an expect reads */
  fprintf(stderr, "ptyrun: cannot run %s: %s\n", argv[0], strerror(errno));
  _exit(127);
}

int main (int argc, char **argv) {
  Cmd *cmds;
  int ncmds, i, argi = 1, waited = 0;
  struct winsize ws;
  struct sigaction sa;
  if (argc > 1 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
    usage(stdout);
    return 0;
  }
  if (argi < argc && strncmp(argv[argi], "-t", 2) == 0) {
    const char *s = argv[argi][2] != '\0' ? argv[argi] + 2 : argv[++argi];
    char *end;
    if (s == NULL) { usage(stderr); return EXIT_USAGE; }
    timeout = strtod(s, &end);
    if (end == s || *end != '\0' || !(timeout > 0 && timeout < 1e6)) {
      fprintf(stderr, "ptyrun: bad timeout '%s' (seconds > 0)\n", s);
      return EXIT_USAGE;
    }
    argi++;
  }
  if (argi + 2 >= argc || strcmp(argv[argi + 1], "--") != 0) {
    usage(stderr);
    return EXIT_USAGE;
  }
  script_name = argv[argi];
  prog_name = argv[argi + 2];
  cmds = read_script(script_name, &ncmds);

  /* SIGCHLD wakes poll() through a pipe (no polling of waitpid) */
  if (pipe(chld_pipe) != 0) {
    perror("ptyrun: pipe");
    return EXIT_USAGE;
  }
  for (i = 0; i < 2; i++) {
    fcntl(chld_pipe[i], F_SETFL, fcntl(chld_pipe[i], F_GETFL) | O_NONBLOCK);
    fcntl(chld_pipe[i], F_SETFD, FD_CLOEXEC);
  }
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_sigchld;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_NOCLDSTOP;
  sigaction(SIGCHLD, &sa, NULL);

  fflush(stdout);   /* nothing buffered may be written twice after fork */
  memset(&ws, 0, sizeof ws);
  ws.ws_col = 80;
  ws.ws_row = 24;
  child = forkpty(&master, NULL, NULL, &ws);
  if (child < 0) {
    fprintf(stderr, "ptyrun: cannot create a pseudo-terminal: %s\n", strerror(errno));
    return EXIT_USAGE;
  }
  if (child == 0) exec_program(argv + argi + 2);
  fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
  fcntl(master, F_SETFD, FD_CLOEXEC);

  for (i = 0; i < ncmds; i++) {
    const Cmd *c = &cmds[i];
    switch (c->kind) {
      case C_EXPECT: do_expect(c); break;
      case C_SEND:
        do_send(c, c->text, c->len);
        do_send(c, "\r", 1);
        break;
      case C_SENDRAW: do_send(c, c->text, c->len); break;
      case C_SLEEP: do_sleep(c->secs); break;
      default: do_wait(c); waited = 1; break;
    }
  }

  if (!child_done) {
    /* the script is done with the program: show what it wrote, then hang up */
    while (!out_eof && (pump(now(), 0) & P_READ)) {}
    close(master);
    master = -1;
    end_child(SIGHUP, SIGTERM);
  }
  else {
    while (!out_eof && (pump(now(), 0) & P_READ)) {}
    close(master);
  }
  fflush(stdout);
  for (i = 0; i < ncmds; i++) free(cmds[i].text);
  free(cmds);
  free(pending.p);
  if (waited && child_status != 0) {
    if (WIFSIGNALED(child_status))
      fprintf(stderr, "ptyrun: %s exited with status %d (killed by signal %d)\n", prog_name,
              128 + WTERMSIG(child_status), WTERMSIG(child_status));
    else
      fprintf(stderr, "ptyrun: %s exited with status %d\n", prog_name,
              WEXITSTATUS(child_status));
    return EXIT_STATUS;
  }
  return 0;
}
