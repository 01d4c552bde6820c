#pragma once
/// \file What the simulation wants drawn, described through an interface (the way Box2D's
/// b2Draw works): sim calls these, app implements them with ImGui draw lists. Coordinates are
/// world metres; sizes in pixels are marked `_px`.

#include <array>
#include <string>
#include <vector>

#include "control/common/geometry.hpp"

namespace formsim::sim {

/// RGBA colour, components in [0, 1].
struct Color {
  float r = 1, g = 1, b = 1, a = 1;
  Color WithAlpha(float alpha) const { return {r, g, b, alpha}; }
};

/// A qualitative palette (Okabe-Ito, colour-blind safe) used for robots and series.
Color PaletteColor(int index);

/// Kinds of mark a legend shows (the scene names each kind it drew, see DrawSink::Legend).
enum class LegendMark { kBody, kLine, kDashedLine, kGhost, kDot, kCross, kEllipse, kRing, kArrow, kArc, kTrail };

/// What a label names, in the order views place them (earlier roles win a contested spot).
enum class LabelRole { kName, kLink, kValue };

/// An optional layer of a scene ("what the law sees"): its name (scenario `view: {overlays}`,
/// `--overlay`, the View panel), a label for the panel, and whether views show it by default.
struct OverlayInfo {
  std::string name, label;
  bool on_by_default = false;
};
/// Every overlay a scene may draw: slots, control_points, links, measured, errors, triangles,
/// velocity, covariance, graph.
const std::vector<OverlayInfo>& Overlays();
/// Whether overlay `name` is on by default (false for unknown names).
bool OverlayOnByDefault(const std::string& name);

/// The draw interface. Every method has a world-space meaning; the implementation maps it to
/// pixels with the current view (pan, zoom).
class DrawSink {
 public:
  virtual ~DrawSink() = default;
  /// Closed polygon; `fill.a == 0` draws only the outline.
  virtual void Polygon(const std::vector<Vec2>& pts, Color fill, Color outline) = 0;
  virtual void Circle(Vec2 center, double radius, Color fill, Color outline) = 0;
  virtual void Segment(Vec2 a, Vec2 b, Color color, float thickness_px = 1.5f) = 0;
  /// Open polyline; with `fade` the oldest point (first) is transparent and the newest opaque.
  virtual void Polyline(const std::vector<Vec2>& pts, Color color, float thickness_px, bool fade) = 0;
  /// Ellipse of a 2x2 covariance [sxx sxy; sxy syy] scaled to `n_sigma` standard deviations.
  virtual void CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy, double n_sigma,
                                 Color color) = 0;
  /// An 'x' marker of `size` metres (e.g. a rejected measurement).
  virtual void Cross(Vec2 p, double size, Color color) = 0;
  /// A label anchored at a world point, offset in pixels (a value: placed after names and links).
  virtual void Text(Vec2 p, const std::string& text, Color color, float dx_px = 0, float dy_px = 0) = 0;
  /// A label of a given role: views place robot names first, then link labels, then values,
  /// and move (or drop) a later label that would cover an earlier one. Default: Text().
  virtual void Label(Vec2 p, const std::string& text, Color color, LabelRole role, float dx_px = 0,
                     float dy_px = 0) {
    (void)role;
    Text(p, text, color, dx_px, dy_px);
  }
  /// A ring that grows and fades, to flash an event (saturation, collision). `age` in [0,1].
  virtual void Flash(Vec2 p, double radius, Color color, float age) = 0;
  /// Whether the view wants overlay `name` (see Overlays()); by default the overlays that are
  /// on by default.
  virtual bool Shows(const std::string& name) const { return OverlayOnByDefault(name); }
  /// Names a kind of mark the scene drew, for the view's legend (called once per kind per
  /// frame; repeated calls with the same label are ignored). Default: no legend.
  virtual void Legend(LegendMark /*mark*/, Color /*color*/, const std::string& /*label*/) {}
  /// Opens a group of marks that belong together, closed by EndGroup (groups nest): a robot is
  /// `id` "robot-NAME" of `cls` "robot". Vector files keep groups (SVG `<g id class>`, the id
  /// made a valid XML id there) so that figures can be styled and checked; other sinks ignore
  /// them.
  virtual void BeginGroup(const std::string& /*id*/, const std::string& /*cls*/) {}
  virtual void EndGroup() {}
  /// A robot's heading arrow (HeadingArrow(), tip first: its tip is the point farthest from its
  /// centroid and lies on the body's heading axis), `fill` its ink (HeadingInk() of `body`) and
  /// `body` the fill of the body under it, so that a themed sink can pick the ink that contrasts
  /// with the body as it shows it. Default: Polygon() with no outline.
  virtual void Heading(const std::vector<Vec2>& pts, Color fill, Color /*body*/) {
    Polygon(pts, fill, Color{0, 0, 0, 0});
  }
  /// Whether angles in labels are wanted in degrees (else radians); the window's setting.
  virtual bool AnglesInDegrees() const { return true; }
  /// Pixels per metre of the view, for level of detail: a scene of a thousand robots skips what
  /// would be smaller than a pixel or two and labels that could not be read. 0 when the sink
  /// has no such scale (draw everything).
  virtual double PixelsPerMetre() const { return 0.0; }
  /// The world box the view shows, so that a large scene can skip what is off screen; by
  /// default everything.
  virtual void ViewBox(Vec2& lo, Vec2& hi) const {
    lo = {-1e300, -1e300};
    hi = {1e300, 1e300};
  }
};

/// An angle as a label in the unit `draw` wants: "225.0°" or "3.927 rad".
std::string AngleLabel(const DrawSink& draw, double rad);

/// Level of detail for a scene drawn into `draw`: how many pixels `metres` spans (a large
/// number when the sink has no scale, so that everything is drawn).
inline double PixelsOf(const DrawSink& draw, double metres) {
  const double ppm = draw.PixelsPerMetre();
  return ppm > 0.0 ? metres * ppm : 1e9;
}

/// The alpha of a robot body's fill (DrawRobotBody; legends show the same).
inline constexpr float kBodyAlpha = 0.85f;

/// A robot's heading arrow in its body frame, for a body spanning x in [back, front] and y in
/// [-half_width, half_width]: a notched arrow along +x, 2.5 times as long (tip to barbs) as it
/// is wide, its notch a quarter of its length deep; 80 % of the body's length (shorter where the
/// body is long and narrow, so that its width stays within 60 % of the body's), centred on the
/// body's length. Points: tip (on the x axis), left barb, notch (on the x axis), right barb;
/// the tip is the point farthest from the arrow's centroid, and every point sees the tip (a fan
/// from it).
std::array<Vec2, 4> HeadingArrow(double back, double front, double half_width);

/// The ink of a heading arrow on a body of colour `body` (opaque, as seen): white or near-black,
/// whichever has the larger WCAG contrast against it.
Color HeadingInk(Color body);

/// Draws a robot body (polygon in the body frame, metres) at `pose` with a heading arrow
/// (HeadingArrow, HeadingInk) and its name `name`, the whole in a group "robot-ID" of class
/// "robot" (`id`: the robot's name, "" = `name`). `ghost` draws it as a dashed-looking
/// translucent outline (desired slots), without a group. Level of detail: below 12 px across no
/// name, below 6 px neither arrow nor outline, below 2 px a dot (ghosts: nothing).
void DrawRobotBody(DrawSink& draw, const Pose2& pose, const std::vector<Vec2>& body_polygon,
                   Color color, const std::string& name, bool ghost = false,
                   const std::string& id = "");

}  // namespace formsim::sim
