/*
** The light's C tests (test_light.c) again, with the rays' vectors as plain
** arrays of four floats (LSYS_LIGHT_SCALAR): the path every machine without
** SSE2 takes must find exactly what testing every primitive finds.
*/
#define LSYS_LIGHT_SCALAR 1
#include "test_light.c"
