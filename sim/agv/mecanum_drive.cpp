#include "sim/agv/mecanum_drive.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>


namespace formsim::sim::agv {

using control::agv::kMecanumWheels;
using control::agv::MecanumGeometry;

double MecanumDrive::true_radius(int i) const {
  return def_.geometry.wheel_radius * (1.0 + def_.radius_error[i]);
}

bool MecanumDrive::slipping() const {
  return std::any_of(slipping_.begin(), slipping_.end(), [](bool b) { return b; });
}

void MecanumDrive::SetWheelCommand(const control::agv::WheelArray& w) {
  command_limited_ = false;
  for (int i = 0; i < kMecanumWheels; ++i) {
    const double v = std::isfinite(w[i]) ? w[i] : 0.0;
    cmd_[i] = std::clamp(v, -def_.wheel_speed_max, def_.wheel_speed_max);
    if (cmd_[i] != w[i]) command_limited_ = true;
  }
}

void MecanumDrive::Apply(Robot& robot, World& world, double dt) {
  // 1. Motors: first-order speed loop with an acceleration limit; wheel angles integrate.
  const double blend =
      def_.motor_time_constant > 0.0 ? 1.0 - std::exp(-dt / def_.motor_time_constant) : 1.0;
  for (int i = 0; i < kMecanumWheels; ++i) {
    double dw = blend * (cmd_[i] - speed_[i]);
    if (def_.wheel_accel_max > 0.0)
      dw = std::clamp(dw, -def_.wheel_accel_max * dt, def_.wheel_accel_max * dt);
    speed_[i] = std::clamp(speed_[i] + dw, -def_.wheel_speed_max, def_.wheel_speed_max);
    angle_[i] += speed_[i] * dt;
  }

  // 2. Contact rows d_i = [a_x, a_y, p_i × a_i] (body frame) and slip σ_i = d_i·V − r_i ω_i/√2.
  const double vx = robot.forward_speed(), vy = robot.lateral_speed(), wz = robot.yaw_rate();
  const double m = robot.mass(), inertia = robot.inertia();
  const Pose2 pose = robot.pose();
  const double inv_sqrt2 = 1.0 / std::sqrt(2.0);
  double d[4][3], limit[4];
  for (int i = 0; i < kMecanumWheels; ++i) {
    const Vec2 p = def_.geometry.WheelPosition(i), a = MecanumGeometry::RollerAxis(i);
    d[i][0] = a.x;
    d[i][1] = a.y;
    d[i][2] = p.Cross(a);
    slip_[i] = d[i][0] * vx + d[i][1] * vy + d[i][2] * wz - true_radius(i) * speed_[i] * inv_sqrt2;
    limit[i] = world.FrictionAt(pose.ToWorld(p)) * m * kGravity / kMecanumWheels;
  }

  // 3. Implicit viscous contact with a friction box: (I/c + dt W) f = −σ, W = D M⁻¹ Dᵀ,
  //    |f_i| ≤ μ_i N_i. Exact solve first; when a force exceeds its box, projected
  //    Gauss-Seidel from the clamped solution.
  const double inv_c = def_.slip_damping > 0.0 ? 1.0 / def_.slip_damping : 1e-3;
  const double inv_mass[3] = {1.0 / m, 1.0 / m, 1.0 / inertia};
  Eigen::Matrix4d A;
  Eigen::Vector4d rhs0;
  for (int i = 0; i < kMecanumWheels; ++i) {
    rhs0(i) = -slip_[i];
    for (int j = 0; j < kMecanumWheels; ++j) {
      double w = 0.0;
      for (int k = 0; k < 3; ++k) w += d[i][k] * inv_mass[k] * d[j][k];
      A(i, j) = dt * w + (i == j ? inv_c : 0.0);
    }
  }
  const Eigen::Vector4d f0 = A.ldlt().solve(rhs0);
  bool inside = f0.allFinite();
  for (int i = 0; i < kMecanumWheels; ++i) {
    force_[i] = std::isfinite(f0(i)) ? std::clamp(f0(i), -limit[i], limit[i]) : 0.0;
    if (force_[i] != f0(i)) inside = false;
  }
  for (int iter = 0; iter < 60 && !inside; ++iter) {
    double change = 0.0;
    for (int i = 0; i < kMecanumWheels; ++i) {
      double rhs = -slip_[i];
      for (int j = 0; j < kMecanumWheels; ++j)
        if (j != i) rhs -= A(i, j) * force_[j];
      const double f = std::clamp(rhs / A(i, i), -limit[i], limit[i]);
      change = std::max(change, std::abs(f - force_[i]));
      force_[i] = f;
    }
    if (change < 1e-9) break;  // converged
  }

  // 4. Resulting wrench, applied to the Box2D body (world frame).
  double fx = 0.0, fy = 0.0, tau = 0.0;
  for (int i = 0; i < kMecanumWheels; ++i) {
    slipping_[i] = limit[i] <= 0.0 || std::abs(force_[i]) >= limit[i] * (1.0 - 1e-9);
    fx += force_[i] * d[i][0];
    fy += force_[i] * d[i][1];
    tau += force_[i] * d[i][2];
  }
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  b2Body* body = robot.body();
  body->ApplyForceToCenter(
      b2Vec2(static_cast<float>(c * fx - s * fy), static_cast<float>(s * fx + c * fy)), true);
  body->ApplyTorque(static_cast<float>(tau), true);
}

}  // namespace formsim::sim::agv
