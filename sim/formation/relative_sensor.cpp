#include "sim/formation/relative_sensor.hpp"

#include "sim/core/fnv_hash.hpp"

namespace formsim::sim::formation {

std::uint64_t SensorStreamId(const std::string& name) { return Fnv1a64(name); }

control::formation::LinkState RelativeSensor::Sample(const Pose2& leader, const Pose2& follower, double L,
                                          control::formation::BearingConvention convention, double sigma_l,
                                          double sigma_phi, double sigma_alpha,
                                          control::formation::LinkState& truth) {
  truth = control::formation::ComputeLinkState(leader, follower, L, convention);
  // Always draw three numbers so the stream does not depend on which σ are zero.
  const double nl = rng_.Normal(), np = rng_.Normal(), na = rng_.Normal();
  control::formation::LinkState z = truth;
  z.l = truth.l + sigma_l * nl;
  z.phi = control::WrapToPi(truth.phi + sigma_phi * np);
  z.alpha = control::WrapToPi(truth.alpha + sigma_alpha * na);
  return z;
}

}  // namespace formsim::sim::formation
