/* cmake/forbid/core/GL/glext.h stands in for <GL/glext.h> on the include path of csrc/core: the core (csrc/core) must not include GL headers: GL belongs in csrc/gl */
#error "the core (csrc/core) must not include GL headers: GL belongs in csrc/gl"
