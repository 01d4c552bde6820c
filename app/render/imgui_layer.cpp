#include "app/render/imgui_layer.hpp"

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <stdexcept>

#include "app/render/clear_hoist.hpp"
#include "app/render/gl_api.hpp"

namespace formsim::app {
namespace {

// The shaders' language: GLSL 3.30 on desktop GL 3.3 core (window and OSMesa), GLSL ES 3.00 on
// WebGL 2 in the browser page.
#ifdef __EMSCRIPTEN__
constexpr const char* kGlslVersion = "#version 300 es";
#else
constexpr const char* kGlslVersion = "#version 330 core";
#endif

}  // namespace

ImGuiLayer::ImGuiLayer(const Theme& theme) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // layout is computed, not remembered: same pictures every run
  io.LogFilename = nullptr;
  fonts_ = LoadFonts();

  ImGuiStyle& style = ImGui::GetStyle();
  // Square corners throughout: a rounded frame is an anti-aliased fan of ~20 triangles where a
  // square one is 2, and a software rasteriser (llvmpipe: virtual machines, remote desktops,
  // lecture-hall laptops) pays per triangle. The panel of controls drew 3.7 k triangles rounded,
  // 1.7 k square (formation_cascade7 at 1920x1080).
  for (float* rounding :
       {&style.WindowRounding, &style.ChildRounding, &style.PopupRounding, &style.FrameRounding,
        &style.GrabRounding, &style.ScrollbarRounding, &style.TabRounding})
    *rounding = 0.0f;
  style.GrabMinSize = 6.0f;  // thin handles of continuous sliders: they hide no digit
  style.WindowBorderSize = 1.0f;
  style.ItemSpacing = ImVec2(8, 5);
  ApplyImGuiTheme(theme);

  if (!ImGui_ImplOpenGL3_Init(kGlslVersion))
    throw std::runtime_error("ImGui OpenGL3 backend failed to initialise");
}

ImGuiLayer::~ImGuiLayer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::SetFontScale(float scale) {
  if (scale == fonts_.scale) return;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  fonts_ = LoadFonts(scale);
  io.Fonts->Build();
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  if (!ImGui_ImplOpenGL3_CreateFontsTexture())
    throw std::runtime_error("ImGui: cannot upload the font atlas at scale " +
                             std::to_string(scale));
}

void ImGuiLayer::SetTheme(const Theme& theme) {
  ApplyImGuiTheme(theme);
}

void ImGuiLayer::NewHeadlessFrame(int width, int height, float dt) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DisplayFramebufferScale = ImVec2(fonts_.scale, fonts_.scale);
  io.DeltaTime = dt > 0 ? dt : 1.0f / 30.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::NewFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::Render(int fb_width, int fb_height, float r, float g, float b) {
  ImGui::Render();
  ImDrawData* dd = ImGui::GetDrawData();
  skipped_clears_ = 0;
  hoisted_clear_ =
      hoist_clears_ && ClearForFrame(*dd, fb_width, fb_height, r, g, b, &skipped_clears_);
  if (!hoist_clears_) GlClear(fb_width, fb_height, r, g, b);
  ImGui_ImplOpenGL3_RenderDrawData(dd);
}

}  // namespace formsim::app
