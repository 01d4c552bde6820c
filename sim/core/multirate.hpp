#pragma once
/// \file Several rates in one fixed-step loop: a controller at 15 Hz, a laser at 50 Hz, a
/// filter every control period. Each runs every N world steps; N comes from a period (or a
/// rate) and the world step, checked once when the scenario is read.

#include <string>

namespace formsim::sim {

class YamlReader;

/// Runs something every `every` world steps, counting from step 0.
class MultiRate {
 public:
  explicit MultiRate(int every = 1) : every_(every < 1 ? 1 : every) {}
  bool Due(long step) const { return step % every_ == 0; }
  int every() const { return every_; }

 private:
  int every_;
};

/// World steps per `period` seconds at step `dt`. With `exact`, the period must be a whole
/// multiple of dt. Returns "" and sets *steps, or the reason: a period shorter than one step,
/// more than 10^8 steps, not a multiple.
std::string StepsPerPeriod(double period, double dt, bool exact, int* steps);

/// Reads a period in seconds at `key` (default `def`, which may be dt itself) and returns the
/// number of world steps in it, failing at the key with the reason.
int ReadPeriodSteps(YamlReader& r, const std::string& key, double def, double dt, bool exact);

/// Same for a rate in Hz at `key` (already read, `rate_hz`): the steps between two runs.
int RateSteps(YamlReader& r, const std::string& key, double rate_hz, double dt);

}  // namespace formsim::sim
