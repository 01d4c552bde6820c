#pragma once
/// \file Finding the known reference posts in a laser scan (paper section 1.2.2: "identify the
/// reference distances and map them one-to-one to the reference objects"):
///  1. split the scan into clusters of neighbouring returns;
///  2. keep clusters shaped like a post: narrow enough for its diameter and fitting a circle of
///     the post radius (least squares, Gauss-Newton on the centre);
///  3. place each centre in the world with the predicted pose and match it to the nearest
///     surveyed post within a gate. A cluster near two posts, or two clusters on one post, are
///     ambiguous and dropped: a missing post is harmless, a wrongly named one is not.
/// Scan angles are bearings in the paper convention (clockwise from the forward axis).

#include <vector>

#include "control/common/geometry.hpp"
#include "control/inspection/dead_reckoning.hpp"
#include "control/inspection/trilateration.hpp"

namespace formsim::control::inspection {

/// One laser scan: beam k points at bearing angle_min + k * angle_increment.
struct Scan {
  double angle_min = -kPi;
  double angle_increment = Rad(0.5);
  double range_max = 20.0;
  std::vector<double> ranges;  ///< m; NaN (or > range_max) when the beam returned nothing
  double Bearing(int k) const { return angle_min + k * angle_increment; }
  /// True when the beams cover the whole circle (first and last beams are neighbours).
  bool full_circle() const;
};

/// The surveyed reference posts.
struct PostMap {
  std::vector<Vec2> posts;
  double radius = 0.1;  ///< post radius, m
};

struct PostDetectorDef {
  int min_beams = 2;             ///< fewer returns on a cluster: not used
  double cluster_jump = 0.15;    ///< consecutive returns farther apart (m) split clusters
  double span_tolerance = 0.08;  ///< chord longer than the diameter plus this: not a post, m
  double fit_tolerance = 0.03;   ///< RMS circle-fit residual above this: not a post, m
  double gate = 0.6;             ///< predicted centre to surveyed post, m
};
inline PostDetectorDef DefaultPostDetectorDef() {
  return PostDetectorDef{};
}

/// What became of one cluster of returns.
struct ScanCluster {
  enum class Outcome {
    kIdentified,
    kTooFewBeams,
    kNotPostShaped,
    kUnmatched,
    kAmbiguous,
    kDuplicate
  };
  int first_beam = 0;
  int beams = 0;
  double range = 0.0;    ///< fitted centre, m
  double bearing = 0.0;  ///< fitted centre, rad
  int post = -1;         ///< matched post (kIdentified)
  Outcome outcome = Outcome::kUnmatched;
};

struct PostDetection {
  std::vector<PostSighting> sightings;  ///< identified posts, in scan order
  std::vector<ScanCluster> clusters;
};

/// Fits a circle of known radius to points seen from the origin (body frame, any convention).
/// Returns false when the fit is degenerate or lands on the wrong side of the points.
bool FitKnownCircle(const std::vector<Vec2>& points, double radius, Vec2* centre, double* rms);

PostDetection DetectPosts(const Scan& scan, const PaperPose& predicted, const PostMap& map,
                          const PostDetectorDef& def = DefaultPostDetectorDef());

}  // namespace formsim::control::inspection
