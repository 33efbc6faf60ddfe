/* Keeps the GL layer's library non-empty in builds without OSMesa, where it has no sources. */
typedef int lsys_gl_layer_empty;
