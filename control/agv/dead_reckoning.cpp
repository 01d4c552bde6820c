#include "control/agv/dead_reckoning.hpp"

#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::control::agv {

WorldVelocity ToWorld(const BodyTwist& t, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * t.vx - s * t.vy, s * t.vx + c * t.vy, t.omega};
}

Pose2 IntegrateTwist(const Pose2& pose, const BodyTwist& twist, double dt) {
  const WorldVelocity v = ToWorld(twist, pose.theta + 0.5 * twist.omega * dt);
  return {pose.x + v.x_dot * dt, pose.y + v.y_dot * dt, WrapToPi(pose.theta + v.theta_dot * dt)};
}

}  // namespace formsim::control::agv
