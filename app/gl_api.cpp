#include "app/gl_api.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

// The gl3w loader that ImGui ships: this translation unit holds its implementation
// (imgl3wInit2, imgl3wProcs); the backend and this file call GL only through those pointers.
#define IMGL3W_IMPL
#include "imgui_impl_opengl3_loader.h"

namespace formsim::app {
namespace {

// glFinish is not in ImGui's loader table; we load it ourselves from the same context.
using FinishFn = void (*)();
FinishFn g_finish = nullptr;

}  // namespace

void LoadGl(GlGetProcAddress get_proc, const char* context_name) {
  const int rc = imgl3wInit2(reinterpret_cast<GL3WGetProcAddressProc>(get_proc));
  if (rc != GL3W_OK) {
    throw std::runtime_error(std::string(context_name) +
                             ": cannot load OpenGL 3.x entry points (gl3w error " +
                             std::to_string(rc) + ")");
  }
  for (int i = 0; i < static_cast<int>(sizeof(imgl3wProcs.ptr) / sizeof(imgl3wProcs.ptr[0])); ++i)
    if (imgl3wProcs.ptr[i] == nullptr && i != 3 /* glBindSampler is optional */)
      throw std::runtime_error(std::string(context_name) + ": GL entry point #" +
                               std::to_string(i) + " is missing");
  g_finish = reinterpret_cast<FinishFn>(get_proc("glFinish"));
  if (g_finish == nullptr) throw std::runtime_error(std::string(context_name) + ": no glFinish");
}

void GlClear(int width, int height, float r, float g, float b) {
  glViewport(0, 0, width, height);
  glClearColor(r, g, b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void GlFinish() {
  g_finish();
}

std::vector<std::uint8_t> GlReadRgba(int width, int height) {
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  std::vector<std::uint8_t> bottom_up(row * height), top_down(row * height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  // GL's row 0 is the bottom of the image; PNG's is the top.
  for (int y = 0; y < height; ++y)
    std::memcpy(&top_down[y * row], &bottom_up[(height - 1 - y) * row], row);
  return top_down;
}

}  // namespace formsim::app
