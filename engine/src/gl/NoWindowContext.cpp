// The window part of the GL layer in a build without GLFW (PACIFICA_WITH_GLFW=OFF): headless contexts only.
#include "engine/gl/GlContext.h"

namespace pacifica::gl {

std::unique_ptr<GlContext> createWindowContext(const ContextDesc&) {
    throw ContextError("this build has no window support (configured with PACIFICA_WITH_GLFW=OFF)");
}

} // namespace pacifica::gl
