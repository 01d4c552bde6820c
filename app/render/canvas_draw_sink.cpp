#include "app/render/canvas_draw_sink.hpp"

#include "app/render/contrast.hpp"

#include <algorithm>
#include <cmath>

#include "app/render/polyline_simplify.hpp"

namespace formsim::app {

// Scene labels' contrast against the theme's backdrop: 4.5:1 with a margin for what shows
// through the backdrop.
constexpr double kLabelContrast = 6.0;

namespace {
constexpr float kSmallShapePx = 12.0f;

double Cross(ImVec2 o, ImVec2 a, ImVec2 b) {
  return static_cast<double>(a.x - o.x) * (b.y - o.y) -
         static_cast<double>(a.y - o.y) * (b.x - o.x);
}

// `pts` moved `d[k]` pixels inwards (outwards for d[k] < 0) along each edge's normal (a convex
// polygon's mitred inset), in `inset[k]`, for both k (the normals computed once); an inset is
// empty when the shape is too thin to keep an inside. False when `pts` is not strictly convex or
// has a corner sharper than 30 degrees (the mitre would reach far out).
bool InsetConvex(const std::vector<ImVec2>& pts, const float (&d)[2],
                 std::vector<ImVec2>* const (&inset)[2], std::vector<ImVec2>* normal_scratch) {
  const std::size_t n = pts.size();
  if (n < 3) return false;
  double sign = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double c = Cross(pts[i], pts[(i + 1) % n], pts[(i + 2) % n]);
    if (c == 0 || (sign != 0 && (c > 0) != (sign > 0))) return false;
    sign = c;
  }
  // Inward unit normal of the edge i -> i+1.
  std::vector<ImVec2>& normal = *normal_scratch;
  normal.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ImVec2 a = pts[i], b = pts[(i + 1) % n];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) return false;
    const float s = sign > 0 ? 1.0f : -1.0f;
    normal[i] = ImVec2(static_cast<float>(-(b.y - a.y) / len) * s,
                       static_cast<float>((b.x - a.x) / len) * s);
  }
  for (std::vector<ImVec2>* out : inset) out->assign(n, ImVec2());
  for (std::size_t i = 0; i < n; ++i) {
    const ImVec2 na = normal[(i + n - 1) % n], nb = normal[i];
    const float k = 1.0f + na.x * nb.x + na.y * nb.y;
    if (k < 0.134f) return false;  // 1 + cos(150 deg): a corner under 30 degrees
    for (int j = 0; j < 2; ++j)
      (*inset[j])[i] =
          ImVec2(pts[i].x + d[j] * (na.x + nb.x) / k, pts[i].y + d[j] * (na.y + nb.y) / k);
  }
  // Too thin: an inset turned over (its orientation flipped or it has no area left).
  double outer = 0;
  for (std::size_t i = 0; i < n; ++i) outer += Cross(ImVec2(0, 0), pts[i], pts[(i + 1) % n]);
  for (std::vector<ImVec2>* out : inset) {
    double area = 0;
    for (std::size_t i = 0; i < n; ++i) area += Cross(ImVec2(0, 0), (*out)[i], (*out)[(i + 1) % n]);
    if (area * outer <= 0 || std::abs(area) < 1.0) out->clear();
  }
  return true;
}
}  // namespace

void CanvasDrawSink::Legend(sim::LegendMark mark, sim::Color color, const std::string& label) {
  for (const LegendEntry& e : legend_)
    if (e.label == label) return;
  legend_.push_back({mark, color, label});
}

