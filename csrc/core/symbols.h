/*
** The turtle's symbols, in one table (the cpfg guide, Appendix A; docs/drawing.md §1).
** Each row is one turtle operation: the module name the alphabet knows it by, how the
** turtle on several threads treats it (turtle_par.c) and two flags. Everything that lists
** turtle symbols derives from it: the operations themselves (OP_<op>, turtle_impl.h),
** the turtle's symbol -> operation mapping (turtle.c), the '@' names of the scanner
** (alphabet.c), the parallel split's classes (turtle_par.c) and, through the binding's
** core.symbols(), the Lua side. A new turtle symbol is a row here and its case in the
** turtle's dispatch (turtle.c, module()).
*/
#ifndef LSYS_SYMBOLS_H
#define LSYS_SYMBOLS_H

#include <stddef.h>
#include <stdint.h>

/*
** What a module of the operation is to the parallel split of the interpretation. The
** default is not safe: LSYS_SPLIT_CROSS is 0, so a row that gives 0 and an operation
** without a row keep the whole string on one thread.
*/
enum {
  LSYS_SPLIT_CROSS = 0,   /* its effect crosses branches outside the turtle state */
  LSYS_SPLIT_STATE,       /* changes the turtle state only (or nothing) */
  LSYS_SPLIT_OPEN,        /* '[': saves the state, a branch starts */
  LSYS_SPLIT_CLOSE,       /* ']': restores it */
  LSYS_SPLIT_SEGMENT,     /* F G: a record, and a line in the line style, else a shape */
  LSYS_SPLIT_SHAPE,       /* a record and a shape (triangles) */
  LSYS_SPLIT_RECORD       /* a record */
};

