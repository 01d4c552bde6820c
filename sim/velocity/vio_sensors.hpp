#pragma once
/// \file The velocity-control robot's sensors, each with its own rate and noise stream:
///  - wheel encoders (quantised wheel angle with read jitter) turned into wheel odometry with
///    the odometry's own idea of wheel radius and track (calibration errors are biases);
///  - a planar IMU (yaw-rate gyro, 2-axis accelerometer) with bias, bias random walk and white
///    noise, sampling the mean rate and acceleration over its period;
///  - a camera measuring bearings of point landmarks within its field of view and range, with
///    obstacles occluding them.

#include <vector>

#include "control/velocity/sliding_window_estimator.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/world.hpp"
#include "sim/velocity/diff_drive.hpp"

namespace formsim::sim::velocity {

struct EncoderDef {
  double rate = 50.0;         ///< Hz
  int ticks_per_rev = 4096;   ///< counts per wheel turn (after quadrature)
  double angle_noise = 5e-4;  ///< read jitter of the wheel angle, rad (white, per sample)
  double radius_error = 0.0;  ///< odometry radius = true radius · (1 + e)
  double track_error = 0.0;   ///< odometry track = true track · (1 + e)
};

/// One odometry reading over the encoder period.
struct OdometryReading {
  double dt = 0.0;
  double speed = 0.0;              ///< forward speed, m/s
  double yaw_rate = 0.0;           ///< rad/s
  double left = 0.0, right = 0.0;  ///< wheel rim speeds as the odometry sees them, m/s
};

class WheelOdometry {
 public:
  void Reset(const EncoderDef& def, const DiffDriveDef& drive, Rng rng, const DiffDrive& d);
  void SetDef(const EncoderDef& def) { def_ = def; }
  const EncoderDef& def() const { return def_; }
  /// Reads the encoders; the reading covers the `dt` seconds since the previous one.
  OdometryReading Sample(const DiffDrive& drive, double dt);

 private:
  long Ticks(double angle);
  EncoderDef def_;
  double radius_ = 0.05, track_ = 0.3;  ///< true geometry
  long last_[2] = {0, 0};
  Rng rng_;
};

struct ImuDef {
  double rate = 200.0;                               ///< Hz
  double gyro_noise_density = 5e-4;                  ///< rad/s/√Hz
  double accel_noise_density = 4e-3;                 ///< m/s²/√Hz
  double gyro_bias = 0.01;                           ///< initial true bias, rad/s
  double accel_bias_x = 0.05, accel_bias_y = -0.03;  ///< initial true bias, m/s²
  double gyro_bias_rw = 5e-5;                        ///< rad/s²/√Hz
  double accel_bias_rw = 5e-4;                       ///< m/s³/√Hz
};

struct ImuReading {
  double dt = 0.0;
  double gyro = 0.0;
  control::velocity::Vec2d accel = control::velocity::Vec2d::Zero();
};

class ImuSensor {
 public:
  void Reset(const ImuDef& def, Rng rng, const Robot& robot);
  void SetDef(const ImuDef& def);
  const ImuDef& def() const { return def_; }
  ImuReading Sample(const Robot& robot, double dt);
  double gyro_bias() const { return bg_; }
  control::velocity::Vec2d accel_bias() const { return ba_; }

 private:
  ImuDef def_;
  double bg_ = 0.0;
  control::velocity::Vec2d ba_ = control::velocity::Vec2d::Zero();
  double last_theta_ = 0.0;
  Vec2 last_v_;
  Rng rng_;
};

struct CameraDef {
  double rate = 20.0;            ///< frames per second
  double fov = 1.5708;           ///< full horizontal field of view, rad
  double range = 8.0;            ///< m
  double bearing_noise = 0.002;  ///< rad
  double offset = 0.1;           ///< ahead of the body origin, m
  int max_features = 30;         ///< nearest landmarks kept per frame
};

struct Landmark {
  int id = 0;
  Vec2 p;
};

class BearingCamera {
 public:
  void Reset(const CameraDef& def, Rng rng) {
    def_ = def;
    rng_ = rng;
  }
  void SetDef(const CameraDef& def) { def_ = def; }
  const CameraDef& def() const { return def_; }
  /// Bearings of the visible landmarks (in view, in range, not occluded by an obstacle).
  std::vector<control::velocity::BearingObservation> Observe(const Pose2& pose,
                                                        const std::vector<Landmark>& landmarks,
                                                        const World& world);

 private:
  CameraDef def_;
  Rng rng_;
};

}  // namespace formsim::sim::velocity
