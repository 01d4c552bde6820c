#include "control/inspection/post_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/common/angle.hpp"
#include "control/inspection/paper_frame.hpp"

namespace formsim::control::inspection {
namespace {

bool Valid(const Scan& scan, int k) {
  const double r = scan.ranges[k];
  return std::isfinite(r) && r > 0.0 && r <= scan.range_max;
}

// Body-frame point of beam k (x to the right, y forward, so the azimuth is the bearing).
Vec2 BeamPoint(const Scan& scan, int k) {
  return AzimuthDirection(scan.Bearing(k)) * scan.ranges[k];
}

}  // namespace

bool Scan::full_circle() const {
  return angle_increment * static_cast<double>(ranges.size()) >= 2.0 * kPi - 0.5 * angle_increment;
}

bool FitKnownCircle(const std::vector<Vec2>& points, double radius, Vec2* centre, double* rms) {
  if (points.empty()) return false;
  // Start behind the closest return, along its ray: exact for the beam through the centre.
  const Vec2* closest = &points[0];
  for (const Vec2& p : points)
    if (p.Norm() < closest->Norm()) closest = &p;
  const double rc = closest->Norm();
  if (!(rc > 0.0)) return false;
  Vec2 c = *closest * ((rc + radius) / rc);
  // Gauss-Newton on the centre: residual_j = |p_j − c| − R, d residual / dc = −(p_j − c)/|p_j − c|.
  for (int it = 0; it < 10 && points.size() >= 2; ++it) {
    double a11 = 0, a12 = 0, a22 = 0, b1 = 0, b2 = 0;
    for (const Vec2& p : points) {
      const Vec2 d = p - c;
      const double n = d.Norm();
      if (!(n > 1e-12)) continue;
      const Vec2 j{-d.x / n, -d.y / n};
      const double r = n - radius;
      a11 += j.x * j.x;
      a12 += j.x * j.y;
      a22 += j.y * j.y;
      b1 -= j.x * r;
      b2 -= j.y * r;
    }
    const double det = a11 * a22 - a12 * a12;
    if (!(std::abs(det) > 1e-12)) break;  // points on one ray: keep the start value
    const Vec2 step{(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det};
    // A short arc constrains the centre poorly along the ray; never move more than a radius.
    const double sn = step.Norm();
    c = c + (sn > radius ? step * (radius / sn) : step);
    if (sn < 1e-9) break;
  }
  // The returns must lie on the near side of the circle (seen from the scanner).
  if (!(c.Norm() > rc)) return false;
  double sum = 0.0;
  for (const Vec2& p : points) {
    const double r = (p - c).Norm() - radius;
    sum += r * r;
  }
  *centre = c;
  *rms = std::sqrt(sum / static_cast<double>(points.size()));
  return std::isfinite(*rms);
}

PostDetection DetectPosts(const Scan& scan, const PaperPose& predicted, const PostMap& map,
                          const PostDetectorDef& def) {
  PostDetection out;
  const int n = static_cast<int>(scan.ranges.size());
  if (n == 0) return out;

  // 1. Clusters of consecutive valid returns without a range jump.
  std::vector<std::vector<int>> clusters;
  for (int k = 0; k < n; ++k) {
    if (!Valid(scan, k)) continue;
    const bool joins = k > 0 && Valid(scan, k - 1) &&
                       std::abs(scan.ranges[k] - scan.ranges[k - 1]) < def.cluster_jump;
    if (!joins || clusters.empty()) clusters.emplace_back();
    clusters.back().push_back(k);
  }
  // A full circle wraps: the last cluster continues into the first.
  if (scan.full_circle() && clusters.size() >= 2 && clusters.front().front() == 0 &&
      clusters.back().back() == n - 1 &&
      std::abs(scan.ranges[0] - scan.ranges[n - 1]) < def.cluster_jump) {
    clusters.back().insert(clusters.back().end(), clusters.front().begin(), clusters.front().end());
    clusters.erase(clusters.begin());
  }

  // 2. Post-shaped clusters, fitted; 3. matched to the map.
  const double diameter = 2.0 * map.radius;
  for (const auto& beams : clusters) {
    ScanCluster cl;
    cl.first_beam = beams.front();
    cl.beams = static_cast<int>(beams.size());
    std::vector<Vec2> pts;
    pts.reserve(beams.size());
    for (int k : beams) pts.push_back(BeamPoint(scan, k));
    if (cl.beams < def.min_beams) {
      cl.outcome = ScanCluster::Outcome::kTooFewBeams;
      out.clusters.push_back(cl);
      continue;
    }
    Vec2 centre;
    double rms = 0.0;
    const bool narrow = (pts.back() - pts.front()).Norm() <= diameter + def.span_tolerance;
    if (!narrow || !FitKnownCircle(pts, map.radius, &centre, &rms) || rms > def.fit_tolerance) {
      cl.outcome = ScanCluster::Outcome::kNotPostShaped;
      out.clusters.push_back(cl);
      continue;
    }
    cl.range = centre.Norm();
    cl.bearing = Azimuth(centre);
    const Vec2 world = predicted.p() + AzimuthDirection(predicted.theta + cl.bearing) * cl.range;
    int best = -1;
    double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
    for (int i = 0; i < static_cast<int>(map.posts.size()); ++i) {
      const double d = (map.posts[i] - world).Norm();
      if (d < d1) {
        d2 = d1;
        d1 = d;
        best = i;
      } else if (d < d2) {
        d2 = d;
      }
    }
    if (best < 0 || d1 > def.gate) {
      cl.outcome = ScanCluster::Outcome::kUnmatched;
    } else if (d2 <= def.gate) {
      cl.outcome = ScanCluster::Outcome::kAmbiguous;
    } else {
      cl.outcome = ScanCluster::Outcome::kIdentified;
      cl.post = best;
    }
    out.clusters.push_back(cl);
  }
  // Two clusters claiming one post: neither can be trusted.
  for (auto& a : out.clusters) {
    if (a.outcome != ScanCluster::Outcome::kIdentified) continue;
    for (auto& b : out.clusters) {
      if (&a != &b && b.post == a.post &&
          (b.outcome == ScanCluster::Outcome::kIdentified ||
           b.outcome == ScanCluster::Outcome::kDuplicate)) {
        a.outcome = b.outcome = ScanCluster::Outcome::kDuplicate;
      }
    }
  }
  for (const auto& cl : out.clusters) {
    if (cl.outcome != ScanCluster::Outcome::kIdentified) continue;
    PostSighting s;
    s.post = cl.post;
    s.position = map.posts[cl.post];
    s.range = cl.range;
    s.bearing = cl.bearing;
    out.sightings.push_back(s);
  }
  return out;
}

}  // namespace formsim::control::inspection
