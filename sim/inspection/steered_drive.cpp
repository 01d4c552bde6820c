#include "sim/inspection/steered_drive.hpp"

#include <algorithm>
#include <cmath>

#include "control/inspection/paper_frame.hpp"
#include "sim/core/multirate.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim::inspection {
namespace {

using control::inspection::Rad;

double Cross(const Vec2& a, const Vec2& b) {
  return a.x * b.y - a.y * b.x;
}
Vec2 Rotate(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

}  // namespace

void SteeredDrive::SetCommand(double u1, double u2, double u3) {
  u1_ = std::isfinite(u1) ? std::clamp(u1, 0.0, kLevelMax) : 0.0;
  u2_ = std::isfinite(u2) ? std::clamp(u2, 0.0, kLevelMax) : 0.0;
  u3_ = std::isfinite(u3) ? std::clamp(u3, kServoMin, kServoMax) : def_.servo_center;
}

double SteeredDrive::steer_target() const {
  const double lim = Rad(def_.steer_max_deg);
  return std::clamp(Rad(def_.steer_per_unit_deg) * (u3_ - def_.servo_center), -lim, lim);
}

void SteeredDrive::Apply(Robot& robot, World& world, double dt) {
  b2Body* body = robot.body();
  // Servo: slew towards the commanded angle.
  const double max_step = Rad(def_.steer_rate_deg_s) * dt;
  steer_ += std::clamp(steer_target() - steer_, -max_step, max_step);

  const double m = robot.mass(), inertia = robot.inertia();
  const double angle = body->GetAngle();
  const Vec2 centre{body->GetPosition().x, body->GetPosition().y};
  Vec2 v{body->GetLinearVelocity().x, body->GetLinearVelocity().y};
  double w = body->GetAngularVelocity();

  // Wheels in the body frame (x forward, y left). The paper's right steer is clockwise, i.e. a
  // negative mathematical angle.
  struct Wheel {
    Vec2 r;       // world offset from the centre
    Vec2 d, n;    // rolling and lateral directions (world)
    double load;  // N
    double mu;
    double lon = 0.0, lat = 0.0;  // accumulated impulses
    bool drive;
    double target = 0.0;
  };
  const double weight = m * kGravity;
  const double half = 0.5 * def_.track;
  const double front = std::clamp(def_.front_load, 0.05, 0.95);
  std::array<Wheel, 3> wheels;
  const Vec2 body_pos[3] = {
      {def_.rear_axle, half}, {def_.rear_axle, -half}, {def_.rear_axle + def_.wheelbase, 0.0}};
  const double wheel_angle[3] = {0.0, 0.0, -steer_};
  const double loads[3] = {0.5 * (1.0 - front) * weight, 0.5 * (1.0 - front) * weight,
                           front * weight};
  for (int i = 0; i < 3; ++i) {
    Wheel& wh = wheels[i];
    wh.r = Rotate(body_pos[i], angle);
    wh.d = Rotate({1.0, 0.0}, angle + wheel_angle[i]);
    wh.n = Rotate({0.0, 1.0}, angle + wheel_angle[i]);
    wh.load = loads[i];
    wh.mu = world.FrictionAt(centre + wh.r);
    wh.drive = i < 2;
  }
  wheels[0].target = def_.speed_per_level * u1_;
  wheels[1].target = def_.speed_per_level * u2_;

  auto contact_velocity = [&](const Wheel& wh) { return v + Vec2{-w * wh.r.y, w * wh.r.x}; };
  auto effective_mass = [&](const Wheel& wh, const Vec2& dir) {
    const double rn = Cross(wh.r, dir);
    return 1.0 / (1.0 / m + rn * rn / inertia);
  };
  auto apply = [&](const Wheel& wh, const Vec2& impulse) {
    v = v + impulse * (1.0 / m);
    w += Cross(wh.r, impulse) / inertia;
  };

  // Rear motors: proportional speed loops, an explicit force for this step.
  motor_limited_ = false;
  slipping_ = false;
  for (int i = 0; i < 2; ++i) {
    Wheel& wh = wheels[i];
    const double tau = std::max(def_.motor_time_constant, dt);
    double force = 0.5 * m * (wh.target - contact_velocity(wh).Dot(wh.d)) / tau;
    if (std::abs(force) > def_.motor_force_max) {
      force = std::copysign(def_.motor_force_max, force);
      motor_limited_ = true;
    }
    wh.lon = force * dt;
    const double limit = wh.mu * wh.load * dt;
    if (std::abs(wh.lon) > limit) {
      wh.lon = std::copysign(limit, wh.lon);
      slipping_ = true;
    }
    apply(wh, wh.d * wh.lon);
  }
  // Sequential impulses: no sideways sliding at any wheel, free rolling with resistance at the
  // front, each wheel inside its friction circle (traction first, the rest for cornering).
  for (int iter = 0; iter < 10; ++iter) {
    for (Wheel& wh : wheels) {
      const double limit = wh.mu * wh.load * dt;
      if (!wh.drive) {
        const double vl = contact_velocity(wh).Dot(wh.d);
        const double rr = def_.rolling_resistance * wh.load * dt;
        const double lon = std::clamp(wh.lon - effective_mass(wh, wh.d) * vl, -rr, rr);
        apply(wh, wh.d * (lon - wh.lon));
        wh.lon = lon;
      }
      const double lat_limit = std::sqrt(std::max(0.0, limit * limit - wh.lon * wh.lon));
      const double vn = contact_velocity(wh).Dot(wh.n);
      double lat = wh.lat - effective_mass(wh, wh.n) * vn;
      if (std::abs(lat) > lat_limit) lat = std::copysign(lat_limit, lat);
      apply(wh, wh.n * (lat - wh.lat));
      wh.lat = lat;
    }
  }
  Vec2 force{0.0, 0.0};
  double torque = 0.0;
  for (const Wheel& wh : wheels) {
    const Vec2 impulse = wh.d * wh.lon + wh.n * wh.lat;
    force = force + impulse * (1.0 / dt);
    torque += Cross(wh.r, impulse) / dt;
    const double limit = wh.mu * wh.load * dt;
    if (std::hypot(wh.lon, wh.lat) >= limit * (1.0 - 1e-9) && limit > 0.0) {
      // Sideways sliding only counts when something is actually sliding.
      if (std::abs(contact_velocity(wh).Dot(wh.n)) > 1e-3 || wh.drive) slipping_ = true;
    }
  }
  body->ApplyForceToCenter(b2Vec2(static_cast<float>(force.x), static_cast<float>(force.y)), true);
  body->ApplyTorque(static_cast<float>(torque), true);

  // Encoders: a gripping wheel rolls with the ground, a spinning one at its motor speed.
  for (int i = 0; i < 2; ++i) {
    const Wheel& wh = wheels[i];
    const bool spinning = std::abs(wh.lon) >= wh.mu * wh.load * dt * (1.0 - 1e-9);
    const double rim = spinning ? wh.target : contact_velocity(wh).Dot(wh.d);
    wheel_dist_[i] += rim * dt;
  }
}

SteeredDriveDef ReadSteeredDrive(YamlReader& d) {
  const std::string g = "Gains/vehicle scales";
  SteeredDriveDef def = DefaultSteeredDriveDef();
  def.speed_per_level = d.Real("speed_per_level", def.speed_per_level,
                               Tune("speed per level", "m/s").Above(0).AtMost(10).Slider(0.02, 0.4).Group(g));
  def.steer_per_unit_deg =
      d.Real("steer_per_unit_deg", def.steer_per_unit_deg,
             Tune("steer per servo unit", "deg").AtLeast(1e-4).AtMost(10).Slider(0.05, 0.5).Group(g));
  def.servo_center = d.Real("servo_center", def.servo_center,
                            Tune("servo centre").In(SteeredDrive::kServoMin, SteeredDrive::kServoMax)
                                .Slider(300.0, 420.0).Group(g));
  def.steer_rate_deg_s = d.Real("steer_rate_deg_s", def.steer_rate_deg_s,
                                Tune("servo slew rate", "deg/s").Above(0).AtMost(1e4).Slider(10.0, 360.0).Group(g));
  def.motor_force_max = d.Real("motor_force_max", def.motor_force_max,
                               Tune("motor force limit", "N").Above(0).AtMost(1e5).Slider(5.0, 200.0).Group(g));
  // Geometry and dynamics: fixed for a run.
  const Tune length = Tune().In(1e-3, 1e3);
  def.steer_max_deg = d.Double("steer_max_deg", def.steer_max_deg, Tune().Above(0).Below(80));
  def.wheelbase = d.Double("wheelbase", def.wheelbase, length);
  def.track = d.Double("track", def.track, length);
  def.rear_axle = d.Double("rear_axle", -0.5 * def.wheelbase, Tune().In(-1e3, 1e3));
  def.motor_time_constant =
      d.Double("motor_time_constant", def.motor_time_constant, Tune().Above(0).AtMost(1e3));
  def.rolling_resistance =
      d.Double("rolling_resistance", def.rolling_resistance, Tune().AtLeast(0).AtMost(10));
  def.front_load = d.Double("front_load", def.front_load, Tune().Above(0).Below(1));
  d.Finish();
  return def;
}

}  // namespace formsim::sim::inspection
