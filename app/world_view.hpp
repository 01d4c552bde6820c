#pragma once
/// \file The world view: light background, metre grid with coordinates, scale bar, simulated
/// time, then everything the experiment draws through sim::DrawSink.

#include <imgui.h>

#include "app/fonts.hpp"
#include "app/view.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

struct WorldViewOptions {
  bool grid = true;
  bool scale_bar = true;
  bool time_label = true;
  bool coordinates = true;  ///< grid values along the left and bottom edges
  std::string caption;      ///< drawn under the time (scenario name)
};

/// Background colour of the world view (light, so it prints well).
constexpr ImU32 kWorldBackground = IM_COL32(250, 250, 247, 255);

/// Draws the experiment into `view`'s rectangle of `dl` (clipped to it).
void DrawWorldView(ImDrawList* dl, const View& view, const sim::Experiment& exp, const Fonts& fonts,
                   const WorldViewOptions& opt = {});

/// Grid spacing in metres for a zoom: 1-2-5 steps at least `min_px` pixels apart.
double GridStep(double pixels_per_metre, double min_px);

}  // namespace formsim::app
