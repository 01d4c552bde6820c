#pragma once
/// \file Laser localisation from known reference posts (paper section 1.2):
///  - eq. 2: position from the ranges to two posts (intersection of two circles);
///  - eq. 3: heading from the scan angles of the same two posts (straight segments);
///  - eq. 4: radius and heading offsets on a turning segment around a known centre.
/// A wrong fix is worse than none: mirror ambiguity, circles that miss each other, posts nearly
/// in line with the robot and measurements that disagree with the map all give "no fix".
/// Angles follow the paper convention (see paper_frame.hpp): bearings clockwise from forward.

#include <string>
#include <vector>

#include "control/common/geometry.hpp"
#include "control/inspection/paper_frame.hpp"

namespace formsim::control::inspection {

/// One identified reference post as seen by the laser scanner.
struct PostSighting {
  int post = -1;         ///< index in the post map
  Vec2 position;         ///< surveyed (map) position of the post centre, world frame, m
  double range = 0.0;    ///< scanner to post centre, m
  double bearing = 0.0;  ///< scan angle, clockwise from the forward axis, rad
};

/// Which pair of posts in view a fix is computed from first.
enum class PairChoice {
  kBestAngle,  ///< the rays closest to 90° apart (the smallest dilution of precision)
  kNearest,    ///< the two nearest posts (the pair whose farther post is nearest)
};

/// Acceptance limits of a two-post fix.
struct TrilaterationDef {
  PairChoice pair = PairChoice::kBestAngle;  ///< the order in which pairs are tried
  double range_tolerance = 0.10;     ///< circles may miss each other by this much (noise), m
  double min_subtended = Rad(20.0);  ///< angle between the two rays must lie in [this, π − this]
  double angle_tolerance = Rad(4.0);  ///< |measured − map-predicted| angle between the rays, rad
  double max_range = 12.0;            ///< posts farther away are not used, m
};
inline TrilaterationDef DefaultTrilaterationDef() {
  return TrilaterationDef{};
}

enum class FixStatus { kOk, kTooFewPosts, kNoIntersection, kPoorGeometry, kInconsistent };
const char* ToString(FixStatus status);

/// Intersections of two circles (eq. 2). `count` is 0, 1 (tangent, or a miss within
/// `tolerance` resolved to the closest point) or 2.
struct CircleIntersection {
  int count = 0;
  Vec2 a, b;
};
CircleIntersection IntersectCircles(const Vec2& p1, double r1, const Vec2& p2, double r2,
                                    double tolerance);

/// A position (and heading) fix from two posts.
struct Fix {
  FixStatus status = FixStatus::kTooFewPosts;
  Vec2 position;         ///< eq. 2, world frame
  double heading = 0.0;  ///< eq. 3, paper convention
  int sighting_a = -1;   ///< indices into the sightings used
  int sighting_b = -1;
  double subtended = 0.0;  ///< angle between the two rays at the robot, rad
  bool ok() const { return status == FixStatus::kOk; }
};

/// Eq. 2 with the mirror ambiguity resolved by the scan angles: of the two circle
/// intersections, the one from which post 2 appears on the same side of post 1 as in the scan.
Fix TrilaterateTwoPosts(const PostSighting& s1, const PostSighting& s2,
                        const TrilaterationDef& def = DefaultTrilaterationDef());

/// Eq. 3: heading from the two posts' ranges and scan angles, independent of the position fix.
/// d12 by the law of cosines from the measured angle between the rays, β the angle at post 2,
/// γ the azimuth of the line post 2 → post 1 (the paper's arctan of k1 = (x1−x2)/(y1−y2)
/// against the Y axis, kept here with its quadrant), then θ = az(post 2 → robot) + π − α2.
/// Returns NaN when the triangle is degenerate.
double HeadingFromScanAngles(const PostSighting& s1, const PostSighting& s2);

/// The best fix from all sightings: pairs within range are tried in the order `def.pair` says
/// (best geometry: the angle between the rays closest to 90° first; nearest: the pair whose
/// farther post is nearest first) and the first consistent pair is used. With no consistent
/// pair, the status of the first pair tried is returned.
Fix Localise(const std::vector<PostSighting>& sightings,
             const TrilaterationDef& def = DefaultTrilaterationDef());

/// Eq. 4: offsets on a turning segment around `centre` with nominal radius `radius`.
struct TurnMeasurement {
  bool ok = false;
  double radius = 0.0;          ///< measured distance to the centre (the paper's R_mea), m
  double delta_r = 0.0;         ///< radius − nominal radius, m
  double centre_bearing = 0.0;  ///< angle between heading and the radius direction (θ), rad
  double heading_error = 0.0;   ///< Δφ: heading − path tangent, rad (paper: Δθ = π/2 − θ)
  double lateral_offset = 0.0;  ///< s: positive to the right of the direction of travel, m
  double heading = 0.0;         ///< absolute heading implied by the scan angle, rad
};
/// `position` is the eq. 2 fix, `post` a post seen in the scan (the paper uses the inner post
/// 1), `clockwise` the turn direction (centre on the robot's right). θ = α1 ± arccos of the
/// triangle robot–post–centre, as in eq. 4; the sign is the side of the centre w.r.t. the post.
TurnMeasurement TurnGeometry(const Vec2& position, const Vec2& centre, double radius,
                             bool clockwise, const PostSighting& post);

}  // namespace formsim::control::inspection
