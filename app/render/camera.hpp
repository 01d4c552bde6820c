#pragma once
/// \file The presentation camera: a view-only component that frames the formation (the robots
/// plus their recent trails, with a margin) so that it fills at least half of the view's shorter
/// side, follows it smoothly, and stands still once the user zooms by hand until "fit" is asked
/// for again. It only moves a View: nothing of it is recorded as an edit of the session.

#include <vector>

#include "app/render/view.hpp"
#include "sim/core/experiment.hpp"

namespace formsim::app {

/// What the camera keeps in view, in world metres.
struct FocusSet {
  std::vector<Vec2> bodies;   ///< robot positions
  std::vector<double> radii;  ///< their circumscribed radii
  std::vector<Vec2> trails;   ///< points of their recent trails (when collected)
  /// The box of the recent trails' finite points, when known without `trails` (trail_box).
  bool trail_box = false;
  Vec2 trail_lo, trail_hi;
  bool empty() const { return bodies.empty(); }
  /// The robots' bounding box (bodies grown by their radii); false when there are no robots.
  bool RobotBox(Vec2& lo, Vec2& hi) const;
  /// The box of the recent trails' finite points: trail_lo/hi when trail_box, else from
  /// `trails`; false when there are none.
  bool TrailBox(Vec2& lo, Vec2& hi) const;
};

/// How much of the trails the camera frames and the world view's labels and legend keep off.
constexpr double kFocusTrailSeconds = 3.0;

/// What of the recent trails FocusOf collects.
enum class FocusTrails {
  kPoints,  ///< every point (what the legend keeps off), and their box
  kBox,     ///< only their box (what the presentation camera frames)
  kNone,
};

/// The focus of `exp`: its robots and the trail points of the last `trail_seconds`.
FocusSet FocusOf(const sim::Experiment& exp, double trail_seconds);
/// The same into `out`, keeping its storage; `trails` says how much of the trails (a thousand
/// robots' trails are tens of thousands of points, which the window needs once a second).
void FocusOf(const sim::Experiment& exp, double trail_seconds, FocusSet* out,
             FocusTrails trails = FocusTrails::kPoints);

/// Fraction of `view`'s shorter side that the robots' bounding box fills: its larger side on
/// screen over the view's shorter side (0 without robots).
double FormationFraction(const View& view, const FocusSet& focus);

class PresentationCamera {
 public:
  struct Options {
    double min_fill = 0.55;         ///< the robots' box fills at least this of the shorter side
                                    ///< (the issue asks for half; a little more for slack)
    float margin_fraction = 0.06f;  ///< of the shorter side, kept free around the framed box
    double trail_seconds = kFocusTrailSeconds;  ///< how much of the trails is framed
  };
  PresentationCamera() = default;
  explicit PresentationCamera(Options o) : opt_(o) {}

  /// The view that frames `focus` in `view`'s rectangle: the robots and their recent trails with
  /// a margin, zoomed in further (trails cut off first) when the robots would fill less than
  /// `min_fill` of the shorter side. `top_inset`: pixels at the top of the view that something
  /// drawn over it covers (presentation mode's buttons); the framing keeps below them.
  View Target(const View& view, const FocusSet& focus, float top_inset = 0) const;
  /// Moves `view` towards Target(): `smoothing` in (0, 1] of the way (1 jumps), and at once after
  /// Fit(). Does nothing while suspended.
  void Update(View& view, const FocusSet& focus, double smoothing, float top_inset = 0);
  /// The user zoomed or panned: the camera stops following until Fit().
  void Suspend() { suspended_ = true; }
  /// Frames the formation now and follows it again.
  void Fit() { suspended_ = false, jump_ = true; }
  bool following() const { return !suspended_; }
  const Options& options() const { return opt_; }

 private:
  Options opt_;
  bool suspended_ = false;
  bool jump_ = true;
};

}  // namespace formsim::app
