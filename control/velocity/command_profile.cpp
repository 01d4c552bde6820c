#include "control/velocity/command_profile.hpp"

#include <algorithm>
#include <cmath>

namespace formsim::control::velocity {

CommandProfile::CommandProfile(std::vector<CommandStep> steps, double accel_limit,
                               double angular_accel_limit)
    : steps_(std::move(steps)),
      accel_limit_(accel_limit),
      angular_accel_limit_(angular_accel_limit) {
  std::stable_sort(steps_.begin(), steps_.end(),
                   [](const CommandStep& a, const CommandStep& b) { return a.t < b.t; });
}

namespace {
/// Moves from `from` towards `to` at `rate` per second for `elapsed` seconds.
double Ramp(double from, double to, double rate, double elapsed) {
  if (!(rate < std::numeric_limits<double>::infinity())) return to;
  const double max_change = rate * std::max(elapsed, 0.0);
  return from + std::clamp(to - from, -max_change, max_change);
}
}  // namespace

void CommandProfile::At(double t, double& v, double& omega) const {
  v = omega = 0.0;
  // Walk the steps, ramping from the value reached when each step began.
  double prev_v = 0.0, prev_w = 0.0, prev_t = 0.0;
  double target_v = 0.0, target_w = 0.0;
  for (const CommandStep& s : steps_) {
    if (s.t > t) break;
    prev_v = Ramp(prev_v, target_v, accel_limit_, s.t - prev_t);
    prev_w = Ramp(prev_w, target_w, angular_accel_limit_, s.t - prev_t);
    prev_t = s.t;
    target_v = s.v;
    target_w = s.omega;
  }
  v = Ramp(prev_v, target_v, accel_limit_, t - prev_t);
  omega = Ramp(prev_w, target_w, angular_accel_limit_, t - prev_t);
}

}  // namespace formsim::control::velocity
