#include "app/render/offscreen_renderer.hpp"

#include <chrono>
#include <cmath>

#include "app/render/imgui_canvas.hpp"
#include "app/render/world_view.hpp"
#include "sim/core/wall_clock.hpp"

namespace formsim::app {
namespace {

using sim::WallSeconds;

int Device(int logical, float scale) {
  return static_cast<int>(std::lround(logical * static_cast<double>(scale)));
}

}  // namespace

OffscreenRenderer::OffscreenRenderer(int width, int height, const Theme& theme, float scale)
    : ctx_(Device(width, scale), Device(height, scale)),
      theme_(theme),
      layer_(theme),
      logical_w_(width),
      logical_h_(height) {
  layer_.SetFontScale(scale);
}

void OffscreenRenderer::Resize(int width, int height) {
  logical_w_ = width;
  logical_h_ = height;
  const int w = Device(width, scale()), h = Device(height, scale());
  if (w != ctx_.width() || h != ctx_.height()) ctx_.Resize(w, h);
}

void OffscreenRenderer::SetScale(float scale) {
  layer_.SetFontScale(scale);
  Resize(logical_w_, logical_h_);
}

void OffscreenRenderer::Begin() {
  t_begin_ = WallSeconds();
  layer_.NewHeadlessFrame(logical_w_, logical_h_, 1.0f / 30.0f);
}

const std::vector<std::uint8_t>& OffscreenRenderer::End(sim::Color clear) {
  const double t1 = WallSeconds();
  layer_.Render(ctx_.width(), ctx_.height(), clear.r, clear.g, clear.b);
  ctx_.Finish();
  const double t2 = WallSeconds();
  times_.build += t1 - t_begin_;
  times_.gl += t2 - t1;
  return ctx_.pixels();
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderWorld(const sim::Experiment& exp,
                                                                View& view, AutoFit& fit, bool jump,
                                                                const std::string& caption) {
  FrameWorldView(exp, static_cast<float>(logical_w_), static_cast<float>(logical_h_), view, fit,
                 jump);
  return RenderWorldAs(exp, view, caption);
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderWorldAs(const sim::Experiment& exp,
                                                                  const View& view,
                                                                  const std::string& caption) {
  Begin();
  WorldViewOptions opt;
  opt.caption = caption;
  opt.scene_overlays = overlays_;
  opt.legend = legend_;
  opt.legend_state = &legend_state_;
  opt.clock = exp.time();  // frames of a run: the corner moves at most once a simulated second
  ImGuiCanvas canvas(ImGui::GetBackgroundDrawList(), layer_.fonts());
  DrawWorldView(canvas, view, exp, theme_, opt);
  return End(theme_.background);
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderImGuiFrame(
    const std::function<void(ImVec2 display, const Fonts& fonts)>& build) {
  Begin();
  build(ImVec2(static_cast<float>(logical_w_), static_cast<float>(logical_h_)), layer_.fonts());
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  return End({bg.x, bg.y, bg.z, 1.0f});
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderFigure(const PlotData& data, int width,
                                                                 int height) {
  Resize(width, height);
  Begin();
  ImGuiCanvas canvas(ImGui::GetBackgroundDrawList(), layer_.fonts());
  last_layout_ =
      DrawPlot(canvas, ImVec2(0, 0), ImVec2(static_cast<float>(width), static_cast<float>(height)),
               data, FigureStyle(theme_));
  return End(theme_.background);
}

}  // namespace formsim::app
