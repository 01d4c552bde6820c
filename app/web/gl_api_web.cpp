/// \file app/render/gl_api.hpp's loading on WebGL 2: the page has one context (its canvas) and
/// emscripten's GL functions are called directly (app/render/gl_calls.cpp), so there is nothing
/// to load; the context is checked to be WebGL 2, which ImGui's OpenGL ES 3 backend needs.
///
/// It also answers glGetIntegerv(GL_SCISSOR_BOX) from the last glScissor: ImGui's backend asks
/// for the scissor box every frame to restore it, and in a browser that one query waits for the
/// GPU process to finish the frame queued so far (with SwiftShader, 96 % of a cascade7 frame).
/// app/web/CMakeLists.txt routes the backend's and our glScissor and glGetIntegerv here.
#undef glScissor
#undef glGetIntegerv
#include <GLES3/gl3.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "app/render/gl_api.hpp"

namespace {

GLint g_scissor[4] = {0, 0, 0, 0};
bool g_scissor_known = false;

}  // namespace

extern "C" void formsim_gl_scissor(GLint x, GLint y, GLsizei width, GLsizei height) {
  g_scissor[0] = x;
  g_scissor[1] = y;
  g_scissor[2] = width;
  g_scissor[3] = height;
  g_scissor_known = true;
  glScissor(x, y, width, height);
}

extern "C" void formsim_gl_get_integerv(GLenum name, GLint* data) {
  if (name == GL_SCISSOR_BOX) {
    if (!g_scissor_known) {
      glGetIntegerv(GL_SCISSOR_BOX, g_scissor);  // once: the context's initial box
      g_scissor_known = true;
    }
    for (int i = 0; i < 4; ++i) data[i] = g_scissor[i];
    return;
  }
  glGetIntegerv(name, data);
}

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

void GlFlush() {
  glFlush();
}

}  // namespace formsim::app
