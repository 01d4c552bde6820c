#pragma once
/// \file Headless rendering: an OSMesa context plus the ImGui layer, drawing the world view, the
/// whole interface or a figure into an RGBA buffer through exactly the code the GUI uses.

#include <cstdint>
#include <string>
#include <vector>

#include "app/imgui_layer.hpp"
#include "app/offscreen_context.hpp"
#include "app/plot.hpp"
#include "app/view.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

class AppUi;

/// Wall-clock seconds spent per phase (for --timing).
struct RenderTimes {
  double build = 0;  ///< ImGui draw lists: world view, panels, plots
  double gl = 0;     ///< OpenGL rasterisation (llvmpipe) and glFinish
};

class OffscreenRenderer {
 public:
  OffscreenRenderer(int width, int height);

  /// The world view of `exp` filling the frame. `view` is updated by `fit` (smoothly unless
  /// `jump`) and returned for callers that need the projection.
  const std::vector<std::uint8_t>& RenderWorld(const sim::Experiment& exp, View& view, AutoFit& fit,
                                               bool jump, const std::string& caption);
  /// The whole interface, as in the GUI window, without input.
  const std::vector<std::uint8_t>& RenderUi(AppUi& ui);
  /// One figure as a white, paper-style picture of `width` x `height`.
  const std::vector<std::uint8_t>& RenderFigure(const PlotData& data, int width, int height);

  int width() const { return ctx_.width(); }
  int height() const { return ctx_.height(); }
  const Fonts& fonts() const { return layer_.fonts(); }
  const RenderTimes& times() const { return times_; }
  /// Axes and legend of the last RenderFigure (for tests).
  const PlotLayout& last_plot_layout() const { return last_layout_; }
  /// Plot style of exported figures (16 px labels, 14 px ticks, 17 px bold title).
  PlotStyle PaperStyle() const;

 private:
  void Begin();
  const std::vector<std::uint8_t>& End(float r, float g, float b);
  OffscreenContext ctx_;
  ImGuiLayer layer_;
  RenderTimes times_;
  PlotLayout last_layout_;
  double t_begin_ = 0;
};

}  // namespace formsim::app
