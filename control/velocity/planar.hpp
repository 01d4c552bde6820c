#pragma once
/// \file Planar (SE(2)) helpers for the velocity estimator: rotation matrices and the 90°
/// generator J, with R(θ)' = J R(θ). In 2-D rotations commute, so an additive angle
/// perturbation is exact and no manifold machinery is needed.

#include <Eigen/Dense>
#include <cmath>

namespace formsim::control::velocity {

using Vec2d = Eigen::Vector2d;
using Mat2d = Eigen::Matrix2d;

/// Rotation by theta (body to world when theta is the body heading).
inline Mat2d Rot(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Mat2d r;
  r << c, -s, s, c;
  return r;
}

/// The generator of planar rotations: J = [0 -1; 1 0], d/dθ R(θ) = J R(θ) = R(θ) J.
inline Mat2d J90() {
  Mat2d j;
  j << 0.0, -1.0, 1.0, 0.0;
  return j;
}

}  // namespace formsim::control::velocity
