/*
** Shared definitions of the lsys core: status codes, the error record,
** allocation hooks. The core never includes Lua headers (CONTRIBUTING.md).
*/
#ifndef LSYS_COMMON_H
#define LSYS_COMMON_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#define LSYS_OK       0
#define LSYS_ENOMEM  (-1)   /* allocation failed */
#define LSYS_ELIMIT  (-2)   /* a configured limit (max_modules, ...) was hit */
#define LSYS_ESYNTAX (-3)   /* malformed text */
#define LSYS_ERULE   (-4)   /* a rule callback failed or returned bad values */
#define LSYS_EARG    (-5)   /* bad argument or state */
#define LSYS_EBUSY   (-6)   /* the object is in use by a running operation (re-entry) */
#define LSYS_EMEMORY (-7)   /* the memory budget (max_memory) would be exceeded */

/* Allocation goes through these so tests can inject failures. */
#ifndef LSYS_MALLOC
#define LSYS_MALLOC(n)     malloc(n)
#define LSYS_REALLOC(p, n) realloc((p), (n))
#define LSYS_FREE(p)       free(p)
#endif

/* An error record filled by core functions that fail. 'pos' is a byte
** offset into the text being parsed, or a module index, depending on the
** function; it is (size_t)-1 when it does not apply. */
typedef struct lsys_error {
  int code;
  size_t pos;
  char msg[256];
} lsys_error;

int lsys_seterror (lsys_error *e, int code, size_t pos, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 4, 5)))
#endif
  ;

/* Sets the error "where: message" and returns 'code': the one form of the
** messages that name a place, a module ("module 12 'F'") or a line of a
** file (lsys_vseterror_line). The message ('fmt' with 'ap') is cut to 199
** bytes, then the whole to the 255 of e->msg. */
int lsys_vseterror_at (lsys_error *e, int code, size_t pos, const char *where,
                       const char *fmt, va_list ap);

/* The same with the place "name:line", as compilers and Lua write it
** ("leaf.s:3: expected 'CONTACT POINT'"). */
int lsys_vseterror_line (lsys_error *e, int code, size_t pos, const char *name, size_t line,
                         const char *fmt, va_list ap);

/* Grows '*p' (an array of 'elem'-byte items with capacity '*cap') so that it
** holds at least 'need' items; capacity doubles. Returns LSYS_OK or
** LSYS_ENOMEM (the old block stays valid). */
int lsys_common_grow (void **p, size_t *cap, size_t need, size_t elem);

/*
** The memory budget (docs/manual.md §9, max_memory). The buffers that grow with
** the input of one operation (the strings of a derivation step and its
** context tables, the mesh and records of an interpretation) are attached to
** one meter: 'used' counts their bytes, and growing past 'limit' fails with
** LSYS_EMEMORY before anything is allocated, so a runaway model gets a clear
** error instead of exhausting the machine.
*/
typedef struct lsys_meter {
  size_t limit;            /* bytes; (size_t)-1 for no limit */
  size_t used;
  int hit;                 /* a growth was refused (for the message) */
  void *lock;              /* NULL, or a pthread_mutex_t held around each growth when
                              several threads grow within the meter (turtle_par.c) */
} lsys_meter;

/* Asks for huge pages behind the block of n bytes at p when it is big (4 MiB
** or more) and the system gives them on request (Linux): its first touch then
** faults every 2 MiB, not every 4 KiB. lsys_common_grow and the meter's growth call it. */
void lsys_common_hugepages (void *p, size_t n);

/* lsys_common_grow within the meter 'mt' (NULL: none): the doubled capacity is cut
** to what the budget leaves; LSYS_EMEMORY when even 'need' items do not
** fit. 'mt->used' must include the block's present size ('*cap' items). */
int lsys_common_grow_metered (void **p, size_t *cap, size_t need, size_t elem, lsys_meter *mt);

/* The budgeting half of lsys_common_grow_metered, for arrays that grow together:
** the capacity *ncap (>= need) to give a block of 'cap' items of 'elem'
** bytes, counted in the meter; LSYS_EMEMORY when 'need' items do not fit.
** Allocates nothing. */
int lsys_common_meter_take (lsys_meter *mt, size_t cap, size_t need, size_t elem, size_t *ncap);

/* Whether 'bytes' more fit in the meter (NULL: always). */
int lsys_common_meter_fits (const lsys_meter *mt, size_t bytes);

/* The process-wide default budget: what lsys_common_set_memory_limit set, else
** half of the physical memory (or of a smaller cgroup memory limit). */
size_t lsys_common_memory_limit (void);
void lsys_common_set_memory_limit (size_t bytes);   /* 0: back to the default */

/* Physical memory in bytes, lowered to the cgroup's memory limit when there
** is one; 0 when unknown. */
size_t lsys_common_physical_memory (void);

/* A short printable quote of 'n' bytes of a file for messages: at most
** LSYS_QUOTE characters (a longer word is cut to its first LSYS_QUOTE - 4
** and "..."), control and non-ASCII bytes as '?'. A file that a view names
** may be anything (as in cpfg), so a message shows a token, never a line. */
#define LSYS_QUOTE 16
const char *lsys_common_quote (char buf[LSYS_QUOTE + 1], const char *s, size_t n);

/* Writes x in the shortest %g form that reads back to x (the file writers). */
void lsys_common_shortest (char buf[32], double x);

/* Writes 'bytes' as a short size for messages ("512 MiB", "12.0 GiB"). */
const char *lsys_common_fmtsize (char buf[32], size_t bytes);

/* Reads the whole file 'path' (at most 'max' bytes) into a new block (free
** it with LSYS_FREE; not NUL-terminated) of *len bytes. Refuses what is not
** a regular file (a device such as /dev/zero, a FIFO, a folder). On failure
** returns NULL with e->msg naming the file ("cannot open 'x': ...", "cannot
** read 'x': larger than N MiB", "cannot read 'x': not a regular file"). */
char *lsys_common_readfile (const char *path, size_t max, size_t *len, lsys_error *e);

#endif
