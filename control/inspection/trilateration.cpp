#include "control/inspection/trilateration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "control/common/angle.hpp"

namespace formsim::control::inspection {
namespace {

double Sign(double v) {
  return v >= 0.0 ? 1.0 : -1.0;
}
double ClampUnit(double v) {
  return std::clamp(v, -1.0, 1.0);
}

// Angle between the two rays seen from the robot, signed (post 2 clockwise of post 1 > 0).
double SignedSpread(const PostSighting& s1, const PostSighting& s2) {
  return AngleDiff(s2.bearing, s1.bearing);
}

}  // namespace

const char* ToString(FixStatus status) {
  switch (status) {
    case FixStatus::kOk:
      return "ok";
    case FixStatus::kTooFewPosts:
      return "too_few_posts";
    case FixStatus::kNoIntersection:
      return "no_intersection";
    case FixStatus::kPoorGeometry:
      return "poor_geometry";
    case FixStatus::kInconsistent:
      return "inconsistent";
  }
  return "?";
}

CircleIntersection IntersectCircles(const Vec2& p1, double r1, const Vec2& p2, double r2,
                                    double tolerance) {
  CircleIntersection out;
  const Vec2 d = p2 - p1;
  const double dist = d.Norm();
  if (!(dist > 1e-9) || !(r1 >= 0.0) || !(r2 >= 0.0)) return out;
  const Vec2 e = d * (1.0 / dist);
  const Vec2 n{-e.y, e.x};
  // Distance from p1 along the centre line to the chord, and half the chord length.
  const double a = (r1 * r1 - r2 * r2 + dist * dist) / (2.0 * dist);
  const double h2 = r1 * r1 - a * a;
  if (h2 >= 0.0) {
    const double h = std::sqrt(h2);
    out.count = h > 0.0 ? 2 : 1;
    out.a = p1 + e * a + n * h;
    out.b = p1 + e * a - n * h;
    return out;
  }
  // The circles miss each other (noise): accept the closest point if the miss is small.
  const double miss = std::max(dist - (r1 + r2), std::abs(r1 - r2) - dist);
  if (miss > tolerance) return out;
  out.count = 1;
  out.a = out.b = p1 + e * a;
  return out;
}

Fix TrilaterateTwoPosts(const PostSighting& s1, const PostSighting& s2,
                        const TrilaterationDef& def) {
  Fix fix;
  fix.sighting_a = 0;
  fix.sighting_b = 1;
  const double spread = SignedSpread(s1, s2);
  fix.subtended = std::abs(spread);
  // Posts nearly in line with the robot: the circles cross at a grazing angle and the side
  // cannot be told from the scan angles.
  if (std::sin(fix.subtended) < std::sin(def.min_subtended)) {
    fix.status = FixStatus::kPoorGeometry;
    return fix;
  }
  const CircleIntersection ci =
      IntersectCircles(s1.position, s1.range, s2.position, s2.range, def.range_tolerance);
  if (ci.count == 0) {
    fix.status = FixStatus::kNoIntersection;
    return fix;
  }
  // Mirror ambiguity: the two intersections lie on both sides of the post line; the sign of the
  // angle from post 1 to post 2 is preserved by the rotation from body to world frame.
  auto map_spread = [&](const Vec2& x) {
    return AngleDiff(Azimuth(s2.position - x), Azimuth(s1.position - x));
  };
  Vec2 x = ci.a;
  if (ci.count == 2 && Sign(map_spread(ci.a)) != Sign(spread)) x = ci.b;
  if (std::abs(AngleDiff(map_spread(x), spread)) > def.angle_tolerance) {
    fix.status = FixStatus::kInconsistent;
    return fix;
  }
  const double heading = HeadingFromScanAngles(s1, s2);
  if (!std::isfinite(heading)) {
    fix.status = FixStatus::kPoorGeometry;
    return fix;
  }
  fix.status = FixStatus::kOk;
  fix.position = x;
  fix.heading = heading;
  return fix;
}

double HeadingFromScanAngles(const PostSighting& s1, const PostSighting& s2) {
  const double spread = SignedSpread(s1, s2);
  const double dalpha = std::abs(spread);
  const double r1 = s1.range, r2 = s2.range;
  // Law of cosines: distance between the posts from the two ranges and the angle between rays.
  const double d12 = std::sqrt(std::max(0.0, r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * std::cos(dalpha)));
  if (!(d12 > 1e-9) || !(r2 > 1e-9)) return std::numeric_limits<double>::quiet_NaN();
  // β: the angle at post 2 between post 2 → post 1 and post 2 → robot.
  const double beta = std::acos(ClampUnit((r2 * r2 + d12 * d12 - r1 * r1) / (2.0 * r2 * d12)));
  // γ: direction of the post line against the Y axis (with its quadrant).
  const double gamma = Azimuth(s1.position - s2.position);
  // The triangle robot → post 1 → post 2 keeps its orientation at every vertex, so the robot
  // lies clockwise of the post line (seen from post 2) exactly when post 2 is clockwise of
  // post 1 in the scan: az(post 2 → robot) = γ − sign(spread)·β.
  const double az_post2_to_robot = gamma - Sign(spread) * beta;
  return WrapToPi(az_post2_to_robot + kPi - s2.bearing);
}

Fix Localise(const std::vector<PostSighting>& sightings, const TrilaterationDef& def) {
  Fix best;
  best.status = FixStatus::kTooFewPosts;
  struct Pair {
    int i, j;
    double quality;
  };
  std::vector<Pair> pairs;
  for (int i = 0; i < static_cast<int>(sightings.size()); ++i) {
    if (sightings[i].range > def.max_range) continue;
    for (int j = i + 1; j < static_cast<int>(sightings.size()); ++j) {
      if (sightings[j].range > def.max_range) continue;
      const double spread = std::abs(SignedSpread(sightings[i], sightings[j]));
      const double quality = def.pair == PairChoice::kNearest
                                 ? -std::max(sightings[i].range, sightings[j].range)
                                 : std::sin(spread);
      pairs.push_back({i, j, quality});
    }
  }
  if (pairs.empty()) return best;
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.quality > b.quality; });
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    Fix fix = TrilaterateTwoPosts(sightings[pairs[k].i], sightings[pairs[k].j], def);
    fix.sighting_a = pairs[k].i;
    fix.sighting_b = pairs[k].j;
    if (fix.ok()) return fix;
    if (k == 0) best = fix;
  }
  return best;
}

