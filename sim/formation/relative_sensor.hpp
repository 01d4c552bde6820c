#pragma once
/// \file The relative sensor of one leader→follower link: the true (l, φ, α) from the two poses
/// under the scenario's bearing convention, plus seeded Gaussian noise (one Rng stream per link).

#include <cstdint>
#include <string>

#include "control/formation/link_kinematics.hpp"
#include "sim/core/rng.hpp"

namespace formsim::sim::formation {

/// Stable stream id for a named sensor (FNV-1a of the name), so adding a robot does not change
/// the noise of the others.
std::uint64_t SensorStreamId(const std::string& name);

class RelativeSensor {
 public:
  RelativeSensor(const Rng& parent, const std::string& link_name)
      : rng_(parent.Fork(SensorStreamId(link_name))) {}
  /// Samples the link: `truth` receives the exact state, the return value the noisy one
  /// (angles wrapped). σ of zero adds nothing.
  control::formation::LinkState Sample(const Pose2& leader, const Pose2& follower, double L,
                            control::formation::BearingConvention convention, double sigma_l, double sigma_phi,
                            double sigma_alpha, control::formation::LinkState& truth);

 private:
  Rng rng_;
};

}  // namespace formsim::sim::formation