/*
** The table: X(op, name, split, keep, query), one row per operation, in the order of
** the OP_ enum (row k is operation k).
**   op     the operation (OP_<op>)
**   name   the module name, or NULL: the turtle sets the operation otherwise (~X)
**   split  LSYS_SPLIT_<split>
**   keep   1: the module leaves a pending segment open (cpfg calls its EndNode at
**          F f G g [ ] { } ~ and every @ module, not at turns, widths, colours, ...)
**   query  1: the turtle's query mode fills the module's parameters
*/
#define LSYS_SYMBOLS(X) \
  /* op          name    split     keep query */ \
  X(NONE,        NULL,   STATE,    0, 0)  /* a module the turtle does not know */ \
  X(F,           "F",    SEGMENT,  0, 0) \
  X(f,           "f",    STATE,    0, 0) \
  X(G,           "G",    SEGMENT,  0, 0) \
  X(g,           "g",    STATE,    0, 0) \
  X(LEFT,        "+",    STATE,    1, 0) \
  X(RIGHT,       "-",    STATE,    1, 0) \
  X(DOWN,        "&",    STATE,    1, 0) \
  X(UP,          "^",    STATE,    1, 0) \
  X(ROLLL,       "\\",   STATE,    1, 0) \
  X(ROLLR,       "/",    STATE,    1, 0) \
  X(TURN,        "|",    STATE,    1, 0) \
  X(VERT,        "@v",   STATE,    0, 0) \
  X(SETFRAME,    "@R",   STATE,    0, 0) \
  X(MOVETO,      "@M",   STATE,    0, 0) \
  X(PUSH,        "[",    OPEN,     0, 0) \
  X(POP,         "]",    CLOSE,    0, 0) \
  X(WIDER,       "#",    STATE,    1, 0) \
  X(THINNER,     "!",    STATE,    1, 0) \
  X(COLINC,      ";",    STATE,    1, 0) \
  X(COLDEC,      ",",    STATE,    1, 0) \
  X(TEXTURE,     "@Tx",  STATE,    0, 0) \
  X(CONTOUR,     "@#",   STATE,    0, 0) \
  X(DISCZ,       "@o",   SHAPE,    0, 0) \
  X(DISC,        "@c",   SHAPE,    0, 0) \
  X(SPHERE,      "@O",   SHAPE,    0, 0) \
  X(PSTART,      "{",    CROSS,    0, 0)  /* the polygon stack */ \
  X(PEND,        "}",    CROSS,    0, 0) \
  X(PVERT,       ".",    CROSS,    1, 0) \
  X(QP,          "?P",   STATE,    1, 1) \
  X(QH,          "?H",   STATE,    1, 1) \
  X(QU,          "?U",   STATE,    1, 1) \
  X(QL,          "?L",   STATE,    1, 1) \
  X(QE,          "?E",   CROSS,    1, 0)  /* the environment's queries, in order */ \
  X(SCALE,       "@D",   STATE,    0, 0) \
  X(SCALEMUL,    "@Di",  STATE,    0, 0) \
  X(SCALEDIV,    "@Dd",  STATE,    0, 0) \
  X(LABEL,       "@L",   RECORD,   0, 0) \
  X(SYSTEM,      "@S",   CROSS,    0, 0)  /* a command run in string order */ \
  X(STIFF,       "Z",    STATE,    1, 0) \
  X(TSET,        "@Ts",  STATE,    0, 0) \
  X(TINC,        "@Ti",  STATE,    0, 0) \
  X(TDEC,        "@Td",  STATE,    0, 0) \
  X(TPREVENT,    "@Tp",  STATE,    0, 0) \
  X(TFORCE,      "@Tf",  STATE,    0, 0) \
  X(OLDELAST,    "_",    STATE,    1, 0) \
  X(SIDES,       "@!",   STATE,    0, 0) \
  X(SUB,         "?",    CROSS,    0, 0)  /* the sub-L-systems' scales */ \
  X(SUBEND,      "$",    CROSS,    0, 0) \
  X(GSTART,      "@Gs",  CROSS,    0, 0)  /* the control points */ \
  X(GPOINT,      "@Gc",  CROSS,    0, 0) \
  X(GEND,        "@Ge",  CROSS,    0, 0) \
  X(GTAN,        "@Gt",  CROSS,    0, 0) \
  X(GRAD,        "@Gr",  CROSS,    0, 0) \
  X(PSTARTP,     "@PS",  CROSS,    0, 0)  /* the patches */ \
  X(PCTRL,       "@PC",  CROSS,    0, 0) \
  X(PDRAW,       "@PD",  CROSS,    0, 0) \
  X(SURFACE,     NULL,   CROSS,    0, 0)  /* ~X of a view surface X */ \
  X(NOSURFACE,   NULL,   CROSS,    0, 0)  /* ~X of no view surface */ \
  X(JOINT,       "@J",   STATE,    0, 0)

/* One row of the table. */
typedef struct lsys_symbol {
  const char *name;       /* the module name; NULL: none */
  const char *op;         /* the operation's name ("F", "LEFT", ...) */
  uint8_t split;          /* LSYS_SPLIT_* */
  uint8_t keep, query;
} lsys_symbol;

#define LSYS_SYMBOLS_ONE(op, name, split, keep, query) + 1
enum { LSYS_NSYMBOLS = 0 LSYS_SYMBOLS(LSYS_SYMBOLS_ONE) };   /* the rows (operations) */
#undef LSYS_SYMBOLS_ONE

/* The rows, lsys_symbols[op] for op = 0 .. LSYS_NSYMBOLS - 1. */
extern const lsys_symbol lsys_symbols[LSYS_NSYMBOLS];

/* The split class of operation 'op': LSYS_SPLIT_CROSS for an operation out of the
** table. */
static inline int lsys_symbols_split (unsigned op) {
  return op < LSYS_NSYMBOLS ? lsys_symbols[op].split : LSYS_SPLIT_CROSS;
}

/* Does operation 'op' leave the pending segment open? Not when out of the table. */
static inline int lsys_symbols_keep (unsigned op) {
  return op < LSYS_NSYMBOLS && lsys_symbols[op].keep;
}

/* The length of the longest module name of the table that 's' (of 'len' bytes) starts
** with and that starts with 'c' ('@' for the scanner's cpfg names), or 0. */
size_t lsys_symbols_match (const char *s, size_t len, char c);

#endif
