#include "sim/velocity/vio_sensors.hpp"

#include <algorithm>
#include <cmath>

#include "control/common/angle.hpp"

namespace formsim::sim::velocity {

using control::velocity::Vec2d;

void WheelOdometry::Reset(const EncoderDef& def, const DiffDriveDef& drive, Rng rng,
                          const DiffDrive& d) {
  def_ = def;
  radius_ = drive.wheel_radius;
  track_ = drive.track_width;
  rng_ = rng;
  last_[0] = Ticks(d.wheel_angle(DiffDrive::kLeft));
  last_[1] = Ticks(d.wheel_angle(DiffDrive::kRight));
}

long WheelOdometry::Ticks(double angle) {
  const double tick = 2.0 * control::kPi / std::max(def_.ticks_per_rev, 1);
  return static_cast<long>(std::floor((angle + def_.angle_noise * rng_.Normal()) / tick));
}

OdometryReading WheelOdometry::Sample(const DiffDrive& drive, double dt) {
  OdometryReading r;
  r.dt = dt;
  const double tick = 2.0 * control::kPi / std::max(def_.ticks_per_rev, 1);
  // The odometry's geometry: the calibrated values, off by the calibration errors.
  const double radius = radius_ * (1.0 + def_.radius_error);
  const double track = track_ * (1.0 + def_.track_error);
  double rim[2];
  for (int s = 0; s < 2; ++s) {
    const long now = Ticks(drive.wheel_angle(static_cast<DiffDrive::Side>(s)));
    rim[s] = dt > 0.0 ? (now - last_[s]) * tick * radius / dt : 0.0;
    last_[s] = now;
  }
  r.left = rim[0];
  r.right = rim[1];
  r.speed = 0.5 * (rim[0] + rim[1]);
  r.yaw_rate = (rim[1] - rim[0]) / track;
  return r;
}

void ImuSensor::Reset(const ImuDef& def, Rng rng, const Robot& robot) {
  def_ = def;
  rng_ = rng;
  bg_ = def.gyro_bias;
  ba_ = Vec2d(def.accel_bias_x, def.accel_bias_y);
  last_theta_ = robot.pose().theta;
  last_v_ = robot.world_velocity();
}

void ImuSensor::SetDef(const ImuDef& def) {
  // Changing the configured bias moves the current bias by the same amount (GUI sliders).
  bg_ += def.gyro_bias - def_.gyro_bias;
  ba_ += Vec2d(def.accel_bias_x - def_.accel_bias_x, def.accel_bias_y - def_.accel_bias_y);
  def_ = def;
}

ImuReading ImuSensor::Sample(const Robot& robot, double dt) {
  ImuReading r;
  r.dt = dt;
  const double theta = robot.pose().theta;
  const Vec2 v = robot.world_velocity();
  if (!(dt > 0.0)) return r;
  // Mean yaw rate and mean acceleration over the period (what an integrating IMU reports),
  // the acceleration rotated into the body frame at the mid-period heading.
  const double rate = control::AngleDiff(theta, last_theta_) / dt;
  const Vec2d a_world((v.x - last_v_.x) / dt, (v.y - last_v_.y) / dt);
  const Vec2d a_body = control::velocity::Rot(last_theta_ + 0.5 * rate * dt).transpose() * a_world;
  last_theta_ = theta;
  last_v_ = v;
  // Bias random walk, then white noise of the averaged sample (density / √dt).
  bg_ += def_.gyro_bias_rw * std::sqrt(dt) * rng_.Normal();
  ba_.x() += def_.accel_bias_rw * std::sqrt(dt) * rng_.Normal();
  ba_.y() += def_.accel_bias_rw * std::sqrt(dt) * rng_.Normal();
  r.gyro = rate + bg_ + def_.gyro_noise_density / std::sqrt(dt) * rng_.Normal();
  r.accel.x() = a_body.x() + ba_.x() + def_.accel_noise_density / std::sqrt(dt) * rng_.Normal();
  r.accel.y() = a_body.y() + ba_.y() + def_.accel_noise_density / std::sqrt(dt) * rng_.Normal();
  return r;
}

std::vector<control::velocity::BearingObservation> BearingCamera::Observe(
    const Pose2& pose, const std::vector<Landmark>& landmarks, const World& world) {
  const Vec2 cam = pose.ToWorld({def_.offset, 0.0});
  Pose2 cam_pose = pose;
  cam_pose.x = cam.x;
  cam_pose.y = cam.y;
  struct Candidate {
    double dist, bearing;
    int id;
    Vec2 p;
  };
  std::vector<Candidate> seen;
  for (const Landmark& l : landmarks) {
    const Vec2 q = cam_pose.ToBody(l.p);
    const double d = q.Norm();
    const double b = std::atan2(q.y, q.x);
    if (d < 0.05 || d > def_.range || std::abs(b) > 0.5 * def_.fov) continue;
    seen.push_back({d, b, l.id, l.p});
  }
  // Nearest first (ties by id, so the order never depends on the container).
  std::sort(seen.begin(), seen.end(), [](const Candidate& a, const Candidate& b) {
    return a.dist != b.dist ? a.dist < b.dist : a.id < b.id;
  });
  std::vector<control::velocity::BearingObservation> out;
  for (const Candidate& c : seen) {
    if (static_cast<int>(out.size()) >= def_.max_features) break;
    if (!world.obstacles().empty()) {
      const RayHit hit = world.RayCast(cam, c.p, false);
      if (hit.hit && hit.distance < c.dist - 1e-3) continue;
    }
    out.push_back({c.id, c.bearing + def_.bearing_noise * rng_.Normal()});
  }
  return out;
}

}  // namespace formsim::sim::velocity
