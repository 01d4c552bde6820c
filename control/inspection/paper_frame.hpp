#pragma once
/// \file The paper's angle convention (Li et al. 2013, eq. 1) and conversions at the boundary.
///
/// Inside the inspection robot's estimator and controller every heading and azimuth follows the
/// paper: measured from the world +Y axis towards +X (clockwise seen from above with X right and
/// Y up), so that dead reckoning reads x += ΔS sin θ, y += ΔS cos θ. Body-frame bearings (laser
/// scan angles) are measured the same way, clockwise from the robot's forward axis, so that
/// world azimuth = heading + bearing. The rest of formsim (Box2D, Pose2, drawing) uses the
/// mathematical convention (from +X, counter-clockwise); convert only with the functions below.

#include <cmath>

#include "control/common/angle.hpp"
#include "control/common/geometry.hpp"

namespace formsim::control::inspection {

/// Azimuth of a world vector in the paper convention (from +Y towards +X), in (-pi, pi].
inline double Azimuth(const Vec2& d) {
  return std::atan2(d.x, d.y);
}

/// Unit vector pointing along a paper-convention azimuth.
inline Vec2 AzimuthDirection(double azimuth) {
  return {std::sin(azimuth), std::cos(azimuth)};
}

/// Paper heading (from +Y, clockwise) from a mathematical heading (from +X, counter-clockwise).
/// The map is its own inverse: θ_paper = π/2 − θ_math.
inline double PaperFromMath(double theta_math) {
  return WrapToPi(kPi / 2.0 - theta_math);
}

/// Mathematical heading (from +X, counter-clockwise) from a paper heading.
inline double MathFromPaper(double theta_paper) {
  return WrapToPi(kPi / 2.0 - theta_paper);
}

/// Degrees to radians and back (the FLL rule base and the YAML speak degrees).
inline double Deg(double rad) {
  return rad * 180.0 / kPi;
}
inline double Rad(double deg) {
  return deg * kPi / 180.0;
}

}  // namespace formsim::control::inspection