TurnMeasurement TurnGeometry(const Vec2& position, const Vec2& centre, double radius,
                             bool clockwise, const PostSighting& post) {
  TurnMeasurement m;
  const double r_mea = (position - centre).Norm();
  const double r1 = post.range;
  const double post_to_centre = (post.position - centre).Norm();
  if (!(r_mea > 1e-6) || !(r1 > 1e-6)) return m;
  // Angle at the robot between the post and the centre (law of cosines, as in eq. 4).
  const double c = std::acos(
      ClampUnit((r_mea * r_mea + r1 * r1 - post_to_centre * post_to_centre) / (2.0 * r_mea * r1)));
  const double side =
      Sign(AngleDiff(Azimuth(centre - position), Azimuth(post.position - position)));
  m.ok = true;
  m.radius = r_mea;
  m.delta_r = r_mea - radius;
  m.centre_bearing = WrapToPi(post.bearing + side * c);
  m.heading = WrapToPi(Azimuth(centre - position) - m.centre_bearing);
  // The path tangent is the radius direction turned by ∓90°: centre on the right for a
  // clockwise turn (ideal θ = +π/2), on the left for a counter-clockwise one (θ = −π/2).
  if (clockwise) {
    m.heading_error = WrapToPi(kPi / 2.0 - m.centre_bearing);
    m.lateral_offset = radius - r_mea;
  } else {
    m.heading_error = WrapToPi(-kPi / 2.0 - m.centre_bearing);
    m.lateral_offset = r_mea - radius;
  }
  return m;
}

}  // namespace formsim::control::inspection
