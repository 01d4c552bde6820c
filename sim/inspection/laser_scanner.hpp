#pragma once
/// \file A 2-D laser scanner (the paper's SICK LMS: 50 Hz, 360°, 20 m) simulated with Box2D ray
/// casts against the world's obstacles (robots are not seen). Beam k points at bearing
/// −fov/2 + k·resolution, clockwise from the robot's forward axis (paper convention). Each
/// beam's direction jitters by angle_sigma, each return gets Gaussian range noise and, with
/// probability outlier_prob, a gross error of outlier_sigma (dust, reflections). Noise comes
/// from the scanner's own Rng stream, drawn for every beam, so a run is reproducible; the ray
/// casts (a `RayFan` per scan: Box2D's hits, bearing-binned) are shared out on a thread pool, and the scan
/// does not depend on the number of threads.

#include <vector>

#include "control/common/geometry.hpp"
#include "control/inspection/post_detector.hpp"
#include "sim/core/rng.hpp"
#include "sim/core/thread_pool.hpp"
#include "sim/core/world.hpp"

namespace formsim::sim {
class YamlReader;
}  // namespace formsim::sim

namespace formsim::sim::inspection {

struct LaserScannerDef {
  double rate_hz = 50.0;
  double range_max = 20.0;  ///< m
  double fov_deg = 360.0;
  double resolution_deg = 0.5;
  double range_sigma = 0.01;      ///< m
  double angle_sigma_deg = 0.05;  ///< beam direction jitter, deg
  double outlier_prob = 0.002;    ///< per beam
  double outlier_sigma = 0.3;     ///< m
};
inline LaserScannerDef DefaultLaserScannerDef() {
  return LaserScannerDef{};
}

/// Reads `laser:` (keys as in LaserScannerDef) and declares its tunables (group "Noise/laser").
/// `*every` receives the world steps between two scans at step `dt`.
LaserScannerDef ReadLaserScanner(YamlReader& laser_map, double dt, int* every);

class LaserScanner {
 public:
  LaserScanner(const LaserScannerDef& def, Rng rng) : def_(def), rng_(rng) {}
  LaserScannerDef& def() { return def_; }
  const LaserScannerDef& def() const { return def_; }
  /// One scan taken at `sensor` (the scanner's true world pose, mathematical convention), not
  /// seeing `carrier` (the robot it is mounted on). `endpoints` (optional) receives the world
  /// point of every beam (the hit, or the end of the range). The beams are cast on `pool` when
  /// given.
  control::inspection::Scan Sample(const World& world, const Pose2& sensor, const Robot* carrier,
                                   std::vector<Vec2>* endpoints = nullptr,
                                   ThreadPool* pool = nullptr);

 private:
  // The noise of one beam, drawn in beam order before any ray is cast.
  struct BeamNoise {
    double jitter = 0.0, range = 0.0, gross = 0.0;
    bool outlier = false;
  };
  LaserScannerDef def_;
  Rng rng_;
  std::vector<BeamNoise> noise_;
};

}  // namespace formsim::sim::inspection
