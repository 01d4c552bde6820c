#include "control/velocity/triangulation.hpp"

#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::velocity {

TriangulationResult Triangulate(const std::vector<BearingRay>& rays, double min_parallax,
                                double min_depth, double max_range) {
  TriangulationResult res;
  if (rays.size() < 2) {
    res.reason = "fewer than two rays";
    return res;
  }
  for (std::size_t a = 0; a < rays.size(); ++a)
    for (std::size_t b = a + 1; b < rays.size(); ++b)
      res.parallax = std::max(res.parallax, std::abs(AngleDiff(rays[a].angle, rays[b].angle)));
  if (res.parallax < min_parallax) {
    res.reason = "parallax too small";
    return res;
  }
  // Normal equations of Σ (nᵀ (f - c))², n the unit normal of each ray.
  Mat2d A = Mat2d::Zero();
  Vec2d b = Vec2d::Zero();
  for (const BearingRay& r : rays) {
    const Vec2d n(-std::sin(r.angle), std::cos(r.angle));
    A += n * n.transpose();
    b += n * n.dot(r.origin);
  }
  Eigen::LDLT<Mat2d> ldlt(A);
  if (ldlt.info() != Eigen::Success || A.determinant() < 1e-12) {
    res.reason = "degenerate rays";
    return res;
  }
  res.point = ldlt.solve(b);
  for (const BearingRay& r : rays) {
    const Vec2d d(std::cos(r.angle), std::sin(r.angle));
    if ((res.point - r.origin).dot(d) < min_depth) {
      res.reason = "point behind a camera";
      return res;
    }
  }
  if ((res.point - rays.back().origin).norm() > max_range) {
    res.reason = "point out of range";
    return res;
  }
  res.ok = res.point.allFinite();
  if (!res.ok) res.reason = "non-finite point";
  return res;
}

}  // namespace formsim::control::velocity
