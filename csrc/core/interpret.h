/*
** Interpretation with a model (docs/drawing.md): the turtle over a string of
** the model, with the model's homomorphism streamed into it module by module
** (never expanded whole) and the model's memory budget on what the turtle
** grows (the scene's mesh and records, the branch stack).
*/
#ifndef LSYS_INTERPRET_H
#define LSYS_INTERPRET_H

#include "derive.h"
#include "turtle.h"

/* Runs 't' (its mode, options and, to draw, scene set) over 's' of model
** 'm'; with 'homo', modules that the homomorphism rewrites are replaced by
** what it gives. The model must not be busy (the bindings mark it). Returns
** what lsys_turtle_run returns, with t->err set on failure. */
int lsys_interpret_run (lsys_rules *m, lsys_turtle *t, lsys_lstring *s, const lsys_alphabet *ab,
                        int homo);

#endif
