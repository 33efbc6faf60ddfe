/* cmake/forbid/lua/GL/glext.h stands in for <GL/glext.h> on the include path of csrc/lua: the bindings (csrc/lua) must not include GL headers: use render.h or viewer.h of csrc/gl */
#error "the bindings (csrc/lua) must not include GL headers: use render.h or viewer.h of csrc/gl"
