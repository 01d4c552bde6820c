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
FinishFn g_flush = nullptr;

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
  g_flush = reinterpret_cast<FinishFn>(get_proc("glFlush"));
  if (g_flush == nullptr) throw std::runtime_error(std::string(context_name) + ": no glFlush");
}

std::string GlRendererText() {
#ifndef GL_RENDERER
#define GL_RENDERER 0x1F01
#endif
  const auto text = [](unsigned name) {
    const GLubyte* s = glGetString(name);
    return s == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(s));
  };
  return text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

void GlFinish() {
  g_finish();
}

void GlFlush() {
  g_flush();
}

}  // namespace formsim::app
