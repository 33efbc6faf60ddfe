/* cmake/forbid/core/GLFW/glfw3.h stands in for <GLFW/glfw3.h> on the include path of csrc/core: the core (csrc/core) must not include GL headers: GL belongs in csrc/gl */
#error "the core (csrc/core) must not include GL headers: GL belongs in csrc/gl"
