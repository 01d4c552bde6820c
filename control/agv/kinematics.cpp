#include "control/agv/kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace formsim::control::agv {

double MecanumGeometry::RollerSign(int wheel) {
  return (wheel == kFrontLeft || wheel == kRearRight) ? -1.0 : 1.0;
}

Vec2 MecanumGeometry::WheelPosition(int wheel) const {
  const double x = (wheel == kFrontLeft || wheel == kFrontRight) ? half_wheelbase : -half_wheelbase;
  const double y = (wheel == kFrontLeft || wheel == kRearLeft) ? half_track : -half_track;
  return {x, y};
}

Vec2 MecanumGeometry::RollerAxis(int wheel) {
  const double k = 1.0 / std::sqrt(2.0);
  return {k, k * RollerSign(wheel)};
}

WheelArray InverseKinematics(const MecanumGeometry& g, const BodyTwist& t) {
  // r ω_i = v_cx + s_i v_cy with the contact velocity v_c = v + ω × p_i.
  WheelArray w{};
  for (int i = 0; i < kMecanumWheels; ++i) {
    const Vec2 p = g.WheelPosition(i);
    const double vcx = t.vx - t.omega * p.y;
    const double vcy = t.vy + t.omega * p.x;
    w[i] = (vcx + MecanumGeometry::RollerSign(i) * vcy) / g.wheel_radius;
  }
  return w;
}

BodyTwist ForwardKinematics(const MecanumGeometry& g, const WheelArray& w) {
  const double r = g.wheel_radius;
  const double L = g.half_wheelbase + g.half_track;
  BodyTwist t;
  t.vx = r / 4.0 * (w[kFrontLeft] + w[kFrontRight] + w[kRearLeft] + w[kRearRight]);
  t.vy = r / 4.0 * (-w[kFrontLeft] + w[kFrontRight] + w[kRearLeft] - w[kRearRight]);
  t.omega = r / (4.0 * L) * (-w[kFrontLeft] + w[kFrontRight] - w[kRearLeft] + w[kRearRight]);
  return t;
}

double ScaleToLimit(WheelArray& w, double limit) {
  double peak = 0.0;
  for (double v : w) peak = std::max(peak, std::abs(v));
  if (!(limit > 0.0) || peak <= limit) return 1.0;
  const double k = limit / peak;
  for (double& v : w) v *= k;
  return k;
}

}  // namespace formsim::control::agv
