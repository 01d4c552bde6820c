/// \file The GL calls of app/render/gl_api.hpp that are the same on every context: through the
/// pointers LoadGl filled on the desktop (ImGui's gl3w loader, window or OSMesa), directly on
/// WebGL 2 in the browser page (emscripten's OpenGL ES 3 functions).
#include <imgui.h>

#include <cstring>

#include "app/render/gl_api.hpp"
#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
#else
#include "imgui_impl_opengl3_loader.h"
#endif

namespace formsim::app {

void GlClear(int width, int height, float r, float g, float b) {
  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(r, g, b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void GlClearRect(int x, int y, int width, int height, float r, float g, float b, float a) {
  if (width <= 0 || height <= 0) return;
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, width, height);
  glClearColor(r, g, b, a);
  glClear(GL_COLOR_BUFFER_BIT);
}

void GlClearRect(int x, int y, int width, int height, std::uint32_t rgba) {
  auto channel = [rgba](int shift) { return static_cast<float>((rgba >> shift) & 0xFF) / 255.0f; };
  GlClearRect(x, y, width, height, channel(IM_COL32_R_SHIFT), channel(IM_COL32_G_SHIFT),
              channel(IM_COL32_B_SHIFT), channel(IM_COL32_A_SHIFT));
}

void GlScissorOff() {
  glDisable(GL_SCISSOR_TEST);
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
