#include "app/offscreen_renderer.hpp"

#include <chrono>

#include "app/ui.hpp"
#include "app/world_view.hpp"

namespace formsim::app {
namespace {

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

OffscreenRenderer::OffscreenRenderer(int width, int height) : ctx_(width, height), layer_() {}

void OffscreenRenderer::Begin() {
  t_begin_ = Now();
  layer_.NewHeadlessFrame(ctx_.width(), ctx_.height(), 1.0f / 30.0f);
}

const std::vector<std::uint8_t>& OffscreenRenderer::End(float r, float g, float b) {
  const double t1 = Now();
  layer_.Render(ctx_.width(), ctx_.height(), r, g, b);
  ctx_.Finish();
  const double t2 = Now();
  times_.build += t1 - t_begin_;
  times_.gl += t2 - t1;
  return ctx_.pixels();
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderWorld(const sim::Experiment& exp,
                                                                View& view, AutoFit& fit, bool jump,
                                                                const std::string& caption) {
  Begin();
  view.min = ImVec2(0, 0);
  view.max = ImVec2(static_cast<float>(ctx_.width()), static_cast<float>(ctx_.height()));
  Vec2 lo, hi;
  exp.Bounds(lo, hi);
  fit.Update(view, lo, hi, jump ? 1.0 : 0.15);
  WorldViewOptions opt;
  opt.caption = caption;
  DrawWorldView(ImGui::GetBackgroundDrawList(), view, exp, layer_.fonts(), opt);
  return End(0.98f, 0.98f, 0.97f);
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderUi(AppUi& ui) {
  Begin();
  ui.Draw(ImVec2(static_cast<float>(ctx_.width()), static_cast<float>(ctx_.height())),
          layer_.fonts(), false);
  return End(0.96f, 0.96f, 0.95f);
}

PlotStyle OffscreenRenderer::PaperStyle() const {
  PlotStyle s;
  s.title_font = layer_.fonts().title;
  s.label_font = layer_.fonts().label;
  s.tick_font = layer_.fonts().small;
  s.line_width = 2.0f;
  s.padding = 14.0f;
  return s;
}

const std::vector<std::uint8_t>& OffscreenRenderer::RenderFigure(const PlotData& data, int width,
                                                                 int height) {
  if (width != ctx_.width() || height != ctx_.height()) ctx_.Resize(width, height);
  Begin();
  last_layout_ =
      DrawPlot(ImGui::GetBackgroundDrawList(), ImVec2(0, 0),
               ImVec2(static_cast<float>(width), static_cast<float>(height)), data, PaperStyle());
  return End(1.0f, 1.0f, 1.0f);
}

}  // namespace formsim::app
