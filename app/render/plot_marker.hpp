#pragma once
/// \file Marker shapes of plot series (the print theme tells series apart by dash pattern and
/// marker): drawn at a point, filled or hollow, by every canvas alike.

#include <imgui.h>

#include "app/render/canvas.hpp"
#include "app/render/theme.hpp"

namespace formsim::app {

/// Draws `shape` centred on `c` with "radius" `r` (half its width) in `color`; hollow: the
/// outline only (plus and cross are lines either way).
void DrawMarker(Canvas& cv, ImVec2 c, float r, MarkerShape shape, sim::Color color, bool hollow);

}  // namespace formsim::app
