#include "sim/velocity/diff_drive.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace formsim::sim::velocity {

namespace {

/// Everything the sub-step dynamics need that stays fixed during one world step.
struct StepInputs {
  double m, I, r, half, J, caster_x;
  double volts[2];
  double load, force_max[2], shear[2], rolling[2];
  double caster_fx, caster_fy;
  const DcMotorDef* motor;
  double slip_floor;
};

/// Outputs of one evaluation of the dynamics.
struct Forces {
  double traction[2], rolling[2], current[2], slip[2];
};

double SlipRatio(double wheel_rim_speed, double contact_speed, double floor) {
  const double den = std::max({std::abs(wheel_rim_speed), std::abs(contact_speed), floor});
  return (wheel_rim_speed - contact_speed) / den;
}

/// ds/dt for s = [v_x, ω_body, ω_left, ω_right].
Eigen::Vector4d Dynamics(const Eigen::Vector4d& s, const StepInputs& in, Forces* out) {
  Eigen::Vector4d ds;
  double net[2];
  for (int side = 0; side < 2; ++side) {
    const double y = side == DiffDrive::kLeft ? in.half : -in.half;
    const double vc = s(0) - s(1) * y;  // contact point speed along the heading
    const double w = s(2 + side);
    const double kappa = SlipRatio(w * in.r, vc, in.slip_floor);
    const double f = in.force_max[side] * (1.0 - std::exp(-std::abs(kappa) / in.shear[side])) *
                     (kappa >= 0.0 ? 1.0 : -1.0);
    const double rolling = in.rolling[side] * in.load * std::tanh(vc / 0.01);
    const DcMotorDef& mo = *in.motor;
    const double i =
        std::clamp((in.volts[side] - mo.torque_constant * mo.gear_ratio * w) / mo.resistance,
                   -mo.current_max, mo.current_max);
    const double torque = mo.gear_ratio * mo.torque_constant * i - mo.viscous_friction * w;
    ds(2 + side) = (torque - f * in.r) / in.J;
    net[side] = f - rolling;
    if (out) {
      out->traction[side] = f;
      out->rolling[side] = rolling;
      out->current[side] = i;
      out->slip[side] = kappa;
    }
  }
  ds(0) = (net[0] + net[1] + in.caster_fx) / in.m;
  ds(1) = ((net[1] - net[0]) * in.half + in.caster_x * in.caster_fy) / in.I;
  return ds;
}

}  // namespace

void DiffDrive::SetVoltages(double left, double right) {
  cmd_ = {std::isfinite(left) ? left : 0.0, std::isfinite(right) ? right : 0.0};
}

const TerrainDef& DiffDrive::TerrainAt(const World& world, Vec2 p) const {
  auto it = def_.terrain.find(world.PatchNameAt(p));
  return it == def_.terrain.end() ? def_.floor_terrain : it->second;
}

