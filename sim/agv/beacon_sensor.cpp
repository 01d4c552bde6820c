#include "sim/agv/beacon_sensor.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::sim::agv {

BeaconFix BeaconSensor::Sample(double t, const Pose2& truth) {
  // Fixed draw order per sample: 3 normals, dropout, outlier, direction, size, heading.
  const double nx = rng_.Normal(), ny = rng_.Normal(), nt = rng_.Normal();
  const double u_drop = rng_.Uniform(), u_out = rng_.Uniform();
  const double u_dir = rng_.Uniform(), u_size = rng_.Uniform(), u_head = rng_.Uniform();
  // Next sample on the period grid after t (robust to a period changed live).
  const double period = std::max(def_.period, 1e-3);
  next_time_ = std::max(next_time_ + period, t + 0.5 * period);

  BeaconFix fix;
  fix.t = t;
  fix.valid = u_drop >= def_.dropout_probability;
  fix.outlier = u_out < def_.outlier_probability;
  fix.pose = {truth.x + def_.sigma_xy * nx, truth.y + def_.sigma_xy * ny,
              truth.theta + def_.sigma_theta * nt};
  if (fix.outlier) {
    const double a = 2.0 * control::kPi * u_dir, r = def_.outlier_size * (0.5 + u_size);
    fix.pose.x += r * std::cos(a);
    fix.pose.y += r * std::sin(a);
    fix.pose.theta += def_.outlier_heading * (2.0 * u_head - 1.0);
  }
  fix.pose.theta = control::WrapToPi(fix.pose.theta);
  return fix;
}

}  // namespace formsim::sim::agv
