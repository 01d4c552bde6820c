#pragma once
/// \file Headless rendering: an OSMesa context plus the ImGui layer, drawing the world view, a
/// figure or any ImGui frame (the whole interface, drawn by the layer above) into an RGBA buffer
/// through exactly the code the GUI uses. Sizes are logical pixels; the buffer is `scale` times
/// larger (PNG at a chosen dpi).

#include <imgui.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "app/render/imgui_layer.hpp"
#include "app/render/offscreen_context.hpp"
#include "app/render/plot.hpp"
#include "app/render/theme.hpp"
#include "app/render/view.hpp"
#include "app/render/world_legend.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// Wall-clock seconds spent per phase (for --timing).
struct RenderTimes {
  double build = 0;  ///< ImGui draw lists: world view, panels, plots
  double gl = 0;     ///< OpenGL rasterisation (llvmpipe) and glFinish
};

class OffscreenRenderer {
 public:
  /// A `width` x `height` logical frame in `theme`, rendered `scale` times larger.
  OffscreenRenderer(int width, int height, const Theme& theme = GetTheme(ThemeId::kLight),
                    float scale = 1.0f);

  /// The world view of `exp` filling the frame. `view` is updated by `fit` (smoothly unless
  /// `jump`) and returned for callers that need the projection.
  const std::vector<std::uint8_t>& RenderWorld(const sim::Experiment& exp, View& view, AutoFit& fit,
                                               bool jump, const std::string& caption);
  /// The world view of `exp` with `view` as it is (already framed).
  const std::vector<std::uint8_t>& RenderWorldAs(const sim::Experiment& exp, const View& view,
                                                 const std::string& caption);
  /// One ImGui frame that `build` draws (windows and panels) on a screen of the frame's logical
  /// size; the background is the style's window colour as `build` leaves it.
  const std::vector<std::uint8_t>& RenderImGuiFrame(
      const std::function<void(ImVec2 display, const Fonts& fonts)>& build);
  /// One figure as a paper-style picture of `width` x `height` logical pixels.
  const std::vector<std::uint8_t>& RenderFigure(const PlotData& data, int width, int height);

  /// Changes the frame size (logical pixels) for the next renders.
  void Resize(int width, int height);
  /// Device pixels per logical pixel for the next renders (fonts are rasterised again).
  void SetScale(float scale);
  float scale() const { return layer_.fonts().scale; }
  /// Size of the rendered image in device pixels (logical size × scale).
  int width() const { return ctx_.width(); }
  int height() const { return ctx_.height(); }
  const Fonts& fonts() const { return layer_.fonts(); }
  /// The last rendered image (RGBA, device pixels).
  const std::vector<std::uint8_t>& pixels() const { return ctx_.pixels(); }
  /// The last rendered image handed over without a copy (pixels() is then no longer it); `next`
  /// becomes the buffer of the following renders (OffscreenContext::TakePixels).
  std::vector<std::uint8_t> TakePixels(std::vector<std::uint8_t> next) {
    return ctx_.TakePixels(std::move(next));
  }
  const Theme& theme() const { return theme_; }
  /// Overlays of the scene (nullptr: the defaults; the set must outlive the renderer) and the
  /// legend, for RenderWorld / RenderWorldAs.
  void SetSceneOverlays(const std::set<std::string>* overlays, bool legend) {
    overlays_ = overlays;
    legend_ = legend;
  }
  const RenderTimes& times() const { return times_; }
  /// Axes and legend of the last RenderFigure (for tests), logical pixels.
  const PlotLayout& last_plot_layout() const { return last_layout_; }

 private:
  void Begin();
  const std::vector<std::uint8_t>& End(sim::Color clear);
  OffscreenContext ctx_;
  const Theme& theme_;
  const std::set<std::string>* overlays_ = nullptr;
  bool legend_ = false;
  LegendState legend_state_;  ///< the legend's corner, kept a second of simulated time
  ImGuiLayer layer_;
  int logical_w_, logical_h_;
  RenderTimes times_;
  PlotLayout last_layout_;
  double t_begin_ = 0;
};

}  // namespace formsim::app
