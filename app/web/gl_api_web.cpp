/// \file app/render/gl_api.hpp's loading on WebGL 2: the page has one context (its canvas) and
/// emscripten's GL functions are called directly (app/render/gl_calls.cpp), so there is nothing
/// to load; the context is checked to be WebGL 2, which ImGui's OpenGL ES 3 backend needs.
#include <GLES3/gl3.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "app/render/gl_api.hpp"

namespace formsim::app {

void LoadGl(GlGetProcAddress, const char* context_name) {
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (version == nullptr || std::strstr(version, "OpenGL ES 3") == nullptr)
    throw std::runtime_error(std::string(context_name) +
                             ": this browser gives no WebGL 2 context (" +
                             (version ? version : "none") + ")");
}

void GlFinish() {
  glFinish();
}

}  // namespace formsim::app
