#include "sim/inspection/wheel_odometry.hpp"

#include <cmath>

#include "sim/core/multirate.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::inspection {

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
  const std::string g = "Noise/odometry";
  WheelOdometryDef def;
  def.sigma_per_sqrt_m = o.Real("sigma_per_sqrt_m", def.sigma_per_sqrt_m,
                                Tune("encoder noise", "m/√m").AtLeast(0).AtMost(1).Slider(0.0, 0.05).Group(g));
  def.scale_error_left = o.Real("scale_error_left", def.scale_error_left,
                                Tune("left scale error").Above(-0.5).Below(0.5).Slider(-0.1, 0.1).Group(g));
  def.scale_error_right = o.Real("scale_error_right", def.scale_error_right,
                                 Tune("right scale error").Above(-0.5).Below(0.5).Slider(-0.1, 0.1).Group(g));
  def.track = o.Double("track", def.track, Tune().In(1e-3, 1e3));
  o.Finish();
  return def;
}

}  // namespace formsim::sim::inspection