void CanvasDrawSink::Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color outline) {
  if (pts.size() < 2) return;
  // Scratch kept between calls: a thousand robots draw two polygons each a frame.
  std::vector<ImVec2>& s = screen_;
  s.clear();
  for (const Vec2& p : pts) s.push_back(view_.ToScreen(p));
  const int n = static_cast<int>(s.size());
  // Level of detail (the window only): a shape under kSmallShapePx (a robot of a zoomed-out
  // swarm, its heading wedge) is filled without ImGui's anti-aliasing fringe (an outline covers
  // the edge; a wedge's steps are under a pixel at that size) and gets a one-pixel outline, which
  // ImGui draws with fewer triangles a side. The fringe and the wider outline are thin triangles,
  // which a software rasteriser pays for per block they touch.
  bool small = false;
  if (level_of_detail_) {
    float lo_x = s[0].x, hi_x = s[0].x, lo_y = s[0].y, hi_y = s[0].y;
    for (const ImVec2& p : s) {
      lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x);
      lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
    }
    small = std::max(hi_x - lo_x, hi_y - lo_y) < kSmallShapePx;
  }
  const sim::Color fill_ink = theme_.Fill(fill);
  if (small && outline.a > 0 && fill.a > 0) {
    // A small filled shape with its outline: the outline's colour filled half a pixel beyond the
    // edge, then the fill half a pixel inside it, where a one-pixel outline would have run (four
    // triangles for a rectangle, none of them thin). The fill is made
    // opaque as it looks over the background: at this size nothing shows through it anyway.
    std::vector<ImVec2>& outer = outer_;
    std::vector<ImVec2>& inner = inner_;
    if (InsetConvex(s, {-0.5f, 0.5f}, {&outer, &inner}, &normals_) && !outer.empty()) {
      const sim::Color bg = theme_.background;
      const float a = fill_ink.a;
      const sim::Color solid{fill_ink.r * a + bg.r * (1 - a), fill_ink.g * a + bg.g * (1 - a),
                             fill_ink.b * a + bg.b * (1 - a), 1.0f};
      cv_.FillPolygonAliased(outer.data(), n, theme_.Ink(outline));
      if (!inner.empty()) cv_.FillPolygonAliased(inner.data(), n, solid);
      return;
    }
  }
  if (fill.a > 0) {
    if (small)
      cv_.FillPolygonAliased(s.data(), n, fill_ink);
    else
      cv_.FillPolygon(s.data(), n, fill_ink);
  }
  if (outline.a <= 0) return;
  cv_.Polyline(s.data(), n, {theme_.Ink(outline), Width(small ? 1.0f : 1.5f)}, true);
}

void CanvasDrawSink::Heading(const std::vector<Vec2>& pts, sim::Color fill, sim::Color body) {
  if (pts.size() < 3 || fill.a <= 0) return;
  std::vector<ImVec2>& s = screen_;
  s.clear();
  for (const Vec2& p : pts) s.push_back(view_.ToScreen(p));
  const sim::Color ink = theme_.HeadingInk(body).WithAlpha(fill.a);
  const int n = static_cast<int>(s.size());
  if (level_of_detail_) {
    // Under kSmallShapePx (the window's level of detail): filled without anti-aliasing fringes,
    // as the body under it.
    float lo_x = s[0].x, hi_x = s[0].x, lo_y = s[0].y, hi_y = s[0].y;
    for (const ImVec2& p : s) {
      lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x);
      lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
    }
    if (std::max(hi_x - lo_x, hi_y - lo_y) < kSmallShapePx) {
      cv_.FillPolygonAliased(s.data(), n, ink);
      return;
    }
  }
  cv_.FillFan(s.data(), n, ink, "heading");
}

void CanvasDrawSink::Circle(Vec2 center, double radius, sim::Color fill, sim::Color outline) {
  const ImVec2 c = view_.ToScreen(center);
  const float r = static_cast<float>(radius * view_.scale);
  if (r < 0.5f) return;
  if (fill.a > 0) cv_.FillCircle(c, r, theme_.Fill(fill));
  if (outline.a > 0) cv_.StrokeCircle(c, r, theme_.Ink(outline), Width(1.5f));
}

void CanvasDrawSink::Segment(Vec2 a, Vec2 b, sim::Color color, float thickness_px) {
  cv_.Line(view_.ToScreen(a), view_.ToScreen(b), {theme_.Ink(color), Width(thickness_px)});
}

void CanvasDrawSink::Polyline(const std::vector<Vec2>& pts, sim::Color color, float thickness_px,
                              bool fade) {
  if (pts.size() < 2) return;
  // Drop points closer than a pixel to the previous kept one: long trails stay cheap.
  std::vector<ImVec2> s;
  s.reserve(pts.size());
  for (const Vec2& p : pts) {
    const ImVec2 q = view_.ToScreen(p);
    if (!s.empty() && std::abs(q.x - s.back().x) + std::abs(q.y - s.back().y) < 1.0f &&
        &p != &pts.back())
      continue;
    s.push_back(q);
  }
  s = SimplifyPolyline(s);
  const sim::Color ink = theme_.Ink(color);
  const float th = Width(thickness_px);
  if (!fade) {
    cv_.Polyline(s.data(), static_cast<int>(s.size()), {ink, th});
    return;
  }
  // Fading trail: a few chunks of increasing opacity, each one polyline (joins stay smooth).
  const int chunks = std::min<int>(12, static_cast<int>(s.size()) - 1);
  for (int k = 0; k < chunks; ++k) {
    const std::size_t i0 = s.size() * k / chunks,
                      i1 = std::min(s.size() - 1, s.size() * (k + 1) / chunks);
    if (i1 <= i0) continue;
    const float alpha = ink.a * (0.08f + 0.92f * static_cast<float>(k + 1) / chunks);
    cv_.Polyline(&s[i0], static_cast<int>(i1 - i0 + 1), {ink.WithAlpha(alpha), th});
  }
}

