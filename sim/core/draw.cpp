#include "sim/core/draw.hpp"

#include <algorithm>
#include <cmath>

#include "sim/core/number_format.hpp"

namespace formsim::sim {

Color PaletteColor(int index) {
  auto hex = [](unsigned v) {
    return Color{((v >> 16) & 0xFF) / 255.0f, ((v >> 8) & 0xFF) / 255.0f, (v & 0xFF) / 255.0f, 1};
  };
  // Okabe-Ito, ordered so the first colours contrast most on a light background; then Tol's
  // muted scheme (its colours farthest from those: at least ΔE*ab 20 between any two).
  static const Color kPalette[] = {hex(0x0072B2), hex(0xD55E00), hex(0x009E73), hex(0xCC79A7),
                                   hex(0xE69F00), hex(0x56B4E9), hex(0x332288), hex(0x882255),
                                   hex(0x117733), hex(0x999933), hex(0xCC6677), hex(0xAA4499)};
  // Twelve colours: app::kPaletteSize, which a test ties to this table.
  constexpr int n = sizeof(kPalette) / sizeof(kPalette[0]);
  return kPalette[((index % n) + n) % n];
}

std::array<Vec2, 4> HeadingArrow(double back, double front, double half_width) {
  // Length : width 5 : 2 (tip to barbs : barb to barb), the notch a quarter of the length deep:
  // barbs wide enough to read at a 20 px robot, the tip clearly the point farthest from the
  // centroid (0.58 of the length from it, the barbs 0.46).
  const double length = std::min(0.8 * (front - back), 2.5 * 0.6 * 2.0 * half_width);
  const double w = length / 5.0, tail = 0.5 * (back + front) - 0.5 * length;
  return {Vec2{tail + length, 0.0}, Vec2{tail, w}, Vec2{tail + 0.25 * length, 0.0}, Vec2{tail, -w}};
}

Color HeadingInk(Color body) {
  // WCAG relative luminance; white and the outlines' near-black (luminance 0.01).
  auto lin = [](float v) {
    return v <= 0.04045f ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  const double y = 0.2126 * lin(body.r) + 0.7152 * lin(body.g) + 0.0722 * lin(body.b);
  constexpr Color kLight{1, 1, 1, 1}, kDark{0.1f, 0.1f, 0.1f, 1};
  const double dark_y = 0.2126 * lin(kDark.r) + 0.7152 * lin(kDark.g) + 0.0722 * lin(kDark.b);
  const double on_white = 1.05 / (y + 0.05), on_dark = (y + 0.05) / (dark_y + 0.05);
  return on_white >= on_dark ? kLight : kDark;
}

void DrawRobotBody(DrawSink& draw, const Pose2& pose, const std::vector<Vec2>& body_polygon,
                   Color color, const std::string& name, bool ghost, const std::string& id) {
  double extent = 0.0;
  for (const Vec2& b : body_polygon) extent = std::max(extent, b.Norm());
  const double extent_px = PixelsOf(draw, 2.0 * extent);
  if (!ghost) draw.BeginGroup("robot-" + (id.empty() ? name : id), "robot");
  if (extent_px < 2.0) {
    // A dot of at least a pixel and a half, so that a formation seen from afar stays visible.
    const double metres_per_px = 2.0 * extent / extent_px;
    if (!ghost) {
      draw.Circle(pose.p(), std::max(extent, 0.75 * metres_per_px), color, Color{0, 0, 0, 0});
      draw.EndGroup();
    }
    return;
  }
  // Pose2::ToWorld's arithmetic with one cosine and sine per robot, into storage kept between
  // calls (a thousand robots a frame in the window).
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  auto to_world = [&](const Vec2& b) {
    return Vec2{pose.x + c * b.x - s * b.y, pose.y + s * b.x + c * b.y};
  };
  thread_local std::vector<Vec2> world, arrow;
  world.clear();
  double front = 0.0, back = 0.0, half_width = 0.0;
  for (const Vec2& b : body_polygon) {
    world.push_back(to_world(b));
    front = std::max(front, b.x);
    back = std::min(back, b.x);
    half_width = std::max(half_width, std::abs(b.y));
  }
  if (ghost) {
    draw.Polygon(world, color.WithAlpha(0.0f), color.WithAlpha(0.55f));
    return;
  }
  // A small body without its dark outline, which would hide its colour.
  if (extent_px < 6.0) {
    draw.Polygon(world, color.WithAlpha(0.9f), Color{0, 0, 0, 0});
    draw.EndGroup();
    return;
  }
  const Color fill = color.WithAlpha(kBodyAlpha);
  draw.Polygon(world, fill, Color{0.1f, 0.1f, 0.1f, 1.0f});
  // Heading: a slender notched arrow along the body's x axis, its tip on the axis.
  arrow.clear();
  for (const Vec2& b : HeadingArrow(back, front, half_width)) arrow.push_back(to_world(b));
  draw.Heading(arrow, HeadingInk(fill), fill);
  draw.EndGroup();
  // The name sits just above the body's circumscribed circle, whatever the zoom, once the body
  // is large enough for a name to sit beside its neighbours'.
  if (!name.empty() && extent_px >= 12.0)
    draw.Label({pose.x, pose.y + extent}, name, Color{0.1f, 0.1f, 0.1f, 1.0f}, LabelRole::kName,
               -6.0f, -16.0f);
}

std::string AngleLabel(const DrawSink& draw, double rad) {
  if (draw.AnglesInDegrees()) return Sprintf("%.1f°", rad * 180.0 / 3.14159265358979323846);
  return Sprintf("%.3f rad", rad);
}

const std::vector<OverlayInfo>& Overlays() {
  static const std::vector<OverlayInfo> k = {
      {"slots", "desired slots (ghosts)", true},
      {"control_points", "control points M", true},
      {"links", "links with l (and φ)", true},
      {"measured", "measured l, φ and estimates (arcs)", false},
      {"errors", "error vectors M -> slot", false},
      {"triangles", "l-l triangles and singular lines", false},
      {"velocity", "command: feed-forward + feedback", false},
      {"covariance", "estimates and UKF ellipses", true},
      {"graph", "formation graph (arrows, law)", false},
  };
  return k;
}

bool OverlayOnByDefault(const std::string& name) {
  for (const OverlayInfo& o : Overlays())
    if (o.name == name) return o.on_by_default;
  return false;
}

}  // namespace formsim::sim
