#pragma once
/// \file `RayFan`: many rays from one origin (a laser scan's beams), each with exactly the hit of
/// `World::RayCast`, at a fraction of its cost. Box2D's `b2World::RayCast` walks its broad-phase
/// tree for every ray; a fan gathers once the fixtures within reach of the origin, files them by
/// bearing, and per ray asks only the few whose bearing interval holds the ray, through the very
/// shape ray cast Box2D calls (`b2Fixture::RayCast`, same float input). Box2D's answer is the
/// smallest hit fraction of all fixtures the ray meets (it clips the ray at each hit and rejects
/// farther ones), so the smallest fraction over the filed fixtures gives the same fraction, the
/// same point (computed as Box2D's wrapper computes it) and the same distance, bit for bit
/// (tests/sim/test_ray_fan.cpp compares them on random rays). Only when two bodies are hit at
/// exactly the same fraction may `body_name` name the other one.

#include <cstddef>
#include <vector>

#include "sim/core/world.hpp"

namespace formsim::sim {

class RayFan {
 public:
  /// Prepares rays from `origin` of length up to `range` (m) that see what `World::RayCast(origin,
  /// to, include_robots, ignore)` sees. The world must not change while the fan is used.
  RayFan(const World& world, Vec2 origin, double range, bool include_robots = false,
         const Robot* ignore = nullptr);

  /// `World::RayCast(origin, to, ...)`. A ray longer than the fan's range is cast by the world.
  /// Safe to call from several threads at once.
  RayHit Cast(Vec2 to) const;

  /// Fixtures filed (tests and benchmarks).
  std::size_t candidates() const { return candidates_.size(); }

 private:
  /// A fixture child within reach, with a circle around it (world frame).
  struct Candidate {
    const b2Fixture* fixture;
    int child;
    Vec2 center;
    double radius;  ///< with a margin far above float round-off
  };
  static constexpr int kBins = 512;  ///< bearing bins over the full turn
  /// The bin of direction (x, y) (not zero).
  static int BinOf(double x, double y);

  const World& world_;
  Vec2 origin_;
  double range_;
  bool include_robots_;
  const Robot* ignore_;
  std::vector<Candidate> candidates_;
  /// Candidates per bin: bin_items_[bin_start_[b] .. bin_start_[b + 1]) (indices, ascending).
  std::vector<int> bin_start_, bin_items_;
};

}  // namespace formsim::sim