void CanvasDrawSink::CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy,
                                       double n_sigma, sim::Color color) {
  if (!std::isfinite(sxx) || !std::isfinite(sxy) || !std::isfinite(syy)) return;
  // Eigen-decomposition of the symmetric 2x2 covariance: axes along the eigenvectors.
  const double tr = 0.5 * (sxx + syy), det = sxx * syy - sxy * sxy;
  const double disc = std::sqrt(std::max(0.0, tr * tr - det));
  const double l1 = std::max(0.0, tr + disc), l2 = std::max(0.0, tr - disc);
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  const double a = n_sigma * std::sqrt(l1), b = n_sigma * std::sqrt(l2);
  const double ca = std::cos(angle), sa = std::sin(angle);
  constexpr int kN = 48;
  ImVec2 pts[kN];
  for (int i = 0; i < kN; ++i) {
    const double t = 2 * M_PI * i / kN, ex = a * std::cos(t), ey = b * std::sin(t);
    pts[i] = view_.ToScreen({center.x + ca * ex - sa * ey, center.y + sa * ex + ca * ey});
  }
  const sim::Color ink = theme_.Ink(color), fill = theme_.Fill(color);
  cv_.FillPolygon(pts, kN, fill.WithAlpha(fill.a * 0.15f));
  cv_.Polyline(pts, kN, {ink, Width(1.2f)}, true);
}

void CanvasDrawSink::Cross(Vec2 p, double size, sim::Color color) {
  const double h = 0.5 * size;
  const Stroke st{theme_.Ink(color), Width(1.5f)};
  cv_.Line(view_.ToScreen({p.x - h, p.y - h}), view_.ToScreen({p.x + h, p.y + h}), st);
  cv_.Line(view_.ToScreen({p.x - h, p.y + h}), view_.ToScreen({p.x + h, p.y - h}), st);
}

void CanvasDrawSink::Text(Vec2 p, const std::string& text, sim::Color color, float dx_px,
                          float dy_px) {
  Label(p, text, color, sim::LabelRole::kValue, dx_px, dy_px);
}

void CanvasDrawSink::Label(Vec2 p, const std::string& text, sim::Color color, sim::LabelRole role,
                           float dx_px, float dy_px) {
  const ImVec2 s = view_.ToScreen(p);
  // Far off screen: not even queued (a scene of thousands of robots names them all).
  ImVec2 clip_min, clip_max;
  cv_.Clip(clip_min, clip_max);
  constexpr float kReach = 80.0f;  // a label may move this far towards the view
  if (s.x < clip_min.x - kReach - 400 || s.x > clip_max.x + kReach || s.y < clip_min.y - kReach ||
      s.y > clip_max.y + kReach)
    return;
  queued_.push_back(
      {s, ImVec2(std::round(s.x + dx_px), std::round(s.y + dy_px)), text, color, role});
}

namespace {

bool Overlaps(const ImVec4& a, const ImVec4& b) {
  return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
}

// Boxes bucketed by 64-pixel cells of the view, so that a thousand robots and their labels cost
// a few tests per candidate spot, not a thousand.
class BoxGrid {
 public:
  BoxGrid(ImVec2 min, ImVec2 max) : min_(min) {
    nx_ = std::max(1, static_cast<int>((max.x - min.x) / kCell) + 1);
    ny_ = std::max(1, static_cast<int>((max.y - min.y) / kCell) + 1);
    cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  }
  void Add(const ImVec4& b) {
    boxes_.push_back(b);
    ForCells(b, [&](std::vector<int>& c) {
      c.push_back(static_cast<int>(boxes_.size()) - 1);
      return false;
    });
  }
  bool Hits(const ImVec4& b) const {
    return const_cast<BoxGrid*>(this)->ForCells(b, [&](std::vector<int>& c) {
      for (int i : c)
        if (Overlaps(b, boxes_[static_cast<std::size_t>(i)])) return true;
      return false;
    });
  }

