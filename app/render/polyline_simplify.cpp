#include "app/render/polyline_simplify.hpp"

#include <cmath>

namespace formsim::app {

std::vector<ImVec2> SimplifyPolyline(const std::vector<ImVec2>& pts, float tol) {
  if (pts.size() < 3) return pts;
  std::vector<ImVec2> out;
  out.reserve(pts.size() / 4 + 2);
  out.push_back(pts[0]);
  std::size_t key = 0;  // last kept point
  std::size_t i = 1;
  while (i < pts.size()) {
    // Direction from the key point to the first point far enough away to define a line.
    while (i < pts.size() &&
           std::abs(pts[i].x - pts[key].x) + std::abs(pts[i].y - pts[key].y) < tol)
      ++i;
    if (i >= pts.size()) break;
    const float dx = pts[i].x - pts[key].x, dy = pts[i].y - pts[key].y;
    const float inv = 1.0f / std::sqrt(dx * dx + dy * dy);
    std::size_t j = i + 1;
    float along_prev = 1.0f / inv;
    for (; j < pts.size(); ++j) {
      const float ex = pts[j].x - pts[key].x, ey = pts[j].y - pts[key].y;
      const float dist = std::abs(ex * dy - ey * dx) * inv;  // distance from the line
      const float along = (ex * dx + ey * dy) * inv;
      if (dist > tol || along < along_prev - tol) break;  // left the strip, or turned back
      along_prev = along;
    }
    key = j - 1;  // last point still on the line
    out.push_back(pts[key]);
    i = key + 1;
  }
  if (out.back().x != pts.back().x || out.back().y != pts.back().y) out.push_back(pts.back());
  return out;
}

}  // namespace formsim::app
