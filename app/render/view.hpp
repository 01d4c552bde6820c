#pragma once
/// \file The world-to-pixel mapping of a world view: centre, zoom (pixels per metre) and the
/// screen rectangle it fills. Pan, zoom about a point, follow a robot and fit-all work on it.

#include <imgui.h>

#include "control/common/geometry.hpp"

namespace formsim::app {

struct View {
  Vec2 center;           ///< world point at the middle of the rectangle, m
  double scale = 100.0;  ///< pixels per metre
  ImVec2 min{0, 0};      ///< screen rectangle, pixels (y down)
  ImVec2 max{640, 480};

  ImVec2 ToScreen(Vec2 w) const {
    return ImVec2(static_cast<float>(0.5 * (min.x + max.x) + (w.x - center.x) * scale),
                  static_cast<float>(0.5 * (min.y + max.y) - (w.y - center.y) * scale));
  }
  Vec2 ToWorld(ImVec2 s) const {
    return {center.x + (s.x - 0.5 * (min.x + max.x)) / scale,
            center.y - (s.y - 0.5 * (min.y + max.y)) / scale};
  }
  float width() const { return max.x - min.x; }
  float height() const { return max.y - min.y; }

  /// Centres and zooms so the box [lo, hi] fills the rectangle with `margin_px` to spare.
  void Fit(Vec2 lo, Vec2 hi, float margin_px = 40.0f);
  /// Zooms by `factor` keeping the world point under `screen` fixed.
  void ZoomAt(ImVec2 screen, double factor);
  /// Moves the view by a screen-space drag.
  void Pan(ImVec2 delta_px);
};

/// A camera that keeps a box in view, approached smoothly: either the box given now (`kTrack`:
/// follows the robots at a readable zoom) or the union of all boxes since Reset() (`kGrow`:
/// widens as the robots travel, never jumps back, shows the whole run).
class AutoFit {
 public:
  enum class Mode { kTrack, kGrow };
  void Reset() { valid_ = false; }
  void set_mode(Mode m) { mode_ = m; }
  Mode mode() const { return mode_; }
  /// `smoothing` in (0, 1]: fraction of the way to the target per call (1 jumps).
  void Update(View& view, Vec2 lo, Vec2 hi, double smoothing);
  /// kGrow: adds a box to the union without moving any view (runs exported without frames).
  void Include(Vec2 lo, Vec2 hi);

 private:
  Vec2 lo_, hi_;
  bool valid_ = false;
  Mode mode_ = Mode::kTrack;
};

}  // namespace formsim::app