 private:
  static constexpr float kCell = 64.0f;
  template <class F>
  bool ForCells(const ImVec4& b, F&& f) {
    const int x0 = std::clamp(static_cast<int>((b.x - min_.x) / kCell), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>((b.z - min_.x) / kCell), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>((b.y - min_.y) / kCell), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>((b.w - min_.y) / kCell), 0, ny_ - 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (f(cells_[static_cast<std::size_t>(y) * nx_ + x])) return true;
    return false;
  }
  ImVec2 min_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
  std::vector<ImVec4> boxes_;
};

}  // namespace

void CanvasDrawSink::FlushLabels() {
  std::stable_sort(queued_.begin(), queued_.end(),
                   [](const Queued& a, const Queued& b) { return a.role < b.role; });
  ImVec2 clip_min, clip_max;
  cv_.Clip(clip_min, clip_max);
  const float fs = cv_.FontSize(font_);
  BoxGrid taken(clip_min, clip_max);
  for (const ImVec4& o : keep_clear_)
    if (o.z >= clip_min.x && o.x <= clip_max.x && o.w >= clip_min.y && o.y <= clip_max.y)
      taken.Add(o);
  for (const Queued& q : queued_) {
    const ImVec2 ext = cv_.TextSize(font_, q.text);
    auto box_at = [&](ImVec2 pos) {
      return ImVec4(pos.x - 2, pos.y - 1, pos.x + ext.x + 2, pos.y + ext.y + 1);
    };
    auto free = [&](const ImVec4& b) {
      if (b.x < clip_min.x || b.z > clip_max.x || b.y < clip_min.y || b.w > clip_max.y)
        return false;
      return !taken.Hits(b);
    };
    // The scene's own spot, then spots around the anchor: above, below, right, left, the
    // corners, at one and two line heights.
    ImVec2 pos = q.pos;
    bool found = free(box_at(pos)), moved = false;
    for (int ring = 1; ring <= 2 && !found; ++ring) {
      const float d = fs * (0.6f + 1.1f * static_cast<float>(ring));
      const ImVec2 offsets[8] = {ImVec2(-ext.x / 2, -d - ext.y),
                                 ImVec2(-ext.x / 2, d),
                                 ImVec2(d, -ext.y / 2),
                                 ImVec2(-d - ext.x, -ext.y / 2),
                                 ImVec2(d, -d - ext.y),
                                 ImVec2(-d - ext.x, -d - ext.y),
                                 ImVec2(d, d),
                                 ImVec2(-d - ext.x, d)};
      for (const ImVec2& o : offsets) {
        const ImVec2 c(std::round(q.anchor.x + o.x), std::round(q.anchor.y + o.y));
        if (free(box_at(c))) {
          pos = c, found = true, moved = true;
          break;
        }
      }
    }
    if (!found) {
      ++dropped_;
      continue;
    }
    const ImVec4 box = box_at(pos);
    placed_.push_back(box);
    taken.Add(box);
    // Readable over whatever passes under the backdrop (a trail, a robot, a filled triangle):
    // a margin over 4.5:1 against the backdrop itself.
    const sim::Color ink = WithContrast(theme_.TextInk(q.color), theme_.backdrop, kLabelContrast);
    if (moved) {
      // A thin leader from the anchor to the nearest point of the label's box.
      const ImVec2 to(std::clamp(q.anchor.x, box.x, box.z), std::clamp(q.anchor.y, box.y, box.w));
      cv_.Line(q.anchor, to, {ink.WithAlpha(0.7f), 1.0f});
    }
    // A translucent backdrop keeps labels readable over grid lines and trails.
    cv_.FillRect(ImVec2(box.x, box.y), ImVec2(box.z, box.w), theme_.backdrop.WithAlpha(0.92f),
                 2.0f);
    cv_.Text(pos, font_, ink, q.text);
  }
  queued_.clear();
}

void CanvasDrawSink::ViewBox(Vec2& lo, Vec2& hi) const {
  // The part of the view rectangle the canvas can reach, in world coordinates (y up).
  ImVec2 a, b;
  cv_.Clip(a, b);
  const Vec2 p = view_.ToWorld(a), q = view_.ToWorld(b);
  lo = {std::min(p.x, q.x), std::min(p.y, q.y)};
  hi = {std::max(p.x, q.x), std::max(p.y, q.y)};
}

void CanvasDrawSink::Flash(Vec2 p, double radius, sim::Color color, float age) {
  age = std::clamp(age, 0.0f, 1.0f);
  const float r = static_cast<float>(radius * view_.scale) * (1.0f + 0.5f * age) + 4.0f;
  const sim::Color ink = theme_.Ink(color);
  cv_.StrokeCircle(view_.ToScreen(p), r, ink.WithAlpha(ink.a * (1.0f - age)), Width(3.0f));
}

}  // namespace formsim::app
