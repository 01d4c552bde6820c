#include "app/render/gl_api.hpp"

#include <imgui.h>

#include <cstring>
#include <stdexcept>
#include <string>

// The gl3w loader that ImGui ships: this translation unit holds its implementation
// (imgl3wProcs); the backend and this file call GL only through those pointers.
#define IMGL3W_IMPL
#include "imgui_impl_opengl3_loader.h"

namespace formsim::app {
namespace {

// glFinish is not in ImGui's loader table; we load it ourselves from the same context.
using FinishFn = void (*)();
FinishFn g_finish = nullptr;

}  // namespace

void LoadGl(GlGetProcAddress get_proc, const char* context_name) {
  // What imgl3wInit2() does, without its load_procs(): ImGui 1.86's loader declares ptr[53] for
  // its 54 entry points (ocornut/imgui#4830), so load_procs() indexes one past ptr[] (undefined
  // behaviour; the pointer lands in gl.Viewport). We store each pointer into the union's bytes.
  constexpr int kProcs = static_cast<int>(sizeof(proc_names) / sizeof(proc_names[0]));
  static_assert(sizeof(imgl3wProcs) >= kProcs * sizeof(GL3WglProc), "gl3w table too small");
  GL3WglProc procs[kProcs];
  for (int i = 0; i < kProcs; ++i)
    procs[i] = reinterpret_cast<GL3WglProc>(get_proc(proc_names[i]));
  std::memcpy(&imgl3wProcs, procs, sizeof(procs));
  const int rc = parse_version();
  if (rc != GL3W_OK) {
    throw std::runtime_error(std::string(context_name) +
                             ": cannot load OpenGL 3.x entry points (gl3w error " +
                             std::to_string(rc) + ")");
  }
  for (int i = 0; i < kProcs; ++i)
    if (procs[i] == nullptr && i != 3 /* glBindSampler is optional */)
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

void GlClearRect(int x, int y, int width, int height, std::uint32_t rgba) {
  if (width <= 0 || height <= 0) return;
  auto channel = [rgba](int shift) { return static_cast<float>((rgba >> shift) & 0xFF) / 255.0f; };
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, width, height);
  glClearColor(channel(IM_COL32_R_SHIFT), channel(IM_COL32_G_SHIFT), channel(IM_COL32_B_SHIFT),
               channel(IM_COL32_A_SHIFT));
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
