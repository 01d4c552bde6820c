#include "sim/core/unicycle_drive.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

void UnicycleDrive::Apply(Robot& robot, World& world, double dt) {
  b2Body* body = robot.body();
  const control::SinCos sc = control::SinCosOf(body->GetAngle());
  const double c = sc.c, s = sc.s;
  // Forward and lateral speeds as Robot::forward_speed and lateral_speed compute them, from the
  // sine and cosine already at hand.
  const Vec2 vel = robot.world_velocity();
  const double u = c * vel.x + s * vel.y;
  // Motor acceleration limit on the forward speed.
  double v_target = v_cmd_;
  if (std::isfinite(def_.accel_max)) {
    const double dv_max = def_.accel_max * dt;
    v_target = std::clamp(v_cmd_, u - dv_max, u + dv_max);
  }

  if (def_.mode == UnicycleDriveDef::Mode::kIdeal) {
    slipping_ = false;
    body->SetLinearVelocity(b2Vec2(static_cast<float>(v_target * c), static_cast<float>(v_target * s)));
    body->SetAngularVelocity(static_cast<float>(w_cmd_));
    return;
  }

  // Traction: the forces that would reach the command in one step, shared by two wheels at
  // ±track_half_width, each wheel's force limited by μ·N (N = m g / 2): friction circle.
  const double lat = -s * vel.x + c * vel.y, r = robot.yaw_rate();
  const double m = robot.mass(), inertia = robot.inertia(), b = def_.track_half_width;
  const double mu = world.FrictionAt(robot.pose().p());
  const double fx = m * (v_target - u) / dt;   // longitudinal, body frame
  const double fy = m * (0.0 - lat) / dt;      // lateral no-slip
  const double tau = inertia * (w_cmd_ - r) / dt;
  const double wheel_limit = mu * m * kGravity / 2.0;
  double left_long = fx / 2 - tau / (2 * b), right_long = fx / 2 + tau / (2 * b);
  double left_lat = fy / 2, right_lat = fy / 2;
  slipping_ = false;
  for (auto [lon, la] : {std::pair<double*, double*>{&left_long, &left_lat}, {&right_long, &right_lat}}) {
    const double mag = std::hypot(*lon, *la);
    if (mag > wheel_limit) {
      const double k = wheel_limit / mag;
      *lon *= k;
      *la *= k;
      slipping_ = true;
    }
  }
  const double fx_out = left_long + right_long, fy_out = left_lat + right_lat;
  const double tau_out = (right_long - left_long) * b;
  body->ApplyForceToCenter(b2Vec2(static_cast<float>(c * fx_out - s * fy_out),
                                  static_cast<float>(s * fx_out + c * fy_out)),
                           true);
  body->ApplyTorque(static_cast<float>(tau_out), true);
}

UnicycleDriveDef ReadUnicycleDrive(YamlReader& d, const std::string& group) {
  UnicycleDriveDef def = DefaultUnicycleDriveDef();
  def.mode = static_cast<UnicycleDriveDef::Mode>(
      d.Pick("mode", {"ideal", "traction"}, 0, Tune("mode").Group(group)));
  def.v_max = d.Real("v_max", def.v_max, Tune("v max", "m/s").Above(0).AtMost(100).Slider(0.1, 10.0).Group(group));
  def.omega_max =
      d.Real("omega_max", def.omega_max, Tune("ω max", "rad/s").Above(0).AtMost(1000).Slider(0.1, 20.0).Group(group));
  def.accel_max = d.Double("accel_max", def.accel_max);
  def.track_half_width = d.Double("track_half_width", def.track_half_width);
  if (def.accel_max <= 0) d.Fail("accel_max", "must be positive");
  if (def.track_half_width <= 0) d.Fail("track_half_width", "must be positive");
  d.Finish();
  return def;
}

}  // namespace formsim::sim
