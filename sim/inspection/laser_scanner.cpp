#include "sim/inspection/laser_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/inspection/paper_frame.hpp"
#include "sim/core/yaml_reader.hpp"

namespace formsim::sim {

using control::inspection::AzimuthDirection;
using control::inspection::PaperFromMath;
using control::inspection::Rad;

control::inspection::Scan LaserScanner::Sample(const World& world, const Pose2& sensor,
                                               const Robot* carrier, std::vector<Vec2>* endpoints) {
  control::inspection::Scan scan;
  const double fov = Rad(std::clamp(def_.fov_deg, 1.0, 360.0));
  const double res = Rad(std::max(def_.resolution_deg, 0.05));
  const int n = std::max(1, static_cast<int>(std::lround(fov / res)));
  scan.angle_increment = res;
  scan.angle_min = -0.5 * fov;
  scan.range_max = def_.range_max;
  scan.ranges.resize(n);
  if (endpoints) endpoints->resize(n);
  const Vec2 origin = sensor.p();
  const double heading = PaperFromMath(sensor.theta);
  const double angle_sigma = Rad(def_.angle_sigma_deg);
  for (int k = 0; k < n; ++k) {
    // Draw all noise first, hit or not, so the stream does not depend on the scene.
    const double jitter = rng_.Normal(0.0, angle_sigma);
    const double noise = rng_.Normal(0.0, def_.range_sigma);
    const bool outlier = rng_.Bernoulli(def_.outlier_prob);
    const double gross = rng_.Normal(0.0, def_.outlier_sigma);
    const Vec2 dir = AzimuthDirection(heading + scan.Bearing(k) + jitter);
    const Vec2 end = origin + dir * def_.range_max;
    const RayHit hit = world.RayCast(origin, end, false, carrier);
    if (!hit.hit) {
      scan.ranges[k] = std::numeric_limits<double>::quiet_NaN();
      if (endpoints) (*endpoints)[k] = end;
      continue;
    }
    const double r = std::max(0.0, hit.distance + noise + (outlier ? gross : 0.0));
    scan.ranges[k] = r;
    if (endpoints) (*endpoints)[k] = origin + dir * r;
  }
  return scan;
}

LaserScannerDef ReadLaserScanner(YamlReader& l) {
  LaserScannerDef def = DefaultLaserScannerDef();
  def.rate_hz = l.Double("rate_hz", def.rate_hz);
  def.range_max = l.Double("range_max", def.range_max);
  def.fov_deg = l.Double("fov_deg", def.fov_deg);
  def.resolution_deg = l.Double("resolution_deg", def.resolution_deg);
  def.range_sigma = l.Double("range_sigma", def.range_sigma);
  def.angle_sigma_deg = l.Double("angle_sigma_deg", def.angle_sigma_deg);
  def.outlier_prob = l.Double("outlier_prob", def.outlier_prob);
  def.outlier_sigma = l.Double("outlier_sigma", def.outlier_sigma);
  if (def.rate_hz <= 0) l.Fail("rate_hz", "must be positive");
  if (def.range_max <= 0) l.Fail("range_max", "must be positive");
  if (def.fov_deg <= 0 || def.fov_deg > 360) l.Fail("fov_deg", "must be in (0, 360]");
  if (def.resolution_deg < 0.05 || def.resolution_deg > 10)
    l.Fail("resolution_deg", "must be in [0.05, 10]");
  if (def.range_sigma < 0) l.Fail("range_sigma", "must be >= 0");
  if (def.angle_sigma_deg < 0) l.Fail("angle_sigma_deg", "must be >= 0");
  if (def.outlier_prob < 0 || def.outlier_prob > 1) l.Fail("outlier_prob", "must be in [0, 1]");
  if (def.outlier_sigma < 0) l.Fail("outlier_sigma", "must be >= 0");
  l.Finish();
  return def;
}

}  // namespace formsim::sim
