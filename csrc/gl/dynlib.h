/*
** Opening a shared library at run time (osmesa.c, glfw_viewer.c): libOSMesa
** and libglfw are opened with dlopen when first needed rather than linked,
** so that lsys.core loads without them, without LLVM and without a display.
*/
#ifndef LSYS_DYNLIB_H
#define LSYS_DYNLIB_H

#include <stddef.h>

/* A function to take from a library: 'fn' points at the function pointer
** variable to fill, of 'size' bytes. */
typedef struct lsys_dynsym {
  void *fn;
  size_t size;
  const char *name;
} lsys_dynsym;

/*
** Opens the first library of the NULL-terminated list 'names' that loads
** (RTLD_NOW | RTLD_LOCAL); a name met earlier in the list is not tried
** again. Returns its handle, or NULL with 'err' (nerr bytes) saying why the
** first name failed and which names were tried.
*/
void *lsys_dynlib_open (const char *const *names, char *err, size_t nerr);

/* Fills the n function pointers of 'syms' from 'lib'. Returns NULL, or the
** name of the first function missing (the pointers are then partly set). */
const char *lsys_dynlib_syms (void *lib, const lsys_dynsym *syms, size_t n);

#endif
