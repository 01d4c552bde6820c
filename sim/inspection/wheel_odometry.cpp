#include "sim/inspection/wheel_odometry.hpp"

#include <cmath>

#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

control::inspection::OdometryIncrement WheelOdometry::Read(double left_distance,
                                                           double right_distance) {
  const double dl = latched_ ? left_distance - last_left_ : 0.0;
  const double dr = latched_ ? right_distance - last_right_ : 0.0;
  latched_ = true;
  last_left_ = left_distance;
  last_right_ = right_distance;
  const double nl = rng_.Normal(0.0, def_.sigma_per_sqrt_m * std::sqrt(std::abs(dl)));
  const double nr = rng_.Normal(0.0, def_.sigma_per_sqrt_m * std::sqrt(std::abs(dr)));
  return control::inspection::DifferentialOdometry(dl * (1.0 + def_.scale_error_left) + nl,
                                                   dr * (1.0 + def_.scale_error_right) + nr,
                                                   def_.track);
}

WheelOdometryDef ReadWheelOdometry(YamlReader& o) {
  WheelOdometryDef def;
  def.sigma_per_sqrt_m = o.Double("sigma_per_sqrt_m", def.sigma_per_sqrt_m);
  def.scale_error_left = o.Double("scale_error_left", def.scale_error_left);
  def.scale_error_right = o.Double("scale_error_right", def.scale_error_right);
  def.track = o.Double("track", def.track);
  if (def.sigma_per_sqrt_m < 0) o.Fail("sigma_per_sqrt_m", "must be >= 0");
  if (std::abs(def.scale_error_left) >= 0.5) o.Fail("scale_error_left", "must be in (-0.5, 0.5)");
  if (std::abs(def.scale_error_right) >= 0.5) o.Fail("scale_error_right", "must be in (-0.5, 0.5)");
  if (def.track <= 0) o.Fail("track", "must be positive");
  o.Finish();
  return def;
}

}  // namespace formsim::sim