void DiffDrive::Apply(Robot& robot, World& world, double dt) {
  const Pose2 pose = robot.pose();
  const double m = robot.mass(), I = robot.inertia();
  const double half = 0.5 * def_.track_width;
  const DcMotorDef& mo = def_.motor;

  voltage_limited_ = false;
  for (int s = 0; s < 2; ++s) {
    volts_[s] = std::clamp(cmd_[s], -mo.voltage_max, mo.voltage_max);
    voltage_limited_ = voltage_limited_ || volts_[s] != cmd_[s];
  }

  const double vx = robot.forward_speed(), vy = robot.lateral_speed(), w = robot.yaw_rate();
  const Vec2 wheel_pos[2] = {pose.ToWorld({0.0, half}), pose.ToWorld({0.0, -half})};
  const Vec2 caster_pos = pose.ToWorld({def_.caster_x, 0.0});
  const double load = m * kGravity * (1.0 - def_.caster_load) / 2.0;
  const double caster_load = m * kGravity * def_.caster_load;

  StepInputs in{};
  in.m = m;
  in.I = I;
  in.r = def_.wheel_radius;
  in.half = half;
  in.J = std::max(def_.wheel_inertia, 1e-6);
  in.caster_x = def_.caster_x;
  in.volts[0] = volts_[0];
  in.volts[1] = volts_[1];
  in.load = load;
  in.motor = &mo;
  in.slip_floor = std::max(def_.slip_speed_floor, 1e-3);

  // The caster rolls where it is pushed: its rolling resistance opposes its own velocity.
  const TerrainDef& tc = TerrainAt(world, caster_pos);
  const double cvx = vx, cvy = vy + w * def_.caster_x;
  const double cn = std::sqrt(cvx * cvx + cvy * cvy + 1e-4);
  in.caster_fx = -tc.rolling_resistance * caster_load * cvx / cn;
  in.caster_fy = -tc.rolling_resistance * caster_load * cvy / cn;

  // Lateral force that keeps the axle on its track (centripetal m ω v plus cancelling any side
  // velocity within the step), shared by the wheels and limited by each one's friction.
  const double lateral_need = m * (w * vx - vy / dt) - in.caster_fy;
  double lateral[2];
  skidding_ = false;
  for (int s = 0; s < 2; ++s) {
    mu_[s] = world.FrictionAt(wheel_pos[s]);
    const TerrainDef& t = TerrainAt(world, wheel_pos[s]);
    const double limit = mu_[s] * load;
    lateral[s] = std::clamp(0.5 * lateral_need, -0.98 * limit, 0.98 * limit);
    skidding_ = skidding_ || std::abs(lateral[s]) < std::abs(0.5 * lateral_need) - 1e-9;
    in.force_max[s] = std::sqrt(std::max(limit * limit - lateral[s] * lateral[s], 0.0));
    in.shear[s] = std::max(t.shear_slip, 1e-4);
    in.rolling[s] = t.rolling_resistance;
  }

  // Linearly implicit Euler on [v_x, ω, ω_l, ω_r]: stable for the stiff slip law at any dt.
  Eigen::Vector4d s(vx, w, omega_[0], omega_[1]);
  const int n = std::max(def_.substeps, 1);
  const double h = dt / n;
  Forces forces{};
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector4d f0 = Dynamics(s, in, nullptr);
    Eigen::Matrix4d A;
    for (int c = 0; c < 4; ++c) {
      Eigen::Vector4d sp = s;
      const double eps = 1e-7 * std::max(1.0, std::abs(s(c)));
      sp(c) += eps;
      A.col(c) = (Dynamics(sp, in, nullptr) - f0) / eps;
    }
    const Eigen::Vector4d ds = (Eigen::Matrix4d::Identity() - h * A).partialPivLu().solve(h * f0);
    const Eigen::Vector4d next = ds.allFinite() ? Eigen::Vector4d(s + ds) : s;
    for (int side = 0; side < 2; ++side) angle_[side] += 0.5 * (s(2 + side) + next(2 + side)) * h;
    s = next;
  }
  Dynamics(s, in, &forces);
  omega_ = {s(2), s(3)};

  // Forces that make Box2D reproduce the integrated velocity change over this step.
  const double fx_total = m * (s(0) - vx) / dt;
  const double torque = I * (s(1) - w) / dt;
  const double diff = (torque - def_.caster_x * in.caster_fy) / half;  // F_r - F_l
  const double sum = fx_total - in.caster_fx;                          // F_l + F_r
  const double f_long[2] = {0.5 * (sum - diff), 0.5 * (sum + diff)};
  const Vec2 ex{std::cos(pose.theta), std::sin(pose.theta)}, ey{-ex.y, ex.x};
  b2Body* body = robot.body();
  for (int side = 0; side < 2; ++side) {
    const Vec2 f = ex * f_long[side] + ey * lateral[side];
    body->ApplyForce(
        b2Vec2(static_cast<float>(f.x), static_cast<float>(f.y)),
        b2Vec2(static_cast<float>(wheel_pos[side].x), static_cast<float>(wheel_pos[side].y)), true);
    force_[side] = forces.traction[side];
    current_[side] = forces.current[side];
    slip_[side] = forces.slip[side];
    wheel_slipping_[side] = std::abs(forces.traction[side]) > 0.9 * in.force_max[side] + 1e-9;
  }
  const Vec2 fc = ex * in.caster_fx + ey * in.caster_fy;
  body->ApplyForce(b2Vec2(static_cast<float>(fc.x), static_cast<float>(fc.y)),
                   b2Vec2(static_cast<float>(caster_pos.x), static_cast<float>(caster_pos.y)),
                   true);
}

}  // namespace formsim::sim::velocity
