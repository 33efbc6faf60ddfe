/*
** Environmental programs (docs/open.md): the process and the bytes of cpfg's
** protocol with a "field" program (vlab's honda81, chiba, ...). This layer
** starts the program, moves one message and its reply at a time and ends the
** program, over cpfg's three local transports:
**
**   pipes   the program's stdin and stdout; it writes one byte 0x01 when it
**           runs and one when it leaves
**   files   .to_field<EXT> and .from_field<EXT> in its folder, EXT being
**           "<pid>.<index>", with a pair of SysV semaphores (sem0: the
**           program may run, sem1: it answered; it sets sem1 to 0 at start)
**   memory  SysV shared memory at key - 1 (a 50000-byte area to the program,
**           then a 10000-byte area from it) and the same semaphores
**
** The text itself (items, chunking, answers) is the Lua side's
** (lua/lsys/environment.lua). Programs are run without a shell; every wait
** is bounded by the timeout given at start; whatever was made (the child,
** IPC objects, files) is undone on failure and by lsys_envproc_close. POSIX
** only.
**
** Messages name the program as its argv[0]: "environmental program 'honda81':
** not found on the PATH", "... exited with status 3", "... was killed by
** signal 9", "... did not answer within 0.5 s", "... cannot start: <reason>".
*/
#ifndef LSYS_ENVPROC_H
#define LSYS_ENVPROC_H

#include "common.h"

typedef struct lsys_envproc lsys_envproc;

enum { LSYS_ENVPROC_PIPES = 0, LSYS_ENVPROC_FILES = 1, LSYS_ENVPROC_MEMORY = 2 };

/* The sizes of cpfg's shared memory areas (memory transport). */
#define LSYS_ENVPROC_TOFIELD   50000
#define LSYS_ENVPROC_FROMFIELD 10000

/* The longest reply (one Control chunk) by default: longer is an error. */
#define LSYS_ENVPROC_MAXREPLY ((size_t)256 << 20)

/*
** Starts the environmental program argv[0] (looked up on the PATH when it has
** no '/', as execvp; a name with '/' is relative to 'dir') with the arguments
** argv[1..] (NULL-terminated) in the folder 'dir' (NULL: the current one),
** speaking 'transport'. The caller's argv holds "-e", EFILE where cpfg puts
** them (argv[1], argv[2]); for files and memory, "-k KEY" (and "-ext EXT" for
** files) are inserted after that pair, as cpfg does. KEY is
** (unsigned short)((pid << 2) + 4 * index), index 0 unless that key's
** semaphore set (or shared memory) exists already, e.g. for another program
** this process runs: then the next free index (cpfg's field index). Waits at
** most 'timeout' seconds (> 0) for the program to say it runs. Returns
** LSYS_OK and *p, or an error (LSYS_EARG for bad arguments, not found,
** exited, no answer; LSYS_ENOMEM) with nothing left behind: the child killed
** and reaped, IPC objects removed, files unlinked.
*/
int lsys_envproc_start (lsys_envproc **p, int transport, const char *dir,
                        const char *const *argv, double timeout, lsys_error *e);

/*
** Sends one message of 'len' bytes (a chunk of items ending with its
** "Control: F S\n" line: anything else is refused with LSYS_EARG) and reads
** the program's reply up to and including the first line that starts with
** "Control:". *reply points into a buffer the process owns, valid until the
** next call on it, NUL-terminated; *rlen its length. Refused (LSYS_EARG)
** while the last reply lacked the last-chunk flag (4): read the rest with
** lsys_envproc_more first. A program that dies, stops answering within the
** timeout, or answers more than the limit is an error after which the
** process only closes (further exchanges are refused).
*/
int lsys_envproc_exchange (lsys_envproc *p, const char *msg, size_t len,
                           const char **reply, size_t *rlen, lsys_error *e);

/* The next part of a reply whose Control line lacked the last-chunk flag
** (4): files and memory let the program run again (sem0 += 1, wait sem1);
** pipes read on to the next Control line. Refused (LSYS_EARG) when the last
** reply was complete. */
int lsys_envproc_more (lsys_envproc *p, const char **reply, size_t *rlen, lsys_error *e);

/*
** Ends the program: sends "Control: 8 0\n" (files, memory: with the
** handshake; pipes: then reads what it writes, its goodbye byte, until it
** leaves), waits for it to exit, kills it (SIGTERM, then SIGKILL) if it does
** not, reaps it, removes the semaphores and the shared memory, unlinks the
** two files, frees 'p'. After a failed exchange the program is not asked but
** terminated. Safe on NULL; returns within the timeout given at start.
*/
void lsys_envproc_close (lsys_envproc *p);

/* The longest reply accepted (default LSYS_ENVPROC_MAXREPLY; at least 64). */
void lsys_envproc_set_limit (lsys_envproc *p, size_t max_reply);

/* The program's process id; its IPC key (0 for pipes); the program as
** given (argv[0]); the transport. */
long lsys_envproc_pid (const lsys_envproc *p);
int lsys_envproc_key (const lsys_envproc *p);
const char *lsys_envproc_name (const lsys_envproc *p);
int lsys_envproc_transport (const lsys_envproc *p);

#endif
