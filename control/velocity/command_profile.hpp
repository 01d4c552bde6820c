#pragma once
/// \file Commanded body speeds over time: constant, steps, or a circle (constant v and ω),
/// as in the paper's experiments. Steps may be ramped with an acceleration limit.

#include <limits>
#include <string>
#include <vector>

namespace formsim::control::velocity {

/// From time t on, command (v, ω).
struct CommandStep {
  double t = 0.0;
  double v = 0.0;      ///< m/s
  double omega = 0.0;  ///< rad/s
};

class CommandProfile {
 public:
  /// Steps sorted by time; before the first step the command is zero. `accel_limit` (m/s²) and
  /// `angular_accel_limit` (rad/s²) ramp each change linearly (infinite: true steps).
  explicit CommandProfile(std::vector<CommandStep> steps = {},
                          double accel_limit = std::numeric_limits<double>::infinity(),
                          double angular_accel_limit = std::numeric_limits<double>::infinity());
  static CommandProfile Constant(double v, double omega) {
    return CommandProfile({{0.0, v, omega}});
  }

  /// The command at time t (v in m/s, ω in rad/s).
  void At(double t, double& v, double& omega) const;
  const std::vector<CommandStep>& steps() const { return steps_; }

 private:
  std::vector<CommandStep> steps_;
  double accel_limit_, angular_accel_limit_;
};

}  // namespace formsim::control::velocity
