#include "app/imgui_draw_sink.hpp"

#include <algorithm>
#include <cmath>

#include "app/polyline_simplify.hpp"

namespace formsim::app {
namespace {

double SignedArea(const std::vector<ImVec2>& p) {
  double a = 0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    a += static_cast<double>(p[j].x) * p[i].y - static_cast<double>(p[i].x) * p[j].y;
  return 0.5 * a;
}

bool IsConvex(const std::vector<ImVec2>& p) {
  int sign = 0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ImVec2 &a = p[i], &b = p[(i + 1) % n], &c = p[(i + 2) % n];
    const double cross =
        static_cast<double>(b.x - a.x) * (c.y - b.y) - static_cast<double>(b.y - a.y) * (c.x - b.x);
    if (std::abs(cross) < 1e-9) continue;
    const int s = cross > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

bool PointInTriangle(ImVec2 p, ImVec2 a, ImVec2 b, ImVec2 c) {
  auto side = [](ImVec2 p1, ImVec2 p2, ImVec2 p3) {
    return (p1.x - p3.x) * (p2.y - p3.y) - (p2.x - p3.x) * (p1.y - p3.y);
  };
  const float d1 = side(p, a, b), d2 = side(p, b, c), d3 = side(p, c, a);
  const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
  return !(neg && pos);
}

}  // namespace

// Concave polygons (floor patches may be any simple polygon) are ear-clipped into triangles;
// convex ones go to ImGui's anti-aliased convex fill.
void ImDrawSink::FillSimplePolygon(const std::vector<ImVec2>& pts, ImU32 col) {
  if (pts.size() < 3) return;
  if (IsConvex(pts)) {
    dl_->AddConvexPolyFilled(pts.data(), static_cast<int>(pts.size()), col);
    return;
  }
  std::vector<ImVec2> p = pts;
  if (SignedArea(p) < 0) std::reverse(p.begin(), p.end());  // counter-clockwise in y-up terms
  std::vector<int> idx(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) idx[i] = static_cast<int>(i);
  int guard = 0;
  while (idx.size() > 3 && guard++ < 10000) {
    bool clipped = false;
    for (std::size_t i = 0; i < idx.size(); ++i) {
      const ImVec2 a = p[idx[(i + idx.size() - 1) % idx.size()]], b = p[idx[i]],
                   c = p[idx[(i + 1) % idx.size()]];
      const float cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (cross <= 0) continue;  // reflex vertex
      bool ear = true;
      for (int k : idx) {
        const ImVec2 q = p[k];
        if ((q.x == a.x && q.y == a.y) || (q.x == b.x && q.y == b.y) || (q.x == c.x && q.y == c.y))
          continue;
        if (PointInTriangle(q, a, b, c)) {
          ear = false;
          break;
        }
      }
      if (!ear) continue;
      dl_->AddTriangleFilled(a, b, c, col);
      idx.erase(idx.begin() + static_cast<long>(i));
      clipped = true;
      break;
    }
    if (!clipped) break;  // degenerate input: draw what is left as a fan
  }
  for (std::size_t i = 1; i + 1 < idx.size(); ++i)
    dl_->AddTriangleFilled(p[idx[0]], p[idx[i]], p[idx[i + 1]], col);
}

void ImDrawSink::Polygon(const std::vector<Vec2>& pts, sim::Color fill, sim::Color outline) {
  if (pts.size() < 2) return;
  std::vector<ImVec2> s;
  s.reserve(pts.size());
  for (const Vec2& p : pts) s.push_back(view_.ToScreen(p));
  if (fill.a > 0) FillSimplePolygon(s, ToImColor(fill));
  if (outline.a > 0)
    dl_->AddPolyline(s.data(), static_cast<int>(s.size()), ToImColor(outline), ImDrawFlags_Closed,
                     1.5f * line_scale_);
}

void ImDrawSink::Circle(Vec2 center, double radius, sim::Color fill, sim::Color outline) {
  const ImVec2 c = view_.ToScreen(center);
  const float r = static_cast<float>(radius * view_.scale);
  if (r < 0.5f) return;
  const int segments = std::clamp(static_cast<int>(r * 0.8f), 12, 64);
  if (fill.a > 0) dl_->AddCircleFilled(c, r, ToImColor(fill), segments);
  if (outline.a > 0) dl_->AddCircle(c, r, ToImColor(outline), segments, 1.5f * line_scale_);
}

void ImDrawSink::Segment(Vec2 a, Vec2 b, sim::Color color, float thickness_px) {
  dl_->AddLine(view_.ToScreen(a), view_.ToScreen(b), ToImColor(color), thickness_px * line_scale_);
}

void ImDrawSink::Polyline(const std::vector<Vec2>& pts, sim::Color color, float thickness_px,
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
  const float th = thickness_px * line_scale_;
  if (!fade) {
    dl_->AddPolyline(s.data(), static_cast<int>(s.size()), ToImColor(color), ImDrawFlags_None, th);
    return;
  }
  // Fading trail: a few chunks of increasing opacity, each one polyline (joins stay smooth).
  const int chunks = std::min<int>(12, static_cast<int>(s.size()) - 1);
  for (int k = 0; k < chunks; ++k) {
    const std::size_t i0 = s.size() * k / chunks,
                      i1 = std::min(s.size() - 1, s.size() * (k + 1) / chunks);
    if (i1 <= i0) continue;
    const float alpha = color.a * (0.08f + 0.92f * static_cast<float>(k + 1) / chunks);
    dl_->AddPolyline(&s[i0], static_cast<int>(i1 - i0 + 1), ToImColor(color.WithAlpha(alpha)),
                     ImDrawFlags_None, th);
  }
}

void ImDrawSink::CovarianceEllipse(Vec2 center, double sxx, double sxy, double syy, double n_sigma,
                                   sim::Color color) {
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
  dl_->AddConvexPolyFilled(pts, kN, ToImColor(color.WithAlpha(color.a * 0.15f)));
  dl_->AddPolyline(pts, kN, ToImColor(color), ImDrawFlags_Closed, 1.2f * line_scale_);
}

void ImDrawSink::Cross(Vec2 p, double size, sim::Color color) {
  const double h = 0.5 * size;
  const ImU32 c = ToImColor(color);
  dl_->AddLine(view_.ToScreen({p.x - h, p.y - h}), view_.ToScreen({p.x + h, p.y + h}), c,
               1.5f * line_scale_);
  dl_->AddLine(view_.ToScreen({p.x - h, p.y + h}), view_.ToScreen({p.x + h, p.y - h}), c,
               1.5f * line_scale_);
}

void ImDrawSink::Text(Vec2 p, const std::string& text, sim::Color color, float dx_px, float dy_px) {
  const ImVec2 s = view_.ToScreen(p);
  const ImVec2 pos(std::round(s.x + dx_px), std::round(s.y + dy_px));
  const float size = font_->FontSize;
  const ImVec2 ext = font_->CalcTextSizeA(size, 1e9f, 0.0f, text.c_str());
  const ImVec4 box(pos.x - 2, pos.y - 1, pos.x + ext.x + 2, pos.y + ext.y + 1);
  // Off screen: neither drawn nor kept for the overlap test (which then stays short).
  const ImVec2 clip_min = dl_->GetClipRectMin(), clip_max = dl_->GetClipRectMax();
  if (box.z < clip_min.x || box.x > clip_max.x || box.w < clip_min.y || box.y > clip_max.y) return;
  for (const ImVec4& o : labels_)
    if (box.x < o.z && o.x < box.z && box.y < o.w && o.y < box.w) return;
  labels_.push_back(box);
  // A translucent backdrop keeps labels readable over grid lines and trails.
  dl_->AddRectFilled(ImVec2(pos.x - 2, pos.y - 1), ImVec2(pos.x + ext.x + 2, pos.y + ext.y + 1),
                     IM_COL32(255, 255, 255, 170), 2.0f);
  dl_->AddText(font_, size, pos, ToImColor(color), text.c_str());
}

void ImDrawSink::ViewBox(Vec2& lo, Vec2& hi) const {
  // The part of the view rectangle the draw list can reach, in world coordinates (y up).
  const ImVec2 a = dl_->GetClipRectMin(), b = dl_->GetClipRectMax();
  const Vec2 p = view_.ToWorld(a), q = view_.ToWorld(b);
  lo = {std::min(p.x, q.x), std::min(p.y, q.y)};
  hi = {std::max(p.x, q.x), std::max(p.y, q.y)};
}

void ImDrawSink::Flash(Vec2 p, double radius, sim::Color color, float age) {
  age = std::clamp(age, 0.0f, 1.0f);
  const float r = static_cast<float>(radius * view_.scale) * (1.0f + 0.5f * age) + 4.0f;
  // num_segments 0: ImGui picks enough segments for a smooth ring at any radius.
  dl_->AddCircle(view_.ToScreen(p), r, ToImColor(color.WithAlpha(color.a * (1.0f - age))), 0,
                 3.0f * line_scale_);
}

}  // namespace formsim::app
