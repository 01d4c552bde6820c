#include "sim/agv/beacon_sensor.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

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

BeaconDef ReadBeacon(YamlReader& b) {
  BeaconDef def;
  def.period = b.Double("period", def.period);
  if (!(def.period >= 0.005)) b.Fail("period", "must be at least 0.005 s");
  def.sigma_xy = b.Double("sigma_xy", def.sigma_xy);
  if (def.sigma_xy < 0) b.Fail("sigma_xy", "must be >= 0");
  def.sigma_theta = b.Double("sigma_theta", def.sigma_theta);
  if (def.sigma_theta < 0) b.Fail("sigma_theta", "must be >= 0");
  def.outlier_probability = b.Double("outlier_probability", def.outlier_probability);
  if (def.outlier_probability < 0 || def.outlier_probability > 1)
    b.Fail("outlier_probability", "must be in [0, 1]");
  def.outlier_size = b.Double("outlier_size", def.outlier_size);
  if (def.outlier_size < 0) b.Fail("outlier_size", "must be >= 0");
  def.outlier_heading = b.Double("outlier_heading", def.outlier_heading);
  if (def.outlier_heading < 0) b.Fail("outlier_heading", "must be >= 0");
  def.dropout_probability = b.Double("dropout_probability", def.dropout_probability);
  if (def.dropout_probability < 0 || def.dropout_probability > 1)
    b.Fail("dropout_probability", "must be in [0, 1]");
  b.Finish();
  return def;
}

}  // namespace formsim::sim
